/* triangle.c: the triangle, vertices p[0..2]; front side along (p1−p0)×(p2−p0). The watertight
 * test of Woop, Benthin and Wald, JCGT 2(1) 2013, as in pbrt-v4 (the BVH's 4-wide form is in
 * bvh.c, over the blocks of tri4.c), which the quad shares; uniform points by mc_warp_triangle. Meshes are triangles
 * with shading normals (prim.normals), interpolated in prim.c. */
#include "geom/shape_impl.h"
#include "sample/warp.h"

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
static int collinear(const vec3 *v)
{
    double ax = (double)v[1].x - v[0].x, ay = (double)v[1].y - v[0].y,
           az = (double)v[1].z - v[0].z, bx = (double)v[2].x - v[0].x,
           by = (double)v[2].y - v[0].y, bz = (double)v[2].z - v[0].z;
    return ay * bz - az * by == 0.0 && az * bx - ax * bz == 0.0 && ax * by - ay * bx == 0.0;
}

int mc_prim_degenerate(const struct prim *p)
{
    vec3 v[3];
    mc_prim_corners(p, v);
    return collinear(v);
}

/* Woop et al. 2013: translate the vertices to the ray origin, permute and shear so that the ray
 * becomes the +z axis, then the 2D edge functions decide the hit. Triangles sharing an edge
 * compute its edge function from the same two transformed vertices, so they agree on the side the
 * ray passes (with opposite signs), and a 0 (the ray exactly on the edge) is accepted by both: no
 * ray slips between neighbours. When a float edge function is exactly 0 it is recomputed in
 * double (pbrt-v4, Triangle::Intersect), where the products are exact, so the 0 is real. */
int mc_watertight_intersect(const vec3 *v, const struct ray_prep *q, int parallelogram,
                            struct hit *h)
{
    vec3 a = permute(v3_sub(v[0], q->r.o), q->kx, q->ky, q->kz);
    vec3 b = permute(v3_sub(v[1], q->r.o), q->kx, q->ky, q->kz);
    vec3 c = permute(v3_sub(v[2], q->r.o), q->kx, q->ky, q->kz);
    float e0, e1, e2, det, ts, t;

    a.x += q->sx * a.z;
    a.y += q->sy * a.z;
    b.x += q->sx * b.z;
    b.y += q->sy * b.z;
    c.x += q->sx * c.z;
    c.y += q->sy * c.z;
    e0 = b.x * c.y - b.y * c.x; /* weight of v0 */
    e1 = c.x * a.y - c.y * a.x; /* weight of v1 */
    e2 = a.x * b.y - a.y * b.x; /* weight of v2 */
    /* Bitwise | and & rather than || and &&: the signs are data dependent and unpredictable, and
     * one branch per test instead of up to six halves the cost of a typical rejection. */
    if ((e0 == 0.0f) | (e1 == 0.0f) | (e2 == 0.0f)) {
        e0 = (float)((double)b.x * c.y - (double)b.y * c.x);
        e1 = (float)((double)c.x * a.y - (double)c.y * a.x);
        e2 = (float)((double)a.x * b.y - (double)a.y * b.x);
    }
    det = e0 + e1 + e2;
    if (parallelogram) {
        /* s = e1/det and t = e2/det in [0, 1]: e1 and e2 of det's sign (or 0), at most |det|;
         * e0, the weight of v0, is 1 - s - t and free. */
        if (((det < 0.0f) & ((e1 > 0.0f) | (e2 > 0.0f)))
            | ((det > 0.0f) & ((e1 < 0.0f) | (e2 < 0.0f)))
            | (fabsf(e1) > fabsf(det)) | (fabsf(e2) > fabsf(det)))
            return 0;
    } else if (((e0 < 0.0f) | (e1 < 0.0f) | (e2 < 0.0f))
               & ((e0 > 0.0f) | (e1 > 0.0f) | (e2 > 0.0f))) {
        return 0;
    }
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
    if (!mc_shape_accept(t, h)
        || !(t > mc_tri_t_error(mc_abs_max3(a.x, b.x, c.x), mc_abs_max3(a.y, b.y, c.y),
                                mc_abs_max3(a.z, b.z, c.z), mc_abs_max3(e0, e1, e2), det))
        || collinear(v))
        return 0;
    h->t = t;
    h->u = e1 / det;
    h->v = e2 / det;
    return 1;
}

int mc_triangle_intersect(const struct prim *p, const struct ray_prep *q, struct hit *h)
{
    return mc_watertight_intersect(p->p, q, 0, h);
}

struct aabb mc_triangle_bounds(const struct prim *p)
{
    return aabb_grow(aabb_grow(aabb_grow(aabb_empty(), p->p[0]), p->p[1]), p->p[2]);
}

/* The unnormalised front-side normal. */
static vec3 normal(const struct prim *p)
{
    return v3_cross(v3_sub(p->p[1], p->p[0]), v3_sub(p->p[2], p->p[0]));
}

float mc_triangle_area(const struct prim *p) { return 0.5f * v3_length(normal(p)); }

float mc_triangle_magnitude(const struct prim *p)
{
    return fmaxf(mc_shape_max_abs(p->p[0]),
                 fmaxf(mc_shape_max_abs(p->p[1]), mc_shape_max_abs(p->p[2])));
}

vec3 mc_triangle_surface(const struct prim *p, const struct ray *r, const struct hit *h,
                         vec3 *point)
{
    float b0 = 1.0f - h->u - h->v;
    (void)r;
    *point = v3_add(v3_add(v3_scale(p->p[0], b0), v3_scale(p->p[1], h->u)),
                    v3_scale(p->p[2], h->v));
    return v3_normalize(normal(p));
}

/* A mesh triangle's own coordinates are prim.c's (mc_prim_uv). */
vec2 mc_triangle_uv(const struct prim *p, const struct ray *r, const struct hit *h)
{
    (void)p;
    (void)r;
    return v2(h->u, h->v);
}

vec3 mc_triangle_sample(const struct prim *p, vec2 u, vec3 *n)
{
    vec2 b = mc_warp_triangle(u);
    vec3 q = v3_add(v3_add(v3_scale(p->p[0], 1.0f - b.x - b.y), v3_scale(p->p[1], b.x)),
                    v3_scale(p->p[2], b.y));
    *n = v3_normalize(normal(p));
    return q;
}

/* Default: (-1,-1,0), (1,-1,0), (0,1,0), facing +z. */
static const struct block_param params[] = {
    {"v0", PARAM_POINT, {-1.0f, -1.0f, 0.0f}},
    {"v1", PARAM_POINT, {1.0f, -1.0f, 0.0f}},
    {"v2", PARAM_POINT, {0.0f, 1.0f, 0.0f}},
};

static const char *build(struct prim *p, const vec3 *v, unsigned *blame)
{
    p->p[0] = v[0];
    p->p[1] = v[1];
    p->p[2] = v[2];
    if (mc_edges_degenerate(v3_sub(p->p[1], p->p[0]), v3_sub(p->p[2], p->p[0])))
        return *blame = 7, "triangle has zero area (its vertices are collinear)";
    return NULL;
}

const struct shape mc_triangle_shape = {params, 3, build};
