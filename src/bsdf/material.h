/* material.h: a material's parameters and the table of material kinds. The kinds are the lines of
 * materials.def; the scene parser (its keys, defaults and checks), the scene's features, the
 * POV-Ray exporter, the manual's check (tests/docs.sh) and the generic BSDF tests read them from
 * mc_material_kinds, and the BSDF (bsdf.h) dispatches through each kind's mc_material_ops, so
 * that a new kind is one file plus one line of materials.def. */
#ifndef MCRT_MATERIAL_H
#define MCRT_MATERIAL_H

#include <stddef.h>

#include "bsdf/bsdf.h"

/* What follows a kind's keyword in a material block. */
enum mc_material_value {
    MC_VALUE_ALBEDO,        /* an RGB in [0, 1]: the material's color */
    MC_VALUE_NONE,          /* nothing */
    MC_VALUE_ALBEDO_OR_NONE /* an albedo, or nothing (the kind's complete() says what then) */
};

/* The keys a kind may take besides its keyword; each sets the struct material field of its name
 * (tint: color; roughness r: alpha = r²; texture and roughness_texture: the fields of those
 * names, a texture's index + 1). */
enum mc_material_key { MC_KEY_IOR, MC_KEY_TINT, MC_KEY_ROUGHNESS, MC_KEY_ALPHA, MC_KEY_ETA, MC_KEY_K,
                       MC_KEY_TEXTURE, MC_KEY_ROUGHNESS_TEXTURE, MC_KEY_COUNT };
#define MC_KEY_BIT(key) (1u << (key))
#define MC_KEYS_ROUGHNESS (MC_KEY_BIT(MC_KEY_ROUGHNESS) | MC_KEY_BIT(MC_KEY_ALPHA))
/* In the `given` set of mc_material_ops.complete: the keyword was followed by numbers. */
#define MC_GIVEN_VALUE (1u << MC_KEY_COUNT)

/* Index of each kind in mc_material_kinds (MC_MATERIAL_diffuse, ...). */
enum mc_material_id {
#define MC_MATERIAL(name, value, noun, keys) MC_MATERIAL_##name,
#include "bsdf/materials.def"
#undef MC_MATERIAL
    MC_MATERIAL_COUNT
};

struct material {
    char name[64];
    const struct mc_material_kind *kind;
    vec3 color;                      /* diffuse albedo, mirror reflectance, glass tint,
                                        metal reflectance at normal incidence, plastic base */
    float ior;                       /* glass, plastic: index of refraction inside / outside (1.5) */
    float alpha;                     /* GGX α = roughness² (metal, glass, plastic); 0 = smooth */
    vec3 eta, k;                     /* metal: complex index of refraction per channel */
    /* Textures (scene/texture.h), as 1 + the scene's texture index, 0 for none. At a hit the
     * BSDF's colour is color × texture(uv), and its α is alpha × r² for the roughness texture's
     * value r (the mean of its channels): the texture gives the roughness, scaled by the
     * material's (mc_scene_bsdf). */
    int texture, roughness_texture;
    struct mc_dielectric_ms ms;      /* rough glass: filled by mc_bsdf_prepare */
};

/* The largest base albedo of plastic (plastic.c says why): the exporters write the capped value. */
#define MC_PLASTIC_MAX_ALBEDO 0.999f

/* Whether every lobe of a kind is a delta lobe (mc_bsdf_is_delta). */
enum mc_delta {
    MC_DELTA_NEVER,
    MC_DELTA_ALWAYS,
    MC_DELTA_WHEN_SMOOTH /* when the BSDF's α is 0 (mc_bsdf_init) */
};

/* What a kind's complete() found wrong: the message, and where it points: the kind's keyword
 * (key < 0) or key `key`, its first number when at_number. */
struct mc_material_problem {
    int key, at_number;
    char what[192];
};

/* A representative parameter set of a kind, for the tests that hold for every material
 * (tests/unit/test_materials.c). furnace > 0: the set reflects and transmits all it receives,
 * so its directional albedo is 1 within furnace (plus the estimate's noise) at every wo. */
struct mc_material_example {
    vec3 color;
    float ior, alpha;
    vec3 eta, k;
    double furnace;
};

/* A kind's behaviour, defined in its own file as mc_material_ops_<name> (bsdf_impl.h lists them;
 * bsdf.h states the rules eval, pdf and sample follow). */
struct mc_material_ops {
    const char *what;                /* what it is in a few words, for messages ("glossy metal") */
    enum mc_delta delta;
    /* Whether sample reads its 1D number uc: a choice between reflection and transmission (glass)
     * or between the coat and the base (plastic). The others ignore it, and the integrators then
     * draw none (mc_bsdf_chooses): a sampler dimension spent on nothing costs a draw (130
     * instructions of a Sobol sample) and nothing else. */
    int chooses;
    /* After the parser has set the fields the given keys name (`given`: MC_KEY_BITs and
     * MC_GIVEN_VALUE), derive the rest (metal: η and k from a reflectance) and check them.
     * Returns 0 with *p filled when they are wrong. NULL: nothing to derive or check. */
    int (*complete)(struct material *m, unsigned given, struct mc_material_problem *p);
    void (*prepare)(struct material *m);                   /* NULL: nothing to precompute */
    void (*init)(struct bsdf *b, const struct material *m); /* NULL: the common fields suffice */
    /* NULL for kinds that are always delta (never called: mc_bsdf_eval and pdf return 0). */
    vec3 (*eval)(const struct bsdf *b, vec3 wo, vec3 wi, enum mc_transport mode);
    float (*pdf)(const struct bsdf *b, vec3 wo, vec3 wi);
    int (*sample)(const struct bsdf *b, vec3 wo, float uc, vec2 u, enum mc_transport mode,
                  struct bsdf_sample *out);
    const struct mc_material_example *examples;
    int example_count;
};

/* One line of materials.def. */
struct mc_material_kind {
    const char *name;
    enum mc_material_value value;
    const char *noun;
    unsigned keys;
    const struct mc_material_ops *ops;
};

extern const struct mc_material_kind mc_material_kinds[MC_MATERIAL_COUNT];
#define MC_MATERIAL_KIND(name) (&mc_material_kinds[MC_MATERIAL_##name])
/* Their keywords, NULL at [MC_MATERIAL_COUNT] (core/names.h), for listing them (mcrt_names). */
extern const char *const mc_material_names[MC_MATERIAL_COUNT + 1];

/* The lobes of material m, for the scene's features. */
enum { MC_LOBE_SPECULAR = 1 << 0, MC_LOBE_GLOSSY = 1 << 1 };
unsigned mc_material_lobes(const struct material *m);

#endif
