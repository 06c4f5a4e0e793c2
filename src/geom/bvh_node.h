/* bvh_node.h: the 8-wide BVH node, private to src/geom/bvh.c and bvh_build.c (and read by the BVH test and the
 * benchmark's statistics). 256 bytes, four 64-byte cache lines. */
#ifndef MCRT_BVH_NODE_H
#define MCRT_BVH_NODE_H

#include <stdint.h>

/* 8 rather than 4: measured against Embree on the anchor's ray sets, 8-wide nodes (tested as two
 * SSE halves) traced 15 to 30% faster than 4-wide ones, from the shallower tree (depth 7 against
 * 9 to 14); one 8-wide AVX test instead of the two halves gained another 5 to 15% where the
 * processor has AVX2 (src/geom/bvh.c). A multiple of 4, for the SSE node test. */
#define BVH_WIDTH 8

/* No node is deeper than this (the build guarantees it, see SAH_DEPTH in bvh_build.c): a traversal
 * pushes at most BVH_WIDTH - 1 nodes per level, so a stack of (BVH_WIDTH - 1) * BVH_DEPTH_MAX
 * entries cannot overflow. */
#define BVH_DEPTH_MAX 64

/* The root is node 0. A node holds up to BVH_WIDTH children, each either an inner node or a leaf
 * (a run of primitives), with their boxes stored plane by plane (structure of arrays), so that one
 * 4-wide SIMD operation computes a slab distance for four children at once (Wald et al. 2008,
 * "Getting rid of packets"; Dammertz et al. 2008, "Shallow bounding volume hierarchies"). Unused
 * slots, after the used ones, have an empty box (lower corner +inf, upper -inf), which no ray
 * meets, so the traversal needs no count of children. The planes are one array so that a
 * traversal picks the near and far plane of each axis by index, from the signs of the ray
 * direction, without branching. */
struct bvh_node {
    float b[6][BVH_WIDTH];     /* b[plane][child]: lower x, y, z, then upper x, y, z */
    uint32_t child[BVH_WIDTH]; /* inner child: its node index; leaf: its first block (tri4.h) */
    uint8_t count[BVH_WIDTH];  /* leaf: number of primitives (>= 1); inner child or unused: 0 */
    uint8_t pad[24];           /* to 256 bytes, so that nodes stay aligned to cache lines */
};

#endif
