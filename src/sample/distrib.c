/* distrib.c: piecewise-constant 1D and 2D distributions sampled by inverting a double CDF.
 * Reference: pbrt-v4 (Pharr, Jakob and Humphreys), §A.4.1 PiecewiseConstant1D and §A.4.2
 * PiecewiseConstant2D. Used only by its tests until environment maps arrive (see distrib.h). */
#include "sample/distrib.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"

static double width(const struct mc_distrib1d *d) { return (double)d->max - (double)d->min; }

/* Density and probability of a bin holding value f. When the function is all zero (sum 0)
 * every bin is sampled uniformly, whatever its value. */
static float bin_pdf(const struct mc_distrib1d *d, float f)
{
    if (!(d->sum > 0.0))
        return (float)(1.0 / width(d));
    return (float)((double)f * (double)d->count / (d->sum * width(d)));
}
static float bin_pmf(const struct mc_distrib1d *d, float f)
{
    return d->sum > 0.0 ? (float)(f / d->sum) : (float)(1.0 / (double)d->count);
}

/* The bin containing x, or count when x is outside [min, max). Non-decreasing in x. */
static size_t bin_of(const struct mc_distrib1d *d, float x)
{
    double t;
    if (!(x >= d->min && x < d->max))
        return d->count;
    t = ((double)x - d->min) / width(d) * (double)d->count;
    return t < (double)d->count ? (size_t)t : d->count - 1; /* t may round up to count */
}

/* The largest o < n with cdf[o] <= u: then cdf[o] <= u < cdf[o + 1] (cdf[n] = 1 > u), so the
 * bin is never a zero bin, whose CDF step is empty. */
static size_t find_bin(const double *cdf, size_t n, double u)
{
    size_t lo = 0, hi = n;
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (cdf[mid] <= u)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

static mcrt_status check_values(const float *f, size_t n, mc_diag *diag)
{
    size_t i;
    for (i = 0; i < n; i++)
        if (!(f[i] >= 0.0f && isfinite(f[i])))
            return mc_fail(diag, MCRT_ERR_INVALID, "distribution: value %zu is %g (must be finite and >= 0)",
                           i, f[i]);
    return MCRT_OK;
}

/* Set d up over caller-provided storage func (n floats) and cdf (n + 1 doubles) from checked
 * values f (f may be func itself). */
static void fill(struct mc_distrib1d *d, float *func, double *cdf, const float *f, size_t n, float min,
                 float max)
{
    double sum = 0.0;
    size_t i;
    for (i = 0; i < n; i++)
        sum += f[i];
    d->func = func;
    d->cdf = cdf;
    d->sum = sum;
    d->min = min;
    d->max = max;
    d->count = n;
    /* Copy, zeroing the values whose float pdf or pmf would round to 0 (distrib.h), while
     * accumulating the CDF. Dropping terms can only lower every rounded partial sum, so the
     * kept values' pdfs stay > 0 under the final sum. */
    sum = 0.0;
    cdf[0] = 0.0;
    for (i = 0; i < n; i++) {
        float v = f[i];
        func[i] = v > 0.0f && (bin_pdf(d, v) == 0.0f || bin_pmf(d, v) == 0.0f) ? 0.0f : v;
        sum += func[i];
        cdf[i + 1] = sum;
    }
    d->sum = sum;
    /* Dividing by the final partial sum makes cdf[n], and the CDF past the last non-zero bin,
     * exactly 1. */
    for (i = 1; i <= n; i++)
        cdf[i] = sum > 0.0 ? cdf[i] / sum : (double)i / (double)n;
}

mcrt_status mc_distrib1d_build(struct mc_distrib1d *d, const float *f, size_t n, float min, float max,
                               mc_diag *diag)
{
    float *func;
    double *cdf;
    mcrt_status st;
    memset(d, 0, sizeof *d);
    if (n == 0 || !(min < max) || !isfinite(min) || !isfinite(max))
        return mc_fail(diag, MCRT_ERR_INVALID, "distribution: %zu bins over [%g, %g)", n, min, max);
    if (n >= SIZE_MAX / sizeof *cdf)
        return mc_fail(diag, MCRT_ERR_NOMEM, "distribution: %zu bins do not fit in memory", n);
    st = check_values(f, n, diag);
    if (st != MCRT_OK)
        return st;
    func = mc_malloc(n * sizeof *func);
    cdf = mc_malloc((n + 1) * sizeof *cdf);
    if (!func || !cdf) {
        free(func);
        free(cdf);
        return mc_fail(diag, MCRT_ERR_NOMEM, "distribution: out of memory for %zu bins", n);
    }
    fill(d, func, cdf, f, n, min, max);
    return MCRT_OK;
}

void mc_distrib1d_free(struct mc_distrib1d *d)
{
    free(d->func);
    free(d->cdf);
    memset(d, 0, sizeof *d);
}

float mc_distrib1d_sample(const struct mc_distrib1d *d, double u, float *pdf, size_t *offset)
{
    size_t o = find_bin(d->cdf, d->count, u);
    /* The CDF is linear within the bin, so u's position in the bin's CDF step is x's position
     * in the bin. */
    double du = (u - d->cdf[o]) / (d->cdf[o + 1] - d->cdf[o]);
    float x = (float)(d->min + width(d) * (((double)o + du) / (double)d->count));
    /* Rounding to float may carry x across an edge of the bin (or onto max): step it back so
     * that x lies in bin o, whose pdf is returned. Only bins narrower than the float spacing
     * (over 2^23 bins on [0, 1)) can fail to contain x. The bounds stop the steps at the ends
     * of the domain, and at once for a NaN x (from a NaN u). */
    while (x > d->min && bin_of(d, x) > o)
        x = nextafterf(x, -INFINITY);
    while (x < d->max && bin_of(d, x) < o)
        x = nextafterf(x, INFINITY);
    if (pdf)
        *pdf = bin_pdf(d, d->func[o]);
    if (offset)
        *offset = o;
    return x;
}

float mc_distrib1d_pdf(const struct mc_distrib1d *d, float x)
{
    size_t o = bin_of(d, x);
    return o < d->count ? bin_pdf(d, d->func[o]) : 0.0f;
}

double mc_distrib1d_integral(const struct mc_distrib1d *d) { return d->sum * width(d) / (double)d->count; }

int mc_distrib1d_invert(const struct mc_distrib1d *d, float x, double *u)
{
    size_t o = bin_of(d, x);
    double t;
    if (o == d->count)
        return 0;
    /* x's position in the bin (clamped: bin_of clamps x rounding onto the top edge) */
    t = fmin(((double)x - d->min) / width(d) * (double)d->count - (double)o, 1.0);
    *u = d->cdf[o] + t * (d->cdf[o + 1] - d->cdf[o]);
    return 1;
}

size_t mc_distrib1d_sample_discrete(const struct mc_distrib1d *d, double u, float *pmf)
{
    size_t o = find_bin(d->cdf, d->count, u);
    if (pmf)
        *pmf = bin_pmf(d, d->func[o]);
    return o;
}

float mc_distrib1d_pmf(const struct mc_distrib1d *d, size_t i)
{
    return i < d->count ? bin_pmf(d, d->func[i]) : 0.0f;
}

mcrt_status mc_distrib2d_build(struct mc_distrib2d *d, const float *f, size_t nx, size_t ny,
                               mc_diag *diag)
{
    size_t n, i, j;
    double total = 0.0, max_row = 0.0;
    float *rel = NULL;
    mcrt_status st;
    memset(d, 0, sizeof *d);
    if (nx == 0 || ny == 0)
        return mc_fail(diag, MCRT_ERR_INVALID, "distribution: %zu x %zu table", nx, ny);
    /* ny·(nx + 1) doubles (the largest array) and ny row structures must fit in size_t. */
    if (nx >= SIZE_MAX / sizeof *d->cdf / ny || ny > SIZE_MAX / sizeof *d->rows)
        return mc_fail(diag, MCRT_ERR_NOMEM, "distribution: a %zu x %zu table does not fit in memory", nx,
                       ny);
    n = nx * ny;
    st = check_values(f, n, diag);
    if (st != MCRT_OK)
        return st;
    d->func = mc_malloc(n * sizeof *d->func);
    d->cdf = mc_malloc(ny * (nx + 1) * sizeof *d->cdf);
    d->rows = mc_malloc(ny * sizeof *d->rows);
    rel = mc_malloc(ny * sizeof *rel);
    if (!d->func || !d->cdf || !d->rows || !rel) {
        free(rel);
        mc_distrib2d_free(d);
        return mc_fail(diag, MCRT_ERR_NOMEM, "distribution: out of memory for a %zu x %zu table", nx, ny);
    }
    d->nx = nx;
    d->ny = ny;
    for (i = 0; i < n; i++)
        total += f[i];
    d->mean = total / (double)n;
    /* Zero the values whose pdf f/mean would round to 0 in float (distrib.h); then each row's
     * conditional is built in place over its slice of func and cdf. */
    for (i = 0; i < n; i++)
        d->func[i] = d->mean > 0.0 && (float)(f[i] / d->mean) == 0.0f ? 0.0f : f[i];
    for (j = 0; j < ny; j++) {
        float *row = d->func + j * nx;
        fill(&d->rows[j], row, d->cdf + j * (nx + 1), row, nx, 0.0f, 1.0f);
        max_row = fmax(max_row, d->rows[j].sum);
    }
    /* The marginal needs only the rows' relative masses: each row's sum over the largest, in
     * [0, 1], so that no row's float value overflows and the largest never underflows. */
    for (j = 0; j < ny; j++)
        rel[j] = max_row > 0.0 ? (float)(d->rows[j].sum / max_row) : 0.0f;
    st = mc_distrib1d_build(&d->marginal, rel, ny, 0.0f, 1.0f, diag);
    free(rel);
    if (st != MCRT_OK)
        mc_distrib2d_free(d);
    return st;
}

void mc_distrib2d_free(struct mc_distrib2d *d)
{
    mc_distrib1d_free(&d->marginal);
    free(d->rows);
    free(d->func);
    free(d->cdf);
    memset(d, 0, sizeof *d);
}

/* Density of cell (i, j). A row the marginal never chooses (its mass negligible next to the
 * largest row's) has density 0 throughout, so that pdf > 0 exactly where samples land. */
static float cell_pdf(const struct mc_distrib2d *d, size_t i, size_t j)
{
    if (!(d->mean > 0.0))
        return 1.0f; /* the all-zero function is sampled uniformly */
    if (d->marginal.func[j] == 0.0f)
        return 0.0f;
    return (float)(d->func[j * d->nx + i] / d->mean);
}

vec2 mc_distrib2d_sample(const struct mc_distrib2d *d, double ux, double uy, float *pdf)
{
    size_t i, j;
    float y = mc_distrib1d_sample(&d->marginal, uy, NULL, &j);
    float x = mc_distrib1d_sample(&d->rows[j], ux, NULL, &i);
    if (pdf)
        *pdf = cell_pdf(d, i, j);
    return v2(x, y);
}

float mc_distrib2d_pdf(const struct mc_distrib2d *d, float x, float y)
{
    size_t j = bin_of(&d->marginal, y), i;
    if (j == d->ny)
        return 0.0f;
    i = bin_of(&d->rows[j], x);
    return i < d->nx ? cell_pdf(d, i, j) : 0.0f;
}

double mc_distrib2d_integral(const struct mc_distrib2d *d) { return d->mean; }
