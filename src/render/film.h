/* film.h: per-pixel accumulation of samples: running mean and sum of squared deviations in double
 * (Welford 1962), so that long accumulations neither drift nor lose small values next to large
 * ones, and the variance of each pixel mean is known. Box filter: a pixel is the mean of its
 * samples. */
#ifndef MCRT_FILM_H
#define MCRT_FILM_H

#include <stddef.h>
#include <stdint.h>

#include "core/vec.h"

struct film_pixel {
    double mean[3];
    double m2[3];   /* Σ (x − mean)² */
    uint64_t count;
};

struct film {
    int width, height;
    struct film_pixel *pixels;
};

/* Allocate a zeroed W×H film. Returns 0, or -1 when out of memory (or W·H overflows). */
int mc_film_init(struct film *f, int width, int height);
void mc_film_free(struct film *f);

static inline void mc_film_add(struct film_pixel *p, vec3 v)
{
    double x[3];
    int c;
    x[0] = v.x;
    x[1] = v.y;
    x[2] = v.z;
    p->count++;
    for (c = 0; c < 3; c++) {
        double delta = x[c] - p->mean[c];
        p->mean[c] += delta / (double)p->count;
        p->m2[c] += delta * (x[c] - p->mean[c]);
    }
}

/* The pixel means as linear RGB floats, rows top to bottom (rgb holds W·H·3 floats). */
void mc_film_resolve(const struct film *f, float *rgb);

#endif
