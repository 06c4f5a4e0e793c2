/* test_light_edge.c: the fit of the emission along a light's edge (src/denoise/light_edge.h) on
 * synthetic renders whose truth is known. The light, of radiance (10, 6, 0), covers the part of
 * a W×H film below the slanted line y = 9.3 + 0.23·x and left of x = 31.6, so that it has a
 * slanted edge, a vertical one and a corner where they meet; each pixel's true emission is the
 * radiance times the share of the pixel it covers (4096 points a pixel). Each render draws 16
 * independent uniform rays a pixel, 8 a half, so that a half's emission is the radiance times
 * its hits over 8 and the samples' variance s²/n is unbiased (the fit's scale near 1). Over
 * SEEDS renders:
 *   - the fitted edge pixels' mean squared error is below half the raw's: a fit over a window's
 *     5 to 40 edge pixels with 3 coefficients has a variance several times smaller, but where
 *     the slanted edge crosses from one row to the next (a quarter of its pixels) the share is
 *     no plane, and the windows there are smaller or refused (measured: 0.46 of the raw's, the
 *     pole and the second light below included);
 *   - the pixels within one pixel of the corner, where no plane fits, are no worse than raw
 *     beyond the noise of their mean squared error over the seeds (3 standard errors);
 *   - the returned variances summed over the edge pixels are within a factor 2 of the squared
 *     errors summed (the denoiser's error estimate adds them);
 *   - a second light, x > 36.3 to the film's right side (4 dark columns from the first, more
 *     than light_edge.c bridges), is lit over a tenth of each pixel of row 28 (y > 28.9), as the
 *     Cornell box's light's far edge is: the pixels of that row from x = 37 on that every ray of
 *     both halves missed (33 in 20 renders, most between lit pixels) are fitted, their squared
 *     error below half of what they had as 0 (measured: 0.34);
 *   - a pixel off the edge and the blue channel, which has no variance, keep their values and
 *     variances, and nothing is NaN. Among those pixels is a pole in front of the first light,
 *     2 pixels wide at x = 9.5 to 11.5 and at half the light's depth: its middle column is dark
 *     between two columns half lit, an unseen pixel's pattern, and the depth tells it from one
 *     (without the depth test its pixels took their neighbours' variance, and the fits of those
 *     neighbours their zeros: the edge's fitted error 2901 against the raw 3588). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "denoise/light_edge.h"
#include "t.h"

enum { W = 48, H = 32, N = W * H, RAYS = 16, SEEDS = 20, SUB = 64 };
static const float radiance[3] = {10.0f, 6.0f, 0.0f};

static int pole(double x) { return x >= 9.5 && x < 11.5; }
static int lit(double x, double y)
{
    return (y > 9.3 + 0.23 * x && x < 31.6 && !pole(x)) || (x >= 36.3 && y > 28.9);
}

int main(void)
{
    static float truth[N], em[2][N * 3], var[N * 3], out[N * 3], out_var[N * 3], depth[N];
    const float *const depths[2] = {depth, depth};
    static unsigned char edge[N], corner[N];
    double raw_se = 0.0, fit_se = 0.0, est = 0.0, cr[SEEDS], cf[SEEDS], cm = 0.0, cv = 0.0;
    double unseen_raw = 0.0, unseen_fit = 0.0;
    int x, y, i, j, c, s, h, n_edge = 0, n_corner = 0, n_unseen = 0, kept = 1, finite = 1;
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            int hits = 0, near = 0;
            for (i = 0; i < SUB; i++)
                for (j = 0; j < SUB; j++) {
                    hits += lit(x + (j + 0.5) / SUB, y + (i + 0.5) / SUB);
                    near += pole(x + (j + 0.5) / SUB);
                }
            truth[y * W + x] = (float)hits / (SUB * SUB);
            /* The depth feature: the mean of the rays' first hits, the pole at 0.5, else 1. */
            depth[y * W + x] = 1.0f - 0.5f * (float)near / (SUB * SUB);
        }
    /* The edge pixels: partly lit. The corner's: within a pixel of (31.6, 16.568). */
    for (i = 0; i < N; i++) {
        edge[i] = truth[i] > 0.0f && truth[i] < 1.0f;
        x = i % W;
        y = i / W;
        corner[i] = edge[i] && abs(x - 31) <= 1 && abs(y - 16) <= 1;
        n_edge += edge[i];
        n_corner += corner[i];
    }
    for (s = 0; s < SEEDS; s++) {
        pcg32 g;
        double raw_c = 0.0, fit_c = 0.0;
        const float *const halves[2] = {em[0], em[1]};
        pcg32_seed(&g, 11 + (uint64_t)s, 3);
        for (i = 0; i < N; i++) {
            int k[2] = {0, 0};
            double p;
            for (h = 0; h < 2; h++)
                for (j = 0; j < RAYS / 2; j++)
                    k[h] += lit(i % W + pcg32_double(&g), i / W + pcg32_double(&g));
            p = (double)(k[0] + k[1]) / RAYS;
            for (c = 0; c < 3; c++) {
                for (h = 0; h < 2; h++)
                    em[h][3 * i + c] = radiance[c] * (float)k[h] / (RAYS / 2);
                /* s²/n: the samples' variance (with n − 1) over n. */
                var[3 * i + c] = (float)(radiance[c] * radiance[c] * p * (1.0 - p) / (RAYS - 1));
            }
        }
        T_CHECK(mc_light_edge_fit(halves, var, depths, W, H, out, out_var) == 0, "fit");
        for (i = 0; i < N; i++)
            for (c = 0; c < 3; c++) {
                double t = radiance[c] * truth[i], m = 0.5 * (em[0][3 * i + c] + em[1][3 * i + c]);
                finite = finite && isfinite(out[3 * i + c]) && isfinite(out_var[3 * i + c]);
                if ((!edge[i] || c == 2)
                    && (out[3 * i + c] != (float)m || out_var[3 * i + c] != var[3 * i + c]))
                    kept = 0;
                if (!edge[i] || c == 2)
                    continue;
                raw_se += (m - t) * (m - t);
                fit_se += (out[3 * i + c] - t) * (out[3 * i + c] - t);
                if (i / W == 28 && i % W >= 37 && em[0][3 * i] + em[1][3 * i] == 0.0f) {
                    unseen_raw += t * t;
                    unseen_fit += (out[3 * i + c] - t) * (out[3 * i + c] - t);
                    n_unseen += c == 0;
                }
                est += out_var[3 * i + c];
                if (corner[i]) {
                    raw_c += (m - t) * (m - t);
                    fit_c += (out[3 * i + c] - t) * (out[3 * i + c] - t);
                }
            }
        cr[s] = raw_c;
        cf[s] = fit_c;
    }
    T_CHECK(finite, "a NaN or an infinity");
    T_CHECK(kept, "a pixel off the edge, or a channel without variance, changed its value or "
                  "its variance");
    T_NOTE("%d edge pixels, %d renders: squared error raw %.4g, fitted %.4g, estimated %.4g",
           n_edge, SEEDS, raw_se, fit_se, est);
    T_CHECK(fit_se < 0.5 * raw_se, "fitted %.4g against raw %.4g", fit_se, raw_se);
    T_NOTE("row 28 of the second light: %d pixels missed by every ray in %d renders, squared "
           "error as 0 %.4g, fitted %.4g", n_unseen, SEEDS, unseen_raw, unseen_fit);
    T_CHECK(n_unseen > 0 && unseen_fit < 0.5 * unseen_raw,
            "unseen pixels: fitted %.4g against %.4g", unseen_fit, unseen_raw);
    T_CHECK(est > fit_se / 2 && est < 2 * fit_se, "estimated %.4g against %.4g", est, fit_se);
    for (s = 0; s < SEEDS; s++)
        cm += (cf[s] - cr[s]) / SEEDS;
    for (s = 0; s < SEEDS; s++)
        cv += (cf[s] - cr[s] - cm) * (cf[s] - cr[s] - cm) / (SEEDS - 1);
    T_NOTE("the %d pixels at the corner: fitted minus raw squared error %.4g (standard error %.4g)",
           n_corner, cm, sqrt(cv / SEEDS));
    T_CHECK(cm < 3.0 * sqrt(cv / SEEDS), "corner: fitted minus raw %.4g, standard error %.4g", cm,
            sqrt(cv / SEEDS));
    return t_done();
}
