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
};

struct pass_result {
    int passes;           /* complete passes in the film */
    double seconds;
    uint64_t rays, nan_count;
};

/* The seed of pass k: rs->seed itself for pass 0, so that a one-pass render is the plain render,
 * and a hash of (seed, k) after it. */
uint64_t mc_pass_seed(uint64_t seed, int k);

/* Render scene s into film f (zeroed, sized as rs's crop). Without a budget or a target: one pass
 * straight into f (mc_render). With either: passes into a scratch film, each merged into f only
 * when complete, until the target is met, or the next pass (estimated to last as long as the
 * last) would end after the budget, or max_passes; at least one pass. A cancelled render returns
 * MCRT_ERR_CANCELLED with f holding the complete passes (and, for a single plain pass, the
 * finished tiles). The result depends only on the seed and the number of passes. */
mcrt_status mc_render_passes(const struct scene *s, const struct render_settings *rs,
                             const struct pass_settings *ps, struct film *f,
                             struct pass_result *out, mc_diag *d);

#endif
