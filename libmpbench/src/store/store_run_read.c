/*
 * store_run_read.c - reading one run back whole, for drawing it (mpb view):
 * where it belongs (experiment, configuration, query, scene), its outcome,
 * and every stage with its waypoints and verdict.
 */
#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "store/store_columns.h"
#include "store/store_internal.h"

int mpb_store_run_get(mpb_store *s, int64_t run_id,
                      int (*cb)(void *ud, const mpb_run_detail *row), void *ud)
{
    /* runs.in_time, or for a database made before it, what its runs
     * say: only a claimed run with a valid final stage could be no
     * success, and then for its time alone (store.c, add_outcomes()). */
    /* A database made before seen scenes judged nothing on them. */
    char sql[800];
    snprintf(sql, sizeof sql,
        "SELECT r.id, r.experiment_id, r.planner_config_id, r.query_id,"
        " q.scene_id, r.repetition, r.state, p.name, r.planner_id, r.status,"
        " r.message, r.verdict, r.success, r.time_total,"
        " coalesce(r.claimed_success, 0), coalesce(r.valid, 0), %s, %s"
        " FROM runs r JOIN planner_configs p ON p.id = r.planner_config_id"
        " JOIN queries q ON q.id = r.query_id WHERE r.id = ?",
        mpb__store_has_column(s, "runs", "in_time")
            ? "coalesce(r.in_time, 1)"
            : "NOT (coalesce(r.claimed_success, 0) AND coalesce(r.valid, 0)"
              " AND NOT coalesce(r.success, 0))",
        mpb__store_has_column(s, "runs", "seen_success")
            ? "r.seen_verdict, r.seen_detail, r.seen_success"
            : "NULL, NULL, NULL");
    sqlite3_stmt *st = mpb__store_prepare(s, sql);
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, run_id);
    int step = sqlite3_step(st), rc = MPB_OK;
    if (step == SQLITE_ROW) {
        mpb_run_detail d = {
            .run_id = sqlite3_column_int64(st, 0),
            .experiment_id = sqlite3_column_int64(st, 1),
            .planner_config_id = sqlite3_column_int64(st, 2),
            .query_id = sqlite3_column_int64(st, 3),
            .scene_id = sqlite3_column_int64(st, 4),
            .repetition = sqlite3_column_int(st, 5),
            .state = mpb__col_text_or_empty(st, 6),
            .planner_config = mpb__col_text_or_empty(st, 7),
            .planner_id = mpb__col_text_or_empty(st, 8),
            .status = mpb__col_text_or_empty(st, 9),
            .message = mpb__col_text_or_empty(st, 10),
            .verdict = mpb__col_text_or_empty(st, 11),
            .success = mpb__col_int_or(st, 12, -1),
            .time_total = mpb__col_real(st, 13),
            .claimed = sqlite3_column_int(st, 14),
            .final_valid = sqlite3_column_int(st, 15),
            .in_time = sqlite3_column_int(st, 16),
            .seen_verdict = mpb__col_text(st, 17),
            .seen_detail = mpb__col_text(st, 18),
            .seen_success = mpb__col_int_or(st, 19, -1),
        };
        if (d.seen_verdict == NULL || d.seen_success < 0) {
            d.seen_verdict = d.seen_detail = NULL;
            d.seen_success = -1;
        }
        rc = cb(ud, &d);
    } else if (step == SQLITE_DONE) {
        rc = mpb__store_fail(s, MPB_ENOTFOUND, "no run %lld",
                             (long long)run_id);
    } else {
        rc = mpb__store_db_fail(s, "read run");
    }
    sqlite3_finalize(st);
    return rc;
}

int mpb_store_run_stages(mpb_store *s, int64_t run_id,
                         int (*cb)(void *ud, const mpb_stage_record *stage),
                         void *ud)
{
    /* A database made before stages.verification (read-only, so never
     * given the column) stored sampled verdicts: read as NULL; one made
     * before stages.times had no timed stages; one made before the depth
     * columns, no depths. */
    char sql[400];
    snprintf(sql, sizeof sql,
             "SELECT name, time, num_waypoints, num_joints, waypoints, valid,"
             " verdict, verdict_detail, verdict_segment, %s, %s, %s"
             " FROM stages WHERE run_id = ? ORDER BY idx",
             mpb__store_has_column(s, "stages", "verification")
                 ? "verification" : "NULL",
             mpb__store_has_column(s, "stages", "times") ? "times" : "NULL",
             mpb__store_has_column(s, "stages", "depth_upper_mm")
                 ? "depth_lower_mm, depth_upper_mm" : "NULL, NULL");
    sqlite3_stmt *st = mpb__store_prepare(s, sql);
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, run_id);
    int step, stop = 0;
    while (!stop && (step = sqlite3_step(st)) == SQLITE_ROW) {
        int n = sqlite3_column_int(st, 2), nj = sqlite3_column_int(st, 3);
        const void *blob = sqlite3_column_blob(st, 4);
        size_t bytes = (size_t)sqlite3_column_bytes(st, 4);
        double *wp = NULL;
        /* A blob that does not hold n * nj doubles is given as none. */
        if (n > 0 && nj > 0 && blob != NULL &&
            bytes == sizeof(double) * (size_t)n * (size_t)nj) {
            if ((wp = malloc(bytes)) == NULL) {
                sqlite3_finalize(st);
                return mpb__store_fail(s, MPB_ENOMEM, "out of memory "
                                       "reading run %lld", (long long)run_id);
            }
            memcpy(wp, blob, bytes);   /* aligned; little-endian as stored */
        }
        /* Times that are not one double per waypoint are given as none. */
        const void *tblob = sqlite3_column_blob(st, 10);
        size_t tbytes = (size_t)sqlite3_column_bytes(st, 10);
        double *times = NULL;
        if (wp != NULL && tblob != NULL &&
            tbytes == sizeof(double) * (size_t)n) {
            if ((times = malloc(tbytes)) == NULL) {
                free(wp);
                sqlite3_finalize(st);
                return mpb__store_fail(s, MPB_ENOMEM, "out of memory "
                                       "reading run %lld", (long long)run_id);
            }
            memcpy(times, tblob, tbytes);
        }
        mpb_stage_record rec = {
            .name = mpb__col_text_or_empty(st, 0),
            .time = mpb__col_real(st, 1),
            .num_waypoints = wp ? n : 0,
            .num_joints = wp ? nj : 0,
            .waypoints = wp,
            .valid = sqlite3_column_int(st, 5),
            .verdict = mpb__col_text_or_empty(st, 6),
            .verdict_detail = mpb__col_text_or_empty(st, 7),
            .verdict_segment = mpb__col_int_or(st, 8, -1),
            .verification = mpb__col_text(st, 9),
            .times = times,
            .has_depth = !mpb__col_is_null(st, 12),
            .depth_lower_mm = mpb__col_real(st, 11),
            .depth_upper_mm = mpb__col_real(st, 12),
        };
        stop = cb(ud, &rec);
        free(times);
        free(wp);
    }
    sqlite3_finalize(st);
    if (stop)
        return stop;
    return step == SQLITE_DONE ? MPB_OK : mpb__store_db_fail(s, "read stages");
}
