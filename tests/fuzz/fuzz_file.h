/* fuzz_file.h: the harnesses of readers that open a file (fuzz_obj.c, fuzz_mtl.c) write the
 * fuzzer's input to one first. */
#ifndef MCRT_FUZZ_FILE_H
#define MCRT_FUZZ_FILE_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

/* Write data to a per-process file NAME-PID.SUFFIX in TMPDIR (or /tmp), named in path (kept by
 * the caller between calls); 0, or -1 when it cannot be written. */
static int fuzz_to_file(char path[256], const char *name, const char *suffix, const uint8_t *data,
                        size_t size)
{
    FILE *f;
    if (!path[0]) {
        const char *dir = getenv("TMPDIR");
        snprintf(path, 256, "%s/%s-%ld.%s", dir && dir[0] ? dir : "/tmp", name, (long)getpid(), suffix);
    }
    if (!(f = fopen(path, "wb")))
        return -1;
    if (size && fwrite(data, 1, size, f) != size) {
        fclose(f);
        return -1;
    }
    return fclose(f) == 0 ? 0 : -1;
}

#endif
