/* envmap.h: an environment map — radiance over the sphere of directions from a latitude-longitude
 * image — and its importance sampling by a 2D piecewise-constant distribution of luminance × sin θ
 * (pbrt-v3 InfiniteAreaLight; Pharr, Jakob and Humphreys, 3rd ed. §14.2.4). The image arrives as
 * floats: the core reads no image file (the API layer loads it, src/README).
 *
 * The convention (man/mcrt.5), in mcrt's y-up frame: pixel column u ∈ [0,1) left to right and row
 * v ∈ [0,1) top to bottom map to θ = π·v from +y (the top row is straight up) and φ = 2π·(u − ½),
 * direction (sin θ sin φ, cos θ, −sin θ cos φ): the image's centre looks along −z, its right
 * quarter along +x, and its left and right edges meet (the seam) along +z. Seen from inside, by a
 * camera looking along −z with y up, the image appears unmirrored. An `orient` frame rotates the
 * map in the world.
 *
 * Radiance is constant over each pixel (nearest lookup), the same piecewise-constant function the
 * distribution samples, so that eval, pdf and sample agree exactly and a constant map is a
 * constant sky. */
#ifndef MCRT_ENVMAP_H
#define MCRT_ENVMAP_H

#include "core/diag.h"
#include "core/vec.h"
#include "sample/distrib.h"

struct envmap {
    float *rgb;                /* w·h·3 linear radiance, rows top to bottom (copied) */
    int w, h;
    struct mc_distrib2d dist;  /* over (u, v) of luminance × sin θ of the row's centre */
    double power_integral;     /* ∫ mean(RGB) dω over the sphere (sr·radiance) */
    double square_integral;    /* ∫ mean(RGB)² dω: with power_integral, how far from uniform the
                                * map is (light/select.h) */
};

/* Build from rgb[0..w·h·3) (copied). A NaN, infinite or negative value is an error "NAME: pixel
 * (x, y) has a WHAT value" (MCRT_ERR_PARSE: bad input), as is an empty image. */
mcrt_status mc_envmap_build(struct envmap *m, const float *rgb, int w, int h, const char *name,
                            mc_diag *d);
void mc_envmap_free(struct envmap *m);
/* Bytes the map and its distribution hold. */
size_t mc_envmap_bytes(const struct envmap *m);

/* The map's own direction of image point (u, v), and its inverse (u, v in [0,1]). */
vec3 mc_envmap_direction(float u, float v);
vec2 mc_envmap_uv(vec3 dir);

/* Radiance toward the map direction dir (unit). */
vec3 mc_envmap_eval(const struct envmap *m, vec3 dir);
/* Sample a map direction for u in [0,1)²; *pdf gets its solid-angle density (0: no sample, at a
 * pole) and *L the radiance of the pixel sampled, which is eval's but for a direction on a
 * pixel's edge, where float rounding could otherwise pair one pixel's pdf with its neighbour's
 * radiance (the seam at u = 0). */
vec3 mc_envmap_sample(const struct envmap *m, vec2 u, float *pdf, vec3 *L);
/* Solid-angle density of mc_envmap_sample at the map direction dir: pdf(u, v)/(2π² sin θ). */
float mc_envmap_pdf(const struct envmap *m, vec3 dir);

#endif
