/* bvh_build.c: binned-SAH binary BVH build (Wald 2007, "On fast Construction of SAH-based Bounding
 * Volume Hierarchies"), parallel over subtrees, collapsed into an 8-wide BVH (Dammertz et al. 2008,
 * "Shallow Bounding Volume Hierarchies for Fast SIMD Ray Tracing of Incoherent Rays"). */
#if defined(__linux__)
#define _DEFAULT_SOURCE /* madvise (alloc_large) */
#endif
#include "geom/bvh.h"

#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "core/alloc.h"
#include "core/atomic.h"
#include "core/simd.h"
#include "geom/bvh_node.h"
#include "geom/tri4.h"

#if defined(__SSE2__) && !defined(MCRT_BVH_PORTABLE)
#include <emmintrin.h>
#define BUILD_SSE 1
#endif

enum {
    BINS = 16,       /* SAH candidates per axis; Wald 2007 finds 16 within a few % of a full sweep */
    LEAF_MIN = 4,    /* a node of at most this many triangles and quads is always a leaf: one block */
    LEAF_MAX = 8,    /* the SAH may choose a leaf of up to this many: two blocks */
    MAX_BUILD_THREADS = 64,
    /* Below this depth nodes split at the median index, so that no node is deeper than
     * BVH_DEPTH_MAX: from depth SAH_DEPTH on every split halves the count, and a node of n < 2^31
     * primitives reaches LEAF_MAX after at most 28 more levels, depth 60 at most. */
    SAH_DEPTH = 32
};
/* The SAH counts a leaf's cost in the traversal's leaf tests (bvh.c): a 4-wide test of one block
 * (tri4.h) for up to four primitives, and with AVX2 one 8-wide test of two blocks for five to
 * eight, which costs LEAF8_COST 4-wide ones. (The tree does not depend on the processor: where SSE
 * tests the two blocks one by one, such a leaf costs two.) COST_TRAVERSE is the cost of visiting an
 * inner node (two box tests) in the same unit. Measured on the anchor scenes (tests/tools/bench.c),
 * counting blocks as Embree's builder counts its Triangle4 leaves: at COST_TRAVERSE 1.0 and above
 * the SAH preferred two-block leaves (5.3 to 6.6 primitives a leaf on sphere-1M, 8.7 to 10.3
 * expected block tests a ray against Embree's 6.6); at 0.5 the tree's expected node visits and
 * block tests were Embree's within 10% on all three scenes (sphere-1M 18.8 / 6.1 against 18.2 /
 * 6.6), with 3.8 primitives a leaf and 64 bytes a triangle, and the trace times of 0.5 to 2 were
 * within the benchmark's noise of each other. */
#define COST_TRAVERSE 0.5f
#define LEAF8_COST 1.25f
/* A sphere's or a disk's test, which the SIMD test leaves to the scalar one (tri4.h), in the same
 * unit: about 80 instructions with its call (callgrind, scenes/glossy-floor.mcrt) against about 100
 * of a 4-wide test. Without it the SAH made the five primitives of that scene one leaf, whose three
 * spheres every ray then tested one by one: 14% more instructions a render than with it. */
#define SCALAR_COST 0.8f

/* The leaf tests of a leaf of n primitives, in units of one 4-wide test. */
static float leaf_tests(uint32_t n)
{
    uint32_t rest = n % 8;
    return (float)(n / 8) * LEAF8_COST + (rest == 0 ? 0.0f : rest <= 4 ? 1.0f : LEAF8_COST);
}

/* The cost of a leaf of n primitives of which `scalar` take the scalar test as well. */
static float leaf_cost(uint32_t n, uint32_t scalar)
{
    return leaf_tests(n) + SCALAR_COST * (float)scalar;
}

/* A node of the binary tree the build makes and then collapses: 32 bytes. The two children of an
 * inner node are stored together, at index and index + 1. */
struct bnode {
    float b[6];      /* lower corner x, y, z, then upper corner x, y, z */
    uint32_t index;  /* inner: index of the first child; leaf: of the first primitive */
    uint16_t count;  /* leaf: number of primitives (1 to LEAF_MAX); inner: 0 */
    uint16_t scalar; /* leaf: how many of them are scalar (struct ref) */
};

/* An axis-aligned box as arrays, so that the build can index it by axis. */
struct box {
    float lo[3], hi[3];
};

/* Min and max written as comparisons compile to single minss/maxss instructions (fminf and
 * fmaxf are library calls under the C rules for NaN). */
static float min2(float a, float b) { return a < b ? a : b; }
static float max2(float a, float b) { return a > b ? a : b; }

static struct box box_empty(void)
{
    struct box b;
    int a;
    for (a = 0; a < 3; a++) {
        b.lo[a] = INFINITY;
        b.hi[a] = -INFINITY;
    }
    return b;
}

/* Written out: -O2 does not unroll the loop, and this is the build's innermost operation. */
static inline void box_grow(struct box *b, const float *lo, const float *hi)
{
    b->lo[0] = min2(b->lo[0], lo[0]);
    b->lo[1] = min2(b->lo[1], lo[1]);
    b->lo[2] = min2(b->lo[2], lo[2]);
    b->hi[0] = max2(b->hi[0], hi[0]);
    b->hi[1] = max2(b->hi[1], hi[1]);
    b->hi[2] = max2(b->hi[2], hi[2]);
}

/* Half the surface area; 0 for an empty box. */
static float box_half_area(const struct box *b)
{
    float x = b->hi[0] - b->lo[0], y = b->hi[1] - b->lo[1], z = b->hi[2] - b->lo[2];
    return x >= 0.0f && y >= 0.0f && z >= 0.0f ? x * y + y * z + z * x : 0.0f;
}

/* A primitive during the build: its bounds and original index, and whether the leaf tests leave
 * it to the scalar test (a sphere or a disk: scalar 1, else 0; see leaf_cost). Centroids are used
 * doubled, lo + hi, which saves a multiplication and changes no decision. 32 bytes: lo and hi are
 * each read as one 4-lane vector (below), whose fourth lane (id, scalar) is ignored. */
struct ref {
    float lo[3];
    uint32_t id;
    float hi[3];
    float scalar;
};

/* Four floats, of which the build uses lanes 0..2 (x, y, z): one SSE register where SSE2 is there,
 * else a plain array, with the same results lane by lane (f4_min and f4_max are min2 and max2, NaN
 * handling included). The binning and partition loops, which are most of the build, do a third of
 * the operations on whole boxes that they would do coordinate by coordinate. */
#ifdef BUILD_SSE
typedef __m128 f4;
static inline f4 f4_load(const float *p) { return _mm_loadu_ps(p); } /* reads p[0..3] */
/* p[0..2] with lane 3 zero (reads p[3]). For a ref's lower corner, whose fourth float is the id:
 * as a float mostly a denormal, which must not enter arithmetic (slow on some processors). */
static inline f4 f4_load3(const float *p)
{
    return _mm_and_ps(_mm_loadu_ps(p), _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0)));
}
static inline f4 f4_set(float x, float y, float z) { return _mm_setr_ps(x, y, z, 0.0f); }
static inline f4 f4_add(f4 a, f4 b) { return _mm_add_ps(a, b); }
static inline f4 f4_sub(f4 a, f4 b) { return _mm_sub_ps(a, b); }
static inline f4 f4_mul(f4 a, f4 b) { return _mm_mul_ps(a, b); }
static inline f4 f4_min(f4 a, f4 b) { return _mm_min_ps(a, b); }
static inline f4 f4_max(f4 a, f4 b) { return _mm_max_ps(a, b); }
/* Lanes 0..2 truncated to int, into out[0..2]; each must be in int range (out[3] gets lane 3,
 * which may be anything). */
static inline void f4_trunc(f4 a, int32_t *out)
{
    _mm_storeu_si128((__m128i *)out, _mm_cvttps_epi32(a));
}
static inline void f4_store3(float *p, f4 a)
{
    float v[4];
    _mm_storeu_ps(v, a);
    p[0] = v[0];
    p[1] = v[1];
    p[2] = v[2];
}
#else
typedef struct { float v[4]; } f4;
static inline f4 f4_load(const float *p)
{
    f4 r;
    r.v[0] = p[0];
    r.v[1] = p[1];
    r.v[2] = p[2];
    r.v[3] = 0.0f;
    return r;
}
static inline f4 f4_load3(const float *p) { return f4_load(p); }
static inline f4 f4_set(float x, float y, float z)
{
    f4 r;
    r.v[0] = x;
    r.v[1] = y;
    r.v[2] = z;
    r.v[3] = 0.0f;
    return r;
}
#define F4_LANES(name, expr)                                                                       \
    static inline f4 name(f4 a, f4 b)                                                              \
    {                                                                                              \
        f4 r;                                                                                      \
        int i;                                                                                     \
        for (i = 0; i < 4; i++)                                                                    \
            r.v[i] = expr;                                                                         \
        return r;                                                                                  \
    }
F4_LANES(f4_add, a.v[i] + b.v[i])
F4_LANES(f4_sub, a.v[i] - b.v[i])
F4_LANES(f4_mul, a.v[i] * b.v[i])
F4_LANES(f4_min, min2(a.v[i], b.v[i]))
F4_LANES(f4_max, max2(a.v[i], b.v[i]))
#undef F4_LANES
static inline void f4_trunc(f4 a, int32_t *out)
{
    out[0] = (int32_t)a.v[0];
    out[1] = (int32_t)a.v[1];
    out[2] = (int32_t)a.v[2];
}
static inline void f4_store3(float *p, f4 a)
{
    p[0] = a.v[0];
    p[1] = a.v[1];
    p[2] = a.v[2];
}
#endif

/* box_half_area of the box lo, hi. */
static inline float f4_half_area(f4 lo, f4 hi)
{
    float e[3];
    f4_store3(e, f4_sub(hi, lo));
    return e[0] >= 0.0f && e[1] >= 0.0f && e[2] >= 0.0f ? e[0] * e[1] + e[1] * e[2] + e[2] * e[0]
                                                         : 0.0f;
}

/* The bin of a ref's (doubled) centroid c = lo + hi on each axis, into bin[0..2]: bin_of for three
 * axes at once. clo is the centroid box's lower corner, scale bin_scale per axis, top nbins - 1 in
 * every lane. */
static inline void bins_of(f4 c, f4 clo, f4 scale, f4 top, int32_t *bin)
{
    f4 f = f4_mul(f4_sub(c, clo), scale);
    /* min(f, top) is f < top ? f : top: the top edge and NaN go to the last bin, as in bin_of. */
    f4_trunc(f4_min(f, top), bin);
}

/* A range of refs that becomes node `node` (its slot is allocated already). box bounds the
 * primitives, cbox their doubled centroids. */
struct task {
    uint32_t begin, end, node;
    int depth;
    struct box box, cbox;
};

struct split {
    int axis, bin;          /* refs whose centroid falls in bins < bin go left */
    float cost;             /* area-weighted block counts: A_l·B(N_l) + A_r·B(N_r) (half areas) */
    struct box left, right; /* bounds of the two sides */
    struct box lc, rc;      /* and of their (doubled) centroids (partition) */
};

/* Bins for a node of n primitives: BINS, but no more than n for small nodes, where the fixed
 * cost of sweeping the bins would otherwise dominate the build. (Fewer for small nodes, 6 up to 16
 * primitives and 12 up to 64, built sphere-1M 5% faster with an equal SAH estimate, but traced
 * spheres-16's primary and shadow rays 1 to 3% slower: bench --medium, 3 runs side by side.) */
static int bin_count(const struct task *t)
{
    uint32_t n = t->end - t->begin;
    return n < BINS ? (int)n : BINS;
}

/* Bin of a centroid coordinate. The float test clamps both the top edge and NaN (from a primitive
 * with non-finite bounds) into the last bin, so the conversion to int is always defined. */
static int bin_of(float c, float lo, float scale, int nbins)
{
    float f = (c - lo) * scale;
    return f < (float)(nbins - 1) ? (int)f : nbins - 1;
}

static float bin_scale(const struct box *cbox, int axis, int nbins)
{
    float ext = cbox->hi[axis] - cbox->lo[axis];
    /* Slightly less than nbins/ext so the largest centroid maps into the last bin, not past it. */
    return ext > 0.0f ? (float)nbins * 0.99999f / ext : 0.0f;
}

/* Bin boxes and counts per axis. */
struct bins {
    f4 lo[3][BINS], hi[3][BINS];
    uint32_t cnt[3][BINS];
};

/* How a node's refs are binned: the centroid box's lower corner, bin_scale per axis, nbins - 1. */
struct binning {
    f4 lo, scale, top;
    int nbins;
};

static void bins_clear(struct bins *b, int nbins)
{
    f4 lo = f4_set(INFINITY, INFINITY, INFINITY), hi = f4_set(-INFINITY, -INFINITY, -INFINITY);
    int axis, i;
    for (axis = 0; axis < 3; axis++)
        for (i = 0; i < nbins; i++) {
            b->lo[axis][i] = lo;
            b->hi[axis][i] = hi;
            b->cnt[axis][i] = 0;
        }
}

/* Add the ref r to b, binned as bn says. Written out per axis: -O2 does not unroll the loop,
 * whose index arithmetic then costs as much as the update. */
static inline void bin_ref(struct bins *b, const struct binning *bn, const struct ref *r)
{
    f4 lo = f4_load3(r->lo), hi = f4_load(r->hi);
    int32_t i[4];
    bins_of(f4_add(lo, hi), bn->lo, bn->scale, bn->top, i);
    b->lo[0][i[0]] = f4_min(b->lo[0][i[0]], lo);
    b->hi[0][i[0]] = f4_max(b->hi[0][i[0]], hi);
    b->cnt[0][i[0]]++;
    b->lo[1][i[1]] = f4_min(b->lo[1][i[1]], lo);
    b->hi[1][i[1]] = f4_max(b->hi[1][i[1]], hi);
    b->cnt[1][i[1]]++;
    b->lo[2][i[2]] = f4_min(b->lo[2][i[2]], lo);
    b->hi[2][i[2]] = f4_max(b->hi[2][i[2]], hi);
    b->cnt[2][i[2]]++;
}

static void bins_merge(struct bins *into, const struct bins *b, int nbins)
{
    int axis, i;
    for (axis = 0; axis < 3; axis++)
        for (i = 0; i < nbins; i++) {
            into->lo[axis][i] = f4_min(into->lo[axis][i], b->lo[axis][i]);
            into->hi[axis][i] = f4_max(into->hi[axis][i], b->hi[axis][i]);
            into->cnt[axis][i] += b->cnt[axis][i];
        }
}

/* Ranges of at least PAIRED_MIN refs are binned two refs at a time into two sets of bins, merged
 * at the end. Consecutive refs of a mesh lie side by side and fall into the same bins, so that
 * each bin's update waits for the one before it, through memory (a load, min and store chain a
 * ref); two sets make two independent chains. Measured (bench --build-only, cycles of the binary
 * build's nodes of more than 4,096 primitives, sphere-1M): 250 M -> 195 M (4 sets: 215 M). Below
 * a few hundred refs, clearing and merging the second set costs what it saves. */
enum { PAIRED_MIN = 512 };

/* Add refs[begin, end) to b. */
static void bin_refs(struct bins *b, const struct binning *bn, const struct ref *refs,
                     uint32_t begin, uint32_t end)
{
    uint32_t k = begin;
    if (end - begin >= PAIRED_MIN) {
        struct bins b2;
        bins_clear(&b2, bn->nbins);
        for (; k + 1 < end; k += 2) {
            bin_ref(b, bn, &refs[k]);
            bin_ref(&b2, bn, &refs[k + 1]);
        }
        bins_merge(b, &b2, bn->nbins);
    }
    for (; k < end; k++)
        bin_ref(b, bn, &refs[k]);
}

/* Run fn(ctx, c) for c = 0..n-1 on up to `threads` threads (the caller's included), taking the
 * items from an atomic counter; returns when all are done. With threads < 2, or if no thread
 * can be started, the caller runs them all. */
struct par_for {
    void (*fn)(void *ctx, size_t item);
    void *ctx;
    size_t n;
    mc_atomic_size next;
};

static void *par_for_worker(void *arg)
{
    struct par_for *p = arg;
    size_t i;
    while ((i = mc_atomic_fetch_add(&p->next, 1)) < p->n)
        p->fn(p->ctx, i);
    return NULL;
}

static void parallel_for(int threads, size_t n, void (*fn)(void *ctx, size_t item), void *ctx)
{
    pthread_t tid[MAX_BUILD_THREADS];
    struct par_for p;
    int t, started = 0;
    p.fn = fn;
    p.ctx = ctx;
    p.n = n;
    p.next = 0;
    if (threads > MAX_BUILD_THREADS)
        threads = MAX_BUILD_THREADS;
    if ((size_t)threads > n)
        threads = (int)n;
    for (t = 1; t < threads; t++) {
        if (pthread_create(&tid[started], NULL, par_for_worker, &p) != 0)
            break;
        started++;
    }
    par_for_worker(&p);
    for (t = 0; t < started; t++)
        pthread_join(tid[t], NULL);
}

/* Nodes of more than BIN_CHUNK refs are binned a chunk at a time, each chunk into its own bins,
 * which are then merged in chunk order: the chunks can go to different threads, and as the chunks
 * do not depend on the number of threads, neither does the result (min and max are not
 * associative for signed zeros and NaN). Small enough that the thread-independence test's scene
 * (about 10^4 primitives) is binned in several chunks; merging a chunk's bins costs about as much
 * as binning 50 refs. */
enum { BIN_CHUNK = 4096 };

struct chunked_binning {
    const struct binning *bn;
    const struct ref *refs;
    uint32_t begin, end;
    struct bins *bins; /* one per chunk */
};

static void bin_chunk(void *ctx, size_t c)
{
    struct chunked_binning *cb = ctx;
    uint32_t begin = cb->begin + (uint32_t)c * BIN_CHUNK;
    uint32_t end = cb->end - begin > BIN_CHUNK ? begin + BIN_CHUNK : cb->end;
    bins_clear(&cb->bins[c], cb->bn->nbins);
    bin_refs(&cb->bins[c], cb->bn, cb->refs, begin, end);
}

/* Bin refs[t->begin, t->end) into b, on up to `threads` threads for large nodes; returns 0 when
 * out of memory. */
static int bin_node(struct bins *b, const struct binning *bn, const struct ref *refs,
                    const struct task *t, int threads)
{
    uint32_t n = t->end - t->begin;
    size_t nchunks = (n + (size_t)BIN_CHUNK - 1) / BIN_CHUNK, c;
    struct chunked_binning cb;
    bins_clear(b, bn->nbins);
    if (nchunks <= 1) {
        bin_refs(b, bn, refs, t->begin, t->end);
        return 1;
    }
    cb.bn = bn;
    cb.refs = refs;
    cb.begin = t->begin;
    cb.end = t->end;
    cb.bins = mc_malloc(nchunks * sizeof *cb.bins);
    if (!cb.bins)
        return 0;
    parallel_for(threads, nchunks, bin_chunk, &cb);
    for (c = 0; c < nchunks; c++)
        bins_merge(b, &cb.bins[c], bn->nbins);
    free(cb.bins);
    return 1;
}

/* The cheapest bin boundary over all three axes; returns 0 when no boundary separates anything
 * (all centroids coincide), -1 when out of memory. */
static int find_split(const struct ref *refs, const struct task *t, int threads,
                      struct split *best)
{
    struct bins bins;
    struct binning bn;
    float scale[3];
    int axis, i, nbins = bin_count(t), found = 0;
    f4 empty_lo = f4_set(INFINITY, INFINITY, INFINITY),
       empty_hi = f4_set(-INFINITY, -INFINITY, -INFINITY);

    for (axis = 0; axis < 3; axis++)
        scale[axis] = bin_scale(&t->cbox, axis, nbins);
    bn.lo = f4_set(t->cbox.lo[0], t->cbox.lo[1], t->cbox.lo[2]);
    bn.scale = f4_set(scale[0], scale[1], scale[2]);
    bn.top = f4_set((float)(nbins - 1), (float)(nbins - 1), (float)(nbins - 1));
    bn.nbins = nbins;
    if (!bin_node(&bins, &bn, refs, t, threads))
        return -1;
    for (axis = 0; axis < 3; axis++) {
        float right_cost[BINS];
        f4 alo = empty_lo, ahi = empty_hi;
        uint32_t n = 0, left_n = 0;
        if (scale[axis] == 0.0f)
            continue;
        /* Sweep from the right: right_cost[i] is the cost of bins i..nbins-1 as one side. */
        for (i = nbins - 1; i > 0; i--) {
            alo = f4_min(alo, bins.lo[axis][i]);
            ahi = f4_max(ahi, bins.hi[axis][i]);
            n += bins.cnt[axis][i];
            right_cost[i] = f4_half_area(alo, ahi) * leaf_tests(n);
        }
        alo = empty_lo;
        ahi = empty_hi;
        for (i = 1; i < nbins; i++) {
            float cost;
            alo = f4_min(alo, bins.lo[axis][i - 1]);
            ahi = f4_max(ahi, bins.hi[axis][i - 1]);
            left_n += bins.cnt[axis][i - 1];
            if (left_n == 0 || left_n == t->end - t->begin)
                continue;
            cost = f4_half_area(alo, ahi) * leaf_tests(left_n) + right_cost[i];
            if (!found || cost < best->cost) {
                found = 1;
                best->axis = axis;
                best->bin = i;
                best->cost = cost;
            }
        }
    }
    if (found) {
        f4 llo = empty_lo, lhi = empty_hi, rlo = empty_lo, rhi = empty_hi;
        const int a = best->axis;
        for (i = 0; i < best->bin; i++) {
            llo = f4_min(llo, bins.lo[a][i]);
            lhi = f4_max(lhi, bins.hi[a][i]);
        }
        for (; i < nbins; i++) {
            rlo = f4_min(rlo, bins.lo[a][i]);
            rhi = f4_max(rhi, bins.hi[a][i]);
        }
        f4_store3(best->left.lo, llo);
        f4_store3(best->left.hi, lhi);
        f4_store3(best->right.lo, rlo);
        f4_store3(best->right.hi, rhi);
    }
    return found;
}

/* The doubled centroid of ref r, lanes 0..2. */
static inline f4 ref_centroid(const struct ref *r)
{
    return f4_add(f4_load3(r->lo), f4_load(r->hi));
}

/* Partition refs by the split, and bound the two sides' (doubled) centroids into s->lc and s->rc;
 * returns the first index of the right side. Hoare's scheme: each ref is read once, and only
 * those on the wrong side are written, swapped in pairs. */
static uint32_t partition(struct ref *refs, const struct task *t, struct split *s)
{
    int nbins = bin_count(t), axis = s->axis, bin = s->bin;
    float lo = t->cbox.lo[axis], scale = bin_scale(&t->cbox, axis, nbins);
    uint32_t l = t->begin, r = t->end;
    f4 llo = f4_set(INFINITY, INFINITY, INFINITY), lhi = f4_set(-INFINITY, -INFINITY, -INFINITY);
    f4 rlo = llo, rhi = lhi;
    for (;;) {
        f4 cl, cr;
        struct ref x;
        /* cl, cr: the centroids of the refs that stop the two scans, a right one and a left. */
        for (; l < r; l++) {
            cl = ref_centroid(&refs[l]);
            if (bin_of(refs[l].lo[axis] + refs[l].hi[axis], lo, scale, nbins) >= bin)
                break;
            llo = f4_min(llo, cl);
            lhi = f4_max(lhi, cl);
        }
        for (; l < r; r--) {
            cr = ref_centroid(&refs[r - 1]);
            if (bin_of(refs[r - 1].lo[axis] + refs[r - 1].hi[axis], lo, scale, nbins) < bin)
                break;
            rlo = f4_min(rlo, cr);
            rhi = f4_max(rhi, cr);
        }
        if (l >= r)
            break;
        x = refs[l];
        refs[l] = refs[r - 1];
        refs[r - 1] = x;
        llo = f4_min(llo, cr);
        lhi = f4_max(lhi, cr);
        rlo = f4_min(rlo, cl);
        rhi = f4_max(rhi, cl);
        l++;
        r--;
    }
    f4_store3(s->lc.lo, llo);
    f4_store3(s->lc.hi, lhi);
    f4_store3(s->rc.lo, rlo);
    f4_store3(s->rc.hi, rhi);
    return l;
}

/* Bounds and centroid bounds of refs[begin, end). */
static void range_bounds(const struct ref *refs, uint32_t begin, uint32_t end, struct box *box,
                         struct box *cbox)
{
    uint32_t k;
    *box = *cbox = box_empty();
    for (k = begin; k < end; k++) {
        float c[3];
        int a;
        for (a = 0; a < 3; a++)
            c[a] = refs[k].lo[a] + refs[k].hi[a];
        box_grow(box, refs[k].lo, refs[k].hi);
        box_grow(cbox, c, c);
    }
}

static void set_node_box(struct bnode *n, const struct box *b)
{
    int a;
    for (a = 0; a < 3; a++) {
        n->b[a] = b->lo[a];
        n->b[a + 3] = b->hi[a];
    }
}

/* Memory for one of the build's large arrays, 64-byte aligned; NULL when out of memory. Arrays of
 * at least HUGE_MIN bytes are aligned to 2 MB and offered to Linux's transparent huge pages
 * (madvise; a no-op where they are off), as Embree does for its BVH and build memory: on 4 KB
 * pages, first touching a 1M-triangle build's arrays took some 45,000 page faults, a quarter of
 * its time, and a ray through a large scene misses the TLB on most of the few nodes and blocks
 * it reads far apart. Smaller arrays stay on small pages, where rounding up to 2 MB would cost
 * more memory than the TLB saves. */
#define HUGE_PAGE ((size_t)2 << 20)
#define HUGE_MIN (4 * HUGE_PAGE)
static void *alloc_large(size_t bytes)
{
    void *p;
    size_t align = 64;
#ifdef MADV_HUGEPAGE
    if (bytes >= HUGE_MIN)
        align = HUGE_PAGE;
#endif
    if (!(p = mc_aligned_alloc(align, bytes)))
        return NULL;
#ifdef MADV_HUGEPAGE
    if (align == HUGE_PAGE)
        (void)madvise(p, bytes, MADV_HUGEPAGE); /* advice only: failure changes nothing */
#endif
    return p;
}

/* How many of the scalar refs of t's range split s sends to the left side, and to the right. */
static void scalar_sides(const struct ref *refs, const struct task *t, const struct split *s,
                         uint32_t *left, uint32_t *right)
{
    int nbins = bin_count(t), axis = s->axis;
    float lo = t->cbox.lo[axis], scale = bin_scale(&t->cbox, axis, nbins);
    uint32_t i;
    *left = *right = 0;
    for (i = t->begin; i < t->end; i++)
        if (refs[i].scalar != 0.0f) {
            if (bin_of(refs[i].lo[axis] + refs[i].hi[axis], lo, scale, nbins) < s->bin)
                ++*left;
            else
                ++*right;
        }
}

/* The binary build of the subtree of task root (root->node is ignored: the subtree's root is
 * node 0, and node 1 is unused) into nodes, which has room for 2 (root->end - root->begin) nodes;
 * returns the number used. Depth first with an explicit stack. With defer > 0, subtrees of more
 * than LEAF_MAX and at most defer primitives are not built but appended to deferred[*ndeferred]
 * with their node slot allocated, for the parallel build to finish. */
static size_t build_nodes(struct bnode *nodes, struct ref *refs, const struct task *root,
                          int threads, uint32_t defer, struct task *deferred, size_t *ndeferred)
{
    struct task stack[BVH_DEPTH_MAX + 1];
    int sp = 0;
    size_t count = 2;

    memset(&nodes[1], 0, sizeof nodes[1]);
    stack[sp] = *root;
    stack[sp].node = 0;
    sp++;
    while (sp > 0) {
        struct task t = stack[--sp];
        struct bnode *node = &nodes[t.node];
        uint32_t size = t.end - t.begin, mid, c = (uint32_t)count, scalar = 0, i;
        struct split s;
        int split_found = 0, leaf = size <= LEAF_MAX;

        if (size <= defer && !leaf) {
            deferred[(*ndeferred)++] = t;
            continue;
        }

        set_node_box(node, &t.box);
        if (leaf)
            for (i = t.begin; i < t.end; i++)
                scalar += refs[i].scalar != 0.0f;
        /* A node of scalar primitives may still gain by a split: each is a test of its own. */
        if (size <= LEAF_MIN && (scalar == 0 || size == 1)) {
            leaf = 1;
        } else if (t.depth < SAH_DEPTH) {
            split_found = find_split(refs, &t, threads, &s);
            if (split_found < 0)
                return 0;
            /* SAH leaf test in units of one 4-wide leaf test, both sides scaled by the node's half
             * area A so that no division is needed: leaf B(N)·A + S·N_s·A against split C_t·A +
             * A_l·B(N_l) + A_r·B(N_r) + S·(A_l·N_sl + A_r·N_sr), B(N) = leaf_tests(N), N_s the
             * scalar primitives and S = SCALAR_COST. Without a split (all centroids coincide) only
             * the size decides. */
            if (split_found && leaf) {
                float area = box_half_area(&t.box);
                uint32_t sl = 0, sr = 0;
                if (scalar) /* triangles and quads only, as most nodes: no sides to count */
                    scalar_sides(refs, &t, &s, &sl, &sr);
                leaf = leaf_cost(size, sl + sr) * area
                       <= COST_TRAVERSE * area + s.cost
                              + SCALAR_COST * (box_half_area(&s.left) * (float)sl
                                               + box_half_area(&s.right) * (float)sr);
            }
        }
        if (leaf) {
            node->index = t.begin;
            node->count = (uint16_t)size;
            node->scalar = (uint16_t)scalar;
            continue;
        }
        if (split_found) {
            mid = partition(refs, &t, &s);
        } else {
            /* Coinciding centroids, or too deep: halve the range as it stands. */
            mid = t.begin + size / 2;
            range_bounds(refs, t.begin, mid, &s.left, &s.lc);
            range_bounds(refs, mid, t.end, &s.right, &s.rc);
        }
        node->index = c;
        node->count = 0;
        node->scalar = 0;
        count += 2;
        stack[sp].begin = mid;
        stack[sp].end = t.end;
        stack[sp].node = c + 1;
        stack[sp].depth = t.depth + 1;
        stack[sp].box = s.right;
        stack[sp].cbox = s.rc;
        sp++;
        stack[sp].begin = t.begin;
        stack[sp].end = mid;
        stack[sp].node = c;
        stack[sp].depth = t.depth + 1;
        stack[sp].box = s.left;
        stack[sp].cbox = s.lc;
        sp++;
    }
    return count;
}

/* The parallel build: the top of the tree is built on the calling thread (its large nodes binned
 * by all the threads, a chunk each, see bin_node) down to subtrees of at most
 * n / (PAR_SPLIT · threads) primitives, which the threads then build independently (their ranges
 * of refs are disjoint), each into its own node array; the arrays are then appended to the top's,
 * in the order of the subtrees, so the tree is the same whatever the number of threads. The top's
 * partitions stay on one thread: per the build's instruction counts (callgrind, sphere of 250k
 * triangles, 2 threads) the calling thread then does 53 to 57% of the work, so 2 threads are at
 * most about 1.8 times as fast as one. */
enum { PAR_MIN = 4096, PAR_SPLIT = 8 };

struct subtree {
    struct task task;      /* task.node: its root's slot in the top array */
    struct bnode *nodes;   /* its own array, node 0 its root */
    size_t count;
};

struct par_build {
    struct ref *refs;
    struct subtree *sub;
    mc_atomic_int failed;  /* out of memory in a worker */
};

static void build_subtree(void *ctx, size_t i)
{
    struct par_build *p = ctx;
    struct subtree *st = &p->sub[i];
    st->nodes = alloc_large(2 * (size_t)(st->task.end - st->task.begin) * sizeof *st->nodes);
    st->count = st->nodes ? build_nodes(st->nodes, p->refs, &st->task, 1, 0, NULL, NULL) : 0;
    if (st->count == 0)
        mc_atomic_store(&p->failed, 1);
}

/* The binary tree over refs[0, n) into nodes (room for 2n), on up to `threads` threads; returns
 * the number of nodes, or 0 when out of memory. */
static size_t build_tree(struct bnode *nodes, struct ref *refs, const struct task *root,
                         int threads)
{
    uint32_t n = root->end - root->begin;
    struct par_build p;
    size_t count, nsub = 0, i, k;

    if (threads > MAX_BUILD_THREADS)
        threads = MAX_BUILD_THREADS;
    if (threads < 2 || n < PAR_MIN)
        return build_nodes(nodes, refs, root, 1, 0, NULL, NULL);
    /* Every deferred subtree has more than LEAF_MAX primitives, so there are fewer than n/LEAF_MAX. */
    p.sub = mc_malloc((n / LEAF_MAX + 1) * sizeof *p.sub);
    if (!p.sub)
        return 0;
    {
        struct task *tasks = mc_malloc((n / LEAF_MAX + 1) * sizeof *tasks);
        if (!tasks) {
            free(p.sub);
            return 0;
        }
        count = build_nodes(nodes, refs, root, threads, n / (PAR_SPLIT * (uint32_t)threads), tasks,
                            &nsub);
        for (i = 0; i < nsub; i++) {
            p.sub[i].task = tasks[i];
            p.sub[i].nodes = NULL;
        }
        free(tasks);
    }
    p.refs = refs;
    mc_atomic_store(&p.failed, count == 0);
    if (count != 0)
        parallel_for(threads, nsub, build_subtree, &p);
    /* Append each subtree: its root goes into the slot reserved for it, its other nodes (from 2
     * on) after the top's, with their child indices moved by the same offset. */
    for (i = 0; i < nsub; i++) {
        struct subtree *st = &p.sub[i];
        size_t off = count - 2;
        if (mc_atomic_load(&p.failed))
            break;
        for (k = 0; k < st->count; k++) {
            struct bnode x = st->nodes[k];
            if (k == 1)
                continue;
            if (x.count == 0)
                x.index += (uint32_t)off;
            nodes[k == 0 ? st->task.node : k + off] = x;
        }
        count += st->count - 2;
    }
    for (i = 0; i < nsub; i++)
        free(p.sub[i].nodes);
    free(p.sub);
    return mc_atomic_load(&p.failed) ? 0 : count;
}

/* Build threads: the processors online, at most MAX_BUILD_THREADS. */
static int build_threads(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > MAX_BUILD_THREADS ? MAX_BUILD_THREADS : (int)n;
}

static float bnode_half_area(const struct bnode *n)
{
    float x = n->b[3] - n->b[0], y = n->b[4] - n->b[1], z = n->b[5] - n->b[2];
    return x * y + y * z + z * x;
}

/* ---- Collapse into the wide BVH ----
 * Which binary nodes become wide nodes, which subtrees become leaves, is chosen by dynamic
 * programming for the least SAH cost of the wide tree (Ylitie, Karras and Laine 2017, "Efficient
 * Incoherent Ray Traversal on GPUs Through Compressed Wide BVHs", §3.1). The greedy collapse it
 * replaces (open the child of largest area until the node is full; Dammertz et al. 2008) left
 * nearly a third of sphere-1M's nodes with two leaves each, below parents already full. */

/* The cost of visiting a wide node, in units of one block test (tri4.h), as COST_TRAVERSE is for
 * the binary build. Measured on sphere-1M's diffuse rays (node visits / block tests per ray): the
 * greedy collapse 10.1 / 2.84 with 82,586 nodes; 0.5: 9.9 / 2.84 with 52,802; 1: 9.8 / 2.93;
 * 2: 9.4 / 3.50 (fewer, fuller nodes over bigger leaves). */
#define COST_WIDE 0.5f

/* The plan for binary node x's subtree: cost[x][i - 1] is the least cost of representing it by at
 * most i slots of a wide node, areas times unit costs as in the SAH. */
struct plan {
    uint32_t first, count;       /* its primitives: prims[order[first .. first + count)] */
    uint8_t leaf;                /* as one slot: 1 a leaf of all of them, 0 a wide node */
    uint8_t scalar;              /* how many of them are scalar (struct ref), at most 255: exact
                                  * where it is read, for at most LEAF_MAX primitives */
    uint8_t node_left;           /* as a wide node: how many of its slots its left child takes */
    uint8_t left[BVH_WIDTH + 1]; /* left[i], i >= 2: in at most i slots, how many the left child
                                  * takes; 0: one slot (the subtree as leaf or node, as `leaf`) */
};

/* Fills plan[x] for every binary node. Children have larger indices than their parent (build_nodes
 * allocates them after it, build_tree appends subtrees after the top), so one pass from the last
 * node back sees every child before its parent. Node 1 is unused. */
static void plan_collapse(const struct bnode *bn, size_t count, struct plan *plan,
                          float (*cost)[BVH_WIDTH])
{
    size_t x = count;
    while (x-- > 0) {
        const struct bnode *b = &bn[x];
        struct plan *p = &plan[x];
        float area = bnode_half_area(b), dist[BVH_WIDTH + 1], as_leaf, as_node;
        uint8_t dist_left[BVH_WIDTH + 1];
        uint32_t l = b->index, r = b->index + 1;
        int i, k;
        if (x == 1)
            continue;
        memset(p->left, 0, sizeof p->left);
        if (b->count) {
            p->first = b->index;
            p->count = b->count;
            p->leaf = 1;
            p->scalar = (uint8_t)b->scalar;
            p->node_left = 0;
            for (i = 0; i < BVH_WIDTH; i++)
                cost[x][i] = area * leaf_cost(b->count, b->scalar);
            continue;
        }
        p->first = plan[l].first;
        p->count = plan[l].count + plan[r].count;
        p->scalar = (uint8_t)(plan[l].scalar + plan[r].scalar < 255u ? plan[l].scalar + plan[r].scalar
                                                                      : 255u);
        /* dist[i]: the two children's subtrees in at most i slots together. */
        for (i = 2; i <= BVH_WIDTH; i++) {
            dist[i] = INFINITY;
            dist_left[i] = 1;
            for (k = 1; k < i; k++) {
                float c = cost[l][k - 1] + cost[r][i - k - 1];
                if (c < dist[i]) {
                    dist[i] = c;
                    dist_left[i] = (uint8_t)k;
                }
            }
        }
        /* One slot: a leaf (a subtree of at most LEAF_MAX primitives, which are consecutive), or a
         * wide node whose slots the children share. */
        as_leaf = p->count <= LEAF_MAX ? area * leaf_cost(p->count, p->scalar) : INFINITY;
        as_node = COST_WIDE * area + dist[BVH_WIDTH];
        p->leaf = as_leaf <= as_node;
        p->node_left = dist_left[BVH_WIDTH];
        cost[x][0] = p->leaf ? as_leaf : as_node;
        for (i = 2; i <= BVH_WIDTH; i++) {
            int split = dist[i] < cost[x][0];
            cost[x][i - 1] = split ? dist[i] : cost[x][0];
            p->left[i] = split ? dist_left[i] : 0;
        }
    }
}

enum { PREFETCH_AHEAD = 32 };

struct collapse {
    const struct bnode *bn;
    const struct plan *plan;
    const struct prim *prims;
    const uint32_t *order; /* the primitives' indices in leaf order */
    size_t n, ahead;       /* order's length; primitives order[0, ahead) are prefetched */
    struct bvh_node *nodes;
    size_t node_count;
    struct tri4 *tri4;
    size_t tri4_count;
};

/* The binary nodes whose subtrees fill the at most `slots` slots that binary node x takes, by its
 * plan, into out[*k], left to right. */
static void gather_slots(const struct collapse *c, uint32_t x, int slots, uint32_t *out, int *k)
{
    int left = slots >= 2 ? c->plan[x].left[slots] : 0;
    if (left == 0) {
        out[(*k)++] = x;
        return;
    }
    gather_slots(c, c->bn[x].index, left, out, k);
    gather_slots(c, c->bn[x].index + 1, slots - left, out, k);
}

/* The wide node for binary node x (and, recursively, its subtree) into c->nodes; returns its
 * index. A node of one leaf is the root of a tree that is one leaf. Nodes are numbered in
 * pre-order, the root 0; leaves get their blocks (tri4.h) in the same order, which is the
 * order's. The recursion is no deeper than the binary tree. */
static uint32_t emit_node(struct collapse *c, uint32_t x)
{
    const struct plan *p = &c->plan[x];
    uint32_t slot[BVH_WIDTH], wi = (uint32_t)c->node_count++;
    struct bvh_node *w = &c->nodes[wi];
    int k = 0, i, a;

    if (p->leaf) {
        slot[k++] = x;
    } else {
        gather_slots(c, c->bn[x].index, p->node_left, slot, &k);
        gather_slots(c, c->bn[x].index + 1, BVH_WIDTH - p->node_left, slot, &k);
    }
    memset(w, 0, sizeof *w);
    for (i = 0; i < BVH_WIDTH; i++)
        for (a = 0; a < 3; a++) {
            w->b[a][i] = i < k ? c->bn[slot[i]].b[a] : INFINITY;
            w->b[a + 3][i] = i < k ? c->bn[slot[i]].b[a + 3] : -INFINITY;
        }
    for (i = 0; i < k; i++) {
        const struct plan *q = &c->plan[slot[i]];
        if (q->leaf) {
            w->count[i] = (uint8_t)q->count;
            w->child[i] = (uint32_t)c->tri4_count;
            /* The leaves come in the order's order, and the primitives they read are scattered:
             * asked for PREFETCH_AHEAD ahead, they arrive together rather than one by one. */
            for (; c->ahead < c->n && c->ahead < (size_t)q->first + q->count + PREFETCH_AHEAD;
                 c->ahead++)
                MC_PREFETCH(&c->prims[c->order[c->ahead]]);
            mc_tri4_fill(&c->tri4[c->tri4_count], c->prims, c->order + q->first, q->count);
            c->tri4_count += mc_tri4_blocks(q->count);
        } else {
            w->child[i] = emit_node(c, slot[i]);
        }
    }
    return wi;
}

/* The wide BVH over the binary tree bn[0, count) into b: nodes and blocks. order (from malloc,
 * of order_bytes) holds the n primitives' indices in leaf order; the memory after them is the
 * collapse's scratch, given back before the wide nodes are made (peak memory), and order is freed
 * at the end. Returns 0 when out of memory (b is then left for mc_bvh_free). */
static int collapse(const struct bnode *bn, size_t count, const struct prim *prims,
                    uint32_t *order, size_t n, size_t order_bytes, struct bvh *b)
{
    struct collapse c;
    /* The costs go into the scratch memory when they fit: pages already mapped, where fresh ones
     * would cost a page fault each (about 1.5 us on this project's machine, 260 of a
     * 65,536-triangle build's). */
    size_t cost_bytes = count * sizeof(float[BVH_WIDTH]);
    size_t scratch_at = (n * sizeof *order + 63) / 64 * 64;
    int in_scratch = scratch_at + cost_bytes <= order_bytes;
    float (*cost)[BVH_WIDTH] = in_scratch ? (void *)((char *)order + scratch_at)
                                          : mc_malloc(cost_bytes);
    struct plan *plan = mc_malloc(count * sizeof *plan);
    /* Bounds: each wide node but a one-leaf root makes one binary inner node a wide node; merging
     * leaves never adds blocks (ceil((a + b)/4) <= ceil(a/4) + ceil(b/4)). */
    size_t inner = (count - 2) / 2, blocks = 0, i;
    if (cost && plan)
        plan_collapse(bn, count, plan, cost);
    if (!in_scratch)
        free(cost);
    order = mc_shrink(order, n * sizeof *order);
    if (!cost || !plan) {
        free(plan);
        free(order);
        return 0;
    }
    for (i = 0; i < count; i++)
        blocks += bn[i].count ? mc_tri4_blocks(bn[i].count) : 0;
    c.bn = bn;
    c.plan = plan;
    c.prims = prims;
    c.order = order;
    c.n = n;
    c.ahead = 0;
    c.node_count = c.tri4_count = 0;
    c.nodes = alloc_large((inner > 1 ? inner : 1) * sizeof *c.nodes);
    c.tri4 = alloc_large(blocks * sizeof *c.tri4);
    if (c.nodes && c.tri4)
        emit_node(&c, 0);
    free(plan);
    free(order);
    /* Give back the unused tails. A shrinking realloc keeps the block in place in practice; if it
     * moved, the arrays would still be 16-byte aligned, which is all the SIMD loads assume. */
    b->nodes = mc_shrink(c.nodes, c.node_count * sizeof *c.nodes);
    b->node_count = c.node_count;
    b->tri4 = mc_shrink(c.tri4, c.tri4_count * sizeof *c.tri4);
    b->tri4_count = c.tri4_count;
    return c.nodes && c.tri4;
}

/* The refs of the primitives, BIN_CHUNK at a time on the build's threads, with each chunk's
 * bounds and centroid bounds, merged in chunk order as the binning's are. */
struct ref_setup {
    struct ref *refs;
    const struct prim *prims;
    const struct aabb *bounds;
    size_t n;
    struct box *box; /* per chunk: bounds, then centroid bounds */
};

static void setup_chunk(void *ctx, size_t c)
{
    struct ref_setup *rs = ctx;
    size_t i, end = (c + 1) * BIN_CHUNK < rs->n ? (c + 1) * BIN_CHUNK : rs->n;
    struct box box = box_empty(), cbox = box_empty();
    for (i = c * BIN_CHUNK; i < end; i++) {
        struct aabb pb = rs->bounds ? rs->bounds[i] : mc_prim_bounds(&rs->prims[i]);
        struct ref *r = &rs->refs[i];
        float cc[3];
        int a;
        r->lo[0] = pb.lo.x;
        r->lo[1] = pb.lo.y;
        r->lo[2] = pb.lo.z;
        r->hi[0] = pb.hi.x;
        r->hi[1] = pb.hi.y;
        r->hi[2] = pb.hi.z;
        r->id = (uint32_t)i;
        r->scalar = mc_tri4_simd_kind(rs->prims[i].kind) ? 0.0f : 1.0f;
        for (a = 0; a < 3; a++)
            cc[a] = r->lo[a] + r->hi[a];
        box_grow(&box, r->lo, r->hi);
        box_grow(&cbox, cc, cc);
    }
    rs->box[2 * c] = box;
    rs->box[2 * c + 1] = cbox;
}

mcrt_status mc_bvh_build_threads(struct bvh *b, const struct prim *prims,
                                 const struct aabb *bounds, size_t n, int threads, mc_diag *d)
{
    struct ref *refs;
    struct bnode *bin;
    struct task root;
    uint32_t *order;
    size_t bin_count;
    struct box box = box_empty(), cbox = box_empty();
    size_t i;

    b->nodes = NULL;
    b->node_count = 0;
    b->tri4 = NULL;
    b->tri4_count = 0;
    b->bounds = aabb_empty();
    if (n == 0)
        return MCRT_OK;
    if (n > UINT32_MAX / 2)
        return mc_fail(d, MCRT_ERR_INVALID, "too many primitives for the BVH (%zu)", n);
    if (threads <= 0)
        threads = build_threads();
    refs = alloc_large(n * sizeof *refs);
    bin = alloc_large(2 * n * sizeof *bin);
    if (!refs || !bin) {
        free(refs);
        free(bin);
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory building the BVH of %zu primitives", n);
    }
    {
        struct ref_setup rs;
        size_t nchunks = (n + BIN_CHUNK - 1) / BIN_CHUNK, c;
        rs.refs = refs;
        rs.prims = prims;
        rs.bounds = bounds;
        rs.n = n;
        rs.box = mc_malloc(2 * nchunks * sizeof *rs.box);
        if (!rs.box) {
            free(refs);
            free(bin);
            return mc_fail(d, MCRT_ERR_NOMEM, "out of memory building the BVH of %zu primitives",
                           n);
        }
        parallel_for(threads, nchunks, setup_chunk, &rs);
        for (c = 0; c < nchunks; c++) {
            box_grow(&box, rs.box[2 * c].lo, rs.box[2 * c].hi);
            box_grow(&cbox, rs.box[2 * c + 1].lo, rs.box[2 * c + 1].hi);
        }
        free(rs.box);
    }
    root.begin = 0;
    root.end = (uint32_t)n;
    root.node = 0;
    root.depth = 0;
    root.box = box;
    root.cbox = cbox;
    bin_count = build_tree(bin, refs, &root, threads);
    if (bin_count == 0) {
        free(refs);
        free(bin);
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory building the BVH of %zu primitives", n);
    }
    /* The refs are now in leaf order: their storage becomes the order, the primitives' indices
     * in leaf order, which the blocks are made from; the primitives are not moved. */
    order = (uint32_t *)refs;
    for (i = 0; i < n; i++)
        order[i] = refs[i].id;
    if (!collapse(bin, bin_count, prims, order, n, n * sizeof *refs, b)) {
        free(bin);
        mc_bvh_free(b);
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory building the BVH of %zu primitives", n);
    }
    free(bin);
    b->bounds.lo = v3(box.lo[0], box.lo[1], box.lo[2]);
    b->bounds.hi = v3(box.hi[0], box.hi[1], box.hi[2]);
    return MCRT_OK;
}

mcrt_status mc_bvh_build_bounds(struct bvh *b, const struct prim *prims, const struct aabb *bounds,
                                size_t n, mc_diag *d)
{
    return mc_bvh_build_threads(b, prims, bounds, n, 0, d);
}

mcrt_status mc_bvh_build(struct bvh *b, const struct prim *prims, size_t n, mc_diag *d)
{
    return mc_bvh_build_threads(b, prims, NULL, n, 0, d);
}

void mc_bvh_free(struct bvh *b)
{
    free(b->nodes);
    free(b->tri4);
    b->nodes = NULL;
    b->node_count = 0;
    b->tri4 = NULL;
    b->tri4_count = 0;
}
