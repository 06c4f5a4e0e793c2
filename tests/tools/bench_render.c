/* bench_render.c: end-to-end path-tracer throughput through the public API, and what the
 * feature-specialised code paths gain over the general one (--all-features). Not a test: it prints
 * a table. Each row renders a scene alternately specialised and general, single-threaded, and
 * reports the median samples per second of each and their ratio (> 1: specialising pays).
 *
 *   bench_render [--quick]
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mcrt.h"

/* A static pinhole scene of diffuse surfaces under point lights: the specialised path draws no
 * lens or time samples, queries no motion BVH and does no MIS. */
static const char diffuse_points[] =
    "film { width 128 height 128 spp 16 }\n"
    "camera { eye 0 2 6 look 0 0.5 0 }\n"
    "sphere { center -1 0.5 0 radius 0.5 }\n"
    "sphere { center 1 0.5 0 radius 0.5 }\n"
    "sphere { center 0 1 -1.5 radius 1 }\n"
    "quad { corner -5 0 5 edge1 10 0 0 edge2 0 0 -10 }\n"
    "point_light { position 2 4 2 intensity 20 }\n"
    "point_light { position -3 3 1 intensity 8 }\n";

struct bench_case {
    const char *name;
    const char *text; /* scene text, or NULL to load `path` */
    const char *path;
    int size, spp;    /* the film is overridden by the spp option only; size for the label */
};

static int render_once(mcrt_scene *s, int all_features, int spp, double *seconds, long long *samples)
{
    mcrt_options o;
    mcrt_render *r;
    mcrt_stats st;
    int w, h;
    mcrt_options_init(&o);
    o.spp = spp;
    o.threads = 1;
    o.all_features = all_features;
    r = mcrt_render_new(s, &o);
    if (!r || mcrt_render_run(r) != MCRT_OK) {
        fprintf(stderr, "bench_render: %s\n", r ? mcrt_render_error(r) : "out of memory");
        mcrt_render_free(r);
        return 0;
    }
    mcrt_render_stats(r, &st);
    mcrt_scene_film(s, &w, &h, NULL);
    *seconds = st.seconds;
    *samples = (long long)w * h * spp;
    mcrt_render_free(r);
    return 1;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    static const struct bench_case cases[] = {
        {"diffuse, point lights", diffuse_points, NULL, 128, 16},
        {"cornell box", NULL, "scenes/cornell.mcrt", 512, 4},
    };
    int reps = 5, i;
    size_t c;
    if (argc == 2 && strcmp(argv[1], "--quick") == 0)
        reps = 1;
    else if (argc != 1) {
        fprintf(stderr, "usage: bench_render [--quick]\n");
        return 2;
    }
    printf("mcrt end-to-end: 1 thread, median of %d alternating renders each; "
           "ratio = specialised / general samples per second\n\n", reps);
    printf("%-24s %-28s %12s %12s %7s\n", "scene", "features", "special S/s", "general S/s",
           "ratio");
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
        for (i = 0; i < reps; i++) {
            int general;
            for (general = 0; general < 2; general++) {
                double sec;
                long long samples;
                if (!render_once(s, general, bc->spp, &sec, &samples)) {
                    mcrt_scene_free(s);
                    return 1;
                }
                rate[general][i] = (double)samples / sec;
            }
        }
        for (i = 0; i < 2; i++) {
            qsort(rate[i], (size_t)reps, sizeof rate[i][0], cmp_double);
            med[i] = rate[i][reps / 2];
        }
        printf("%-24s %-28s %12.0f %12.0f %7.3f\n", bc->name, features, med[0], med[1],
               med[0] / med[1]);
        fflush(stdout);
        mcrt_scene_free(s);
    }
    return 0;
}
