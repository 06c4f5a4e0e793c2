/* args.c: option and number parsing for the mcrt command (see args.h). GNU-style long options,
 * POSIX-style short ones (POSIX.1-2017 XBD 12.2, Utility Syntax Guidelines). */
#include "cli/args.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mcrt.h"

void mc_args_init(struct arg_parser *p, int argc, char **argv)
{
    p->argc = argc;
    p->argv = argv;
    p->next = 1;
    p->options_done = 0;
}

static int find_long(const struct arg_spec *specs, const char *name, size_t len)
{
    int i;
    for (i = 0; specs[i].name || specs[i].letter; i++)
        if (specs[i].name && strlen(specs[i].name) == len && strncmp(specs[i].name, name, len) == 0)
            return i;
    return -1;
}

static int find_letter(const struct arg_spec *specs, char letter)
{
    int i;
    for (i = 0; specs[i].name || specs[i].letter; i++)
        if (specs[i].letter && specs[i].letter == letter)
            return i;
    return -1;
}

/* The option as messages name it: "--spp" or "-o". */
static const char *label(const struct arg_spec *s, char *buf, size_t size)
{
    if (s->name)
        snprintf(buf, size, "--%s", s->name);
    else
        snprintf(buf, size, "-%c", s->letter);
    return buf;
}

int mc_args_next(struct arg_parser *p, const struct arg_spec *specs, const char **value)
{
    const char *arg, *eq = NULL;
    char buf[64];
    int i;

    *value = NULL;
    if (p->next >= p->argc)
        return ARG_END;
    arg = p->argv[p->next++];
    if (p->options_done || arg[0] != '-' || arg[1] == '\0') { /* "-" alone is an operand */
        *value = arg;
        return ARG_OPERAND;
    }
    if (strcmp(arg, "--") == 0) {
        p->options_done = 1;
        return mc_args_next(p, specs, value);
    }
    if (arg[1] == '-') { /* --name or --name=value */
        eq = strchr(arg + 2, '=');
        i = find_long(specs, arg + 2, eq ? (size_t)(eq - arg - 2) : strlen(arg + 2));
        if (i < 0) {
            fprintf(stderr, "mcrt: unknown option '%.*s' (see mcrt --help)\n",
                    eq ? (int)(eq - arg) : (int)strlen(arg), arg);
            return ARG_ERROR;
        }
        if (eq && !specs[i].has_value) {
            fprintf(stderr, "mcrt: %s takes no value\n", label(&specs[i], buf, sizeof buf));
            return ARG_ERROR;
        }
        if (eq)
            *value = eq + 1;
    } else { /* -x, -xVALUE or -x VALUE */
        i = find_letter(specs, arg[1]);
        if (i < 0 || (arg[2] && !specs[i].has_value)) {
            fprintf(stderr, "mcrt: unknown option '%s' (see mcrt --help)\n", arg);
            return ARG_ERROR;
        }
        if (arg[2])
            *value = arg + 2;
    }
    if (specs[i].has_value && !*value) {
        if (p->next >= p->argc) {
            fprintf(stderr, "mcrt: %s needs a value\n", label(&specs[i], buf, sizeof buf));
            return ARG_ERROR;
        }
        *value = p->argv[p->next++];
    }
    return i;
}

/* Digits only: strtoull alone would take "-1" (as 2^64-1), " 1", "+1" and "0x10". */
static int parse_decimal(const char *text, unsigned long long *out)
{
    const char *c;
    char *end;
    for (c = text; *c; c++)
        if (!isdigit((unsigned char)*c))
            return 0;
    if (c == text)
        return 0;
    errno = 0;
    *out = strtoull(text, &end, 10);
    return errno == 0;
}

int mc_args_int(const char *name, const char *text, int min, int max, int *out)
{
    unsigned long long v;
    if (!parse_decimal(text, &v) || v < (unsigned long long)min) {
        fprintf(stderr, "mcrt: --%s: expected a %s integer, got '%s'\n", name,
                min > 0 ? "positive" : "non-negative", text);
        return 0;
    }
    if (v > (unsigned long long)max) {
        fprintf(stderr, "mcrt: --%s: %s is too large (at most %d)\n", name, text, max);
        return 0;
    }
    *out = (int)v;
    return 1;
}

int mc_args_u64(const char *name, const char *text, uint64_t *out)
{
    unsigned long long v;
    if (!parse_decimal(text, &v)) { /* unsigned long long has at least 64 bits */
        fprintf(stderr, "mcrt: --%s: expected an integer from 0 to %llu, got '%s'\n", name,
                (unsigned long long)UINT64_MAX, text);
        return 0;
    }
    *out = (uint64_t)v;
    return 1;
}

int mc_args_real(const char *name, const char *text, int positive, int below_one, double *out)
{
    char *end;
    double v;
    errno = 0;
    v = strtod(text, &end);
    if (end == text || *end || errno || !(v >= 0.0) || !isfinite(v) || (positive && v == 0.0) ||
        (below_one && v >= 1.0) || isspace((unsigned char)text[0])) {
        fprintf(stderr, "mcrt: --%s: expected a number %s, got '%s'\n", name,
                below_one ? "between 0 and 1" : positive ? "> 0" : ">= 0", text);
        return 0;
    }
    *out = v;
    return 1;
}

int mc_args_window(const char *name, const char *text, int out[4])
{
    const char *p = text;
    char *end;
    long v[4];
    int i;
    for (i = 0; i < 4; i++) {
        errno = 0;
        v[i] = isdigit((unsigned char)*p) ? strtol(p, &end, 10) : -1;
        if (v[i] < 0 || errno || v[i] > 1L << 30 || *end != (i < 3 ? ',' : '\0'))
            break;
        p = end + 1;
    }
    if (i < 4 || v[0] >= v[2] || v[1] >= v[3]) {
        fprintf(stderr, "mcrt: --%s: expected x0,y0,x1,y1 with x0 < x1 and y0 < y1, got '%s'\n",
                name, text);
        return 0;
    }
    for (i = 0; i < 4; i++)
        out[i] = (int)v[i];
    return 1;
}

const char *mc_args_names(const char *set, const char *sep, const char *last, char *buf,
                          size_t size)
{
    const char *const *names = mcrt_names(set);
    size_t i, used = 0;
    buf[0] = '\0';
    for (i = 0; names && names[i]; i++) {
        const char *before = i == 0 ? "" : names[i + 1] ? sep : last;
        if (used + strlen(before) + strlen(names[i]) >= size)
            break;
        used += (size_t)sprintf(buf + used, "%s%s", before, names[i]);
    }
    return buf;
}

int mc_args_name(const char *name, const char *set, const char *text)
{
    const char *const *names = mcrt_names(set);
    char list[128];
    while (names && *names && strcmp(*names, text) != 0)
        names++;
    if (names && *names)
        return 1;
    fprintf(stderr, "mcrt: --%s: expected %s, got '%s'\n", name,
            mc_args_names(set, ", ", " or ", list, sizeof list), text);
    return 0;
}

#define RENDER_ARG_NAME(id, name, has_value) name,
static const char *const render_arg_names[RENDER_ARGS_END] = {MC_RENDER_ARGS(RENDER_ARG_NAME)};

int mc_args_render(int opt, const char *v, mcrt_options *o)
{
    const char *name = opt >= 0 && opt < RENDER_ARGS_END ? render_arg_names[opt] : NULL;
    int crop[4];
    switch (opt) {
    case RENDER_ARG_SPP: return mc_args_int(name, v, 1, 2147483647, &o->spp);
    case RENDER_ARG_THREADS: return mc_args_int(name, v, 0, 2147483647, &o->threads);
    case RENDER_ARG_SEED: return mc_args_u64(name, v, &o->seed);
    case RENDER_ARG_INTEGRATOR:
        o->integrator = v;
        return mc_args_name(name, "integrator", v);
    case RENDER_ARG_SAMPLER:
        o->sampler = v;
        return mc_args_name(name, "sampler", v);
    case RENDER_ARG_ALL_FEATURES: o->all_features = 1; return 1;
    case RENDER_ARG_CROP:
        if (!mc_args_window(name, v, crop))
            return 0;
        o->crop_x0 = crop[0];
        o->crop_y0 = crop[1];
        o->crop_x1 = crop[2];
        o->crop_y1 = crop[3];
        return 1;
    case RENDER_ARG_PASSES: return mc_args_int(name, v, 1, 2147483647, &o->passes);
    case RENDER_ARG_TIME: return mc_args_real(name, v, 1, 0, &o->time_budget);
    case RENDER_ARG_TARGET_ERROR: return mc_args_real(name, v, 1, 0, &o->target_error);
    case RENDER_ARG_STATE: o->save_state = 1; return 1;
    }
    return 0; /* not a render option: a caller's mistake */
}
