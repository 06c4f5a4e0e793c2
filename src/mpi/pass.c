/* pass.c: one pass of mcrt-mpi's render, the unit of work that every schedule hands out (see
 * job.h). */
#include <limits.h>
#include <stdio.h>
#include <time.h>
#include <unistd.h>

#include "cli/args.h"
#include "mpi/job.h"

double mc_mpi_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int mc_mpi_pass_limit(const struct job *j, const mcrt_scene *scene)
{
    int spp;
    mcrt_scene_film(scene, NULL, NULL, &spp);
    /* The spp limit of the library (2^24, mcrt_options.passes) caps a render without --passes. */
    return j->o.passes ? j->o.passes : (1 << 24) / (j->o.spp ? j->o.spp : spp);
}

mcrt_render *mc_mpi_pass_new(const struct job *j, const mcrt_scene *scene, int k)
{
    mcrt_options o = j->o;
    o.first_pass = k;
    o.passes = 1;
    o.time_budget = o.target_error = 0.0;
    /* The accumulating render of rank 0 writes the state as mcrt would. */
    o.save_state = j->o.save_state || j->o.time_budget > 0.0 || j->o.target_error > 0.0;
    return mcrt_render_new(scene, &o);
}

int mc_mpi_pass_run(mcrt_render *r, char *msg)
{
    mcrt_status st;
    size_t bytes = 0;
    if (!r) {
        snprintf(msg, MSG_LEN, "out of memory");
        return STATUS_FAIL;
    }
    st = mcrt_render_run(r);
    if (st == MCRT_OK && !(mcrt_render_sums(r, &bytes) && bytes <= INT_MAX)) {
        /* MPI counts are ints. */
        snprintf(msg, MSG_LEN, "%s", bytes ? "the image is too large for one MPI message"
                                           : "out of memory for the render's sums");
        return STATUS_FAIL;
    }
    if (st == MCRT_OK)
        return 0;
    snprintf(msg, MSG_LEN, "%s", mcrt_render_error(r));
    return st == MCRT_ERR_INVALID ? STATUS_USAGE : STATUS_FAIL;
}

void mc_mpi_progress(const struct job *j, int passes, double t0)
{
    if (!j->quiet && isatty(STDERR_FILENO))
        fprintf(stderr, "\rmcrt-mpi: %d passes, %.1f s ", passes, mc_mpi_now() - t0);
}
