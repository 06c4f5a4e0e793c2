/* fuzz_obj.c: libFuzzer harness for the OBJ reader: the input is an OBJ file's bytes, loaded with
 * mc_obj_load under a non-trivial transform (scale, rotation, mirror) and, when it loads, prepared
 * (BVH, light table of its emitting triangles) so that garbage geometry reaches the builder too.
 * Built by `make fuzz` with clang -fsanitize=fuzzer; tests/fuzz/replay.c runs it on the corpus. */
#include <stdint.h>
#include <string.h>

#include "fuzz_file.h"
#include "scene/obj.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* mc_obj_load reads a file: the input goes to a per-process file in TMPDIR (or /tmp). */
    static char path[256];
    static const float xf[12] = {0.0f, -2.0f, 0.0f, 1.0f, 3.0f, 0.0f, 0.0f, -1.0f, 0.0f, 0.0f, -0.5f, 1e3f};
    struct scene s;
    struct obj_mesh m;
    mc_diag d;
    if (fuzz_to_file(path, "mcrt-fuzz-obj", "obj", data, size))
        return 0;
    mc_scene_init(&s);
    memset(&m, 0, sizeof m);
    m.path = path;
    m.origin = "fuzz.mcrt:1:1";
    memcpy(m.xform, xf, sizeof xf);
    m.proto.material = 0;
    m.proto.light = -1;
    m.proto.normals = -1;
    m.proto.emit = v3(1.0f, 2.0f, 0.5f); /* emitting, so that prepare builds area lights too */
    if (mc_obj_load(&s, &m, NULL, &d) == MCRT_OK)
        (void)mc_scene_prepare(&s, &d);
    mc_scene_free(&s);
    return 0;
}
