/* bsdf.c: the material-independent BSDF interface of bsdf.h, dispatching through the kind's
 * mc_material_ops (material.h), and the table of kinds generated from materials.def. */
#include "bsdf/bsdf_impl.h"

const struct mc_material_kind mc_material_kinds[MC_MATERIAL_COUNT] = {
#define MC_MATERIAL(name, value, noun, keys) {#name, MC_VALUE_##value, noun, keys, &mc_material_ops_##name},
#include "bsdf/materials.def"
#undef MC_MATERIAL
};

const char *const mc_material_names[MC_MATERIAL_COUNT + 1] = {
#define MC_MATERIAL(name, value, noun, keys) #name,
#include "bsdf/materials.def"
#undef MC_MATERIAL
    NULL};

unsigned mc_material_lobes(const struct material *m)
{
    /* A kind with a roughness is smooth (delta lobes) below MC_BSDF_SMOOTH_ALPHA, glossy above;
     * one without has fixed lobes. */
    if (m->roughness_texture) /* α varies over the surface, down to the smooth limit */
        return MC_LOBE_SPECULAR | MC_LOBE_GLOSSY;
    if (m->kind->keys & MC_KEYS_ROUGHNESS)
        return m->alpha < MC_BSDF_SMOOTH_ALPHA ? MC_LOBE_SPECULAR : MC_LOBE_GLOSSY;
    return m->kind->ops->delta == MC_DELTA_ALWAYS ? MC_LOBE_SPECULAR : 0;
}

void mc_bsdf_prepare(struct material *m)
{
    m->ms.ready = 0;
    if (m->kind->ops->prepare)
        m->kind->ops->prepare(m);
}

void mc_bsdf_init(struct bsdf *b, const struct material *m) { mc_bsdf_init_at(b, m, m->color, m->alpha); }

void mc_bsdf_init_at(struct bsdf *b, const struct material *m, vec3 color, float alpha)
{
    const struct mc_material_ops *ops = m->kind->ops;
    b->ops = ops;
    b->color = color;
    b->ior = m->ior;
    /* !(α >= …) also sends a NaN α to the smooth case. */
    b->alpha = !(alpha >= MC_BSDF_SMOOTH_ALPHA) ? 0.0f : alpha;
    b->ms = NULL;
    b->eta = m->eta;
    b->k = m->k;
    b->albedo = v3s(0.0f);
    b->fdr = 0.0f;
    if (ops->init)
        ops->init(b, m);
    b->delta = ops->delta == MC_DELTA_ALWAYS || (ops->delta == MC_DELTA_WHEN_SMOOTH && b->alpha == 0.0f);
}

vec3 mc_bsdf_eval(const struct bsdf *b, vec3 wo, vec3 wi, enum mc_transport mode)
{
    /* Delta lobes have no density a direction chosen elsewhere could hit. */
    return b->delta ? v3s(0.0f) : b->ops->eval(b, wo, wi, mode);
}

int mc_bsdf_chooses(const struct bsdf *b) { return b->ops->chooses; }

int mc_bsdf_transmits(const struct bsdf *b) { return b->ops == &mc_material_ops_glass; }

float mc_bsdf_pdf(const struct bsdf *b, vec3 wo, vec3 wi)
{
    return b->delta ? 0.0f : b->ops->pdf(b, wo, wi);
}

int mc_bsdf_sample(const struct bsdf *b, vec3 wo, float uc, vec2 u, enum mc_transport mode,
                   struct bsdf_sample *out)
{
    return b->ops->sample(b, wo, uc, u, mode, out);
}
