/* main.c: mcrt-mpi, one render across the processes of an MPI job (mcrt(1), mcrt-mpi).
 * Like mcrt it is a client of the public API (mcrt.h) only; MPI never enters the library.
 *
 * Rank 0 reads the scene file and broadcasts its text, so one file is read, not one per rank.
 * The render is a sequence of passes, each an independent sample set keyed by (seed, pass)
 * (mcrt_options.first_pass), so any rank can render any pass; a schedule (job.h: static.c,
 * dynamic.c) says which. Rank 0 adds the passes' sums to its image one after another in pass
 * order (mcrt_render_add_sums), whatever order they arrive in: exactly the sums a single process
 * makes when it merges its passes as it renders them, so the image is bit-identical to one
 * process's. MPI's own reductions would regroup the floating-point sums (anchor notes, section
 * 4), so they are not used for the image. A rank that fails sends its message instead of sums;
 * rank 0 prints it and every rank stops; the output is written only by rank 0 at the end
 * (through a temporary file), so it is never touched by a failed job. */
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
#include "mpi/job.h"

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
    "  --schedule NAME   how passes are given to ranks (default: dynamic):\n"
    "%s"
    "\n"
    "exit status: 0 success; 1 a rank failed or the image could not be written; 2 bad input\n";

/* mcrt's render options (MC_RENDER_ARGS), then mcrt-mpi's own. */
enum { OPT_OUTPUT = RENDER_ARGS_END, OPT_SCHEDULE, OPT_QUIET, OPT_HELP, OPT_END };
static const struct arg_spec options[OPT_END + 1] = {
    MC_RENDER_ARGS(MC_RENDER_ARG_SPEC)
    [OPT_OUTPUT] = {NULL, 'o', 1}, [OPT_SCHEDULE] = {"schedule", 0, 1},
    [OPT_QUIET] = {"quiet", 0, 0}, [OPT_HELP] = {"help", 0, 0}, [OPT_END] = {NULL, 0, 0}};

#define SCHEDULE_ENTRY(id, name, run, description) {name, run, description},
static const struct schedule {
    const char *name;
    int (*run)(const struct job *j, const mcrt_scene *scene, struct outcome *out);
    const char *description;
} schedules[SCHEDULES_END] = {MC_MPI_SCHEDULES(SCHEDULE_ENTRY)};

/* --help: the usage with the schedules' table. */
static void print_usage(void)
{
    char lines[512] = "";
    size_t used = 0;
    int i;
    for (i = 0; i < SCHEDULES_END; i++)
        used += (size_t)snprintf(lines + used, used < sizeof lines ? sizeof lines - used : 0,
                                 "      %-8s  %s\n", schedules[i].name, schedules[i].description);
    printf(usage, lines);
}

/* --schedule NAME into *out; says which there are when NAME is none of them. */
static int parse_schedule(const char *text, int *out)
{
    int i;
    for (i = 0; i < SCHEDULES_END; i++)
        if (strcmp(text, schedules[i].name) == 0) {
            *out = i;
            return 1;
        }
    fprintf(stderr, "mcrt-mpi: --schedule: expected");
    for (i = 0; i < SCHEDULES_END; i++)
        fprintf(stderr, "%s %s", i == 0 ? "" : i + 1 < SCHEDULES_END ? "," : " or",
                schedules[i].name);
    fprintf(stderr, ", got '%s'\n", text);
    return 0;
}

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
    /* The default measured faster on an oversubscribed box (mcrt(1), tests/tools/mpi_bench.sh). */
    j->schedule = SCHEDULE_DYNAMIC;
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
        case OPT_SCHEDULE:
            if (!parse_schedule(v, &j->schedule))
                return STATUS_USAGE;
            break;
        case OPT_QUIET: j->quiet = 1; break;
        case OPT_HELP:
            if (j->rank == 0)
                print_usage();
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

int main(int argc, char **argv)
{
    struct job j;
    mcrt_scene *scene = NULL;
    struct outcome out;
    char *text, ranks[256] = "";
    long len;
    int code, provided, r;
    double t0;
    memset(&j, 0, sizeof j);
    memset(&out, 0, sizeof out);
    /* The dynamic schedule's rank 0 renders in a second thread, which never calls MPI. */
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &j.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &j.size);
    t0 = mc_mpi_now();
    code = parse(argc, argv, &j);
    if (code < 0 && j.schedule == SCHEDULE_DYNAMIC && provided < MPI_THREAD_FUNNELED) {
        fprintf(stderr, "mcrt-mpi: --schedule dynamic needs threads, which this MPI refuses "
                        "(MPI_THREAD_FUNNELED)\n"); /* printed by rank 0 only (parse) */
        code = STATUS_FAIL;
    }
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
    if (code < 0 && !(out.by_rank = calloc((size_t)j.size, sizeof *out.by_rank)))
        MPI_Abort(MPI_COMM_WORLD, 1); /* out of memory: nothing to do but stop */
    if (code < 0) {
        code = schedules[j.schedule].run(&j, scene, &out);
        if (j.rank == 0 && !j.quiet && isatty(STDERR_FILENO))
            fprintf(stderr, "\n"); /* after the progress line */
    }
    if (code < 0 && j.rank == 0) {
        mcrt_stats st;
        code = STATUS_OK;
        if (mcrt_render_save(out.acc, j.output) != MCRT_OK) {
            fprintf(stderr, "mcrt-mpi: %s\n", mcrt_render_error(out.acc));
            code = STATUS_FAIL;
        } else if (!j.quiet) {
            /* The passes each rank rendered, "3+2+2": the load balance. */
            for (r = 0; r < j.size && strlen(ranks) + 16 < sizeof ranks; r++)
                sprintf(ranks + strlen(ranks), "%s%d", r ? "+" : "", out.by_rank[r]);
            mcrt_render_stats(out.acc, &st, sizeof st);
            fprintf(stderr,
                    "%s: %dx%d, %d spp, %d passes on %d rank%s (%s%s, %s), %.2f s (%.3f s in "
                    "rank 0's exchanges), est. relMSE %.3g\n",
                    j.output, st.width, st.height, st.spp, out.done, j.size,
                    j.size == 1 ? "" : "s", ranks, r < j.size ? "+..." : "",
                    schedules[j.schedule].name, mc_mpi_now() - t0, out.exchange, st.est_relmse);
        }
    }
    free(out.by_rank);
    mcrt_render_free(out.acc);
    mcrt_scene_free(scene);
    MPI_Finalize();
    return code < 0 ? STATUS_OK : code;
}
