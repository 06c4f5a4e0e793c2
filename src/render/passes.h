/* passes.h: progressive rendering for integrators whose passes are independent sample sets of
 * every pixel (each per-ray integrator, through integrator.h): passes of rs->spp samples per
 * pixel, each with its own seed, added to the film one complete pass at a time, until a time
 * budget is spent or the estimated error falls below a target; or adaptive passes. The integrator
 * supplies one pass; --time, --target-error and --adaptive come from here. */
#ifndef MCRT_PASSES_H
#define MCRT_PASSES_H

#include "render/render.h"

/* One pass: render the samples rs asks for (its seed, spp and pixel_spp are the pass's) into f,
 * which is zeroed and sized as rs's crop, as the integrator's ctx says. */
typedef mcrt_status (*mc_pass_fn)(void *ctx, const struct render_settings *rs, struct film *f,
                                  struct tile_result *out, mc_diag *d);

/* The seed of pass k: rs->seed itself for pass 0, so that a one-pass render is the plain render,
 * and a hash of (seed, k) after it. */
uint64_t mc_pass_seed(uint64_t seed, int k);

/* Render into film f (zeroed, sized as rs's crop) with pass(ctx, ...). Without a budget, a target
 * or adaptive: one pass straight into f. Otherwise: passes into a scratch film, each merged into
 * f only when complete, until the target is met, or the next pass (estimated to last as long as
 * the last) would end after the budget, or rs->max_passes (with a budget or a target) or the
 * adaptive render's spp are reached; at least one pass. A cancelled render returns
 * MCRT_ERR_CANCELLED with f holding the complete passes (and, for a single plain pass, the
 * finished tiles). The result depends only on the seed and the number of passes. */
mcrt_status mc_render_passes(const struct render_settings *rs, mc_pass_fn pass, void *ctx,
                             struct film *f, struct render_result *out, mc_diag *d);

#endif
