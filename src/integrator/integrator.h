/* integrator.h: estimators of the radiance arriving along a camera ray. */
#ifndef MCRT_INTEGRATOR_H
#define MCRT_INTEGRATOR_H

#include <stdint.h>

#include "sample/sampler.h"
#include "scene/features.h"
#include "scene/scene.h"

/* The bounce limits a method implies: `direct` is the path tracer stopped after one bounce
 * (emitted light plus direct lighting at the first hit, with the same MIS), so that the two can
 * never disagree on what they share. */
struct integrator_desc mc_integrator_config(const struct integrator_desc *scene_desc,
                                            enum integrator_kind method);

/* Unidirectional path tracing with next-event estimation (cfg->light_samples shadow rays per
 * non-delta hit) and multiple importance sampling (Veach 1997, ch. 9, power heuristic β = 2)
 * between BSDF sampling and light sampling, and Russian roulette after cfg->rr_depth bounces.
 * Unbiased. Adds the rays it traced to *rays. The result may be non-finite only if the scene's
 * numbers are; callers count and drop such samples. */
typedef vec3 (*mc_path_fn)(const struct scene *s, const struct integrator_desc *cfg, struct ray r,
                           struct sampler *smp, uint64_t *rays);
/* The path tracer compiled for these features (scene/features.h); FEATURE_ALL gives the general
 * one, which renders every scene (the same image in expectation). */
mc_path_fn mc_path_kernel(unsigned features);

#endif
