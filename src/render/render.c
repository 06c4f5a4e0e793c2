/* render.c: the tile queue and the worker threads (see render.h). */
#include "render/render.h"

#include <pthread.h>
#include <stdlib.h>
#include <time.h>

#include "camera/camera.h"
#include "integrator/integrator.h"
#include "sample/sampler.h"

enum { TILE = 16 };

struct job {
    const struct scene *scene;
    const struct render_settings *rs;
    struct film *film;
    struct camera camera;
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
    return j->rs->cancel && __atomic_load_n(j->rs->cancel, __ATOMIC_RELAXED);
}

static void render_tile(struct job *j, int tile, struct worker *w)
{
    const struct render_settings *rs = j->rs;
    int x0 = (tile % j->tiles_x) * TILE, y0 = (tile / j->tiles_x) * TILE;
    int x1 = x0 + TILE < j->film->width ? x0 + TILE : j->film->width;
    int y1 = y0 + TILE < j->film->height ? y0 + TILE : j->film->height;
    int stratified = j->scene->film.sampler == SAMPLER_STRATIFIED;
    int x, y, i;
    for (y = y0; y < y1; y++) {
        for (x = x0; x < x1; x++) {
            struct film_pixel *px = &j->film->pixels[(size_t)y * (size_t)j->film->width + (size_t)x];
            struct sampler smp;
            mc_sampler_pixel(&smp, rs->seed, x, y, rs->spp, stratified);
            for (i = 0; i < rs->spp; i++) {
                vec2 u = mc_sampler_start(&smp, (uint32_t)i);
                struct ray r = mc_camera_ray(&j->camera, (float)x + u.x, (float)y + u.y);
                vec3 L = mc_path_radiance(j->scene, &rs->integrator, r, &smp, &w->rays);
                if (v3_is_finite(L))
                    mc_film_add(px, L);
                else
                    w->nans++;
            }
        }
    }
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
            __atomic_store_n(j->rs->cancel, 1, __ATOMIC_RELAXED);
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
    mc_camera_init(&j.camera, &s->camera, f->width, f->height);
    j.tiles_x = (f->width + TILE - 1) / TILE;
    j.tile_count = j.tiles_x * ((f->height + TILE - 1) / TILE);
    j.next_tile = j.tiles_done = 0;
    workers = calloc((size_t)rs->threads, sizeof *workers);
    threads = calloc((size_t)rs->threads, sizeof *threads);
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
