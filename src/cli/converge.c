/* converge.c: the `mcrt converge` command: render a scene at a ladder of budgets (spp or seconds),
 * each with a fresh seed, measure each render's error against a reference with mcrt_diff and its
 * own estimate, and write a CSV and a log-log plot of relative MSE against seconds (gnuplot). */
#include "cli/converge.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/args.h"
#include "mcrt.h"

enum { MAX_RUNGS = 32, MAX_VARIANTS = 8 };

/* The help up to the sampler names, which the library lists (mcrt_names). */
static const char usage[] =
    "usage: mcrt converge [options] SCENE\n"
    "Render SCENE at a ladder of budgets, each with a fresh seed, and write DIR/NAME-converge.csv\n"
    "(estimator, sampler, denoise, spp, seconds, MSE, relMSE, estimated relMSE) and a log-log\n"
    "plot of relMSE against seconds, the true one beside the renders' own estimate (dashed),\n"
    "DIR/NAME-converge.png (with gnuplot, if installed).\n"
    "\n"
    "options:\n"
    "  --ref FILE          the reference image (default: a render at 16 times the largest\n"
    "                      budget with another seed, written to DIR/NAME-ref.pfm)\n"
    "  --spp LIST          the ladder in samples per pixel, comma-separated (default: 1,4,16,64)\n"
    "  --times LIST        the ladder in seconds instead (progressive passes of 1 spp)\n"
    "  --compare KEY=LIST  one curve per value: integrator=path,direct, the unbiased and the\n"
    "                      consistent estimator integrator=path,sppm (a ladder of passes for\n"
    "                      sppm), the path tracer's strategies integrator=mis,bsdf,light,\n"
    "                      the raw image against the denoised one denoise=off,on (mcrt(1),\n"
    "                      --denoise; its seconds include the denoiser's), or\n"
    "                      sampler=";
/* The help after the sampler names. */
static const char usage_tail[] =
    "\n"
    "  -o DIR              the folder to write into (default: the current folder)\n"
    "  --threads N         worker threads; 0 means one per core (default: 0)\n"
    "  --seed N            the first seed (default: 0)\n"
    "  --quiet             print nothing but errors\n";

enum { OPT_REF, OPT_SPP, OPT_TIMES, OPT_COMPARE, OPT_OUTPUT, OPT_THREADS, OPT_SEED, OPT_QUIET,
       OPT_HELP, OPT_END };
static const struct arg_spec options[OPT_END + 1] = {
    [OPT_REF] = {"ref", 0, 1},         [OPT_SPP] = {"spp", 0, 1},
    [OPT_TIMES] = {"times", 0, 1},     [OPT_COMPARE] = {"compare", 0, 1},
    [OPT_OUTPUT] = {NULL, 'o', 1},     [OPT_THREADS] = {"threads", 0, 1},
    [OPT_SEED] = {"seed", 0, 1},       [OPT_QUIET] = {"quiet", 0, 0},
    [OPT_HELP] = {"help", 'h', 0},     [OPT_END] = {NULL, 0, 0}};

/* The options --compare varies, one curve per value. Each is a column of the CSV, where a render
 * that does not vary it has the value unset (the scene's choice, or the option's default). */
struct compare_key {
    const char *name, *column, *unset;
    const char *reference;        /* its value in the default reference; NULL: as unset */
    const char *const *values;    /* the values it takes; NULL: the library checks them */
    void (*set)(mcrt_options *o, const char *value);
};
static void set_integrator(mcrt_options *o, const char *v) { o->integrator = v; }
static void set_sampler(mcrt_options *o, const char *v) { o->sampler = v; }
static void set_denoise(mcrt_options *o, const char *v) { o->denoise = strcmp(v, "on") == 0; }
static const char *const off_on[] = {"off", "on", NULL};
/* The reference of an integrator comparison is the unbiased path tracer's, whatever the scene's
 * integrator; a denoised reference would carry the denoiser's bias into every curve. */
static const struct compare_key compare_keys[] = {
    {"integrator", "estimator", "scene", "path", NULL, set_integrator},
    {"sampler", "sampler", "scene", NULL, NULL, set_sampler},
    {"denoise", "denoise", "off", NULL, off_on, set_denoise},
};
enum { COMPARE_KEYS = sizeof compare_keys / sizeof compare_keys[0] };

struct converge {
    const char *scene, *ref, *dir;
    const struct compare_key *key;       /* the compared option; NULL: one curve */
    char *values[MAX_VARIANTS];          /* the compared values (strdup'ed) */
    int nvalues, nrungs, threads, quiet, by_time;
    double rungs[MAX_RUNGS];
    uint64_t seed;
};

/* "a,b,c" of positive numbers into c->rungs. */
static int parse_ladder(const char *name, const char *text, struct converge *c)
{
    char buf[32];
    const char *p = text;
    c->nrungs = 0;
    while (*p) {
        size_t len = strcspn(p, ",");
        if (len == 0 || len >= sizeof buf || c->nrungs == MAX_RUNGS) {
            fprintf(stderr, "mcrt: --%s: expected up to %d comma-separated numbers, got '%s'\n",
                    name, MAX_RUNGS, text);
            return 0;
        }
        memcpy(buf, p, len);
        buf[len] = '\0';
        if (!mc_args_real(name, buf, 1, 0, &c->rungs[c->nrungs]))
            return 0;
        if (!c->by_time && (c->rungs[c->nrungs] != (int)c->rungs[c->nrungs])) {
            fprintf(stderr, "mcrt: --spp: '%s' is not a whole number\n", buf);
            return 0;
        }
        c->nrungs++;
        p += len + (p[len] == ',');
    }
    return c->nrungs > 0;
}

/* Whether value is one of key's values; if not, says which they are. */
static int check_value(const struct compare_key *key, const char *value)
{
    const char *const *p;
    if (!key->values)
        return 1;
    for (p = key->values; *p; p++)
        if (strcmp(value, *p) == 0)
            return 1;
    fprintf(stderr, "mcrt: --compare: %s takes", key->name);
    for (p = key->values; *p; p++)
        fprintf(stderr, "%s %s", p == key->values ? "" : p[1] ? "," : " or", *p);
    fprintf(stderr, ", not '%s'\n", value);
    return 0;
}

/* KEY=LIST, KEY one of compare_keys: "integrator=path,direct", "denoise=off,on". */
static int parse_compare(const char *text, struct converge *c)
{
    const char *eq = strchr(text, '='), *p;
    size_t k;
    for (k = 0; eq && k < COMPARE_KEYS; k++)
        if (strlen(compare_keys[k].name) == (size_t)(eq - text) &&
            strncmp(text, compare_keys[k].name, (size_t)(eq - text)) == 0)
            break;
    if (!eq || k == COMPARE_KEYS || !eq[1]) {
        fprintf(stderr, "mcrt: --compare: expected");
        for (k = 0; k < COMPARE_KEYS; k++)
            fprintf(stderr, "%s %s=LIST", k == 0 ? "" : k + 1 < COMPARE_KEYS ? "," : " or",
                    compare_keys[k].name);
        fprintf(stderr, ", got '%s'\n", text);
        return 0;
    }
    c->key = &compare_keys[k];
    while (c->nvalues > 0)
        free(c->values[--c->nvalues]);
    p = eq + 1;
    while (*p) {
        size_t len = strcspn(p, ",");
        char *v;
        if (len == 0 || c->nvalues == MAX_VARIANTS) {
            fprintf(stderr, "mcrt: --compare: expected up to %d comma-separated values, got "
                            "'%s'\n", MAX_VARIANTS, text);
            return 0;
        }
        if (!(v = malloc(len + 1))) {
            fprintf(stderr, "mcrt: out of memory\n");
            return 0;
        }
        memcpy(v, p, len);
        v[len] = '\0';
        c->values[c->nvalues++] = v;
        if (!check_value(c->key, v))
            return 0;
        p += len + (p[len] == ',');
    }
    return 1;
}

/* DIR/NAME-SUFFIX, NAME being the scene file's name without folder and suffix. */
static char *out_path(const struct converge *c, const char *suffix)
{
    const char *base = strrchr(c->scene, '/'), *dot;
    size_t len;
    char *out;
    base = base ? base + 1 : c->scene;
    dot = strrchr(base, '.');
    len = dot && dot != base ? (size_t)(dot - base) : strlen(base);
    out = malloc(strlen(c->dir) + len + strlen(suffix) + 3);
    if (out)
        sprintf(out, "%s/%.*s-%s", c->dir, (int)len, base, suffix);
    return out;
}

/* Render with o and save to path; prints why and returns 0 on failure. */
static int render_to(const mcrt_scene *s, const mcrt_options *o, const char *path,
                     mcrt_stats *st)
{
    mcrt_render *r = mcrt_render_new(s, o);
    int ok = r && mcrt_render_run(r) == MCRT_OK && mcrt_render_save(r, path) == MCRT_OK;
    if (!ok)
        fprintf(stderr, "mcrt: %s\n", r ? mcrt_render_error(r) : "out of memory");
    else
        mcrt_render_stats(r, st, sizeof *st);
    mcrt_render_free(r);
    return ok;
}

/* The options of rung i (0-based) of variant v: a fresh seed per rung. */
static void rung_options(const struct converge *c, int v, int i, mcrt_options *o)
{
    mcrt_options_init(o);
    o->threads = c->threads;
    o->seed = c->seed + (uint64_t)i;
    if (c->by_time) {
        o->spp = 1;
        o->time_budget = c->rungs[i];
    } else
        o->spp = (int)c->rungs[i];
    if (c->key)
        c->key->set(o, c->values[v]);
}

/* The value of compare_keys[k] in the renders of variant v. */
static const char *variant_value(const struct converge *c, size_t k, int v)
{
    return c->key == &compare_keys[k] ? c->values[v] : compare_keys[k].unset;
}

/* A gnuplot script drawing two curves per variant from the CSV, in one colour: the true relMSE
 * (solid, points) and the render's own estimate of it (dashed), so that a reader sees at a
 * glance whether the render's error bar can be trusted. */
static int write_plot(const struct converge *c, const char *csv, const char *gp, const char *png)
{
    FILE *f = fopen(gp, "w");
    int v, n = c->key ? c->nvalues : 1;
    if (!f)
        return 0;
    fprintf(f, "set terminal pngcairo size 800,600\nset output '%s'\n"
               "set datafile separator ','\nset logscale xy\nset grid\n"
               "set xlabel 'seconds'\nset ylabel 'relative MSE'\nset key top right\n"
               "plot ", png);
    for (v = 0; v < n; v++) {
        /* The rows of variant v: its value in the compared key's column. */
        char pat[80] = ",", name[80] = "render";
        int col = c->key ? (int)(c->key - compare_keys) : 0;
        if (c->key) {
            snprintf(pat, sizeof pat, "\"^([^,]*,){%d}%s,\"", col, c->values[v]);
            /* A value of the key's own ("on") is named with the key; a library name as it is. */
            if (c->key->values)
                snprintf(name, sizeof name, "%s %s", c->key->name, c->values[v]);
            else
                snprintf(name, sizeof name, "%s", c->values[v]);
        }
        fprintf(f, "%s'< grep -v -e ^# -e ^estimator %s | grep -E %s' using %d:%d with "
                   "linespoints lc %d dt 1 title '%s', \\\n     '' using %d:%d with lines "
                   "lc %d dt 2 title '%s, estimated'",
                v ? ", \\\n     " : "", csv, pat, COMPARE_KEYS + 2, COMPARE_KEYS + 4, v + 1,
                name, COMPARE_KEYS + 2, COMPARE_KEYS + 5, v + 1, name);
    }
    fprintf(f, "\n");
    return fclose(f) == 0;
}

static int run(struct converge *c)
{
    mcrt_scene *s = mcrt_scene_new();
    mcrt_diff_options dopt;
    mcrt_diff_result dr;
    mcrt_options o;
    mcrt_stats st;
    char *csv = out_path(c, "converge.csv"), *tmp = out_path(c, "converge-tmp.pfm");
    char *gp = out_path(c, "converge.gp"), *png = out_path(c, "converge.png"), *ref = NULL;
    char err[512];
    FILE *f = NULL;
    int v, i, code = STATUS_FAIL, n = c->key ? c->nvalues : 1;
    size_t k;
    double top = 0.0;

    if (!s || !csv || !tmp || !gp || !png) {
        fprintf(stderr, "mcrt: out of memory\n");
        goto done;
    }
    if (mcrt_scene_load_file(s, c->scene) != MCRT_OK) {
        fprintf(stderr, "%s\n", mcrt_scene_error(s));
        code = STATUS_USAGE;
        goto done;
    }
    if (!(f = fopen(csv, "w"))) {
        fprintf(stderr, "mcrt: cannot write '%s'\n", csv);
        goto done;
    }
    for (i = 0; i < c->nrungs; i++)
        top = c->rungs[i] > top ? c->rungs[i] : top;
    if (c->ref)
        fprintf(f, "# reference: %s\n", c->ref);
    else {
        /* 16 times the largest budget with a seed no rung uses: its own relMSE is about 1/16 of
         * the best rung's. */
        if (!(ref = out_path(c, "ref.pfm")))
            goto done;
        rung_options(c, 0, 0, &o);
        o.seed = c->seed + 1000003;
        o.integrator = NULL;
        o.sampler = NULL;
        o.denoise = 0;
        if (c->key && c->key->reference)
            c->key->set(&o, c->key->reference);
        if (c->by_time)
            o.time_budget = 16.0 * top;
        else
            o.spp = (int)(16.0 * top);
        if (!c->quiet)
            fprintf(stderr, "mcrt: rendering the reference %s\n", ref);
        if (!render_to(s, &o, ref, &st))
            goto done;
        fprintf(f, "# reference: a render of %d spp, seed %llu, %.3f s (no --ref given): %s\n",
                st.spp, (unsigned long long)o.seed, st.seconds, ref);
    }
    for (k = 0; k < COMPARE_KEYS; k++)
        fprintf(f, "%s,", compare_keys[k].column);
    fprintf(f, "spp,seconds,mse,relmse,est_relmse\n");
    mcrt_diff_options_init(&dopt);
    for (v = 0; v < n; v++)
        for (i = 0; i < c->nrungs; i++) {
            rung_options(c, v, i, &o);
            if (!render_to(s, &o, tmp, &st))
                goto done;
            if (mcrt_diff(tmp, c->ref ? c->ref : ref, &dopt, &dr, sizeof dr, err, sizeof err) != MCRT_OK) {
                fprintf(stderr, "mcrt: %s\n", err);
                code = STATUS_USAGE;
                goto done;
            }
            for (k = 0; k < COMPARE_KEYS; k++)
                fprintf(f, "%s,", variant_value(c, k, v));
            fprintf(f, "%d,%.6g,%.6g,%.6g,%.6g\n", st.spp, st.seconds, dr.whole.mse,
                    dr.whole.relmse, st.est_relmse);
            if (!c->quiet)
                fprintf(stderr, "%s%s%s: %d spp, %.3f s, relMSE %.4g (estimated %.4g)\n",
                        c->key ? c->key->name : "", c->key ? "=" : "",
                        c->key ? c->values[v] : "", st.spp, st.seconds, dr.whole.relmse,
                        st.est_relmse);
        }
    if (fclose(f) != 0) {
        f = NULL;
        fprintf(stderr, "mcrt: cannot write '%s'\n", csv);
        goto done;
    }
    f = NULL;
    code = STATUS_OK;
    if (!write_plot(c, csv, gp, png))
        fprintf(stderr, "mcrt: cannot write '%s'\n", gp);
    else {
        char *cmd = malloc(strlen(gp) + 64);
        if (cmd) {
            sprintf(cmd, "gnuplot '%s' 2>/dev/null", gp);
            if (system(cmd) != 0)
                fprintf(stderr, "mcrt: gnuplot failed or is not installed: no %s (the CSV "
                                "and %s are written)\n", png, gp);
            else if (!c->quiet)
                fprintf(stderr, "mcrt: wrote %s and %s\n", csv, png);
            free(cmd);
        }
    }
done:
    if (f)
        fclose(f);
    if (tmp)
        unlink(tmp);
    free(csv);
    free(tmp);
    free(gp);
    free(png);
    free(ref);
    mcrt_scene_free(s);
    return code;
}

int mc_cli_converge(int argc, char **argv)
{
    struct arg_parser p;
    struct converge c;
    const char *v;
    int opt, i, code, ok;
    memset(&c, 0, sizeof c);
    c.dir = ".";
    mc_args_init(&p, argc, argv);
    parse_ladder("spp", "1,4,16,64", &c);
    while ((opt = mc_args_next(&p, options, &v)) != ARG_END) {
        ok = 1;
        switch (opt) {
        case ARG_ERROR: ok = 0; break;
        case ARG_OPERAND:
            if (c.scene) {
                fprintf(stderr, "mcrt: more than one scene given ('%s' and '%s')\n", c.scene, v);
                ok = 0;
            }
            c.scene = v;
            break;
        case OPT_REF: c.ref = v; break;
        case OPT_SPP: c.by_time = 0; ok = parse_ladder("spp", v, &c); break;
        case OPT_TIMES: c.by_time = 1; ok = parse_ladder("times", v, &c); break;
        case OPT_COMPARE: ok = parse_compare(v, &c); break;
        case OPT_OUTPUT: c.dir = v; break;
        case OPT_THREADS: ok = mc_args_int("threads", v, 0, 1024, &c.threads); break;
        case OPT_SEED: ok = mc_args_u64("seed", v, &c.seed); break;
        case OPT_QUIET: c.quiet = 1; break;
        case OPT_HELP: {
            char names[128];
            fputs(usage, stdout);
            fputs(mc_args_names("sampler", ",", ",", names, sizeof names), stdout);
            fputs(usage_tail, stdout);
            return fflush(stdout) == 0 ? STATUS_OK : STATUS_FAIL;
        }
        }
        if (!ok) {
            for (i = 0; i < c.nvalues; i++)
                free(c.values[i]);
            return STATUS_USAGE;
        }
    }
    if (!c.scene) {
        fprintf(stderr, "mcrt: usage: mcrt converge [options] SCENE (see mcrt converge --help)\n");
        code = STATUS_USAGE;
    } else
        code = run(&c);
    for (i = 0; i < c.nvalues; i++)
        free(c.values[i]);
    return code;
}
