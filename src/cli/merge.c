/* merge.c: the `mcrt merge` command: merge EXR images with render states through mcrt_merge
 * (mcrt.h), and say what was written. */
#include "cli/merge.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/args.h"
#include "mcrt.h"

static const char usage[] =
    "usage: mcrt merge [options] A.exr B.exr ... -o OUT.exr\n"
    "Merge renders of one scene with one set of options, each an EXR with its render state\n"
    "(mcrt --state, --time or --target-error): renders of the same pixels with other seeds or\n"
    "--first-pass ranges combine their samples exactly (Chan, Golub and LeVeque 1979), and\n"
    "--crop windows that tile the image are assembled. OUT gets the merged image and state;\n"
    "it is written whole or not at all.\n"
    "\n"
    "options:\n"
    "  -o FILE   the EXR image to write (required)\n"
    "  --quiet   print nothing but errors\n"
    "  --help    print this help and exit\n"
    "\n"
    "exit status: 0 written; 1 out of memory or the output could not be written; 2 bad input\n"
    "(another scene, options or size, overlapping or gapped crops, a damaged file)\n";

enum { OPT_OUTPUT, OPT_QUIET, OPT_HELP, OPT_END };
static const struct arg_spec options[OPT_END + 1] = {
    [OPT_OUTPUT] = {NULL, 'o', 1}, [OPT_QUIET] = {"quiet", 0, 0}, [OPT_HELP] = {"help", 'h', 0},
    [OPT_END] = {NULL, 0, 0}};

int mc_cli_merge(int argc, char **argv)
{
    struct arg_parser p;
    const char *v, *output = NULL;
    const char **inputs = malloc((size_t)argc * sizeof *inputs);
    char error[600];
    mcrt_stats st;
    mcrt_status status;
    int opt, n = 0, quiet = 0, code;
    if (!inputs) {
        fprintf(stderr, "mcrt: out of memory\n");
        return STATUS_FAIL;
    }
    mc_args_init(&p, argc, argv);
    while ((opt = mc_args_next(&p, options, &v)) != ARG_END) {
        if (opt == ARG_ERROR) {
            free(inputs);
            return STATUS_USAGE;
        }
        if (opt == OPT_HELP) {
            free(inputs);
            fputs(usage, stdout);
            return fflush(stdout) == 0 ? STATUS_OK : STATUS_FAIL;
        }
        if (opt == OPT_OUTPUT)
            output = v;
        else if (opt == OPT_QUIET)
            quiet = 1;
        else
            inputs[n++] = v;
    }
    if (!output || n < 1) {
        fprintf(stderr, "mcrt: merge needs %s (see mcrt merge --help)\n",
                output ? "at least one input" : "-o OUT.exr");
        free(inputs);
        return STATUS_USAGE;
    }
    status = mcrt_merge(inputs, n, output, &st, sizeof st, error, sizeof error);
    free(inputs);
    if (status != MCRT_OK) {
        fprintf(stderr, "%s\n", error);
        return status == MCRT_ERR_NOMEM ? STATUS_FAIL : STATUS_USAGE;
    }
    code = STATUS_OK;
    if (!quiet)
        fprintf(stderr, "%s: %dx%d, %d spp, %d passes from %d file%s, est. relMSE %.6g\n", output,
                st.width, st.height, st.spp, st.passes, n, n == 1 ? "" : "s", st.est_relmse);
    return code;
}
