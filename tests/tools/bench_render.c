/* bench_render.c: end-to-end path-tracer throughput through the public API. Not a test: it prints
 * three tables. The first renders each scene alternately specialised and general (--all-features),
 * single-threaded, and reports the median samples per CPU second of each and their ratio (> 1:
 * specialising pays). CPU seconds rather than the clock's: on a shared machine a render that
 * waits for a core loses wall time but no CPU time, and wall-clock medians of this table put the
 * Cornell box's specialised path at 0.93x the general one under load, when it executes 5.7% fewer
 * instructions (callgrind) with as many branch mispredictions (cachegrind's model). The best
 * ratio, of each side's fastest render (the one least disturbed by other jobs), is printed beside
 * the ratio of the medians; nine renders each, since under load single renders vary by ±10%. The second renders scenes/cornell.mcrt and a 1M-triangle terrain (written as
 * an OBJ file into a temporary folder) alternately on 1 thread and on all threads: samples per
 * second by the clock and per CPU second, and the thread-scaling factor (issue 7). The third
 * prices textures: one scene untextured, under a checker and under an image (texture_cost).
 *
 *   bench_render [--quick]
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "mcrt.h"
#include "median.h"
#include "terrain.h"

/* A static pinhole scene of diffuse surfaces under point lights: the specialised path draws no
 * lens or time samples, queries no motion BVH and does no MIS. FLOOR_MATERIAL is the floor's
 * material (the default, diffuse 0.8, here; textured alike in the third table). */
#define DIFFUSE_POINTS(FLOOR_MATERIAL)                                                          \
    "film { width 128 height 128 spp 16 }\n"                                                    \
    "camera { eye 0 2 6 look 0 0.5 0 }\n"                                                       \
    "sphere { center -1 0.5 0 radius 0.5 }\n"                                                   \
    "sphere { center 1 0.5 0 radius 0.5 }\n"                                                    \
    "sphere { center 0 1 -1.5 radius 1 }\n"                                                     \
    "quad { corner -5 0 5 edge1 10 0 0 edge2 0 0 -10 " FLOOR_MATERIAL "}\n"                     \
    "point_light { position 2 4 2 intensity 20 }\n"                                             \
    "point_light { position -3 3 1 intensity 8 }\n"
static const char diffuse_points[] = DIFFUSE_POINTS("");

struct bench_case {
    const char *name;
    const char *text; /* scene text, or NULL to load `path` */
    const char *path;
    int size, spp;    /* the film is overridden by the spp option only; size for the label */
};

/* User plus system CPU seconds of the whole process (all its threads). */
static double cpu_seconds(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
           (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
}

/* One render of s at spp samples per pixel on `threads` threads (0: all); *seconds gets the wall
 * time of mcrt_render_run, *cpu the process CPU time spent in it. */
static int render_once(mcrt_scene *s, int all_features, int threads, int spp, double *seconds,
                       double *cpu, long long *samples)
{
    mcrt_options o;
    mcrt_render *r;
    mcrt_stats st;
    int w, h;
    double c0;
    mcrt_options_init(&o);
    o.spp = spp;
    o.threads = threads;
    o.all_features = all_features;
    r = mcrt_render_new(s, &o);
    c0 = cpu_seconds();
    if (!r || mcrt_render_run(r) != MCRT_OK) {
        fprintf(stderr, "bench_render: %s\n", r ? mcrt_render_error(r) : "out of memory");
        mcrt_render_free(r);
        return 0;
    }
    *cpu = cpu_seconds() - c0;
    mcrt_render_stats(r, &st, sizeof st);
    mcrt_scene_film(s, &w, &h, NULL);
    *seconds = st.seconds;
    *samples = (long long)w * h * spp;
    mcrt_render_free(r);
    return 1;
}

/* A 1,000,000-triangle scene: the terrain of terrain.h under a point light, as an OBJ file in dir.
 * Returns the scene text, or NULL. */
static char *terrain_scene(const char *dir, char *obj, size_t objsize)
{
    static char text[512];
    snprintf(obj, objsize, "%s/terrain-1M.obj", dir);
    if (!terrain_obj(obj))
        return NULL;
    snprintf(text, sizeof text,
             "film { width 256 height 256 spp 4 }\n"
             "camera { eye 0 1.2 1.6 look 0 0 0 fov 40 }\n"
             "mesh { file \"%s\" }\n"
             "point_light { position 1 2 1 intensity 6 }\n", obj);
    return text;
}

/* The second table: 1 thread against all threads, renders alternating, medians. Samples per CPU
 * second equal on both rows means the threads do not slow each other down (no lock or shared cache
 * line in the hot path); the wall-clock scaling then falls short of the thread count only where
 * other jobs hold the cores. SCALING_SPP samples a pixel make a 1-thread render of about a second:
 * at 4 (0.14 s on 2 threads) the renders' fixed costs took about 1% off the terrain's scaling. */
enum { SCALING_SPP = 16 };

static int scaling(int reps)
{
    char dir[] = "/tmp/mcrt-bench-XXXXXX", obj[256];
    const char *terrain;
    long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
    int c, ok = 1;
    if (!mkdtemp(dir)) {
        fprintf(stderr, "bench_render: cannot make a temporary folder\n");
        return 0;
    }
    terrain = terrain_scene(dir, obj, sizeof obj);
    printf("\nthread scaling: %ld processors; renders alternate 1 thread / all threads, median "
           "of %d;\nS/s = samples per second by the clock, S/CPU-s = per second of CPU time (all "
           "threads);\nscaling = all-threads S/s / 1-thread S/s (ideal: the processor count, if "
           "they are idle);\nCPU use = CPU time / (wall time x processors) of the all-threads "
           "renders\n\n",
           ncpu, reps);
    printf("%-24s %12s %13s %12s %13s %8s %9s\n", "scene", "1 thr S/s", "1 thr S/CPU-s",
           "all thr S/s", "all S/CPU-s", "scaling", "CPU use");
    for (c = 0; c < 2 && ok; c++) {
        const char *name = c == 0 ? "cornell box" : "terrain, 1M triangles";
        mcrt_scene *s = mcrt_scene_new();
        double wall[2][16], percpu[2][16], use[16], m[2], pc[2];
        int i, t;
        if (!s || (c == 0 ? mcrt_scene_load_file(s, "scenes/cornell.mcrt")
                          : !terrain ? MCRT_ERR_IO
                                     : mcrt_scene_load_string(s, terrain, strlen(terrain), name)) !=
                      MCRT_OK) {
            fprintf(stderr, "bench_render: %s: %s\n", name, s ? mcrt_scene_error(s) : "no memory");
            mcrt_scene_free(s);
            ok = 0;
            break;
        }
        for (i = 0; i < reps && ok; i++)
            for (t = 0; t < 2 && ok; t++) {
                double sec, cpu;
                long long samples;
                ok = render_once(s, 0, t == 0 ? 1 : 0, SCALING_SPP, &sec, &cpu, &samples);
                wall[t][i] = (double)samples / sec;
                percpu[t][i] = (double)samples / cpu;
                if (t == 1)
                    use[i] = cpu / (sec * (double)(ncpu > 0 ? ncpu : 1));
            }
        if (ok) {
            for (t = 0; t < 2; t++) {
                m[t] = median(wall[t], reps);
                pc[t] = median(percpu[t], reps);
            }
            printf("%-24s %12.0f %13.0f %12.0f %13.0f %8.2f %8.0f%%\n", name, m[0], pc[0], m[1],
                   pc[1], m[1] / m[0], 100.0 * median(use, reps));
            fflush(stdout);
        }
        mcrt_scene_free(s);
    }
    if (terrain)
        remove(obj);
    rmdir(dir);
    return ok;
}

/* The third table: what textures cost. The diffuse scene with its floor untextured, under a
 * checker and under a 512 x 512 image texture, each of colour 0.8 everywhere: the same image and
 * the same paths, so that the difference is the texture lookups (uv and evaluation at each floor
 * hit) and the textured kernel. Renders alternate; medians of samples per CPU second. */
static int texture_cost(int reps)
{
    enum { N = 512 };
    char dir[] = "/tmp/mcrt-bench-XXXXXX", pfm[256], text[1024];
    double rate[3][16], med[3];
    const char *names[3] = {"untextured", "checker", "image 512x512"};
    mcrt_scene *s[3] = {NULL, NULL, NULL};
    int i, k, ok = 1;
    FILE *f;
    if (!mkdtemp(dir))
        return 0;
    snprintf(pfm, sizeof pfm, "%s/white.pfm", dir);
    /* A PFM of 1.0 everywhere (little-endian floats, the scale's sign says so). */
    if (!(f = fopen(pfm, "wb")))
        ok = 0;
    if (f) {
        float row[3 * N];
        for (i = 0; i < 3 * N; i++)
            row[i] = 1.0f;
        fprintf(f, "PF\n%d %d\n-1.0\n", N, N);
        for (i = 0; i < N; i++)
            ok &= fwrite(row, sizeof row, 1, f) == 1;
        ok &= fclose(f) == 0;
    }
    for (k = 0; k < 3 && ok; k++) {
        if (k == 0)
            snprintf(text, sizeof text, "material floor { diffuse 0.8 }\n%s",
                     DIFFUSE_POINTS("material floor "));
        else if (k == 1)
            snprintf(text, sizeof text, "texture t { checker 1 1 scale 8 }\n"
                     "material floor { diffuse 0.8 texture t }\n%s", DIFFUSE_POINTS("material floor "));
        else
            snprintf(text, sizeof text, "texture t { image \"%s\" scale 8 }\n"
                     "material floor { diffuse 0.8 texture t }\n%s", pfm, DIFFUSE_POINTS("material floor "));
        s[k] = mcrt_scene_new();
        if (!s[k] || mcrt_scene_load_string(s[k], text, strlen(text), names[k]) != MCRT_OK) {
            fprintf(stderr, "bench_render: %s: %s\n", names[k], s[k] ? mcrt_scene_error(s[k]) : "no memory");
            ok = 0;
        }
    }
    for (i = 0; i < reps && ok; i++)
        for (k = 0; k < 3 && ok; k++) {
            double sec, cpu;
            long long samples;
            ok = render_once(s[k], 0, 1, 16, &sec, &cpu, &samples);
            rate[k][i] = (double)samples / cpu;
        }
    if (ok) {
        printf("\ntextures: the diffuse scene's floor untextured and textured (colour 0.8 "
               "everywhere: the same image);\n1 thread, %d alternating renders, median samples "
               "per CPU second; ratio = textured / untextured\n\n", reps);
        printf("%-24s %14s %7s\n", "floor", "S/CPU-s", "ratio");
        for (k = 0; k < 3; k++) {
            med[k] = median(rate[k], reps);
            printf("%-24s %14.0f %7.3f\n", names[k], med[k], med[k] / med[0]);
        }
    }
    for (k = 0; k < 3; k++)
        mcrt_scene_free(s[k]);
    remove(pfm);
    rmdir(dir);
    return ok;
}

int main(int argc, char **argv)
{
    static const struct bench_case cases[] = {
        {"diffuse, point lights", diffuse_points, NULL, 128, 16},
        {"cornell box", NULL, "scenes/cornell.mcrt", 512, 4},
    };
    int reps = 5, compare_reps, i;
    size_t c;
    if (argc == 2 && strcmp(argv[1], "--quick") == 0)
        reps = 1;
    else if (argc != 1) {
        fprintf(stderr, "usage: bench_render [--quick]\n");
        return 2;
    }
    compare_reps = reps == 1 ? 1 : 9;
    printf("mcrt end-to-end: 1 thread, %d alternating renders each; ratio = specialised / general "
           "median samples per CPU second, best = of the fastest renders\n\n", compare_reps);
    printf("%-24s %-28s %14s %14s %7s %6s\n", "scene", "features", "special S/CPU-s",
           "general S/CPU-s", "ratio", "best");
    for (c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        const struct bench_case *bc = &cases[c];
        mcrt_scene *s = mcrt_scene_new();
        double rate[2][16], med[2];
        char features[64];
        const char *info;
        size_t n;
        if (!s)
            return 1;
        if ((bc->text ? mcrt_scene_load_string(s, bc->text, strlen(bc->text), bc->name)
                      : mcrt_scene_load_file(s, bc->path)) != MCRT_OK) {
            fprintf(stderr, "bench_render: %s\n", mcrt_scene_error(s));
            mcrt_scene_free(s);
            return 1;
        }
        info = mcrt_scene_info(s) + strlen("features: ");
        n = strcspn(info, "\n");
        snprintf(features, sizeof features, "%.*s", (int)n, info);
        for (i = 0; i < compare_reps; i++) {
            int general;
            for (general = 0; general < 2; general++) {
                double sec, cpu;
                long long samples;
                if (!render_once(s, general, 1, bc->spp, &sec, &cpu, &samples)) {
                    mcrt_scene_free(s);
                    return 1;
                }
                rate[general][i] = (double)samples / cpu;
            }
        }
        for (i = 0; i < 2; i++)
            med[i] = median(rate[i], compare_reps); /* sorts: the fastest is last */
        printf("%-24s %-28s %14.0f %14.0f %7.3f %6.3f\n", bc->name, features, med[0], med[1],
               med[0] / med[1], rate[0][compare_reps - 1] / rate[1][compare_reps - 1]);
        fflush(stdout);
        mcrt_scene_free(s);
    }
    return scaling(reps) && texture_cost(compare_reps) ? 0 : 1;
}
