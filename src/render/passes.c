/* passes.c: progressive passes over an integrator's pass (see passes.h). A pass renders into a
 * scratch film and is merged (Chan, Golub and LeVeque 1979) only when complete, so an interrupted
 * render holds whole passes: every pixel has the samples of each pass it was given (the same
 * number in each pixel unless adaptive). */
#include "render/passes.h"

#include <math.h>
#include <stdlib.h>

#include "core/alloc.h"
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

enum { MIN_FIT_PASSES = 8 };

/* (log samples, log est_relmse) after each pass, for the rate at which the error falls with the
 * work done. Samples rather than seconds: the passes' times vary with the machine's load (1.4 to
 * 3 s for equal passes on a shared machine, measured), their sample counts do not. */
struct rate_fit {
    double *x, *y;
    int n, cap;
};

/* Add a point; -1 when out of memory. */
static int fit_add(struct rate_fit *r, double samples, double relmse)
{
    if (!(samples > 0.0) || !(relmse > 0.0) || !isfinite(relmse))
        return 0;
    if (r->n == r->cap) {
        int cap = r->cap ? 2 * r->cap : 64;
        double *x = mc_realloc(r->x, (size_t)cap * sizeof *x), *y;
        if (x)
            r->x = x;
        y = x ? mc_realloc(r->y, (size_t)cap * sizeof *y) : NULL;
        if (!y)
            return -1;
        r->y = y;
        r->cap = cap;
    }
    r->x[r->n] = log(samples);
    r->y[r->n++] = log(relmse);
    return 0;
}

/* The least-squares slope over the later half of the passes, from MIN_FIT_PASSES on; before
 * that, and when it does not fall, -1. Fewer passes leave it to noise: a glossy scene's 4 passes
 * gave -0.65, its 45 passes -1.00 to -1.02 over three seeds (measured). The first passes are
 * left out: with few samples per pixel the estimate's own bias (a rare bright sample raises a
 * pixel's mean with its variance) is largest, and it flattens the line: est·passes rose from 0.026 at pass 1 to 0.036 at 4 and
 * 0.039 at 14 on the Cornell box (passes of 4 spp), a slope of -0.89 over all 14 passes and
 * -0.94 over the later half. */
static double fit_slope(const struct rate_fit *r)
{
    double n = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0, den, slope;
    int i;
    if (r->n < MIN_FIT_PASSES)
        return -1.0;
    for (i = r->n / 2; i < r->n; i++) {
        n += 1.0;
        sx += r->x[i];
        sy += r->y[i];
        sxx += r->x[i] * r->x[i];
        sxy += r->x[i] * r->y[i];
    }
    den = n * sxx - sx * sx;
    if (!(den > 1e-9 * n * n))
        return -1.0;
    slope = (n * sxy - sx * sy) / den;
    return slope < 0.0 ? slope : -1.0;
}

/* Progress over the whole render, from the passes' own reports (their tiles' fraction): with a
 * time budget alone, the share of it spent; otherwise pass k of an expected `expected`, 0 until a
 * first pass has given an error to extrapolate from when the render runs to a target. Never
 * decreases. */
struct whole_progress {
    const struct render_settings *rs;
    double t0;
    int done;             /* complete passes */
    double expected;      /* passes the render is expected to need, >= done + 1 */
    double last;
};

static int report(void *user, double fraction)
{
    struct whole_progress *w = user;
    const struct render_settings *rs = w->rs;
    double f;
    if (rs->time_budget > 0.0 && !(rs->target_error > 0.0))
        f = (mc_seconds() - w->t0) / rs->time_budget;
    else if (rs->target_error > 0.0 && w->done == 0)
        f = 0.0;
    else
        f = ((double)w->done + fraction) / w->expected;
    if (f < w->last)
        f = w->last;
    w->last = f;
    return rs->progress(rs->user, f < 1.0 ? f : 1.0);
}

mcrt_status mc_render_passes(const struct render_settings *rs, mc_pass_fn pass_fn, void *ctx,
                             struct film *f, struct render_result *out, mc_diag *d)
{
    struct render_settings pass = *rs;
    struct tile_result res;
    struct film scratch;
    struct adaptive ad = {0, NULL, NULL};
    struct rate_fit fit = {NULL, NULL, 0, 0};
    struct whole_progress wp;
    uint64_t pixels = (uint64_t)f->width * (uint64_t)f->height, budget = UINT64_MAX;
    int limited = rs->time_budget > 0.0 || rs->target_error > 0.0 || rs->passes > 0 ||
                  rs->first_pass > 0 || rs->done_passes > 0;
    /* The passes f is to hold: rs->passes, or with a budget or a target the spp limit, or one
     * more than a resumed film holds. */
    int max_passes = rs->passes > 0 && rs->passes < rs->max_passes ? rs->passes
                     : rs->passes > 0 || rs->time_budget > 0.0 || rs->target_error > 0.0
                         ? rs->max_passes
                         : rs->done_passes + 1;
    double t0 = mc_seconds(), elapsed, relmse;
    mcrt_status st;
    size_t i;
    out->passes = rs->done_passes;
    out->samples = out->rays = out->nan_count = 0;
    for (i = 0; i < pixels; i++)
        out->samples += mc_film_count(&f->pixels[i]);
    out->relmse_slope = -1.0;
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
    wp.rs = rs;
    wp.t0 = t0;
    wp.done = out->passes;
    wp.expected = limited ? (double)max_passes : (double)((rs->spp + pass.spp - 1) / pass.spp);
    wp.last = 0.0;
    if (rs->progress) {
        pass.progress = report;
        pass.user = &wp;
    }
    for (;;) {
        uint64_t given = (uint64_t)pass.spp * pixels;
        if (given > budget - out->samples)
            given = budget - out->samples;
        pass.pass = rs->first_pass + out->passes;
        pass.seed = mc_pass_seed(rs->seed, pass.pass);
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
        relmse = mc_film_est_relmse(f);
        if (fit_add(&fit, (double)out->samples, relmse) != 0) {
            st = mc_fail(d, MCRT_ERR_NOMEM, "out of memory for the error's history");
            break;
        }
        out->relmse_slope = fit_slope(&fit);
        if (limited ? out->passes >= max_passes : out->samples >= budget)
            break;
        if (rs->target_error > 0.0 && relmse <= rs->target_error)
            break;
        if (rs->time_budget > 0.0 && elapsed + res.seconds > rs->time_budget)
            break;
        /* The passes still expected: to the target along the fitted rate, e ∝ t^slope, with
         * passes of equal length; to the end of the time budget. */
        wp.done = out->passes;
        if (limited) {
            double more = (double)max_passes;
            if (rs->target_error > 0.0 && relmse > 0.0)
                more = fmin(more, out->passes * pow(rs->target_error / relmse,
                                                    1.0 / out->relmse_slope));
            if (rs->time_budget > 0.0)
                more = fmin(more, rs->time_budget / (elapsed / out->passes));
            wp.expected = fmax(more, out->passes + 1.0);
        }
    }
    mc_film_free(&scratch);
    mc_adaptive_free(&ad);
    free(fit.x);
    free(fit.y);
    out->seconds = mc_seconds() - t0;
    return st;
}
