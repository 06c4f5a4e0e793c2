/* bvh.c: single-ray traversal of the 8-wide BVH (built in bvh_build.c) with SIMD node tests and
 * SIMD watertight triangle and quad tests (tri_wide.h: 4-wide with SSE, 8-wide for a leaf's two
 * blocks with AVX2; portable C99 under MCRT_BVH_PORTABLE), of static primitives and of moving ones
 * (tested in their time-0 frame, one by one). */
#include "geom/bvh.h"

#include <string.h>

#include "core/simd.h"
#include "geom/bvh_node.h"
#include "geom/motion.h"
#include "geom/tri4.h"

/* SIMD: SSE2 (baseline x86-64) for the triangle tests and the node test, and the node test as one
 * 8-wide AVX operation when the processor has AVX2 (x86-64-v3, whose register broadcasts the
 * per-ray set-up uses: 1.4% fewer instructions a ray than AVX alone): always when compiled for it
 * (-mavx2, -march=native), else chosen at run time with GCC's target attribute and
 * __builtin_cpu_supports (GCC and Clang on x86-64). MCRT_BVH_NO_AVX keeps to SSE, so that a test
 * can cover that path on a processor with AVX2. */
#if defined(__SSE2__) && !defined(MCRT_BVH_PORTABLE)
#include <emmintrin.h>
#define BVH_SSE 1
#if defined(MCRT_BVH_NO_AVX) || BVH_WIDTH != 8
#elif defined(__AVX2__)
#include <immintrin.h>
#define BVH_AVX 1
#define AVX_TARGET
#elif defined(MC_AVX2_DISPATCH)
#include <immintrin.h>
#define BVH_AVX 1
#define BVH_AVX_DISPATCH 1
#define AVX_TARGET MC_AVX2_TARGET
#endif
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
#ifdef BVH_AVX
    __m256 o8[3], inv8[3]; /* the same for node_test8 */
    __m256 invg8[3];       /* inv · SLAB_GROW, for node_test8's exit distances */
#endif
};

/* The slab_ray of r, but for the broadcasts (the node test's set-up, below); returns 0, leaving s
 * unset, for a ray that hits nothing: a non-finite or zero direction, or a non-finite origin. */
static inline int slab_ray_init(struct slab_ray *s, const struct ray *r)
{
    int a;
#ifdef BVH_SSE
    /* Two loads cover o and d: (o.x, o.y, o.z, d.x) and (d.x, d.y, d.z, tmax), both inside the
     * struct. x - x is NaN exactly when x is infinite or NaN, so lanes 0-2 of the ordered test
     * are all true exactly when the six coordinates are finite; lane 3 (tmax) is ignored. The
     * reciprocals are one division of four lanes, bitwise the scalar 1.0f / d. */
    __m128 o = _mm_loadu_ps(&r->o.x), d = _mm_loadu_ps(&r->d.x), inv;
    float inv4[4];
    if ((_mm_movemask_ps(_mm_cmpord_ps(_mm_sub_ps(o, o), _mm_sub_ps(d, d))) & 7) != 7 ||
        (_mm_movemask_ps(_mm_cmpneq_ps(d, _mm_setzero_ps())) & 7) == 0)
        return 0;
    inv = _mm_div_ps(_mm_set1_ps(1.0f), d);
    _mm_storeu_ps(inv4, inv);
    for (a = 0; a < 3; a++)
        s->inv[a] = inv4[a];
#else
    if (!v3_is_finite(r->o) || !v3_is_finite(r->d) || v3_is_zero(r->d))
        return 0;
    s->inv[0] = 1.0f / r->d.x;
    s->inv[1] = 1.0f / r->d.y;
    s->inv[2] = 1.0f / r->d.z;
#endif
    s->o[0] = r->o.x;
    s->o[1] = r->o.y;
    s->o[2] = r->o.z;
    for (a = 0; a < 3; a++) {
        s->near[a] = s->inv[a] < 0.0f ? a + 3 : a;
        s->far[a] = s->inv[a] < 0.0f ? a : a + 3;
    }
    return 1;
}

/* A node test's per-ray set-up: the broadcasts above of the slab_ray's o and inv. */
static inline void node_prep(struct slab_ray *s)
{
#ifdef BVH_SSE
    int a;
    for (a = 0; a < 3; a++) {
        s->o4[a] = _mm_set1_ps(s->o[a]);
        s->inv4[a] = _mm_set1_ps(s->inv[a]);
    }
#else
    (void)s;
#endif
}

/* The slab test of a node's BVH_WIDTH children against the ray's segment [0, tmax]: returns the
 * mask of children met (bit i for child i) and their entry distances in tn. tmax_grown is
 * tmax · SLAB_GROW, which the traversal computes once per nearer hit rather than node_test8 at
 * every node. A zero direction
 * component with the origin exactly on a slab plane gives 0·inf = NaN; the minima and maxima are
 * ordered so that a NaN leaves the interval unchanged, which is right for a ray lying in the
 * (closed) slab. Unused children have empty boxes (lower +inf, upper -inf): entry +inf, exit -inf. */
#ifdef BVH_SSE
/* One axis of the SSE node test for children g .. g + 3, as node_test8's slab8. */
static inline void slab4(const struct bvh_node *n, const struct slab_ray *s, int a, int g,
                         __m128 *t0, __m128 *t1)
{
    /* _mm_max_ps(a, b) and _mm_min_ps(a, b) return b when either is NaN: the accumulator goes
     * second, as in the portable version's comparisons. */
    __m128 ta = _mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(&n->b[s->near[a]][g]), s->o4[a]), s->inv4[a]);
    __m128 tb = _mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(&n->b[s->far[a]][g]), s->o4[a]), s->inv4[a]);
    *t0 = _mm_max_ps(ta, *t0);
    *t1 = _mm_min_ps(tb, *t1);
}

static inline unsigned node_test(const struct bvh_node *n, const struct slab_ray *s, float tmax,
                                 float tmax_grown, float *tn)
{
    /* Four children per SSE vector. */
    unsigned mask = 0;
    int g;
    (void)tmax_grown; /* the exit distances are grown after the minimum, as the portable test's */
    for (g = 0; g < BVH_WIDTH; g += 4) {
        __m128 t0 = _mm_setzero_ps(), t1 = _mm_set1_ps(tmax);
        slab4(n, s, 0, g, &t0, &t1);
        slab4(n, s, 1, g, &t0, &t1);
        slab4(n, s, 2, g, &t0, &t1);
        _mm_storeu_ps(&tn[g], t0);
        mask |= (unsigned)_mm_movemask_ps(_mm_cmple_ps(t0, _mm_mul_ps(t1, _mm_set1_ps(SLAB_GROW))))
                << g;
    }
    return mask;
}
#else
/* One axis of the portable node test, as node_test8's slab8: constant axes, and a loop over the
 * children that compilers can turn into SIMD code (GCC -O2 does, for t0 and t1 the node test's
 * own arrays, which it can see do not alias the node). */
static MC_ALWAYS_INLINE void slab1(const struct bvh_node *n, const struct slab_ray *s, int a,
                                float *t0, float *t1)
{
    const float *near = n->b[s->near[a]], *far = n->b[s->far[a]], o = s->o[a], inv = s->inv[a];
    int i;
    for (i = 0; i < BVH_WIDTH; i++) {
        float ta = (near[i] - o) * inv, tb = (far[i] - o) * inv;
        t0[i] = ta > t0[i] ? ta : t0[i];
        t1[i] = tb < t1[i] ? tb : t1[i];
    }
}

static MC_ALWAYS_INLINE unsigned node_test(const struct bvh_node *n, const struct slab_ray *s,
                                           float tmax, float tmax_grown, float *tn)
{
    float t0[BVH_WIDTH], t1[BVH_WIDTH];
    unsigned mask = 0;
    int i;
    (void)tmax_grown; /* node_test8's */
    for (i = 0; i < BVH_WIDTH; i++) {
        t0[i] = 0.0f;
        t1[i] = tmax;
    }
    slab1(n, s, 0, t0, t1);
    slab1(n, s, 1, t0, t1);
    slab1(n, s, 2, t0, t1);
    for (i = 0; i < BVH_WIDTH; i++) {
        tn[i] = t0[i];
        mask |= (unsigned)(t0[i] <= t1[i] * SLAB_GROW) << i;
    }
    return mask;
}
#endif

/* The same with all eight children in one AVX operation (BVH_WIDTH is 8). */
#ifdef BVH_AVX
/* Written out axis by axis: GCC -O2 keeps a loop over the axes, which cost 36 instructions a ray
 * here against 12. */
static inline AVX_TARGET void node_prep8(struct slab_ray *s)
{
    const __m256 grow = _mm256_set1_ps(SLAB_GROW);
    s->o8[0] = _mm256_set1_ps(s->o[0]);
    s->o8[1] = _mm256_set1_ps(s->o[1]);
    s->o8[2] = _mm256_set1_ps(s->o[2]);
    s->inv8[0] = _mm256_set1_ps(s->inv[0]);
    s->inv8[1] = _mm256_set1_ps(s->inv[1]);
    s->inv8[2] = _mm256_set1_ps(s->inv[2]);
    s->invg8[0] = _mm256_mul_ps(s->inv8[0], grow);
    s->invg8[1] = _mm256_mul_ps(s->inv8[1], grow);
    s->invg8[2] = _mm256_mul_ps(s->inv8[2], grow);
}

/* One axis of node_test8: folds the slab distances of axis a into t0 and t1. Called with a
 * constant axis, rather than in a loop over a (which GCC -O2 does not unroll), so that once
 * inlined into the traversal the axis's broadcasts and plane rows are loop invariants. */
static inline AVX_TARGET void slab8(const struct bvh_node *n, const struct slab_ray *s, int a,
                                    __m256 *t0, __m256 *t1)
{
    __m256 o = s->o8[a];
    __m256 ta = _mm256_mul_ps(_mm256_sub_ps(_mm256_loadu_ps(n->b[s->near[a]]), o), s->inv8[a]);
    __m256 tb = _mm256_mul_ps(_mm256_sub_ps(_mm256_loadu_ps(n->b[s->far[a]]), o), s->invg8[a]);
    *t0 = _mm256_max_ps(ta, *t0);
    *t1 = _mm256_min_ps(tb, *t1);
}

static inline AVX_TARGET unsigned node_test8(const struct bvh_node *n, const struct slab_ray *s,
                                             float tmax, float tmax_grown, float *tn)
{
    /* The exit distances come out grown by SLAB_GROW already (invg8), which takes the growth off
     * the chain of dependent operations that a node visit waits on. Still conservative: an entry
     * distance is at most (1 + 2^-24)^3 of the exact one (the rounding of 1/d, b - o and the
     * product), an exit at least (1 - 2^-24)^4 SLAB_GROW of it (the fourth rounding is that of
     * inv · SLAB_GROW), and (1 + 2^-24)^3 / (1 - 2^-24)^4 < 1 + 8·2^-24 = SLAB_GROW. */
    __m256 t0 = _mm256_setzero_ps(), t1 = _mm256_set1_ps(tmax_grown);
    (void)tmax; /* the other node tests' */
    slab8(n, s, 0, &t0, &t1);
    slab8(n, s, 1, &t0, &t1);
    slab8(n, s, 2, &t0, &t1);
    _mm256_storeu_ps(tn, t0);
    return (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(t0, t1, _CMP_LE_OQ));
}
#endif

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

/* ---- Static primitives: four or eight triangles at a time ---- */

/* The ray as the triangle tests need it: the watertight test's constants (q, also what the scalar
 * test of undecided lanes takes) and their broadcasts, made at the ray's first leaf (ready: 1 the
 * 4-wide ones, 2 the 8-wide ones too, at its first leaf of more than four primitives): a ray that
 * meets no leaf, as 37 to 44% of the anchor scenes' primary rays, never needs them. det: the
 * nearest hit's determinant, for its u and v (below). */
struct tri_ray {
    const struct ray *r;
    int ready;
    float det;
    struct ray_prep q;
#ifdef BVH_SSE
    struct { __m128 o[3], sx, sy, sz; } l4; /* the origin in the permuted axis order, the shear */
#endif
#ifdef BVH_AVX
    struct { __m256 o[3], sx, sy, sz; } l8;
#endif
};

/* The origin is read from the ray, not from the slab_ray's o: indexing that by a run-time axis
 * would keep the whole slab_ray in memory, and the node test's constants out of registers. */
static inline void tri_ray_init(struct tri_ray *t, const struct ray *r)
{
    t->ready = 1;
    mc_ray_prep(&t->q, r);
#ifdef BVH_SSE
    {
        const float o[3] = {r->o.x, r->o.y, r->o.z};
        t->l4.o[0] = _mm_set1_ps(o[t->q.kx]);
        t->l4.o[1] = _mm_set1_ps(o[t->q.ky]);
        t->l4.o[2] = _mm_set1_ps(o[t->q.kz]);
        t->l4.sx = _mm_set1_ps(t->q.sx);
        t->l4.sy = _mm_set1_ps(t->q.sy);
        t->l4.sz = _mm_set1_ps(t->q.sz);
    }
#endif
}

/* What a SIMD test decides for the lanes of `live` (lane l: lane l & 3 of the (l >> 2)th block
 * tested): hit, lanes hit in (0, tmax), with their t, e1, e2 and det (for the barycentrics);
 * undecided, lanes it leaves to the scalar test. */
struct tri_result {
    unsigned hit, undecided;
    float t[8], e1[8], e2[8], det[8];
};

#ifdef BVH_SSE
/* tri_wide.h on one block of four lanes (SSE). */
#define TRI_TEST tri4_test
#define TRI_TARGET
#define TRI_LANES l4
#define VF __m128
#define VI __m128i
#define VOP(op) _mm_##op##_ps
#define V_LOAD(k, vertex, axis) _mm_load_ps((k)->v[vertex][axis])
#define V_PRIM(k) _mm_load_si128((const __m128i *)(k)->prim)
#define V_EQ(a, b) _mm_cmpeq_ps(a, b)
#define V_GT(a, b) _mm_cmpgt_ps(a, b)
#define V_LT(a, b) _mm_cmplt_ps(a, b)
#define V_UNORD(a, b) _mm_cmpunord_ps(a, b)
#define V_CAST_FI(x) _mm_castsi128_ps(x)
#define V_SIGN_FILL(x) _mm_castsi128_ps(_mm_srai_epi32(x, 31))
#include "geom/tri_wide.h"
#else
/* The same decisions lane by lane, in portable C99. */
static MC_ALWAYS_INLINE void tri4_test(const struct tri4 *k, const struct tri_ray *r,
                                    float tmax, unsigned live, struct tri_result *out)
{
    const float o[3] = {r->q.r.o.x, r->q.r.o.y, r->q.r.o.z};
    const int kx = r->q.kx, ky = r->q.ky, kz = r->q.kz;
    int l;
    out->hit = out->undecided = 0;
    for (l = 0; l < 4; l++) {
        float az = k->v[0][kz][l] - o[kz], bz = k->v[1][kz][l] - o[kz],
              cz = k->v[2][kz][l] - o[kz];
        float ax = (k->v[0][kx][l] - o[kx]) + r->q.sx * az,
              ay = (k->v[0][ky][l] - o[ky]) + r->q.sy * az;
        float bx = (k->v[1][kx][l] - o[kx]) + r->q.sx * bz,
              by = (k->v[1][ky][l] - o[ky]) + r->q.sy * bz;
        float cx = (k->v[2][kx][l] - o[kx]) + r->q.sx * cz,
              cy = (k->v[2][ky][l] - o[ky]) + r->q.sy * cz;
        float e0 = bx * cy - by * cx, e1 = cx * ay - cy * ax, e2 = ax * by - ay * bx;
        float det = e0 + e1 + e2;
        float zs[3] = {r->q.sz * az, r->q.sz * bz, r->q.sz * cz};
        float ts = e0 * zs[0] + e1 * zs[1] + e2 * zs[2], t;
        if (!(live >> l & 1))
            continue;
        if ((e0 == 0.0f) | (e1 == 0.0f) | (e2 == 0.0f) | (det != det)) {
            out->undecided |= 1u << l;
            continue;
        }
        if (k->prim[l] & MC_TRI4_QUAD
                ? ((det < 0.0f) != (e1 < 0.0f)) | ((det < 0.0f) != (e2 < 0.0f))
                      | (fabsf(e1) > fabsf(det)) | (fabsf(e2) > fabsf(det))
                : ((e0 < 0.0f) | (e1 < 0.0f) | (e2 < 0.0f))
                      & ((e0 > 0.0f) | (e1 > 0.0f) | (e2 > 0.0f)))
            continue;
        if ((det == 0.0f) | (ts == 0.0f) | ((det < 0.0f) != (ts < 0.0f)))
            continue;
        t = ts / det;
        if (!(t < tmax)
            || !(t > mc_tri_t_error(mc_abs_max3(ax, bx, cx), mc_abs_max3(ay, by, cy),
                                    mc_abs_max3(zs[0], zs[1], zs[2]), mc_abs_max3(e0, e1, e2),
                                    det)))
            continue;
        out->hit |= 1u << l;
        out->t[l] = t;
        out->e1[l] = e1;
        out->e2[l] = e2;
        out->det[l] = det;
    }
}
#endif

#ifdef BVH_AVX
/* tri_wide.h on two consecutive blocks of a leaf, eight lanes (AVX2): the lanes of block k in
 * the low half, of block k + 1 in the high. */
#define TRI_TEST tri8_test
#define TRI_TARGET AVX_TARGET
#define TRI_LANES l8
#define VF __m256
#define VI __m256i
#define VOP(op) _mm256_##op##_ps
#define V_LOAD(k, vertex, axis) \
    _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_load_ps((k)[0].v[vertex][axis])), \
                         _mm_load_ps((k)[1].v[vertex][axis]), 1)
#define V_PRIM(k) \
    _mm256_inserti128_si256(_mm256_castsi128_si256(_mm_load_si128((const __m128i *)(k)[0].prim)), \
                            _mm_load_si128((const __m128i *)(k)[1].prim), 1)
#define V_EQ(a, b) _mm256_cmp_ps(a, b, _CMP_EQ_OQ)
#define V_GT(a, b) _mm256_cmp_ps(a, b, _CMP_GT_OQ)
#define V_LT(a, b) _mm256_cmp_ps(a, b, _CMP_LT_OQ)
#define V_UNORD(a, b) _mm256_cmp_ps(a, b, _CMP_UNORD_Q)
#define V_CAST_FI(x) _mm256_castsi256_ps(x)
#define V_SIGN_FILL(x) _mm256_castsi256_ps(_mm256_srai_epi32(x, 31))
#include "geom/tri_wide.h"

/* The 8-wide broadcasts, from the 4-wide ones (tri_ray_init's, made before). */
static inline AVX_TARGET void tri_ray_init8(struct tri_ray *t)
{
    t->ready = 2;
    t->l8.o[0] = _mm256_broadcastss_ps(t->l4.o[0]);
    t->l8.o[1] = _mm256_broadcastss_ps(t->l4.o[1]);
    t->l8.o[2] = _mm256_broadcastss_ps(t->l4.o[2]);
    t->l8.sx = _mm256_broadcastss_ps(t->l4.sx);
    t->l8.sy = _mm256_broadcastss_ps(t->l4.sy);
    t->l8.sz = _mm256_broadcastss_ps(t->l4.sz);
}
#endif

/* Takes the lanes that the test of the blocks from k decided as hits, or left undecided (tested
 * here by the scalar test), in lane order, so that of equal distances the first primitive wins, as
 * in a loop over the primitives. Returns whether h was updated (h->prim too); with any_hit, stops
 * at the first hit. */
static MC_ALWAYS_INLINE int take_hits(struct tri_ray *r, const struct prim *prims,
                                      const struct tri4 *k, const struct tri_result *res,
                                      struct hit *h, int any_hit)
{
    unsigned todo;
    int found = 0;
    for (todo = res->hit | res->undecided; todo; todo &= todo - 1) {
        int l = lowest_bit(todo);
        uint32_t prim = mc_tri4_prim(k[l >> 2].prim[l & 3]);
        if (res->hit >> l & 1) {
            if (!(res->t[l] < h->t)) /* an earlier lane is nearer */
                continue;
            /* u and v are e1 / det and e2 / det, divided once the nearest hit is known
             * (query_static) rather than at every nearer hit found on the way. */
            h->t = res->t[l];
            h->u = res->e1[l];
            h->v = res->e2[l];
            r->det = res->det[l];
        } else if (mc_prim_intersect_prep(&prims[prim], &r->q, h)) {
            r->det = 1.0f; /* u and v are final: dividing by 1 keeps them */
        } else {
            continue;
        }
        h->prim = prim;
        found = 1;
        if (any_hit)
            break;
    }
    return found;
}

/* Static primitives: ctx is the tri_ray. The leaf of count primitives whose blocks start at block
 * `first` (tri4.h) is tested a block at a time, lanes in primitive order. Returns whether h was
 * updated (h->prim too); with any_hit, stops at the first hit. */
static MC_ALWAYS_INLINE int leaf_static(void *ctx, const struct bvh *b, const struct prim *prims,
                                     uint32_t first, uint32_t count, struct hit *h, int any_hit)
{
    struct tri_ray *r = ctx;
    const struct tri4 *k = &b->tri4[first], *end = k + mc_tri4_blocks(count);
    int found = 0;
    if (!r->ready)
        tri_ray_init(r, r->r);
    /* count goes down by 4 a block: the lanes of the leaf in this block are its first min(count, 4). */
    for (; k < end; k++, count -= 4) {
        struct tri_result res;
        tri4_test(k, r, h->t, count >= 4 ? 0xFu : 0xFu >> (4 - count), &res);
        if (take_hits(r, prims, k, &res, h, any_hit)) {
            if (any_hit)
                return 1;
            found = 1;
        }
    }
    return found;
}

#ifdef BVH_AVX
/* leaf_static's contract, two blocks at a time in one 8-wide test; a last block alone (a leaf of
 * at most four primitives, as most are) in the 4-wide one. */
static MC_ALWAYS_INLINE AVX_TARGET int leaf_static8(void *ctx, const struct bvh *b,
                                                    const struct prim *prims, uint32_t first,
                                                    uint32_t count, struct hit *h, int any_hit)
{
    struct tri_ray *r = ctx;
    const struct tri4 *k = &b->tri4[first];
    int found = 0;
    if (count <= 4)
        return leaf_static(ctx, b, prims, first, count, h, any_hit);
    if (r->ready < 2) {
        if (!r->ready)
            tri_ray_init(r, r->r);
        tri_ray_init8(r);
    }
    /* count goes down by 8 a pair of blocks: the lanes of the leaf in it are its first
     * min(count, 8). */
    for (; count > 4; k += 2, count = count > 8 ? count - 8 : 0) {
        struct tri_result res;
        tri8_test(k, r, h->t, count >= 8 ? 0xFFu : 0xFFu >> (8 - count), &res);
        if (take_hits(r, prims, k, &res, h, any_hit)) {
            if (any_hit)
                return 1;
            found = 1;
        }
    }
    if (count)
        found |= leaf_static(ctx, b, prims, (uint32_t)(k - b->tri4), count, h, any_hit);
    return found;
}
#endif

/* ---- Moving primitives: one at a time ---- */

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

/* leaf_static's contract for moving primitives: ctx is the moving_ray. Only the blocks' primitive
 * indices are used: the leaf's count primitives are the first count lanes of its blocks from
 * block `first`. */
static MC_ALWAYS_INLINE int leaf_moving(void *ctx, const struct bvh *b, const struct prim *prims,
                                     uint32_t first, uint32_t count, struct hit *h, int any_hit)
{
    struct moving_ray *m = ctx;
    uint32_t i;
    int found = 0;
    for (i = 0; i < count; i++) {
        uint32_t k = mc_tri4_prim(b->tri4[first + i / 4].prim[i % 4]);
        const struct prim *p = &prims[k];
        if (p->motion != m->motion) {
            struct rigid x;
            struct ray local;
            mc_motion_at(&m->motions[p->motion - 1], m->r->time, &x);
            local = rigid_inv_ray(&x, m->r);
            mc_ray_prep(&m->q, &local);
            m->motion = p->motion;
        }
        if (mc_prim_intersect_prep(p, &m->q, h)) {
            if (any_hit)
                return 1;
            h->prim = k;
            found = 1;
        }
    }
    return found;
}

/* A node test's set-up: node_prep's contract. */
typedef void (*node_prep_fn)(struct slab_ray *s);

/* A node test: node_test's contract. */
typedef unsigned (*node_test_fn)(const struct bvh_node *n, const struct slab_ray *s, float tmax,
                                 float tmax_grown, float *tn);

/* A leaf test: the leaf of count primitives from block `first` against the ray in ctx, as
 * leaf_static. */
typedef int (*leaf_test)(void *ctx, const struct bvh *b, const struct prim *prims,
                         uint32_t first, uint32_t count, struct hit *h, int any_hit);

/* ---- Traversal ---- */

/* A subtree still to visit, as one 64-bit key so that sorting and stack moves are single integer
 * operations (as Embree packs its node references): the high word is the bits of the distance at
 * which the ray enters the subtree's box with the low 8 bits replaced by the slot's count (0: inner
 * node; else a leaf of that many primitives), the low word the slot's child. Entry distances are
 * >= +0 and not NaN (node_test), so their bits order as the floats do, and clearing 8 low bits
 * rounds a distance down by at most 2^-15 relatively: keys order as distances do up to such ties,
 * and a distance test on the key is conservative (it keeps a subtree it might skip, never skips
 * one it needs). */
typedef uint64_t item;
#define ITEM_COUNT_BITS 8
/* Compile-time check (C99 has no static_assert) that bvh_node.count fits those bits. */
typedef char count_fits_item[sizeof(((struct bvh_node *)0)->count[0]) * 8 <= ITEM_COUNT_BITS
                             ? 1 : -1];

static inline uint32_t float_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

/* Child i of node n as an item, with entry distance tn[i]. */
static inline item child_item(const struct bvh_node *n, const float *tn, int i)
{
    uint32_t hi = (float_bits(tn[i]) & ~((1u << ITEM_COUNT_BITS) - 1)) | n->count[i];
    return (uint64_t)hi << 32 | n->child[i];
}

/* Child i of node n as an item for an occlusion query, which neither orders its subtrees nor
 * skips them by distance: the entry distance left out (0), so that the node test's distances
 * need not be kept. */
static inline item child_item_any(const struct bvh_node *n, int i)
{
    return (uint64_t)n->count[i] << 32 | n->child[i];
}

/* The largest high word of an item whose distance may still matter when the nearest hit so far
 * is at tmax, given tmax · SLAB_GROW: the node test keeps a box whose entry t0 <= exit ·
 * SLAB_GROW, with exit <= tmax. */
static inline uint32_t item_limit(float tmax_grown)
{
    return float_bits(tmax_grown) | ((1u << ITEM_COUNT_BITS) - 1);
}

/* Order a and b so that *a <= *b, without a branch on their (unpredictable) order. */
static inline void sort2(item *a, item *b)
{
    item lo = *a < *b ? *a : *b, hi = *a ^ *b ^ lo;
    *a = lo;
    *b = hi;
}

/* Shared traversal; any_hit, node and leaf are constants at each call site, and the function is
 * always inlined, so each caller gets its own specialised copy (node(...) and leaf(ctx, ...) become
 * direct, inlined tests). The slab tests use the world ray r; leaf tests whatever ctx holds for it.
 * A node's children are tested together. A nearest-hit query visits the children met nearest
 * entry first (Wald et al. 2008, "Getting rid of packets": ordered traversal): the nearest goes on
 * in a register, the others are pushed farthest first with their entry distances, by a sorting
 * network for the common two to four (as Embree's BVHNNodeTraverser1Hit), so that it skips them
 * once a closer hit is found. An occlusion query stops at the first hit, so the order buys it
 * little and it skips the sort, as Embree's any-hit traversal does (sorting measured 1% fewer
 * instructions on spheres-16 shadow rays, 3% more on grid-city's); nor does it skip subtrees by
 * distance, so its items carry none (child_item_any): 1,320 -> 1,261 instructions a sphere-1M
 * shadow ray (callgrind, bench --quick), the same answers. The ray constants and the
 * current nearest distance live in locals (not behind pointers that the primitive tests could
 * alias), so that they stay in registers. Rays with a non-finite or zero direction, or a
 * non-finite origin, hit nothing. */
static MC_ALWAYS_INLINE int traverse(const struct bvh *b, const struct prim *prims,
                                  const struct ray *r, struct hit *out, int any_hit,
                                  node_prep_fn prep, node_test_fn node, leaf_test leaf,
                                  void *ctx)
{
    /* Each level pushes at most BVH_WIDTH - 1 items, and the wide tree is no deeper than the
     * binary one (BVH_DEPTH_MAX). */
    item stack[(BVH_WIDTH - 1) * BVH_DEPTH_MAX], cur;
    const struct bvh_node *nodes = b->nodes;
    struct slab_ray s;
    struct hit h;
    float tmax = r->tmax, tmax_grown;
    uint32_t limit;
    int sp = 0, found = 0;

    if (b->node_count == 0 || !slab_ray_init(&s, r))
        return 0;
    prep(&s);
    h.t = tmax;
    tmax_grown = tmax * SLAB_GROW;
    limit = item_limit(tmax_grown);
    cur = 0; /* the root: inner node 0 */
    for (;;) {
        uint32_t count = (uint32_t)(cur >> 32) & ((1u << ITEM_COUNT_BITS) - 1);
        if (count == 0) {
            const struct bvh_node *n = &nodes[(uint32_t)cur];
            float tn[BVH_WIDTH];
            unsigned mask = node(n, &s, tmax, tmax_grown, tn);
            item c1, c2, c3;
            if (mask && any_hit) {
                cur = child_item_any(n, lowest_bit(mask));
                for (mask &= mask - 1; mask; mask &= mask - 1)
                    stack[sp++] = child_item_any(n, lowest_bit(mask));
                continue;
            }
            if (mask) {
                /* Only the set bits are visited: a loop over all slots mispredicts on them. */
                cur = child_item(n, tn, lowest_bit(mask));
                mask &= mask - 1;
                if (!mask)
                    continue;
                c1 = child_item(n, tn, lowest_bit(mask));
                mask &= mask - 1;
                sort2(&cur, &c1);
                if (!mask) {
                    stack[sp++] = c1;
                    continue;
                }
                c2 = child_item(n, tn, lowest_bit(mask));
                mask &= mask - 1;
                if (!mask) {
                    sort2(&c1, &c2);
                    sort2(&cur, &c1);
                    stack[sp] = c2;
                    stack[sp + 1] = c1;
                    sp += 2;
                    continue;
                }
                c3 = child_item(n, tn, lowest_bit(mask));
                mask &= mask - 1;
                if (!mask) {
                    sort2(&c2, &c3);
                    sort2(&cur, &c2);
                    sort2(&c1, &c3);
                    sort2(&c1, &c2);
                    stack[sp] = c3;
                    stack[sp + 1] = c2;
                    stack[sp + 2] = c1;
                    sp += 3;
                    continue;
                }
                {
                    /* Five or more: rare, so an insertion sort of the rest, farthest first. */
                    int base = sp, i, j;
                    stack[sp++] = cur;
                    stack[sp++] = c1;
                    stack[sp++] = c2;
                    stack[sp++] = c3;
                    for (; mask; mask &= mask - 1)
                        stack[sp++] = child_item(n, tn, lowest_bit(mask));
                    for (i = base + 1; i < sp; i++) {
                        item x = stack[i];
                        for (j = i; j > base && stack[j - 1] < x; j--)
                            stack[j] = stack[j - 1];
                        stack[j] = x;
                    }
                    cur = stack[--sp];
                    continue;
                }
            }
        } else if (leaf(ctx, b, prims, (uint32_t)cur, count, &h, any_hit)) {
            if (any_hit)
                return 1;
            found = 1;
            tmax = h.t;
            tmax_grown = tmax * SLAB_GROW;
            limit = item_limit(tmax_grown);
        }
        /* Pop, skipping subtrees that start beyond the nearest hit so far (an occlusion query
         * has none: it returned at its first hit). */
        do {
            if (sp == 0) {
                if (found)
                    *out = h;
                return found;
            }
            cur = stack[--sp];
        } while (!any_hit && (uint32_t)(cur >> 32) > limit);
    }
}

/* Static queries: traversal specialised for the node test, any_hit and the leaf test; h is
 * written only on a hit. */
static MC_ALWAYS_INLINE int query_static(const struct bvh *b, const struct prim *prims,
                                      const struct ray *r, struct hit *h, int any_hit,
                                      node_prep_fn prep, node_test_fn node, leaf_test leaf)
{
    struct tri_ray t;
    struct hit nearest;
    t.r = r;
    t.ready = 0;
    if (!traverse(b, prims, r, &nearest, any_hit, prep, node, leaf, &t))
        return 0;
    if (!any_hit) {
        nearest.u /= t.det;
        nearest.v /= t.det;
        *h = nearest;
    }
    return 1;
}

/* The queries for each instruction set, each its own function: with the dispatch, the public
 * functions below are then a test and a jump, with no stack frame of their own. */
#ifdef BVH_AVX
/* The traversal compiled for AVX2 (the SSE code in it, inlined, is VEX-encoded). */
static MC_NOINLINE AVX_TARGET int intersect_simd(const struct bvh *b, const struct prim *prims,
                                              const struct ray *r, struct hit *h)
{
    return query_static(b, prims, r, h, 0, node_prep8, node_test8, leaf_static8);
}

static MC_NOINLINE AVX_TARGET int occluded_simd(const struct bvh *b, const struct prim *prims,
                                             const struct ray *r)
{
    return query_static(b, prims, r, NULL, 1, node_prep8, node_test8, leaf_static8);
}
#endif

#if !defined(BVH_AVX) || defined(BVH_AVX_DISPATCH)
/* SSE, or the portable C99 code. */
static MC_NOINLINE int intersect_plain(const struct bvh *b, const struct prim *prims,
                                    const struct ray *r, struct hit *h)
{
    return query_static(b, prims, r, h, 0, node_prep, node_test, leaf_static);
}

static MC_NOINLINE int occluded_plain(const struct bvh *b, const struct prim *prims,
                                   const struct ray *r)
{
    return query_static(b, prims, r, NULL, 1, node_prep, node_test, leaf_static);
}
#endif

int mc_bvh_intersect(const struct bvh *b, const struct prim *prims, const struct ray *r,
                     struct hit *h)
{
#if defined(BVH_AVX_DISPATCH)
    if (mc_cpu_has_avx2())
        return intersect_simd(b, prims, r, h);
    return intersect_plain(b, prims, r, h);
#elif defined(BVH_AVX)
    return intersect_simd(b, prims, r, h);
#else
    return intersect_plain(b, prims, r, h);
#endif
}

int mc_bvh_occluded(const struct bvh *b, const struct prim *prims, const struct ray *r)
{
#if defined(BVH_AVX_DISPATCH)
    if (mc_cpu_has_avx2())
        return occluded_simd(b, prims, r);
    return occluded_plain(b, prims, r);
#elif defined(BVH_AVX)
    return occluded_simd(b, prims, r);
#else
    return occluded_plain(b, prims, r);
#endif
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
    return traverse(b, prims, r, h, 0, node_prep, node_test, leaf_moving, &m);
}

int mc_bvh_occluded_moving(const struct bvh *b, const struct prim *prims,
                           const struct motion *motions, const struct ray *r)
{
    struct moving_ray m;
    struct hit h;
    moving_ray_init(&m, motions, r);
    return traverse(b, prims, r, &h, 1, node_prep, node_test, leaf_moving, &m);
}

size_t mc_bvh_bytes(const struct bvh *b)
{
    return b->node_count * sizeof(struct bvh_node) + b->tri4_count * sizeof(struct tri4);
}
