/* aov.h: first-surface data for extra image layers ("arbitrary output variables") and for the
 * denoiser's features: the albedo, the shading normal and the depth of the first non-specular
 * surface each camera ray meets (the ray followed through mirrors and smooth glass, as Intel Open
 * Image Denoise asks of its albedo and normal inputs), and the light emitted along the way,
 * averaged over a pixel's camera rays, per half of its samples (film.h) so that a feature's own
 * noise can be estimated and filtered as the colour's is. */
#ifndef MCRT_AOV_H
#define MCRT_AOV_H

#include <stdint.h>

#include "core/names.h"
#include "geom/ray.h"
#include "scene/scene.h"

struct aov_sums {
    double albedo[3], normal[3], depth, emission[3]; /* sums over the half's camera rays */
    double emission2[3];                             /* Σ emission², for its variance */
    uint64_t count;
};

struct aov_pixel {
    struct aov_sums half[2];
};

struct aov_film {
    int width, height;
    struct aov_pixel *pixels;
};

/* The extra image layers, X(KIND, NAME): the enum and the name that mcrt_options.aovs, the
 * EXR layer (NAME.R/G/B) and mcrt --help use. The variance (mc_film_variance) and the halves
 * (two layers, A and B: the means of each half of every pixel's samples, mc_film_resolve_half)
 * come from the film; the others are first-surface data recorded here. */
#define MC_AOVS(X)                                                                             \
    X(AOV_VARIANCE, "variance") X(AOV_HALVES, "halves") X(AOV_ALBEDO, "albedo")                \
    X(AOV_NORMAL, "normal") X(AOV_DEPTH, "depth") X(AOV_EMISSION, "emission")
enum aov_kind { MC_AOVS(MC_NAMES_ENUM) };
#define AOV_COUNT (0 MC_AOVS(MC_NAMES_COUNT))
/* The names by kind, NULL at [AOV_COUNT] (core/names.h). */
extern const char *const mc_aov_names[AOV_COUNT + 1];

/* Whether layer k comes from the film rather than from first surfaces. */
static inline int mc_aov_from_film(enum aov_kind k) { return k == AOV_VARIANCE || k == AOV_HALVES; }

/* Allocate a zeroed W×H film of first-surface data. Returns 0, or -1 when out of memory. */
int mc_aov_init(struct aov_film *a, int width, int height);
void mc_aov_free(struct aov_film *a);
/* Trace the camera ray r (unit direction) in s through delta (mirror, smooth glass) surfaces, up
 * to a few bounces, each taking the lobe a sampler's 0.5 would, and add to half h of p: the
 * colour of the first non-delta surface times the delta lobes' weights (0 for a miss), its unit
 * shading normal turned towards the incoming ray (0 for a miss), the path length to it (0 for a
 * miss), and the light emitted towards the camera by the surfaces (and the environment) met on
 * the way, times the same weights. */
void mc_aov_record(struct aov_pixel *p, int h, const struct scene *s, const struct ray *r);
/* One first-surface layer (any kind not mc_aov_from_film) as W·H·3 floats: the mean over each
 * pixel's camera rays of half h (0 or 1), or of both for h < 0 (0 without any); the normal is the
 * mean of unit vectors, not renormalised; depth fills all three channels. */
void mc_aov_resolve(const struct aov_film *a, enum aov_kind kind, int h, float *rgb);

/* The variance of each pixel's mean emission over both halves, from its samples: s²/n, the
 * sample variance s² of its n rays (0 below 2). Unbiased for independent samples, and biased up
 * for stratified and Sobol ones, whose means vary less (film.h): an estimate that errs on the
 * side of caution, for the denoiser's error estimate (denoise/nfor.h). */
void mc_aov_emission_variance(const struct aov_film *a, float *var);

#endif
