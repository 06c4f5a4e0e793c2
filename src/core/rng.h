/* rng.h: PCG32 (O'Neill 2014, pcg32_random_r) and integer hashes for deriving independent streams.
 * Every random stream in mcrt is derived from (seed, pixel, ...) by hashing, never from shared state,
 * so results do not depend on thread count or scheduling. */
#ifndef MCRT_RNG_H
#define MCRT_RNG_H

#include <stdint.h>

typedef struct pcg32 { uint64_t state, inc; } pcg32;

/* pcg32_srandom_r: state 0, inc = (seq << 1) | 1, step, add initstate, step. */
static inline uint32_t pcg32_next(pcg32 *r)
{
    uint64_t old = r->state;
    uint32_t xs, rot;
    r->state = old * 6364136223846793005ULL + r->inc;
    xs = (uint32_t)(((old >> 18) ^ old) >> 27);
    rot = (uint32_t)(old >> 59);
    return (xs >> rot) | (xs << ((0u - rot) & 31u));
}
static inline void pcg32_seed(pcg32 *r, uint64_t initstate, uint64_t initseq)
{
    r->state = 0;
    r->inc = (initseq << 1) | 1u;
    pcg32_next(r);
    r->state += initstate;
    pcg32_next(r);
}
/* Uniform float in [0, 1): 24 random bits, so the largest value is 1 - 2^-24 and never 1. */
static inline float pcg32_float(pcg32 *r) { return (float)(pcg32_next(r) >> 8) * 0x1p-24f; }
/* Uniform double in [0, 1) from 53 random bits. */
static inline double pcg32_double(pcg32 *r)
{
    uint64_t hi = pcg32_next(r) >> 5, lo = pcg32_next(r) >> 6;
    return (double)((hi << 26) | lo) * 0x1p-53;
}

/* 64-bit finaliser (splitmix64 / Stafford variant 13): a bijection with full avalanche. */
static inline uint64_t mc_hash64(uint64_t x)
{
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    x ^= x >> 31;
    return x;
}
/* Hash of a tuple: each word is folded through the finaliser in turn. */
static inline uint64_t mc_hash3(uint64_t a, uint64_t b, uint64_t c)
{
    return mc_hash64(mc_hash64(mc_hash64(a) ^ b) ^ c);
}

#endif
