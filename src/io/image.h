/* image.h: reading and writing float RGB images (PNG, OpenEXR, PFM), chosen by file suffix.
 * The only module that touches libpng or OpenEXR; linear to sRGB conversion happens only here. */
#ifndef MCRT_IMAGE_H
#define MCRT_IMAGE_H

#include <stdint.h>

#include "core/diag.h"

struct image {
    int width, height;
    float *rgb;      /* 3 floats per pixel, linear, rows top to bottom; owned */
};

/* Whether this build supports a suffix ("png", "exr", "pfm", with or without the dot). */
int mc_image_supported(const char *suffix);
/* Write rgb (w·h·3 floats, linear) to path: to a temporary file in the same folder, renamed over
 * path only when complete. PNG gets 8-bit sRGB with an sRGB chunk; EXR float R,G,B; PFM float. */
mcrt_status mc_image_write(const char *path, const float *rgb, int w, int h, mc_diag *d);
/* Read an image into im (linear RGB; PNG is decoded from sRGB). */
mcrt_status mc_image_read(const char *path, struct image *im, mc_diag *d);
void mc_image_free(struct image *im);

/* One RGB layer of a multi-layer image: name NULL or "" for the main R, G, B channels. */
struct image_layer {
    const char *name;
    const float *rgb; /* w·h·3 floats, linear */
};
/* Write n >= 1 layers of w×h pixels (crash-safe as mc_image_write). More than one layer, or a
 * named one, needs EXR (channels LAYER.R, .G, .B); other formats are refused. */
mcrt_status mc_image_write_layers(const char *path, const struct image_layer *layers, int n, int w,
                                  int h, mc_diag *d);
/* Exact data an EXR carries beside its layers (a render's state, render/state.h): per_pixel
 * 32-bit words per pixel as the UINT channels NAME.00, NAME.01, ..., and a text as the string
 * attribute NAME of the header. */
struct image_words {
    const char *name;  /* "mcrtState" */
    int per_pixel;     /* 1 to 99 */
    const char *text;  /* written into the header */
    uint32_t *data;    /* w·h·per_pixel words, rows top to bottom */
};
/* mc_image_write_layers with words beside the layers; path must be an EXR. */
mcrt_status mc_image_write_words(const char *path, const struct image_layer *layers, int n,
                                 const struct image_words *words, int w, int h, mc_diag *d);
/* Read the words called words->name (per_pixel of them) of an EXR: words->data and *text are
 * allocated (the caller frees both; nothing to free on failure), *w and *h the image's size. */
mcrt_status mc_image_read_words(const char *path, struct image_words *words, char **text, int *w,
                                int *h, mc_diag *d);
/* Whether path's suffix is a format that holds named layers (EXR, in a build with it). */
int mc_image_layered(const char *path);
/* Read the named layer (NULL: as mc_image_read). Only EXR files have named layers. */
mcrt_status mc_image_read_layer(const char *path, const char *layer, struct image *im,
                                mc_diag *d);
/* Read n named layers of an EXR into ims[0..n-1] (freed again on failure), decompressing the
 * file once: n reads of one layer each decompress all of it (the denoiser's 11 layers of a 512²
 * render took 1.3 s that way). */
enum { MC_IMAGE_MAX_LAYERS = 33 };
mcrt_status mc_image_read_layers(const char *path, const char *const *layers, int n,
                                 struct image *ims, mc_diag *d);

#endif
