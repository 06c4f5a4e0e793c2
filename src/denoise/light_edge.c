/* light_edge.c: the emission along a light's edge fitted as a plane (see light_edge.h). */
#include "denoise/light_edge.h"

#include <stddef.h>
#include <stdlib.h>

#include "core/alloc.h"
#include "denoise/ldl.h"

/* A fit is kept when its residuals' mean square, Σ (e − fit)²/(n − rank), is below EDGE_CHI2
 * times the pixels' mean variance (scaled, below): a reduced chi-square, which for the pixels of a
 * straight edge has mean 1 and, with 2 degrees of freedom (n = EDGE_MIN), exceeds 2 with
 * probability e^-2 = 14%, less often with more; where two edges meet, or the window reaches the
 * far side of a thin light, the misfit is many times the noise. The radii {6, 4, 2} tried in
 * turn, the first accepted kept. Measured by the denoised error of the Cornell box (160², 10
 * seeds, 16 / 64 spp, relMSE 6.89e-4 / 1.68e-4 without the fit): 5.35e-4 / 1.40e-4 with it; the
 * threshold 1.5: 5.82e-4 / 1.55e-4, 3: 5.47e-4 / 1.36e-4; the radii {4, 2}: 5.91e-4 / 1.50e-4,
 * {6, 4}: 5.39e-4 / 1.43e-4, {8, 6, 4, 3, 2}: 5.32e-4 / 1.39e-4 (all with the inverse-variance
 * weights of before, below). cornell-spheres, whose light's edges its Sobol samples measure closely, moved
 * by under 0.1%.
 *
 * The pixels of a window weigh the same. Weighted by the inverse of their own variances s²/n,
 * as they were, a pixel that k of n rays saw lit has s²/n ∝ k(n − k): along an edge lit over
 * less than half of each pixel, the pixels that happened to get fewer hits weighed more, and the
 * fits came out low (the denoised Cornell box's mean 2.5e-4 below the raw's at 16 spp, 6.3e-5
 * at 64; with equal weights 2.2e-5 and 2.2e-5, and the error 5.43e-4 / 1.37e-4, the unseen
 * pixels below left out). Along one straight edge the pixels' shares of light, and so their
 * variances, are close to equal, which equal weights assume. */
#define EDGE_CHI2 2.0
/* The pixels a fit needs: its three coefficients and two degrees of freedom for the test. */
#define EDGE_MIN 5

static const int edge_radius[] = {6, 4, 2};
enum { EDGE_RADII = sizeof edge_radius / sizeof edge_radius[0], EDGE_RMAX = 6 };
enum { EDGE_WIN = (2 * EDGE_RMAX + 1) * (2 * EDGE_RMAX + 1) };

/* Whether pixel i is on a light's edge: its rays saw different emission, and one of its eight
 * neighbours saw none. */
static int on_edge(const float *mean, const float *var, int w, int h, int x, int y)
{
    size_t i = (size_t)y * (size_t)w + (size_t)x;
    int dx, dy;
    if (var[3 * i] + var[3 * i + 1] + var[3 * i + 2] <= 0.0f)
        return 0;
    for (dy = -1; dy <= 1; dy++)
        for (dx = -1; dx <= 1; dx++) {
            int xq = x + dx, yq = y + dy;
            size_t q = (size_t)yq * (size_t)w + (size_t)xq;
            if ((dx || dy) && xq >= 0 && xq < w && yq >= 0 && yq < h
                && mean[3 * q] + mean[3 * q + 1] + mean[3 * q + 2] <= 0.0f)
                return 1;
        }
    return 0;
}

/* The least squares of e = a + b·dx + c·dy over the n window pixels (offsets dx, dy, values e):
 * its a, the first diagonal element of (XᵀX)⁻¹ (a's variance over the pixels' variance), and
 * the residuals' mean square, Σ (e − fit)²/(n − rank). A column adding nothing to those before it
 * (all the pixels in one row, so that dy is constant) is dropped with its coefficient 0 (ldl.h).
 * Returns that mean square, or a negative number when no degree of freedom is left. */
static double plane_fit(const int *dx, const int *dy, const float *e, int n, double *a,
                        double *g00)
{
    /* The right-hand sides: Xᵀe for the coefficients, e₀ for the first column of (XᵀX)⁻¹. */
    double M[3 * 3] = {0.0}, b[3 * 2] = {0.0, 1.0, 0.0, 0.0, 0.0, 0.0}, D[3], rss = 0.0;
    int i, j, k, rank;
    for (i = 0; i < n; i++) {
        double x[3];
        x[0] = 1.0;
        x[1] = dx[i];
        x[2] = dy[i];
        for (j = 0; j < 3; j++) {
            b[2 * j] += x[j] * e[i];
            for (k = 0; k <= j; k++)
                M[3 * j + k] += x[j] * x[k];
        }
    }
    rank = mc_ldl_factor(M, 3, D);
    if (n <= rank || D[0] == 0.0)
        return -1.0;
    mc_ldl_solve(M, D, 3, b, 2);
    for (i = 0; i < n; i++) {
        double d = e[i] - (b[0] + b[2] * dx[i] + b[4] * dy[i]);
        rss += d * d;
    }
    *a = b[0];
    *g00 = b[1];
    return rss / (double)(n - rank);
}

/* Pixel (x, y)'s emission fitted over the edge pixels of the window of radius R, into fit[3] and
 * fit_var[3]. Returns 1 when every channel's fit is accepted, else 0. A channel without variance
 * anywhere in the window (a light without blue) keeps the pixel's value. */
static int fit_window(const float *mean, const float *var, const double scale[3],
                      const unsigned char *edge, int w, int h, int x, int y, int R, float fit[3],
                      float fit_var[3])
{
    int dx[EDGE_WIN], dy[EDGE_WIN], n = 0, c, i, xq, yq;
    float e[EDGE_WIN];
    size_t p = (size_t)y * (size_t)w + (size_t)x, q[EDGE_WIN];
    for (yq = y - R; yq <= y + R; yq++)
        for (xq = x - R; xq <= x + R; xq++)
            if (xq >= 0 && xq < w && yq >= 0 && yq < h
                && edge[(size_t)yq * (size_t)w + (size_t)xq]) {
                q[n] = (size_t)yq * (size_t)w + (size_t)xq;
                dx[n] = xq - x;
                dy[n] = yq - y;
                n++;
            }
    if (n < EDGE_MIN)
        return 0;
    for (c = 0; c < 3; c++) {
        float emax = 0.0f;
        double a = 0.0, g00 = 0.0, v = 0.0, ms;
        for (i = 0; i < n; i++)
            v += var[3 * q[i] + c] / (double)n;
        if (v <= 0.0) {
            fit[c] = mean[3 * p + c];
            fit_var[c] = var[3 * p + c];
            continue;
        }
        for (i = 0; i < n; i++)
            e[i] = mean[3 * q[i] + c];
        ms = plane_fit(dx, dy, e, n, &a, &g00);
        if (ms < 0.0 || ms >= EDGE_CHI2 * scale[c] * v)
            return 0;
        /* No more than the brightest pixel around, no less than none. */
        for (yq = y - R; yq <= y + R; yq++)
            for (xq = x - R; xq <= x + R; xq++)
                if (xq >= 0 && xq < w && yq >= 0 && yq < h
                    && mean[3 * ((size_t)yq * (size_t)w + (size_t)xq) + c] > emax)
                    emax = mean[3 * ((size_t)yq * (size_t)w + (size_t)xq) + c];
        fit[c] = (float)(a < 0.0 ? 0.0 : a > emax ? emax : a);
        fit_var[c] = (float)(g00 * v * scale[c]);
    }
    return 1;
}

/* Whether depth d lies between those of the pixels on either side, a and b, within
 * UNSEEN_DEPTH_TOL of them. */
#define UNSEEN_DEPTH_TOL 0.02f
static int depth_between(float d, float a, float b)
{
    float lo = a < b ? a : b, hi = a < b ? b : a;
    return d >= lo * (1.0f - UNSEEN_DEPTH_TOL) && d <= hi * (1.0f + UNSEEN_DEPTH_TOL);
}

/* The longest run of unseen pixels (below) between two edge pixels. */
enum { UNSEEN_RUN = 2 };

/* Whether pixel i has no emission and no variance: no ray of either half saw a light there. */
static int dark(const float *mean, const float *var, size_t i)
{
    return mean[3 * i] + mean[3 * i + 1] + mean[3 * i + 2] <= 0.0f
           && var[3 * i] + var[3 * i + 1] + var[3 * i + 2] <= 0.0f;
}

/* The first pixel that is not dark from (x, y) on in steps of (sx, sy), at most UNSEEN_RUN steps
 * away and inside the film, into *q; returns 0 when there is none. */
static int next_lit(const float *mean, const float *var, int w, int h, int x, int y, int sx,
                    int sy, size_t *q)
{
    int k;
    for (k = 1; k <= UNSEEN_RUN; k++) {
        int xq = x + k * sx, yq = y + k * sy;
        if (xq < 0 || xq >= w || yq < 0 || yq >= h)
            return 0;
        *q = (size_t)yq * (size_t)w + (size_t)xq;
        if (!dark(mean, var, *q))
            return 1;
    }
    return 0;
}

/* Whether the dark pixel (x, y) is an edge pixel that no ray of either half saw lit: in a run of
 * at most UNSEEN_RUN dark pixels between two edge pixels along its row or its column, at a depth
 * between theirs; those two into *a and *b. A light is convex (a quad, a disk, a sphere's
 * outline), so its intersection with a row (column) of pixels is one interval; an interval that
 * reaches into pixels on both sides crosses the whole of every pixel between them, which are
 * therefore partly lit too: the Cornell box's light (160², 16 spp) has a row along its far edge
 * lit over a tenth of each pixel, and in 9 renders of 10 one to three of those pixels were
 * missed by both halves, each holding 7% of the denoised image's error, which the error
 * estimate, seeing two halves agree, could not see. What is not convex is a light seen past an
 * occluder (a wire in front of a lamp, a light behind a gap), and the depth test refuses that:
 * the occluder's pixels are nearer (the gap's farther) than the mixtures of it and the light on
 * either side. Two coplanar lights a few pixels apart would pass it. */
static int unseen(const float *mean, const float *var, const float *depth,
                  const unsigned char *edge, int w, int h, int x, int y, size_t *a, size_t *b)
{
    size_t i = (size_t)y * (size_t)w + (size_t)x;
    int axis;
    if (!dark(mean, var, i))
        return 0;
    for (axis = 0; axis < 2; axis++)
        if (next_lit(mean, var, w, h, x, y, -!axis, -axis, a) && edge[*a] == 1
            && next_lit(mean, var, w, h, x, y, !axis, axis, b) && edge[*b] == 1
            && depth_between(depth[i], depth[*a], depth[*b]))
            return 1;
    return 0;
}

int mc_light_edge_fit(const float *const em[2], const float *var_in, const float *const depth[2],
                      int width, int height, float *out, float *out_var)
{
    size_t n = (size_t)width * (size_t)height, i;
    unsigned char *edge = mc_malloc(n);
    /* The halves' mean emission, its variance with the unseen pixels' (below), the mean depth. */
    float *mean = mc_malloc(n * 7 * sizeof *mean), *var = mean + n * 3, *dep = var + n * 3;
    double scale[3];
    int x, y, k, c;
    if (!edge || !mean) {
        free(edge);
        free(mean);
        return -1;
    }
    for (i = 0; i < n * 3; i++) {
        mean[i] = 0.5f * (em[0][i] + em[1][i]);
        var[i] = var_in[i];
    }
    for (i = 0; depth[0] && i < n; i++)
        dep[i] = 0.5f * (depth[0][i] + depth[1][i]);
    for (y = 0; y < height; y++)
        for (x = 0; x < width; x++)
            edge[(size_t)y * (size_t)width + (size_t)x] = (unsigned char)on_edge(mean, var, width,
                                                                                 height, x, y);
    /* The variances' scale: the halves' (A − B)²/4 over the samples' s²/n, summed over the
     * edge pixels (film.h: the first is unbiased for stratified and Sobol samples too, the
     * second is biased up for them). */
    for (c = 0; c < 3; c++) {
        double halves = 0.0, samples = 0.0;
        for (i = 0; i < n; i++)
            if (edge[i]) {
                double dh = (double)em[0][3 * i + (size_t)c] - em[1][3 * i + (size_t)c];
                halves += 0.25 * dh * dh;
                samples += var[3 * i + (size_t)c];
            }
        scale[c] = samples > 0.0 ? halves / samples : 1.0;
    }
    /* The unseen edge pixels join the fits as what they are, pixels of the edge whose rays all
     * missed: their emission 0 is an observation as unbiased as their neighbours' (leaving them
     * out kept only the pixels that happened to be hit, biasing the fits up), and their
     * variance, which no sample measured, is taken as the mean of the two edge neighbours', whose
     * shares of light are close to theirs. Where no fit is accepted they keep 0 with that
     * variance, so that the error estimate counts them. Marked 2, after the scale above. */
    for (y = 0; depth[0] && y < height; y++)
        for (x = 0; x < width; x++) {
            size_t a, b;
            i = (size_t)y * (size_t)width + (size_t)x;
            /* var_in, not var, so that the pixels marked before are still seen as dark. */
            if (!unseen(mean, var_in, dep, edge, width, height, x, y, &a, &b))
                continue;
            edge[i] = 2;
            for (c = 0; c < 3; c++)
                var[3 * i + (size_t)c] = 0.5f * (var_in[3 * a + (size_t)c]
                                                 + var_in[3 * b + (size_t)c]);
        }
    for (i = 0; i < n * 3; i++) {
        out[i] = mean[i];
        out_var[i] = var[i];
    }
    for (y = 0; y < height; y++)
        for (x = 0; x < width; x++) {
            float fit[3], fit_var[3];
            i = (size_t)y * (size_t)width + (size_t)x;
            if (!edge[i])
                continue;
            for (c = 0; c < 3; c++)
                out_var[3 * i + (size_t)c] = (float)(var[3 * i + (size_t)c] * scale[c]);
            for (k = 0; k < EDGE_RADII; k++)
                if (fit_window(mean, var, scale, edge, width, height, x, y, edge_radius[k], fit,
                               fit_var)) {
                    for (c = 0; c < 3; c++) {
                        out[3 * i + (size_t)c] = fit[c];
                        out_var[3 * i + (size_t)c] = fit_var[c];
                    }
                    break;
                }
        }
    free(edge);
    free(mean);
    return 0;
}
