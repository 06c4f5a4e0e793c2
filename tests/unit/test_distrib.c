/* test_distrib.c: the tabulated distributions (src/sample/distrib.h), the alias table
 * (src/sample/alias.h) and the rejection-sampled disk (src/sample/warp.h): samples against
 * their pdfs (chi-square, tests/chi2.h), pdfs and pmfs against the tabulated function, the
 * probabilities the alias table realises, inversion, edges of [0, 1) and degenerate inputs. */
#include <limits.h>
#include <stdint.h>
#include <string.h>

#include "chi2.h"
#include "sample/alias.h"
#include "sample/distrib.h"
#include "sample/warp.h"
#include "t.h"

/* Chi-square tests this binary expects to accept (the Šidák correction divides 0.01 among them). */
#define CHI2_TESTS 11

/* One float rounding of a double quotient that itself carries a few double roundings: within
 * half an ulp plus ~1e-16, so within one ulp, 2^-23 relative (normal floats), plus 2^-149
 * absolute where the float is subnormal. */
#define FLOAT_REL 0x1p-23
#define FLOAT_ABS 0x1p-149

static int near_float(double got, double want)
{
    return fabs(got - want) <= FLOAT_REL * fabs(want) + FLOAT_ABS;
}

#define U_TOP 0x1.fffffffffffffp-1 /* the largest double below 1 */

static struct chi2_spec spec(const char *name, chi2_sample_fn sample, chi2_density_fn density, void *ctx,
                             double x0, double x1, int nx, int ny, uint64_t seed)
{
    struct chi2_spec s = chi2_rect_spec(name, sample, density, ctx, x0, x1, 0.0, 1.0, nx, ny);
    s.seed = seed;
    s.tests = CHI2_TESTS;
    return s;
}

static void report(const char *name, const struct chi2_result *r)
{
    T_NOTE("%s: chi2 %.1f, dof %d, p %.3f (alpha %.2g), density integral %.7f, strays %ld", name, r->chi2,
           r->dof, r->p, r->alpha, r->integral, r->stray);
    T_CHECK(r->pass, "%s: %s", name, r->why);
    T_CHECK(r->stray == 0, "%s: %ld samples where the density is 0", name, r->stray);
}

/* ---- test functions ---- */

/* Bumps with a gap of zeros in the middle and a zero at each end. */
#define BUMPS_N 50
static void bumps(float *f)
{
    int i;
    for (i = 0; i < BUMPS_N; i++)
        f[i] = (i == 0 || i == BUMPS_N - 1 || (i >= 20 && i < 30))
                   ? 0.0f
                   : (float)(1.0 + 0.8 * sin(2.0 * CHI2_PI * i / 10.0));
}
/* A steep exponential: the last bin is e^15 ≈ 3.3e6 times the first. */
#define STEEP_N 64
static void steep(float *f)
{
    int i;
    for (i = 0; i < STEEP_N; i++)
        f[i] = (float)exp(15.0 * i / (STEEP_N - 1));
}

/* ---- 1D continuous ---- */

struct c1d {
    const struct mc_distrib1d *d;
    long bad; /* draws whose x, pdf or offset disagree (x outside, pdf 0, pdf != pdf(x), wrong bin) */
};

static int sample_c1d(void *ctx, pcg32 *rng, double *x, double *y)
{
    struct c1d *c = (struct c1d *)ctx;
    const struct mc_distrib1d *d = c->d;
    float pdf;
    size_t o;
    float xs = mc_distrib1d_sample(d, pcg32_double(rng), &pdf, &o);
    double t = ((double)xs - d->min) / ((double)d->max - d->min) * (double)d->count;
    if (!(xs >= d->min && xs < d->max && pdf > 0.0f && pdf == mc_distrib1d_pdf(d, xs) && o == (size_t)t))
        c->bad++;
    *x = xs;
    *y = 0.5;
    return 1;
}
static double density_c1d(void *ctx, double x, double y)
{
    (void)y;
    return mc_distrib1d_pdf(((struct c1d *)ctx)->d, (float)x);
}

/* Every bin's pdf and pmf against f_i·n/(Σf·(max − min)) and f_i/Σf, and the integral. */
static void check_values_1d(const char *name, const struct mc_distrib1d *d, const float *f, size_t n,
                            double min, double max)
{
    double sum = 0.0, w = max - min;
    size_t i;
    int bad = 0;
    for (i = 0; i < n; i++)
        sum += f[i];
    for (i = 0; i < n; i++) {
        float x = (float)(min + w * (i + 0.5) / n);
        double pdf = sum > 0.0 ? f[i] * n / (sum * w) : 1.0 / w, pmf = sum > 0.0 ? f[i] / sum : 1.0 / n;
        if (!near_float(mc_distrib1d_pdf(d, x), pdf) || !near_float(mc_distrib1d_pmf(d, i), pmf)) {
            bad++;
            printf("  %s bin %zu: pdf %.9g (want %.9g), pmf %.9g (want %.9g)\n", name, i,
                   mc_distrib1d_pdf(d, x), pdf, mc_distrib1d_pmf(d, i), pmf);
        }
    }
    T_CHECK(bad == 0, "%s: %d bins with a wrong pdf or pmf", name, bad);
    /* Σf·w/n in double, summed in the same order: a few roundings, 1e-15 relative. */
    T_CHECK(fabs(mc_distrib1d_integral(d) - sum * w / n) <= 1e-15 * sum * w / n,
            "%s: integral %.17g, want %.17g", name, mc_distrib1d_integral(d), sum * w / n);
    T_CHECK(mc_distrib1d_pdf(d, (float)min - 1.0f) == 0.0f && mc_distrib1d_pdf(d, (float)max) == 0.0f,
            "%s: pdf outside [min, max) must be 0", name);
}

static void check_continuous(const char *name, const float *f, size_t n, float min, float max, uint64_t seed)
{
    struct mc_distrib1d d;
    struct c1d c;
    struct chi2_spec s;
    struct chi2_result r;
    mc_diag diag;
    if (mc_distrib1d_build(&d, f, n, min, max, &diag) != MCRT_OK) {
        T_CHECK(0, "%s: build: %s", name, diag.msg);
        return;
    }
    check_values_1d(name, &d, f, n, min, max);
    c.d = &d;
    c.bad = 0;
    /* Four histogram cells per bin: the density is constant on each cell, so the harness's
     * quadrature is exact, and a bin sampled unevenly inside shows. */
    s = spec(name, sample_c1d, density_c1d, &c, min, max, (int)(4 * n), 1, seed);
    r = chi2_run(&s);
    report(name, &r);
    T_CHECK(c.bad == 0, "%s: %ld samples outside the domain, with pdf 0, or disagreeing with pdf(x)", name,
            c.bad);
    mc_distrib1d_free(&d);
}

/* ---- discrete sampling (both the 1D distribution and the alias table) ---- */

typedef long (*draw_fn)(const void *table, double u, float *pmf);
static long draw_distrib(const void *t, double u, float *pmf)
{
    return (long)mc_distrib1d_sample_discrete((const struct mc_distrib1d *)t, u, pmf);
}
static long draw_alias(const void *t, double u, float *pmf)
{
    return mc_alias_sample((const struct mc_alias *)t, u, pmf);
}

struct discrete {
    draw_fn draw;
    const void *table;
    const double *pmf; /* the exact probabilities w_i/Σw */
    size_t n;
    long bad;          /* draws returning a pmf of 0 or one that is not outcome's pmf to a float ulp */
};

/* Outcome i is binned at x = i + 1/2 of [0, n): the density per unit x is its probability. */
static int sample_discrete(void *ctx, pcg32 *rng, double *x, double *y)
{
    struct discrete *c = (struct discrete *)ctx;
    float pmf = 0.0f;
    long i = c->draw(c->table, pcg32_double(rng), &pmf);
    if (i < 0 || (size_t)i >= c->n)
        return -1;
    if (!(pmf > 0.0f) || !near_float(pmf, c->pmf[i]))
        c->bad++;
    *x = (double)i + 0.5;
    *y = 0.5;
    return 1;
}
static double density_discrete(void *ctx, double x, double y)
{
    const struct discrete *c = (const struct discrete *)ctx;
    (void)y;
    return c->pmf[(size_t)x];
}

static struct chi2_result run_discrete(const char *name, draw_fn draw, const void *table, const double *pmf,
                                       size_t n, uint64_t seed, int quiet, long *bad)
{
    struct discrete c;
    struct chi2_spec s;
    struct chi2_result r;
    c.draw = draw;
    c.table = table;
    c.pmf = pmf;
    c.n = n;
    c.bad = 0;
    s = spec(name, sample_discrete, density_discrete, &c, 0.0, (double)n, (int)n, 1, seed);
    s.quiet = quiet;
    r = chi2_run(&s);
    *bad = c.bad;
    return r;
}

static void check_discrete(const char *name, draw_fn draw, const void *table, const double *pmf, size_t n,
                           uint64_t seed)
{
    long bad;
    struct chi2_result r = run_discrete(name, draw, table, pmf, n, seed, 0, &bad);
    report(name, &r);
    T_CHECK(bad == 0, "%s: %ld draws with pmf 0 or a pmf not the outcome's", name, bad);
}

/* w_i/Σw in double. */
static double *exact_pmf(const double *w, size_t n)
{
    double *p = (double *)malloc(n * sizeof *p), sum = 0.0;
    size_t i;
    if (!p)
        return NULL;
    for (i = 0; i < n; i++)
        sum += w[i];
    for (i = 0; i < n; i++)
        p[i] = w[i] / sum;
    return p;
}

static void test_distrib1d_sampling(void)
{
    float fb[BUMPS_N], fs[STEEP_N], fz[10];
    double wb[BUMPS_N], ws[STEEP_N], *pb, *ps;
    struct mc_distrib1d db, ds;
    size_t i;
    bumps(fb);
    steep(fs);
    memset(fz, 0, sizeof fz);
    check_continuous("1D bumps with zeros", fb, BUMPS_N, 0.0f, 1.0f, 1);
    check_continuous("1D steep exponential on [-2, 3)", fs, STEEP_N, -2.0f, 3.0f, 2);
    check_continuous("1D all zero (uniform)", fz, 10, 0.0f, 1.0f, 3);

    for (i = 0; i < BUMPS_N; i++)
        wb[i] = fb[i];
    for (i = 0; i < STEEP_N; i++)
        ws[i] = fs[i];
    pb = exact_pmf(wb, BUMPS_N);
    ps = exact_pmf(ws, STEEP_N);
    T_CHECK(pb && ps, "out of memory");
    if (pb && ps && mc_distrib1d_build(&db, fb, BUMPS_N, 0.0f, 1.0f, NULL) == MCRT_OK &&
        mc_distrib1d_build(&ds, fs, STEEP_N, 0.0f, 1.0f, NULL) == MCRT_OK) {
        check_discrete("1D discrete bumps", draw_distrib, &db, pb, BUMPS_N, 4);
        check_discrete("1D discrete steep", draw_distrib, &ds, ps, STEEP_N, 5);
        mc_distrib1d_free(&db);
        mc_distrib1d_free(&ds);
    }
    free(pb);
    free(ps);
}

/* ---- 1D edges, inversion and degenerate inputs ---- */

static void test_distrib1d_edges(void)
{
    static const double us[] = {0.0, 0x1p-53, 0.5, 0x1.fffffep-1 /* largest float below 1 */, U_TOP};
    float f[BUMPS_N];
    struct mc_distrib1d d;
    size_t k, o;
    int bad = 0;
    bumps(f);
    if (mc_distrib1d_build(&d, f, BUMPS_N, 0.0f, 1.0f, NULL) != MCRT_OK) {
        T_CHECK(0, "build");
        return;
    }
    /* Leading and trailing zero bins: the ends of [0, 1) must land in the first and last
     * non-zero bins, with x inside them. */
    for (k = 0; k < sizeof us / sizeof us[0]; k++) {
        float pdf, pmf, x = mc_distrib1d_sample(&d, us[k], &pdf, &o);
        size_t i = mc_distrib1d_sample_discrete(&d, us[k], &pmf);
        if (!(x >= 0.0f && x < 1.0f && pdf > 0.0f && pdf == mc_distrib1d_pdf(&d, x) && d.func[o] > 0.0f &&
              i == o && pmf > 0.0f)) {
            bad++;
            printf("  u = %a: x %a, pdf %g, offset %zu, discrete %zu (pmf %g)\n", us[k], x, pdf, o, i, pmf);
        }
    }
    T_CHECK(bad == 0, "%d edge values of u gave a bad sample", bad);
    {
        /* u = 0 gives the first float of bin 1, x >= 1/50 (the float nearest 1/50 lies below it) */
        float x0 = mc_distrib1d_sample(&d, 0.0, NULL, &o), x1 = mc_distrib1d_sample(&d, U_TOP, NULL, NULL);
        T_CHECK(o == 1 && x0 >= 1.0 / BUMPS_N && nextafterf(x0, 0.0f) < 1.0 / BUMPS_N,
                "u = 0: x %a in bin %zu, want the first float of bin 1", x0, o);
        T_CHECK(x1 < (BUMPS_N - 1.0f) / BUMPS_N && x1 >= (BUMPS_N - 1.0f) / BUMPS_N - 1e-6f,
                "u -> 1: x %.9g, want just below 49/50", x1);
    }

    /* A NaN u breaks the contract, but must not hang the sampler or index outside the table. */
    mc_distrib1d_sample(&d, NAN, NULL, &o);
    T_CHECK(o < BUMPS_N, "NaN u gave bin %zu", o);

    /* Inversion: u -> x -> u'. x is u's image rounded to float (and stepped back into its bin
     * when the rounding crossed an edge), so |x − x*| <= one float spacing at x, and the map's
     * slope is the realised density, the pdf to a float ulp (hence 1.001): |u' − u| <= 1.001
     * pdf·spacing, plus ~1e-16 per double operation (1e-13). */
    {
        pcg32 rng;
        int i, worse = 0;
        double worst = 0.0;
        pcg32_seed(&rng, 6, 0);
        for (i = 0; i < 100000; i++) {
            double u = pcg32_double(&rng), v = -1.0;
            float pdf, x = mc_distrib1d_sample(&d, u, &pdf, NULL);
            double spacing = nextafterf(x, INFINITY) - x, tol = 1.001 * pdf * spacing + 1e-13;
            if (!mc_distrib1d_invert(&d, x, &v) || !(fabs(v - u) <= tol))
                worse++;
            if (fabs(v - u) / tol > worst)
                worst = fabs(v - u) / tol;
        }
        T_NOTE("invert(sample(u)): worst |u' - u| is %.3f of its tolerance", worst);
        T_CHECK(worse == 0, "%d of 1e5 inversions off by more than the float rounding of x", worse);
    }
    {
        double a = -1.0, b = -2.0, c;
        /* bins 20..29, x in [0.4, 0.6), are zero: all of the gap maps to one u */
        T_CHECK(mc_distrib1d_invert(&d, 0.41f, &a) && mc_distrib1d_invert(&d, 0.59f, &b) && a == b,
                "zero bins invert to %.17g and %.17g", a, b);
        T_CHECK(mc_distrib1d_invert(&d, 0.0f, &c) && c == 0.0, "invert(0) = %g", c);
        T_CHECK(!mc_distrib1d_invert(&d, 1.0f, &c) && !mc_distrib1d_invert(&d, -0.1f, &c),
                "invert outside [min, max) must fail");
    }
    mc_distrib1d_free(&d);

    /* One bin: uniform on [2, 6), pdf 1/4, integral 3·4. */
    {
        float one = 3.0f, pdf;
        float x;
        T_CHECK(mc_distrib1d_build(&d, &one, 1, 2.0f, 6.0f, NULL) == MCRT_OK, "single bin build");
        x = mc_distrib1d_sample(&d, 0.25, &pdf, NULL);
        T_CHECK(x == 3.0f && pdf == 0.25f, "single bin: x %g pdf %g", x, pdf);
        T_CHECK(mc_distrib1d_integral(&d) == 12.0 && mc_distrib1d_pmf(&d, 0) == 1.0f,
                "single bin integral %g", mc_distrib1d_integral(&d));
        mc_distrib1d_free(&d);
    }
    /* A value whose probability underflows float (1.4e-45/1e38) is treated as zero: never
     * sampled, pdf and pmf 0. */
    {
        float f2[2] = {0x1p-149f, 1e38f}, pdf, pmf;
        T_CHECK(mc_distrib1d_build(&d, f2, 2, 0.0f, 1.0f, NULL) == MCRT_OK, "tiny value build");
        mc_distrib1d_sample(&d, 0.0, &pdf, &o);
        T_CHECK(o == 1 && pdf == 2.0f, "u = 0 chose bin %zu with pdf %g", o, pdf);
        T_CHECK(mc_distrib1d_sample_discrete(&d, 0.0, &pmf) == 1 && pmf == 1.0f, "discrete u = 0, pmf %g",
                pmf);
        T_CHECK(mc_distrib1d_pmf(&d, 0) == 0.0f && mc_distrib1d_pdf(&d, 0.25f) == 0.0f,
                "negligible bin: pmf %g, pdf %g", mc_distrib1d_pmf(&d, 0), mc_distrib1d_pdf(&d, 0.25f));
        mc_distrib1d_free(&d);
    }
    /* Invalid input: the call fails with a message, leaves d empty and reads nothing past n. */
    {
        float bad_vals[3][2] = {{1.0f, -1.0f}, {1.0f, NAN}, {INFINITY, 1.0f}};
        mc_diag diag;
        int v;
        for (v = 0; v < 3; v++) {
            diag.msg[0] = '\0';
            T_CHECK(mc_distrib1d_build(&d, bad_vals[v], 2, 0.0f, 1.0f, &diag) == MCRT_ERR_INVALID &&
                        d.func == NULL && d.count == 0 && diag.msg[0] != '\0',
                    "invalid value %g accepted", bad_vals[v][1]);
        }
        T_CHECK(mc_distrib1d_build(&d, f, 0, 0.0f, 1.0f, NULL) == MCRT_ERR_INVALID, "n = 0 accepted");
        T_CHECK(mc_distrib1d_build(&d, f, 4, 1.0f, 1.0f, NULL) == MCRT_ERR_INVALID, "min == max accepted");
        T_CHECK(mc_distrib1d_build(&d, f, 4, 0.0f, INFINITY, NULL) == MCRT_ERR_INVALID, "max = inf accepted");
        T_CHECK(mc_distrib1d_build(&d, f, SIZE_MAX / 4, 0.0f, 1.0f, &diag) == MCRT_ERR_NOMEM && d.cdf == NULL,
                "a size that overflows must fail with NOMEM before reading");
        mc_distrib1d_free(&d); /* no-op on an empty distribution */
    }
}

/* ---- 2D: an environment-map-like image ---- */

#define ENV_NX 64
#define ENV_NY 32

/* Rows are polar angle from the zenith (y), columns azimuth (x): a sky brightening upward, a
 * dim horizon band, black ground rows, a black building blocking part of the sky, and a sun
 * 500 times the sky with a width of about a pixel — not separable into g(x)·h(y). */
static void env_image(float *f)
{
    int i, j;
    for (j = 0; j < ENV_NY; j++)
        for (i = 0; i < ENV_NX; i++) {
            double x = (i + 0.5) / ENV_NX, y = (j + 0.5) / ENV_NY, v;
            double r2 = (x - 0.3) * (x - 0.3) + (y - 0.25) * (y - 0.25);
            if (y >= 0.875)
                v = 0.0;
            else if (y >= 0.75)
                v = 0.05;
            else if (x >= 0.6 && x < 0.8 && y >= 0.3 && y < 0.5)
                v = 0.0;
            else
                v = 0.2 + 0.8 * (1.0 - y) + 500.0 * exp(-r2 / (2.0 * 0.02 * 0.02));
            f[j * ENV_NX + i] = (float)v;
        }
}

struct c2d {
    const struct mc_distrib2d *d;
    long bad; /* draws outside [0,1)², with pdf 0, or with a pdf other than pdf(x, y) */
};
static int sample_c2d(void *ctx, pcg32 *rng, double *x, double *y)
{
    struct c2d *c = (struct c2d *)ctx;
    double ux = pcg32_double(rng), uy = pcg32_double(rng);
    float pdf;
    vec2 p = mc_distrib2d_sample(c->d, ux, uy, &pdf);
    if (!(p.x >= 0.0f && p.x < 1.0f && p.y >= 0.0f && p.y < 1.0f && pdf > 0.0f &&
          pdf == mc_distrib2d_pdf(c->d, p.x, p.y)))
        c->bad++;
    *x = p.x;
    *y = p.y;
    return 1;
}
static double density_c2d(void *ctx, double x, double y)
{
    return mc_distrib2d_pdf(((struct c2d *)ctx)->d, (float)x, (float)y);
}

static void test_distrib2d(void)
{
    static float f[ENV_NX * ENV_NY];
    struct mc_distrib2d d;
    struct c2d c;
    struct chi2_spec s;
    struct chi2_result r;
    double sum = 0.0, mean, pdf_sum = 0.0;
    int i, j, bad = 0;
    mc_diag diag;
    env_image(f);
    for (i = 0; i < ENV_NX * ENV_NY; i++)
        sum += f[i];
    mean = sum / (ENV_NX * ENV_NY);
    if (mc_distrib2d_build(&d, f, ENV_NX, ENV_NY, &diag) != MCRT_OK) {
        T_CHECK(0, "2D build: %s", diag.msg);
        return;
    }
    /* Each pixel's pdf against f/mean (a float ulp), and the pdf's integral over the square:
     * a weighted mean of per-pixel relative errors below 2^-24, so within 2^-23 of 1. */
    for (j = 0; j < ENV_NY; j++)
        for (i = 0; i < ENV_NX; i++) {
            float p = mc_distrib2d_pdf(&d, (i + 0.5f) / ENV_NX, (j + 0.5f) / ENV_NY);
            pdf_sum += p;
            if (!near_float(p, f[j * ENV_NX + i] / mean))
                bad++;
        }
    T_CHECK(bad == 0, "2D: %d pixels with pdf other than f/mean", bad);
    T_NOTE("2D pdf integral - 1 = %.3g; integral %.9g (mean of the image %.9g)",
           pdf_sum / (ENV_NX * ENV_NY) - 1.0, mc_distrib2d_integral(&d), mean);
    T_CHECK(fabs(pdf_sum / (ENV_NX * ENV_NY) - 1.0) <= FLOAT_REL, "2D pdf integrates to %.9g",
            pdf_sum / (ENV_NX * ENV_NY));
    T_CHECK(fabs(mc_distrib2d_integral(&d) - mean) <= 1e-15 * mean, "2D integral %.17g, mean %.17g",
            mc_distrib2d_integral(&d), mean);
    T_CHECK(mc_distrib2d_pdf(&d, 0.5f, 0.95f) == 0.0f && mc_distrib2d_pdf(&d, 0.7f, 0.4f) == 0.0f &&
                mc_distrib2d_pdf(&d, 1.0f, 0.5f) == 0.0f && mc_distrib2d_pdf(&d, 0.5f, -0.1f) == 0.0f,
            "2D pdf must be 0 on black pixels and outside the square");

    /* Two histogram cells per pixel along each axis (the density is constant on each). */
    c.d = &d;
    c.bad = 0;
    s = spec("2D environment map", sample_c2d, density_c2d, &c, 0.0, 1.0, 2 * ENV_NX, 2 * ENV_NY, 7);
    s.samples = 2000000;
    r = chi2_run(&s);
    report("2D environment map", &r);
    T_CHECK(c.bad == 0, "2D: %ld samples outside, with pdf 0 or disagreeing with pdf(x, y)", c.bad);

    {
        static const double us[] = {0.0, 0.5, U_TOP};
        int a, b, edge_bad = 0;
        for (a = 0; a < 3; a++)
            for (b = 0; b < 3; b++) {
                float pdf;
                vec2 p = mc_distrib2d_sample(&d, us[a], us[b], &pdf);
                if (!(p.x >= 0.0f && p.x < 1.0f && p.y >= 0.0f && p.y < 1.0f && pdf > 0.0f &&
                      pdf == mc_distrib2d_pdf(&d, p.x, p.y)))
                    edge_bad++;
            }
        T_CHECK(edge_bad == 0, "2D: %d bad samples at the edges of [0, 1)^2", edge_bad);
    }
    mc_distrib2d_free(&d);

    /* All zero: uniform, so the sample is u itself up to the float rounding of x (half an ulp)
     * and one step back into its bin: 2^-23 absolute on [0, 1). Likewise a single pixel. */
    {
        float zero[12] = {0}, five = 5.0f;
        pcg32 rng;
        int k, off = 0;
        T_CHECK(mc_distrib2d_build(&d, zero, 4, 3, NULL) == MCRT_OK, "all-zero 2D build");
        pcg32_seed(&rng, 8, 0);
        for (k = 0; k < 1000; k++) {
            double ux = pcg32_double(&rng), uy = pcg32_double(&rng);
            float pdf;
            vec2 p = mc_distrib2d_sample(&d, ux, uy, &pdf);
            if (!(fabs(p.x - ux) <= 0x1p-23 && fabs(p.y - uy) <= 0x1p-23 && pdf == 1.0f))
                off++;
        }
        T_CHECK(off == 0 && mc_distrib2d_integral(&d) == 0.0 && mc_distrib2d_pdf(&d, 0.3f, 0.9f) == 1.0f,
                "all-zero 2D: %d samples not uniform", off);
        mc_distrib2d_free(&d);
        T_CHECK(mc_distrib2d_build(&d, &five, 1, 1, NULL) == MCRT_OK, "1x1 build");
        {
            float pdf;
            vec2 p = mc_distrib2d_sample(&d, 0.25, 0.75, &pdf);
            T_CHECK(p.x == 0.25f && p.y == 0.75f && pdf == 1.0f && mc_distrib2d_integral(&d) == 5.0,
                    "1x1: (%g, %g) pdf %g", p.x, p.y, pdf);
        }
        mc_distrib2d_free(&d);
    }
    /* Row 1's share of the mass, 2^-151, rounds to 0 in float, so the marginal never chooses
     * it, although its value's own pdf, 2^-151·nx·ny = 2^-149, does not round to 0: the pdf
     * must still be 0 there, where no sample can land. */
    {
        float f2[4] = {0x1p100f, 0.0f, 0x1p-51f, 0.0f};
        int all = 1;
        size_t k;
        T_CHECK(mc_distrib2d_build(&d, f2, 2, 2, NULL) == MCRT_OK, "2x2 build");
        T_CHECK(mc_distrib2d_pdf(&d, 0.25f, 0.75f) == 0.0f && mc_distrib2d_pdf(&d, 0.25f, 0.25f) == 4.0f,
                "negligible row: pdf %g (want 0), heavy cell %g (want 4)", mc_distrib2d_pdf(&d, 0.25f, 0.75f),
                mc_distrib2d_pdf(&d, 0.25f, 0.25f));
        for (k = 0; k < 3; k++) {
            static const double us[] = {0.0, 0.5, U_TOP};
            float pdf;
            vec2 p = mc_distrib2d_sample(&d, 0.5, us[k], &pdf);
            all &= p.y < 0.5f && p.x < 0.5f && pdf == 4.0f;
        }
        T_CHECK(all, "negligible row: a sample left the heavy cell");
        mc_distrib2d_free(&d);
    }
    /* Row 0 = {2^-56, 2^-41} beside a row of 2^100s: within its row the first value is not
     * negligible (2^-15 of the row), but its pdf f/mean = 2^-155 rounds to 0, so it must be
     * treated as 0, and u = (0, 0), which lands in row 0, must take the second cell. */
    {
        float f2[4] = {0x1p-56f, 0x1p-41f, 0x1p100f, 0x1p100f}, pdf;
        vec2 p;
        T_CHECK(mc_distrib2d_build(&d, f2, 2, 2, NULL) == MCRT_OK, "2x2 build");
        p = mc_distrib2d_sample(&d, 0.0, 0.0, &pdf);
        T_CHECK(p.x >= 0.5f && p.y < 0.5f && pdf > 0.0f && pdf == mc_distrib2d_pdf(&d, p.x, p.y) &&
                    mc_distrib2d_pdf(&d, 0.25f, 0.25f) == 0.0f,
                "negligible cell: sample (%g, %g) with pdf %g", p.x, p.y, pdf);
        mc_distrib2d_free(&d);
    }
    {
        float neg[4] = {1.0f, 2.0f, -3.0f, 4.0f};
        T_CHECK(mc_distrib2d_build(&d, neg, 2, 2, NULL) == MCRT_ERR_INVALID && d.rows == NULL,
                "negative 2D value accepted");
        T_CHECK(mc_distrib2d_build(&d, neg, 0, 2, NULL) == MCRT_ERR_INVALID, "nx = 0 accepted");
        T_CHECK(mc_distrib2d_build(&d, neg, SIZE_MAX / 2, 4, NULL) == MCRT_ERR_NOMEM && d.func == NULL,
                "an overflowing 2D size must fail with NOMEM before reading");
    }
}

/* ---- alias table ---- */

/* The probability the table realises for each outcome, from its columns:
 * P_i = (q_i + Σ_{j: alias_j = i} (1 − q_j))/n, against w_i/Σw. Errors, in columns (1/n):
 * - each Vose step rounds at most twice at the magnitude of the heavy outcome's mass, at most
 *   P_max + 1 where P_max = n·max w/Σw; there are at most n steps: 2n(P_max + 1)·2^-53;
 * - the masses p_i = n·w_i/Σw (two roundings each, and a compensated Σw) miss a total of n by
 *   at most n·2^-51;
 * an outcome that took part as a heavy one, or was left over at the end (and so took every
 * error above), holds at least about a column, and a light one has only its two roundings.
 * The reference's plain sum adds n·2^-53 relative. */
static void check_alias_exact(const char *name, const struct mc_alias *a, const double *w, size_t n)
{
    double *got = (double *)calloc(n, sizeof *got), sum = 0.0, wmax = 0.0, tol, worst = 0.0;
    size_t i;
    int bad_p = 0, bad_pmf = 0;
    if (!got) {
        T_CHECK(0, "out of memory");
        return;
    }
    for (i = 0; i < n; i++) {
        sum += w[i];
        wmax = fmax(wmax, w[i]);
    }
    tol = 2.0 * n * (n * wmax / sum + 1.0) * 0x1p-53 + n * 0x1p-51 + n * 0x1p-53 + 0x1p-50;
    T_CHECK(a->count == n, "%s: count %zu, want %zu", name, a->count, n);
    for (i = 0; i < a->count; i++) {
        got[i] += a->bins[i].q;
        got[a->bins[i].alias] += 1.0 - a->bins[i].q;
    }
    for (i = 0; i < a->count; i++) {
        double want = w[i] / sum, p = got[i] / (double)n;
        /* a weight whose pmf underflows float is dropped: it may realise 0 instead of < 2^-149 */
        if (!(fabs(p - want) <= tol * want + (want < FLOAT_ABS ? want : 0.0)))
            bad_p++;
        if (want >= FLOAT_ABS && fabs(p - want) / want > worst)
            worst = fabs(p - want) / want;
        if (!near_float(mc_alias_pmf(a, i), want))
            bad_pmf++;
    }
    T_NOTE("%s: realised probabilities within %.2g relative of w/sum(w) (bound %.2g)", name, worst, tol);
    T_CHECK(bad_p == 0, "%s: %d outcomes realised with the wrong probability", name, bad_p);
    T_CHECK(bad_pmf == 0, "%s: %d pmfs not w/sum(w) to a float ulp", name, bad_pmf);
    T_CHECK(mc_alias_pmf(a, n) == 0.0f, "%s: pmf past the end must be 0", name);
    free(got);
}

/* The coin keeps u's bits below the column's: in every column c with 0.01 < q < 0.99, u at
 * (c + q(1 ∓ 1e-9))/n must keep c and take the alias respectively. Recovering the coin as
 * u·n − c costs ~n·2^-53 (1e-12 for n = 10^4), far inside the 1e-9·q margin; a coin computed
 * in float (2^-24 of u·n, 6e-4 at n = 10^4) could not tell the two apart. */
static void check_coin(const char *name, const struct mc_alias *a)
{
    size_t c;
    int wrong = 0, tried = 0;
    for (c = 0; c < a->count; c++) {
        double q = a->bins[c].q, n = (double)a->count;
        if (!(q > 0.01 && q < 0.99) || a->bins[c].alias == c)
            continue;
        tried++;
        if (mc_alias_sample(a, (c + q * (1.0 - 1e-9)) / n, NULL) != (int)c ||
            mc_alias_sample(a, (c + q * (1.0 + 1e-9)) / n, NULL) != (int)a->bins[c].alias)
            wrong++;
    }
    T_CHECK(wrong == 0, "%s: %d of %d columns resolve the coin worse than 1e-9", name, wrong, tried);
}

static void check_alias(const char *name, const double *w, size_t n, uint64_t seed)
{
    struct mc_alias a;
    double *p = exact_pmf(w, n);
    mc_diag diag;
    if (!p || mc_alias_build(&a, w, n, &diag) != MCRT_OK) {
        T_CHECK(0, "%s: build failed: %s", name, p ? diag.msg : "out of memory");
        free(p);
        return;
    }
    check_alias_exact(name, &a, w, n);
    check_coin(name, &a);
    check_discrete(name, draw_alias, &a, p, n, seed);
    mc_alias_free(&a);
    free(p);
}

static void test_alias_sampling(void)
{
    enum { NU = 100, NS = 1000, NR = 10000, ND = 1000 };
    static double w[NR];
    pcg32 rng;
    size_t i;
    pcg32_seed(&rng, 9, 0);

    for (i = 0; i < NU; i++)
        w[i] = 1.0;
    check_alias("alias uniform (100)", w, NU, 10);

    /* Zipf-like 1/(i+1)^2, every 7th weight zero (which chi2 would count as strays) */
    for (i = 0; i < NS; i++)
        w[i] = i % 7 == 3 ? 0.0 : 1.0 / ((i + 1.0) * (i + 1.0));
    check_alias("alias skewed 1/i^2 with zeros (1000)", w, NS, 11);

    for (i = 0; i < NR; i++)
        w[i] = pcg32_double(&rng);
    check_alias("alias 10^4 random weights", w, NR, 12);

    for (i = 0; i < ND; i++)
        w[i] = pow(10.0, 60.0 * pcg32_double(&rng) - 30.0);
    check_alias("alias weights 1e-30..1e30 (1000)", w, ND, 13);

    /* The discrete test has power: a table whose weight 7 is 20% heavier than the reference
     * says must be rejected on statistics (expected ~11976 draws against 10000, σ = 100). */
    {
        struct mc_alias a;
        double ref[NU], *p;
        long bad;
        struct chi2_result r;
        for (i = 0; i < NU; i++)
            ref[i] = w[i] = 1.0;
        w[7] = 1.2;
        p = exact_pmf(ref, NU);
        if (p && mc_alias_build(&a, w, NU, NULL) == MCRT_OK) {
            r = run_discrete("alias against wrong weights", draw_alias, &a, p, NU, 14, 1, &bad);
            T_NOTE("alias against wrong weights (expected to be rejected): chi2 %.1f, dof %d, p %.3g", r.chi2,
                   r.dof, r.p);
            T_CHECK(!r.pass && r.dof > 0 && r.stray == 0 && r.p < 1e-12, "power: pass %d, p %g, %s", r.pass,
                    r.p, r.why);
            mc_alias_free(&a);
        }
        free(p);
    }
}

static void test_alias_degenerate(void)
{
    struct mc_alias a;
    float pmf;
    mc_diag diag;
    static const double us[] = {0.0, 1.0 / 3.0, 0.5, 2.0 / 3.0, U_TOP};
    size_t k;

    T_CHECK(mc_alias_build(&a, NULL, 0, NULL) == MCRT_OK && a.count == 0 &&
                mc_alias_sample(&a, 0.5, &pmf) == -1 && mc_alias_pmf(&a, 0) == 0.0f,
            "n = 0: an empty table");
    mc_alias_free(&a);
    {
        double z[5] = {0};
        T_CHECK(mc_alias_build(&a, z, 5, NULL) == MCRT_OK && a.count == 0 && a.bins == NULL &&
                    mc_alias_sample(&a, 0.5, NULL) == -1,
                "all zero: an empty table");
        mc_alias_free(&a);
    }
    {
        double one = 2.5;
        int all = 1;
        T_CHECK(mc_alias_build(&a, &one, 1, NULL) == MCRT_OK && a.count == 1, "single weight build");
        for (k = 0; k < sizeof us / sizeof us[0]; k++)
            all &= mc_alias_sample(&a, us[k], &pmf) == 0 && pmf == 1.0f;
        T_CHECK(all, "single weight: always 0 with pmf 1");
        mc_alias_free(&a);
    }
    {
        double w[3] = {0.0, 3.0, 0.0};
        int all = 1;
        T_CHECK(mc_alias_build(&a, w, 3, NULL) == MCRT_OK, "{0, 3, 0} build");
        for (k = 0; k < sizeof us / sizeof us[0]; k++)
            all &= mc_alias_sample(&a, us[k], &pmf) == 1 && pmf == 1.0f;
        T_CHECK(all && mc_alias_pmf(&a, 0) == 0.0f && mc_alias_pmf(&a, 2) == 0.0f, "{0, 3, 0}: always 1");
        mc_alias_free(&a);
    }
    /* 1e-30 against 1e30: a probability of 1e-60 underflows float, so that outcome is dropped and
     * even u = 0 (coin 0) does not choose it. 1e-20 against 1e20 (1e-40, a subnormal float) is
     * kept, and u = 0 chooses it, with its tiny pmf. */
    {
        double w[2] = {1e-30, 1e30};
        int i;
        T_CHECK(mc_alias_build(&a, w, 2, NULL) == MCRT_OK, "{1e-30, 1e30} build");
        i = mc_alias_sample(&a, 0.0, &pmf);
        T_CHECK(i == 1 && pmf == 1.0f && mc_alias_pmf(&a, 0) == 0.0f, "{1e-30, 1e30}: u = 0 gave %d, pmf %g",
                i, pmf);
        mc_alias_free(&a);
        w[0] = 1e-20;
        w[1] = 1e20;
        T_CHECK(mc_alias_build(&a, w, 2, NULL) == MCRT_OK, "{1e-20, 1e20} build");
        i = mc_alias_sample(&a, 0.0, &pmf);
        T_CHECK(i == 0 && pmf > 0.0f && near_float(pmf, 1e-40), "{1e-20, 1e20}: u = 0 gave %d, pmf %g", i,
                pmf);
        mc_alias_free(&a);
    }
    /* Weights near DBL_MAX: their sum would overflow without the power-of-two rescaling. */
    {
        double w[3] = {1e308, 1e308, 1e308};
        T_CHECK(mc_alias_build(&a, w, 3, NULL) == MCRT_OK && near_float(mc_alias_pmf(&a, 1), 1.0 / 3.0),
                "{1e308 x 3}: pmf %g", mc_alias_pmf(&a, 1));
        mc_alias_free(&a);
    }
    {
        double bad[3][2] = {{1.0, -1e-300}, {1.0, NAN}, {INFINITY, 1.0}};
        int v;
        for (v = 0; v < 3; v++) {
            diag.msg[0] = '\0';
            T_CHECK(mc_alias_build(&a, bad[v], 2, &diag) == MCRT_ERR_INVALID && a.bins == NULL &&
                        a.count == 0 && diag.msg[0] != '\0',
                    "invalid weight %g accepted", bad[v][1]);
        }
        T_CHECK(mc_alias_build(&a, bad[0], (size_t)INT_MAX + 1, NULL) == MCRT_ERR_INVALID,
                "more outcomes than an int can index must be refused before reading");
    }
}

/* ---- rejection-sampled disk ---- */

struct disk_ctx {
    long attempts; /* pcg32 steps / 2 */
};

/* As test_warp: a uniform disk point has uniform (r², φ). The attempts are counted by stepping
 * a copy of the generator until it catches up (each attempt takes two values). */
static int sample_rejection_disk(void *ctx, pcg32 *rng, double *x, double *y)
{
    struct disk_ctx *c = (struct disk_ctx *)ctx;
    pcg32 before = *rng;
    long steps = 0;
    vec2 p = mc_warp_rejection_disk(rng);
    double phi = atan2((double)p.y, (double)p.x);
    while (before.state != rng->state) {
        pcg32_next(&before);
        steps++;
    }
    c->attempts += steps / 2;
    *x = (double)p.x * p.x + (double)p.y * p.y;
    *y = phi < 0.0 ? phi + 2.0 * CHI2_PI : phi;
    /* strictly inside, two values per attempt, and coordinates on the grid of cell centres
     * (2k + 1)/2^24 − 1, symmetric about 0 */
    return *x < 1.0 && steps % 2 == 0 && fabs(fmod(p.x * 0x1p24, 2.0)) == 1.0 &&
                   fabs(fmod(p.y * 0x1p24, 2.0)) == 1.0
               ? 1
               : -1;
}
static double density_polar(void *ctx, double x, double y)
{
    (void)ctx;
    (void)x;
    (void)y;
    return 1.0 / (2.0 * CHI2_PI);
}

static void test_rejection_disk(void)
{
    struct disk_ctx c;
    struct chi2_spec s;
    struct chi2_result r;
    double p = CHI2_PI / 4.0, mean, se;
    c.attempts = 0;
    s = spec("rejection disk", sample_rejection_disk, density_polar, &c, 0.0, 1.0, 50, 100, 15);
    s.y1 = 2.0 * CHI2_PI;
    s.samples = 1000000;
    r = chi2_run(&s);
    report("rejection disk in (r^2, phi)", &r);
    /* Attempts per sample are geometric with success p = π/4: mean 1/p = 4/π, variance
     * (1 − p)/p², so the mean of 1e6 has standard error 5.9e-4; allow 5 of them (a false
     * alarm has probability 6e-7). */
    mean = (double)c.attempts / (double)s.samples;
    se = sqrt((1.0 - p) / (p * p) / (double)s.samples);
    T_NOTE("rejection disk: %.5f attempts per sample (4/pi = %.5f, standard error %.2g)", mean, 1.0 / p, se);
    T_CHECK(fabs(mean - 1.0 / p) <= 5.0 * se, "rejection disk: %.5f attempts per sample", mean);
}

int main(void)
{
    test_distrib1d_sampling();
    test_distrib1d_edges();
    test_distrib2d();
    test_alias_sampling();
    test_alias_degenerate();
    test_rejection_disk();
    return t_done();
}
