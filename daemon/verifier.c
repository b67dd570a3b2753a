/*
 * verifier.c - verification and metrics beside the loop: a pool of worker
 * threads (--verify-threads; by default the host's cores less one, for
 * the loop) takes the results the loop hands over, verifies and measures
 * their stages (mpbd_result_measure()), and hands them back through a
 * queue and a pipe the loop polls. The loop stores them in order of
 * completion, in its transaction, and acknowledges each after the commit:
 * exactly once, resumable, as when it verified inline.
 *
 * Verifying changes the world it uses (the held joints, caches), so each
 * worker has worlds of its own: the first uses the experiment's, each
 * other a copy of every scene's world opened before it starts
 * (mpbd_scene_world_copy()). A world is never touched by two threads.
 *
 * What crosses: a job, owned by the loop until submitted, by a worker
 * while on the todo list, by the loop again once on the done list; the
 * lists are under mu. The job holds copies of the flight and the message.
 *
 * A result known to be quick (no waypoint, or a scene whose last cost
 * per waypoint puts it under MPBD_INLINE_S) is verified in the loop
 * instead, when every worker is idle: a hand-over would cost more.
 */
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "daemon.h"

typedef struct job {
    struct job        *next;
    mpbd_flight        f;        /* the run's flight, as it ended */
    mpb_plan_result_t *m;        /* the result, copied */
    double             recv;     /* when it arrived, monotonic s */
    mpbd_measured      ms;
    int                ok;       /* measured (else out of memory) */
    double             bytes;    /* the result's encoded size */
} job;

typedef struct job_list {
    job *head, *tail;
} job_list;

/* One thread of the pool, and the worlds only it touches. */
typedef struct worker {
    struct mpbd_verifier *v;
    pthread_t       thread;
    int             started;
    mpbd_worlds     worlds;      /* per scene; NULL: the experiment's */
    job            *current;     /* the one it is measuring (under mu) */
} worker;

struct mpbd_verifier {
    worker         *workers;
    int             num_workers;
    int             busy;        /* workers measuring a job (under mu) */
    pthread_mutex_t mu;
    pthread_cond_t  cond;
    pthread_cond_t  idle;        /* signalled when the todo list empties */
    job_list        todo, done;
    int             quit;
    int             pending;     /* submitted, not yet stored (loop only) */
    double          bytes;       /* their results' bytes (loop only) */
    int             fresh;       /* submitted since the last settle (loop only) */
    int             pipe[2];     /* a byte per job done: wakes the loop */
    const mpbd     *d;           /* read by the workers: the experiment */
    double         *rate;        /* per scene: s per waypoint last measured,
                                    0 if none yet (loop only) */
    double          any_rate;    /* the last measured, of any scene */
};

static void push(job_list *l, job *j)
{
    j->next = NULL;
    if (l->tail != NULL)
        l->tail->next = j;
    else
        l->head = j;
    l->tail = j;
}

static job *pop(job_list *l)
{
    job *j = l->head;
    if (j != NULL && (l->head = j->next) == NULL)
        l->tail = NULL;
    return j;
}

static void job_free(job *j)
{
    if (j == NULL)
        return;
    mpbd_measured_free(&j->ms);
    if (j->m != NULL)
        mpb_plan_result_t_destroy(j->m);
    free(j);
}

/* A result's waypoints, over its stages: what its verification costs. */
static long waypoints(const mpb_plan_result_t *m)
{
    long n = 0;
    for (int i = 0; i < m->num_stages; i++)
        n += m->stages[i].num_waypoints > 0 ? m->stages[i].num_waypoints : 0;
    return n;
}

static void *work(void *arg)
{
    worker *w = arg;
    struct mpbd_verifier *v = w->v;
    pthread_mutex_lock(&v->mu);
    for (;;) {
        while (v->todo.head == NULL && !v->quit)
            pthread_cond_wait(&v->cond, &v->mu);
        if (v->quit)
            break;
        job *j = w->current = pop(&v->todo);
        v->busy++;
        pthread_mutex_unlock(&v->mu);
        mpbd_measured_free(&j->ms);
        j->ok = mpbd_result_measure(v->d, w->worlds.truth ? &w->worlds : NULL,
                                    &j->f, j->m,
                                    &j->ms) == MPB_OK;
        pthread_mutex_lock(&v->mu);
        w->current = NULL;
        v->busy--;
        push(&v->done, j);
        if (v->todo.head == NULL && v->busy == 0)
            pthread_cond_broadcast(&v->idle);
        ssize_t n;
        do
            n = write(v->pipe[1], "", 1);
        while (n < 0 && errno == EINTR);
    }
    pthread_mutex_unlock(&v->mu);
    return NULL;
}

/* The worlds of worker w: none for the first (the experiment's), a copy
 * of every scene's (and of what its planners were given) for the others. */
static int open_worlds(struct mpbd_verifier *v, worker *w)
{
    const mpbd_experiment *e = v->d->exp;
    char why[512];
    if (w == &v->workers[0])
        return MPB_OK;
    size_t n = (size_t)e->num_scenes + 1;
    if ((w->worlds.truth = calloc(n, sizeof *w->worlds.truth)) == NULL ||
        (w->worlds.seen = calloc(n, sizeof *w->worlds.seen)) == NULL)
        return MPB_ENOMEM;
    for (int i = 0; i < e->num_scenes; i++)
        for (int seen = 0; seen < 1 + (e->scenes[i].seen != NULL); seen++) {
            mpb_world **out = seen ? &w->worlds.seen[i] : &w->worlds.truth[i];
            int rc = mpbd_scene_world_copy(e, i, seen, out, why, sizeof why);
            if (rc != MPB_OK) {
                mpbd_log("verifier thread %d: cannot open scene '%s'%s "
                         "again: %s", (int)(w - v->workers) + 1,
                         e->scenes[i].name, seen ? " as seen" : "", why);
                return rc;
            }
        }
    return MPB_OK;
}

static void close_worlds(const mpbd_experiment *e, worker *w)
{
    for (int i = 0; i < e->num_scenes; i++) {
        if (w->worlds.truth != NULL)
            mpb_world_close(w->worlds.truth[i]);
        if (w->worlds.seen != NULL)
            mpb_world_close(w->worlds.seen[i]);
    }
    free(w->worlds.truth);
    free(w->worlds.seen);
    w->worlds.truth = w->worlds.seen = NULL;
}

/* Stop and join the workers started, and free everything of v. */
static void pool_free(struct mpbd_verifier *v)
{
    pthread_mutex_lock(&v->mu);
    v->quit = 1;
    pthread_cond_broadcast(&v->cond);
    pthread_mutex_unlock(&v->mu);
    for (int i = 0; i < v->num_workers; i++) {
        if (v->workers[i].started)
            pthread_join(v->workers[i].thread, NULL);
        close_worlds(v->d->exp, &v->workers[i]);
    }
    /* Not stored: the runs stay sent in the database, and a restart runs
     * them again, as after a crash. */
    for (job *j; (j = pop(&v->todo)) != NULL || (j = pop(&v->done)) != NULL;)
        job_free(j);
    pthread_mutex_destroy(&v->mu);
    pthread_cond_destroy(&v->cond);
    pthread_cond_destroy(&v->idle);
    close(v->pipe[0]);
    close(v->pipe[1]);
    free(v->workers);
    free(v->rate);
    free(v);
}

int mpbd_verifier_threads_default(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 2 ? (int)(n - 1) : 1;
}

int mpbd_verifier_start(mpbd *d, int threads)
{
    if (threads < 1)
        threads = 1;
    struct mpbd_verifier *v = calloc(1, sizeof *v);
    if (v == NULL)
        return MPB_ENOMEM;
    v->d = d;
    v->rate = calloc((size_t)d->exp->num_scenes + 1, sizeof *v->rate);
    v->workers = calloc((size_t)threads, sizeof *v->workers);
    if (v->rate == NULL || v->workers == NULL || pipe(v->pipe) != 0) {
        free(v->rate);
        free(v->workers);
        free(v);
        return MPB_ENOMEM;
    }
    v->num_workers = threads;
    /* The loop drains it without blocking; a full pipe already wakes it. */
    fcntl(v->pipe[0], F_SETFL, fcntl(v->pipe[0], F_GETFL) | O_NONBLOCK);
    fcntl(v->pipe[1], F_SETFL, fcntl(v->pipe[1], F_GETFL) | O_NONBLOCK);
    pthread_mutex_init(&v->mu, NULL);
    pthread_cond_init(&v->cond, NULL);
    /* The loop's short waits (mpbd_verifier_settle()) are on the
     * monotonic clock, as its every other time. */
    pthread_condattr_t ca;
    pthread_condattr_init(&ca);
    pthread_condattr_setclock(&ca, CLOCK_MONOTONIC);
    pthread_cond_init(&v->idle, &ca);
    pthread_condattr_destroy(&ca);
    /* Every world opened before any thread starts: opening is not for two
     * threads at once. */
    for (int i = 0; i < threads; i++) {
        v->workers[i].v = v;
        if (open_worlds(v, &v->workers[i]) != MPB_OK) {
            pool_free(v);
            return MPB_EERROR;
        }
    }
    /* The workers take no signals: they belong to the loop's thread. */
    sigset_t all, old;
    sigfillset(&all);
    pthread_sigmask(SIG_SETMASK, &all, &old);
    int rc = 0;
    for (int i = 0; i < threads && rc == 0; i++)
        if ((rc = pthread_create(&v->workers[i].thread, NULL, work,
                                 &v->workers[i])) == 0)
            v->workers[i].started = 1;
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    if (rc != 0) {
        pool_free(v);
        return MPB_EERROR;
    }
    d->verifier = v;
    return MPB_OK;
}

void mpbd_verifier_stop(mpbd *d)
{
    if (d->verifier == NULL)
        return;
    pool_free(d->verifier);
    d->verifier = NULL;
}

/* A copy of m for the job to own, made through the wire format, not by
 * mpb_plan_result_t_copy(): LCM 1.3's generated copy hands memcpy() a
 * NULL destination for an empty double array (an untimed stage's times:
 * lcm_malloc(0) is NULL), which is undefined and stops UBSan. Destroyed
 * with mpb_plan_result_t_destroy(). */
static mpb_plan_result_t *result_copy(const mpb_plan_result_t *m)
{
    int n = mpb_plan_result_t_encoded_size(m);
    mpb_plan_result_t *c = n > 0 ? calloc(1, sizeof *c) : NULL;
    void *buf = c ? malloc((size_t)n) : NULL;
    if (buf == NULL || mpb_plan_result_t_encode(buf, 0, n, m) != n) {
        free(buf);
        free(c);
        return NULL;
    }
    int got = mpb_plan_result_t_decode(buf, 0, n, c);
    free(buf);
    if (got != n) {
        if (got >= 0)
            mpb_plan_result_t_decode_cleanup(c);
        free(c);
        return NULL;
    }
    return c;
}

int mpbd_verifier_submit(mpbd *d, const mpbd_flight *f,
                         const mpb_plan_result_t *m, double recv)
{
    struct mpbd_verifier *v = d->verifier;
    if (v == NULL || d->replaying)
        return MPB_EINVAL;
    job *j = calloc(1, sizeof *j);
    if (j == NULL || (j->m = result_copy(m)) == NULL) {
        free(j);
        return MPB_ENOMEM;
    }
    j->f = *f;
    j->recv = recv;
    j->bytes = (double)mpb_plan_result_t_encoded_size(m);
    v->bytes += j->bytes;
    pthread_mutex_lock(&v->mu);
    push(&v->todo, j);
    pthread_cond_signal(&v->cond);
    pthread_mutex_unlock(&v->mu);
    v->pending++;
    /* Worth the settle unless its scene (or, not measured yet, the
     * last one: the robot is the same) says it takes longer. */
    double rate = v->rate[d->exp->queries[f->run.query].scene];
    if (rate == 0)
        rate = v->any_rate;
    if (!(rate * (double)waypoints(m) > MPBD_SETTLE_S))
        v->fresh = 1;
    return MPB_OK;
}

/*
 * Whether to verify m in the loop rather than hand it over: the workers
 * are idle (nothing submitted and not stored: none touches a world,
 * and stores keep their order) and m has no waypoint (a failure) or the
 * scene's last cost per waypoint says it takes at most MPBD_INLINE_S.
 * Handing over costs two wake-ups and a commit's wait (bench/run.sh: 1
 * null planner 5,692 runs/s against 8,592 verifying inline); a quick
 * verification costs less than that, and less than the settle the loop
 * would wait for it anyway.
 */
int mpbd_verifier_quick(const mpbd *d, const mpbd_flight *f,
                        const mpb_plan_result_t *m)
{
    const struct mpbd_verifier *v = d->verifier;
    if (v == NULL || v->pending != 0)
        return 0;
    long n = waypoints(m);
    double rate = v->rate[d->exp->queries[f->run.query].scene];
    return n == 0 || (rate > 0 && rate * (double)n <= MPBD_INLINE_S);
}

void mpbd_verifier_learn(mpbd *d, const mpbd_flight *f,
                         const mpb_plan_result_t *m, const mpbd_measured *ms)
{
    struct mpbd_verifier *v = d->verifier;
    long n = waypoints(m);
    if (v == NULL || n == 0)
        return;
    double t = ms->verified - ms->verify_start;
    v->any_rate = v->rate[d->exp->queries[f->run.query].scene] =
        (t > 0 ? t : 1e-9) / (double)n;
}

/*
 * Results handed over since the last call get up to max_s to be measured
 * before the loop collects: most take microseconds (a null planner's, a
 * short planar path), and stored in the same round of the loop they cost
 * one commit and no extra wake-up (bench/run.sh: 1 null planner's runs/s
 * halved without it). A long one is left to finish beside the loop,
 * which waits for it only once; one its scene's last cost per waypoint
 * says is longer than MPBD_SETTLE_S is not waited for at all (a Panda
 * path, tens of milliseconds: the wait would only delay the planner's
 * next request).
 */
void mpbd_verifier_settle(mpbd *d, double max_s)
{
    struct mpbd_verifier *v = d->verifier;
    if (v == NULL || !v->fresh)
        return;
    v->fresh = 0;
    struct timespec until;
    clock_gettime(CLOCK_MONOTONIC, &until);
    long ns = until.tv_nsec + (long)(max_s * 1e9);
    until.tv_sec += ns / 1000000000L;
    until.tv_nsec = ns % 1000000000L;
    pthread_mutex_lock(&v->mu);
    while ((v->todo.head != NULL || v->busy > 0) &&
           pthread_cond_timedwait(&v->idle, &v->mu, &until) == 0)
        ;
    pthread_mutex_unlock(&v->mu);
}

static int has_in(const job_list *l, const char *attempt_id)
{
    for (const job *j = l->head; j != NULL; j = j->next)
        if (strcmp(j->f.run.attempt_id, attempt_id) == 0)
            return 1;
    return 0;
}

int mpbd_verifier_has(const mpbd *d, const char *attempt_id)
{
    struct mpbd_verifier *v = d->verifier;
    if (v == NULL || v->pending == 0)
        return 0;
    pthread_mutex_lock(&v->mu);
    int has = has_in(&v->todo, attempt_id) || has_in(&v->done, attempt_id);
    for (int i = 0; i < v->num_workers && !has; i++)
        has = v->workers[i].current != NULL &&
              strcmp(v->workers[i].current->f.run.attempt_id, attempt_id) == 0;
    pthread_mutex_unlock(&v->mu);
    return has;
}

int mpbd_verifier_pending(const mpbd *d)
{
    return d->verifier != NULL ? d->verifier->pending : 0;
}

double mpbd_verifier_bytes(const mpbd *d)
{
    return d->verifier != NULL ? d->verifier->bytes : 0;
}

int mpbd_verifier_fd(const mpbd *d)
{
    return d->verifier != NULL ? d->verifier->pipe[0] : -1;
}

void mpbd_verifier_collect(mpbd *d)
{
    struct mpbd_verifier *v = d->verifier;
    if (v == NULL)
        return;
    char buf[256];
    while (read(v->pipe[0], buf, sizeof buf) > 0)
        ;
    for (;;) {
        pthread_mutex_lock(&v->mu);
        job *j = v->done.head;
        pthread_mutex_unlock(&v->mu);
        if (j == NULL)
            return;
        pthread_mutex_lock(&v->mu);
        if (!j->ok) {
            /* Out of memory measuring it: measured again, later. */
            pop(&v->done);
            push(&v->todo, j);
            pthread_cond_signal(&v->cond);
            pthread_mutex_unlock(&v->mu);
            return;
        }
        pthread_mutex_unlock(&v->mu);
        mpbd_verifier_learn(d, &j->f, j->m, &j->ms);
        if (mpbd_result_store(d, &j->f, j->m, j->recv, &j->ms) == MPBD_RETRY)
            return;     /* the store failed: this one first, next round */
        pthread_mutex_lock(&v->mu);
        pop(&v->done);
        pthread_mutex_unlock(&v->mu);
        v->pending--;
        v->bytes -= j->bytes;
        job_free(j);
    }
}
