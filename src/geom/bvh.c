/* bvh.c: binned-SAH BVH build (Wald 2007, "On fast Construction of SAH-based Bounding Volume
 * Hierarchies") into one depth-first array of 32-byte nodes, and single-ray traversal. */
#include "geom/bvh.h"

#include <stdlib.h>
#include <string.h>

#include "geom/bvh_node.h"

enum {
    BINS = 16,       /* SAH candidates per axis; Wald 2007 finds 16 within a few % of a full sweep */
    LEAF_MIN = 2,    /* a node of at most this many primitives is always a leaf */
    LEAF_MAX = 8,    /* the SAH may choose a leaf of up to this many */
    SAH_DEPTH = 32,  /* below this depth nodes split at the median index (see DEPTH_MAX) */
    /* From depth SAH_DEPTH on every split halves the count, so a node of n < 2^32 primitives
     * reaches LEAF_MAX after at most 29 more levels: no node is deeper than 61. A traversal pushes
     * at most one node per level, so this stack cannot overflow. */
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

static void box_grow(struct box *b, const float *lo, const float *hi)
{
    int a;
    for (a = 0; a < 3; a++) {
        b->lo[a] = min2(b->lo[a], lo[a]);
        b->hi[a] = max2(b->hi[a], hi[a]);
    }
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

/* Bin of a centroid coordinate. The float test clamps both the top edge and NaN (from a primitive
 * with non-finite bounds) into the last bin, so the conversion to int is always defined. */
static int bin_of(float c, float lo, float scale)
{
    float f = (c - lo) * scale;
    return f < (float)(BINS - 1) ? (int)f : BINS - 1;
}

static float bin_scale(const struct box *cbox, int axis)
{
    float ext = cbox->hi[axis] - cbox->lo[axis];
    /* Slightly less than BINS/ext so the largest centroid maps into the last bin, not past it. */
    return ext > 0.0f ? (float)BINS * 0.99999f / ext : 0.0f;
}

/* The cheapest bin boundary over all three axes; returns 0 when no boundary separates anything
 * (all centroids coincide). */
static int find_split(const struct ref *refs, const struct task *t, struct split *best)
{
    struct box bins[3][BINS];
    uint32_t cnt[3][BINS];
    float scale[3];
    int axis, i, found = 0;
    uint32_t k;

    for (axis = 0; axis < 3; axis++) {
        scale[axis] = bin_scale(&t->cbox, axis);
        for (i = 0; i < BINS; i++) {
            bins[axis][i] = box_empty();
            cnt[axis][i] = 0;
        }
    }
    for (k = t->begin; k < t->end; k++) {
        const struct ref *r = &refs[k];
        for (axis = 0; axis < 3; axis++) {
            int b = bin_of(r->lo[axis] + r->hi[axis], t->cbox.lo[axis], scale[axis]);
            box_grow(&bins[axis][b], r->lo, r->hi);
            cnt[axis][b]++;
        }
    }
    for (axis = 0; axis < 3; axis++) {
        float right_cost[BINS];
        struct box right_box[BINS], acc = box_empty();
        uint32_t n = 0, left_n = 0;
        if (scale[axis] == 0.0f)
            continue;
        /* Sweep from the right: right_cost[i] is the cost of bins i..BINS-1 as one side. */
        for (i = BINS - 1; i > 0; i--) {
            box_grow(&acc, bins[axis][i].lo, bins[axis][i].hi);
            n += cnt[axis][i];
            right_box[i] = acc;
            right_cost[i] = box_half_area(&acc) * (float)n;
        }
        acc = box_empty();
        for (i = 1; i < BINS; i++) {
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
                best->left = acc;
                best->right = right_box[i];
            }
        }
    }
    return found;
}

/* Partition refs by the split; returns the first index of the right side and fills the
 * children's centroid bounds. */
static uint32_t partition(struct ref *refs, const struct task *t, const struct split *s,
                          struct box *lc, struct box *rc)
{
    float lo = t->cbox.lo[s->axis], scale = bin_scale(&t->cbox, s->axis);
    uint32_t i = t->begin, j = t->end;
    *lc = *rc = box_empty();
    while (i < j) {
        float c[3];
        int a;
        for (a = 0; a < 3; a++)
            c[a] = refs[i].lo[a] + refs[i].hi[a];
        if (bin_of(c[s->axis], lo, scale) < s->bin) {
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
        n->b[0][a] = b->lo[a];
        n->b[1][a] = b->hi[a];
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

mcrt_status mc_bvh_build(struct bvh *b, struct prim *prims, size_t n, mc_diag *d)
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
        struct aabb pb = mc_prim_bounds(&prims[i]);
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
    b->nodes = mem;
    b->node_count = build_nodes(b->nodes, refs, (uint32_t)n, &box, &cbox);
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

void mc_bvh_free(struct bvh *b)
{
    free(b->nodes);
    b->nodes = NULL;
    b->node_count = 0;
}

/* Per-ray constants of the slab test. */
struct slab_ray {
    vec3 o, inv;   /* origin and 1/d (±inf for a zero component) */
    int near[3];   /* per axis, which corner (0 = lower) the ray enters through */
};

/* 1 + 4·2^-23: covers the 1 + 2γ3 relative error of the slab distances (Ize, "Robust BVH Ray
 * Traversal", JCGT 2(2) 2013; pbrt-v4 Bounds3::IntersectP) plus the rounding of this product, so
 * a box is never missed by a ray that passes through it. */
#define SLAB_GROW 1.00000048f

/* Entry distance of the ray into box n within [0, tmax], or INFINITY when it misses. A zero
 * direction component with the origin exactly on a slab plane gives 0·inf = NaN; the comparisons
 * are ordered so that a NaN leaves the interval unchanged, which is right for a ray lying in the
 * (closed) slab, and makes a NaN ray visit boxes without ever reporting a hit. */
static inline float slab_enter(const struct bvh_node *n, const struct slab_ray *s, float tmax)
{
    float tx0 = (n->b[s->near[0]][0] - s->o.x) * s->inv.x;
    float ty0 = (n->b[s->near[1]][1] - s->o.y) * s->inv.y;
    float tz0 = (n->b[s->near[2]][2] - s->o.z) * s->inv.z;
    float tx1 = (n->b[1 - s->near[0]][0] - s->o.x) * s->inv.x;
    float ty1 = (n->b[1 - s->near[1]][1] - s->o.y) * s->inv.y;
    float tz1 = (n->b[1 - s->near[2]][2] - s->o.z) * s->inv.z;
    float t0 = 0.0f, t1 = tmax;
    t0 = tx0 > t0 ? tx0 : t0;
    t0 = ty0 > t0 ? ty0 : t0;
    t0 = tz0 > t0 ? tz0 : t0;
    t1 = tx1 < t1 ? tx1 : t1;
    t1 = ty1 < t1 ? ty1 : t1;
    t1 = tz1 < t1 ? tz1 : t1;
    return t0 <= t1 * SLAB_GROW ? t0 : INFINITY;
}

/* Shared traversal; any_hit is a constant at each call site, so the compiler specialises it.
 * Children are tested in pairs at their parent, the nearer one is visited first and the other is
 * pushed with its entry distance, so that it is skipped when a closer hit has been found since. */
static inline int traverse(const struct bvh *b, const struct prim *prims, const struct ray *r,
                           struct hit *h, int any_hit)
{
    struct { uint32_t node; float t; } stack[DEPTH_MAX];
    const struct bvh_node *nodes = b->nodes;
    struct ray_prep q;
    struct slab_ray s;
    int sp = 0, found = 0;
    uint32_t ni = 0;

    if (b->node_count == 0)
        return 0;
    mc_ray_prep(&q, r);
    s.o = r->o;
    s.inv = v3(1.0f / r->d.x, 1.0f / r->d.y, 1.0f / r->d.z);
    s.near[0] = r->d.x < 0.0f;
    s.near[1] = r->d.y < 0.0f;
    s.near[2] = r->d.z < 0.0f;
    h->t = r->tmax;
    if (slab_enter(&nodes[0], &s, h->t) == INFINITY)
        return 0;
    for (;;) {
        const struct bvh_node *n = &nodes[ni];
        if (n->count == 0) {
            uint32_t l = n->index, rr = n->index + 1;
            float tl = slab_enter(&nodes[l], &s, h->t), tr = slab_enter(&nodes[rr], &s, h->t);
            if (tl != INFINITY && tr != INFINITY) {
                if (tr < tl) {
                    uint32_t u = l;
                    float tu = tl;
                    l = rr;
                    rr = u;
                    tl = tr;
                    tr = tu;
                }
                stack[sp].node = rr;
                stack[sp].t = tr;
                sp++;
                ni = l;
                continue;
            }
            if (tl != INFINITY) {
                ni = l;
                continue;
            }
            if (tr != INFINITY) {
                ni = rr;
                continue;
            }
        } else {
            uint32_t k, end = n->index + n->count;
            for (k = n->index; k < end; k++) {
                if (mc_prim_intersect_prep(&prims[k], &q, h)) {
                    if (any_hit)
                        return 1;
                    h->prim = k;
                    found = 1;
                }
            }
        }
        /* Pop, skipping nodes that start beyond the nearest hit so far. */
        do {
            if (sp == 0)
                return found;
            sp--;
        } while (!(stack[sp].t <= h->t * SLAB_GROW));
        ni = stack[sp].node;
    }
}

int mc_bvh_intersect(const struct bvh *b, const struct prim *prims, const struct ray *r,
                     struct hit *h)
{
    return traverse(b, prims, r, h, 0);
}

int mc_bvh_occluded(const struct bvh *b, const struct prim *prims, const struct ray *r)
{
    struct hit h;
    return traverse(b, prims, r, &h, 1);
}
