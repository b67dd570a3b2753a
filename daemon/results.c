/*
 * results.c - a planner's answer, checked and measured: is it for a run we
 * sent, to that planner? Does each stage solve the query (mpbench's own
 * verdict, the planner's claim kept beside it)? Then its metrics, and one
 * row per run, stage, metric and value in the store.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "daemon.h"
#include "mpbench/planner.h"
#include "mpb_plan_result_t.h"
#include "mpb_run_ack_t.h"

/* Per stage, what the store needs, owned here for the length of a result. */
typedef struct mpbd_stage_work {
    mpb_stage_record  rec;
    mpb_named         metrics[MPB_NUM_METRICS];
    mpb_stage_measure m;
} stage_work;

static void remember(mpbd *d, const char *uid)
{
    memcpy(d->recent[d->recent_next], uid, MPB_RUN_ID_SIZE);
    d->recent_next = (d->recent_next + 1) % (int)(sizeof d->recent / sizeof d->recent[0]);
}

int mpbd_recently_done(const mpbd *d, const char *uid)
{
    for (size_t i = 0; i < sizeof d->recent / sizeof d->recent[0]; i++)
        if (strcmp(d->recent[i], uid) == 0)
            return 1;
    return 0;
}

static void reject(mpbd *d, const char *why, const mpb_plan_result_t *m)
{
    d->count.rejected++;
    /* A flood of strays must not become a flood of log lines. */
    if (d->count.rejected <= 10 || d->count.rejected % 1000 == 0) {
        char run[4 * 32 + 4], planner[4 * MPB_PLANNER_ID_MAX + 4];
        mpbd_log("rejected result %s from %s: %s (%ld rejected so far)",
                 mpb_escape(m->run_id, run, sizeof run),
                 mpb_escape(m->planner_id, planner, sizeof planner), why,
                 d->count.rejected);
    }
}

/* Check and measure one stage (mpb_measure_stage()). */
static void measure_stage(const mpbd *d, const mpbd_query *q,
                          const mpb_stage_t *st, stage_work *w)
{
    const mpbd_experiment *e = d->exp;
    mpb_world *world = e->scenes[q->scene].world;
    mpb_goal goal = mpbd_query_goal(q);
    char why[200];

    w->rec.name = st->name;
    w->rec.time = st->time;
    if (!mpb_stage_sizes_ok(st, e->num_joints, w->m.verdict.detail,
                            sizeof w->m.verdict.detail)) {
        w->m.verdict.code = MPB_VERDICT_WRONG_SIZE;
        w->m.verdict.segment = -1;
        /* Stored as sent when its sizes agree with its values (another
         * number of joints): the blob is the message's own array. */
        if (st->num_waypoints > 0 && st->num_joints > 0 &&
            (int64_t)st->num_waypoints * st->num_joints == st->num_values) {
            w->rec.num_waypoints = st->num_waypoints;
            w->rec.num_joints = st->num_joints;
            w->rec.waypoints = st->waypoints;
        }
        mpb_measure_metrics(world, w->rec.waypoints, w->rec.num_waypoints,
                            w->rec.num_joints, st->time, d->resolution,
                            &w->m);
    } else if (st->num_times != 0 &&
               !mpb_times_ok(st->times, st->num_times, st->num_waypoints,
                             why, sizeof why)) {
        /* Times that are no timing of the waypoints: refused, the path's
         * own metrics measured (of a path whose values are all finite),
         * the times kept when there is one per waypoint. */
        int finite = 1;
        for (int32_t k = 0; k < st->num_values && finite; k++)
            finite = isfinite(st->waypoints[k]);
        w->m.verdict.code = MPB_VERDICT_BAD_TIMES;
        w->m.verdict.segment = -1;
        snprintf(w->m.verdict.detail, sizeof w->m.verdict.detail,
                 "stage '%.40s' waypoint times: %s", st->name, why);
        w->rec.num_waypoints = st->num_waypoints;
        w->rec.num_joints = st->num_joints;
        w->rec.waypoints = st->waypoints;
        if (st->num_times == st->num_waypoints)
            w->rec.times = st->times;
        mpb_measure_metrics(world, finite ? st->waypoints : NULL,
                            st->num_waypoints, st->num_joints, st->time,
                            d->resolution, &w->m);
    } else {
        w->rec.num_waypoints = st->num_waypoints;
        w->rec.num_joints = st->num_joints;
        w->rec.waypoints = st->waypoints;
        w->rec.times = st->num_times > 0 ? st->times : NULL;
        mpb_measure_stage_timed(world, q->start, q->tolerance, &goal,
                                st->waypoints, w->rec.times,
                                st->num_waypoints, st->num_joints, st->time,
                                d->resolution, 0, &w->m);
    }
    /* Proved over the whole segment, or sampled where the proof could
     * not close (docs/verification.md); a verdict of no path, none. */
    w->rec.verification = mpb_verdict_verification(&w->m.verdict);
    w->rec.valid = w->m.verdict.code == MPB_VERDICT_VALID;
    w->rec.verdict = mpb_verdict_name(w->m.verdict.code);
    w->rec.verdict_detail = w->m.verdict.detail;
    w->rec.verdict_segment = w->m.verdict.segment;
    w->rec.has_depth = w->m.verdict.code == MPB_VERDICT_COLLISION &&
                       isfinite(w->m.verdict.depth_upper);
    w->rec.depth_lower_mm = w->m.verdict.code == MPB_VERDICT_COLLISION
                                ? 1e3 * w->m.verdict.depth_lower : NAN;
    w->rec.depth_upper_mm = w->m.verdict.code == MPB_VERDICT_COLLISION
                                ? 1e3 * w->m.verdict.depth_upper : NAN;
    for (int i = 0; i < w->m.num_metrics; i++)
        w->metrics[i] = (mpb_named){w->m.metrics[i].name,
                                    w->m.metrics[i].value};
    w->rec.metrics = w->metrics;
    w->rec.num_metrics = w->m.num_metrics;
}

static int count_progress(const mpb_plan_result_t *m)
{
    int n = 0;
    for (int i = 0; i < m->num_progress; i++)
        n += m->progress[i].num_values;
    return n;
}

/* What the daemon refused or changed in a result, one note after another
 * ("; " between), for runs.message: bounded, however much is wrong. */
typedef struct notes {
    char text[1024];
    size_t len;
} notes;

static void note(notes *n, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

static void note(notes *n, const char *fmt, ...)
{
    va_list ap;
    size_t room = sizeof n->text - n->len;
    if (room <= 1)
        return;
    if (n->len > 0) {
        int k = snprintf(n->text + n->len, room, "; ");
        n->len += (size_t)k < room ? (size_t)k : room - 1;
        room = sizeof n->text - n->len;
    }
    va_start(ap, fmt);
    int k = vsnprintf(n->text + n->len, room, fmt, ap);
    va_end(ap);
    if (k > 0)
        n->len += (size_t)k < room ? (size_t)k : room - 1;
}

/* A time as the planner sent it is a time: finite and not negative. */
static int is_time(double t)
{
    return isfinite(t) && t >= 0;
}

typedef struct named_at {
    const char *name;
    int         idx;
} named_at;

static int by_name_then_index(const void *a, const void *b)
{
    const named_at *x = a, *y = b;
    int c = strcmp(x->name, y->name);
    return c != 0 ? c : (x->idx > y->idx) - (x->idx < y->idx);
}

static int by_name(const void *key, const void *elem)
{
    return strcmp(key, ((const named_at *)elem)->name);
}

/*
 * Make names[0..n) unique, keeping every entry: the first use of a name
 * keeps it, the k-th (k >= 2, in the planner's order) becomes "name#k",
 * k raised past any name the planner sent itself. Two such new names never
 * meet (the number after the last '#' tells them apart). New names are
 * malloc'd into owned[i] (NULL where unchanged; the caller frees them) and
 * replace names[i]; what was renamed is noted, "what" naming the kind.
 * Returns how many were renamed, or MPB_ENOMEM.
 */
static int unique_names(const char **names, char **owned, int n,
                        const char *what, notes *nt)
{
    named_at *sorted;
    int renamed = 0;
    if (n < 2)
        return 0;
    if ((sorted = malloc((size_t)n * sizeof *sorted)) == NULL)
        return MPB_ENOMEM;
    for (int i = 0; i < n; i++)
        sorted[i] = (named_at){names[i], i};
    qsort(sorted, (size_t)n, sizeof *sorted, by_name_then_index);
    for (int g = 0, e; g < n; g = e) {
        int k = 1;
        for (e = g + 1; e < n && strcmp(sorted[e].name, sorted[g].name) == 0; e++) {
            size_t len = strlen(sorted[g].name) + 16;
            char *name = malloc(len);
            if (name == NULL) {
                free(sorted);
                return MPB_ENOMEM;
            }
            do
                snprintf(name, len, "%s#%d", sorted[g].name, ++k);
            while (bsearch(name, sorted, (size_t)n, sizeof *sorted, by_name));
            int i = sorted[e].idx;
            owned[i] = name;
            if (++renamed <= 3)
                note(nt, "%s %d '%.64s' stored as '%.64s#%d' (a name used "
                     "before)", what, i, sorted[g].name, sorted[g].name, k);
        }
    }
    free(sorted);
    if (renamed > 3)
        note(nt, "%d more %ss renamed so", renamed - 3, what);
    for (int i = 0; i < n; i++)
        if (owned[i] != NULL)
            names[i] = owned[i];
    return renamed;
}

/* The planner's times, checked: one that is no time, or a time_other above
 * time_total, is noted and stored as NULL (NaN), so that no mean, plot or
 * export ever takes it in; the numbers sent stay in the note. Returns 1 if
 * all were sound. */
static int check_times(const mpb_plan_result_t *m, stage_work *works,
                       double *total, double *other, notes *nt)
{
    int ok = 1, bad_stages = 0;
    *total = m->time_total;
    *other = m->time_other;
    if (!is_time(*total)) {
        note(nt, "time_total %g s is %s", *total,
             isfinite(*total) ? "negative" : "not finite");
        *total = NAN;
        ok = 0;
    }
    if (!is_time(*other)) {
        note(nt, "time_other %g s is %s", *other,
             isfinite(*other) ? "negative" : "not finite");
        *other = NAN;
        ok = 0;
    } else if (isfinite(m->time_total) && *other > m->time_total) {
        note(nt, "time_other %g s exceeds time_total %g s", *other,
             m->time_total);
        *other = NAN;
        ok = 0;
    }
    for (int i = 0; i < m->num_stages; i++) {
        if (is_time(m->stages[i].time))
            continue;
        if (++bad_stages <= 3)
            note(nt, "stage %d time %g s is %s", i, m->stages[i].time,
                 isfinite(m->stages[i].time) ? "negative" : "not finite");
        works[i].rec.time = NAN;
        for (int k = 0; k < works[i].rec.num_metrics; k++)
            if (strcmp(works[i].metrics[k].name,
                       mpb_metric_info_of(MPB_METRIC_TIME)->name) == 0)
                works[i].metrics[k].value = NAN;
        ok = 0;
    }
    if (bad_stages > 3)
        note(nt, "%d more stage times not times", bad_stages - 3);
    return ok;
}

/* The latest the planner can have started the run, by the clock of
 * f->sent_at: the request's last send (a planner starts on the first copy
 * it receives; re-sends stop once it acknowledges one), or for a request
 * queued at the planner, its start. Replaying, replay.c has placed sent_at
 * at the logged last send already. */
static double latest_start(const mpbd *d, const mpbd_flight *f)
{
    return d->replaying ? f->sent_at : f->last_send;
}

/* For tests and bench/backlog.sh only: MPBD_TEST_SLOW_VERIFY=F (1 to
 * 1000) makes every verification take F times as long, by sleeping the
 * difference, as a slower verifier or a heavier scene would. */
static void test_slow_down(mpbd_measured *out)
{
    const char *e = getenv("MPBD_TEST_SLOW_VERIFY");
    double f = e != NULL ? strtod(e, NULL) : 0;
    if (!(f > 1 && f <= 1000))
        return;
    double extra = (f - 1) * (out->verified - out->verify_start);
    struct timespec ts = {(time_t)extra,
                          (long)((extra - (double)(time_t)extra) * 1e9)};
    nanosleep(&ts, NULL);
    out->verified = mpb_monotonic_s();
}

int mpbd_result_measure(const mpbd *d, const mpbd_flight *f,
                        const mpb_plan_result_t *m, mpbd_measured *out)
{
    const mpbd_query *q = &d->exp->queries[f->run.query];
    out->works = calloc((size_t)m->num_stages + 1, sizeof *out->works);
    if (out->works == NULL)
        return MPB_ENOMEM;
    /* runs.verify_time: the daemon's verification and metrics of every
     * stage, a cost of the scene (its meshes), not of the planner. */
    out->verify_start = mpb_monotonic_s();
    /* The scene's world holds the joints outside the group as this
     * query does (its start state may set a Panda's fingers). */
    mpbd_query_hold(d->exp, q);
    for (int i = 0; i < m->num_stages; i++)
        measure_stage(d, q, &m->stages[i], &out->works[i]);
    out->verified = mpb_monotonic_s();
    test_slow_down(out);
    return MPB_OK;
}

void mpbd_measured_free(mpbd_measured *ms)
{
    free(ms->works);
    ms->works = NULL;
}

/* Store the run measured as ms; returns what mpb_store_run_finish()
 * returns. recv is when the result arrived (mpb_monotonic_s() clock). */
static int store_result(mpbd *d, const mpbd_flight *f,
                        const mpb_plan_result_t *m, double recv,
                        const mpbd_measured *ms)
{
    const double limit = d->exp->time_limit;
    int np = count_progress(m);
    stage_work *works = ms->works;
    mpb_stage_record *stages = calloc((size_t)m->num_stages + 1, sizeof *stages);
    mpb_named *values = calloc((size_t)m->num_values + 1, sizeof *values);
    mpb_progress_record *prog = calloc((size_t)np + 1, sizeof *prog);
    const char **names = calloc((size_t)m->num_stages + (size_t)m->num_values + 1,
                                sizeof *names);
    char **owned = calloc((size_t)m->num_stages + (size_t)m->num_values + 1,
                          sizeof *owned);
    char *message = NULL;
    notes nt = {.len = 0};
    int rc = MPB_ENOMEM;

    if (!stages || !values || !prog || !names || !owned)
        goto done;
    /* A status the protocol does not give planners: the daemon alone says
     * crash, and a number outside the list means nothing. */
    int status = m->status;
    if (!mpb_status_is_planners(status)) {
        note(&nt, "status %d (%s) is not a planner's to send: recorded as "
             "failed", (int)m->status,
             status == MPB_PLAN_RESULT_T_CRASH ? "crash, set by the daemon alone"
                                               : "no such status");
        status = MPB_PLAN_RESULT_T_FAILED;
    }
    double verify_start = ms->verify_start, verified = ms->verified;
    for (int i = 0; i < m->num_stages; i++)
        names[i] = m->stages[i].name;
    for (int i = 0; i < m->num_values; i++)
        names[m->num_stages + i] = m->values[i].name;
    /* Metrics are keyed by stage name, values by name: a repeated name
     * would overwrite the rows before it. */
    if (unique_names(names, owned, m->num_stages, "stage", &nt) < 0 ||
        unique_names(names + m->num_stages, owned + m->num_stages,
                     m->num_values, "value", &nt) < 0)
        goto done;
    double total, other;
    int times_ok = check_times(m, works, &total, &other, &nt);
    for (int i = 0; i < m->num_stages; i++) {
        works[i].rec.name = names[i];
        stages[i] = works[i].rec;
    }
    for (int i = 0; i < m->num_values; i++)
        values[i] = (mpb_named){names[m->num_stages + i], m->values[i].value};
    np = 0;
    for (int i = 0; i < m->num_progress; i++)
        for (int k = 0; k < m->progress[i].num_values; k++)
            prog[np++] = (mpb_progress_record){m->progress[i].time,
                                               m->progress[i].values[k].name,
                                               m->progress[i].values[k].value};

    /* Success: the rule of outcome.h, mpb_run_success(): claimed, the
     * final stage valid (every stage was verified above, whatever the
     * status), and in time by the planner's clock and, with
     * MPBD_WALL_SLACK_S for the network, by the daemon's
     * (docs/metrics.md). Each reason it is not is noted. */
    int claimed = status == MPB_PLAN_RESULT_T_SOLVED;
    int final_valid = m->num_stages > 0 && stages[m->num_stages - 1].valid;
    /* Less the time the link was away meanwhile: a hub outage delays a
     * result by as long, through no fault of the planner's. */
    double took = recv - latest_start(d, f) - f->away;
    /* Building the world is outside the run's time (docs/protocol.md,
     * world_setup_time), as OMPL's Benchmark keeps its setup apart: a
     * planner that reports it has it left out of the daemon's clock too,
     * up to MPBD_SETUP_ALLOWANCE_S, so that a library that takes seconds
     * to load a scene is not late for it. */
    double setup = 0;
    for (int i = 0; i < m->num_values; i++)
        if (strcmp(m->values[i].name, MPB_WORLD_SETUP_TIME) == 0 &&
            m->values[i].value > 0 && isfinite(m->values[i].value))
            setup = fmin(m->values[i].value, MPBD_SETUP_ALLOWANCE_S);
    took -= setup;
    int in_time = mpb_run_in_time(times_ok, total, took, limit,
                                  MPBD_WALL_SLACK_S);
    int success = mpb_run_success(claimed, final_valid, in_time);
    if (claimed) {
        const mpb_stage_record *last =
            m->num_stages > 0 ? &stages[m->num_stages - 1] : NULL;
        if (last == NULL)
            note(&nt, "solved, but no stages");
        else if (!final_valid)
            note(&nt, "final stage %d '%.64s' is %s: %s", m->num_stages - 1,
                 last->name, last->verdict, last->verdict_detail);
        if (isfinite(total) && total > limit)
            note(&nt, "time_total %g s exceeds the time limit %g s", total,
                 limit);
        if (took > limit + MPBD_WALL_SLACK_S)
            note(&nt, "%.3f s by the daemon's clock, request to result less "
                 "%.3f s of world setup, over the time limit %g s plus %g s "
                 "slack", took, setup, limit, MPBD_WALL_SLACK_S);
    } else if (nt.len == 0 && m->message[0] == '\0') {
        note(&nt, "the planner reported %s with no message",
             mpb_status_name(status));
    }
    /* runs.message: the daemon's notes, then the planner's own words. */
    if (nt.len > 0) {
        size_t len = nt.len + strlen(m->message) + 32;
        if ((message = malloc(len)) == NULL)
            goto done;
        snprintf(message, len, "%s%s%s", nt.text,
                 m->message[0] ? "; planner's message: " : "", m->message);
    }
    mpb_run_record rec = {
        .run_id = f->run.id,
        .run_uid = f->run.uid,
        .planner_id = m->planner_id,
        .status = mpb_status_name(status),
        .message = message ? message : m->message,
        .claimed_success = claimed,
        .success = success,
        .late = !in_time,
        .time_total = total,
        .time_raw = total - other,
        .time_other = other,
        /* To the result verified and measured, as docs/schema.md says:
         * taken on arrival, it left the verification out. */
        .wall_time = verified - f->sent_at,
        .verify_time = verified - verify_start,
        /* The planner's peak (MB); not measured: NULL. */
        .memory = m->memory > 0 && isfinite(m->memory) ? m->memory : NAN,
        .num_stages = m->num_stages,
        .stages = stages,
        .num_values = m->num_values,
        .values = values,
        .num_progress = np,
        .progress = prog,
    };
    rc = mpb_store_run_finish(d->store, &rec);
    if (rc == MPB_OK) {
        mpbd_doomed_result(d, f->run.config, rec.status, rec.message);
        d->count.done++;
        if (rec.success)
            d->count.succeeded++;
        else
            d->count.failed++;
        if (d->verbose) {
            char why[404];
            mpbd_log("run %lld %s: %s, verdict %s: %s%s",
                     (long long)f->run.id, d->exp->configs[f->run.config].name,
                     rec.status, m->num_stages > 0
                         ? stages[m->num_stages - 1].verdict : "none",
                     rec.success ? "success" : "not a success: ",
                     rec.success ? "" : mpb_escape(rec.message, why, sizeof why));
        }
    }
done:
    for (int i = 0; owned && i < m->num_stages + m->num_values; i++)
        free(owned[i]);
    free(owned);
    free(names);
    free(message);
    free(stages);
    free(values);
    free(prog);
    return rc;
}

/* recv: when the result arrived, by the monotonic clock. */
static void on_result(mpbd *d, const mpb_plan_result_t *m, double recv)
{
    mpbd_flight *f;

    if (!mpb_run_id_is_valid(m->run_id)) {
        /* No run has such an id: answered so that a planner stops
         * re-sending it (if it names a valid planner to answer). */
        reject(d, "malformed run id", m);
        mpbd_ack(d, m->planner_id, m->run_id, MPB_RUN_ACK_T_RESULT_REJECTED);
        return;
    }
    if ((f = mpbd_flight_find(d, m->run_id)) == NULL) {
        /* Being verified: acknowledged once stored. */
        if (mpbd_verifier_has(d, m->run_id))
            return;
        if (mpbd_recently_done(d, m->run_id)) {
            /* Stored, perhaps in the transaction still open: acknowledged
             * again once that commits. */
            mpbd_ack_after_commit(d, m->planner_id, m->run_id, -1.0);
            return;
        }
        reject(d, "no such run in flight", m);
        mpbd_ack(d, m->planner_id, m->run_id, MPB_RUN_ACK_T_RESULT_REJECTED);
        return;
    }
    if (strcmp(d->planners[f->planner].id, m->planner_id) != 0) {
        /* Not acknowledged: the planner the run went to may still answer. */
        reject(d, "sent by a planner the run did not go to", m);
        return;
    }
    mpbd_planner_heard(d, f->planner, mpb_monotonic_s());
    /* Verified beside the loop (verifier.c): the run's flight ends now,
     * so that its planner's next request need not wait; unless it is
     * known to be quick. */
    if (!mpbd_verifier_quick(d, f, m) &&
        mpbd_verifier_submit(d, f, m, recv) == MPB_OK) {
        mpbd_flight_remove(d, f);
        return;
    }
    mpbd_measured ms = {0};
    int rc = MPBD_RETRY;        /* out of memory: the planner re-sends */
    if (mpbd_result_measure(d, f, m, &ms) == MPB_OK) {
        mpbd_verifier_learn(d, f, m, &ms);
        rc = mpbd_result_store(d, f, m, recv, &ms);
    }
    mpbd_measured_free(&ms);
    if (rc != MPBD_RETRY)
        mpbd_flight_remove(d, f);
}

int mpbd_result_store(mpbd *d, const mpbd_flight *f,
                      const mpb_plan_result_t *m, double recv,
                      const mpbd_measured *ms)
{
    int rc = store_result(d, f, m, recv, ms);
    if (rc == MPB_OK || rc == MPB_EEXISTS) {
        d->planners[f->planner].runs_done++;
        remember(d, f->run.uid);
        mpbd_ack_after_commit(d, m->planner_id, f->run.uid,
                              rc == MPB_OK ? f->sent_at : -1.0);
        return MPB_OK;
    }
    if (rc == MPB_ENOTFOUND) {
        reject(d, "not the run's current attempt", m);
        return MPB_OK;
    }
    /* The store failed: the caller keeps the result to store again (the
     * flight, which the planner's re-sent result finds). */
    mpbd_db_error(d);
    return MPBD_RETRY;
}

static void on_result_raw(const lcm_recv_buf_t *rbuf, const char *channel,
                          void *user)
{
    mpb_plan_result_t m;
    if (!mpbd_receive(user, MPB_WIRE_PLAN_RESULT, rbuf, channel, &m))
        return;
    /* When it arrived, from LCM's receive time (the kernel's, where it
     * keeps one): not when a busy daemon got round to it. */
    double now = mpb_monotonic_s();
    double waited = (double)(mpb_utime_now() - rbuf->recv_utime) * 1e-6;
    on_result(user, &m, waited > 0 && waited < 3600 ? now - waited : now);
    mpb_receive_done(MPB_WIRE_PLAN_RESULT, &m);
}

void mpbd_results_subscribe(mpbd *d)
{
    d->sub_result = lcm_subscribe(d->lcm, MPB_CHANNEL_RESULT, on_result_raw, d);
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
    if (f->run.attempts <= d->exp->retries) {
        int rc = mpb_store_run_retry(d->store, f->run.id, f->run.uid, why);
        if (rc == MPB_OK && mpbd_requeue(d, &f->run) == MPB_OK) {
            mpbd_log("run %lld %s on %s: %s; retrying (attempt %d of %d)",
                     (long long)f->run.id, d->exp->configs[f->run.config].name,
                     d->planners[f->planner].id, why, f->run.attempts + 1,
                     d->exp->retries + 1);
            d->count.retried++;
            mpbd_flight_remove(d, f);
            return rc;
        }
        if (rc != MPB_OK)
            mpbd_db_error(d);
    }
    mpb_run_record rec = {
        .run_id = f->run.id,
        .run_uid = f->run.uid,
        .planner_id = d->planners[f->planner].id,
        .status = "crash",
        .message = why,
        .time_total = NAN, .time_raw = NAN, .time_other = NAN,
        .wall_time = mpb_monotonic_s() - f->sent_at,
        .verify_time = NAN,
        .memory = NAN,
    };
    int rc = mpb_store_run_finish(d->store, &rec);
    if (rc == MPB_OK) {
        d->count.done++;
        d->count.crashed++;
        mpbd_log("run %lld %s on %s: crash: %s", (long long)f->run.id,
                 d->exp->configs[f->run.config].name,
                 d->planners[f->planner].id, why);
    } else if (rc != MPB_EEXISTS) {
        mpbd_db_error(d);
    }
    /* Not remembered: a late result of this attempt is a stray now. */
    mpbd_flight_remove(d, f);
    return rc;
}
