/* replay.c: runs a libFuzzer harness (fuzz_scene.c or fuzz_obj.c) on the files named on the command
 * line, without libFuzzer, so that the seed corpus and every input that once crashed stay regression
 * tests in `make test` (tests/fuzz.sh) under any compiler and under ASan/UBSan. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int main(int argc, char **argv)
{
    int i, bad = 0;
    for (i = 1; i < argc; i++) {
        FILE *f = fopen(argv[i], "rb");
        uint8_t *buf = NULL;
        size_t n = 0, cap = 0, got;
        if (!f) {
            fprintf(stderr, "replay: cannot open %s\n", argv[i]);
            bad++;
            continue;
        }
        do {
            if (n == cap) {
                uint8_t *nb = realloc(buf, cap = cap ? 2 * cap : 4096);
                if (!nb) {
                    fclose(f);
                    free(buf);
                    fprintf(stderr, "replay: out of memory\n");
                    return 1;
                }
                buf = nb;
            }
            got = fread(buf + n, 1, cap - n, f);
            n += got;
        } while (got > 0);
        fclose(f);
        LLVMFuzzerTestOneInput(buf, n);
        free(buf);
    }
    printf("replay: %d inputs, %d unreadable\n", argc - 1, bad);
    return bad != 0;
}
