/* bvh_node.h: the flattened BVH node, private to src/geom/bvh.c (and read by the BVH test and the
 * benchmark's statistics). 32 bytes, so two nodes share a 64-byte cache line. */
#ifndef MCRT_BVH_NODE_H
#define MCRT_BVH_NODE_H

#include <stdint.h>

/* The root is node 0 (node 1 is unused padding). The two children of an inner node are stored
 * together, at index and index + 1 with index even, so that in the 64-byte aligned array the pair
 * a traversal tests together is one cache line; a wider BVH would keep its children together the
 * same way. The corners are one array so that a traversal can pick the near and far slab planes by
 * index, from the signs of the ray direction, without branching. */
struct bvh_node {
    float b[6];      /* lower corner x, y, z, then upper corner x, y, z */
    uint32_t index;  /* inner: index of the first child; leaf: index of the first primitive */
    uint16_t count;  /* leaf: number of primitives (>= 1); inner: 0 */
    uint16_t axis;   /* inner: the split axis (0, 1, 2) */
};

#endif
