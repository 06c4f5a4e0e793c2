/* bvh.h: bounding volume hierarchy over the scene's primitives.
 * Binned SAH build (Wald 2007, "On fast Construction of SAH-based Bounding Volume Hierarchies"),
 * parallel over subtrees, collapsed into an 8-wide BVH; traversal visits the nearest child first. */
#ifndef MCRT_BVH_H
#define MCRT_BVH_H

#include <stddef.h>

#include "core/diag.h"
#include "geom/prim.h"

struct bvh_node;
struct motion;
struct tri4;

struct bvh {
    struct bvh_node *nodes;
    size_t node_count;
    struct tri4 *tri4;  /* the primitives four at a time, for the 4-wide triangle test (tri4.h) */
    size_t tri4_count;
    struct aabb bounds; /* of the whole scene */
};

/* Build over prims[0..n), which the BVH reads but does not move: a hit's prim is an index into
 * prims. n may be 0. On failure (out of memory) b is left empty and the message is in d. */
mcrt_status mc_bvh_build(struct bvh *b, const struct prim *prims, size_t n, mc_diag *d);
/* The same build with the primitives' boxes given: bounds[i] bounds prims[i]. For moving
 * primitives, bounds over the times their rays will carry. NULL: the primitives' own bounds
 * (mc_bvh_build). */
mcrt_status mc_bvh_build_bounds(struct bvh *b, const struct prim *prims, const struct aabb *bounds,
                                size_t n, mc_diag *d);
/* mc_bvh_build_bounds on up to `threads` threads (0: one per processor online). The result is the
 * same for any number of threads. (The other two builds use one per processor.) */
mcrt_status mc_bvh_build_threads(struct bvh *b, const struct prim *prims, const struct aabb *bounds,
                                 size_t n, int threads, mc_diag *d);
void mc_bvh_free(struct bvh *b);
/* Bytes the BVH holds beyond the primitives: its nodes and its leaf data (the triangle blocks). */
size_t mc_bvh_bytes(const struct bvh *b);

/* Nearest hit in (0, r->tmax). Returns 1 and fills h (h->prim included) on a hit. */
int mc_bvh_intersect(const struct bvh *b, const struct prim *prims, const struct ray *r,
                     struct hit *h);
/* Whether anything is hit in (0, r->tmax); stops at the first hit found. */
int mc_bvh_occluded(const struct bvh *b, const struct prim *prims, const struct ray *r);

/* The same queries over moving primitives (every prims[i].motion >= 1, indexing motions[motion - 1])
 * at time r->time, with b built from bounds that cover r->time. Each primitive is tested in its
 * time-0 frame against the ray carried there, so h->t is the world distance and h->u, h->v are
 * the primitive's own parameters; h->prim indexes prims as passed. */
int mc_bvh_intersect_moving(const struct bvh *b, const struct prim *prims,
                            const struct motion *motions, const struct ray *r, struct hit *h);
int mc_bvh_occluded_moving(const struct bvh *b, const struct prim *prims,
                           const struct motion *motions, const struct ray *r);

#endif
