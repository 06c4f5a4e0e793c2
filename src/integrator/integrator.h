/* integrator.h: the integrator interface, after pbrt-v4's Integrator::Render: an integrator owns
 * its render loop and computes a film from a scene and the resolved options. The list of
 * integrators is scene/integrators.h; mc_integrator_get gives the descriptor of each.
 *
 * What an integrator gets without writing it (render/):
 *   - a per-ray integrator (pbrt-v4's RayIntegrator: path, direct and the strategies) supplies
 *     only its radiance function, MC_RAY_INTEGRATOR below; tiles, threads, camera rays, filter
 *     importance sampling, AOVs, the NaN count, progress, cancellation, crops (render.h) and the
 *     progressive passes, --time, --target-error and --adaptive (passes.h) are shared;
 *   - an integrator with a loop of its own (e.g. progressive photon mapping: a camera pass, a
 *     photon pass and per-pixel statistics, in a file of its own) runs its image passes on
 *     mc_tiles_run (tiles.h), which brings threads, progress, cancellation and the crop window
 *     (rs->crop_x0/y0 and the film's size), reads rs->time_budget itself, keeps its statistics in
 *     the state its prepare makes, and refuses in prepare the options it cannot honour (e.g. an
 *     adaptive render); a denoiser is a step on the film after render returns. */
#ifndef MCRT_INTEGRATOR_H
#define MCRT_INTEGRATOR_H

#include "render/render.h"

struct integrator {
    const char *description; /* one line, for --help and --list */
    /* Before rendering (may be NULL): set the parameters the integrator implies in rs (e.g.
     * direct's single bounce), refuse the options it cannot honour, and make *state, what
     * render needs besides rs (NULL if nothing). */
    mcrt_status (*prepare)(const struct integrator *self, const struct scene *s,
                           struct render_settings *rs, void **state, mc_diag *d);
    /* The whole render of s into film f (zeroed, rs's crop of the image), with rs's passes,
     * budget, AOVs, progress and cancellation; MCRT_ERR_CANCELLED when stopped early, with f
     * holding what is complete. */
    mcrt_status (*render)(const struct integrator *self, void *state, const struct scene *s,
                          const struct render_settings *rs, struct film *f,
                          struct render_result *out, mc_diag *d);
    void (*release)(void *state); /* after render (may be NULL) */
    /* A per-ray integrator's radiance function compiled for these features (scene/features.h);
     * FEATURE_ALL gives the general one, which renders every scene (the same image in
     * expectation). NULL for an integrator with its own loop. */
    mc_radiance_fn (*radiance)(unsigned features);
};

/* The render of every per-ray integrator: progressive passes (passes.h) of mc_render_rays with
 * self->radiance(rs->features). */
mcrt_status mc_ray_integrator_render(const struct integrator *self, void *state,
                                     const struct scene *s, const struct render_settings *rs,
                                     struct film *f, struct render_result *out, mc_diag *d);

/* The descriptor of a per-ray integrator: its description, its prepare (or NULL) and the
 * function giving its radiance function for a set of features. */
#define MC_RAY_INTEGRATOR(description, prepare, radiance) \
    {(description), (prepare), mc_ray_integrator_render, NULL, (radiance)}

/* The descriptor of each line of scene/integrators.h, defined in its own file. */
#define MC_INTEGRATOR_DECLARE(id, name) extern const struct integrator mc_integrator_##name;
MC_INTEGRATORS(MC_INTEGRATOR_DECLARE)
#undef MC_INTEGRATOR_DECLARE

/* The integrator of each kind (its name is mc_integrator_names[kind], scene.h). */
const struct integrator *mc_integrator_get(enum integrator_kind kind);

#endif
