/* crops.c: the same window of several images, each enlarged by a whole factor (nearest
 * neighbour, so that every pixel's noise stays visible as a square) and set side by side, 2
 * pixels of white between them, into one image: for the README's raw, denoised and reference
 * crops (tests/tools/denoise_figures.sh), and with one image and a factor 1 for reading one
 * layer of an EXR out as a plain image (tests/denoise_use.sh).
 * usage: crops OUT X0,Y0,X1,Y1 SCALE IN[:LAYER]...  (formats by suffix, through src/io) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/image.h"

enum { GAP = 2, MAX_INPUTS = 8 };

int main(int argc, char **argv)
{
    struct image im;
    int x0, y0, x1, y1, scale, n = argc - 4, k, x, y, w, cw, ch, width;
    float *out;
    mc_diag d;
    if (argc < 5 || n > MAX_INPUTS ||
        sscanf(argv[2], "%d,%d,%d,%d", &x0, &y0, &x1, &y1) != 4 || x0 < 0 || y0 < 0 ||
        x1 <= x0 || y1 <= y0 || (scale = atoi(argv[3])) < 1 || scale > 64) {
        fprintf(stderr, "usage: crops OUT X0,Y0,X1,Y1 SCALE IN[:LAYER]... (up to %d images)\n",
                MAX_INPUTS);
        return 2;
    }
    cw = (x1 - x0) * scale;
    ch = (y1 - y0) * scale;
    width = n * cw + (n - 1) * GAP;
    if (!(out = malloc((size_t)width * (size_t)ch * 3 * sizeof *out))) {
        fprintf(stderr, "crops: out of memory\n");
        return 1;
    }
    for (k = 0; k < width * ch * 3; k++)
        out[k] = 1.0f;
    for (k = 0; k < n; k++) {
        char *path = argv[4 + k], *layer = strrchr(path, ':');
        if (layer)
            *layer++ = '\0';
        if (mc_image_read_layer(path, layer, &im, &d) != MCRT_OK) {
            fprintf(stderr, "crops: %s\n", d.msg);
            return 1;
        }
        if (x1 > im.width || y1 > im.height) {
            fprintf(stderr, "crops: %s is %dx%d, smaller than the window\n", path, im.width,
                    im.height);
            return 1;
        }
        w = im.width;
        for (y = 0; y < ch; y++)
            for (x = 0; x < cw; x++) {
                const float *src = im.rgb + 3 * ((size_t)(y0 + y / scale) * w + x0 + x / scale);
                memcpy(out + 3 * ((size_t)y * width + k * (cw + GAP) + x), src, 3 * sizeof *src);
            }
        mc_image_free(&im);
    }
    if (mc_image_write(argv[1], out, width, ch, &d) != MCRT_OK) {
        fprintf(stderr, "crops: %s\n", d.msg);
        return 1;
    }
    free(out);
    return 0;
}
