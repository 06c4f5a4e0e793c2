/* conductor.c: metal: the Torrance–Sparrow microfacet reflection of GGX with the exact Fresnel
 * reflectance of a conductor, or a delta reflection when smooth.
 * Reference: Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces"
 * (eq. 20); pbrt-v4 §9.4 and §9.6 (ConductorBxDF, TrowbridgeReitzDistribution). */
#include "bsdf/bsdf_impl.h"

#include <stdio.h>

static vec3 conductor_eval(const struct bsdf *b, vec3 wo, vec3 wi, enum mc_transport mode)
{
    float c, f;
    (void)mode; /* reflection only: the same f either way */
    if (b->alpha == 0.0f || !(wo.z * wi.z > 0.0f))
        return v3s(0.0f);
    f = mc_ggx_reflection(b->alpha, mc_front(wo), mc_front(wi), &c);
    return v3_scale(mc_fresnel_conductor(c, b->eta, b->k), f);
}

static float conductor_pdf(const struct bsdf *b, vec3 wo, vec3 wi)
{
    if (b->alpha == 0.0f || !(wo.z * wi.z > 0.0f))
        return 0.0f;
    return mc_ggx_reflection_pdf(b->alpha, mc_front(wo), mc_front(wi));
}

static int conductor_sample(const struct bsdf *b, vec3 wo, float uc, vec2 u, enum mc_transport mode,
                            struct bsdf_sample *out)
{
    vec3 w = mc_front(wo), wi;
    float c;
    (void)uc;
    (void)mode;
    if (b->alpha == 0.0f)
        return mc_specular_reflection(wo, mc_fresnel_conductor(w.z, b->eta, b->k), 1.0f, out);
    if (wo.z == 0.0f)
        return 0;
    wi = mc_reflect(w, mc_ggx_sample_visible(b->alpha, w, u));
    if (wi.z <= 0.0f)
        return 0; /* reflected below the surface: the masking in G2 is what this sample lost */
    out->wi = wo.z > 0.0f ? wi : mc_mirror_z(wi);
    /* The pdf as mc_conductor_pdf computes it (see dielectric.c's sample). The weight f·cosθi/pdf
     * = D F G2/(4 cosθo) · 4 cosθo/(G1(wo) D) = F G2/G1(wo): D cancels, so the weight stays at
     * most F however peaked the lobe. */
    out->pdf = mc_ggx_reflection_pdf(b->alpha, w, wi);
    mc_ggx_reflection(b->alpha, w, wi, &c);
    out->weight = v3_scale(mc_fresnel_conductor(c, b->eta, b->k),
                           mc_ggx_g2(b->alpha, w, wi) / mc_ggx_g1(b->alpha, w));
    out->delta = 0;
    out->eta = 1.0f;
    return out->pdf > 0.0f;
}

/* A metal is given by its reflectance ("metal RGB": η and k follow from it) or, without one, by
 * both η (positive) and k. */
static int conductor_complete(struct material *m, unsigned given, struct mc_material_problem *p)
{
    static const int eta_k[] = {MC_KEY_ETA, MC_KEY_K};
    static const char *const names[] = {"eta", "k"};
    int i;
    p->at_number = 0;
    if (given & MC_GIVEN_VALUE) {
        for (i = 0; i < 2; i++)
            if (given & MC_KEY_BIT(eta_k[i])) {
                p->key = eta_k[i];
                snprintf(p->what, sizeof p->what, "'%s' is only for a metal given without a reflectance", names[i]);
                return 0;
            }
        mc_metal_from_reflectance(m->color, &m->eta, &m->k);
        return 1;
    }
    if (!(given & MC_KEY_BIT(MC_KEY_ETA)) || !(given & MC_KEY_BIT(MC_KEY_K))) {
        p->key = -1;
        snprintf(p->what, sizeof p->what, "metal '%s' needs a reflectance ('metal 0.9 0.6 0.3') or both 'eta' and 'k'",
                 m->name);
        return 0;
    }
    if (!(m->eta.x > 0.0f && m->eta.y > 0.0f && m->eta.z > 0.0f)) {
        p->key = MC_KEY_ETA;
        snprintf(p->what, sizeof p->what, "'eta' must be positive");
        return 0;
    }
    return 1;
}

/* Gold at about 650, 550, 450 nm (Johnson and Christy 1972, as tabulated by pbrt) from smooth to
 * rough, and a white metal (reflectance 0.9999: η = 1, k = 2√R/√(1 − R)) that loses only what
 * single-scattering GGX loses. */
#define GOLD {0.0f, 0.0f, 0.0f}, 1.0f
#define GOLD_ETA_K {0.166f, 0.428f, 1.38f}, {3.15f, 2.35f, 1.87f}
static const struct mc_material_example examples[] = {
    {GOLD, 0.0f, GOLD_ETA_K, 0.0},
    {GOLD, 0.1f, GOLD_ETA_K, 0.0},
    {GOLD, 0.5f, GOLD_ETA_K, 0.0},
    {GOLD, 1.0f, GOLD_ETA_K, 0.0},
    {{1.0f, 1.0f, 1.0f}, 1.0f, 0.3f, {1.0f, 1.0f, 1.0f}, {199.99f, 199.99f, 199.99f}, 0.0},
};
#undef GOLD
#undef GOLD_ETA_K

const struct mc_material_ops mc_material_ops_metal = {
    "glossy metal", MC_DELTA_WHEN_SMOOTH, 0, conductor_complete, NULL, NULL, conductor_eval, conductor_pdf,
    conductor_sample, examples, (int)(sizeof examples / sizeof examples[0])};
