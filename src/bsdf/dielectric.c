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

/* The microfacet normal that refracts wo (z > 0) into wi (z < 0): the generalised half vector
 * wo + η wi (Walter 2007 eq. 16), turned to face z > 0. Returns 0 when no microfacet can: a
 * normal facing away from wo, or not between wo and wi (light enters a facet's front and
 * leaves through its back). */
static int refraction_normal(vec3 wo, vec3 wi, float eta, vec3 *wm)
{
    vec3 h = v3_madd(wo, wi, eta);
    if (v3_length2(h) == 0.0f)
        return 0;
    h = v3_normalize(h);
    if (h.z < 0.0f)
        h = v3_neg(h);
    if (!(v3_dot(wo, h) > 0.0f && v3_dot(wi, h) < 0.0f))
        return 0;
    *wm = h;
    return 1;
}

/* 1 − F at wm for the refraction from wo (z > 0) to wi. 1 − F is the same seen from either
 * side, so it is taken from the outside, whichever side wo is on: from the denser side, near
 * the critical angle, η cosθt = √(cos²θ − cos²θc) keeps none of cosθ's digits. */
static float refraction_transmittance(const struct bsdf *b, vec3 wo, vec3 wi, vec3 wm, float eta)
{
    return 1.0f - mc_fresnel_dielectric(eta == b->ior ? v3_dot(wo, wm) : -v3_dot(wi, wm), b->ior);
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
    float eta, c, f;
    if (wo.z == 0.0f || wi.z == 0.0f)
        return v3s(0.0f);
    eta = orient(b, &wo, &wi);
    if (wi.z > 0.0f) {
        /* Reflection, untinted as smooth glass. */
        f = mc_ggx_reflection(b->alpha, wo, wi, &c);
        return v3s(mc_fresnel_dielectric(c, eta) * f);
    }
    if (!refraction_normal(wo, wi, eta, &wm))
        return v3s(0.0f);
    /* Walter 2007 eq. 21: f = |wi·wm| |wo·wm| η_wo² (1 − F) D G2 / (|cosθi| cosθo (η_wo wo·wm +
     * η_wi wi·wm)²). With η_wo = 1 this is the Jacobian above over η², i.e. the radiance-mode BTDF
     * (the 1/η² of specular.c), here times the tint. G2 is the height-correlated form of
     * reflection, as in pbrt-v4 (Heitz 2014's exact height-correlated form for transmission
     * is a Beta function of the Λs; not used here). */
    f = refraction_transmittance(b, wo, wi, wm, eta) * mc_ggx_d(b->alpha, wm) * mc_ggx_g2(b->alpha, wo, wi) *
        v3_dot(wo, wm) * refraction_jacobian(wo, wi, wm, eta) / (eta * eta * wo.z * -wi.z);
    return v3_scale(b->color, f);
}

float mc_dielectric_pdf(const struct bsdf *b, vec3 wo, vec3 wi)
{
    vec3 wm;
    float eta;
    if (wo.z == 0.0f || wi.z == 0.0f)
        return 0.0f;
    eta = orient(b, &wo, &wi);
    /* The visible normal's density, times the probability of the lobe (F or 1 − F:
     * mc_dielectric_sample), through the lobe's Jacobian. */
    if (wi.z > 0.0f)
        return mc_fresnel_dielectric(mc_ggx_half(wo, wi, &wm), eta) * mc_ggx_reflection_pdf(b->alpha, wo, wi);
    if (!refraction_normal(wo, wi, eta, &wm))
        return 0.0f;
    return refraction_transmittance(b, wo, wi, wm, eta) * mc_ggx_visible_pdf(b->alpha, wo, wm) *
           refraction_jacobian(wo, wi, wm, eta);
}

int mc_dielectric_sample(const struct bsdf *b, vec3 wo, float uc, vec2 u, struct bsdf_sample *out)
{
    vec3 w = wo, wm, wi = v3s(0.0f);
    float eta, f;
    if (wo.z == 0.0f)
        return 0;
    eta = orient(b, &w, &wi); /* wi is not known yet: flipping its zero is harmless */
    wm = mc_ggx_sample_visible(b->alpha, w, u);
    f = mc_fresnel_dielectric(v3_dot(w, wm), eta);
    if (uc < f) {
        /* Reflection, with probability F: weight f cosθi / (F D_wo / (4 wo·wm)) = G2/G1(wo). */
        wi = mc_reflect(w, wm);
        if (wi.z <= 0.0f)
            return 0;
        out->weight = v3s(1.0f);
        out->eta = 1.0f;
    } else {
        /* Refraction, with probability 1 − F (< 1: no total internal reflection at wm): weight
         * tint · G2/G1(wo) / η², the 1 − F, D and Jacobian cancelling likewise. */
        if (!mc_refract(w, wm, eta, &wi) || wi.z >= 0.0f)
            return 0;
        out->weight = v3_scale(b->color, 1.0f / (eta * eta));
        out->eta = eta;
    }
    out->weight = v3_scale(out->weight, mc_ggx_g2(b->alpha, w, wi) / mc_ggx_g1(b->alpha, w));
    out->wi = wo.z > 0.0f ? wi : mc_mirror_z(wi);
    /* The pdf of wi as mc_dielectric_pdf computes it, from the normal recomputed from wo and
     * wi: the value light sampling's MIS weights use too; a wi that rounding left no microfacet
     * to produce is dropped. */
    out->pdf = mc_dielectric_pdf(b, wo, out->wi);
    out->delta = 0;
    return out->pdf > 0.0f;
}
