/* test_envmap.c: environment maps (light/envmap.h) through the light interface (light.h).
 *
 * - The lat-long convention of man/mcrt.5 on a 4×2 map whose pixels all differ: +y sees the top
 *   row, −z the centre, +x the right quarter, −x the left; `rotate` turns the map.
 * - Spherical chi-square tests (tests/chi2.h) of the sampled directions against mc_light_pdf, on
 *   the anchors' cases (Mitsuba's test_envmap.py): a constant 100×100 map, a 3×2 map, a 100×10
 *   map with one bright pixel on a black ground (tested in the map's own (u, v) rectangle with
 *   cells on the pixel edges, where the pdf is smooth in each cell), a rotated 3×2 map and the
 *   photon emission directions.
 * - Every sample's radiance and pdf are what eval and pdf give for its direction.
 * - A constant map is the constant sky: the same radiance in every direction and the same power;
 *   the white furnace (albedo 1, E[L·cos/(π·pdf)] = 1) within 4 standard errors.
 * - Suns on the pole, on the seam (u = 0 and u = 1) and in the open sky: no NaN, irradiance by
 *   light sampling within 4 standard errors of the closed form Σ L ∫cos dω over the pixels.
 * - The sun: at an equal number of samples, MIS of light and cosine sampling has a variance at
 *   least 10× below cosine sampling alone, with 3 standard errors of each variance as margin.
 * - Bad maps: a NaN and a negative pixel are refused with their position; zeros are allowed. */
#include <stdlib.h>
#include <string.h>

#include "chi2.h"
#include "light/envmap.h"
#include "light/light.h"
#include "sample/warp.h"
#include "t.h"

#define CHI2_TESTS 7
static const double PI = 3.14159265358979323846;

struct env {
    struct envmap map;
    struct light l;
    struct light_scene ls;
};

/* An environment light over the map of rgb (w × h), turned by `degrees` about `axis`. */
static int env_make(struct env *e, const float *rgb, int w, int h, vec3 axis, float degrees)
{
    mc_diag d;
    vec3 v[4];
    memset(e, 0, sizeof *e);
    if (mc_envmap_build(&e->map, rgb, w, h, "test", &d) != MCRT_OK) {
        T_CHECK(0, "map does not build: %s", d.msg);
        return 0;
    }
    v[0] = v3s(1.0f);                   /* radiance */
    v[1] = v3(1.0f, 0.0f, 0.0f);        /* map: image 1 */
    v[2] = v3(1.0f, 0.0f, 0.0f);        /* scale */
    v[3] = v3_scale(axis, degrees);     /* rotate */
    e->l.kind = LIGHT_ENVIRONMENT;
    mc_light_kinds[LIGHT_ENVIRONMENT]->build(&e->l, v);
    e->l.map = &e->map;
    e->ls.radius = 2.0f;
    return 1;
}

/* A w × h map of grey `base` with the pixels (px[i], py[i]) set to `bright`. */
static float *grey_map(int w, int h, float base, int n, const int *px, const int *py, float bright)
{
    float *rgb = malloc((size_t)w * (size_t)h * 3 * sizeof *rgb);
    int i;
    for (i = 0; i < w * h * 3; i++)
        rgb[i] = base;
    for (i = 0; i < n; i++) {
        float *c = &rgb[3 * (py[i] * w + px[i])];
        c[0] = c[1] = c[2] = bright;
    }
    return rgb;
}

static int same_rgb(vec3 a, vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

static vec3 unit(float x, float y, float z) { return v3_normalize(v3(x, y, z)); }

static void test_convention(void)
{
    float rgb[4 * 2 * 3];
    struct env e;
    int i;
    for (i = 0; i < 8; i++)
        rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = (float)(1 + i); /* pixel (x, y): 1 + x + 4y */
    if (!env_make(&e, rgb, 4, 2, v3(0, 1, 0), 0.0f))
        return;
    T_NEAR(mc_environment_radiance(&e.l, unit(0, 1, -0.1f)).x, 1 + 2, 0, "up: the top row");
    T_NEAR(mc_environment_radiance(&e.l, unit(0, 0.1f, -1)).x, 1 + 2, 0, "-z: the centre");
    T_NEAR(mc_environment_radiance(&e.l, unit(1, 0.1f, 0)).x, 1 + 3, 0, "+x: u in [3/4, 1)");
    T_NEAR(mc_environment_radiance(&e.l, unit(-1, 0.1f, 0)).x, 1 + 1, 0, "-x: u in [1/4, 1/2)");
    T_NEAR(mc_environment_radiance(&e.l, unit(-1, -0.1f, 0)).x, 1 + 5, 0, "below: the bottom row");
    T_NEAR(mc_environment_radiance(&e.l, unit(0.01f, 0.1f, 1)).x, 1 + 3, 0, "+z, x > 0: u = 1");
    T_NEAR(mc_environment_radiance(&e.l, unit(-0.01f, 0.1f, 1)).x, 1 + 0, 0, "+z, x < 0: u = 0");
    mc_envmap_free(&e.map);
    /* Turned 90° about +y, the map's +x (pixel 3) faces the world's −z. */
    if (!env_make(&e, rgb, 4, 2, v3(0, 1, 0), 90.0f))
        return;
    T_NEAR(mc_environment_radiance(&e.l, unit(0, 0.1f, -1)).x, 1 + 3, 0, "rotated: -z sees +x");
    mc_envmap_free(&e.map);
}

/* ---- sampling against the pdf ---- */

static int dir_sample(void *ctx, pcg32 *g, vec3 *w)
{
    struct env *e = ctx;
    struct light_sample s;
    vec2 u;
    u.x = pcg32_float(g);
    u.y = pcg32_float(g);
    if (!mc_light_sample(&e->ls, &e->l, v3s(0.0f), 0.0f, u, &s))
        return 0;
    *w = s.wi;
    return isfinite(s.pdf) && s.pdf > 0.0f ? 1 : -1;
}

static double dir_pdf(void *ctx, vec3 w)
{
    struct env *e = ctx;
    return mc_light_pdf(&e->ls, &e->l, v3s(0.0f), 0.0f, w, INFINITY, NULL);
}

/* Photons travel along d from the sky direction −d. */
static int emit_sample(void *ctx, pcg32 *g, vec3 *w)
{
    struct env *e = ctx;
    struct light_emission em;
    vec2 a, b;
    a.x = pcg32_float(g);
    a.y = pcg32_float(g);
    b.x = pcg32_float(g);
    b.y = pcg32_float(g);
    if (!mc_light_sample_emission(&e->ls, &e->l, 0.0f, a, b, &em))
        return 0;
    *w = v3_neg(em.d);
    return isfinite(em.pdf_dir) && em.pdf_dir > 0.0f ? 1 : -1;
}

static void chi2_dirs(const char *name, struct env *e, chi2_dir_sample_fn sample)
{
    struct chi2_dir_spec s = chi2_dir_spec_of(name, sample, dir_pdf, e, 0.0);
    struct chi2_result r;
    s.tests = CHI2_TESTS;
    s.seed = 17;
    r = chi2_run_directions(&s);
    T_CHECK(r.pass, "%s: chi2 %.1f, p %.3g (alpha %.3g), %s", name, r.chi2, r.p, r.alpha, r.why);
}

/* The map's own rectangle: (u, v) of a sample, density pdf·2π² sin θ per unit area. */
static int uv_sample(void *ctx, pcg32 *g, double *x, double *y)
{
    vec3 w;
    vec2 uv;
    int ok = dir_sample(ctx, g, &w);
    if (ok <= 0)
        return ok;
    uv = mc_envmap_uv(w);
    *x = uv.x;
    *y = uv.y;
    return 1;
}

static double uv_density(void *ctx, double u, double v)
{
    vec3 w = mc_envmap_direction((float)u, (float)v);
    return dir_pdf(ctx, w) * 2.0 * PI * PI * sin(PI * v);
}

/* Each sample's radiance and pdf are eval's and pdf's for its direction; none is NaN. */
static void check_agree(const char *name, struct env *e)
{
    pcg32 g;
    long i, bad_l = 0, bad_pdf = 0, nan = 0;
    pcg32_seed(&g, 5, 7);
    for (i = 0; i < 100000; i++) {
        struct light_sample s;
        vec2 u;
        float p;
        u.x = pcg32_float(&g);
        u.y = pcg32_float(&g);
        if (!mc_light_sample(&e->ls, &e->l, v3s(0.0f), 0.0f, u, &s))
            continue;
        p = mc_light_pdf(&e->ls, &e->l, v3s(0.0f), 0.0f, s.wi, INFINITY, NULL);
        nan += !v3_is_finite(s.L) || !isfinite(s.pdf) || !v3_is_finite(s.wi);
        /* Float rounding of a direction on a pixel's edge (u = 0 exactly, the seam) may move it
         * to the neighbour, and sin θ within 1e-5 of a pole is known to ~1e-3: a few in 1e5. */
        bad_l += !same_rgb(s.L, mc_environment_radiance(&e->l, s.wi));
        bad_pdf += fabsf(p - s.pdf) > 1e-3f * s.pdf;
    }
    T_CHECK(nan == 0, "%s: %ld NaN samples", name, nan);
    T_CHECK(bad_l <= 10, "%s: %ld of 1e5 samples whose radiance is not eval's", name, bad_l);
    T_CHECK(bad_pdf <= 10, "%s: %ld of 1e5 samples whose pdf is not pdf's", name, bad_pdf);
}

static void test_sampling(void)
{
    static const float small[3 * 2 * 3] = {1, 1, 1, 2, 2, 2, 3, 0.5f, 3, 4, 4, 4, 0.5f, 0.5f, 0.5f, 6, 6, 6};
    int bx = 37, by = 4;
    float *rgb;
    struct env e;
    rgb = grey_map(100, 100, 1.0f, 0, NULL, NULL, 0.0f);
    if (env_make(&e, rgb, 100, 100, v3(0, 1, 0), 0.0f)) {
        chi2_dirs("constant 100x100", &e, dir_sample);
        check_agree("constant 100x100", &e);
        mc_envmap_free(&e.map);
    }
    free(rgb);
    if (env_make(&e, small, 3, 2, v3(0, 1, 0), 0.0f)) {
        chi2_dirs("3x2", &e, dir_sample);
        chi2_dirs("3x2 emission", &e, emit_sample);
        check_agree("3x2", &e);
        mc_envmap_free(&e.map);
    }
    if (env_make(&e, small, 3, 2, v3(1, 1, 0.3f), 30.0f)) {
        chi2_dirs("3x2 rotated", &e, dir_sample);
        check_agree("3x2 rotated", &e);
        mc_envmap_free(&e.map);
    }
    rgb = grey_map(100, 10, 0.0f, 1, &bx, &by, 1.0f);
    if (env_make(&e, rgb, 100, 10, v3(0, 1, 0), 0.0f)) {
        struct chi2_spec s = chi2_rect_spec("one bright pixel, (u, v)", uv_sample, uv_density, &e,
                                            0.0, 1.0, 0.0, 1.0, 100, 40);
        struct chi2_result r;
        s.tests = CHI2_TESTS;
        s.seed = 3;
        r = chi2_run(&s);
        T_CHECK(r.pass, "one bright pixel: chi2 %.1f, p %.3g, %s", r.chi2, r.p, r.why);
        check_agree("one bright pixel", &e);
        mc_envmap_free(&e.map);
    }
    free(rgb);
}

/* ---- estimators ---- */

struct moments {
    double mean, se, var, var_se; /* the mean, its standard error, the variance and its */
};

static struct moments moments_of(const double *x, long n)
{
    struct moments m;
    double s = 0, s2 = 0, s4 = 0;
    long i;
    for (i = 0; i < n; i++)
        s += x[i];
    m.mean = s / (double)n;
    for (i = 0; i < n; i++) {
        double d = x[i] - m.mean;
        s2 += d * d;
        s4 += d * d * d * d;
    }
    m.var = s2 / (double)(n - 1);
    m.se = sqrt(m.var / (double)n);
    /* Var of the sample variance ≈ (μ4 − σ⁴)/n. */
    m.var_se = sqrt(fmax(0.0, s4 / (double)n - m.var * m.var) / (double)n);
    return m;
}

/* Irradiance at a point facing +y: the closed form Σ L ∫ cos⁺ dω over the pixels above the horizon,
 * where ∫ cos dω over a pixel of row [θ0, θ1] is (2π/w)·(sin²θ1 − sin²θ0)/2. */
static double exact_irradiance(const float *rgb, int w, int h)
{
    double e = 0.0;
    int x, y;
    for (y = 0; y < h; y++) {
        double t0 = PI * y / h, t1 = PI * (y + 1) / h;
        if (t1 > PI / 2)
            t1 = PI / 2;
        if (t0 >= t1)
            break;
        for (x = 0; x < w; x++) {
            const float *c = &rgb[3 * (y * w + x)];
            e += (c[0] + c[1] + c[2]) / 3.0 * (2.0 * PI / w) * (sin(t1) * sin(t1) - sin(t0) * sin(t0)) / 2.0;
        }
    }
    return e;
}

#define N_EST 400000L

/* One estimate per sample at a point facing +y: light sampling (mis = 0) or the power-heuristic
 * MIS of one light sample and one cosine sample (mis = 1), or cosine sampling alone (mis = -1). */
static struct moments irradiance(struct env *e, int mis, uint64_t seed)
{
    double *x = malloc(N_EST * sizeof *x);
    struct moments m;
    frame f = frame_from_normal(v3(0, 1, 0));
    pcg32 g;
    long i;
    pcg32_seed(&g, seed, 11);
    for (i = 0; i < N_EST; i++) {
        double v = 0.0;
        vec2 u;
        u.x = pcg32_float(&g);
        u.y = pcg32_float(&g);
        if (mis >= 0) {
            struct light_sample s;
            if (mc_light_sample(&e->ls, &e->l, v3s(0.0f), 0.0f, u, &s) && s.wi.y > 0.0f) {
                double pl = s.pdf, pb = s.wi.y / PI;
                double wt = mis ? pl * pl / (pl * pl + pb * pb) : 1.0;
                v += v3_avg(s.L) * s.wi.y / pl * wt;
            }
            u.x = pcg32_float(&g);
            u.y = pcg32_float(&g);
        }
        if (mis != 0) {
            vec3 wi = frame_to_world(&f, mc_warp_cosine_hemisphere(u));
            double pb = wi.y / PI, pl = dir_pdf(e, wi);
            double wt = mis > 0 ? pb * pb / (pl * pl + pb * pb) : 1.0;
            if (pb > 0.0)
                v += v3_avg(mc_environment_radiance(&e->l, wi)) * wi.y / pb * wt;
        }
        x[i] = v;
    }
    m = moments_of(x, N_EST);
    free(x);
    return m;
}

static void check_irradiance(const char *name, const float *rgb, int w, int h, uint64_t seed)
{
    struct env e;
    double exact = exact_irradiance(rgb, w, h);
    struct moments m;
    if (!env_make(&e, rgb, w, h, v3(0, 1, 0), 0.0f))
        return;
    m = irradiance(&e, 0, seed);
    T_NOTE("%s: irradiance %.5f ± %.5f, exact %.5f", name, m.mean, m.se, exact);
    T_CHECK(isfinite(m.mean), "%s: NaN", name);
    T_NEAR(m.mean, exact, 4.0 * m.se + 1e-5 * exact, "%s: light sampling vs closed form", name);
    check_agree(name, &e);
    mc_envmap_free(&e.map);
}

static void test_suns(void)
{
    int pole_x[] = {20}, pole_y[] = {0}, seam_x[] = {0, 63}, seam_y[] = {10, 12}, sun_x[] = {48},
        sun_y[] = {8};
    float *rgb;
    rgb = grey_map(64, 32, 0.05f, 1, pole_x, pole_y, 2000.0f);
    check_irradiance("sun on the pole", rgb, 64, 32, 21);
    free(rgb);
    rgb = grey_map(64, 32, 0.05f, 2, seam_x, seam_y, 2000.0f);
    check_irradiance("suns on the seam", rgb, 64, 32, 22);
    free(rgb);
    rgb = grey_map(64, 32, 0.0f, 1, sun_x, sun_y, 2000.0f);
    check_irradiance("sun on black (zeros)", rgb, 64, 32, 23);
    free(rgb);
    rgb = grey_map(64, 32, 0.05f, 1, sun_x, sun_y, 2000.0f);
    {
        struct env e;
        if (env_make(&e, rgb, 64, 32, v3(0, 1, 0), 0.0f)) {
            double exact = exact_irradiance(rgb, 64, 32);
            struct moments b = irradiance(&e, -1, 31), m = irradiance(&e, 1, 32);
            double low = (b.var - 3.0 * b.var_se) / (m.var + 3.0 * m.var_se);
            T_NOTE("sun: cosine sampling %.4f ± %.4f (variance %.4g ± %.2g), MIS %.4f ± %.4f "
                   "(variance %.4g ± %.2g), exact %.4f: variance ratio %.1f, at least %.1f",
                   b.mean, b.se, b.var, b.var_se, m.mean, m.se, m.var, m.var_se, exact,
                   b.var / m.var, low);
            T_NEAR(b.mean, exact, 4.0 * b.se, "sun: cosine sampling vs closed form");
            T_NEAR(m.mean, exact, 4.0 * m.se + 1e-5 * exact, "sun: MIS vs closed form");
            T_CHECK(low >= 10.0, "sun: MIS lowers the variance by %.1f (at least %.1f), not 10",
                    b.var / m.var, low);
            mc_envmap_free(&e.map);
        }
    }
    free(rgb);
}

/* A constant map is the constant sky: radiance, power, and the white furnace. */
static void test_constant(void)
{
    float *rgb = grey_map(16, 8, 1.0f, 0, NULL, NULL, 0.0f);
    struct env e;
    struct light sky;
    struct moments m;
    pcg32 g;
    int i, same = 1;
    if (!env_make(&e, rgb, 16, 8, v3(0, 1, 0), 0.0f)) {
        free(rgb);
        return;
    }
    memset(&sky, 0, sizeof sky);
    sky.kind = LIGHT_ENVIRONMENT;
    sky.intensity = v3s(1.0f);
    pcg32_seed(&g, 9, 9);
    for (i = 0; i < 10000; i++) {
        vec2 u;
        vec3 w;
        u.x = pcg32_float(&g);
        u.y = pcg32_float(&g);
        w = mc_warp_uniform_sphere(u);
        same &= same_rgb(mc_environment_radiance(&e.l, w), mc_environment_radiance(&sky, w));
    }
    T_CHECK(same, "a constant map's radiance is the constant sky's");
    T_NEAR(mc_light_power(&e.ls, &e.l), mc_light_power(&e.ls, &sky), 1e-6 * mc_light_power(&e.ls, &sky),
           "a constant map's power is the constant sky's");
    m = irradiance(&e, 0, 41);
    T_NEAR(m.mean / PI, 1.0, 4.0 * m.se / PI + 1e-5, "white furnace: albedo 1 reflects 1");
    m = irradiance(&e, 1, 42);
    T_NEAR(m.mean / PI, 1.0, 4.0 * m.se / PI + 1e-5, "white furnace under MIS");
    mc_envmap_free(&e.map);
    free(rgb);
}

/* The mean photon flux is πR²∫L dω, four times the power used for light selection (the power is
 * per side of the disk, as the constant sky's). */
static void test_emission_power(void)
{
    static const float small[3 * 2 * 3] = {1, 1, 1, 2, 2, 2, 3, 0.5f, 3, 4, 4, 4, 0.5f, 0.5f, 0.5f, 6, 6, 6};
    struct env e;
    double *x = malloc(N_EST * sizeof *x);
    struct moments m;
    pcg32 g;
    long i;
    if (!env_make(&e, small, 3, 2, v3(0, 1, 0), 0.0f)) {
        free(x);
        return;
    }
    pcg32_seed(&g, 4, 4);
    for (i = 0; i < N_EST; i++) {
        struct light_emission em;
        vec2 a, b;
        a.x = pcg32_float(&g);
        a.y = pcg32_float(&g);
        b.x = pcg32_float(&g);
        b.y = pcg32_float(&g);
        x[i] = mc_light_sample_emission(&e.ls, &e.l, 0.0f, a, b, &em) ? v3_avg(em.weight) : 0.0;
    }
    m = moments_of(x, N_EST);
    T_NEAR(m.mean, 4.0 * mc_light_power(&e.ls, &e.l), 4.0 * m.se, "mean photon flux");
    mc_envmap_free(&e.map);
    free(x);
}

static void test_bad_maps(void)
{
    float rgb[4 * 2 * 3];
    struct envmap m;
    mc_diag d;
    int i;
    for (i = 0; i < 24; i++)
        rgb[i] = 1.0f;
    rgb[3 * (1 * 4 + 2) + 1] = NAN;
    T_CHECK(mc_envmap_build(&m, rgb, 4, 2, "nan.pfm", &d) == MCRT_ERR_PARSE, "NaN refused");
    T_CHECK(strstr(d.msg, "nan.pfm: pixel (2, 1) has a NaN value") == d.msg, "message: %s", d.msg);
    rgb[3 * (1 * 4 + 2) + 1] = -0.5f;
    T_CHECK(mc_envmap_build(&m, rgb, 4, 2, "neg.pfm", &d) == MCRT_ERR_PARSE, "negative refused");
    T_CHECK(strstr(d.msg, "neg.pfm: pixel (2, 1) has a negative value") == d.msg, "message: %s", d.msg);
    for (i = 0; i < 24; i++)
        rgb[i] = 0.0f;
    T_CHECK(mc_envmap_build(&m, rgb, 4, 2, "black.pfm", &d) == MCRT_OK, "an all-black map is a map");
    mc_envmap_free(&m);
}

int main(void)
{
    test_convention();
    test_sampling();
    test_constant();
    test_suns();
    test_emission_power();
    test_bad_maps();
    return t_done();
}
