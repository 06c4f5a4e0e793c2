/* exr.c: OpenEXR through its C library, OpenEXRCore: writes scanline float R, G, B and named
 * layers (LAYER.R/G/B), and exact words beside them (UINT channels and a string attribute);
 * reads the R, G, B (or the first or a named LAYER.R/G/B) half or float channels of a scanline
 * file's first part, or its words. */
#include "io/formats.h"
#include "core/alloc.h"

#ifdef MCRT_HAVE_EXR

#include <errno.h>
#include <openexr.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* One read or write: the file and the first message the library reported, with its code. */
struct exr_job {
    int fd;
    char msg[256];
    exr_result_t code;
};

/* The job of the EXR call running on this thread, for the error handler. The handler cannot get
 * it from the context (exr_get_user_data): for a context being set up for writing that call locks
 * the context's mutex, which the library may still hold when it reports an error, and the mutex
 * is not recursive (with OpenEXR 3.1.5 an error in exr_add_channel then deadlocks). */
static pthread_key_t job_key;
static pthread_once_t job_once = PTHREAD_ONCE_INIT;
static int job_key_ok;

static void make_job_key(void)
{
    job_key_ok = pthread_key_create(&job_key, NULL) == 0;
}

static void begin(struct exr_job *job, int fd)
{
    job->fd = fd;
    job->msg[0] = '\0';
    job->code = EXR_ERR_SUCCESS;
    pthread_once(&job_once, make_job_key);
    if (job_key_ok)
        pthread_setspecific(job_key, job);
}

static void end(void)
{
    if (job_key_ok)
        pthread_setspecific(job_key, NULL);
}

/* Keep the first message: the later ones describe consequences ("unable to write chunk"). The
 * library's default handler would print to stderr; this library never prints. */
static void on_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    struct exr_job *job = job_key_ok ? pthread_getspecific(job_key) : NULL;
    (void)ctxt;
    if (job && !job->msg[0]) {
        snprintf(job->msg, sizeof job->msg, "%s", msg);
        job->code = code;
    }
}

/* The job's message, or the library's text for the code when it reported none. Out of memory
 * is often returned as a consequence ("bad header" when the header's attributes could not be
 * stored), so the first reported code decides too. */
static mcrt_status fail(const struct exr_job *job, exr_result_t rv, mc_diag *d)
{
    int nomem = rv == EXR_ERR_OUT_OF_MEMORY || job->code == EXR_ERR_OUT_OF_MEMORY;
    return mc_fail(d, nomem ? MCRT_ERR_NOMEM : MCRT_ERR_IO, "%s",
                   job->msg[0] ? job->msg : exr_get_default_error_message(rv));
}

/* Stream callbacks on the descriptor of the FILE image.c opened (nothing goes through the FILE's
 * buffer). OpenEXR wants pread/pwrite semantics: it seeks back to write the chunk offset table. */
static int64_t read_fd(exr_const_context_t ctxt, void *user, void *buf, uint64_t size,
                       uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    struct exr_job *job = user;
    uint64_t done = 0;
    (void)ctxt;
    (void)error_cb;
    while (done < size) {
        ssize_t n =
            pread(job->fd, (char *)buf + done, (size_t)(size - done), (off_t)(offset + done));
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0)
            return -1;
        if (n == 0)
            break; /* end of file: a short read, which the library reports as truncation */
        done += (uint64_t)n;
    }
    return (int64_t)done;
}

static int64_t size_fd(exr_const_context_t ctxt, void *user)
{
    struct exr_job *job = user;
    struct stat st;
    (void)ctxt;
    return fstat(job->fd, &st) == 0 ? (int64_t)st.st_size : -1;
}

static int64_t write_fd(exr_const_context_t ctxt, void *user, const void *buf, uint64_t size,
                        uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    struct exr_job *job = user;
    uint64_t done = 0;
    (void)ctxt;
    (void)error_cb;
    while (done < size) {
        ssize_t n = pwrite(job->fd, (const char *)buf + done, (size_t)(size - done),
                           (off_t)(offset + done));
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            if (!job->msg[0]) /* the reason, before the library's "unable to write" */
                snprintf(job->msg, sizeof job->msg, "%s", strerror(n < 0 ? errno : EIO));
            return -1;
        }
        done += (uint64_t)n;
    }
    return (int64_t)done;
}

static exr_context_initializer_t initializer(struct exr_job *job)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = on_error;
    init.user_data = job;
    init.read_fn = read_fd;
    init.size_fn = size_fd;
    init.write_fn = write_fd;
    init.alloc_fn = mc_malloc; /* so that the tests can make OpenEXR's allocations fail too */
    init.free_fn = free;
    return init;
}

/* The pixels of the layer a channel name "R" or "LAYER.R" belongs to (unnamed layers, name NULL
 * or "", own the bare R, G, B), with *k its component: 0, 1, 2 for R, G, B. */
static const float *channel_source(const char *channel, const struct image_layer *layers, int n,
                                   int *k)
{
    const char *dot = strrchr(channel, '.');
    size_t plen = dot ? (size_t)(dot - channel) : 0;
    const char *comp = dot ? dot + 1 : channel;
    int i;
    *k = comp[0] == 'R' ? 0 : comp[0] == 'G' ? 1 : 2;
    for (i = 0; i < n; i++) {
        const char *name = layers[i].name ? layers[i].name : "";
        if (strlen(name) == plen && strncmp(name, channel, plen) == 0)
            return layers[i].rgb;
    }
    return layers[0].rgb; /* not reached: exr_write added only the layers' channels */
}

/* Our side of a channel in an encode or decode pipeline: element k of `count` 4-byte elements per
 * pixel (float R, G, B, or a state's words), a row of w pixels after another. */
static void set_layout(exr_coding_channel_info_t *ch, size_t w, int count, exr_pixel_type_t type)
{
    ch->user_pixel_stride = count * 4;
    ch->user_line_stride = (int32_t)((size_t)count * 4 * w);
    ch->user_bytes_per_element = 4;
    ch->user_data_type = (uint16_t)type;
}

/* Whether channel is "NAME.KK" of words (two digits), with *k the KK. */
static int word_channel(const char *channel, const struct image_words *words, int *k)
{
    size_t len = strlen(words->name);
    const char *p = channel + len + 1;
    if (strncmp(channel, words->name, len) != 0 || channel[len] != '.' || strlen(p) != 2 ||
        p[0] < '0' || p[0] > '9' || p[1] < '0' || p[1] > '9')
        return 0;
    *k = (p[0] - '0') * 10 + (p[1] - '0');
    return *k < words->per_pixel;
}

/* The library's compressor, then a chunk whose deflate output is exactly as long as its raw bytes
 * replaced by the raw bytes: every EXR reader takes a chunk of the raw size as stored raw, but
 * OpenEXRCore before 3.4.8 keeps the raw bytes only when deflate's output is longer (its issue
 * 2306), so such a chunk (one in a few hundred of a noisy render's) was decoded as garbage. */
struct encoder {
    exr_encode_pipeline_t enc; /* first: the callback's pointer is the struct's */
    exr_result_t (*library_compress)(exr_encode_pipeline_t *enc);
};

static exr_result_t compress_chunk(exr_encode_pipeline_t *enc)
{
    exr_result_t rv = ((struct encoder *)enc)->library_compress(enc);
    if (rv == EXR_ERR_SUCCESS && enc->compressed_bytes == enc->packed_bytes &&
        enc->compressed_buffer != enc->packed_buffer)
        memcpy(enc->compressed_buffer, enc->packed_buffer, enc->packed_bytes);
    return rv;
}

/* Encode the layers (and words) chunk by chunk (16 scanlines per ZIP chunk). The library's pack
 * step gathers each channel from our interleaved rows through the pixel and line strides. */
static exr_result_t encode_pixels(exr_context_t ctx, const struct image_layer *layers, int n,
                                  const struct image_words *words, int w, int h)
{
    struct encoder coder = {EXR_ENCODE_PIPELINE_INITIALIZER, NULL};
    exr_encode_pipeline_t *enc = &coder.enc;
    exr_chunk_info_t cinfo;
    exr_result_t rv;
    int32_t lines;
    int y, c, started = 0;

    rv = exr_get_scanlines_per_chunk(ctx, 0, &lines);
    for (y = 0; rv == EXR_ERR_SUCCESS && y < h; y += lines) {
        rv = exr_write_scanline_chunk_info(ctx, 0, y, &cinfo);
        if (rv == EXR_ERR_SUCCESS)
            rv = started ? exr_encoding_update(ctx, 0, &cinfo, enc)
                         : exr_encoding_initialize(ctx, 0, &cinfo, enc);
        if (rv != EXR_ERR_SUCCESS)
            break;
        for (c = 0; c < enc->channel_count; c++) {
            exr_coding_channel_info_t *ch = &enc->channels[c];
            /* The file lists channels alphabetically (B, G, R, variance.B, ...); our pixels are
             * R, G, B per layer. */
            int k;
            if (words && word_channel(ch->channel_name, words, &k)) {
                ch->encode_from_ptr = (const uint8_t *)(words->data +
                                                        (size_t)cinfo.start_y * (size_t)w *
                                                            (size_t)words->per_pixel + (size_t)k);
                set_layout(ch, (size_t)w, words->per_pixel, EXR_PIXEL_UINT);
                continue;
            }
            const float *rgb = channel_source(ch->channel_name, layers, n, &k);
            ch->encode_from_ptr =
                (const uint8_t *)(rgb + (size_t)cinfo.start_y * (size_t)w * 3 + (size_t)k);
            set_layout(ch, (size_t)w, 3, EXR_PIXEL_FLOAT);
        }
        if (!started) {
            rv = exr_encoding_choose_default_routines(ctx, 0, enc);
            if (enc->compress_fn) {
                coder.library_compress = enc->compress_fn;
                enc->compress_fn = compress_chunk;
            }
        }
        started = 1;
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_encoding_run(ctx, 0, enc);
    }
    if (started)
        exr_encoding_destroy(ctx, enc);
    return rv;
}

mcrt_status mc_exr_write_layers(FILE *f, const struct image_layer *layers, int n,
                                const struct image_words *words, int w, int h, mc_diag *d)
{
    static const char *const comp[3] = {"R", "G", "B"};
    struct exr_job job;
    exr_context_initializer_t init;
    exr_context_t ctx = NULL;
    exr_result_t rv, rv_finish;
    int part, c, i;

    /* the library's line stride is an int32_t */
    if (w > INT32_MAX / (4L * (words ? words->per_pixel > 3 ? words->per_pixel : 3 : 3)))
        return mc_fail(d, MCRT_ERR_INVALID, "%d pixels is too wide for one EXR scanline", w);
    for (i = 0; i < n; i++)
        if (layers[i].name && strlen(layers[i].name) > 200)
            return mc_fail(d, MCRT_ERR_INVALID, "layer name '%.40s...' is too long",
                           layers[i].name);
    begin(&job, fileno(f));
    init = initializer(&job);
    rv = exr_start_write(&ctx, "image", EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, &part);
    /* ZIP (deflate on 16-line chunks) is lossless and every EXR reader decodes it. The trade-off,
     * measured here on a 1024x1024 image: with +-30% noise in every pixel it saves only 3% and
     * takes 0.33 s against 0.02 s for NONE (float noise fills the low mantissa bits); a noise-free
     * gradient shrinks 60x. Once per render, the time is small next to rendering. */
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(ctx, part, w, h, EXR_COMPRESSION_ZIP);
    /* Layers follow the OpenEXR naming convention "LAYER.R" (Technical Introduction, "Layers"),
     * so that other tools show them as layers. */
    for (i = 0; i < n && rv == EXR_ERR_SUCCESS; i++)
        for (c = 0; c < 3 && rv == EXR_ERR_SUCCESS; c++) {
            char name[256];
            if (layers[i].name && layers[i].name[0])
                snprintf(name, sizeof name, "%s.%s", layers[i].name, comp[c]);
            else
                snprintf(name, sizeof name, "%s", comp[c]);
            rv = exr_add_channel(ctx, part, name, EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LOGARITHMIC,
                                 1, 1);
        }
    /* A state's words are UINT channels, which hold them exactly (FLOAT would not hold every
     * bit pattern: NaN payloads are not kept by every reader), and its text a string attribute. */
    for (i = 0; words && i < words->per_pixel && rv == EXR_ERR_SUCCESS; i++) {
        char name[256];
        snprintf(name, sizeof name, "%s.%02d", words->name, i);
        rv = exr_add_channel(ctx, part, name, EXR_PIXEL_UINT, EXR_PERCEPTUALLY_LINEAR, 1, 1);
    }
    if (words && rv == EXR_ERR_SUCCESS)
        rv = exr_attr_set_string(ctx, part, words->name, words->text);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_write_header(ctx);
    if (rv == EXR_ERR_SUCCESS)
        rv = encode_pixels(ctx, layers, n, words, w, h);
    /* exr_finish writes the chunk offset table, so its result matters too. */
    rv_finish = exr_finish(&ctx);
    if (rv == EXR_ERR_SUCCESS)
        rv = rv_finish;
    end();
    return rv == EXR_ERR_SUCCESS ? MCRT_OK : fail(&job, rv, d);
}

static mcrt_status exr_write(FILE *f, const float *rgb, int w, int h, mc_diag *d)
{
    struct image_layer beauty;
    beauty.name = NULL;
    beauty.rgb = rgb;
    return mc_exr_write_layers(f, &beauty, 1, NULL, w, h, d);
}

/* Whether chlist has the channels NAME.R, NAME.G, NAME.B (R, G, B when plen is 0), where NAME is
 * the first plen characters of name; idx gets their chlist indices. */
static int find_layer(const exr_attr_chlist_t *chl, const char *name, size_t plen, int idx[3])
{
    static const char rgb[3] = {'R', 'G', 'B'};
    int j, k;
    for (k = 0; k < 3; k++) {
        idx[k] = -1;
        for (j = 0; j < chl->num_channels; j++) {
            const exr_attr_string_t *s = &chl->entries[j].name;
            size_t want = plen ? plen + 2 : 1; /* "NAME.R" or "R" */
            if ((size_t)s->length == want && strncmp(s->str, name, plen) == 0 &&
                (!plen || s->str[plen] == '.') && s->str[want - 1] == rgb[k])
                idx[k] = j;
        }
        if (idx[k] < 0)
            return 0;
    }
    return 1;
}

/* Pick the channels to read as R, G, B. With a layer name, exactly LAYER.R, .G, .B. Without one:
 * "R", "G", "B" if present, else the alphabetically first layer with all three ("diffuse.R",
 * "diffuse.G", "diffuse.B"). idx gets chlist indices. */
static int pick_channels(const exr_attr_chlist_t *chl, const char *layer, int idx[3])
{
    int i;
    if (layer)
        return find_layer(chl, layer, strlen(layer), idx);
    if (find_layer(chl, "", 0, idx))
        return 1;
    for (i = 0; i < chl->num_channels; i++) {
        /* Entry i ending in ".R" names a layer. */
        const char *name = chl->entries[i].name.str;
        size_t len = (size_t)chl->entries[i].name.length;
        if (len >= 3 && name[len - 2] == '.' && name[len - 1] == 'R' &&
            find_layer(chl, name, len - 2, idx))
            return 1;
    }
    return 0;
}

/* The bytes of one pixel of every channel of chl, as a scanline chunk stores them unpacked. */
static uint64_t pixel_bytes(const exr_attr_chlist_t *chl)
{
    uint64_t n = 0;
    int k;
    for (k = 0; k < chl->num_channels; k++)
        n += chl->entries[k].pixel_type == EXR_PIXEL_HALF ? 2 : 4;
    return n;
}

/* The most a packed byte can unpack to with compression c: 1032 for deflate (ZIP, ZIPS; RFC 1951,
 * 258 bytes from a 2-bit code at best), 64 for EXR's run-length coding (128 bytes from 2), 1
 * uncompressed; 0 where no such bound is known (the wavelet and lossy codecs). */
static double unpack_ratio(exr_compression_t c)
{
    return c == EXR_COMPRESSION_NONE ? 1.0
           : c == EXR_COMPRESSION_RLE ? 64.0
           : c == EXR_COMPRESSION_ZIP || c == EXR_COMPRESSION_ZIPS ? 1032.0 : 0.0;
}

/* Whether the data window dw of part 0 can be what its file holds: no more pixels than the file's
 * bytes can unpack to (unpack_ratio), so that a damaged or hostile header is refused before its
 * pixels are allocated, as pfm.c compares its header with the file's size (make fuzz found a
 * 1.4 KB EXR declaring 2.4 GB). MCRT_OK, or MCRT_ERR_IO explained in d. */
static mcrt_status check_window(exr_context_t ctx, const struct exr_job *job,
                                const exr_attr_box2i_t *dw, const exr_attr_chlist_t *chl,
                                mc_diag *d)
{
    exr_compression_t comp;
    struct stat sb;
    double raw = ((double)dw->max.x - dw->min.x + 1) * ((double)dw->max.y - dw->min.y + 1)
                 * (double)pixel_bytes(chl);
    if (exr_get_compression(ctx, 0, &comp) == EXR_ERR_SUCCESS && unpack_ratio(comp) > 0.0 &&
        fstat(job->fd, &sb) == 0 && S_ISREG(sb.st_mode) &&
        raw > unpack_ratio(comp) * (double)sb.st_size + 65536.0)
        return mc_fail(d, MCRT_ERR_IO, "its %ldx%ld pixels (%.0f bytes) are more than its %ld "
                                       "bytes can hold", (long)dw->max.x - dw->min.x + 1,
                       (long)dw->max.y - dw->min.y + 1, raw, (long)sb.st_size);
    return MCRT_OK;
}

/* Decode the chosen channels idx[0..count-1] of part 0, channel k into the rows of to[k]: w pixels
 * a row, per_pixel 4-byte elements of this type a pixel (half is converted to float on the way).
 * One pass over the chunks, each decompressed once however many channels are wanted. */
static exr_result_t decode_pixels(exr_context_t ctx, const exr_attr_box2i_t *dw, const int *idx,
                                  int count, exr_pixel_type_t type, uint8_t *const *to,
                                  int per_pixel, size_t w, int *corrupt)
{
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    exr_chunk_info_t cinfo;
    exr_result_t rv;
    int32_t lines;
    int y, k, started = 0;

    const exr_attr_chlist_t *chl;
    uint64_t bytes = 0; /* all the channels' bytes in one pixel */
    rv = exr_get_scanlines_per_chunk(ctx, 0, &lines);
    if (rv == EXR_ERR_SUCCESS && (rv = exr_get_channels(ctx, 0, &chl)) == EXR_ERR_SUCCESS)
        bytes = pixel_bytes(chl);
    for (y = dw->min.y; rv == EXR_ERR_SUCCESS && y <= dw->max.y; y += lines) {
        rv = exr_read_scanline_chunk_info(ctx, 0, y, &cinfo);
        if (rv != EXR_ERR_SUCCESS)
            break;
        /* The chunk must lie inside the data window, or our strides would write out of bounds.
         * Its unpacked size, which the decoder allocates before it inflates a byte, can be no
         * more than its pixels' bytes, nor more than its packed bytes can unpack to
         * (unpack_ratio): a 1.4 KB file found by make fuzz (tests/fuzz/fuzz_image.c) claimed
         * 5.2 GB from 154 packed bytes, and the decoder asked mc_malloc for them. */
        if (cinfo.start_y < dw->min.y || cinfo.height < 1 ||
            (int64_t)cinfo.start_y + cinfo.height - 1 > dw->max.y || (size_t)cinfo.width != w ||
            cinfo.unpacked_size > (uint64_t)cinfo.width * (uint64_t)cinfo.height * bytes ||
            (unpack_ratio(cinfo.compression) > 0.0
             && (double)cinfo.unpacked_size
                    > unpack_ratio(cinfo.compression) * (double)cinfo.packed_size + 1024.0)) {
            *corrupt = 1;
            break;
        }
        rv = started ? exr_decoding_update(ctx, 0, &cinfo, &dec)
                     : exr_decoding_initialize(ctx, 0, &cinfo, &dec);
        if (rv != EXR_ERR_SUCCESS)
            break;
        /* Channels we do not want keep a NULL pointer, which the decoder skips. */
        for (k = 0; k < count; k++) {
            exr_coding_channel_info_t *ch = &dec.channels[idx[k]];
            ch->decode_to_ptr =
                to[k] + 4 * (size_t)(cinfo.start_y - dw->min.y) * w * (size_t)per_pixel;
            set_layout(ch, w, per_pixel, type);
        }
        if (!started)
            rv = exr_decoding_choose_default_routines(ctx, 0, &dec);
        started = 1;
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_decoding_run(ctx, 0, &dec);
    }
    if (started)
        exr_decoding_destroy(ctx, &dec);
    return rv;
}

/* The most channels one read decodes: a render state's words (1 to 99), or MC_IMAGE_MAX_LAYERS
 * layers of 3. */
enum { MAX_CHANNELS = 99 };

/* Check part 0 and read its n layers into ims; anything we refuse is explained in d with status
 * MCRT_ERR_IO. */
static mcrt_status read_part(exr_context_t ctx, struct exr_job *job, const char *const *layers,
                             int n, struct image *ims, mc_diag *d)
{
    exr_storage_t storage;
    exr_attr_box2i_t dw;
    const exr_attr_chlist_t *chl;
    exr_result_t rv;
    uint8_t *to[MAX_CHANNELS];
    int idx[MAX_CHANNELS], i, k, corrupt = 0;
    mcrt_status st = MCRT_OK;

    if ((rv = exr_get_storage(ctx, 0, &storage)) != EXR_ERR_SUCCESS ||
        (rv = exr_get_data_window(ctx, 0, &dw)) != EXR_ERR_SUCCESS ||
        (rv = exr_get_channels(ctx, 0, &chl)) != EXR_ERR_SUCCESS)
        return fail(job, rv, d);
    if (storage != EXR_STORAGE_SCANLINE)
        return mc_fail(d, MCRT_ERR_IO, "%s EXR images are not supported (only scanline ones)",
                       storage == EXR_STORAGE_TILED ? "tiled" : "deep");
    for (i = 0; i < n; i++) {
        const char *layer = layers ? layers[i] : NULL;
        if (!pick_channels(chl, layer, idx + 3 * i))
            return layer ? mc_fail(d, MCRT_ERR_IO, "no layer '%s' (channels %s.R, .G, .B)", layer,
                                   layer)
                         : mc_fail(d, MCRT_ERR_IO,
                                   "no R, G, B channels (nor LAYER.R, .G, .B) in the first part");
    }
    for (k = 0; k < 3 * n; k++) {
        const exr_attr_chlist_entry_t *e = &chl->entries[idx[k]];
        if ((e->pixel_type != EXR_PIXEL_HALF && e->pixel_type != EXR_PIXEL_FLOAT) ||
            e->x_sampling != 1 || e->y_sampling != 1)
            return mc_fail(d, MCRT_ERR_IO, "channel '%s' is not full-resolution half or float",
                           e->name.str);
    }
    /* The data window is the pixel rectangle stored; it becomes our image whatever its origin. */
    if ((long)dw.max.x - dw.min.x + 1 > INT32_MAX / (3 * (long)sizeof(float)))
        return mc_fail(d, MCRT_ERR_IO, "the image is too wide");
    if ((st = check_window(ctx, job, &dw, chl, d)) != MCRT_OK)
        return st;
    for (i = 0; i < n && st == MCRT_OK; i++)
        st = mc_image_alloc(&ims[i], (long)dw.max.x - dw.min.x + 1, (long)dw.max.y - dw.min.y + 1,
                            d);
    for (k = 0; k < 3 * n && st == MCRT_OK; k++)
        to[k] = (uint8_t *)(ims[k / 3].rgb + k % 3);
    if (st == MCRT_OK) {
        rv = decode_pixels(ctx, &dw, idx, 3 * n, EXR_PIXEL_FLOAT, to, 3, (size_t)ims[0].width,
                           &corrupt);
        if (rv == EXR_ERR_SUCCESS && !corrupt)
            return MCRT_OK;
        st = corrupt ? mc_fail(d, MCRT_ERR_IO, "corrupt scanline chunk") : fail(job, rv, d);
    }
    for (i = 0; i < n; i++)
        mc_image_free(&ims[i]);
    return st;
}

/* Begin job on f and open it for reading into *ctx (to exr_finish, then end, whatever this
 * returns). */
static exr_result_t start_read(FILE *f, struct exr_job *job, exr_context_t *ctx)
{
    exr_context_initializer_t init;
    begin(job, fileno(f));
    init = initializer(job);
    /* Without reconstruction a damaged chunk table is an error, not a guess. */
    init.flags = EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
    return exr_start_read(ctx, "image", &init);
}

mcrt_status mc_exr_read_layers(FILE *f, const char *const *layers, int n, struct image *ims,
                               mc_diag *d)
{
    struct exr_job job;
    exr_context_t ctx = NULL;
    exr_result_t rv;
    mcrt_status st;
    if (n < 1 || n > MC_IMAGE_MAX_LAYERS)
        return mc_fail(d, MCRT_ERR_INVALID, "cannot read %d layers at once (1 to %d)", n,
                       MC_IMAGE_MAX_LAYERS);
    rv = start_read(f, &job, &ctx);
    st = rv == EXR_ERR_SUCCESS ? read_part(ctx, &job, layers, n, ims, d) : fail(&job, rv, d);
    exr_finish(&ctx);
    end();
    return st;
}

/* The words of part 0 (checked as read_part checks the image) and its text attribute. */
static mcrt_status read_words(exr_context_t ctx, struct exr_job *job, struct image_words *words,
                              char **text, int *w, int *h, mc_diag *d)
{
    exr_storage_t storage;
    exr_attr_box2i_t dw;
    const exr_attr_chlist_t *chl;
    const char *str;
    int32_t len;
    exr_result_t rv;
    int idx[MAX_CHANNELS], i, k, corrupt = 0;
    uint8_t *to[MAX_CHANNELS];
    long width, height;
    mcrt_status st;

    if ((rv = exr_get_storage(ctx, 0, &storage)) != EXR_ERR_SUCCESS ||
        (rv = exr_get_data_window(ctx, 0, &dw)) != EXR_ERR_SUCCESS ||
        (rv = exr_get_channels(ctx, 0, &chl)) != EXR_ERR_SUCCESS)
        return fail(job, rv, d);
    if (storage != EXR_STORAGE_SCANLINE ||
        exr_attr_get_string(ctx, 0, words->name, &len, &str) != EXR_ERR_SUCCESS)
        return mc_fail(d, MCRT_ERR_IO, "no render state in it (the '%s' attribute of mcrt --state)",
                       words->name);
    for (k = 0; k < words->per_pixel; k++) {
        idx[k] = -1;
        for (i = 0; i < chl->num_channels; i++) {
            const exr_attr_chlist_entry_t *e = &chl->entries[i];
            int j;
            if (word_channel(e->name.str, words, &j) && j == k && e->pixel_type == EXR_PIXEL_UINT &&
                e->x_sampling == 1 && e->y_sampling == 1)
                idx[k] = i;
        }
        if (idx[k] < 0)
            return mc_fail(d, MCRT_ERR_IO, "render state without its channel '%s.%02d'",
                           words->name, k);
    }
    width = (long)dw.max.x - dw.min.x + 1;
    height = (long)dw.max.y - dw.min.y + 1;
    if (width > INT32_MAX / (4L * words->per_pixel))
        return mc_fail(d, MCRT_ERR_IO, "the image is too wide");
    if ((st = mc_image_check_size(width, height, d)) != MCRT_OK ||
        (st = check_window(ctx, job, &dw, chl, d)) != MCRT_OK)
        return st;
    words->data = mc_malloc((size_t)width * (size_t)height * (size_t)words->per_pixel * 4);
    *text = mc_malloc((size_t)len + 1);
    if (!words->data || !*text) {
        free(words->data);
        free(*text);
        words->data = NULL;
        *text = NULL;
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory for a %ldx%ld render state", width,
                       height);
    }
    memcpy(*text, str, (size_t)len);
    (*text)[len] = '\0';
    for (k = 0; k < words->per_pixel; k++)
        to[k] = (uint8_t *)(words->data + k);
    rv = decode_pixels(ctx, &dw, idx, words->per_pixel, EXR_PIXEL_UINT, to, words->per_pixel,
                       (size_t)width, &corrupt);
    if (rv == EXR_ERR_SUCCESS && !corrupt) {
        *w = (int)width;
        *h = (int)height;
        return MCRT_OK;
    }
    free(words->data);
    free(*text);
    words->data = NULL;
    *text = NULL;
    return corrupt ? mc_fail(d, MCRT_ERR_IO, "corrupt scanline chunk") : fail(job, rv, d);
}

mcrt_status mc_exr_read_words(FILE *f, struct image_words *words, char **text, int *w, int *h,
                              mc_diag *d)
{
    struct exr_job job;
    exr_context_t ctx = NULL;
    exr_result_t rv = start_read(f, &job, &ctx);
    mcrt_status st = rv == EXR_ERR_SUCCESS ? read_words(ctx, &job, words, text, w, h, d)
                                           : fail(&job, rv, d);
    exr_finish(&ctx);
    end();
    return st;
}

static mcrt_status exr_read(FILE *f, struct image *im, mc_diag *d)
{
    return mc_exr_read_layers(f, NULL, 1, im, d);
}

const struct image_format mc_exr_format = {"exr", "OpenEXR", "libopenexr-dev", exr_write, exr_read};

#else

const struct image_format mc_exr_format = {"exr", "OpenEXR", "libopenexr-dev", NULL, NULL};

mcrt_status mc_exr_write_layers(FILE *f, const struct image_layer *layers, int n,
                                const struct image_words *words, int w, int h, mc_diag *d)
{
    (void)f, (void)layers, (void)n, (void)words, (void)w, (void)h;
    return mc_fail(d, MCRT_ERR_UNSUPPORTED, "built without OpenEXR");
}

mcrt_status mc_exr_read_words(FILE *f, struct image_words *words, char **text, int *w, int *h,
                              mc_diag *d)
{
    (void)f, (void)words, (void)text, (void)w, (void)h;
    return mc_fail(d, MCRT_ERR_UNSUPPORTED, "built without OpenEXR");
}

mcrt_status mc_exr_read_layers(FILE *f, const char *const *layers, int n, struct image *ims,
                               mc_diag *d)
{
    (void)f, (void)layers, (void)n, (void)ims;
    return mc_fail(d, MCRT_ERR_UNSUPPORTED, "built without OpenEXR");
}

#endif
