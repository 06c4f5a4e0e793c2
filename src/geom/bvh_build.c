/* bvh_build.c: binned-SAH binary BVH build (Wald 2007, "On fast Construction of SAH-based Bounding
 * Volume Hierarchies"), parallel over subtrees, collapsed into an 8-wide BVH (Dammertz et al. 2008,
 * "Shallow Bounding Volume Hierarchies for Fast SIMD Ray Tracing of Incoherent Rays"). */
#include "geom/bvh.h"

#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "geom/bvh_node.h"

enum {
    BINS = 16,       /* SAH candidates per axis; Wald 2007 finds 16 within a few % of a full sweep */
    LEAF_MIN = 2,    /* a node of at most this many primitives is always a leaf */
    LEAF_MAX = 8,    /* the SAH may choose a leaf of up to this many */
    MAX_BUILD_THREADS = 64,
    /* Below this depth nodes split at the median index, so that no node is deeper than
     * BVH_DEPTH_MAX: from depth SAH_DEPTH on every split halves the count, and a node of n < 2^31
     * primitives reaches LEAF_MAX after at most 28 more levels, depth 60 at most. */
    SAH_DEPTH = 32
};
/* SAH cost of visiting an inner node (two box tests), in units of one primitive test. */
#define COST_TRAVERSE 1.0f

/* A node of the binary tree the build makes and then collapses: 32 bytes. The two children of an
 * inner node are stored together, at index and index + 1. */
struct bnode {
    float b[6];      /* lower corner x, y, z, then upper corner x, y, z */
    uint32_t index;  /* inner: index of the first child; leaf: index of the first primitive */
    uint32_t count;  /* leaf: number of primitives (>= 1); inner: 0 */
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

static void set_node_box(struct bnode *n, const struct box *b)
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

/* The binary build of the subtree of task root (root->node is ignored: the subtree's root is
 * node 0, and node 1 is unused) into nodes, which has room for 2 (root->end - root->begin) nodes;
 * returns the number used. Depth first with an explicit stack. With defer > 0, subtrees of more
 * than LEAF_MAX and at most defer primitives are not built but appended to deferred[*ndeferred]
 * with their node slot allocated, for the parallel build to finish. */
static size_t build_nodes(struct bnode *nodes, struct ref *refs, const struct task *root,
                          uint32_t defer, struct task *deferred, size_t *ndeferred)
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
        uint32_t size = t.end - t.begin, mid, c = (uint32_t)count;
        struct split s;
        struct box lc, rc;
        int split_found = 0, leaf = size <= LEAF_MAX;

        if (size <= defer && !leaf) {
            deferred[(*ndeferred)++] = t;
            continue;
        }

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
            node->count = size;
            continue;
        }
        if (split_found) {
            mid = partition(refs, &t, &s, &lc, &rc);
        } else {
            /* Coinciding centroids, or too deep: halve the range as it stands. */
            mid = t.begin + size / 2;
            range_bounds(refs, t.begin, mid, &s.left, &lc);
            range_bounds(refs, mid, t.end, &s.right, &rc);
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

/* The parallel build: the top of the tree is built on the calling thread down to subtrees of at
 * most n / (PAR_SPLIT · threads) primitives, which the threads then build independently (their
 * ranges of refs are disjoint), each into its own node array; the arrays are then appended to the
 * top's, in the order of the subtrees, so the tree is the same whatever the number of threads. */
enum { PAR_MIN = 4096, PAR_SPLIT = 8 };

struct subtree {
    struct task task;      /* task.node: its root's slot in the top array */
    struct bnode *nodes;   /* its own array, node 0 its root */
    size_t count;
};

struct par_build {
    struct ref *refs;
    struct subtree *sub;
    size_t nsub;
    size_t next;           /* next subtree to build, taken with an atomic add */
    int failed;            /* out of memory in a worker */
};

static void *build_worker(void *arg)
{
    struct par_build *p = arg;
    for (;;) {
        size_t i = __atomic_fetch_add(&p->next, 1, __ATOMIC_RELAXED);
        struct subtree *st;
        if (i >= p->nsub)
            return NULL;
        st = &p->sub[i];
        st->nodes = malloc(2 * (size_t)(st->task.end - st->task.begin) * sizeof *st->nodes);
        if (!st->nodes) {
            __atomic_store_n(&p->failed, 1, __ATOMIC_RELAXED);
            continue;
        }
        st->count = build_nodes(st->nodes, p->refs, &st->task, 0, NULL, NULL);
    }
}

/* The binary tree over refs[0, n) into nodes (room for 2n), on up to `threads` threads; returns
 * the number of nodes, or 0 when out of memory. */
static size_t build_tree(struct bnode *nodes, struct ref *refs, const struct task *root,
                         int threads)
{
    uint32_t n = root->end - root->begin;
    struct par_build p;
    pthread_t tid[MAX_BUILD_THREADS];
    size_t count, i, k;
    int started = 0, t;

    if (threads > MAX_BUILD_THREADS)
        threads = MAX_BUILD_THREADS;
    if (threads < 2 || n < PAR_MIN)
        return build_nodes(nodes, refs, root, 0, NULL, NULL);
    /* Every deferred subtree has more than LEAF_MAX primitives, so there are fewer than n/LEAF_MAX. */
    p.sub = malloc((n / LEAF_MAX + 1) * sizeof *p.sub);
    if (!p.sub)
        return 0;
    {
        struct task *tasks = malloc((n / LEAF_MAX + 1) * sizeof *tasks);
        if (!tasks) {
            free(p.sub);
            return 0;
        }
        p.nsub = 0;
        count = build_nodes(nodes, refs, root, n / (PAR_SPLIT * (uint32_t)threads), tasks, &p.nsub);
        for (i = 0; i < p.nsub; i++) {
            p.sub[i].task = tasks[i];
            p.sub[i].nodes = NULL;
        }
        free(tasks);
    }
    p.refs = refs;
    p.next = 0;
    p.failed = 0;
    for (t = 1; t < threads; t++) {
        if (pthread_create(&tid[t], NULL, build_worker, &p) != 0)
            break;
        started++;
    }
    build_worker(&p);
    for (t = 1; t <= started; t++)
        pthread_join(tid[t], NULL);
    /* Append each subtree: its root goes into the slot reserved for it, its other nodes (from 2
     * on) after the top's, with their child indices moved by the same offset. */
    for (i = 0; i < p.nsub; i++) {
        struct subtree *st = &p.sub[i];
        size_t off = count - 2;
        if (p.failed)
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
    for (i = 0; i < p.nsub; i++)
        free(p.sub[i].nodes);
    free(p.sub);
    return p.failed ? 0 : count;
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

/* The wide node made from binary node bi (and, recursively, its subtree) into w[*count]; returns
 * its index. As in Dammertz et al. 2008 and Embree's collapse, the node takes bi's two children,
 * then repeatedly opens the inner child of largest surface area (the one a ray crossing the node
 * most likely enters, by the SAH's argument) until it has BVH_WIDTH children or only leaves. A
 * binary leaf bi (the root of a tree that is one leaf) becomes a node with that one leaf. Nodes are
 * numbered in pre-order, so the root is 0; the recursion is no deeper than the binary tree. */
static uint32_t collapse(const struct bnode *bn, uint32_t bi, struct bvh_node *w, size_t *count)
{
    uint32_t slot[BVH_WIDTH], wi = (uint32_t)(*count)++;
    int k = 0, i, a;

    if (bn[bi].count) {
        slot[k++] = bi;
    } else {
        slot[k++] = bn[bi].index;
        slot[k++] = bn[bi].index + 1;
    }
    while (k < BVH_WIDTH) {
        int best = -1;
        float best_area = 0.0f;
        for (i = 0; i < k; i++)
            if (bn[slot[i]].count == 0 && (best < 0 || bnode_half_area(&bn[slot[i]]) > best_area)) {
                best = i;
                best_area = bnode_half_area(&bn[slot[i]]);
            }
        if (best < 0)
            break;
        slot[k++] = bn[slot[best]].index + 1;
        slot[best] = bn[slot[best]].index;
    }
    memset(&w[wi], 0, sizeof w[wi]);
    for (i = 0; i < BVH_WIDTH; i++) {
        const struct bnode *c = i < k ? &bn[slot[i]] : NULL;
        for (a = 0; a < 3; a++) {
            w[wi].b[a][i] = c ? c->b[a] : INFINITY;
            w[wi].b[a + 3][i] = c ? c->b[a + 3] : -INFINITY;
        }
        if (c) {
            w[wi].count[i] = (uint8_t)c->count;
            w[wi].child[i] = c->count ? c->index : collapse(bn, slot[i], w, count);
        }
    }
    return wi;
}

mcrt_status mc_bvh_build_threads(struct bvh *b, struct prim *prims, const struct aabb *bounds,
                                 size_t n, int threads, mc_diag *d)
{
    struct ref *refs;
    struct bnode *bin;
    struct task root;
    uint32_t *order;
    void *mem = NULL;
    size_t bin_count, inner;
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
    bin = malloc(2 * n * sizeof *bin);
    if (!refs || !bin) {
        free(refs);
        free(bin);
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
    root.begin = 0;
    root.end = (uint32_t)n;
    root.node = 0;
    root.depth = 0;
    root.box = box;
    root.cbox = cbox;
    bin_count = build_tree(bin, refs, &root, threads > 0 ? threads : build_threads());
    if (bin_count == 0) {
        free(refs);
        free(bin);
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory building the BVH of %zu primitives", n);
    }
    /* Every split adds two binary nodes to the root and the unused node 1; each wide node but a
     * one-leaf root opens at least one binary inner node, so there are at most max(1, inner). */
    inner = (bin_count - 2) / 2;
    if (posix_memalign(&mem, 64, (inner > 1 ? inner : 1) * sizeof(struct bvh_node)) != 0) {
        free(refs);
        free(bin);
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory building the BVH of %zu primitives", n);
    }
    collapse(bin, 0, mem, &b->node_count);
    free(bin);
    /* Give back the unused tail. A shrinking realloc keeps the block in place in practice; if it
     * moved, the nodes would still be 16-byte aligned, which is all the SIMD loads assume. */
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

mcrt_status mc_bvh_build_bounds(struct bvh *b, struct prim *prims, const struct aabb *bounds,
                                size_t n, mc_diag *d)
{
    return mc_bvh_build_threads(b, prims, bounds, n, 0, d);
}

mcrt_status mc_bvh_build(struct bvh *b, struct prim *prims, size_t n, mc_diag *d)
{
    return mc_bvh_build_threads(b, prims, NULL, n, 0, d);
}

void mc_bvh_free(struct bvh *b)
{
    free(b->nodes);
    b->nodes = NULL;
    b->node_count = 0;
}
