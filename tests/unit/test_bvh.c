/* test_bvh.c: the BVH against brute force (nearest hit and occlusion), its structural invariants,
 * and degenerate inputs (empty scene, coinciding centroids, coplanar triangles, NaN rays). */
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "geom/bvh.h"
#include "geom/bvh_node.h"
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

/* Walk the tree and check: child boxes inside their parent's, every primitive's bounds inside
 * its leaf's box, the leaves cover [0, n) exactly once in depth-first order, and the depth bound
 * the traversal stack relies on. Returns the number of violations; *depth gets the maximum. */
static int check_tree(const struct bvh *b, const struct prim *prims, size_t n, int *depth)
{
    struct { uint32_t node; int depth; } stack[128];
    int sp = 0, bad = 0;
    uint32_t next_prim = 0;
    *depth = 0;
    if (n == 0)
        return b->node_count != 0;
    stack[sp].node = 0;
    stack[sp].depth = 0;
    sp++;
    while (sp > 0) {
        const struct bvh_node *nd;
        int dep;
        uint32_t k, c[2];
        sp--;
        nd = &b->nodes[stack[sp].node];
        dep = stack[sp].depth;
        if (dep > *depth)
            *depth = dep;
        if (nd->count > 0) {
            bad += nd->index != next_prim;
            for (k = nd->index; k < nd->index + nd->count && k < n; k++) {
                struct aabb pb = mc_prim_bounds(&prims[k]);
                bad += pb.lo.x < nd->b[0] || pb.lo.y < nd->b[1] || pb.lo.z < nd->b[2] ||
                       pb.hi.x > nd->b[3] || pb.hi.y > nd->b[4] || pb.hi.z > nd->b[5];
            }
            next_prim += nd->count;
            continue;
        }
        c[0] = nd->index;
        c[1] = nd->index + 1;
        if (c[1] >= b->node_count || sp + 2 > 128)
            return bad + 1;
        /* Push right then left so leaves are met in depth-first (left to right) order. */
        for (k = 2; k-- > 0;) {
            const struct bvh_node *ch = &b->nodes[c[k]];
            int a;
            for (a = 0; a < 3; a++)
                bad += ch->b[a] < nd->b[a] || ch->b[a + 3] > nd->b[a + 3];
            stack[sp].node = c[k];
            stack[sp].depth = dep + 1;
            sp++;
        }
    }
    return bad + (next_prim != n);
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
    T_NOTE("mixed scene: %zu prims, %zu nodes, depth %d", n, b.node_count, depth);
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

int main(void)
{
    test_empty();
    test_against_brute_force();
    test_coincident_centroids();
    test_coplanar();
    test_bad_rays();
    return t_done();
}
