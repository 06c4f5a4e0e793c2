/* bsdf.h: scattering at a surface. One interface (eval, pdf, sample) for every material.
 *
 * Rules, written once here: directions are in the local shading frame (z = shading normal on the
 * primitive's front side); wo (toward the viewer) and wi (toward the light) both point away from
 * the surface; eval returns f without the cosine; pdf is per unit solid angle of wi; sample
 * returns the weight f·|cos θi| / pdf. Delta lobes (mirror, smooth glass) have eval = pdf = 0 and
 * are reached only through sample, which sets delta. Opaque materials behave the same on both
 * faces (wo.z < 0 is handled by mirroring); glass's front side (z > 0) is its outside. */
#ifndef MCRT_BSDF_H
#define MCRT_BSDF_H

#include "core/vec.h"

struct material;

struct bsdf {
    int kind;        /* enum material_kind */
    vec3 color;      /* albedo / reflectance / tint */
    float ior;       /* glass */
};

struct bsdf_sample {
    vec3 wi;
    vec3 weight;     /* f·|cos θi| / pdf (for delta lobes: the lobe's weight) */
    float pdf;       /* solid angle; for delta lobes the discrete probability of the lobe */
    int delta;       /* wi came from a delta lobe */
    float eta;       /* relative ior crossed (ior or 1/ior on transmission, else 1): RR uses it */
};

void mc_bsdf_init(struct bsdf *b, const struct material *m);
/* Whether every lobe is a delta lobe (no light sampling is useful then). */
int mc_bsdf_is_delta(const struct bsdf *b);
vec3 mc_bsdf_eval(const struct bsdf *b, vec3 wo, vec3 wi);
float mc_bsdf_pdf(const struct bsdf *b, vec3 wo, vec3 wi);
/* uc chooses a lobe, u the direction. Returns 0 when no direction was produced. */
int mc_bsdf_sample(const struct bsdf *b, vec3 wo, float uc, vec2 u, struct bsdf_sample *out);

/* Exact unpolarised Fresnel reflectance of a dielectric interface (Born and Wolf; pbrt-v4
 * eq. 9.6): cos_i is the cosine on the incident side (negative: incidence from inside), eta the
 * ratio of inside to outside ior. Returns 1 under total internal reflection. */
float mc_fresnel_dielectric(float cos_i, float eta);

#endif
