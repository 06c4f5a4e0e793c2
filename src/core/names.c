/* names.c: lookup and listing of the NULL-terminated name arrays of names.h. */
#include "core/names.h"

#include <stdio.h>
#include <string.h>

int mc_names_find(const char *const *names, const char *name, size_t len)
{
    int i;
    for (i = 0; names[i]; i++)
        if (strlen(names[i]) == len && memcmp(names[i], name, len) == 0)
            return i;
    return -1;
}

const char *mc_names_join(const char *const *names, const char *last, char *buf, size_t size)
{
    size_t n = 0;
    int i;
    buf[0] = '\0';
    for (i = 0; names[i] && n < size; i++) {
        const char *sep = i == 0 ? "" : names[i + 1] ? ", " : last;
        int w = snprintf(buf + n, size - n, "%s%s", sep, names[i]);
        n = w < 0 ? size : n + (size_t)w;
    }
    return buf;
}
