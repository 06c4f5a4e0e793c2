/* integrators.c: the table of integrators, from the list in scene/integrators.h, and the render
 * loop shared by the per-ray ones (see integrator.h). */
#include "integrator/integrator.h"

#include <stdio.h>
#include <string.h>

#include "render/passes.h"

#define MC_INTEGRATOR_ENTRY(id, name) {#name, &mc_integrator_##name},
static const struct {
    const char *name;
    const struct integrator *it;
} table[INTEGRATOR_COUNT] = {MC_INTEGRATORS(MC_INTEGRATOR_ENTRY)};
#undef MC_INTEGRATOR_ENTRY

const struct integrator *mc_integrator_get(enum integrator_kind kind) { return table[kind].it; }

const char *mc_integrator_name(enum integrator_kind kind) { return table[kind].name; }

int mc_integrator_find(const char *name)
{
    int i;
    for (i = 0; i < INTEGRATOR_COUNT; i++)
        if (strcmp(name, table[i].name) == 0)
            return i;
    return -1;
}

void mc_integrator_choices(char *buf, size_t size)
{
    size_t len = 0;
    int i;
    buf[0] = '\0';
    for (i = 0; i < INTEGRATOR_COUNT && len < size; i++) {
        int n = snprintf(buf + len, size - len, "%s%s",
                         i == 0 ? "" : i == INTEGRATOR_COUNT - 1 ? " or " : ", ", table[i].name);
        len += n > 0 ? (size_t)n : 0;
    }
}

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
