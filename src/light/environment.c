/* environment.c: the constant environment of radiance L, sampled uniformly over the sphere; its
 * power is that of a disk of the scene's radius receiving L (pbrt-v4, UniformInfiniteLight::Phi).
 * Preparation puts it last among the lights (scene/prepare.c), and the default white sky of a
 * scene without lights is one. */
#include "light/light_impl.h"
#include "sample/warp.h"

double mc_environment_light_power(const struct light_scene *s, const struct light *l)
{
    return MC_PI * MC_PI * s->radius * s->radius * v3_avg(l->intensity);
}

int mc_environment_light_sample(const struct light_scene *s, const struct light *l, vec3 p,
                                float time, vec2 u, struct light_sample *out)
{
    (void)s, (void)p, (void)time;
    out->wi = mc_warp_uniform_sphere(u);
    out->dist = INFINITY;
    out->point = out->normal = v3s(0.0f);
    out->L = l->intensity;
    out->pdf = mc_warp_uniform_sphere_pdf();
    out->delta = 0;
    return 1;
}

float mc_environment_light_pdf(const struct light_scene *s, const struct light *l, vec3 p,
                               float time, vec3 wi, float t, const struct surface *sf)
{
    (void)s, (void)l, (void)p, (void)time, (void)wi, (void)t, (void)sf;
    return mc_warp_uniform_sphere_pdf();
}

/* A direction w toward the sky uniform on the sphere; the photon travels along d = −w from a point
 * uniform on the disk of radius R centred at centre + R·w and normal to w, which lies outside the
 * bounding sphere and covers the whole scene as seen along d. */
int mc_environment_light_emission(const struct light_scene *s, const struct light *l, float time,
                                  vec2 u_pos, vec2 u_dir, struct light_emission *out)
{
    vec3 w = mc_warp_uniform_sphere(u_dir);
    vec2 q = mc_warp_concentric_disk(u_pos);
    frame f = frame_from_normal(w);
    float r = s->radius;
    (void)time;
    out->d = v3_neg(w);
    out->n = out->d;
    out->p = v3_add(v3_madd(s->center, w, r), frame_to_world(&f, v3(q.x * r, q.y * r, 0.0f)));
    out->Le = l->intensity;
    out->pdf_pos = 1.0f / (MC_PI * r * r);
    out->pdf_dir = mc_warp_uniform_sphere_pdf();
    out->weight = v3_scale(l->intensity, 1.0f / (out->pdf_pos * out->pdf_dir));
    return isfinite(out->pdf_pos) && out->pdf_pos > 0.0f;
}

/* Default radiance 1: the white sky a scene without lights gets anyway. */
static const struct block_param params[] = {
    {"radiance", PARAM_RGB, {1.0f, 1.0f, 1.0f}},
};

static void build(struct light *l, const vec3 *v) { l->intensity = v[0]; }

const struct light_desc mc_environment_light = {"environment", 1, 0, params, 1, build};
