/* test_bvh.c: the BVH against brute force (nearest hit and occlusion), its structural invariants,
 * and degenerate inputs (empty scene, one leaf, coinciding centroids, coplanar triangles, rays
 * exactly through edges and vertices, degenerate triangles, NaN rays). Built twice: with the
 * library's node and triangle tests (SIMD where available) as test_bvh, and with the portable C99
 * ones as test_bvh_portable. */
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "geom/bvh.h"
#include "geom/bvh_node.h"
#include "geom/tri4.h"
#include "prim_util.h"
#include "t.h"

static struct prim triangle(vec3 a, vec3 b, vec3 c) { return test_prim(PRIM_TRIANGLE, a, b, c); }

static vec3 rand_in_box(pcg32 *g, float lo, float hi)
{
    float x = pcg32_float(g), y = pcg32_float(g), z = pcg32_float(g);
    return v3(lo + (hi - lo) * x, lo + (hi - lo) * y, lo + (hi - lo) * z);
}

static vec3 rand_dir(pcg32 *g)
{
    float z = 1.0f - 2.0f * pcg32_float(g), phi = 2.0f * MC_PI * pcg32_float(g);
    float s = sqrtf(fmaxf(0.0f, 1.0f - z * z));
    return v3(s * cosf(phi), s * sinf(phi), z);
}

/* The ray in double, with 1/d, for the brute-force box filter. */
struct dray { double o[3], inv[3], tmax; int zero[3]; };

static struct dray dray_of(const struct ray *r)
{
    struct dray q;
    const float o[3] = {r->o.x, r->o.y, r->o.z}, d[3] = {r->d.x, r->d.y, r->d.z};
    int a;
    for (a = 0; a < 3; a++) {
        q.o[a] = o[a];
        q.zero[a] = d[a] == 0;
        q.inv[a] = q.zero[a] ? 0 : 1.0 / d[a];
    }
    q.tmax = r->tmax;
    return q;
}

/* Whether the ray's segment [0, tmax] meets box b widened by 1e-3 (double precision). */
static int box_may_hit(const struct aabb *b, const struct dray *q)
{
    const double margin = 1e-3;
    double t0 = 0, t1 = q->tmax;
    const float lo[3] = {b->lo.x, b->lo.y, b->lo.z}, hi[3] = {b->hi.x, b->hi.y, b->hi.z};
    int a;
    for (a = 0; a < 3; a++) {
        double l = lo[a] - margin, u = hi[a] + margin, ta, tb;
        if (q->zero[a]) {
            if (q->o[a] < l || q->o[a] > u)
                return 0;
            continue;
        }
        ta = ((q->inv[a] < 0 ? u : l) - q->o[a]) * q->inv[a];
        tb = ((q->inv[a] < 0 ? l : u) - q->o[a]) * q->inv[a];
        t0 = ta > t0 ? ta : t0;
        t1 = tb < t1 ? tb : t1;
    }
    return t0 <= t1;
}

/* Brute force over every primitive, in array order. When boxes is not NULL, it holds the bounds
 * of each run of BLOCK consecutive primitives (after the build they are in leaf order, so runs
 * are compact), and runs whose bounds widened by 1e-3 the ray misses are skipped. 1e-3 is a
 * thousand times the float rounding of where any primitive test can report a hit in these
 * unit-sized scenes, so this is only a speed-up, with its own double-precision slab test,
 * independent of the BVH. */
enum { BLOCK = 16 };
static int brute_intersect(const struct prim *prims, const struct aabb *boxes, size_t n,
                           const struct ray *r, struct hit *h)
{
    struct ray_prep q;
    struct dray dq = dray_of(r);
    size_t i;
    int found = 0;
    mc_ray_prep(&q, r);
    h->t = r->tmax;
    for (i = 0; i < n; i++) {
        if (boxes && i % BLOCK == 0 && !box_may_hit(&boxes[i / BLOCK], &dq)) {
            i += BLOCK - 1;
            continue;
        }
        if (mc_prim_intersect_prep(&prims[i], &q, h)) {
            h->prim = (uint32_t)i;
            found = 1;
        }
    }
    return found;
}

/* Whether box (lo, hi) lies within slot i of node n (the parent's box for that child). */
static int box_outside(const float *lo, const float *hi, const struct bvh_node *n, int i)
{
    int a;
    for (a = 0; a < 3; a++)
        if (lo[a] < n->b[a][i] || hi[a] > n->b[a + 3][i])
            return 1;
    return 0;
}

/* The leaf layout (tri4.h) of a leaf of count primitives from block first: its blocks exist and no
 * other leaf has them (blocks_used counts), its first count lanes name primitives, each marked
 * in covered (every primitive in exactly one leaf: check_tree), with bounds inside slot i of
 * node nd; the padding lanes name none and have NaN vertices. Returns the number of violations. */
static int check_leaf(const struct bvh *b, const struct prim *prims, size_t n, uint32_t first,
                      uint32_t count, const struct bvh_node *nd, int i, unsigned char *covered,
                      unsigned char *blocks_used)
{
    uint32_t nb = mc_tri4_blocks(count), j;
    int bad = 0;
    if ((size_t)first + nb > b->tri4_count)
        return 1;
    for (j = 0; j < 4 * nb; j++) {
        const struct tri4 *k = &b->tri4[first + j / 4];
        uint32_t p = k->prim[j % 4];
        if (j % 4 == 0)
            bad += blocks_used[first + j / 4]++ != 0;
        if (j >= count) {
            bad += p != UINT32_MAX || k->v[0][0][j % 4] == k->v[0][0][j % 4];
            continue;
        }
        /* A quad's lane, and only a quad's, carries the flag. */
        if ((size_t)mc_tri4_prim(p) < n)
            bad += !(p & MC_TRI4_QUAD) != (prims[mc_tri4_prim(p)].kind != PRIM_QUAD);
        p = mc_tri4_prim(p);
        if (p >= n) {
            bad++;
            continue;
        }
        {
            struct aabb pb = mc_prim_bounds(&prims[p]);
            const float lo[3] = {pb.lo.x, pb.lo.y, pb.lo.z}, hi[3] = {pb.hi.x, pb.hi.y, pb.hi.z};
            bad += covered[p]++ != 0;
            bad += box_outside(lo, hi, nd, i);
        }
    }
    return bad;
}

/* Walk the wide tree and check: every child box inside its parent's slot box, every primitive's
 * bounds inside its leaf's box, the leaves cover [0, n) exactly once and the blocks exactly once
 * (check_leaf), unused slots (empty boxes) only after the used ones, child nodes after their
 * parent (pre-order) and each reached once, and the depth bound the traversal stack relies on.
 * Returns the number of violations; *depth gets the maximum. */
static int check_tree(const struct bvh *b, const struct prim *prims, size_t n, int *depth)
{
    struct { uint32_t node; int depth; } stack[256];
    unsigned char *covered, *reached, *blocks_used;
    int sp = 0, bad = 0;
    size_t k;
    *depth = 0;
    if (n == 0)
        return b->node_count != 0;
    if (b->node_count == 0)
        return 1;
    covered = calloc(n, 1);
    reached = calloc(b->node_count, 1);
    blocks_used = calloc(b->tri4_count + 1, 1);
    stack[sp].node = 0;
    stack[sp].depth = 0;
    sp++;
    while (sp > 0) {
        const struct bvh_node *nd;
        int dep, i, used = 0, empty_seen = 0;
        uint32_t self;
        sp--;
        self = stack[sp].node;
        nd = &b->nodes[self];
        dep = stack[sp].depth;
        bad += reached[self]++ != 0;
        if (dep > *depth)
            *depth = dep;
        for (i = 0; i < BVH_WIDTH; i++) {
            int empty = nd->b[0][i] == INFINITY;
            if (empty) {
                bad += nd->b[3][i] != -INFINITY || nd->count[i] != 0;
                empty_seen = 1;
                continue;
            }
            bad += empty_seen; /* a used slot after an unused one */
            used++;
            if (nd->count[i] > 0) {
                bad += check_leaf(b, prims, n, nd->child[i], nd->count[i], nd, i, covered,
                                  blocks_used);
                continue;
            }
            if (nd->child[i] <= self || nd->child[i] >= b->node_count || sp + 1 > 256) {
                bad++;
                continue;
            }
            {
                const struct bvh_node *ch = &b->nodes[nd->child[i]];
                int j, a;
                for (j = 0; j < BVH_WIDTH; j++) {
                    float lo[3], hi[3];
                    if (ch->b[0][j] == INFINITY)
                        continue;
                    for (a = 0; a < 3; a++) {
                        lo[a] = ch->b[a][j];
                        hi[a] = ch->b[a + 3][j];
                    }
                    bad += box_outside(lo, hi, nd, i);
                }
            }
            stack[sp].node = nd->child[i];
            stack[sp].depth = dep + 1;
            sp++;
        }
        bad += used == 0;
    }
    for (k = 0; k < n; k++)
        bad += covered[k] != 1;
    for (k = 0; k < b->node_count; k++)
        bad += reached[k] != 1;
    for (k = 0; k < b->tri4_count; k++)
        bad += blocks_used[k] != 1;
    free(covered);
    free(reached);
    free(blocks_used);
    return bad;
}

/* A heightfield over [-1,1]² (a wavy, mostly-connected mesh), triangles floating above it, and a
 * few spheres and quads: 10^4 triangles in all, plus 100 other primitives. */
static size_t make_scene(struct prim *prims, pcg32 *g)
{
    enum { G = 70 };
    size_t n = 0;
    int i, j;
    for (j = 0; j < G; j++)
        for (i = 0; i < G; i++) {
            vec3 c[4];
            int k;
            for (k = 0; k < 4; k++) {
                float x = -1.0f + 2.0f * (float)(i + (k & 1)) / G;
                float y = -1.0f + 2.0f * (float)(j + (k >> 1)) / G;
                c[k] = v3(x, y, 0.3f * sinf(5.0f * x) * cosf(4.0f * y));
            }
            prims[n++] = triangle(c[0], c[1], c[3]);
            prims[n++] = triangle(c[0], c[3], c[2]);
        }
    while (n < 10000) {
        vec3 a = rand_in_box(g, -1.0f, 1.0f);
        prims[n++] = triangle(a, v3_add(a, v3_scale(rand_dir(g), 0.1f)),
                              v3_add(a, v3_scale(rand_dir(g), 0.1f)));
    }
    for (i = 0; i < 50; i++) {
        struct prim s = triangle(rand_in_box(g, -1.0f, 1.0f), v3s(0.0f), v3s(0.0f));
        struct prim q = triangle(rand_in_box(g, -1.0f, 1.0f), v3_scale(rand_dir(g), 0.3f),
                                 v3_scale(rand_dir(g), 0.2f));
        s.kind = PRIM_SPHERE;
        s.p[1].x = 0.02f + 0.1f * pcg32_float(g);
        q.kind = PRIM_QUAD;
        prims[n++] = s;
        prims[n++] = q;
    }
    return n;
}

/* The index of primitive j of the leaf whose blocks start at block first. */
static uint32_t leaf_prim(const struct bvh *b, uint32_t first, uint32_t j)
{
    return mc_tri4_prim(b->tri4[first + j / 4].prim[j % 4]);
}

/* Leaves of more than four primitives, which the AVX2 traversal tests eight lanes at a time
 * (two blocks), and how many of them hold a quad, or a sphere (a lane the SIMD test leaves to the
 * scalar one). */
struct wide_leaves {
    size_t leaves, with_quad, with_sphere;
};

static struct wide_leaves count_wide_leaves(const struct bvh *b, const struct prim *prims)
{
    struct wide_leaves w = {0, 0, 0};
    size_t k;
    int i;
    for (k = 0; k < b->node_count; k++)
        for (i = 0; i < BVH_WIDTH; i++) {
            const struct bvh_node *nd = &b->nodes[k];
            uint32_t j, quad = 0, sphere = 0;
            if (nd->count[i] <= 4)
                continue;
            for (j = 0; j < nd->count[i]; j++) {
                uint32_t p = leaf_prim(b, nd->child[i], j);
                quad |= prims[p].kind == PRIM_QUAD;
                sphere |= prims[p].kind == PRIM_SPHERE;
            }
            w.leaves++;
            w.with_quad += quad;
            w.with_sphere += sphere;
        }
    return w;
}

/* The BVH must give the brute-force answer bit for bit: the same t, and the same primitive unless
 * two primitives are hit at exactly the same t (then the order of testing decides). */
static void test_against_brute_force(void)
{
    enum { RAYS = 100000 };
    struct prim *prims = malloc(10200 * sizeof *prims);
    struct aabb *boxes = malloc(10200 * sizeof *boxes);
    struct bvh b;
    mc_diag d;
    pcg32 g;
    size_t n, k;
    int i, depth, hit_bad = 0, occ_bad = 0, filter_bad = 0, hits = 0, ties = 0;
    pcg32_seed(&g, 7, 1);
    n = make_scene(prims, &g);
    T_CHECK(mc_bvh_build(&b, prims, n, &d) == MCRT_OK, "build: %s", d.msg);
    for (k = 0; k < n; k++)
        boxes[k / BLOCK] = k % BLOCK ? aabb_union(boxes[k / BLOCK], mc_prim_bounds(&prims[k]))
                                     : mc_prim_bounds(&prims[k]);
    T_CHECK(check_tree(&b, prims, n, &depth) == 0, "tree invariants");
    T_CHECK(depth < 64, "depth %d", depth);
    T_NOTE("mixed scene: %zu prims, %zu nodes, depth %d, %zu blocks", n, b.node_count, depth,
           b.tri4_count);
    /* Leaves that do not fill their last block, so that the rays below cover the masked lanes. */
    T_CHECK(4 * b.tri4_count > n, "%zu blocks for %zu prims: no padded lane", b.tri4_count, n);
    {
        struct wide_leaves w = count_wide_leaves(&b, prims);
        T_CHECK(w.leaves > 100 && w.with_quad > 0 && w.with_sphere > 0,
                "leaves of 5-8 prims: %zu, %zu with a quad, %zu with a sphere: the 8-wide test "
                "would go untested", w.leaves, w.with_quad, w.with_sphere);
        T_NOTE("%zu leaves of 5-8 prims, %zu with a quad, %zu with a sphere", w.leaves,
               w.with_quad, w.with_sphere);
    }
    for (i = 0; i < RAYS; i++) {
        struct ray r;
        struct hit hb, hf;
        int fb, ff;
        r.o = rand_in_box(&g, -1.2f, 1.2f);
        r.d = rand_dir(&g);
        /* One ray in four is a segment, as for shadow rays. */
        r.tmax = (i & 3) == 0 ? 2.0f * pcg32_float(&g) : INFINITY;
        fb = mc_bvh_intersect(&b, prims, &r, &hb);
        ff = brute_intersect(prims, boxes, n, &r, &hf);
        if (i < RAYS / 20) { /* the box filter must not change the brute-force answer */
            struct hit hu;
            int fu = brute_intersect(prims, NULL, n, &r, &hu);
            filter_bad += fu != ff || (ff && (hu.t != hf.t || hu.prim != hf.prim));
        }
        hits += ff;
        if (fb != ff || (ff && (memcmp(&hb.t, &hf.t, sizeof hb.t) != 0 ||
                                hb.u != hf.u || hb.v != hf.v)))
            hit_bad++;
        else if (ff && hb.prim != hf.prim)
            ties++;
        occ_bad += mc_bvh_occluded(&b, prims, &r) != ff;
    }
    T_CHECK(filter_bad == 0, "box filter changed %d brute-force answers", filter_bad);
    T_CHECK(hit_bad == 0, "%d of %d rays differ from brute force", hit_bad, RAYS);
    T_CHECK(occ_bad == 0, "%d of %d occlusion answers differ", occ_bad, RAYS);
    T_CHECK(hits > RAYS / 4, "only %d hits: the test would be weak", hits);
    T_NOTE("%d rays, %d hits, %d exact-t ties resolved to another prim", RAYS, hits, ties);
    mc_bvh_free(&b);
    free(boxes);
    free(prims);
}

static void test_empty(void)
{
    struct bvh b;
    struct ray r;
    struct hit h;
    mc_diag d;
    T_CHECK(mc_bvh_build(&b, NULL, 0, &d) == MCRT_OK, "empty build");
    r.o = v3s(0.0f);
    r.d = v3(0.0f, 0.0f, 1.0f);
    r.tmax = INFINITY;
    T_CHECK(mc_bvh_intersect(&b, NULL, &r, &h) == 0, "empty intersect");
    T_CHECK(mc_bvh_occluded(&b, NULL, &r) == 0, "empty occluded");
    mc_bvh_free(&b);
    mc_bvh_free(&b); /* freeing twice is harmless */
}

/* 3000 triangles rotated about one common centroid: binning cannot separate them, so the build
 * must fall back to median splits and still produce a correct, bounded tree. */
static void test_coincident_centroids(void)
{
    enum { N = 3000 };
    struct prim *prims = malloc(N * sizeof *prims);
    struct bvh b;
    mc_diag d;
    pcg32 g;
    int i, depth, bad = 0;
    pcg32_seed(&g, 11, 2);
    for (i = 0; i < N; i++) {
        /* a + b + c = 0 for every triangle, so each centroid is exactly the origin. */
        vec3 a = rand_dir(&g), b0 = rand_dir(&g);
        prims[i] = triangle(a, b0, v3_neg(v3_add(a, b0)));
    }
    T_CHECK(mc_bvh_build(&b, prims, N, &d) == MCRT_OK, "build: %s", d.msg);
    T_CHECK(check_tree(&b, prims, N, &depth) == 0, "tree invariants");
    T_CHECK(depth < 64, "depth %d", depth);
    for (i = 0; i < 300; i++) {
        struct ray r;
        struct hit hb, hf;
        int fb, ff;
        r.o = v3_scale(rand_dir(&g), 3.0f);
        r.d = v3_normalize(v3_sub(v3_scale(rand_dir(&g), 0.5f), r.o));
        r.tmax = INFINITY;
        fb = mc_bvh_intersect(&b, prims, &r, &hb);
        ff = brute_intersect(prims, NULL, N, &r, &hf);
        bad += fb != ff || (ff && hb.t != hf.t);
    }
    T_CHECK(bad == 0, "%d of 300 rays differ from brute force", bad);
    T_NOTE("coincident centroids: %zu nodes, depth %d", b.node_count, depth);
    mc_bvh_free(&b);
    free(prims);
}

/* 10^5 triangles in the plane z = 0 (a 224×224 grid of quads, cut in two): every downward ray
 * over the grid has the analytic answer t = o.z / -d.z at a known cell. */
static void test_coplanar(void)
{
    enum { G = 224, N = 2 * G * G, RAYS = 20000 };
    struct prim *prims = malloc(N * sizeof *prims);
    struct bvh b;
    mc_diag d;
    pcg32 g;
    int i, j, depth, miss = 0, far = 0, n = 0;
    for (j = 0; j < G; j++)
        for (i = 0; i < G; i++) {
            vec3 a = v3((float)i, (float)j, 0.0f), bb = v3((float)i + 1, (float)j, 0.0f);
            vec3 c = v3((float)i + 1, (float)j + 1, 0.0f), e = v3((float)i, (float)j + 1, 0.0f);
            prims[n++] = triangle(a, bb, c);
            prims[n++] = triangle(a, c, e);
        }
    T_CHECK(mc_bvh_build(&b, prims, N, &d) == MCRT_OK, "build: %s", d.msg);
    T_CHECK(check_tree(&b, prims, N, &depth) == 0, "tree invariants");
    T_CHECK(depth < 64, "depth %d", depth);
    pcg32_seed(&g, 13, 3);
    for (i = 0; i < RAYS; i++) {
        struct ray r;
        struct hit h;
        vec3 target = v3(1.0f + (G - 2) * pcg32_float(&g), 1.0f + (G - 2) * pcg32_float(&g), 0.0f);
        r.o = v3(target.x + 2.0f * pcg32_float(&g) - 1.0f, target.y + 2.0f * pcg32_float(&g) - 1.0f,
                 1.0f + 5.0f * pcg32_float(&g));
        r.d = v3_normalize(v3_sub(target, r.o));
        r.tmax = INFINITY;
        if (!mc_bvh_intersect(&b, prims, &r, &h)) {
            miss++;
            continue;
        }
        /* The hit point must lie in the reported triangle's cell and t must be o.z / -d.z to
         * within a few ulps (float t, float direction: relative error below 1e-6). */
        {
            float t_ref = r.o.z / -r.d.z;
            vec3 p = v3_madd(r.o, r.d, h.t);
            const struct prim *pr = &prims[h.prim];
            float cx = fminf(pr->p[0].x, fminf(pr->p[1].x, pr->p[2].x));
            float cy = fminf(pr->p[0].y, fminf(pr->p[1].y, pr->p[2].y));
            far += fabsf(h.t - t_ref) > 1e-6f * t_ref || p.x < cx - 1e-3f ||
                   p.x > cx + 1.001f || p.y < cy - 1e-3f || p.y > cy + 1.001f;
        }
    }
    T_CHECK(miss == 0, "%d of %d rays missed the plane", miss, RAYS);
    T_CHECK(far == 0, "%d of %d hits at the wrong place", far, RAYS);
    T_NOTE("coplanar: %d triangles, %zu nodes, depth %d", N, b.node_count, depth);
    mc_bvh_free(&b);
    free(prims);
}

/* The 4-wide triangle test of the traversal must answer exactly as the scalar one, also where it
 * hands a lane back to it: rays exactly through mesh vertices and edges (edge functions exactly
 * 0, recomputed in double by the scalar test), degenerate triangles (collinear or coincident
 * vertices, which the scalar test rejects after the fact), and spheres and quads sharing the
 * leaves' blocks. The mesh has integer vertices and the rays are parallel to z from integer and
 * half-integer points, so the watertight test's sheared coordinates are exact and the zeros are
 * real. Every such ray over the mesh must hit (no ray slips between triangles), with the
 * brute-force t, u, v bit for bit. */
static void test_exact_edges(void)
{
    enum { G = 24 };
    struct prim *prims = malloc((2 * G * G + 3 * G + 8) * sizeof *prims);
    struct bvh b;
    mc_diag d;
    size_t n = 0;
    int i, j, s, rays = 0, miss = 0, bad = 0, occ_bad = 0, ties = 0;
    for (j = 0; j < G; j++)
        for (i = 0; i < G; i++) {
            /* Heights in quarters, so that the mesh is not flat but stays exact. */
            vec3 c[4];
            int k;
            for (k = 0; k < 4; k++) {
                int x = i + (k & 1), y = j + (k >> 1);
                c[k] = v3((float)x, (float)y, 0.25f * (float)((x + 2 * y) % 3));
            }
            prims[n++] = triangle(c[0], c[1], c[3]);
            prims[n++] = triangle(c[0], c[3], c[2]);
            if (i == j) { /* degenerate: along an edge, and a point */
                prims[n++] = triangle(c[0], c[1], v3_scale(v3_add(c[0], c[1]), 0.5f));
                prims[n++] = triangle(c[3], c[3], c[3]);
            }
        }
    for (i = 0; i < 4; i++) {
        struct prim sp = triangle(v3(3.0f + 5.0f * (float)i, 7.0f, 2.0f), v3(0.75f, 0, 0), v3s(0));
        sp.kind = PRIM_SPHERE;
        prims[n++] = sp;
        prims[n++] = test_prim(PRIM_QUAD, v3(2.0f, 3.0f + 5.0f * (float)i, 1.0f), v3(2, 0, 0),
                               v3(0, 2, 0));
    }
    T_CHECK(mc_bvh_build(&b, prims, n, &d) == MCRT_OK, "build: %s", d.msg);
    /* From above and from below, through every vertex, edge midpoint and cell centre. */
    for (s = 0; s < 2; s++)
        for (j = 0; j <= 2 * G; j++)
            for (i = 0; i <= 2 * G; i++) {
                struct ray r = test_ray(v3(0.5f * (float)i, 0.5f * (float)j, s ? -3.0f : 3.0f),
                                        v3(0.0f, 0.0f, s ? 1.0f : -1.0f));
                struct hit hb, hf;
                int fb = mc_bvh_intersect(&b, prims, &r, &hb);
                int ff = brute_intersect(prims, NULL, n, &r, &hf);
                rays++;
                miss += !fb;
                /* At a vertex or an edge several triangles meet at the same t: the order of
                 * testing picks one, and u, v are then that one's. */
                if (fb != ff || (ff && memcmp(&hb.t, &hf.t, sizeof hb.t) != 0))
                    bad++;
                else if (ff && hb.prim != hf.prim)
                    ties++;
                else if (ff && (hb.u != hf.u || hb.v != hf.v))
                    bad++;
                occ_bad += mc_bvh_occluded(&b, prims, &r) != ff;
            }
    T_CHECK(miss == 0, "%d of %d rays through vertices and edges slipped through", miss, rays);
    T_CHECK(bad == 0, "%d of %d rays differ from brute force", bad, rays);
    T_CHECK(occ_bad == 0, "%d of %d occlusion answers differ", occ_bad, rays);
    T_NOTE("exact edges: %zu prims, %d rays, %d exact-t ties resolved to another prim", n, rays,
           ties);
    mc_bvh_free(&b);
    free(prims);
}

/* Non-finite and zero directions: no crash, no endless loop, no hit. */
static void test_bad_rays(void)
{
    struct prim prims[64];
    struct bvh b;
    mc_diag d;
    pcg32 g;
    int i, k, hits = 0;
    const float bad[] = {NAN, INFINITY, -INFINITY, 0.0f};
    pcg32_seed(&g, 17, 4);
    for (i = 0; i < 64; i++) {
        vec3 a = rand_in_box(&g, -1.0f, 1.0f);
        prims[i] = triangle(a, v3_add(a, v3(0.2f, 0.0f, 0.0f)), v3_add(a, v3(0.0f, 0.2f, 0.1f)));
    }
    T_CHECK(mc_bvh_build(&b, prims, 64, &d) == MCRT_OK, "build: %s", d.msg);
    for (k = 0; k < 4; k++)
        for (i = 0; i < 3; i++) {
            struct ray r;
            struct hit h;
            r.o = v3s(0.0f);
            r.d = v3s(bad[k]);
            if (k < 3) { /* one bad component in an otherwise valid direction */
                r.d = v3(0.3f, 0.4f, 0.5f);
                if (i == 0) r.d.x = bad[k];
                if (i == 1) r.d.y = bad[k];
                if (i == 2) r.d.z = bad[k];
            }
            r.tmax = INFINITY;
            hits += mc_bvh_intersect(&b, prims, &r, &h);
            hits += mc_bvh_occluded(&b, prims, &r);
            r.o.x = NAN;
            hits += mc_bvh_intersect(&b, prims, &r, &h);
            hits += mc_bvh_occluded(&b, prims, &r);
        }
    T_CHECK(hits == 0, "%d hits from non-finite rays", hits);
    mc_bvh_free(&b);
}

/* The SAH prices a sphere by its scalar test (bvh_build.c, SCALAR_COST): glossy-floor's five
 * primitives, a 20 x 20 floor, a small light and three unit spheres, are not one leaf of five,
 * whose spheres every ray would test, but a leaf of the floor and the light beside the spheres'. */
static void test_scalar_prims_apart(void)
{
    struct prim prims[5];
    struct bvh b;
    mc_diag d;
    size_t k;
    int i, depth, floor_leaves = 0, floor_with_sphere = 0;
    prims[0] = test_prim(PRIM_QUAD, v3(-10.0f, 0.0f, 10.0f), v3(20.0f, 0.0f, 0.0f),
                         v3(0.0f, 0.0f, -20.0f));
    prims[1] = test_prim(PRIM_QUAD, v3(-0.75f, 4.0f, 1.5f), v3(1.5f, 0.0f, 0.0f),
                         v3(0.0f, 0.0f, 0.5f));
    for (i = 0; i < 3; i++) {
        prims[2 + i] = test_prim(PRIM_SPHERE, v3(-2.4f + 2.4f * (float)i, 1.0f, i == 1 ? -0.5f : 0.0f),
                                 v3s(0.0f), v3s(0.0f));
        prims[2 + i].p[1].x = 1.0f;
    }
    T_CHECK(mc_bvh_build(&b, prims, 5, &d) == MCRT_OK, "build: %s", d.msg);
    T_CHECK(check_tree(&b, prims, 5, &depth) == 0, "tree invariants");
    for (k = 0; k < b.node_count; k++)
        for (i = 0; i < BVH_WIDTH; i++) {
            const struct bvh_node *nd = &b.nodes[k];
            uint32_t j, has_floor = 0, has_sphere = 0;
            for (j = 0; j < nd->count[i]; j++) {
                uint32_t p = leaf_prim(&b, nd->child[i], j);
                has_floor |= p == 0;
                has_sphere |= prims[p].kind == PRIM_SPHERE;
            }
            floor_leaves += (int)has_floor;
            floor_with_sphere += (int)(has_floor && has_sphere);
        }
    T_CHECK(floor_leaves == 1 && floor_with_sphere == 0,
            "the floor's leaf holds a sphere too (%d of %d leaves): every ray meeting the floor "
            "tests it", floor_with_sphere, floor_leaves);
    mc_bvh_free(&b);
}

/* One or two primitives make a binary tree that is a single leaf: the wide root holds it alone. */
static void test_single_leaf(void)
{
    struct prim prims[2];
    struct bvh b;
    struct ray r;
    struct hit h;
    mc_diag d;
    int depth, n;
    for (n = 1; n <= 2; n++) {
        prims[0] = triangle(v3(-1.0f, -1.0f, 0.0f), v3(1.0f, -1.0f, 0.0f), v3(0.0f, 1.0f, 0.0f));
        prims[1] = triangle(v3(-1.0f, -1.0f, 1.0f), v3(1.0f, -1.0f, 1.0f), v3(0.0f, 1.0f, 1.0f));
        T_CHECK(mc_bvh_build(&b, prims, (size_t)n, &d) == MCRT_OK, "build: %s", d.msg);
        T_CHECK(b.node_count == 1 && check_tree(&b, prims, (size_t)n, &depth) == 0,
                "%d prims: %zu nodes, tree invariants", n, b.node_count);
        r.o = v3(0.0f, 0.0f, 5.0f);
        r.d = v3(0.0f, 0.0f, -1.0f);
        r.tmax = INFINITY;
        /* Exact: the planes z = 1 and z = 0 are 4 and 5 away along an axis ray. */
        T_CHECK(mc_bvh_intersect(&b, prims, &r, &h) && h.t == (n == 2 ? 4.0f : 5.0f),
                "%d prims: nearest hit", n);
        r.d = v3(0.0f, 0.0f, 1.0f);
        T_CHECK(!mc_bvh_occluded(&b, prims, &r), "%d prims: ray away from them", n);
        mc_bvh_free(&b);
    }
}

/* The parallel build (subtrees on several threads, appended in order) must give the same tree and
 * primitive order as the one-thread build, byte for byte, whatever the number of threads. */
static void test_parallel_build_same(void)
{
    struct prim *p1 = malloc(10200 * sizeof *p1), *p2 = malloc(10200 * sizeof *p2);
    struct bvh b1, b2;
    mc_diag d;
    pcg32 g;
    size_t n;
    int threads;
    pcg32_seed(&g, 7, 1);
    n = make_scene(p1, &g);
    memcpy(p2, p1, n * sizeof *p1);
    T_CHECK(mc_bvh_build_threads(&b1, p1, NULL, n, 1, &d) == MCRT_OK, "build: %s", d.msg);
    for (threads = 2; threads <= 5; threads += 3) {
        struct prim *q = malloc(n * sizeof *q);
        memcpy(q, p2, n * sizeof *q);
        T_CHECK(mc_bvh_build_threads(&b2, q, NULL, n, threads, &d) == MCRT_OK, "build: %s", d.msg);
        T_CHECK(b1.node_count == b2.node_count
                    && memcmp(b1.nodes, b2.nodes, b1.node_count * sizeof *b1.nodes) == 0
                    && b1.tri4_count == b2.tri4_count
                    && memcmp(b1.tri4, b2.tri4, b1.tri4_count * sizeof *b1.tri4) == 0
                    && memcmp(p1, q, n * sizeof *q) == 0,
                "%d threads: %zu nodes, 1 thread: %zu; same nodes, blocks and order", threads,
                b2.node_count, b1.node_count);
        mc_bvh_free(&b2);
        free(q);
    }
    mc_bvh_free(&b1);
    free(p1);
    free(p2);
}

/* A ray that starts in a triangle's plane meets it at t = 0, which is no hit; rounding turns that t
 * into noise of either sign, which the triangle tests must not report (pbrt-v4's conservative
 * t, prim.h mc_tri_t_error). The case is a secondary ray at a concave corner, spawned off the
 * floor into the plane of the wall. The wall's vertices have inexact float coordinates, so the
 * sheared coordinates round. Checked for the traversal (4-wide test) and the scalar test. */
static void test_origin_in_plane(void)
{
    enum { G = 16, N = 2 * G * G, RAYS = 20000 };
    const float x = 0.455f, step = 0.1f;
    struct prim *prims = malloc(N * sizeof *prims);
    struct bvh b;
    mc_diag d;
    pcg32 g;
    int i, j, n = 0, hits = 0, occluded = 0, scalar = 0;
    for (j = 0; j < G; j++)
        for (i = 0; i < G; i++) {
            vec3 a = v3(x, step * (float)j, step * (float)i);
            vec3 bb = v3(x, step * (float)j, step * (float)(i + 1));
            vec3 c = v3(x, step * (float)(j + 1), step * (float)(i + 1));
            vec3 e = v3(x, step * (float)(j + 1), step * (float)i);
            prims[n++] = triangle(a, bb, c);
            prims[n++] = triangle(a, c, e);
        }
    T_CHECK(mc_bvh_build(&b, prims, N, &d) == MCRT_OK, "build: %s", d.msg);
    pcg32_seed(&g, 17, 5);
    for (i = 0; i < RAYS; i++) {
        struct ray r;
        struct hit h;
        r.o = v3(x, step * G * pcg32_float(&g), step * G * pcg32_float(&g));
        r.d = rand_dir(&g);
        r.tmax = INFINITY;
        r.time = 0.0f;
        hits += mc_bvh_intersect(&b, prims, &r, &h);
        occluded += mc_bvh_occluded(&b, prims, &r);
        h.t = INFINITY;
        for (j = 0; j < N; j++)
            scalar += mc_prim_intersect(&prims[j], &r, &h);
    }
    T_CHECK(hits == 0 && occluded == 0 && scalar == 0,
            "rays from the triangles' plane: %d hits, %d occluded, %d scalar hits of %d rays", hits,
            occluded, scalar, RAYS);
    mc_bvh_free(&b);
    free(prims);
}

int main(void)
{
    test_empty();
    test_parallel_build_same();
    test_single_leaf();
    test_scalar_prims_apart();
    test_against_brute_force();
    test_coincident_centroids();
    test_coplanar();
    test_exact_edges();
    test_origin_in_plane();
    test_bad_rays();
    return t_done();
}
