/* alias.h: Walker's alias method — O(1) sampling of a discrete distribution over n outcomes
 * (light selection by power), built in O(n) by Vose's numerically stable algorithm.
 * Walker 1977, "An Efficient Method for Generating Discrete Random Variables with General
 * Distributions", ACM TOMS 3(3); Vose 1991, "A Linear Algorithm for Generating Random Numbers
 * with a Given Distribution", IEEE TSE 17(9). */
#ifndef MCRT_ALIAS_H
#define MCRT_ALIAS_H

#include <stddef.h>
#include <stdint.h>

#include "core/diag.h"

/* Column i of the table: a sample landing in it keeps i with probability q, else takes alias.
 * q is double so that the table realises every pmf far below float precision: in float, the
 * roundings of 1 − q over the many columns that one heavy outcome absorbs would add up. */
struct mc_alias_bin {
    double q;
    uint32_t alias;
    float pmf;       /* probability of outcome i: w_i/Σw rounded to float */
};

struct mc_alias {
    struct mc_alias_bin *bins; /* count bins, owned: free with mc_alias_free */
    size_t count;              /* 0 for an empty table (no weights, or all zero) */
};

/* Build from weights w[0..n), each finite and >= 0 (MCRT_ERR_INVALID otherwise; also for
 * n > INT_MAX). Outcome i gets probability w_i/Σw for any finite weights (they are rescaled by
 * a power of two before summing, so even 1e300 does not overflow). A weight whose probability
 * would round to 0 in float (below ~1e-45 of the total) is treated as 0, so that an outcome is
 * never sampled with pmf 0. n = 0 or all-zero weights give an empty table (MCRT_OK, count 0).
 * MCRT_ERR_NOMEM when out of memory. On failure *a is left empty. */
mcrt_status mc_alias_build(struct mc_alias *a, const double *w, size_t n, mc_diag *d);
void mc_alias_free(struct mc_alias *a);

/* Choose an outcome with ONE uniform u in [0, 1): column ⌊u·n⌋, then the coin u·n − ⌊u·n⌋ —
 * the bits of u below those that chose the column, rescaled to [0, 1) — against its q. *pmf
 * (may be NULL) receives the outcome's probability. Returns -1 for an empty table.
 * The coin inherits u's precision less log2 n bits: a 53-bit u (pcg32_double) leaves ~40 bits
 * for 10^4 outcomes, so every probability is realised exactly; a float u (24 bits) would leave
 * only 10, realising each probability only to within 2^-24 absolute. */
int mc_alias_sample(const struct mc_alias *a, double u, float *pmf);
/* Probability of outcome i; 0 when i >= count. */
float mc_alias_pmf(const struct mc_alias *a, size_t i);

#endif
