/* test_tiles.c: the tile pool every integrator's image pass runs on (render/tiles.h): the tiles
 * cover a crop window exactly once, and the progress callback runs outside the lock that hands
 * out tiles: while a slow callback sleeps the other worker goes on rendering tiles, two calls
 * never overlap, and the fractions never decrease and end at 1. */
#include <string.h>
#include <time.h>

#include "render/render.h"
#include "render/tiles.h"
#include "t.h"

enum { X0 = 3, Y0 = 5, W = 250, H = 130, SLOW_CALLS = 3, MAX_CALLS = 4096 };

struct probe {
    unsigned char covered[W * H]; /* times each pixel of the window was given to a tile */
    int tiles;                    /* atomic: tiles rendered so far */
    int in_call, overlaps;        /* atomic: a callback is running; calls that found one */
    int calls;
    double fractions[MAX_CALLS];
    int most_during_sleep;        /* the most tiles another worker finished during one sleep */
};

static void count_tile(void *ctx, struct tile_worker *w, int x0, int y0, int x1, int y1)
{
    struct probe *p = ctx;
    int x, y;
    for (y = y0; y < y1; y++)
        for (x = x0; x < x1; x++)
            if (x >= X0 && x < X0 + W && y >= Y0 && y < Y0 + H)
                p->covered[(y - Y0) * W + (x - X0)]++;
            else
                w->nans++; /* outside the window: counted as a failure below */
    w->rays++;
    __atomic_add_fetch(&p->tiles, 1, __ATOMIC_SEQ_CST);
}

/* The first SLOW_CALLS calls sleep 50 ms each and count the tiles finished meanwhile. */
static int slow_progress(void *user, double done)
{
    struct probe *p = user;
    if (__atomic_exchange_n(&p->in_call, 1, __ATOMIC_SEQ_CST))
        __atomic_add_fetch(&p->overlaps, 1, __ATOMIC_SEQ_CST);
    if (p->calls < MAX_CALLS)
        p->fractions[p->calls] = done;
    if (p->calls++ < SLOW_CALLS) {
        struct timespec nap = {0, 50 * 1000 * 1000};
        int before = __atomic_load_n(&p->tiles, __ATOMIC_SEQ_CST), after;
        nanosleep(&nap, NULL);
        after = __atomic_load_n(&p->tiles, __ATOMIC_SEQ_CST);
        if (after - before > p->most_during_sleep)
            p->most_during_sleep = after - before;
    }
    __atomic_store_n(&p->in_call, 0, __ATOMIC_SEQ_CST);
    return 0;
}

static void test_slow_progress(void)
{
    static struct probe p;
    struct render_settings rs;
    struct tile_result res;
    mc_diag d;
    int i, tiles = ((W + MC_TILE - 1) / MC_TILE) * ((H + MC_TILE - 1) / MC_TILE), once = 1;
    int monotone = 1;
    memset(&p, 0, sizeof p);
    memset(&rs, 0, sizeof rs);
    rs.threads = 2;
    rs.progress = slow_progress;
    rs.user = &p;
    T_CHECK(mc_tiles_run(&rs, X0, Y0, W, H, count_tile, &p, &res, &d) == MCRT_OK, "%s", d.msg);
    T_CHECK(!res.cancelled && res.rays == (uint64_t)tiles && p.tiles == tiles && res.nan_count == 0,
            "%d of %d tiles, %llu outside the window", p.tiles, tiles,
            (unsigned long long)res.nan_count);
    for (i = 0; i < W * H; i++)
        once &= p.covered[i] == 1;
    T_CHECK(once, "every pixel of the window in exactly one tile");
    /* With the callback under the tile lock the other worker could finish at most the tile it
     * had when the sleep began. */
    T_NOTE("most tiles finished by the other worker during a 50 ms callback: %d of %d",
           p.most_during_sleep, tiles);
    T_CHECK(p.most_during_sleep >= 2, "a sleeping callback stalled the other worker (%d tiles)",
            p.most_during_sleep);
    T_CHECK(p.overlaps == 0, "%d overlapping calls", p.overlaps);
    for (i = 1; i < p.calls && i < MAX_CALLS; i++)
        monotone &= p.fractions[i] >= p.fractions[i - 1];
    T_CHECK(p.calls > 0 && monotone && p.fractions[p.calls - 1] == 1.0,
            "%d calls, monotone %d, last %g", p.calls, monotone,
            p.calls ? p.fractions[p.calls - 1] : 0.0);
}

/* Nonzero from the callback sets the cancel flag and stops the run before every tile is done. */
static int cancel_at_once(void *user, double done)
{
    (void)user;
    (void)done;
    return 1;
}

static void test_cancel(void)
{
    static struct probe p;
    struct render_settings rs;
    struct tile_result res;
    mc_diag d;
    int cancel = 0;
    memset(&p, 0, sizeof p);
    memset(&rs, 0, sizeof rs);
    rs.threads = 1;
    rs.progress = cancel_at_once;
    rs.cancel = &cancel;
    T_CHECK(mc_tiles_run(&rs, X0, Y0, W, H, count_tile, &p, &res, &d) == MCRT_ERR_CANCELLED
                && res.cancelled && cancel == 1 && p.tiles == 1,
            "cancelled after %d tiles", p.tiles);
}

int main(void)
{
    test_slow_progress();
    test_cancel();
    return t_done();
}
