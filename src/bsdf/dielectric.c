/* dielectric.c: rough glass: GGX microfacet reflection and refraction at a dielectric interface,
 * each microfacet choosing between them by its Fresnel reflectance, plus the energy-compensation
 * lobe of dielectric_ms.c for the light that scatters more than once among the microfacets.
 * References: Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces"
 * (eq. 13–21); pbrt-v4 §9.7 (DielectricBxDF, rough case); Kulla and Conty 2017. */
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

/* ---- single scattering ---- */

/* f and pdf of the single-scattering model; wo.z, wi.z != 0. */
static vec3 single_eval(const struct bsdf *b, vec3 wo, vec3 wi, enum mc_transport mode)
{
    vec3 wm;
    float eta = orient(b, &wo, &wi), c, f;
    if (wi.z > 0.0f) {
        /* Reflection, untinted as smooth glass. */
        f = mc_ggx_reflection(b->alpha, wo, wi, &c);
        return v3s(mc_fresnel_dielectric(c, eta) * f);
    }
    if (!refraction_normal(wo, wi, eta, &wm))
        return v3s(0.0f);
    /* Walter 2007 eq. 21: f = |wi·wm| |wo·wm| η_wo² (1 − F) D G2 / (|cosθi| cosθo (η_wo wo·wm +
     * η_wi wi·wm)²). With η_wo = 1 this is the Jacobian above over η², i.e. the radiance-mode BTDF
     * (the 1/η² of specular.c), here times the tint; importance lacks the 1/η² (bsdf.h). G2 is
     * the height-correlated form of reflection, as in pbrt-v4 (Heitz 2014's exact
     * height-correlated form for transmission is a Beta function of the Λs; not used here). */
    f = refraction_transmittance(b, wo, wi, wm, eta) * mc_ggx_d(b->alpha, wm) * mc_ggx_g2(b->alpha, wo, wi) *
        v3_dot(wo, wm) * refraction_jacobian(wo, wi, wm, eta) /
        ((mode == MC_RADIANCE ? eta * eta : 1.0f) * wo.z * -wi.z);
    return v3_scale(b->color, f);
}

static float single_pdf(const struct bsdf *b, vec3 wo, vec3 wi)
{
    vec3 wm;
    float eta = orient(b, &wo, &wi);
    /* The visible normal's density, times the probability of the lobe (F or 1 − F:
     * single_sample), through the lobe's Jacobian. */
    if (wi.z > 0.0f)
        return mc_fresnel_dielectric(mc_ggx_half(wo, wi, &wm), eta) * mc_ggx_reflection_pdf(b->alpha, wo, wi);
    if (!refraction_normal(wo, wi, eta, &wm))
        return 0.0f;
    return refraction_transmittance(b, wo, wi, wm, eta) * mc_ggx_visible_pdf(b->alpha, wo, wm) *
           refraction_jacobian(wo, wi, wm, eta);
}

/* A direction from the visible normals of wo (wo.z != 0): reflected with probability F, else
 * refracted. Returns 0 when it leaves on the wrong side (the loss the compensation restores). */
static int single_sample(const struct bsdf *b, vec3 wo, float uc, vec2 u, vec3 *wi)
{
    vec3 w = wo, wm, v = v3s(0.0f);
    float eta = orient(b, &w, &v); /* wi is not known yet: flipping its zero is harmless */
    wm = mc_ggx_sample_visible(b->alpha, w, u);
    if (uc < mc_fresnel_dielectric(v3_dot(w, wm), eta)) {
        v = mc_reflect(w, wm);
        if (v.z <= 0.0f)
            return 0;
    } else if (!mc_refract(w, wm, eta, &v) || v.z >= 0.0f) {
        return 0; /* (no total internal reflection here: F < 1 at wm) */
    }
    *wi = wo.z > 0.0f ? v : mc_mirror_z(v);
    return 1;
}

/* ---- with the compensation lobe ---- */

/* The probability of sampling the compensation lobe from wo: its share of wo's energy,
 * 1 − Ê(μo), so that each lobe is sampled in proportion to what it scatters. */
static float compensation_probability(const struct bsdf *b, vec3 wo)
{
    return b->ms ? 1.0f - mc_dielectric_ms_albedo(b->ms, wo.z < 0.0f, wo.z) : 0.0f;
}

static vec3 dielectric_eval(const struct bsdf *b, vec3 wo, vec3 wi, enum mc_transport mode)
{
    vec3 f;
    if (wo.z == 0.0f || wi.z == 0.0f)
        return v3s(0.0f);
    f = single_eval(b, wo, wi, mode);
    if (b->ms) {
        /* Tinted on crossing, as the refraction is. The lobe's radiance f is reciprocal in the
         * sense of bsdf.h (dielectric_ms.c), so its importance f, the adjoint, is f(wi, wo). */
        float g = mode == MC_RADIANCE ? mc_dielectric_ms_eval(b->ms, wo, wi) : mc_dielectric_ms_eval(b->ms, wi, wo);
        f = v3_add(f, wo.z * wi.z < 0.0f ? v3_scale(b->color, g) : v3s(g));
    }
    return f;
}

static float dielectric_pdf(const struct bsdf *b, vec3 wo, vec3 wi)
{
    float p = compensation_probability(b, wo), single;
    if (wo.z == 0.0f || wi.z == 0.0f)
        return 0.0f;
    single = single_pdf(b, wo, wi);
    return p > 0.0f ? (1.0f - p) * single + p * mc_dielectric_ms_pdf(b->ms, wo, wi) : single;
}

static int rough_sample(const struct bsdf *b, vec3 wo, float uc, vec2 u, enum mc_transport mode,
                       struct bsdf_sample *out)
{
    float p = compensation_probability(b, wo);
    int ok;
    if (wo.z == 0.0f)
        return 0;
    /* uc picks the lobe, then is rescaled to [0, 1) to pick within it. */
    if (uc < p)
        ok = mc_dielectric_ms_sample(b->ms, wo, uc / p, u, &out->wi);
    else
        ok = single_sample(b, wo, p > 0.0f ? fminf((uc - p) / (1.0f - p), 0x1.fffffep-1f) : uc, u, &out->wi);
    if (!ok)
        return 0;
    /* The pdf of wi as dielectric_pdf computes it, over both lobes: the value light
     * sampling's MIS weights use too; a wi that rounding left no microfacet to produce is
     * dropped. The weight is f |cosθi| / pdf of the mixture (with both lobes no closed form
     * cancels). */
    out->pdf = dielectric_pdf(b, wo, out->wi);
    if (!(out->pdf > 0.0f))
        return 0;
    out->weight = v3_scale(dielectric_eval(b, wo, out->wi, mode), fabsf(out->wi.z) / out->pdf);
    out->eta = wo.z * out->wi.z < 0.0f ? (wo.z > 0.0f ? b->ior : 1.0f / b->ior) : 1.0f;
    out->delta = 0;
    return 1;
}

/* ---- the glass material ---- */

/* A glass of ior 1 is no interface at all, rough or not: light passes straight through
 * (specular.c), as in pbrt-v4. */
static float glass_alpha(float alpha, float ior) { return ior == 1.0f ? 0.0f : alpha; }

static void glass_prepare(struct material *m)
{
    if (m->alpha >= MC_BSDF_SMOOTH_ALPHA && glass_alpha(m->alpha, m->ior) > 0.0f) /* rough (mc_bsdf_init) */
        mc_dielectric_ms_build(&m->ms, m->alpha, m->ior);
}

static void glass_init(struct bsdf *b, const struct material *m)
{
    b->alpha = glass_alpha(b->alpha, b->ior);
    b->ms = b->alpha > 0.0f && m->ms.ready ? &m->ms : NULL;
}

static int glass_sample(const struct bsdf *b, vec3 wo, float uc, vec2 u, enum mc_transport mode,
                        struct bsdf_sample *out)
{
    return b->alpha > 0.0f ? rough_sample(b, wo, uc, u, mode, out) : mc_glass_sample(b, wo, uc, mode, out);
}

/* Tinted and clear, smooth and rough; clear glass with its compensation conserves energy
 * (the tolerance of test_glass_energy in test_microfacet.c). */
static const struct mc_material_example examples[] = {
    {{1.0f, 0.9f, 0.8f}, 1.5f, 0.0f, {0, 0, 0}, {0, 0, 0}, 0.0},
    {{1.0f, 0.9f, 0.8f}, 1.5f, 0.1f, {0, 0, 0}, {0, 0, 0}, 0.0},
    {{1.0f, 1.0f, 1.0f}, 1.5f, 0.0f, {0, 0, 0}, {0, 0, 0}, 1e-6},
    {{1.0f, 1.0f, 1.0f}, 1.33f, 0.3f, {0, 0, 0}, {0, 0, 0}, 3e-3},
    {{1.0f, 1.0f, 1.0f}, 2.4f, 1.0f, {0, 0, 0}, {0, 0, 0}, 3e-3},
};

const struct mc_material_ops mc_material_ops_glass = {
    "glass", MC_DELTA_WHEN_SMOOTH, 1, NULL, glass_prepare, glass_init, dielectric_eval, dielectric_pdf, glass_sample,
    examples, (int)(sizeof examples / sizeof examples[0])};
