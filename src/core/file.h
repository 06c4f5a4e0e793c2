/* file.h: reading a whole file into memory, with a size limit and an error message. */
#ifndef MCRT_FILE_H
#define MCRT_FILE_H

#include <stddef.h>

#include "core/diag.h"

/* Read path into a new buffer (*data, NUL-terminated so that strtod stops at the end; *len
 * excludes the NUL); the caller frees *data. Files larger than max_bytes are refused.
 * Messages name the place that asked for the file when `where` is given ("scene.mcrt:4:8: cannot
 * open 'x.obj': reason"), else they start with the path ("x.mcrt: cannot open: reason"). */
mcrt_status mc_read_file(const char *path, size_t max_bytes, const char *where, char **data,
                         size_t *len, mc_diag *d);

#endif
