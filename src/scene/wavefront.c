/* wavefront.c: the text shared by OBJ and MTL files (see wavefront.h). */
#include "scene/wavefront.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

mcrt_status mc_wf_fail(const struct wf_reader *r, const char *p, const char *fmt, ...)
{
    char what[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    return mc_fail(r->d, MCRT_ERR_PARSE, "%s:%d:%d: %s", r->path, r->line,
                   (int)(p - r->line_start) + 1, what);
}

const char *mc_wf_show(const char *p, const char *e, char buf[48])
{
    size_t i, n = (size_t)(e - p) > 40 ? 40 : (size_t)(e - p);
    for (i = 0; i < n; i++)
        buf[i] = p[i] > 0x20 && p[i] < 0x7f ? p[i] : '?';
    strcpy(buf + n, (size_t)(e - p) > n ? "..." : "");
    return buf;
}

mcrt_status mc_wf_check_keyword(const struct wf_reader *r, const char *p, const char *q)
{
    for (; p < q; p++)
        if (*p <= 0x20 || *p >= 0x7f)
            return mc_wf_fail(r, p, "unexpected byte 0x%02x", (unsigned char)*p);
    return MCRT_OK;
}

mcrt_status mc_wf_number(const struct wf_reader *r, const char *p, const char *q, double *out)
{
    char *endp = NULL;
    char buf[48];
    double v = 0.0;
    if (q - p > 255) /* as in scene files; it also bounds the time strtod may take */
        return mc_wf_fail(r, p, "number longer than 255 characters");
    /* strtod skips leading white space, newlines included: never let it start on one. The
     * buffer's final NUL stops it at the end of the file. */
    errno = 0;
    if (*p != '\f' && *p != '\v')
        v = strtod(p, &endp);
    if (endp != q)
        return mc_wf_fail(r, p, "malformed number '%s'", mc_wf_show(p, q, buf));
    if (!isfinite(v) && errno != ERANGE)
        return mc_wf_fail(r, p, "'%s' is not a finite number", mc_wf_show(p, q, buf));
    if (!isfinite(v) || fabs(v) > FLT_MAX)
        return mc_wf_fail(r, p, "number '%s' is too large (the largest is about 3.4e38)",
                          mc_wf_show(p, q, buf));
    *out = v;
    return MCRT_OK;
}

/* Line and column of byte z in buf, for a message about it. */
static void locate(struct wf_reader *r, const char *buf, const char *z)
{
    const char *p;
    r->line = 1;
    r->line_start = buf;
    for (p = buf; p < z; p++)
        if (*p == '\n') {
            r->line++;
            r->line_start = p + 1;
        }
}

mcrt_status mc_wf_lines(struct wf_reader *r, const char *buf, size_t len,
                        mcrt_status (*line)(void *user, const char *p, const char *le), void *user)
{
    const char *p = buf, *end = buf + len, *z = memchr(buf, '\0', len);
    mcrt_status st = MCRT_OK;
    if (z) {
        locate(r, buf, z);
        return mc_wf_fail(r, z, "unexpected byte 0x00 (%s is text)", r->kind);
    }
    if (len >= 3 && memcmp(p, "\xef\xbb\xbf", 3) == 0)
        p += 3; /* a UTF-8 byte order mark */
    r->line = 0;
    while (p < end && !st) {
        const char *le = memchr(p, '\n', (size_t)(end - p));
        if (!le)
            le = end;
        r->line++;
        r->line_start = p;
        st = line(user, p, le);
        p = le + 1;
    }
    return st;
}
