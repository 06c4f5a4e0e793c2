/* formats.h: private to src/io: the per-format readers and writers behind image.c, the shared
 * pixel-count limit and the sRGB transfer function (IEC 61966-2-1). */
#ifndef MCRT_FORMATS_H
#define MCRT_FORMATS_H

#include <math.h>
#include <stdio.h>

#include "io/image.h"

/* Images with more pixels than this are refused (2^28 pixels = 3 GiB of float RGB): a corrupt or
 * hostile header must not make us allocate without bound. */
#define MC_IMAGE_MAX_PIXELS (1L << 28)

/* One file format. The functions work on a file image.c has opened (binary, positioned at 0) and,
 * on failure, leave only the reason in d ("truncated pixel data"); image.c prefixes the path.
 * write and read are NULL when the format's library was not found at build time. */
struct image_format {
    const char *suffix;  /* "png", without the dot */
    const char *library; /* what the format needs, for messages: "OpenEXR"; NULL if built in */
    const char *package; /* the Debian package providing it: "libopenexr-dev" */
    /* Write rgb (w*h*3 floats, linear, rows top to bottom; w, h > 0 and w*h within the limit). */
    mcrt_status (*write)(FILE *f, const float *rgb, int w, int h, mc_diag *d);
    /* Read into im (filled only on success; nothing to free on failure). */
    mcrt_status (*read)(FILE *f, struct image *im, mc_diag *d);
};

extern const struct image_format mc_png_format; /* png.c: 8-bit sRGB via libpng */
extern const struct image_format mc_exr_format; /* exr.c: float RGB via OpenEXRCore */
extern const struct image_format mc_pfm_format; /* pfm.c: portable float map, always built */

/* exr.c, behind mc_image_write_layers and mc_image_read_layers: several RGB layers in one EXR part
 * (unnamed: R, G, B; named: NAME.R, NAME.G, NAME.B), and reading n of them in one pass (layers
 * NULL: n = 1, the first RGB one, as mc_exr_format's read). MCRT_ERR_UNSUPPORTED when built
 * without OpenEXR. */
mcrt_status mc_exr_write_layers(FILE *f, const struct image_layer *layers, int n,
                                const struct image_words *words, int w, int h, mc_diag *d);
mcrt_status mc_exr_read_layers(FILE *f, const char *const *layers, int n, struct image *ims,
                               mc_diag *d);
/* Behind mc_image_read_words. */
mcrt_status mc_exr_read_words(FILE *f, struct image_words *words, char **text, int *w, int *h,
                              mc_diag *d);

/* For readers: check a file's w x h: MCRT_ERR_IO unless 1 <= w, h and w*h <= MC_IMAGE_MAX_PIXELS.
 * d gets the reason only. */
mcrt_status mc_image_check_size(long w, long h, mc_diag *d);
/* mc_image_check_size, then allocate im->rgb (uninitialised); MCRT_ERR_NOMEM when out of memory. */
mcrt_status mc_image_alloc(struct image *im, long w, long h, mc_diag *d);

/* The sRGB transfer function, IEC 61966-2-1 (the exact piecewise curve, not a 2.2 power).
 * Encode clamps to [0, 1] and maps NaN to 0, so any float yields a displayable value. */
static inline float mc_srgb_encode(float linear)
{
    if (!(linear > 0.0f)) /* also catches NaN */
        return 0.0f;
    if (linear >= 1.0f)
        return 1.0f;
    return linear <= 0.0031308f ? 12.92f * linear : 1.055f * powf(linear, 1.0f / 2.4f) - 0.055f;
}
/* The inverse of mc_srgb_encode on [0, 1]. */
static inline float mc_srgb_decode(float encoded)
{
    return encoded <= 0.04045f ? encoded / 12.92f : powf((encoded + 0.055f) / 1.055f, 2.4f);
}

#endif
