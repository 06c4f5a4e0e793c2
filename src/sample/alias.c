/* alias.c: alias tables for O(1) discrete sampling, built by Vose's O(n) algorithm.
 * References: Vose 1991, IEEE TSE 17(9); pbrt-v4 AliasTable (src/pbrt/util/sampling.cpp). */
#include "sample/alias.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"

/* Σ ldexp(w_i, -e) by Neumaier's compensated summation (Neumaier 1974, ZAMM 54): relative
 * error ~2^-53 whatever n. With plain summation, up to n·2^-53, the columns' total mass could
 * miss n by n²·2^-53, all of it landing on the outcomes left over at the end of Vose's loop. */
static double scaled_sum(const double *w, size_t n, int e)
{
    double s = 0.0, c = 0.0;
    size_t i;
    for (i = 0; i < n; i++) {
        double x = ldexp(w[i], -e), t = s + x;
        c += fabs(s) >= fabs(x) ? (s - t) + x : (x - t) + s; /* the rounding error of s + x */
        s = t;
    }
    return s + c;
}

mcrt_status mc_alias_build(struct mc_alias *a, const double *w, size_t n, mc_diag *d)
{
    double wmax = 0.0, sum, *p;
    uint32_t *work;
    size_t i, small = 0, large = n; /* the two stacks: work[0, small) and work[large, n) */
    int e;
    memset(a, 0, sizeof *a);
    if (n > INT_MAX)
        return mc_fail(d, MCRT_ERR_INVALID, "alias table: %zu outcomes (at most %d)", n, INT_MAX);
    for (i = 0; i < n; i++) {
        if (!(w[i] >= 0.0 && isfinite(w[i])))
            return mc_fail(d, MCRT_ERR_INVALID, "alias table: weight %zu is %g (must be finite and >= 0)", i,
                           w[i]);
        wmax = fmax(wmax, w[i]);
    }
    if (!(wmax > 0.0))
        return MCRT_OK; /* nothing to choose from */
    /* Scale every weight by the same power of two, which is exact, so that the largest lies in
     * [0.5, 1) and the sum cannot overflow (it is at most n). */
    frexp(wmax, &e);
    sum = scaled_sum(w, n, e);

    p = mc_malloc(n * sizeof *p);
    work = mc_malloc(n * sizeof *work);
    a->bins = mc_malloc(n * sizeof *a->bins);
    if (!p || !work || !a->bins) {
        free(p);
        free(work);
        mc_alias_free(a);
        return mc_fail(d, MCRT_ERR_NOMEM, "alias table: out of memory for %zu outcomes", n);
    }
    a->count = n;
    for (i = 0; i < n; i++) {
        double r = ldexp(w[i], -e) / sum;
        a->bins[i].pmf = (float)r;
        /* p_i = n·w_i/Σw: outcome i's mass in units of one column (1/n). A weight whose pmf
         * rounds to 0 is dropped (alias.h): its probability, below 1e-45, is lost in round-off. */
        p[i] = a->bins[i].pmf > 0.0f ? r * (double)n : 0.0;
        if (p[i] < 1.0)
            work[small++] = (uint32_t)i;
        else
            work[--large] = (uint32_t)i;
    }
    /* Fill the column of an outcome short of mass (p < 1) with part of one holding an excess
     * (p >= 1), which keeps the rest. Each step completes one column, so the stacks never meet.
     * The excess is updated as (p_l + p_s) − 1 (Vose; pbrt-v4): for p_l + p_s <= 2 subtracting
     * 1 is exact (Sterbenz), so a step rounds once, in the sum. */
    while (small > 0 && large < n) {
        uint32_t s = work[--small], l = work[large++];
        a->bins[s].q = p[s];
        a->bins[s].alias = l;
        p[l] = (p[l] + p[s]) - 1.0;
        if (p[l] < 1.0)
            work[small++] = l;
        else
            work[--large] = l;
    }
    /* Every outcome left holds one column's mass up to round-off, and keeps its column. A
     * dropped (zero) weight is never left: the other k − 1 outcomes would then hold a mass of
     * k, one of them more than 1, and so the large stack would not be empty. */
    for (i = 0; i < n; i++)
        if (i < small || i >= large) {
            a->bins[work[i]].q = 1.0;
            a->bins[work[i]].alias = work[i];
        }
    free(p);
    free(work);
    return MCRT_OK;
}

void mc_alias_free(struct mc_alias *a)
{
    free(a->bins);
    a->bins = NULL;
    a->count = 0;
}

int mc_alias_sample(const struct mc_alias *a, double u, float *pmf)
{
    double un = u * (double)a->count, coin;
    size_t c;
    int i;
    if (a->count == 0)
        return -1;
    /* u·n rounds at most once (not at all for a float u and n < 2^29); it reaches n only for u
     * within 2^-53 of 1, which the clamp sends to the last column. */
    c = (size_t)un;
    if (c >= a->count)
        c = a->count - 1;
    /* The coin: u·n − c is exact (Sterbenz: un and c are within a factor of 2, or c = 0). */
    coin = un - (double)c;
    i = coin < a->bins[c].q ? (int)c : (int)a->bins[c].alias;
    if (pmf)
        *pmf = a->bins[i].pmf;
    return i;
}

float mc_alias_pmf(const struct mc_alias *a, size_t i) { return i < a->count ? a->bins[i].pmf : 0.0f; }
