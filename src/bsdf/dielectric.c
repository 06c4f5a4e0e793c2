/* dielectric.c: rough glass: GGX microfacet reflection and refraction at a dielectric interface,
 * each microfacet choosing between them by its Fresnel reflectance.
 * Reference: Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces"
 * (eq. 13–21); pbrt-v4 §9.7 (DielectricBxDF, rough case). */
#include "bsdf/bsdf_impl.h"

/* Walter's formulas below are written for wo on the front side. A wo inside (z < 0) is the
 * mirror image, in the tangent plane, of a wo outside an interface with the media swapped; D
 * and G are unchanged by the mirroring. Flips wo and wi to z > 0 if needed and returns the
 * relative ior of the far side over wo's side. */
static float orient(const struct bsdf *b, vec3 *wo, vec3 *wi)
{
    if (wo->z > 0.0f)
        return b->ior;
    wo->z = -wo->z;
    wi->z = -wi->z;
    return 1.0f / b->ior;
}

/* The microfacet normal that scatters wo (z > 0) into wi: the half vector wo + wi for
 * reflection, the generalised half vector wo + η wi for refraction (Walter 2007 eq. 13 and 16),
 * turned to face z > 0. Returns 0 when no microfacet can: wi in the tangent plane, or a normal
 * facing away from wo or, for refraction, not between wo and wi (light must enter the facet's
 * front and leave through its back). */
static int half_vector(vec3 wo, vec3 wi, float eta, vec3 *wm)
{
    vec3 h;
    if (wi.z == 0.0f)
        return 0;
    h = wi.z > 0.0f ? v3_add(wo, wi) : v3_add(wo, v3_scale(wi, eta));
    if (v3_length2(h) == 0.0f)
        return 0;
    h = v3_normalize(h);
    if (h.z < 0.0f)
        h = v3_neg(h);
    if (!(v3_dot(wo, h) > 0.0f && v3_dot(wi, h) * wi.z > 0.0f))
        return 0;
    *wm = h;
    return 1;
}

/* dωm/dωi of refraction through wm (Walter 2007 eq. 17): η² |wi·wm| / (wo·wm + η wi·wm)². */
static float refraction_jacobian(vec3 wo, vec3 wi, vec3 wm, float eta)
{
    float ci = v3_dot(wi, wm), d = v3_dot(wo, wm) + eta * ci;
    return eta * eta * fabsf(ci) / (d * d);
}

vec3 mc_dielectric_eval(const struct bsdf *b, vec3 wo, vec3 wi)
{
    vec3 wm;
    float eta, f, dg;
    if (wo.z == 0.0f)
        return v3s(0.0f);
    eta = orient(b, &wo, &wi);
    if (!half_vector(wo, wi, eta, &wm))
        return v3s(0.0f);
    f = mc_fresnel_dielectric(v3_dot(wo, wm), eta);
    /* Height-correlated G2 for refraction too, as pbrt-v4 does (Heitz 2014 §6.2 gives the exact
     * height-correlated form for transmission as a Beta function of Λ; not used here). */
    dg = mc_ggx_d(b->alpha, wm) * mc_ggx_g2(b->alpha, wo, wi);
    if (wi.z > 0.0f)
        return v3s(f * dg / (4.0f * wo.z * wi.z)); /* reflection, untinted as smooth glass */
    /* Walter 2007 eq. 21: f = |wi·wm| |wo·wm| η_wo² (1 − F) D G2 / (|cosθi| cosθo (η_wo wo·wm +
     * η_wi wi·wm)²). With η_wo = 1 this is the Jacobian above over η², i.e. the radiance-mode BTDF
     * (the 1/η² of specular.c) times the tint. */
    return v3_scale(b->color, (1.0f - f) * dg * v3_dot(wo, wm) * refraction_jacobian(wo, wi, wm, eta) /
                                  (eta * eta * wo.z * fabsf(wi.z)));
}

float mc_dielectric_pdf(const struct bsdf *b, vec3 wo, vec3 wi)
{
    vec3 wm;
    float eta, f, pm;
    if (wo.z == 0.0f)
        return 0.0f;
    eta = orient(b, &wo, &wi);
    if (!half_vector(wo, wi, eta, &wm))
        return 0.0f;
    /* Visible normal density, the lobe's probability (F or 1 − F: mc_dielectric_sample) and
     * the lobe's Jacobian. */
    f = mc_fresnel_dielectric(v3_dot(wo, wm), eta);
    pm = mc_ggx_visible_pdf(b->alpha, wo, wm);
    if (wi.z > 0.0f)
        return f * pm / (4.0f * v3_dot(wo, wm));
    return (1.0f - f) * pm * refraction_jacobian(wo, wi, wm, eta);
}

int mc_dielectric_sample(const struct bsdf *b, vec3 wo, float uc, vec2 u, struct bsdf_sample *out)
{
    vec3 w = wo, wm, wi = v3s(0.0f);
    float eta, f, pm;
    if (wo.z == 0.0f)
        return 0;
    eta = orient(b, &w, &wi); /* wi is not known yet: flipping its zero is harmless */
    wm = mc_ggx_sample_visible(b->alpha, w, u);
    f = mc_fresnel_dielectric(v3_dot(w, wm), eta);
    pm = mc_ggx_visible_pdf(b->alpha, w, wm);
    if (uc < f) {
        /* Reflection with probability F: weight f cosθi / (F D_wo / (4 wo·wm)) = G2/G1(wo). */
        wi = mc_reflect(w, wm);
        if (wi.z <= 0.0f)
            return 0;
        out->pdf = f * pm / (4.0f * v3_dot(w, wm));
        out->weight = v3s(1.0f);
        out->eta = 1.0f;
    } else {
        /* Refraction with probability 1 − F (F < 1: no total internal reflection at wm):
         * weight tint · G2/G1(wo) / η², the (1 − F), D and Jacobian cancelling. */
        if (!mc_refract(w, wm, eta, &wi) || wi.z >= 0.0f)
            return 0;
        out->pdf = (1.0f - f) * pm * refraction_jacobian(w, wi, wm, eta);
        out->weight = v3_scale(b->color, 1.0f / (eta * eta));
        out->eta = eta;
    }
    if (!(out->pdf > 0.0f))
        return 0;
    out->weight = v3_scale(out->weight, mc_ggx_g2(b->alpha, w, wi) / mc_ggx_g1(b->alpha, w));
    out->wi = wo.z > 0.0f ? wi : v3(wi.x, wi.y, -wi.z);
    out->delta = 0;
    return 1;
}
