/* firefly.c: fireflies taken out of the halves and spread back (see firefly.h). */
#include "denoise/firefly.h"

#include <math.h>
#include <stdlib.h>

#include "core/alloc.h"
#include "core/vec.h"

/* A firefly's halves differ by more than FIREFLY_K standard deviations of its neighbourhood's
 * half differences: var, the channel mean of (a − b)²/2, exceeds 16 times its neighbours' mean.
 * Gaussian noise does that in 2e-10 of the pixels when the channels' noises are independent (χ²₃
 * above 48) and in 6e-5 when they are one (χ²₁ above 16); a pixel with a caustic's path in one
 * half does it at once (cornell-spheres at 4 spp: every pixel more than 4 times the reference). */
#define FIREFLY_K 4.0f
/* And its bright half exceeds the other by more than FIREFLY_E times the mean level of the
 * window's other pixels: a firefly is an outlier of energy, not only of variance. Where a thin
 * bright edge crosses a row of pixels, each half's rays hit it or not, and the halves of those
 * pixels differ as much against their smooth neighbours (tests/stiff/denoise_range.mcrt at 16
 * spp: 11 such pixels, their halves 0.001 and 0.1, at most 0.8 times their window's level); set
 * to the dim half, the row lost its light (the image's relMSE 0.0027 against 0.0014). A caustic's
 * moderate outliers are better left to the regression, which spreads them along its features:
 * cornell-spheres at 16 spp, 400² (make bench-denoise with SIZE=400), lost 27% against the
 * denoiser without this step at a level of 4 and 12% at 16; at 160² it lost 5% at 4 and 2% at 16,
 * and 4 spp's fireflies (48², 10 to 100 times their window's level) lost nothing at 16 (relMSE
 * 0.034 and 0.035 either way, against 0.080 and 0.069 without the step). */
#define FIREFLY_E 16.0f
/* A spread excess's peak, in the mean image, at most SPREAD_KAPPA standard errors of the pixel
 * mean there, so that even the mean over the few hundred pixels around a handful of fireflies
 * stays near its own noise. The wider the spread, the lower the error too (a firefly's energy e
 * over an area a adds about e²/a to the squared error): cornell-spheres at 4 spp (48², seeds 1
 * and 2; tests/denoise_stiff.sh) with κ = 1, 0.5, 0.25, 0.1 and 0.05 had relMSE 0.054 / 0.059,
 * 0.045 / 0.049, 0.040 / 0.042, 0.034 / 0.035 and 0.031 / 0.031, and its fireflies' ring excess
 * 0.036, 0.028, 0.020, 0.013 and 0.009 (standard errors 0.015 and 0.008). */
#define SPREAD_KAPPA 0.1f
/* The widest Gaussian (its weights reach 3 σ): a 97×97 patch. Excesses too large for it keep a
 * halo above the noise rather than move their energy further from where it was found. */
#define SPREAD_SIGMA_MAX 16.0f
#define SPREAD_R_MAX 48

int mc_firefly_split(float *a, float *b, const float *var, const float *var_box,
                     const float *mean_box, int box_pixels, int width, int height,
                     struct firefly **out, int *count)
{
    size_t n = (size_t)width * (size_t)height, p;
    int cap = 0, c;
    *out = NULL;
    *count = 0;
    for (p = 0; p < n; p++) {
        float d = var[p];
        /* The mean of the window's other pixels (its edge pixels repeated at the image's edge,
         * so that there the pixel's own term counts more than once and a firefly is found less
         * readily). */
        float others = (var_box[p] * (float)box_pixels - d) / (float)(box_pixels - 1);
        float *hi, *lo, mean, level;
        struct firefly *f;
        if (!(d > 0.0f) || !isfinite(d) || !(d > FIREFLY_K * FIREFLY_K * fmaxf(others, 0.0f)))
            continue;
        hi = a + 3 * p;
        lo = b + 3 * p;
        if (hi[0] + hi[1] + hi[2] < lo[0] + lo[1] + lo[2]) {
            hi = b + 3 * p;
            lo = a + 3 * p;
        }
        mean = (hi[0] + hi[1] + hi[2] + lo[0] + lo[1] + lo[2]) / 6.0f;
        level = (mean_box[p] * (float)box_pixels - mean) / (float)(box_pixels - 1);
        if (!((hi[0] + hi[1] + hi[2] - lo[0] - lo[1] - lo[2]) / 3.0f > FIREFLY_E * level))
            continue;
        if (*count == cap) {
            int ncap = cap ? 2 * cap : 64;
            struct firefly *grown = mc_realloc(*out, (size_t)ncap * sizeof *grown);
            if (!grown) {
                free(*out);
                *out = NULL;
                *count = 0;
                return -1;
            }
            *out = grown;
            cap = ncap;
        }
        /* The bright half takes the other half's value. Moving it only to the threshold left a
         * bright pixel four standard deviations out for the filters to spread: cornell-spheres
         * at 4 spp, relMSE 0.071 against 0.032 (seed 1, both with a spread of κ = 0.5). */
        f = *out + (*count)++;
        f->pixel = (int)p;
        f->half = hi == b + 3 * p;
        f->var = fmaxf(others, 0.0f);
        for (c = 0; c < 3; c++) {
            f->excess[c] = hi[c] - lo[c];
            hi[c] = lo[c];
        }
    }
    return 0;
}

void mc_firefly_spread(const struct firefly *ff, int count, const float *se, int width,
                       int height, float *rgb, float *mse)
{
    float wx[2 * SPREAD_R_MAX + 1], wy[2 * SPREAD_R_MAX + 1];
    int i, c;
    for (i = 0; i < count; i++) {
        const struct firefly *f = ff + i;
        int px = f->pixel % width, py = f->pixel / width, r, dx, dy;
        const float *s = se + 3 * (size_t)f->pixel;
        float sigma2 = 0.0f, sx = 0.0f, sy = 0.0f, share[3];
        /* A normalised Gaussian's peak is about 1/(2πσ²): half the excess e (the image is the
         * mean of the halves) stays within κ standard errors s of the mean when
         * σ² >= e / (4π κ s). Weighting each pixel's share by its own standard error, so that
         * the dark and clean pixels around a firefly receive less, lost on cornell-spheres at 16
         * spp (make bench-denoise: 1.39e-2 against 1.09e-2): it put the energy back into the
         * caustic's noisiest pixels. */
        for (c = 0; c < 3; c++)
            sigma2 = fmaxf(sigma2, s[c] > 0.0f ? fabsf(f->excess[c])
                                                     / (4.0f * MC_PI * SPREAD_KAPPA * s[c])
                                               : SPREAD_SIGMA_MAX * SPREAD_SIGMA_MAX);
        sigma2 = fminf(sigma2, SPREAD_SIGMA_MAX * SPREAD_SIGMA_MAX);
        r = (int)ceilf(3.0f * sqrtf(sigma2));
        /* A Gaussian is separable, and so is its sum over the pixels inside the image. */
        for (dx = -r; dx <= r; dx++) {
            float g = sigma2 > 0.0f ? expf(-0.5f * (float)(dx * dx) / sigma2) : (float)(dx == 0);
            wx[dx + r] = px + dx >= 0 && px + dx < width ? g : 0.0f;
            wy[dx + r] = py + dx >= 0 && py + dx < height ? g : 0.0f;
            sx += wx[dx + r];
            sy += wy[dx + r];
        }
        for (c = 0; c < 3; c++)
            share[c] = 0.5f * f->excess[c] / (sx * sy);
        for (dy = -r; dy <= r; dy++) {
            if (wy[dy + r] == 0.0f)
                continue;
            for (dx = -r; dx <= r; dx++) {
                float g = wx[dx + r] * wy[dy + r];
                size_t q;
                if (g == 0.0f)
                    continue;
                q = 3 * ((size_t)(py + dy) * (size_t)width + (size_t)(px + dx));
                for (c = 0; c < 3; c++) {
                    float add = share[c] * g;
                    rgb[q + c] += add;
                    if (mse)
                        mse[q + c] += add * add;
                }
            }
        }
    }
}
