/* fuzz_scene.c: libFuzzer harness for the scene parser: the input is scene text given to
 * mc_scene_parse (no file of its own), and a scene that parses is prepared (BVH, light table).
 * Built by `make fuzz` with clang -fsanitize=fuzzer; tests/fuzz/replay.c runs it on the corpus. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "scene/scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct scene s;
    mc_diag d;
    /* Mesh paths resolve from the current directory (so seeds can name scenes/cube.obj); device
     * and proc files are skipped because reading /dev/zero up to the 1 GiB OBJ limit is a slow
     * input, not a parser bug. */
    static const char *const skip[] = {"/dev", "/proc", "/sys"};
    size_t i;
    for (i = 0; i < sizeof skip / sizeof skip[0]; i++) {
        size_t k = strlen(skip[i]), j;
        for (j = 0; j + k <= size; j++)
            if (memcmp(data + j, skip[i], k) == 0)
                return 0;
    }
    mc_scene_init(&s);
    if (mc_scene_parse(&s, (const char *)data, size, "fuzz.mcrt", NULL, &d) == MCRT_OK)
        (void)mc_scene_prepare(&s, &d);
    mc_scene_free(&s);
    return 0;
}
