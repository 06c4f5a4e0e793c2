/* file.c: whole-file reads (see file.h). */
#include "core/file.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

mcrt_status mc_read_file(const char *path, size_t max_bytes, char **data, size_t *len, mc_diag *d)
{
    FILE *fp = fopen(path, "rb");
    char *buf = NULL;
    size_t n = 0, cap = 0;
    *data = NULL;
    *len = 0;
    if (!fp)
        return mc_fail(d, MCRT_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    /* Grow as we read: works for pipes and for files whose size changes, and needs no seeking.
     * The buffer never exceeds max_bytes + 2, so reading a byte past the limit is detected. */
    for (;;) {
        size_t got;
        if (cap - n < 2) {
            size_t ncap = cap ? cap * 2 : 65536;
            char *p;
            if (ncap > max_bytes + 2)
                ncap = max_bytes + 2;
            p = realloc(buf, ncap);
            if (!p) {
                free(buf);
                fclose(fp);
                return mc_fail(d, MCRT_ERR_NOMEM, "%s: out of memory reading the file", path);
            }
            buf = p;
            cap = ncap;
        }
        got = fread(buf + n, 1, cap - n - 1, fp);
        n += got;
        if (n > max_bytes) {
            free(buf);
            fclose(fp);
            return mc_fail(d, MCRT_ERR_IO, "%s: file is larger than %zu bytes", path, max_bytes);
        }
        if (got == 0)
            break;
    }
    if (ferror(fp)) {
        int e = errno;
        free(buf);
        fclose(fp);
        return mc_fail(d, MCRT_ERR_IO, "%s: cannot read: %s", path, strerror(e));
    }
    fclose(fp);
    buf[n] = '\0';
    *data = buf;
    *len = n;
    return MCRT_OK;
}
