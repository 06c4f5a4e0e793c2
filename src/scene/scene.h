/* scene.h: the parsed scene, the owning container every later stage reads.
 * The parser fills it (mc_scene_* adders), mc_scene_prepare builds the BVH and light table, and
 * from then on it is read-only and shared by all render threads. */
#ifndef MCRT_SCENE_H
#define MCRT_SCENE_H

#include <stddef.h>

#include "bsdf/bsdf.h"      /* struct mc_dielectric_ms */
#include "core/diag.h"
#include "geom/bvh.h"
#include "geom/motion.h"
#include "light/light.h"
#include "sample/alias.h"
#include "sample/filter.h"   /* enum filter_kind */
#include "sample/sampler.h"  /* enum sampler_kind */

enum integrator_kind { INTEGRATOR_PATH, INTEGRATOR_DIRECT };
/* How the path tracer finds light: both ways weighted by MIS, or one way only (for measuring). */
enum strategy { STRATEGY_MIS, STRATEGY_BSDF, STRATEGY_LIGHT };
enum material_kind { MATERIAL_DIFFUSE, MATERIAL_MIRROR, MATERIAL_GLASS, MATERIAL_METAL, MATERIAL_PLASTIC };

struct film_desc {
    int width, height, spp;          /* 512, 512, 16 */
    enum sampler_kind sampler;       /* stratified */
    enum filter_kind filter;         /* box */
};

struct camera_desc {
    vec3 eye, look, up;              /* (0 0 5), (0 0 0), (0 1 0) */
    float fov;                       /* full vertical angle in degrees: 40 */
    float lens_radius;               /* thin lens; 0 = pinhole (the default) */
    float focus_distance;            /* along the view direction; 0 = |look - eye| (the default) */
    float shutter[2];                /* open and close times: 0 1 */
    vec3 move;                       /* translation of eye and look per unit time: 0 */
};

struct integrator_desc {
    enum integrator_kind method;     /* path */
    int max_depth;                   /* bounces; -1 = unlimited (Russian roulette ends paths) */
    int rr_depth;                    /* Russian roulette starts after this many bounces: 5 */
    int light_samples;               /* shadow rays per non-delta hit: 1 */
    enum strategy strategy;          /* mis */
};

struct material {
    char name[64];
    enum material_kind kind;
    vec3 color;                      /* diffuse albedo, mirror reflectance, glass tint,
                                        metal reflectance at normal incidence, plastic base */
    float ior;                       /* glass, plastic: index of refraction inside / outside (1.5) */
    float alpha;                     /* GGX α = roughness² (metal, glass, plastic); 0 = smooth */
    vec3 eta, k;                     /* metal: complex index of refraction per channel */
    struct mc_dielectric_ms ms;      /* rough glass: filled by mc_scene_prepare (mc_bsdf_prepare) */
};

struct scene {
    struct film_desc film;
    struct camera_desc camera;
    struct integrator_desc integrator;

    struct material *materials;      /* [0] is the default: diffuse 0.8, named "" */
    size_t material_count, material_cap;

    struct prim *prims;
    size_t prim_count, prim_cap;
    vec3 *normals;                   /* shading normals, 3 per smooth triangle */
    size_t normal_count, normal_cap;

    struct motion *motions;          /* a moving primitive's motion is motions[prim.motion - 1] */
    size_t motion_count, motion_cap;

    struct light *lights;            /* point lights as parsed; area and environment added by prepare */
    size_t light_count, light_cap;
    int has_environment;             /* an environment block was given */
    vec3 environment;                /* its radiance */

    /* Built by mc_scene_prepare: prims[0, static_count) are static, in `bvh`; the moving ones
     * follow, in `motion_bvh`, bounded over the whole shutter. */
    struct bvh bvh;
    struct bvh motion_bvh;
    size_t static_count;
    struct mc_alias light_select;    /* chooses a light in proportion to its power */
    int env_light;                   /* index of the environment light or -1 */
    int prepared;
};

/* An empty scene holding all defaults and the default material (material 0, which the parser's
 * materials follow); 0, or -1 when out of memory for that material (the scene is then empty, to
 * be freed). */
int mc_scene_init(struct scene *s);
void mc_scene_free(struct scene *s);

/* Adders: each returns the new element's index, or -1 when out of memory. */
int mc_scene_add_material(struct scene *s, const struct material *m);
int mc_scene_add_prim(struct scene *s, const struct prim *p);
int mc_scene_add_normals(struct scene *s, vec3 n0, vec3 n1, vec3 n2);
int mc_scene_add_light(struct scene *s, const struct light *l);
/* A motion, for prims whose `motion` field is the returned index + 1; -1 when out of memory or
 * past 65535 motions. */
int mc_scene_add_motion(struct scene *s, const struct motion *m);
/* Index of the material with this name, or -1. */
int mc_scene_find_material(const struct scene *s, const char *name);

/* Build the BVH and the light table; adds the default white sky when the scene has no light.
 * Idempotent. */
mcrt_status mc_scene_prepare(struct scene *s, mc_diag *d);

/* Ray queries on a prepared scene, static and moving primitives alike (trace.c). h->prim indexes
 * s->prims. The surface of a moving primitive is found in its time-0 frame and carried to the
 * world at r->time. */
int mc_scene_intersect(const struct scene *s, const struct ray *r, struct hit *h);
int mc_scene_occluded(const struct scene *s, const struct ray *r);
void mc_scene_surface(const struct scene *s, const struct ray *r, const struct hit *h,
                      struct surface *sf);

/* Parse scene text (parse.c). name is used in messages; base_dir is where relative OBJ paths start
 * (NULL = current directory). On failure the message is "name:line:col: what is wrong" and s is
 * left in a state that mc_scene_free handles. */
mcrt_status mc_scene_parse(struct scene *s, const char *text, size_t len, const char *name,
                           const char *base_dir, mc_diag *d);

#endif
