/* aov.h: first-hit data for extra image layers ("arbitrary output variables"): the albedo, the
 * shading normal and the depth of the surface each camera ray meets first, averaged over a pixel's
 * camera rays, as denoisers (e.g. Intel Open Image Denoise's albedo and normal inputs) and
 * compositing use them. */
#ifndef MCRT_AOV_H
#define MCRT_AOV_H

#include <stdint.h>

#include "core/names.h"
#include "geom/ray.h"
#include "scene/scene.h"

struct aov_pixel {
    double albedo[3], normal[3], depth; /* sums over the pixel's camera rays */
    uint64_t count;
};

struct aov_film {
    int width, height;
    struct aov_pixel *pixels;
};

/* The extra image layers, X(KIND, NAME): the enum and the name that mcrt_options.aovs, the
 * EXR layer (NAME.R/G/B) and mcrt --help use. The variance (mc_film_variance) and the halves
 * (two layers, A and B: the means of each half of every pixel's samples, mc_film_resolve_half)
 * come from the film; the others are first-hit data recorded here. */
#define MC_AOVS(X)                                                                             \
    X(AOV_VARIANCE, "variance") X(AOV_HALVES, "halves") X(AOV_ALBEDO, "albedo")                \
    X(AOV_NORMAL, "normal") X(AOV_DEPTH, "depth")
enum aov_kind { MC_AOVS(MC_NAMES_ENUM) };
#define AOV_COUNT (0 MC_AOVS(MC_NAMES_COUNT))
/* The names by kind, NULL at [AOV_COUNT] (core/names.h). */
extern const char *const mc_aov_names[AOV_COUNT + 1];

/* Whether layer k comes from the film rather than from first hits. */
static inline int mc_aov_from_film(enum aov_kind k) { return k == AOV_VARIANCE || k == AOV_HALVES; }

/* Allocate a zeroed W×H film of first-hit data. Returns 0, or -1 when out of memory. */
int mc_aov_init(struct aov_film *a, int width, int height);
void mc_aov_free(struct aov_film *a);
/* Trace the camera ray r (unit direction) in s and add what it meets first to p: the material's
 * colour (0 for a miss), the unit shading normal turned towards the camera (0 for a miss), and
 * the distance along r (0 for a miss). */
void mc_aov_record(struct aov_pixel *p, const struct scene *s, const struct ray *r);
/* One first-hit layer (any kind not mc_aov_from_film) as W·H·3 floats: the mean over each pixel's
 * camera rays (0 without any); the normal is the mean of unit vectors, not renormalised; depth
 * fills all three channels. */
void mc_aov_resolve(const struct aov_film *a, enum aov_kind kind, float *rgb);

#endif
