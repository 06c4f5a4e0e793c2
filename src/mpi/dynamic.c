/* dynamic.c: mcrt-mpi's dynamic schedule (job.h). Rank 0 hands out the passes one at a time, the
 * next to whichever rank reports one done, so that a slower rank (a busier machine, fewer cores)
 * renders fewer of them instead of holding up a round. Rank 0 renders too, in a second thread
 * (which never calls MPI, hence MPI_THREAD_FUNNELED), while its main thread serves the ranks.
 *
 * The passes arrive in any order but are added in pass order, so the image is the one process's
 * (main.c): a pass that comes before its predecessors waits in a window of WINDOW(N) passes past
 * the last one added, and no pass beyond that window is handed out, which bounds rank 0's memory
 * at WINDOW(N) passes' sums (112 bytes a pixel each) when one rank is far slower than the rest.
 * --target-error is checked after each pass added, as one process does; the passes rendered past
 * the one that met it are dropped (rank 0's own is cancelled). --time hands a rank no pass that,
 * as long as its last, would end after the budget, as mcrt starts no such pass.
 *
 * The waits poll with a sleep of a millisecond (wait_quietly) instead of OpenMPI's blocking
 * calls, which spin at full speed: on an oversubscribed machine a spinning rank takes the core
 * of one that renders. */
#include <mpi.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "mpi/job.h"

/* Rank 0 keeps at most this many passes past the last one added. */
#define WINDOW(ranks) (2 * (ranks))

enum { TAG_ASSIGN = 10, TAG_REPORT, TAG_MSG, TAG_SUMS };
enum { STOP = -1, NONE = -2 }; /* assignments besides a pass number */

static void nap(void)
{
    struct timespec ms = {0, 1000000};
    nanosleep(&ms, NULL);
}

static void wait_quietly(MPI_Request *req)
{
    int flag = 0;
    for (MPI_Test(req, &flag, MPI_STATUS_IGNORE); !flag; MPI_Test(req, &flag, MPI_STATUS_IGNORE))
        nap();
}

/* The job's exit status from rank 0, for every rank. */
static int final_code(int code)
{
    MPI_Request req;
    MPI_Ibcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD, &req);
    wait_quietly(&req);
    return code;
}

/* The next assignment from rank 0: a pass number or STOP. */
static int assignment(void)
{
    MPI_Request req;
    int k;
    MPI_Irecv(&k, 1, MPI_INT, 0, TAG_ASSIGN, MPI_COMM_WORLD, &req);
    wait_quietly(&req);
    return k;
}

/* A rank other than 0: render what rank 0 hands out, reporting each pass (its status and pass
 * number, then its sums or its failure's message), until it says stop. */
static int worker(const struct job *j, const mcrt_scene *scene)
{
    char msg[MSG_LEN];
    int k, header[2];
    for (k = assignment(); k != STOP; k = assignment()) {
        mcrt_render *r = mc_mpi_pass_new(j, scene, k);
        MPI_Request req;
        size_t bytes = 0;
        msg[0] = '\0';
        header[0] = mc_mpi_pass_run(r, msg);
        header[1] = k;
        MPI_Send(header, 2, MPI_INT, 0, TAG_REPORT, MPI_COMM_WORLD);
        if (header[0])
            MPI_Isend(msg, MSG_LEN, MPI_CHAR, 0, TAG_MSG, MPI_COMM_WORLD, &req);
        else {
            const void *sums = mcrt_render_sums(r, &bytes);
            MPI_Isend((void *)sums, (int)bytes, MPI_BYTE, 0, TAG_SUMS, MPI_COMM_WORLD, &req);
        }
        wait_quietly(&req);
        mcrt_render_free(r);
    }
    return final_code(-1);
}

/* Rank 0's render thread and its main thread meet here, under lock. */
struct own {
    pthread_mutex_t lock;
    pthread_cond_t news; /* an assignment for the thread, or a report for the main thread */
    const struct job *j;
    const mcrt_scene *scene;
    int assigned;         /* the pass to render next, STOP, or NONE */
    mcrt_render *running; /* the pass being rendered, for mcrt_render_cancel */
    int reported;         /* the pass just rendered, or NONE once the main thread took it */
    mcrt_render *result;
    int status;
    char msg[MSG_LEN];
};

static void *own_thread(void *arg)
{
    struct own *o = arg;
    pthread_mutex_lock(&o->lock);
    for (;;) {
        mcrt_render *r;
        char msg[MSG_LEN] = "";
        int k, status;
        while (o->assigned == NONE || o->reported != NONE)
            pthread_cond_wait(&o->news, &o->lock);
        if ((k = o->assigned) == STOP)
            break;
        o->assigned = NONE;
        o->running = r = mc_mpi_pass_new(o->j, o->scene, k);
        pthread_mutex_unlock(&o->lock);
        status = mc_mpi_pass_run(r, msg);
        pthread_mutex_lock(&o->lock);
        o->running = NULL;
        o->reported = k;
        o->result = r;
        o->status = status;
        memcpy(o->msg, msg, sizeof msg);
        pthread_cond_broadcast(&o->news);
    }
    pthread_mutex_unlock(&o->lock);
    return NULL;
}

/* A pass received before its predecessors: another rank's sums, or rank 0's own render. */
struct slot {
    int present, rank;
    void *buf;
    size_t bytes;
    mcrt_render *render;
};

/* What a rank is doing, for rank 0. */
enum { BUSY, WAITING, STOPPED };

/* Rank 0's bookkeeping. */
struct coordinator {
    const struct job *j;
    struct own *own;
    struct outcome *out;
    int limit, window;
    int next;     /* the next pass to hand out */
    int added;    /* passes added to *acc, in order */
    int dropping; /* no more passes count: a failure, or the target met */
    int code;     /* the exit status, or -1 */
    int active;   /* ranks not told to stop */
    int *state;
    double t0, *handed, *took; /* a rank's last hand-out, and how long its pass took */
    struct slot *slots;                   /* pass k, while it waits, in slots[k % window] */
};

/* Give rank r its next pass, tell it to stop, or let it wait for the window to move. */
static void hand_out(struct coordinator *c, int r)
{
    const struct job *j = c->j;
    double t = mc_mpi_now();
    int k = c->next;
    if (c->dropping || k >= c->limit ||
        (j->o.time_budget > 0.0 && t - c->t0 + c->took[r] > j->o.time_budget))
        k = STOP;
    else if (k >= c->added + c->window) {
        c->state[r] = WAITING;
        return;
    } else
        c->next++;
    c->state[r] = k == STOP ? STOPPED : BUSY;
    c->active -= k == STOP;
    c->handed[r] = t;
    if (r == 0) {
        pthread_mutex_lock(&c->own->lock);
        c->own->assigned = k;
        pthread_cond_broadcast(&c->own->news);
        pthread_mutex_unlock(&c->own->lock);
    } else
        MPI_Send(&k, 1, MPI_INT, r, TAG_ASSIGN, MPI_COMM_WORLD);
}

/* No more passes count: rank 0's own is cancelled, the others' are dropped as they arrive. */
static void drop_the_rest(struct coordinator *c)
{
    c->dropping = 1;
    pthread_mutex_lock(&c->own->lock);
    if (c->own->running)
        mcrt_render_cancel(c->own->running);
    pthread_mutex_unlock(&c->own->lock);
}

/* Rank r's pass failed: the job fails with its status (the first failure's message is printed;
 * passes rendered after a failure or the target do not count). */
static void failed(struct coordinator *c, int r, int status, const char *msg)
{
    if (c->dropping)
        return;
    fprintf(stderr, "mcrt-mpi: rank %d: %s\n", r, msg);
    c->code = status;
    drop_the_rest(c);
}

/* Add the passes that are next in order, checking the target after each as one process does. */
static void add_ready(struct coordinator *c)
{
    struct slot *s;
    while (!c->dropping && (s = &c->slots[c->added % c->window])->present) {
        double t = mc_mpi_now();
        if (c->added == 0) { /* pass 0 is rank 0's own (run): the image starts as it */
            c->out->acc = s->render;
            s->render = NULL;
        } else {
            size_t bytes = s->bytes;
            const void *sums = s->render ? mcrt_render_sums(s->render, &bytes) : s->buf;
            if (mcrt_render_add_sums(c->out->acc, sums, bytes, c->added, 1) != MCRT_OK) {
                failed(c, 0, 1, mcrt_render_error(c->out->acc));
                return;
            }
        }
        c->out->by_rank[s->rank]++;
        mcrt_render_free(s->render);
        free(s->buf);
        memset(s, 0, sizeof *s);
        c->out->done = ++c->added;
        c->out->exchange += mc_mpi_now() - t;
        if (c->j->o.target_error > 0.0) {
            mcrt_stats st;
            mcrt_render_stats(c->out->acc, &st, sizeof st);
            if (st.est_relmse <= c->j->o.target_error)
                drop_the_rest(c);
        }
        mc_mpi_progress(c->j, c->added, c->t0);
    }
}

/* Rank r reported pass k: keep it for its turn (unless no more passes count), and note how long
 * it took. */
static void reported(struct coordinator *c, int r, int k, void *buf, size_t bytes,
                     mcrt_render *render)
{
    c->state[r] = WAITING;
    c->took[r] = mc_mpi_now() - c->handed[r];
    if (c->dropping) {
        free(buf);
        mcrt_render_free(render);
        return;
    }
    c->slots[k % c->window] = (struct slot){1, r, buf, bytes, render};
}

/* Take the report waiting from another rank: its header, then its message or its sums. */
static void receive(struct coordinator *c, int r)
{
    char msg[MSG_LEN];
    MPI_Status probe;
    int header[2], count;
    void *buf;
    double t = mc_mpi_now();
    MPI_Recv(header, 2, MPI_INT, r, TAG_REPORT, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (header[0]) {
        MPI_Recv(msg, MSG_LEN, MPI_CHAR, r, TAG_MSG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        reported(c, r, header[1], NULL, 0, NULL);
        failed(c, r, header[0], msg);
        return;
    }
    MPI_Probe(r, TAG_SUMS, MPI_COMM_WORLD, &probe);
    MPI_Get_count(&probe, MPI_BYTE, &count);
    if (!(buf = malloc(count ? (size_t)count : 1)))
        MPI_Abort(MPI_COMM_WORLD, 1); /* out of memory: nothing to do but stop */
    MPI_Recv(buf, count, MPI_BYTE, r, TAG_SUMS, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    c->out->exchange += mc_mpi_now() - t;
    reported(c, r, header[1], buf, (size_t)count, NULL);
}

/* Take rank 0's own report, if there is one; whether there was. */
static int take_own(struct coordinator *c)
{
    struct own *o = c->own;
    mcrt_render *r;
    char msg[MSG_LEN];
    int k, status;
    pthread_mutex_lock(&o->lock);
    if ((k = o->reported) == NONE) {
        pthread_mutex_unlock(&o->lock);
        return 0;
    }
    r = o->result;
    status = o->status;
    memcpy(msg, o->msg, sizeof msg);
    o->reported = NONE;
    o->result = NULL;
    pthread_mutex_unlock(&o->lock);
    if (status) {
        reported(c, 0, k, NULL, 0, NULL);
        mcrt_render_free(r);
        failed(c, 0, status, msg);
    } else
        reported(c, 0, k, NULL, 0, r);
    return 1;
}

/* Wait for rank 0's thread to report, or a millisecond for the other ranks. */
static void wait_for_news(struct own *o)
{
    struct timespec until;
    clock_gettime(CLOCK_REALTIME, &until);
    until.tv_nsec += 1000000;
    until.tv_sec += until.tv_nsec / 1000000000;
    until.tv_nsec %= 1000000000;
    pthread_mutex_lock(&o->lock);
    if (o->reported == NONE)
        pthread_cond_timedwait(&o->news, &o->lock, &until);
    pthread_mutex_unlock(&o->lock);
}

static int coordinate(const struct job *j, const mcrt_scene *scene, struct outcome *out)
{
    struct own own;
    struct coordinator c;
    pthread_t thread;
    int r, i;
    memset(&own, 0, sizeof own);
    memset(&c, 0, sizeof c);
    own.j = j;
    own.scene = scene;
    own.assigned = own.reported = NONE;
    c.j = j;
    c.own = &own;
    c.out = out;
    c.limit = mc_mpi_pass_limit(j, scene);
    c.window = WINDOW(j->size);
    c.code = -1;
    c.active = j->size;
    c.t0 = mc_mpi_now();
    c.state = calloc((size_t)j->size, sizeof *c.state);
    c.handed = calloc((size_t)j->size, sizeof *c.handed);
    c.took = calloc((size_t)j->size, sizeof *c.took);
    c.slots = calloc((size_t)c.window, sizeof *c.slots);
    if (!c.state || !c.handed || !c.took || !c.slots)
        MPI_Abort(MPI_COMM_WORLD, 1);
    pthread_mutex_init(&own.lock, NULL);
    pthread_cond_init(&own.news, NULL);
    if (pthread_create(&thread, NULL, own_thread, &own) != 0)
        MPI_Abort(MPI_COMM_WORLD, 1); /* no thread to be had: nothing to do but stop */
    for (r = 0; r < j->size; r++) /* rank r starts with pass r: pass 0 is rank 0's own */
        hand_out(&c, r);
    while (c.active > 0) {
        int flag = 1, news = 0;
        MPI_Status st;
        while (MPI_Iprobe(MPI_ANY_SOURCE, TAG_REPORT, MPI_COMM_WORLD, &flag, &st), flag) {
            receive(&c, st.MPI_SOURCE);
            news = 1;
        }
        news |= take_own(&c);
        add_ready(&c);
        if (c.added >= c.limit)
            c.dropping = 1; /* every pass added: the ranks are told to stop */
        for (r = 0; r < j->size; r++)
            if (c.state[r] == WAITING)
                hand_out(&c, r);
        if (!news && c.active > 0)
            wait_for_news(&own);
    }
    pthread_join(thread, NULL);
    for (i = 0; i < c.window; i++) { /* passes past the last one added: dropped */
        free(c.slots[i].buf);
        mcrt_render_free(c.slots[i].render);
    }
    pthread_cond_destroy(&own.news);
    pthread_mutex_destroy(&own.lock);
    free(c.state);
    free(c.handed);
    free(c.took);
    free(c.slots);
    return final_code(c.code);
}

int mc_mpi_run_dynamic(const struct job *j, const mcrt_scene *scene, struct outcome *out)
{
    return j->rank == 0 ? coordinate(j, scene, out) : worker(j, scene);
}
