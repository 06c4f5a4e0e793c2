/* chi2.h: Pearson chi-square goodness-of-fit test of a sampling routine against the density it
 * claims, after pbrt-v4 (src/pbrt/bsdfs_test.cpp) and Mitsuba 3 (python/chi2.py). Header-only.
 *
 * Samples are histogrammed over a rectangle of 2D coordinates; each cell's expected count is
 * N times the density integrated over the cell (Gauss–Legendre on sub-cells). Cells expecting
 * fewer than 5 samples are pooled; the p-value comes from the regularised incomplete gamma
 * function; the significance level 0.01 is Šidák-corrected for the number of chi-square tests
 * in the binary. Hard rejections, before any statistics: an invalid sample (non-finite, not
 * unit), more than 1e-5·N samples where the density is zero, a density integral above
 * 1 + 1e-3, or no degrees of freedom. chi2_run_directions adapts direction samplers with
 * solid-angle pdfs to the (θ, φ) rectangle, where the density is pdf·sinθ. */
#ifndef MCRT_CHI2_H
#define MCRT_CHI2_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "core/vec.h"

/* One draw of the sampler under test, as coordinates in the test's rectangle. Returns 1 for a
 * sample, 0 when the sampler produced none (such draws are counted, not binned), and -1 for an
 * invalid sample, which rejects at once. */
typedef int (*chi2_sample_fn)(void *ctx, pcg32 *rng, double *x, double *y);
/* The claimed density per unit area of the rectangle at (x, y). */
typedef double (*chi2_density_fn)(void *ctx, double x, double y);

struct chi2_spec {
    const char *name;
    chi2_sample_fn sample;
    chi2_density_fn density;
    void *ctx;
    double x0, x1, y0, y1; /* the rectangle */
    int nx, ny;            /* histogram cells along x and y */
    long samples;          /* 0: 1e6 */
    uint64_t seed;
    int tests;             /* chi-square tests in this binary, for the Šidák correction; 0: 1 */
    int quiet;             /* no tables on rejection, for tests that expect one */
};

struct chi2_result {
    double chi2, p;      /* the statistic and its p-value */
    double alpha;        /* the corrected significance level p was compared with */
    int dof;
    double integral;     /* the density integrated over the rectangle */
    long missing;        /* draws that produced no sample */
    long stray;          /* samples outside the rectangle or in cells of zero density */
    int pass;
    char why[160];       /* why the test rejected */
};

#define CHI2_PI 3.14159265358979323846

/* A test of sample against density on [x0, x1] × [y0, y1] with nx × ny cells; the other fields
 * are zero (their defaults), for the caller to set as needed. */
static inline struct chi2_spec chi2_rect_spec(const char *name, chi2_sample_fn sample,
                                              chi2_density_fn density, void *ctx, double x0,
                                              double x1, double y0, double y1, int nx, int ny)
{
    struct chi2_spec s;
    memset(&s, 0, sizeof s);
    s.name = name;
    s.sample = sample;
    s.density = density;
    s.ctx = ctx;
    s.x0 = x0;
    s.x1 = x1;
    s.y0 = y0;
    s.y1 = y1;
    s.nx = nx;
    s.ny = ny;
    return s;
}

/* The same on the unit square with n × n cells. */
static inline struct chi2_spec chi2_unit_spec(const char *name, chi2_sample_fn sample,
                                              chi2_density_fn density, void *ctx, int n)
{
    return chi2_rect_spec(name, sample, density, ctx, 0.0, 1.0, 0.0, 1.0, n, n);
}

/* The density of a uniform distribution on the unit square, for samplers tested on [0,1)². */
static inline double chi2_unit_density(void *ctx, double x, double y)
{
    (void)ctx;
    (void)x;
    (void)y;
    return 1.0;
}
#define CHI2_SIGNIFICANCE 0.01
#define CHI2_MIN_EXPECTED 5.0
/* pbrt-v4's allowance for round-off placing a sample just across a zero-density boundary. */
#define CHI2_STRAY_FRACTION 1e-5
/* Gauss–Legendre on 4×4 sub-cells integrates smooth densities to ~1e-8, so an integral above
 * 1 + 1e-3 is a pdf that claims more than all the probability (Mitsuba allows 1.1). */
#define CHI2_INTEGRAL_TOL 1e-3
#define CHI2_SUBCELLS 4

/* Regularised upper incomplete gamma function Q(a, x) = Γ(a, x)/Γ(a), a > 0 (Abramowitz and
 * Stegun 6.5.3). For x < a + 1 the power series of P = 1 − Q (A&S 6.5.29) converges quickly;
 * beyond, Legendre's continued fraction for Q (A&S 6.5.31) does, evaluated forward by the
 * modified Lentz method (Thompson and Barnett 1986). The chi-square survival function is
 * Q(dof/2, χ²/2). */
static inline double chi2_gamma_q(double a, double x)
{
    const double eps = 1e-15, tiny = 1e-300;
    double front, f, c, d, delta, an, bn;
    int i;
    if (!(x > 0.0))
        return 1.0;
    front = exp(a * log(x) - x - lgamma(a)); /* x^a e^-x / Γ(a) */
    if (x < a + 1.0) {
        /* P = x^a e^-x/Γ(a) · Σ_n x^n / (a(a+1)…(a+n)) */
        double term = 1.0 / a, sum = term;
        for (i = 1; i < 100000 && term > sum * eps; i++) {
            term *= x / (a + i);
            sum += term;
        }
        return 1.0 - front * sum;
    }
    /* Q = front / (b0 + a1/(b1 + a2/(b2 + …))), b_i = x + 2i + 1 − a, a_i = −i(i − a). */
    f = x + 1.0 - a;
    if (fabs(f) < tiny)
        f = tiny;
    c = f;
    d = 0.0;
    for (i = 1; i < 100000; i++) {
        an = -i * (i - a);
        bn = x + 2.0 * i + 1.0 - a;
        d = bn + an * d;
        c = bn + an / c;
        if (fabs(d) < tiny)
            d = tiny;
        if (fabs(c) < tiny)
            c = tiny;
        d = 1.0 / d;
        delta = c * d;
        f *= delta;
        if (fabs(delta - 1.0) < eps)
            break;
    }
    return front / f;
}

/* P(χ²_dof ≥ x): the p-value of a chi-square statistic. */
static inline double chi2_p_value(double x, int dof) { return chi2_gamma_q(0.5 * dof, 0.5 * x); }

/* Integral of the density over cell (i, j): 2-point Gauss–Legendre on each of S×S sub-cells.
 * Its nodes are interior, so a density that jumps on a cell edge (a hemisphere's rim) is
 * never evaluated on the jump. */
static inline double chi2_cell_integral(const struct chi2_spec *s, int i, int j)
{
    const double g = 0.5 / sqrt(3.0); /* nodes at the sub-cell centre ± h/(2√3), weights h/2 */
    double hx = (s->x1 - s->x0) / s->nx / CHI2_SUBCELLS, hy = (s->y1 - s->y0) / s->ny / CHI2_SUBCELLS;
    double sum = 0.0;
    int a, b, p, q;
    for (a = 0; a < CHI2_SUBCELLS; a++)
        for (b = 0; b < CHI2_SUBCELLS; b++) {
            double cx = s->x0 + (i * CHI2_SUBCELLS + a + 0.5) * hx;
            double cy = s->y0 + (j * CHI2_SUBCELLS + b + 0.5) * hy;
            for (p = -1; p <= 1; p += 2)
                for (q = -1; q <= 1; q += 2)
                    sum += s->density(s->ctx, cx + p * g * hx, cy + q * g * hy);
        }
    return sum * 0.25 * hx * hy;
}

struct chi2_cell { double obs, exp; int index; };

static inline int chi2_cell_cmp(const void *pa, const void *pb)
{
    const struct chi2_cell *a = (const struct chi2_cell *)pa, *b = (const struct chi2_cell *)pb;
    return a->exp < b->exp ? -1 : a->exp > b->exp ? 1 : a->index - b->index;
}

/* Cell index of coordinate v in [v0, v1] split n ways, or -1 when v is outside by more than
 * round-off (1e-6 of the extent; Mitsuba allows 1e-4). */
static inline int chi2_bin(double v, double v0, double v1, int n)
{
    double t = (v - v0) / (v1 - v0);
    int k;
    if (!(t >= -1e-6 && t <= 1.0 + 1e-6))
        return -1;
    k = (int)(t * n);
    return k < 0 ? 0 : k >= n ? n - 1 : k;
}

/* (o − e)²/e of one cell; a zero-expectation cell holding samples ranks above every other. */
static inline double chi2_term(double o, double e)
{
    return e > 0.0 ? (o - e) * (o - e) / e : o > 0.0 ? HUGE_VAL : 0.0;
}

/* On rejection: observed and expected counts summed over blocks of cells (at most 8 × 10
 * blocks; rows along x), then the five cells contributing most to χ². */
static inline void chi2_print_tables(const struct chi2_spec *s, const double *obs, const double *expect)
{
    int bx = (s->nx + 7) / 8, by = (s->ny + 9) / 10, n = s->nx * s->ny, i, j, k, r;
    int shown[5];
    printf("  chi2 %s: observed/expected in blocks of %dx%d cells (rows: x, columns: y from %g to %g)\n",
           s->name, bx, by, s->y0, s->y1);
    for (i = 0; i < s->nx; i += bx) {
        printf("  chi2  x=%-9.4g", s->x0 + (s->x1 - s->x0) * i / s->nx);
        for (j = 0; j < s->ny; j += by) {
            double o = 0.0, e = 0.0;
            int a, b;
            for (a = i; a < i + bx && a < s->nx; a++)
                for (b = j; b < j + by && b < s->ny; b++) {
                    o += obs[a * s->ny + b];
                    e += expect[a * s->ny + b];
                }
            printf(" %7.0f/%-7.0f", o, e);
        }
        printf("\n");
    }
    for (r = 0; r < 5 && r < n; r++) {
        int best = -1;
        for (k = 0; k < n; k++) {
            int taken = 0, m;
            for (m = 0; m < r; m++)
                taken |= shown[m] == k;
            if (!taken && (best < 0 || chi2_term(obs[k], expect[k]) > chi2_term(obs[best], expect[best])))
                best = k;
        }
        shown[r] = best;
        printf("  chi2  cell x=[%.5g, %.5g) y=[%.5g, %.5g): observed %.0f, expected %.2f\n",
               s->x0 + (s->x1 - s->x0) * (best / s->ny) / s->nx,
               s->x0 + (s->x1 - s->x0) * (best / s->ny + 1) / s->nx,
               s->y0 + (s->y1 - s->y0) * (best % s->ny) / s->ny,
               s->y0 + (s->y1 - s->y0) * (best % s->ny + 1) / s->ny, obs[best], expect[best]);
    }
}

/* Run the test. Never prints unless it rejects (and then only when !quiet). */
static inline struct chi2_result chi2_run(const struct chi2_spec *s_in)
{
    struct chi2_spec s = *s_in;
    struct chi2_result r;
    int n, k, pooled_cells = 0;
    long t;
    double *obs, *expect, pool_obs = 0.0, pool_exp = 0.0, zero_obs = 0.0;
    struct chi2_cell *cells;
    pcg32 rng;

    memset(&r, 0, sizeof r);
    if (s.samples <= 0)
        s.samples = 1000000;
    if (s.tests <= 0)
        s.tests = 1;
    n = s.nx * s.ny;
    /* Šidák: the chance that any of `tests` true hypotheses is rejected stays at 0.01. */
    r.alpha = 1.0 - pow(1.0 - CHI2_SIGNIFICANCE, 1.0 / s.tests);
    obs = (double *)calloc((size_t)n, sizeof *obs);
    expect = (double *)calloc((size_t)n, sizeof *expect);
    cells = (struct chi2_cell *)calloc((size_t)n, sizeof *cells);
    if (!obs || !expect || !cells) {
        snprintf(r.why, sizeof r.why, "out of memory");
        goto done;
    }

    pcg32_seed(&rng, s.seed, 0x63686932u /* "chi2" */);
    for (t = 0; t < s.samples; t++) {
        double x = 0.0, y = 0.0;
        int ok = s.sample(s.ctx, &rng, &x, &y), i, j;
        if (ok < 0 || (ok && !(isfinite(x) && isfinite(y)))) {
            snprintf(r.why, sizeof r.why, "invalid sample (draw %ld) at (%g, %g)", t, x, y);
            goto done;
        }
        if (!ok) {
            r.missing++;
            continue;
        }
        i = chi2_bin(x, s.x0, s.x1, s.nx);
        j = chi2_bin(y, s.y0, s.y1, s.ny);
        if (i < 0 || j < 0)
            r.stray++;
        else
            obs[i * s.ny + j] += 1.0;
    }

    for (k = 0; k < n; k++) {
        double p = chi2_cell_integral(&s, k / s.ny, k % s.ny);
        if (p < 0.0) {
            snprintf(r.why, sizeof r.why, "negative density integral %g in cell %d", p, k);
            goto done;
        }
        r.integral += p;
        expect[k] = p * (double)s.samples;
        if (expect[k] == 0.0)
            zero_obs += obs[k];
    }
    r.stray += (long)zero_obs;
    if (r.integral > 1.0 + CHI2_INTEGRAL_TOL) {
        snprintf(r.why, sizeof r.why, "density integrates to %.6f > 1", r.integral);
        goto done;
    }
    if ((double)r.stray > CHI2_STRAY_FRACTION * (double)s.samples) {
        snprintf(r.why, sizeof r.why, "%ld samples outside the domain or where the density is 0", r.stray);
        goto done;
    }

    /* Pool, in order of increasing expectation, the cells expecting < 5 until the pool itself
     * expects >= 5 (pbrt-v4 bsdfs_test.cpp, Chi2Test). */
    for (k = 0; k < n; k++) {
        cells[k].obs = obs[k];
        cells[k].exp = expect[k];
        cells[k].index = k;
    }
    qsort(cells, (size_t)n, sizeof *cells, chi2_cell_cmp);
    for (k = 0; k < n; k++) {
        const struct chi2_cell *c = &cells[k];
        if (c->exp == 0.0)
            continue; /* counted as strays above */
        if (c->exp < CHI2_MIN_EXPECTED || (pool_exp > 0.0 && pool_exp < CHI2_MIN_EXPECTED)) {
            pool_obs += c->obs;
            pool_exp += c->exp;
            pooled_cells++;
        } else {
            r.chi2 += (c->obs - c->exp) * (c->obs - c->exp) / c->exp;
            r.dof++;
        }
    }
    if (pooled_cells > 0) {
        r.chi2 += (pool_obs - pool_exp) * (pool_obs - pool_exp) / pool_exp;
        r.dof++;
    }
    r.dof -= 1; /* the counts' total is fixed; the density has no fitted parameters */
    if (r.dof <= 0) {
        snprintf(r.why, sizeof r.why, "no degrees of freedom");
        goto done;
    }
    r.p = chi2_p_value(r.chi2, r.dof);
    if (!(r.p > r.alpha)) {
        snprintf(r.why, sizeof r.why, "p-value %.3g <= %.3g (chi2 %.1f, dof %d)", r.p, r.alpha, r.chi2,
                 r.dof);
        goto done;
    }
    r.pass = 1;
done:
    if (!r.pass && !s.quiet) {
        printf("  chi2 %s rejected: %s\n", s.name, r.why);
        if (obs && expect && cells)
            chi2_print_tables(&s, obs, expect);
    }
    free(obs);
    free(expect);
    free(cells);
    return r;
}

/* Direction samplers: w must be unit. The pdf is per unit solid angle. */
typedef int (*chi2_dir_sample_fn)(void *ctx, pcg32 *rng, vec3 *w);
typedef double (*chi2_dir_pdf_fn)(void *ctx, vec3 w);

struct chi2_dir_spec {
    const char *name;
    chi2_dir_sample_fn sample;
    chi2_dir_pdf_fn pdf;
    void *ctx;
    double theta_max;   /* the domain is θ ∈ [0, theta_max] around +z; 0: π (the sphere) */
    int ntheta, nphi;   /* 0: pbrt's 80 × 160 */
    long samples;       /* 0: 1e6 */
    uint64_t seed;
    int tests;
    int quiet;
};

/* A direction test of sample against pdf over θ ≤ theta_max (0: the sphere) on pbrt's grid; the
 * other fields are zero (their defaults), for the caller to set as needed. */
static inline struct chi2_dir_spec chi2_dir_spec_of(const char *name, chi2_dir_sample_fn sample,
                                                    chi2_dir_pdf_fn pdf, void *ctx, double theta_max)
{
    struct chi2_dir_spec s;
    memset(&s, 0, sizeof s);
    s.name = name;
    s.sample = sample;
    s.pdf = pdf;
    s.ctx = ctx;
    s.theta_max = theta_max;
    return s;
}

static inline int chi2_dir_sample(void *ctx, pcg32 *rng, double *x, double *y)
{
    const struct chi2_dir_spec *d = (const struct chi2_dir_spec *)ctx;
    vec3 w;
    double len2, phi;
    int ok = d->sample(d->ctx, rng, &w);
    if (ok <= 0)
        return ok;
    len2 = (double)w.x * w.x + (double)w.y * w.y + (double)w.z * w.z;
    /* θ from atan2 rather than acos(z): float z near 1 carries no information about small θ. */
    *x = atan2(sqrt((double)w.x * w.x + (double)w.y * w.y), (double)w.z);
    phi = atan2((double)w.y, (double)w.x);
    *y = phi < 0.0 ? phi + 2.0 * CHI2_PI : phi;
    /* Float unit vectors are unit to a few ulps; 1e-5 leaves margin and still catches bugs. */
    return v3_is_finite(w) && fabs(len2 - 1.0) <= 1e-5 ? 1 : -1;
}

static inline double chi2_dir_density(void *ctx, double theta, double phi)
{
    const struct chi2_dir_spec *d = (const struct chi2_dir_spec *)ctx;
    double st = sin(theta);
    vec3 w = v3((float)(st * cos(phi)), (float)(st * sin(phi)), (float)cos(theta));
    return d->pdf(d->ctx, w) * st; /* dω = sinθ dθ dφ */
}

static inline struct chi2_result chi2_run_directions(const struct chi2_dir_spec *d)
{
    struct chi2_spec s;
    double tmax = d->theta_max > 0.0 ? d->theta_max : CHI2_PI;
    memset(&s, 0, sizeof s);
    s.name = d->name;
    s.sample = chi2_dir_sample;
    s.density = chi2_dir_density;
    s.ctx = (void *)d;
    s.x0 = 0.0;
    s.x1 = tmax;
    s.y0 = 0.0;
    s.y1 = 2.0 * CHI2_PI;
    s.nx = d->ntheta > 0 ? d->ntheta : 80;
    s.ny = d->nphi > 0 ? d->nphi : 160;
    s.samples = d->samples;
    s.seed = d->seed;
    s.tests = d->tests;
    s.quiet = d->quiet;
    return chi2_run(&s);
}

#endif
