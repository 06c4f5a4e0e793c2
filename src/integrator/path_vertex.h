/* path_vertex.h: what a camera path does at a vertex, shared by the path tracer (path.c, which
 * compiles it once per feature set F) and photon mapping's camera pass (sppm.c, which passes its
 * features at run time): the ray queries by feature, the power heuristic, and one light sample of
 * next-event estimation. */
#ifndef MCRT_PATH_VERTEX_H
#define MCRT_PATH_VERTEX_H

#include <math.h>

#include "bsdf/bsdf.h"
#include "scene/features.h"
#include "scene/scene.h"

/* Veach's power heuristic with β = 2 for the strategy with pdf a against one with pdf b, each pdf
 * already multiplied by its number of samples (Veach 1997, eq. 9.13). */
static inline float power_heuristic(float a, float b)
{
    float a2 = a * a, b2 = b * b;
    if (isinf(a2))
        return 1.0f;
    return a2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

/* Ray queries: a static scene asks the static BVH alone, and surfaces need no motion. Where F is
 * a constant (path.c's instantiations), these branches are resolved at compile time. */
static inline int trace(const struct scene *s, const struct ray *r, struct hit *h, unsigned F)
{
    return F & FEATURE_MOTION ? mc_scene_intersect(s, r, h) : mc_bvh_intersect(&s->bvh, s->prims, r, h);
}
static inline int occluded(const struct scene *s, const struct ray *r, unsigned F)
{
    return F & FEATURE_MOTION ? mc_scene_occluded(s, r) : mc_bvh_occluded(&s->bvh, s->prims, r);
}
static inline void surface(const struct scene *s, const struct ray *r, const struct hit *h,
                           struct surface *sf, unsigned F)
{
    if (F & FEATURE_MOTION)
        mc_scene_surface(s, r, h, sf);
    else
        mc_prim_surface(&s->prims[h->prim], s->normals, r, h, sf);
}

/* The BSDF at a hit on pr (= s->prims[h->prim], which the caller has at hand: looked up again
 * here, it cost the untextured path tracer 0.1% more instructions): with its textures only when
 * the scene has some (F: FEATURE_TEXTURES). */
static inline void bsdf_at(const struct scene *s, const struct ray *r, const struct hit *h,
                           const struct prim *pr, struct bsdf *b, unsigned F)
{
    if (F & FEATURE_TEXTURES)
        mc_scene_bsdf(s, r, h, b);
    else
        mc_bsdf_init(b, &s->materials[pr->material]);
}

/* Whether wo and wi (world directions) lie on the two geometric sides of a surface that only
 * reflects. The BSDF sees them in the shading frame, where both can be above the horizon when
 * the shading normal leans away from the geometric one: light would then pass through an
 * opaque surface (a shadow ray spawned on the far side is not stopped by it; a reflected ray
 * leaves through it). Such pairs carry nothing, for light and camera paths alike (pbrt-v3
 * BSDF::f and Sample_f test the same with the geometric normal; Veach 1997 §5.3). */
static inline int through_surface(const struct bsdf *b, vec3 ng, vec3 wo, vec3 wi)
{
    return !(v3_dot(wo, ng) * v3_dot(wi, ng) > 0.0f) && !mc_bsdf_transmits(b);
}

/* The MIS weight of emission from `light` that a BSDF sample of pdf bsdf_pdf from the shading
 * point at found along r (at distance t on surface sf; the environment: INFINITY, NULL), against
 * the n_samples light samples there: the light's selection pmf at that same point (the one its
 * light samples chose with, light/select.h) times its solid-angle pdf. */
static inline float emitted_mis_weight(const struct scene *s, int n_samples, int light,
                                       struct light_select_at *at, float bsdf_pdf,
                                       const struct ray *r, float t, const struct surface *sf)
{
    vec3 p = v3((float)at->p[0], (float)at->p[1], (float)at->p[2]); /* exact: made from floats */
    float light_pdf = (float)mc_light_select_pmf(&s->light_select, at, light)
                      * mc_light_pdf(&s->light_scene, &s->lights[light], p, r->time, r->d, t, sf);
    return power_heuristic(bsdf_pdf, (float)n_samples * light_pdf);
}

/* One shadow ray of next-event estimation, one of n: a light chosen for sf's point and shading
 * normal, at (light/select.h), a point on it, weighted against BSDF sampling when mis is nonzero
 * (and the light is not a delta light). Returns the contribution before the path throughput. */
static inline vec3 light_sample(const struct scene *s, const struct surface *sf,
                                struct light_select_at *at, float time, const frame *fr,
                                const struct bsdf *b, vec3 wo, struct sampler *smp,
                                uint64_t *rays, int n, unsigned F, int mis)
{
    struct light_sample ls;
    struct ray shadow;
    double pmf;
    float light_pdf, weight;
    vec3 wi, f, target;
    /* With one light there is nothing to choose: its draw would be a sampler dimension spent. */
    double u_light = s->light_count > 1 ? mc_sampler_1d_double(smp) : 0.5;
    int li = mc_light_select_sample(&s->light_select, at, u_light, &pmf);
    vec2 u = mc_sampler_2d(smp);
    if (li < 0 || !mc_light_sample(&s->light_scene, &s->lights[li], sf->p, time, u, &ls)
        || v3_is_zero(ls.L) || through_surface(b, sf->ng, frame_to_world(fr, wo), ls.wi))
        return v3s(0.0f);
    wi = frame_to_local(fr, ls.wi);
    f = v3_scale(mc_bsdf_eval(b, wo, wi, MC_RADIANCE), fabsf(wi.z));
    if (v3_is_zero(f))
        return v3s(0.0f);
    shadow.o = ray_spawn(sf->p, side_normal(sf->ng, ls.wi), sf->err);
    shadow.time = time;
    if (isinf(ls.dist)) {
        shadow.d = ls.wi;
        shadow.tmax = INFINITY;
    } else {
        /* Aim at the light point moved off its own surface, so that the light itself never
         * occludes the segment. */
        target = v3_is_zero(ls.normal)
                     ? ls.point
                     : ray_spawn(ls.point, ls.normal, s->lights[li].point_error);
        shadow.d = v3_sub(target, shadow.o);
        shadow.tmax = v3_length(shadow.d);
        if (!(shadow.tmax > 0.0f))
            return v3s(0.0f);
        shadow.d = v3_scale(shadow.d, 1.0f / shadow.tmax);
    }
    ++*rays;
    if (occluded(s, &shadow, F))
        return v3s(0.0f);
    light_pdf = (float)pmf * ls.pdf;
    weight = !mis || ls.delta ? 1.0f
                              : power_heuristic((float)n * light_pdf, mc_bsdf_pdf(b, wo, wi));
    return v3_scale(v3_mul(f, ls.L), weight / ((float)n * light_pdf));
}

#endif
