/* camera.c: pinhole and thin-lens perspective camera with a vertical field of view and a moving
 * shutter (conventions in man/mcrt.5; the thin lens after pbrt-v4, PerspectiveCamera). */
#include "camera/camera.h"

#include "sample/warp.h"

void mc_camera_init(struct camera *c, const struct camera_desc *d, int width, int height)
{
    vec3 view = v3_sub(d->look, d->eye);
    float focus = d->focus_distance > 0.0f ? d->focus_distance : v3_length(view);
    c->eye = d->eye;
    c->forward = v3_normalize(view);
    c->right = v3_normalize(v3_cross(c->forward, d->up));
    c->up = v3_cross(c->right, c->forward);
    c->move = d->move;
    c->origin = v3_madd(d->eye, d->move, d->shutter[0]);
    c->tan_half = tanf(0.5f * d->fov * (MC_PI / 180.0f));
    c->aspect = (float)width / (float)height;
    c->inv_width = 1.0f / (float)width;
    c->inv_height = 1.0f / (float)height;
    c->lens_radius = d->lens_radius;
    c->lens_per_focus = d->lens_radius / focus;
    c->shutter_open = d->shutter[0];
    c->shutter_length = d->shutter[1] - d->shutter[0];
}

/* The direction to film point (x, y), scaled so that its component along forward is 1: the
 * pinhole ray meets the focus plane at eye + focus·film_direction. */
static inline vec3 film_direction(const struct camera *c, float x, float y)
{
    float sx = (2.0f * x * c->inv_width - 1.0f) * c->tan_half * c->aspect;
    float sy = (1.0f - 2.0f * y * c->inv_height) * c->tan_half;
    return v3_add(c->forward, v3_add(v3_scale(c->right, sx), v3_scale(c->up, sy)));
}

struct ray mc_camera_ray(const struct camera *c, float x, float y)
{
    struct ray r;
    r.o = c->origin;
    r.d = v3_normalize(film_direction(c, x, y));
    r.tmax = INFINITY;
    r.time = c->shutter_open;
    return r;
}

struct ray mc_camera_ray_lens(const struct camera *c, float x, float y, vec2 u)
{
    vec2 l = mc_warp_concentric_disk(u);
    vec3 lens = v3_add(v3_scale(c->right, l.x), v3_scale(c->up, l.y)); /* on the unit disk */
    struct ray r;
    /* From lens point o = eye + R·lens to the focus point eye + F·D the ray runs along
     * F·D − R·lens = F·(D − (R/F)·lens). Written in this form, R = 0 subtracts an exact zero
     * from D and adds one to the eye, which makes the pinhole ray bit for bit. */
    r.o = v3_madd(c->origin, lens, c->lens_radius);
    r.d = v3_normalize(v3_madd(film_direction(c, x, y), lens, -c->lens_per_focus));
    r.tmax = INFINITY;
    r.time = c->shutter_open;
    return r;
}

float mc_camera_time(const struct camera *c, float u)
{
    return c->shutter_open + u * c->shutter_length;
}

void mc_camera_at_time(const struct camera *c, struct ray *r, float t)
{
    r->o = v3_madd(r->o, c->move, t - r->time);
    r->time = t;
}
