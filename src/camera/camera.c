/* camera.c: pinhole camera with a vertical field of view (conventions in man/mcrt.5). */
#include "camera/camera.h"

void mc_camera_init(struct camera *c, const struct camera_desc *d, int width, int height)
{
    c->eye = d->eye;
    c->forward = v3_normalize(v3_sub(d->look, d->eye));
    c->right = v3_normalize(v3_cross(c->forward, d->up));
    c->up = v3_cross(c->right, c->forward);
    c->tan_half = tanf(0.5f * d->fov * (MC_PI / 180.0f));
    c->aspect = (float)width / (float)height;
    c->inv_width = 1.0f / (float)width;
    c->inv_height = 1.0f / (float)height;
}

struct ray mc_camera_ray(const struct camera *c, float x, float y)
{
    struct ray r;
    float sx = (2.0f * x * c->inv_width - 1.0f) * c->tan_half * c->aspect;
    float sy = (1.0f - 2.0f * y * c->inv_height) * c->tan_half;
    r.o = c->eye;
    r.d = v3_normalize(v3_add(c->forward, v3_add(v3_scale(c->right, sx), v3_scale(c->up, sy))));
    r.tmax = INFINITY;
    return r;
}
