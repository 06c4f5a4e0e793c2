/* image.c: image files by suffix: the format table, reading, and writing all-or-nothing (through
 * core/file.h's mc_output: an existing image survives a failed write). */
#include "io/formats.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/alloc.h"
#include "core/file.h"

static const struct image_format *const formats[] = {&mc_png_format, &mc_exr_format,
                                                      &mc_pfm_format};
#define NFORMATS (sizeof formats / sizeof formats[0])

static const struct image_format *find_format(const char *suffix)
{
    size_t i;
    if (suffix[0] == '.')
        suffix++;
    for (i = 0; i < NFORMATS; i++)
        if (strcasecmp(suffix, formats[i]->suffix) == 0)
            return formats[i];
    return NULL;
}

/* The suffix of the last path component including the dot ("" if none). */
static const char *path_suffix(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash + 1 : path, '.');
    return dot ? dot : "";
}

/* Find path's format or explain (verb is "write" or "read") why there is none in this build. */
static mcrt_status lookup(const char *path, const char *verb, const struct image_format **out,
                          mc_diag *d)
{
    const char *suffix = path_suffix(path);
    const struct image_format *fmt = find_format(suffix);
    if (!fmt) {
        if (!suffix[0])
            return mc_fail(d, MCRT_ERR_UNSUPPORTED,
                           "cannot %s '%s': no image suffix (use .png, .exr or .pfm)", verb, path);
        return mc_fail(d, MCRT_ERR_UNSUPPORTED,
                       "cannot %s '%s': unknown image format '%s' (use .png, .exr or .pfm)", verb,
                       path, suffix);
    }
    if (!fmt->write || !fmt->read)
        return mc_fail(d, MCRT_ERR_UNSUPPORTED,
                       "cannot %s '%s': this mcrt was built without %s (install %s and rebuild)",
                       verb, path, fmt->library, fmt->package);
    *out = fmt;
    return MCRT_OK;
}

/* Turn the bare reason a format left in d into "cannot VERB 'path': reason". */
static mcrt_status explain(mc_diag *d, mcrt_status status, const char *verb, const char *path)
{
    char reason[sizeof d->msg];
    if (!d)
        return status;
    memcpy(reason, d->msg, sizeof reason);
    return mc_fail(d, status, "cannot %s '%s': %s", verb, path, reason);
}

int mc_image_supported(const char *suffix)
{
    const struct image_format *fmt = suffix ? find_format(suffix) : NULL;
    return fmt && fmt->write && fmt->read;
}

mcrt_status mc_image_check_size(long w, long h, mc_diag *d)
{
    if (w <= 0 || h <= 0 || w > MC_IMAGE_MAX_PIXELS / h)
        return mc_fail(d, MCRT_ERR_IO, "image size %ldx%ld is out of range (at most %ld pixels)",
                       w, h, (long)MC_IMAGE_MAX_PIXELS);
    return MCRT_OK;
}

mcrt_status mc_image_alloc(struct image *im, long w, long h, mc_diag *d)
{
    mcrt_status st = mc_image_check_size(w, h, d);
    if (st != MCRT_OK)
        return st;
    im->rgb = mc_malloc((size_t)w * (size_t)h * 3 * sizeof(float));
    if (!im->rgb)
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory for a %ldx%ld image", w, h);
    im->width = (int)w;
    im->height = (int)h;
    return MCRT_OK;
}

mcrt_status mc_image_write(const char *path, const float *rgb, int w, int h, mc_diag *d)
{
    struct image_layer beauty;
    beauty.name = NULL;
    beauty.rgb = rgb;
    return mc_image_write_layers(path, &beauty, 1, w, h, d);
}

mcrt_status mc_image_write_layers(const char *path, const struct image_layer *layers, int n, int w,
                                  int h, mc_diag *d)
{
    return mc_image_write_words(path, layers, n, NULL, w, h, d);
}

mcrt_status mc_image_write_words(const char *path, const struct image_layer *layers, int n,
                                 const struct image_words *words, int w, int h, mc_diag *d)
{
    const struct image_format *fmt;
    struct mc_output out;
    mcrt_status st;
    int i, layered = words || n > 1 || (n == 1 && layers[0].name && layers[0].name[0]);

    for (i = 0; i < n && layers[i].rgb; i++)
        ;
    if (!path || n < 1 || i < n)
        return mc_fail(d, MCRT_ERR_INVALID, "cannot write an image: no %s",
                       path ? "pixels" : "path");
    if ((st = lookup(path, "write", &fmt, d)) != MCRT_OK)
        return st;
    if (layered && fmt != &mc_exr_format)
        return mc_fail(d, MCRT_ERR_UNSUPPORTED,
                       "cannot write '%s': only EXR images hold extra layers", path);
    if (w <= 0 || h <= 0 || w > MC_IMAGE_MAX_PIXELS / h)
        return mc_fail(d, MCRT_ERR_INVALID, "cannot write '%s': image size %dx%d is out of range",
                       path, w, h);
    if ((st = mc_output_open(&out, path, d)) != MCRT_OK)
        return st;
    st = layered ? mc_exr_write_layers(out.f, layers, n, words, w, h, d)
                 : fmt->write(out.f, layers[0].rgb, w, h, d);
    if (st != MCRT_OK)
        st = explain(d, st, "write", path);
    return mc_output_close(&out, st, d);
}

int mc_image_layered(const char *path)
{
    return path && find_format(path_suffix(path)) == &mc_exr_format;
}

mcrt_status mc_image_read(const char *path, struct image *im, mc_diag *d)
{
    return mc_image_read_layer(path, NULL, im, d);
}

mcrt_status mc_image_read_layer(const char *path, const char *layer, struct image *im,
                                mc_diag *d)
{
    const struct image_format *fmt;
    struct image got = {0, 0, NULL};
    FILE *f;
    mcrt_status st;

    if (layer)
        return mc_image_read_layers(path, &layer, 1, im, d);
    if (!path || !im)
        return mc_fail(d, MCRT_ERR_INVALID, "cannot read an image: no %s", path ? "image" : "path");
    im->width = im->height = 0;
    im->rgb = NULL;
    if ((st = lookup(path, "read", &fmt, d)) != MCRT_OK)
        return st;
    f = fopen(path, "rb");
    if (!f)
        return mc_fail(d, MCRT_ERR_IO, "cannot read '%s': %s", path, strerror(errno));
    st = fmt->read(f, &got, d);
    fclose(f);
    if (st != MCRT_OK)
        return explain(d, st, "read", path);
    *im = got;
    return MCRT_OK;
}

mcrt_status mc_image_read_layers(const char *path, const char *const *layers, int n,
                                 struct image *ims, mc_diag *d)
{
    const struct image_format *fmt;
    FILE *f;
    mcrt_status st;
    int i;

    if (!path || !ims || !layers || n < 1)
        return mc_fail(d, MCRT_ERR_INVALID, "cannot read an image: no %s",
                       path ? "layers" : "path");
    for (i = 0; i < n; i++) {
        ims[i].width = ims[i].height = 0;
        ims[i].rgb = NULL;
    }
    if ((st = lookup(path, "read", &fmt, d)) != MCRT_OK)
        return st;
    if (fmt != &mc_exr_format)
        return mc_fail(d, MCRT_ERR_UNSUPPORTED,
                       "cannot read layer '%s' of '%s': only EXR images have layers", layers[0],
                       path);
    f = fopen(path, "rb");
    if (!f)
        return mc_fail(d, MCRT_ERR_IO, "cannot read '%s': %s", path, strerror(errno));
    st = mc_exr_read_layers(f, layers, n, ims, d);
    fclose(f);
    return st != MCRT_OK ? explain(d, st, "read", path) : MCRT_OK;
}

void mc_image_free(struct image *im)
{
    if (!im)
        return;
    free(im->rgb);
    im->rgb = NULL;
    im->width = im->height = 0;
}

mcrt_status mc_image_read_words(const char *path, struct image_words *words, char **text, int *w,
                                int *h, mc_diag *d)
{
    const struct image_format *fmt;
    FILE *f;
    mcrt_status st;
    words->data = NULL;
    *text = NULL;
    if ((st = lookup(path, "read", &fmt, d)) != MCRT_OK)
        return st;
    if (fmt != &mc_exr_format)
        return mc_fail(d, MCRT_ERR_UNSUPPORTED,
                       "cannot read '%s': only EXR images hold a render state", path);
    f = fopen(path, "rb");
    if (!f)
        return mc_fail(d, MCRT_ERR_IO, "cannot read '%s': %s", path, strerror(errno));
    st = mc_exr_read_words(f, words, text, w, h, d);
    fclose(f);
    return st == MCRT_OK ? st : explain(d, st, "read", path);
}
