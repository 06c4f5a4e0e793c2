/* terrain.h: the 1,000,000-triangle terrain of the benchmarks (bench_render's thread scaling,
 * bench_scenes' terrain.mcrt for the efficiency against Mitsuba 3), written as an OBJ file. */
#ifndef MCRT_TERRAIN_H
#define MCRT_TERRAIN_H

#include <math.h>
#include <stdio.h>

/* 1000 x 500 quads, each two triangles, z = 0.05 sin(40x) sin(40y) over [-1,1] x [-0.5,0.5]
 * (the anchor's sphere-1M displacement, on a plane so that no triangle is degenerate), written
 * as the vertices (x, z, y): up is +y. Returns 1, or 0 if the file cannot be written. */
static int terrain_obj(const char *path)
{
    enum { NX = 1000, NY = 500 };
    FILE *f = fopen(path, "w");
    int i, j;
    if (!f)
        return 0;
    for (j = 0; j <= NY; j++)
        for (i = 0; i <= NX; i++) {
            double x = -1.0 + 2.0 * i / NX, y = -0.5 + 1.0 * j / NY;
            fprintf(f, "v %.7g %.7g %.7g\n", x, 0.05 * sin(40.0 * x) * sin(40.0 * y), y);
        }
    for (j = 0; j < NY; j++)
        for (i = 0; i < NX; i++) {
            int a = j * (NX + 1) + i + 1, b = a + 1, c = a + NX + 2, d = a + NX + 1;
            fprintf(f, "f %d %d %d\nf %d %d %d\n", a, c, b, a, d, c);
        }
    return fclose(f) == 0;
}

#endif
