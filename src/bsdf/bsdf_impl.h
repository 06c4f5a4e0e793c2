/* bsdf_impl.h: the per-material halves of bsdf.h and their shared optics, private to src/bsdf.
 * bsdf.c dispatches through each kind's mc_material_ops to these; each follows the rules at the
 * top of bsdf.h.
 * Microfacet code sees only α >= MC_BSDF_SMOOTH_ALPHA (mc_bsdf_init sends smaller α to the
 * delta lobes). */
#ifndef MCRT_BSDF_IMPL_H
#define MCRT_BSDF_IMPL_H

#include "bsdf/bsdf.h"
#include "bsdf/material.h"

/* ---- interface optics (fresnel.c) ---- */

/* w reflected about the unit normal n. */
vec3 mc_reflect(vec3 w, vec3 n);
/* w refracted through the unit normal n, which must be on w's side (w·n >= 0), into a medium of
 * relative ior eta (far side over w's side). Returns 0 under total internal reflection. */
int mc_refract(vec3 w, vec3 n, float eta, vec3 *wt);
/* ∫ F(μ) 2μ dμ over the hemisphere: the cosine-weighted average of mc_fresnel_dielectric from
 * the outside of an interface of relative ior eta >= 1. */
double mc_fresnel_diffuse(double eta);

/* ---- the GGX microfacet distribution (ggx.c); directions unit, w.z != 0 ---- */

/* Normal distribution D(wm) (0 for wm.z <= 0). */
float mc_ggx_d(float alpha, vec3 wm);
/* Smith masking G1(w) = 1/(1 + Λ(w)). */
float mc_ggx_g1(float alpha, vec3 w);
/* Height-correlated Smith masking–shadowing G2 = 1/(1 + Λ(wo) + Λ(wi)). */
float mc_ggx_g2(float alpha, vec3 wo, vec3 wi);
/* A normal sampled from the distribution of normals visible from wo (wo.z > 0), and that
 * distribution's density D_wo(wm) = G1(wo) max(0, wo·wm) D(wm) / wo.z. */
vec3 mc_ggx_sample_visible(float alpha, vec3 wo, vec2 u);
float mc_ggx_visible_pdf(float alpha, vec3 wo, vec3 wm);
/* Reflection from wo to wi, both with z > 0, off the microfacet wm = the half vector:
 * mc_ggx_half gives wm and wo·wm = wi·wm (formed symmetrically in wo and wi, for Fresnel);
 * mc_ggx_reflection f without the Fresnel factor, D(wm) G2 / (4 cosθo cosθi), and that cosine;
 * mc_ggx_reflection_pdf the pdf of wi when wm is sampled from the visible normals of wo. */
float mc_ggx_half(vec3 wo, vec3 wi, vec3 *wm);
float mc_ggx_reflection(float alpha, vec3 wo, vec3 wi, float *cos_h);
float mc_ggx_reflection_pdf(float alpha, vec3 wo, vec3 wi);

/* ---- materials ---- */

/* Opaque materials scatter alike from both faces: a back-face configuration is mirrored to the
 * front (mc_mirror_z flips a direction through the tangent plane), computed there, and mirrored
 * back. */
static inline vec3 mc_mirror_z(vec3 w) { return v3(w.x, w.y, -w.z); }
static inline vec3 mc_front(vec3 w) { return v3(w.x, w.y, fabsf(w.z)); }

/* Delta lobes (specular.c): mc_specular_reflection is the mirror direction of wo about the
 * normal as a delta sample of the given weight and probability; mc_glass_sample the smooth
 * dielectric interface (the 1/η² of radiance on crossing in MC_RADIANCE mode only). */
int mc_specular_reflection(vec3 wo, vec3 weight, float pdf, struct bsdf_sample *out);
int mc_glass_sample(const struct bsdf *b, vec3 wo, float uc, enum mc_transport mode, struct bsdf_sample *out);

/* Rough glass's multiple-scattering compensation lobe (dielectric_ms.c). build tabulates it for
 * α and ior; albedo is the tabulated single-scattering energy albedo Ê_side(|mu|); eval the
 * lobe's radiance-mode f (untinted: the caller tints crossings); pdf the density of sample's wi,
 * with which sample crosses with probability ms->t[side of wo] (uc) and draws |μi| from the
 * table (u). */
void mc_dielectric_ms_build(struct mc_dielectric_ms *ms, float alpha, float ior);
float mc_dielectric_ms_albedo(const struct mc_dielectric_ms *ms, int side, float mu);
float mc_dielectric_ms_eval(const struct mc_dielectric_ms *ms, vec3 wo, vec3 wi);
float mc_dielectric_ms_pdf(const struct mc_dielectric_ms *ms, vec3 wo, vec3 wi);
int mc_dielectric_ms_sample(const struct mc_dielectric_ms *ms, vec3 wo, float uc, vec2 u, vec3 *wi);

/* Each kind's behaviour, one per line of materials.def, in its own file: diffuse.c (Lambertian),
 * specular.c (mirror), dielectric.c (glass: smooth, or GGX reflection and refraction after
 * Walter et al. 2007 with the compensation lobe), conductor.c (metal: GGX with conductor
 * Fresnel, smooth at α = 0), plastic.c (a diffuse base under a smooth or GGX dielectric coat). */
#define MC_MATERIAL(name, value, noun, keys) extern const struct mc_material_ops mc_material_ops_##name;
#include "bsdf/materials.def"
#undef MC_MATERIAL

#endif
