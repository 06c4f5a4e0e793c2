/* adaptive.h: adaptive sampling: how many samples each pixel gets in the next progressive pass,
 * from the error its samples so far estimate, so that a fixed budget lowers the image's relative
 * MSE (mc_film_est_relmse) as much as those estimates allow. */
#ifndef MCRT_ADAPTIVE_H
#define MCRT_ADAPTIVE_H

#include <stddef.h>
#include <stdint.h>

#include "render/film.h"

/* Share of every pass spread uniformly over the pixels (a defensive mixture): see adaptive.c. */
#define MC_ADAPTIVE_UNIFORM 0.2
/* No pixel gets more than this many times the pass's mean samples per pixel in one pass. */
#define MC_ADAPTIVE_MAX_RATIO 64

struct adaptive {
    size_t pixels;
    double *weight;  /* per pixel: sqrt of its error weight, see adaptive.c */
    int *counts;     /* per pixel: the samples of the next pass (render_settings.pixel_spp) */
};

/* Allocate the buffers for a film of `pixels` pixels. Returns 0, or -1 when out of memory. */
int mc_adaptive_init(struct adaptive *a, size_t pixels);
void mc_adaptive_free(struct adaptive *a);

/* Fill a->counts (film f's size) with the samples of the next pass, `budget` in all, from f's
 * per-pixel means and variances; returns the number given out: `budget`, or fewer when pixels hit
 * the MC_ADAPTIVE_MAX_RATIO cap. A pure function of f and budget (deterministic). */
uint64_t mc_adaptive_allocate(struct adaptive *a, const struct film *f, uint64_t budget);

/* The uniform first pass of an adaptive render with an average budget of spp samples per pixel
 * and no time or error limit; the later passes have the same mean size. At most spp. */
int mc_adaptive_pass_spp(int spp);

/* The fewest and most samples any pixel of f has. */
void mc_adaptive_count_range(const struct film *f, uint64_t *min, uint64_t *max);

#endif
