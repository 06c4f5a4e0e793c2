/* export.c: the pieces every exporter shares (export.h). */
#include "export/export.h"

#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"

int mc_export_moves(const struct scene *s)
{
    size_t i;
    if (!v3_is_zero(s->camera.move))
        return 1;
    for (i = 0; i < s->prim_count; i++)
        if (s->prims[i].motion)
            return 1;
    return 0;
}

/* The place of each kind in the order (that of the POV-Ray references in ref/). */
static int kind_rank(int kind)
{
    static const int rank[PRIM_KIND_COUNT] = {
        [PRIM_TRIANGLE] = 1, [PRIM_SPHERE] = 2, [PRIM_QUAD] = 3, [PRIM_DISK] = 4};
    return rank[kind];
}

static int prim_order(const void *a, const void *b)
{
    const struct prim *p = *(const struct prim *const *)a, *q = *(const struct prim *const *)b;
    int c;
    if (p->kind != q->kind)
        return kind_rank(p->kind) < kind_rank(q->kind) ? -1 : 1;
    if (p->material != q->material)
        return p->material < q->material ? -1 : 1;
    if (p->flags != q->flags)
        return p->flags < q->flags ? -1 : 1;
    if (p->motion != q->motion)
        return p->motion < q->motion ? -1 : 1;
    if (p->normals != q->normals)
        return p->normals < q->normals ? -1 : 1;
    c = memcmp(p->p, q->p, sizeof p->p);
    return c ? c : memcmp(&p->emit, &q->emit, sizeof p->emit);
}

const struct prim **mc_export_sorted_prims(const struct scene *s)
{
    size_t i;
    const struct prim **prims = mc_malloc((s->prim_count ? s->prim_count : 1) * sizeof *prims);
    if (!prims)
        return NULL;
    for (i = 0; i < s->prim_count; i++)
        prims[i] = &s->prims[i];
    qsort(prims, s->prim_count, sizeof *prims, prim_order);
    return prims;
}

mcrt_status mc_export_refuse(mc_diag *d, const struct scene *s, int mark, const char *target,
                             const char *what, const char *why)
{
    const char *name = s->name ? s->name : "<scene>";
    if (mark >= 0 && mark < MARK_COUNT && s->marks[mark].line > 0)
        return mc_fail(d, MCRT_ERR_UNSUPPORTED, "%s:%d:%d: cannot export %s to %s: %s", name,
                       s->marks[mark].line, s->marks[mark].col, what, target, why);
    return mc_fail(d, MCRT_ERR_UNSUPPORTED, "%s: cannot export %s to %s: %s", name, what, target,
                   why);
}
