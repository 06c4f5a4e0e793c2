/* prim.c: ray intersection, bounds, area, surface geometry and area sampling of the primitives.
 * Triangles: the watertight test of Woop, Benthin and Wald, JCGT 2(1) 2013, as in pbrt-v4;
 * disks: a plane test in double; uniform points by the concentric map (Shirley and Chiu 1997). */
#include "geom/prim.h"

#include "sample/warp.h"

/* The hit distance is accepted only if it is a number in (0, h->t). Comparing the final rounded t,
 * and nothing else, makes the outcome independent of the order in which primitives are tested, so a
 * BVH and a brute-force loop report the very same nearest hit. NaN fails both comparisons. */
static int accept(float t, const struct hit *h) { return t > 0.0f && t < h->t; }

/* (v[kx], v[ky], v[kz]) */
static vec3 permute(vec3 v, int kx, int ky, int kz)
{
    const float a[3] = {v.x, v.y, v.z};
    return v3(a[kx], a[ky], a[kz]);
}

/* The edge functions of a zero-area triangle are zero only in exact arithmetic: rounded, they can
 * pass the sign test when the ray meets the degenerate segment. Its cross product is therefore
 * checked in double, where the float vertex differences are exact and the products carry 29 more
 * bits than float. This runs only for accepted hits, not for every test. */
int mc_prim_degenerate(const struct prim *p)
{
    double ax = (double)p->p[1].x - p->p[0].x, ay = (double)p->p[1].y - p->p[0].y,
           az = (double)p->p[1].z - p->p[0].z, bx = (double)p->p[2].x - p->p[0].x,
           by = (double)p->p[2].y - p->p[0].y, bz = (double)p->p[2].z - p->p[0].z;
    return ay * bz - az * by == 0.0 && az * bx - ax * bz == 0.0 && ax * by - ay * bx == 0.0;
}

/* Woop et al. 2013: translate the vertices to the ray origin, permute and shear so that the ray
 * becomes the +z axis, then the 2D edge functions decide the hit. Triangles sharing an edge
 * compute its edge function from the same two transformed vertices, so they agree on the side the
 * ray passes (with opposite signs), and a 0 (the ray exactly on the edge) is accepted by both: no
 * ray slips between neighbours. When a float edge function is exactly 0 it is recomputed in
 * double (pbrt-v4, Triangle::Intersect), where the products are exact, so the 0 is real. */
static int intersect_triangle(const struct prim *p, const struct ray_prep *q, struct hit *h)
{
    vec3 a = permute(v3_sub(p->p[0], q->r.o), q->kx, q->ky, q->kz);
    vec3 b = permute(v3_sub(p->p[1], q->r.o), q->kx, q->ky, q->kz);
    vec3 c = permute(v3_sub(p->p[2], q->r.o), q->kx, q->ky, q->kz);
    float e0, e1, e2, det, ts, t;

    a.x += q->sx * a.z;
    a.y += q->sy * a.z;
    b.x += q->sx * b.z;
    b.y += q->sy * b.z;
    c.x += q->sx * c.z;
    c.y += q->sy * c.z;
    e0 = b.x * c.y - b.y * c.x; /* weight of p0 */
    e1 = c.x * a.y - c.y * a.x; /* weight of p1 */
    e2 = a.x * b.y - a.y * b.x; /* weight of p2 */
    /* Bitwise | and & rather than || and &&: the signs are data dependent and unpredictable, and
     * one branch per test instead of up to six halves the cost of a typical rejection. */
    if ((e0 == 0.0f) | (e1 == 0.0f) | (e2 == 0.0f)) {
        e0 = (float)((double)b.x * c.y - (double)b.y * c.x);
        e1 = (float)((double)c.x * a.y - (double)c.y * a.x);
        e2 = (float)((double)a.x * b.y - (double)a.y * b.x);
    }
    if (((e0 < 0.0f) | (e1 < 0.0f) | (e2 < 0.0f)) & ((e0 > 0.0f) | (e1 > 0.0f) | (e2 > 0.0f)))
        return 0;
    det = e0 + e1 + e2;
    if (det == 0.0f) /* degenerate triangle, or the ray lies in its plane */
        return 0;
    a.z *= q->sz;
    b.z *= q->sz;
    c.z *= q->sz;
    ts = e0 * a.z + e1 * b.z + e2 * c.z;
    /* The scaled distance must have the sign of det for t > 0; rejecting here skips the divide. */
    if (((det < 0.0f) & (ts >= 0.0f)) | ((det > 0.0f) & (ts <= 0.0f)))
        return 0;
    t = ts / det;
    if (!accept(t, h)
        || !(t > mc_tri_t_error(mc_abs_max3(a.x, b.x, c.x), mc_abs_max3(a.y, b.y, c.y),
                                mc_abs_max3(a.z, b.z, c.z), mc_abs_max3(e0, e1, e2), det))
        || mc_prim_degenerate(p))
        return 0;
    h->t = t;
    h->u = e1 / det;
    h->v = e2 / det;
    return 1;
}

/* Roots of |o + t·d − c|² = r², in double. The discriminant uses the form of Haines et al.,
 * "Precision Improvements for Ray/Sphere Intersection", Ray Tracing Gems (2019) ch. 7, eq. 10:
 * b² − ac = a·(r² − |f − (f·d/a)·d|²) with f = o − c, which does not cancel when the sphere is far
 * away or small; the roots are then c/q and q/a with q = −(b + sign(b)·√disc) (Press et al.),
 * avoiding the cancellation of −b + √disc. Double precision keeps c = |f|² − r² accurate too. */
static int intersect_sphere(const struct prim *p, const struct ray *r, struct hit *h)
{
    double rad = p->p[1].x;
    double fx = (double)r->o.x - p->p[0].x, fy = (double)r->o.y - p->p[0].y,
           fz = (double)r->o.z - p->p[0].z;
    double dx = r->d.x, dy = r->d.y, dz = r->d.z;
    double a = dx * dx + dy * dy + dz * dz, b = fx * dx + fy * dy + fz * dz;
    double lx, ly, lz, disc, c, qq, t0, t1;
    float tn, tf;
    if (!(rad > 0.0) || !(a > 0.0))
        return 0;
    lx = fx - b / a * dx;
    ly = fy - b / a * dy;
    lz = fz - b / a * dz;
    disc = a * (rad * rad - (lx * lx + ly * ly + lz * lz));
    if (!(disc >= 0.0))
        return 0;
    c = fx * fx + fy * fy + fz * fz - rad * rad;
    qq = -(b + copysign(sqrt(disc), b));
    if (qq == 0.0) /* origin on the sphere and the ray tangent to it: only the root t = 0 */
        return 0;
    t0 = c / qq;
    t1 = qq / a;
    tn = (float)fmin(t0, t1);
    tf = (float)fmax(t0, t1);
    if (accept(tn, h))
        h->t = tn;
    else if (accept(tf, h))
        h->t = tf;
    else
        return 0;
    h->u = h->v = 0.0f;
    return 1;
}

/* Plane hit, then (s, t) from the dual basis of (e1, e2): with n = e1×e2, the vectors
 * (e2×n)/|n|² and (n×e1)/|n|² have dot products δij with e1 and e2. */
static int intersect_quad(const struct prim *p, const struct ray *r, struct hit *h)
{
    vec3 e1 = p->p[1], e2 = p->p[2], n = v3_cross(e1, e2);
    float denom = v3_dot(n, r->d), n2, t, s, tt;
    vec3 w;
    if (denom == 0.0f) /* parallel ray, or a degenerate quad (n = 0) */
        return 0;
    t = v3_dot(n, v3_sub(p->p[0], r->o)) / denom;
    if (!accept(t, h))
        return 0;
    w = v3_madd(v3_sub(r->o, p->p[0]), r->d, t);
    n2 = v3_dot(n, n);
    s = v3_dot(w, v3_cross(e2, n)) / n2;
    tt = v3_dot(w, v3_cross(n, e1)) / n2;
    if (!(s >= 0.0f && s <= 1.0f && tt >= 0.0f && tt <= 1.0f))
        return 0;
    h->t = t;
    h->u = s;
    h->v = tt;
    return 1;
}

/* A disk is a plane test followed by a distance test, both in double: o − c of two floats is
 * exact there, and so the offset w = (o − c) + t·d of the hit from the centre keeps its accuracy
 * when the disk is tiny beside its distance from the ray origin or the ray grazes it (large t),
 * where float would cancel most of w's digits and move the rim. */
static int intersect_disk(const struct prim *p, const struct ray *r, struct hit *h)
{
    double nx = p->p[1].x, ny = p->p[1].y, nz = p->p[1].z, rad = p->p[2].x;
    double fx = (double)r->o.x - p->p[0].x, fy = (double)r->o.y - p->p[0].y,
           fz = (double)r->o.z - p->p[0].z;
    double denom = nx * r->d.x + ny * r->d.y + nz * r->d.z, t, wx, wy, wz;
    float tf;
    if (denom == 0.0) /* the ray is parallel to the plane (or lies in it) */
        return 0;
    t = -(nx * fx + ny * fy + nz * fz) / denom;
    tf = (float)t;
    if (!accept(tf, h))
        return 0;
    wx = fx + t * r->d.x;
    wy = fy + t * r->d.y;
    wz = fz + t * r->d.z;
    if (!(wx * wx + wy * wy + wz * wz <= rad * rad))
        return 0;
    h->t = tf;
    h->u = h->v = 0.0f;
    return 1;
}

/* The primitives whose tests need none of the per-ray constants of struct ray_prep. */
static int intersect_plain(const struct prim *p, const struct ray *r, struct hit *h)
{
    switch (p->kind) {
    case PRIM_SPHERE:
        return intersect_sphere(p, r, h);
    case PRIM_DISK:
        return intersect_disk(p, r, h);
    default:
        return intersect_quad(p, r, h);
    }
}

int mc_prim_intersect_prep(const struct prim *p, const struct ray_prep *q, struct hit *h)
{
    return p->kind == PRIM_TRIANGLE ? intersect_triangle(p, q, h) : intersect_plain(p, &q->r, h);
}

int mc_prim_intersect(const struct prim *p, const struct ray *r, struct hit *h)
{
    struct ray_prep q;
    if (p->kind != PRIM_TRIANGLE)
        return intersect_plain(p, r, h);
    mc_ray_prep(&q, r);
    return intersect_triangle(p, &q, h);
}

/* Bounds computed with float arithmetic (centre ± r, corner + e) are rounded and may lie a hair
 * inside the true surface; widening by one ulp outward keeps them conservative. */
static struct aabb widen(struct aabb b)
{
    b.lo = v3(nextafterf(b.lo.x, -INFINITY), nextafterf(b.lo.y, -INFINITY),
              nextafterf(b.lo.z, -INFINITY));
    b.hi = v3(nextafterf(b.hi.x, INFINITY), nextafterf(b.hi.y, INFINITY),
              nextafterf(b.hi.z, INFINITY));
    return b;
}

/* The tight box of a disk: its extent along axis i is r·sinθi, θi the angle between the normal
 * and the axis. sin²θi is computed as (n_j² + n_k²)/|n|², which unlike 1 − n_i² does not cancel
 * when the normal is close to the axis, in double, then rounded and widened by one ulp. */
static struct aabb disk_bounds(const struct prim *p)
{
    vec3 c = p->p[0], n = p->p[1];
    double x2 = (double)n.x * n.x, y2 = (double)n.y * n.y, z2 = (double)n.z * n.z;
    double n2 = x2 + y2 + z2, rad = fabs((double)p->p[2].x);
    double ex = rad * sqrt((y2 + z2) / n2), ey = rad * sqrt((x2 + z2) / n2),
           ez = rad * sqrt((x2 + y2) / n2);
    struct aabb b;
    b.lo = v3((float)(c.x - ex), (float)(c.y - ey), (float)(c.z - ez));
    b.hi = v3((float)(c.x + ex), (float)(c.y + ey), (float)(c.z + ez));
    return widen(b);
}

struct aabb mc_prim_bounds(const struct prim *p)
{
    struct aabb b = aabb_empty();
    vec3 r;
    switch (p->kind) {
    case PRIM_TRIANGLE:
        b = aabb_grow(aabb_grow(aabb_grow(b, p->p[0]), p->p[1]), p->p[2]);
        return b;
    case PRIM_SPHERE:
        r = v3s(fabsf(p->p[1].x));
        b.lo = v3_sub(p->p[0], r);
        b.hi = v3_add(p->p[0], r);
        return widen(b);
    case PRIM_DISK:
        return disk_bounds(p);
    default:
        b = aabb_grow(b, p->p[0]);
        b = aabb_grow(b, v3_add(p->p[0], p->p[1]));
        b = aabb_grow(b, v3_add(p->p[0], p->p[2]));
        b = aabb_grow(b, v3_add(v3_add(p->p[0], p->p[1]), p->p[2]));
        return widen(b);
    }
}

float mc_prim_area(const struct prim *p)
{
    switch (p->kind) {
    case PRIM_TRIANGLE:
        return 0.5f * v3_length(v3_cross(v3_sub(p->p[1], p->p[0]), v3_sub(p->p[2], p->p[0])));
    case PRIM_SPHERE:
        return 4.0f * MC_PI * p->p[1].x * p->p[1].x;
    case PRIM_DISK:
        return MC_PI * p->p[2].x * p->p[2].x;
    default:
        return v3_length(v3_cross(p->p[1], p->p[2]));
    }
}

/* The unnormalised front-side normal of a triangle or quad (not used for spheres and disks). */
static vec3 flat_normal(const struct prim *p)
{
    if (p->kind == PRIM_TRIANGLE)
        return v3_cross(v3_sub(p->p[1], p->p[0]), v3_sub(p->p[2], p->p[0]));
    return v3_cross(p->p[1], p->p[2]);
}

static vec3 flip(const struct prim *p, vec3 n) { return (p->flags & PRIM_FLIP) ? v3_neg(n) : n; }

/* The hit point of a disk: the offset w = (o − c) + t·d from the centre, in double as in
 * intersect_disk, projected onto the plane. The projection removes the error of t along the
 * normal, the direction in which an error would put the point on the wrong side. */
static vec3 disk_point(const struct prim *p, const struct ray *r, float t)
{
    double nx = p->p[1].x, ny = p->p[1].y, nz = p->p[1].z;
    double wx = (double)r->o.x - p->p[0].x + (double)t * r->d.x,
           wy = (double)r->o.y - p->p[0].y + (double)t * r->d.y,
           wz = (double)r->o.z - p->p[0].z + (double)t * r->d.z;
    double k = (nx * wx + ny * wy + nz * wz) / (nx * nx + ny * ny + nz * nz);
    return v3((float)(p->p[0].x + (wx - k * nx)), (float)(p->p[0].y + (wy - k * ny)),
              (float)(p->p[0].z + (wz - k * nz)));
}

static float max_abs(vec3 v) { return fmaxf(fabsf(v.x), fmaxf(fabsf(v.y), fabsf(v.z))); }

float mc_prim_point_error(const struct prim *p)
{
    float m;
    switch (p->kind) {
    case PRIM_TRIANGLE: m = fmaxf(max_abs(p->p[0]), fmaxf(max_abs(p->p[1]), max_abs(p->p[2]))); break;
    case PRIM_SPHERE: m = max_abs(p->p[0]) + fabsf(p->p[1].x); break;
    case PRIM_DISK: m = max_abs(p->p[0]) + fabsf(p->p[2].x); break;
    default: m = max_abs(p->p[0]) + max_abs(p->p[1]) + max_abs(p->p[2]); break;
    }
    return 0x1p-19f * m;
}

void mc_prim_surface(const struct prim *p, const vec3 *normals, const struct ray *r,
                     const struct hit *h, struct surface *s)
{
    float b0 = 1.0f - h->u - h->v;
    vec3 ng;
    switch (p->kind) {
    case PRIM_TRIANGLE:
        s->p = v3_add(v3_add(v3_scale(p->p[0], b0), v3_scale(p->p[1], h->u)),
                      v3_scale(p->p[2], h->v));
        ng = v3_normalize(flat_normal(p));
        break;
    case PRIM_SPHERE:
        /* Reprojecting o + t·d onto the sphere removes the error of t along the ray. */
        ng = v3_normalize(v3_sub(v3_madd(r->o, r->d, h->t), p->p[0]));
        s->p = v3_madd(p->p[0], ng, p->p[1].x);
        break;
    case PRIM_DISK:
        s->p = disk_point(p, r, h->t);
        ng = v3_normalize(p->p[1]);
        break;
    default:
        s->p = v3_add(v3_add(p->p[0], v3_scale(p->p[1], h->u)), v3_scale(p->p[2], h->v));
        ng = v3_normalize(flat_normal(p));
        break;
    }
    s->ng = flip(p, ng);
    s->ns = s->ng;
    s->err = mc_prim_point_error(p);
    if (p->kind == PRIM_TRIANGLE && p->normals >= 0) {
        const vec3 *n = normals + p->normals;
        vec3 ns = v3_add(v3_add(v3_scale(n[0], b0), v3_scale(n[1], h->u)), v3_scale(n[2], h->v));
        float len = v3_length(ns);
        if (len > 0.0f && isfinite(len)) {
            ns = flip(p, v3_scale(ns, 1.0f / len));
            /* Shading normals given against the winding describe the same surface side. */
            s->ns = v3_dot(ns, s->ng) < 0.0f ? v3_neg(ns) : ns;
        }
    }
    s->front = v3_dot(r->d, s->ng) < 0.0f;
}

vec3 mc_prim_sample_area(const struct prim *p, vec2 u, vec3 *n)
{
    vec3 q;
    switch (p->kind) {
    case PRIM_TRIANGLE: {
        vec2 b = mc_warp_triangle(u);
        q = v3_add(v3_add(v3_scale(p->p[0], 1.0f - b.x - b.y), v3_scale(p->p[1], b.x)),
                   v3_scale(p->p[2], b.y));
        *n = flip(p, v3_normalize(flat_normal(p)));
        return q;
    }
    case PRIM_SPHERE: {
        vec3 w = mc_warp_uniform_sphere(u);
        *n = flip(p, w);
        return v3_madd(p->p[0], w, p->p[1].x);
    }
    case PRIM_DISK: {
        vec2 d = mc_warp_concentric_disk(u);
        vec3 t, b, nd = v3_normalize(p->p[1]);
        float r = p->p[2].x;
        v3_basis(nd, &t, &b);
        *n = flip(p, nd);
        return v3_add(p->p[0], v3_add(v3_scale(t, r * d.x), v3_scale(b, r * d.y)));
    }
    default:
        q = v3_add(v3_add(p->p[0], v3_scale(p->p[1], u.x)), v3_scale(p->p[2], u.y));
        *n = flip(p, v3_normalize(flat_normal(p)));
        return q;
    }
}
