/* camera.h: the pinhole camera: film points in pixel units to world-space rays. */
#ifndef MCRT_CAMERA_H
#define MCRT_CAMERA_H

#include "geom/ray.h"
#include "scene/scene.h"

struct camera {
    vec3 eye, forward, right, up;  /* orthonormal, right-handed: right = forward × up */
    float tan_half;                /* tan(fov / 2) */
    float aspect;                  /* W / H */
    float inv_width, inv_height;
};

/* Set up from the scene's description for a W×H film. The parser guarantees eye != look and up
 * not parallel to the view direction. */
void mc_camera_init(struct camera *c, const struct camera_desc *d, int width, int height);
/* The ray through film point (x, y) in pixel units, row 0 at the top: direction
 * f + (2x/W − 1)·tan(fov/2)·(W/H)·r + (1 − 2y/H)·tan(fov/2)·u, normalised. */
struct ray mc_camera_ray(const struct camera *c, float x, float y);

#endif
