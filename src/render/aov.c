/* aov.c: first-surface albedo, normal, depth and emission per pixel and half (see aov.h). Its own
 * rays, traced only when a layer is asked for, keep the path tracer itself untouched. */
#include "render/aov.h"

#include <math.h>
#include <stdlib.h>

#include "bsdf/bsdf.h"
#include "core/alloc.h"
#include "light/light.h"

/* Delta bounces followed before the surface met is taken as it is (a hall of mirrors). */
#define MAX_DELTA_BOUNCES 8

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

static void add3(double *sum, vec3 v)
{
    sum[0] += v.x;
    sum[1] += v.y;
    sum[2] += v.z;
}

void mc_aov_record(struct aov_pixel *p, int half, const struct scene *s, const struct ray *r)
{
    struct aov_sums *a = &p->half[half];
    struct ray ray = *r;
    vec3 beta = v3s(1.0f), E = v3s(0.0f);
    double length = 0.0;
    int bounce;
    a->count++;
    for (bounce = 0;; bounce++) {
        struct hit h;
        struct surface sf;
        struct bsdf b;
        struct bsdf_sample bs;
        const struct prim *pr;
        frame fr;
        vec2 u;
        h.t = ray.tmax;
        if (!mc_scene_intersect(s, &ray, &h)) {
            if (s->env_light >= 0)
                E = v3_add(E, v3_mul(beta, mc_environment_radiance(&s->lights[s->env_light],
                                                                   ray.d)));
            break;
        }
        mc_scene_surface(s, &ray, &h, &sf);
        pr = &s->prims[h.prim];
        length += h.t;
        if (pr->light >= 0)
            E = v3_add(E, v3_mul(beta, mc_light_emitted(pr, &sf)));
        mc_scene_bsdf(s, &ray, &h, &b);
        if (!mc_bsdf_is_delta(&b) || bounce == MAX_DELTA_BOUNCES) {
            add3(a->albedo, v3_mul(beta, b.color));
            add3(a->normal, v3_dot(sf.ns, ray.d) > 0.0f ? v3_neg(sf.ns) : sf.ns);
            a->depth += length;
            break;
        }
        fr = frame_from_normal(sf.ns);
        u.x = u.y = 0.5f;
        if (!mc_bsdf_sample(&b, frame_to_local(&fr, v3_neg(ray.d)), 0.5f, u, MC_RADIANCE, &bs))
            break;
        beta = v3_mul(beta, bs.weight);
        ray.d = frame_to_world(&fr, bs.wi);
        ray.o = ray_spawn(sf.p, side_normal(sf.ng, ray.d), sf.err);
        ray.tmax = INFINITY;
    }
    add3(a->emission, E);
    a->emission2[0] += (double)E.x * E.x;
    a->emission2[1] += (double)E.y * E.y;
    a->emission2[2] += (double)E.z * E.z;
}

void mc_aov_emission_variance(const struct aov_film *a, float *var)
{
    size_t i, n = (size_t)a->width * (size_t)a->height;
    int c;
    for (i = 0; i < n; i++) {
        const struct aov_sums *p = a->pixels[i].half;
        double k = (double)(p[0].count + p[1].count);
        for (c = 0; c < 3; c++) {
            double s = p[0].emission[c] + p[1].emission[c];
            double s2 = p[0].emission2[c] + p[1].emission2[c], v = (s2 - s * s / k) / (k - 1.0);
            var[3 * i + c] = k >= 2.0 && v > 0.0 ? (float)(v / k) : 0.0f;
        }
    }
}

void mc_aov_resolve(const struct aov_film *a, enum aov_kind kind, int h, float *rgb)
{
    size_t i, n = (size_t)a->width * (size_t)a->height;
    int c, k;
    for (i = 0; i < n; i++) {
        double sum[3] = {0.0, 0.0, 0.0};
        uint64_t count = 0;
        for (k = 0; k < 2; k++) {
            const struct aov_sums *p = &a->pixels[i].half[k];
            if (h >= 0 && k != h)
                continue;
            count += p->count;
            for (c = 0; c < 3; c++)
                sum[c] += kind == AOV_ALBEDO   ? p->albedo[c]
                          : kind == AOV_NORMAL ? p->normal[c]
                          : kind == AOV_DEPTH  ? p->depth
                                               : p->emission[c];
        }
        for (c = 0; c < 3; c++)
            rgb[3 * i + c] = (float)(count ? sum[c] / (double)count : 0.0);
    }
}
