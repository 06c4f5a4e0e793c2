/* envmap_gen.c: latitude-longitude environment maps (man/mcrt.5, environment map) for the tests
 * and scenes/sky.mcrt, so that no image needs a licence.
 * usage: envmap_gen KIND W H OUT, KIND one of
 *   sky       a blue sky brightening to the horizon, a grey ground and a sun of radiance 2000
 *             about 1.5° across at u = 0.62, v = 0.3 (elevation 36°, front right)
 *   sun       grey 0.05 with one pixel of 2000 at u = 0.75, v = 0.3 (toward +x, 36° up)
 *   pole      grey 0.05 with a top row of 2000: a sun on the pole
 *   seam      grey 0.05 with pixels of 2000 in the first and last columns: suns on the seam
 *   constant  1 everywhere
 *   nan       1 with pixel (1, 0) NaN
 * The format follows OUT's suffix (src/io). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/image.h"

static const double PI = 3.14159265358979323846;

static void sky(float *c, double u, double v, int w, int h)
{
    double theta = PI * v, phi = 2.0 * PI * (u - 0.5);
    double d[3] = {sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi)};
    double st = 2.0 * PI * (0.62 - 0.5), sv = PI * 0.3;
    double s[3] = {sin(sv) * sin(st), cos(sv), -sin(sv) * cos(st)};
    double cosang = d[0] * s[0] + d[1] * s[1] + d[2] * s[2];
    /* The sun's disc is at least a pixel wide, so that it shows at any size. */
    double sun_radius = fmax(0.013, 1.5 * PI / h);
    (void)w;
    if (cosang > cos(sun_radius)) {
        c[0] = 2000.0f, c[1] = 1900.0f, c[2] = 1700.0f;
    } else if (d[1] >= 0.0) {
        double t = pow(1.0 - d[1], 3.0); /* 0 at the zenith, 1 at the horizon */
        c[0] = (float)(0.25 + 0.75 * t), c[1] = (float)(0.45 + 0.5 * t), c[2] = (float)(1.0);
    } else {
        c[0] = c[1] = c[2] = 0.15f;
    }
}

int main(int argc, char **argv)
{
    int w, h, x, y;
    float *rgb;
    mc_diag d;
    if (argc != 5 || (w = atoi(argv[2])) < 1 || (h = atoi(argv[3])) < 1) {
        fprintf(stderr, "usage: envmap_gen sky|sun|pole|seam|constant|nan W H OUT\n");
        return 2;
    }
    rgb = malloc((size_t)w * (size_t)h * 3 * sizeof *rgb);
    if (!rgb) {
        fprintf(stderr, "envmap_gen: out of memory\n");
        return 1;
    }
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            float *c = &rgb[3 * ((size_t)y * (size_t)w + (size_t)x)];
            double u = (x + 0.5) / w, v = (y + 0.5) / h;
            if (!strcmp(argv[1], "sky"))
                sky(c, u, v, w, h);
            else if (!strcmp(argv[1], "sun"))
                c[0] = c[1] = c[2] = x == (int)(0.75 * w) && y == (int)(0.3 * h) ? 2000.0f : 0.05f;
            else if (!strcmp(argv[1], "pole"))
                c[0] = c[1] = c[2] = y == 0 ? 2000.0f : 0.05f;
            else if (!strcmp(argv[1], "seam"))
                c[0] = c[1] = c[2] = (x == 0 || x == w - 1) && y == h / 3 ? 2000.0f : 0.05f;
            else if (!strcmp(argv[1], "constant"))
                c[0] = c[1] = c[2] = 1.0f;
            else if (!strcmp(argv[1], "nan"))
                c[0] = c[1] = c[2] = x == 1 && y == 0 ? (float)NAN : 1.0f;
            else {
                fprintf(stderr, "envmap_gen: unknown kind '%s'\n", argv[1]);
                free(rgb);
                return 2;
            }
        }
    if (mc_image_write(argv[4], rgb, w, h, &d) != MCRT_OK) {
        fprintf(stderr, "envmap_gen: %s\n", d.msg);
        free(rgb);
        return 1;
    }
    free(rgb);
    return 0;
}
