/* bvh.c: binned-SAH BVH build (Wald 2007, "On fast Construction of SAH-based Bounding Volume
 * Hierarchies") into one depth-first array of 32-byte nodes, and single-ray traversal of static
 * primitives and of moving ones (tested in their time-0 frame). */
#include "geom/bvh.h"

#include <stdlib.h>
#include <string.h>

#include "geom/bvh_node.h"
#include "geom/motion.h"

enum {
    BINS = 16,       /* SAH candidates per axis; Wald 2007 finds 16 within a few % of a full sweep */
    LEAF_MIN = 2,    /* a node of at most this many primitives is always a leaf */
    LEAF_MAX = 8,    /* the SAH may choose a leaf of up to this many */
    SAH_DEPTH = 32,  /* below this depth nodes split at the median index (see DEPTH_MAX) */
    /* From depth SAH_DEPTH on every split halves the count, so a node of n < 2^31 primitives
     * reaches LEAF_MAX after at most 28 more levels: no node is deeper than 60. A traversal pushes
     * at most one node per level, so its stack of DEPTH_MAX entries cannot overflow. */
    DEPTH_MAX = 64
};
/* SAH cost of visiting an inner node (two box tests), in units of one primitive test. */
#define COST_TRAVERSE 1.0f

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

/* A primitive during the build: its bounds and original index. Centroids are used doubled,
 * lo + hi, which saves a multiplication and changes no decision. */
struct ref {
    float lo[3];
    uint32_t id;
    float hi[3];
};

/* A range of refs that becomes node `node` (its slot is allocated already). box bounds the
 * primitives, cbox their doubled centroids. */
struct task {
    uint32_t begin, end, node;
    int depth;
    struct box box, cbox;
};

struct split {
    int axis, bin;          /* refs whose centroid falls in bins < bin go left */
    float cost;             /* area-weighted counts: A_l·N_l + A_r·N_r (half areas) */
    struct box left, right; /* bounds of the two sides */
};

/* Bins for a node of n primitives: BINS, but no more than n for small nodes, where the fixed
 * cost of sweeping the bins would otherwise dominate the build. */
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

/* The cheapest bin boundary over all three axes; returns 0 when no boundary separates anything
 * (all centroids coincide). */
static int find_split(const struct ref *refs, const struct task *t, struct split *best)
{
    struct box bins[3][BINS];
    uint32_t cnt[3][BINS];
    float scale[3];
    int axis, i, nbins = bin_count(t), found = 0;
    uint32_t k;

    for (axis = 0; axis < 3; axis++) {
        scale[axis] = bin_scale(&t->cbox, axis, nbins);
        for (i = 0; i < nbins; i++) {
            bins[axis][i] = box_empty();
            cnt[axis][i] = 0;
        }
    }
    for (k = t->begin; k < t->end; k++) {
        const struct ref *r = &refs[k];
        int bx = bin_of(r->lo[0] + r->hi[0], t->cbox.lo[0], scale[0], nbins);
        int by = bin_of(r->lo[1] + r->hi[1], t->cbox.lo[1], scale[1], nbins);
        int bz = bin_of(r->lo[2] + r->hi[2], t->cbox.lo[2], scale[2], nbins);
        box_grow(&bins[0][bx], r->lo, r->hi);
        box_grow(&bins[1][by], r->lo, r->hi);
        box_grow(&bins[2][bz], r->lo, r->hi);
        cnt[0][bx]++;
        cnt[1][by]++;
        cnt[2][bz]++;
    }
    for (axis = 0; axis < 3; axis++) {
        float right_cost[BINS];
        struct box acc = box_empty();
        uint32_t n = 0, left_n = 0;
        if (scale[axis] == 0.0f)
            continue;
        /* Sweep from the right: right_cost[i] is the cost of bins i..nbins-1 as one side. */
        for (i = nbins - 1; i > 0; i--) {
            box_grow(&acc, bins[axis][i].lo, bins[axis][i].hi);
            n += cnt[axis][i];
            right_cost[i] = box_half_area(&acc) * (float)n;
        }
        acc = box_empty();
        for (i = 1; i < nbins; i++) {
            float cost;
            box_grow(&acc, bins[axis][i - 1].lo, bins[axis][i - 1].hi);
            left_n += cnt[axis][i - 1];
            if (left_n == 0 || left_n == t->end - t->begin)
                continue;
            cost = box_half_area(&acc) * (float)left_n + right_cost[i];
            if (!found || cost < best->cost) {
                found = 1;
                best->axis = axis;
                best->bin = i;
                best->cost = cost;
            }
        }
    }
    if (found) {
        best->left = best->right = box_empty();
        for (i = 0; i < nbins; i++)
            box_grow(i < best->bin ? &best->left : &best->right, bins[best->axis][i].lo,
                     bins[best->axis][i].hi);
    }
    return found;
}

/* Partition refs by the split; returns the first index of the right side and fills the
 * children's centroid bounds. */
static uint32_t partition(struct ref *refs, const struct task *t, const struct split *s,
                          struct box *lc, struct box *rc)
{
    int nbins = bin_count(t);
    float lo = t->cbox.lo[s->axis], scale = bin_scale(&t->cbox, s->axis, nbins);
    uint32_t i = t->begin, j = t->end;
    *lc = *rc = box_empty();
    while (i < j) {
        float c[3];
        int a;
        for (a = 0; a < 3; a++)
            c[a] = refs[i].lo[a] + refs[i].hi[a];
        if (bin_of(c[s->axis], lo, scale, nbins) < s->bin) {
            box_grow(lc, c, c);
            i++;
        } else {
            struct ref tmp = refs[i];
            refs[i] = refs[--j];
            refs[j] = tmp;
            box_grow(rc, c, c);
        }
    }
    return i;
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

static void set_node_box(struct bvh_node *n, const struct box *b)
{
    int a;
    for (a = 0; a < 3; a++) {
        n->b[a] = b->lo[a];
        n->b[a + 3] = b->hi[a];
    }
}

/* Reorder prims so that prims[k] becomes the old prims[order[k]], following the permutation's
 * cycles in place (order is consumed: each entry is set to its own index once placed). */
static void permute_prims(struct prim *prims, uint32_t *order, uint32_t n)
{
    uint32_t i, j, k;
    for (i = 0; i < n; i++) {
        struct prim tmp;
        if (order[i] == i)
            continue;
        tmp = prims[i];
        for (j = i;; j = k) {
            k = order[j];
            order[j] = j;
            if (k == i) {
                prims[j] = tmp;
                break;
            }
            prims[j] = prims[k];
        }
    }
}

/* The build proper, over refs[0, n) into nodes (room for 2n). Depth first with an explicit
 * stack. The root is node 0 and node 1 is padding, so that every sibling pair, allocated together
 * when their parent splits, starts at an even index: with a 64-byte aligned array the two child
 * boxes a traversal tests together share one cache line. */
static size_t build_nodes(struct bvh_node *nodes, struct ref *refs, uint32_t n,
                          const struct box *box, const struct box *cbox)
{
    struct task stack[DEPTH_MAX + 1];
    int sp = 0;
    size_t count = 2;

    memset(&nodes[1], 0, sizeof nodes[1]);
    stack[sp].begin = 0;
    stack[sp].end = n;
    stack[sp].node = 0;
    stack[sp].depth = 0;
    stack[sp].box = *box;
    stack[sp].cbox = *cbox;
    sp++;
    while (sp > 0) {
        struct task t = stack[--sp];
        struct bvh_node *node = &nodes[t.node];
        uint32_t size = t.end - t.begin, mid, c = (uint32_t)count;
        struct split s;
        struct box lc, rc;
        int split_found = 0, leaf = size <= LEAF_MAX;

        set_node_box(node, &t.box);
        if (size <= LEAF_MIN) {
            leaf = 1;
        } else if (t.depth < SAH_DEPTH) {
            split_found = find_split(refs, &t, &s);
            /* SAH leaf test in units of one primitive test, both sides scaled by the node's half
             * area A so that no division is needed: leaf N·A against split C_t·A + A_l·N_l + A_r·N_r.
             * Without a split (all centroids coincide) only the size decides. */
            if (split_found && leaf) {
                float area = box_half_area(&t.box);
                leaf = (float)size * area <= COST_TRAVERSE * area + s.cost;
            }
        }
        if (leaf) {
            node->index = t.begin;
            node->count = (uint16_t)size;
            node->axis = 0;
            continue;
        }
        if (split_found) {
            mid = partition(refs, &t, &s, &lc, &rc);
            node->axis = (uint16_t)s.axis;
        } else {
            /* Coinciding centroids, or too deep: halve the range as it stands. */
            mid = t.begin + size / 2;
            range_bounds(refs, t.begin, mid, &s.left, &lc);
            range_bounds(refs, mid, t.end, &s.right, &rc);
            node->axis = 0;
        }
        node->index = c;
        node->count = 0;
        count += 2;
        stack[sp].begin = mid;
        stack[sp].end = t.end;
        stack[sp].node = c + 1;
        stack[sp].depth = t.depth + 1;
        stack[sp].box = s.right;
        stack[sp].cbox = rc;
        sp++;
        stack[sp].begin = t.begin;
        stack[sp].end = mid;
        stack[sp].node = c;
        stack[sp].depth = t.depth + 1;
        stack[sp].box = s.left;
        stack[sp].cbox = lc;
        sp++;
    }
    return count;
}

mcrt_status mc_bvh_build_bounds(struct bvh *b, struct prim *prims, const struct aabb *bounds,
                                size_t n, mc_diag *d)
{
    struct ref *refs;
    uint32_t *order;
    void *mem = NULL;
    struct box box = box_empty(), cbox = box_empty();
    size_t i;

    b->nodes = NULL;
    b->node_count = 0;
    b->bounds = aabb_empty();
    if (n == 0)
        return MCRT_OK;
    if (n > UINT32_MAX / 2)
        return mc_fail(d, MCRT_ERR_INVALID, "too many primitives for the BVH (%zu)", n);
    refs = malloc(n * sizeof *refs);
    if (!refs || posix_memalign(&mem, 64, 2 * n * sizeof(struct bvh_node)) != 0) {
        free(refs);
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory building the BVH of %zu primitives", n);
    }
    for (i = 0; i < n; i++) {
        struct aabb pb = bounds ? bounds[i] : mc_prim_bounds(&prims[i]);
        float c[3];
        int a;
        refs[i].lo[0] = pb.lo.x;
        refs[i].lo[1] = pb.lo.y;
        refs[i].lo[2] = pb.lo.z;
        refs[i].hi[0] = pb.hi.x;
        refs[i].hi[1] = pb.hi.y;
        refs[i].hi[2] = pb.hi.z;
        refs[i].id = (uint32_t)i;
        for (a = 0; a < 3; a++)
            c[a] = refs[i].lo[a] + refs[i].hi[a];
        box_grow(&box, refs[i].lo, refs[i].hi);
        box_grow(&cbox, c, c);
    }
    b->node_count = build_nodes(mem, refs, (uint32_t)n, &box, &cbox);
    /* Give back the unused tail (leaves hold several primitives). A shrinking realloc keeps the
     * block in place in practice; if it moved, only the cache-line alignment would be lost. */
    b->nodes = realloc(mem, b->node_count * sizeof *b->nodes);
    if (!b->nodes)
        b->nodes = mem;
    b->bounds.lo = v3(box.lo[0], box.lo[1], box.lo[2]);
    b->bounds.hi = v3(box.hi[0], box.hi[1], box.hi[2]);

    /* The refs are now in leaf order; reuse their storage for the permutation. */
    order = (uint32_t *)refs;
    for (i = 0; i < n; i++)
        order[i] = refs[i].id;
    permute_prims(prims, order, (uint32_t)n);
    free(refs);
    return MCRT_OK;
}

mcrt_status mc_bvh_build(struct bvh *b, struct prim *prims, size_t n, mc_diag *d)
{
    return mc_bvh_build_bounds(b, prims, NULL, n, d);
}

void mc_bvh_free(struct bvh *b)
{
    free(b->nodes);
    b->nodes = NULL;
    b->node_count = 0;
}

/* 1 + 4·2^-23: covers the 1 + 2γ3 relative error of the slab distances (Ize, "Robust BVH Ray
 * Traversal", JCGT 2(2) 2013; pbrt-v4 Bounds3::IntersectP) plus the rounding of this product, so
 * a box is never missed by a ray that passes through it. */
#define SLAB_GROW 1.00000048f

/* The ray as the slab test needs it: origin, 1/d (±inf for a zero component) and, per axis, the
 * index into bvh_node.b of the plane the ray enters through (near) and leaves through (far). */
struct slab_ray {
    float o[3], inv[3];
    int near[3], far[3];
};

/* Whether the ray meets box b (lower corner b[0..2], upper b[3..5]) within [0, tmax]; *tnear gets
 * the entry distance. A zero direction component with the origin exactly on a slab plane gives
 * 0·inf = NaN; the comparisons are ordered so that a NaN leaves the interval unchanged, which is
 * right for a ray lying in the (closed) slab. */
static inline int slab(const float *b, const struct slab_ray *s, float tmax, float *tnear)
{
    float tx0 = (b[s->near[0]] - s->o[0]) * s->inv[0];
    float ty0 = (b[s->near[1]] - s->o[1]) * s->inv[1];
    float tz0 = (b[s->near[2]] - s->o[2]) * s->inv[2];
    float tx1 = (b[s->far[0]] - s->o[0]) * s->inv[0];
    float ty1 = (b[s->far[1]] - s->o[1]) * s->inv[1];
    float tz1 = (b[s->far[2]] - s->o[2]) * s->inv[2];
    float t0 = 0.0f, t1 = tmax;
    t0 = tx0 > t0 ? tx0 : t0;
    t0 = ty0 > t0 ? ty0 : t0;
    t0 = tz0 > t0 ? tz0 : t0;
    t1 = tx1 < t1 ? tx1 : t1;
    t1 = ty1 < t1 ? ty1 : t1;
    t1 = tz1 < t1 ? tz1 : t1;
    *tnear = t0;
    return t0 <= t1 * SLAB_GROW;
}

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

/* Shared traversal; any_hit and leaf are constants at each call site, and the function is always
 * inlined, so each caller gets its own specialised copy (leaf(ctx, ...) becomes a direct, inlined
 * primitive test). The slab tests use the world ray r; leaf tests whatever ctx holds for it.
 * Both children are tested at their parent. When both are hit, the one on the near side of the
 * split plane (by the sign of the direction along the split axis) is visited first, and the other
 * is pushed with its entry distance, so that it is skipped if a closer hit is found meanwhile.
 * The ray constants and the current nearest distance live in locals (not behind pointers that the
 * primitive tests could alias), so that they stay in registers. Rays with a non-finite or zero
 * direction, or a non-finite origin, hit nothing. */
static ALWAYS_INLINE int traverse(const struct bvh *b, const struct prim *prims,
                                  const struct ray *r, struct hit *out, int any_hit,
                                  leaf_test leaf, void *ctx)
{
    struct { uint32_t node; float t; } stack[DEPTH_MAX];
    const struct bvh_node *nodes = b->nodes;
    struct slab_ray s;
    struct hit h;
    float tmax = r->tmax, t_root;
    int sp = 0, found = 0, a;
    uint32_t ni = 0;

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
    }
    if (!slab(nodes[0].b, &s, tmax, &t_root))
        return 0;
    h.t = tmax;
    for (;;) {
        const struct bvh_node *n = &nodes[ni];
        if (n->count == 0) {
            const struct bvh_node *c = &nodes[n->index];
            float tl, tr;
            int hl = slab(c[0].b, &s, tmax, &tl), hr = slab(c[1].b, &s, tmax, &tr);
            /* Branches, not arithmetic, choose the next node: a predicted branch lets the
             * processor start loading that node before the box tests have finished, which
             * matters more than the occasional misprediction. */
            if (hl && hr) {
                if (s.inv[n->axis] < 0.0f) {
                    stack[sp].node = n->index;
                    stack[sp].t = tl;
                    ni = n->index + 1;
                } else {
                    stack[sp].node = n->index + 1;
                    stack[sp].t = tr;
                    ni = n->index;
                }
                sp++;
                continue;
            }
            if (hl) {
                ni = n->index;
                continue;
            }
            if (hr) {
                ni = n->index + 1;
                continue;
            }
        } else {
            uint32_t k, end = n->index + n->count;
            for (k = n->index; k < end; k++) {
                if (leaf(ctx, &prims[k], &h)) {
                    if (any_hit)
                        return 1;
                    h.prim = k;
                    found = 1;
                }
            }
            tmax = h.t;
        }
        /* Pop, skipping nodes that start beyond the nearest hit so far. */
        do {
            if (sp == 0) {
                if (found)
                    *out = h;
                return found;
            }
            sp--;
        } while (!(stack[sp].t <= tmax * SLAB_GROW));
        ni = stack[sp].node;
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
