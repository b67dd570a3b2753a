/*
 * test_export_paper.h - the results databases the Planner Arena and OMPL
 * log export tests (tests/unit/interop/test_export_*.c) read: one written
 * through the store with every status and stage shape, small ones of
 * their own (mini_experiment), and the helpers that export them and read
 * the export back with SQLite. Include it after <cmocka.h>.
 */
#ifndef MPB_TEST_EXPORT_PAPER_H
#define MPB_TEST_EXPORT_PAPER_H

#include <math.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mpbench/mpbench.h"
#include "test_store.h"
#include "test_tool.h"

/*
 * Experiment 1, "paper": A = ompl/RRTConnect (range=0.5), B = ara/ARAstar
 * (eps=100); scenes KITCHEN (k1, k2) and TABLETOP (t1).
 */
enum { A, B };
enum { K1, K2, T1 };

typedef struct stage_spec {
    const char *name;
    double      time, length, smooth, clearance;   /* clearance < 0: none */
    int         waypoints, valid;
} stage_spec;

typedef struct run_spec {
    int         cfg, query, rep, done;
    const char *status;
    int         claimed, success;
    double      total, wall;
    int         num_stages;
    stage_spec  stages[3];
} run_spec;

static const run_spec runs[] = {
    /* 0: three stages, planner values, progress */
    {A, K1, 0, 1, "solved", 1, 1, 1.5, 1.0, 3, {
        {"raw", 0.5, 10.0, 0.4, 0.02, 11, 1},
        {"shortcut", 0.1, 6.0, 0.3, 0.03, 5, 1},
        {"smoothed", 0.2, 5.0, 0.1, 0.05, 50, 1}}},
    /* 1: approximate, one stage (first = final), invalid */
    {A, K1, 1, 1, "approximate", 0, 0, 2.0, 2.0, 1, {
        {"raw", 1.9, 3.0, 0.2, -1, 4, 0}}},
    /* 2: timeout, no stage */
    {A, K2, 0, 1, "timeout", 0, 0, 4.0, 4.0, 0, {{0}}},
    /* 3: failed */
    {B, K1, 0, 1, "failed", 0, 0, 0.5, 0.5, 0, {{0}}},
    /* 4: crash */
    {B, K2, 0, 1, "crash", 0, 0, NAN, 0.25, 0, {{0}}},
    /* 5: invalid request */
    {B, T1, 0, 1, "invalid_request", 0, 0, 0.0, 0.125, 0, {{0}}},
    /* 6: two stages, no shortcut */
    {A, T1, 0, 1, "solved", 1, 1, 7.0, 8.0, 2, {
        {"raw", 6.0, 9.0, 0.5, 0.1, 10, 1},
        {"smoothed", 0.5, 8.0, 0.2, 0.2, 20, 1}}},
    /* 7: not finished: never exported */
    {B, K1, 1, 0, NULL, 0, 0, 0, 0, 0, {{0}}},
};
#define NUM_RUNS ((int)(sizeof runs / sizeof runs[0]))

typedef struct fixture {
    char    dir[64];            /* first: test_store_teardown() */
    char    db[96];
    char    out[96];
    int64_t run_id[NUM_RUNS];
    int64_t cfg[2], query[3];
} fixture;

static inline void finish(mpb_store *s, int64_t run_id, const run_spec *r, int index)
{
    char attempt[32];
    snprintf(attempt, sizeof attempt, "attempt-%lld", (long long)run_id);
    assert_int_equal(mpb_store_run_sent(s, run_id, attempt, "planner-1"), MPB_OK);
    mpb_named m[3][5];
    mpb_stage_record st[3];
    for (int i = 0; i < r->num_stages; i++) {
        const stage_spec *sp = &r->stages[i];
        int n = 0;
        m[i][n++] = (mpb_named){"path_length", sp->length};
        m[i][n++] = (mpb_named){"smoothness", sp->smooth};
        m[i][n++] = (mpb_named){"waypoints", sp->waypoints};
        m[i][n++] = (mpb_named){"time", sp->time};
        if (sp->clearance >= 0)
            m[i][n++] = (mpb_named){"clearance", sp->clearance};
        st[i] = (mpb_stage_record){
            .name = sp->name, .time = sp->time,
            .num_waypoints = sp->waypoints, .num_joints = 0,
            .valid = sp->valid, .verdict = sp->valid ? "valid" : "collision",
            .verdict_segment = -1, .num_metrics = n, .metrics = m[i]};
    }
    /* Run 0's planner numbers: "solved" and "time" are taken by the
     * export's own properties and must come out renamed. */
    static const mpb_named values[] = {
        {"graph states", 24}, {"solved", 1}, {"time", 9}, {"cost(best)", 5}};
    /* Two samples of two values, a third of one. */
    static const mpb_progress_record progress[] = {
        {0.1, "best cost", 12.0}, {0.1, "iterations", 10},
        {0.2, "best cost", 11.0}, {0.2, "iterations", 20},
        {0.3, "iterations", 30},
    };
    mpb_run_record rec = {
        .run_id = run_id, .attempt_id = attempt, .planner_id = "planner-1",
        .status = r->status, .message = "", .claimed_success = r->claimed,
        .success = r->success, .time_total = r->total,
        .time_raw = r->total - 0.25, .time_other = 0.25,
        .wall_time = r->wall, .num_stages = r->num_stages, .stages = st,
        .num_values = index == 0 ? 4 : 0, .values = values,
        .num_progress = index == 0 ? 5 : 0, .progress = progress,
        .verify_time = index == 0 ? 0.125 : NAN,
        /* Run 0's planner peaked at 40.25 MB; the others said nothing. */
        .memory = index == 0 ? 40.25 : NAN,
    };
    assert_int_equal(mpb_store_run_finish(s, &rec), MPB_OK);
}

static inline int first_id(void *ud, const mpb_run_row *row)
{
    *(int64_t *)ud = row->id;
    return 1;
}

static inline int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    mpb_store *s;
    int64_t exp, scene[2];
    s = test_store_new(f->dir, sizeof f->dir, f->db, sizeof f->db, "export");
    snprintf(f->out, sizeof f->out, "%s/arena.db", f->dir);

    mpb_experiment_info e = {"paper", "paper.yaml", "h1",
                             "experiment: {name: paper}\n", 3, 60.0, NULL, 0};
    assert_int_equal(mpb_store_experiment_create(s, &e, &exp), MPB_OK);
    assert_int_equal(mpb_store_planner_config_add(s, exp, "ompl/RRTConnect",
                                                  "ompl", "RRTConnect",
                                                  "range=0.5", &f->cfg[A]),
                     MPB_OK);
    assert_int_equal(mpb_store_planner_config_add(s, exp, "ara/ARAstar", "ara",
                                                  "ARAstar", "eps=100",
                                                  &f->cfg[B]), MPB_OK);
    mpb_scene_info kitchen = {"KITCHEN", "planar", "r", "r", "planar", "k", "k"};
    mpb_scene_info table = {"TABLE TOP", "planar", "r", "r", "planar", "t", "t"};
    assert_int_equal(mpb_store_scene_add(s, exp, &kitchen, &scene[0]), MPB_OK);
    assert_int_equal(mpb_store_scene_add(s, exp, &table, &scene[1]), MPB_OK);
    const char *qname[] = {"k1", "k2", "t1"};
    for (int i = 0; i < 3; i++)
        f->query[i] = test_store_query(s, scene[i == T1], qname[i]);
    for (int i = 0; i < NUM_RUNS; i++)
        f->run_id[i] = test_store_run(s, exp, f->cfg[runs[i].cfg],
                                      f->query[runs[i].query], runs[i].rep, i);
    for (int i = 0; i < NUM_RUNS; i++)
        if (runs[i].done)
            finish(s, f->run_id[i], &runs[i], i);

    /* Experiment 2, "second": the same configuration A, one run. */
    int64_t exp2, cfg2, scene2, query2, run2 = 0;
    mpb_experiment_info e2 = {"second", "second.yaml", "h2", "x", 1, 10.0, NULL, 0};
    assert_int_equal(mpb_store_experiment_create(s, &e2, &exp2), MPB_OK);
    assert_int_equal(mpb_store_planner_config_add(s, exp2, "ompl/RRTConnect",
                                                  "ompl", "RRTConnect",
                                                  "range=0.5", &cfg2), MPB_OK);
    assert_int_equal(mpb_store_scene_add(s, exp2, &kitchen, &scene2), MPB_OK);
    query2 = test_store_query(s, scene2, "k9");
    run2 = test_store_run(s, exp2, cfg2, query2, 0, 1);
    run_spec r2 = {A, 0, 0, 1, "solved", 1, 1, 0.75, 1.0, 1,
                   {{"raw", 0.7, 2.0, 0.0, -1, 2, 1}}};
    finish(s, run2, &r2, 1);
    mpb_store_close(s);
    *state = f;
    return 0;
}

/* Export experiment ids (all when n == 0) to a fresh f->out. */
static inline void export_fresh(fixture *f, const int64_t *ids, int n,
                         mpb_export_counts *counts)
{
    mpb_store *s;
    unlink(f->out);
    assert_int_equal(mpb_store_open(f->db, 1, &s), MPB_OK);
    int rc = mpb_store_export_planner_arena(s, f->out, ids, n, 0, counts);
    if (rc != MPB_OK)
        fprintf(stderr, "export: %s\n", mpb_store_errmsg(s));
    assert_int_equal(rc, MPB_OK);
    mpb_store_close(s);
}

/* ---- small stores of their own ------------------------------------------------ */

/* A query of mini_experiment(): its scene (an index into the scene
 * names), its name, and a pose region (12 numbers) or NULL for a joint
 * goal. */
typedef struct mini_query {
    int           scene;
    const char   *name;
    const double *region;
} mini_query;

/*
 * Add experiment name to the store at path (made if missing): its scenes,
 * its queries, one configuration (null/straight_line) and num_runs finished
 * runs per query, each with the stages of OMPL's planner (raw, shortcut,
 * smoothed) and every metric the daemon stores (daemon/record.c). Its id
 * into *id.
 */
static inline void mini_experiment(const char *path, const char *name,
                            const char *const *scenes, int num_scenes,
                            const mini_query *queries, int num_queries,
                            int num_runs, int64_t *id)
{
    static const char *const joints[] = {"j"};
    static const double zero[] = {0.0}, one[] = {1.0};
    static const mpb_named metrics[] = {
        {"time", 0.5}, {"waypoints", 3}, {"path_length", 1.0},
        {"smoothness", 0.25}, {"clearance", 0.125}, {"min_clearance", 0.0625},
        {"ee_path_length", 2.0}};
    mpb_store *s;
    int64_t cfg, scene_id[8];
    assert_true(num_scenes <= 8);
    assert_int_equal(mpb_store_open(path, 0, &s), MPB_OK);
    mpb_experiment_info e = {name, "mini.yaml", "h", "x", num_runs, 1.0, NULL, 0};
    assert_int_equal(mpb_store_experiment_create(s, &e, id), MPB_OK);
    assert_int_equal(mpb_store_planner_config_add(s, *id, "null/straight_line",
                                                  "null", "straight_line", "",
                                                  &cfg), MPB_OK);
    for (int i = 0; i < num_scenes; i++) {
        mpb_scene_info sc = {scenes[i], "planar", "r", "r", "planar", "s",
                             "s"};
        assert_int_equal(mpb_store_scene_add(s, *id, &sc, &scene_id[i]),
                         MPB_OK);
    }
    for (int i = 0; i < num_queries; i++) {
        const mini_query *mq = &queries[i];
        mpb_query_info q = {mq->name, 1, joints, zero,
                            mq->region ? MPB_GOAL_POSE_REGION
                                       : MPB_GOAL_JOINTS,
                            mq->region ? NULL : one, 0.001,
                            mq->region ? "tool" : NULL, mq->region};
        int64_t query_id;
        assert_int_equal(mpb_store_query_add(s, scene_id[mq->scene], &q,
                                             &query_id), MPB_OK);
        for (int rep = 0; rep < num_runs; rep++) {
            int64_t run_id = 0;
            char attempt[32];
            assert_int_equal(mpb_store_run_add(s, *id, cfg, query_id, rep,
                                               rep), MPB_OK);
            assert_int_equal(mpb_store_runs_unfinished(s, *id, first_id,
                                                       &run_id), 1);
            snprintf(attempt, sizeof attempt, "attempt-%lld", (long long)run_id);
            assert_int_equal(mpb_store_run_sent(s, run_id, attempt, "p"),
                             MPB_OK);
            static const char *const stages[] = {"raw", "shortcut",
                                                 "smoothed"};
            mpb_stage_record st[3];
            for (int k = 0; k < 3; k++)
                st[k] = (mpb_stage_record){
                    .name = stages[k], .time = 0.5, .num_waypoints = 3,
                    .valid = 1, .verdict = "valid", .verdict_segment = -1,
                    .num_metrics = (int)(sizeof metrics / sizeof metrics[0]),
                    .metrics = metrics};
            mpb_run_record rec = {
                .run_id = run_id, .attempt_id = attempt, .planner_id = "p",
                .status = "solved", .message = "", .claimed_success = 1,
                .success = 1, .time_total = 1.5, .time_raw = 1.5,
                .wall_time = 2.0, .num_stages = 3, .stages = st};
            assert_int_equal(mpb_store_run_finish(s, &rec), MPB_OK);
        }
    }
    mpb_store_close(s);
}

/* Export the store at path for Planner Arena into a new f->out, or with
 * MPB_EXPORT_APPEND into the one there. */
static inline void export_store(fixture *f, const char *path, int flags,
                         mpb_export_counts *counts)
{
    mpb_store *s;
    if (!(flags & MPB_EXPORT_APPEND))
        unlink(f->out);
    assert_int_equal(mpb_store_open(path, 1, &s), MPB_OK);
    int rc = mpb_store_export_planner_arena(s, f->out, NULL, 0, flags,
                                            counts);
    if (rc != MPB_OK)
        fprintf(stderr, "export: %s\n", mpb_store_errmsg(s));
    assert_int_equal(rc, MPB_OK);
    mpb_store_close(s);
}

/* ---- reading the export back ------------------------------------------------ */

static inline sqlite3 *open_out(const fixture *f)
{
    sqlite3 *db;
    assert_int_equal(sqlite3_open_v2(f->out, &db, SQLITE_OPEN_READONLY, NULL),
                     SQLITE_OK);
    return db;
}

/* The rows of sql, columns joined by '|', rows by '\n' (NULL as ""). */
static inline const char *rows(sqlite3 *db, const char *sql)
{
    static char buf[8192];
    sqlite3_stmt *st;
    size_t len = 0;
    buf[0] = '\0';
    if (sqlite3_prepare_v2(db, sql, -1, &st, NULL) != SQLITE_OK) {
        fprintf(stderr, "%s: %s\n", sql, sqlite3_errmsg(db));
        fail();
    }
    while (sqlite3_step(st) == SQLITE_ROW) {
        for (int i = 0; i < sqlite3_column_count(st); i++) {
            const char *t = (const char *)sqlite3_column_text(st, i);
            len += (size_t)snprintf(buf + len, sizeof buf - len, "%s%s",
                                    i ? "|" : "", t ? t : "");
        }
        len += (size_t)snprintf(buf + len, sizeof buf - len, "\n");
    }
    sqlite3_finalize(st);
    return buf;
}

/* The column names of a table, joined by ' '; with their types if typed. */
static inline const char *columns(sqlite3 *db, const char *table, int typed)
{
    char sql[128];
    static char buf[4096];
    snprintf(sql, sizeof sql, "SELECT name%s FROM pragma_table_info('%s')",
             typed ? " || ':' || type" : "", table);
    const char *r = rows(db, sql);
    snprintf(buf, sizeof buf, "%s", r);
    for (char *p = buf; *p; p++)
        if (*p == '\n')
            *p = p[1] ? ' ' : '\0';
    return buf;
}

static inline double number(sqlite3 *db, const char *sql)
{
    sqlite3_stmt *st;
    assert_int_equal(sqlite3_prepare_v2(db, sql, -1, &st, NULL), SQLITE_OK);
    assert_int_equal(sqlite3_step(st), SQLITE_ROW);
    double v = sqlite3_column_type(st, 0) == SQLITE_NULL
                   ? NAN : sqlite3_column_double(st, 0);
    sqlite3_finalize(st);
    return v;
}

/* A file's text (the first 64 KiB), until the next call. */
static inline char *slurp(const char *path)
{
    FILE *in = fopen(path, "r");
    assert_non_null(in);
    static char buf[65536];
    size_t n = fread(buf, 1, sizeof buf - 1, in);
    buf[n] = '\0';
    fclose(in);
    return buf;
}


#endif
