/* tiles.h: the parallel loop every integrator's image pass runs on (pbrt-v4's ParallelFor2D under
 * ImageTileIntegrator::Render): a pool of threads takes 16×16 tiles of a window of the image from
 * a shared counter, and between tiles checks for cancellation and reports progress. A per-ray
 * integrator's pass (render.h) is one run; a loop-owning integrator (e.g. a photon mapper's camera
 * pass) calls it with its own tile function and gets the same threads, progress and cancellation. */
#ifndef MCRT_TILES_H
#define MCRT_TILES_H

#include <stdint.h>

#include "core/diag.h"

enum { MC_TILE = 16 };

struct render_settings; /* render.h: threads, progress, user, cancel */

/* Per-thread counters, each on its own cache lines so that workers never share one. */
struct tile_worker {
    uint64_t rays, nans; /* rays traced; non-finite samples counted and dropped */
    char pad[64];
};

/* Render the pixels x0 <= x < x1, y0 <= y < y1 of the image (coordinates of the whole image, not
 * of a crop), adding to w's counters. Called concurrently for different tiles. */
typedef void (*mc_tile_fn)(void *ctx, struct tile_worker *w, int x0, int y0, int x1, int y1);

struct tile_result {
    double seconds;
    uint64_t rays, nan_count; /* summed over the workers */
    int cancelled;            /* stopped before every tile was done */
};

/* Run fn over the tiles of the window of width × height pixels at (x0, y0) on rs->threads threads
 * (the caller is one of them; fewer if a thread cannot be started). rs->progress, if set, is told
 * the fraction of tiles done: outside the lock that hands out tiles, so a slow callback stalls no
 * worker; never by two threads at once; with fractions that never decrease, the last 1 when every
 * tile is done. Its nonzero return, or *rs->cancel set nonzero, stops the run after the tiles
 * under way: MCRT_ERR_CANCELLED. */
mcrt_status mc_tiles_run(const struct render_settings *rs, int x0, int y0, int width, int height,
                         mc_tile_fn fn, void *ctx, struct tile_result *out, mc_diag *d);

#endif
