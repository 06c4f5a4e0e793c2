/* distrib.h: tabulated distributions sampled by inverting their CDF — a piecewise-constant
 * density on an interval (1D, also usable as a discrete distribution over its bins) and on the
 * unit square (2D: a marginal over rows, then a conditional within the row), as environment
 * maps need (light/envmap.c samples their pixels by luminance × sin θ with the 2D one). After
 * pbrt-v4 PiecewiseConstant1D/2D (Pharr, Jakob and Humphreys, §A.4).
 *
 * Conventions shared by both:
 * - Input values must be finite and >= 0 (MCRT_ERR_INVALID otherwise). An all-zero function
 *   falls back to the uniform distribution (pdf 1/(max − min), pmf 1/n; integral 0).
 * - The CDF is accumulated and stored in double, so every bin is sampled with its probability
 *   f_i/Σf to ~1e-16 absolute; pdfs and pmfs are returned in float. A bin whose float pdf or pmf
 *   would underflow to 0 (probability below ~1e-45) is treated as zero, so that a sample never
 *   carries pdf 0 and pdf > 0 exactly where samples can land.
 * - Uniform inputs u are double in [0, 1). A float u (24 bits) converts exactly and works, but
 *   then bins of probability below ~2^-24 are realised only to within 2^-24; pass a 53-bit u
 *   (pcg32_double) where such bins matter.
 * - The structures own their arrays: a successful build must be paired with the matching
 *   _free. A failed build leaves the structure empty (nothing to free; _free is a no-op on it). */
#ifndef MCRT_DISTRIB_H
#define MCRT_DISTRIB_H

#include <stddef.h>

#include "core/diag.h"
#include "core/vec.h"

/* Piecewise-constant density on [min, max) with `count` equal bins. */
struct mc_distrib1d {
    float *func;     /* the count values (negligible ones zeroed, see above) */
    double *cdf;     /* count + 1 entries: cdf[0] = 0, cdf[count] = 1, non-decreasing */
    double sum;      /* Σ func; 0 for the all-zero function (sampled uniformly) */
    float min, max;
    size_t count;
};

/* Build from f[0..n), n >= 1, over [min, max) (finite, min < max). The values are copied.
 * MCRT_ERR_INVALID for bad arguments, MCRT_ERR_NOMEM when out of memory. */
mcrt_status mc_distrib1d_build(struct mc_distrib1d *d, const float *f, size_t n, float min, float max,
                               mc_diag *diag);
void mc_distrib1d_free(struct mc_distrib1d *d);

/* Continuous sample for u in [0, 1): x in [min, max) with density pdf(x); *pdf (may be NULL)
 * receives it and *offset (may be NULL) the bin containing x, which is never a zero bin. */
float mc_distrib1d_sample(const struct mc_distrib1d *d, double u, float *pdf, size_t *offset);
/* Density at x per unit length: f(x)/∫f; 0 outside [min, max). */
float mc_distrib1d_pdf(const struct mc_distrib1d *d, float x);
/* ∫f over [min, max) = Σf·(max − min)/n (0 for the all-zero function). */
double mc_distrib1d_integral(const struct mc_distrib1d *d);
/* Inverse of mc_distrib1d_sample: stores in *u the u in [0, 1] that maps to x and returns 1, or
 * returns 0 when x is outside [min, max). Every x of a zero bin maps to the same u. */
int mc_distrib1d_invert(const struct mc_distrib1d *d, float x, double *u);

/* Discrete sample for u in [0, 1): a bin index with probability f_i/Σf; *pmf (may be NULL)
 * receives that probability. */
size_t mc_distrib1d_sample_discrete(const struct mc_distrib1d *d, double u, float *pmf);
/* Probability of bin i under mc_distrib1d_sample_discrete; 0 when i >= count. */
float mc_distrib1d_pmf(const struct mc_distrib1d *d, size_t i);

/* Piecewise-constant density on the unit square [0,1)² from an nx × ny table, row-major:
 * value (i, j) is f[j·nx + i] and covers x ∈ [i/nx, (i+1)/nx), y ∈ [j/ny, (j+1)/ny). */
struct mc_distrib2d {
    struct mc_distrib1d marginal; /* over y: each row's sum relative to the largest row's */
    struct mc_distrib1d *rows;    /* ny conditionals over x; their arrays live in func and cdf */
    float *func;                  /* nx·ny values, row-major, negligible ones zeroed */
    double *cdf;                  /* ny·(nx + 1) row CDFs */
    double mean;                  /* mean value = ∫∫f; 0 for the all-zero function */
    size_t nx, ny;
};

/* Build from f[0..nx·ny), nx, ny >= 1; errors as mc_distrib1d_build. */
mcrt_status mc_distrib2d_build(struct mc_distrib2d *d, const float *f, size_t nx, size_t ny,
                               mc_diag *diag);
void mc_distrib2d_free(struct mc_distrib2d *d);

/* Sample (x, y) in [0,1)²: uy chooses the row through the marginal, ux the position within it.
 * *pdf (may be NULL) receives the density per unit area, equal to mc_distrib2d_pdf(x, y). */
vec2 mc_distrib2d_sample(const struct mc_distrib2d *d, double ux, double uy, float *pdf);
/* Density per unit area at (x, y): f(x, y)/∫∫f; 0 outside [0,1)². */
float mc_distrib2d_pdf(const struct mc_distrib2d *d, float x, float y);
/* ∫∫f over the unit square (the mean of the table). */
double mc_distrib2d_integral(const struct mc_distrib2d *d);

#endif
