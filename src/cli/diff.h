/* diff.h: the `mcrt diff` command (see mcrt(1)). */
#ifndef MCRT_CLI_DIFF_H
#define MCRT_CLI_DIFF_H

/* Run `mcrt diff` with argv from "diff"; returns the exit status: 0 pass, 1 fail, 2 bad input. */
int mc_cli_diff(int argc, char **argv);

#endif
