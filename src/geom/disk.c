/* disk.c: the disk, p[0] its centre, p[1] its unit normal (the front side) and p[2].x its radius.
 * A plane test and a distance test, both in double; uniform points by the concentric map
 * (Shirley and Chiu 1997). */
#include "geom/shape_impl.h"
#include "sample/warp.h"

/* A disk is a plane test followed by a distance test, both in double: o − c of two floats is
 * exact there, and so the offset w = (o − c) + t·d of the hit from the centre keeps its accuracy
 * when the disk is tiny beside its distance from the ray origin or the ray grazes it (large t),
 * where float would cancel most of w's digits and move the rim. */
int mc_disk_intersect(const struct prim *p, const struct ray_prep *q, struct hit *h)
{
    const struct ray *r = &q->r;
    double nx = p->p[1].x, ny = p->p[1].y, nz = p->p[1].z, rad = p->p[2].x;
    double fx = (double)r->o.x - p->p[0].x, fy = (double)r->o.y - p->p[0].y,
           fz = (double)r->o.z - p->p[0].z;
    double denom = nx * r->d.x + ny * r->d.y + nz * r->d.z, t, wx, wy, wz;
    float tf;
    if (denom == 0.0) /* the ray is parallel to the plane (or lies in it) */
        return 0;
    t = -(nx * fx + ny * fy + nz * fz) / denom;
    tf = (float)t;
    if (!mc_shape_accept(tf, h))
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

/* The tight box of a disk: its extent along axis i is r·sinθi, θi the angle between the normal
 * and the axis. sin²θi is computed as (n_j² + n_k²)/|n|², which unlike 1 − n_i² does not cancel
 * when the normal is close to the axis, in double, then rounded and widened by one ulp. */
struct aabb mc_disk_bounds(const struct prim *p)
{
    vec3 c = p->p[0], n = p->p[1];
    double x2 = (double)n.x * n.x, y2 = (double)n.y * n.y, z2 = (double)n.z * n.z;
    double n2 = x2 + y2 + z2, rad = fabs((double)p->p[2].x);
    double ex = rad * sqrt((y2 + z2) / n2), ey = rad * sqrt((x2 + z2) / n2),
           ez = rad * sqrt((x2 + y2) / n2);
    struct aabb b;
    b.lo = v3((float)(c.x - ex), (float)(c.y - ey), (float)(c.z - ez));
    b.hi = v3((float)(c.x + ex), (float)(c.y + ey), (float)(c.z + ez));
    return mc_shape_widen(b);
}

float mc_disk_area(const struct prim *p) { return MC_PI * p->p[2].x * p->p[2].x; }

float mc_disk_magnitude(const struct prim *p)
{
    return mc_shape_max_abs(p->p[0]) + fabsf(p->p[2].x);
}

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

vec3 mc_disk_surface(const struct prim *p, const struct ray *r, const struct hit *h, vec3 *point)
{
    *point = disk_point(p, r, h->t);
    return v3_normalize(p->p[1]);
}

/* Planar, in the frame of the disk's area samples (mc_disk_sample). */
vec2 mc_disk_uv(const struct prim *p, const struct ray *r, const struct hit *h)
{
    vec3 t, b, w = v3_sub(disk_point(p, r, h->t), p->p[0]);
    float k = 0.5f / p->p[2].x;
    v3_basis(v3_normalize(p->p[1]), &t, &b);
    return v2(0.5f + k * v3_dot(w, t), 0.5f + k * v3_dot(w, b));
}

vec3 mc_disk_sample(const struct prim *p, vec2 u, vec3 *n)
{
    vec2 d = mc_warp_concentric_disk(u);
    vec3 t, b, nd = v3_normalize(p->p[1]);
    float r = p->p[2].x;
    v3_basis(nd, &t, &b);
    *n = nd;
    return v3_add(p->p[0], v3_add(v3_scale(t, r * d.x), v3_scale(b, r * d.y)));
}

/* Default: the unit disk at the origin facing +z, like the quad and the triangle. */
static const struct block_param params[] = {
    {"center", PARAM_POINT, {0.0f, 0.0f, 0.0f}},
    {"normal", PARAM_DIRECTION, {0.0f, 0.0f, 1.0f}},
    {"radius", PARAM_LENGTH, {1.0f, 0.0f, 0.0f}},
};

static const char *build(struct prim *p, const vec3 *v, unsigned *blame)
{
    (void)blame;
    p->p[0] = v[0];
    p->p[1] = v[1];
    p->p[2] = v3(v[2].x, 0.0f, 0.0f);
    return NULL;
}

const struct shape mc_disk_shape = {params, 3, build};
