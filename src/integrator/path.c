/* path.c: the path tracer, after pbrt-v4's PathIntegrator::Li, compiled once per combination
 * of the features that change its code (scene/features.h); and the integrators that are the path
 * tracer with fixed parameters: direct, and the strategies mis, bsdf and light. */
#include "integrator/integrator.h"

#include <limits.h>

#include "integrator/path_vertex.h"

/* Next-event estimation at a non-delta surface, the shading point at: the mean of
 * `light_samples` shadow rays. */
static inline vec3 sample_direct(const struct scene *s, const struct integrator_desc *cfg,
                                 const struct surface *sf, struct light_select_at *at, float time,
                                 const frame *fr, const struct bsdf *b, vec3 wo,
                                 struct sampler *smp, uint64_t *rays, unsigned F)
{
    vec3 L = v3s(0.0f);
    int i, n = F & FEATURE_LIGHT_SAMPLES ? cfg->light_samples : 1;
    for (i = 0; i < n; i++)
        L = v3_add(L, light_sample(s, sf, at, time, fr, b, wo, smp, rays, n, F,
                                   mc_features_need_mis(F) && cfg->strategy != STRATEGY_LIGHT));
    return L;
}

/* Weight of light found by BSDF sampling (pdf bsdf_pdf at the previous vertex, the shading point
 * prev, a non-delta bounce): with MIS, the power heuristic against the light samples that could
 * also have produced it; with one strategy alone, all or nothing. */
static float emitted_weight(const struct scene *s, const struct integrator_desc *cfg, int light,
                            struct light_select_at *prev, float bsdf_pdf, const struct ray *r,
                            float t, const struct surface *sf)
{
    if (cfg->strategy != STRATEGY_MIS)
        return cfg->strategy == STRATEGY_BSDF ? 1.0f : 0.0f;
    return emitted_mis_weight(s, cfg->light_samples, light, prev, bsdf_pdf, r, t, sf);
}

static inline vec3 radiance(const struct scene *s, const struct integrator_desc *cfg, struct ray r,
                            struct sampler *smp, uint64_t *rays, unsigned F)
{
    vec3 L = v3s(0.0f), beta = v3s(1.0f);
    float eta_scale = 1.0f, prev_pdf = 0.0f;
    int depth = 0, specular = 1; /* the camera ray counts as specular: its emission is not MIS'd */
    /* The last non-delta vertex, where the light samples chose and where the MIS weight of the
     * light that the BSDF sample finds next reads the same choice's pmf. */
    struct light_select_at prev;
    mc_light_select_at(&prev, r.o, v3s(0.0f));
    for (;;) {
        struct hit h;
        struct surface sf;
        struct bsdf b;
        struct bsdf_sample bs;
        const struct prim *pr;
        frame fr;
        vec3 wo, wi;
        h.t = r.tmax;
        ++*rays;
        if (!trace(s, &r, &h, F)) {
            if (mc_features_need_mis(F) && s->env_light >= 0) {
                float w = specular ? 1.0f
                                   : emitted_weight(s, cfg, s->env_light, &prev, prev_pdf, &r,
                                                    INFINITY, NULL);
                vec3 Le = mc_environment_radiance(&s->lights[s->env_light], r.d);
                L = v3_add(L, v3_scale(v3_mul(beta, Le), w));
            }
            break;
        }
        pr = &s->prims[h.prim];
        surface(s, &r, &h, &sf, F);
        /* Without area lights no primitive emits. */
        if (mc_features_need_mis(F)) {
            vec3 Le = mc_light_emitted(pr, &sf);
            if (!v3_is_zero(Le)) {
                float w = specular ? 1.0f
                                   : emitted_weight(s, cfg, pr->light, &prev, prev_pdf, &r, h.t, &sf);
                L = v3_add(L, v3_scale(v3_mul(beta, Le), w));
            }
        }
        if (depth == cfg->max_depth)
            break;

        bsdf_at(s, &r, &h, pr, &b, F);
        fr = frame_from_normal(sf.ns);
        wo = frame_to_local(&fr, v3_neg(r.d));
        if (!mc_bsdf_is_delta(&b)) {
            mc_light_select_at(&prev, sf.p, sf.ns);
            if (cfg->strategy != STRATEGY_BSDF)
                L = v3_add(L, v3_mul(beta, sample_direct(s, cfg, &sf, &prev, r.time, &fr, &b, wo,
                                                         smp, rays, F)));
        }

        {
            float uc = mc_bsdf_chooses(&b) ? mc_sampler_1d(smp) : 0.5f;
            vec2 u = mc_sampler_2d(smp);
            if (!mc_bsdf_sample(&b, wo, uc, u, MC_RADIANCE, &bs))
                break;
        }
        beta = v3_mul(beta, bs.weight);
        if (v3_is_zero(beta))
            break;
        if (bs.eta != 1.0f)
            eta_scale *= bs.eta * bs.eta; /* undo the 1/η² radiance scaling for roulette */
        wi = frame_to_world(&fr, bs.wi);
        if (through_surface(&b, sf.ng, v3_neg(r.d), wi))
            break;
        specular = bs.delta;
        prev_pdf = bs.pdf;
        r.o = ray_spawn(sf.p, side_normal(sf.ng, wi), sf.err);
        r.d = wi;
        r.tmax = INFINITY;
        depth++;

        /* Russian roulette: survive with probability q = max(β·η-scale), clamped to 1, and divide
         * by q, which keeps the estimator unbiased (Arvo and Kirk 1990). */
        if (depth >= cfg->rr_depth) {
            float q = v3_max_comp(beta) * eta_scale;
            if (q < 1.0f) {
                if (!(mc_sampler_1d(smp) < q))
                    break;
                beta = v3_scale(beta, 1.0f / q);
            }
        }
    }
    return L;
}

/* The instantiations: every combination of the features that change the code. */
#define KERNEL(name, F)                                                                         \
    static vec3 name(const struct scene *s, const struct integrator_desc *cfg, struct ray r,   \
                     struct sampler *smp, uint64_t *rays)                                      \
    {                                                                                          \
        return radiance(s, cfg, r, smp, rays, F);                                              \
    }
#define KERNELS(suffix, T)                                                                     \
    KERNEL(path_delta##suffix, T)                                                              \
    KERNEL(path_mis##suffix, T | FEATURE_AREA_LIGHTS)                                          \
    KERNEL(path_mis_n##suffix, T | FEATURE_AREA_LIGHTS | FEATURE_LIGHT_SAMPLES)                \
    KERNEL(path_delta_n##suffix, T | FEATURE_LIGHT_SAMPLES)                                    \
    KERNEL(path_motion_delta##suffix, T | FEATURE_MOTION)                                      \
    KERNEL(path_motion_mis##suffix, T | FEATURE_MOTION | FEATURE_AREA_LIGHTS)                  \
    KERNEL(path_motion_delta_n##suffix, T | FEATURE_MOTION | FEATURE_LIGHT_SAMPLES)
KERNELS(, 0u)
KERNELS(_textured, FEATURE_TEXTURES)
KERNEL(path_general, FEATURE_ALL)
#undef KERNELS

static mc_radiance_fn path_kernel(unsigned features)
{
    unsigned key = (features & FEATURE_TEXTURES ? 8u : 0u) | (features & FEATURE_MOTION ? 4u : 0u)
                   | (mc_features_need_mis(features) ? 2u : 0u)
                   | (features & FEATURE_LIGHT_SAMPLES ? 1u : 0u);
    static const mc_radiance_fn table[16] = {
        path_delta,                 path_delta_n,
        path_mis,                   path_mis_n,
        path_motion_delta,          path_motion_delta_n,
        path_motion_mis,            path_general,
        path_delta_textured,        path_delta_n_textured,
        path_mis_textured,          path_mis_n_textured,
        path_motion_delta_textured, path_motion_delta_n_textured,
        path_motion_mis_textured,   path_general};
    return table[key];
}

/* Unidirectional path tracing with next-event estimation (integrator_desc.light_samples shadow
 * rays per non-delta hit) and multiple importance sampling (Veach 1997, ch. 9, power heuristic
 * β = 2) between BSDF sampling and light sampling, and Russian roulette after rr_depth bounces.
 * Unbiased. The scene's parameters as they are. */
const struct integrator mc_integrator_path = MC_RAY_INTEGRATOR(
    "path tracing, the scene's strategy (by default MIS)", NULL, path_kernel);

/* `direct` is the path tracer stopped after one bounce (emitted light plus direct lighting at the
 * first hit, with the same MIS), so that the two can never disagree on what they share. */
static mcrt_status direct_prepare(const struct integrator *self, const struct scene *s,
                                  struct render_settings *rs, void **state, mc_diag *d)
{
    (void)self;
    (void)s;
    (void)state;
    (void)d;
    rs->integrator.max_depth = 1;
    rs->integrator.rr_depth = INT_MAX;
    return MCRT_OK;
}
const struct integrator mc_integrator_direct = MC_RAY_INTEGRATOR(
    "emission plus direct lighting at the first hit", direct_prepare, path_kernel);

/* The path tracer with one way of finding light, whatever the scene's strategy: both weighted
 * by MIS, BSDF sampling only, or light sampling only (for measuring them). */
static mcrt_status strategy_prepare(const struct integrator *self, const struct scene *s,
                                    struct render_settings *rs, void **state, mc_diag *d)
{
    (void)s;
    (void)state;
    (void)d;
    rs->integrator.strategy = self == &mc_integrator_bsdf    ? STRATEGY_BSDF
                              : self == &mc_integrator_light ? STRATEGY_LIGHT
                                                             : STRATEGY_MIS;
    return MCRT_OK;
}
const struct integrator mc_integrator_mis = MC_RAY_INTEGRATOR(
    "path tracing, BSDF and light sampling under MIS", strategy_prepare, path_kernel);
const struct integrator mc_integrator_bsdf = MC_RAY_INTEGRATOR(
    "path tracing by BSDF sampling (point lights unseen)", strategy_prepare, path_kernel);
const struct integrator mc_integrator_light = MC_RAY_INTEGRATOR(
    "path tracing by light sampling only", strategy_prepare, path_kernel);
