/* bench_obj.c: how fast a large OBJ file loads (issue 17). Writes a torus of about 1M triangles
 * with texture coordinates and normals on every corner (the form exporters write, "f v/vt/vn"),
 * as a 1000 x 500 grid of quads split in two, to a temporary file, then loads it with mc_obj_load
 * five times: the median wall and CPU time, the file's MB/s and triangles/s, and the memory the
 * load adds (resident at its peak: the file's text, the vertex arrays and the scene's; and kept:
 * the scene's triangles and corner attributes). Not a test: it prints a table.
 *
 *   bench_obj [--keep FILE]   (--keep: write the OBJ to FILE and leave it there)
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>
#include <unistd.h>

#include "median.h"
#include "rss.h"
#include "scene/obj.h"

#define NU 1000
#define NV 500
#define REPS 5

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The torus of radii 1 and 0.35 about y, u around the ring and v around the tube, its vertex grid
 * closed in both directions (the last row and column repeat the first, so that the texture
 * coordinates run 0 to 1). */
static long write_torus(const char *path)
{
    FILE *f = fopen(path, "w");
    int i, j;
    long bytes;
    if (!f)
        return -1;
    fprintf(f, "# bench_obj: torus, %d x %d quads, %d triangles\n", NU, NV, 2 * NU * NV);
    for (j = 0; j <= NV; j++)
        for (i = 0; i <= NU; i++) {
            double u = 2.0 * 3.14159265358979 * i / NU, v = 2.0 * 3.14159265358979 * j / NV;
            double cu = cos(u), su = sin(u), cv = cos(v), sv = sin(v), r = 1.0 + 0.35 * cv;
            fprintf(f, "v %.6f %.6f %.6f\nvt %.6f %.6f\nvn %.6f %.6f %.6f\n", r * cu, 0.35 * sv,
                    r * su, (double)i / NU, (double)j / NV, cv * cu, sv, cv * su);
        }
    for (j = 0; j < NV; j++)
        for (i = 0; i < NU; i++) {
            int a = 1 + j * (NU + 1) + i, b = a + 1, c = a + NU + 2, d = a + NU + 1;
            fprintf(f, "f %d/%d/%d %d/%d/%d %d/%d/%d\nf %d/%d/%d %d/%d/%d %d/%d/%d\n", a, a, a, d, d,
                    d, c, c, c, a, a, a, c, c, c, b, b, b);
        }
    bytes = ftell(f);
    return fclose(f) == 0 ? bytes : -1;
}

int main(int argc, char **argv)
{
    char path[256];
    const char *dir = getenv("TMPDIR");
    double wall[REPS], cpu[REPS];
    struct rss mem = {-1, -1};
    size_t triangles = 0, scene_bytes = 0;
    long bytes;
    int k, keep = argc == 3 && !strcmp(argv[1], "--keep");
    if (keep)
        snprintf(path, sizeof path, "%s", argv[2]);
    else
        snprintf(path, sizeof path, "%s/mcrt-bench-%ld.obj", dir && dir[0] ? dir : "/tmp", (long)getpid());
    if ((bytes = write_torus(path)) < 0) {
        fprintf(stderr, "bench_obj: cannot write %s\n", path);
        return 1;
    }
    for (k = 0; k < REPS; k++) {
        struct scene s;
        struct obj_mesh m;
        struct obj_stats st;
        mc_diag d;
        long long mark;
        double t0, c0;
        memset(&m, 0, sizeof m);
        m.path = path;
        m.origin = "bench";
        m.xform[0] = m.xform[5] = m.xform[10] = 1.0f;
        m.proto.light = -1;
        m.proto.normals = -1;
        if (mc_scene_init(&s) != 0)
            return 1;
        mark = mark_rss();
        t0 = now();
        c0 = (double)clock() / CLOCKS_PER_SEC;
        if (mc_obj_load(&s, &m, &st, &d) != MCRT_OK) {
            fprintf(stderr, "bench_obj: %s\n", d.msg);
            return 1;
        }
        cpu[k] = (double)clock() / CLOCKS_PER_SEC - c0;
        wall[k] = now() - t0;
        triangles = st.triangles;
        if (k == 0) {
            mem = rss_since(mark, triangles);
            scene_bytes = s.prim_cap * sizeof *s.prims + s.normal_cap * sizeof *s.normals +
                          s.uv_cap * sizeof *s.uvs;
        }
        mc_scene_free(&s);
    }
    if (!keep)
        remove(path);
    {
        double w = median(wall, REPS), c = median(cpu, REPS);
        printf("OBJ load (mc_obj_load), a torus of %zu triangles, f v/vt/vn, %.1f MB; median of %d\n",
               triangles, (double)bytes / 1e6, REPS);
        printf("  wall %.3f s, CPU %.3f s: %.1f MB/s, %.2f M triangles/s (CPU)\n", w, c,
               (double)bytes / 1e6 / c, (double)triangles / 1e6 / c);
        printf("  memory: scene arrays %.1f B/triangle (%.0f MB); resident added at the peak %.1f,"
               " kept %.1f B/triangle\n",
               (double)scene_bytes / (double)triangles, (double)scene_bytes / 1e6, mem.peak, mem.kept);
    }
    return 0;
}
