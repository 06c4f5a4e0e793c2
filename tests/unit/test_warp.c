/* test_warp.c: every warp of src/sample/warp.h against its pdf (chi-square, tests/chi2.h),
 * pdf normalisation, finite unit outputs at the ends of [0, 1), precision of tiny cones, and
 * the harness's own p-values and power. */
#include <stdint.h>
#include <string.h>

#include "chi2.h"
#include "sample/warp.h"
#include "t.h"

/* Chi-square tests this binary expects to accept (the Šidák correction divides 0.01 among them). */
#define CHI2_TESTS 10

static vec2 rand2(pcg32 *r)
{
    float a = pcg32_float(r);
    return v2(a, pcg32_float(r));
}

/* ---- direction warps in (θ, φ) ---- */

struct cone { float cos_max, sin2_max; };

static int sample_cosine(void *ctx, pcg32 *rng, vec3 *w)
{
    (void)ctx;
    *w = mc_warp_cosine_hemisphere(rand2(rng));
    return 1;
}
static double pdf_cosine(void *ctx, vec3 w)
{
    (void)ctx;
    return mc_warp_cosine_hemisphere_pdf(w.z);
}
static int sample_hemisphere(void *ctx, pcg32 *rng, vec3 *w)
{
    (void)ctx;
    *w = mc_warp_uniform_hemisphere(rand2(rng));
    return 1;
}
static double pdf_hemisphere(void *ctx, vec3 w)
{
    (void)ctx;
    return w.z > 0.0f ? mc_warp_uniform_hemisphere_pdf() : 0.0;
}
static int sample_sphere(void *ctx, pcg32 *rng, vec3 *w)
{
    (void)ctx;
    *w = mc_warp_uniform_sphere(rand2(rng));
    return 1;
}
static double pdf_sphere(void *ctx, vec3 w)
{
    (void)ctx;
    (void)w;
    return mc_warp_uniform_sphere_pdf();
}
static int sample_cone(void *ctx, pcg32 *rng, vec3 *w)
{
    const struct cone *c = (const struct cone *)ctx;
    *w = mc_warp_uniform_cone(rand2(rng), c->cos_max, c->sin2_max);
    return 1;
}
/* The test's domain is the cone itself (θ ≤ θmax), so the density is constant on it; a sample
 * outside the cone falls outside the domain and is rejected as a stray. */
static double pdf_cone(void *ctx, vec3 w)
{
    const struct cone *c = (const struct cone *)ctx;
    (void)w;
    return mc_warp_uniform_cone_pdf(c->cos_max, c->sin2_max);
}

static struct cone cone_of(double theta_max)
{
    struct cone c;
    c.cos_max = (float)cos(theta_max);
    c.sin2_max = (float)(sin(theta_max) * sin(theta_max));
    return c;
}

/* pdf integrals: the pdfs are float (relative error ~1e-7) and the harness's quadrature is good
 * to ~1e-9 for these smooth integrands, so 1e-5 is generous yet catches any wrong constant. */
#define INTEGRAL_TOL 1e-5

static void check_direction_warp(const char *name, chi2_dir_sample_fn sample, chi2_dir_pdf_fn pdf,
                                 void *ctx, double theta_max, uint64_t seed)
{
    struct chi2_dir_spec s;
    struct chi2_result r;
    s = chi2_dir_spec_of(name, sample, pdf, ctx, theta_max);
    s.seed = seed;
    s.tests = CHI2_TESTS;
    r = chi2_run_directions(&s);
    T_NOTE("%s: chi2 %.1f, dof %d, p %.3f (alpha %.2g), pdf integral %.7f, strays %ld", name, r.chi2,
           r.dof, r.p, r.alpha, r.integral, r.stray);
    T_CHECK(r.pass, "%s: %s", name, r.why);
    T_CHECK(fabs(r.integral - 1.0) <= INTEGRAL_TOL, "%s: pdf integral %.9f", name, r.integral);
}

static void test_direction_warps(void)
{
    struct cone c30 = cone_of(MC_PI / 6.0), c90 = cone_of(MC_PI / 2.0), c150 = cone_of(5.0 * MC_PI / 6.0),
                c2 = cone_of(2.0 * MC_PI / 180.0);
    check_direction_warp("cosine hemisphere", sample_cosine, pdf_cosine, NULL, 0.0, 1);
    check_direction_warp("uniform hemisphere", sample_hemisphere, pdf_hemisphere, NULL, 0.0, 2);
    check_direction_warp("uniform sphere", sample_sphere, pdf_sphere, NULL, 0.0, 3);
    check_direction_warp("cone 30 deg", sample_cone, pdf_cone, &c30, MC_PI / 6.0, 4);
    check_direction_warp("cone 90 deg", sample_cone, pdf_cone, &c90, MC_PI / 2.0, 5);
    check_direction_warp("cone 150 deg", sample_cone, pdf_cone, &c150, 5.0 * MC_PI / 6.0, 6);
    check_direction_warp("cone 2 deg", sample_cone, pdf_cone, &c2, 2.0 * MC_PI / 180.0, 7);
}

/* ---- tiny cones ---- */

/* A cone too narrow for (θ, φ) bins (θ ~ 1e-7 rad, where float cosθ is exactly 1) is binned by
 * (sin²θ/sin²θmax, φ): for a uniform cone 1 − cosθ is uniform on [0, 1 − cosθmax] and
 * sin²θ = (1 − cosθ)(1 + cosθ), so the first coordinate is uniform up to O(sin²θmax). */
static int sample_tiny_cone(void *ctx, pcg32 *rng, double *x, double *y)
{
    const struct cone *c = (const struct cone *)ctx;
    vec3 w = mc_warp_uniform_cone(rand2(rng), c->cos_max, c->sin2_max);
    double phi = atan2((double)w.y, (double)w.x);
    if (!v3_is_finite(w))
        return -1;
    *x = ((double)w.x * w.x + (double)w.y * w.y) / c->sin2_max;
    *y = phi < 0.0 ? phi + 2.0 * CHI2_PI : phi;
    return 1;
}
/* Uniform densities on [0, 1] × [0, 2π) and on the unit square. */
static double density_polar(void *ctx, double x, double y)
{
    (void)ctx;
    (void)x;
    (void)y;
    return 1.0 / (2.0 * CHI2_PI);
}
static double density_square(void *ctx, double x, double y)
{
    (void)ctx;
    (void)x;
    (void)y;
    return 1.0;
}

static struct chi2_result run_2d(const char *name, chi2_sample_fn sample, chi2_density_fn density,
                                 void *ctx, double y1, uint64_t seed, int quiet)
{
    struct chi2_spec s;
    s = chi2_rect_spec(name, sample, density, ctx, 0.0, 1.0, 0.0, y1, 50, 100);
    s.seed = seed;
    s.tests = CHI2_TESTS;
    s.quiet = quiet;
    return chi2_run(&s);
}

static void test_tiny_cone(void)
{
    static const float sin2s[] = {1e-14f, 1e-10f, 1e-6f};
    size_t k;
    for (k = 0; k < sizeof sin2s / sizeof sin2s[0]; k++) {
        struct cone c;
        pcg32 rng;
        double omc = sin2s[k] / (1.0 + sqrt(1.0 - sin2s[k])), max_s2 = 0.0, max_dlen = 0.0;
        int i, finite = 1;
        c.sin2_max = sin2s[k];
        c.cos_max = (float)sqrt(1.0 - sin2s[k]);
        pcg32_seed(&rng, 100 + k, 0);
        for (i = 0; i < 100000; i++) {
            vec2 u = i < 4 ? v2(i & 1 ? 0x1.fffffep-1f : 0.0f, i & 2 ? 0x1.fffffep-1f : 0.0f) : rand2(&rng);
            vec3 w = mc_warp_uniform_cone(u, c.cos_max, c.sin2_max);
            double s2 = (double)w.x * w.x + (double)w.y * w.y, len2 = s2 + (double)w.z * w.z;
            finite &= v3_is_finite(w) && w.z > 0.0f;
            if (s2 / sin2s[k] > max_s2)
                max_s2 = s2 / sin2s[k];
            if (fabs(len2 - 1.0) > max_dlen)
                max_dlen = fabs(len2 - 1.0);
        }
        T_NOTE("cone sin2_max %g: max sin2/sin2_max %.7f, max |len2 - 1| %.2g, pdf %.6g", sin2s[k], max_s2,
               max_dlen, mc_warp_uniform_cone_pdf(c.cos_max, c.sin2_max));
        T_CHECK(finite, "cone sin2_max %g: non-finite sample or one below the horizon", sin2s[k]);
        /* x, y are float products (≤ 3 roundings each): sin²θ is good to ~1e-6 relative. */
        T_CHECK(max_s2 <= 1.0 + 1e-5, "cone sin2_max %g: sample outside the cone (%.9g)", sin2s[k], max_s2);
        T_CHECK(max_dlen <= 1e-6, "cone sin2_max %g: |len2 - 1| = %g", sin2s[k], max_dlen);
        /* The float pdf against 1/(2π(1 − cosθmax)) in double, to float precision. */
        {
            double ratio = mc_warp_uniform_cone_pdf(c.cos_max, c.sin2_max) * (2.0 * CHI2_PI * omc);
            T_CHECK(fabs(ratio - 1.0) <= 1e-5, "cone pdf at sin2_max %g: %.9g of exact", sin2s[k], ratio);
        }
    }
    {
        struct cone c;
        struct chi2_result r;
        c.sin2_max = 1e-14f;
        c.cos_max = 1.0f;
        r = run_2d("cone sin2_max 1e-14", sample_tiny_cone, density_polar, &c, 2.0 * CHI2_PI, 8, 0);
        T_NOTE("cone sin2_max 1e-14 in (sin2/sin2_max, phi): chi2 %.1f, dof %d, p %.3f, integral %.7f",
               r.chi2, r.dof, r.p, r.integral);
        T_CHECK(r.pass, "tiny cone: %s", r.why);
    }
}

/* ---- 2D warps, through independent inverse maps onto uniform coordinates ---- */

/* A uniform disk point has uniform (r², φ): the disk's area inside radius r is πr². */
static int disk_coords(vec2 p, double *x, double *y)
{
    double phi = atan2((double)p.y, (double)p.x);
    *x = (double)p.x * p.x + (double)p.y * p.y;
    *y = phi < 0.0 ? phi + 2.0 * CHI2_PI : phi;
    return *x <= 1.0 + 1e-6 ? 1 : -1;
}
static int sample_disk(void *ctx, pcg32 *rng, double *x, double *y)
{
    (void)ctx;
    return disk_coords(mc_warp_concentric_disk(rand2(rng)), x, y);
}
/* The textbook mistake r = ξ1, φ = 2πξ2: it crowds the centre (density 1/(2πr)). */
static int sample_naive_disk(void *ctx, pcg32 *rng, double *x, double *y)
{
    vec2 u = rand2(rng);
    float phi = 2.0f * MC_PI * u.y;
    (void)ctx;
    return disk_coords(v2(u.x * cosf(phi), u.x * sinf(phi)), x, y);
}

/* Uniform barycentrics map to the uniform square through the inverse of the classic
 * square-root map (b1, b2) = (1 − √s, t√s) (Osada et al. 2002; its Jacobian is the constant
 * 1/2), an independent check of Heitz's map. */
static int sample_triangle(void *ctx, pcg32 *rng, double *x, double *y)
{
    vec2 b = mc_warp_triangle(rand2(rng));
    double b1 = b.x, b2 = b.y;
    (void)ctx;
    /* b1 ≤ max(u) < 1, so 1 − b1 > 0 */
    if (!(b1 >= 0.0 && b2 >= 0.0 && b1 + b2 <= 1.0 + 1e-6))
        return -1;
    *x = (1.0 - b1) * (1.0 - b1);
    *y = b2 / (1.0 - b1);
    return 1;
}

static void test_planar_warps(void)
{
    struct chi2_result r;
    r = run_2d("concentric disk", sample_disk, density_polar, NULL, 2.0 * CHI2_PI, 9, 0);
    T_NOTE("concentric disk in (r^2, phi): chi2 %.1f, dof %d, p %.3f", r.chi2, r.dof, r.p);
    T_CHECK(r.pass, "concentric disk: %s", r.why);

    r = run_2d("triangle", sample_triangle, density_square, NULL, 1.0, 10, 0);
    T_NOTE("triangle in (s, t) of the square-root map: chi2 %.1f, dof %d, p %.3f", r.chi2, r.dof, r.p);
    T_CHECK(r.pass, "triangle: %s", r.why);

    /* The harness has power: the naive disk must be rejected on statistics (not by a hard
     * failure), with a vanishing p-value. */
    r = run_2d("naive disk", sample_naive_disk, density_polar, NULL, 2.0 * CHI2_PI, 11, 1);
    T_NOTE("naive disk r = u1 (expected to be rejected): chi2 %.1f, dof %d, p %.3g", r.chi2, r.dof, r.p);
    T_CHECK(!r.pass && r.dof > 0 && r.stray == 0 && r.p < 1e-12, "naive disk: pass %d, p %g, %s", r.pass,
            r.p, r.why);
}

/* ---- edges of the unit square ---- */

static void test_edges(void)
{
    static const float us[] = {0.0f, 0.5f, 0x1.fffffep-1f}; /* 1 − 2^-24: pcg32_float's largest */
    static const float cones[][2] = {
        {1.0f, 1e-14f}, {0.99999999f, 2e-8f}, {0.8f, 0.36f}, {0.0f, 1.0f}, {-0.5f, 0.75f}, {-1.0f, 0.0f}};
    int i, j, bad_dir = 0, bad_disk = 0, bad_tri = 0;
    size_t k;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            vec2 u = v2(us[i], us[j]), d = mc_warp_concentric_disk(u), b = mc_warp_triangle(u);
            vec3 w[3 + sizeof cones / sizeof cones[0]];
            int n = 0, m;
            w[n++] = mc_warp_cosine_hemisphere(u);
            w[n++] = mc_warp_uniform_hemisphere(u);
            w[n++] = mc_warp_uniform_sphere(u);
            for (k = 0; k < sizeof cones / sizeof cones[0]; k++)
                w[n++] = mc_warp_uniform_cone(u, cones[k][0], cones[k][1]);
            /* float unit vectors: |len − 1| within a few ulps (1e-6) */
            for (m = 0; m < n; m++)
                if (!v3_is_finite(w[m]) || fabsf(v3_length(w[m]) - 1.0f) > 1e-6f ||
                    (m < 2 && w[m].z < 0.0f)) {
                    bad_dir++;
                    printf("  edge u=(%a, %a): direction %d = (%g, %g, %g)\n", u.x, u.y, m, w[m].x, w[m].y,
                           w[m].z);
                }
            if (!(isfinite(d.x) && isfinite(d.y) && d.x * d.x + d.y * d.y <= 1.0f + 1e-6f))
                bad_disk++;
            if (!(isfinite(b.x) && isfinite(b.y) && b.x >= 0.0f && b.y >= 0.0f && b.x + b.y <= 1.0f))
                bad_tri++;
        }
    T_CHECK(bad_dir == 0, "%d direction warps gave non-finite or non-unit output at the edges", bad_dir);
    T_CHECK(bad_disk == 0, "%d disk points off the disk at the edges", bad_disk);
    T_CHECK(bad_tri == 0, "%d invalid barycentrics at the edges", bad_tri);
    {
        vec2 c = mc_warp_concentric_disk(v2(0.5f, 0.5f));
        T_CHECK(c.x == 0.0f && c.y == 0.0f, "disk centre: (%g, %g)", c.x, c.y);
    }
    for (k = 0; k < sizeof cones / sizeof cones[0]; k++) {
        float p = mc_warp_uniform_cone_pdf(cones[k][0], cones[k][1]);
        T_CHECK(isfinite(p) && p > 0.0f, "cone pdf (%g, %g) = %g", cones[k][0], cones[k][1], p);
    }
    T_CHECK(mc_warp_uniform_cone_pdf(1.0f, 0.0f) == 0.0f, "degenerate cone pdf must be 0");
}

/* ---- the harness's p-values ---- */

static void test_p_values(void)
{
    /* Reference values from mpmath.gammainc(dof/2, x/2, inf, regularized=True) at 30 digits;
     * the series and continued fraction both converge to ~1e-14. */
    T_NEAR(chi2_p_value(5.0, 10), 0.891178018914151, 1e-12, "series branch");
    T_NEAR(chi2_p_value(23.209251158954356, 10), 0.01, 1e-12, "chi2 0.99 quantile, dof 10");
    T_NEAR(chi2_p_value(135.80672317102676, 100), 0.01, 1e-12, "chi2 0.99 quantile, dof 100");
    T_NEAR(chi2_p_value(3.841458820694124, 1), 0.05, 1e-12, "chi2 0.95 quantile, dof 1");
    T_NEAR(chi2_p_value(10.0, 2), exp(-5.0), 1e-14, "dof 2 is exponential");
    T_NEAR(chi2_p_value(12000.0, 12799), 0.9999998280351775, 1e-10, "large dof, series");
    T_NEAR(chi2_p_value(13200.0, 12799), 0.00648126511068456, 1e-10, "large dof, fraction");
    T_CHECK(chi2_p_value(1e7, 5000) == 0.0, "huge chi2 underflows to 0, not NaN");
}

int main(void)
{
    test_p_values();
    test_direction_warps();
    test_tiny_cone();
    test_planar_warps();
    test_edges();
    return t_done();
}
