/* quad.c: the parallelogram, p[0] a corner and p[1], p[2] its edges; front side along
 * edge1×edge2. The triangles' watertight test over the parallelogram's region; uniform points by
 * the affine map of [0,1)². */
#include "geom/shape_impl.h"

/* The watertight test's edge functions for the triangle (corner, corner + e1, corner + e2),
 * accepted over the parallelogram (shape_impl.h): the weights of its second and third vertices
 * are s and t. Quads sharing an edge with the same corners agree on it as triangles do, and the
 * BVH tests quads four at a time in its triangle blocks with the same float operations. */
int mc_quad_intersect(const struct prim *p, const struct ray_prep *q, struct hit *h)
{
    vec3 v[3];
    mc_prim_corners(p, v);
    return mc_watertight_intersect(v, q, 1, h);
}

struct aabb mc_quad_bounds(const struct prim *p)
{
    struct aabb b = aabb_empty();
    b = aabb_grow(b, p->p[0]);
    b = aabb_grow(b, v3_add(p->p[0], p->p[1]));
    b = aabb_grow(b, v3_add(p->p[0], p->p[2]));
    b = aabb_grow(b, v3_add(v3_add(p->p[0], p->p[1]), p->p[2]));
    return mc_shape_widen(b);
}

float mc_quad_area(const struct prim *p) { return v3_length(v3_cross(p->p[1], p->p[2])); }

float mc_quad_magnitude(const struct prim *p)
{
    return mc_shape_max_abs(p->p[0]) + mc_shape_max_abs(p->p[1]) + mc_shape_max_abs(p->p[2]);
}

vec3 mc_quad_surface(const struct prim *p, const struct ray *r, const struct hit *h, vec3 *point)
{
    (void)r;
    *point = v3_add(v3_add(p->p[0], v3_scale(p->p[1], h->u)), v3_scale(p->p[2], h->v));
    return v3_normalize(v3_cross(p->p[1], p->p[2]));
}

vec2 mc_quad_uv(const struct prim *p, const struct ray *r, const struct hit *h)
{
    (void)p;
    (void)r;
    return v2(h->u, h->v);
}

vec3 mc_quad_sample(const struct prim *p, vec2 u, vec3 *n)
{
    vec3 q = v3_add(v3_add(p->p[0], v3_scale(p->p[1], u.x)), v3_scale(p->p[2], u.y));
    *n = v3_normalize(v3_cross(p->p[1], p->p[2]));
    return q;
}

/* Default: the 2 x 2 square centred on the origin in the z = 0 plane, facing +z. */
static const struct block_param params[] = {
    {"corner", PARAM_POINT, {-1.0f, -1.0f, 0.0f}},
    {"edge1", PARAM_POINT, {2.0f, 0.0f, 0.0f}},
    {"edge2", PARAM_POINT, {0.0f, 2.0f, 0.0f}},
};

static const char *build(struct prim *p, const vec3 *v, unsigned *blame)
{
    p->p[0] = v[0];
    p->p[1] = v[1];
    p->p[2] = v[2];
    if (v3_is_zero(p->p[1]))
        return *blame = 2, "'edge1' has zero length";
    if (v3_is_zero(p->p[2]))
        return *blame = 4, "'edge2' has zero length";
    if (mc_edges_degenerate(p->p[1], p->p[2]))
        return *blame = 6, "quad edges 'edge1' and 'edge2' are parallel";
    return NULL;
}

const struct shape mc_quad_shape = {params, 3, build};
