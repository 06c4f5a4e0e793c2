/* features.h: what a prepared scene uses, so that a render is built from only that (as Cycles
 * compiles feature-adaptive kernels): no lens or time samples for a still pinhole camera, no MIS
 * when every light is a delta light, no motion BVH query for a static scene. */
#ifndef MCRT_FEATURES_H
#define MCRT_FEATURES_H

#include <stddef.h>

#include "scene/scene.h"

enum feature {
    FEATURE_LENS = 1 << 0,          /* thin lens: two lens dimensions per camera ray */
    FEATURE_MOTION = 1 << 1,        /* a shape or the camera moves: a time dimension, motion BVH */
    FEATURE_AREA_LIGHTS = 1 << 2,   /* emitting shapes */
    FEATURE_DELTA_LIGHTS = 1 << 3,  /* point lights */
    FEATURE_ENVIRONMENT = 1 << 4,   /* the constant environment (given or the default sky) */
    FEATURE_GLOSSY = 1 << 5,        /* rough microfacet lobes */
    FEATURE_SPECULAR = 1 << 6,      /* delta lobes (mirror, smooth glass/metal/coat): specular chains */
    FEATURE_MESHES = 1 << 7,        /* triangles */
    FEATURE_LIGHT_SAMPLES = 1 << 8, /* several shadow rays per hit */
    FEATURE_TEXTURES = 1 << 9,      /* a material that some primitive uses has a texture */
    FEATURE_ALL = (1 << 10) - 1
};

/* The features of a prepared scene. */
unsigned mc_scene_features(const struct scene *s);

/* Whether light found by BSDF sampling must be weighted against light sampling: only when some
 * light has a non-delta distribution (area lights or the environment). */
static inline int mc_features_need_mis(unsigned f)
{
    return (f & (FEATURE_AREA_LIGHTS | FEATURE_ENVIRONMENT)) != 0;
}

/* Name of one feature bit ("lens", "motion", ...). */
const char *mc_feature_name(unsigned bit);

/* Sample dimensions one path through scene s (rendered with these features) draws: `camera` per
 * camera ray, `per_bounce` at most at each non-delta hit (light choice, when there are two lights
 * or more, and light point per shadow ray; the BSDF's choice of lobe, when a material some
 * primitive uses chooses one (bsdf.h, mc_bsdf_chooses), and its direction), plus one roulette
 * dimension per bounce from rr_depth on. */
struct sample_dims {
    int camera, per_bounce, roulette;
};
struct sample_dims mc_scene_dims(const struct scene *s, unsigned features);

#endif
