/* firefly.h: a half buffer's fireflies taken out before the denoiser filters it, and their
 * energy put back after, spread thinly enough to stay below the image's noise.
 *
 * A firefly is a pixel one of whose halves caught a rare, bright path (a caustic found by 1 of a
 * pixel's 2 rays at 4 spp): its two halves disagree far beyond their neighbourhood's spread. The
 * regression and NL-means would spread that half's excess over the pixels whose patches resemble
 * its own, which are its neighbours: a blotch of a few pixels, 2 to 5 standard errors above the
 * reference around cornell-spheres' caustic fireflies. Left in its pixel the excess is kept but
 * is a far larger error (a pixel's error squared against a blotch's: cornell-spheres' relMSE 10 to
 * 40 times the denoised one's at 4 spp, README). So the firefly's bright half takes the other
 * half's value (mc_firefly_split), the denoiser filters the halves so cleaned, and the difference
 * goes back as a normalised Gaussian around its pixel (mc_firefly_spread), wide enough for its
 * peak to stay within a tenth of the pixel mean's local standard error: no energy is lost (the
 * weights sum to 1 over the pixels inside the image), and no halo stands above the noise unless
 * the excess is too large for the widest kernel.
 *
 * As samples grow, a half's excess over the threshold falls with its noise, so the energy moved
 * goes to 0 and the denoiser stays consistent. */
#ifndef MCRT_FIREFLY_H
#define MCRT_FIREFLY_H

/* One firefly: its pixel, its half (0: A, 1: B), the excess taken out of it (RGB) and the mean
 * var of its window's other pixels, the pixel's variance as its neighbourhood shows it. */
struct firefly {
    int pixel, half;
    float excess[3];
    float var;
};

/* Find and take out the fireflies of the halves a and b (W·H·3 floats each, modified in place).
 * var: the channel mean of each pixel's (a − b)²/2, var_box its box mean over a window of
 * `box_pixels` pixels (the pixel's own term included), mean_box the box mean of the channel mean
 * of (a + b)/2 over the same window. A pixel is a firefly when its var exceeds FIREFLY_K² times
 * the mean of the window's other pixels and its bright half (by the channel sum of a − b) exceeds
 * the other by FIREFLY_E times their mean level (firefly.c); its bright half takes the other
 * half's value, and the difference is recorded. *out receives a malloc'ed array (NULL when there
 * is none), *count its length. Returns 0, or -1 when out of memory. */
int mc_firefly_split(float *a, float *b, const float *var, const float *var_box,
                     const float *mean_box, int box_pixels, int width, int height,
                     struct firefly **out, int *count);

/* Add each firefly's excess, halved (the image is the mean of the halves), to rgb as a Gaussian
 * around its pixel, normalised over the pixels inside the image and as wide as keeps its peak
 * within SPREAD_KAPPA of the pixel's standard error se (of the mean, per pixel and channel,
 * W·H·3; firefly.c); and the share's square to mse (when not NULL: the spread excess is noise
 * whose mean is unknown, so its square is its error's estimate). In the order of the array: the
 * same result for any thread count. */
void mc_firefly_spread(const struct firefly *ff, int count, const float *se, int width,
                       int height, float *rgb, float *mse);

#endif
