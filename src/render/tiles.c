/* tiles.c: the tile queue, the worker threads and the progress reports (see tiles.h). */
#include "render/tiles.h"

#include <pthread.h>
#include <stdlib.h>

#include "core/alloc.h"
#include "core/atomic.h"
#include "core/clock.h"
#include "render/render.h"

struct job {
    const struct render_settings *rs;
    mc_tile_fn fn;
    void *ctx;
    int x0, y0, x1, y1;     /* the window, in image coordinates */
    int tiles_x, tile_count;
    pthread_mutex_t lock;   /* guards next_tile and tiles_done */
    int next_tile, tiles_done;
    /* Held by the one thread that is calling the progress callback; `reported`, the count it
     * last reported, is read and written only under it. */
    pthread_mutex_t report_lock;
    int reported;
};

struct worker {
    struct job *job;
    struct tile_worker counters;
};

static int cancelled(const struct job *j)
{
    return j->rs->cancel && mc_atomic_load(j->rs->cancel);
}

static int tiles_done(struct job *j)
{
    int done;
    pthread_mutex_lock(&j->lock);
    done = j->tiles_done;
    pthread_mutex_unlock(&j->lock);
    return done;
}

/* Report the latest count of finished tiles, unless another thread is reporting: that one then
 * reports it, so no worker ever waits for the callback (it is called outside the tile lock, and
 * a slow one delays only its own thread). The reporter calls back while there is a count newer
 * than the one it reported, and after letting go of report_lock looks once more: a tile counted
 * between its last look and the release, whose thread found report_lock taken, is then reported
 * by one of the two. Counts only grow, so the fractions never decrease. */
static void report_progress(struct job *j)
{
    const struct render_settings *rs = j->rs;
    int done, last;
    do {
        if (pthread_mutex_trylock(&j->report_lock) != 0)
            return;
        while ((done = tiles_done(j)) > j->reported) {
            j->reported = done;
            if (rs->progress(rs->user, (double)done / j->tile_count) && rs->cancel)
                mc_atomic_store(rs->cancel, 1);
        }
        last = j->reported;
        pthread_mutex_unlock(&j->report_lock);
    } while (tiles_done(j) > last);
}

static void *work(void *arg)
{
    struct worker *w = arg;
    struct job *j = w->job;
    for (;;) {
        int tile, x0, y0;
        if (cancelled(j))
            break;
        pthread_mutex_lock(&j->lock);
        tile = j->next_tile < j->tile_count ? j->next_tile++ : -1;
        pthread_mutex_unlock(&j->lock);
        if (tile < 0)
            break;
        x0 = j->x0 + (tile % j->tiles_x) * MC_TILE;
        y0 = j->y0 + (tile / j->tiles_x) * MC_TILE;
        j->fn(j->ctx, &w->counters, x0, y0, x0 + MC_TILE < j->x1 ? x0 + MC_TILE : j->x1,
              y0 + MC_TILE < j->y1 ? y0 + MC_TILE : j->y1);
        pthread_mutex_lock(&j->lock);
        j->tiles_done++;
        pthread_mutex_unlock(&j->lock);
        if (j->rs->progress)
            report_progress(j);
    }
    return NULL;
}

mcrt_status mc_tiles_run(const struct render_settings *rs, int x0, int y0, int width, int height,
                         mc_tile_fn fn, void *ctx, struct tile_result *out, mc_diag *d)
{
    struct job j;
    struct worker *workers;
    pthread_t *threads;
    int i, running;
    double t0 = mc_seconds();
    out->rays = out->nan_count = 0;
    out->cancelled = 0;
    j.rs = rs;
    j.fn = fn;
    j.ctx = ctx;
    j.x0 = x0;
    j.y0 = y0;
    j.x1 = x0 + width;
    j.y1 = y0 + height;
    j.tiles_x = (width + MC_TILE - 1) / MC_TILE;
    j.tile_count = j.tiles_x * ((height + MC_TILE - 1) / MC_TILE);
    j.next_tile = j.tiles_done = j.reported = 0;
    workers = mc_calloc((size_t)rs->threads, sizeof *workers);
    threads = mc_calloc((size_t)rs->threads, sizeof *threads);
    if (!workers || !threads || pthread_mutex_init(&j.lock, NULL) != 0) {
        free(workers);
        free(threads);
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory");
    }
    if (pthread_mutex_init(&j.report_lock, NULL) != 0) {
        pthread_mutex_destroy(&j.lock);
    pthread_mutex_destroy(&j.report_lock);
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
        out->rays += workers[i].counters.rays;
        out->nan_count += workers[i].counters.nans;
    }
    pthread_mutex_destroy(&j.lock);
    pthread_mutex_destroy(&j.report_lock);
    free(workers);
    free(threads);
    out->seconds = mc_seconds() - t0;
    out->cancelled = j.tiles_done < j.tile_count;
    return out->cancelled ? MCRT_ERR_CANCELLED : MCRT_OK;
}
