/* bvh.c: single-ray traversal of the 8-wide BVH (built in bvh_build.c) with SIMD node tests (SSE,
 * or portable C99 under MCRT_BVH_PORTABLE), of static primitives and of moving ones (tested in
 * their time-0 frame). */
#include "geom/bvh.h"

#include "geom/bvh_node.h"
#include "geom/motion.h"

#if defined(__SSE2__) && !defined(MCRT_BVH_PORTABLE)
#include <emmintrin.h>
#define BVH_SSE 1
#endif

/* 1 + 4·2^-23: covers the 1 + 2γ3 relative error of the slab distances (Ize, "Robust BVH Ray
 * Traversal", JCGT 2(2) 2013; pbrt-v4 Bounds3::IntersectP) plus the rounding of this product, so
 * a box is never missed by a ray that passes through it. */
#define SLAB_GROW 1.00000048f

/* The ray as the slab test needs it: origin, 1/d (±inf for a zero component) and, per axis, the
 * plane (row of bvh_node.b) the ray enters through (near) and leaves through (far). */
struct slab_ray {
    float o[3], inv[3];
    int near[3], far[3];
#ifdef BVH_SSE
    __m128 o4[3], inv4[3]; /* o and inv broadcast, made once per ray rather than per node */
#endif
};

/* The slab test of a node's BVH_WIDTH children against the ray's segment [0, tmax]: returns the
 * mask of children met (bit i for child i) and their entry distances in tn. A zero direction
 * component with the origin exactly on a slab plane gives 0·inf = NaN; the minima and maxima are
 * ordered so that a NaN leaves the interval unchanged, which is right for a ray lying in the
 * (closed) slab. Unused children have empty boxes (lower +inf, upper -inf): entry +inf, exit -inf. */
#ifdef BVH_SSE
static inline unsigned node_test(const struct bvh_node *n, const struct slab_ray *s, float tmax,
                                 float *tn)
{
    /* _mm_max_ps(a, b) and _mm_min_ps(a, b) return b when either is NaN: the accumulator goes
     * second, as in the portable version's comparisons. Four children per SSE vector. */
    unsigned mask = 0;
    int a, g;
    for (g = 0; g < BVH_WIDTH; g += 4) {
        __m128 t0 = _mm_setzero_ps(), t1 = _mm_set1_ps(tmax);
        for (a = 0; a < 3; a++) {
            __m128 o = s->o4[a], inv = s->inv4[a];
            __m128 ta = _mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(&n->b[s->near[a]][g]), o), inv);
            __m128 tb = _mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(&n->b[s->far[a]][g]), o), inv);
            t0 = _mm_max_ps(ta, t0);
            t1 = _mm_min_ps(tb, t1);
        }
        _mm_storeu_ps(&tn[g], t0);
        mask |= (unsigned)_mm_movemask_ps(_mm_cmple_ps(t0, _mm_mul_ps(t1, _mm_set1_ps(SLAB_GROW))))
                << g;
    }
    return mask;
}
#else
static inline unsigned node_test(const struct bvh_node *n, const struct slab_ray *s, float tmax,
                                 float *tn)
{
    unsigned mask = 0;
    int i, a;
    for (i = 0; i < BVH_WIDTH; i++) {
        float t0 = 0.0f, t1 = tmax;
        for (a = 0; a < 3; a++) {
            float ta = (n->b[s->near[a]][i] - s->o[a]) * s->inv[a];
            float tb = (n->b[s->far[a]][i] - s->o[a]) * s->inv[a];
            t0 = ta > t0 ? ta : t0;
            t1 = tb < t1 ? tb : t1;
        }
        tn[i] = t0;
        mask |= (unsigned)(t0 <= t1 * SLAB_GROW) << i;
    }
    return mask;
}
#endif

/* Left to itself, GCC -O2 keeps one out-of-line traverse() (it is large) with any_hit a run-time
 * argument; forced inlining makes any_hit and the leaf test constants of each caller's copy. */
#if defined(__GNUC__)
#define ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define ALWAYS_INLINE inline
#endif

/* A leaf's primitive test: mc_prim_intersect_prep's contract, with the per-ray state in ctx. */
typedef int (*leaf_test)(void *ctx, const struct prim *p, struct hit *h);

/* Static primitives: ctx is the prepared ray. */
static ALWAYS_INLINE int test_static(void *ctx, const struct prim *p, struct hit *h)
{
    return mc_prim_intersect_prep(p, ctx, h);
}

/* Moving primitives are tested in their time-0 frame against the ray mapped there by the inverse
 * of their motion at the ray's time. The map is rigid, so t along the mapped ray is the world
 * distance and hits in different frames compare directly. Consecutive primitives of a leaf
 * usually share a motion (the triangles of one mesh), so the mapped ray is kept until the motion
 * changes. */
struct moving_ray {
    const struct motion *motions;
    const struct ray *r;
    unsigned motion;        /* prim.motion of the mapped ray q; 0 before the first */
    struct ray_prep q;
};

static ALWAYS_INLINE int test_moving(void *ctx, const struct prim *p, struct hit *h)
{
    struct moving_ray *m = ctx;
    if (p->motion != m->motion) {
        struct rigid x;
        struct ray local;
        mc_motion_at(&m->motions[p->motion - 1], m->r->time, &x);
        local = rigid_inv_ray(&x, m->r);
        mc_ray_prep(&m->q, &local);
        m->motion = p->motion;
    }
    return mc_prim_intersect_prep(p, &m->q, h);
}

/* Index of the lowest set bit of a nonzero mask. */
static inline int lowest_bit(unsigned mask)
{
#if defined(__GNUC__)
    return __builtin_ctz(mask);
#else
    int i = 0;
    while (!(mask >> i & 1))
        i++;
    return i;
#endif
}

/* A subtree still to visit: a node (count 0) or a leaf (count primitives from index), with the
 * distance at which the ray enters its box. */
struct item {
    uint32_t index, count;
    float t;
};

/* Shared traversal; any_hit and leaf are constants at each call site, and the function is always
 * inlined, so each caller gets its own specialised copy (leaf(ctx, ...) becomes a direct, inlined
 * primitive test). The slab tests use the world ray r; leaf tests whatever ctx holds for it.
 * A node's children are tested together. The children met are visited nearest entry first (Wald
 * et al. 2008, "Getting rid of packets": ordered traversal), the others pushed with their entry
 * distances, so that a nearest-hit query skips them once a closer hit is found; an occlusion query
 * stops at the first hit. The ray constants and the current nearest
 * distance live in locals (not behind pointers that the primitive tests could alias), so that they
 * stay in registers. Rays with a non-finite or zero direction, or a non-finite origin, hit
 * nothing. */
static ALWAYS_INLINE int traverse(const struct bvh *b, const struct prim *prims,
                                  const struct ray *r, struct hit *out, int any_hit,
                                  leaf_test leaf, void *ctx)
{
    /* Each level pushes at most BVH_WIDTH - 1 items, and the wide tree is no deeper than the
     * binary one (BVH_DEPTH_MAX). */
    struct item stack[(BVH_WIDTH - 1) * BVH_DEPTH_MAX], cur;
    const struct bvh_node *nodes = b->nodes;
    struct slab_ray s;
    struct hit h;
    float tmax = r->tmax;
    int sp = 0, found = 0, a;

    if (b->node_count == 0 || !v3_is_finite(r->o) || !v3_is_finite(r->d) || v3_is_zero(r->d))
        return 0;
    s.o[0] = r->o.x;
    s.o[1] = r->o.y;
    s.o[2] = r->o.z;
    s.inv[0] = 1.0f / r->d.x;
    s.inv[1] = 1.0f / r->d.y;
    s.inv[2] = 1.0f / r->d.z;
    for (a = 0; a < 3; a++) {
        s.near[a] = s.inv[a] < 0.0f ? a + 3 : a;
        s.far[a] = s.inv[a] < 0.0f ? a : a + 3;
#ifdef BVH_SSE
        s.o4[a] = _mm_set1_ps(s.o[a]);
        s.inv4[a] = _mm_set1_ps(s.inv[a]);
#endif
    }
    h.t = tmax;
    cur.index = 0;
    cur.count = 0;
    for (;;) {
        if (cur.count == 0) {
            const struct bvh_node *n = &nodes[cur.index];
            float tn[BVH_WIDTH];
            unsigned mask = node_test(n, &s, tmax, tn);
            struct item hit[BVH_WIDTH];
            int k = 0, i, j;
            /* Visit only the set bits: a loop over all slots mispredicts on the mask's bits. */
            for (; mask; mask &= mask - 1, k++) {
                i = lowest_bit(mask);
                hit[k].index = n->child[i];
                hit[k].count = n->count[i];
                hit[k].t = tn[i];
            }
            if (k == 1) {
                cur = hit[0];
                continue;
            }
            if (k > 1) {
                /* Insertion sort, farthest first: at most BVH_WIDTH items. */
                for (i = 1; i < k; i++) {
                        struct item x = hit[i];
                        for (j = i; j > 0 && hit[j - 1].t < x.t; j--)
                            hit[j] = hit[j - 1];
                        hit[j] = x;
                    }
                for (i = 0; i < k - 1; i++)
                    stack[sp++] = hit[i];
                cur = hit[k - 1];
                continue;
            }
        } else {
            uint32_t k, end = cur.index + cur.count;
            for (k = cur.index; k < end; k++) {
                if (leaf(ctx, &prims[k], &h)) {
                    if (any_hit)
                        return 1;
                    h.prim = k;
                    found = 1;
                }
            }
            tmax = h.t;
        }
        /* Pop, skipping subtrees that start beyond the nearest hit so far. */
        do {
            if (sp == 0) {
                if (found)
                    *out = h;
                return found;
            }
            sp--;
        } while (!(stack[sp].t <= tmax * SLAB_GROW));
        cur = stack[sp];
    }
}

int mc_bvh_intersect(const struct bvh *b, const struct prim *prims, const struct ray *r,
                     struct hit *h)
{
    struct ray_prep q;
    mc_ray_prep(&q, r);
    return traverse(b, prims, r, h, 0, test_static, &q);
}

int mc_bvh_occluded(const struct bvh *b, const struct prim *prims, const struct ray *r)
{
    struct ray_prep q;
    struct hit h;
    mc_ray_prep(&q, r);
    return traverse(b, prims, r, &h, 1, test_static, &q);
}

static void moving_ray_init(struct moving_ray *m, const struct motion *motions, const struct ray *r)
{
    m->motions = motions;
    m->r = r;
    m->motion = 0;
}

int mc_bvh_intersect_moving(const struct bvh *b, const struct prim *prims,
                            const struct motion *motions, const struct ray *r, struct hit *h)
{
    struct moving_ray m;
    moving_ray_init(&m, motions, r);
    return traverse(b, prims, r, h, 0, test_moving, &m);
}

int mc_bvh_occluded_moving(const struct bvh *b, const struct prim *prims,
                           const struct motion *motions, const struct ray *r)
{
    struct moving_ray m;
    struct hit h;
    moving_ray_init(&m, motions, r);
    return traverse(b, prims, r, &h, 1, test_moving, &m);
}
