/* wavefront.c: the text shared by OBJ and MTL files (see wavefront.h). */
#include "scene/wavefront.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
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

/* A plain decimal [p, q) ([+-]digits[.digits][e[+-]digits]) of at most 19 significant digits,
 * whose digits m < 2^53 and power of ten 10^e with |e| <= 22 are exact doubles, is m * 10^e
 * or m / 10^-e correctly rounded by one IEEE operation (Clinger 1990, "How to read floating
 * point numbers accurately", the fast path), so bit for bit strtod's value; it is most of what
 * exporters write, and strtod's general algorithm was half the time of loading a large OBJ
 * file. Returns 0 for anything else, which strtod then reads. Only where double arithmetic is
 * done in double (FLT_EVAL_METHOD 0): x87 extended precision would round twice. */
static int fast_decimal(const char *p, const char *q, double *out)
{
#if FLT_EVAL_METHOD == 0
    static const double pow10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                     1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                     1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    uint64_t m = 0;
    int neg = 0, digits = 0, significant = 0, e = 0, exp = 0, eneg = 0, edigits = 0;
    if (p < q && (*p == '-' || *p == '+'))
        neg = *p++ == '-';
    for (; p < q && *p >= '0' && *p <= '9'; p++, digits++)
        if (m || *p != '0') {
            if (++significant > 19)
                return 0;
            m = m * 10 + (uint64_t)(*p - '0');
        }
    if (p < q && *p == '.')
        for (p++; p < q && *p >= '0' && *p <= '9'; p++, digits++, e--)
            if (m || *p != '0') {
                if (++significant > 19)
                    return 0;
                m = m * 10 + (uint64_t)(*p - '0');
            }
    if (!digits)
        return 0;
    if (p < q && (*p == 'e' || *p == 'E')) {
        if (++p < q && (*p == '-' || *p == '+'))
            eneg = *p++ == '-';
        for (; p < q && *p >= '0' && *p <= '9' && edigits < 4; p++, edigits++)
            exp = exp * 10 + (*p - '0');
        if (!edigits)
            return 0;
        e += eneg ? -exp : exp;
    }
    if (p != q || m >= (uint64_t)1 << 53 || e < -22 || e > 22)
        return 0;
    *out = e >= 0 ? (double)m * pow10[e] : (double)m / pow10[-e];
    if (neg)
        *out = -*out;
    return 1;
#else
    (void)p, (void)q, (void)out;
    return 0;
#endif
}

mcrt_status mc_wf_number(const struct wf_reader *r, const char *p, const char *q, double *out)
{
    char *endp = NULL;
    char buf[48];
    double v = 0.0;
    if (fast_decimal(p, q, out))
        return MCRT_OK;
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
