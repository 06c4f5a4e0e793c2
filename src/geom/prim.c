/* prim.c: the primitives' interface over the shapes of MC_SHAPES: a switch over the kind that
 * calls the shape's own function (src/geom/NAME.c), and what every shape shares: the flip, the
 * interpolated shading normals and texture coordinates of mesh triangles, the point error and the table of descriptors.
 * A switch rather than an array of function pointers: it compiles to a jump table of tail calls,
 * and the BVH's leaves call mc_prim_intersect_prep once per primitive they test. */
#include "geom/prim.h"

#include "geom/shape_impl.h"

#define X(kind, name) [kind] = &mc_##name##_shape,
const struct shape *const mc_shapes[PRIM_KIND_COUNT] = {MC_SHAPES(X)};
#undef X
const char *const mc_shape_names[PRIM_KIND_COUNT + 1] = {MC_SHAPES(MC_NAMES_IDENT)
                                                         [PRIM_KIND_COUNT] = NULL};

int mc_prim_intersect_prep(const struct prim *p, const struct ray_prep *q, struct hit *h)
{
    switch (p->kind) {
#define X(kind, name) case kind: return mc_##name##_intersect(p, q, h);
        MC_SHAPES(X)
#undef X
    }
    return 0;
}

int mc_prim_intersect(const struct prim *p, const struct ray *r, struct hit *h)
{
    struct ray_prep q;
    mc_ray_prep(&q, r);
    return mc_prim_intersect_prep(p, &q, h);
}

struct aabb mc_prim_bounds(const struct prim *p)
{
    switch (p->kind) {
#define X(kind, name) case kind: return mc_##name##_bounds(p);
        MC_SHAPES(X)
#undef X
    }
    return aabb_empty();
}

float mc_prim_area(const struct prim *p)
{
    switch (p->kind) {
#define X(kind, name) case kind: return mc_##name##_area(p);
        MC_SHAPES(X)
#undef X
    }
    return 0.0f;
}

float mc_prim_point_error(const struct prim *p)
{
    float m = 0.0f;
    switch (p->kind) {
#define X(kind, name) case kind: m = mc_##name##_magnitude(p); break;
        MC_SHAPES(X)
#undef X
    }
    return 0x1p-19f * m;
}

static vec3 flip(const struct prim *p, vec3 n) { return (p->flags & PRIM_FLIP) ? v3_neg(n) : n; }

void mc_prim_surface(const struct prim *p, const vec3 *normals, const struct ray *r,
                     const struct hit *h, struct surface *s)
{
    vec3 ng = v3s(0.0f);
    switch (p->kind) {
#define X(kind, name) case kind: ng = mc_##name##_surface(p, r, h, &s->p); break;
        MC_SHAPES(X)
#undef X
    }
    s->ng = flip(p, ng);
    s->ns = s->ng;
    s->err = mc_prim_point_error(p);
    /* Mesh triangles: the shading normals at the vertices, interpolated by the barycentrics. */
    if (p->kind == PRIM_TRIANGLE && p->normals >= 0) {
        const vec3 *n = normals + p->normals;
        float b0 = 1.0f - h->u - h->v;
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

vec2 mc_prim_uv(const struct prim *p, const vec2 *uvs, const struct ray *r, const struct hit *h)
{
    /* Mesh triangles: the corners' coordinates, interpolated by the barycentrics. */
    if (p->kind == PRIM_TRIANGLE && p->normals >= 0 && uvs) {
        const vec2 *t = uvs + p->normals;
        float b0 = 1.0f - h->u - h->v;
        return v2(b0 * t[0].x + h->u * t[1].x + h->v * t[2].x,
                  b0 * t[0].y + h->u * t[1].y + h->v * t[2].y);
    }
    switch (p->kind) {
#define X(kind, name) case kind: return mc_##name##_uv(p, r, h);
        MC_SHAPES(X)
#undef X
    }
    return v2(0.0f, 0.0f);
}

vec3 mc_prim_sample_area(const struct prim *p, vec2 u, vec3 *n)
{
    vec3 q = v3s(0.0f);
    *n = v3s(0.0f);
    switch (p->kind) {
#define X(kind, name) case kind: q = mc_##name##_sample(p, u, n); break;
        MC_SHAPES(X)
#undef X
    }
    *n = flip(p, *n);
    return q;
}

int mc_edges_degenerate(vec3 e1, vec3 e2)
{
    double ax = e1.x, ay = e1.y, az = e1.z, bx = e2.x, by = e2.y, bz = e2.z;
    double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    double c2 = cx * cx + cy * cy + cz * cz;
    double l2 = (ax * ax + ay * ay + az * az) * (bx * bx + by * by + bz * bz);
    /* The renderer computes the normal in float: it must not underflow to zero there either.
     * Written as !(a > b) so that a NaN (from an infinite edge) also counts as degenerate. */
    return !(c2 > 1e-12 * l2) || !(v3_length2(v3_cross(e1, e2)) > 0.0f);
}

