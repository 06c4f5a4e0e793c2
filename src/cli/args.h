/* args.h: command-line parsing for mcrt's commands: long options as "--name value" or
 * "--name=value", one-letter aliases ("-o FILE", "-oFILE"), "--" ending the options, and strict
 * numbers. Errors are printed to stderr as one line starting "mcrt: "; nothing else is printed. */
#ifndef MCRT_ARGS_H
#define MCRT_ARGS_H

#include <stddef.h>
#include <stdint.h>

#include "mcrt.h"

/* One option a command accepts. A table of them ends with {NULL, 0, 0}. */
struct arg_spec {
    const char *name; /* "spp" for --spp, or NULL for a one-letter option only */
    char letter;      /* 'o' for -o, or 0 for none */
    int has_value;    /* 1: takes a value; 0: a flag */
};

/* The commands' exit statuses, as documented in --help and mcrt(1): success (for `mcrt diff`: the
 * images agree), failure (the render, or the comparison's limits), bad input or usage. */
enum { STATUS_OK = 0, STATUS_FAIL = 1, STATUS_USAGE = 2 };

/* Results of mc_args_next besides an index into the spec table. */
enum { ARG_END = -1, ARG_OPERAND = -2, ARG_ERROR = -3 };

struct arg_parser {
    int argc, next;
    char **argv;
    int options_done; /* after "--" everything is an operand */
};

/* Start parsing argv[1..argc-1]. */
void mc_args_init(struct arg_parser *p, int argc, char **argv);
/* The next option's index in specs (*value: its value, or NULL for a flag), ARG_OPERAND (*value:
 * the operand), ARG_END, or ARG_ERROR once the problem has been printed (unknown option,
 * missing value, value given to a flag). */
int mc_args_next(struct arg_parser *p, const struct arg_spec *specs, const char **value);
/* Parse text as a decimal integer in [min, max] (min is 0 or 1) into *out; on failure print
 * "mcrt: --NAME: expected a positive integer, got 'TEXT'" (or the range) and return 0. */
int mc_args_int(const char *name, const char *text, int min, int max, int *out);
/* Parse text as a decimal integer in [0, 2^64 - 1]; like mc_args_int. */
int mc_args_u64(const char *name, const char *text, uint64_t *out);
/* Parse text as a finite number >= 0 (> 0 when positive; < 1 as well when below_one); like
 * mc_args_int. */
int mc_args_real(const char *name, const char *text, int positive, int below_one, double *out);
/* Parse "x0,y0,x1,y1", integers with 0 <= x0 < x1 and 0 <= y0 < y1, into out; like mc_args_int. */
int mc_args_window(const char *name, const char *text, int out[4]);
/* The names of the library's set (mcrt_names) joined into buf, `sep` between them and `last`
 * before the final one ("a, b or c"); cut short when buf is too small. Returns buf. */
const char *mc_args_names(const char *set, const char *sep, const char *last, char *buf,
                          size_t size);
/* Whether text is one of the names of the library's set; if not, says which are, like
 * mc_args_int. */
int mc_args_name(const char *name, const char *set, const char *text);

/* The options that set a render's mcrt_options the same way in mcrt and mcrt-mpi: one table,
 * X(ID, NAME, HAS_VALUE), that both commands' option tables begin with (MC_RENDER_ARG_SPEC) and
 * that mc_args_render reads, so that a value means the same, and is checked the same, in both. */
#define MC_RENDER_ARGS(X)                                                                          \
    X(SPP, "spp", 1) X(THREADS, "threads", 1) X(SEED, "seed", 1) X(INTEGRATOR, "integrator", 1)    \
    X(SAMPLER, "sampler", 1) X(ALL_FEATURES, "all-features", 0) X(CROP, "crop", 1)                 \
    X(PASSES, "passes", 1) X(TIME, "time", 1) X(TARGET_ERROR, "target-error", 1)                   \
    X(STATE, "state", 0)
#define MC_RENDER_ARG_ENUM(id, name, has_value) RENDER_ARG_##id,
/* The render options' indices; a command's own options are numbered from RENDER_ARGS_END. */
enum { MC_RENDER_ARGS(MC_RENDER_ARG_ENUM) RENDER_ARGS_END };
#define MC_RENDER_ARG_SPEC(id, name, has_value) {name, 0, has_value},
/* Set the render option of index opt (below RENDER_ARGS_END) in *o from its value (NULL for a
 * flag); 0 when the value is bad, which has then been printed, as by mc_args_int. Strings are
 * pointed at, not copied (mcrt_render_new copies them). */
int mc_args_render(int opt, const char *value, mcrt_options *o);

#endif
