/* passes.h: progressive rendering: passes of rs->spp samples per pixel, each with its own seed,
 * added to the film one complete pass at a time, until a time budget is spent or the estimated
 * error falls below a target. */
#ifndef MCRT_PASSES_H
#define MCRT_PASSES_H

#include "render/render.h"

struct pass_settings {
    double time_budget;   /* seconds; 0 = none */
    double target_error;  /* stop when mc_film_est_relmse falls to this; 0 = none */
    int max_passes;       /* >= 1: never more (the spp limit) */
    /* Nonzero: after a uniform first pass, each pass spreads its samples over the pixels by
     * their estimated error (render/adaptive.h). Without a budget or a target, rs->spp is then
     * the mean samples per pixel of the whole render, spent in passes of mc_adaptive_pass_spp. */
    int adaptive;
};

struct pass_result {
    int passes;           /* complete passes in the film */
    uint64_t samples;     /* camera samples in the film, over all pixels */
    double seconds;
    uint64_t rays, nan_count;
};

/* The seed of pass k: rs->seed itself for pass 0, so that a one-pass render is the plain render,
 * and a hash of (seed, k) after it. */
uint64_t mc_pass_seed(uint64_t seed, int k);

/* Render scene s into film f (zeroed, sized as rs's crop). Without a budget, a target or
 * adaptive: one pass straight into f (mc_render). Otherwise: passes into a scratch film, each
 * merged into f only when complete, until the target is met, or the next pass (estimated to last
 * as long as the last) would end after the budget, or max_passes (with a budget or a target) or
 * the adaptive render's spp are reached; at least one pass. A cancelled render returns
 * MCRT_ERR_CANCELLED with f holding the complete passes (and, for a single plain pass, the
 * finished tiles). The result depends only on the seed and the number of passes. */
mcrt_status mc_render_passes(const struct scene *s, const struct render_settings *rs,
                             const struct pass_settings *ps, struct film *f,
                             struct pass_result *out, mc_diag *d);

#endif
