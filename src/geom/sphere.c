/* sphere.c: the sphere, p[0] its centre and p[1].x its radius; front side outward. Intersection
 * in double after Haines et al. (Ray Tracing Gems, 2019, ch. 7); uniform points on it by
 * mc_warp_uniform_sphere. (Its light sampling by the subtended cone is in light/light.c.) */
#include "geom/shape_impl.h"
#include "sample/warp.h"

/* Roots of |o + t·d − c|² = r², in double. The discriminant uses the form of Haines et al.,
 * "Precision Improvements for Ray/Sphere Intersection", Ray Tracing Gems (2019) ch. 7, eq. 10:
 * b² − ac = a·(r² − |f − (f·d/a)·d|²) with f = o − c, which does not cancel when the sphere is far
 * away or small; the roots are then c/q and q/a with q = −(b + sign(b)·√disc) (Press et al.),
 * avoiding the cancellation of −b + √disc. Double precision keeps c = |f|² − r² accurate too. */
int mc_sphere_intersect(const struct prim *p, const struct ray_prep *q, struct hit *h)
{
    const struct ray *r = &q->r;
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
    /* t0 and t1 are finite (qq and a are not 0): a comparison, where libm's fmin is a call. */
    tn = (float)(t0 < t1 ? t0 : t1);
    tf = (float)(t0 < t1 ? t1 : t0);
    if (mc_shape_accept(tn, h))
        h->t = tn;
    else if (mc_shape_accept(tf, h))
        h->t = tf;
    else
        return 0;
    h->u = h->v = 0.0f;
    return 1;
}

struct aabb mc_sphere_bounds(const struct prim *p)
{
    vec3 r = v3s(fabsf(p->p[1].x));
    struct aabb b;
    b.lo = v3_sub(p->p[0], r);
    b.hi = v3_add(p->p[0], r);
    return mc_shape_widen(b);
}

float mc_sphere_area(const struct prim *p) { return 4.0f * MC_PI * p->p[1].x * p->p[1].x; }

float mc_sphere_magnitude(const struct prim *p)
{
    return mc_shape_max_abs(p->p[0]) + fabsf(p->p[1].x);
}

/* Reprojecting o + t·d onto the sphere removes the error of t along the ray. */
vec3 mc_sphere_surface(const struct prim *p, const struct ray *r, const struct hit *h, vec3 *point)
{
    vec3 ng = v3_normalize(v3_sub(v3_madd(r->o, r->d, h->t), p->p[0]));
    *point = v3_madd(p->p[0], ng, p->p[1].x);
    return ng;
}

/* The environment map's longitude (light/envmap.c) and the latitude from the south pole of the
 * outward direction, as mc_sphere_surface finds it; θ by atan2 rather than acos(y), which says
 * little about θ near the poles. */
vec2 mc_sphere_uv(const struct prim *p, const struct ray *r, const struct hit *h)
{
    vec3 d = v3_normalize(v3_sub(v3_madd(r->o, r->d, h->t), p->p[0]));
    return v2(atan2f(d.x, -d.z) * (0.5f / MC_PI) + 0.5f,
              1.0f - atan2f(sqrtf(d.x * d.x + d.z * d.z), d.y) * (1.0f / MC_PI));
}

vec3 mc_sphere_sample(const struct prim *p, vec2 u, vec3 *n)
{
    vec3 w = mc_warp_uniform_sphere(u);
    *n = w;
    return v3_madd(p->p[0], w, p->p[1].x);
}

static const struct block_param params[] = {
    {"center", PARAM_POINT, {0.0f, 0.0f, 0.0f}},
    {"radius", PARAM_LENGTH, {1.0f, 0.0f, 0.0f}},
};

static const char *build(struct prim *p, const vec3 *v, unsigned *blame)
{
    (void)blame;
    p->p[0] = v[0];
    p->p[1] = v3(v[1].x, 0.0f, 0.0f);
    return NULL;
}

const struct shape mc_sphere_shape = {params, 2, build};
