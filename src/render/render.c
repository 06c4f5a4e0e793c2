/* render.c: the tile queue and the worker threads (see render.h). */
#include "render/render.h"

#include <pthread.h>
#include <stdlib.h>
#include <time.h>

#include "camera/camera.h"
#include "core/alloc.h"
#include "integrator/integrator.h"
#include "sample/filter.h"
#include "sample/sampler.h"

enum { TILE = 16 };

struct job;
struct worker;
typedef void (*tile_fn)(struct job *j, int x0, int y0, int x1, int y1, struct worker *w);

struct job {
    const struct scene *scene;
    const struct render_settings *rs;
    struct film *film;
    struct camera camera;
    tile_fn tile;                     /* specialised for the scene's features */
    mc_path_fn path;
    int x0, y0;                       /* the film's origin in the image (render_settings crop) */
    int tiles_x, tile_count;
    pthread_mutex_t lock;   /* guards next_tile, tiles_done and the progress callback */
    int next_tile, tiles_done;
};

/* Per-thread counters, each on its own cache lines so that workers never share one. */
struct worker {
    struct job *job;
    uint64_t rays, nans;
    char pad[64];
};

static int cancelled(const struct job *j)
{
    return j->rs->cancel && mc_atomic_load(j->rs->cancel);
}

/* The samples of pixel (x, y) of the image (the film may be a crop of it). F (the features that change camera rays) is a constant in each
 * instantiation below, so a pinhole camera in a still scene draws neither lens nor time samples. */
static inline void render_pixel(struct job *j, struct worker *w, int x, int y, unsigned F)
{
    const struct render_settings *rs = j->rs;
    struct film_pixel *px = &j->film->pixels[(size_t)(y - j->y0) * (size_t)j->film->width
                                             + (size_t)(x - j->x0)];
    struct sampler smp;
    int i, spp = rs->pixel_spp ? rs->pixel_spp[px - j->film->pixels] : rs->spp;
    mc_sampler_pixel(&smp, rs->sampler, rs->seed, x, y, spp);
    for (i = 0; i < spp; i++) {
        vec2 off;
        struct ray r;
        vec3 L;
        mc_sampler_start(&smp, (uint32_t)i);
        /* Filter importance sampling (Ernst et al. 2006): film points distributed as the filter
         * around the pixel centre, every sample of weight 1. */
        off = mc_filter_sample(j->scene->film.filter, mc_sampler_2d(&smp));
        off.x += (float)x + 0.5f;
        off.y += (float)y + 0.5f;
        r = F & FEATURE_LENS ? mc_camera_ray_lens(&j->camera, off.x, off.y, mc_sampler_2d(&smp))
                             : mc_camera_ray(&j->camera, off.x, off.y);
        if (F & FEATURE_MOTION)
            mc_camera_at_time(&j->camera, &r, mc_camera_time(&j->camera, mc_sampler_1d(&smp)));
        if (rs->aov)
            mc_aov_record(&rs->aov->pixels[px - j->film->pixels], j->scene, &r);
        L = j->path(j->scene, &rs->integrator, r, &smp, &w->rays);
        if (v3_is_finite(L))
            mc_film_add(px, L);
        else
            w->nans++;
    }
}

#define TILE_KERNEL(name, F)                                                                   \
    static void name(struct job *j, int x0, int y0, int x1, int y1, struct worker *w)          \
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

static tile_fn tile_kernel(unsigned features)
{
    static const tile_fn table[4] = {tile_pinhole, tile_lens, tile_pinhole_motion, tile_lens_motion};
    return table[(features & FEATURE_LENS ? 1 : 0) | (features & FEATURE_MOTION ? 2 : 0)];
}

static void render_tile(struct job *j, int tile, struct worker *w)
{
    int x0 = j->x0 + (tile % j->tiles_x) * TILE, y0 = j->y0 + (tile / j->tiles_x) * TILE;
    int x1 = x0 + TILE < j->x0 + j->film->width ? x0 + TILE : j->x0 + j->film->width;
    int y1 = y0 + TILE < j->y0 + j->film->height ? y0 + TILE : j->y0 + j->film->height;
    j->tile(j, x0, y0, x1, y1, w);
}

static void *work(void *arg)
{
    struct worker *w = arg;
    struct job *j = w->job;
    for (;;) {
        int tile;
        if (cancelled(j))
            break;
        pthread_mutex_lock(&j->lock);
        tile = j->next_tile < j->tile_count ? j->next_tile++ : -1;
        pthread_mutex_unlock(&j->lock);
        if (tile < 0)
            break;
        render_tile(j, tile, w);
        pthread_mutex_lock(&j->lock);
        j->tiles_done++;
        if (j->rs->progress && j->rs->progress(j->rs->user, (double)j->tiles_done / j->tile_count)
            && j->rs->cancel)
            mc_atomic_store(j->rs->cancel, 1);
        pthread_mutex_unlock(&j->lock);
    }
    return NULL;
}

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

mcrt_status mc_render(const struct scene *s, const struct render_settings *rs, struct film *f,
                      struct render_result *out, mc_diag *d)
{
    struct job j;
    struct worker *workers;
    pthread_t *threads;
    int i, running;
    double t0 = now_seconds();
    out->rays = out->nan_count = 0;
    out->cancelled = 0;
    j.scene = s;
    j.rs = rs;
    j.film = f;
    mc_camera_init(&j.camera, &s->camera, s->film.width, s->film.height);
    j.x0 = rs->crop_x0;
    j.y0 = rs->crop_y0;
    j.tile = tile_kernel(rs->features);
    j.path = mc_path_kernel(rs->features);
    j.tiles_x = (f->width + TILE - 1) / TILE;
    j.tile_count = j.tiles_x * ((f->height + TILE - 1) / TILE);
    j.next_tile = j.tiles_done = 0;
    workers = mc_calloc((size_t)rs->threads, sizeof *workers);
    threads = mc_calloc((size_t)rs->threads, sizeof *threads);
    if (!workers || !threads || pthread_mutex_init(&j.lock, NULL) != 0) {
        free(workers);
        free(threads);
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory");
    }
    /* The calling thread works too, as worker 0. If a thread cannot be started the render goes
     * on with fewer: the image is the same, only slower. */
    workers[0].job = &j;
    for (running = 1; running < rs->threads; running++) {
        workers[running].job = &j;
        if (pthread_create(&threads[running], NULL, work, &workers[running]) != 0)
            break;
    }
    work(&workers[0]);
    for (i = 1; i < running; i++)
        pthread_join(threads[i], NULL);
    for (i = 0; i < running; i++) {
        out->rays += workers[i].rays;
        out->nan_count += workers[i].nans;
    }
    pthread_mutex_destroy(&j.lock);
    free(workers);
    free(threads);
    out->seconds = now_seconds() - t0;
    out->cancelled = j.tiles_done < j.tile_count;
    return out->cancelled ? MCRT_ERR_CANCELLED : MCRT_OK;
}
