/* conductor.c: metal: the Torrance–Sparrow microfacet reflection of GGX with the exact Fresnel
 * reflectance of a conductor, or a delta reflection when smooth.
 * Reference: Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces"
 * (eq. 20); pbrt-v4 §9.6 (ConductorBxDF). */
#include "bsdf/bsdf_impl.h"

/* Opaque: both faces reflect alike, so a back-face configuration is mirrored to the front. */
static vec3 front(vec3 w) { return v3(w.x, w.y, fabsf(w.z)); }

vec3 mc_conductor_eval(const struct bsdf *b, vec3 wo, vec3 wi)
{
    vec3 wm;
    if (b->alpha == 0.0f || !(wo.z * wi.z > 0.0f))
        return v3s(0.0f);
    wo = front(wo);
    wi = front(wi);
    wm = v3_normalize(v3_add(wo, wi)); /* nonzero: both are above the surface */
    /* f = D(wm) F(wo·wm) G2(wo, wi) / (4 cosθo cosθi) */
    return v3_scale(mc_fresnel_conductor(v3_dot(wo, wm), b->eta, b->k),
                    mc_ggx_d(b->alpha, wm) * mc_ggx_g2(b->alpha, wo, wi) / (4.0f * wo.z * wi.z));
}

float mc_conductor_pdf(const struct bsdf *b, vec3 wo, vec3 wi)
{
    vec3 wm;
    if (b->alpha == 0.0f || !(wo.z * wi.z > 0.0f))
        return 0.0f;
    wo = front(wo);
    wi = front(wi);
    wm = v3_normalize(v3_add(wo, wi));
    /* Visible normals, through the reflection Jacobian dωm/dωi = 1/(4 |wo·wm|) (Walter 2007
     * eq. 14). */
    return mc_ggx_visible_pdf(b->alpha, wo, wm) / (4.0f * v3_dot(wo, wm));
}

int mc_conductor_sample(const struct bsdf *b, vec3 wo, vec2 u, struct bsdf_sample *out)
{
    vec3 w = front(wo), wm, wi;
    float pdf;
    if (b->alpha == 0.0f)
        return mc_specular_reflection(wo, mc_fresnel_conductor(w.z, b->eta, b->k), 1.0f, out);
    if (wo.z == 0.0f)
        return 0;
    wm = mc_ggx_sample_visible(b->alpha, w, u);
    wi = mc_reflect(w, wm);
    if (wi.z <= 0.0f)
        return 0; /* reflected below the surface: the masking in G2 is what this sample lost */
    pdf = mc_ggx_visible_pdf(b->alpha, w, wm) / (4.0f * v3_dot(w, wm));
    if (!(pdf > 0.0f))
        return 0;
    out->wi = wo.z > 0.0f ? wi : v3(wi.x, wi.y, -wi.z);
    out->pdf = pdf;
    /* f·cosθi/pdf = D F G2/(4 cosθo) · 4 cosθo/(G1(wo) D) = F G2/G1(wo): D cancels, so the
     * weight stays at most F however peaked the lobe. */
    out->weight = v3_scale(mc_fresnel_conductor(v3_dot(w, wm), b->eta, b->k),
                           mc_ggx_g2(b->alpha, w, wi) / mc_ggx_g1(b->alpha, w));
    out->delta = 0;
    out->eta = 1.0f;
    return 1;
}
