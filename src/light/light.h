/* light.h: emitters — point lights, area lights (emitting primitives) and the environment
 * (constant or an image map, light/envmap.h) — with sampling by solid angle, and the bounds by
 * which a shading point's light is chosen (light/select.h). */
#ifndef MCRT_LIGHT_H
#define MCRT_LIGHT_H

#include <stddef.h>

#include "geom/motion.h"
#include "geom/prim.h"

struct envmap;

/* The kinds of light, X(KIND, name): each is the file src/light/NAME.c, which defines the
 * functions of light/light_impl.h and the descriptor below. Adding a kind is that file and a line
 * here (and, to export it, one in export/pov.c). */
#define MC_LIGHTS(X) X(LIGHT_POINT, point) X(LIGHT_AREA, area) X(LIGHT_ENVIRONMENT, environment)
enum light_kind { MC_LIGHTS(MC_NAMES_ENUM) };
#define LIGHT_KIND_COUNT (0 MC_LIGHTS(MC_NAMES_COUNT))

struct light {
    enum light_kind kind;
    vec3 position;   /* point */
    vec3 intensity;  /* point: W/sr; environment: radiance */
    uint32_t prim;   /* area: the emitting primitive, */
    float area;      /* its area (mc_prim_area) and */
    float point_error; /* the bound on its points' error (mc_prim_point_error), kept with the
                        * light by scene/prepare.c so that sampling it does not recompute them */
    /* environment: the map (NULL: the constant sky of radiance `intensity`), which `intensity`
     * then scales; orient turns the map's own directions (light/envmap.h) into the world's;
     * image is 1 + the scene's image the map is made from (0: none), for preparation. */
    const struct envmap *map;
    frame orient;
    int image;
    double power;    /* scalar power (mean over channels) used for selection; set by prepare */
};

/* A kind of light in the scene language and in the integrators' eyes. */
struct light_desc {
    const char *block;                 /* its block, `block { KEY value ... }`; NULL: none (area
                                        * lights are made from emitting shapes) */
    int unique;                        /* at most one block per scene */
    int delta;                         /* a delta distribution: found by light sampling alone */
    const struct block_param *params;  /* at most MC_BLOCK_PARAMS */
    int nparams;
    /* Fill l (zeroed, kind set) from the parameters' values v[] (defaults applied). */
    void (*build)(struct light *l, const vec3 *v);
};
/* The descriptors and the kinds' names, indexed by enum light_kind; the names end in NULL
 * (core/names.h). */
extern const struct light_desc *const mc_light_kinds[LIGHT_KIND_COUNT];
extern const char *const mc_light_names[LIGHT_KIND_COUNT + 1];

/* What the light functions read of a prepared scene (scene/prepare.c fills it): the primitives
 * area lights index, the motions moving ones follow, and the radius of a sphere bounding the
 * scene (moving primitives over the whole shutter), which gives the environment its power. */
struct light_scene {
    const struct prim *prims;
    const struct motion *motions;
    float radius;
    vec3 center;     /* the centre of that sphere: the environment's emission disk faces it */
    float shutter[2];/* the camera's: moving emitters are bounded over it */
};

/* Where a light is and where it sends light, for choosing among lights by their importance to a
 * shading point (Conty Estevez and Kulla 2018, §4.1; light/select.h): every emitting point lies in
 * box; every emitting normal lies within θo of axis (cos_o = −1: any normal), and each sends
 * light within θe of its normal (a Lambertian emitter: θe = π/2, cos_e = 0); two_sided: the
 * normals' opposites too. phi scales the importance so that phi·cos θ'·cos θi/d² estimates π
 * times the irradiance the light gives a point at distance d: π·L·A for a planar emitter of
 * radiance L and area A (per side), π·L·πr² for a sphere (its silhouette's area, since θo = π
 * lets every point see a full cos θ' = 1), π·I for a point light of intensity I. */
struct light_bounds {
    struct aabb box;
    vec3 axis;
    float cos_o, cos_e;
    float phi;
    int two_sided;
};

/* A sample toward a light from a shading point. */
struct light_sample {
    vec3 wi;         /* unit direction toward the light */
    float dist;      /* distance to the sampled point (INFINITY for the environment) */
    vec3 point;      /* the sampled point (point and area lights) */
    vec3 normal;     /* its unit normal facing the shading point (area lights), else zero */
    vec3 L;          /* radiance arriving along -wi (before visibility) */
    float pdf;       /* solid-angle pdf of wi given this light; for a point light, 1 (delta) */
    int delta;       /* the light is a delta distribution (point light): no MIS */
};

/* A ray leaving a light, for tracing light paths (photons): pbrt-v4's Light::SampleLe. */
struct light_emission {
    vec3 p;          /* where it starts */
    vec3 n;          /* area lights: the unit normal at p on the side d leaves; environment: d (the
                      * normal of the disk it starts on); point lights: zero */
    vec3 d;          /* unit direction of travel */
    vec3 Le;         /* radiance leaving p along d; for a point light, its intensity (W/sr) */
    float pdf_pos;   /* density of p per unit area (point light: 1, a delta) */
    float pdf_dir;   /* density of d per unit solid angle, given p */
    vec3 weight;     /* Le·|n·d| / (pdf_pos·pdf_dir) (point light: Le / pdf_dir): the flux the
                      * ray carries, before dividing by the light's selection probability */
};

/* Sample a ray leaving l at scene time `time` (a moving emitter where it is then): u_pos chooses
 * the point, u_dir the direction. Area lights: a point uniform by area, a cosine-weighted
 * direction about the emitting side's normal (two-sided: either side, with probability ½ each,
 * so pdf_dir = |cos θ|/(2π)); point lights: a uniform direction; the environment: a direction
 * uniform on the sphere, starting on the disk of the bounding sphere's radius R that faces it
 * from outside the sphere (pdf_pos = 1/(πR²); pbrt-v3 InfiniteAreaLight::Sample_Le). Returns 0
 * when there is no ray (zero pdf). */
int mc_light_sample_emission(const struct light_scene *s, const struct light *l, float time,
                             vec2 u_pos, vec2 u_dir, struct light_emission *out);

/* Scalar power of a light (mean over RGB channels), for selection. */
double mc_light_power(const struct light_scene *s, const struct light *l);
/* The bounds of l (a moving emitter over the whole shutter); 0 for a light without bounds (the
 * environment), which is chosen apart. */
int mc_light_bounds(const struct light_scene *s, const struct light *l, struct light_bounds *b);
/* Sample a direction toward l from point p at scene time `time` (a moving emitter is sampled where
 * it is then). Returns 0 when there is no sample (pdf 0, or the
 * sampled point shows p its non-emitting side). */
int mc_light_sample(const struct light_scene *s, const struct light *l, vec3 p, float time,
                    vec2 u, struct light_sample *out);
/* Solid-angle pdf that mc_light_sample would have given direction wi from p at `time`, given that
 * the ray p + t·wi first hits light l's primitive at distance t with surface sf (area lights; sf
 * in world space at that time), or escapes (environment). */
float mc_light_pdf(const struct light_scene *s, const struct light *l, vec3 p, float time,
                   vec3 wi, float t, const struct surface *sf);
/* Radiance the environment light l sends back along a ray leaving in direction d (unit). */
vec3 mc_environment_radiance(const struct light *l, vec3 d);

/* Radiance emitted by primitive pr back along the ray that found surface sf (0 when the side the
 * ray arrived on does not emit). */
vec3 mc_light_emitted(const struct prim *pr, const struct surface *sf);

#endif
