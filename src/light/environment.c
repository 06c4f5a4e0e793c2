/* environment.c: the environment, radiance from every direction at infinity: a constant sky of
 * radiance L, sampled uniformly over the sphere, or an image map (light/envmap.h) that `intensity`
 * scales, sampled in proportion to its luminance × sin θ. Its power is that of a disk of the
 * scene's radius R receiving it: πR²·¼∫L dω, which is π²R²L for the constant sky (pbrt-v4,
 * UniformInfiniteLight::Phi, here per side of the disk). Preparation puts it last among the lights
 * (scene/prepare.c), and the default white sky of a scene without lights is one. */
#include "light/light_impl.h"

#include "light/envmap.h"
#include "sample/warp.h"

double mc_environment_light_power(const struct light_scene *s, const struct light *l)
{
    double integral = l->map ? l->map->power_integral : 4.0 * MC_PI;
    return MC_PI * s->radius * s->radius * 0.25 * integral * v3_avg(l->intensity);
}

int mc_environment_light_bounds(const struct light_scene *s, const struct light *l,
                                struct light_bounds *b)
{
    (void)s, (void)l, (void)b;
    return 0;
}

vec3 mc_environment_radiance(const struct light *l, vec3 d)
{
    if (!l->map)
        return l->intensity;
    return v3_mul(l->intensity, mc_envmap_eval(l->map, frame_to_local(&l->orient, d)));
}

/* A direction toward the sky from the map's distribution or uniform, with its solid-angle pdf
 * and the radiance arriving from it. */
static vec3 sample_direction(const struct light *l, vec2 u, float *pdf, vec3 *L)
{
    vec3 w, Lmap;
    if (!l->map) {
        *pdf = mc_warp_uniform_sphere_pdf();
        *L = l->intensity;
        return mc_warp_uniform_sphere(u);
    }
    w = frame_to_world(&l->orient, mc_envmap_sample(l->map, u, pdf, &Lmap));
    *L = v3_mul(l->intensity, Lmap);
    return w;
}

int mc_environment_light_sample(const struct light_scene *s, const struct light *l, vec3 p,
                                float time, vec2 u, struct light_sample *out)
{
    (void)s, (void)p, (void)time;
    out->wi = sample_direction(l, u, &out->pdf, &out->L);
    out->dist = INFINITY;
    out->point = out->normal = v3s(0.0f);
    out->delta = 0;
    return out->pdf > 0.0f;
}

float mc_environment_light_pdf(const struct light_scene *s, const struct light *l, vec3 p,
                               float time, vec3 wi, float t, const struct surface *sf)
{
    (void)s, (void)p, (void)time, (void)t, (void)sf;
    if (!l->map)
        return mc_warp_uniform_sphere_pdf();
    return mc_envmap_pdf(l->map, frame_to_local(&l->orient, wi));
}

/* A direction w toward the sky as light sampling chooses it; the photon travels along d = −w from
 * a point uniform on the disk of radius R centred at centre + R·w and normal to w, which lies
 * outside the bounding sphere and covers the whole scene as seen along d (pbrt-v3
 * InfiniteAreaLight::Sample_Le). */
int mc_environment_light_emission(const struct light_scene *s, const struct light *l, float time,
                                  vec2 u_pos, vec2 u_dir, struct light_emission *out)
{
    vec3 w = sample_direction(l, u_dir, &out->pdf_dir, &out->Le);
    vec2 q = mc_warp_concentric_disk(u_pos);
    frame f = frame_from_normal(w);
    float r = s->radius;
    (void)time;
    out->d = v3_neg(w);
    out->n = out->d;
    out->p = v3_add(v3_madd(s->center, w, r), frame_to_world(&f, v3(q.x * r, q.y * r, 0.0f)));
    out->pdf_pos = 1.0f / (MC_PI * r * r);
    if (!(out->pdf_dir > 0.0f) || !isfinite(out->pdf_pos) || !(out->pdf_pos > 0.0f))
        return 0;
    out->weight = v3_scale(out->Le, 1.0f / (out->pdf_pos * out->pdf_dir));
    return 1;
}

/* Default radiance 1: the white sky a scene without lights gets anyway. radiance × scale is the
 * constant sky's radiance, or what the map's pixels are multiplied by. */
enum { P_RADIANCE, P_MAP, P_SCALE, P_ROTATE };
static const struct block_param params[] = {
    {"radiance", PARAM_RGB, {1.0f, 1.0f, 1.0f}},
    {"map", PARAM_IMAGE, {0.0f, 0.0f, 0.0f}},
    {"scale", PARAM_LENGTH, {1.0f, 0.0f, 0.0f}},
    {"rotate", PARAM_SPIN, {0.0f, 0.0f, 0.0f}},
};

/* The rotation by |spin| degrees about spin's direction (Rodrigues' formula) as the frame whose
 * axes are the images of x, y and z. */
static frame rotation(vec3 spin)
{
    float deg = sqrtf(v3_length2(spin)), a = deg * (MC_PI / 180.0f), c = cosf(a), s = sinf(a);
    vec3 k = deg > 0.0f ? v3_scale(spin, 1.0f / deg) : v3(0.0f, 1.0f, 0.0f);
    vec3 e[3] = {{1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}}, r[3];
    frame f;
    int i;
    for (i = 0; i < 3; i++) /* v cos a + (k×v) sin a + k (k·v)(1 − cos a) */
        r[i] = v3_add(v3_add(v3_scale(e[i], c), v3_scale(v3_cross(k, e[i]), s)),
                      v3_scale(k, v3_dot(k, e[i]) * (1.0f - c)));
    f.t = r[0];
    f.b = r[1];
    f.n = r[2];
    return f;
}

static void build(struct light *l, const vec3 *v)
{
    l->image = (int)v[P_MAP].x;
    l->intensity = v3_scale(v[P_RADIANCE], v[P_SCALE].x);
    l->orient = rotation(v[P_ROTATE]);
}

const struct light_desc mc_environment_light = {"environment", 1, 0, params, 4, build};
