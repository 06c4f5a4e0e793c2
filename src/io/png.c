/* png.c: PNG through libpng: writes 8-bit sRGB RGB with an sRGB chunk; reads 1-16 bit grey, RGB,
 * RGBA and palette images to linear RGB (PNG spec 1.2, 11.3.3). libpng's setjmp stays in here. */
#include "io/formats.h"

#ifdef MCRT_HAVE_PNG

#include <errno.h>
#include <png.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"

/* One read or write. libpng reports errors by longjmp to the setjmp in read_pixels/write_pixels;
 * after that jump, locals changed since setjmp are indeterminate (C99 7.13.2.1), so everything
 * the cleanup needs lives in this struct, which those functions reach only through a pointer. */
struct png_job {
    FILE *f;
    mc_diag *d;
    png_structp png;
    png_infop info;
    unsigned char *bytes; /* write: one row; read: the whole image as libpng delivers it */
    png_bytep *rows;      /* read: row pointers into bytes */
    float *lut;           /* read: linear value of every possible sample */
    struct image im;      /* read: the result */
    int nomem;            /* an allocation of libpng's failed: its error is then out of memory */
};

/* The status of an error libpng reported. */
static mcrt_status png_status(const struct png_job *job)
{
    return job->nomem ? MCRT_ERR_NOMEM : MCRT_ERR_IO;
}

static void on_error(png_structp png, png_const_charp msg)
{
    struct png_job *job = png_get_error_ptr(png);
    mc_fail(job->d, png_status(job), "%s", msg);
    png_longjmp(png, 1);
}

/* libpng's allocations through mc_malloc, so that the tests can make them fail too. */
static png_voidp png_alloc(png_structp png, png_alloc_size_t n)
{
    struct png_job *job = png_get_mem_ptr(png);
    void *p = mc_malloc(n);
    if (!p)
        job->nomem = 1;
    return p;
}

static void png_release(png_structp png, png_voidp p)
{
    (void)png;
    free(p);
}

static void on_warning(png_structp png, png_const_charp msg)
{
    (void)png; /* the library never prints; warnings do not stop a read */
    (void)msg;
}

/* Our own IO callbacks, so messages say why (libpng's default ones only say "Read Error"). */
static void read_data(png_structp png, png_bytep out, png_size_t n)
{
    struct png_job *job = png_get_io_ptr(png);
    if (fread(out, 1, n, job->f) != n)
        png_error(png, feof(job->f) ? "truncated file" : strerror(errno));
}

static void write_data(png_structp png, png_bytep data, png_size_t n)
{
    struct png_job *job = png_get_io_ptr(png);
    if (fwrite(data, 1, n, job->f) != n)
        png_error(png, strerror(errno));
}

static void flush_data(png_structp png)
{
    (void)png; /* image.c's fclose flushes and reports */
}

static unsigned char encode8(float linear)
{
    return (unsigned char)(mc_srgb_encode(linear) * 255.0f + 0.5f);
}

static mcrt_status write_pixels(struct png_job *job, const float *rgb, int w, int h)
{
    int x, y;
    job->png = png_create_write_struct_2(PNG_LIBPNG_VER_STRING, job, on_error, on_warning, job,
                                         png_alloc, png_release);
    if (!job->png || !(job->info = png_create_info_struct(job->png)))
        return mc_fail(job->d, MCRT_ERR_NOMEM, "out of memory");
    if (setjmp(png_jmpbuf(job->png)))
        return png_status(job);
    png_set_write_fn(job->png, job, write_data, flush_data);
    png_set_IHDR(job->png, job->info, (png_uint_32)w, (png_uint_32)h, 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    /* sRGB plus the matching gAMA and cHRM, for decoders that only know the latter. */
    png_set_sRGB_gAMA_and_cHRM(job->png, job->info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(job->png, job->info);
    for (y = 0; y < h; y++) {
        const float *src = rgb + (size_t)y * (size_t)w * 3;
        for (x = 0; x < w * 3; x++)
            job->bytes[x] = encode8(src[x]);
        png_write_row(job->png, job->bytes);
    }
    png_write_end(job->png, NULL);
    return MCRT_OK;
}

static mcrt_status png_write(FILE *f, const float *rgb, int w, int h, mc_diag *d)
{
    struct png_job job;
    mcrt_status st;
    memset(&job, 0, sizeof job);
    job.f = f;
    job.d = d;
    job.bytes = mc_malloc((size_t)w * 3);
    if (!job.bytes)
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory for a %d-pixel row", w);
    st = write_pixels(&job, rgb, w, h);
    png_destroy_write_struct(&job.png, &job.info);
    free(job.bytes);
    return st;
}

/* Fill job->lut with the linear value of each of the 2^depth sample values. PNG spec 11.3.3: an
 * sRGB chunk means the sRGB curve; otherwise a gAMA chunk gives the exponent (sample =
 * linear^gamma, so gamma 1.0 marks linear data); with neither, sRGB is the only sane guess. */
static void build_lut(struct png_job *job, int depth)
{
    size_t i, n = (size_t)1 << depth;
    double gamma = 0.0, maxv = (double)(n - 1);
    int intent;
    if (png_get_sRGB(job->png, job->info, &intent) ||
        !png_get_gAMA(job->png, job->info, &gamma) || !(gamma > 0.01 && gamma < 100.0))
        gamma = 0.0;
    for (i = 0; i < n; i++) {
        float v = (float)((double)i / maxv);
        job->lut[i] = gamma > 0.0 ? (float)pow(v, 1.0 / gamma) : mc_srgb_decode(v);
    }
}

static mcrt_status read_pixels(struct png_job *job)
{
    png_uint_32 w, h, y;
    int depth, color, bytes_per;
    size_t rowbytes, i, n;
    mcrt_status st;

    job->png = png_create_read_struct_2(PNG_LIBPNG_VER_STRING, job, on_error, on_warning, job,
                                        png_alloc, png_release);
    if (!job->png || !(job->info = png_create_info_struct(job->png)))
        return mc_fail(job->d, MCRT_ERR_NOMEM, "out of memory");
    if (setjmp(png_jmpbuf(job->png)))
        return png_status(job);
    png_set_read_fn(job->png, job, read_data);
    png_set_sig_bytes(job->png, 8);
    png_read_info(job->png, job->info);
    w = png_get_image_width(job->png, job->info);
    h = png_get_image_height(job->png, job->info);
    color = png_get_color_type(job->png, job->info);
    depth = png_get_bit_depth(job->png, job->info);
    /* Bring every kind of PNG to 8- or 16-bit RGB; alpha and tRNS transparency are dropped, as an
     * RGB image has no use for them. */
    if (color == PNG_COLOR_TYPE_PALETTE)
        png_set_palette_to_rgb(job->png);
    if (color == PNG_COLOR_TYPE_GRAY && depth < 8)
        png_set_expand_gray_1_2_4_to_8(job->png);
    if (color & PNG_COLOR_MASK_ALPHA)
        png_set_strip_alpha(job->png);
    if (!(color & PNG_COLOR_MASK_COLOR))
        png_set_gray_to_rgb(job->png);
    png_set_interlace_handling(job->png);
    png_read_update_info(job->png, job->info);
    depth = png_get_bit_depth(job->png, job->info);
    bytes_per = depth == 16 ? 2 : 1;
    rowbytes = png_get_rowbytes(job->png, job->info);
    if (png_get_channels(job->png, job->info) != 3 || (depth != 8 && depth != 16) ||
        rowbytes != (size_t)w * 3 * (size_t)bytes_per)
        png_error(job->png, "unexpected pixel layout after conversion to RGB");

    if ((st = mc_image_alloc(&job->im, (long)w, (long)h, job->d)) != MCRT_OK)
        return st;
    job->lut = mc_malloc(((size_t)1 << depth) * sizeof *job->lut);
    job->bytes = mc_malloc(rowbytes * h);
    job->rows = mc_malloc(h * sizeof *job->rows);
    if (!job->lut || !job->bytes || !job->rows)
        return mc_fail(job->d, MCRT_ERR_NOMEM, "out of memory for a %lux%lu image",
                       (unsigned long)w, (unsigned long)h);
    for (y = 0; y < h; y++)
        job->rows[y] = job->bytes + (size_t)y * rowbytes;
    png_read_image(job->png, job->rows);
    png_read_end(job->png, NULL);

    build_lut(job, depth);
    n = (size_t)w * h * 3;
    for (i = 0; i < n; i++) {
        const unsigned char *p = job->bytes + i * (size_t)bytes_per;
        /* 16-bit samples are big-endian (PNG spec 7.1). */
        job->im.rgb[i] = job->lut[bytes_per == 2 ? (p[0] << 8 | p[1]) : p[0]];
    }
    return MCRT_OK;
}

static mcrt_status png_read(FILE *f, struct image *im, mc_diag *d)
{
    struct png_job job;
    unsigned char sig[8];
    mcrt_status st;
    if (fread(sig, 1, sizeof sig, f) != sizeof sig || png_sig_cmp(sig, 0, sizeof sig))
        return mc_fail(d, MCRT_ERR_IO, "not a PNG file (bad signature)");
    memset(&job, 0, sizeof job);
    job.f = f;
    job.d = d;
    st = read_pixels(&job);
    png_destroy_read_struct(&job.png, &job.info, NULL);
    free(job.lut);
    free(job.bytes);
    free(job.rows);
    if (st == MCRT_OK)
        *im = job.im;
    else
        mc_image_free(&job.im);
    return st;
}

const struct image_format mc_png_format = {"png", "libpng", "libpng-dev", png_write, png_read};

#else

const struct image_format mc_png_format = {"png", "libpng", "libpng-dev", NULL, NULL};

#endif
