/* prim_util.h: building primitives, rays and random directions by hand in tests (not lights, no
 * shading normals). */
#ifndef MCRT_PRIM_UTIL_H
#define MCRT_PRIM_UTIL_H

#include <string.h>

#include "core/rng.h"
#include "geom/prim.h"

/* A primitive of the given kind with p[0..2] = a, b, c (see geom/prim.h for their meaning). */
static inline struct prim test_prim(int kind, vec3 a, vec3 b, vec3 c)
{
    struct prim p;
    memset(&p, 0, sizeof p);
    p.kind = (uint8_t)kind;
    p.light = -1;
    p.normals = -1;
    p.p[0] = a;
    p.p[1] = b;
    p.p[2] = c;
    return p;
}

/* The ray o + t·d, t in (0, ∞), at time 0. */
static inline struct ray test_ray(vec3 o, vec3 d)
{
    struct ray r;
    r.o = o;
    r.d = d;
    r.tmax = INFINITY;
    r.time = 0.0f;
    return r;
}

/* Intersect one primitive with a fresh hit record (t = tmax). */
static inline int test_hit1(const struct prim *p, struct ray r, struct hit *h)
{
    h->t = r.tmax;
    h->u = h->v = -1.0f;
    return mc_prim_intersect(p, &r, h);
}

/* A direction uniform on the unit sphere (Archimedes: z uniform in [−1, 1]). */
static inline vec3 test_rand_dir(pcg32 *g)
{
    float z = 1.0f - 2.0f * pcg32_float(g), phi = 2.0f * MC_PI * pcg32_float(g);
    float s = sqrtf(fmaxf(0.0f, 1.0f - z * z));
    return v3(s * cosf(phi), s * sinf(phi), z);
}

#endif
