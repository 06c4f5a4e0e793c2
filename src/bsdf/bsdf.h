/* bsdf.h: scattering at a surface. One interface (eval, pdf, sample) for every material.
 *
 * Rules, written once here: directions are in the local shading frame (z = shading normal on the
 * primitive's front side); wo (toward the viewer) and wi (toward the light) both point away from
 * the surface; eval returns f without the cosine; pdf is per unit solid angle of wi; sample
 * returns the weight f·|cos θi| / pdf. Opaque materials (diffuse, mirror, metal, plastic) behave
 * the same on both faces (wo.z < 0 is handled by mirroring); glass's front side (z > 0) is its
 * outside.
 *
 * Delta lobes (mirror, smooth glass, smooth metal, the smooth coat of plastic) have no density:
 * eval and pdf leave them out, and only sample reaches them, setting delta. A BSDF may mix a
 * delta lobe with non-delta ones (plastic with alpha 0: a delta coat reflection over a diffuse
 * base). Then mc_bsdf_is_delta is 0, eval and pdf cover the non-delta lobes only (pdf already
 * scaled by the probability of choosing them), and sample returns either kind of lobe: a delta
 * sample has pdf = the discrete probability of that lobe and must be treated as specular (no
 * MIS: no other strategy can produce its direction), a non-delta sample has pdf = mc_bsdf_pdf.
 *
 * Roughness: metal, glass and plastic take the GGX α of struct material (α = roughness²).
 * α below MC_BSDF_SMOOTH_ALPHA is treated as a perfectly smooth (delta) interface.
 *
 * Transport mode (Veach 1997 §5.2; pbrt-v4 TransportMode): camera paths carry radiance, light
 * paths (photons, light tracing) importance. The BSDF that importance sees is the adjoint,
 * f*(wo, wi) = f(wi, wo), which differs from f only across a refracting interface: radiance is
 * compressed into the smaller solid angle on the denser side, so f_radiance(wo, wi) carries a
 * factor (n_wo/n_wi)² that f_importance lacks (Veach eq. 5.14: f(wo, wi)/n_wo² = f(wi, wo)/n_wi²).
 * Only eval and sample depend on the mode; pdf does not. The other asymmetry of light paths, that
 * of shading normals (Veach §5.3, pbrt-v4 §10.1.1), belongs to the integrator: it is a property of
 * the geometry, not of the BSDF in its local frame. */
#ifndef MCRT_BSDF_H
#define MCRT_BSDF_H

#include "core/vec.h"

struct material;
struct mc_material_ops;

enum mc_transport {
    MC_RADIANCE,  /* camera paths: wo toward the camera, wi toward the light */
    MC_IMPORTANCE /* light paths: wo toward the light, wi toward the camera */
};

/* The α below which a surface is perfectly smooth, pbrt-v4's threshold for an "effectively
 * smooth" TrowbridgeReitzDistribution. Such a lobe, ~2α = 0.1° wide, blurs a reflection by a
 * few pixels at most (a 40° view 1000 pixels wide has 0.04° pixels). As a delta lobe it costs
 * no light sample (one would almost never land in so narrow a lobe, and MIS would give it
 * almost no weight when it did), its paths stay specular and noise-free, and the microfacet
 * code never meets the ever larger D ~ 1/(πα²) (3e5 here) of smaller α. So α = 1e-4 renders
 * exactly as the mirror. */
#define MC_BSDF_SMOOTH_ALPHA 1e-3f

/* The multiple-scattering compensation of rough glass (dielectric_ms.c; Kulla and Conty 2017):
 * the single-scattering GGX dielectric's directional energy albedo Ê from each side, tabulated
 * for one material (α, ior) at MC_MS_NODES nodes x_k = k/(MC_MS_NODES − 1) of x = √μ, and the
 * constants of the added lobe. Side 0 is the outside, 1 the inside. */
#define MC_MS_NODES 32
struct mc_dielectric_ms {
    float e[2][MC_MS_NODES];   /* Ê at x_k, linearly interpolated in x */
    float cdf[2][MC_MS_NODES]; /* sampling μ on a side: probability of the segments before node k */
    float norm[2];             /* 1/(π W) of that sampling density (dielectric_ms.c) */
    float c[2][2];             /* f_ms(wo on a, wi on b) = c[a][b] (1 − Ê_a(μo)) (1 − Ê_b(μi)) */
    float t[2];                /* the share of side a's compensated energy that crosses */
    int ready;                 /* filled (mc_bsdf_prepare) for this material's α and ior */
};

struct bsdf {
    const struct mc_material_ops *ops; /* the material's kind (material.h) */
    int delta;       /* every lobe is a delta lobe (mc_bsdf_is_delta) */
    vec3 color;      /* albedo / mirror reflectance / glass tint / plastic base albedo */
    float ior;       /* glass, plastic: inside over outside */
    float alpha;     /* GGX α (metal, glass, plastic); 0: smooth (set for α < MC_BSDF_SMOOTH_ALPHA) */
    vec3 eta, k;     /* metal: complex index of refraction η + ik per channel */
    vec3 albedo;     /* plastic: directional albedo of the base seen through a smooth coat, per
                        unit coat transmittance (plastic.c) */
    float fdr;       /* plastic: the coat's hemispherical-average Fresnel reflectance from outside */
    const struct mc_dielectric_ms *ms; /* rough glass: its material's compensation, or NULL
                                          (material not prepared: single scattering only) */
};

struct bsdf_sample {
    vec3 wi;
    vec3 weight;     /* f·|cos θi| / pdf (for delta lobes: the lobe's weight) */
    float pdf;       /* solid angle; for delta lobes the discrete probability of the lobe */
    int delta;       /* wi came from a delta lobe */
    float eta;       /* relative ior crossed (ior or 1/ior on transmission, else 1): RR uses it */
};

/* Per-material precomputation, once the material's parameters are final (mc_scene_prepare):
 * rough glass tabulates its multiple-scattering compensation in m->ms (~1 ms, deterministic);
 * other materials mark it unused. */
void mc_bsdf_prepare(struct material *m);
/* b refers to m (rough glass's compensation table), which must outlive it. */
void mc_bsdf_init(struct bsdf *b, const struct material *m);
/* The same with the colour and α given (a textured material's at a hit: mc_scene_bsdf). */
void mc_bsdf_init_at(struct bsdf *b, const struct material *m, vec3 color, float alpha);
/* Whether every lobe is a delta lobe (no light sampling is useful then): mirror, smooth glass
 * (or glass of ior 1, which is no interface at all), smooth metal. */
static inline int mc_bsdf_is_delta(const struct bsdf *b) { return b->delta; }
/* Whether mc_bsdf_sample reads uc (material.h, chooses); where it does not, pass any value. */
int mc_bsdf_chooses(const struct bsdf *b);
/* Whether light can cross the surface (glass); every other kind only reflects. */
int mc_bsdf_transmits(const struct bsdf *b);
vec3 mc_bsdf_eval(const struct bsdf *b, vec3 wo, vec3 wi, enum mc_transport mode);
float mc_bsdf_pdf(const struct bsdf *b, vec3 wo, vec3 wi);
/* uc chooses a lobe, u the direction. Returns 0 when no direction was produced. */
int mc_bsdf_sample(const struct bsdf *b, vec3 wo, float uc, vec2 u, enum mc_transport mode,
                   struct bsdf_sample *out);

/* Exact unpolarised Fresnel reflectance of a dielectric interface (Born and Wolf; pbrt-v4
 * eq. 9.6): cos_i is the cosine on the incident side (negative: incidence from inside), eta the
 * ratio of inside to outside ior. Returns 1 under total internal reflection. */
float mc_fresnel_dielectric(float cos_i, float eta);
/* Exact unpolarised Fresnel reflectance of a conductor of complex ior η + ik (per channel, relative
 * to the outside) at incidence cosine cos_i in [0, 1] (pbrt-v4 FrComplex). */
vec3 mc_fresnel_conductor(float cos_i, vec3 eta, vec3 k);
/* The η = 1 and k of a metal whose reflectance at normal incidence is r (each channel clamped
 * to [0, 0.9999] so that k stays finite); the "metal RGB" form of the scene language. */
void mc_metal_from_reflectance(vec3 r, vec3 *eta, vec3 *k);

#endif
