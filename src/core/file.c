/* file.c: whole-file reads and all-or-nothing writes (see file.h). */
#include "core/file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/alloc.h"

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
            p = mc_realloc(buf, ncap);
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

static mcrt_status cannot_write(mc_diag *d, mcrt_status st, const char *path, const char *reason)
{
    return mc_fail(d, st, "cannot write '%s': %s", path, reason);
}

mcrt_status mc_output_open(struct mc_output *o, const char *path, mc_diag *d)
{
    size_t len = strlen(path) + 48;
    struct stat sb;
    int attempt, fd = -1, e;
    o->path = path;
    o->tmp = NULL;
    /* lstat, not stat: /dev/stdout is a symbolic link, and renaming over it would replace the
     * link itself, even when it leads to a regular file (output redirected to a file). */
    if (lstat(path, &sb) == 0 && !S_ISREG(sb.st_mode)) {
        o->f = fopen(path, "wb");
        return o->f ? MCRT_OK : cannot_write(d, MCRT_ERR_IO, path, strerror(errno));
    }
    if (!(o->tmp = mc_malloc(len)))
        return cannot_write(d, MCRT_ERR_NOMEM, path, "out of memory");
    for (attempt = 0; attempt < 100 && fd < 0; attempt++) {
        snprintf(o->tmp, len, "%s.tmp-%ld-%d", path, (long)getpid(), attempt);
        fd = open(o->tmp, O_WRONLY | O_CREAT | O_EXCL, 0666);
        if (fd < 0 && errno != EEXIST)
            break;
    }
    o->f = fd >= 0 ? fdopen(fd, "wb") : NULL;
    if (o->f)
        return MCRT_OK;
    e = errno;
    if (fd >= 0) {
        close(fd);
        unlink(o->tmp);
    }
    free(o->tmp);
    o->tmp = NULL;
    return cannot_write(d, e == ENOMEM ? MCRT_ERR_NOMEM : MCRT_ERR_IO, path, strerror(e));
}

mcrt_status mc_output_close(struct mc_output *o, mcrt_status st, mc_diag *d)
{
    int failed = ferror(o->f);
    if (fclose(o->f) != 0 || failed) {
        if (st == MCRT_OK)
            st = cannot_write(d, MCRT_ERR_IO, o->path, failed ? "write error" : strerror(errno));
    } else if (st == MCRT_OK && o->tmp && rename(o->tmp, o->path) != 0) {
        st = cannot_write(d, MCRT_ERR_IO, o->path, strerror(errno));
    }
    if (st != MCRT_OK && o->tmp)
        unlink(o->tmp);
    free(o->tmp);
    o->tmp = NULL;
    o->f = NULL;
    return st;
}
