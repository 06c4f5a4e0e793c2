/* integrators.c: the table of integrators, from the list in scene/integrators.h, and the render
 * loop shared by the per-ray ones (see integrator.h). */
#include "integrator/integrator.h"

#include "render/passes.h"

#define MC_INTEGRATOR_ENTRY(id, name) [INTEGRATOR_##id] = &mc_integrator_##name,
static const struct integrator *const table[INTEGRATOR_COUNT] = {
    MC_INTEGRATORS(MC_INTEGRATOR_ENTRY)};
#undef MC_INTEGRATOR_ENTRY

const struct integrator *mc_integrator_get(enum integrator_kind kind) { return table[kind]; }

/* A per-ray integrator's pass: the scene and the radiance function it was given. */
struct ray_pass {
    const struct scene *scene;
    mc_radiance_fn Li;
};

static mcrt_status ray_pass(void *ctx, const struct render_settings *rs, struct film *f,
                            struct tile_result *out, mc_diag *d)
{
    const struct ray_pass *p = ctx;
    return mc_render_rays(p->scene, rs, p->Li, f, out, d);
}

mcrt_status mc_ray_integrator_render(const struct integrator *self, void *state,
                                     const struct scene *s, const struct render_settings *rs,
                                     struct film *f, struct render_result *out, mc_diag *d)
{
    struct ray_pass p;
    (void)state;
    p.scene = s;
    p.Li = self->radiance(rs->features);
    return mc_render_passes(rs, ray_pass, &p, f, out, d);
}
