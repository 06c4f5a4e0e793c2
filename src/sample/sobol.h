/* sobol.h: the two-dimensional Sobol (0,2)-sequence and hash-based Owen scrambling, the building
 * blocks of the padded Sobol sampler (sampler.c). Static inline: a path draws tens of these.
 *
 * Values are 32-bit binary fractions, most significant digit first: v represents v·2^-32.
 * Sobol 1967, "On the distribution of points in a cube and the approximate evaluation of
 * integrals"; the first two dimensions are the only ones needed because the sampler pads every
 * further dimension with independently shuffled and scrambled copies of them (pbrt-v4
 * PaddedSobolSampler; Burley 2020). */
#ifndef MCRT_SOBOL_H
#define MCRT_SOBOL_H

#include <stdint.h>

/* The 32 bits of v in reverse order. */
static inline uint32_t mc_reverse_bits(uint32_t v)
{
    v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
    v = ((v >> 8) & 0x00ff00ffu) | ((v & 0x00ff00ffu) << 8);
    return (v >> 16) | (v << 16);
}

/* Point `index` of Sobol dimension 0 or 1. Dimension 0 is the van der Corput sequence (identity
 * generator matrix: the bits of index reversed); dimension 1 has the upper-triangular Pascal
 * matrix mod 2 as generator (Kollig and Keller 2002, "Efficient Multidimensional Sampling",
 * Sobol02): column k is v_k = v_{k-1} ^ (v_{k-1} >> 1), v_0 = 2^31, so row j of column k is
 * C(k, j) mod 2. Every 2^m consecutive points starting at a multiple of 2^m form a (0,m,2)-net
 * in base 2: one point in every elementary interval of area 2^-m. */
static inline uint32_t mc_sobol(uint32_t index, int dim)
{
    uint32_t r = 0, v = 0x80000000u;
    if (dim == 0)
        return mc_reverse_bits(index);
    for (; index; index >>= 1, v ^= v >> 1)
        if (index & 1u)
            r ^= v;
    return r;
}

/* The scramble of mc_owen_scramble on bit-reversed values (digit k is bit k-1): every step
 * flips bit k or not according to the bits below it only — adding, multiplying by an odd
 * number, xoring a multiple by an even number — which is Owen's nested condition, and each step
 * is invertible. Burley 2020's hash with the constants of Vegdahl 2021 ("Building a Better LK
 * Hash"), as in pbrt-v4's FastOwenScrambler. */
static inline uint32_t mc_owen_reversed(uint32_t v, uint32_t seed)
{
    v ^= v * 0x3d20adeau;
    v += seed;
    v *= (seed >> 16) | 1u;
    v ^= v * 0x05526c56u;
    v ^= v * 0x53a22864u;
    return v;
}

/* A nested uniform (Owen 1995) scramble of the digits of v chosen by seed: digit k is flipped by
 * a hash of seed and digits 1..k-1 only, so scrambling maps every elementary interval onto an
 * elementary interval of the same shape and preserves (t,m,s)-nets. Burley 2020, "Practical
 * Hash-based Owen Scrambling", JCGT 9(4). A bijection of 32-bit values for every seed. */
static inline uint32_t mc_owen_scramble(uint32_t v, uint32_t seed)
{
    return mc_reverse_bits(mc_owen_reversed(mc_reverse_bits(v), seed));
}

/* mc_owen_scramble(mc_sobol(index, dim), seed), without reversing van der Corput's bits twice. */
static inline uint32_t mc_sobol_scrambled(uint32_t index, int dim, uint32_t seed)
{
    if (dim == 0)
        return mc_reverse_bits(mc_owen_reversed(index, seed));
    return mc_owen_scramble(mc_sobol(index, 1), seed);
}

#endif
