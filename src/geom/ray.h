/* ray.h: rays, bounding boxes, and robust spawning of secondary rays. */
#ifndef MCRT_RAY_H
#define MCRT_RAY_H

#include <stdint.h>
#include <string.h>

#include "core/vec.h"

/* A ray o + t·d for t in (0, tmax) at scene time `time` (within the camera's shutter; read only
 * by moving primitives). d need not be unit length for intersection, but the integrators always
 * pass unit directions so that t is a distance. */
struct ray {
    vec3 o, d;
    float tmax;
    float time;
};

struct aabb { vec3 lo, hi; };

static inline struct aabb aabb_empty(void)
{
    struct aabb b;
    b.lo = v3s(INFINITY);
    b.hi = v3s(-INFINITY);
    return b;
}
static inline struct aabb aabb_union(struct aabb a, struct aabb b)
{
    a.lo = v3_min(a.lo, b.lo);
    a.hi = v3_max(a.hi, b.hi);
    return a;
}
static inline struct aabb aabb_grow(struct aabb a, vec3 p)
{
    a.lo = v3_min(a.lo, p);
    a.hi = v3_max(a.hi, p);
    return a;
}
static inline vec3 aabb_center(struct aabb a) { return v3_scale(v3_add(a.lo, a.hi), 0.5f); }
/* Half the surface area (the SAH only needs ratios); 0 for an empty box. */
static inline float aabb_half_area(struct aabb a)
{
    vec3 e = v3_sub(a.hi, a.lo);
    if (e.x < 0.0f || e.y < 0.0f || e.z < 0.0f)
        return 0.0f;
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

/* Move a surface point off its surface for spawning a ray, along the geometric normal n (either
 * side: pass n facing the side the new ray leaves from). The offset scales with the magnitude of p,
 * so it covers the floating-point error of the hit point at any distance from the origin:
 * Wächter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems
 * (2019) ch. 6, listing 6-1. Near the origin a fixed tiny offset (float_scale·n) is used, since
 * integer ulp steps of tiny numbers are too small.
 * int_scale is 16 ulps, not the chapter's 256: its 256 covers a hit point rebuilt as o + t·d,
 * whose error grows with t, while mc_prim_surface computes the point from the primitive's own
 * parameters (b0·p0 + u·p1 + v·p2, p0 + u·e1 + v·e2), off the surface by at most a few ulps
 * (γ3..γ5 of the coordinates, plus γ3 for a motion transform): 16 ulps times the dominant
 * normal component (≥ 1/√3) still clears that 2-3 times over. 256 ulps moved rays by 16 mm at 1e6
 * from the origin, which in the Cornell box (556 mm) lit contact shadows through the block
 * bases and the wall corners: +0.4% image mean, block z 12 at 128 spp (tests/unit/test_stiff.c). */
static inline float ray_offset_component(float p, float n)
{
    const float origin = 1.0f / 32.0f, float_scale = 1.0f / 65536.0f, int_scale = 16.0f;
    int32_t of = (int32_t)(int_scale * n);
    int32_t bits;
    float moved;
    if (fabsf(p) < origin)
        return p + float_scale * n;
    memcpy(&bits, &p, sizeof bits);
    bits += (p < 0.0f) ? -of : of;
    memcpy(&moved, &bits, sizeof moved);
    return moved;
}
static inline vec3 ray_offset(vec3 p, vec3 n)
{
    return v3(ray_offset_component(p.x, n.x), ray_offset_component(p.y, n.y),
              ray_offset_component(p.z, n.z));
}

/* The origin of a ray spawned from a point p that may lie up to err off its surface (the bound
 * of pbrt-v4's OffsetRayOrigin, Pharr et al. 4th ed. §6.8.6, from the primitive's magnitude:
 * mc_prim_point_error): moved err along n, then ray_offset for the rounding of that move and of
 * p's own magnitude. W&B alone scales with |p|, which fails when p is small but was computed
 * from large terms (a point near the origin on a huge quad or sphere: acne). */
static inline vec3 ray_spawn(vec3 p, vec3 n, float err)
{
    return ray_offset(v3_madd(p, n, err), n);
}

/* The side of the surface a direction leaves from, for offsetting ray origins. */
static inline vec3 side_normal(vec3 ng, vec3 w) { return v3_dot(w, ng) >= 0.0f ? ng : v3_neg(ng); }

#endif
