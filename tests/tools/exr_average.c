/* exr_average.c: the per-pixel mean of several images of one size, for `make ref`: the motion-blur
 * reference is the average of POV-Ray's K clock frames (povray-mapping.md, motion-blur row).
 * usage: exr_average OUT IN... (formats by suffix, through src/io). */
#include <stdio.h>
#include <stdlib.h>

#include "io/image.h"

int main(int argc, char **argv)
{
    struct image im;
    double *sum = NULL;
    float *mean;
    size_t n = 0, i;
    int w = 0, h = 0, k;
    mc_diag d;
    if (argc < 3) {
        fprintf(stderr, "usage: exr_average OUT IN...\n");
        return 2;
    }
    for (k = 2; k < argc; k++) {
        if (mc_image_read(argv[k], &im, &d) != MCRT_OK) {
            fprintf(stderr, "exr_average: %s\n", d.msg);
            return 1;
        }
        if (!sum) {
            w = im.width, h = im.height, n = (size_t)w * (size_t)h * 3;
            if (!(sum = calloc(n, sizeof *sum))) {
                fprintf(stderr, "exr_average: out of memory\n");
                return 1;
            }
        } else if (im.width != w || im.height != h) {
            fprintf(stderr, "exr_average: %s is %dx%d, not %dx%d\n", argv[k], im.width,
                    im.height, w, h);
            return 1;
        }
        for (i = 0; i < n; i++)
            sum[i] += im.rgb[i];
        mc_image_free(&im);
    }
    if (!(mean = malloc(n * sizeof *mean))) {
        fprintf(stderr, "exr_average: out of memory\n");
        return 1;
    }
    for (i = 0; i < n; i++)
        mean[i] = (float)(sum[i] / (argc - 2));
    if (mc_image_write(argv[1], mean, w, h, &d) != MCRT_OK) {
        fprintf(stderr, "exr_average: %s\n", d.msg);
        return 1;
    }
    free(mean);
    free(sum);
    return 0;
}
