/* denoise.h: the `mcrt denoise` command (see mcrt(1)). */
#ifndef MCRT_CLI_DENOISE_H
#define MCRT_CLI_DENOISE_H

/* Run `mcrt denoise` with argv from "denoise"; returns the exit status: 0 done, 1 the output
 * could not be written or out of memory, 2 bad input. */
int mc_cli_denoise(int argc, char **argv);

#endif
