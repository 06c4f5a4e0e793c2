/* warp.h: maps from the unit square [0,1)^2 to directions and points, each with its pdf.
 * Directions are in the local frame (z up) unless stated; pdfs are per unit solid angle for
 * directions and per unit area for points.
 * Kept for what is planned, with only their tests using them today: the uniform cone (a sun, a
 * sphere light seen from afar) and the rejection-sampled disk, which environment maps and their
 * importance sampling will want; the uniform hemisphere serves the BSDF tests as the plain
 * reference sampler. */
#ifndef MCRT_WARP_H
#define MCRT_WARP_H

#include "core/rng.h"
#include "core/vec.h"

/* Cosine-weighted hemisphere (Malley's method via the concentric disk); pdf cosθ/π. */
vec3 mc_warp_cosine_hemisphere(vec2 u);
float mc_warp_cosine_hemisphere_pdf(float cos_theta);
/* Uniform hemisphere z >= 0; pdf 1/(2π). */
vec3 mc_warp_uniform_hemisphere(vec2 u);
float mc_warp_uniform_hemisphere_pdf(void);
/* Uniform sphere; pdf 1/(4π). */
vec3 mc_warp_uniform_sphere(vec2 u);
float mc_warp_uniform_sphere_pdf(void);
/* Uniform over the cone of directions within angle θmax of +z, given cosθmax (and sin²θmax,
 * passed separately so that tiny cones keep their precision); pdf 1/(2π(1 − cosθmax)). */
vec3 mc_warp_uniform_cone(vec2 u, float cos_max, float sin2_max);
float mc_warp_uniform_cone_pdf(float cos_max, float sin2_max);
/* Concentric map of the square onto the unit disk (Shirley and Chiu 1997); pdf 1/π. */
vec2 mc_warp_concentric_disk(vec2 u);
/* Uniform point on the unit disk by rejection from the square [-1, 1]² (pdf 1/π). Each attempt
 * draws two pcg32_float values from rng; an attempt succeeds with probability π/4, so a sample
 * costs 4/π ≈ 1.27 attempts on average (geometric). It consumes a stream, not a point of
 * [0,1)², so it cannot carry stratification: prefer mc_warp_concentric_disk where u is stratified. */
vec2 mc_warp_rejection_disk(pcg32 *rng);
/* Uniform barycentrics (b1, b2) on a triangle (Heitz 2019 low-distortion map or the square-root
 * map); b0 = 1 − b1 − b2. */
vec2 mc_warp_triangle(vec2 u);

#endif
