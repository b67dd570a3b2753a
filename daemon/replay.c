/*
 * replay.c - mpbenchd --replay: rebuild an experiment's results from an LCM
 * log written by lcm-logger during a live benchmark, without planning again.
 *
 * The logged requests say which run each attempt id was (their seed is
 * mpbd_run_seed() of one run of the experiment, their algorithm and
 * addressee name its configuration); the logged announcements and results
 * go through the live daemon's own handlers (planners.c, results.c) over an
 * in-process memq:// LCM, so a replayed result is checked, verified,
 * measured and stored exactly as a live one: a result whose attempt id no
 * logged request carried, or that came from another planner, is rejected
 * and counted. Nothing reaches the network: acknowledgements go to memq and
 * are dropped.
 */
#include <errno.h>
#include <math.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <lcm/eventlog.h>

#include "daemon.h"
#include "mpb_daemon_status_t.h"
#include "mpb_plan_request_t.h"

/* What a replay knows of one run of the experiment. */
typedef struct replay_run {
    mpbd_run run;
    int      done;          /* stored, or its attempt superseded for good */
} replay_run;

typedef struct replay {
    mpbd       *d;
    const char *path;
    replay_run *runs;        /* sorted by seed */
    int         num_runs;
    replay_run **open;       /* runs in flight, at most one entry each */
    int         num_open;
    long        events, requests, matched, unknown_requests;
    int         finished_live; /* the log has the daemon's "done" status */
    double      log_now;     /* s, the log's clock: the current event's time */
    double      retime_at;   /* monotonic s, for retime() */
} replay;

/* The header of an event in an LCM log: magic, event number, timestamp,
 * channel length, data length (lcm/eventlog.c writes them in this order). */
#define LOG_EVENT_HEADER (4 + 8 + 8 + 4 + 4)

static int by_seed(const void *a, const void *b)
{
    int64_t x = ((const replay_run *)a)->run.seed;
    int64_t y = ((const replay_run *)b)->run.seed;
    return (x > y) - (x < y);
}

static void collect_run(void *ud, const mpbd_run *run)
{
    replay *r = ud;
    r->runs[r->num_runs++].run = *run;
}

/* Every run the store holds as not done, from the pending queues. */
static int collect_runs(replay *r)
{
    mpbd *d = r->d;
    r->runs = calloc((size_t)d->runs.total_pending + 1, sizeof *r->runs);
    r->open = calloc((size_t)d->runs.total_pending + 1, sizeof *r->open);
    if (r->runs == NULL || r->open == NULL)
        return MPB_ENOMEM;
    mpbd_runs_each_pending(d, collect_run, r);
    if (r->num_runs > 1)
        qsort(r->runs, (size_t)r->num_runs, sizeof *r->runs, by_seed);
    return MPB_OK;
}

static int planner_index(const mpbd *d, const char *id)
{
    for (int i = 0; i < d->num_planners; i++)
        if (strcmp(d->planners[i].id, id) == 0)
            return i;
    return -1;
}

/* The run a request is for: its seed, configuration and addressee's family
 * agree. A run already sent under this very id is returned too (a resend). */
static replay_run *find_run(replay *r, const mpb_plan_request_t *rq,
                            const mpbd_planner *p)
{
    replay_run key = {.run.seed = rq->seed}, *hit;
    hit = bsearch(&key, r->runs, (size_t)r->num_runs, sizeof *r->runs, by_seed);
    if (hit == NULL)
        return NULL;
    while (hit > r->runs && hit[-1].run.seed == rq->seed)
        hit--;
    /* Seeds are 31 bits: two runs may share one; the rest tells them apart. */
    replay_run *fallback = NULL;
    for (; hit < r->runs + r->num_runs && hit->run.seed == rq->seed; hit++) {
        const mpbd_config *c = &r->d->exp->configs[hit->run.config];
        if (strcmp(c->algorithm, rq->algorithm) != 0 ||
            strcmp(c->planner, p->name) != 0)
            continue;
        if (strcmp(hit->run.attempt_id, rq->attempt_id) == 0)
            return hit;
        if (!hit->done && fallback == NULL)
            fallback = hit;
    }
    return fallback;
}

/* A logged request: the run it names goes in flight, as send_next() in
 * scheduler.c puts it there live. */
static void on_request(replay *r, const lcm_eventlog_event_t *ev)
{
    mpbd *d = r->d;
    lcm_recv_buf_t rbuf = {.data = ev->data, .data_size = (uint32_t)ev->datalen,
                           .recv_utime = ev->timestamp, .lcm = d->lcm};
    mpb_plan_request_t rq;
    if (!mpbd_receive(d, MPB_WIRE_PLAN_REQUEST, &rbuf, ev->channel, &rq))
        return;
    r->requests++;
    const char *addressee = ev->channel + strlen(MPB_CHANNEL_REQUEST_PREFIX);
    int p = planner_index(d, rq.planner_id);
    replay_run *run = NULL;
    if (strcmp(addressee, rq.planner_id) == 0 && p >= 0 &&
        mpb_attempt_id_is_valid(rq.attempt_id))
        run = find_run(r, &rq, &d->planners[p]);
    if (run == NULL) {
        if (++r->unknown_requests <= 10)
            mpbd_log("%s: request %.32s to %.96s is no run of this experiment"
                     " (or its planner never announced itself); ignored",
                     r->path, rq.attempt_id, rq.planner_id);
        goto done;
    }
    r->matched++;
    if (run->done || strcmp(run->run.attempt_id, rq.attempt_id) == 0)
        goto done; /* a resend */
    if (run->run.attempt_id[0] != '\0') {
        /* A new attempt: the live daemon gave up on the previous one, or
         * took it back if it never started (taken_back() forgets it). */
        mpbd_flight *old = mpbd_flight_find(d, run->run.attempt_id);
        if (old != NULL && old->queued) {
            mpbd_take_back(d, old, "a new attempt before it started");
        } else {
            mpb_store_run_retry(d->store, run->run.id, run->run.attempt_id,
                                "no result in the log before a new attempt");
            if (old != NULL)
                mpbd_flight_remove(d, old);
        }
    }
    if (run->run.attempt_id[0] == '\0')
        r->open[r->num_open++] = run;
    memcpy(run->run.attempt_id, rq.attempt_id, MPB_ATTEMPT_ID_SIZE);
    if (mpb_store_run_sent(d->store, run->run.id, run->run.attempt_id,
                           rq.planner_id) != MPB_OK) {
        mpbd_db_error(d);
        goto done;
    }
    run->run.attempts++;
    /* Timed by the log's clock (mpbd_clock(): no resends happen in a
     * replay), so that wall times are the logged ones. A request to a busy
     * planner waits in its queue, as it did live (with no queue live, such
     * a request followed a run given up on: a crash this replay does not
     * see). */
    const mpbd_planner *pl = &d->planners[p];
    int queued = d->exp->queue_at_planner > 0 && pl->active >= pl->capacity;
    mpbd_flight *f = mpbd_flight_start(d, &run->run, p, queued, r->log_now);
    if (f != NULL) {
        f->acked = 1;
        f->deadline = INFINITY;
    }
done:
    mpb_receive_done(MPB_WIRE_PLAN_REQUEST, &rq);
}

/* The live handlers took a run back (its planner declined it, or closed
 * before starting it): it is no longer in flight, and its next request is
 * a new attempt. */
static void taken_back(void *ud, const mpbd_run *taken)
{
    replay *r = ud;
    for (int i = 0; i < r->num_open; i++) {
        replay_run *run = r->open[i];
        if (strcmp(run->run.attempt_id, taken->attempt_id) == 0) {
            run->run.attempt_id[0] = '\0';
            run->run.attempts--;
            r->open[i] = r->open[--r->num_open];
            return;
        }
    }
}

/* Hand queued in-process messages to their handlers. */
static void drain(mpbd *d)
{
    struct pollfd pfd = {.fd = lcm_get_fileno(d->lcm), .events = POLLIN};
    while (poll(&pfd, 1, 0) > 0 && (pfd.revents & POLLIN))
        if (lcm_handle(d->lcm) != 0)
            break;
}

/* A flight's sent_at on the monotonic clock, its request's logged time
 * (last_send) before the current event's as long before now. */
static void retime(void *ud, mpbd_flight *f)
{
    const replay *r = ud;
    f->sent_at = r->retime_at - (r->log_now - f->last_send);
}

/* A logged announcement, result or planner's acknowledgement: through the
 * live handlers. */
static void on_message(replay *r, const lcm_eventlog_event_t *ev, int result)
{
    mpbd *d = r->d;
    if (result) {
        /* results.c measures wall time as now - sent_at: place sent_at so
         * that it is the logged time from request to result. */
        r->retime_at = mpb_monotonic_s();
        mpbd_runs_each_flight(d, retime, r);
    }
    lcm_publish(d->lcm, ev->channel, ev->data, (unsigned)ev->datalen);
    drain(d);
    if (!result)
        return;
    /* A run whose flight ended was stored (or refused for good). */
    for (int i = 0; i < r->num_open;) {
        replay_run *run = r->open[i];
        if (mpbd_flight_find(d, run->run.attempt_id) == NULL) {
            run->done = 1;
            r->open[i] = r->open[--r->num_open];
        } else {
            i++;
        }
    }
}

/* The live daemon's status: did it finish this experiment? */
static void on_status(replay *r, const lcm_eventlog_event_t *ev)
{
    mpbd *d = r->d;
    lcm_recv_buf_t rbuf = {.data = ev->data, .data_size = (uint32_t)ev->datalen,
                           .recv_utime = ev->timestamp, .lcm = d->lcm};
    mpb_daemon_status_t st;
    if (!mpbd_receive(d, MPB_WIRE_DAEMON_STATUS, &rbuf, ev->channel, &st))
        return;
    if (strcmp(st.state, "done") == 0 &&
        strcmp(st.experiment, d->exp->name) == 0)
        r->finished_live = 1;
    mpb_receive_done(MPB_WIRE_DAEMON_STATUS, &st);
}

/*
 * Once the live daemon said the experiment was done, every run had ended:
 * a run still in flight here had no result, and was recorded as crashed
 * (its planner fell silent, or its deadline passed, with no retry left).
 */
static void record_crashes(replay *r)
{
    mpbd *d = r->d;
    while (r->num_open > 0) {
        replay_run *run = r->open[--r->num_open];
        mpbd_flight *f = mpbd_flight_find(d, run->run.attempt_id);
        if (f == NULL)
            continue;
        mpbd_run_crashed(d, f, "no result in the log of a finished "
                         "experiment", r->log_now - f->last_send);
        run->done = 1;
    }
}

/* Commit what the open transaction holds; the acknowledgements it made
 * true are dropped (nobody waits for them). */
static int commit(mpbd *d)
{
    mpbd_acks_drop(d);
    if (mpb_store_commit(d->store) != MPB_OK) {
        mpbd_db_error(d);
        mpb_store_rollback(d->store);
        return -1;
    }
    return 0;
}

static int starts_with(const char *s, const char *prefix)
{
    return strncmp(s, prefix, strlen(prefix)) == 0;
}

/* Read every event; 0 at a clean end of the log, 1 at a damaged one, -1 on
 * a database error. */
static int read_log(replay *r, lcm_eventlog_t *log, long size)
{
    mpbd *d = r->d;
    long good_end = 0;
    lcm_eventlog_event_t *ev;

    if (mpb_store_begin(d->store) != MPB_OK)
        return -1;
    while ((ev = lcm_eventlog_read_next_event(log)) != NULL) {
        long end = ftell(log->f);
        long start = end - LOG_EVENT_HEADER - ev->channellen - ev->datalen;
        if (start != good_end) {
            /* LCM skips bytes it cannot read to the next event: say so. */
            lcm_eventlog_free_event(ev);
            break;
        }
        good_end = end;
        r->events++;
        r->log_now = d->replay_now = (double)ev->timestamp * 1e-6;
        if (strcmp(ev->channel, MPB_CHANNEL_ANNOUNCE) == 0 ||
            strcmp(ev->channel, MPB_CHANNEL_ACK) == 0)
            on_message(r, ev, 0);
        else if (strcmp(ev->channel, MPB_CHANNEL_RESULT) == 0)
            on_message(r, ev, 1);
        else if (starts_with(ev->channel, MPB_CHANNEL_REQUEST_PREFIX))
            on_request(r, ev);
        else if (strcmp(ev->channel, MPB_CHANNEL_STATUS) == 0)
            on_status(r, ev);
        lcm_eventlog_free_event(ev);
        if (r->events % 1024 == 0 &&
            (commit(d) != 0 || mpb_store_begin(d->store) != MPB_OK))
            return -1;
    }
    if (good_end == size && r->finished_live)
        record_crashes(r);
    if (commit(d) != 0)
        return -1;
    if (good_end != size) {
        fprintf(stderr, "mpbenchd: %s: truncated or corrupt event at byte %ld "
                "(after %ld good events); the runs before it are stored\n",
                r->path, good_end, r->events);
        return 1;
    }
    return 0;
}

int mpbd_replay_log_readable(const char *log_path)
{
    struct stat st;
    errno = 0;
    if (stat(log_path, &st) != 0 || S_ISDIR(st.st_mode) ||
        access(log_path, R_OK) != 0) {
        fprintf(stderr, "mpbenchd: cannot read log %s: %s\n", log_path,
                strerror(errno ? errno : EISDIR));
        return -1;
    }
    return 0;
}

int mpbd_replay(mpbd *d, const char *log_path)
{
    replay r = {.d = d, .path = log_path};
    lcm_eventlog_t *log = NULL;
    struct stat st;
    int rc = 1;

    if (mpbd_replay_log_readable(log_path) != 0 || stat(log_path, &st) != 0)
        return 1;
    if ((log = lcm_eventlog_create(log_path, "r")) == NULL) {
        fprintf(stderr, "mpbenchd: cannot read log %s: %s\n", log_path,
                strerror(errno));
        return 1;
    }
    /* memq: the live handlers, with no network behind them. */
    if ((d->lcm = lcm_create("memq://")) == NULL || collect_runs(&r) != MPB_OK) {
        fprintf(stderr, "mpbenchd: cannot set up the replay\n");
        goto out;
    }
    d->replaying = 1;
    d->runs.on_take_back = taken_back;
    d->runs.take_back_ud = &r;
    mpbd_announce_subscribe(d);
    mpbd_results_subscribe(d);
    mpbd_scheduler_subscribe(d);

    int status = read_log(&r, log, (long)st.st_size);
    if (status < 0) {
        fprintf(stderr, "mpbenchd: %s: database error during the replay\n",
                log_path);
        goto out;
    }
    if (r.matched == 0) {
        fprintf(stderr, "mpbenchd: %s: none of its %ld requests is a run of "
                "experiment '%s' (recorded with another experiment file?)\n",
                log_path, r.requests, d->exp->name);
        goto out;
    }
    mpb_run_counts counts = {0};
    mpb_store_run_counts(d->store, d->experiment_id, &counts);
    if (counts.done == counts.total)
        mpb_store_experiment_finish(d->store, d->experiment_id);
    mpbd_log("replayed %s: %ld events, %d of %d runs stored (%d succeeded, "
             "%d crashed), %d without a result in the log, %ld rejected "
             "messages", log_path, r.events, counts.done, counts.total,
             counts.succeeded, counts.crashed, counts.total - counts.done,
             d->count.rejected);
    rc = status;
out:
    free(r.runs);
    free(r.open);
    lcm_eventlog_destroy(log);
    return rc;
}
