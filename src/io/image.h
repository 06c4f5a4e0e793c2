/* image.h: reading and writing float RGB images (PNG, OpenEXR, PFM), chosen by file suffix.
 * The only module that touches libpng or OpenEXR; linear to sRGB conversion happens only here. */
#ifndef MCRT_IMAGE_H
#define MCRT_IMAGE_H

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
/* Whether path's suffix is a format that holds named layers (EXR, in a build with it). */
int mc_image_layered(const char *path);
/* Read the named layer (NULL: as mc_image_read). Only EXR files have named layers. */
mcrt_status mc_image_read_layer(const char *path, const char *layer, struct image *im,
                                mc_diag *d);

#endif
