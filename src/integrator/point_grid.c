/* point_grid.c: the hash grid of point_grid.h. */
#include "integrator/point_grid.h"

#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/rng.h"

static size_t bucket(const struct point_grid *g, int x, int y, int z)
{
    uint64_t h = mc_hash3((uint64_t)(uint32_t)x, (uint64_t)(uint32_t)y, (uint64_t)(uint32_t)z);
    return (size_t)(h % g->size);
}

static int cell(const struct point_grid *g, double v, int axis)
{
    double c = (v - g->lo[axis]) * g->inv_cell;
    if (!(c > 0.0))
        return 0;
    if (c >= (double)g->res[axis])
        return g->res[axis] - 1;
    return (int)c;
}

static int reserve(uint32_t **a, size_t *cap, size_t n)
{
    uint32_t *b;
    if (n <= *cap)
        return 0;
    b = mc_malloc(n * sizeof *b);
    if (!b)
        return -1;
    free(*a);
    *a = b;
    *cap = n;
    return 0;
}

int mc_point_grid_build(struct point_grid *g, const vec3 *p, const double *r, size_t n)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    double rmax = 0.0;
    size_t i, k, count = 0, run;
    int a, place;
    g->size = 0;
    for (i = 0; i < n; i++) {
        const double q[3] = {p[i].x, p[i].y, p[i].z};
        if (!(r[i] > 0.0))
            continue;
        count++;
        rmax = r[i] > rmax ? r[i] : rmax;
        for (a = 0; a < 3; a++) {
            lo[a] = q[a] < lo[a] ? q[a] : lo[a];
            hi[a] = q[a] > hi[a] ? q[a] : hi[a];
        }
    }
    if (count == 0)
        return 0;
    g->inv_cell = 1.0 / (2.0 * rmax);
    for (a = 0; a < 3; a++) {
        double cells;
        g->lo[a] = lo[a] - rmax;
        cells = (hi[a] + rmax - g->lo[a]) * g->inv_cell + 1.0;
        g->res[a] = cells > (double)(1 << 20) ? 1 << 20 : (int)cells;
    }
    if (reserve(&g->start, &g->cap_start, 2 * count + 2) != 0)
        return -1;
    g->size = 2 * count + 1;
    memset(g->start, 0, (g->size + 1) * sizeof *g->start);
    /* The same loop twice: count the entries of each bucket, then (after an exclusive prefix sum)
     * place them, which leaves start[k] at the end of bucket k; a shift makes it the start. */
    for (place = 0; place < 2; place++) {
        if (place) {
            for (k = 0, run = 0; k < g->size; k++) {
                size_t c = g->start[k];
                g->start[k] = (uint32_t)run;
                run += c;
            }
            if (run > UINT32_MAX || reserve(&g->items, &g->cap_items, run ? run : 1) != 0) {
                g->size = 0;
                return -1;
            }
            g->start[g->size] = (uint32_t)run;
        }
        for (i = 0; i < n; i++) {
            int x, y, z, c0[3], c1[3];
            size_t seen[8], nb;
            const double q[3] = {p[i].x, p[i].y, p[i].z};
            if (!(r[i] > 0.0))
                continue;
            for (a = 0; a < 3; a++) {
                c0[a] = cell(g, q[a] - r[i], a);
                c1[a] = cell(g, q[a] + r[i], a);
            }
            /* The cells' buckets, each once: two cells of a point may share one. */
            nb = 0;
            for (z = c0[2]; z <= c1[2]; z++)
                for (y = c0[1]; y <= c1[1]; y++)
                    for (x = c0[0]; x <= c1[0]; x++) {
                        size_t b = bucket(g, x, y, z), j;
                        for (j = 0; j < nb && seen[j] != b; j++)
                            ;
                        if (j < nb || nb == 8)
                            continue;
                        seen[nb++] = b;
                        if (place)
                            g->items[g->start[b]++] = (uint32_t)i;
                        else
                            g->start[b]++;
                    }
        }
    }
    memmove(g->start + 1, g->start, g->size * sizeof *g->start);
    g->start[0] = 0;
    return 0;
}

const uint32_t *mc_point_grid_query(const struct point_grid *g, vec3 x, size_t *count)
{
    size_t b;
    double q[3];
    if (g->size == 0) {
        *count = 0;
        return NULL;
    }
    q[0] = x.x;
    q[1] = x.y;
    q[2] = x.z;
    /* Outside the grid (beyond every point's reach) is no candidate. */
    if (q[0] < g->lo[0] || q[1] < g->lo[1] || q[2] < g->lo[2]
        || q[0] > g->lo[0] + g->res[0] / g->inv_cell || q[1] > g->lo[1] + g->res[1] / g->inv_cell
        || q[2] > g->lo[2] + g->res[2] / g->inv_cell) {
        *count = 0;
        return NULL;
    }
    b = bucket(g, cell(g, q[0], 0), cell(g, q[1], 1), cell(g, q[2], 2));
    *count = g->start[b + 1] - g->start[b];
    return g->items + g->start[b];
}

void mc_point_grid_free(struct point_grid *g)
{
    free(g->start);
    free(g->items);
    memset(g, 0, sizeof *g);
}
