/*
 * store_runs.c - the life of a run in the database: pending, sent (with the
 * attempt's random id), done with its stages, metrics and values.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/outcome.h"
#include "store/store_columns.h"
#include "store/store_internal.h"

int mpb_store_runs_unfinished(mpb_store *s, int64_t experiment_id,
                              int (*cb)(void *ud, const mpb_run_row *row),
                              void *ud)
{
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT id, planner_config_id, query_id, repetition, seed, attempts,"
        " state, attempt_id FROM runs WHERE experiment_id = ? AND state != 'done'"
        " ORDER BY id");
    int rc, stop = 0;
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, experiment_id);
    while (!stop && (rc = sqlite3_step(st)) == SQLITE_ROW) {
        mpb_run_row row = {
            .id = sqlite3_column_int64(st, 0),
            .planner_config_id = sqlite3_column_int64(st, 1),
            .query_id = sqlite3_column_int64(st, 2),
            .repetition = sqlite3_column_int(st, 3),
            .seed = sqlite3_column_int64(st, 4),
            .attempts = sqlite3_column_int(st, 5),
            .sent = strcmp(mpb__col_text(st, 6), "sent") == 0,
            .attempt_id = mpb__col_text(st, 7),
        };
        stop = cb(ud, &row);
    }
    sqlite3_finalize(st);
    if (stop)
        return stop;
    return rc == SQLITE_DONE ? MPB_OK : mpb__store_db_fail(s, "list runs");
}

int mpb_store_run_counts(mpb_store *s, int64_t experiment_id,
                         mpb_run_counts *out)
{
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT count(*), count(*) FILTER (WHERE state = 'done'),"
        " count(*) FILTER (WHERE success = 1),"
        " count(*) FILTER (WHERE status = 'crash')"
        " FROM runs WHERE experiment_id = ?");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, experiment_id);
    int rc = sqlite3_step(st);
    if (rc == SQLITE_ROW) {
        out->total = sqlite3_column_int(st, 0);
        out->done = sqlite3_column_int(st, 1);
        out->succeeded = sqlite3_column_int(st, 2);
        out->crashed = sqlite3_column_int(st, 3);
    }
    sqlite3_finalize(st);
    return rc == SQLITE_ROW ? MPB_OK : mpb__store_db_fail(s, "count runs");
}

int mpb_store_run_sent(mpb_store *s, int64_t run_id, const char *attempt_id,
                       const char *planner_id)
{
    sqlite3_stmt *st = mpb__store_stmt(s, MPB__ST_RUN_SENT);
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, run_id);
    sqlite3_bind_text(st, 2, attempt_id, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 3, planner_id, -1, SQLITE_STATIC);
    sqlite3_bind_double(st, 4, mpb__store_now());
    int rc = sqlite3_step(st);
    sqlite3_reset(st);
    if (rc != SQLITE_DONE)
        return mpb__store_db_fail(s, "mark run sent");
    return sqlite3_changes(s->db) ? MPB_OK
        : mpb__store_fail(s, MPB_EEXISTS, "run %lld is already done",
                          (long long)run_id);
}

/* A sent run back to pending by sql (?1 run id, ?2 its attempt's id,
 * ?3 why, if not NULL); MPB_ENOTFOUND if that is not its current attempt. */
static int run_back_to_pending(mpb_store *s, const char *sql, int64_t run_id,
                               const char *attempt_id, const char *why,
                               const char *what)
{
    sqlite3_stmt *st = mpb__store_prepare(s, sql);
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, run_id);
    sqlite3_bind_text(st, 2, attempt_id, -1, SQLITE_STATIC);
    if (why != NULL)
        sqlite3_bind_text(st, 3, why, -1, SQLITE_STATIC);
    int rc = sqlite3_step(st);
    sqlite3_finalize(st);
    if (rc != SQLITE_DONE)
        return mpb__store_db_fail(s, what);
    return sqlite3_changes(s->db) ? MPB_OK
        : mpb__store_fail(s, MPB_ENOTFOUND, "run %lld has no attempt %s in "
                          "flight", (long long)run_id, attempt_id);
}

int mpb_store_run_retry(mpb_store *s, int64_t run_id, const char *attempt_id,
                        const char *why)
{
    return run_back_to_pending(s,
        "UPDATE runs SET state = 'pending', attempt_id = NULL, message = ?3,"
        " crashes = crashes + 1 WHERE id = ?1 AND attempt_id = ?2"
        " AND state = 'sent'", run_id, attempt_id, why, "retry run");
}

int mpb_store_run_unsent(mpb_store *s, int64_t run_id, const char *attempt_id)
{
    return run_back_to_pending(s,
        "UPDATE runs SET state = 'pending', attempt_id = NULL,"
        " attempts = attempts - 1 WHERE id = ?1 AND attempt_id = ?2"
        " AND state = 'sent'", run_id, attempt_id, NULL, "take back run");
}

int mpb__metrics_pack(mpb_store *s, const mpb_named *m, int n,
                      const unsigned char **out, int *len)
{
    /* The buffer: the sort order (n ints), then the packed metrics, and one
     * byte more, so that it exists even for no metrics: an empty list is a
     * zero-length blob, not NULL. */
    size_t need = 1 + (size_t)(n > 0 ? n : 0) * sizeof(int);
    int *order;
    *out = NULL;
    *len = 0;
    for (int i = 0; i < n; i++) {
        if (m[i].name == NULL)
            return MPB_OK;      /* the metrics table refuses it anyway */
        size_t k = strlen(m[i].name);
        if (k > MPB__PACK_NAME_MAX)
            return MPB_OK;
        need += 1 + k + 8;
    }
    if (need > (size_t)INT32_MAX)
        return MPB_OK;
    if (need > s->pack_cap) {
        unsigned char *p = realloc(s->pack, need);
        if (p == NULL)
            return mpb__store_fail(s, MPB_ENOMEM, "finish run: out of memory");
        s->pack = p;
        s->pack_cap = need;
    }
    /* In name order, the last of equal names only: as the metrics table
     * (primary key run, stage, name; INSERT OR REPLACE) gives them back. A
     * stage has a handful of metrics: insertion sort, stable. */
    order = (int *)(void *)s->pack;
    for (int i = 0; i < n; i++) {
        int j = i;
        while (j > 0 && strcmp(m[order[j - 1]].name, m[i].name) > 0) {
            order[j] = order[j - 1];
            j--;
        }
        order[j] = i;
    }
    unsigned char *start = s->pack + (size_t)(n > 0 ? n : 0) * sizeof(int);
    unsigned char *p = start;
    for (int r = 0; r < n; r++) {
        const mpb_named *x = &m[order[r]];
        if (r + 1 < n && strcmp(x->name, m[order[r + 1]].name) == 0)
            continue;
        size_t k = strlen(x->name);
        uint64_t bits;
        memcpy(&bits, &x->value, 8);
        *p++ = (unsigned char)k;
        memcpy(p, x->name, k);
        p += k;
        for (int b = 0; b < 8; b++)
            *p++ = (unsigned char)(bits >> (8 * b));
    }
    *out = start;
    *len = (int)(p - start);
    return MPB_OK;
}

/* The INSERT of k (1..MPB__METRIC_ROWS_MAX) metric rows, prepared once. */
static sqlite3_stmt *metric_rows(mpb_store *s, int k)
{
    sqlite3_stmt **st = &s->metric_rows[k - 1];
    if (*st == NULL) {
        static const char head[] =
            "INSERT OR REPLACE INTO metrics(run_id, stage, name, value) VALUES ";
        char sql[sizeof head + MPB__METRIC_ROWS_MAX * 12];
        size_t n = sizeof head - 1;
        memcpy(sql, head, n);
        for (int r = 0; r < k; r++) {
            memcpy(sql + n, r ? ",(?,?,?,?)" : "(?,?,?,?)", r ? 10 : 9);
            n += r ? 10 : 9;
        }
        sql[n] = '\0';
        *st = mpb__store_prepare(s, sql);
        return *st;
    }
    /* The transaction is opened as by mpb__store_stmt(). */
    if (mpb__store_tx_open(s) != MPB_OK)
        return NULL;
    sqlite3_clear_bindings(*st);
    return *st;
}

static int write_stage(mpb_store *s, int64_t run_id, int idx,
                       const mpb_stage_record *sg)
{
    sqlite3_stmt *st = mpb__store_stmt(s, MPB__ST_STAGE_INSERT);
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, run_id);
    sqlite3_bind_int(st, 2, idx);
    sqlite3_bind_text(st, 3, sg->name, -1, SQLITE_STATIC);
    sqlite3_bind_double(st, 4, sg->time);
    sqlite3_bind_int(st, 5, sg->num_waypoints);
    sqlite3_bind_int(st, 6, sg->num_joints);
    /* Waypoints as raw float64 (this machine's order, little-endian on
     * every platform mpbench runs on): compact and exact. */
    if (sg->waypoints != NULL && sg->num_waypoints > 0)
        sqlite3_bind_blob(st, 7, sg->waypoints,
                          (int)(sizeof(double) * (size_t)sg->num_waypoints *
                                (size_t)sg->num_joints), SQLITE_STATIC);
    sqlite3_bind_int(st, 8, sg->valid);
    sqlite3_bind_text(st, 9, sg->verdict ? sg->verdict : "", -1, SQLITE_STATIC);
    if (sg->verdict_detail)
        sqlite3_bind_text(st, 10, sg->verdict_detail, -1, SQLITE_STATIC);
    sqlite3_bind_int(st, 11, sg->verdict_segment);
    if (sg->verification)
        sqlite3_bind_text(st, 12, sg->verification, -1, SQLITE_STATIC);
    /* Times as raw float64 too, one per waypoint; NULL: untimed. */
    if (sg->times != NULL && sg->num_waypoints > 0)
        sqlite3_bind_blob(st, 13, sg->times,
                          (int)(sizeof(double) * (size_t)sg->num_waypoints),
                          SQLITE_STATIC);
    /* Only a collision has a depth; none binds as NULL. */
    if (sg->has_depth && sg->verdict && strcmp(sg->verdict, "collision") == 0 &&
        isfinite(sg->depth_lower_mm) && isfinite(sg->depth_upper_mm)) {
        sqlite3_bind_double(st, 14, sg->depth_lower_mm);
        sqlite3_bind_double(st, 15, sg->depth_upper_mm);
    }
    if (sqlite3_step(st) != SQLITE_DONE)
        return mpb__store_db_fail(s, "store stage");

    /* Up to MPB__METRIC_ROWS_MAX rows per statement: one statement's
     * overhead (reset, bind, step, its journal) instead of one per metric
     * (callgrind, bench/results/history.md). Rows in order, so that a repeated
     * name ends with its last value, as one INSERT OR REPLACE each did. */
    for (int i = 0; i < sg->num_metrics;) {
        int k = sg->num_metrics - i;
        if (k > MPB__METRIC_ROWS_MAX)
            k = MPB__METRIC_ROWS_MAX;
        sqlite3_stmt *m = metric_rows(s, k);
        if (m == NULL)
            return MPB_EDB;
        for (int r = 0; r < k; r++, i++) {
            sqlite3_bind_int64(m, 4 * r + 1, run_id);
            sqlite3_bind_text(m, 4 * r + 2, sg->name, -1, SQLITE_STATIC);
            sqlite3_bind_text(m, 4 * r + 3, sg->metrics[i].name, -1,
                              SQLITE_STATIC);
            sqlite3_bind_double(m, 4 * r + 4, sg->metrics[i].value);
        }
        int rc = sqlite3_step(m);
        sqlite3_reset(m);
        if (rc != SQLITE_DONE)
            return mpb__store_db_fail(s, "store metric");
    }
    return MPB_OK;
}

static int write_values(mpb_store *s, const mpb_run_record *r)
{
    int x = 0;      /* the next of r->exact, by index */
    for (int i = 0; i < r->num_values; i++) {
        sqlite3_stmt *st = mpb__store_stmt(s, MPB__ST_VALUE_INSERT);
        if (st == NULL)
            return MPB_EDB;
        sqlite3_bind_int64(st, 1, r->run_id);
        sqlite3_bind_text(st, 2, r->values[i].name, -1, SQLITE_STATIC);
        sqlite3_bind_double(st, 3, r->values[i].value);
        while (r->exact && x < r->num_exact && r->exact[x].index < i)
            x++;
        if (r->exact && x < r->num_exact && r->exact[x].index == i)
            sqlite3_bind_int64(st, 4, r->exact[x].value);
        if (sqlite3_step(st) != SQLITE_DONE)
            return mpb__store_db_fail(s, "store planner value");
    }
    for (int i = 0; i < r->num_progress; i++) {
        sqlite3_stmt *st = mpb__store_stmt(s, MPB__ST_PROGRESS_INSERT);
        if (st == NULL)
            return MPB_EDB;
        sqlite3_bind_int64(st, 1, r->run_id);
        sqlite3_bind_int(st, 2, i);
        sqlite3_bind_double(st, 3, r->progress[i].time);
        sqlite3_bind_text(st, 4, r->progress[i].name, -1, SQLITE_STATIC);
        sqlite3_bind_double(st, 5, r->progress[i].value);
        if (sqlite3_step(st) != SQLITE_DONE)
            return mpb__store_db_fail(s, "store progress");
    }
    return MPB_OK;
}

/* The body of mpb_store_run_finish, inside a transaction. */
static int finish_run(mpb_store *s, const mpb_run_record *r)
{
    sqlite3_stmt *st = mpb__store_stmt(s, MPB__ST_RUN_FINISH);
    const mpb_stage_record *last =
        r->num_stages > 0 ? &r->stages[r->num_stages - 1] : NULL;
    int rc;

    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, r->run_id);
    sqlite3_bind_text(st, 2, r->attempt_id, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 3, r->planner_id, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 4, r->status, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 5, r->message ? r->message : "", -1, SQLITE_STATIC);
    sqlite3_bind_int(st, 6, r->claimed_success);
    if (last) {
        sqlite3_bind_int(st, 7, last->valid);
        sqlite3_bind_text(st, 8, last->verdict, -1, SQLITE_STATIC);
        sqlite3_bind_text(st, 14, last->name, -1, SQLITE_STATIC);
        const unsigned char *packed;
        int len;
        if ((rc = mpb__metrics_pack(s, last->metrics, last->num_metrics,
                                    &packed, &len)) != MPB_OK)
            return rc;
        if (packed != NULL)
            sqlite3_bind_blob(st, 15, packed, len, SQLITE_STATIC);
    }
    sqlite3_bind_int(st, 9, r->success);
    /* The run's outcome by the rule's own function (outcome.h). */
    sqlite3_bind_text(st, 20, mpb_outcome_name(mpb_run_outcome(
                          r->claimed_success, last != NULL && last->valid,
                          r->success)), -1, SQLITE_STATIC);
    sqlite3_bind_int(st, 21, !r->late);
    if (r->seen_verdict != NULL) {
        sqlite3_bind_text(st, 22, r->seen_verdict, -1, SQLITE_STATIC);
        sqlite3_bind_text(st, 23, r->seen_detail ? r->seen_detail : "", -1,
                          SQLITE_STATIC);
        sqlite3_bind_int(st, 24, r->seen_success);
    }
    sqlite3_bind_double(st, 10, r->time_total);
    sqlite3_bind_double(st, 11, r->time_raw);
    sqlite3_bind_double(st, 12, r->time_other);
    sqlite3_bind_double(st, 13, r->wall_time);
    sqlite3_bind_double(st, 16, mpb__store_now());
    /* NaN (no verification, as of a crash) binds as NULL. */
    sqlite3_bind_double(st, 18, r->verify_time);
    /* Not reported (NaN), or no size: NULL. 0 is a size (an OMPL log's
     * memory is the growth of the process over the run). */
    if (r->memory >= 0 && isfinite(r->memory))
        sqlite3_bind_double(st, 19, r->memory);
    else
        sqlite3_bind_null(st, 19);
    /* The planner's world setup time, also kept on the run's row, where
     * a report reads it without a lookup per run. */
    for (int i = 0; i < r->num_values; i++)
        if (r->values[i].name != NULL &&
            strcmp(r->values[i].name, "world_setup_time") == 0)
            sqlite3_bind_double(st, 17, r->values[i].value);
    if (sqlite3_step(st) != SQLITE_DONE)
        return mpb__store_db_fail(s, "finish run");
    if (sqlite3_changes(s->db) == 0) {
        /* Either already done (a repeated result) or not this attempt. */
        sqlite3_stmt *q = mpb__store_prepare(s,
            "SELECT state = 'done' FROM runs WHERE id = ? AND attempt_id = ?");
        if (q == NULL)
            return MPB_EDB;
        sqlite3_bind_int64(q, 1, r->run_id);
        sqlite3_bind_text(q, 2, r->attempt_id, -1, SQLITE_STATIC);
        rc = sqlite3_step(q) == SQLITE_ROW && sqlite3_column_int(q, 0)
                 ? mpb__store_fail(s, MPB_EEXISTS, "run %lld is already done",
                                   (long long)r->run_id)
                 : mpb__store_fail(s, MPB_ENOTFOUND,
                                   "run %lld has no attempt %s",
                                   (long long)r->run_id, r->attempt_id);
        sqlite3_finalize(q);
        return rc;
    }
    for (int i = 0; i < r->num_stages; i++)
        if ((rc = write_stage(s, r->run_id, i, &r->stages[i])) != MPB_OK)
            return rc;
    return write_values(s, r);
}

int mpb_store_run_finish(mpb_store *s, const mpb_run_record *r)
{
    /* Inside the caller's transaction a savepoint keeps a failed run from
     * leaving half its rows; alone, the run is its own transaction. */
    int nested = s->in_tx != MPB__TX_NONE;
    int rc = nested ? mpb__store_step(s, MPB__ST_SAVEPOINT, "begin run")
                    : mpb__store_step(s, MPB__ST_BEGIN, "begin run");
    if (rc != MPB_OK)
        return rc;
    rc = finish_run(s, r);
    if (rc == MPB_OK)
        rc = nested ? mpb__store_step(s, MPB__ST_RELEASE, "commit run")
                    : mpb__store_step(s, MPB__ST_COMMIT, "commit run");
    if (rc != MPB_OK) {
        /* Keep the error of what failed, not of the undoing. */
        sqlite3_stmt *undo = mpb__store_stmt(s, nested ? MPB__ST_ROLLBACK_TO
                                                       : MPB__ST_ROLLBACK);
        if (undo != NULL) {
            sqlite3_step(undo);
            sqlite3_reset(undo);
        }
        if (nested && (undo = mpb__store_stmt(s, MPB__ST_RELEASE)) != NULL) {
            sqlite3_step(undo);
            sqlite3_reset(undo);
        }
    }
    return rc;
}
