/* obj.c: Wavefront OBJ reader (see obj.h). The file is read whole and scanned line by line in
 * place, with no allocation per token; format after Wavefront's "Object Files (.obj)" appendix B1. */
#include "scene/obj.h"

#include "core/alloc.h"
#include "core/file.h"
#include "core/hash.h"
#include "scene/mtl.h"
#include "scene/wavefront.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A growable array of vec3. */
struct vec3_array {
    vec3 *v;
    size_t n, cap;
};

static int vec3_push(struct vec3_array *a, vec3 x)
{
    if (a->n == a->cap) {
        size_t ncap = a->cap ? a->cap * 2 : 1024;
        vec3 *nv = mc_realloc(a->v, ncap * sizeof *nv);
        if (!nv)
            return -1;
        a->v = nv;
        a->cap = ncap;
    }
    a->v[a->n++] = x;
    return 0;
}

/* One corner of a face: indices into the vertex, texture coordinate and normal arrays (uv and
 * normal -1 when absent). */
struct corner {
    size_t v;
    long uv, normal;
};

struct reader {
    struct wf_reader r;     /* where we are, for messages */
    const struct obj_mesh *m;
    struct scene *s;
    mc_diag *d;
    float nxf[9];           /* normal matrix: sign(det)·cofactor(A), scaled to max |entry| 1 */
    int mirror;             /* det(A) < 0 */
    struct vec3_array v, vn, vt; /* vt: (u, v, 0) */
    struct mtl_library lib; /* the materials of the mtllib files read so far */
    struct prim proto;      /* what the faces copy: the mesh's, with usemtl's material and Ke */
    struct corner *corners; /* the face being read */
    size_t corner_cap;
    struct obj_stats stats;
};

static mcrt_status nomem(struct reader *r)
{
    return mc_fail(r->d, MCRT_ERR_NOMEM, "%s: out of memory loading '%s'", r->m->origin, r->m->path);
}

/* Read up to three numbers after a v, vn or vt keyword (kw), of which the first need must be
 * there; the others are 0 when absent. Anything after the third (the optional w of a vertex or a
 * texture coordinate, or the vertex colours some exporters write) is ignored. */
static mcrt_status read_vec3(struct reader *r, const char *kw, const char *p, const char *le,
                             int need, vec3 *out)
{
    float x[3] = {0.0f, 0.0f, 0.0f};
    int i, kwlen = (int)(mc_wf_token_end(kw, le) - kw);
    for (i = 0; i < 3; i++) {
        const char *q;
        double v;
        mcrt_status st;
        p = mc_wf_skip_blank(p, le);
        if (i >= need && (p == le || *p == '#'))
            break;
        if (p == le)
            return mc_wf_fail(&r->r, kw, "'%.*s' needs %d number%s, found %d", kwlen, kw, need,
                              need == 1 ? "" : "s", i);
        q = mc_wf_token_end(p, le);
        if ((st = mc_wf_number(&r->r, p, q, &v)))
            return st;
        x[i] = (float)v;
        p = q;
    }
    *out = v3(x[0], x[1], x[2]);
    return MCRT_OK;
}

static vec3 xform_point(const float *m, vec3 p)
{
    return v3(m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3], m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7],
              m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11]);
}

static mcrt_status read_vertex(struct reader *r, const char *kw, const char *le)
{
    vec3 p;
    mcrt_status st = read_vec3(r, kw, kw + 1, le, 3, &p);
    if (st)
        return st;
    p = xform_point(r->m->xform, p);
    if (!v3_is_finite(p))
        return mc_wf_fail(&r->r, kw, "vertex is not finite after the mesh transform");
    return vec3_push(&r->v, p) ? nomem(r) : MCRT_OK;
}

/* A vn is stored transformed and normalised, or as zero when it has no direction (a zero
 * vector, or one the transform collapses): faces using it are then shaded flat. */
static mcrt_status read_normal(struct reader *r, const char *kw, const char *le)
{
    const float *a = r->nxf;
    vec3 n;
    double x, y, z, l;
    mcrt_status st = read_vec3(r, kw, kw + 2, le, 3, &n);
    if (st)
        return st;
    x = (double)a[0] * n.x + (double)a[1] * n.y + (double)a[2] * n.z;
    y = (double)a[3] * n.x + (double)a[4] * n.y + (double)a[5] * n.z;
    z = (double)a[6] * n.x + (double)a[7] * n.y + (double)a[8] * n.z;
    l = sqrt(x * x + y * y + z * z);
    n = l > 0.0 && isfinite(l) ? v3((float)(x / l), (float)(y / l), (float)(z / l)) : v3s(0.0f);
    return vec3_push(&r->vn, n) ? nomem(r) : MCRT_OK;
}

/* A vt: u, and v (0 when absent, as the format says); a w is ignored. Texture coordinates are not
 * transformed: they live on the surface. */
static mcrt_status read_uv(struct reader *r, const char *kw, const char *le)
{
    vec3 t;
    mcrt_status st = read_vec3(r, kw, kw + 2, le, 1, &t);
    if (st)
        return st;
    t.z = 0.0f;
    return vec3_push(&r->vt, t) ? nomem(r) : MCRT_OK;
}

/* An index: an optional '-' and 1 to 12 digits (longer is out of range anyway). Returns the end,
 * or NULL when there is none. */
static const char *read_index(const char *p, const char *e, long long *out)
{
    long long v = 0;
    int neg = p < e && *p == '-', digits = 0;
    p += neg;
    while (p < e && *p >= '0' && *p <= '9') {
        if (digits++ < 12)
            v = v * 10 + (*p - '0');
        p++;
    }
    *out = neg ? -v : v;
    return digits ? p : NULL;
}

/* Resolve an OBJ index (1-based, or negative counting back from the latest of count elements). */
static mcrt_status resolve(struct reader *r, const char *at, long long idx, size_t count,
                           const char *what, const char *one, const char *many, size_t *out)
{
    long long n = (long long)count;
    if (idx == 0)
        return mc_wf_fail(&r->r, at, "%s index 0 is invalid (OBJ indices start at 1)", what);
    if (idx > n || idx < -n)
        return mc_wf_fail(&r->r, at, "%s index %lld out of range (the file has %zu %s so far)", what, idx,
                       count, count == 1 ? one : many);
    *out = (size_t)(idx > 0 ? idx - 1 : n + idx);
    return MCRT_OK;
}

/* One face corner in the forms v, v/vt, v//vn, v/vt/vn, spanning [p, e). */
static mcrt_status read_corner(struct reader *r, const char *p, const char *e, struct corner *c)
{
    const char *q = p;
    long long iv, it = 0, in = 0;
    mcrt_status st;
    char buf[48];
    int has_t = 0, has_n = 0;
    q = read_index(q, e, &iv);
    if (q && q < e && *q == '/') {
        if (++q < e && *q == '/') {
            q = read_index(q + 1, e, &in);
            has_n = 1;
        } else {
            q = read_index(q, e, &it);
            has_t = 1;
            if (q && q < e && *q == '/') {
                q = read_index(q + 1, e, &in);
                has_n = 1;
            }
        }
    }
    if (q != e)
        return mc_wf_fail(&r->r, p, "malformed face vertex '%s' (expected v, v/vt, v//vn or v/vt/vn)",
                       mc_wf_show(p, e, buf));
    st = resolve(r, p, iv, r->v.n, "face", "vertex", "vertices", &c->v);
    c->uv = c->normal = -1;
    if (!st && has_t) {
        size_t t;
        st = resolve(r, p, it, r->vt.n, "texture coordinate", "texture coordinate",
                     "texture coordinates", &t);
        c->uv = (long)t;
    }
    if (!st && has_n) {
        size_t n;
        st = resolve(r, p, in, r->vn.n, "normal", "normal", "normals", &n);
        c->normal = (long)n;
    }
    return st;
}

/* Add triangle (a, b, c), reversing the winding under a mirroring transform (obj.h), with its
 * corners' normals when smooth and their texture coordinates when textured. */
static mcrt_status add_triangle(struct reader *r, struct corner a, struct corner b, struct corner c,
                                int smooth, int textured)
{
    struct prim t = r->proto;
    if (r->mirror) {
        struct corner tmp = b;
        b = c;
        c = tmp;
    }
    t.kind = PRIM_TRIANGLE;
    t.light = -1;
    t.normals = -1;
    t.p[0] = r->v.v[a.v];
    t.p[1] = r->v.v[b.v];
    t.p[2] = r->v.v[c.v];
    if (mc_edges_degenerate(v3_sub(t.p[1], t.p[0]), v3_sub(t.p[2], t.p[0]))) {
        r->stats.degenerate++;
        return MCRT_OK;
    }
    if (smooth || textured) {
        const struct corner *k[3] = {&a, &b, &c};
        vec3 n[3];
        vec2 uv[3];
        int i;
        for (i = 0; i < 3; i++) {
            n[i] = smooth ? r->vn.v[k[i]->normal] : v3s(0.0f);
            if (textured)
                uv[i] = v2(r->vt.v[k[i]->uv].x, r->vt.v[k[i]->uv].y);
        }
        t.normals = mc_scene_add_corners(r->s, n, textured ? uv : NULL);
        if (t.normals < 0)
            return nomem(r);
    }
    if (mc_scene_add_prim(r->s, &t) < 0)
        return nomem(r);
    r->stats.triangles++;
    return MCRT_OK;
}

/* A face: its corners read once into r->corners and validated whole (so that a bad corner adds
 * nothing, and so that smooth shading is known to hold for every corner), then added as the fan
 * (0, k, k+1). */
static mcrt_status read_face(struct reader *r, const char *kw, const char *le)
{
    const char *p, *q;
    size_t n = 0, k;
    int smooth = 1, textured = 1;
    mcrt_status st;
    /* A '#' ends the corners: some exporters put comments after them. */
    for (p = mc_wf_skip_blank(kw + 1, le); p < le && *p != '#'; p = mc_wf_skip_blank(q, le)) {
        struct corner *c;
        q = mc_wf_token_end(p, le);
        if (n == r->corner_cap) {
            size_t ncap = r->corner_cap ? 2 * r->corner_cap : 16;
            struct corner *nc = mc_realloc(r->corners, ncap * sizeof *nc);
            if (!nc)
                return nomem(r);
            r->corners = nc;
            r->corner_cap = ncap;
        }
        c = &r->corners[n++];
        if ((st = read_corner(r, p, q, c)))
            return st;
        smooth = smooth && c->normal >= 0 && !v3_is_zero(r->vn.v[c->normal]);
        textured = textured && c->uv >= 0;
    }
    if (n < 3)
        return mc_wf_fail(&r->r, kw, "a face needs at least 3 vertices, found %d", (int)n);
    for (k = 2; k < n; k++)
        if ((st = add_triangle(r, r->corners[0], r->corners[k - 1], r->corners[k], smooth, textured)))
            return st;
    return MCRT_OK;
}

/* The folder of the OBJ file, with its final '/', joined to name [p, q): where an mtllib is. */
static char *beside(const char *obj, const char *p, const char *q)
{
    const char *slash = strrchr(obj, '/');
    size_t nd = slash ? (size_t)(slash + 1 - obj) : 0, n = (size_t)(q - p);
    char *path = mc_malloc(nd + n + 1);
    if (path) {
        memcpy(path, obj, nd);
        memcpy(path + nd, p, n);
        path[nd + n] = '\0';
    }
    return path;
}

/* mtllib FILE...: each a library of materials, relative to the OBJ file's folder. */
static mcrt_status read_mtllib(struct reader *r, const char *kw, const char *le)
{
    const char *p, *q;
    mcrt_status st = MCRT_OK;
    int files = 0;
    for (p = mc_wf_skip_blank(kw + 6, le); p < le && *p != '#' && !st; p = mc_wf_skip_blank(q, le)) {
        char origin[600], *path;
        q = mc_wf_token_end(p, le);
        snprintf(origin, sizeof origin, "%s:%d:%d", r->m->path, r->r.line,
                 (int)(p - r->r.line_start) + 1);
        if (!(path = beside(r->m->path, p, q)))
            return nomem(r);
        st = mc_mtl_load(&r->lib, path, origin, r->s, r->d);
        free(path);
        files++;
    }
    if (!st && !files)
        st = mc_wf_fail(&r->r, kw, "'mtllib' needs a file name");
    return st;
}

/* usemtl NAME: the faces that follow take material NAME of the libraries read, and its Ke unless
 * the scene gave the mesh an emission. The name is read as newmtl's (mc_wf_name_end). A material enters the scene when a face first uses it. */
static mcrt_status read_usemtl(struct reader *r, const char *kw, const char *le)
{
    const char *p = mc_wf_skip_blank(kw + 6, le), *q = mc_wf_name_end(p, le);
    struct mtl_entry *e;
    int i;
    if (q == p)
        return mc_wf_fail(&r->r, kw, "'usemtl' needs a material name");
    if ((i = mc_mtl_find(&r->lib, p, (size_t)(q - p))) < 0) {
        char buf[48];
        if (r->lib.npaths == 0)
            return mc_wf_fail(&r->r, p, "unknown material '%s' (no 'mtllib' before it)",
                              mc_wf_show(p, q, buf));
        return mc_wf_fail(&r->r, p, "unknown material '%s' (not in '%s'%s)", mc_wf_show(p, q, buf),
                          r->lib.paths[0], r->lib.npaths > 1 ? " and the other mtllib files" : "");
    }
    if ((r->proto.material = mc_mtl_use(&r->lib, (size_t)i, r->s)) < 0)
        return nomem(r);
    e = &r->lib.e[i];
    if (r->m->mtl_emit)
        r->proto.emit = e->emit;
    return MCRT_OK;
}

static mcrt_status read_line(void *user, const char *p, const char *le)
{
    struct reader *r = user;
    const char *q;
    char buf[48];
    size_t n;
    mcrt_status st;
    p = mc_wf_skip_blank(p, le);
    if (p == le || *p == '#')
        return MCRT_OK;
    q = mc_wf_token_end(p, le);
    n = (size_t)(q - p);
    if (n == 1 && p[0] == 'v')
        return read_vertex(r, p, le);
    if (n == 2 && p[0] == 'v' && p[1] == 'n')
        return read_normal(r, p, le);
    if (n == 2 && p[0] == 'v' && p[1] == 't')
        return read_uv(r, p, le);
    if (n == 1 && p[0] == 'f')
        return read_face(r, p, le);
    if (r->m->mtl && n == 6 && !memcmp(p, "mtllib", 6))
        return read_mtllib(r, p, le);
    if (r->m->mtl && n == 6 && !memcmp(p, "usemtl", 6))
        return read_usemtl(r, p, le);
    /* Every other statement (o, g, s, l, p, curves...) is ignored, but only if it
     * looks like one: a keyword of printable ASCII starting with a letter. Anything else means
     * the file is not OBJ text. */
    if ((st = mc_wf_check_keyword(&r->r, p, q)))
        return st;
    if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z')))
        return mc_wf_fail(&r->r, p, "expected an OBJ statement (v, vn, f, ...), found '%s'", mc_wf_show(p, q, buf));
    return MCRT_OK;
}

/* The normal matrix: the cofactor matrix of the linear part A is det(A)·A^-T; times sign(det)
 * it maps normals like A^-T up to a positive factor, which normalisation removes. Scaled to a
 * largest entry of 1 so that it fits a float whatever the scale of A. */
static void normal_matrix(struct reader *r)
{
    const float *m = r->m->xform;
    double a0 = m[0], a1 = m[1], a2 = m[2], a4 = m[4], a5 = m[5], a6 = m[6], a8 = m[8], a9 = m[9],
           a10 = m[10];
    double c[9], det, big = 0.0;
    int i;
    c[0] = a5 * a10 - a6 * a9;
    c[1] = a6 * a8 - a4 * a10;
    c[2] = a4 * a9 - a5 * a8;
    c[3] = a2 * a9 - a1 * a10;
    c[4] = a0 * a10 - a2 * a8;
    c[5] = a1 * a8 - a0 * a9;
    c[6] = a1 * a6 - a2 * a5;
    c[7] = a2 * a4 - a0 * a6;
    c[8] = a0 * a5 - a1 * a4;
    det = a0 * c[0] + a1 * c[1] + a2 * c[2];
    r->mirror = det < 0.0;
    for (i = 0; i < 9; i++)
        big = fmax(big, fabs(c[i]));
    for (i = 0; i < 9; i++)
        r->nxf[i] = big > 0.0 ? (float)((r->mirror ? -c[i] : c[i]) / big) : 0.0f;
}

mcrt_status mc_obj_load(struct scene *s, const struct obj_mesh *m, struct obj_stats *stats,
                        mc_diag *d)
{
    struct reader r;
    char *buf = NULL;
    size_t len = 0;
    mcrt_status st;
    memset(&r, 0, sizeof r);
    r.r.path = m->path;
    r.r.kind = "an OBJ file";
    r.r.d = d;
    r.proto = m->proto;
    r.m = m;
    r.s = s;
    r.d = d;
    normal_matrix(&r);
    st = mc_read_file(m->path, MC_OBJ_MAX_BYTES, m->origin, &buf, &len, d);
    if (st)
        return st;
    s->hash = mc_hash(s->hash, buf, len);
    st = mc_wf_lines(&r.r, buf, len, read_line, &r);
    free(buf);
    mc_mtl_free(&r.lib);
    free(r.v.v);
    free(r.vn.v);
    free(r.vt.v);
    free(r.corners);
    if (stats)
        *stats = r.stats;
    if (st)
        return st;
    if (r.stats.triangles == 0 && r.stats.degenerate > 0)
        return mc_fail(d, MCRT_ERR_PARSE, "%s: '%s' has no faces of nonzero area (%zu dropped)",
                       m->origin, m->path, r.stats.degenerate);
    if (r.stats.triangles == 0)
        return mc_fail(d, MCRT_ERR_PARSE, "%s: '%s' has no faces", m->origin, m->path);
    return MCRT_OK;
}
