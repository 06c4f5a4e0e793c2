/* diff.h: comparing a rendered image with a reference: error statistics (MSE, relative MSE, PSNR,
 * bias) over a pixel window, and a per-pixel z-test against the render's own variance estimate,
 * as Mitsuba 3's render tests do it (Jakob et al. 2022, src/render/tests/test_render.py). */
#ifndef MCRT_DIFF_H
#define MCRT_DIFF_H

#include <stddef.h>

#include "io/image.h"

/* A pixel window [x0, x1) × [y0, y1). */
struct diff_rect {
    int x0, y0, x1, y1;
};

struct diff_stats {
    size_t pixels;
    double mse;        /* mean over pixels and channels of (t − r)² */
    double relmse;     /* mean over pixels and channels of (t − r)² / (r² + 0.01) */
    double psnr;       /* 10 log10(1 / mse) in dB, peak 1 (display white); +inf when mse is 0 */
    double max_abs;    /* largest |t − r| */
    double bias;       /* mean over pixels and channels of t − r */
    double bias_rgb[3];
};

/* Error statistics of test against ref (same size) over rect (inside both). */
void mc_diff_stats(const struct image *test, const struct image *ref, struct diff_rect rect,
                   struct diff_stats *out);

struct diff_ztest {
    /* In: */
    double floor;      /* added in quadrature to each standard deviation: the reference's own error */
    double alpha;      /* family-wise significance over all pixels and channels, e.g. 0.01 */
    /* Out: */
    size_t pixels, rejected;  /* pixels with any channel significant */
    double alpha_test;        /* Šidák per-test level: 1 − (1 − alpha)^(1/tests) */
    double z_crit;            /* |z| above which a channel is significant */
    double agree;             /* fraction of pixels not rejected */
    double max_z;
};

/* z = |t − r| / sqrt(var + floor²) per pixel and channel over rect; var holds the variance of
 * test's pixel means. A channel is significant when its two-sided p-value erfc(z/√2) is below the
 * Šidák level for 3·pixels tests. z_image, if not NULL, gets each pixel's largest z (rect-sized,
 * rows top to bottom). A channel with var + floor² <= 0 gets z = 0 when t = r and +inf otherwise. */
void mc_diff_ztest(const struct image *test, const struct image *ref, const struct image *var,
                   struct diff_rect rect, struct diff_ztest *z, float *z_image);

/* A false-colour picture of n z values for people: black at 0 rising to blue at z_crit, then red
 * turning yellow at 2·z_crit and above (rgb gets 3n linear floats). */
void mc_diff_zcolour(const float *z, size_t n, double z_crit, float *rgb);

#endif
