/* bench_sppm.c: photon-mapping throughput through the public API. Not a test: it prints one
 * table for scenes/cornell-spheres.mcrt at 200², single-threaded, medians of 3 renders of 8 passes:
 * with P photons per pass, with 2P (the difference is the cost of P·passes photons: photons per
 * second per core, their tracing and their gather together), and with 2P at twice the default
 * radius (four times the visible points a photon meets: the difference is the gather's share).
 *
 *   bench_sppm [--quick]
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "file_util.h"
#include "mcrt.h"
#include "median.h"

/* Seconds of one render of `passes` passes of text on one thread; negative on failure. */
static double render_seconds(const char *text, int passes, unsigned long long *rays)
{
    mcrt_scene *s = mcrt_scene_new();
    mcrt_render *r = NULL;
    mcrt_options o;
    mcrt_stats st;
    double sec = -1.0;
    if (s && mcrt_scene_load_string(s, text, strlen(text), "bench") == MCRT_OK) {
        mcrt_options_init(&o);
        o.spp = passes;
        o.threads = 1;
        o.integrator = "sppm";
        r = mcrt_render_new(s, &o);
        if (r && mcrt_render_run(r) == MCRT_OK) {
            mcrt_render_stats(r, &st, sizeof st);
            sec = st.seconds;
            *rays = (unsigned long long)st.rays;
        }
    } else {
        fprintf(stderr, "bench_sppm: %s\n", s ? mcrt_scene_error(s) : "out of memory");
    }
    mcrt_render_free(r);
    mcrt_scene_free(s);
    return sec;
}

int main(int argc, char **argv)
{
    enum { W = 200, PASSES = 8, P = W * W };
    /* The scene's bounding radius is √3 (its 2 × 2 × 2 box), so the default radius is
     * 5·√3/200. */
    const double r0 = 5.0 * 1.7320508 / W;
    char extra[3][160], film[80];
    char *text[3];
    double t[3][5], med[3];
    unsigned long long rays = 0;
    (void)rays;
    int reps = 3, i, k;
    if (argc == 2 && strcmp(argv[1], "--quick") == 0)
        reps = 1;
    else if (argc != 1) {
        fprintf(stderr, "usage: bench_sppm [--quick]\n");
        return 2;
    }
    snprintf(film, sizeof film, "film { width %d height %d sampler sobol }", W, W);
    snprintf(extra[0], sizeof extra[0], "integrator { photons %d }", P);
    snprintf(extra[1], sizeof extra[1], "integrator { photons %d }", 2 * P);
    snprintf(extra[2], sizeof extra[2], "integrator { photons %d  radius %g }", 2 * P, 2.0 * r0);
    for (k = 0; k < 3; k++) {
        text[k] = t_scene_with_film("scenes/cornell-spheres.mcrt", film, extra[k]);
        if (!text[k]) {
            fprintf(stderr, "bench_sppm: cannot read scenes/cornell-spheres.mcrt\n");
            return 1;
        }
    }
    for (i = 0; i < reps; i++)
        for (k = 0; k < 3; k++)
            if ((t[k][i] = render_seconds(text[k], PASSES, &rays)) < 0.0)
                return 1;
    for (k = 0; k < 3; k++) {
        med[k] = median(t[k], reps);
        free(text[k]);
    }
    printf("mcrt sppm: scenes/cornell-spheres.mcrt %dx%d, %d passes, 1 thread, median of %d\n\n",
           W, W, PASSES, reps);
    printf("%-44s %10s\n", "render", "seconds");
    printf("%-44s %10.3f\n", "P = 40000 photons per pass, default radius", med[0]);
    printf("%-44s %10.3f\n", "2P photons per pass", med[1]);
    printf("%-44s %10.3f\n", "2P photons per pass, twice the radius", med[2]);
    printf("\nphotons per second per core (traced and gathered): %.0f\n",
           (double)P * PASSES / (med[1] - med[0]));
    printf("the camera pass and the rest, per pass: %.3f s (P photons %.3f s)\n",
           (2.0 * med[0] - med[1]) / PASSES, (med[1] - med[0]) / PASSES);
    printf("gather at twice the radius (4x the visible points per photon): +%.1f%% of the 2P "
           "render (%.3f s per pass)\n",
           100.0 * (med[2] - med[1]) / med[1], (med[2] - med[1]) / PASSES);
    return 0;
}
