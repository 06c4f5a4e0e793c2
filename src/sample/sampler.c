/* sampler.c: per-sample random streams and stratified film positions (see sampler.h). */
#include "sample/sampler.h"

#include <math.h>

uint32_t mc_permute(uint32_t i, uint32_t n, uint32_t key)
{
    uint32_t w = n - 1;
    if (n <= 1)
        return 0;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    /* Cycle-walking: the hash is a bijection on [0, w]; repeat until the value falls below n. */
    do {
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
        i ^= i >> 5;
    } while (i >= n);
    return (i + key) % n;
}

void mc_sampler_pixel(struct sampler *s, uint64_t seed, int x, int y, int spp, int stratified)
{
    s->pixel_key = mc_hash3(seed, (uint64_t)(uint32_t)x, (uint64_t)(uint32_t)y);
    s->stratified = stratified && spp > 1;
    s->nx = (uint32_t)ceil(sqrt((double)spp));
    s->ny = ((uint32_t)spp + s->nx - 1) / s->nx;
    s->index = 0;
}

vec2 mc_sampler_start(struct sampler *s, uint32_t index)
{
    vec2 u;
    s->index = index;
    pcg32_seed(&s->rng, mc_hash64(s->pixel_key ^ mc_hash64(index)), s->pixel_key);
    u = mc_sampler_2d(s);
    if (s->stratified) {
        uint32_t cell = mc_permute(index % (s->nx * s->ny), s->nx * s->ny, (uint32_t)s->pixel_key);
        /* (cell + u) / n rounds up to exactly 1 for u near 1: keep the result inside [0, 1). */
        u.x = fminf(((float)(cell % s->nx) + u.x) / (float)s->nx, 0x1.fffffep-1f);
        u.y = fminf(((float)(cell / s->nx) + u.y) / (float)s->ny, 0x1.fffffep-1f);
    }
    return u;
}
