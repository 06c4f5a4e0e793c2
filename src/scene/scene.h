/* scene.h: the parsed scene, the owning container every later stage reads.
 * The parser fills it (mc_scene_* adders), mc_scene_prepare builds the BVH and light table, and
 * from then on it is read-only and shared by all render threads. */
#ifndef MCRT_SCENE_H
#define MCRT_SCENE_H

#include <stddef.h>

#include "bsdf/material.h"  /* struct material */
#include "camera/camera.h"  /* struct camera_desc */
#include "core/diag.h"
#include "geom/bvh.h"
#include "geom/motion.h"
#include "light/envmap.h"
#include "light/light.h"
#include "light/select.h"
#include "sample/filter.h"   /* enum filter_kind */
#include "sample/sampler.h"  /* enum sampler_kind */
#include "scene/integrators.h"
#include "scene/texture.h"

#define MC_INTEGRATOR_ENUM(id, name) INTEGRATOR_##id,
enum integrator_kind { MC_INTEGRATORS(MC_INTEGRATOR_ENUM) INTEGRATOR_COUNT };
#undef MC_INTEGRATOR_ENUM
/* The integrators' names by kind, NULL at [INTEGRATOR_COUNT] (core/names.h): the scene's
 * `method` words and mcrt_options.integrator's. */
extern const char *const mc_integrator_names[INTEGRATOR_COUNT + 1];
/* How the path tracer finds light: both ways weighted by MIS, or one way only (for measuring). */
enum strategy { STRATEGY_MIS, STRATEGY_BSDF, STRATEGY_LIGHT };

struct film_desc {
    int width, height, spp;          /* 512, 512, 16 */
    enum sampler_kind sampler;       /* stratified */
    enum filter_kind filter;         /* box */
};

struct integrator_desc {
    enum integrator_kind method;     /* path */
    int max_depth;                   /* bounces; -1 = unlimited (Russian roulette ends paths) */
    int rr_depth;                    /* Russian roulette starts after this many bounces: 5 */
    int light_samples;               /* shadow rays per non-delta hit: 1 */
    enum strategy strategy;          /* mis */
    enum light_select_kind light_select; /* power */
    /* Stochastic progressive photon mapping (integrator/sppm.c): */
    long photons;                    /* photons per pass; 0 = the film's pixel count */
    float radius;                    /* initial gather radius; 0 = 5 × the scene's bounding radius
                                        / the film's larger side (Mitsuba's default) */
    float alpha;                     /* the fraction of new photons kept: 2/3 */
};

/* An image file the scene uses (an environment map, an image texture): the parser names it, the
 * API layer reads it (the core reads no image file, src/README) and hands the pixels over with
 * mc_scene_set_image. */
struct scene_image {
    char *path;                      /* as opened: under the scene's folder (owned) */
    char *origin;                    /* where the scene names it, "FILE:LINE:COL", for messages
                                        about the image (owned) */
    float *rgb;                      /* w·h·3 linear floats, rows top to bottom; NULL until set
                                        (owned, malloc'd) */
    int w, h;
};

/* Constructs an exporter may refuse (export/), by where the scene text first uses them, so that a
 * refusal points there as "file:line:col:". */
enum scene_mark {
    MARK_INTEGRATOR,        /* the integrator block */
    MARK_CAMERA_MOVE,       /* a camera's nonzero `move` */
    MARK_SHAPE_MOVE,        /* a shape's nonzero `move` or a mesh's nonzero `spin` */
    MARK_TWO_SIDED_EMITTER, /* `two_sided` on an emitting shape */
    MARK_ENVIRONMENT,       /* the environment block */
    MARK_TEXTURE,           /* a material's `texture` or `roughness_texture` */
    MARK_COUNT
};
struct scene_pos {
    int line, col;                   /* 1-based; line 0: not in the text */
};

struct scene {
    char *name;                      /* the scene's name in messages, as parsed (owned); NULL
                                        for a scene not parsed */
    struct scene_pos marks[MARK_COUNT];
    struct film_desc film;
    struct camera_desc camera;
    struct integrator_desc integrator;

    struct material *materials;      /* [0] is the default: diffuse 0.8, named "" */
    size_t material_count, material_cap;

    struct prim *prims;
    size_t prim_count, prim_cap;
    vec3 *normals;                   /* mesh triangles' corner attributes (prim.normals): shading
                                        normals, 3 per triangle, zero when flat */
    size_t normal_count, normal_cap;
    vec2 *uvs;                       /* their texture coordinates, uvs[i] for normals[i]; NULL
                                        until some mesh has them (uv_cap = 0 then) */
    size_t uv_cap;

    struct motion *motions;          /* a moving primitive's motion is motions[prim.motion - 1] */
    size_t motion_count, motion_cap;

    struct light *lights;            /* as parsed; prepare adds the area lights and puts the
                                        environment (given or the default sky) last */
    size_t light_count, light_cap;

    uint64_t hash;                   /* FNV-1a (core/hash.h) of the scene's inputs in the order
                                        read: its text, each OBJ and MTL file, each image's
                                        pixels (for render states); MC_HASH_INIT before them */
    char *warnings;                  /* about the input, one line each ending in '\n' ("file:
                                        line:col: warning: what"); NULL when none (owned) */
    size_t warnings_len;

    struct scene_image *images;
    size_t image_count, image_cap;
    struct texture *textures;        /* what materials' texture fields index (minus 1) */
    size_t texture_count, texture_cap;
    struct envmap *envmap;           /* the environment's map, built by prepare (or NULL) */

    /* Built by mc_scene_prepare: prims[0, static_count) are static, in `bvh`; the moving ones
     * follow, in `motion_bvh`, bounded over the whole shutter. */
    struct bvh bvh;
    struct bvh motion_bvh;
    size_t static_count;
    struct light_scene light_scene;  /* what the light functions read: prims, motions, radius */
    struct light_select light_select;/* chooses the light of a light sample (light/select.h) */
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
/* A mesh triangle's corner attributes (prim.normals): its 3 shading normals (zero when flat) and
 * its 3 texture coordinates, or uv NULL for the triangle's own (its barycentrics, geom/prim.h). */
int mc_scene_add_corners(struct scene *s, const vec3 n[3], const vec2 *uv);
int mc_scene_add_light(struct scene *s, const struct light *l);
/* A motion, for prims whose `motion` field is the returned index + 1; -1 when out of memory or
 * past 65535 motions. */
int mc_scene_add_motion(struct scene *s, const struct motion *m);
/* An image to be read from path, named at origin ("FILE:LINE:COL"; both copied); the new image's
 * index, or -1 when out of memory. */
int mc_scene_add_image(struct scene *s, const char *path, const char *origin);
/* A texture (copied); its index, or -1 when out of memory. */
int mc_scene_add_texture(struct scene *s, const struct texture *t);
/* The index of an image texture of the file at path, named at origin ("FILE:LINE:COL", for its
 * messages), untransformed: an existing one if the scene has it, else a new one called `name`
 * (cut to 63 bytes), whose image is read with the scene's others (mc_scene_add_image). -1 when
 * out of memory. For the scene language's `texture` block and OBJ materials' maps alike. */
int mc_scene_image_texture(struct scene *s, const char *name, const char *path, const char *origin);
/* Index of the texture with this name, or -1. */
int mc_scene_find_texture(const struct scene *s, const char *name);
/* Give image i its pixels: rgb (w·h·3 floats, malloc'd) becomes the scene's. */
void mc_scene_set_image(struct scene *s, size_t i, float *rgb, int w, int h);
/* Add the warning the format makes ("file:line:col: warning: what", without a newline), unless the
 * scene has it already; 0, or -1 when out of memory. */
int mc_scene_warn(struct scene *s, const char *fmt, ...) MC_PRINTF(2, 3);
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
/* The texture coordinates of the hit (mc_prim_uv), a moving primitive's in its own frame. */
vec2 mc_scene_uv(const struct scene *s, const struct ray *r, const struct hit *h);
/* The BSDF at a hit: its primitive's material, with its textures evaluated at the hit's texture
 * coordinates (material.h says how). A material without textures costs one test. */
void mc_scene_bsdf(const struct scene *s, const struct ray *r, const struct hit *h, struct bsdf *b);

/* Parse scene text (parse.c). name is used in messages; base_dir is where relative OBJ paths start
 * (NULL = current directory). On failure the message is "name:line:col: what is wrong" and s is
 * left in a state that mc_scene_free handles. */
mcrt_status mc_scene_parse(struct scene *s, const char *text, size_t len, const char *name,
                           const char *base_dir, mc_diag *d);

/* Every word of the scene language, from the parser's tables: word(user, BLOCK, NULL, NULL) for
 * each block kind, word(user, BLOCK, KEY, NULL) for each of its keys and word(user, BLOCK, KEY,
 * VALUE) for each value a choice key takes (tests/tools/words lists them for tests/docs.sh). */
void mc_scene_words(void (*word)(void *user, const char *block, const char *key,
                                  const char *value),
                    void *user);

#endif
