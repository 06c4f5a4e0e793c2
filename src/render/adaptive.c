/* adaptive.c: per-pixel sample allocation for adaptive progressive passes (see adaptive.h):
 * water-filling of the relMSE-optimal counts (Lagrange multipliers, as in Neyman allocation for
 * stratified sampling, Cochran 1977 §5.5), mixed with a uniform share (Hesterberg 1995). */
#include "render/adaptive.h"

#include <math.h>
#include <stdlib.h>

#include "core/alloc.h"

int mc_adaptive_init(struct adaptive *a, size_t pixels)
{
    a->pixels = pixels;
    a->weight = mc_malloc(pixels * sizeof *a->weight);
    a->counts = mc_malloc(pixels * sizeof *a->counts);
    if (a->weight && a->counts)
        return 0;
    mc_adaptive_free(a);
    return -1;
}

void mc_adaptive_free(struct adaptive *a)
{
    free(a->weight);
    free(a->counts);
    a->weight = NULL;
    a->counts = NULL;
}

int mc_adaptive_pass_spp(int spp)
{
    /* Passes of 1/8 of the budget: the first, uniform, for the estimates, then seven that refine
     * them as they go. At least 8 samples (a variance from fewer is too rough to act on). */
    int pass = (spp + 7) / 8;
    return pass >= 8 ? pass : spp < 8 ? spp : 8;
}

/* The error weight of one pixel (its square root, w_i below): Σ_c σ_c²/(μ_c² + ε), σ² the
 * per-sample variance of all its samples, both halves pooled, and μ² as mc_film_mean_squared; -1
 * when the pixel has fewer than 2 samples. Pooled whatever the sampler, not from the halves as
 * the film's error estimate is for stratified and Sobol samples (film.h): the halves' (A − B)²
 * has one degree of freedom, so the pixels where it happened to come out small would get few
 * samples and keep that small estimate, and the image's estimate would read low (Cornell box,
 * 48², 64 spp, 8 seeds: 0.35 of the true relMSE, stratified and Sobol alike). The pooled s² has
 * n − 1, and is nearly independent of A − B. For stratified samples it is too large (film.h),
 * by a factor much alike from pixel to pixel, which the allocation, proportional to w_i,
 * divides out. */
static double pixel_weight(const struct film_pixel *p)
{
    struct film_sums all = mc_film_pixel_sums(p);
    double sum = 0.0;
    int c;
    if (all.count < 2)
        return -1.0;
    for (c = 0; c < 3; c++)
        sum += all.m2[c] / (double)(all.count - 1) / (mc_film_mean_squared(p, c) + MC_RELMSE_EPS);
    return sqrt(sum);
}

/* Σ_i max(0, s·w_i − n_i): the samples the pixels lack of the targets s·w_i. */
static double deficit(const struct adaptive *a, const struct film *f, double s)
{
    double sum = 0.0;
    size_t i;
    for (i = 0; i < a->pixels; i++) {
        double d = s * a->weight[i] - (double)mc_film_count(&f->pixels[i]);
        sum += d > 0.0 ? d : 0.0;
    }
    return sum;
}

/* The allocation. Pixel i with n_i samples of per-sample variance σ_ic² and mean μ_ic adds
 * σ_ic²/(n_i (μ_ic² + ε)) to the image's relMSE (summed over channels c, up to the constant 1/3P),
 * i.e. A_i/n_i with A_i = Σ_c σ_ic²/(μ_ic² + ε). Minimising Σ_i A_i/n_i subject to Σ_i n_i = N:
 * the Lagrangian Σ A_i/n_i + λ(Σ n_i − N) is stationary where −A_i/n_i² + λ = 0, so
 *     n_i = sqrt(A_i/λ) ∝ w_i = sqrt(A_i)  (= σ_i/sqrt(μ_i² + ε) for one channel),
 * and the minimum is (Σ w_i)²/N against uniform's P·Σ A_i/N: the gain is the ratio of the mean
 * of w² to the square of the mean of w, large when few pixels hold most of the error. With the
 * samples already taken as lower bounds n_i ≥ n_i⁰ (Karush–Kuhn–Tucker), the optimum is
 * n_i = max(n_i⁰, s·w_i) for the s that spends the budget: water-filling; s is found by bisection
 * (the deficit is continuous and nondecreasing in s). The estimates of w_i replace the truth.
 *
 * Starvation. A pixel whose first samples all missed a small bright feature (a caustic, a light
 * seen through a gap) has s² = 0 and would never be sampled again, and the image would keep its
 * error there for ever. So a share MC_ADAPTIVE_UNIFORM (α) of every pass goes to every pixel
 * alike, a defensive mixture (Hesterberg 1995, "Weighted average importance sampling and
 * defensive mixture distributions", Technometrics 37(2)): each pixel keeps sampling at ≥ α times
 * the uniform rate, so its variance is at most 1/α times uniform's and every pixel converges,
 * while the water-filled share (1 − α) keeps the image within 1/(1 − α) of the estimated optimum.
 * α = 0.2: at most 25% above the optimum, at worst 5× uniform's variance in a pixel whose
 * estimate is wrong. A prior on the variance was the alternative; the mixture needs no scale.
 * Pixels without an estimate (too few samples) take the mean weight.
 *
 * Bias. The counts depend on the samples already taken, so a pixel's mean is a ratio with a
 * random denominator and is biased by O(1/n) (Kirk and Arvo 1991, "Unbiased sampling techniques
 * for image synthesis", SIGGRAPH): e.g. a pixel whose early samples came out high gets a smaller
 * share. Every pixel's count grows without bound, so the render is consistent; Kirk and Arvo's
 * cure, discarding the samples that chose the counts, would throw away the first pass. */
uint64_t mc_adaptive_allocate(struct adaptive *a, const struct film *f, uint64_t budget)
{
    double mean_pass = (double)budget / (double)a->pixels, wsum = 0.0, nsum = 0.0, known = 0.0;
    double spread = (1.0 - MC_ADAPTIVE_UNIFORM) * (double)budget, lo = 0.0, hi, got, scale;
    double cap = MC_ADAPTIVE_MAX_RATIO * ceil(mean_pass), prefix = 0.0, uniform;
    uint64_t given = 0;
    size_t i;
    for (i = 0; i < a->pixels; i++) {
        a->weight[i] = pixel_weight(&f->pixels[i]);
        nsum += (double)mc_film_count(&f->pixels[i]);
        if (a->weight[i] >= 0.0) {
            wsum += a->weight[i];
            known += 1.0;
        }
    }
    for (i = 0; i < a->pixels; i++)
        if (a->weight[i] < 0.0)
            a->weight[i] = known > 0.0 ? wsum / known : 1.0;
    wsum = 0.0;
    for (i = 0; i < a->pixels; i++)
        wsum += a->weight[i];
    /* No error anywhere (a black or constant image): the pass is uniform. */
    if (!(wsum > 0.0))
        spread = 0.0;
    uniform = ((double)budget - spread) / (double)a->pixels;
    /* At s = (Σ n + spread)/Σ w the deficit is at least s·Σ w − Σ n = spread. 40 halvings leave
     * s within 2^-40 of its value, and the rescaling below spends the rest exactly. */
    hi = spread > 0.0 ? (nsum + spread) / wsum : 0.0;
    for (i = 0; i < 40 && spread > 0.0; i++) {
        double mid = 0.5 * (lo + hi);
        if (deficit(a, f, mid) < spread)
            lo = mid;
        else
            hi = mid;
    }
    got = spread > 0.0 ? deficit(a, f, hi) : 0.0;
    scale = got > 0.0 ? spread / got : 0.0;
    /* Real-valued counts rounded by their running sum, so that they add up to the budget exactly
     * and each pixel's count is within 1 of its share. */
    for (i = 0; i < a->pixels; i++) {
        double d = hi * a->weight[i] - (double)mc_film_count(&f->pixels[i]);
        double share = uniform + (d > 0.0 ? d * scale : 0.0);
        double before = floor(prefix + 0.5);
        int n;
        prefix += share;
        n = (int)(floor(prefix + 0.5) - before);
        if ((double)n > cap) {
            prefix -= (double)n - cap; /* the excess is not given to the next pixel either */
            n = (int)cap;
        }
        a->counts[i] = n;
        given += (uint64_t)n;
    }
    return given;
}

void mc_adaptive_count_range(const struct film *f, uint64_t *min, uint64_t *max)
{
    size_t i, n = (size_t)f->width * (size_t)f->height;
    *min = n ? mc_film_count(&f->pixels[0]) : 0;
    *max = *min;
    for (i = 1; i < n; i++) {
        uint64_t k = mc_film_count(&f->pixels[i]);
        *min = k < *min ? k : *min;
        *max = k > *max ? k : *max;
    }
}
