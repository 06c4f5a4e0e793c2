/* tri4.h: the BVH's leaves as blocks of four primitives, with the triangles' vertices stored lane by
 * lane for the 4-wide watertight triangle test of the traversal (src/geom/bvh.c). Private to
 * src/geom. */
#ifndef MCRT_TRI4_H
#define MCRT_TRI4_H

#include "geom/bvh.h"

/* Every leaf starts a block of its own (Embree's Triangle4 leaves do the same): a leaf of count
 * primitives is the mc_tri4_blocks(count) consecutive blocks from the index its node slot holds,
 * its primitives in lanes 0, 1, ... in order, so a leaf of up to 4 primitives is one aligned block
 * test, never two half-used ones, and a leaf of 5 to 8 two consecutive blocks, which the AVX2
 * traversal tests as one 8-wide vector (bvh.c). The lanes past count (padding) belong to no primitive; the
 * traversal masks them out by count, and their coordinates are NaN, so that a test that did not
 * would leave them undecided rather than report a hit.
 *
 * v[vertex][axis][lane] is the vertex coordinate, so that one 4-wide load gives an axis of a vertex
 * of four triangles, and the traversal picks the axes of the ray's permutation (Woop et al. 2013,
 * §3) by index. A quad's lane holds its mc_prim_corners (corner, corner + edge1, corner + edge2)
 * and is flagged by MC_TRI4_QUAD in prim[lane]: the same edge functions, accepted over the
 * parallelogram, as mc_quad_intersect does. A lane whose coordinates are all NaN is one the 4-wide
 * test must not decide: a sphere or a disk, or a triangle or quad the scalar test rejects as
 * degenerate (mc_prim_degenerate); the traversal tests it with mc_prim_intersect_prep. The NaN marks them at no extra
 * cost: the 4-wide test's determinant comes out NaN there. prim[lane] is the lane's index in the
 * BVH's primitive array (what a hit reports), below 2^31 (mc_bvh_build), with MC_TRI4_QUAD or'd
 * in for a quad. 160 bytes: the vertices' 144 and the indices' 16 keep every block's vectors
 * 16-byte aligned. */
struct tri4 {
    float v[3][3][4];
    uint32_t prim[4]; /* padding lanes: UINT32_MAX */
};

/* prim[lane]'s flag of a quad, and the primitive's index without it. */
#define MC_TRI4_QUAD 0x80000000u
static inline uint32_t mc_tri4_prim(uint32_t lane_prim) { return lane_prim & ~MC_TRI4_QUAD; }

/* Whether primitives of this kind go in the SIMD lanes: triangles and quads (but for degenerate
 * ones, tri4.c). The others, spheres and disks, take the scalar test in a NaN lane. */
static inline int mc_tri4_simd_kind(enum prim_kind kind)
{
    return kind == PRIM_TRIANGLE || kind == PRIM_QUAD;
}

/* Blocks that a leaf of count primitives takes. */
static inline uint32_t mc_tri4_blocks(uint32_t count) { return (count + 3) / 4; }

/* Fill the mc_tri4_blocks(count) blocks from k with the leaf of the count primitives
 * prims[ids[0]], ..., prims[ids[count - 1]], in that order. */
void mc_tri4_fill(struct tri4 *k, const struct prim *prims, const uint32_t *ids, uint32_t count);

#endif
