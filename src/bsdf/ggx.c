/* ggx.c: the isotropic GGX (Trowbridge–Reitz) microfacet distribution: normal density, Smith
 * masking–shadowing and sampling of the visible normals. References: Walter et al. 2007,
 * "Microfacet Models for Refraction through Rough Surfaces"; Heitz 2014, "Understanding the
 * Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT 3(2); Heitz 2018, "Sampling the
 * GGX Distribution of Visible Normals", JCGT 7(4). */
#include "bsdf/bsdf_impl.h"

#include "sample/warp.h"

/* sin²θ from the tangential components rather than 1 − z²: near the normal, where a narrow
 * lobe lives, 1 − z² has lost all its digits (sin²θ ~ α² = 1e-6 is 17 ulps of 1). */
static float sin2(vec3 w) { return w.x * w.x + w.y * w.y; }

float mc_ggx_d(float alpha, vec3 wm)
{
    /* D = α² / (π (α² cos²θ + sin²θ)²) for unit wm (Walter 2007 eq. 33, with
     * cos⁴θ (α² + tan²θ)² multiplied out so that nothing divides by cosθ). */
    float a2 = alpha * alpha, t;
    if (wm.z <= 0.0f)
        return 0.0f;
    t = a2 * wm.z * wm.z + sin2(wm);
    return a2 / (MC_PI * t * t);
}

/* √(1 + α² tan²θ) = 1 + 2Λ(w), with Λ GGX's Smith auxiliary function (Heitz 2014). In
 * this form G1 and G2 below need no subtraction, and a grazing w (tan θ → ∞) gives +∞ and so
 * G = 0 rather than ∞/∞. Callers pass w.z ≠ 0. */
static float smith_root(float alpha, vec3 w)
{
    return sqrtf(1.0f + alpha * alpha * sin2(w) / (w.z * w.z));
}

float mc_ggx_g1(float alpha, vec3 w)
{
    return 2.0f / (1.0f + smith_root(alpha, w)); /* 1/(1 + Λ) */
}

float mc_ggx_g2(float alpha, vec3 wo, vec3 wi)
{
    /* Height-correlated Smith masking–shadowing, G2 = 1/(1 + Λ(wo) + Λ(wi)) (Heitz 2014):
     * a microfacet hidden from wo is more likely also hidden from wi, which the separable
     * G1(wo)·G1(wi) ignores. */
    return 2.0f / (smith_root(alpha, wo) + smith_root(alpha, wi));
}

float mc_ggx_visible_pdf(float alpha, vec3 wo, vec3 wm)
{
    /* D_wo(wm) = G1(wo) max(0, wo·wm) D(wm) / cosθo (Heitz 2018). */
    float c = v3_dot(wo, wm);
    return c > 0.0f ? mc_ggx_g1(alpha, wo) * c * mc_ggx_d(alpha, wm) / wo.z : 0.0f;
}

vec3 mc_ggx_sample_visible(float alpha, vec3 wo, vec2 u)
{
    /* Heitz 2018's algorithm. Stretching by 1/α turns GGX into the distribution of a
     * hemisphere's normals, whose visible normals from vh are the hemisphere's points above a
     * uniform point of the projected disk: half a disk (the projection of the lit cap) and
     * half an ellipse (the side), joined by warping the disk point's second coordinate. */
    vec3 vh = v3_normalize(v3(alpha * wo.x, alpha * wo.y, wo.z)), t1, t2, nh;
    float len2 = vh.x * vh.x + vh.y * vh.y, s, pz;
    /* Any uniform map onto the disk will do; the concentric one keeps stratification. */
    vec2 p = mc_warp_concentric_disk(u);
    t1 = len2 > 0.0f ? v3_scale(v3(-vh.y, vh.x, 0.0f), 1.0f / sqrtf(len2)) : v3(1.0f, 0.0f, 0.0f);
    t2 = v3_cross(vh, t1);
    s = 0.5f * (1.0f + vh.z);
    p.y = (1.0f - s) * sqrtf(f_max(0.0f, 1.0f - p.x * p.x)) + s * p.y;
    pz = sqrtf(f_max(0.0f, 1.0f - p.x * p.x - p.y * p.y));
    nh = v3_add(v3_add(v3_scale(t1, p.x), v3_scale(t2, p.y)), v3_scale(vh, pz));
    /* Unstretch. The floor on z (pbrt-v4's) keeps a rim sample off the horizon, where it
     * would be a normal of zero density. */
    return v3_normalize(v3(alpha * nh.x, alpha * nh.y, f_max(1e-6f, nh.z)));
}

float mc_ggx_half(vec3 wo, vec3 wi, vec3 *wm)
{
    /* wo·wm = wi·wm in exact arithmetic; their mean is the same float whichever direction comes
     * first, which makes every reflection f built on it exactly reciprocal. */
    *wm = v3_normalize(v3_add(wo, wi)); /* nonzero: both are above the surface */
    return 0.5f * (v3_dot(wo, *wm) + v3_dot(wi, *wm));
}

float mc_ggx_reflection(float alpha, vec3 wo, vec3 wi, float *cos_h)
{
    /* Torrance–Sparrow (Walter 2007 eq. 20) without its Fresnel factor. */
    vec3 wm;
    *cos_h = mc_ggx_half(wo, wi, &wm);
    return mc_ggx_d(alpha, wm) * mc_ggx_g2(alpha, wo, wi) / (4.0f * wo.z * wi.z);
}

float mc_ggx_reflection_pdf(float alpha, vec3 wo, vec3 wi)
{
    /* The visible normal's density through the reflection Jacobian dωm/dωi = 1/(4 wo·wm)
     * (Walter 2007 eq. 14). */
    vec3 wm = v3_normalize(v3_add(wo, wi));
    return mc_ggx_visible_pdf(alpha, wo, wm) / (4.0f * v3_dot(wo, wm));
}
