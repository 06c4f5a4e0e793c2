/* bvh.h: bounding volume hierarchy over the scene's primitives.
 * Binned SAH build (Wald 2007, "On fast Construction of SAH-based Bounding Volume Hierarchies"),
 * flattened into one node array; traversal visits the nearer child first. */
#ifndef MCRT_BVH_H
#define MCRT_BVH_H

#include <stddef.h>

#include "core/diag.h"
#include "geom/prim.h"

struct bvh_node;

struct bvh {
    struct bvh_node *nodes;
    size_t node_count;
    struct aabb bounds; /* of the whole scene */
};

/* Build over prims[0..n), reordering prims in place into leaf order. n may be 0.
 * On failure (out of memory) b is left empty and the message is in d. */
mcrt_status mc_bvh_build(struct bvh *b, struct prim *prims, size_t n, mc_diag *d);
void mc_bvh_free(struct bvh *b);

/* Nearest hit in (0, r->tmax). Returns 1 and fills h (h->prim included) on a hit. */
int mc_bvh_intersect(const struct bvh *b, const struct prim *prims, const struct ray *r,
                     struct hit *h);
/* Whether anything is hit in (0, r->tmax); stops at the first hit found. */
int mc_bvh_occluded(const struct bvh *b, const struct prim *prims, const struct ray *r);

#endif
