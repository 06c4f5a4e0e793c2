/* mtl.c: Wavefront MTL reader (see mtl.h), after the "Material Library File (.mtl)" chapter of
 * Wavefront's Advanced Visualizer manual, the statements its exporters write. */
#include "scene/mtl.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/file.h"
#include "core/hash.h"
#include "scene/scene.h"
#include "scene/wavefront.h"

/* The largest MTL file read, in bytes (64 MiB: a library holds materials, not geometry). */
#define MTL_MAX_BYTES ((size_t)64 << 20)

#define MC_MTL_NAME(name, how) #name,
const char *const mc_mtl_statement_names[MTL_STATEMENT_COUNT + 1] = {
    MC_MTL_STATEMENTS(MC_MTL_NAME) NULL};
#undef MC_MTL_NAME

enum how { READ, QUIET, WARN };
#define MC_MTL_HOW(name, how) how,
static const unsigned char statement_how[MTL_STATEMENT_COUNT] = {MC_MTL_STATEMENTS(MC_MTL_HOW)};
#undef MC_MTL_HOW

/* Why a WARN statement is ignored, for its warning. */
static const char *ignored_why(enum mtl_statement st)
{
    switch (st) {
    case MTL_bump: case MTL_map_bump: case MTL_norm: case MTL_disp:
        return "mcrt has no bump, normal or displacement maps";
    case MTL_map_d: case MTL_decal: return "mcrt has no cut-out or decal textures";
    case MTL_refl: return "reflections come from the scene, not from a map";
    default: return "mcrt does not support it";
    }
}

/* The statement written so far of the material being read: what each number was given as and
 * where, for the mapping and its messages. */
struct pending {
    int open;                  /* a newmtl has been read */
    unsigned given;            /* bits 1 << enum mtl_statement */
    vec3 kd, ks, ke, tf;
    double ns, ni, d, tr, pr, pm;
    int illum;
    struct mtl_entry entry;
};

struct mtl_reader {
    struct wf_reader r;
    struct mtl_library *lib;
    struct scene *warn;
    unsigned warned[(MTL_STATEMENT_COUNT + 31) / 32];
    int map_warned;            /* a texture map option was ignored (said once per file) */
    struct pending cur;
};

static mcrt_status nomem(struct mtl_reader *m)
{
    return mc_fail(m->r.d, MCRT_ERR_NOMEM, "%s: out of memory", m->r.path);
}

/* GGX α from the Phong exponent Ns: Walter, Marschner, Li and Torrance 2007, "Microfacet Models
 * for Refraction through Rough Surfaces", §5.2, match the Phong distribution of exponent α_p to
 * Beckmann's of width α_b by α_p = 2/α_b² − 2, so α_b = sqrt(2 / (Ns + 2)); GGX's α is taken
 * as Beckmann's (the two agree in width near the peak). Ns 0 gives 1 (very rough), Ns 1000
 * 0.045. */
static float alpha_from_ns(double ns) { return (float)sqrt(2.0 / (ns + 2.0)); }

/* "file:name", cut to fit size bytes. */
static void set_name(char *out, size_t size, const char *file, const char *name)
{
    size_t nf = strlen(file), nn = strlen(name);
    nf = nf < size - 1 ? nf : size - 1;
    memcpy(out, file, nf);
    if (nf < size - 1)
        out[nf++] = ':';
    nn = nn < size - 1 - nf ? nn : size - 1 - nf;
    memcpy(out + nf, name, nn);
    out[nf + nn] = '\0';
}

static int given(const struct pending *c, enum mtl_statement st) { return (c->given >> st) & 1u; }

/* Make the material read into m->cur an entry of the library (at the next newmtl or the end). */
static mcrt_status finish_material(struct mtl_reader *m)
{
    struct pending *c = &m->cur;
    struct mtl_entry *e = &c->entry;
    struct material *mt = &e->m;
    struct mc_material_problem problem;
    unsigned keys = MC_GIVEN_VALUE;
    const char *base = strrchr(m->r.path, '/');
    int glass = c->illum == 4 || c->illum == 6 || c->illum == 7 || c->illum == 9 ||
                (given(c, MTL_d) && c->d < 1.0) || (given(c, MTL_Tr) && c->tr > 0.0);
    int metallic = given(c, MTL_Pm) && c->pm > 0.5;
    int specular = (v3_max_comp(c->ks) > 0.0f && !(given(c, MTL_illum) && c->illum < 2)) ||
                   given(c, MTL_Pr);
    static const unsigned map_key[2] = {MC_KEY_BIT(MC_KEY_TEXTURE), MC_KEY_BIT(MC_KEY_ROUGHNESS_TEXTURE)};
    static const char *const map_what[2] = {"colour", "roughness"};
    int i;
    if (!c->open)
        return MCRT_OK;
    if (e->maps[MTL_MAP_KD].path && !given(c, MTL_Kd))
        c->kd = v3s(1.0f); /* the image alone is the colour */
    set_name(mt->name, sizeof mt->name, base ? base + 1 : m->r.path, e->name);
    mt->ior = 1.5f;
    mt->alpha = 0.0f;
    if (glass) {
        mt->kind = MC_MATERIAL_KIND(glass);
        mt->color = given(c, MTL_Tf) ? c->tf : v3s(1.0f);
        keys = MC_KEY_BIT(MC_KEY_TINT) | MC_KEY_BIT(MC_KEY_IOR);
        if (given(c, MTL_Ni))
            mt->ior = (float)c->ni;
    } else if (metallic || specular) {
        /* Pr is perceptual roughness: α = Pr² as for a scene's 'roughness'; map_Pr scales it. */
        if (given(c, MTL_Pr))
            mt->alpha = (float)(c->pr * c->pr);
        else if (given(c, MTL_Ns))
            mt->alpha = alpha_from_ns(c->ns);
        else if (e->maps[MTL_MAP_PR].path)
            mt->alpha = 1.0f;
        if (metallic) {
            mt->kind = MC_MATERIAL_KIND(metal);
            mt->color = c->kd;
        } else if (v3_max_comp(c->kd) > 0.0f) {
            mt->kind = MC_MATERIAL_KIND(plastic);
            mt->color = c->kd;
            if (given(c, MTL_Ni) && c->ni > 1.0) /* many exporters write Ni 1 for opaque ones */
                mt->ior = (float)c->ni;
        } else {
            mt->kind = MC_MATERIAL_KIND(metal);
            mt->color = c->ks;
        }
    } else {
        mt->kind = MC_MATERIAL_KIND(diffuse);
        mt->color = c->kd;
    }
    /* The kind derives the rest (metal: eta and k from its reflectance) and checks the values as
     * for a scene's material. */
    if (mt->kind->ops->complete && !mt->kind->ops->complete(mt, keys, &problem))
        return mc_fail(m->r.d, MCRT_ERR_PARSE, "%s:%d:%d: material '%s': %s", m->r.path, e->line,
                       e->col, e->name, problem.what);
    for (i = 0; i < 2; i++) {
        struct mtl_map *mp = &e->maps[i];
        if (!mp->path || (mt->kind->keys & map_key[i]))
            continue;
        if (mc_scene_warn(m->warn, "%s: warning: material '%s' is %s, which takes no %s texture: "
                          "its map_%s is ignored", mp->origin, e->name, mt->kind->name, map_what[i],
                          i == MTL_MAP_KD ? "Kd" : "Pr") < 0)
            return nomem(m);
        free(mp->path);
        free(mp->origin);
        mp->path = mp->origin = NULL;
    }
    e->emit = c->ke;
    e->scene_index = -1;
    if (m->lib->n == m->lib->cap) {
        size_t ncap = m->lib->cap ? m->lib->cap * 2 : 8;
        struct mtl_entry *ne = mc_realloc(m->lib->e, ncap * sizeof *ne);
        if (!ne)
            return nomem(m);
        m->lib->e = ne;
        m->lib->cap = ncap;
    }
    m->lib->e[m->lib->n++] = *e; /* the entry's strings now the library's */
    c->open = 0;
    return MCRT_OK;
}

/* The name after newmtl (mc_wf_name_end: names with blanks occur in the wild). */
static mcrt_status read_newmtl(struct mtl_reader *m, const char *kw, const char *p, const char *le)
{
    const char *q = mc_wf_name_end(p, le);
    struct pending *c = &m->cur;
    mcrt_status st = finish_material(m);
    int prev;
    if (st)
        return st;
    if (q == p)
        return mc_wf_fail(&m->r, kw, "'newmtl' needs a material name");
    if ((size_t)(q - p) >= sizeof c->entry.name)
        return mc_wf_fail(&m->r, p, "material name longer than %d characters",
                          (int)sizeof c->entry.name - 1);
    if ((prev = mc_mtl_find(m->lib, p, (size_t)(q - p))) >= 0) {
        const struct mtl_entry *e = &m->lib->e[prev];
        if (e->file == m->lib->npaths - 1)
            return mc_wf_fail(&m->r, p, "duplicate material '%.*s' (first defined at line %d)",
                              (int)(q - p), p, e->line);
        return mc_wf_fail(&m->r, p, "duplicate material '%.*s' (first defined in '%s' line %d)",
                          (int)(q - p), p, m->lib->paths[e->file], e->line);
    }
    memset(c, 0, sizeof *c);
    c->open = 1;
    memcpy(c->entry.name, p, (size_t)(q - p));
    c->entry.file = m->lib->npaths - 1;
    c->entry.line = m->r.line;
    c->entry.col = (int)(p - m->r.line_start) + 1;
    return MCRT_OK;
}

/* The numbers of a statement: between need and max of them, then only a comment. n gets how many;
 * at[i] where each starts. */
static mcrt_status read_numbers(struct mtl_reader *m, const char *kw, const char *p, const char *le,
                                int need, int max, double *x, const char **at, int *n)
{
    int kwlen = (int)(mc_wf_token_end(kw, le) - kw);
    char buf[48];
    *n = 0;
    for (;;) {
        const char *q;
        mcrt_status st;
        p = mc_wf_skip_blank(p, le);
        if (p == le || *p == '#')
            break;
        q = mc_wf_token_end(p, le);
        if (*n == max)
            return mc_wf_fail(&m->r, p, "unexpected '%s' after the %d number%s of '%.*s'",
                              mc_wf_show(p, q, buf), max, max == 1 ? "" : "s", kwlen, kw);
        if (*n == 0 && max == 3 && ((q - p == 8 && !memcmp(p, "spectral", 8)) ||
                        (q - p == 3 && !memcmp(p, "xyz", 3))))
            return mc_wf_fail(&m->r, p, "'%.*s %.*s' colours are not supported: give r g b",
                              kwlen, kw, (int)(q - p), p);
        if ((st = mc_wf_number(&m->r, p, q, &x[*n])))
            return st;
        at[(*n)++] = p;
        p = q;
    }
    if (*n < need)
        return mc_wf_fail(&m->r, *n ? at[*n - 1] : kw, "'%.*s' needs %s%d number%s, found %d", kwlen,
                          kw, need < max ? "at least " : "", need, need == 1 ? "" : "s", *n);
    return MCRT_OK;
}

/* A colour: r, or r g b (the spec's "Kd r [g b]": one number is grey), each at least 0 and, for a
 * reflectance or transmittance, at most 1. */
static mcrt_status read_colour(struct mtl_reader *m, const char *kw, const char *p, const char *le,
                               int at_most_one, vec3 *out)
{
    double x[3];
    const char *at[3];
    int n, i;
    mcrt_status st = read_numbers(m, kw, p, le, 1, 3, x, at, &n);
    if (st)
        return st;
    if (n == 2)
        return mc_wf_fail(&m->r, at[1], "a colour is one number (grey) or three, not two");
    for (i = 1; i < 3; i++)
        if (n == 1)
            x[i] = x[0];
    for (i = 0; i < n; i++) {
        if (x[i] < 0.0)
            return mc_wf_fail(&m->r, at[i], "a colour cannot be negative");
        if (at_most_one && x[i] > 1.0)
            return mc_wf_fail(&m->r, at[i],
                              "'%.2s' above 1 would reflect or pass more light than arrives", kw);
    }
    *out = v3((float)x[0], (float)x[1], (float)x[2]);
    return MCRT_OK;
}

/* One number with lo <= x <= hi (lo < x when open_lo). */
static mcrt_status read_real(struct mtl_reader *m, const char *kw, const char *p, const char *le,
                             double lo, int open_lo, double hi, const char *rule, double *out)
{
    const char *at;
    int n, kwlen = (int)(mc_wf_token_end(kw, le) - kw);
    mcrt_status st = read_numbers(m, kw, p, le, 1, 1, out, &at, &n);
    if (st)
        return st;
    if (*out < lo || (open_lo && *out == lo) || *out > hi)
        return mc_wf_fail(&m->r, at, "'%.*s' %s", kwlen, kw, rule);
    return MCRT_OK;
}

/* The options a texture map statement may take before its file name, with how many arguments
 * each (at most; -o, -s and -t take 1 to 3 numbers), after the MTL chapter's "Texture map
 * options". mcrt reads none of them: each is skipped, and the first in a file warned about. */
static const struct {
    const char *name;
    int args;
} map_options[] = {{"-blendu", 1}, {"-blendv", 1}, {"-bm", 1}, {"-boost", 1}, {"-cc", 1},
                   {"-clamp", 1}, {"-imfchan", 1}, {"-mm", 2}, {"-o", 3}, {"-s", 3}, {"-t", 3},
                   {"-texres", 1}, {"-type", 1}};

/* map_Kd or map_Pr [-option args...] FILE (into maps[which]): the file (the rest of the line, read
 * as a name: mc_wf_name_end), relative to the MTL file's folder. */
static mcrt_status read_map(struct mtl_reader *m, int which, const char *kw, const char *p,
                            const char *le)
{
    struct mtl_map *mp = &m->cur.entry.maps[which];
    const char *q, *slash = strrchr(m->r.path, '/');
    size_t nd = slash ? (size_t)(slash + 1 - m->r.path) : 0, i, n;
    char buf[48], origin[600];
    mcrt_status st;
    for (p = mc_wf_skip_blank(p, le); p < le && *p == '-'; p = mc_wf_skip_blank(p, le)) {
        int args;
        q = mc_wf_token_end(p, le);
        for (i = 0; i < sizeof map_options / sizeof map_options[0]; i++)
            if (strlen(map_options[i].name) == (size_t)(q - p) && !memcmp(map_options[i].name, p, (size_t)(q - p)))
                break;
        if (i == sizeof map_options / sizeof map_options[0])
            return mc_wf_fail(&m->r, p, "unknown map option '%s'", mc_wf_show(p, q, buf));
        if (!m->map_warned) {
            m->map_warned = 1;
            if (mc_scene_warn(m->warn, "%s:%d:%d: warning: texture map options such as '%s' are "
                              "ignored (later ones in this file are not reported)", m->r.path,
                              m->r.line, (int)(p - m->r.line_start) + 1, map_options[i].name) < 0)
                return nomem(m);
        }
        /* Its arguments: numbers or on/off words; -o, -s and -t stop at the first that is not a
         * number (the file name). */
        for (p = q, args = 0; args < map_options[i].args; args++) {
            double x;
            const char *a = mc_wf_skip_blank(p, le);
            q = mc_wf_token_end(a, le);
            if (a == q || (map_options[i].args == 3 && args > 0 &&
                           (*a < '0' || *a > '9') && *a != '-' && *a != '.' && *a != '+'))
                break;
            if (map_options[i].args == 3 && (st = mc_wf_number(&m->r, a, q, &x)))
                return st;
            p = q;
        }
    }
    q = mc_wf_name_end(p, le);
    if (p == q)
        return mc_wf_fail(&m->r, kw, "'%.6s' needs an image file name", kw);
    free(mp->path); /* a second map of one kind in one material replaces the first */
    free(mp->origin);
    n = (size_t)(q - p);
    snprintf(origin, sizeof origin, "%s:%d:%d", m->r.path, m->r.line, (int)(p - m->r.line_start) + 1);
    mp->path = mc_malloc(nd + n + 1);
    mp->origin = mc_malloc(strlen(origin) + 1);
    if (!mp->path || !mp->origin)
        return nomem(m);
    memcpy(mp->path, m->r.path, nd);
    memcpy(mp->path + nd, p, n);
    mp->path[nd + n] = '\0';
    strcpy(mp->origin, origin);
    return MCRT_OK;
}

static mcrt_status read_statement(struct mtl_reader *m, enum mtl_statement s, const char *kw,
                                  const char *p, const char *le)
{
    struct pending *c = &m->cur;
    double illum;
    mcrt_status st;
    c->given |= 1u << s;
    switch (s) {
    case MTL_Kd: return read_colour(m, kw, p, le, 1, &c->kd);
    case MTL_Ks: return read_colour(m, kw, p, le, 1, &c->ks);
    case MTL_Tf: return read_colour(m, kw, p, le, 1, &c->tf);
    case MTL_Ke: return read_colour(m, kw, p, le, 0, &c->ke);
    case MTL_map_Kd: return read_map(m, MTL_MAP_KD, kw, p, le);
    case MTL_map_Pr: return read_map(m, MTL_MAP_PR, kw, p, le);
    case MTL_Pr: return read_real(m, kw, p, le, 0.0, 0, 1.0, "must be from 0 to 1", &c->pr);
    case MTL_Pm: return read_real(m, kw, p, le, 0.0, 0, 1.0, "must be from 0 to 1", &c->pm);
    case MTL_Ns: return read_real(m, kw, p, le, 0.0, 0, INFINITY, "must not be negative", &c->ns);
    case MTL_Ni: return read_real(m, kw, p, le, 0.0, 1, INFINITY, "must be positive", &c->ni);
    case MTL_d: return read_real(m, kw, p, le, 0.0, 0, 1.0, "must be from 0 to 1", &c->d);
    case MTL_Tr: return read_real(m, kw, p, le, 0.0, 0, 1.0, "must be from 0 to 1", &c->tr);
    case MTL_illum:
        st = read_real(m, kw, p, le, 0.0, 0, 10.0, "must be an integer from 0 to 10", &illum);
        if (!st && illum != floor(illum))
            st = mc_wf_fail(&m->r, mc_wf_skip_blank(p, le), "'illum' must be an integer from 0 to 10");
        c->illum = (int)illum;
        return st;
    default: return MCRT_OK;
    }
}

static mcrt_status read_line(void *user, const char *p, const char *le)
{
    struct mtl_reader *m = user;
    const char *q;
    char buf[48];
    int i;
    p = mc_wf_skip_blank(p, le);
    if (p == le || *p == '#')
        return MCRT_OK;
    q = mc_wf_token_end(p, le);
    for (i = 0; i < MTL_STATEMENT_COUNT; i++)
        if (strlen(mc_mtl_statement_names[i]) == (size_t)(q - p) &&
            !memcmp(mc_mtl_statement_names[i], p, (size_t)(q - p)))
            break;
    if (i == MTL_STATEMENT_COUNT) {
        mcrt_status st = mc_wf_check_keyword(&m->r, p, q);
        return st ? st : mc_wf_fail(&m->r, p, "unknown MTL statement '%s'", mc_wf_show(p, q, buf));
    }
    if (i == MTL_newmtl)
        return read_newmtl(m, p, mc_wf_skip_blank(q, le), le);
    if (!m->cur.open)
        return mc_wf_fail(&m->r, p, "'%s' before any 'newmtl'", mc_mtl_statement_names[i]);
    if (statement_how[i] == READ)
        return read_statement(m, (enum mtl_statement)i, p, q, le);
    if (statement_how[i] == WARN && !(m->warned[i / 32] >> (i % 32) & 1u)) {
        m->warned[i / 32] |= 1u << (i % 32);
        if (mc_scene_warn(m->warn, "%s:%d:%d: warning: '%s' is ignored: %s (later ones in this "
                          "file are not reported)", m->r.path, m->r.line, (int)(p - m->r.line_start) + 1,
                          mc_mtl_statement_names[i], ignored_why((enum mtl_statement)i)) < 0)
            return nomem(m);
    }
    return MCRT_OK;
}

static void free_maps(struct mtl_entry *e)
{
    int k;
    for (k = 0; k < 2; k++) {
        free(e->maps[k].path);
        free(e->maps[k].origin);
    }
}

mcrt_status mc_mtl_load(struct mtl_library *lib, const char *path, const char *origin,
                        struct scene *warn, mc_diag *d)
{
    struct mtl_reader m;
    char *buf = NULL, **np, *own;
    size_t len = 0;
    mcrt_status st;
    memset(&m, 0, sizeof m);
    m.r.path = path;
    m.r.kind = "an MTL file";
    m.r.d = d;
    m.lib = lib;
    m.warn = warn;
    np = mc_realloc(lib->paths, (lib->npaths + 1) * sizeof *np);
    if (!np)
        return nomem(&m);
    lib->paths = np;
    if (!(own = mc_malloc(strlen(path) + 1)))
        return nomem(&m);
    lib->paths[lib->npaths++] = strcpy(own, path);
    st = mc_read_file(path, MTL_MAX_BYTES, origin, &buf, &len, d);
    if (st)
        return st;
    warn->hash = mc_hash(warn->hash, buf, len);
    st = mc_wf_lines(&m.r, buf, len, read_line, &m);
    if (!st)
        st = finish_material(&m);
    if (m.cur.open) /* a material not finished owns its strings still */
        free_maps(&m.cur.entry);
    free(buf);
    return st;
}

int mc_mtl_find(const struct mtl_library *lib, const char *name, size_t len)
{
    size_t i;
    for (i = 0; i < lib->n; i++)
        if (strlen(lib->e[i].name) == len && !memcmp(lib->e[i].name, name, len))
            return (int)i;
    return -1;
}

int mc_mtl_use(struct mtl_library *lib, size_t i, struct scene *s)
{
    struct mtl_entry *e = &lib->e[i];
    int k;
    if (e->scene_index >= 0)
        return e->scene_index;
    for (k = 0; k < 2; k++)
        if (e->maps[k].path) {
            const char *base = strrchr(e->maps[k].path, '/');
            int t = mc_scene_image_texture(s, base ? base + 1 : e->maps[k].path, e->maps[k].path,
                                           e->maps[k].origin);
            if (t < 0)
                return -1;
            *(k == MTL_MAP_KD ? &e->m.texture : &e->m.roughness_texture) = t + 1;
        }
    return e->scene_index = mc_scene_add_material(s, &e->m);
}

void mc_mtl_free(struct mtl_library *lib)
{
    while (lib->npaths > 0)
        free(lib->paths[--lib->npaths]);
    free(lib->paths);
    while (lib->n > 0)
        free_maps(&lib->e[--lib->n]);
    free(lib->e);
    memset(lib, 0, sizeof *lib);
}
