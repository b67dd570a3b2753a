/*
 * scheduler.c - which run goes to which planner, and what happens to a run
 * on the network: resent until the planner acknowledges it, recorded as
 * crashed if its planner goes silent or its deadline passes.
 *
 * With experiment.queue_at_planner above 0 (default 0), a busy planner also
 * holds its next request, so that it starts its next run the moment it
 * ends the last instead of idling while the daemon verifies and stores
 * that one (at the cost of that work overlapping its planning). Such a
 * request is queued: it starts, with its times and deadline, when the run
 * before it on that planner ends, or when the planner announces it is
 * working on it. One its planner never started (declined, or left at one
 * that closed or went away) is taken back: pending again, no attempt and
 * no crash counted.
 *
 * A run given up on at its deadline may still be planned: while its
 * planner's announcements name it, it holds a slot of that planner's
 * capacity, so that the next run does not wait behind it and crash in its
 * turn. A planner that declines requests although it announces room for
 * them gets none for a while, longer each time (1 s doubling to 60 s).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/grow.h"
#include "daemon.h"
#include "mpbench/auth.h"
#include "mpbench/lcm_filter.h"
#include "mpb_plan_request_t.h"
#include "mpb_run_ack_t.h"

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

static int push_pending(mpbd *d, int config, const mpbd_run *run)
{
    /* Arrays grow by doubling; the length is a power of two or zero. */
    int n = d->pending_len[config];
    if ((n & (n - 1)) == 0) {
        mpbd_run *a = realloc(d->pending[config],
                              (size_t)(n ? 2 * n : 16) * sizeof *a);
        if (a == NULL)
            return MPB_ENOMEM;
        d->pending[config] = a;
    }
    d->pending[config][n] = *run;
    d->pending_len[config] = n + 1;
    d->total_pending++;
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
    if (row->sent && row->run_uid && mpb_run_id_is_valid(row->run_uid))
        memcpy(run.uid, row->run_uid, MPB_RUN_ID_SIZE);
    return push_pending(d, run.config, &run);
}

int mpbd_scheduler_load(mpbd *d)
{
    int n = d->exp->num_configs;
    d->pending = calloc((size_t)n, sizeof *d->pending);
    d->pending_len = calloc((size_t)n, sizeof *d->pending_len);
    d->pending_head = calloc((size_t)n, sizeof *d->pending_head);
    if (!d->pending || !d->pending_len || !d->pending_head)
        return MPB_ENOMEM;
    int rc = mpb_store_runs_unfinished(d->store, d->experiment_id, load_row, d);
    if (rc != MPB_OK)
        return rc;
    /* Runs already sent before a restart go first. */
    for (int c = 0; c < n; c++) {
        mpbd_run *a = d->pending[c];
        int front = 0;
        for (int i = 0; i < d->pending_len[c]; i++)
            if (a[i].uid[0] != '\0') {
                mpbd_run t = a[i];
                memmove(&a[front + 1], &a[front], (size_t)(i - front) * sizeof *a);
                a[front++] = t;
            }
    }
    return MPB_OK;
}

/* The request for a run of config c on query q, without what changes
 * from one send to the next (utime, run_id, planner_id, seed, stored).
 * It points into e. */
static void fill_request(const mpbd_experiment *e, int config, int query,
                         mpb_plan_request_t *rq)
{
    const mpbd_config *c = &e->configs[config];
    const mpbd_query *q = &e->queries[query];
    const mpbd_scene *s = &e->scenes[q->scene];
    *rq = (mpb_plan_request_t){
        .run_id = "",
        .planner_id = "",
        .algorithm = c->algorithm,
        .num_params = (int16_t)c->num_params,
        .params = c->params,
        .time_limit = e->time_limit,
        .memory_limit = e->memory_limit,
        .robot_format = s->robot_format,
        .robot_hash = (char *)s->robot_hash,
        .robot = s->robot,
        .scene_format = s->scene_format,
        .scene_hash = (char *)s->scene_hash,
        .scene = s->scene,
        .num_joints = (int16_t)e->num_joints,
        .joint_names = e->joint_names,
        .start = q->start,
        .num_held = (int16_t)e->num_held,
        .held_names = e->held_names,
        .held_values = q->held,
        .goal = {
            .kind = MPB_GOAL_T_JOINTS,
            .num_joints = (int16_t)e->num_joints,
            .joints = q->goal,
            .joint_tolerance = q->tolerance,
            .link = "",
        },
    };
    if (q->goal_kind == MPB_GOAL_POSE_REGION) {
        rq->goal = (mpb_goal_t){.kind = MPB_GOAL_T_POSE_REGION,
                                .link = q->goal_link};
        memcpy(rq->goal.position, q->position, sizeof q->position);
        memcpy(rq->goal.position_tolerance, q->position_tolerance,
               sizeof q->position_tolerance);
        memcpy(rq->goal.orientation_rpy, q->rpy, sizeof q->rpy);
        memcpy(rq->goal.orientation_tolerance, q->rpy_tolerance,
               sizeof q->rpy_tolerance);
    }
}

int mpbd_requests_fit(const mpbd_experiment *e, int authenticated, char *err,
                      size_t errlen)
{
    /* The longest a request can be: the longest planner id and a full
     * load of acknowledgements riding on it. The robot and scene text,
     * counted once per scene, stand apart from the rest. */
    static char planner_id[MPB_PLANNER_ID_MAX + 1];
    static char run_id[MPB_RUN_ID_SIZE];
    char *stored[MPBD_STORED_MAX];
    memset(planner_id, 'x', MPB_PLANNER_ID_MAX);
    memset(run_id, '0', MPB_RUN_ID_SIZE - 1);
    for (int i = 0; i < MPBD_STORED_MAX; i++)
        stored[i] = run_id;
    for (int q = 0; q < e->num_queries; q++) {
        const mpbd_scene *s = &e->scenes[e->queries[q].scene];
        size_t robot = strlen(s->robot), scene = strlen(s->scene);
        size_t rest = 0;
        for (int c = 0; c < e->num_configs; c++) {
            mpb_plan_request_t rq;
            fill_request(e, c, q, &rq);
            rq.run_id = run_id;
            rq.planner_id = planner_id;
            rq.num_stored = MPBD_STORED_MAX;
            rq.stored = stored;
            rq.robot = rq.scene = "";
            size_t n = (size_t)mpb_plan_request_t_encoded_size(&rq);
            if (n > rest)
                rest = n;
        }
        size_t total = rest + robot + scene +
                       (authenticated ? MPB_AUTH_TRAILER_SIZE : 0);
        if (total > MPB_LCM_MESSAGE_MAX) {
            snprintf(err, errlen,
                     "%s: scene '%s' (query '%s'): its plan request would be "
                     "%zu bytes (robot %zu, scene %zu), over the %u-byte "
                     "bound of an LCM message (MPB_LCM_MESSAGE_MAX)",
                     e->file, s->name, e->queries[q].name, total, robot,
                     scene, MPB_LCM_MESSAGE_MAX);
            return MPB_EINVAL;
        }
    }
    return MPB_OK;
}

static int publish_request(mpbd *d, const mpbd_flight *f)
{
    const mpbd_experiment *e = d->exp;
    const mpbd_planner *p = &d->planners[f->planner];
    char channel[sizeof MPB_CHANNEL_REQUEST_PREFIX + MPB_PLANNER_ID_MAX];
    mpb_plan_request_t rq;
    fill_request(e, f->run.config, f->run.query, &rq);
    rq.utime = mpb_utime_now();
    rq.run_id = (char *)f->run.uid;
    rq.planner_id = (char *)p->id;
    rq.seed = f->run.seed;
    if (mpb_request_channel(p->id, channel, sizeof channel) != MPB_OK)
        return MPB_EINVAL;
    /* The planner's stored results ride along (acks.c). If this send
     * fails, the planner re-sends those results and is answered again. */
    char stored_ids[MPBD_STORED_MAX][MPB_RUN_ID_SIZE];
    char *stored[MPBD_STORED_MAX];
    rq.num_stored = (int16_t)mpbd_owed_take(d, p->id, stored_ids, MPBD_STORED_MAX);
    for (int i = 0; i < rq.num_stored; i++)
        stored[i] = stored_ids[i];
    rq.stored = stored;
    d->requested = 1;
    return mpb_publish_request(d->lcm, d->auth, p->instance, channel, &rq);
}

/* Send the next run of config c to planner p (to wait in its queue if
 * queued); 0 if there was none. */
static int send_next(mpbd *d, int c, int p, int queued)
{
    double now;
    mpbd_run run;
    mpbd_flight *f;
    if (d->pending_head[c] >= d->pending_len[c])
        return 0;
    run = d->pending[c][d->pending_head[c]];
    /* A new attempt, or one sent before a restart going again with its id
     * (the same attempt: not counted again, here or in the store). */
    int fresh = run.uid[0] == '\0';
    if (fresh && mpb_run_id_new(run.uid) != MPB_OK) {
        mpbd_log("cannot draw a random run id");
        return 0;
    }
    if (mpb__grow((void **)&d->unrecorded, &d->cap_unrecorded,
                  d->num_unrecorded + 1, sizeof *d->unrecorded) != MPB_OK)
        return 0;
    if ((f = mpbd_flight_add(d)) == NULL)
        return 0;
    /* Written by the next transaction, before the result it may hold: a
     * request goes out as soon as a commit has made room for it. */
    mpbd_unrecorded *u = &d->unrecorded[d->num_unrecorded++];
    u->run_id = run.id;
    memcpy(u->run_uid, run.uid, sizeof u->run_uid);
    snprintf(u->planner_id, sizeof u->planner_id, "%s", d->planners[p].id);
    d->pending_head[c]++;
    d->total_pending--;
    if (fresh)
        run.attempts++;
    /* The clock now, not the loop's wake-up: the results handled since
     * then are not this run's time (its wall_time and latency). */
    now = mpb_monotonic_s();
    *f = (mpbd_flight){.run = run, .planner = p, .queued = queued,
                       .sent_at = now, .last_send = now, .sends = 1,
                       .next_send = now + MPBD_REQUEST_RESEND_S,
                       .deadline = queued ? INFINITY
                           : now + d->exp->time_limit + MPBD_DEADLINE_GRACE_S};
    if (queued)
        d->planners[p].queued++;
    else
        d->planners[p].active++;
    if (publish_request(d, f) != MPB_OK)
        mpbd_log("could not publish run %s (will resend)", run.uid);
    return 1;
}

static void log_waiting(mpbd *d, double now)
{
    if (now - d->last_wait_log < 5.0)
        return;
    for (int c = 0; c < d->exp->num_configs; c++) {
        const mpbd_config *cf = &d->exp->configs[c];
        const mpbd_planner *declining = NULL;
        int offered = 0;
        if (d->pending_head[c] >= d->pending_len[c])
            continue;
        for (int p = 0; p < d->num_planners && !offered; p++) {
            const mpbd_planner *pl = &d->planners[p];
            if (pl->gone || !mpbd_planner_offers(pl, cf->planner, cf->algorithm))
                continue;
            if (now < pl->declined_until && !pl->closing)
                declining = pl;
            else
                offered = 1;
        }
        if (!offered && declining != NULL) {
            mpbd_log("%s: waiting for a planner '%s' offering '%s' (%d runs): "
                     "%s declined its last %d request%s; next try in %.0f s",
                     cf->name, cf->planner, cf->algorithm,
                     d->pending_len[c] - d->pending_head[c], declining->id,
                     declining->declines, declining->declines == 1 ? "" : "s",
                     declining->declined_until - now);
            d->last_wait_log = now;
        } else if (!offered) {
            mpbd_log("%s: waiting for a planner '%s' offering '%s' "
                     "(%d runs)", cf->name, cf->planner, cf->algorithm,
                     d->pending_len[c] - d->pending_head[c]);
            d->last_wait_log = now;
        }
    }
}

/* A planner's runs in flight, and those it still plans that were given up
 * on, before a restart too: what it has room for is its capacity less
 * these. */
static int busy(const mpbd_planner *p)
{
    return p->active + p->num_abandoned + p->unknown;
}

/* Runs in flight on the planners of one host. */
static int host_active(const mpbd *d, const char *host)
{
    int n = 0;
    for (int p = 0; p < d->num_planners; p++)
        if (strcmp(d->planners[p].host, host) == 0)
            n += d->planners[p].active;
    return n;
}

int mpbd_requeue(mpbd *d, const mpbd_run *run)
{
    mpbd_run again = *run;
    again.uid[0] = '\0';
    return push_pending(d, run->config, &again);
}

/* What a planner has room for now: START a run, QUEUE one behind its
 * runs in flight (experiment queue_at_planner), or NONE. An idle planner
 * held back by its host's limit gets none: a request would start. */
enum room { ROOM_NONE, ROOM_START, ROOM_QUEUE };

static enum room room(const mpbd *d, const mpbd_planner *pl, double now)
{
    if (pl->gone || pl->closing || now < pl->declined_until)
        return ROOM_NONE;
    if (busy(pl) < pl->capacity)
        return host_active(d, pl->host) < d->exp->runs_per_host
                   ? ROOM_START : ROOM_NONE;
    return pl->queued < d->exp->queue_at_planner ? ROOM_QUEUE : ROOM_NONE;
}

/* The planner to take config c's next run: one that can start it, else
 * one that can queue it; the search starts after the planner that took
 * the last run, so that planners alike share the runs. -1: none. */
static int pick_planner(const mpbd *d, int c, double now, int *queued)
{
    const mpbd_config *cf = &d->exp->configs[c];
    int np = d->num_planners, queue_at = -1;
    for (int k = 0; k < np; k++) {
        int p = (d->next_planner + k) % np;
        const mpbd_planner *pl = &d->planners[p];
        enum room r = room(d, pl, now);
        if (r == ROOM_NONE ||
            !mpbd_planner_offers(pl, cf->planner, cf->algorithm))
            continue;
        if (r == ROOM_START) {
            *queued = 0;
            return p;
        }
        if (queue_at < 0)
            queue_at = p;
    }
    *queued = 1;
    return queue_at;
}

/* One run at a time, to the configurations in turn (and to the planners
 * in turn within one), whichever planner is free: each configuration
 * advances at the same pace, even when its planners share a host's slot,
 * so that an experiment stopped part-way is balanced. */
/* Too many results wait for the verifier: no request goes out (each
 * would bring one more) until they drain below the bounds. */
static int backlog_full(mpbd *d)
{
    int n = mpbd_verifier_pending(d);
    double bytes = mpbd_verifier_bytes(d);
    int full = (d->backlog_max > 0 && n >= d->backlog_max) ||
               (d->backlog_bytes_max > 0 && bytes >= d->backlog_bytes_max);
    double t = mpb_monotonic_s();
    if (full && !d->backlog_held && t - d->backlog_logged >= 10.0 &&
        (d->backlog_logged = t) > 0)
        mpbd_log("%d results (%.0f MB) await verification, at the bound "
                 "(--backlog %ld, --backlog-mb %.0f): no request goes out "
                 "until they drain", n, bytes / 1048576.0, d->backlog_max,
                 d->backlog_bytes_max / 1048576.0);
    if (!full && d->backlog_held && d->verbose)
        mpbd_log("the verification backlog drained to %d results: "
                 "requests go out again", n);
    d->backlog_held = full;
    return full;
}

int mpbd_scheduler_dispatch(mpbd *d, double now)
{
    int sent = 0, nc = d->exp->num_configs;
    if (d->total_pending > 0 && backlog_full(d))
        return 0;
    while (d->total_pending > 0) {
        int got = 0;
        for (int k = 0; k < nc && !got; k++) {
            int c = (d->next_config + k) % nc, p, queued;
            if (d->pending_head[c] >= d->pending_len[c] ||
                (p = pick_planner(d, c, now, &queued)) < 0)
                continue;
            if ((got = send_next(d, c, p, queued))) {
                d->next_config = (c + 1) % nc;
                d->next_planner = (p + 1) % d->num_planners;
            }
        }
        if (!got)
            break;
        sent++;
    }
    if (d->total_pending > 0)
        log_waiting(d, now);
    return sent;
}

int mpbd_scheduler_record_sent(mpbd *d)
{
    int rc = MPB_OK;
    for (int i = 0; i < d->num_unrecorded; i++) {
        const mpbd_unrecorded *u = &d->unrecorded[i];
        int r = mpb_store_run_sent(d->store, u->run_id, u->run_uid,
                                   u->planner_id);
        /* Done already: its result came in a transaction before (a resend
         * after a restart). Anything else is the database failing. */
        if (r != MPB_OK && r != MPB_EEXISTS) {
            mpbd_db_error(d);
            rc = r;
        }
    }
    d->num_unrecorded = 0;
    return rc;
}

mpbd_flight *mpbd_flight_add(mpbd *d)
{
    if (mpb__grow((void **)&d->flights, &d->cap_flights, d->num_flights + 1,
                  sizeof *d->flights) != MPB_OK)
        return NULL;
    return &d->flights[d->num_flights++];
}

mpbd_flight *mpbd_flight_find(mpbd *d, const char *uid)
{
    for (int i = 0; i < d->num_flights; i++)
        if (strcmp(d->flights[i].run.uid, uid) == 0)
            return &d->flights[i];
    return NULL;
}

double mpbd_clock(const mpbd *d)
{
    return d->replaying ? d->replay_now : mpb_monotonic_s();
}

/* A queued request starts: its planner has begun it, or is about to. */
static void start_queued(mpbd *d, mpbd_flight *f)
{
    mpbd_planner *p = &d->planners[f->planner];
    double now = mpbd_clock(d);
    f->queued = 0;
    p->queued--;
    p->active++;
    f->sent_at = f->last_send = now;
    f->sends = 1;
    f->next_send = now + MPBD_REQUEST_RESEND_S;
    f->away = 0;
    f->deadline = now + d->exp->time_limit + MPBD_DEADLINE_GRACE_S;
}

/* A planner with room takes its next request, the oldest waiting, now. */
static void start_next_queued(mpbd *d, int planner)
{
    const mpbd_planner *p = &d->planners[planner];
    if (p->queued == 0 || p->gone || p->closing || busy(p) >= p->capacity)
        return;
    mpbd_flight *next = NULL;
    for (int i = 0; i < d->num_flights; i++) {
        mpbd_flight *g = &d->flights[i];
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
    *f = d->flights[--d->num_flights];
    if (!was_queued)
        start_next_queued(d, planner);
}

int mpbd_take_back(mpbd *d, mpbd_flight *f, const char *why)
{
    int rc = mpb_store_run_unsent(d->store, f->run.id, f->run.uid);
    if (rc == MPB_OK) {
        mpbd_run run = f->run;
        run.attempts--;
        if (d->on_take_back != NULL)
            d->on_take_back(d->take_back_ud, &f->run);
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

static int names_run(char *const *runs, int n, const char *uid)
{
    for (int k = 0; k < n; k++)
        if (strcmp(runs[k], uid) == 0)
            return 1;
    return 0;
}

void mpbd_planner_closing(mpbd *d, int planner, char *const *active_runs,
                          int num_active)
{
    for (int i = 0; i < d->num_flights;) {
        mpbd_flight *f = &d->flights[i];
        if (f->planner == planner && f->queued &&
            !names_run(active_runs, num_active, f->run.uid))
            mpbd_take_back(d, f, "its planner is closing"); /* f: the next */
        else
            i++;
    }
}

static int is_abandoned(const mpbd_planner *p, const char *uid)
{
    for (int i = 0; i < p->num_abandoned; i++)
        if (strcmp(p->abandoned[i].uid, uid) == 0)
            return 1;
    return 0;
}

/* A run sent before a restart, to be sent again with its id: such runs
 * lead their configuration's queue (mpbd_scheduler_load). */
static int pending_resend(const mpbd *d, const char *uid)
{
    for (int c = 0; c < d->exp->num_configs; c++)
        for (int i = d->pending_head[c];
             i < d->pending_len[c] && d->pending[c][i].uid[0] != '\0'; i++)
            if (strcmp(d->pending[c][i].uid, uid) == 0)
                return 1;
    return 0;
}

void mpbd_planner_working_on(mpbd *d, int planner, char *const *active_runs,
                             int num_active)
{
    mpbd_planner *p = &d->planners[planner];
    int dropped = 0, unknown = 0;
    for (int k = 0; k < num_active; k++) {
        mpbd_flight *f;
        if (!mpb_run_id_is_valid(active_runs[k]))
            continue;
        if ((f = mpbd_flight_find(d, active_runs[k])) != NULL) {
            if (f->planner != planner)
                continue;
            f->acked = 1;           /* it has the request: no more resends */
            p->declines = 0;
            if (f->queued)
                start_queued(d, f);
        } else if (!is_abandoned(p, active_runs[k]) &&
                   !mpbd_verifier_has(d, active_runs[k]) &&
                   !mpbd_recently_done(d, active_runs[k]) &&
                   !pending_resend(d, active_runs[k])) {
            unknown++;     /* not in flight, given up on, being verified,
                              just stored, or to be sent again after a
                              restart */
        }
    }
    /* Runs it plans that this daemon did not send it: given up on by this
     * daemon before a restart. Each holds a slot, as below. */
    if (unknown > 0 && p->unknown == 0)
        mpbd_log("planner %s is planning %d run%s this daemon did not send "
                 "it (given up on before a restart?): it gets no run in "
                 "%s place until it stops", p->id, unknown,
                 unknown == 1 ? "" : "s", unknown == 1 ? "its" : "their");
    else if (unknown == 0 && p->unknown > 0)
        mpbd_log("planner %s has stopped planning the run%s this daemon did "
                 "not send it: it takes runs again", p->id,
                 p->unknown == 1 ? "" : "s");
    if (unknown < p->unknown)
        dropped = 1;
    p->unknown = unknown;
    /* A run given up on holds its slot while the planner names it. */
    for (int i = 0; i < p->num_abandoned;) {
        mpbd_abandoned *a = &p->abandoned[i];
        if (names_run(active_runs, num_active, a->uid)) {
            if (!a->named)
                mpbd_log("planner %s still plans run %lld, given up on at its "
                         "deadline: it gets no run in its place until it "
                         "stops", p->id, (long long)a->run_id);
            a->named = 1;
            i++;
            continue;
        }
        if (a->named)
            mpbd_log("planner %s has stopped planning run %lld, %.1f s after "
                     "its deadline: it takes runs again", p->id,
                     (long long)a->run_id, mpb_monotonic_s() - a->since);
        *a = p->abandoned[--p->num_abandoned];
        dropped = 1;
    }
    if (dropped)
        start_next_queued(d, planner);
}

static void resend(mpbd *d, mpbd_flight *f, double now);

/* A run given up on at its deadline, which its planner may still plan. */
static void abandon(mpbd *d, const mpbd_flight *f)
{
    mpbd_planner *p = &d->planners[f->planner];
    if (mpb__grow((void **)&p->abandoned, &p->cap_abandoned,
                  p->num_abandoned + 1, sizeof *p->abandoned) != MPB_OK)
        return;                 /* then its slot is free at once, as before */
    mpbd_abandoned *a = &p->abandoned[p->num_abandoned++];
    memcpy(a->uid, f->run.uid, sizeof a->uid);
    a->run_id = f->run.id;
    a->since = mpb_monotonic_s();
    a->named = 0;
}

void mpbd_scheduler_tick(mpbd *d, double now)
{
    mpbd_planners_expire(d, now);
    for (int i = 0; i < d->num_flights;) {
        mpbd_flight *f = &d->flights[i];
        const mpbd_planner *p = &d->planners[f->planner];
        if (p->gone) {
            if (f->queued)
                mpbd_take_back(d, f, "its planner went silent before "
                                     "starting it");
            else
                mpbd_record_crash(d, f, "planner went silent during the run");
            continue; /* f now holds another flight */
        }
        if (f->queued) {
            i++;
            continue;
        }
        /* A planner that holds other requests may be planning one of them
         * before it re-sends a lost result of this run. */
        double deadline = f->deadline;
        if (p->queued > 0 || busy(p) > p->capacity)
            deadline += d->exp->time_limit;
        if (now > deadline && !mpbd_hub_unproven(d, now)) {
            char why[sizeof MPB_CHANNEL_REQUEST_PREFIX + MPB_PLANNER_ID_MAX + 128];
            if (f->acked)
                snprintf(why, sizeof why,
                         "no result within the time limit and grace");
            else
                snprintf(why, sizeof why, "request never acknowledged (%d "
                         "sends): is the planner subscribed to %s%s?",
                         f->sends, MPB_CHANNEL_REQUEST_PREFIX, p->id);
            abandon(d, f);
            mpbd_record_crash(d, f, why);
            continue;
        }
        /* Not while the hub is away: such a send is lost, and the first
         * after it comes back goes at once (mpbd_scheduler_relink). */
        if (!f->acked && d->hub_state != MPBD_HUB_AWAY &&
            d->hub_state != MPBD_HUB_STALLED && now >= f->next_send)
            resend(d, f, now);
        i++;
    }
}

/* Re-send a request not acknowledged: the planner may start on this copy,
 * so its time starts again here; the next waits twice as long. */
static void resend(mpbd *d, mpbd_flight *f, double now)
{
    double wait = MPBD_REQUEST_RESEND_S * (double)(1 << (f->sends < 5 ? f->sends : 5));
    f->last_send = now;
    f->away = 0;
    f->sends++;
    f->next_send = now + fmin(wait, MPBD_REQUEST_RESEND_MAX_S);
    publish_request(d, f);
}

static void hold_clocks(mpbd *d, double secs)
{
    for (int i = 0; i < d->num_planners; i++)
        d->planners[i].last_seen += secs;
    for (int i = 0; i < d->num_flights; i++)
        d->flights[i].deadline += secs;   /* INFINITY stays so */
}

void mpbd_scheduler_pause(mpbd *d, double secs)
{
    hold_clocks(d, secs);
    for (int i = 0; i < d->num_flights; i++)
        if (!d->flights[i].queued)
            d->flights[i].away += secs;
}

void mpbd_scheduler_relink(mpbd *d, double now)
{
    for (int i = 0; i < d->num_planners; i++)
        if (!d->planners[i].gone)
            d->planners[i].relinked = now;
    for (int i = 0; i < d->num_flights; i++)
        if (!d->flights[i].acked && !d->flights[i].queued)
            d->flights[i].next_send = now;
}

void mpbd_planner_heard(mpbd *d, int planner, double now)
{
    mpbd_planner *p = &d->planners[planner];
    if (p->relinked <= 0)
        return;
    for (int i = 0; i < d->num_flights; i++) {
        mpbd_flight *f = &d->flights[i];
        if (f->planner != planner || f->queued)
            continue;
        double since = fmax(p->relinked, f->last_send);
        if (now > since) {
            f->away += now - since;
            f->deadline += now - since;
        }
        /* What it finished while away it answers from its kept results;
         * what it still plans it acknowledges again. An acknowledged
         * request's time does not start again. */
        if (f->acked)
            publish_request(d, f);
        else
            resend(d, f, now);
    }
    p->relinked = 0;
}

void mpbd_scheduler_stalled(mpbd *d, double secs)
{
    /* The hub away or stalled (its publishing blocks the loop): network
     * time, logged once by hub.c. */
    if (d->hub_state == MPBD_HUB_AWAY || d->hub_state == MPBD_HUB_STALLED) {
        mpbd_scheduler_pause(d, secs);
        return;
    }
    /* Not network time: what planners sent meanwhile carries the
     * kernel's receive time, so runs are timed as they ran. */
    hold_clocks(d, secs);
    mpbd_log("read no message for %.1f s (stopped, its machine "
             "suspended, or busy): planners' silence and runs' deadlines "
             "are counted without that time", secs);
}

int mpbd_scheduler_done(const mpbd *d)
{
    return d->total_pending == 0 && d->num_flights == 0;
}

void mpbd_scheduler_free(mpbd *d)
{
    for (int c = 0; d->pending && c < d->exp->num_configs; c++)
        free(d->pending[c]);
    free(d->pending);
    free(d->pending_len);
    free(d->pending_head);
    free(d->flights);
    free(d->unrecorded);
    free(d->acks);
    free(d->owed);
}

/* A planner declined a request: it goes to another. A planner declines
 * only when closing, and then announces capacity 0; one that has not (or
 * not yet) gets no request for a while, 1 s doubling to 60 s, so that one
 * that declines everything does not have the daemon send it a request and
 * take it back, with two log lines, every heartbeat for ever. */
static void declined(mpbd *d, mpbd_flight *f)
{
    mpbd_planner *p = &d->planners[f->planner];
    long long run = (long long)f->run.id;
    if (!p->closing) {
        double pause = p->declines < 6 ? (double)(1 << p->declines) : 60.0;
        p->declines++;
        p->declined_until = mpb_monotonic_s() + pause;
        if (p->declines == 1)
            mpbd_log("planner %s declined run %lld: no request goes to it "
                     "for %.0f s", p->id, run, pause);
        else
            mpbd_log("planner %s declined run %lld, %d in a row, while it "
                     "announces capacity %d (a planner declines only when "
                     "closing, at capacity 0): no request goes to it for "
                     "%.0f s", p->id, run, p->declines, p->capacity, pause);
    }
    mpbd_take_back(d, f, "its planner declined it");
}

/* A planner acknowledged a request: stop re-sending it. Or it declined
 * it: it goes to another. */
static void on_ack(mpbd *d, const mpb_run_ack_t *m)
{
    mpbd_flight *f;
    if (!mpb_run_id_is_valid(m->run_id) ||
        (f = mpbd_flight_find(d, m->run_id)) == NULL ||
        strcmp(d->planners[f->planner].id, m->sender_id) != 0)
        return;
    mpbd_planner_heard(d, f->planner, mpb_monotonic_s());
    if (m->kind == MPB_RUN_ACK_T_REQUEST_RECEIVED) {
        f->acked = 1;
        d->planners[f->planner].declines = 0;
    } else if (m->kind == MPB_RUN_ACK_T_REQUEST_DECLINED) {
        declined(d, f);
    }
}

static void on_ack_raw(const lcm_recv_buf_t *rbuf, const char *channel,
                       void *user)
{
    mpb_run_ack_t m;
    if (!mpbd_receive(user, MPB_WIRE_RUN_ACK, rbuf, channel, &m))
        return;
    on_ack(user, &m);
    mpb_receive_done(MPB_WIRE_RUN_ACK, &m);
}

void mpbd_scheduler_subscribe(mpbd *d)
{
    d->sub_ack = lcm_subscribe(d->lcm, MPB_CHANNEL_ACK, on_ack_raw, d);
}
