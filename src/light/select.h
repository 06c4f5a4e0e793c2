/* select.h: choosing the light of one light sample at a shading point, by one of the strategies
 * of MC_LIGHT_SELECTS, and the probability of that choice for multiple importance sampling (a
 * BSDF sample that hits a light weighs it against the light samples that could have chosen it,
 * at the same point with the same normal: the pmf must be the one the choice used, or the MIS
 * weights no longer sum to one and the estimate is biased).
 *
 * tree: the bounded lights (area and point lights) in a binary tree of light bounds
 * (light/light.h struct light_bounds), descended from the root by each child's importance to the
 * point: Conty Estevez and Kulla 2018, "Importance Sampling of Many Lights with Adaptive Tree
 * Splitting", §4 (without the splitting), as pbrt-v4's BVHLightSampler builds and reads it. The
 * environment, which has no bounds, is chosen first with probability I_env / (I_env + I_tree),
 * both estimates of π × the irradiance at the point: I_tree the importance of the root's two
 * children, I_env = π²·L̄ for an environment of mean radiance L̄ (that of a uniform sky on an
 * unoccluded surface), which is its power / R² (light/environment.c), times what its light
 * samples add to BSDF sampling under MIS: from 0.1 for a uniform sky, which BSDF sampling finds
 * as well by itself, to 1 for a map lit by a small sun (select.c, env_need). pbrt-v4 gives it a
 * fixed ½: measured worse on every scene tried (direct light, equal samples: glossy 0.0068 against
 * 0.0038 relative MSE, spheres 0.0101 against 0.0062; the sky map with a lamp 0.0129 against
 * 0.0099).
 * power: every light in proportion to its power, wherever the point (an alias table). */
#ifndef MCRT_LIGHT_SELECT_H
#define MCRT_LIGHT_SELECT_H

#include "light/light.h"
#include "sample/alias.h"

#define MC_LIGHT_SELECTS(X) X(LIGHT_SELECT_POWER, power) X(LIGHT_SELECT_TREE, tree)
enum light_select_kind { MC_LIGHT_SELECTS(MC_NAMES_ENUM) };
#define LIGHT_SELECT_COUNT (0 MC_LIGHT_SELECTS(MC_NAMES_COUNT))
/* The names, indexed by enum light_select_kind, ending in NULL (core/names.h). */
extern const char *const mc_light_select_names[LIGHT_SELECT_COUNT + 1];

/* A node of the tree: a leaf holds one light; an interior node's first child follows it, and
 * `index` is its second. Its light bounds (light/light.h) are kept in the form the importance
 * reads (select.c, importance), what depends on them alone made once at the build: a descent on
 * scenes of many lights spends most of its time there (many-lights, 10^4 triangles: 35% of the
 * render's instructions, 161 a node before). */
struct light_node {
    double center[3]; /* the centre of the bounds' box */
    double r, r2;     /* half its diagonal and its square: the radius of its bounding sphere */
    double sin_o;     /* sin θo */
    vec3 axis;
    float cos_o, cos_e, phi;
    uint32_t index;   /* leaf: the light; interior: the second child */
    uint16_t leaf, two_sided;
};

struct light_select {
    enum light_select_kind kind;
    struct mc_alias power;     /* every light by power: the power strategy, and photons */
    struct light_node *nodes;  /* the tree of the bounded lights; NULL when there are none */
    size_t node_count;
    uint64_t *trail;           /* per light: bit k set when the path from the root takes the
                                * second child at depth k; all ones for a light not in the tree */
    size_t light_count;
    int env;                   /* the environment light or -1 */
    double env_importance;     /* I_env */
};

/* Build both the tree and the power table over lights[0, n) (env: the environment's index or
 * -1), for the strategy `kind`. MCRT_ERR_NOMEM when out of memory (ls is then empty). */
mcrt_status mc_light_select_build(struct light_select *ls, enum light_select_kind kind,
                                  const struct light_scene *s, const struct light *lights,
                                  size_t n, int env, mc_diag *d);
void mc_light_select_free(struct light_select *ls);

/* A shading point as light selection sees it: the point p and its unit normal n (zero: none, as
 * in a medium) and, once a choice or a pmf there has needed them, what every choice at the point
 * shares: the importance of the tree's top and the environment's probability. A path tracer keeps
 * one per vertex, so that its light samples and the MIS weight of the light its BSDF sample finds
 * at the next vertex compute the top once (glossy-floor, where the top is the whole tree: the
 * pmf's descent cost 231 instructions, 3.5% of the render's, most of it that importance again). */
struct light_select_at {
    double p[3], n[3]; /* in double, as the importance reads them */
    int has_n;         /* n is not zero */
    int ready;         /* c and p_env are set */
    double c[2];  /* the importance of the root's two children; a leaf root's in c[0], c[1] 0 */
    double p_env; /* the probability of choosing the environment */
};

/* A shading point at p, n, its shared part not computed yet. */
static inline void mc_light_select_at(struct light_select_at *at, vec3 p, vec3 n)
{
    at->p[0] = p.x, at->p[1] = p.y, at->p[2] = p.z;
    at->n[0] = n.x, at->n[1] = n.y, at->n[2] = n.z;
    at->has_n = n.x != 0.0f || n.y != 0.0f || n.z != 0.0f;
    at->ready = 0;
}

/* Choose a light for the point at with one uniform u in [0, 1) (53 bits: pcg32_double,
 * mc_sampler_1d_double). Returns it and its probability in *pmf, or -1 (pmf 0) when no light can
 * reach the point. */
int mc_light_select_sample(const struct light_select *ls, struct light_select_at *at, double u,
                           double *pmf);
/* The probability that mc_light_select_sample chooses `light` at the point at: computed by the
 * same descent, so equal to the *pmf it returns bit for bit. */
double mc_light_select_pmf(const struct light_select *ls, struct light_select_at *at, int light);

#endif
