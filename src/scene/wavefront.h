/* wavefront.h: the line-oriented text that Wavefront's OBJ and MTL files share (obj.c, mtl.c):
 * a file read whole and scanned line by line in place, statements of blank-separated tokens,
 * numbers, and messages "path:line:col: what" at a byte of the current line. */
#ifndef MCRT_WAVEFRONT_H
#define MCRT_WAVEFRONT_H

#include <stddef.h>

#include "core/diag.h"

/* Where a reader is: the file (its name in messages), the current line and its first byte. */
struct wf_reader {
    const char *path;
    const char *kind;       /* "an OBJ file", for the message about a NUL byte */
    int line;
    const char *line_start;
    mc_diag *d;
};

static inline int mc_wf_is_blank(int c) { return c == ' ' || c == '\t' || c == '\r'; }

static inline const char *mc_wf_skip_blank(const char *p, const char *le)
{
    while (p < le && mc_wf_is_blank((unsigned char)*p))
        p++;
    return p;
}

static inline const char *mc_wf_token_end(const char *p, const char *le)
{
    while (p < le && !mc_wf_is_blank((unsigned char)*p))
        p++;
    return p;
}

/* The end of a name that is the rest of the line from p (after a newmtl or usemtl): at a '#' or
 * the line's end, the blanks before it dropped, so that a name may hold blanks. */
static inline const char *mc_wf_name_end(const char *p, const char *le)
{
    const char *q = p;
    while (q < le && *q != '#')
        q++;
    while (q > p && mc_wf_is_blank((unsigned char)q[-1]))
        q--;
    return q;
}

/* Fail with MCRT_ERR_PARSE at the column of p on the current line: "path:line:col: what". */
mcrt_status mc_wf_fail(const struct wf_reader *r, const char *p, const char *fmt, ...) MC_PRINTF(3, 4);

/* The token [p, e) for a message: at most 40 bytes, bytes that are not printable ASCII as '?',
 * "..." when cut. */
const char *mc_wf_show(const char *p, const char *e, char buf[48]);

/* MCRT_OK when the keyword [p, q) is printable ASCII, else a message at its first other byte. */
mcrt_status mc_wf_check_keyword(const struct wf_reader *r, const char *p, const char *q);

/* The number that is the whole token [p, q): finite and within a float's range, else a message
 * at p. The file's buffer must end in a NUL (mc_read_file's does). */
mcrt_status mc_wf_number(const struct wf_reader *r, const char *p, const char *q, double *out);

/* Call line(user, first byte, end) for each line of buf[0, len) (without its '\n'), r->line and
 * r->line_start set, until one fails; a NUL byte anywhere is an error (the file is not text) and a
 * leading UTF-8 byte order mark is skipped. */
mcrt_status mc_wf_lines(struct wf_reader *r, const char *buf, size_t len,
                        mcrt_status (*line)(void *user, const char *p, const char *le), void *user);

#endif
