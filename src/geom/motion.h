/* motion.h: rigid motion of shapes over the exposure. A moving shape is stored at its place at
 * time 0 and is at x(t) = R(axis, ω·t)·(x − c) + c + t·v at scene time t: a rotation by ω·t
 * radians about the axis through c (mesh `spin`) followed by a translation t·v (`move`). Both are
 * rigid, so distances, areas and solid angles are the same in the shape's time-0 frame as in the
 * world: a moving shape is intersected, shaded and sampled in that frame. */
#ifndef MCRT_MOTION_H
#define MCRT_MOTION_H

#include "geom/ray.h"

struct motion {
    vec3 move;      /* translation per unit time */
    vec3 center;    /* a point on the spin axis */
    vec3 axis;      /* unit spin axis (any unit vector when omega is 0) */
    float omega;    /* spin in radians per unit time, right-handed about axis */
};

/* A rigid map x -> R·x + t, R orthonormal (rows r[0..2]). */
struct rigid {
    vec3 r[3];
    vec3 t;
};

/* The map from the time-0 frame to the world at time `time`. */
void mc_motion_at(const struct motion *m, float time, struct rigid *x);

/* Conservative bounds of box b (in the time-0 frame) carried by m over all times in [t0, t1]:
 * for a pure translation the union of the two end boxes, otherwise looser by at most
 * r·(2π/64)²/8 ≈ 0.0012·r per face (r the box's largest distance from the spin axis; past a full
 * turn, plus the translation during one turn); both padded by 2^-20 of the magnitudes involved
 * for float rounding (motion.c). */
struct aabb mc_motion_bounds(const struct motion *m, struct aabb b, float t0, float t1);

static inline vec3 rigid_vector(const struct rigid *x, vec3 v)
{
    return v3(v3_dot(x->r[0], v), v3_dot(x->r[1], v), v3_dot(x->r[2], v));
}
static inline vec3 rigid_point(const struct rigid *x, vec3 p) { return v3_add(rigid_vector(x, p), x->t); }
/* Rᵀ·v: R is orthonormal, so its transpose is its inverse. */
static inline vec3 rigid_inv_vector(const struct rigid *x, vec3 v)
{
    return v3_add(v3_add(v3_scale(x->r[0], v.x), v3_scale(x->r[1], v.y)), v3_scale(x->r[2], v.z));
}
static inline vec3 rigid_inv_point(const struct rigid *x, vec3 p)
{
    return rigid_inv_vector(x, v3_sub(p, x->t));
}
/* The ray in the time-0 frame; t along it means the same distance as in the world. */
static inline struct ray rigid_inv_ray(const struct rigid *x, const struct ray *r)
{
    struct ray o = *r;
    o.o = rigid_inv_point(x, r->o);
    o.d = rigid_inv_vector(x, r->d);
    return o;
}

#endif
