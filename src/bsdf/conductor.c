/* conductor.c: metal: the Torrance–Sparrow microfacet reflection of GGX with the exact Fresnel
 * reflectance of a conductor, or a delta reflection when smooth.
 * Reference: Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces"
 * (eq. 20); pbrt-v4 §9.4 and §9.6 (ConductorBxDF, TrowbridgeReitzDistribution). */
#include "bsdf/bsdf_impl.h"

vec3 mc_conductor_eval(const struct bsdf *b, vec3 wo, vec3 wi)
{
    float c, f;
    if (b->alpha == 0.0f || !(wo.z * wi.z > 0.0f))
        return v3s(0.0f);
    f = mc_ggx_reflection(b->alpha, mc_front(wo), mc_front(wi), &c);
    return v3_scale(mc_fresnel_conductor(c, b->eta, b->k), f);
}

float mc_conductor_pdf(const struct bsdf *b, vec3 wo, vec3 wi)
{
    if (b->alpha == 0.0f || !(wo.z * wi.z > 0.0f))
        return 0.0f;
    return mc_ggx_reflection_pdf(b->alpha, mc_front(wo), mc_front(wi));
}

int mc_conductor_sample(const struct bsdf *b, vec3 wo, vec2 u, struct bsdf_sample *out)
{
    vec3 w = mc_front(wo), wi;
    float c;
    if (b->alpha == 0.0f)
        return mc_specular_reflection(wo, mc_fresnel_conductor(w.z, b->eta, b->k), 1.0f, out);
    if (wo.z == 0.0f)
        return 0;
    wi = mc_reflect(w, mc_ggx_sample_visible(b->alpha, w, u));
    if (wi.z <= 0.0f)
        return 0; /* reflected below the surface: the masking in G2 is what this sample lost */
    out->wi = wo.z > 0.0f ? wi : mc_mirror_z(wi);
    /* The pdf as mc_conductor_pdf computes it (see mc_dielectric_sample). The weight f·cosθi/pdf
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
