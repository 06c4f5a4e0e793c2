/* diag.h: an error message buffer carried by every fallible internal call.
 * Internal functions return an mcrt_status and, on failure, fill a diag with one line of text
 * ("file:line:col: what is wrong" for input errors). Nothing is printed by the library. */
#ifndef MCRT_DIAG_H
#define MCRT_DIAG_H

#include "mcrt.h"

typedef struct mc_diag { char msg[512]; } mc_diag;

#if defined(__GNUC__)
#define MC_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define MC_PRINTF(f, a)
#endif

/* Format a message into d (truncated to fit) and return status, so a caller can write
 * `return mc_fail(d, MCRT_ERR_IO, "cannot open '%s'", path);`. d may be NULL. */
mcrt_status mc_fail(mc_diag *d, mcrt_status status, const char *fmt, ...) MC_PRINTF(3, 4);

#endif
