/* denoise.c: the `mcrt denoise` command: denoise an EXR saved by `mcrt render --denoise` (or
 * holding the same layers) through mcrt_denoise_file (mcrt.h). */
#include "cli/denoise.h"

#include <stdio.h>

#include "cli/args.h"
#include "mcrt.h"

static const char usage[] =
    "usage: mcrt denoise [options] IN.exr -o OUT.exr\n"
    "Denoise IN.exr, which holds the half buffers (layers A and B) and, per half, the first\n"
    "non-specular surface's albedo, normal, depth and emission (layers albedo.A, albedo.B,\n"
    "normal.A, ..., emission.B), as `mcrt render --denoise -o IN.exr` writes them. OUT.exr gets\n"
    "the denoised image and the layer raw, the mean of A and B.\n"
    "\n"
    "options:\n"
    "  -o FILE             the denoised image (EXR); required\n"
    "  --threads N         worker threads; 0 means one per core (default: 0); the image does\n"
    "                      not depend on it\n"
    "  --quiet             print nothing but errors\n"
    "\n"
    "exit status: 0 done, 1 the output could not be written or out of memory, 2 bad input\n";

enum { OPT_OUTPUT, OPT_THREADS, OPT_QUIET, OPT_HELP, OPT_END };
static const struct arg_spec options[OPT_END + 1] = {
    [OPT_OUTPUT] = {NULL, 'o', 1},  [OPT_THREADS] = {"threads", 0, 1},
    [OPT_QUIET] = {"quiet", 0, 0},  [OPT_HELP] = {"help", 'h', 0},
    [OPT_END] = {NULL, 0, 0}};

int mc_cli_denoise(int argc, char **argv)
{
    struct arg_parser p;
    const char *v, *in = NULL, *out = NULL;
    int opt, threads = 0, quiet = 0;
    double est_raw, est, sd;
    char error[512];
    mcrt_status st;
    mc_args_init(&p, argc, argv);
    while ((opt = mc_args_next(&p, options, &v)) != ARG_END) {
        switch (opt) {
        case ARG_ERROR: return STATUS_USAGE;
        case ARG_OPERAND:
            if (in) {
                fprintf(stderr, "mcrt: denoise takes one image; '%s' is a second\n", v);
                return STATUS_USAGE;
            }
            in = v;
            break;
        case OPT_OUTPUT: out = v; break;
        case OPT_THREADS:
            if (!mc_args_int("threads", v, 0, 1024, &threads))
                return STATUS_USAGE;
            break;
        case OPT_QUIET: quiet = 1; break;
        case OPT_HELP:
            fputs(usage, stdout);
            return fflush(stdout) == 0 ? STATUS_OK : STATUS_FAIL;
        }
    }
    if (!in || !out) {
        fprintf(stderr, "mcrt: usage: mcrt denoise [options] IN.exr -o OUT.exr (see mcrt denoise "
                        "--help)\n");
        return STATUS_USAGE;
    }
    st = mcrt_denoise_file(in, out, threads, &est_raw, &est, &sd, error, sizeof error);
    if (st != MCRT_OK) {
        fprintf(stderr, "mcrt: %s\n", error);
        /* The input's faults are bad input; writing the output, or memory, a failure. */
        return st == MCRT_ERR_NOMEM || st == MCRT_ERR_IO ? STATUS_FAIL : STATUS_USAGE;
    }
    if (!quiet)
        fprintf(stderr, "%s: est. relMSE %.3g +- %.2g (raw %.3g)\n", out, est, sd, est_raw);
    return STATUS_OK;
}
