/* passes.c: progressive passes over an integrator's pass (see passes.h). A pass renders into a
 * scratch film and is merged (Chan, Golub and LeVeque 1979) only when complete, so an interrupted
 * render holds whole passes: every pixel has the samples of each pass it was given (the same
 * number in each pixel unless adaptive). */
#include "render/passes.h"

#include "core/clock.h"
#include "core/rng.h"
#include "render/adaptive.h"

uint64_t mc_pass_seed(uint64_t seed, int k)
{
    /* The constant separates pass seeds from the seeds a user picks ("passes" in ASCII). */
    return k == 0 ? seed : mc_hash3(seed, (uint64_t)k, 0x706173736573ULL);
}

static void add_counts(struct render_result *out, const struct tile_result *res)
{
    out->rays += res->rays;
    out->nan_count += res->nan_count;
}

mcrt_status mc_render_passes(const struct render_settings *rs, mc_pass_fn pass_fn, void *ctx,
                             struct film *f, struct render_result *out, mc_diag *d)
{
    struct render_settings pass = *rs;
    struct tile_result res;
    struct film scratch;
    struct adaptive ad = {0, NULL, NULL};
    uint64_t pixels = (uint64_t)f->width * (uint64_t)f->height, budget = UINT64_MAX;
    int limited = rs->time_budget > 0.0 || rs->target_error > 0.0;
    double t0 = mc_seconds(), elapsed;
    mcrt_status st;
    out->passes = 0;
    out->samples = out->rays = out->nan_count = 0;
    if (!limited && !rs->adaptive) {
        st = pass_fn(ctx, rs, f, &res, d);
        add_counts(out, &res);
        out->passes = st == MCRT_OK;
        out->samples = (uint64_t)out->passes * (uint64_t)rs->spp * pixels;
        out->seconds = res.seconds;
        return st;
    }
    /* Adaptive without a limit: rs->spp is the mean of the whole render, spent in passes. */
    if (!limited) {
        budget = (uint64_t)rs->spp * pixels;
        pass.spp = mc_adaptive_pass_spp(rs->spp);
    }
    if (mc_film_init(&scratch, f->width, f->height) != 0
        || (rs->adaptive && mc_adaptive_init(&ad, (size_t)pixels) != 0)) {
        mc_film_free(&scratch);
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory for a %dx%d film", f->width, f->height);
    }
    for (;;) {
        uint64_t given = (uint64_t)pass.spp * pixels;
        if (given > budget - out->samples)
            given = budget - out->samples;
        pass.seed = mc_pass_seed(rs->seed, out->passes);
        pass.pixel_spp = NULL;
        if (rs->adaptive && out->passes > 0) {
            given = mc_adaptive_allocate(&ad, f, given);
            pass.pixel_spp = ad.counts;
        }
        mc_film_clear(&scratch);
        st = pass_fn(ctx, &pass, &scratch, &res, d);
        add_counts(out, &res);
        if (st != MCRT_OK)
            break; /* cancelled: the partial pass is dropped */
        mc_film_merge(f, &scratch);
        out->passes++;
        out->samples += given;
        elapsed = mc_seconds() - t0;
        if (limited ? out->passes >= rs->max_passes : out->samples >= budget)
            break;
        if (rs->target_error > 0.0 && mc_film_est_relmse(f) <= rs->target_error)
            break;
        if (rs->time_budget > 0.0 && elapsed + res.seconds > rs->time_budget)
            break;
    }
    mc_film_free(&scratch);
    mc_adaptive_free(&ad);
    out->seconds = mc_seconds() - t0;
    return st;
}
