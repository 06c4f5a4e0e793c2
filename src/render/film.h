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

/* Add the samples of src (same size) to dst, pixel by pixel: the means and M2 combine exactly as
 * if dst had seen src's samples after its own (Chan, Golub and LeVeque 1979). A pixel of dst with
 * no samples becomes a copy of src's, bit for bit. */
void mc_film_merge(struct film *dst, const struct film *src);
/* Remove every sample (the film keeps its size). */
void mc_film_clear(struct film *f);

/* The pixel means as linear RGB floats, rows top to bottom (rgb holds W·H·3 floats). */
void mc_film_resolve(const struct film *f, float *rgb);

/* The estimated variance of each pixel mean, s²/n with s² = M2/(n − 1) the unbiased sample
 * variance, per channel as W·H·3 floats (0 where a pixel has fewer than 2 samples). Exact in
 * expectation for independent samples; stratified and low-discrepancy samplers correlate a pixel's
 * samples, and their true variance is lower than this. */
void mc_film_variance(const struct film *f, float *var);

/* Relative MSE of the image estimated from its own samples (issue 5): the mean over pixels and
 * channels of Var(mean)/(mean² + 0.01), Var(mean) as in mc_film_variance. Pixels with fewer than 2
 * samples carry no estimate and are left out; NaN when no pixel has 2. The mean in the denominator
 * comes from the same samples as the variance, so a rare bright sample (a caustic path) inflates
 * both and the ratio hides part of it. Measured with the random sampler on scenes/ against 4096
 * spp references: 0.6 to 1 times the true relMSE at 16 spp, 0.83 to 1.03 at 64; with the
 * reference's mean in the denominator instead, within 10% at 16 spp. Taking the variance and the
 * mean from disjoint halves of the samples overestimated up to 4x (1/mean² of a half-size mean is
 * biased up, by Jensen's inequality). */
double mc_film_est_relmse(const struct film *f);

#endif
