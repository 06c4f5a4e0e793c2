/* static.c: mcrt-mpi's static schedule (job.h). In round j rank r renders pass j·N + r; every
 * pass costs about the same, so a round waits for its slowest rank only as long as one pass on
 * ranks of equal speed. Rank 0 then takes the passes' sums in pass order, which is rank order,
 * and adds them one after another to its image (mcrt_render_add_sums). After each round rank 0
 * decides whether to go on (--passes reached, --target-error met after some pass, whose later
 * passes of the round are dropped as one process would not have rendered them, or --time spent)
 * and broadcasts it: one collective per round. A rank that fails sends its message instead of
 * sums, and rank 0 prints it. */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

#include "mpi/job.h"

int mc_mpi_run_static(const struct job *j, const mcrt_scene *scene, struct outcome *out)
{
    mcrt_render **acc = &out->acc;
    int *done = &out->done;
    int round, stop = 0, code = -1, verdict[2];
    int limit = mc_mpi_pass_limit(j, scene);
    double t0 = mc_mpi_now(), last_round = 0.0;
    char msg[MSG_LEN];
    for (round = 0; !stop; round++) {
        int k = round * j->size + j->rank, status = 0, r;
        mcrt_render *mine = NULL;
        double t = mc_mpi_now(), tr;
        msg[0] = '\0';
        if (k < limit)
            status = mc_mpi_pass_run(mine = mc_mpi_pass_new(j, scene, k), msg);
        tr = mc_mpi_now();
        if (j->rank != 0) {
            size_t bytes = 0;
            const void *sums = status || k >= limit ? NULL : mcrt_render_sums(mine, &bytes);
            MPI_Send(&status, 1, MPI_INT, 0, 0, MPI_COMM_WORLD);
            if (status)
                MPI_Send(msg, MSG_LEN, MPI_CHAR, 0, 1, MPI_COMM_WORLD);
            else if (k < limit)
                MPI_Send(sums, (int)bytes, MPI_BYTE, 0, 2, MPI_COMM_WORLD);
        } else {
            /* Rank 0: its own pass, then each rank's in rank order, which is pass order. */
            void *buf = NULL;
            size_t bytes = 0;
            const void *own = status || k >= limit ? NULL : mcrt_render_sums(mine, &bytes);
            if (status) {
                fprintf(stderr, "mcrt-mpi: rank 0: %s\n", msg);
                code = status;
            } else if (k < limit && !*acc) {
                *acc = mine; /* pass 0: the image starts as it */
                mine = NULL;
                ++*done;
                out->by_rank[0]++;
            } else if (k < limit && !stop) {
                if (mcrt_render_add_sums(*acc, own, bytes, k, 1) != MCRT_OK)
                    code = 1;
                else {
                    ++*done;
                    out->by_rank[0]++;
                }
            }
            if (*acc && j->o.target_error > 0.0) {
                mcrt_stats st;
                mcrt_render_stats(*acc, &st, sizeof st);
                stop |= st.est_relmse <= j->o.target_error;
            }
            for (r = 1; r < j->size; r++) {
                int their = 0, kr = round * j->size + r, count;
                MPI_Status probe;
                MPI_Recv(&their, 1, MPI_INT, r, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
                if (their) {
                    MPI_Recv(msg, MSG_LEN, MPI_CHAR, r, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
                    fprintf(stderr, "mcrt-mpi: rank %d: %s\n", r, msg);
                    code = code > their ? code : their;
                } else if (kr < limit) {
                    /* The size from the message: rank 0's own pass may have failed. */
                    MPI_Probe(r, 2, MPI_COMM_WORLD, &probe);
                    MPI_Get_count(&probe, MPI_BYTE, &count);
                    if (!buf && !(buf = malloc((size_t)count)))
                        MPI_Abort(MPI_COMM_WORLD, 1); /* out of memory: nothing to do but stop */
                    bytes = (size_t)count;
                    MPI_Recv(buf, count, MPI_BYTE, r, 2, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
                    /* Passes after the one that met the target are dropped, as one process
                     * would not have rendered them. */
                    if (code < 0 && !stop) {
                        if (mcrt_render_add_sums(*acc, buf, bytes, kr, 1) != MCRT_OK)
                            code = 1;
                        else {
                            ++*done;
                            out->by_rank[r]++;
                        }
                    }
                    if (code < 0 && !stop && j->o.target_error > 0.0) {
                        mcrt_stats st;
                        mcrt_render_stats(*acc, &st, sizeof st);
                        stop |= st.est_relmse <= j->o.target_error;
                    }
                }
            }
            free(buf);
            last_round = mc_mpi_now() - t;
            stop |= code >= 0 || *done >= limit || (round + 1) * j->size >= limit;
            /* As mcrt: no round that, as long as the last, would end after the budget. */
            if (j->o.time_budget > 0.0 && mc_mpi_now() - t0 + last_round > j->o.time_budget)
                stop = 1;
            mc_mpi_progress(j, *done, t0);
        }
        mcrt_render_free(mine);
        verdict[0] = stop;
        verdict[1] = code;
        MPI_Bcast(verdict, 2, MPI_INT, 0, MPI_COMM_WORLD); /* the round's one collective */
        stop = verdict[0];
        code = verdict[1];
        out->exchange += mc_mpi_now() - tr;
    }
    return code;
}
