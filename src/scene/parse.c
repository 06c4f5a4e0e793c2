/* parse.c: the mcrt scene language (for users: man/mcrt.5): blocks `kind [name] { key value ... }`
 * read by one table-driven loop, with one key table and one finishing function per block kind. An error longjmps back to mc_scene_parse (setjmp is
 * confined to this file, as Lua confines its error jumps to ldo.c). */
#include "scene/scene.h"

#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "scene/lex.h"
#include "scene/obj.h"

#if defined(__GNUC__)
#define NORETURN __attribute__((noreturn))
#else
#define NORETURN
#endif

/* What a key's value is. */
enum vkind {
    V_REAL,      /* one number x with lo < x < hi */
    V_INT,       /* one integer in [lo, hi] */
    V_POINT,     /* three numbers (a point or a vector) */
    V_PAIR,      /* two numbers */
    V_SPIN,      /* four numbers: an axis and an angle in degrees (not a transform step) */
    V_RGB,       /* one number (grey) or three, none negative */
    V_ALBEDO,    /* V_RGB at most 1: a surface reflecting more than arrives would create energy */
    V_ALBEDO_OR_NONE, /* V_ALBEDO, or no number at all (metal: then 'eta' and 'k' say it) */
    V_COLOR,     /* V_ALBEDO, or no number at all when the material has a texture */
    V_ALBEDO2,   /* two albedos of one number each, or of three (a checker's two colours) */
    V_UV,        /* one number (for u and v) or two, neither zero (a texture's scale) */
    V_UNIT,      /* one number in [0, 1] */
    V_CHOICE,    /* one of the key's words */
    V_NAME,      /* the name of a material or texture (the key's noun says which) */
    V_PATH,      /* a quoted string */
    V_FLAG,      /* no value */
    V_SCALE,     /* mesh transform steps: repeatable, applied in the order written */
    V_ROTATE,
    V_TRANSLATE
};

struct key {
    const char *name;
    enum vkind kind;
    double lo, hi;               /* V_REAL, V_INT */
    const char *rule;            /* V_REAL: what the range is, for the message */
    const char *const *choices;  /* V_CHOICE: NULL-terminated, indexed by the enum */
    const char *noun;            /* V_ALBEDO: what the number is, for the message; V_NAME: what
                                    is named */
};

/* The most keys of a block: the mesh's 11, or the material's (a key per material kind and its
 * further keys), whichever is larger. */
#define MATERIAL_KEY_COUNT (MC_MATERIAL_COUNT + MC_KEY_COUNT)
#define MAX_KEYS (MATERIAL_KEY_COUNT > 11 ? MATERIAL_KEY_COUNT : 11)

/* The most numbers a key takes: a checker's two colours. */
#define MAX_NUMBERS 6

/* The values of one block as given; the finishing function applies defaults. */
struct value {
    int set;
    struct token key;            /* the key, for messages */
    int n;                       /* numbers given */
    double x[MAX_NUMBERS];
    struct token at[MAX_NUMBERS]; /* the number tokens, for messages */
    struct token arg;            /* V_CHOICE, V_NAME, V_PATH: the word or string */
    int choice;
};

struct parser;
struct block;

struct block_kind {
    const char *name;
    const struct key *keys;
    int nkeys;
    int unique;                  /* at most once per scene */
    int named;                   /* `kind NAME { ... }` */
    void (*finish)(struct parser *p, struct block *b);
    int shape;                   /* a shape of MC_SHAPES: its enum prim_kind; otherwise -1 */
    int light;                   /* a kind of light of MC_LIGHTS: its enum light_kind; or -1 */
};

/* The block kinds in the order messages list them: the fixed ones around the shapes of
 * MC_SHAPES, whose key tables are made from their descriptors (see block_kinds_make). */
#define MAX_BLOCK_KINDS 16
struct block_kinds {
    struct block_kind kind[MAX_BLOCK_KINDS];
    int count;
    struct key shape_keys[PRIM_KIND_COUNT][MAX_KEYS];
    struct key light_keys[LIGHT_KIND_COUNT][MAX_KEYS];
};

struct block {
    const struct block_kind *kind;
    struct token head, name;
    struct value v[MAX_KEYS];
    double xf[12];               /* mesh: the composed transform, row-major 3x4 */
};

/* A shape's `material NAME`, resolved when the whole file has been read so that materials may be
 * defined in any order. */
struct matref {
    struct token name;
    size_t first, last;          /* the shape's primitives [first, last) */
};

/* A material's `texture NAME` or `roughness_texture NAME`, resolved likewise. */
struct texref {
    struct token name;
    size_t material;             /* the scene's material index */
    int roughness;               /* its roughness_texture, else its texture */
};

struct parser {
    struct lexer lx;
    struct token tok;            /* the lookahead */
    struct scene *s;
    const char *name, *base_dir;
    mc_diag *d;
    jmp_buf jump;
    mcrt_status status;
    struct matref *refs;
    size_t nrefs, cap_refs;
    struct texref *texrefs;
    size_t ntexrefs, cap_texrefs;
    struct token *texdefs;       /* name token of each texture this file defined, in order */
    size_t ntexdefs, cap_texdefs;
    struct token *defs;          /* name token of each material this file defined, in order */
    size_t ndefs, cap_defs;
    struct block_kinds kinds;
    struct token seen[MAX_BLOCK_KINDS]; /* first block of each unique kind (line 0: none yet) */
};

/* ---- Errors ---- */

static void NORETURN throw(struct parser *p, mcrt_status status)
{
    p->status = status;
    longjmp(p->jump, 1);
}

static void fail(struct parser *p, const struct token *at, const char *fmt, ...) MC_PRINTF(3, 4) NORETURN;

static void fail(struct parser *p, const struct token *at, const char *fmt, ...)
{
    char what[448];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    mc_fail(p->d, MCRT_ERR_PARSE, "%s:%d:%d: %s", p->name, at->line, at->col, what);
    throw(p, MCRT_ERR_PARSE);
}

static void NORETURN fail_nomem(struct parser *p)
{
    mc_fail(p->d, MCRT_ERR_NOMEM, "%s: out of memory", p->name);
    throw(p, MCRT_ERR_NOMEM);
}

/* Remember where the text first uses construct k (enum scene_mark). */
static void mark(struct parser *p, enum scene_mark k, const struct token *at)
{
    if (!p->s->marks[k].line) {
        p->s->marks[k].line = at->line;
        p->s->marks[k].col = at->col;
    }
}

/* A token as a message shows it; long words are cut at 64 bytes. */
static const char *describe(const struct token *t, char buf[96])
{
    int n = t->len > 64 ? 64 : (int)t->len;
    switch (t->kind) {
    case TOK_WORD: snprintf(buf, 96, "'%.*s'", n, t->text); break;
    case TOK_NUMBER: snprintf(buf, 96, "number '%.*s'", n, t->text); break;
    case TOK_STRING: snprintf(buf, 96, "a string"); break;
    case TOK_LBRACE: snprintf(buf, 96, "'{'"); break;
    case TOK_RBRACE: snprintf(buf, 96, "'}'"); break;
    default: snprintf(buf, 96, "end of file"); break;
    }
    return buf;
}

static void NORETURN fail_unclosed(struct parser *p, const struct block *b)
{
    fail(p, &p->tok, "unexpected end of file: block '%s' opened at %d:%d is not closed",
         b->kind->name, b->head.line, b->head.col);
}

/* ---- Did-you-mean (after Clang's typo correction): the closest candidate by optimal string
 * alignment distance (Levenshtein plus adjacent transpositions), if it is close enough. ---- */

struct match {
    const char *word;
    size_t len;
    const char *best;
    int dist;
};

static int osa_distance(const char *a, size_t n, const char *b, size_t m)
{
    int rows[3][65], *pp = rows[0], *prev = rows[1], *cur = rows[2];
    size_t i, j;
    if (n > 64 || m > 64)
        return 1000;
    for (j = 0; j <= m; j++)
        prev[j] = (int)j;
    for (i = 1; i <= n; i++) {
        int *t;
        cur[0] = (int)i;
        for (j = 1; j <= m; j++) {
            int cost = a[i - 1] != b[j - 1], v = prev[j - 1] + cost;
            if (prev[j] + 1 < v)
                v = prev[j] + 1;
            if (cur[j - 1] + 1 < v)
                v = cur[j - 1] + 1;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] && pp[j - 2] + 1 < v)
                v = pp[j - 2] + 1;
            cur[j] = v;
        }
        t = pp;
        pp = prev;
        prev = cur;
        cur = t;
    }
    return prev[m];
}

static void consider(struct match *m, const char *candidate)
{
    size_t len = strlen(candidate);
    int d = osa_distance(m->word, m->len, candidate, len);
    int limit = len <= 3 ? 1 : len <= 6 ? 2 : 3;
    if (d <= limit && (!m->best || d < m->dist)) {
        m->best = candidate;
        m->dist = d;
    }
}

static struct match matcher(const struct token *t)
{
    struct match m;
    m.word = t->text;
    m.len = t->len;
    m.best = NULL;
    m.dist = 0;
    return m;
}

static int token_is(const struct token *t, const char *s)
{
    return t->len == strlen(s) && memcmp(t->text, s, t->len) == 0;
}

/* ---- Tokens and values ---- */

static void advance(struct parser *p)
{
    if (mc_lex_next(&p->lx, &p->tok) == TOK_ERROR)
        throw(p, MCRT_ERR_PARSE);
}

/* Whether t spells a non-number that strtod would accept (nan, inf, infinity, any case). */
static int is_nonfinite_word(const struct token *t)
{
    static const char *const words[] = {"nan", "inf", "infinity"};
    size_t i, j;
    for (i = 0; i < 3; i++) {
        if (t->len != strlen(words[i]))
            continue;
        for (j = 0; j < t->len && (t->text[j] | 0x20) == words[i][j]; j++)
            ;
        if (j == t->len)
            return 1;
    }
    return 0;
}

/* Read the numbers after a key into v: all of them, so that a wrong count is reported as such. */
static void read_numbers(struct parser *p, struct value *v)
{
    for (;;) {
        if (p->tok.kind == TOK_WORD && is_nonfinite_word(&p->tok))
            fail(p, &p->tok, "'%.*s' is not a finite number", (int)p->tok.len, p->tok.text);
        if (p->tok.kind != TOK_NUMBER)
            return;
        if (v->n < MAX_NUMBERS) {
            /* Rounded to float first, so that every check sees the value the scene stores
             * (1e-50 is a zero scale, not a tiny one). */
            v->x[v->n] = (float)p->tok.num;
            v->at[v->n] = p->tok;
        }
        v->n++; /* cannot overflow: each number takes at least two bytes of a text below 2^30 */
        advance(p);
    }
}

static void check_count(struct parser *p, const struct block *b, const struct key *k,
                        const struct value *v)
{
    int one_or_three = k->kind == V_RGB || k->kind == V_ALBEDO || k->kind == V_SCALE
                       || k->kind == V_ALBEDO_OR_NONE || k->kind == V_COLOR;
    int want = k->kind == V_POINT || k->kind == V_TRANSLATE       ? 3
               : k->kind == V_ROTATE || k->kind == V_SPIN ? 4
               : k->kind == V_PAIR                        ? 2
                                                          : 1;
    if (k->kind == V_ALBEDO2 ? v->n == 2 || v->n == 6
        : k->kind == V_UV    ? v->n == 1 || v->n == 2
        : one_or_three
            ? v->n == 1 || v->n == 3 || (v->n == 0 && (k->kind == V_ALBEDO_OR_NONE || k->kind == V_COLOR))
            : v->n == want)
        return;
    if (p->tok.kind == TOK_EOF)
        fail_unclosed(p, b);
    if (k->kind == V_ALBEDO2)
        fail(p, &v->key, "'%s' needs 2 numbers (two greys) or 6 (two RGB colours), found %d",
             k->name, v->n);
    if (k->kind == V_UV)
        fail(p, &v->key, "'%s' needs 1 or 2 numbers, found %d", k->name, v->n);
    if (k->kind == V_ALBEDO_OR_NONE)
        fail(p, &v->key, "'%s' needs 1 or 3 numbers, or none with 'eta' and 'k', found %d",
             k->name, v->n);
    if (one_or_three)
        fail(p, &v->key, "'%s' needs 1 or 3 numbers, found %d", k->name, v->n);
    if (k->kind == V_ROTATE || k->kind == V_SPIN)
        fail(p, &v->key, "'%s' needs 4 numbers (an axis and an angle in degrees), found %d",
             k->name, v->n);
    fail(p, &v->key, "'%s' needs %d number%s, found %d", k->name, want, want == 1 ? "" : "s", v->n);
}

static vec3 vec_of(const struct value *v)
{
    return v->n == 1 ? v3s((float)v->x[0]) : v3((float)v->x[0], (float)v->x[1], (float)v->x[2]);
}

/* The value of key k, or the default when it was not given. */
static vec3 vec_or(const struct block *b, int k, vec3 def)
{
    return b->v[k].set ? vec_of(&b->v[k]) : def;
}

/* The first three numbers of v as a unit vector, normalised in double (the float square of a tiny
 * axis would underflow to zero); a zero vector fails with "WHAT has zero length" at v's key. */
static vec3 unit_of(struct parser *p, const struct value *v, const char *what)
{
    double l = sqrt(v->x[0] * v->x[0] + v->x[1] * v->x[1] + v->x[2] * v->x[2]);
    if (!(l > 0.0))
        fail(p, &v->key, "%s has zero length", what);
    return v3((float)(v->x[0] / l), (float)(v->x[1] / l), (float)(v->x[2] / l));
}

/* ---- Mesh transforms ---- */

/* xf = s·xf for the affine maps s and xf (row-major 3x4): s is applied after what is there. */
static void compose(struct parser *p, struct block *b, const double s[12], const struct token *at)
{
    double r[12];
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 4; j++) {
            double x = s[4 * i] * b->xf[j] + s[4 * i + 1] * b->xf[4 + j] + s[4 * i + 2] * b->xf[8 + j];
            r[4 * i + j] = j == 3 ? x + s[4 * i + 3] : x;
            if (!(fabs(r[4 * i + j]) <= FLT_MAX))
                fail(p, at, "'%.*s' makes the mesh transform too large for a float",
                     (int)at->len, at->text);
        }
    memcpy(b->xf, r, sizeof r);
}

static void transform_step(struct parser *p, struct block *b, const struct key *k,
                           const struct value *v)
{
    double s[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    int i;
    if (k->kind == V_TRANSLATE) {
        s[3] = v->x[0];
        s[7] = v->x[1];
        s[11] = v->x[2];
    } else if (k->kind == V_SCALE) {
        for (i = 0; i < 3; i++) {
            int at = v->n == 1 ? 0 : i;
            if (v->x[at] == 0.0)
                fail(p, &v->at[at], "'scale' must not be zero");
            s[5 * i] = v->x[at];
        }
    } else {
        /* Rodrigues' rotation formula: R = cos·I + sin·[a]x + (1 - cos)·a·aT, right-handed. */
        double x = v->x[0], y = v->x[1], z = v->x[2], l = sqrt(x * x + y * y + z * z);
        double th = v->x[3] * (3.14159265358979323846 / 180.0), c = cos(th), sn = sin(th);
        if (!(l > 0.0))
            fail(p, &v->key, "'rotate' axis has zero length");
        x /= l;
        y /= l;
        z /= l;
        s[0] = c + x * x * (1 - c);
        s[1] = x * y * (1 - c) - z * sn;
        s[2] = x * z * (1 - c) + y * sn;
        s[4] = y * x * (1 - c) + z * sn;
        s[5] = c + y * y * (1 - c);
        s[6] = y * z * (1 - c) - x * sn;
        s[8] = z * x * (1 - c) - y * sn;
        s[9] = z * y * (1 - c) + x * sn;
        s[10] = c + z * z * (1 - c);
    }
    compose(p, b, s, &v->key);
}

/* ---- Keys ---- */

/* Append word to the comma-separated list in buf[0..size), *n bytes long so far; a list too long
 * for buf is cut short. */
static void list_add(char *buf, size_t size, size_t *n, const char *word)
{
    if (*n == 0)
        buf[0] = '\0';
    if (*n < size) {
        int w = snprintf(buf + *n, size - *n, "%s%s", *n ? ", " : "", word);
        *n = w < 0 || (size_t)w >= size - *n ? size : *n + (size_t)w;
    }
}

static int find_key(struct parser *p, const struct block *b)
{
    const struct block_kind *kind = b->kind;
    struct match m = matcher(&p->tok);
    char keys[200];
    size_t n = 0;
    int i;
    for (i = 0; i < kind->nkeys; i++)
        if (token_is(&p->tok, kind->keys[i].name))
            return i;
    for (i = 0; i < kind->nkeys; i++)
        consider(&m, kind->keys[i].name);
    if (m.best)
        fail(p, &p->tok, "unknown key '%.*s' in %s (did you mean '%s'?)", (int)p->tok.len,
             p->tok.text, kind->name, m.best);
    for (i = 0; i < kind->nkeys; i++)
        list_add(keys, sizeof keys, &n, kind->keys[i].name);
    fail(p, &p->tok, "unknown key '%.*s' in %s (its keys: %s)", (int)p->tok.len, p->tok.text,
         kind->name, keys);
}

static void read_choice(struct parser *p, const struct block *b, const struct key *k,
                        struct value *v)
{
    char list[128];
    size_t n = 0;
    struct match m = matcher(&p->tok);
    int i;
    for (i = 0; k->choices[i]; i++) {
        list_add(list, sizeof list, &n, k->choices[i]);
        if (p->tok.kind == TOK_WORD && token_is(&p->tok, k->choices[i])) {
            v->choice = i;
            v->arg = p->tok;
            advance(p);
            return;
        }
        consider(&m, k->choices[i]);
    }
    if (p->tok.kind == TOK_EOF)
        fail_unclosed(p, b);
    if (p->tok.kind != TOK_WORD)
        fail(p, &v->key, "'%s' needs one of: %s", k->name, list);
    if (m.best)
        fail(p, &p->tok, "unknown %s '%.*s' (did you mean '%s'?)", k->name, (int)p->tok.len,
             p->tok.text, m.best);
    fail(p, &p->tok, "unknown %s '%.*s' (choices: %s)", k->name, (int)p->tok.len, p->tok.text, list);
}

/* Check the numbers of a numeric value against its kind. */
static void check_numbers(struct parser *p, const struct key *k, const struct value *v)
{
    int i;
    switch (k->kind) {
    case V_REAL:
        if (!(k->lo < v->x[0] && v->x[0] < k->hi))
            fail(p, &v->at[0], "'%s' %s", k->name, k->rule);
        break;
    case V_INT: /* on the unrounded value: 16777217 must not pass as 16777216 */
        if (!(v->at[0].num >= k->lo && v->at[0].num <= k->hi) || v->at[0].num != floor(v->at[0].num))
            fail(p, &v->at[0], "'%s' must be an integer from %.0f to %.0f, not '%.*s'", k->name,
                 k->lo, k->hi, (int)v->at[0].len, v->at[0].text);
        break;
    case V_UNIT:
        if (!(v->x[0] >= 0.0 && v->x[0] <= 1.0))
            fail(p, &v->at[0], "'%s' must be between 0 and 1", k->name);
        break;
    case V_UV:
        for (i = 0; i < v->n; i++)
            if (v->x[i] == 0.0)
                fail(p, &v->at[i], "'%s' must not be zero", k->name);
        break;
    case V_RGB:
    case V_ALBEDO:
    case V_ALBEDO_OR_NONE:
    case V_COLOR:
    case V_ALBEDO2:
        for (i = 0; i < v->n; i++) {
            if (v->x[i] < 0.0)
                fail(p, &v->at[i], "'%s' must not be negative", k->name);
            if (k->kind != V_RGB && v->x[i] > 1.0)
                fail(p, &v->at[i], "'%s' must be at most 1 (%s above 1 creates energy)", k->name,
                     k->noun);
        }
        break;
    default:
        break;
    }
}

static void read_key(struct parser *p, struct block *b)
{
    int idx = find_key(p, b);
    const struct key *k = &b->kind->keys[idx];
    struct value *v = &b->v[idx];
    int step = k->kind == V_SCALE || k->kind == V_ROTATE || k->kind == V_TRANSLATE;
    if (v->set && !step)
        fail(p, &p->tok, "duplicate key '%s' in %s (first given at %d:%d)", k->name, b->kind->name,
             v->key.line, v->key.col);
    v->set = 1;
    v->key = p->tok;
    v->n = 0;
    advance(p);
    switch (k->kind) {
    case V_FLAG:
        if (p->tok.kind == TOK_NUMBER)
            fail(p, &p->tok, "'%s' is a flag and takes no value", k->name);
        return;
    case V_CHOICE:
        read_choice(p, b, k, v);
        return;
    case V_NAME:
    case V_PATH:
        if (p->tok.kind == TOK_EOF)
            fail_unclosed(p, b);
        if (k->kind == V_NAME && p->tok.kind != TOK_WORD)
            fail(p, &v->key, "'%s' needs a %s name", k->name, k->noun);
        if (k->kind == V_PATH && p->tok.kind != TOK_STRING)
            fail(p, &v->key, "'%s' needs a path in double quotes", k->name);
        if (p->tok.len == 0)
            fail(p, &p->tok, "'%s' path is empty", k->name);
        v->arg = p->tok;
        advance(p);
        return;
    default:
        read_numbers(p, v);
        check_count(p, b, k, v);
        check_numbers(p, k, v);
        if (step)
            transform_step(p, b, k, v);
        return;
    }
}

/* Whether token a comes after token b in the file. */
static int after(const struct token *a, const struct token *b)
{
    return a->line > b->line || (a->line == b->line && a->col > b->col);
}

/* The given key of b that comes last in the file among keys[0..n), or the block's head: where a
 * message about a combination of values points. */
static const struct token *latest(const struct block *b, int n, const int *keys)
{
    const struct token *t = &b->head;
    int i;
    for (i = 0; i < n; i++)
        if (b->v[keys[i]].set && after(&b->v[keys[i]].key, t))
            t = &b->v[keys[i]].key;
    return t;
}

/* ---- Blocks ---- */

static const char *const strategy_names[] = {"mis", "bsdf", "light", NULL};

enum { FILM_WIDTH, FILM_HEIGHT, FILM_SPP, FILM_SAMPLER, FILM_FILTER };
static const struct key film_keys[] = {
    {"width", V_INT, 1, 65536, NULL, NULL, NULL},
    {"height", V_INT, 1, 65536, NULL, NULL, NULL},
    {"spp", V_INT, 1, 16777216, NULL, NULL, NULL},
    {"sampler", V_CHOICE, 0, 0, NULL, mc_sampler_names, NULL},
    {"filter", V_CHOICE, 0, 0, NULL, mc_filter_names, NULL},
};

static void finish_film(struct parser *p, struct block *b)
{
    static const int size_keys[] = {FILM_WIDTH, FILM_HEIGHT};
    struct film_desc *f = &p->s->film;
    if (b->v[FILM_WIDTH].set)
        f->width = (int)b->v[FILM_WIDTH].at[0].num;
    if (b->v[FILM_HEIGHT].set)
        f->height = (int)b->v[FILM_HEIGHT].at[0].num;
    if (b->v[FILM_SPP].set)
        f->spp = (int)b->v[FILM_SPP].at[0].num;
    if (b->v[FILM_SAMPLER].set)
        f->sampler = (enum sampler_kind)b->v[FILM_SAMPLER].choice;
    if (b->v[FILM_FILTER].set)
        f->filter = (enum filter_kind)b->v[FILM_FILTER].choice;
    if ((long long)f->width * f->height > (1LL << 28))
        fail(p, latest(b, 2, size_keys), "film of %d x %d pixels is too large (the limit is 2^28 "
             "pixels)", f->width, f->height);
}

enum { CAM_EYE, CAM_LOOK, CAM_UP, CAM_FOV, CAM_LENS_RADIUS, CAM_FOCUS_DISTANCE, CAM_SHUTTER,
       CAM_MOVE };
static const struct key camera_keys[] = {
    {"eye", V_POINT, 0, 0, NULL, NULL, NULL},
    {"look", V_POINT, 0, 0, NULL, NULL, NULL},
    {"up", V_POINT, 0, 0, NULL, NULL, NULL},
    {"fov", V_REAL, 0, 180, "must be between 0 and 180 degrees", NULL, NULL},
    /* Every negative float is below -DBL_MIN, so this admits exactly the non-negative radii. */
    {"lens_radius", V_REAL, -DBL_MIN, INFINITY, "must not be negative", NULL, NULL},
    {"focus_distance", V_REAL, 0, INFINITY, "must be positive", NULL, NULL},
    {"shutter", V_PAIR, 0, 0, NULL, NULL, NULL},
    {"move", V_POINT, 0, 0, NULL, NULL, NULL},
};

static void finish_camera(struct parser *p, struct block *b)
{
    static const int ends[] = {CAM_EYE, CAM_LOOK}, all[] = {CAM_EYE, CAM_LOOK, CAM_UP};
    struct camera_desc *c = &p->s->camera;
    float dist2;
    if (b->v[CAM_EYE].set)
        c->eye = vec_of(&b->v[CAM_EYE]);
    if (b->v[CAM_LOOK].set)
        c->look = vec_of(&b->v[CAM_LOOK]);
    if (b->v[CAM_UP].set)
        c->up = vec_of(&b->v[CAM_UP]);
    if (b->v[CAM_FOV].set)
        c->fov = (float)b->v[CAM_FOV].x[0];
    if (b->v[CAM_LENS_RADIUS].set)
        c->lens_radius = (float)b->v[CAM_LENS_RADIUS].x[0];
    if (b->v[CAM_FOCUS_DISTANCE].set)
        c->focus_distance = (float)b->v[CAM_FOCUS_DISTANCE].x[0];
    c->move = vec_or(b, CAM_MOVE, c->move);
    if (b->v[CAM_MOVE].set && !v3_is_zero(c->move))
        mark(p, MARK_CAMERA_MOVE, &b->v[CAM_MOVE].key);
    if (b->v[CAM_SHUTTER].set) {
        const struct value *v = &b->v[CAM_SHUTTER];
        if (!(v->x[1] >= v->x[0]))
            fail(p, &v->at[1], "camera 'shutter' closes (at %g) before it opens (at %g)", v->x[1],
                 v->x[0]);
        c->shutter[0] = (float)v->x[0];
        c->shutter[1] = (float)v->x[1];
    }
    /* The camera normalises look - eye and up in float: both lengths must be usable there. */
    dist2 = v3_length2(v3_sub(c->look, c->eye));
    if (!(dist2 > 0.0f))
        fail(p, latest(b, 2, ends), "camera 'eye' and 'look' are the same point");
    if (!isfinite(dist2))
        fail(p, latest(b, 2, ends), "camera 'eye' and 'look' are too far apart for a float");
    if (!(v3_length2(c->up) > 0.0f))
        fail(p, latest(b, 3, all), "camera 'up' has zero length");
    if (mc_edges_degenerate(v3_sub(c->look, c->eye), c->up))
        fail(p, latest(b, 3, all), "camera 'up' is parallel to the view direction from 'eye' to "
             "'look'");
}

enum { INT_METHOD, INT_MAX_DEPTH, INT_RR_DEPTH, INT_LIGHT_SAMPLES, INT_STRATEGY, INT_LIGHT_SELECT,
       INT_PHOTONS, INT_RADIUS, INT_ALPHA };
static const struct key integrator_keys[] = {
    {"method", V_CHOICE, 0, 0, NULL, mc_integrator_names, NULL},
    {"max_depth", V_INT, 0, 65536, NULL, NULL, NULL},
    {"rr_depth", V_INT, 0, 65536, NULL, NULL, NULL},
    {"light_samples", V_INT, 1, 1024, NULL, NULL, NULL},
    {"strategy", V_CHOICE, 0, 0, NULL, strategy_names, NULL},
    {"light_select", V_CHOICE, 0, 0, NULL, mc_light_select_names, NULL},
    {"photons", V_INT, 1, 1 << 30, NULL, NULL, NULL},
    {"radius", V_REAL, 0, INFINITY, "must be positive", NULL, NULL},
    {"alpha", V_REAL, 0, 1, "must be between 0 and 1, both excluded", NULL, NULL},
};

static void finish_integrator(struct parser *p, struct block *b)
{
    struct integrator_desc *it = &p->s->integrator;
    mark(p, MARK_INTEGRATOR, &b->head);
    if (b->v[INT_METHOD].set)
        it->method = (enum integrator_kind)b->v[INT_METHOD].choice;
    if (b->v[INT_MAX_DEPTH].set)
        it->max_depth = (int)b->v[INT_MAX_DEPTH].at[0].num;
    if (b->v[INT_RR_DEPTH].set)
        it->rr_depth = (int)b->v[INT_RR_DEPTH].at[0].num;
    if (b->v[INT_LIGHT_SAMPLES].set)
        it->light_samples = (int)b->v[INT_LIGHT_SAMPLES].at[0].num;
    if (b->v[INT_STRATEGY].set)
        it->strategy = (enum strategy)b->v[INT_STRATEGY].choice;
    if (b->v[INT_LIGHT_SELECT].set)
        it->light_select = (enum light_select_kind)b->v[INT_LIGHT_SELECT].choice;
    if (b->v[INT_PHOTONS].set)
        it->photons = (long)b->v[INT_PHOTONS].at[0].num;
    if (b->v[INT_RADIUS].set)
        it->radius = (float)b->v[INT_RADIUS].x[0];
    if (b->v[INT_ALPHA].set)
        it->alpha = (float)b->v[INT_ALPHA].x[0];
}

/* The material block's keys: first one per kind of the material table (materials.def), whose
 * keyword is followed by what enum mc_material_value says, exactly one of them given; then the
 * further keys, in enum mc_material_key order. */
#define V_OF_ALBEDO V_COLOR
#define V_OF_NONE V_FLAG
#define V_OF_ALBEDO_OR_NONE V_ALBEDO_OR_NONE
#define MAT_KEY(key) (MC_MATERIAL_COUNT + (key))
static const struct key material_keys[] = {
#define MC_MATERIAL(name, value, noun, keys) {#name, V_OF_##value, 0, 0, NULL, NULL, noun},
#include "bsdf/materials.def"
#undef MC_MATERIAL
    {"ior", V_REAL, 0, INFINITY, "must be positive", NULL, NULL},
    {"tint", V_ALBEDO, 0, 0, NULL, NULL, "tint"},
    {"roughness", V_UNIT, 0, 0, NULL, NULL, NULL},
    {"alpha", V_UNIT, 0, 0, NULL, NULL, NULL},
    {"eta", V_RGB, 0, 0, NULL, NULL, NULL},
    {"k", V_RGB, 0, 0, NULL, NULL, NULL},
    {"texture", V_NAME, 0, 0, NULL, NULL, "texture"},
    {"roughness_texture", V_NAME, 0, 0, NULL, NULL, "texture"},
};
typedef char check_material_key_count[sizeof material_keys / sizeof material_keys[0] == MATERIAL_KEY_COUNT ? 1 : -1];

/* array, with room for at least count + 1 elements of size elem (capacity *cap, doubled). */
static void *grow(struct parser *p, void *array, size_t *cap, size_t count, size_t elem)
{
    size_t ncap;
    void *q;
    if (count < *cap)
        return array;
    ncap = *cap ? *cap * 2 : 16;
    if (!(q = mc_realloc(array, ncap * elem)))
        fail_nomem(p);
    *cap = ncap;
    return q;
}

/* The material kinds taking every key of `keys` (0: all kinds), as "a, b and c" (each in
 * quotes when quoted) with `last` for "and". */
static void kind_list(char *buf, size_t size, unsigned keys, int quoted, const char *last)
{
    int i, n = 0, count = 0;
    size_t len = 0;
    buf[0] = '\0';
    for (i = 0; i < MC_MATERIAL_COUNT; i++)
        count += (mc_material_kinds[i].keys & keys) == keys;
    for (i = 0; i < MC_MATERIAL_COUNT && len < size; i++) {
        int w;
        if ((mc_material_kinds[i].keys & keys) != keys)
            continue;
        w = snprintf(buf + len, size - len, "%s%s%s%s", n == 0 ? "" : n == count - 1 ? last : ", ",
                     quoted ? "'" : "", mc_material_kinds[i].name, quoted ? "'" : "");
        len = w < 0 ? size : len + (size_t)w;
        n++;
    }
}

/* A named block's name into name[size) (a material's or a texture's, as b's kind says), which
 * must be new: find looks the name up in the scene, defs[0, ndefs) are the name tokens of this
 * file's definitions. They are searched by name, not by the scene's index: the materials and
 * textures meshes take from MTL files come in between, under names no word spells (mtl.h). */
static void new_name(struct parser *p, const struct block *b, char *name, size_t size,
                     int (*find)(const struct scene *, const char *), const struct token *defs,
                     size_t ndefs)
{
    const struct token *nm = &b->name;
    const char *what = b->kind->name;
    size_t i;
    if (nm->len >= size)
        fail(p, nm, "%s name longer than %d characters", what, (int)size - 1);
    memcpy(name, nm->text, nm->len);
    name[nm->len] = '\0';
    if (find(p->s, name) < 0)
        return;
    for (i = 0; i < ndefs; i++)
        if (defs[i].len == nm->len && !memcmp(defs[i].text, nm->text, nm->len))
            fail(p, nm, "duplicate %s '%s' (first defined at %d:%d)", what, name, defs[i].line,
                 defs[i].col);
    fail(p, nm, "duplicate %s '%s'", what, name);
}

/* The one of b's first n keys (a kind of material or texture) that is given, or -1 when none is;
 * two are an error. */
static int one_kind(struct parser *p, const struct block *b, int n, const char *name)
{
    int i, first = -1;
    for (i = 0; i < n; i++) {
        const struct value *v = &b->v[i];
        if (!v->set)
            continue;
        if (first >= 0)
            fail(p, after(&v->key, &b->v[first].key) ? &v->key : &b->v[first].key,
                 "%s '%s' has both '%s' and '%s': give one", b->kind->name, name,
                 b->kind->keys[first].name, b->kind->keys[i].name);
        first = i;
    }
    return first;
}

static void finish_material(struct parser *p, struct block *b)
{
    const struct token *nm = &b->name;
    const struct mc_material_kind *kind;
    const struct value *rough = &b->v[MAT_KEY(MC_KEY_ROUGHNESS)], *alpha = &b->v[MAT_KEY(MC_KEY_ALPHA)];
    const struct value *tint = &b->v[MAT_KEY(MC_KEY_TINT)], *ior = &b->v[MAT_KEY(MC_KEY_IOR)];
    const struct value *tex = &b->v[MAT_KEY(MC_KEY_TEXTURE)];
    const struct value *rtex = &b->v[MAT_KEY(MC_KEY_ROUGHNESS_TEXTURE)];
    struct material m;
    struct mc_material_problem problem;
    char kinds[160];
    unsigned given = 0;
    int i, first, idx;
    memset(&m, 0, sizeof m);
    new_name(p, b, m.name, sizeof m.name, mc_scene_find_material, p->defs, p->ndefs);
    if ((first = one_kind(p, b, MC_MATERIAL_COUNT, m.name)) < 0) {
        kind_list(kinds, sizeof kinds, 0, 1, " or ");
        fail(p, nm, "material '%s' needs one of %s", m.name, kinds);
    }
    kind = &mc_material_kinds[first];
    /* Each further key only for the kinds that take it. */
    for (i = 0; i < MC_KEY_COUNT; i++) {
        if (!b->v[MAT_KEY(i)].set)
            continue;
        given |= MC_KEY_BIT(i);
        if (!(kind->keys & MC_KEY_BIT(i))) {
            kind_list(kinds, sizeof kinds, MC_KEY_BIT(i), 0, " and ");
            fail(p, &b->v[MAT_KEY(i)].key, "'%s' is only for %s materials", material_keys[MAT_KEY(i)].name, kinds);
        }
    }
    if (rough->set && alpha->set)
        fail(p, after(&alpha->key, &rough->key) ? &alpha->key : &rough->key,
             "material '%s' has both 'roughness' and 'alpha': give one", m.name);
    m.kind = kind;
    if (b->v[first].n > 0)
        given |= MC_GIVEN_VALUE;
    else if (material_keys[first].kind == V_COLOR && !tex->set)
        fail(p, &b->v[first].key, "'%s' needs 1 or 3 numbers, or a 'texture'", kind->name);
    /* A texture's colour is scaled by the numbers given (1 without). */
    m.color = b->v[first].n > 0 ? vec_of(&b->v[first]) : tint->set ? vec_of(tint) : v3s(1.0f);
    m.ior = ior->set ? (float)ior->x[0] : 1.5f;
    /* Perceptual roughness r maps to α = r² (Burley 2012; pbrt-v4 remaproughness); a roughness
     * texture gives r, scaled by the roughness given (1 without). */
    m.alpha = alpha->set ? (float)alpha->x[0] : rough->set ? (float)(rough->x[0] * rough->x[0])
              : rtex->set ? 1.0f : 0.0f;
    m.eta = vec_or(b, MAT_KEY(MC_KEY_ETA), v3s(0.0f));
    m.k = vec_or(b, MAT_KEY(MC_KEY_K), v3s(0.0f));
    if (kind->ops->complete && !kind->ops->complete(&m, given, &problem)) {
        const struct value *v = problem.key < 0 ? &b->v[first] : &b->v[MAT_KEY(problem.key)];
        fail(p, problem.at_number ? &v->at[0] : &v->key, "%s", problem.what);
    }
    p->defs = grow(p, p->defs, &p->cap_defs, p->ndefs, sizeof *p->defs);
    p->defs[p->ndefs++] = *nm;
    if ((idx = mc_scene_add_material(p->s, &m)) < 0)
        fail_nomem(p);
    for (i = 0; i < 2; i++) {
        const struct value *v = i ? rtex : tex;
        struct texref *r;
        if (!v->set)
            continue;
        mark(p, MARK_TEXTURE, &v->key);
        p->texrefs = grow(p, p->texrefs, &p->cap_texrefs, p->ntexrefs, sizeof *p->texrefs);
        r = &p->texrefs[p->ntexrefs++];
        r->name = v->arg;
        r->material = (size_t)idx;
        r->roughness = i;
    }
}

/* The texture block's keys: one per kind of MC_TEXTURES, exactly one of them given, then the
 * mapping of the texture coordinates. */
#define TEXTURE_KEY(kind, name) \
    {#name, kind == TEXTURE_IMAGE ? V_PATH : V_ALBEDO2, 0, 0, NULL, NULL, "a texture's colour"},
enum { TEX_SCALE = TEXTURE_KIND_COUNT, TEX_OFFSET };
static const struct key texture_keys[] = {
    MC_TEXTURES(TEXTURE_KEY)
    {"scale", V_UV, 0, 0, NULL, NULL, NULL},
    {"offset", V_PAIR, 0, 0, NULL, NULL, NULL},
};
#undef TEXTURE_KEY

/* Where a token is, as "FILE:LINE:COL", for messages that come later (an image's). */
static void origin_of(const struct parser *p, const struct token *t, char *buf, size_t size)
{
    snprintf(buf, size, "%s:%d:%d", p->name, t->line, t->col);
}

static char *file_path(struct parser *p, const struct token *file);

static void finish_texture(struct parser *p, struct block *b)
{
    const struct token *nm = &b->name;
    const struct value *scale = &b->v[TEX_SCALE], *offset = &b->v[TEX_OFFSET];
    struct texture t;
    int first;
    memset(&t, 0, sizeof t);
    new_name(p, b, t.name, sizeof t.name, mc_scene_find_texture, p->texdefs, p->ntexdefs);
    if ((first = one_kind(p, b, TEXTURE_KIND_COUNT, t.name)) < 0)
        fail(p, nm, "texture '%s' needs 'image \"FILE\"' or 'checker A B'", t.name);
    t.kind = (enum texture_kind)first;
    t.scale = scale->set ? v2((float)scale->x[0], (float)scale->x[scale->n - 1]) : v2(1.0f, 1.0f);
    t.offset = offset->set ? v2((float)offset->x[0], (float)offset->x[1]) : v2(0.0f, 0.0f);
    if (t.kind == TEXTURE_IMAGE) {
        char origin[600], *path = file_path(p, &b->v[first].arg);
        int k;
        origin_of(p, &b->v[first].arg, origin, sizeof origin);
        k = mc_scene_add_image(p->s, path, origin);
        free(path);
        if (k < 0)
            fail_nomem(p);
        t.image = k + 1;
    } else {
        const struct value *v = &b->v[first];
        int h = v->n / 2;
        struct value half = *v;
        half.n = h;
        t.even = vec_of(&half);
        memmove(half.x, v->x + h, (size_t)h * sizeof *half.x);
        t.odd = vec_of(&half);
    }
    p->texdefs = grow(p, p->texdefs, &p->cap_texdefs, p->ntexdefs, sizeof *p->texdefs);
    p->texdefs[p->ntexdefs++] = *nm;
    if (mc_scene_add_texture(p->s, &t) < 0)
        fail_nomem(p);
}

/* Every shape takes these first five keys. */
#define SHAPE_KEYS                                                                             \
    {"material", V_NAME, 0, 0, NULL, NULL, "material"}, {"emit", V_RGB, 0, 0, NULL, NULL, NULL},     \
    {"two_sided", V_FLAG, 0, 0, NULL, NULL, NULL}, {"flip", V_FLAG, 0, 0, NULL, NULL, NULL},  \
    {"move", V_POINT, 0, 0, NULL, NULL, NULL}
enum { SHAPE_MATERIAL, SHAPE_EMIT, SHAPE_TWO_SIDED, SHAPE_FLIP, SHAPE_MOVE, SHAPE_KEYS_END };

/* The primitive fields every shape sets the same way; the material is resolved at the end. */
static struct prim shape_proto(const struct block *b)
{
    struct prim pr;
    memset(&pr, 0, sizeof pr);
    pr.material = 0;
    pr.light = -1;
    pr.normals = -1;
    if (b->v[SHAPE_EMIT].set)
        pr.emit = vec_of(&b->v[SHAPE_EMIT]);
    pr.flags = (uint8_t)((b->v[SHAPE_TWO_SIDED].set ? PRIM_TWO_SIDED : 0)
                         | (b->v[SHAPE_FLIP].set ? PRIM_FLIP : 0));
    return pr;
}

/* Remember that the shape's primitives [first, scene count) use the material it names. */
static void note_material(struct parser *p, const struct block *b, size_t first)
{
    struct matref *r;
    if (!b->v[SHAPE_MATERIAL].set)
        return;
    p->refs = grow(p, p->refs, &p->cap_refs, p->nrefs, sizeof *p->refs);
    r = &p->refs[p->nrefs++];
    r->name = b->v[SHAPE_MATERIAL].arg;
    r->first = first;
    r->last = p->s->prim_count;
}

/* A shape that moves (a nonzero `move`, or a mesh's nonzero `spin` about the centre of its bounding
 * box) gets one motion shared by its primitives [first, scene count). A zero motion is no motion,
 * so that such a scene is as static, and renders exactly as, the scene without the key. */
static void note_motion(struct parser *p, const struct block *b, size_t first,
                        const struct value *spin)
{
    struct motion m;
    size_t i;
    int idx;
    memset(&m, 0, sizeof m);
    m.move = vec_or(b, SHAPE_MOVE, v3s(0.0f));
    m.axis = v3(0.0f, 1.0f, 0.0f);
    if (spin && spin->set && spin->x[3] != 0.0) {
        struct aabb box = aabb_empty();
        m.axis = unit_of(p, spin, "'spin' axis");
        m.omega = (float)(spin->x[3] * (3.14159265358979323846 / 180.0));
        for (i = first; i < p->s->prim_count; i++)
            box = aabb_union(box, mc_prim_bounds(&p->s->prims[i]));
        m.center = aabb_center(box);
    }
    if (v3_is_zero(m.move) && m.omega == 0.0f)
        return;
    mark(p, MARK_SHAPE_MOVE, m.omega != 0.0f ? &spin->key : &b->v[SHAPE_MOVE].key);
    idx = mc_scene_add_motion(p->s, &m);
    if (idx < 0 && p->s->motion_count >= 65535)
        fail(p, &b->head, "too many moving shapes (the limit is 65535)");
    if (idx < 0)
        fail_nomem(p);
    for (i = first; i < p->s->prim_count; i++)
        p->s->prims[i].motion = (uint16_t)(idx + 1);
}

/* What every shape block notes of itself once its primitives [first, scene count) are added. */
static void note_shape(struct parser *p, const struct block *b, size_t first,
                       const struct value *spin)
{
    if (b->v[SHAPE_TWO_SIDED].set && b->v[SHAPE_EMIT].set && !v3_is_zero(vec_of(&b->v[SHAPE_EMIT])))
        mark(p, MARK_TWO_SIDED_EMITTER, &b->v[SHAPE_TWO_SIDED].key);
    note_material(p, b, first);
    note_motion(p, b, first, spin);
}

static void add_shape(struct parser *p, const struct block *b, const struct prim *pr)
{
    size_t first = p->s->prim_count;
    if (mc_scene_add_prim(p->s, pr) < 0)
        fail_nomem(p);
    note_shape(p, b, first, NULL);
}

/* The path of a file the scene names (an OBJ mesh, an image): as written when absolute or when
 * there is no base directory, else under it. */
static char *file_path(struct parser *p, const struct token *file)
{
    size_t nb = p->base_dir && file->text[0] != '/' ? strlen(p->base_dir) : 0;
    int slash = nb > 0 && p->base_dir[nb - 1] != '/';
    char *path = mc_malloc(nb + (size_t)slash + file->len + 1);
    if (!path)
        fail_nomem(p);
    if (nb)
        memcpy(path, p->base_dir, nb);
    if (slash)
        path[nb] = '/';
    memcpy(path + nb + slash, file->text, file->len);
    path[nb + (size_t)slash + file->len] = '\0';
    return path;
}

/* The values of the parameters, keys first, first + 1, ... of b, into v: the defaults where not
 * given, directions normalised. */
static void param_values(struct parser *p, const struct block *b, int first,
                         const struct block_param *params, int n, vec3 *v)
{
    int i;
    for (i = 0; i < n; i++) {
        const struct value *val = &b->v[first + i];
        char what[96];
        v[i] = params[i].def;
        if (!val->set)
            continue;
        if (params[i].kind == PARAM_DIRECTION) {
            snprintf(what, sizeof what, "%s '%s'", b->kind->name, params[i].name);
            v[i] = unit_of(p, val, what);
        } else if (params[i].kind == PARAM_SPIN) {
            snprintf(what, sizeof what, "%s '%s' axis", b->kind->name, params[i].name);
            v[i] = v3_scale(unit_of(p, val, what), (float)val->x[3]);
        } else if (params[i].kind == PARAM_IMAGE) {
            char *path = file_path(p, &val->arg), origin[600];
            int k;
            origin_of(p, &val->arg, origin, sizeof origin);
            k = mc_scene_add_image(p->s, path, origin);
            free(path);
            if (k < 0)
                fail_nomem(p);
            v[i] = v3((float)(k + 1), 0.0f, 0.0f);
        } else {
            v[i] = params[i].kind == PARAM_LENGTH ? v3((float)val->x[0], 0.0f, 0.0f) : vec_of(val);
        }
    }
}

/* Any shape of MC_SHAPES: its parameters (after the common keys), defaults applied and
 * directions normalised, made into a primitive by the shape's own build. */
static void finish_shape(struct parser *p, struct block *b)
{
    const struct shape *sh = mc_shapes[b->kind->shape];
    struct prim pr = shape_proto(b);
    vec3 v[MC_BLOCK_PARAMS];
    int keys[MC_BLOCK_PARAMS], n = 0, i;
    unsigned blame = 0;
    const char *why;
    param_values(p, b, SHAPE_KEYS_END, sh->params, sh->nparams, v);
    pr.kind = (uint8_t)b->kind->shape;
    if ((why = sh->build(&pr, v, &blame)) != NULL) {
        for (i = 0; i < sh->nparams; i++)
            if (blame & (1u << i))
                keys[n++] = SHAPE_KEYS_END + i;
        fail(p, latest(b, n, keys), "%s", why);
    }
    add_shape(p, b, &pr);
}

enum { MESH_FILE = SHAPE_KEYS_END, MESH_SCALE, MESH_ROTATE, MESH_TRANSLATE, MESH_SPIN };
static const struct key mesh_keys[] = {
    SHAPE_KEYS,
    {"file", V_PATH, 0, 0, NULL, NULL, NULL},
    {"scale", V_SCALE, 0, 0, NULL, NULL, NULL},
    {"rotate", V_ROTATE, 0, 0, NULL, NULL, NULL},
    {"translate", V_TRANSLATE, 0, 0, NULL, NULL, NULL},
    {"spin", V_SPIN, 0, 0, NULL, NULL, NULL},
};

static void finish_mesh(struct parser *p, struct block *b)
{
    const struct token *file = &b->v[MESH_FILE].arg;
    char origin[600];
    struct obj_mesh m;
    size_t first = p->s->prim_count;
    mcrt_status st;
    int i;
    if (!b->v[MESH_FILE].set)
        fail(p, &b->head, "mesh needs 'file \"NAME.obj\"'");
    origin_of(p, file, origin, sizeof origin);
    m.path = file_path(p, file);
    m.origin = origin;
    for (i = 0; i < 12; i++)
        m.xform[i] = (float)b->xf[i];
    m.proto = shape_proto(b);
    /* The OBJ's own materials and emission unless the scene gives them (man/mcrt.5). */
    m.mtl = !b->v[SHAPE_MATERIAL].set;
    m.mtl_emit = !b->v[SHAPE_EMIT].set;
    st = mc_obj_load(p->s, &m, NULL, p->d);
    free((char *)m.path);
    if (st)
        throw(p, st);
    note_shape(p, b, first, &b->v[MESH_SPIN]);
}

/* Any kind of light of MC_LIGHTS that has a block: its parameters made into a light by the kind's
 * own build. */
static void finish_light(struct parser *p, struct block *b)
{
    const struct light_desc *ld = mc_light_kinds[b->kind->light];
    struct light l;
    vec3 v[MC_BLOCK_PARAMS];
    param_values(p, b, 0, ld->params, ld->nparams, v);
    memset(&l, 0, sizeof l);
    l.kind = (enum light_kind)b->kind->light;
    if (l.kind == LIGHT_ENVIRONMENT)
        mark(p, MARK_ENVIRONMENT, &b->head);
    ld->build(&l, v);
    if (mc_scene_add_light(p->s, &l) < 0)
        fail_nomem(p);
}

#define KEYS(k) k, (int)(sizeof k / sizeof k[0])
static const struct block_kind kinds_before_shapes[] = {
    {"film", KEYS(film_keys), 1, 0, finish_film, -1, -1},
    {"camera", KEYS(camera_keys), 1, 0, finish_camera, -1, -1},
    {"integrator", KEYS(integrator_keys), 1, 0, finish_integrator, -1, -1},
    {"texture", KEYS(texture_keys), 0, 1, finish_texture, -1, -1},
    {"material", KEYS(material_keys), 0, 1, finish_material, -1, -1},
};
static const struct block_kind mesh_kind = {"mesh", KEYS(mesh_keys), 0, 0, finish_mesh, -1, -1};
#define N_BEFORE (int)(sizeof kinds_before_shapes / sizeof kinds_before_shapes[0])
static const struct key common_shape_keys[] = {SHAPE_KEYS};

/* Compile-time checks: struct block holds MAX_KEYS values (the material and the mesh have the most
 * keys, a shape at most MC_BLOCK_PARAMS besides the common ones), and the parser remembers the
 * first block of up to MAX_BLOCK_KINDS kinds. */
typedef char check_max_keys[sizeof mesh_keys / sizeof mesh_keys[0] <= MAX_KEYS ? 1 : -1];
typedef char check_material_keys[sizeof material_keys / sizeof material_keys[0] <= MAX_KEYS ? 1 : -1];
typedef char check_shape_keys[SHAPE_KEYS_END + MC_BLOCK_PARAMS <= MAX_KEYS ? 1 : -1];
typedef char check_kinds[N_BEFORE + PRIM_KIND_COUNT + 1 + LIGHT_KIND_COUNT <= MAX_BLOCK_KINDS ? 1
                                                                                       : -1];

/* A parameter of a shape or a light as a key of the scene language. */
static struct key param_key(const struct block_param *bp)
{
    struct key k = {NULL, V_POINT, 0, 0, NULL, NULL, NULL};
    k.name = bp->name;
    if (bp->kind == PARAM_RGB)
        k.kind = V_RGB;
    if (bp->kind == PARAM_IMAGE)
        k.kind = V_PATH;
    if (bp->kind == PARAM_SPIN)
        k.kind = V_SPIN;
    if (bp->kind == PARAM_LENGTH) {
        k.kind = V_REAL;
        k.hi = INFINITY;
        k.rule = "must be positive";
    }
    return k;
}

/* A block kind whose keys are `first` fixed ones followed by the parameters. */
static struct block_kind param_kind(const char *name, struct key *keys, const struct key *fixed,
                                    int first, const struct block_param *params, int nparams)
{
    struct block_kind k;
    int j;
    if (first) /* memcpy from NULL is undefined even for no bytes */
        memcpy(keys, fixed, (size_t)first * sizeof *keys);
    for (j = 0; j < nparams; j++)
        keys[first + j] = param_key(&params[j]);
    k.name = name;
    k.keys = keys;
    k.nkeys = first + nparams;
    k.unique = k.named = 0;
    k.shape = k.light = -1;
    return k;
}

/* Every block kind: the fixed ones, the shapes of MC_SHAPES, meshes, then the kinds of light of
 * MC_LIGHTS that have a block. */
static void block_kinds_make(struct block_kinds *bk)
{
    int i, n = 0;
    for (i = 0; i < N_BEFORE; i++)
        bk->kind[n++] = kinds_before_shapes[i];
    for (i = 0; i < PRIM_KIND_COUNT; i++) {
        bk->kind[n] = param_kind(mc_shape_names[i], bk->shape_keys[i], common_shape_keys,
                                 SHAPE_KEYS_END, mc_shapes[i]->params, mc_shapes[i]->nparams);
        bk->kind[n].finish = finish_shape;
        bk->kind[n++].shape = i;
    }
    bk->kind[n++] = mesh_kind;
    for (i = 0; i < LIGHT_KIND_COUNT; i++) {
        const struct light_desc *ld = mc_light_kinds[i];
        if (!ld->block)
            continue;
        bk->kind[n] = param_kind(ld->block, bk->light_keys[i], NULL, 0, ld->params, ld->nparams);
        bk->kind[n].unique = ld->unique;
        bk->kind[n].finish = finish_light;
        bk->kind[n++].light = i;
    }
    bk->count = n;
}

void mc_scene_words(void (*word)(void *user, const char *block, const char *key,
                                  const char *value),
                    void *user)
{
    struct block_kinds bk;
    int i, j, c;
    block_kinds_make(&bk);
    for (i = 0; i < bk.count; i++) {
        const struct block_kind *b = &bk.kind[i];
        word(user, b->name, NULL, NULL);
        for (j = 0; j < b->nkeys; j++) {
            word(user, b->name, b->keys[j].name, NULL);
            for (c = 0; b->keys[j].kind == V_CHOICE && b->keys[j].choices[c]; c++)
                word(user, b->name, b->keys[j].name, b->keys[j].choices[c]);
        }
    }
}

static int find_block(struct parser *p)
{
    struct match m = matcher(&p->tok);
    char list[200];
    size_t n = 0;
    int i;
    if (p->tok.kind != TOK_WORD) {
        char buf[96];
        fail(p, &p->tok, "expected a block such as 'sphere { }', found %s", describe(&p->tok, buf));
    }
    for (i = 0; i < p->kinds.count; i++)
        if (token_is(&p->tok, p->kinds.kind[i].name))
            return i;
    for (i = 0; i < p->kinds.count; i++) {
        consider(&m, p->kinds.kind[i].name);
        list_add(list, sizeof list, &n, p->kinds.kind[i].name);
    }
    if (m.best)
        fail(p, &p->tok, "unknown block '%.*s' (did you mean '%s'?)", (int)p->tok.len, p->tok.text,
             m.best);
    fail(p, &p->tok, "unknown block '%.*s' (blocks: %s)", (int)p->tok.len, p->tok.text, list);
}

static void read_block(struct parser *p)
{
    struct block b;
    char buf[96];
    int k = find_block(p);
    memset(&b, 0, sizeof b);
    b.kind = &p->kinds.kind[k];
    b.head = p->tok;
    b.xf[0] = b.xf[5] = b.xf[10] = 1.0;
    if (b.kind->unique) {
        if (p->seen[k].line)
            fail(p, &b.head, "second '%s' block (the first is at %d:%d)", b.kind->name,
                 p->seen[k].line, p->seen[k].col);
        p->seen[k] = b.head;
    }
    advance(p);
    if (b.kind->named) {
        if (p->tok.kind != TOK_WORD)
            fail(p, &p->tok, "expected a name after '%s', found %s", b.kind->name,
                 describe(&p->tok, buf));
        b.name = p->tok;
        advance(p);
    }
    if (p->tok.kind != TOK_LBRACE)
        fail(p, &p->tok, "expected '{' after '%s%s%.*s', found %s", b.kind->name,
             b.kind->named ? " " : "", (int)b.name.len, b.name.text, describe(&p->tok, buf));
    advance(p);
    while (p->tok.kind != TOK_RBRACE) {
        if (p->tok.kind == TOK_EOF)
            fail_unclosed(p, &b);
        if (p->tok.kind != TOK_WORD)
            fail(p, &p->tok, "expected a key or '}' in %s, found %s", b.kind->name,
                 describe(&p->tok, buf));
        read_key(p, &b);
    }
    b.kind->finish(p, &b);
    advance(p);
}

static void NORETURN unknown_material(struct parser *p, const struct token *t)
{
    struct match m = matcher(t);
    size_t i;
    for (i = 1; i < p->s->material_count; i++)
        consider(&m, p->s->materials[i].name);
    if (m.best)
        fail(p, t, "unknown material '%.*s' (did you mean '%s'?)", (int)t->len, t->text, m.best);
    if (p->s->material_count <= 1)
        fail(p, t, "unknown material '%.*s' (no material is defined)", (int)t->len, t->text);
    fail(p, t, "unknown material '%.*s'", (int)t->len, t->text);
}

static void resolve_materials(struct parser *p)
{
    size_t i, j;
    for (i = 0; i < p->nrefs; i++) {
        const struct matref *r = &p->refs[i];
        char name[sizeof p->s->materials[0].name];
        int idx = -1;
        if (r->name.len < sizeof name) {
            memcpy(name, r->name.text, r->name.len);
            name[r->name.len] = '\0';
            idx = mc_scene_find_material(p->s, name);
        }
        if (idx < 0)
            unknown_material(p, &r->name);
        for (j = r->first; j < r->last; j++)
            p->s->prims[j].material = idx;
    }
}

static void resolve_textures(struct parser *p)
{
    size_t i, j;
    for (i = 0; i < p->ntexrefs; i++) {
        const struct texref *r = &p->texrefs[i];
        const struct token *t = &r->name;
        char name[sizeof p->s->textures[0].name];
        struct material *m = &p->s->materials[r->material];
        int idx = -1;
        if (t->len < sizeof name) {
            memcpy(name, t->text, t->len);
            name[t->len] = '\0';
            idx = mc_scene_find_texture(p->s, name);
        }
        if (idx < 0) {
            struct match mt = matcher(t);
            for (j = 0; j < p->s->texture_count; j++)
                consider(&mt, p->s->textures[j].name);
            if (mt.best)
                fail(p, t, "unknown texture '%.*s' (did you mean '%s'?)", (int)t->len, t->text,
                     mt.best);
            fail(p, t, "unknown texture '%.*s'%s", (int)t->len, t->text,
                 p->s->texture_count ? "" : " (no texture is defined)");
        }
        if (r->roughness)
            m->roughness_texture = idx + 1;
        else
            m->texture = idx + 1;
    }
}

static void read_scene(struct parser *p)
{
    int blocks = 0;
    advance(p);
    for (; p->tok.kind != TOK_EOF; blocks++)
        read_block(p);
    if (!blocks)
        fail(p, &p->tok, "empty scene: a scene needs at least one block, such as 'sphere { }'");
    resolve_materials(p);
    resolve_textures(p);
}

/* The setjmp lives apart from mc_scene_parse so that the parser state it longjmps over belongs to
 * the caller's frame, whose objects keep their values (C99 7.13.2.1). */
static mcrt_status run(struct parser *p)
{
    if (setjmp(p->jump))
        return p->status;
    read_scene(p);
    return MCRT_OK;
}

mcrt_status mc_scene_parse(struct scene *s, const char *text, size_t len, const char *name,
                           const char *base_dir, mc_diag *d)
{
    struct parser p;
    mcrt_status st;
    if (!name)
        name = "<string>";
    if (!text)
        text = "", len = 0;
    if (len >= (size_t)1 << 30)
        return mc_fail(d, MCRT_ERR_PARSE, "%s:1:1: scene text is larger than 1 GiB", name);
    memset(&p, 0, sizeof p);
    p.s = s;
    p.name = name;
    p.base_dir = base_dir;
    p.d = d;
    free(s->name);
    if (!(s->name = mc_malloc(strlen(name) + 1)))
        return mc_fail(d, MCRT_ERR_NOMEM, "%s: out of memory", name);
    strcpy(s->name, name);
    block_kinds_make(&p.kinds);
    mc_lex_init(&p.lx, text, len, name, d);
    st = run(&p);
    free(p.refs);
    free(p.defs);
    free(p.texrefs);
    free(p.texdefs);
    return st;
}
