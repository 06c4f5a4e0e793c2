/* camera.h: the camera: film points in pixel units to world-space rays, through a pinhole or a
 * thin lens, at a time within the shutter.
 *
 * The three parts compose, so that a render draws only the sample dimensions its scene needs:
 *     r = mc_camera_ray(c, x, y)                 pinhole (no lens dimensions)
 *     r = mc_camera_ray_lens(c, x, y, u)         thin lens (2 dimensions)
 *     mc_camera_at_time(c, &r, mc_camera_time(c, u))   a moving camera (1 dimension)
 * A camera ray always starts where the camera is at r.time: the first two give r.time = shutter
 * open, and mc_camera_at_time moves a ray to another time. Every direction is unit length. */
#ifndef MCRT_CAMERA_H
#define MCRT_CAMERA_H

#include "geom/ray.h"

/* The camera as the scene describes it (scene/parse.c fills it; defaults after each field). */
struct camera_desc {
    vec3 eye, look, up;              /* (0 0 5), (0 0 0), (0 1 0) */
    float fov;                       /* full vertical angle in degrees: 40 */
    float lens_radius;               /* thin lens; 0 = pinhole (the default) */
    float focus_distance;            /* along the view direction; 0 = |look - eye| (the default) */
    float shutter[2];                /* open and close times: 0 1 */
    vec3 move;                       /* translation of eye and look per unit time: 0 */
};

struct camera {
    vec3 eye, forward, right, up;  /* orthonormal, right-handed: right = forward × up */
    vec3 origin;                   /* the eye at shutter open: eye + shutter[0]·move */
    vec3 move;                     /* translation of the whole camera per unit time */
    float tan_half;                /* tan(fov / 2) */
    float aspect;                  /* W / H */
    float inv_width, inv_height;
    float lens_radius;             /* 0 for a pinhole */
    float lens_per_focus;          /* lens_radius / focus distance */
    float shutter_open, shutter_length;
};

/* Set up from the scene's description for a W×H film. The parser guarantees eye != look, up
 * not parallel to the view direction, lens_radius >= 0, focus_distance >= 0 (0 meaning
 * |look − eye|) and shutter[1] >= shutter[0]. */
void mc_camera_init(struct camera *c, const struct camera_desc *d, int width, int height);

/* The pinhole ray through film point (x, y) in pixel units, row 0 at the top, at shutter open:
 * from the eye along f + (2x/W − 1)·tan(fov/2)·(W/H)·r + (1 − 2y/H)·tan(fov/2)·u, normalised.
 * The lens radius is ignored: this is the path for scenes without depth of field. */
struct ray mc_camera_ray(const struct camera *c, float x, float y);

/* The thin-lens ray through film point (x, y) at shutter open (pbrt-v4's PerspectiveCamera): it
 * starts at the lens point eye + lens_radius·(l.x·r + l.y·u), l = the concentric disk map of u,
 * and passes through the point where the pinhole ray of (x, y) meets the focus plane (normal to
 * the view direction, at the focus distance), so that plane is imaged sharply. With
 * lens_radius 0 it returns exactly mc_camera_ray's ray. */
struct ray mc_camera_ray_lens(const struct camera *c, float x, float y, vec2 u);

/* The scene time of a shutter sample u in [0, 1): shutter open + u·(close − open). */
float mc_camera_time(const struct camera *c, float u);

/* Move a camera ray to time t: the camera translates by (t − r.time)·move; r.time = t. The
 * direction is unchanged (the camera does not rotate). */
void mc_camera_at_time(const struct camera *c, struct ray *r, float t);

#endif
