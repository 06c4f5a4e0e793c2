/* shape_impl.h: private to src/geom: what each shape's file (src/geom/NAME.c, one per line of
 * MC_SHAPES in prim.h) defines, and the helpers they share. prim.c dispatches to these with a
 * switch over the kind, which the compiler makes a jump table of tail calls. */
#ifndef MCRT_SHAPE_IMPL_H
#define MCRT_SHAPE_IMPL_H

#include "geom/prim.h"

/* For shape NAME:
 *   mc_NAME_intersect  the hit in (0, h->t): update h (t, u, v) and return 1, as mc_prim_intersect
 *   mc_NAME_bounds     a conservative box
 *   mc_NAME_area       the surface area
 *   mc_NAME_magnitude  the largest magnitude of its parameters (mc_prim_point_error's M)
 *   mc_NAME_surface    the hit point from the shape's own parameters; returns the unit geometric
 *                      normal on the front side before any flip
 *   mc_NAME_sample     a point uniform in area, with the unit front-side normal before any flip
 *   mc_NAME_uv         the texture coordinates of the hit (mc_prim_uv)
 *   mc_NAME_shape      its descriptor: block name and parameters in the scene language */
#define MC_SHAPE_DECLARE(kind, name)                                                           \
    int mc_##name##_intersect(const struct prim *p, const struct ray_prep *q, struct hit *h);  \
    struct aabb mc_##name##_bounds(const struct prim *p);                                      \
    float mc_##name##_area(const struct prim *p);                                              \
    float mc_##name##_magnitude(const struct prim *p);                                         \
    vec3 mc_##name##_surface(const struct prim *p, const struct ray *r, const struct hit *h,   \
                             vec3 *point);                                                     \
    vec3 mc_##name##_sample(const struct prim *p, vec2 u, vec3 *n);                            \
    vec2 mc_##name##_uv(const struct prim *p, const struct ray *r, const struct hit *h);       \
    extern const struct shape mc_##name##_shape;
MC_SHAPES(MC_SHAPE_DECLARE)
#undef MC_SHAPE_DECLARE

/* The watertight test (triangle.c) of the triangle v[0..2], or with parallelogram set of the
 * parallelogram v[0] + s·(v[1] − v[0]) + t·(v[2] − v[0]), s, t in [0, 1]: the same edge functions,
 * accepted over the other region. As mc_NAME_intersect, with h->u, h->v the weights of v[1] and
 * v[2] (a quad's s and t). Collinear vertices (in double) are never hit. */
int mc_watertight_intersect(const vec3 *v, const struct ray_prep *q, int parallelogram,
                            struct hit *h);

/* The hit distance is accepted only if it is a number in (0, h->t). Comparing the final rounded t,
 * and nothing else, makes the outcome independent of the order in which primitives are tested, so a
 * BVH and a brute-force loop report the very same nearest hit. NaN fails both comparisons. */
static inline int mc_shape_accept(float t, const struct hit *h) { return t > 0.0f && t < h->t; }

/* Bounds computed with float arithmetic (centre ± r, corner + e) are rounded and may lie a hair
 * inside the true surface; widening by one ulp outward keeps them conservative. */
static inline struct aabb mc_shape_widen(struct aabb b)
{
    b.lo = v3(nextafterf(b.lo.x, -INFINITY), nextafterf(b.lo.y, -INFINITY),
              nextafterf(b.lo.z, -INFINITY));
    b.hi = v3(nextafterf(b.hi.x, INFINITY), nextafterf(b.hi.y, INFINITY),
              nextafterf(b.hi.z, INFINITY));
    return b;
}

static inline float mc_shape_max_abs(vec3 v)
{
    return f_max(fabsf(v.x), f_max(fabsf(v.y), fabsf(v.z)));
}

#endif
