/* scene.c: the scene container: defaults, growable arrays, lookup by name, and release. */
#include "scene/scene.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/hash.h"

#define MC_INTEGRATOR_NAME(id, name) [INTEGRATOR_##id] = #name,
const char *const mc_integrator_names[INTEGRATOR_COUNT + 1] = {
    MC_INTEGRATORS(MC_INTEGRATOR_NAME)[INTEGRATOR_COUNT] = NULL};
#undef MC_INTEGRATOR_NAME

int mc_scene_init(struct scene *s)
{
    struct material def;
    memset(s, 0, sizeof *s);
    s->hash = MC_HASH_INIT;
    s->film.width = 512;
    s->film.height = 512;
    s->film.spp = 16;
    s->film.sampler = SAMPLER_SOBOL; /* lower error than stratified at the same cost (README, Performance) */
    s->film.filter = FILTER_BOX;
    s->camera.eye = v3(0.0f, 0.0f, 5.0f);
    s->camera.look = v3(0.0f, 0.0f, 0.0f);
    s->camera.up = v3(0.0f, 1.0f, 0.0f);
    s->camera.fov = 40.0f;
    s->integrator.method = INTEGRATOR_PATH;
    s->integrator.max_depth = -1;
    s->integrator.rr_depth = 5;
    s->integrator.light_samples = 1;
    s->integrator.light_select = LIGHT_SELECT_POWER;
    s->integrator.photons = 0;
    s->integrator.radius = 0.0f;
    s->integrator.alpha = 2.0f / 3.0f;
    s->camera.shutter[1] = 1.0f;
    s->env_light = -1;
    memset(&def, 0, sizeof def);
    def.kind = MC_MATERIAL_KIND(diffuse);
    def.color = v3s(0.8f);
    def.ior = 1.5f;
    return mc_scene_add_material(s, &def) < 0 ? -1 : 0;
}

void mc_scene_free(struct scene *s)
{
    free(s->name);
    mc_bvh_free(&s->bvh);
    mc_bvh_free(&s->motion_bvh);
    mc_light_select_free(&s->light_select);
    free(s->materials);
    free(s->prims);
    free(s->normals);
    free(s->uvs);
    free(s->lights);
    free(s->motions);
    while (s->image_count > 0) {
        s->image_count--;
        free(s->images[s->image_count].path);
        free(s->images[s->image_count].origin);
        free(s->images[s->image_count].rgb);
    }
    free(s->images);
    free(s->textures);
    free(s->warnings);
    if (s->envmap)
        mc_envmap_free(s->envmap);
    free(s->envmap);
    memset(s, 0, sizeof *s);
}

/* Append one element of size elem to a growable array, doubling its capacity. Returns the new
 * index or -1 when out of memory or past INT32_MAX elements. */
static int push(void **array, size_t *count, size_t *cap, size_t elem, const void *value)
{
    if (*count >= 0x7fffffff)
        return -1;
    if (*count == *cap) {
        size_t ncap = *cap ? *cap * 2 : 16;
        void *p = mc_realloc(*array, ncap * elem);
        if (!p)
            return -1;
        *array = p;
        *cap = ncap;
    }
    memcpy((char *)*array + *count * elem, value, elem);
    return (int)(*count)++;
}

int mc_scene_warn(struct scene *s, const char *fmt, ...)
{
    char line[640], *w;
    size_t n;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line - 1, fmt, ap);
    va_end(ap);
    n = strlen(line);
    line[n++] = '\n';
    line[n] = '\0';
    /* Each warning once: a library that several meshes read warns once in all. */
    for (w = s->warnings; w && w < s->warnings + s->warnings_len; w = strchr(w, '\n') + 1)
        if (!strncmp(w, line, n))
            return 0;
    if (!(w = mc_realloc(s->warnings, s->warnings_len + n + 1)))
        return -1;
    memcpy(w + s->warnings_len, line, n + 1);
    s->warnings = w;
    s->warnings_len += n;
    return 0;
}

int mc_scene_add_material(struct scene *s, const struct material *m)
{
    return push((void **)&s->materials, &s->material_count, &s->material_cap, sizeof *m, m);
}

int mc_scene_add_prim(struct scene *s, const struct prim *p)
{
    return push((void **)&s->prims, &s->prim_count, &s->prim_cap, sizeof *p, p);
}

/* The uv array holds as many elements as the normals once it exists: a scene whose meshes have no
 * texture coordinates never allocates it; the first that has them fills the earlier corners with
 * their triangles' own coordinates. */
int mc_scene_add_corners(struct scene *s, const vec3 n[3], const vec2 *uv)
{
    static const vec2 own[3] = {{0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 1.0f}};
    size_t first = s->normal_count, i;
    for (i = 0; i < 3; i++)
        if (push((void **)&s->normals, &s->normal_count, &s->normal_cap, sizeof *n, &n[i]) < 0) {
            s->normal_count = first;
            return -1;
        }
    if (!uv && !s->uvs)
        return (int)first;
    if (s->uv_cap < s->normal_cap) {
        vec2 *p = mc_realloc(s->uvs, s->normal_cap * sizeof *p);
        if (!p) {
            s->normal_count = first;
            return -1;
        }
        if (!s->uvs)
            for (i = 0; i < first; i++)
                p[i] = own[i % 3];
        s->uvs = p;
        s->uv_cap = s->normal_cap;
    }
    for (i = 0; i < 3; i++)
        s->uvs[first + i] = uv ? uv[i] : own[i];
    return (int)first;
}

int mc_scene_add_light(struct scene *s, const struct light *l)
{
    return push((void **)&s->lights, &s->light_count, &s->light_cap, sizeof *l, l);
}

static char *copy_string(const char *text)
{
    char *c = mc_malloc(strlen(text) + 1);
    if (c)
        strcpy(c, text);
    return c;
}

int mc_scene_add_image(struct scene *s, const char *path, const char *origin)
{
    struct scene_image im;
    int i = -1;
    memset(&im, 0, sizeof im);
    im.path = copy_string(path);
    im.origin = copy_string(origin);
    if (im.path && im.origin)
        i = push((void **)&s->images, &s->image_count, &s->image_cap, sizeof im, &im);
    if (i < 0) {
        free(im.path);
        free(im.origin);
    }
    return i;
}

int mc_scene_add_texture(struct scene *s, const struct texture *t)
{
    return push((void **)&s->textures, &s->texture_count, &s->texture_cap, sizeof *t, t);
}

int mc_scene_image_texture(struct scene *s, const char *name, const char *path, const char *origin)
{
    struct texture t;
    size_t i;
    int k;
    for (i = 0; i < s->texture_count; i++) {
        const struct texture *e = &s->textures[i];
        if (e->kind == TEXTURE_IMAGE && strcmp(s->images[e->image - 1].path, path) == 0
            && e->scale.x == 1.0f && e->scale.y == 1.0f && e->offset.x == 0.0f && e->offset.y == 0.0f)
            return (int)i;
    }
    memset(&t, 0, sizeof t);
    strncpy(t.name, name, sizeof t.name - 1);
    t.kind = TEXTURE_IMAGE;
    t.scale = v2(1.0f, 1.0f);
    if ((k = mc_scene_add_image(s, path, origin)) < 0)
        return -1;
    t.image = k + 1;
    return mc_scene_add_texture(s, &t);
}

int mc_scene_find_texture(const struct scene *s, const char *name)
{
    size_t i;
    for (i = 0; i < s->texture_count; i++)
        if (strcmp(s->textures[i].name, name) == 0)
            return (int)i;
    return -1;
}

void mc_scene_set_image(struct scene *s, size_t i, float *rgb, int w, int h)
{
    free(s->images[i].rgb);
    s->images[i].rgb = rgb;
    s->images[i].w = w;
    s->images[i].h = h;
}

int mc_scene_find_material(const struct scene *s, const char *name)
{
    size_t i;
    for (i = 1; i < s->material_count; i++)
        if (strcmp(s->materials[i].name, name) == 0)
            return (int)i;
    return -1;
}

int mc_scene_add_motion(struct scene *s, const struct motion *m)
{
    if (s->motion_count >= 65535)
        return -1;
    return push((void **)&s->motions, &s->motion_count, &s->motion_cap, sizeof *m, m);
}
