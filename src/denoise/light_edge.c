/* light_edge.c: the emission along a light's edge fitted as a plane (see light_edge.h). */
#include "denoise/light_edge.h"

#include <stddef.h>
#include <stdlib.h>

#include "core/alloc.h"
#include "denoise/ldl.h"

/* A fit is kept when its reduced chi-square, Σ w·(e − fit)²/(n − rank), is below EDGE_CHI2 times
 * the variances' scale (below): for the pixels of a straight edge it has mean 1 and, with 2
 * degrees of freedom (n = EDGE_MIN), exceeds 2 with probability e^-2 = 14%, less often with
 * more; where two edges meet, or the window reaches the far side of a thin light, the misfit is
 * many times the noise. The radii {6, 4, 2} tried in turn, the first accepted kept. Measured by
 * the denoised error of the Cornell box (160², 10 seeds, 16 / 64 spp, relMSE 6.89e-4 / 1.68e-4
 * without the fit): 5.35e-4 / 1.40e-4 with it; the threshold 1.5: 5.82e-4 / 1.55e-4, 3:
 * 5.47e-4 / 1.36e-4; the radii {4, 2}: 5.91e-4 / 1.50e-4, {6, 4}: 5.39e-4 / 1.43e-4, {8, 6, 4,
 * 3, 2}: 5.32e-4 / 1.39e-4. cornell-spheres, whose light's edges its Sobol samples measure
 * closely, moved by under 0.1%. */
#define EDGE_CHI2 2.0
/* The pixels a fit needs: its three coefficients and two degrees of freedom for the test. */
#define EDGE_MIN 5
/* A pixel's weight is 1/variance, the variance floored at EDGE_VAR_FLOOR of the window's largest
 * so that a pixel whose few hits happened to agree cannot take all the weight. */
#define EDGE_VAR_FLOOR 1e-3f

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

/* The weighted least squares of e = a + b·dx + c·dy over the n window pixels (offsets dx, dy,
 * values e, weights wt): its a and the variance of a, [(XᵀWX)⁻¹]₀₀, and its reduced chi-square.
 * A column adding nothing to those before it (all the pixels in one row, so that dy is constant)
 * is dropped with its coefficient 0 (ldl.h). Returns the chi-square, or a negative number when
 * no degree of freedom is left. */
static double plane_fit(const int *dx, const int *dy, const float *e, const float *wt, int n,
                        double *a, double *var_a)
{
    /* The right-hand sides: XᵀWe for the coefficients, e₀ for the first column of (XᵀWX)⁻¹. */
    double M[3 * 3] = {0.0}, b[3 * 2] = {0.0, 1.0, 0.0, 0.0, 0.0, 0.0}, D[3], chi = 0.0;
    int i, j, k, rank;
    for (i = 0; i < n; i++) {
        double x[3];
        x[0] = 1.0;
        x[1] = dx[i];
        x[2] = dy[i];
        for (j = 0; j < 3; j++) {
            b[2 * j] += wt[i] * x[j] * e[i];
            for (k = 0; k <= j; k++)
                M[3 * j + k] += wt[i] * x[j] * x[k];
        }
    }
    rank = mc_ldl_factor(M, 3, D);
    if (n <= rank || D[0] == 0.0)
        return -1.0;
    mc_ldl_solve(M, D, 3, b, 2);
    for (i = 0; i < n; i++) {
        double d = e[i] - (b[0] + b[2] * dx[i] + b[4] * dy[i]);
        chi += wt[i] * d * d;
    }
    *a = b[0];
    *var_a = b[1];
    return chi / (double)(n - rank);
}

/* Pixel (x, y)'s emission fitted over the edge pixels of the window of radius R, into fit[3] and
 * fit_var[3]. Returns 1 when every channel's fit is accepted, else 0. A channel without variance
 * anywhere in the window (a light without blue) keeps the pixel's value. */
static int fit_window(const float *mean, const float *var, const double scale[3],
                      const unsigned char *edge, int w, int h, int x, int y, int R, float fit[3],
                      float fit_var[3])
{
    int dx[EDGE_WIN], dy[EDGE_WIN], n = 0, c, i, xq, yq;
    float e[EDGE_WIN], wt[EDGE_WIN];
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
        float vmax = 0.0f, emax = 0.0f;
        double a = 0.0, var_a = 0.0, chi;
        for (i = 0; i < n; i++)
            if (var[3 * q[i] + c] > vmax)
                vmax = var[3 * q[i] + c];
        if (vmax <= 0.0f) {
            fit[c] = mean[3 * p + c];
            fit_var[c] = var[3 * p + c];
            continue;
        }
        for (i = 0; i < n; i++) {
            float v = var[3 * q[i] + c];
            e[i] = mean[3 * q[i] + c];
            wt[i] = 1.0f / (v > EDGE_VAR_FLOOR * vmax ? v : EDGE_VAR_FLOOR * vmax);
        }
        chi = plane_fit(dx, dy, e, wt, n, &a, &var_a);
        if (chi < 0.0 || chi >= EDGE_CHI2 * scale[c])
            return 0;
        /* No more than the brightest pixel around, no less than none. */
        for (yq = y - R; yq <= y + R; yq++)
            for (xq = x - R; xq <= x + R; xq++)
                if (xq >= 0 && xq < w && yq >= 0 && yq < h
                    && mean[3 * ((size_t)yq * (size_t)w + (size_t)xq) + c] > emax)
                    emax = mean[3 * ((size_t)yq * (size_t)w + (size_t)xq) + c];
        fit[c] = (float)(a < 0.0 ? 0.0 : a > emax ? emax : a);
        fit_var[c] = (float)(var_a * scale[c]);
    }
    return 1;
}

int mc_light_edge_fit(const float *const em[2], const float *var, int width, int height,
                      float *out, float *out_var)
{
    size_t n = (size_t)width * (size_t)height, i;
    unsigned char *edge = mc_malloc(n);
    float *mean = mc_malloc(n * 3 * sizeof *mean);
    double scale[3];
    int x, y, k, c;
    if (!edge || !mean) {
        free(edge);
        free(mean);
        return -1;
    }
    for (i = 0; i < n * 3; i++)
        mean[i] = 0.5f * (em[0][i] + em[1][i]);
    for (y = 0; y < height; y++)
        for (x = 0; x < width; x++)
            edge[(size_t)y * (size_t)width + (size_t)x] = (unsigned char)on_edge(mean, var, width,
                                                                                 height, x, y);
    for (i = 0; i < n * 3; i++) {
        out[i] = mean[i];
        out_var[i] = var[i];
    }
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
