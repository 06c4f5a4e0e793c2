/* model_gen.c: the textured OBJ model of scenes/vase.mcrt, so that no model or image needs a
 * licence: a vase turned on a lathe (vase.obj, with texture coordinates and smooth normals), its
 * materials (vase.mtl: a glazed body whose colour is an image, an unglazed foot) and the glaze's
 * painted pattern (vase-glaze.png, 512 x 256, cream with blue bands and a wave).
 * usage: model_gen DIR   (writes DIR/vase.obj, DIR/vase.mtl, DIR/vase-glaze.png) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/image.h"

static const double PI = 3.14159265358979323846;

#define AROUND 64  /* segments around the axis */
#define UP 32      /* segments along the profile */
#define HEIGHT 1.6
#define TW 512
#define TH 256

/* The profile: the radius at height fraction t in [0, 1], a belly below a narrow neck that flares
 * at the lip. */
static double radius(double t)
{
    double belly = 0.42 * pow(sin(PI * (0.12 + 0.8 * t)), 1.5) * (1.0 - 0.55 * t);
    double lip = 0.14 * pow(fmax(0.0, (t - 0.78) / 0.22), 2.0);
    return 0.2 + belly + lip;
}

static double smooth(double e0, double e1, double x)
{
    double t = fmin(1.0, fmax(0.0, (x - e0) / (e1 - e0)));
    return t * t * (3.0 - 2.0 * t);
}

/* The glaze at texture coordinates (u around, v up), a linear reflectance. */
static void glaze(double u, double v, float *c)
{
    static const double cream[3] = {0.80, 0.72, 0.55}, blue[3] = {0.04, 0.09, 0.38};
    double wave = 0.5 + 0.07 * sin(2.0 * PI * 6.0 * u), ink = 0.0;
    int i;
    /* Two bands near the foot and the lip, a thin one under the neck, the wave between. */
    ink = fmax(ink, smooth(0.08, 0.09, v) - smooth(0.15, 0.16, v));
    ink = fmax(ink, smooth(0.86, 0.87, v));
    ink = fmax(ink, 1.0 - smooth(0.0, 0.008, fabs(v - 0.72)));
    ink = fmax(ink, 1.0 - smooth(0.012, 0.02, fabs(v - wave)));
    /* Dots between the wave's crests. */
    {
        double du = fmod(u * 6.0 + 0.25, 1.0) - 0.5, dv = (v - 0.36) * 3.0;
        ink = fmax(ink, 1.0 - smooth(0.05, 0.07, sqrt(du * du + dv * dv)));
    }
    for (i = 0; i < 3; i++)
        c[i] = (float)(cream[i] + (blue[i] - cream[i]) * fmin(1.0, fmax(0.0, ink)));
}

static int write_obj(const char *path)
{
    FILE *f = fopen(path, "w");
    int i, j, n = AROUND + 1;
    if (!f)
        return -1;
    fprintf(f, "# vase.obj: a vase turned on a lathe, made by tests/tools/model_gen.c\n"
               "mtllib vase.mtl\n");
    /* The surface's vertices, row j at height fraction j / UP, column i at angle 2 pi i / AROUND
     * (the last column repeats the first, with u = 1), and the foot's centre last. */
    for (j = 0; j <= UP; j++) {
        double t = (double)j / UP, r = radius(t), h = 1e-4;
        /* The profile's normal: perpendicular to (dr/dy, 1) in the (r, y) plane. */
        double dr = (radius(fmin(1.0, t + h)) - radius(fmax(0.0, t - h))) /
                    ((fmin(1.0, t + h) - fmax(0.0, t - h)) * HEIGHT);
        double nl = sqrt(1.0 + dr * dr), nr = 1.0 / nl, ny = -dr / nl;
        for (i = 0; i < n; i++) {
            double a = 2.0 * PI * i / AROUND, ca = cos(a), sa = sin(a);
            fprintf(f, "v %.5f %.5f %.5f\nvt %.5f %.5f\nvn %.5f %.5f %.5f\n", r * ca, t * HEIGHT,
                    -r * sa, (double)i / AROUND, t, nr * ca, ny, -nr * sa);
        }
    }
    fprintf(f, "v 0 0 0\nvt 0.5 0\nvn 0 -1 0\n");
    fprintf(f, "usemtl glaze\n");
    for (j = 0; j < UP; j++)
        for (i = 0; i < AROUND; i++) {
            int a = 1 + j * n + i, b = a + 1, c = b + n, d = a + n;
            fprintf(f, "f %d/%d/%d %d/%d/%d %d/%d/%d %d/%d/%d\n", a, a, a, b, b, b, c, c, c, d, d, d);
        }
    /* The foot: a fan under the bottom row, facing down, flat. */
    fprintf(f, "usemtl foot\n");
    for (i = 0; i < AROUND; i++) {
        int a = 1 + i, b = a + 1, z = n * (UP + 1) + 1;
        fprintf(f, "f %d %d %d\n", z, b, a);
    }
    return fclose(f) == 0 ? 0 : -1;
}

static int write_mtl(const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    fprintf(f, "# vase.mtl: made by tests/tools/model_gen.c\n"
               "# A glaze: a plastic whose albedo is the painted image, with a sharp highlight\n"
               "newmtl glaze\nKd 1 1 1\nKs 0.04 0.04 0.04\nNs 400\nNi 1.5\nillum 2\nmap_Kd vase-glaze.png\n"
               "# The unglazed foot: terracotta\n"
               "newmtl foot\nKd 0.35 0.16 0.08\nillum 1\n");
    return fclose(f) == 0 ? 0 : -1;
}

int main(int argc, char **argv)
{
    char path[1024];
    float *img;
    mc_diag d;
    int x, y;
    if (argc != 2) {
        fprintf(stderr, "usage: model_gen DIR\n");
        return 2;
    }
    snprintf(path, sizeof path, "%s/vase.obj", argv[1]);
    if (write_obj(path) != 0) {
        fprintf(stderr, "model_gen: cannot write %s\n", path);
        return 1;
    }
    snprintf(path, sizeof path, "%s/vase.mtl", argv[1]);
    if (write_mtl(path) != 0) {
        fprintf(stderr, "model_gen: cannot write %s\n", path);
        return 1;
    }
    if (!(img = malloc(sizeof *img * TW * TH * 3)))
        return 1;
    /* Texel (x, y) from the top is centred at u = (x + 1/2) / w, v = 1 - (y + 1/2) / h. */
    for (y = 0; y < TH; y++)
        for (x = 0; x < TW; x++)
            glaze((x + 0.5) / TW, 1.0 - (y + 0.5) / TH, &img[3 * (y * TW + x)]);
    snprintf(path, sizeof path, "%s/vase-glaze.png", argv[1]);
    if (mc_image_write(path, img, TW, TH, &d) != MCRT_OK) {
        fprintf(stderr, "model_gen: %s\n", d.msg);
        free(img);
        return 1;
    }
    free(img);
    return 0;
}
