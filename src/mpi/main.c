/* main.c: mcrt-mpi, one render across the processes of an MPI job (mcrt(1), mcrt-mpi).
 * Like mcrt it is a client of the public API (mcrt.h) only; MPI never enters the library.
 *
 * Rank 0 reads the scene file and broadcasts its text, so one file is read, not one per rank.
 * The render is a sequence of passes, each an independent sample set keyed by (seed, pass)
 * (mcrt_options.first_pass), so any rank can render any pass: in round j rank r renders pass
 * j·N + r (a static rule; every pass costs about the same, so a round waits for its slowest rank
 * only as long as one pass). Rank 0 then takes the passes' sums in pass order, which is rank
 * order, and adds them one after another to its image (mcrt_render_add_sums): exactly the sums
 * a single process makes when it merges its passes as it renders them, so the image is
 * bit-identical to one process's. MPI's own reductions would regroup the floating-point sums
 * (anchor notes, section 4), so they are not used for the image. After each round rank 0
 * decides whether to go on (--passes reached, --target-error met after some pass, whose later
 * passes of the round are dropped as one process would not have rendered them, or --time
 * spent) and broadcasts it: one collective per round. A rank that fails sends its message
 * instead of sums; rank 0 prints it and every rank stops; the output is written only by rank 0
 * at the end (through a temporary file), so it is never touched by a failed job. */
#include <errno.h>
#include <limits.h>
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli/args.h"
#include "mcrt.h"

static const char usage[] =
    "usage: mpirun -np N mcrt-mpi [options] SCENE -o OUT\n"
    "Render SCENE across the N processes of an MPI job: the image is bit-identical to\n"
    "`mcrt --passes P` (or --target-error) with the same options and seed. Rank 0 reads SCENE and\n"
    "sends it to the others; OBJ meshes are read by every rank, relative to its working folder.\n"
    "\n"
    "options (as mcrt's): -o FILE, --spp N, --threads N (per rank), --seed N, --integrator NAME\n"
    "(per-ray ones), --sampler NAME, --all-features, --crop x0,y0,x1,y1, --passes N (default:\n"
    "one pass per rank without --time or --target-error), --time SECONDS, --target-error E,\n"
    "--state, --quiet, --help\n"
    "\n"
    "exit status: 0 success; 1 a rank failed or the image could not be written; 2 bad input\n";

/* mcrt's render options (MC_RENDER_ARGS), then mcrt-mpi's own. */
enum { OPT_OUTPUT = RENDER_ARGS_END, OPT_QUIET, OPT_HELP, OPT_END };
static const struct arg_spec options[OPT_END + 1] = {
    MC_RENDER_ARGS(MC_RENDER_ARG_SPEC)
    [OPT_OUTPUT] = {NULL, 'o', 1}, [OPT_QUIET] = {"quiet", 0, 0}, [OPT_HELP] = {"help", 0, 0},
    [OPT_END] = {NULL, 0, 0}};

struct job {
    const char *scene, *output;
    mcrt_options o; /* the options of the whole render; each pass's are made from them */
    int quiet;
    int rank, size;
};

/* Parse argv (the same on every rank) into j; -1 to go on, else the exit status. Only rank 0
 * prints. */
static int parse(int argc, char **argv, struct job *j)
{
    struct arg_parser p;
    const char *v;
    int opt, ok = 1;
    if (j->rank != 0) /* the same arguments fail on every rank: rank 0 says why */
        ok = freopen("/dev/null", "w", stderr) != NULL;
    (void)ok;
    mcrt_options_init(&j->o);
    mc_args_init(&p, argc, argv);
    while ((opt = mc_args_next(&p, options, &v)) != ARG_END) {
        if (opt >= 0 && opt < RENDER_ARGS_END) {
            if (!mc_args_render(opt, v, &j->o))
                return STATUS_USAGE;
            continue;
        }
        switch (opt) {
        case ARG_ERROR: return STATUS_USAGE;
        case ARG_OPERAND:
            if (j->scene) {
                fprintf(stderr, "mcrt-mpi: more than one scene given ('%s' and '%s')\n",
                        j->scene, v);
                return STATUS_USAGE;
            }
            j->scene = v;
            break;
        case OPT_OUTPUT: j->output = v; break;
        case OPT_QUIET: j->quiet = 1; break;
        case OPT_HELP:
            if (j->rank == 0)
                fputs(usage, stdout);
            return STATUS_OK;
        }
    }
    if (!j->scene || !j->output) {
        fprintf(stderr, "mcrt-mpi: no %s given (see mcrt-mpi --help)\n",
                j->scene ? "output (-o FILE)" : "scene file");
        return STATUS_USAGE;
    }
    if (!j->o.passes && !(j->o.time_budget > 0.0) && !(j->o.target_error > 0.0))
        j->o.passes = j->size;
    return -1;
}

/* Rank 0 reads the scene file; every rank gets its text (NULL on rank 0's failure, which it
 * has printed). */
static char *broadcast_scene(const struct job *j, long *len)
{
    char *text = NULL;
    *len = -1;
    if (j->rank == 0) {
        FILE *f;
        int ok;
        errno = 0;
        f = fopen(j->scene, "rb");
        /* MPI counts are ints: a longer scene is surely not a scene. */
        ok = f && fseek(f, 0, SEEK_END) == 0 && (*len = ftell(f)) >= 0 && *len < INT_MAX &&
             fseek(f, 0, SEEK_SET) == 0 && (text = malloc((size_t)*len + 1)) &&
             fread(text, 1, (size_t)*len, f) == (size_t)*len;
        if (!ok) {
            fprintf(stderr, "%s: %s\n", j->scene, errno ? strerror(errno) : "cannot read it");
            *len = -1;
        }
        if (f)
            fclose(f);
    }
    MPI_Bcast(len, 1, MPI_LONG, 0, MPI_COMM_WORLD);
    if (*len < 0) {
        free(text);
        return NULL;
    }
    if (j->rank != 0 && !(text = malloc((size_t)*len + 1)))
        MPI_Abort(MPI_COMM_WORLD, 1);
    MPI_Bcast(text, (int)*len, MPI_CHAR, 0, MPI_COMM_WORLD);
    return text;
}

enum { MSG_LEN = 600 };

/* Whether every rank has its scene; rank 0 prints the message of each that has not. Returns
 * the job's exit status, or -1 to go on. */
static int gather_failures(const struct job *j, int status, const char *msg)
{
    char *all = j->rank == 0 ? malloc((size_t)j->size * MSG_LEN) : NULL;
    char mine[MSG_LEN];
    int worst = status, r, code = -1;
    snprintf(mine, sizeof mine, "%s", status ? msg : "");
    MPI_Allreduce(&status, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (!worst) {
        free(all);
        return -1;
    }
    MPI_Gather(mine, MSG_LEN, MPI_CHAR, all, MSG_LEN, MPI_CHAR, 0, MPI_COMM_WORLD);
    for (r = 0; j->rank == 0 && all && r < j->size; r++)
        if (all[(size_t)r * MSG_LEN])
            fprintf(stderr, "mcrt-mpi: rank %d: %s\n", r, all + (size_t)r * MSG_LEN);
    code = worst;
    free(all);
    return code;
}

/* Render pass k into *out (a new render); 0, or the exit status with the reason in msg. */
static int render_pass(const struct job *j, const mcrt_scene *scene, int k, mcrt_render **out,
                       char *msg)
{
    mcrt_options o = j->o;
    mcrt_status st;
    size_t bytes = 0;
    o.first_pass = k;
    o.passes = 1;
    o.time_budget = o.target_error = 0.0;
    /* The accumulating render of rank 0 writes the state as mcrt would. */
    o.save_state = j->o.save_state || j->o.time_budget > 0.0 || j->o.target_error > 0.0;
    *out = mcrt_render_new(scene, &o);
    if (!*out) {
        snprintf(msg, MSG_LEN, "out of memory");
        return STATUS_FAIL;
    }
    st = mcrt_render_run(*out);
    if (st == MCRT_OK && !(mcrt_render_sums(*out, &bytes) && bytes <= INT_MAX)) {
        snprintf(msg, MSG_LEN, "%s", bytes ? "the image is too large for one MPI message"
                                           : "out of memory for the render's sums");
        return STATUS_FAIL;
    }
    if (st == MCRT_OK)
        return 0;
    snprintf(msg, MSG_LEN, "%s", mcrt_render_error(*out));
    return st == MCRT_ERR_INVALID ? STATUS_USAGE : STATUS_FAIL;
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The rounds; rank 0's image in *acc. Returns the exit status, or -1 on success. */
static int run(const struct job *j, const mcrt_scene *scene, mcrt_render **acc, int *done,
               double *reduce_seconds)
{
    int round, stop = 0, code = -1, verdict[2];
    /* The spp limit of the library (mcrt_options.passes) caps a render without --passes. */
    int spp, limit;
    double t0 = now(), last_round = 0.0;
    char msg[MSG_LEN];
    mcrt_scene_film(scene, NULL, NULL, &spp);
    limit = j->o.passes ? j->o.passes : (1 << 24) / (j->o.spp ? j->o.spp : spp);
    *done = 0;
    *reduce_seconds = 0.0;
    for (round = 0; !stop; round++) {
        int k = round * j->size + j->rank, status = 0, r;
        mcrt_render *mine = NULL;
        double t = now(), tr;
        msg[0] = '\0';
        if (k < limit)
            status = render_pass(j, scene, k, &mine, msg);
        tr = now();
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
            } else if (k < limit && !stop)
                mcrt_render_add_sums(*acc, own, bytes, k, 1) == MCRT_OK ? (void)++*done
                                                                         : (void)(code = 1);
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
                        else
                            ++*done;
                    }
                    if (code < 0 && !stop && j->o.target_error > 0.0) {
                        mcrt_stats st;
                        mcrt_render_stats(*acc, &st, sizeof st);
                        stop |= st.est_relmse <= j->o.target_error;
                    }
                }
            }
            free(buf);
            last_round = now() - t;
            stop |= code >= 0 || *done >= limit || (round + 1) * j->size >= limit;
            /* As mcrt: no round that, as long as the last, would end after the budget. */
            if (j->o.time_budget > 0.0 && now() - t0 + last_round > j->o.time_budget)
                stop = 1;
            if (!j->quiet && isatty(STDERR_FILENO))
                fprintf(stderr, "\rmcrt-mpi: %d passes, %.1f s ", *done, now() - t0);
        }
        mcrt_render_free(mine);
        verdict[0] = stop;
        verdict[1] = code;
        MPI_Bcast(verdict, 2, MPI_INT, 0, MPI_COMM_WORLD); /* the round's one collective */
        stop = verdict[0];
        code = verdict[1];
        *reduce_seconds += now() - tr;
    }
    if (j->rank == 0 && !j->quiet && isatty(STDERR_FILENO))
        fprintf(stderr, "\n");
    return code;
}

int main(int argc, char **argv)
{
    struct job j;
    mcrt_scene *scene = NULL;
    mcrt_render *acc = NULL;
    char *text;
    long len;
    int code, done = 0;
    double t0, reduce = 0.0;
    memset(&j, 0, sizeof j);
    MPI_Init(&argc, &argv);
    MPI_Comm_rank(MPI_COMM_WORLD, &j.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &j.size);
    t0 = now();
    code = parse(argc, argv, &j);
    if (code < 0 && !(text = broadcast_scene(&j, &len)))
        code = STATUS_USAGE;
    if (code < 0) {
        mcrt_status st = (scene = mcrt_scene_new())
                             ? mcrt_scene_load_string(scene, text, (size_t)len, j.scene)
                             : MCRT_ERR_NOMEM;
        free(text);
        code = gather_failures(&j, st == MCRT_OK ? 0 : st == MCRT_ERR_NOMEM ? STATUS_FAIL
                                                                             : STATUS_USAGE,
                               scene ? mcrt_scene_error(scene) : "out of memory");
    }
    if (code < 0)
        code = run(&j, scene, &acc, &done, &reduce);
    if (code < 0 && j.rank == 0) {
        mcrt_stats st;
        code = STATUS_OK;
        if (mcrt_render_save(acc, j.output) != MCRT_OK) {
            fprintf(stderr, "mcrt-mpi: %s\n", mcrt_render_error(acc));
            code = STATUS_FAIL;
        } else if (!j.quiet) {
            mcrt_render_stats(acc, &st, sizeof st);
            fprintf(stderr,
                    "%s: %dx%d, %d spp, %d passes on %d rank%s, %.2f s (%.3f s in rank 0's "
                    "exchanges), est. relMSE %.3g\n",
                    j.output, st.width, st.height, st.spp, done, j.size, j.size == 1 ? "" : "s",
                    now() - t0, reduce, st.est_relmse);
        }
    }
    mcrt_render_free(acc);
    mcrt_scene_free(scene);
    MPI_Finalize();
    return code < 0 ? STATUS_OK : code;
}
