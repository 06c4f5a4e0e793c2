/* tri4.c: the BVH's blocks for the 4-wide watertight test (Woop, Benthin and Wald, JCGT 2(1)
 * 2013) of triangles and quads, filled leaf by leaf; layout and contract in tri4.h. */
#include "geom/tri4.h"

/* Whether the 4-wide test may decide p: a triangle or a quad whose corners are not collinear.
 * The scalar test rejects hits on collinear ones after the fact (mc_prim_degenerate); the 4-wide
 * test has no such check, so those go to scalar lanes. */
static int decidable(const struct prim *p)
{
    return mc_tri4_simd_kind(p->kind) && !mc_prim_degenerate(p);
}

void mc_tri4_fill(struct tri4 *k, const struct prim *prims, const uint32_t *ids, uint32_t count)
{
    uint32_t i, lanes = 4 * mc_tri4_blocks(count);
    for (i = 0; i < lanes; i++) {
        struct tri4 *blk = &k[i / 4];
        int lane = (int)(i % 4), v;
        const struct prim *q = i < count ? &prims[ids[i]] : NULL;
        int simd = q && decidable(q);
        vec3 c[3];
        if (simd)
            mc_prim_corners(q, c);
        for (v = 0; v < 3; v++) {
            vec3 p = simd ? c[v] : v3s(NAN);
            blk->v[v][0][lane] = p.x;
            blk->v[v][1][lane] = p.y;
            blk->v[v][2][lane] = p.z;
        }
        blk->prim[lane] = !q ? UINT32_MAX : q->kind == PRIM_QUAD ? ids[i] | MC_TRI4_QUAD : ids[i];
    }
}
