/*
 * runs.c - a run's life from send to result, and the one owner of its
 * state (mpbd_runs): the pending queue of each configuration, the runs in
 * flight, the sends not yet written, the runs given up on that their
 * planner still plans, and the runs stored lately.
 *
 * A run goes from its configuration's queue into flight when it is sent
 * (mpbd_runs_send); leaves it when its result is stored (the caller
 * removes the flight), when it crashes (retried while the experiment
 * allows, else stored as a crash) or when it is taken back because its
 * planner never started it (pending again, no attempt counted). With
 * experiment.queue_at_planner above 0, a request may wait at a busy
 * planner: it is queued, and its times and deadline start only when the
 * run before it on that planner ends, or when the planner names it among
 * its active runs. A flight's deadline is its time limit and grace from
 * its send; a planner that builds its model first says so (SETTING_UP:
 * the deadline waits up to MPBD_SETUP_ALLOWANCE_S more) and when it
 * plans (PLANNING: the limit and grace from then).
 *
 * A run given up on at its deadline may still be planned: while its
 * planner's announcements name it, it holds a slot of that planner's
 * capacity (mpbd_planner_busy), so that the next run does not wait behind
 * it and crash in its turn.
 *
 * Nothing here sends a message: this file is below the scheduler and the
 * handlers, which call it.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/grow.h"
#include "daemon.h"

/* Index of the configuration / query with this database id, or -1. */
static int config_index(const mpbd *d, int64_t db_id)
{
    for (int i = 0; i < d->exp->num_configs; i++)
        if (d->exp->configs[i].db_id == db_id)
            return i;
    return -1;
}

static int query_index(const mpbd *d, int64_t db_id)
{
    for (int i = 0; i < d->exp->num_queries; i++)
        if (d->exp->queries[i].db_id == db_id)
            return i;
    return -1;
}

static int push_pending(mpbd_runs *r, int config, const mpbd_run *run)
{
    /* Arrays grow by doubling; the length is a power of two or zero. */
    int n = r->pending_len[config];
    if ((n & (n - 1)) == 0) {
        mpbd_run *a = realloc(r->pending[config],
                              (size_t)(n ? 2 * n : 16) * sizeof *a);
        if (a == NULL)
            return MPB_ENOMEM;
        r->pending[config] = a;
    }
    r->pending[config][n] = *run;
    r->pending_len[config] = n + 1;
    r->total_pending++;
    return MPB_OK;
}

static int load_row(void *ud, const mpb_run_row *row)
{
    mpbd *d = ud;
    mpbd_run run = {.id = row->id, .seed = row->seed, .attempts = row->attempts};
    run.config = config_index(d, row->planner_config_id);
    run.query = query_index(d, row->query_id);
    if (run.config < 0 || run.query < 0)
        return MPB_ENOTFOUND;
    /* A run sent before a restart keeps its id, so that its result, if the
     * planner still delivers it, is accepted once. */
    if (row->sent && row->attempt_id && mpb_attempt_id_is_valid(row->attempt_id))
        memcpy(run.attempt_id, row->attempt_id, MPB_ATTEMPT_ID_SIZE);
    return push_pending(&d->runs, run.config, &run);
}

int mpbd_runs_load(mpbd *d)
{
    mpbd_runs *r = &d->runs;
    int n = d->exp->num_configs;
    r->num_configs = n;
    r->pending = calloc((size_t)n, sizeof *r->pending);
    r->pending_len = calloc((size_t)n, sizeof *r->pending_len);
    r->pending_head = calloc((size_t)n, sizeof *r->pending_head);
    if (!r->pending || !r->pending_len || !r->pending_head)
        return MPB_ENOMEM;
    int rc = mpb_store_runs_unfinished(d->store, d->experiment_id, load_row, d);
    if (rc != MPB_OK)
        return rc;
    /* Runs already sent before a restart go first. */
    for (int c = 0; c < n; c++) {
        mpbd_run *a = r->pending[c];
        int front = 0;
        for (int i = 0; i < r->pending_len[c]; i++)
            if (a[i].attempt_id[0] != '\0') {
                mpbd_run t = a[i];
                memmove(&a[front + 1], &a[front], (size_t)(i - front) * sizeof *a);
                a[front++] = t;
            }
    }
    return MPB_OK;
}

int mpbd_runs_waiting(const mpbd *d, int config)
{
    return d->runs.pending_len[config] - d->runs.pending_head[config];
}

void mpbd_runs_each_pending(const mpbd *d,
                            void (*fn)(void *ud, const mpbd_run *run), void *ud)
{
    const mpbd_runs *r = &d->runs;
    for (int c = 0; c < r->num_configs; c++)
        for (int i = r->pending_head[c]; i < r->pending_len[c]; i++)
            fn(ud, &r->pending[c][i]);
}

void mpbd_runs_each_flight(mpbd *d, void (*fn)(void *ud, mpbd_flight *f),
                           void *ud)
{
    for (int i = 0; i < d->runs.num_flights; i++)
        fn(ud, &d->runs.flights[i]);
}

int mpbd_requeue(mpbd *d, const mpbd_run *run)
{
    mpbd_run again = *run;
    again.attempt_id[0] = '\0';
    return push_pending(&d->runs, run->config, &again);
}

double mpbd_clock(const mpbd *d)
{
    return d->replaying ? d->replay_now : mpb_monotonic_s();
}

/* Runs a planner still plans that were given up on at their deadline. */
static int abandoned_on(const mpbd *d, int planner)
{
    int n = 0;
    for (int i = 0; i < d->runs.num_abandoned; i++)
        n += d->runs.abandoned[i].planner == planner;
    return n;
}

int mpbd_planner_busy(const mpbd *d, int planner)
{
    const mpbd_planner *p = &d->planners[planner];
    return p->active + abandoned_on(d, planner) + p->unknown;
}

/* Times of a flight that starts now: its deadline and first resend. */
static void start_clock(const mpbd *d, mpbd_flight *f, double now)
{
    f->sent_at = f->last_send = now;
    f->sends = 1;
    f->next_send = now + MPBD_REQUEST_RESEND_S;
    f->away = 0;
    f->phase = MPBD_PHASE_SENT;
    f->deadline = now + d->exp->time_limit + MPBD_DEADLINE_GRACE_S;
}

mpbd_flight *mpbd_flight_start(mpbd *d, const mpbd_run *run, int planner,
                               int queued, double now)
{
    mpbd_runs *r = &d->runs;
    if (mpb__grow((void **)&r->flights, &r->cap_flights, r->num_flights + 1,
                  sizeof *r->flights) != MPB_OK)
        return NULL;
    mpbd_flight *f = &r->flights[r->num_flights++];
    *f = (mpbd_flight){.run = *run, .planner = planner, .queued = queued};
    start_clock(d, f, now);
    if (queued) {
        f->deadline = INFINITY;
        d->planners[planner].queued++;
    } else {
        d->planners[planner].active++;
    }
    return f;
}

mpbd_flight *mpbd_runs_send(mpbd *d, int config, int planner, int queued)
{
    mpbd_runs *r = &d->runs;
    if (mpbd_runs_waiting(d, config) <= 0)
        return NULL;
    mpbd_run run = r->pending[config][r->pending_head[config]];
    /* A new attempt, or one sent before a restart going again with its id
     * (the same attempt: not counted again, here or in the store). */
    int fresh = run.attempt_id[0] == '\0';
    if (fresh && mpb_attempt_id_new(run.attempt_id) != MPB_OK) {
        mpbd_log("cannot draw a random attempt id");
        return NULL;
    }
    if (mpb__grow((void **)&r->unrecorded, &r->cap_unrecorded,
                  r->num_unrecorded + 1, sizeof *r->unrecorded) != MPB_OK)
        return NULL;
    if (fresh)
        run.attempts++;
    /* The clock now, not the loop's wake-up: the results handled since
     * then are not this run's time (its wall_time and latency). */
    mpbd_flight *f = mpbd_flight_start(d, &run, planner, queued,
                                       mpb_monotonic_s());
    if (f == NULL)
        return NULL;
    /* Written by the next transaction, before the result it may hold: a
     * request goes out as soon as a commit has made room for it. */
    mpbd_unrecorded *u = &r->unrecorded[r->num_unrecorded++];
    u->run_id = run.id;
    memcpy(u->attempt_id, run.attempt_id, sizeof u->attempt_id);
    snprintf(u->planner_id, sizeof u->planner_id, "%s", d->planners[planner].id);
    r->pending_head[config]++;
    r->total_pending--;
    return f;
}

int mpbd_runs_record_sent(mpbd *d)
{
    mpbd_runs *r = &d->runs;
    int rc = MPB_OK;
    for (int i = 0; i < r->num_unrecorded; i++) {
        const mpbd_unrecorded *u = &r->unrecorded[i];
        int e = mpb_store_run_sent(d->store, u->run_id, u->attempt_id,
                                   u->planner_id);
        /* Done already: its result came in a transaction before (a resend
         * after a restart). Anything else is the database failing. */
        if (e != MPB_OK && e != MPB_EEXISTS) {
            mpbd_db_error(d);
            rc = e;
        }
    }
    r->num_unrecorded = 0;
    return rc;
}

mpbd_flight *mpbd_flight_find(mpbd *d, const char *attempt_id)
{
    for (int i = 0; i < d->runs.num_flights; i++)
        if (strcmp(d->runs.flights[i].run.attempt_id, attempt_id) == 0)
            return &d->runs.flights[i];
    return NULL;
}

/* A queued request starts: its planner has begun it, or is about to. */
static void start_queued(mpbd *d, mpbd_flight *f)
{
    mpbd_planner *p = &d->planners[f->planner];
    f->queued = 0;
    p->queued--;
    p->active++;
    start_clock(d, f, mpbd_clock(d));
}

/* A planner with room takes its next request, the oldest waiting, now. */
static void start_next_queued(mpbd *d, int planner)
{
    const mpbd_planner *p = &d->planners[planner];
    if (p->queued == 0 || p->gone || p->closing ||
        mpbd_planner_busy(d, planner) >= p->capacity)
        return;
    mpbd_flight *next = NULL;
    for (int i = 0; i < d->runs.num_flights; i++) {
        mpbd_flight *g = &d->runs.flights[i];
        if (g->planner == planner && g->queued &&
            (next == NULL || g->sent_at < next->sent_at))
            next = g;
    }
    if (next != NULL)
        start_queued(d, next);
}

void mpbd_flight_remove(mpbd *d, mpbd_flight *f)
{
    int planner = f->planner, was_queued = f->queued;
    mpbd_planner *p = &d->planners[planner];
    if (was_queued && p->queued > 0)
        p->queued--;
    else if (!was_queued && p->active > 0)
        p->active--;
    *f = d->runs.flights[--d->runs.num_flights];
    if (!was_queued)
        start_next_queued(d, planner);
}

int mpbd_take_back(mpbd *d, mpbd_flight *f, const char *why)
{
    int rc = mpb_store_run_unsent(d->store, f->run.id, f->run.attempt_id);
    if (rc == MPB_OK) {
        mpbd_run run = f->run;
        run.attempts--;
        if (d->runs.on_take_back != NULL)
            d->runs.on_take_back(d->runs.take_back_ud, &f->run);
        rc = mpbd_requeue(d, &run);
        if (d->verbose)
            mpbd_log("run %lld %s: taken back from %s: %s",
                     (long long)f->run.id, d->exp->configs[f->run.config].name,
                     d->planners[f->planner].id, why);
    } else {
        mpbd_db_error(d);
    }
    mpbd_flight_remove(d, f);
    return rc;
}

static int names_run(char *const *runs, int n, const char *attempt_id)
{
    for (int k = 0; k < n; k++)
        if (strcmp(runs[k], attempt_id) == 0)
            return 1;
    return 0;
}

void mpbd_planner_closing(mpbd *d, int planner, char *const *active_runs,
                          int num_active)
{
    for (int i = 0; i < d->runs.num_flights;) {
        mpbd_flight *f = &d->runs.flights[i];
        if (f->planner == planner && f->queued &&
            !names_run(active_runs, num_active, f->run.attempt_id))
            mpbd_take_back(d, f, "its planner is closing"); /* f: the next */
        else
            i++;
    }
}

static int is_abandoned(const mpbd *d, int planner, const char *attempt_id)
{
    for (int i = 0; i < d->runs.num_abandoned; i++)
        if (d->runs.abandoned[i].planner == planner &&
            strcmp(d->runs.abandoned[i].attempt_id, attempt_id) == 0)
            return 1;
    return 0;
}

/* A run sent before a restart, to be sent again with its id: such runs
 * lead their configuration's queue (mpbd_runs_load). */
static int pending_resend(const mpbd *d, const char *attempt_id)
{
    const mpbd_runs *r = &d->runs;
    for (int c = 0; c < r->num_configs; c++)
        for (int i = r->pending_head[c];
             i < r->pending_len[c] && r->pending[c][i].attempt_id[0] != '\0'; i++)
            if (strcmp(r->pending[c][i].attempt_id, attempt_id) == 0)
                return 1;
    return 0;
}

int mpbd_runs_knows(const mpbd *d, int planner, const char *attempt_id)
{
    for (int i = 0; i < d->runs.num_flights; i++)
        if (strcmp(d->runs.flights[i].run.attempt_id, attempt_id) == 0)
            return 1;
    return is_abandoned(d, planner, attempt_id) || mpbd_recently_done(d, attempt_id) ||
           pending_resend(d, attempt_id);
}

/* The planner said it has the request: a queued one has started. */
static void heard_start(mpbd *d, mpbd_flight *f)
{
    f->acked = 1;
    d->planners[f->planner].declines = 0;
    if (f->queued)
        start_queued(d, f);
}

void mpbd_flight_setting_up(mpbd *d, mpbd_flight *f, double now)
{
    heard_start(d, f);
    if (f->phase != MPBD_PHASE_SENT)
        return;
    f->phase = MPBD_PHASE_SETTING_UP;
    f->deadline = fmax(f->deadline, now + MPBD_SETUP_ALLOWANCE_S +
                                        d->exp->time_limit +
                                        MPBD_DEADLINE_GRACE_S);
}

void mpbd_flight_planning(mpbd *d, mpbd_flight *f, double now)
{
    heard_start(d, f);
    if (f->phase == MPBD_PHASE_PLANNING)
        return;
    /* Never past the bound of the setup before it, nor sooner than the
     * send's own deadline (the request's way to the planner). */
    double from_now = now + d->exp->time_limit + MPBD_DEADLINE_GRACE_S;
    f->deadline = f->phase == MPBD_PHASE_SETTING_UP
                      ? fmin(f->deadline, from_now)
                      : fmax(f->deadline, from_now);
    f->phase = MPBD_PHASE_PLANNING;
}

void mpbd_planner_working_on(mpbd *d, int planner, char *const *active_runs,
                             int num_active, int unknown)
{
    mpbd_runs *r = &d->runs;
    mpbd_planner *p = &d->planners[planner];
    int dropped = unknown < p->unknown;
    for (int k = 0; k < num_active; k++) {
        mpbd_flight *f;
        if (!mpb_attempt_id_is_valid(active_runs[k]) ||
            (f = mpbd_flight_find(d, active_runs[k])) == NULL ||
            f->planner != planner)
            continue;
        heard_start(d, f);      /* it has the request: no more resends */
    }
    p->unknown = unknown;
    /* A run given up on holds its slot while the planner names it. */
    for (int i = 0; i < r->num_abandoned;) {
        mpbd_abandoned *a = &r->abandoned[i];
        if (a->planner != planner) {
            i++;
        } else if (names_run(active_runs, num_active, a->attempt_id)) {
            if (!a->named)
                mpbd_log("planner %s still plans run %lld, given up on at its "
                         "deadline: it gets no run in its place until it "
                         "stops", p->id, (long long)a->run_id);
            a->named = 1;
            i++;
        } else {
            if (a->named)
                mpbd_log("planner %s has stopped planning run %lld, %.1f s "
                         "after its deadline: it takes runs again", p->id,
                         (long long)a->run_id, mpb_monotonic_s() - a->since);
            *a = r->abandoned[--r->num_abandoned];
            dropped = 1;
        }
    }
    if (dropped)
        start_next_queued(d, planner);
}

void mpbd_runs_abandon(mpbd *d, const mpbd_flight *f)
{
    mpbd_runs *r = &d->runs;
    if (mpb__grow((void **)&r->abandoned, &r->cap_abandoned,
                  r->num_abandoned + 1, sizeof *r->abandoned) != MPB_OK)
        return;                 /* then its slot is free at once, as before */
    mpbd_abandoned *a = &r->abandoned[r->num_abandoned++];
    memcpy(a->attempt_id, f->run.attempt_id, sizeof a->attempt_id);
    a->planner = f->planner;
    a->run_id = f->run.id;
    a->since = mpb_monotonic_s();
    a->named = 0;
}

void mpbd_runs_remember(mpbd *d, const char *attempt_id)
{
    mpbd_runs *r = &d->runs;
    memcpy(r->recent[r->recent_next], attempt_id, MPB_ATTEMPT_ID_SIZE);
    r->recent_next = (r->recent_next + 1) %
                     (int)(sizeof r->recent / sizeof r->recent[0]);
}

int mpbd_recently_done(const mpbd *d, const char *attempt_id)
{
    const mpbd_runs *r = &d->runs;
    for (size_t i = 0; i < sizeof r->recent / sizeof r->recent[0]; i++)
        if (strcmp(r->recent[i], attempt_id) == 0)
            return 1;
    return 0;
}

int mpbd_run_crashed(mpbd *d, mpbd_flight *f, const char *why, double wall_time)
{
    mpb_run_record rec = {
        .run_id = f->run.id,
        .attempt_id = f->run.attempt_id,
        .planner_id = d->planners[f->planner].id,
        .status = "crash",
        .message = why,
        .time_total = NAN, .time_raw = NAN, .time_other = NAN,
        .wall_time = wall_time,
        .verify_time = NAN,
        .memory = NAN,
    };
    int rc = mpb_store_run_finish(d->store, &rec);
    if (rc == MPB_OK) {
        d->count.done++;
        d->count.crashed++;
    } else if (rc != MPB_EEXISTS) {
        mpbd_db_error(d);
    }
    /* Not remembered: a late result of this attempt is a stray now. */
    mpbd_flight_remove(d, f);
    return rc;
}

int mpbd_record_crash(mpbd *d, mpbd_flight *f, const char *why)
{
    /* Under a memory limit a planner that died of it says so in its
     * last words (a MEMORY result, stored before this); one killed
     * outright (SIGKILL, the OOM killer) cannot: say what may be. */
    char limited[512];
    if (d->exp->memory_limit > 0) {
        snprintf(limited, sizeof limited, "%s (under memory_limit %g MB; a "
                 "planner killed outright, as by the OOM killer, leaves no "
                 "last words)", why, d->exp->memory_limit);
        why = limited;
    }
    const char *config = d->exp->configs[f->run.config].name;
    const char *planner = d->planners[f->planner].id;
    long long id = (long long)f->run.id;
    if (f->run.attempts <= d->exp->retries) {
        int rc = mpb_store_run_retry(d->store, f->run.id, f->run.attempt_id, why);
        if (rc == MPB_OK && mpbd_requeue(d, &f->run) == MPB_OK) {
            mpbd_log("run %lld %s on %s: %s; retrying (attempt %d of %d)",
                     id, config, planner, why, f->run.attempts + 1,
                     d->exp->retries + 1);
            d->count.retried++;
            mpbd_flight_remove(d, f);
            return rc;
        }
        if (rc != MPB_OK)
            mpbd_db_error(d);
    }
    /* config and planner stay: the flight goes, the names do not. */
    int rc = mpbd_run_crashed(d, f, why, mpb_monotonic_s() - f->sent_at);
    if (rc == MPB_OK)
        mpbd_log("run %lld %s on %s: crash: %s", id, config, planner, why);
    return rc;
}

int mpbd_runs_done(const mpbd *d)
{
    return d->runs.total_pending == 0 && d->runs.num_flights == 0;
}

void mpbd_runs_free(mpbd *d)
{
    mpbd_runs *r = &d->runs;
    for (int c = 0; r->pending && c < r->num_configs; c++)
        free(r->pending[c]);
    free(r->pending);
    free(r->pending_len);
    free(r->pending_head);
    free(r->flights);
    free(r->unrecorded);
    free(r->abandoned);
    memset(r, 0, sizeof *r);
}
