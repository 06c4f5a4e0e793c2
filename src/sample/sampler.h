/* sampler.h: the sample values of one pixel sample, dimension by dimension.
 *
 * A path asks for dimensions in a fixed order (film 2D, lens 2D, time 1D, then per bounce light
 * choice, light point, lobe, direction, roulette) and may ask for any number of them. Every value
 * is a pure function of (kind, seed, pixel, spp, sample index, dimension, and whether the draws
 * before it were 1D or 2D): any sample can be regenerated alone, and the image depends neither on
 * threads nor on tile order.
 *
 * All three kinds are "padded" (pbrt-v4 §8.5 and §8.7, StratifiedSampler / PaddedSobolSampler):
 * each 1D or 2D dimension is a well-stratified set of spp values whose order over the sample
 * indices is shuffled by its own permutation keyed by hash(seed, pixel, dimension). Dimensions
 * are therefore uncorrelated with each other and with neighbouring pixels, each keeps the
 * stratification of its own 1D or 2D set, and there is no limit on the number of dimensions
 * (nothing is tabulated per dimension). What padding gives up is joint stratification across
 * dimensions (film × lens as a 4D set), which a high-dimensional Sobol sequence offers for its
 * leading dimensions, at the price of tabulated direction numbers for every dimension and of
 * decorrelating pixels some other way.
 *
 *   random      independent uniform values: a PCG32 stream per (seed, pixel, index).
 *   stratified  a 1D dimension puts one value in each of spp equal strata; a 2D dimension puts at
 *               most one point in each cell of an nx×ny grid (mc_sampler_grid: exactly one
 *               whenever spp has a factorisation of aspect at most 2, every power of two among
 *               them); jitter inside the stratum comes from the sample's PCG32 stream (Mitchell
 *               1996; pbrt-v4 StratifiedSampler).
 *   sobol       a 2D dimension is the first spp points of the Sobol (0,2)-sequence, a 1D
 *               dimension the first spp of van der Corput's; each with its own hash-based Owen
 *               scramble (Burley 2020, JCGT 9(4)). Owen scrambling makes every point uniform on
 *               [0,1)^d while keeping the net structure, so any spp is unbiased, and at spp = 2^m
 *               every 2D dimension is a (0,m,2)-net. The index permutation is over [0, spp), not
 *               Burley's nested scramble of the index over [0, 2^⌈log2 spp⌉), so that spp values
 *               that are not powers of two still use a prefix of the sequence (the best-spread
 *               points) rather than a scattered subset of a larger net.
 *
 * Floats carry the top 24 bits of a value (k·2^-24), so 1.0 is never returned; the double
 * variant carries 53 (for the alias table's column and coin over up to millions of lights). */
#ifndef MCRT_SAMPLER_H
#define MCRT_SAMPLER_H

#include <stdint.h>

#include "core/names.h"
#include "core/rng.h"
#include "core/vec.h"

/* The samplers, X(KIND, NAME): the enum and the name that the scene language (film `sampler`),
 * the API (mcrt_options.sampler), mcrt --help and mcrt converge --compare read from here. */
#define MC_SAMPLERS(X)                                                                         \
    X(SAMPLER_RANDOM, "random")                                                                \
    X(SAMPLER_STRATIFIED, "stratified")                                                        \
    X(SAMPLER_SOBOL, "sobol")
enum sampler_kind { MC_SAMPLERS(MC_NAMES_ENUM) };
#define SAMPLER_COUNT (0 MC_SAMPLERS(MC_NAMES_COUNT))
/* The names by kind, NULL at [SAMPLER_COUNT] (core/names.h). */
extern const char *const mc_sampler_names[SAMPLER_COUNT + 1];

struct sampler {
    enum sampler_kind kind;
    uint32_t spp;
    uint32_t nx, ny;       /* stratified: the 2D grid */
    double scale[3];       /* stratified: 2^24 / (spp, nx, ny) */
    /* log2 of spp, nx, ny where that is a power of two up to 2^24, else -1: the stratum
     * arithmetic is then shifts and masks (the same values, exactly) */
    int shift[3];
    uint32_t mask[2];      /* the cycle-walking masks of mc_permute for spp and nx·ny */
    uint64_t pixel_key;    /* hash of (seed, pixel) */
    uint64_t dim_base;     /* dimension d's key is a hash of dim_base + d·γ */
    uint32_t index;        /* current sample */
    uint32_t dim;          /* next dimension: a 2D draw takes two */
    pcg32 rng;             /* the current sample's stream (random values, jitter, low bits) */
};

/* Prepare for pixel (x, y) of a render with `spp` samples per pixel (spp < 1 counts as 1) and
 * this seed. */
void mc_sampler_pixel(struct sampler *s, enum sampler_kind kind, uint64_t seed, int x, int y, int spp);
/* Start sample `index` (0 <= index < spp; larger indices wrap around the strata): the dimension
 * counter goes back to 0. */
void mc_sampler_start(struct sampler *s, uint32_t index);
/* The next dimension, in [0, 1). */
float mc_sampler_1d(struct sampler *s);
/* The next two dimensions as one 2D point (stratified jointly), in [0, 1)^2. */
vec2 mc_sampler_2d(struct sampler *s);
/* The next dimension as a double in [0, 1) with 53 bits (random, stratified) or 32 stratified
 * bits followed by 21 uniform ones (sobol): for choices among very many outcomes. */
double mc_sampler_1d_double(struct sampler *s);

/* The stratified sampler's 2D grid for spp samples: nx·ny = spp with ny the largest divisor of
 * spp up to √spp, when nx = spp/ny is at most 2·ny (every cell holds one point: a half of a
 * pixel's 64 samples is 8×4 rather than 6×6 with 4 cells empty, whose missing cells would add a
 * share 4/36 of the random sampler's variance); otherwise nx = ⌈√spp⌉, ny = ⌈spp/nx⌉, and each
 * cell holds at most one point. */
void mc_sampler_grid(uint32_t spp, uint32_t *nx, uint32_t *ny);

/* A bijection of [0, n) chosen by key, without memory: Kensler 2013, "Correlated Multi-Jittered
 * Sampling", Pixar Technical Memo 13-01, permute(). Requires i < n. */
uint32_t mc_permute(uint32_t i, uint32_t n, uint32_t key);

#endif
