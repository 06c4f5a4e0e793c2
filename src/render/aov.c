/* aov.c: first-hit albedo, normal and depth per pixel (see aov.h). One extra intersection per
 * camera ray, made only when a layer is asked for, keeps the path tracer itself untouched. */
#include "render/aov.h"

#include <math.h>
#include <stdlib.h>

#include "core/alloc.h"

const char *const mc_aov_names[AOV_COUNT + 1] = {MC_AOVS(MC_NAMES_ENTRY)[AOV_COUNT] = NULL};

int mc_aov_init(struct aov_film *a, int width, int height)
{
    size_t n = (size_t)width * (size_t)height;
    a->width = width;
    a->height = height;
    a->pixels = NULL;
    if (width <= 0 || height <= 0 || n / (size_t)width != (size_t)height)
        return -1;
    a->pixels = mc_calloc(n, sizeof *a->pixels);
    return a->pixels ? 0 : -1;
}

void mc_aov_free(struct aov_film *a)
{
    free(a->pixels);
    a->pixels = NULL;
}

void mc_aov_record(struct aov_pixel *p, const struct scene *s, const struct ray *r)
{
    struct hit h;
    struct surface sf;
    vec3 c, n;
    p->count++;
    h.t = r->tmax;
    if (!mc_scene_intersect(s, r, &h))
        return;
    mc_scene_surface(s, r, &h, &sf);
    c = s->materials[s->prims[h.prim].material].color;
    n = v3_dot(sf.ns, r->d) > 0.0f ? v3_neg(sf.ns) : sf.ns;
    p->albedo[0] += c.x;
    p->albedo[1] += c.y;
    p->albedo[2] += c.z;
    p->normal[0] += n.x;
    p->normal[1] += n.y;
    p->normal[2] += n.z;
    p->depth += h.t;
}

void mc_aov_resolve(const struct aov_film *a, enum aov_kind kind, float *rgb)
{
    size_t i, n = (size_t)a->width * (size_t)a->height;
    int c;
    for (i = 0; i < n; i++) {
        const struct aov_pixel *p = &a->pixels[i];
        double inv = p->count ? 1.0 / (double)p->count : 0.0;
        for (c = 0; c < 3; c++)
            rgb[3 * i + c] = (float)(inv * (kind == AOV_ALBEDO   ? p->albedo[c]
                                            : kind == AOV_NORMAL ? p->normal[c]
                                                                 : p->depth));
    }
}
