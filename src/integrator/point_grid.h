/* point_grid.h: a hash grid over points with radii (SPPM's visible points), after pbrt-v4's
 * SPPMIntegrator grid and SmallVCM's HashGrid: cells of twice the largest radius, hashed into
 * 2n + 1 buckets, filled by a counting sort (count, prefix sum, place) in the order of the
 * points, so the lists, and everything summed over them, do not depend on threads. A point is
 * listed in every cell its box p ± r overlaps (at most 8); a query at x returns the one bucket of
 * x's cell: every point within its radius of x is in it (with others, which the caller tests). */
#ifndef MCRT_POINT_GRID_H
#define MCRT_POINT_GRID_H

#include <stddef.h>
#include <stdint.h>

#include "core/vec.h"

struct point_grid {
    double lo[3];      /* the grid's corner */
    double inv_cell;   /* 1 / the cell size */
    int res[3];        /* cells along each axis (coordinates are clamped to them) */
    size_t size;       /* buckets; 0: the grid is empty */
    uint32_t *start;   /* bucket k is items[start[k], start[k + 1]) */
    uint32_t *items;   /* point indices */
    size_t cap_start, cap_items;
};

/* Build over points p[0, n) with radii r[] (a point with r <= 0 is left out), reusing g's
 * memory ({0} the first time). Returns 0, or -1 when out of memory (g is then empty). */
int mc_point_grid_build(struct point_grid *g, const vec3 *p, const double *r, size_t n);
/* The candidates for a query at x: *count indices of points, among which are all those within
 * their radius of x. */
const uint32_t *mc_point_grid_query(const struct point_grid *g, vec3 x, size_t *count);
void mc_point_grid_free(struct point_grid *g);

#endif
