/* specular.c: the delta lobes: reflection about the normal (mirror, smooth metal, plastic's
 * smooth coat), with the mirror material, and a smooth dielectric (glass) interface.
 * Reference: pbrt-v4 §9.3 (ConductorBxDF specular case, DielectricBxDF::Sample_f). */
#include "bsdf/bsdf_impl.h"

int mc_specular_reflection(vec3 wo, vec3 weight, float pdf, struct bsdf_sample *out)
{
    if (wo.z == 0.0f)
        return 0; /* grazing: the reflection would lie in the surface */
    out->wi = v3(-wo.x, -wo.y, wo.z);
    out->weight = weight;
    out->pdf = pdf;
    out->delta = 1;
    out->eta = 1.0f;
    return 1;
}

int mc_glass_sample(const struct bsdf *b, vec3 wo, float uc, enum mc_transport mode, struct bsdf_sample *out)
{
    float f, etap;
    if (wo.z == 0.0f)
        return 0; /* grazing: reflection would lie in the surface and F = 1 leaves nothing else */
    f = mc_fresnel_dielectric(wo.z, b->ior);
    if (uc < f) {
        /* Reflection chosen with probability F: weight F/F = 1 (f·|cos|/pdf with the delta's
         * 1/|cos| cancelled). */
        return mc_specular_reflection(wo, v3s(1.0f), f, out);
    }
    /* Refraction (Snell). etap = ior of the transmitted side over the incident side; the front
     * side (z > 0) is outside, with ior 1. F < 1 here, and mc_refract computes the same
     * radicand as mc_fresnel_dielectric, so it finds no total internal reflection. */
    etap = wo.z > 0.0f ? b->ior : 1.0f / b->ior;
    if (!mc_refract(wo, v3(0.0f, 0.0f, wo.z > 0.0f ? 1.0f : -1.0f), etap, &out->wi))
        return 0;
    out->pdf = 1.0f - f;
    out->delta = 1;
    /* (1 − F)/(1 − F) times the tint, and for radiance 1/etap²: radiance is compressed into the
     * smaller solid angle on the denser side (Veach 1997 §5.2, non-symmetric scattering due to
     * refraction; pbrt-v4 TransportMode::Radiance). Importance has no such factor. */
    out->weight = mode == MC_RADIANCE ? v3_scale(b->color, 1.0f / (etap * etap)) : b->color;
    out->eta = etap;
    return 1;
}

static int mirror_sample(const struct bsdf *b, vec3 wo, float uc, vec2 u, enum mc_transport mode,
                         struct bsdf_sample *out)
{
    (void)uc;
    (void)u;
    (void)mode;
    return mc_specular_reflection(wo, b->color, 1.0f, out);
}

static const struct mc_material_example mirror_examples[] = {
    {{0.9f, 0.7f, 0.3f}, 1.5f, 0.0f, {0, 0, 0}, {0, 0, 0}, 0.0},
    {{1.0f, 1.0f, 1.0f}, 1.5f, 0.0f, {0, 0, 0}, {0, 0, 0}, 1e-6},
};

const struct mc_material_ops mc_material_ops_mirror = {
    "mirror", MC_DELTA_ALWAYS, 0, NULL, NULL, NULL, NULL, NULL, mirror_sample,
    mirror_examples, (int)(sizeof mirror_examples / sizeof mirror_examples[0])};
