/* render.c: the per-ray pass (see render.h): camera samples, filter importance sampling, AOVs and
 * the NaN count around a radiance function, specialised for the camera's features. */
#include "render/render.h"

#include "camera/camera.h"
#include "sample/filter.h"
#include "sample/sampler.h"
#include "scene/features.h"

struct job;
typedef void (*tile_kernel_fn)(struct job *j, int x0, int y0, int x1, int y1,
                               struct tile_worker *w);

struct job {
    const struct scene *scene;
    const struct render_settings *rs;
    struct film *film;
    struct camera camera;
    tile_kernel_fn tile;              /* specialised for the scene's features */
    mc_radiance_fn Li;
    int x0, y0;                       /* the film's origin in the image (render_settings crop) */
};

/* The samples of pixel (x, y) of the image (the film may be a crop of it). F (the features that
 * change camera rays) is a constant in each instantiation below, so a pinhole camera in a still
 * scene draws neither lens nor time samples. */
static inline void render_pixel(struct job *j, struct tile_worker *w, int x, int y, unsigned F)
{
    const struct render_settings *rs = j->rs;
    struct film_pixel *px = &j->film->pixels[(size_t)(y - j->y0) * (size_t)j->film->width
                                             + (size_t)(x - j->x0)];
    struct sampler smp;
    int h, i, spp = rs->pixel_spp ? rs->pixel_spp[px - j->film->pixels] : rs->spp;
    int split = mc_film_half_split(spp, rs->pass);
    /* Each half of the pixel (film.h) is a complete set of the sampler, of its own size and
     * seed, so that the two half means are independent. */
    for (h = 0; h < 2; h++) {
        int n = h == 0 ? split : spp - split;
        mc_sampler_pixel(&smp, rs->sampler, mc_film_half_seed(rs->seed, h), x, y, n);
        for (i = 0; i < n; i++) {
            vec2 off;
            struct ray r;
            vec3 L;
            mc_sampler_start(&smp, (uint32_t)i);
            /* Filter importance sampling (Ernst et al. 2006): film points distributed as the
             * filter around the pixel centre, every sample of weight 1. */
            off = mc_filter_sample(j->scene->film.filter, mc_sampler_2d(&smp));
            off.x += (float)x + 0.5f;
            off.y += (float)y + 0.5f;
            r = F & FEATURE_LENS
                    ? mc_camera_ray_lens(&j->camera, off.x, off.y, mc_sampler_2d(&smp))
                    : mc_camera_ray(&j->camera, off.x, off.y);
            if (F & FEATURE_MOTION)
                mc_camera_at_time(&j->camera, &r,
                                  mc_camera_time(&j->camera, mc_sampler_1d(&smp)));
            if (rs->aov)
                mc_aov_record(&rs->aov->pixels[px - j->film->pixels], h, j->scene, &r);
            L = j->Li(j->scene, &rs->integrator, r, &smp, &w->rays);
            if (v3_is_finite(L))
                mc_film_add(&px->half[h], L);
            else
                w->nans++;
        }
    }
}

#define TILE_KERNEL(name, F)                                                                   \
    static void name(struct job *j, int x0, int y0, int x1, int y1, struct tile_worker *w)     \
    {                                                                                          \
        int x, y;                                                                              \
        for (y = y0; y < y1; y++)                                                              \
            for (x = x0; x < x1; x++)                                                          \
                render_pixel(j, w, x, y, F);                                                   \
    }
TILE_KERNEL(tile_pinhole, 0u)
TILE_KERNEL(tile_lens, FEATURE_LENS)
TILE_KERNEL(tile_pinhole_motion, FEATURE_MOTION)
TILE_KERNEL(tile_lens_motion, FEATURE_LENS | FEATURE_MOTION)

static tile_kernel_fn tile_kernel(unsigned features)
{
    static const tile_kernel_fn table[4] = {tile_pinhole, tile_lens, tile_pinhole_motion,
                                            tile_lens_motion};
    return table[(features & FEATURE_LENS ? 1 : 0) | (features & FEATURE_MOTION ? 2 : 0)];
}

static void render_tile(void *ctx, struct tile_worker *w, int x0, int y0, int x1, int y1)
{
    struct job *j = ctx;
    j->tile(j, x0, y0, x1, y1, w);
}

mcrt_status mc_render_rays(const struct scene *s, const struct render_settings *rs,
                           mc_radiance_fn Li, struct film *f, struct tile_result *out, mc_diag *d)
{
    struct job j;
    j.scene = s;
    j.rs = rs;
    j.film = f;
    mc_camera_init(&j.camera, &s->camera, s->film.width, s->film.height);
    j.x0 = rs->crop_x0;
    j.y0 = rs->crop_y0;
    j.tile = tile_kernel(rs->features);
    j.Li = Li;
    return mc_tiles_run(rs, j.x0, j.y0, f->width, f->height, render_tile, &j, out, d);
}
