/* sampler.c: random, stratified and padded Owen-scrambled Sobol sample values (see sampler.h).
 * References: pbrt-v4 §8.5 (StratifiedSampler), §8.7 (PaddedSobolSampler); Burley 2020, JCGT 9(4);
 * Kensler 2013, Pixar TM 13-01. */
#include "sample/sampler.h"

#include <math.h>

#include "sample/sobol.h"

const char *const mc_sampler_names[SAMPLER_COUNT + 1] = {MC_SAMPLERS(MC_NAMES_ENTRY)
                                                         [SAMPLER_COUNT] = NULL};

/* Salt separating the per-dimension keys from the per-sample stream seeds. */
#define DIM_SALT 0x64696d656e73696fULL /* "dimensio" */
/* splitmix64's increment, 2^64/φ (Steele, Lea and Flood 2014, "Fast Splittable Pseudorandom
 * Number Generators"): hashing base + dim·γ gives independent keys for dimensions 0, 1, ... */
#define GOLDEN_GAMMA 0x9e3779b97f4a7c15ULL

/* The smallest 2^k - 1 >= n - 1: the domain of Kensler's hash, walked down to [0, n). */
static uint32_t permute_mask(uint32_t n)
{
    uint32_t w = n - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    return w;
}

/* One pass of Kensler's hash, a bijection on [0, w] for w = 2^k - 1. */
static inline uint32_t permute_hash(uint32_t i, uint32_t w, uint32_t key)
{
    i ^= key;
    i *= 0xe170893du;
    i ^= key >> 16;
    i ^= (i & w) >> 4;
    i ^= key >> 8;
    i *= 0x0929eb3fu;
    i ^= key >> 23;
    i ^= (i & w) >> 1;
    i *= 1u | key >> 27;
    i *= 0x6935fa69u;
    i ^= (i & w) >> 11;
    i *= 0x74dcb303u;
    i ^= (i & w) >> 2;
    i *= 0x9e501cc3u;
    i ^= (i & w) >> 2;
    i *= 0xc860a3dfu;
    i &= w;
    return i ^ i >> 5;
}

/* mc_permute with its mask w = permute_mask(n) given (the sampler computes it once a pixel). */
static inline uint32_t permute(uint32_t i, uint32_t n, uint32_t w, uint32_t key)
{
    if (n <= 1)
        return 0;
    /* n = w + 1, a power of two: one pass stays below n, and the remainder of the wrapped sum
     * is its low bits. */
    if (w + 1 == n)
        return (permute_hash(i, w, key) + key) & w;
    /* Cycle-walking: the hash is a bijection on [0, w]; repeat until the value falls below n. */
    do
        i = permute_hash(i, w, key);
    while (i >= n);
    return (i + key) % n;
}

uint32_t mc_permute(uint32_t i, uint32_t n, uint32_t key) { return permute(i, n, permute_mask(n), key); }

void mc_sampler_grid(uint32_t spp, uint32_t *nx, uint32_t *ny)
{
    uint32_t d = (uint32_t)floor(sqrt((double)spp));
    while (d > 1 && spp % d != 0)
        d--;
    if (spp / d <= 2 * d) {
        *nx = spp / d;
        *ny = d;
    } else {
        *nx = (uint32_t)ceil(sqrt((double)spp));
        *ny = (spp + *nx - 1) / *nx;
    }
}

/* k where n = 2^k <= 2^24, else -1. */
static int log2_exact(uint32_t n)
{
    int k = 0;
    if (n & (n - 1) || n > 1u << 24)
        return -1;
    while (n >> k > 1)
        k++;
    return k;
}

void mc_sampler_pixel(struct sampler *s, enum sampler_kind kind, uint64_t seed, int x, int y, int spp)
{
    s->kind = kind;
    s->spp = spp > 1 ? (uint32_t)spp : 1u;
    mc_sampler_grid(s->spp, &s->nx, &s->ny);
    s->scale[0] = 0x1p24 / s->spp;
    s->scale[1] = 0x1p24 / s->nx;
    s->scale[2] = 0x1p24 / s->ny;
    s->shift[0] = log2_exact(s->spp);
    s->shift[1] = log2_exact(s->nx);
    s->shift[2] = log2_exact(s->ny);
    s->mask[0] = permute_mask(s->spp);
    s->mask[1] = permute_mask(s->nx * s->ny);
    s->pixel_key = mc_hash3(seed, (uint64_t)(uint32_t)x, (uint64_t)(uint32_t)y);
    s->dim_base = mc_hash64(s->pixel_key ^ DIM_SALT);
    mc_sampler_start(s, 0);
}

void mc_sampler_start(struct sampler *s, uint32_t index)
{
    s->index = index < s->spp ? index : index % s->spp;
    s->dim = 0;
    pcg32_seed(&s->rng, mc_hash64(s->pixel_key ^ mc_hash64(index)), s->pixel_key);
}

/* The key of the dimension about to be drawn, and the counter moved past its n dimensions. */
static uint64_t next_key(struct sampler *s, uint32_t n)
{
    uint64_t key = mc_hash64(s->dim_base + s->dim * GOLDEN_GAMMA);
    s->dim += n;
    return key;
}

/* The stratum (of n, whose mc_permute mask is w) that this sample takes in the dimension keyed
 * by key: Kensler's permutation of the indices, rotated by an offset drawn from the key's other
 * half. When n exceeds spp (a 2D grid with spare cells) the samples leave some strata empty; the
 * rotation makes each sample's stratum uniform over all n (to within n·2^-32), which keeps the
 * estimate unbiased whichever strata are left out. Inline, as in_stratum: GCC -O2 otherwise keeps
 * one out-of-line copy for the three kinds of draw, which costs a stratified draw 11% more
 * instructions (192 against 171, in the order of a path's draws). */
static inline uint32_t stratum(const struct sampler *s, uint32_t n, uint32_t w, uint64_t key)
{
    uint32_t offset = (uint32_t)(((key >> 32) * n) >> 32);
    uint32_t k = permute(s->index, n, w, (uint32_t)key) + offset;
    return k >= n ? k - n : k;
}

/* A point of stratum k of n placed by the 24-bit jitter m (scale = 2^24/n): the grid point
 * q·2^-24 nearest below (k + m·2^-24)/n, moved back inside [k/n, (k+1)/n) when rounding put it
 * across an edge (the tests are exact integer products, below 2^56). So the value lands in its
 * stratum exactly and is below 1; the grid points of a stratum are equally likely to within
 * n·2^-24. */
static inline float in_stratum(uint32_t k, uint32_t n, double scale, int shift, uint32_t m)
{
    uint64_t q;
    /* n = 2^shift: that grid point exactly, k·2^(24-shift) + ⌊m/2^shift⌋, inside the stratum. */
    if (shift >= 0)
        return (float)((k << (24 - shift)) | (m >> shift)) * 0x1p-24f;
    q = (uint64_t)(((double)k + (double)m * 0x1p-24) * scale);
    if (q * n < (uint64_t)k << 24)
        q++;
    else if (q * n >= (uint64_t)(k + 1) << 24)
        q--;
    /* A stratum narrower than the grid (n > 2^24) may hold no grid point; stay below 1 even then. */
    return (float)(q < 0xffffffu ? q : 0xffffffu) * 0x1p-24f;
}

static uint32_t jitter24(struct sampler *s) { return pcg32_next(&s->rng) >> 8; }

/* A 32-bit Sobol fraction as a float: its top 24 bits, so that net cells (at most 2^24 of them
 * along an axis) are kept exactly and the value is below 1. */
static float fraction24(uint32_t v) { return (float)(v >> 8) * 0x1p-24f; }

/* Sobol: the sample's index in the dimension keyed by key, a permutation of [0, spp) by the key's
 * low half (its high half is the dimension's Owen seed). */
static inline uint32_t sobol_index(const struct sampler *s, uint64_t key)
{
    return permute(s->index, s->spp, s->mask[0], (uint32_t)key);
}

float mc_sampler_1d(struct sampler *s)
{
    uint64_t key;
    if (s->kind == SAMPLER_RANDOM) {
        s->dim++;
        return pcg32_float(&s->rng);
    }
    key = next_key(s, 1);
    if (s->kind == SAMPLER_STRATIFIED)
        return in_stratum(stratum(s, s->spp, s->mask[0], key), s->spp, s->scale[0], s->shift[0],
                          jitter24(s));
    return fraction24(mc_sobol_scrambled(sobol_index(s, key), 0, (uint32_t)(key >> 32)));
}

vec2 mc_sampler_2d(struct sampler *s)
{
    uint64_t key, v;
    uint32_t k;
    float a;
    if (s->kind == SAMPLER_RANDOM) {
        a = pcg32_float(&s->rng);
        s->dim += 2;
        return v2(a, pcg32_float(&s->rng));
    }
    key = next_key(s, 2);
    if (s->kind == SAMPLER_STRATIFIED) {
        uint32_t kx, ky;
        k = stratum(s, s->nx * s->ny, s->mask[1], key);
        kx = s->shift[1] >= 0 ? k & (s->nx - 1) : k % s->nx;
        ky = s->shift[1] >= 0 ? k >> s->shift[1] : k / s->nx;
        a = in_stratum(kx, s->nx, s->scale[1], s->shift[1], jitter24(s));
        return v2(a, in_stratum(ky, s->ny, s->scale[2], s->shift[2], jitter24(s)));
    }
    /* The key is a uniform 64-bit hash, so its halves are independent: the second coordinate's
     * seed, the high half xored with a bijection of the low half, is uniform and independent of
     * the first's (the pair is a bijection of the key). */
    v = mc_sobol2_scrambled(sobol_index(s, key), (uint32_t)(key >> 32),
                            (uint32_t)(key >> 32) ^ (uint32_t)key * 0x9e3779b9u);
    return v2(fraction24((uint32_t)(v >> 32)), fraction24((uint32_t)v));
}

double mc_sampler_1d_double(struct sampler *s)
{
    uint64_t key, v;
    double d;
    if (s->kind == SAMPLER_RANDOM) {
        s->dim++;
        return pcg32_double(&s->rng);
    }
    key = next_key(s, 1);
    if (s->kind == SAMPLER_STRATIFIED) {
        d = ((double)stratum(s, s->spp, s->mask[0], key) + pcg32_double(&s->rng)) / (double)s->spp;
        return d < 1.0 ? d : 0x1.fffffffffffffp-1;
    }
    /* A 32-bit index leaves digits 33 and on of a Sobol point at 0; Owen's scramble carried to
     * those depths would make them independent uniform bits, which is what the stream supplies. */
    v = mc_sobol_scrambled(sobol_index(s, key), 0, (uint32_t)(key >> 32));
    return (double)((v << 21) | (pcg32_next(&s->rng) >> 11)) * 0x1p-53;
}
