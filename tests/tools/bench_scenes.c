/* bench_scenes.c: the generated scenes of make bench's efficiency comparison against Mitsuba 3
 * (tests/tools/mitsuba_bench.py; issue 19), too large to keep in scenes/:
 *   many-lights.mcrt  10,000 small emitting triangles in four colours over a 24 x 24 floor among
 *                     spheres: each point is lit mostly by the few lights near it;
 *   terrain.mcrt      the 1,000,000-triangle terrain of terrain.h (terrain.obj) under a small
 *                     quad light and a constant sky.
 * Both choose lights with the light tree (mcrt.5, integrator light_select). The positions come
 * from a fixed integer hash, so the files are the same on every machine.
 * usage: bench_scenes DIR   (writes DIR/many-lights.mcrt, DIR/terrain.mcrt, DIR/terrain.obj) */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "terrain.h"

enum { GRID = 100 }; /* GRID x GRID lights */

/* A uniform number in [0, 1) from an index (the finaliser of SplitMix64, Steele et al. 2014). */
static double hash01(uint64_t i)
{
    uint64_t z = i * 0x9e3779b97f4a7c15u + 0x632be59bd9b4e019u;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

static int many_lights(const char *path)
{
    /* Radiances: warm, cool, green and pink lanterns, of about the same luminance. */
    static const double colour[4][3] = {{28, 19, 10}, {10, 16, 28}, {16, 25, 10}, {25, 10, 19}};
    FILE *f = fopen(path, "w");
    int i, j;
    if (!f)
        return 0;
    fprintf(f, "# many-lights.mcrt, written by tests/tools/bench_scenes.c: %d small emitting\n"
               "# triangles facing down over a diffuse floor among spheres. The light tree picks the\n"
               "# lights near each point; choosing by power (or Mitsuba's uniform choice) mostly\n"
               "# picks far ones.\n"
               "film { width 320 height 180 spp 64 }\n"
               "camera { eye 0 7 13  look 0 0 -1  up 0 1 0  fov 50 }\n"
               "integrator { light_select tree }\n"
               "material floor { diffuse 0.5 }\n"
               "material clay  { diffuse 0.7 0.5 0.35 }\n"
               "material steel { metal 0.75 roughness 0.3 }\n"
               "material lamp  { diffuse 0.5 }\n"
               "quad { corner -12 0 12  edge1 24 0 0  edge2 0 0 -24  material floor }\n",
            GRID * GRID);
    for (i = 0; i < 9; i++) {
        double x = -8.0 + 8.0 * (i % 3) + 2.0 * (hash01(2 * i) - 0.5);
        double z = -8.0 + 8.0 * (i / 3) + 2.0 * (hash01(2 * i + 1) - 0.5);
        fprintf(f, "sphere { center %.4f 0.9 %.4f  radius 0.9  material %s }\n", x, z,
                i % 2 ? "steel" : "clay");
    }
    for (j = 0; j < GRID; j++)
        for (i = 0; i < GRID; i++) {
            uint64_t k = 8u * (uint64_t)(j * GRID + i) + 100u;
            /* A cell of the 24 x 24 grid; the triangle's first corner anywhere in it, at a height
             * from 0.3 to 2.3, its two edges 0.06 long at an angle t about the vertical and tilted
             * up to 0.1 of their length (under 8 degrees): the camera, which sees every lamp from
             * more than 10 degrees above, sees only their backs. (An emitter smaller than a
             * pixel seen directly makes the pixel's error heavy-tailed, which the crosscheck's
             * variance estimate cannot follow.) (c 0 s) x (-s 0 c) = (0 -1 0): it faces down. */
            double x = -12.0 + 24.0 * (i + hash01(k)) / GRID;
            double z = -12.0 + 24.0 * (j + hash01(k + 1)) / GRID;
            double y = 0.3 + 2.0 * hash01(k + 2), t = 2.0 * 3.14159265358979 * hash01(k + 3);
            double e = 0.06, c = e * cos(t), s = e * sin(t);
            double ty1 = e * 0.1 * (2.0 * hash01(k + 4) - 1.0);
            double ty2 = e * 0.1 * (2.0 * hash01(k + 5) - 1.0);
            const double *rgb = colour[(int)(4.0 * hash01(k + 6))];
            fprintf(f, "triangle { v0 %.4f %.4f %.4f  v1 %.4f %.4f %.4f  v2 %.4f %.4f %.4f  "
                       "emit %g %g %g  material lamp }\n",
                    x, y, z, x + c, y + ty1, z + s, x - s, y + ty2, z + c, rgb[0], rgb[1], rgb[2]);
        }
    return fclose(f) == 0;
}

static int terrain(const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return 0;
    fputs("# terrain.mcrt, written by tests/tools/bench_scenes.c: the 1,000,000 triangles of\n"
          "# terrain.obj (2 x 1, waves 0.05 high) under a 0.6 x 0.4 quad light and a blue sky.\n"
          "film { width 256 height 256 spp 64 }\n"
          "camera { eye 0 1.2 1.6  look 0 0 0  up 0 1 0  fov 40 }\n"
          "integrator { light_select tree }\n"
          "material ground { diffuse 0.6 0.5 0.4 }\n"
          "mesh { file \"terrain.obj\"  material ground }\n"
          "# (0.6 0 0) x (0 0 0.4) = (0 -0.24 0): the light faces down.\n"
          "quad { corner -0.3 1.5 -0.2  edge1 0.6 0 0  edge2 0 0 0.4  emit 15 }\n"
          "environment { radiance 0.15 0.2 0.3 }\n",
          f);
    return fclose(f) == 0;
}

int main(int argc, char **argv)
{
    char path[4096];
    const char *dir = argc == 2 ? argv[1] : NULL;
    if (!dir || strlen(dir) > sizeof path - 32) {
        fprintf(stderr, "usage: bench_scenes DIR\n");
        return 2;
    }
    sprintf(path, "%s/many-lights.mcrt", dir);
    if (!many_lights(path))
        goto fail;
    sprintf(path, "%s/terrain.obj", dir);
    if (!terrain_obj(path))
        goto fail;
    sprintf(path, "%s/terrain.mcrt", dir);
    if (!terrain(path))
        goto fail;
    return 0;
fail:
    fprintf(stderr, "bench_scenes: cannot write %s\n", path);
    return 1;
}
