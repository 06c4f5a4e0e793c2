/* point.c: the isotropic point light of intensity I (W/sr): a delta distribution, reached only by
 * light sampling, its radiance at distance d following the inverse-square law I / d². */
#include "light/light_impl.h"
#include "sample/warp.h"

double mc_point_light_power(const struct light_scene *s, const struct light *l)
{
    (void)s;
    return 4.0f * MC_PI * v3_avg(l->intensity);
}

int mc_point_light_bounds(const struct light_scene *s, const struct light *l,
                          struct light_bounds *b)
{
    (void)s;
    b->box.lo = b->box.hi = l->position;
    b->axis = v3(0.0f, 0.0f, 1.0f);
    b->cos_o = -1.0f; /* every direction */
    b->cos_e = 0.0f;
    b->phi = MC_PI * v3_avg(l->intensity);
    b->two_sided = 0;
    return 1;
}

int mc_point_light_sample(const struct light_scene *s, const struct light *l, vec3 p, float time,
                          vec2 u, struct light_sample *out)
{
    vec3 w = v3_sub(l->position, p);
    float d2 = v3_length2(w), d = sqrtf(d2);
    (void)s, (void)time, (void)u;
    if (!(d > 0.0f))
        return 0;
    out->point = l->position;
    out->normal = v3s(0.0f);
    out->wi = v3_scale(w, 1.0f / d);
    out->dist = d;
    out->L = v3_scale(l->intensity, 1.0f / d2); /* inverse-square law: I / r² */
    out->pdf = 1.0f;
    out->delta = 1;
    return 1;
}

float mc_point_light_pdf(const struct light_scene *s, const struct light *l, vec3 p, float time,
                         vec3 wi, float t, const struct surface *sf)
{
    (void)s, (void)l, (void)p, (void)time, (void)wi, (void)t, (void)sf;
    return 0.0f;
}

/* Photons leave the point uniformly over the sphere: pdf 1/(4π), each carrying I·4π. */
int mc_point_light_emission(const struct light_scene *s, const struct light *l, float time,
                            vec2 u_pos, vec2 u_dir, struct light_emission *out)
{
    (void)s, (void)time, (void)u_pos;
    out->p = l->position;
    out->n = v3s(0.0f);
    out->d = mc_warp_uniform_sphere(u_dir);
    out->Le = l->intensity;
    out->pdf_pos = 1.0f;
    out->pdf_dir = mc_warp_uniform_sphere_pdf();
    out->weight = v3_scale(l->intensity, 1.0f / out->pdf_dir);
    return 1;
}

/* Defaults as pbrt's point light: at the origin, intensity 1. */
static const struct block_param params[] = {
    {"position", PARAM_POINT, {0.0f, 0.0f, 0.0f}},
    {"intensity", PARAM_RGB, {1.0f, 1.0f, 1.0f}},
};

static void build(struct light *l, const vec3 *v)
{
    l->position = v[0];
    l->intensity = v[1];
}

const struct light_desc mc_point_light = {"point_light", 0, 1, params, 2, build};
