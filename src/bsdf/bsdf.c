/* bsdf.c: the material-independent BSDF interface of bsdf.h, dispatching on the material kind
 * to diffuse.c, specular.c, conductor.c, dielectric.c and plastic.c. */
#include "bsdf/bsdf_impl.h"

#include "scene/scene.h"

/* The α mc_bsdf_init gives material m: 0 (smooth) below MC_BSDF_SMOOTH_ALPHA. !(α >= …) also
 * sends a NaN α to the smooth case. A glass of ior 1 is no interface at all, rough or not: light
 * passes straight through (specular.c), as in pbrt-v4. */
static float effective_alpha(const struct material *m)
{
    return !(m->alpha >= MC_BSDF_SMOOTH_ALPHA) || (m->kind == MATERIAL_GLASS && m->ior == 1.0f) ? 0.0f : m->alpha;
}

void mc_bsdf_prepare(struct material *m)
{
    m->ms.ready = 0;
    if (m->kind == MATERIAL_GLASS && effective_alpha(m) > 0.0f)
        mc_dielectric_ms_build(&m->ms, m->alpha, m->ior);
}

void mc_bsdf_init(struct bsdf *b, const struct material *m)
{
    b->kind = (int)m->kind;
    b->color = m->color;
    b->ior = m->ior;
    b->alpha = effective_alpha(m);
    b->ms = b->kind == MATERIAL_GLASS && b->alpha > 0.0f && m->ms.ready ? &m->ms : NULL;
    b->eta = m->eta;
    b->k = m->k;
    b->albedo = v3s(0.0f);
    b->fdr = 0.0f;
    if (b->kind == MATERIAL_PLASTIC)
        mc_plastic_init(b);
}

int mc_bsdf_is_delta(const struct bsdf *b)
{
    switch (b->kind) {
    case MATERIAL_MIRROR: return 1;
    case MATERIAL_GLASS:
    case MATERIAL_METAL: return b->alpha == 0.0f;
    default: return 0; /* diffuse; plastic, whose base is never delta */
    }
}

vec3 mc_bsdf_eval(const struct bsdf *b, vec3 wo, vec3 wi)
{
    /* Delta lobes have no density a direction chosen elsewhere could hit. */
    if (mc_bsdf_is_delta(b))
        return v3s(0.0f);
    switch (b->kind) {
    case MATERIAL_DIFFUSE: return mc_diffuse_eval(b, wo, wi);
    case MATERIAL_METAL: return mc_conductor_eval(b, wo, wi);
    case MATERIAL_GLASS: return mc_dielectric_eval(b, wo, wi);
    case MATERIAL_PLASTIC: return mc_plastic_eval(b, wo, wi);
    default: return v3s(0.0f);
    }
}

float mc_bsdf_pdf(const struct bsdf *b, vec3 wo, vec3 wi)
{
    if (mc_bsdf_is_delta(b))
        return 0.0f;
    switch (b->kind) {
    case MATERIAL_DIFFUSE: return mc_diffuse_pdf(wo, wi);
    case MATERIAL_METAL: return mc_conductor_pdf(b, wo, wi);
    case MATERIAL_GLASS: return mc_dielectric_pdf(b, wo, wi);
    case MATERIAL_PLASTIC: return mc_plastic_pdf(b, wo, wi);
    default: return 0.0f;
    }
}

int mc_bsdf_sample(const struct bsdf *b, vec3 wo, float uc, vec2 u, struct bsdf_sample *out)
{
    switch (b->kind) {
    case MATERIAL_DIFFUSE: return mc_diffuse_sample(b, wo, u, out);
    case MATERIAL_MIRROR: return mc_specular_reflection(wo, b->color, 1.0f, out);
    case MATERIAL_GLASS:
        return b->alpha > 0.0f ? mc_dielectric_sample(b, wo, uc, u, out) : mc_glass_sample(b, wo, uc, out);
    case MATERIAL_METAL: return mc_conductor_sample(b, wo, u, out);
    case MATERIAL_PLASTIC: return mc_plastic_sample(b, wo, uc, u, out);
    default: return 0;
    }
}
