/* motion.c: the rigid map of a moving shape at a given time (Rodrigues' rotation formula) and
 * conservative bounds of a box swept over an interval of time (for the motion BVH). */
#include "geom/motion.h"

/* Rotation steps per full turn when sweeping bounds: the angle between samples is at most
 * 2π/64, so the interpolation pad below is at most r·(2π/64)²/8 ≈ 0.0012·r. */
enum { STEPS_PER_TURN = 64 };

/* Relative pad for float rounding in the bounds (16 ulps of 2^-24): see mc_motion_bounds. */
#define ROUNDING_PAD 0x1p-20f

#define TWO_PI 6.28318530717958647692f

void mc_motion_at(const struct motion *m, float time, struct rigid *x)
{
    vec3 k = m->axis, c = m->center;
    float a = m->omega * time, sh, ch, s, cs, u;
    if (m->omega == 0.0f) {
        /* Pure translation. Rodrigues gives exactly this too (R = I, c − R·c = 0), but without
         * the sines, which matters in a leaf test that maps rays through many moving shapes. */
        x->r[0] = v3(1.0f, 0.0f, 0.0f);
        x->r[1] = v3(0.0f, 1.0f, 0.0f);
        x->r[2] = v3(0.0f, 0.0f, 1.0f);
        x->t = v3_scale(m->move, time);
        return;
    }
    /* Rodrigues: R = cos a·I + sin a·[k]× + (1 − cos a)·k·kᵀ. The half angle gives 1 − cos a as
     * 2·sin²(a/2), which does not cancel for small angles. */
    sh = sinf(0.5f * a);
    ch = cosf(0.5f * a);
    s = 2.0f * sh * ch;
    u = 2.0f * sh * sh;
    cs = 1.0f - u;
    x->r[0] = v3(cs + u * k.x * k.x, u * k.x * k.y - s * k.z, u * k.x * k.z + s * k.y);
    x->r[1] = v3(u * k.x * k.y + s * k.z, cs + u * k.y * k.y, u * k.y * k.z - s * k.x);
    x->r[2] = v3(u * k.x * k.z - s * k.y, u * k.y * k.z + s * k.x, cs + u * k.z * k.z);
    /* x -> R·(x − c) + c + time·v = R·x + (c − R·c + time·v) */
    x->t = v3_add(v3_sub(c, rigid_vector(x, c)), v3_scale(m->move, time));
}

static float max_abs(vec3 v) { return v3_max_comp(v3_abs(v)); }

/* Bounds of the 8 corners carried by m to `time`: they bound the moved box, which is their convex
 * hull since the map is affine. */
static struct aabb moved_corners(const struct motion *m, const vec3 *corner, float time)
{
    struct aabb b = aabb_empty();
    struct rigid x;
    int i;
    mc_motion_at(m, time, &x);
    for (i = 0; i < 8; i++)
        b = aabb_grow(b, rigid_point(&x, corner[i]));
    return b;
}

/* The corners carried to n + 1 evenly spaced times over [t0, t1], padded by r·Δ²/8 for the
 * motion between samples (Δ the angle between samples, r the farthest distance of the box from
 * the axis); see mc_motion_bounds for why this is conservative. */
static struct aabb sweep(const struct motion *m, const vec3 *corner, float r, float t0, float t1,
                         int n)
{
    struct aabb b = moved_corners(m, corner, t1);
    float step = fabsf(m->omega * (t1 - t0)) / (float)n;
    vec3 pad = v3s(r * step * step * 0.125f);
    int i;
    for (i = 0; i < n; i++)
        b = aabb_union(b, moved_corners(m, corner, t0 + (t1 - t0) * ((float)i / (float)n)));
    b.lo = v3_sub(b.lo, pad);
    b.hi = v3_add(b.hi, pad);
    return b;
}

/* Why the sampled bounds are conservative. Take a point p of the box, u = p − c, and times
 * t_i < t_{i+1} with angles θ_i, θ_{i+1} = θ_i + Δ. The position x(t) = R(ωt)·u + c + t·v is, per
 * axis k, a function g(θ) = (R(θ)·u)_k plus a function linear in t; θ is linear in t, so the
 * linear interpolation L of x between the two samples (in t, equivalently in θ) reproduces the
 * linear part exactly and errs only in g. The interpolation error theorem bounds that error by
 * max|g''|·(θ − θ_i)(θ_{i+1} − θ)/2 ≤ max|g''|·Δ²/8, and g'' = −(the component of u
 * perpendicular to the axis, rotated)_k, so |g''| ≤ ρ, the distance of p from the axis. ρ is a
 * convex function of p, so ρ ≤ r, its largest value at a corner. L(t) lies on the segment between
 * x(t_i) and x(t_{i+1}), inside the bounds of the moved corners at those two times (each moved
 * box lies in the bounds of its corners and the union of two boxes' bounds is convex). So x(t) is
 * inside those bounds padded by r·Δ²/8 on every axis. (This pad is at least the chord error
 * r·(1 − cos(Δ/2)), since 1 − cos a ≤ a²/2, and within a factor 1 + Δ²/48 of it; the chord error
 * alone bounds the distance to the chord, not to the point reached at the same time, which
 * differs when the shape also translates.) Over more than a full turn every angle is reached, so
 * the bounds of one full turn without translation, plus the translation's span, are conservative
 * and do not grow with the number of turns. */
struct aabb mc_motion_bounds(const struct motion *m, struct aabb b, float t0, float t1)
{
    vec3 corner[8];
    struct aabb out;
    float r = 0.0f, sweep_angle = fabsf(m->omega * (t1 - t0)), mag;
    int i;
    for (i = 0; i < 8; i++) {
        corner[i] = v3(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z);
        if (m->omega != 0.0f) {
            vec3 u = v3_sub(corner[i], m->center);
            vec3 radial = v3_sub(u, v3_scale(m->axis, v3_dot(u, m->axis)));
            r = fmaxf(r, v3_length(radial));
        }
    }
    if (sweep_angle > TWO_PI) {
        struct motion spin = *m;
        vec3 a = v3_scale(m->move, t0), z = v3_scale(m->move, t1);
        spin.move = v3s(0.0f);
        out = sweep(&spin, corner, r, 0.0f, TWO_PI / fabsf(m->omega), STEPS_PER_TURN);
        out.lo = v3_add(out.lo, v3_min(a, z));
        out.hi = v3_add(out.hi, v3_max(a, z));
    } else {
        /* At least one step; a pure translation (ω = 0) is exact with one: x(t) is linear. */
        int n = (int)ceilf(sweep_angle * (float)STEPS_PER_TURN / TWO_PI);
        out = sweep(m, corner, r, t0, t1, n > 1 ? n : 1);
    }
    /* Float rounding: the rigid map carries a few ulps of error in its entries and products
     * (relative to the magnitudes |R·x| ≤ |x| and |t| ≤ 2|c| + |time·v| involved), and the angle
     * ω·t is rounded to half an ulp of θ, which moves a point by up to r·|θ|·2^-24. A pad of
     * 2^-20 (16 ulps) of the sum of these magnitudes covers them, so that a point carried by
     * mc_motion_at at any time in [t0, t1] is inside; for a pure translation this is the only
     * slack beyond the exact union of the two end boxes. */
    mag = fmaxf(max_abs(out.lo), max_abs(out.hi));
    if (m->omega != 0.0f)
        mag += 2.0f * max_abs(m->center) + r * (1.0f + fabsf(m->omega) * fmaxf(fabsf(t0), fabsf(t1)));
    out.lo = v3_sub(out.lo, v3s(ROUNDING_PAD * mag));
    out.hi = v3_add(out.hi, v3s(ROUNDING_PAD * mag));
    return out;
}
