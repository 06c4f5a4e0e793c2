/* converge.h: the `mcrt converge` command (see mcrt(1)). */
#ifndef MCRT_CLI_CONVERGE_H
#define MCRT_CLI_CONVERGE_H

/* Run `mcrt converge` with argv from "converge"; returns the exit status (0, 1 or 2). */
int mc_cli_converge(int argc, char **argv);

#endif
