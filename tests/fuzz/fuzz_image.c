/* fuzz_image.c: libFuzzer harness for the image readers (src/io: PFM, mcrt's own; EXR through
 * OpenEXRCore; PNG through libpng): the input's first byte picks the format (its value mod 3:
 * PFM, EXR, PNG), the rest is the file, read with mc_image_read and, for an EXR, its layers A and
 * B at once (mc_image_read_layers, the denoiser's path). A format the build lacks is refused
 * with a message, as any bad file. Built by `make fuzz` with clang -fsanitize=fuzzer;
 * tests/fuzz/replay.c runs it on the corpus. */
#include <stdint.h>

#include "fuzz_file.h"
#include "io/image.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const char *const suffix[3] = {"pfm", "exr", "png"};
    static char path[3][256];
    static const char *const layers[2] = {"A", "B"};
    struct image im, two[2];
    mc_diag d;
    int k;
    if (size < 1)
        return 0;
    k = data[0] % 3;
    if (fuzz_to_file(path[k], "mcrt-fuzz-image", suffix[k], data + 1, size - 1))
        return 0;
    if (mc_image_read(path[k], &im, &d) == MCRT_OK)
        mc_image_free(&im);
    if (k == 1 && mc_image_read_layers(path[k], layers, 2, two, &d) == MCRT_OK) {
        mc_image_free(&two[0]);
        mc_image_free(&two[1]);
    }
    return 0;
}
