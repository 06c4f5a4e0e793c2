/* file_util.h: files read whole and scene files with another film, for the tests and the tools
 * (header only, like render_util.h). */
#ifndef MCRT_TEST_FILE_UTIL_H
#define MCRT_TEST_FILE_UTIL_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The whole file, NUL-terminated, in a new buffer; *len (when not NULL) gets its size. NULL (and
 * *len 0) when it cannot be read or memory runs out. */
static inline char *t_read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    char *buf = NULL;
    long n;
    if (len)
        *len = 0;
    if (!f)
        return NULL;
    if (fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0
        && (buf = malloc((size_t)n + 1)) != NULL) {
        if (fread(buf, 1, (size_t)n, f) != (size_t)n) {
            free(buf);
            buf = NULL;
        } else {
            buf[n] = '\0';
            if (len)
                *len = (size_t)n;
        }
    }
    fclose(f);
    return buf;
}

/* The scene file at path with its `film { ... }` block (which must start a line) replaced by the
 * text film and the text extra appended; NULL when the file cannot be read or has no film block. */
static inline char *t_scene_with_film(const char *path, const char *film, const char *extra)
{
    char *text = t_read_file(path, NULL), *out = NULL, *at, *end;
    if (text && (at = strstr(text, "\nfilm {")) != NULL && (end = strchr(at, '}')) != NULL
        && (out = malloc(strlen(text) + strlen(film) + strlen(extra) + 3)) != NULL) {
        at[1] = '\0';
        sprintf(out, "%s%s%s\n%s", text, film, end + 1, extra);
    }
    free(text);
    return out;
}

#endif
