/* file.c: whole-file reads (see file.h). */
#include "core/file.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* "WHERE: what 'PATH': reason" or "PATH: what: reason". */
static mcrt_status fail(mc_diag *d, mcrt_status st, const char *where, const char *path,
                        const char *what, const char *reason)
{
    if (where)
        return mc_fail(d, st, "%s: %s '%s': %s", where, what, path, reason);
    return mc_fail(d, st, "%s: %s: %s", path, what, reason);
}

mcrt_status mc_read_file(const char *path, size_t max_bytes, const char *where, char **data,
                         size_t *len, mc_diag *d)
{
    FILE *fp = fopen(path, "rb");
    char *buf = NULL, limit[64];
    size_t n = 0, cap = 0;
    struct stat st;
    *data = NULL;
    *len = 0;
    snprintf(limit, sizeof limit, "larger than the limit of %zu MiB", max_bytes >> 20);
    if (!fp)
        return fail(d, MCRT_ERR_IO, where, path, "cannot open", strerror(errno));
    /* A regular file that is too large is refused before anything is read. */
    if (fstat(fileno(fp), &st) == 0 && S_ISREG(st.st_mode) && (uintmax_t)st.st_size > max_bytes) {
        fclose(fp);
        return fail(d, MCRT_ERR_IO, where, path, "cannot read", limit);
    }
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
                return fail(d, MCRT_ERR_NOMEM, where, path, "cannot read", "out of memory");
            }
            buf = p;
            cap = ncap;
        }
        got = fread(buf + n, 1, cap - n - 1, fp);
        n += got;
        if (n > max_bytes) {
            free(buf);
            fclose(fp);
            return fail(d, MCRT_ERR_IO, where, path, "cannot read", limit);
        }
        if (got == 0)
            break;
    }
    if (ferror(fp)) {
        int e = errno;
        free(buf);
        fclose(fp);
        return fail(d, MCRT_ERR_IO, where, path, "cannot read", strerror(e));
    }
    fclose(fp);
    buf[n] = '\0';
    *data = buf;
    *len = n;
    return MCRT_OK;
}
