/*
 * record.c - a measured result recorded: the planner's times checked, its
 * names made unique, the run counted by the success rule of outcome.h
 * (mpb_run_success(), which `mpb verify` applies too), its notes and the
 * planner's words in runs.message, and one row per run, stage, metric and
 * value in the open transaction; acknowledged once that commits (acks.c).
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon.h"
#include "mpbench/planner.h"

void mpbd_result_reject(mpbd *d, const char *why, const mpb_plan_result_t *m)
{
    d->count.rejected++;
    /* A flood of strays must not become a flood of log lines. */
    if (d->count.rejected <= 10 || d->count.rejected % 1000 == 0) {
        char run[4 * 32 + 4], planner[4 * MPB_PLANNER_ID_MAX + 4];
        mpbd_log("rejected result %s from %s: %s (%ld rejected so far)",
                 mpb_escape(m->attempt_id, run, sizeof run),
                 mpb_escape(m->planner_id, planner, sizeof planner), why,
                 d->count.rejected);
    }
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
static int check_times(const mpb_plan_result_t *m, mpbd_stage_work *works,
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

/* Store the run measured as ms; returns what mpb_store_run_finish()
 * returns. recv is when the result arrived (mpb_monotonic_s() clock). */
static int store_result(mpbd *d, const mpbd_flight *f,
                        const mpb_plan_result_t *m, double recv,
                        const mpbd_measured *ms)
{
    const double limit = d->exp->time_limit;
    int np = count_progress(m);
    mpbd_stage_work *works = ms->works;
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
        .attempt_id = f->run.attempt_id,
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
    /* Judged on what the planner was given too, by the same rule. */
    if (ms->judged_seen) {
        const mpb_verdict *v = &ms->seen.verdict;
        rec.seen_verdict = mpb_verdict_name(v->code);
        rec.seen_detail = v->detail;
        rec.seen_success = mpb_run_success(claimed,
                                           v->code == MPB_VERDICT_VALID,
                                           in_time);
    }
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

int mpbd_result_store(mpbd *d, const mpbd_flight *f,
                      const mpb_plan_result_t *m, double recv,
                      const mpbd_measured *ms)
{
    int rc = store_result(d, f, m, recv, ms);
    if (rc == MPB_OK || rc == MPB_EEXISTS) {
        d->planners[f->planner].runs_done++;
        mpbd_runs_remember(d, f->run.attempt_id);
        mpbd_ack_after_commit(d, m->planner_id, f->run.attempt_id,
                              rc == MPB_OK ? f->sent_at : -1.0);
        return MPB_OK;
    }
    if (rc == MPB_ENOTFOUND) {
        mpbd_result_reject(d, "not the run's current attempt", m);
        return MPB_OK;
    }
    /* The store failed: the caller keeps the result to store again (the
     * flight, which the planner's re-sent result finds). */
    mpbd_db_error(d);
    return MPBD_RETRY;
}

