/* diff.c: image error statistics and the per-pixel z-test (see diff.h). The test follows Mitsuba 3's
 * render tests (src/render/tests/test_render.py): Welch-style z on the variance of the mean, a
 * Šidák correction over all tests (Šidák 1967), and a pass fraction decided by the caller. */
#include "diff/diff.h"

#include <math.h>

/* Relative MSE's denominator guard (issue 5): r² + 0.01 keeps black pixels from dominating. */
#define REL_EPS 0.01

void mc_diff_stats(const struct image *test, const struct image *ref, struct diff_rect rect,
                   struct diff_stats *out)
{
    double se = 0.0, rel = 0.0, bias[3] = {0.0, 0.0, 0.0}, max_abs = 0.0, n;
    int x, y, c;
    for (y = rect.y0; y < rect.y1; y++)
        for (x = rect.x0; x < rect.x1; x++) {
            size_t i = 3 * ((size_t)y * (size_t)test->width + (size_t)x);
            for (c = 0; c < 3; c++) {
                double t = test->rgb[i + c], r = ref->rgb[i + c], e = t - r;
                se += e * e;
                rel += e * e / (r * r + REL_EPS);
                bias[c] += e;
                if (fabs(e) > max_abs)
                    max_abs = fabs(e);
            }
        }
    out->pixels = (size_t)(rect.x1 - rect.x0) * (size_t)(rect.y1 - rect.y0);
    n = out->pixels ? (double)out->pixels : 1.0;
    out->mse = se / (3.0 * n);
    out->relmse = rel / (3.0 * n);
    out->psnr = out->mse > 0.0 ? -10.0 * log10(out->mse) : HUGE_VAL;
    out->max_abs = max_abs;
    for (c = 0; c < 3; c++)
        out->bias_rgb[c] = bias[c] / n;
    out->bias = (bias[0] + bias[1] + bias[2]) / (3.0 * n);
}

/* The |z| whose two-sided p-value erfc(|z|/√2) is p, by bisection (libm has no inverse erfc);
 * erfc is decreasing, and p >= 1e-300 puts the answer below 40. */
static double z_for_p(double p)
{
    double lo = 0.0, hi = 40.0;
    int i;
    for (i = 0; i < 100; i++) {
        double mid = 0.5 * (lo + hi);
        if (erfc(mid / sqrt(2.0)) > p)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

void mc_diff_ztest(const struct image *test, const struct image *ref, const struct image *var,
                   struct diff_rect rect, struct diff_ztest *z, float *z_image)
{
    size_t tests, k = 0;
    int x, y, c;
    z->pixels = (size_t)(rect.x1 - rect.x0) * (size_t)(rect.y1 - rect.y0);
    tests = 3 * z->pixels;
    /* Šidák: with independent tests at level a each, the chance of any false rejection is
     * 1 − (1 − a)^tests; solve for a = alpha. expm1/log1p keep it accurate for tiny levels. */
    z->alpha_test = tests ? -expm1(log1p(-z->alpha) / (double)tests) : z->alpha;
    z->z_crit = z_for_p(z->alpha_test);
    z->rejected = 0;
    z->max_z = 0.0;
    for (y = rect.y0; y < rect.y1; y++)
        for (x = rect.x0; x < rect.x1; x++) {
            size_t i = 3 * ((size_t)y * (size_t)test->width + (size_t)x);
            double zmax = 0.0;
            for (c = 0; c < 3; c++) {
                double e = fabs((double)test->rgb[i + c] - ref->rgb[i + c]);
                double s2 = (double)var->rgb[i + c] + z->floor * z->floor, zc;
                zc = s2 > 0.0 ? e / sqrt(s2) : e > 0.0 ? HUGE_VAL : 0.0;
                if (!(zc <= zmax)) /* NaN counts as the worst */
                    zmax = zc == zc ? zc : HUGE_VAL;
            }
            /* Comparing p-values, as Mitsuba does, rather than z with z_crit: the same decision,
             * but exact for levels where the bisected z_crit is only close. */
            if (erfc(zmax / sqrt(2.0)) < z->alpha_test)
                z->rejected++;
            if (zmax > z->max_z)
                z->max_z = zmax;
            if (z_image)
                z_image[k++] = (float)zmax;
        }
    z->agree = z->pixels ? 1.0 - (double)z->rejected / (double)z->pixels : 1.0;
}

void mc_diff_zcolour(const float *z, size_t n, double z_crit, float *rgb)
{
    size_t i;
    for (i = 0; i < n; i++) {
        double t = z_crit > 0.0 ? z[i] / z_crit : HUGE_VAL;
        float *p = rgb + 3 * i;
        if (!(t >= 0.0))
            t = HUGE_VAL;
        if (t < 1.0) {
            p[0] = p[1] = (float)(0.1 * t);
            p[2] = (float)t;
        } else {
            p[0] = 1.0f;
            p[1] = (float)(t >= 2.0 ? 1.0 : t - 1.0);
            p[2] = 0.0f;
        }
    }
}
