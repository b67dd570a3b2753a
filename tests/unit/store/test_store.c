/* test_store.c - the SQLite store: schema, idempotent writes, the life of a
 * run, and refusing what it must refuse. */
#include <setjmp.h>
#include <stdarg.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <sqlite3.h>

#include "mpbench/mpbench.h"

typedef struct fixture {
    char path[64];
    mpb_store *s;
    int64_t exp, cfg, scene, query;
} fixture;

static const char *const joint_names[] = {"a", "b"};
static const double start[] = {0.0, 0.5};
static const double goal[] = {1.0, -0.25};

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    strcpy(f->path, "/tmp/mpb_test_store_XXXXXX");
    int fd = mkstemp(f->path);
    close(fd);
    unlink(f->path);
    assert_int_equal(mpb_store_open(f->path, 0, &f->s), MPB_OK);

    mpb_experiment_info e = {"exp", "exp.yaml", "h1", "text", 2, 1.5, NULL, 0};
    assert_int_equal(mpb_store_experiment_create(f->s, &e, &f->exp), MPB_OK);
    assert_int_equal(mpb_store_planner_config_add(f->s, f->exp, "p/A", "p", "A",
                                                  "", &f->cfg), MPB_OK);
    mpb_scene_info sc = {"scene", "planar", "rh", "robot", "planar", "sh", "s"};
    assert_int_equal(mpb_store_scene_add(f->s, f->exp, &sc, &f->scene), MPB_OK);
    mpb_query_info q = {"q", 2, joint_names, start, MPB_GOAL_JOINTS, goal, 0.01,
                        NULL, NULL};
    assert_int_equal(mpb_store_query_add(f->s, f->scene, &q, &f->query), MPB_OK);
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    char wal[80];
    mpb_store_close(f->s);
    unlink(f->path);
    snprintf(wal, sizeof wal, "%s-wal", f->path);
    unlink(wal);
    snprintf(wal, sizeof wal, "%s-shm", f->path);
    unlink(wal);
    free(f);
    return 0;
}

/* One integer from the database through a separate connection, as a user
 * at the sqlite3 prompt would see it. */
static long long peek(const fixture *f, const char *sql)
{
    sqlite3 *db;
    sqlite3_stmt *st;
    long long v = -1;
    assert_int_equal(sqlite3_open(f->path, &db), SQLITE_OK);
    assert_int_equal(sqlite3_prepare_v2(db, sql, -1, &st, NULL), SQLITE_OK);
    if (sqlite3_step(st) == SQLITE_ROW)
        v = sqlite3_column_int64(st, 0);
    sqlite3_finalize(st);
    sqlite3_close(db);
    return v;
}

static void adding_twice_returns_the_same_row(void **state)
{
    fixture *f = *state;
    int64_t id;
    assert_int_equal(mpb_store_planner_config_add(f->s, f->exp, "p/A", "p", "A",
                                                  "", &id), MPB_OK);
    assert_true(id == f->cfg);
    mpb_query_info q = {"q", 2, joint_names, start, MPB_GOAL_JOINTS, goal, 0.01,
                        NULL, NULL};
    assert_int_equal(mpb_store_query_add(f->s, f->scene, &q, &id), MPB_OK);
    assert_true(id == f->query);
    for (int i = 0; i < 2; i++)
        assert_int_equal(mpb_store_run_add(f->s, f->exp, f->cfg, f->query, 0, 9),
                         MPB_OK);
    assert_int_equal(peek(f, "SELECT count(*) FROM runs"), 1);
    assert_int_equal(peek(f, "SELECT count(*) FROM planner_configs"), 1);
}

static void queries_are_stored_exactly_and_readably(void **state)
{
    fixture *f = *state;
    assert_int_equal(peek(f, "SELECT start = '0 0.5' AND goal_joints = '1 -0.25'"
                             " AND joint_names = 'a b' FROM queries"), 1);
}

static int collect(void *ud, const mpb_run_row *row)
{
    mpb_run_row *out = ud;
    out[out[0].attempts++ + 1] = *row;
    out[out[0].attempts].attempt_id = NULL;
    return 0;
}

static void a_run_is_finished_once(void **state)
{
    fixture *f = *state;
    mpb_run_row rows[4] = {{0}};
    double wp[] = {0.0, 0.5, 1.0, -0.25};
    mpb_named metrics[] = {{"path_length", 1.25}, {"smoothness", 0.0}};
    mpb_stage_record stage = {"raw", 0.01, 2, 2, wp, 1, "valid", "", -1,
                              2, metrics, NULL, 0, NAN, NAN, NULL};
    mpb_named values[] = {{"graph states", 17}};
    mpb_run_record r = {
        .run_id = 0, .attempt_id = "0123456789abcdef0123456789abcdef",
        .planner_id = "p@h:1", .status = "solved", .message = "",
        .claimed_success = 1, .success = 1, .time_total = 0.02,
        .time_raw = 0.015, .time_other = 0.005, .wall_time = 0.03,
        .num_stages = 1, .stages = &stage, .num_values = 1, .values = values,
    };
    mpb_run_counts c;

    assert_int_equal(mpb_store_run_add(f->s, f->exp, f->cfg, f->query, 0, 9), MPB_OK);
    assert_int_equal(mpb_store_run_add(f->s, f->exp, f->cfg, f->query, 1, 10), MPB_OK);
    assert_int_equal(mpb_store_runs_unfinished(f->s, f->exp, collect, rows), MPB_OK);
    assert_int_equal(rows[0].attempts, 2);
    assert_int_equal(rows[1].repetition, 0);
    assert_true(rows[1].seed == 9);
    assert_int_equal(rows[1].sent, 0);
    r.run_id = rows[1].id;

    /* Not sent yet: no attempt has this id. */
    assert_int_equal(mpb_store_run_finish(f->s, &r), MPB_ENOTFOUND);
    assert_int_equal(mpb_store_run_sent(f->s, r.run_id, r.attempt_id, "p@h:1"), MPB_OK);
    assert_int_equal(mpb_store_run_finish(f->s, &r), MPB_OK);
    /* The same result again: nothing written. */
    assert_int_equal(mpb_store_run_finish(f->s, &r), MPB_EEXISTS);
    /* A run that is done cannot be sent again. */
    assert_int_equal(mpb_store_run_sent(f->s, r.run_id, "ffffffffffffffffffffffffffffffff",
                                        "p@h:1"), MPB_EEXISTS);

    assert_int_equal(peek(f, "SELECT count(*) FROM stages"), 1);
    assert_int_equal(peek(f, "SELECT count(*) FROM metrics"), 2);
    assert_int_equal(peek(f, "SELECT count(*) FROM planner_values"), 1);
    assert_int_equal(peek(f, "SELECT length(waypoints) FROM stages"), 32);
    assert_int_equal(peek(f, "SELECT attempts FROM runs WHERE state = 'done'"), 1);
    assert_int_equal(peek(f, "SELECT path_length * 100 FROM results"), 125);
    /* The view tells experiments of one name apart by their id. */
    assert_true(peek(f, "SELECT experiment_id FROM results") == f->exp);
    assert_int_equal(peek(f, "SELECT message = '' FROM results"), 1);

    assert_int_equal(mpb_store_run_counts(f->s, f->exp, &c), MPB_OK);
    assert_int_equal(c.total, 2);
    assert_int_equal(c.done, 1);
    assert_int_equal(c.succeeded, 1);

    rows[0].attempts = 0;
    assert_int_equal(mpb_store_runs_unfinished(f->s, f->exp, collect, rows), MPB_OK);
    assert_int_equal(rows[0].attempts, 1);
    assert_int_equal(rows[1].repetition, 1);
}

/* A request its planner never started is taken back: pending again, the
 * attempt not counted, no crash; only for the run's current attempt. */
static void a_request_never_started_is_taken_back(void **state)
{
    fixture *f = *state;
    mpb_run_row rows[2] = {{0}};
    const char *uid = "0123456789abcdef0123456789abcdef";
    assert_int_equal(mpb_store_run_add(f->s, f->exp, f->cfg, f->query, 0, 5), MPB_OK);
    assert_int_equal(mpb_store_runs_unfinished(f->s, f->exp, collect, rows), MPB_OK);
    int64_t id = rows[1].id;

    assert_int_equal(mpb_store_run_sent(f->s, id, uid, "p@h:1"), MPB_OK);
    assert_int_equal(mpb_store_run_unsent(f->s, id, "ffffffffffffffffffffffffffffffff"),
                     MPB_ENOTFOUND);
    assert_int_equal(peek(f, "SELECT state = 'sent' AND attempts = 1 FROM runs"), 1);
    assert_int_equal(mpb_store_run_unsent(f->s, id, uid), MPB_OK);
    assert_int_equal(peek(f, "SELECT state = 'pending' AND attempt_id IS NULL"
                             " AND attempts = 0 AND crashes = 0 FROM runs"), 1);
    /* Taken back once: the same attempt again is no attempt in flight. */
    assert_int_equal(mpb_store_run_unsent(f->s, id, uid), MPB_ENOTFOUND);
    assert_non_null(strstr(mpb_store_errmsg(f->s), uid));
}

static void a_failed_write_leaves_no_half_run(void **state)
{
    fixture *f = *state;
    mpb_named metrics[] = {{"path_length", 1.0}, {NULL, 2.0}}; /* NULL name: NOT NULL fails */
    mpb_stage_record stage = {"raw", 0.01, 0, 2, NULL, 0, "empty", "", -1,
                              2, metrics, NULL, 0, NAN, NAN, NULL};
    mpb_run_record r = {
        .attempt_id = "00000000000000000000000000000001", .planner_id = "p",
        .status = "solved", .num_stages = 1, .stages = &stage,
    };
    mpb_run_row rows[2] = {{0}};
    assert_int_equal(mpb_store_run_add(f->s, f->exp, f->cfg, f->query, 0, 1), MPB_OK);
    assert_int_equal(mpb_store_runs_unfinished(f->s, f->exp, collect, rows), MPB_OK);
    r.run_id = rows[1].id;
    assert_int_equal(mpb_store_run_sent(f->s, r.run_id, r.attempt_id, "p"), MPB_OK);
    assert_int_equal(mpb_store_run_finish(f->s, &r), MPB_EDB);
    assert_non_null(strstr(mpb_store_errmsg(f->s), "metric"));
    assert_int_equal(peek(f, "SELECT count(*) FROM stages"), 0);
    assert_int_equal(peek(f, "SELECT count(*) FROM metrics"), 0);
    assert_int_equal(peek(f, "SELECT state = 'sent' FROM runs"), 1);
}

static void resuming_finds_the_unfinished_experiment(void **state)
{
    fixture *f = *state;
    int64_t id;
    assert_int_equal(mpb_store_experiment_find_unfinished(f->s, "exp", "h1", &id), MPB_OK);
    assert_true(id == f->exp);
    assert_int_equal(mpb_store_experiment_find_unfinished(f->s, "exp", "h2", &id),
                     MPB_ENOTFOUND);
    assert_int_equal(mpb_store_experiment_finish(f->s, f->exp), MPB_OK);
    assert_int_equal(mpb_store_experiment_find_unfinished(f->s, "exp", "h1", &id),
                     MPB_ENOTFOUND);
    assert_int_equal(mpb_store_experiment_latest(f->s, &id), MPB_OK);
    assert_true(id == f->exp);
}

/* A change of a run's state writes no index entry (no index has the state
 * column): an older database's state index is dropped when it is opened,
 * the index by experiment is there, and unfinished runs are still found. */
static void an_older_state_index_is_dropped(void **state)
{
    fixture *f = *state;
    sqlite3 *db;
    mpb_run_row rows[3] = {{0}};
    assert_int_equal(mpb_store_run_add(f->s, f->exp, f->cfg, f->query, 0, 1), MPB_OK);
    assert_int_equal(mpb_store_run_add(f->s, f->exp, f->cfg, f->query, 1, 2), MPB_OK);
    assert_int_equal(peek(f, "SELECT count(*) FROM pragma_index_list('runs') l,"
                             " pragma_index_info(l.name) i"
                             " WHERE i.name IN ('state', 'attempt_id')"), 0);
    mpb_store_close(f->s);
    assert_int_equal(sqlite3_open(f->path, &db), SQLITE_OK);
    assert_int_equal(sqlite3_exec(db, "CREATE INDEX runs_by_state ON"
                                      " runs(experiment_id, state)", NULL, NULL,
                                  NULL), SQLITE_OK);
    sqlite3_close(db);

    assert_int_equal(mpb_store_open(f->path, 0, &f->s), MPB_OK);
    assert_int_equal(peek(f, "SELECT count(*) FROM sqlite_schema"
                             " WHERE name = 'runs_by_state'"), 0);
    assert_int_equal(peek(f, "SELECT count(*) FROM sqlite_schema"
                             " WHERE name = 'runs_by_experiment'"), 1);
    assert_int_equal(mpb_store_runs_unfinished(f->s, f->exp, collect, rows), MPB_OK);
    assert_int_equal(rows[0].attempts, 2);
}

/* A database made before results.experiment_id gets the view as it is now
 * when it is opened for writing; its rows are unchanged. */
static void an_older_results_view_is_replaced(void **state)
{
    fixture *f = *state;
    sqlite3 *db;
    mpb_store_close(f->s);
    assert_int_equal(sqlite3_open(f->path, &db), SQLITE_OK);
    assert_int_equal(sqlite3_exec(db, "DROP VIEW results; CREATE VIEW results AS"
                                      " SELECT r.id AS run FROM runs r",
                                  NULL, NULL, NULL), SQLITE_OK);
    sqlite3_close(db);
    assert_int_equal(peek(f, "SELECT count(*) FROM pragma_table_info('results')"
                             " WHERE name = 'experiment_id'"), 0);

    assert_int_equal(mpb_store_open(f->path, 0, &f->s), MPB_OK);
    assert_int_equal(peek(f, "SELECT count(*) FROM pragma_table_info('results')"
                             " WHERE name IN ('experiment_id', 'message',"
                             " 'path_length')"), 3);
}

static int keep_verify_time(void *ud, const mpb_result_row *row)
{
    double *out = ud;
    out[row->repetition] = row->verify_time;
    return 0;
}

/* Finish repetition rep of the fixture's run with the given verify_time. */
static void finish_with_verify_time(fixture *f, int rep, double verify_time)
{
    mpb_run_row rows[3] = {{0}};
    char uid[33];
    snprintf(uid, sizeof uid, "%032d", rep + 1);
    mpb_run_record r = {
        .attempt_id = uid, .planner_id = "p", .status = "failed", .message = "",
        .time_total = 0.1, .time_raw = 0.1, .time_other = 0.0,
        .wall_time = 0.2, .verify_time = verify_time,
    };
    assert_int_equal(mpb_store_run_add(f->s, f->exp, f->cfg, f->query, rep, 1),
                     MPB_OK);
    assert_int_equal(mpb_store_runs_unfinished(f->s, f->exp, collect, rows),
                     MPB_OK);
    assert_int_equal(rows[0].attempts, 1);
    r.run_id = rows[1].id;
    assert_int_equal(mpb_store_run_sent(f->s, r.run_id, uid, "p"), MPB_OK);
    assert_int_equal(mpb_store_run_finish(f->s, &r), MPB_OK);
}

/* runs.verify_time is stored and read back; a database made before it
 * reads (NaN for its runs) and gets the column when opened for writing,
 * NULL for the runs it had. */
static void verify_time_is_stored_and_added_to_an_older_database(void **state)
{
    fixture *f = *state;
    sqlite3 *db;
    double got[2] = {-1.0, -1.0};

    finish_with_verify_time(f, 0, 0.25);
    assert_int_equal(peek(f, "SELECT verify_time * 100 FROM runs"), 25);
    assert_int_equal(mpb_store_results(f->s, f->exp, 0, NULL, NULL, 0,
                                       keep_verify_time, got), MPB_OK);
    assert_true(got[0] == 0.25);
    /* Another stage's walk (the join) reads it too. */
    got[0] = -1.0;
    assert_int_equal(mpb_store_results(f->s, f->exp, 0, "raw", NULL, 0,
                                       keep_verify_time, got), MPB_OK);
    assert_true(got[0] == 0.25);

    /* Make it an older database: no runs.verify_time. */
    mpb_store_close(f->s);
    assert_int_equal(sqlite3_open(f->path, &db), SQLITE_OK);
    assert_int_equal(sqlite3_exec(db, "ALTER TABLE runs DROP COLUMN verify_time",
                                  NULL, NULL, NULL), SQLITE_OK);
    sqlite3_close(db);

    /* Read as it is (a report): no such time. */
    assert_int_equal(mpb_store_open(f->path, 1, &f->s), MPB_OK);
    got[0] = -1.0;
    assert_int_equal(mpb_store_results(f->s, f->exp, 0, NULL, NULL, 0,
                                       keep_verify_time, got), MPB_OK);
    assert_true(isnan(got[0]));
    got[0] = -1.0;
    assert_int_equal(mpb_store_results(f->s, f->exp, 0, "raw", NULL, 0,
                                       keep_verify_time, got), MPB_OK);
    assert_true(isnan(got[0]));
    mpb_store_close(f->s);

    /* A writer adds it: NULL for the old run, stored for a new one. */
    assert_int_equal(mpb_store_open(f->path, 0, &f->s), MPB_OK);
    assert_int_equal(peek(f, "SELECT count(*) FROM runs WHERE verify_time IS NULL"),
                     1);
    finish_with_verify_time(f, 1, 0.5);
    assert_int_equal(peek(f, "SELECT verify_time * 100 FROM runs"
                             " WHERE repetition = 1"), 50);
    assert_int_equal(mpb_store_results(f->s, f->exp, 0, NULL, NULL, 0,
                                       keep_verify_time, got), MPB_OK);
    assert_true(isnan(got[0]));
    assert_true(got[1] == 0.5);
}

/* Finish repetition rep with one stage refused for a collision, with a
 * depth (has_depth) or without. */
static void finish_refused(fixture *f, int rep, int has_depth)
{
    mpb_run_row rows[3] = {{0}};
    char uid[33];
    snprintf(uid, sizeof uid, "%032d", rep + 1);
    double wp[] = {0.0, 0.5, 1.0, -0.25};
    mpb_stage_record st = {.name = "raw", .time = 0.01, .num_waypoints = 2,
        .num_joints = 2, .waypoints = wp, .valid = 0, .verdict = "collision",
        .verdict_detail = "segment 0 collides", .verdict_segment = 0,
        .has_depth = has_depth, .depth_lower_mm = 0.25, .depth_upper_mm = 1.5};
    mpb_run_record r = {
        .attempt_id = uid, .planner_id = "p", .status = "solved", .message = "",
        .time_total = 0.1, .time_raw = 0.1, .time_other = 0.0,
        .wall_time = 0.2, .verify_time = 0.0, .stages = &st, .num_stages = 1,
    };
    assert_int_equal(mpb_store_run_add(f->s, f->exp, f->cfg, f->query, rep, 1),
                     MPB_OK);
    assert_int_equal(mpb_store_runs_unfinished(f->s, f->exp, collect, rows),
                     MPB_OK);
    r.run_id = rows[1].id;
    assert_int_equal(mpb_store_run_sent(f->s, r.run_id, uid, "p"), MPB_OK);
    assert_int_equal(mpb_store_run_finish(f->s, &r), MPB_OK);
}

static int keep_depth(void *ud, int64_t config, double lo, double up)
{
    double *out = ud;
    (void)config;
    int i = out[4]++ > 0 ? 2 : 0;
    out[i] = lo;
    out[i + 1] = up;
    return 0;
}

/* A collision's depth is stored with its stage and read back; one
 * without (has_depth 0) is NULL; a database made before the columns
 * reads NaN and gets them, NULL, when opened for writing. */
static void depth_is_stored_and_added_to_an_older_database(void **state)
{
    fixture *f = *state;
    sqlite3 *db;
    finish_refused(f, 0, 1);
    assert_int_equal(peek(f, "SELECT depth_lower_mm * 100 FROM stages"), 25);
    assert_int_equal(peek(f, "SELECT depth_upper_mm * 100 FROM stages"), 150);
    double got[5] = {0};
    assert_int_equal(mpb_store_refusal_depths(f->s, f->exp, keep_depth, got),
                     MPB_OK);
    assert_true(got[4] == 1 && got[0] == 0.25 && got[1] == 1.5);
    finish_refused(f, 1, 0);
    assert_int_equal(peek(f, "SELECT count(*) FROM stages"
                             " WHERE depth_upper_mm IS NULL"), 1);

    mpb_store_close(f->s);
    assert_int_equal(sqlite3_open(f->path, &db), SQLITE_OK);
    assert_int_equal(sqlite3_exec(db, "ALTER TABLE stages DROP COLUMN depth_lower_mm;"
                                  "ALTER TABLE stages DROP COLUMN depth_upper_mm",
                                  NULL, NULL, NULL), SQLITE_OK);
    sqlite3_close(db);
    assert_int_equal(mpb_store_open(f->path, 1, &f->s), MPB_OK);
    memset(got, 0, sizeof got);
    assert_int_equal(mpb_store_refusal_depths(f->s, f->exp, keep_depth, got),
                     MPB_OK);
    assert_true(got[4] == 2 && isnan(got[0]) && isnan(got[3]));
    mpb_store_close(f->s);
    assert_int_equal(mpb_store_open(f->path, 0, &f->s), MPB_OK);
    assert_int_equal(peek(f, "SELECT count(*) FROM stages"
                             " WHERE depth_upper_mm IS NULL"), 2);
}

static int keep_memory(void *ud, const mpb_result_row *row)
{
    double *out = ud;
    out[row->repetition] = row->memory;
    return 0;
}

/* Finish repetition rep of the fixture's run with the given memory. */
static void finish_with_memory(fixture *f, int rep, double memory)
{
    mpb_run_row rows[3] = {{0}};
    char uid[33];
    snprintf(uid, sizeof uid, "%032d", rep + 1);
    mpb_run_record r = {
        .attempt_id = uid, .planner_id = "p", .status = "memory", .message = "",
        .time_total = 0.1, .time_raw = 0.1, .time_other = 0.0,
        .wall_time = 0.2, .verify_time = NAN, .memory = memory,
    };
    assert_int_equal(mpb_store_run_add(f->s, f->exp, f->cfg, f->query, rep, 1),
                     MPB_OK);
    assert_int_equal(mpb_store_runs_unfinished(f->s, f->exp, collect, rows),
                     MPB_OK);
    r.run_id = rows[1].id;
    assert_int_equal(mpb_store_run_sent(f->s, r.run_id, uid, "p"), MPB_OK);
    assert_int_equal(mpb_store_run_finish(f->s, &r), MPB_OK);
}

/* runs.memory (MB) is stored and read back, NaN as NULL and 0 as 0 (an
 * OMPL log's growth); a database made before it reads (NaN) and gets the
 * column when opened for writing, NULL for the runs it had. */
static void memory_is_stored_and_added_to_an_older_database(void **state)
{
    fixture *f = *state;
    sqlite3 *db;
    double got[3] = {-1.0, -1.0, -1.0};

    finish_with_memory(f, 0, 512.25);
    finish_with_memory(f, 1, NAN);
    finish_with_memory(f, 2, 0.0);
    assert_int_equal(peek(f, "SELECT memory * 100 FROM runs WHERE repetition = 0"),
                     51225);
    assert_int_equal(peek(f, "SELECT count(*) FROM runs WHERE memory IS NULL"), 1);
    assert_int_equal(peek(f, "SELECT count(*) FROM runs WHERE memory = 0"), 1);
    /* Both walks: the packed one and another stage's join. */
    assert_int_equal(mpb_store_results(f->s, f->exp, 0, NULL, NULL, 0,
                                       keep_memory, got), MPB_OK);
    assert_true(got[0] == 512.25 && isnan(got[1]) && got[2] == 0.0);
    got[0] = -1.0;
    assert_int_equal(mpb_store_results(f->s, f->exp, 0, "raw", NULL, 0,
                                       keep_memory, got), MPB_OK);
    assert_true(got[0] == 512.25);

    /* An older database: no runs.memory. */
    mpb_store_close(f->s);
    assert_int_equal(sqlite3_open(f->path, &db), SQLITE_OK);
    assert_int_equal(sqlite3_exec(db, "ALTER TABLE runs DROP COLUMN memory",
                                  NULL, NULL, NULL), SQLITE_OK);
    sqlite3_close(db);
    assert_int_equal(mpb_store_open(f->path, 1, &f->s), MPB_OK);
    got[0] = -1.0;
    assert_int_equal(mpb_store_results(f->s, f->exp, 0, NULL, NULL, 0,
                                       keep_memory, got), MPB_OK);
    assert_true(isnan(got[0]));
    got[0] = -1.0;
    assert_int_equal(mpb_store_results(f->s, f->exp, 0, "raw", NULL, 0,
                                       keep_memory, got), MPB_OK);
    assert_true(isnan(got[0]));
    mpb_store_close(f->s);

    /* A writer adds it, NULL for the runs there were. */
    assert_int_equal(mpb_store_open(f->path, 0, &f->s), MPB_OK);
    assert_int_equal(peek(f, "SELECT count(*) FROM runs WHERE memory IS NULL"), 3);
}

/* Finish repetition rep with two stages: "raw" untimed, "timed" with
 * the time of each of its waypoints. */
static void finish_with_times(fixture *f, int rep, const double *times)
{
    mpb_run_row rows[3] = {{0}};
    char uid[33];
    static const double wp[] = {0.0, 0.5, 0.5, 0.0, 1.0, -0.25};
    snprintf(uid, sizeof uid, "%032d", rep + 1);
    mpb_stage_record st[2] = {
        {.name = "raw", .time = 0.1, .num_waypoints = 3, .num_joints = 2,
         .waypoints = wp, .valid = 1, .verdict = "valid",
         .verdict_segment = -1},
        {.name = "timed", .time = 0.1, .num_waypoints = 3, .num_joints = 2,
         .waypoints = wp, .valid = 1, .verdict = "valid",
         .verdict_segment = -1, .times = times},
    };
    mpb_run_record r = {
        .attempt_id = uid, .planner_id = "p", .status = "solved", .message = "",
        .time_total = 0.1, .time_raw = 0.1, .time_other = 0.0,
        .wall_time = 0.2, .verify_time = NAN, .memory = NAN,
        .num_stages = 2, .stages = st,
    };
    assert_int_equal(mpb_store_run_add(f->s, f->exp, f->cfg, f->query, rep, 1),
                     MPB_OK);
    assert_int_equal(mpb_store_runs_unfinished(f->s, f->exp, collect, rows),
                     MPB_OK);
    r.run_id = rows[1].id;
    assert_int_equal(mpb_store_run_sent(f->s, r.run_id, uid, "p"), MPB_OK);
    assert_int_equal(mpb_store_run_finish(f->s, &r), MPB_OK);
}

typedef struct seen_times {
    int stages, timed;
    double last;
} seen_times;

static int keep_times(void *ud, const mpb_stage_record *st)
{
    seen_times *t = ud;
    t->stages++;
    if (st->times != NULL) {
        t->timed++;
        t->last = st->times[st->num_waypoints - 1];
    }
    return 0;
}

/* stages.times (one float64 per waypoint, NULL untimed) is stored and
 * read back; a database made before it reads (no stage timed) and gets
 * the column when opened for writing, NULL for the stages it had. */
static void times_are_stored_and_added_to_an_older_database(void **state)
{
    fixture *f = *state;
    sqlite3 *db;
    static const double times[] = {0.0, 0.75, 2.5};
    finish_with_times(f, 0, times);
    assert_int_equal(peek(f, "SELECT length(times) FROM stages WHERE name = 'timed'"),
                     3 * 8);
    assert_int_equal(peek(f, "SELECT times IS NULL FROM stages WHERE name = 'raw'"),
                     1);
    int64_t run = peek(f, "SELECT id FROM runs WHERE repetition = 0");
    seen_times t = {0};
    assert_int_equal(mpb_store_run_stages(f->s, run, keep_times, &t), MPB_OK);
    assert_int_equal(t.stages, 2);
    assert_int_equal(t.timed, 1);
    assert_true(t.last == 2.5);

    /* An older database: no stages.times. */
    mpb_store_close(f->s);
    assert_int_equal(sqlite3_open(f->path, &db), SQLITE_OK);
    assert_int_equal(sqlite3_exec(db, "ALTER TABLE stages DROP COLUMN times",
                                  NULL, NULL, NULL), SQLITE_OK);
    sqlite3_close(db);
    assert_int_equal(mpb_store_open(f->path, 1, &f->s), MPB_OK);
    t = (seen_times){0};
    assert_int_equal(mpb_store_run_stages(f->s, run, keep_times, &t), MPB_OK);
    assert_int_equal(t.stages, 2);
    assert_int_equal(t.timed, 0);
    mpb_store_close(f->s);

    /* A writer adds it, NULL for the stages there were, and stores the
     * times of a run it finishes. */
    assert_int_equal(mpb_store_open(f->path, 0, &f->s), MPB_OK);
    assert_int_equal(peek(f, "SELECT count(*) FROM stages WHERE times IS NULL"), 2);
    finish_with_times(f, 1, times);
    assert_int_equal(peek(f, "SELECT count(*) FROM stages WHERE times IS NOT NULL"),
                     1);
}

/*
 * Another database moved over ours while we write: the check says so, and
 * what we wrote after the move does not end up in the other file (our -wal
 * is left beside it otherwise, and SQLite would replay it there).
 */
static void a_file_moved_over_ours_is_left_alone(void **state)
{
    fixture *f = *state;
    char other[80];
    sqlite3 *db;
    snprintf(other, sizeof other, "%s.other", f->path);
    assert_int_equal(mpb_store_claim(f->s), MPB_OK);
    assert_int_equal(sqlite3_open(other, &db), SQLITE_OK);
    assert_int_equal(sqlite3_exec(db, "CREATE TABLE t(x)", NULL, NULL, NULL),
                     SQLITE_OK);
    sqlite3_close(db);
    assert_int_equal(rename(other, f->path), 0);
    /* Written after the move: pages in our -wal. */
    assert_int_equal(mpb_store_run_add(f->s, f->exp, f->cfg, f->query, 0, 9),
                     MPB_OK);
    assert_int_equal(mpb_store_check_file(f->s), MPB_EEXISTS);
    mpb_store_close(f->s);
    f->s = NULL;
    assert_int_equal(peek(f, "SELECT count(*) FROM sqlite_master"), 1);
    assert_int_equal(peek(f, "SELECT count(*) FROM t"), 0);
}

static void refuses_what_is_not_its_database(void **state)
{
    (void)state;
    char path[] = "/tmp/mpb_test_other_XXXXXX";
    int fd = mkstemp(path);
    mpb_store *s;
    assert_int_equal(write(fd, "not a database at all, just some text", 37), 37);
    close(fd);
    assert_int_not_equal(mpb_store_open(path, 1, &s), MPB_OK);
    assert_non_null(strstr(mpb_store_errmsg(s), path));
    mpb_store_close(s);
    assert_int_not_equal(mpb_store_open("/nonexistent/dir/x.db", 0, &s), MPB_OK);
    assert_non_null(strstr(mpb_store_errmsg(s), "/nonexistent/dir/x.db"));
    mpb_store_close(s);
    mpb_store_close(NULL); /* harmless */
    unlink(path);
}

static void refuses_a_newer_schema(void **state)
{
    fixture *f = *state;
    sqlite3 *db;
    mpb_store *s;
    assert_int_equal(sqlite3_open(f->path, &db), SQLITE_OK);
    assert_int_equal(sqlite3_exec(db, "UPDATE meta SET value = '99' WHERE key ="
                                      " 'schema_version'", NULL, NULL, NULL),
                     SQLITE_OK);
    sqlite3_close(db);
    assert_int_equal(mpb_store_open(f->path, 0, &s), MPB_EUNSUPPORTED);
    assert_non_null(strstr(mpb_store_errmsg(s), "99"));
    mpb_store_close(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(adding_twice_returns_the_same_row, setup, teardown),
        cmocka_unit_test_setup_teardown(queries_are_stored_exactly_and_readably, setup, teardown),
        cmocka_unit_test_setup_teardown(a_run_is_finished_once, setup, teardown),
        cmocka_unit_test_setup_teardown(a_request_never_started_is_taken_back, setup, teardown),
        cmocka_unit_test_setup_teardown(a_failed_write_leaves_no_half_run, setup, teardown),
        cmocka_unit_test_setup_teardown(resuming_finds_the_unfinished_experiment, setup, teardown),
        cmocka_unit_test_setup_teardown(an_older_state_index_is_dropped, setup, teardown),
        cmocka_unit_test_setup_teardown(an_older_results_view_is_replaced, setup, teardown),
        cmocka_unit_test_setup_teardown(verify_time_is_stored_and_added_to_an_older_database,
                                        setup, teardown),
        cmocka_unit_test_setup_teardown(times_are_stored_and_added_to_an_older_database,
                                        setup, teardown),
        cmocka_unit_test_setup_teardown(depth_is_stored_and_added_to_an_older_database,
                                        setup, teardown),
        cmocka_unit_test_setup_teardown(memory_is_stored_and_added_to_an_older_database,
                                        setup, teardown),
        cmocka_unit_test_setup_teardown(a_file_moved_over_ours_is_left_alone, setup, teardown),
        cmocka_unit_test(refuses_what_is_not_its_database),
        cmocka_unit_test_setup_teardown(refuses_a_newer_schema, setup, teardown),
    };
    return cmocka_run_group_tests_name("store", tests, NULL, NULL);
}
