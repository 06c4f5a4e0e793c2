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

/* Point `index` of Sobol dimension 1 with its bits reversed (digit k of the fraction is bit k-1).
 * Dimension 1's generator is the upper-triangular Pascal matrix mod 2 (Kollig and Keller 2002,
 * "Efficient Multidimensional Sampling", Sobol02): column b reversed has bit j set when C(b, j) is
 * odd, which by Lucas's theorem is when the bits of j are a subset of those of b. So bit j of the
 * result is the parity of the set bits b of index with j ⊆ b: the transform over supersets
 * (Yates's butterfly, one step per bit of a position's 5-bit index), without a loop over the
 * index's bits. */
static inline uint32_t mc_sobol1_reversed(uint32_t index)
{
    index ^= (index >> 1) & 0x55555555u;
    index ^= (index >> 2) & 0x33333333u;
    index ^= (index >> 4) & 0x0f0f0f0fu;
    index ^= (index >> 8) & 0x00ff00ffu;
    return index ^ index >> 16;
}

/* Point `index` of Sobol dimension 0 or 1. Dimension 0 is the van der Corput sequence (identity
 * generator matrix: the bits of index reversed); dimension 1 is mc_sobol1_reversed's, column k
 * v_k = v_{k-1} ^ (v_{k-1} >> 1), v_0 = 2^31. Every 2^m consecutive points starting at a multiple
 * of 2^m form a (0,m,2)-net in base 2: one point in every elementary interval of area 2^-m. */
static inline uint32_t mc_sobol(uint32_t index, int dim)
{
    return mc_reverse_bits(dim == 0 ? index : mc_sobol1_reversed(index));
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

/* mc_owen_scramble(mc_sobol(index, dim), seed), without reversing the bits twice. */
static inline uint32_t mc_sobol_scrambled(uint32_t index, int dim, uint32_t seed)
{
    return mc_reverse_bits(mc_owen_reversed(dim == 0 ? index : mc_sobol1_reversed(index), seed));
}

/* The 64 bits of v in reverse order. */
static inline uint64_t mc_reverse_bits64(uint64_t v)
{
    v = ((v >> 1) & 0x5555555555555555ULL) | ((v & 0x5555555555555555ULL) << 1);
    v = ((v >> 2) & 0x3333333333333333ULL) | ((v & 0x3333333333333333ULL) << 2);
    v = ((v >> 4) & 0x0f0f0f0f0f0f0f0fULL) | ((v & 0x0f0f0f0f0f0f0f0fULL) << 4);
    v = ((v >> 8) & 0x00ff00ff00ff00ffULL) | ((v & 0x00ff00ff00ff00ffULL) << 8);
    v = ((v >> 16) & 0x0000ffff0000ffffULL) | ((v & 0x0000ffff0000ffffULL) << 16);
    return (v >> 32) | (v << 32);
}

/* Both coordinates of point `index`, mc_sobol_scrambled(index, 0, seed0) in the high 32 bits and
 * mc_sobol_scrambled(index, 1, seed1) in the low: the two scrambled values reversed together by
 * one 64-bit reversal. */
static inline uint64_t mc_sobol2_scrambled(uint32_t index, uint32_t seed0, uint32_t seed1)
{
    return mc_reverse_bits64((uint64_t)mc_owen_reversed(mc_sobol1_reversed(index), seed1) << 32
                             | mc_owen_reversed(index, seed0));
}

#endif
