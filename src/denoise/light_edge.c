/* light_edge.c: the emission along a light's edge fitted as a plane (see light_edge.h). */
#include "denoise/light_edge.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

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

/* The sum of pixel i's three channels of v (W·H·3 floats). */
static double channel_sum(const float *v, size_t i)
{
    return (double)v[3 * i] + v[3 * i + 1] + v[3 * i + 2];
}

/* Whether pixel i is on a light's edge: its rays saw different emission, and one of its eight
 * neighbours saw none. */
static int on_edge(const float *mean, const float *var, int w, int h, int x, int y)
{
    size_t i = (size_t)y * (size_t)w + (size_t)x;
    int dx, dy;
    if (channel_sum(var, i) <= 0.0)
        return 0;
    for (dy = -1; dy <= 1; dy++)
        for (dx = -1; dx <= 1; dx++) {
            int xq = x + dx, yq = y + dy;
            size_t q = (size_t)yq * (size_t)w + (size_t)xq;
            if ((dx || dy) && xq >= 0 && xq < w && yq >= 0 && yq < h
                && channel_sum(mean, q) <= 0.0)
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

/* The straight edge that edge pixel (x, y) lies on, from its four neighbours' emission: 0 or 1
 * for an edge down the film (lit on the left or the right), 2 or 3 for one across it (lit above or
 * below); EDGE_NONE where neither direction's difference is twice the other's, or where neither
 * neighbour along the edge is on an edge (edge): a corner, or a tip that a light's corner cuts
 * (the Cornell box's light at 16 spp, seed 7: a pixel lit over 3% beside a side lit over 12%, with
 * no edge pixel above or below it, was fitted along the slanted side below, 0.82 for a truth of
 * 0.35, where it had had 0.42); EDGE_NONE where a corner of the light cuts the pixel
 * (corner_cuts); EDGE_NONE too for a pixel on no edge, without looking further.
 * A plane fits the shares along one straight edge only (light_edge.h), so a window's fit takes
 * the pixels of the centre's edge alone. With every edge pixel of the window, the chi-square
 * test, which at a few samples a pixel has little power, let planes through that mixed two edges
 * of a light's corner (the Cornell box at 160², 10 spp: a column of shares 0.4, 0.3, 0.1 down
 * the light's slanted side fitted as 0.27, 0.31, 0.36 with the row of 0.4-0.5 below it); the
 * corner's lines drawn through those fits then lit a pixel that no ray of the reference sees
 * lit with 16% of the light, 87% of the denoised image's error. Over 4 seeds, the denoised
 * relMSE without -> with this: 4 spp 2.26e-2 -> 2.52e-3, 6 spp 1.85e-2 -> 1.06e-3, 7 spp
 * 1.22e-2 -> 1.04e-3, 8 spp 6.24e-4 -> 6.11e-4, 10 spp 2.01e-3 -> 5.36e-4, 12 spp 4.21e-4 ->
 * 4.13e-4, 16 spp 2.93e-4 -> 2.83e-4 (10 seeds: 2.86e-4 -> 2.81e-4). */
enum { EDGE_NONE = 4 };

/* Whether a corner of the light cuts edge pixel (x, y): the edge through it ends there on the
 * side (sx, sy), one step along the edge, and another edge of the light passes beside it, in
 * the pixel (lx, ly) across the edge on its lit side. The edge ends where the pixel a step along
 * it is dark and on no edge, and the two beside that one across the edge's direction, where a
 * slanted edge would go on, are on no edge either. A straight edge does not end inside a pixel:
 * the corner is in this one, and its share is less than the edge's run says. A plane along the
 * run extrapolated it (the Cornell box at 160² and 16 spp, seed 39: the last pixel of the light's
 * top edge, lit over 3%, fitted 2.25 from the edge's 15% for a truth of 0.35, 75% of the
 * denoised image's error, its variance reading a twenty-fifth of that); as no edge's pixel it
 * gets the corner's model (corner_fit). Where the other edge does not pass beside it, the
 * corner lies on the pixel's border, the pixel is as lit as the run says, and the plane does
 * better than the corner's model, whose lines are noisier (tests/unit/test_light_edge.c, the
 * third light's right side, which ends on a pixel's bottom border: squared error 98 with the
 * plane, 144 with the corner's model, over 80 renders of 16 rays a pixel). */
static int corner_cuts(const float *mean, const unsigned char *edge, int w, int h, int x, int y,
                       int sx, int sy, int lx, int ly)
{
    int xq = x + sx, yq = y + sy, k;
    if (xq < 0 || xq >= w || yq < 0 || yq >= h || x + lx < 0 || x + lx >= w || y + ly < 0
        || y + ly >= h || !edge[(size_t)(y + ly) * (size_t)w + (size_t)(x + lx)])
        return 0;
    for (k = -1; k <= 1; k++) {
        int xa = xq + k * sy, ya = yq + k * sx;
        size_t q;
        if (xa < 0 || xa >= w || ya < 0 || ya >= h)
            continue;
        q = (size_t)ya * (size_t)w + (size_t)xa;
        if (edge[q] || (k == 0 && channel_sum(mean, q) > 0.0))
            return 0;
    }
    return 1;
}

static unsigned char edge_group(const float *mean, const unsigned char *edge, int w, int h, int x,
                                int y)
{
    size_t i = (size_t)y * (size_t)w + (size_t)x, row = (size_t)w;
    double gx, gy;
    if (!edge[i])
        return EDGE_NONE;
    gx = (x + 1 < w ? channel_sum(mean, i + 1) : 0.0)
         - (x > 0 ? channel_sum(mean, i - 1) : 0.0);
    gy = (y + 1 < h ? channel_sum(mean, i + row) : 0.0)
         - (y > 0 ? channel_sum(mean, i - row) : 0.0);
    if (fabs(gx) >= 2.0 * fabs(gy) && ((y > 0 && edge[i - row]) || (y + 1 < h && edge[i + row]))
        && !corner_cuts(mean, edge, w, h, x, y, 0, -1, gx > 0.0 ? 1 : -1, 0)
        && !corner_cuts(mean, edge, w, h, x, y, 0, 1, gx > 0.0 ? 1 : -1, 0))
        return (unsigned char)(gx > 0.0);
    if (fabs(gy) >= 2.0 * fabs(gx) && ((x > 0 && edge[i - 1]) || (x + 1 < w && edge[i + 1]))
        && !corner_cuts(mean, edge, w, h, x, y, -1, 0, 0, gy > 0.0 ? 1 : -1)
        && !corner_cuts(mean, edge, w, h, x, y, 1, 0, 0, gy > 0.0 ? 1 : -1))
        return (unsigned char)(2 + (gy > 0.0));
    return EDGE_NONE;
}

/* Pixel (x, y)'s emission fitted over the window of radius R's pixels of its edge (group, from
 * edge_group; edge, on an edge at all), into fit[3] and fit_var[3]. Returns 1 when every
 * channel's fit is accepted, else 0. A channel without variance anywhere in the window (a light
 * without blue) keeps the pixel's value. */
static int fit_window(const float *mean, const float *var, const double scale[3],
                      const unsigned char *edge, const unsigned char *group, int w, int h, int x,
                      int y, int R, float fit[3], float fit_var[3])
{
    int dx[EDGE_WIN], dy[EDGE_WIN], n = 0, c, i, xq, yq;
    float e[EDGE_WIN];
    size_t p = (size_t)y * (size_t)w + (size_t)x, q[EDGE_WIN];
    if (group[p] == EDGE_NONE)
        return 0;
    for (yq = y - R; yq <= y + R; yq++)
        for (xq = x - R; xq <= x + R; xq++)
            if (xq >= 0 && xq < w && yq >= 0 && yq < h
                && edge[(size_t)yq * (size_t)w + (size_t)xq]
                && group[(size_t)yq * (size_t)w + (size_t)xq] == group[p]) {
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
    return channel_sum(mean, i) <= 0.0 && channel_sum(var, i) <= 0.0;
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

/* ---- Corners: the pixels no plane fits, covered by the light's edges as straight lines ----
 *
 * Where two edges of a light meet, a pixel's share of the light is no plane of its position,
 * and the fits above refuse it: it kept its own emission, k hits of n rays, whose error is the
 * light's radiance squared times c(1 − c)/n for a share c. With the Sobol sampler, whose hits
 * along a straight edge vary little, the Cornell box's four light corners (10 pixels at 160²)
 * held 39% of its denoised error at 16 spp and 15% at 64, and a corner lit over 2% of a pixel
 * was missed by both halves or hit once (seen as 6% lit) in most renders. But the edges that meet
 * there are straight lines that the edge pixels beside the corner measure: a pixel of a column
 * edge (light on its right, say) that the line crosses from top to bottom is lit over
 * c = x + 1 − u, u the line's abscissa at the pixel's middle row, so each edge pixel gives a
 * point of its edge's line (from its plane fit where it has one), and a least-squares line
 * through those of one edge gives it, slope included. The corner pixel's share is then the area
 * of the pixel inside every edge's half-plane (Sutherland and Hodgman's clipping of the square),
 * exact for a convex polygonal light seen through a box filter, up to the lines' own noise; that
 * noise grows where a line is extrapolated to a tip, so the model is weighed against the pixel's
 * own emission (corner_fit). Measured on the Cornell box (160², 10 seeds, make bench-denoise's
 * inputs, the Sobol sampler): the denoised relMSE 3.94e-4 -> 2.88e-4 at 16 spp, 1.03e-4 -> 9.3e-5
 * at 64. */

/* The window of a corner's lines and radiance: radius CORNER_R. */
enum { CORNER_R = 6, CORNER_GROUPS = 4, CORNER_POLY = 4 + CORNER_GROUPS + 1 };
/* A group's residuals, px: at most CORNER_STRAIGHT² above four times its points' own variance,
 * the tolerance of the line model itself (a line leaving a pixel through a side rather than its
 * top or bottom gives a point off it by up to a few hundredths). */
#define CORNER_STRAIGHT 0.1
/* The model is taken when the emission of the pixel and its neighbours agrees with it: their
 * squared differences over the variance of a mean of hits (a share c: c(1 − c)/N, plus half a
 * hit's square for the discreteness and the model's own variance) sum to at most the 99th
 * percentile of a chi-square of 9 degrees of freedom. N is the sample count as independent rays
 * would have it, read from the edge pixels' s²/n unscaled: a stratified sampler steadies the hits
 * along a straight edge (the scale) but not at a tip lit over 2% of a pixel, and with the scaled
 * count the Cornell box's corners were refused. */
#define CORNER_CHI2 21.67

/* A light's edge as a half-plane of the film: s·(v − a − k·w) ≥ 0, where (w, v) is (y, x) for an
 * edge down the film (a column edge, lit on its right for s = +1), (x, y) for one across it (a
 * row edge, lit below for s = +1). */
struct half_plane {
    int across;
    double a, k, s;
};

static double plane_side(const struct half_plane *h, double x, double y)
{
    return h->across ? h->s * (y - h->a - h->k * x) : h->s * (x - h->a - h->k * y);
}

/* The area of pixel (x, y), the unit square at that corner, inside all n half-planes. */
static double clip_area(int x, int y, const struct half_plane *h, int n)
{
    double px[CORNER_POLY], py[CORNER_POLY], qx[CORNER_POLY], qy[CORNER_POLY], area = 0.0;
    int m = 4, i, j, k;
    px[0] = x, py[0] = y, px[1] = x + 1, py[1] = y, px[2] = x + 1, py[2] = y + 1, px[3] = x;
    py[3] = y + 1;
    for (j = 0; j < n && m > 0; j++) {
        for (i = 0, k = 0; i < m; i++) {
            int i1 = (i + 1) % m;
            double fa = plane_side(&h[j], px[i], py[i]), fb = plane_side(&h[j], px[i1], py[i1]);
            if (fa >= 0.0)
                qx[k] = px[i], qy[k++] = py[i];
            /* The side is affine along the segment: it crosses 0 at fa/(fa − fb). */
            if ((fa >= 0.0) != (fb >= 0.0)) {
                double t = fa / (fa - fb);
                qx[k] = px[i] + t * (px[i1] - px[i]);
                qy[k++] = py[i] + t * (py[i1] - py[i]);
            }
        }
        for (i = 0; i < k; i++)
            px[i] = qx[i], py[i] = qy[i];
        m = k;
    }
    for (i = 0; i < m; i++)
        area += px[i] * py[(i + 1) % m] - px[(i + 1) % m] * py[i];
    return m > 2 ? 0.5 * (area < 0.0 ? -area : area) : 0.0;
}

/* Whether one of pixel (x, y)'s eight neighbours is an edge pixel. */
static int beside_edge(const unsigned char *edge, int w, int h, int x, int y)
{
    int dx, dy;
    for (dy = -1; dy <= 1; dy++)
        for (dx = -1; dx <= 1; dx++)
            if (x + dx >= 0 && x + dx < w && y + dy >= 0 && y + dy < h
                && edge[(size_t)(y + dy) * (size_t)w + (size_t)(x + dx)])
                return 1;
    return 0;
}

/* What the corner model reads: the halves' mean emission and its variance (the samples' s²/n, an
 * unseen pixel's from its neighbours) with the scale measured from the halves, the depth, the
 * edge pixels and which of them a plane fitted, and those fits with their variances. */
struct corner_in {
    const float *mean, *var, *depth, *fit, *fit_var;
    const unsigned char *edge, *fitted;
    const double *scale;
    int w, h;
};

/* The share of pixel i's area that the light covers as its emission says, in channel c of
 * radiance L: the fit where there is one. */
static double share(const struct corner_in *in, size_t i, int c, double L)
{
    return (in->fitted[i] ? in->fit[3 * i + (size_t)c] : in->mean[3 * i + (size_t)c]) / L;
}

/* Whether the line of hp crosses the pixel at t (along the edge, its middle) whose u runs from o
 * to o + 1 from one side to the other: its u at both sides of the pixel within [o, o + 1]. */
static int crosses(const struct half_plane *hp, double t, double o)
{
    double u0 = hp->a + hp->k * (t - 0.5), u1 = hp->a + hp->k * (t + 0.5);
    return u0 >= o && u0 <= o + 1.0 && u1 >= o && u1 <= o + 1.0;
}

/* The least-squares line u = a + k·t through the points of one edge that ok marks (t, u, each
 * with variance v), into hp, and the variance of that line's u at t0: σ²(1/n + (t0 − t̄)²/Σ(t −
 * t̄)²), σ² the points' mean variance. Returns 0 for fewer than two points, points all at one t,
 * or (when test is set) residuals beyond the points' noise and the model's tolerance: an edge
 * that is not straight, or two edges taken for one. */
static int edge_line(const double *t, const double *u, const double *v, const unsigned char *ok,
                     int n, double t0, int test, struct half_plane *hp, double *var_at)
{
    double st = 0.0, su = 0.0, stt = 0.0, stu = 0.0, pv = 0.0, rss = 0.0;
    int i, m = 0;
    for (i = 0; i < n; i++)
        if (ok[i]) {
            st += t[i];
            su += u[i];
            pv += v[i];
            m++;
        }
    if (m < 2)
        return 0;
    st /= m, su /= m, pv /= m;
    for (i = 0; i < n; i++)
        if (ok[i]) {
            stt += (t[i] - st) * (t[i] - st);
            stu += (t[i] - st) * (u[i] - su);
        }
    if (!(stt > 0.0))
        return 0;
    hp->k = stu / stt;
    hp->a = su - hp->k * st;
    for (i = 0; i < n; i++)
        if (ok[i]) {
            double r = u[i] - hp->a - hp->k * t[i];
            rss += r * r;
        }
    if (test && m > 2 && rss / (m - 2) > 4.0 * pv + CORNER_STRAIGHT * CORNER_STRAIGHT)
        return 0;
    *var_at = pv * (1.0 / m + (t0 - st) * (t0 - st) / stt);
    return 1;
}

/* Whether the pixel at corner (x, y) lies wholly inside the half-plane. */
static int pixel_inside(const struct half_plane *h, double x, double y)
{
    return plane_side(h, x, y) >= 0.0 && plane_side(h, x + 1, y) >= 0.0
           && plane_side(h, x, y + 1) >= 0.0 && plane_side(h, x + 1, y + 1) >= 0.0;
}

/* Pixel (x, y)'s emission from the straight edges of the light around it, into out[3] and
 * out_var[3]. Returns 0 (and leaves them) where the model does not apply: no light inside the
 * window of one radiance to scale by, no edge of two fitted pixels or one that is not straight,
 * a depth off the edges' (an occluder), or a pixel whose own samples disagree with the model. */
static int corner_fit(const struct corner_in *in, int x, int y, float out[3], float out_var[3])
{
    enum { WIN = (2 * CORNER_R + 1) * (2 * CORNER_R + 1) };
    double L[3] = {0.0, 0.0, 0.0}, lo = 0.0, hi = 0.0, dlo = 0.0, dhi = 0.0, n_eff = 0.0;
    double t[CORNER_GROUPS][WIN], u[CORNER_GROUPS][WIN], v[CORNER_GROUPS][WIN];
    double o[CORNER_GROUPS][WIN];
    double var_line[CORNER_GROUPS], cov, var_cov = 0.0, var_raw, w, d, chi2 = 0.0;
    struct half_plane hp[CORNER_GROUPS], line[CORNER_GROUPS];
    unsigned char have[CORNER_GROUPS] = {0};
    int round, n[CORNER_GROUPS] = {0}, n_in = 0, n_n = 0, seen = 0, cm = 0, xq, yq, c, g, n_hp = 0;
    size_t p = (size_t)y * (size_t)in->w + (size_t)x, q;
    /* The light's radiance: the pixels of the window that all rays saw lit alike (no variance),
     * the same within 1%; the shares are read in the channel cm where it is largest. */
    for (yq = y - CORNER_R; yq <= y + CORNER_R; yq++)
        for (xq = x - CORNER_R; xq <= x + CORNER_R; xq++) {
            const float *m, *var;
            double sum;
            if (xq < 0 || xq >= in->w || yq < 0 || yq >= in->h)
                continue;
            q = (size_t)yq * (size_t)in->w + (size_t)xq;
            m = in->mean + 3 * q;
            var = in->var + 3 * q;
            sum = (double)m[0] + m[1] + m[2];
            if (!(sum > 0.0) || var[0] + var[1] + var[2] != 0.0f)
                continue;
            for (c = 0; c < 3; c++)
                L[c] += m[c];
            lo = n_in == 0 || sum < lo ? sum : lo;
            hi = n_in == 0 || sum > hi ? sum : hi;
            n_in++;
        }
    if (n_in == 0 || hi > 1.01 * lo)
        return 0;
    for (c = 0; c < 3; c++)
        L[c] /= n_in;
    cm = L[1] > L[cm] ? 1 : cm;
    cm = L[2] > L[cm] ? 2 : cm;
    /* Each edge pixel of the window: the kind of its edge and its lit side from its neighbours'
     * shares (the larger difference across it, half the light or more), and the point of that
     * edge's line it gives: u at t, the line's abscissa at the pixel's middle row for a column
     * edge (its ordinate at the middle column for a row edge), with the variance of its share
     * (its fit's, or its own scaled). Groups g = 2·across + lit side. The depths of these pixels
     * bound the pixel's, as for an unseen pixel: an occluder's is nearer. */
    for (yq = y - CORNER_R; yq <= y + CORNER_R; yq++)
        for (xq = x - CORNER_R; xq <= x + CORNER_R; xq++) {
            double gx, gy, sh;
            int across, lit;
            if (xq < 1 || xq >= in->w - 1 || yq < 1 || yq >= in->h - 1)
                continue;
            q = (size_t)yq * (size_t)in->w + (size_t)xq;
            if (!in->edge[q])
                continue;
            gx = share(in, q + 1, cm, L[cm]) - share(in, q - 1, cm, L[cm]);
            gy = share(in, q + (size_t)in->w, cm, L[cm]) - share(in, q - (size_t)in->w, cm, L[cm]);
            across = fabs(gy) > fabs(gx);
            if ((across ? fabs(gy) : fabs(gx)) < 0.5)
                continue;
            lit = (across ? gy : gx) > 0.0;
            g = 2 * across + lit;
            sh = share(in, q, cm, L[cm]);
            t[g][n[g]] = (across ? xq : yq) + 0.5;
            o[g][n[g]] = across ? yq : xq;
            u[g][n[g]] = o[g][n[g]] + (lit ? 1.0 - sh : sh);
            v[g][n[g]] = (in->fitted[q] ? in->fit_var[3 * q + (size_t)cm]
                                        : in->var[3 * q + (size_t)cm] * in->scale[cm])
                         / (L[cm] * L[cm]);
            n[g]++;
            dlo = seen == 0 || in->depth[q] < dlo ? in->depth[q] : dlo;
            dhi = seen++ == 0 || in->depth[q] > dhi ? in->depth[q] : dhi;
            /* The samples' effective count, from a share's variance c(1 − c)/N. */
            if (in->var[3 * q + (size_t)cm] > 0.0f && sh > 0.02 && sh < 0.98) {
                n_eff += sh * (1.0 - sh) * L[cm] * L[cm] / in->var[3 * q + (size_t)cm];
                n_n++;
            }
        }
    if (n_n == 0 || !depth_between(in->depth[p], (float)dlo, (float)dhi))
        return 0;
    n_eff /= n_n;
    /* The lines, in three rounds: through every point of a group; through the points whose pixels
     * the group's line crosses from one side to the other (a line leaving a pixel through its top
     * covers a triangle of it, not a trapezoid); and through those whose pixels no other group's
     * line enters (where another edge cuts a pixel off, its share says less than the line). */
    for (round = 0; round < 3; round++)
        for (g = 0; g < CORNER_GROUPS; g++) {
            unsigned char ok[WIN];
            int i, h;
            if (n[g] == 0 || (round > 0 && !have[g]))
                continue;
            for (i = 0; i < n[g]; i++) {
                ok[i] = round == 0 || crosses(&line[g], t[g][i], o[g][i]);
                for (h = 0; round == 2 && h < CORNER_GROUPS; h++)
                    if (h != g && have[h] && ok[i])
                        ok[i] = g >= 2 ? pixel_inside(&line[h], t[g][i] - 0.5, o[g][i])
                                       : pixel_inside(&line[h], o[g][i], t[g][i] - 0.5);
            }
            line[g].across = g >= 2;
            line[g].s = g & 1 ? 1.0 : -1.0;
            have[g] = edge_line(t[g], u[g], v[g], ok, n[g], (g >= 2 ? x : y) + 0.5, round == 2,
                                &line[g], &var_line[g]);
            if (round == 2 && !have[g])
                return 0;
        }
    for (g = 0; g < CORNER_GROUPS; g++)
        if (have[g]) {
            hp[n_hp] = line[g];
            var_line[n_hp++] = var_line[g];
        }
    if (n_hp == 0)
        return 0;
    cov = clip_area(x, y, hp, n_hp);
    /* The share's variance from the lines': the area's derivative by each line's offset. */
    for (g = 0; g < n_hp; g++) {
        const double step = 1e-3;
        double a0 = hp[g].a, dA;
        hp[g].a = a0 + step;
        dA = clip_area(x, y, hp, n_hp);
        hp[g].a = a0 - step;
        dA = (dA - clip_area(x, y, hp, n_hp)) / (2.0 * step);
        hp[g].a = a0;
        var_cov += dA * dA * var_line[g];
    }
    /* The model against the samples of the pixel and its eight neighbours: the sum of their
     * squared standardised differences, a chi-square of 9 degrees of freedom where the model is
     * right, below CORNER_CHI2 (its 99th percentile). An edge that no group found (its pixels
     * all unfitted) shows here as a neighbour lit where the model has none, or dark where it has
     * the light. */
    for (yq = y - 1; yq <= y + 1; yq++)
        for (xq = x - 1; xq <= x + 1; xq++) {
            double cq;
            if (xq < 0 || xq >= in->w || yq < 0 || yq >= in->h)
                continue;
            q = (size_t)yq * (size_t)in->w + (size_t)xq;
            cq = q == p ? cov : clip_area(xq, yq, hp, n_hp);
            d = in->mean[3 * q + (size_t)cm] / L[cm] - cq;
            chi2 += d * d / (cq * (1.0 - cq) / n_eff + 0.25 / (n_eff * n_eff) + var_cov);
        }
    if (chi2 > CORNER_CHI2)
        return 0;
    /* The model and the pixel's own emission weighed by their inverse variances, the pixel's
     * that of a mean of hits at the model's share, scaled as the edge pixels' are. On the Cornell
     * box above (16 / 64 spp): blended 2.88e-4 / 9.33e-5; the model alone 2.98e-4 / 9.73e-5 (worse
     * where a line is extrapolated to a sliver or a tip); the model only where its variance is the
     * smaller 3.12e-4 / 9.53e-5. */
    var_raw = in->scale[cm] * (cov * (1.0 - cov) / n_eff + 0.25 / (n_eff * n_eff));
    w = var_raw / (var_raw + var_cov);
    for (c = 0; c < 3; c++) {
        out[c] = (float)(w * cov * L[c] + (1.0 - w) * in->mean[3 * p + (size_t)c]);
        out_var[c] = (float)(w * var_cov * L[c] * L[c]);
    }
    return 1;
}

int mc_light_edge_fit(const float *const em[2], const float *var_in, const float *const depth[2],
                      int width, int height, float *out, float *out_var)
{
    size_t n = (size_t)width * (size_t)height, i;
    /* Per pixel: on an edge (1, or 2 for an unseen one, below); fitted by a plane; its edge's
     * group (edge_group). */
    unsigned char *edge = mc_malloc(3 * n), *fitted = edge + n, *group = fitted + n;
    /* The halves' mean emission, its variance with the unseen pixels' (below), the mean depth. */
    float *mean = mc_malloc(n * 7 * sizeof *mean), *var = mean + n * 3, *dep = var + n * 3;
    double scale[3];
    const struct corner_in in = {mean, var, dep, out, out_var, edge, fitted, scale, width, height};
    int x, y, k, c;
    if (!edge || !mean) {
        free(edge);
        free(mean);
        return -1;
    }
    memset(fitted, 0, n);
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
    for (y = 0; y < height; y++)
        for (x = 0; x < width; x++)
            group[(size_t)y * (size_t)width + (size_t)x] = edge_group(mean, edge, width, height,
                                                                      x, y);
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
                if (fit_window(mean, var, scale, edge, group, width, height, x, y,
                               edge_radius[k], fit, fit_var)) {
                    for (c = 0; c < 3; c++) {
                        out[3 * i + (size_t)c] = fit[c];
                        out_var[3 * i + (size_t)c] = fit_var[c];
                    }
                    fitted[i] = 1;
                    break;
                }
        }
    /* The corners: the pixels on an edge or beside one that no plane fitted. They read only the
     * fitted pixels' results, so the order does not matter. */
    for (y = 0; depth[0] && y < height; y++)
        for (x = 0; x < width; x++) {
            float fit[3], fit_var[3];
            i = (size_t)y * (size_t)width + (size_t)x;
            if (fitted[i]
                || !(edge[i] || (dark(mean, var_in, i) && beside_edge(edge, width, height, x, y)))
                || !corner_fit(&in, x, y, fit, fit_var))
                continue;
            for (c = 0; c < 3; c++) {
                out[3 * i + (size_t)c] = fit[c];
                out_var[3 * i + (size_t)c] = fit_var[c];
            }
        }
    free(edge);
    free(mean);
    return 0;
}
