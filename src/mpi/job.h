/* job.h: what mcrt-mpi's parts share: the job (the render's options, this rank, the number of
 * ranks, the schedule), one pass's render, and the table of schedules, the rules by which the
 * passes are given to the ranks (static.c, dynamic.c). */
#ifndef MCRT_MPI_JOB_H
#define MCRT_MPI_JOB_H

#include "mcrt.h"

/* The schedules, X(ID, NAME, RUN, DESCRIPTION): read by the parser, mcrt-mpi --help and main's
 * dispatch; mcrt(1) gives each with its measured cost (tests/tools/mpi_bench.sh). */
#define MC_MPI_SCHEDULES(X)                                                                        \
    X(STATIC, "static", mc_mpi_run_static,                                                         \
      "in round j rank r renders pass j*N + r; a round waits for its slowest rank")               \
    X(DYNAMIC, "dynamic", mc_mpi_run_dynamic,                                                      \
      "rank 0 hands the next pass to whichever rank has finished one")
#define MC_MPI_SCHEDULE_ENUM(id, name, run, description) SCHEDULE_##id,
enum { MC_MPI_SCHEDULES(MC_MPI_SCHEDULE_ENUM) SCHEDULES_END };

struct job {
    const char *scene, *output;
    mcrt_options o; /* the options of the whole render; each pass's are made from them */
    int quiet, schedule;
    int rank, size;
};

/* The length of a failing rank's message, sent as one fixed-size block. */
enum { MSG_LEN = 600 };

/* Seconds on the monotonic clock. */
double mc_mpi_now(void);
/* How many passes the render may take at most: --passes, or the library's spp limit. */
int mc_mpi_pass_limit(const struct job *j, const mcrt_scene *scene);
/* A render of pass k alone (not run yet), or NULL when out of memory. */
mcrt_render *mc_mpi_pass_new(const struct job *j, const mcrt_scene *scene, int k);
/* Run it (r may be NULL: out of memory); 0 when its sums are ready, else the exit status with the
 * reason in msg (MSG_LEN bytes). */
int mc_mpi_pass_run(mcrt_render *r, char *msg);
/* Rank 0's progress line, on a terminal only. */
void mc_mpi_progress(const struct job *j, int passes, double t0);

/* What a schedule leaves on rank 0 (zero on the others). */
struct outcome {
    mcrt_render *acc; /* the image: the render of pass 0, the others added in pass order */
    int done;         /* the passes in it */
    int *by_rank;     /* how many of them each rank rendered (j->size counts, zeroed) */
    double exchange;  /* seconds rank 0 spent taking and adding the others' sums */
};

/* A schedule: render the passes. Returns the job's exit status, or -1 on success; every rank
 * returns the same. */
#define MC_MPI_SCHEDULE_DECLARE(id, name, run, description)                                        \
    int run(const struct job *j, const mcrt_scene *scene, struct outcome *out);
MC_MPI_SCHEDULES(MC_MPI_SCHEDULE_DECLARE)

#endif
