/* fuzz_mtl.c: libFuzzer harness for the MTL reader: the input is an MTL file's bytes, read with
 * mc_mtl_load and, when it loads, each material put on a triangle of a scene (mc_mtl_use, with
 * its map_Kd's texture) with its Ke, and the scene prepared (the materials' tables, the area
 * lights of the emitting ones), so that what the reader lets through reaches the materials' own
 * preparation too.
 * Built by `make fuzz` with clang -fsanitize=fuzzer; tests/fuzz/replay.c runs it on the corpus. */
#include <stdint.h>
#include <string.h>

#include "fuzz_file.h"
#include "scene/mtl.h"
#include "scene/scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* mc_mtl_load reads a file: the input goes to a per-process file in TMPDIR (or /tmp). */
    static char path[256];
    struct scene s;
    struct mtl_library lib;
    mc_diag d;
    size_t i;
    if (fuzz_to_file(path, "mcrt-fuzz-mtl", "mtl", data, size))
        return 0;
    mc_scene_init(&s);
    memset(&lib, 0, sizeof lib);
    if (mc_mtl_load(&lib, path, "fuzz.obj:1:8", &s, &d) == MCRT_OK) {
        for (i = 0; i < lib.n; i++) {
            struct prim t;
            memset(&t, 0, sizeof t);
            t.kind = PRIM_TRIANGLE;
            t.light = -1;
            t.normals = -1;
            t.material = mc_mtl_use(&lib, i, &s);
            t.emit = lib.e[i].emit;
            t.p[0] = v3((float)i, 0.0f, 0.0f);
            t.p[1] = v3((float)i + 1.0f, 0.0f, 0.0f);
            t.p[2] = v3((float)i, 1.0f, 0.0f);
            if (t.material < 0 || mc_scene_add_prim(&s, &t) < 0)
                break;
        }
        (void)mc_scene_prepare(&s, &d);
    }
    mc_mtl_free(&lib);
    mc_scene_free(&s);
    return 0;
}
