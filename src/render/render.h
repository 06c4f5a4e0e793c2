/* render.h: what a render is asked for (the options resolved against the scene) and what it
 * reports, which every integrator's render takes and fills (integrator/integrator.h); and the
 * per-ray pass, pbrt-v4's RayIntegrator: camera samples of every pixel, each given to a radiance
 * function, the shared image loop of the integrators that estimate one camera ray at a time. */
#ifndef MCRT_RENDER_H
#define MCRT_RENDER_H

#include "core/atomic.h"
#include "core/diag.h"
#include "render/aov.h"
#include "render/film.h"
#include "render/tiles.h"
#include "scene/scene.h"

struct render_settings {
    int spp;
    int threads;                      /* >= 1 */
    uint64_t seed;
    int pass;                         /* this pass's index: which half a pixel's odd sample takes */
    struct integrator_desc integrator; /* the parameters, as the integrator's prepare left them */
    unsigned features;                /* scene/features.h: what the render is built for */
    int (*progress)(void *user, double done); /* serialised; nonzero return cancels */
    void *user;
    mc_atomic_int *cancel;            /* set nonzero from anywhere to stop */
    /* The film's top-left pixel in the scene's image: the film may be a window of it (a crop);
     * the camera always spans the scene's whole film. */
    int crop_x0, crop_y0;
    struct aov_film *aov;             /* film-sized first-hit data to record, or NULL */
    enum sampler_kind sampler;        /* the film's, unless the options override it */
    /* Film-sized samples of each pixel (render/adaptive.h), in place of spp everywhere; NULL:
     * spp each. A pixel's n samples are split into its two halves (film.h), each a
     * complete set of the sampler of its own size and seed. */
    const int *pixel_spp;
    /* Progressive passes (render/passes.h). */
    double time_budget;               /* seconds; 0 = none */
    double target_error;              /* stop when mc_film_est_relmse falls to this; 0 = none */
    int max_passes;                   /* >= 1: never more (the spp limit) */
    int passes;                       /* > 0: the film is to hold this many passes; 0: see passes.h */
    /* The film's first pass is pass first_pass of the seed (0 but for a render continuing or
     * sharing another's), and it holds done_passes complete passes already (a resumed render). */
    int first_pass, done_passes;
    /* Nonzero: after a uniform first pass, each pass spreads its samples over the pixels by
     * their estimated error (render/adaptive.h). Without a budget or a target, spp is then the
     * mean samples per pixel of the whole render, spent in passes of mc_adaptive_pass_spp. */
    int adaptive;
};

struct render_result {
    int passes;                       /* complete passes in the film */
    uint64_t samples;                 /* camera samples in the film, over all pixels */
    double seconds;
    uint64_t rays;
    uint64_t nan_count;               /* non-finite samples: counted, never added */
    /* A biased integrator's estimate of the image's relMSE in two parts (mcrt_stats); left NaN
     * (as the caller sets them) by the others. */
    double est_relmse_bias2, est_relmse_variance;
    /* d log(est. relMSE) / d log(samples) over the passes, fitted from 8 passes on (passes.c);
     * -1 before, the rate of a render continued by independent passes of one size. */
    double relmse_slope;
};

/* The radiance arriving along camera ray r, the whole of a per-ray integrator: with the
 * integrator's parameters cfg, drawing its numbers from smp, adding the rays it traced to *rays.
 * A non-finite result is counted and dropped by the caller. */
typedef vec3 (*mc_radiance_fn)(const struct scene *s, const struct integrator_desc *cfg,
                               struct ray r, struct sampler *smp, uint64_t *rays);

/* One pass of a per-ray integrator: rs->spp samples (or rs->pixel_spp) of each pixel of film f
 * (already sized, rs's crop of the image), each a camera ray given to Li, on the tile pool
 * (tiles.h). Each pixel's samples depend only on (seed, pass, pixel, sample index), so the film is
 * bit-identical for any thread count. Returns MCRT_ERR_CANCELLED when stopped early (f then
 * holds the finished tiles). */
mcrt_status mc_render_rays(const struct scene *s, const struct render_settings *rs,
                           mc_radiance_fn Li, struct film *f, struct tile_result *out, mc_diag *d);

#endif
