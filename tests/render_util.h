/* render_util.h: whole renders through the public API for the tests, in one place. */
#ifndef MCRT_TEST_RENDER_UTIL_H
#define MCRT_TEST_RENDER_UTIL_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mcrt.h"

/* What a test varies; zero fields take the library's defaults (the scene's spp, all cores, seed 0,
 * the scene's integrator, the specialised code path). */
struct t_render_opts {
    int spp, threads, all_features;
    uint64_t seed;
    const char *integrator;
    const char *sampler; /* NULL: the scene's */
};

/* Render scene text; returns the RGB pixels (3 floats each, malloc'd, rows top to bottom) and their
 * size, and the render's statistics when stats is not NULL; or NULL after printing why. */
static inline float *t_render(const char *text, const struct t_render_opts *opt, int *w, int *h,
                              mcrt_stats *stats)
{
    mcrt_scene *s = mcrt_scene_new();
    mcrt_render *r = NULL;
    mcrt_options o;
    float *out = NULL;
    if (!s || mcrt_scene_load_string(s, text, strlen(text), "test") != MCRT_OK) {
        printf("scene error: %s\n", s ? mcrt_scene_error(s) : "out of memory");
        goto done;
    }
    mcrt_options_init(&o);
    o.spp = opt->spp;
    o.threads = opt->threads;
    o.seed = opt->seed;
    o.integrator = opt->integrator;
    o.sampler = opt->sampler;
    o.all_features = opt->all_features;
    r = mcrt_render_new(s, &o);
    if (!r || mcrt_render_run(r) != MCRT_OK) {
        printf("render error: %s\n", r ? mcrt_render_error(r) : "out of memory");
        goto done;
    } else {
        const float *px = mcrt_render_pixels(r, w, h);
        size_t n = (size_t)*w * (size_t)*h * 3;
        out = malloc(n * sizeof *out);
        if (out)
            memcpy(out, px, n * sizeof *out);
        if (stats)
            mcrt_render_stats(r, stats, sizeof *stats);
    }
done:
    mcrt_render_free(r);
    mcrt_scene_free(s);
    return out;
}

#endif
