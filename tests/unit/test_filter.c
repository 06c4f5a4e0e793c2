/* test_filter.c: the pixel filters of src/sample/filter.h: sampling against the pdf (chi-square,
 * tests/chi2.h), the pdf's normalisation, the box filter's exact film points, and continuity of
 * the sampling maps (which is what lets stratification carry over). */
#include <stdint.h>
#include <string.h>

#include "chi2.h"
#include "sample/filter.h"
#include "t.h"

/* Chi-square tests this binary expects to accept (the Šidák correction divides 0.01 among them). */
#define CHI2_TESTS 3

static vec2 rand2(pcg32 *r)
{
    float a = pcg32_float(r);
    return v2(a, pcg32_float(r));
}

/* ---- chi-square ---- */

/* Box and tent in Cartesian offsets: their densities are continuous on the open cells of the
 * histogram (the tent's kinks lie on cell edges for an even cell count), so the harness's
 * quadrature is accurate. */
static int sample_cartesian(void *ctx, pcg32 *rng, double *x, double *y)
{
    vec2 o = mc_filter_sample(*(const enum filter_kind *)ctx, rand2(rng));
    *x = o.x;
    *y = o.y;
    return 1;
}
static double density_cartesian(void *ctx, double x, double y)
{
    return mc_filter_pdf(*(const enum filter_kind *)ctx, v2((float)x, (float)y));
}

/* The Gaussian's support is a disk, whose rim would cut histogram cells where the density jumps
 * from e^-4.5·p(0) to 0 and the quadrature cannot follow. In polar coordinates (r, φ) the domain
 * is the rectangle [0, 1.5] × [0, 2π) and the density p(r)·r is smooth: the same distribution,
 * tested without the jump. */
static int sample_polar(void *ctx, pcg32 *rng, double *r, double *phi)
{
    vec2 o = mc_filter_sample(*(const enum filter_kind *)ctx, rand2(rng));
    double a = atan2((double)o.y, (double)o.x);
    *r = hypot((double)o.x, (double)o.y);
    *phi = a < 0.0 ? a + 2.0 * CHI2_PI : a;
    return 1;
}
static double density_polar(void *ctx, double r, double phi)
{
    vec2 o = v2((float)(r * cos(phi)), (float)(r * sin(phi)));
    return mc_filter_pdf(*(const enum filter_kind *)ctx, o) * r;
}

static void chi2_filter(const char *name, enum filter_kind k, int polar, uint64_t seed)
{
    double rad = mc_filter_radius(k);
    struct chi2_spec s = polar ? chi2_rect_spec(name, sample_polar, density_polar, &k, 0.0, rad, 0.0,
                                                2.0 * CHI2_PI, 40, 80)
                               : chi2_rect_spec(name, sample_cartesian, density_cartesian, &k, -rad,
                                                rad, -rad, rad, 40, 40);
    struct chi2_result r;
    s.seed = seed;
    s.tests = CHI2_TESTS;
    r = chi2_run(&s);
    T_NOTE("%s: chi2 %.1f, dof %d, p %.3f (alpha %.2g), strays %ld", name, r.chi2, r.dof, r.p, r.alpha,
           r.stray);
    T_CHECK(r.pass, "%s: %s", name, r.why);
}

/* ---- normalisation ---- */

/* ∫∫ pdf over the square [-R, R]² by the midpoint rule on M×M cells, M even.
 * box: 1 on the whole square [-½, ½]²: exact.
 * tent: linear on every cell (its kinks at 0 and ±1 are cell edges): midpoint is exact.
 * gaussian: the smooth part has midpoint error O(h²) ~ 1e-7; the cells cut by the rim of the
 * disk (at most 4·2R/h + 4 of them for a convex curve) each err by at most h² times the density
 * there (p(1.5) = e^-4.5/(2πσ²(1 − e^-4.5)) ≈ 7.2e-3), so |error| ≤ (8R/h + 4)·h²·7.2e-3
 * ≈ 0.087·h = 8.7e-5 for h = 1e-3. Float pdfs add ~1e-7 relative. */
static void test_normalisation(void)
{
    static const enum filter_kind kinds[3] = {FILTER_BOX, FILTER_TENT, FILTER_GAUSSIAN};
    static const char *const names[3] = {"box", "tent", "gaussian"};
    static const double tol[3] = {1e-6, 1e-6, 9e-5};
    int k;
    for (k = 0; k < 3; k++) {
        double R = mc_filter_radius(kinds[k]), h = 1e-3, sum = 0.0;
        int M = (int)(2.0 * R / h + 0.5), i, j;
        h = 2.0 * R / M;
        for (i = 0; i < M; i++) {
            double row = 0.0;
            float x = (float)(-R + (i + 0.5) * h);
            for (j = 0; j < M; j++)
                row += mc_filter_pdf(kinds[k], v2(x, (float)(-R + (j + 0.5) * h)));
            sum += row;
        }
        sum *= h * h;
        T_NOTE("%s: pdf integral %.8f over [-%.1f, %.1f]^2 (%d^2 cells)", names[k], sum, R, R, M);
        T_NEAR(sum, 1.0, tol[k], "%s pdf does not integrate to 1", names[k]);
        /* Outside the support the pdf is 0: the filter's radius is its real half-width. */
        T_CHECK(mc_filter_pdf(kinds[k], v2((float)R * 1.001f, 0.0f)) == 0.0f
                    && mc_filter_pdf(kinds[k], v2(0.0f, -(float)R * 1.001f)) == 0.0f,
                "%s: pdf nonzero beyond its radius", names[k]);
    }
}

/* ---- box: the film point is x + u exactly ---- */

static void test_box_exact(void)
{
    pcg32 rng;
    int i, bad = 0;
    pcg32_seed(&rng, 11, 1);
    for (i = 0; i < 100000; i++) {
        vec2 u = rand2(&rng);
        float x = (float)(pcg32_next(&rng) % 8192u);
        vec2 o = mc_filter_sample(FILTER_BOX, u);
        bad += !(o.x == u.x - 0.5f && o.y == u.y - 0.5f && (x + 0.5f) + o.x == x + u.x);
    }
    /* u = 1 − 2^-24, the largest pcg32_float, stays inside the pixel. */
    bad += !(mc_filter_sample(FILTER_BOX, v2(0x1.fffffep-1f, 0.0f)).x < 0.5f);
    T_CHECK(bad == 0, "%d box offsets differ from u - 1/2 or give a film point other than x + u", bad);
}

/* ---- continuity ---- */

/* Along each axis of a 1024-step grid of u, neighbouring offsets move by at most √(2δ), δ = 1/1024:
 * the tent's largest step is at u = 0, where x = √(2u) − 1; the Gaussian's radius is
 * σ√(−2 ln(1 − c·u)) ≤ √(2δ)/2 there and its arc steps are at most 1.5·2πδ ≈ 0.0092. A map with
 * a branch that does not meet its neighbour jumps by much more. The angle's seam (u.y = 0 against
 * 1) joins the same angle and is not on the grid. */
static void test_continuity(void)
{
    static const enum filter_kind kinds[3] = {FILTER_BOX, FILTER_TENT, FILTER_GAUSSIAN};
    const int n = 1024;
    const double bound = sqrt(2.0 / n) * (1.0 + 1e-3);
    int k, i, j;
    for (k = 0; k < 3; k++) {
        double worst = 0.0;
        for (i = 0; i < n; i++)
            for (j = 0; j + 1 < n; j++) {
                float a = (float)i / n, b = (float)j / n, c = (float)(j + 1) / n;
                vec2 p = mc_filter_sample(kinds[k], v2(a, b)), q = mc_filter_sample(kinds[k], v2(a, c));
                vec2 p2 = mc_filter_sample(kinds[k], v2(b, a)), q2 = mc_filter_sample(kinds[k], v2(c, a));
                double d1 = hypot((double)p.x - q.x, (double)p.y - q.y);
                double d2 = hypot((double)p2.x - q2.x, (double)p2.y - q2.y);
                if (d1 > worst)
                    worst = d1;
                if (d2 > worst)
                    worst = d2;
            }
        T_NOTE("filter %d: largest step between neighbouring u %.4f px (bound %.4f)", k, worst, bound);
        T_CHECK(worst <= bound, "filter %d: sampling map jumps by %.4f px", k, worst);
    }
}

int main(void)
{
    chi2_filter("box", FILTER_BOX, 0, 1);
    chi2_filter("tent", FILTER_TENT, 0, 2);
    chi2_filter("gaussian (r, phi)", FILTER_GAUSSIAN, 1, 3);
    test_normalisation();
    test_box_exact();
    test_continuity();
    return t_done();
}
