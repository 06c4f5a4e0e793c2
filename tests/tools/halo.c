/* halo.c: what a denoiser did around the outliers of a render, for tests/denoise_stiff.sh.
 * usage: halo RAW DEN REF [RADIUS]  (images by suffix, IN:LAYER for an EXR's layer; src/io)
 *
 * An outlier (a firefly) is a pixel whose raw value is more than 4 times the reference's plus
 * 0.1, in luminance (Rec. 709 weights). Its ring is the pixels within RADIUS (default 3) of an
 * outlier that are no outlier themselves. Over the ring, the excess over the reference, the mean
 * of luminance(image − reference), for the raw and the denoised image, and the raw excess's
 * standard error (the spread of the raw ring pixels' luminance error over the root of their
 * count): a denoiser that smears a firefly over its neighbours raises their excess above the
 * raw's, which is the raw's own noise there. Prints one line of NAME VALUE pairs:
 *   pixels N nonfinite N negative N min X outliers N ring N raw_excess X den_excess X se X
 * where nonfinite, negative and min are the denoised image's (min: its lowest channel value). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/image.h"

static double lum(const float *p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

static int load(char *arg, struct image *im)
{
    char *layer = strrchr(arg, ':');
    mc_diag d;
    if (layer)
        *layer++ = '\0';
    if (mc_image_read_layer(arg, layer, im, &d) != MCRT_OK) {
        fprintf(stderr, "halo: %s\n", d.msg);
        return -1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    struct image raw, den, ref;
    int radius = argc > 4 ? atoi(argv[4]) : 3, w, h, x, y, dx, dy, c;
    long nonfinite = 0, negative = 0, outliers = 0, ring = 0;
    double lo = INFINITY, sraw = 0.0, sraw2 = 0.0, sden = 0.0, se;
    unsigned char *out;
    if (argc < 4 || argc > 5 || radius < 1 || radius > 64) {
        fprintf(stderr, "usage: halo RAW DEN REF [RADIUS]\n");
        return 2;
    }
    if (load(argv[1], &raw) || load(argv[2], &den) || load(argv[3], &ref))
        return 2;
    w = raw.width;
    h = raw.height;
    if (den.width != w || den.height != h || ref.width != w || ref.height != h) {
        fprintf(stderr, "halo: the three images differ in size\n");
        return 2;
    }
    if (!(out = calloc((size_t)w * (size_t)h, 1))) {
        fprintf(stderr, "halo: out of memory\n");
        return 2;
    }
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            for (c = 0; c < 3; c++) {
                float v = den.rgb[3 * i + (size_t)c];
                nonfinite += !isfinite(v);
                negative += v < 0.0f;
                if (v < lo)
                    lo = v;
            }
            out[i] = lum(raw.rgb + 3 * i) > 4.0 * lum(ref.rgb + 3 * i) + 0.1;
            outliers += out[i];
        }
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            int near = 0;
            if (out[i])
                continue;
            for (dy = -radius; dy <= radius && !near; dy++)
                for (dx = -radius; dx <= radius && !near; dx++)
                    near = x + dx >= 0 && x + dx < w && y + dy >= 0 && y + dy < h
                           && out[(size_t)(y + dy) * (size_t)w + (size_t)(x + dx)];
            if (near) {
                double r = lum(raw.rgb + 3 * i) - lum(ref.rgb + 3 * i);
                ring++;
                sraw += r;
                sraw2 += r * r;
                sden += lum(den.rgb + 3 * i) - lum(ref.rgb + 3 * i);
            }
        }
    se = ring > 1 ? sqrt((sraw2 - sraw * sraw / (double)ring) / (double)(ring - 1) / (double)ring)
                  : 0.0;
    printf("pixels %ld nonfinite %ld negative %ld min %.6g outliers %ld ring %ld raw_excess %.6g "
           "den_excess %.6g se %.6g\n",
           (long)w * h, nonfinite, negative, lo, outliers, ring, ring ? sraw / ring : 0.0,
           ring ? sden / ring : 0.0, se);
    free(out);
    mc_image_free(&raw);
    mc_image_free(&den);
    mc_image_free(&ref);
    return 0;
}
