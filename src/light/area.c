/* area.c: area lights, one per emitting primitive (made by scene/prepare.c, no block of their
 * own). Sampled by area (quads, disks, triangles) converted to solid angle with dist²/|cos θl|,
 * spheres by the cone they subtend (pbrt-v4, Sphere::Sample, after Shirley and Wang 1996). A
 * moving emitter is sampled in its time-0 frame (geom/motion.h). */
#include "light/light_impl.h"
#include "sample/warp.h"

double mc_area_light_power(const struct light_scene *s, const struct light *l)
{
    const struct prim *p = &s->prims[l->prim];
    float sides = (p->flags & PRIM_TWO_SIDED) ? 2.0f : 1.0f;
    return MC_PI * sides * l->area * v3_avg(p->emit);
}

/* A planar emitter's normals are all its front normal (flip applied), which sampling any point
 * gives; a sphere's point every way, and so do a moving emitter's, whose rotation over the shutter
 * is not bounded here. */
int mc_area_light_bounds(const struct light_scene *s, const struct light *l, struct light_bounds *b)
{
    const struct prim *p = &s->prims[l->prim];
    b->box = mc_prim_bounds(p);
    b->axis = v3(0.0f, 0.0f, 1.0f);
    b->cos_o = -1.0f;
    b->cos_e = 0.0f;
    b->two_sided = (p->flags & PRIM_TWO_SIDED) != 0;
    if (p->kind == PRIM_SPHERE)
        b->phi = MC_PI * MC_PI * p->p[1].x * p->p[1].x * v3_avg(p->emit);
    else {
        b->phi = MC_PI * l->area * v3_avg(p->emit);
        mc_prim_sample_area(p, v2(0.5f, 0.5f), &b->axis);
        b->cos_o = 1.0f;
    }
    if (p->motion) {
        b->box = mc_motion_bounds(&s->motions[p->motion - 1], b->box, s->shutter[0], s->shutter[1]);
        b->cos_o = -1.0f;
    }
    return 1;
}

/* Whether light leaves primitive p's surface with front normal n toward direction w. */
static int emits_toward(const struct prim *p, vec3 n, vec3 w)
{
    return (p->flags & PRIM_TWO_SIDED) || v3_dot(n, w) > 0.0f;
}

/* Sphere seen from outside: sample the cone of directions it subtends. The sampled point is
 * found from the angle α at the centre (pbrt-v4 eq. 6.13 ff.), which stays accurate for tiny or
 * far spheres where intersecting the sampled ray would not. 1 − cos θmax is computed as
 * sin²θmax / (1 + cos θmax) to keep precision when the cone is tiny. */
static int sample_sphere_cone(const struct prim *pr, vec3 p, vec2 u, struct light_sample *out)
{
    vec3 c = pr->p[0], to_c = v3_sub(c, p);
    float r = pr->p[1].x, d2 = v3_length2(to_c), d = sqrtf(d2);
    float sin2_max = r * r / d2, sin_max = sqrtf(sin2_max);
    float cos_max = sqrtf(f_max(0.0f, 1.0f - sin2_max));
    float omc = sin2_max / (1.0f + cos_max);            /* 1 − cos θmax */
    float one_minus_cos = u.x * omc;                    /* 1 − cos θ */
    float cos_t = 1.0f - one_minus_cos;
    float sin2_t = one_minus_cos * (2.0f - one_minus_cos);
    float cos_a = sin2_t / sin_max + cos_t * sqrtf(f_max(0.0f, 1.0f - sin2_t / sin2_max));
    float sin_a = sqrtf(f_max(0.0f, 1.0f - cos_a * cos_a));
    float phi = 2.0f * MC_PI * u.y;
    frame f = frame_from_normal(v3_scale(to_c, 1.0f / d));
    vec3 n = frame_to_world(&f, v3(-sin_a * cosf(phi), -sin_a * sinf(phi), -cos_a));
    vec3 front = (pr->flags & PRIM_FLIP) ? v3_neg(n) : n;
    vec3 q = v3_madd(c, n, r), w = v3_sub(q, p);
    float dist = v3_length(w);
    if (!(dist > 0.0f) || !emits_toward(pr, front, v3_neg(w)))
        return 0;
    out->point = q;
    out->normal = n;
    out->wi = v3_scale(w, 1.0f / dist);
    out->dist = dist;
    out->pdf = 1.0f / (2.0f * MC_PI * omc);
    out->L = pr->emit;
    out->delta = 0;
    return 1;
}

/* Whether p is clearly outside sphere pr, so that the cone it subtends can be sampled. Points on
 * the sphere itself (shading points of the light's own surface, whose distance to the centre is
 * r within rounding) and inside it are sampled by area instead, which is valid everywhere. Both
 * the sampler and the pdf use this one test, so they always agree. */
static int sphere_cone_applies(const struct prim *pr, vec3 p)
{
    float r2 = pr->p[1].x * pr->p[1].x;
    return v3_length2(v3_sub(p, pr->p[0])) > r2 * (1.0f + 1e-3f);
}

static int sample_area(const struct light *l, const struct prim *pr, vec3 p, vec2 u,
                       struct light_sample *out)
{
    vec3 n, q, w;
    float dist2, dist, cos_l;
    if (pr->kind == PRIM_SPHERE && sphere_cone_applies(pr, p))
        return sample_sphere_cone(pr, p, u, out);
    q = mc_prim_sample_area(pr, u, &n);
    w = v3_sub(q, p);
    dist2 = v3_length2(w);
    dist = sqrtf(dist2);
    if (!(dist > 0.0f))
        return 0;
    w = v3_scale(w, 1.0f / dist);
    cos_l = fabsf(v3_dot(n, w));
    if (!(cos_l > 0.0f) || !emits_toward(pr, n, v3_neg(w)))
        return 0;
    out->point = q;
    out->normal = v3_dot(n, w) < 0.0f ? n : v3_neg(n);
    out->wi = w;
    out->dist = dist;
    out->pdf = dist2 / (cos_l * l->area);
    out->L = pr->emit;
    out->delta = 0;
    return isfinite(out->pdf);
}

/* A moving emitter's map from its time-0 frame to the world at `time` (and 1), or 0 for a static
 * one. Rigid maps preserve distances and angles, hence solid angles: the emitter is sampled, and
 * its pdf evaluated, in its time-0 frame with the shading point carried there, and the pdfs hold
 * unchanged in the world. */
static int light_frame(const struct light_scene *s, const struct prim *pr, float time,
                       struct rigid *x)
{
    if (pr->motion == 0)
        return 0;
    mc_motion_at(&s->motions[pr->motion - 1], time, x);
    return 1;
}

int mc_area_light_sample(const struct light_scene *s, const struct light *l, vec3 p, float time,
                         vec2 u, struct light_sample *out)
{
    const struct prim *pr = &s->prims[l->prim];
    struct rigid x;
    int moving = light_frame(s, pr, time, &x);
    if (!sample_area(l, pr, moving ? rigid_inv_point(&x, p) : p, u, out))
        return 0;
    if (moving) {
        out->wi = rigid_vector(&x, out->wi);
        out->point = rigid_point(&x, out->point);
        out->normal = rigid_vector(&x, out->normal);
    }
    return 1;
}

float mc_area_light_pdf(const struct light_scene *s, const struct light *l, vec3 p, float time,
                        vec3 wi, float t, const struct surface *sf)
{
    const struct prim *pr = &s->prims[l->prim];
    struct rigid x;
    float cos_l;
    /* The cone depends on where p is relative to the sphere: in its time-0 frame. The area pdf
     * depends only on t and on the angle between sf->ng and wi, which are given in the world and
     * are the same in either frame. */
    if (pr->kind == PRIM_SPHERE && light_frame(s, pr, time, &x))
        p = rigid_inv_point(&x, p);
    if (pr->kind == PRIM_SPHERE && sphere_cone_applies(pr, p)) {
        float sin2_max = pr->p[1].x * pr->p[1].x / v3_length2(v3_sub(p, pr->p[0]));
        float cos_max = sqrtf(f_max(0.0f, 1.0f - sin2_max));
        return (1.0f + cos_max) / (2.0f * MC_PI * sin2_max);
    }
    cos_l = fabsf(v3_dot(sf->ng, wi));
    if (!(cos_l > 0.0f))
        return 0.0f;
    return t * t / (cos_l * l->area);
}

/* A point uniform by area (pdf 1/A) and a cosine-weighted direction about the normal of the side
 * it leaves (a two-sided emitter picks the side with u_dir.x), so that every photon of a one-sided
 * emitter carries π·A·Le (two-sided: 2π·A·Le), the light's power. */
int mc_area_light_emission(const struct light_scene *s, const struct light *l, float time,
                           vec2 u_pos, vec2 u_dir, struct light_emission *out)
{
    const struct prim *pr = &s->prims[l->prim];
    struct rigid x;
    vec3 n, local;
    frame f;
    float area = l->area, sides = 1.0f;
    out->p = mc_prim_sample_area(pr, u_pos, &n);
    if (pr->flags & PRIM_TWO_SIDED) {
        sides = 2.0f;
        if (u_dir.x < 0.5f) {
            u_dir.x *= 2.0f;
        } else {
            u_dir.x = 2.0f * u_dir.x - 1.0f;
            n = v3_neg(n);
        }
        u_dir.x = fminf(u_dir.x, 0x1.fffffep-1f);
    }
    if (light_frame(s, pr, time, &x)) {
        out->p = rigid_point(&x, out->p);
        n = rigid_vector(&x, n);
    }
    f = frame_from_normal(n);
    local = mc_warp_cosine_hemisphere(u_dir);
    out->n = n;
    out->d = v3_normalize(frame_to_world(&f, local));
    out->Le = pr->emit;
    out->pdf_pos = 1.0f / area;
    out->pdf_dir = mc_warp_cosine_hemisphere_pdf(local.z) / sides;
    if (!(out->pdf_dir > 0.0f) || !(area > 0.0f))
        return 0;
    out->weight = v3_scale(pr->emit, MC_PI * sides * area);
    return 1;
}

vec3 mc_light_emitted(const struct prim *pr, const struct surface *sf)
{
    if (v3_is_zero(pr->emit) || !(sf->front || (pr->flags & PRIM_TWO_SIDED)))
        return v3s(0.0f);
    return pr->emit;
}

const struct light_desc mc_area_light = {NULL, 0, 0, NULL, 0, NULL};
