/* film.h: per-pixel accumulation of samples, and the error of each pixel's mean estimated from
 * the samples themselves.
 *
 * A pixel's samples come in two halves, each an independent randomization of the sampler: half h
 * draws its samples as a complete set of the sampler of its own size, keyed by its own seed
 * (render.c, mc_film_half_seed). The two half means A and B are then independent, identically
 * distributed (equal sizes) and unbiased, whatever the sampler does inside a half, so
 *     E[(A − B)²] = Var(A) + Var(B) = 2·Var(A), and the pixel mean m = (A + B)/2 has
 *     Var(m) = Var(A)/2, estimated without bias by (A − B)²/4
 * (randomized quasi-Monte Carlo replicates: Owen 1997, "Monte Carlo variance of scrambled net
 * quadrature", SIAM J. Numer. Anal. 34(5); L'Ecuyer and Lemieux 2002, "Recent advances in
 * randomized quasi-Monte Carlo methods", §3). For halves of nA and nB samples, (A − B)²·nA·nB/n²,
 * exact when the variance of a half falls as 1/n. The independent-sample formula s²/n is biased
 * up for stratified and Sobol samples, whose correlation lowers the variance of the mean (by 1.6x
 * at 64 spp on the Cornell box). With independent samples (the random sampler) the pooled sample
 * variance s²/n is unbiased too and has n − 1 degrees of freedom instead of 1; the film uses it
 * when `pooled` is set, as it is for the random sampler: over five scenes of scenes/, its
 * estimated over true relMSE measured 0.83 to 1.08 (median 0.96 to 0.99 at 16, 64 and 256 spp)
 * against the halves' 0.95 to 1.39 (median 1.00 to 1.13). Two halves rather than K > 2 groups: a stratified or Sobol set of n/K
 * samples converges less well than one of n, and the loss grows with K (README, "error
 * estimate"); two are also the two buffers an image-space denoiser takes (the `halves` AOV).
 *
 * Each half keeps a running mean and sum of squared deviations in double (Welford 1962), so that
 * long accumulations neither drift nor lose small values next to large ones. Box filter: a pixel
 * is the mean of its samples. */
#ifndef MCRT_FILM_H
#define MCRT_FILM_H

#include <stddef.h>
#include <stdint.h>

#include "core/vec.h"

/* The samples of one half of a pixel. */
struct film_sums {
    double mean[3];
    double m2[3];   /* Σ (x − mean)² */
    uint64_t count;
};

struct film_pixel {
    struct film_sums half[2];
};

struct film {
    int width, height;
    /* Nonzero when a pixel's samples are independent (the random sampler): its error is then
     * estimated from the pooled sample variance; otherwise from the two half means. */
    int pooled;
    struct film_pixel *pixels;
};

/* Allocate a zeroed W×H film. Returns 0, or -1 when out of memory (or W·H overflows). */
int mc_film_init(struct film *f, int width, int height);
void mc_film_free(struct film *f);

/* The seed of half h (0 or 1) of a pass of this seed: half 0 keeps it. Any h >= 0 gives an
 * independent seed (sppm.c keys its four groups of passes by it). */
uint64_t mc_film_half_seed(uint64_t seed, int h);

/* How many of a pass's n samples of a pixel go to half 0 (the rest go to half 1): half of them,
 * the odd one to half 0 in even passes and to half 1 in odd ones, so that passes of one sample
 * fill both halves alike. */
static inline int mc_film_half_split(int n, int pass) { return (n + 1 - (pass & 1)) / 2; }

static inline void mc_film_add(struct film_sums *p, vec3 v)
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

/* Add the samples of src (same size) to dst, half by half: the means and M2 combine exactly as
 * if dst had seen src's samples after its own (Chan, Golub and LeVeque 1979). A half of dst with
 * no samples becomes a copy of src's, bit for bit. */
void mc_film_merge(struct film *dst, const struct film *src);
/* mc_film_merge into the window of dst whose top-left pixel is (x0, y0), src's size, which must
 * lie inside dst: the assembly of crops, and the merge of renders of one crop. */
void mc_film_merge_at(struct film *dst, int x0, int y0, const struct film *src);
/* Remove every sample (the film keeps its size). */
void mc_film_clear(struct film *f);

/* The samples of a pixel, both halves. */
static inline uint64_t mc_film_count(const struct film_pixel *p)
{
    return p->half[0].count + p->half[1].count;
}
/* Both halves of p as one: the mean and M2 of all its samples. */
struct film_sums mc_film_pixel_sums(const struct film_pixel *p);

/* The estimated variance of p's mean per channel into var (pooled or from the halves, as f says);
 * returns 0 when p has no estimate (fewer than 2 samples, or pooled off and a half empty). */
int mc_film_pixel_variance(const struct film *f, const struct film_pixel *p, double var[3]);

/* An estimate of the square of p's expected value in channel c, for the denominator of relative
 * errors: the product of the two half means, A·B, whose expectation is exactly μ² (the halves
 * are independent), where the pixel mean's square m² is biased up by Var(m) and grows with the
 * variance estimate (A − B)² in the numerator: a rare bright sample in one half raises m² by its
 * square but A·B only in proportion, so that a firefly's relative error is not all hidden by
 * itself. A·B is floored at m²/2 (halves differing more than 5.8 times): a pixel whose halves
 * hold 0 and 3 hits of a small light seen directly has A·B far below μ², and without the floor
 * such pixels made the estimate 1.64 times the truth on a small Cornell box and 1.33 on the
 * depth-of-field scene (0.97 and 0.95 with it; m² alone: 0.97 and 0.77, and 0.46 against A·B's
 * 0.73 on the fireflies of `spheres` at 16 spp, 0.62 with the floor). m² when a half is empty. */
double mc_film_mean_squared(const struct film_pixel *p, int c);

/* The pixel means as linear RGB floats, rows top to bottom (rgb holds W·H·3 floats). */
void mc_film_resolve(const struct film *f, float *rgb);
/* The means of half h alone, as mc_film_resolve (0 where the half is empty). */
void mc_film_resolve_half(const struct film *f, int h, float *rgb);

/* The estimated variance of each pixel mean (mc_film_pixel_variance), per channel as W·H·3
 * floats, 0 where a pixel has no estimate. */
void mc_film_variance(const struct film *f, float *var);
/* The variance of half h's mean from that half's own samples, s²/n (s² = M2/(n − 1)), per channel
 * as W·H·3 floats. Unbiased for independent samples and biased up for stratified and Sobol ones
 * (film.h above), but of n − 1 degrees of freedom and, unlike (A − B)²/2, a function of that half
 * alone. A half of one sample has no s²; its variance is then taken from the halves' difference,
 * (A − B)²·n_other/(n_h + n_other), as the halves of a pixel are independent (0 where either
 * half is empty). */
void mc_film_half_variance(const struct film *f, int h, float *var);

/* The ε of the relative MSE, (x − ref)²/(ref² + ε): a floor for black pixels. */
#define MC_RELMSE_EPS 0.01

/* Relative MSE of the image estimated from its own samples (issues 5, 14): the mean over pixels
 * and channels of Var(mean)/(μ² + ε), Var(mean) as in mc_film_pixel_variance and μ² as in
 * mc_film_mean_squared. Pixels without an estimate are left out; NaN when none has one. Paths
 * too rare to have been sampled at all (a caustic seen through glass at 16 spp) are missing
 * from it as from the image (measured in the README, "error estimate"). */
double mc_film_est_relmse(const struct film *f);

#endif
