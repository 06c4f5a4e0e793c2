/* merge.h: the `mcrt merge` command (see mcrt(1)). */
#ifndef MCRT_CLI_MERGE_H
#define MCRT_CLI_MERGE_H

/* Run `mcrt merge` with argv from "merge"; returns the exit status: 0 written, 1 failure (out of
 * memory), 2 bad input. */
int mc_cli_merge(int argc, char **argv);

#endif
