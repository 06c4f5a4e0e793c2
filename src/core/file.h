/* file.h: reading a whole file into memory, with a size limit and an error message. */
#ifndef MCRT_FILE_H
#define MCRT_FILE_H

#include <stddef.h>

#include "core/diag.h"

/* Read path into a new buffer (*data, NUL-terminated for convenience; *len excludes the NUL).
 * Files larger than max_bytes are refused. Messages: "PATH: cannot open: <strerror>" and the like.
 * The caller frees *data. */
mcrt_status mc_read_file(const char *path, size_t max_bytes, char **data, size_t *len, mc_diag *d);

#endif
