/* render.h: rendering a prepared scene into a film with a pool of threads over image tiles. */
#ifndef MCRT_RENDER_H
#define MCRT_RENDER_H

#include "core/atomic.h"
#include "core/diag.h"
#include "render/aov.h"
#include "render/film.h"
#include "scene/scene.h"

struct render_settings {
    int spp;
    int threads;                      /* >= 1 */
    uint64_t seed;
    struct integrator_desc integrator;
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
     * spp each. A pixel's n samples are a complete n-sample set of the sampler. */
    const int *pixel_spp;
};

struct render_result {
    double seconds;
    uint64_t rays;
    uint64_t nan_count;               /* non-finite samples: counted, never added */
    int cancelled;
};

/* Render scene s into film f (already sized). Tiles of 16×16 pixels are taken by the threads from
 * a shared counter; each pixel's samples depend only on (seed, pixel, sample index), so the film is
 * bit-identical for any thread count. Returns MCRT_ERR_CANCELLED when stopped early. */
mcrt_status mc_render(const struct scene *s, const struct render_settings *rs, struct film *f,
                      struct render_result *out, mc_diag *d);

#endif
