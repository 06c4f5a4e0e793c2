/* prepare.c: turns a parsed scene into a renderable one: static primitives first with their BVH,
 * then the moving ones with a second BVH bounded over the shutter, one area light per emitting
 * primitive, the environment (the default white sky when nothing emits), and the light selection
 * (light/select.h); and each material's precomputed BSDF tables. */
#include "scene/scene.h"

#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"

/* Move the moving primitives behind the static ones, keeping the order within each group, and set
 * s->static_count. A static scene is left untouched, so its BVH is built exactly as without
 * motion. */
static mcrt_status partition(struct scene *s, mc_diag *d)
{
    size_t i, n_static = 0, n_moving = 0;
    struct prim *moving;
    for (i = 0; i < s->prim_count; i++) {
        if (s->prims[i].motion > s->motion_count)
            return mc_fail(d, MCRT_ERR_INVALID, "primitive %zu has motion %u of %zu", i,
                           (unsigned)s->prims[i].motion, s->motion_count);
        n_moving += s->prims[i].motion != 0;
    }
    s->static_count = s->prim_count - n_moving;
    if (n_moving == 0)
        return MCRT_OK;
    moving = mc_malloc(n_moving * sizeof *moving);
    if (!moving)
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory");
    n_moving = 0;
    for (i = 0; i < s->prim_count; i++) {
        if (s->prims[i].motion)
            moving[n_moving++] = s->prims[i];
        else
            s->prims[n_static++] = s->prims[i];
    }
    memcpy(s->prims + n_static, moving, n_moving * sizeof *moving);
    free(moving);
    return MCRT_OK;
}

/* The BVH of the moving primitives, each bounded over the whole shutter. */
static mcrt_status build_motion_bvh(struct scene *s, mc_diag *d)
{
    size_t i, n = s->prim_count - s->static_count;
    /* Not s->prims + 0 when the scene has no primitives: arithmetic on NULL is undefined. */
    struct prim *prims = n ? s->prims + s->static_count : s->prims;
    struct aabb *bounds;
    mcrt_status st;
    if (n == 0) /* still built, empty, so that its bounds read as empty (light.c) */
        return mc_bvh_build(&s->motion_bvh, prims, 0, d);
    bounds = mc_malloc(n * sizeof *bounds);
    if (!bounds)
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory");
    for (i = 0; i < n; i++)
        bounds[i] = mc_motion_bounds(&s->motions[prims[i].motion - 1], mc_prim_bounds(&prims[i]),
                                     s->camera.shutter[0], s->camera.shutter[1]);
    st = mc_bvh_build_bounds(&s->motion_bvh, prims, bounds, n, d);
    free(bounds);
    return st;
}

/* Radius of a sphere bounding the scene, moving primitives over the whole shutter (1 when the
 * scene is empty), and its centre (the origin then): the environment's power is that of a disk of
 * this radius (light.c), and its photons start on such a disk. */
static float scene_radius(const struct scene *s, vec3 *center)
{
    struct aabb b = aabb_union(s->bvh.bounds, s->motion_bvh.bounds);
    *center = v3s(0.0f);
    if (!(b.hi.x >= b.lo.x))
        return 1.0f;
    *center = v3_scale(v3_add(b.lo, b.hi), 0.5f);
    return fmaxf(0.5f * v3_length(v3_sub(b.hi, b.lo)), 1e-6f);
}

/* The environment's map from its image, which the API layer has read (scene.h); the pixels move
 * into the map, which copies them, so the image's own are released. */
static mcrt_status build_envmap(struct scene *s, struct light *env, mc_diag *d)
{
    struct scene_image *im = &s->images[env->image - 1];
    mcrt_status st;
    if (!im->rgb)
        return mc_fail(d, MCRT_ERR_INVALID, "%s: the environment map was not read", im->path);
    s->envmap = mc_malloc(sizeof *s->envmap);
    if (!s->envmap)
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory");
    st = mc_envmap_build(s->envmap, im->rgb, im->w, im->h, im->path, d);
    if (st != MCRT_OK) {
        free(s->envmap);
        s->envmap = NULL;
        return st;
    }
    mc_scene_set_image(s, (size_t)(env->image - 1), NULL, im->w, im->h);
    env->map = s->envmap;
    return MCRT_OK;
}

/* Image textures take their image's pixels, which the API layer has read (scene.h), and check
 * them. */
static mcrt_status prepare_textures(struct scene *s, mc_diag *d)
{
    size_t i;
    for (i = 0; i < s->texture_count; i++) {
        struct texture *t = &s->textures[i];
        const struct scene_image *im;
        mcrt_status st;
        if (t->kind != TEXTURE_IMAGE)
            continue;
        im = &s->images[t->image - 1];
        if (!im->rgb)
            return mc_fail(d, MCRT_ERR_INVALID, "%s: the image of texture '%s' was not read",
                           im->origin, t->name);
        t->rgb = im->rgb;
        t->w = im->w;
        t->h = im->h;
        if ((st = mc_texture_check(t, im->origin, d)) != MCRT_OK)
            return st;
    }
    return MCRT_OK;
}

mcrt_status mc_scene_prepare(struct scene *s, mc_diag *d)
{
    size_t i;
    struct light l, env;
    mcrt_status st;
    int has_light, has_env = 0;
    if (s->prepared)
        return MCRT_OK;
    if (s->material_count == 0)
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory");
    for (i = 0; i < s->material_count; i++)
        mc_bsdf_prepare(&s->materials[i]);
    if ((st = prepare_textures(s, d)) != MCRT_OK)
        return st;
    /* The split into static and moving primitives reorders them, so lights (which index them)
     * are made after it. */
    st = partition(s, d);
    if (st == MCRT_OK)
        st = mc_bvh_build(&s->bvh, s->prims, s->static_count, d);
    if (st == MCRT_OK)
        st = build_motion_bvh(s, d);
    if (st != MCRT_OK)
        return st;
    /* The environment, given or the default sky, goes last: it is found by s->env_light. */
    memset(&env, 0, sizeof env);
    env.kind = LIGHT_ENVIRONMENT;
    env.intensity = v3s(1.0f);
    for (i = 0; i < s->light_count; i++)
        if (s->lights[i].kind == LIGHT_ENVIRONMENT) { /* at most one (the parser) */
            env = s->lights[i];
            has_env = 1;
            memmove(&s->lights[i], &s->lights[i + 1], (s->light_count - i - 1) * sizeof env);
            s->light_count--;
            break;
        }
    if (env.image && (st = build_envmap(s, &env, d)) != MCRT_OK)
        return st;
    has_light = s->light_count > 0 || has_env;
    for (i = 0; i < s->prim_count; i++) {
        struct prim *p = &s->prims[i];
        p->light = -1;
        if (v3_is_zero(p->emit))
            continue;
        l.kind = LIGHT_AREA;
        l.prim = (uint32_t)i;
        l.area = mc_prim_area(p);
        l.point_error = mc_prim_point_error(p);
        l.position = l.intensity = v3s(0.0f);
        p->light = mc_scene_add_light(s, &l);
        if (p->light < 0)
            return mc_fail(d, MCRT_ERR_NOMEM, "out of memory");
        has_light = 1;
    }
    if (has_env || !has_light) {
        s->env_light = mc_scene_add_light(s, &env);
        if (s->env_light < 0)
            return mc_fail(d, MCRT_ERR_NOMEM, "out of memory");
    }
    s->light_scene.prims = s->prims;
    s->light_scene.motions = s->motions;
    s->light_scene.radius = scene_radius(s, &s->light_scene.center);
    s->light_scene.shutter[0] = s->camera.shutter[0];
    s->light_scene.shutter[1] = s->camera.shutter[1];
    for (i = 0; i < s->light_count; i++)
        s->lights[i].power = mc_light_power(&s->light_scene, &s->lights[i]);
    st = mc_light_select_build(&s->light_select, s->integrator.light_select, &s->light_scene,
                               s->lights, s->light_count, s->env_light, d);
    if (st != MCRT_OK)
        return st;
    s->prepared = 1;
    return MCRT_OK;
}
