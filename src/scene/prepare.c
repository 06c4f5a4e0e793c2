/* prepare.c: turns a parsed scene into a renderable one: the BVH over all primitives, one area
 * light per emitting primitive, the environment (the default white sky when nothing emits), and
 * the alias table that picks lights in proportion to power. */
#include "scene/scene.h"

#include <stdlib.h>

mcrt_status mc_scene_prepare(struct scene *s, mc_diag *d)
{
    size_t i;
    struct light l;
    mcrt_status st;
    int has_light;
    double *power;
    if (s->prepared)
        return MCRT_OK;
    if (s->material_count == 0)
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory");
    st = mc_bvh_build(&s->bvh, s->prims, s->prim_count, d);
    if (st != MCRT_OK)
        return st;
    has_light = s->light_count > 0 || s->has_environment;
    for (i = 0; i < s->prim_count; i++) {
        struct prim *p = &s->prims[i];
        p->light = -1;
        if (v3_is_zero(p->emit))
            continue;
        l.kind = LIGHT_AREA;
        l.prim = (uint32_t)i;
        l.position = l.intensity = v3s(0.0f);
        p->light = mc_scene_add_light(s, &l);
        if (p->light < 0)
            return mc_fail(d, MCRT_ERR_NOMEM, "out of memory");
        has_light = 1;
    }
    if (!has_light) {
        s->has_environment = 1;
        s->environment = v3s(1.0f);
    }
    if (s->has_environment) {
        l.kind = LIGHT_ENVIRONMENT;
        l.prim = 0;
        l.position = v3s(0.0f);
        l.intensity = s->environment;
        s->env_light = mc_scene_add_light(s, &l);
        if (s->env_light < 0)
            return mc_fail(d, MCRT_ERR_NOMEM, "out of memory");
    }
    power = malloc((s->light_count ? s->light_count : 1) * sizeof *power);
    if (!power)
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory");
    for (i = 0; i < s->light_count; i++)
        power[i] = s->lights[i].power = mc_light_power(s, &s->lights[i]);
    st = mc_alias_build(&s->light_select, power, s->light_count, d);
    free(power);
    if (st != MCRT_OK)
        return st;
    s->prepared = 1;
    return MCRT_OK;
}
