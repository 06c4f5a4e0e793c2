/* features.c: the features a prepared scene uses (see features.h). */
#include "scene/features.h"

/* The lobes of a material that some primitive uses. */
static unsigned material_features(const struct material *m)
{
    unsigned lobes = mc_material_lobes(m);
    return (lobes & MC_LOBE_SPECULAR ? FEATURE_SPECULAR : 0) | (lobes & MC_LOBE_GLOSSY ? FEATURE_GLOSSY : 0)
           | (m->texture || m->roughness_texture ? FEATURE_TEXTURES : 0);
}

unsigned mc_scene_features(const struct scene *s)
{
    unsigned f = 0;
    size_t i;
    if (s->camera.lens_radius > 0.0f)
        f |= FEATURE_LENS;
    if (s->motion_count > 0 || !v3_is_zero(s->camera.move))
        f |= FEATURE_MOTION;
    if (s->integrator.light_samples > 1)
        f |= FEATURE_LIGHT_SAMPLES;
    for (i = 0; i < s->light_count; i++)
        f |= mc_light_kinds[s->lights[i].kind]->delta ? FEATURE_DELTA_LIGHTS
             : s->lights[i].kind == LIGHT_AREA         ? FEATURE_AREA_LIGHTS
                                                       : FEATURE_ENVIRONMENT;
    for (i = 0; i < s->prim_count; i++) {
        f |= material_features(&s->materials[s->prims[i].material]);
        if (s->prims[i].kind == PRIM_TRIANGLE)
            f |= FEATURE_MESHES;
    }
    return f;
}

const char *mc_feature_name(unsigned bit)
{
    switch (bit) {
    case FEATURE_LENS: return "lens";
    case FEATURE_MOTION: return "motion";
    case FEATURE_AREA_LIGHTS: return "area_lights";
    case FEATURE_DELTA_LIGHTS: return "delta_lights";
    case FEATURE_ENVIRONMENT: return "environment";
    case FEATURE_GLOSSY: return "glossy";
    case FEATURE_SPECULAR: return "specular";
    case FEATURE_MESHES: return "meshes";
    case FEATURE_LIGHT_SAMPLES: return "light_samples";
    case FEATURE_TEXTURES: return "textures";
    default: return "?";
    }
}

struct sample_dims mc_scene_dims(const struct scene *s, unsigned features)
{
    struct sample_dims d;
    int choose_lobe = 0;
    size_t i;
    for (i = 0; i < s->prim_count && !choose_lobe; i++)
        choose_lobe = s->materials[s->prims[i].material].kind->ops->chooses;
    d.camera = 2 + (features & FEATURE_LENS ? 2 : 0) + (features & FEATURE_MOTION ? 1 : 0);
    d.per_bounce = (2 + (s->light_count > 1)) * s->integrator.light_samples + 2 + choose_lobe;
    d.roulette = 1;
    return d;
}
