/* file.h: reading a whole file into memory, with a size limit and an error message; writing a file
 * so that a failure never leaves a partial file or destroys the one it was to replace. */
#ifndef MCRT_FILE_H
#define MCRT_FILE_H

#include <stddef.h>
#include <stdio.h>

#include "core/diag.h"

/* Read path into a new buffer (*data, NUL-terminated so that strtod stops at the end; *len
 * excludes the NUL); the caller frees *data. Files larger than max_bytes are refused.
 * Messages name the place that asked for the file when `where` is given ("scene.mcrt:4:8: cannot
 * open 'x.obj': reason"), else they start with the path ("x.mcrt: cannot open: reason"). */
mcrt_status mc_read_file(const char *path, size_t max_bytes, const char *where, char **data,
                         size_t *len, mc_diag *d);

/* A file being written. The content goes to a new temporary file beside path, renamed over path
 * only when complete (rename(2) replaces atomically), so readers see the old file or the new one,
 * never a part. A path that exists and is not itself a regular file (a symbolic link such as
 * /dev/stdout, a device, a pipe) is written in place, through it: renaming over it would replace
 * the link, the device node or the pipe. */
struct mc_output {
    FILE *f;          /* write the content here */
    const char *path; /* the target, as given to mc_output_open */
    char *tmp;        /* the temporary file; NULL when writing in place */
};

/* Open path for writing. The temporary file is created exclusively (O_EXCL) with mode 0666, so the
 * finished file gets the permissions the umask gives any new file. */
mcrt_status mc_output_open(struct mc_output *o, const char *path, mc_diag *d);
/* Finish o: close it and, when st is MCRT_OK and everything reached the disk, put the file in
 * place; otherwise remove the temporary file, leaving the target as it was. Returns st, or the
 * error of the close or the rename (fclose flushes, so a full disk shows up there). */
mcrt_status mc_output_close(struct mc_output *o, mcrt_status st, mc_diag *d);

#endif
