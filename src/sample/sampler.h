/* sampler.h: the random numbers of one pixel sample.
 * Every sample (pixel, index) has its own PCG32 stream seeded by hashing (seed, pixel, index), so
 * any sample can be regenerated alone and the image does not depend on threads or tile order.
 * The film position is stratified: sample i of n falls in its own cell of an nx×ny grid
 * (nx·ny ≥ n, a permutation of the cells per pixel), jittered within the cell. */
#ifndef MCRT_SAMPLER_H
#define MCRT_SAMPLER_H

#include <stdint.h>

#include "core/rng.h"
#include "core/vec.h"

struct sampler {
    pcg32 rng;
    int stratified;
    uint32_t nx, ny;       /* film-position strata */
    uint64_t pixel_key;    /* hash of (seed, pixel): decorrelates pixels' permutations */
    uint32_t index;        /* current sample index */
};

/* Prepare for a pixel: spp samples, stratified or purely random. */
void mc_sampler_pixel(struct sampler *s, uint64_t seed, int x, int y, int spp, int stratified);
/* Start sample `index` of the pixel and return its film offset in [0,1)^2 within the pixel. */
vec2 mc_sampler_start(struct sampler *s, uint32_t index);

static inline float mc_sampler_1d(struct sampler *s) { return pcg32_float(&s->rng); }
/* 53 random bits, for choices among many outcomes (the alias table's column and coin). */
static inline double mc_sampler_1d_double(struct sampler *s) { return pcg32_double(&s->rng); }
static inline vec2 mc_sampler_2d(struct sampler *s)
{
    float a = pcg32_float(&s->rng);
    return v2(a, pcg32_float(&s->rng));
}

/* A bijection of [0, n) chosen by key, without memory: Kensler 2013, "Correlated Multi-Jittered
 * Sampling", Pixar Technical Memo 13-01, permute(). */
uint32_t mc_permute(uint32_t i, uint32_t n, uint32_t key);

#endif
