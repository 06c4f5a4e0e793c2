/* filter.h: pixel reconstruction filters, applied by filter importance sampling (Ernst, Stamminger
 * and Greiner 2006, "Filter Importance Sampling", IEEE RT; pbrt-v4 §8.8): each camera sample is
 * placed at an offset from the pixel centre distributed as the normalised filter, and every sample
 * then has weight 1. A pixel is the plain mean of its own samples, so pixels stay independent
 * and deterministic (no splatting into neighbours), and a filter with negative lobes is not
 * needed by any of the kinds here.
 *
 * Every sampling map is a smooth, monotone function of u (an analytic inverse CDF), so the
 * stratification of the film dimension carries over to the offsets. */
#ifndef MCRT_FILTER_H
#define MCRT_FILTER_H

#include "core/names.h"
#include "core/vec.h"

/* The filters, X(KIND, NAME): the enum and the scene language's name (film `filter`).
 *   box       1 on [-½, ½]²; offset = u − ½, so the film point is x + u exactly.
 *   tent      (1 − |x|)(1 − |y|) on [-1, 1]²: separable, each axis by its inverse CDF.
 *   gaussian  radially symmetric, σ = ½ pixel, truncated to the disk of radius 3σ = 1.5 pixels
 *             (the tail beyond holds e^-4.5 ≈ 1.1% of the mass and is cut, not folded back):
 *             p(r) = exp(−r²/2σ²) / (2πσ²(1 − e^-4.5)) for r < 1.5. Sampled exactly: the
 *             truncated Rayleigh radius by its inverse CDF from u.x, the angle 2π·u.y. */
#define MC_FILTERS(X) X(FILTER_BOX, "box") X(FILTER_TENT, "tent") X(FILTER_GAUSSIAN, "gaussian")
enum filter_kind { MC_FILTERS(MC_NAMES_ENUM) };
#define FILTER_COUNT (0 MC_FILTERS(MC_NAMES_COUNT))
/* The names by kind, NULL at [FILTER_COUNT] (core/names.h). */
extern const char *const mc_filter_names[FILTER_COUNT + 1];

/* Offset from the pixel centre, in pixels, distributed as the normalised filter; u in [0,1)². */
vec2 mc_filter_sample(enum filter_kind k, vec2 u);
/* The normalised filter: the density of mc_filter_sample's offsets, in pixels^-2. */
float mc_filter_pdf(enum filter_kind k, vec2 offset);
/* Half-width of the filter's support in pixels (the support lies in the square of this radius). */
float mc_filter_radius(enum filter_kind k);

#endif
