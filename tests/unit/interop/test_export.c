/* test_export.c - the Planner Arena export (store_export.c, `mpb export`):
 * a database written through the store, exported, and read back with
 * SQLite as Planner Arena and OMPL's script read it: the tables, their
 * columns and order, the status enum, booleans as 0/1, values worked out
 * by hand, appending, and failures that leave nothing behind. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <dirent.h>
#include <glob.h>
#include <libgen.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>
#include <sqlite3.h>

#include "mpbench/mpbench.h"

static char mpb_tool[4096];     /* the built mpb */

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
    char    dir[64];
    char    db[96];
    char    out[96];
    int64_t run_id[NUM_RUNS];
    int64_t cfg[2], query[3];
} fixture;

static int find_ids(void *ud, const mpb_run_row *row)
{
    fixture *f = ud;
    for (int i = 0; i < NUM_RUNS; i++)
        if (f->cfg[runs[i].cfg] == row->planner_config_id &&
            f->query[runs[i].query] == row->query_id &&
            runs[i].rep == row->repetition)
            f->run_id[i] = row->id;
    return 0;
}

static void finish(mpb_store *s, int64_t run_id, const run_spec *r, int index)
{
    char uid[32];
    snprintf(uid, sizeof uid, "uid-%lld", (long long)run_id);
    assert_int_equal(mpb_store_run_sent(s, run_id, uid, "planner-1"), MPB_OK);
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
        .run_id = run_id, .run_uid = uid, .planner_id = "planner-1",
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

static int first_id(void *ud, const mpb_run_row *row)
{
    *(int64_t *)ud = row->id;
    return 1;
}

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    mpb_store *s;
    int64_t exp, scene[2];
    strcpy(f->dir, "/tmp/mpb_test_export_XXXXXX");
    assert_non_null(mkdtemp(f->dir));
    snprintf(f->db, sizeof f->db, "%s/results.db", f->dir);
    snprintf(f->out, sizeof f->out, "%s/arena.db", f->dir);
    assert_int_equal(mpb_store_open(f->db, 0, &s), MPB_OK);

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
    static const char *const joints[] = {"j"};
    static const double zero[] = {0.0}, one[] = {1.0};
    const char *qname[] = {"k1", "k2", "t1"};
    for (int i = 0; i < 3; i++) {
        mpb_query_info q = {qname[i], 1, joints, zero, MPB_GOAL_JOINTS, one,
                            0.01, NULL, NULL};
        assert_int_equal(mpb_store_query_add(s, scene[i == T1], &q,
                                             &f->query[i]), MPB_OK);
    }
    for (int i = 0; i < NUM_RUNS; i++)
        assert_int_equal(mpb_store_run_add(s, exp, f->cfg[runs[i].cfg],
                                           f->query[runs[i].query],
                                           runs[i].rep, i), MPB_OK);
    assert_int_equal(mpb_store_runs_unfinished(s, exp, find_ids, f), MPB_OK);
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
    mpb_query_info q2 = {"k9", 1, joints, zero, MPB_GOAL_JOINTS, one, 0.01,
                         NULL, NULL};
    assert_int_equal(mpb_store_query_add(s, scene2, &q2, &query2), MPB_OK);
    assert_int_equal(mpb_store_run_add(s, exp2, cfg2, query2, 0, 1), MPB_OK);
    assert_int_equal(mpb_store_runs_unfinished(s, exp2, first_id, &run2), 1);
    run_spec r2 = {A, 0, 0, 1, "solved", 1, 1, 0.75, 1.0, 1,
                   {{"raw", 0.7, 2.0, 0.0, -1, 2, 1}}};
    finish(s, run2, &r2, 1);
    mpb_store_close(s);
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    char cmd[256];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", f->dir);
    assert_int_equal(system(cmd), 0);
    free(f);
    return 0;
}

/* Export experiment ids (all when n == 0) to a fresh f->out. */
static void export_fresh(fixture *f, const int64_t *ids, int n,
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
 * smoothed) and every metric the daemon stores (daemon/results.c). Its id
 * into *id.
 */
static void mini_experiment(const char *path, const char *name,
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
            char uid[32];
            assert_int_equal(mpb_store_run_add(s, *id, cfg, query_id, rep,
                                               rep), MPB_OK);
            assert_int_equal(mpb_store_runs_unfinished(s, *id, first_id,
                                                       &run_id), 1);
            snprintf(uid, sizeof uid, "uid-%lld", (long long)run_id);
            assert_int_equal(mpb_store_run_sent(s, run_id, uid, "p"),
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
                .run_id = run_id, .run_uid = uid, .planner_id = "p",
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
static void export_store(fixture *f, const char *path, int flags,
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

static sqlite3 *open_out(const fixture *f)
{
    sqlite3 *db;
    assert_int_equal(sqlite3_open_v2(f->out, &db, SQLITE_OPEN_READONLY, NULL),
                     SQLITE_OK);
    return db;
}

/* The rows of sql, columns joined by '|', rows by '\n' (NULL as ""). */
static const char *rows(sqlite3 *db, const char *sql)
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
static const char *columns(sqlite3 *db, const char *table, int typed)
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

static double number(sqlite3 *db, const char *sql)
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
static char *slurp(const char *path)
{
    FILE *in = fopen(path, "r");
    assert_non_null(in);
    static char buf[65536];
    size_t n = fread(buf, 1, sizeof buf - 1, in);
    buf[n] = '\0';
    fclose(in);
    return buf;
}

/* ---- the tests ------------------------------------------------------------ */

static void experiments_keep_planner_arenas_twelve_columns(void **state)
{
    fixture *f = *state;
    int64_t one = 1;
    mpb_export_counts c;
    export_fresh(f, &one, 1, &c);
    /* k1, k2 and t1 have finished runs: three Planner Arena experiments;
     * 7 finished runs; both configurations; the 2 kept samples of run 0. */
    assert_int_equal(c.experiments, 3);
    assert_int_equal(c.runs, 7);
    assert_int_equal(c.planner_configs, 2);
    assert_int_equal(c.progress, 3);

    sqlite3 *db = open_out(f);
    assert_string_equal(columns(db, "experiments", 0),
        "id name totaltime timelimit memorylimit runcount version hostname "
        "cpuinfo date seed setup query mpbench_experiment");
    /* One per query, named by experiment and scene (one word), the query
     * a parameter; totaltime the runs' wall time; version never empty. */
    assert_string_equal(rows(db,
        "SELECT id, name, totaltime, timelimit, memorylimit IS NULL, runcount,"
        " version, length(hostname) > 0, cpuinfo IS NULL, seed IS NULL, query,"
        " mpbench_experiment FROM experiments ORDER BY id"),
        "1|paper/KITCHEN|3.5|60.0|1|3|mpbench " MPB_VERSION_STRING
        "|1|1|1|k1|1\n"
        "2|paper/KITCHEN|4.25|60.0|1|3|mpbench " MPB_VERSION_STRING
        "|1|1|1|k2|1\n"
        "3|paper/TABLE_TOP|8.125|60.0|1|3|mpbench " MPB_VERSION_STRING
        "|1|1|1|t1|1\n");
    /* A date SQLite reads; the setup holds the experiment file and query. */
    assert_true(number(db, "SELECT count(*) FROM experiments"
                           " WHERE julianday(date) IS NOT NULL") == 3);
    assert_string_equal(rows(db, "SELECT setup FROM experiments WHERE id = 2"),
        "experiment: {name: paper}\n\n"
        "mpbench experiment 1, query k2\n"
        "joints: j\nstart: 0\ngoal (joints): 1\ntolerance: 0.01\n\n");
    sqlite3_close(db);
}

static void setup_shows_a_pose_regions_goal(void **state)
{
    fixture *f = *state;
    static const double region[12] = {0.5, -0.25, 1, 0.125, 0.125, 0.125,
                                      0, 1.5, 0, 0.0625, 0.0625, 3.5};
    static const char *const scenes[] = {"shelf"};
    static const mini_query queries[] = {{0, "reach", region},
                                         {0, "home", NULL}};
    char path[128], dir[128], log[256];
    int64_t exp;
    snprintf(path, sizeof path, "%s/region.db", f->dir);
    mini_experiment(path, "pr", scenes, 1, queries, 2, 1, &exp);

    /* The region as the experiment file gives it, the tolerance the
     * start's; a joint goal as before. */
static const char reach[] =
        "x\n\n"
        "mpbench experiment 1, query reach\n"
        "joints: j\nstart: 0\n"
        "goal (pose_region): link tool\n"
        "  position: 0.5 -0.25 1\n"
        "  position_tolerance: 0.125 0.125 0.125\n"
        "  rpy: 0 1.5 0\n"
        "  rpy_tolerance: 0.0625 0.0625 3.5\n"
        "start tolerance: 0.001\n";
    char want[512];
    export_store(f, path, 0, NULL);
    sqlite3 *db = open_out(f);
    snprintf(want, sizeof want, "%s\n", reach);
    assert_string_equal(rows(db, "SELECT setup FROM experiments"
                                 " WHERE query = 'reach'"), want);
    assert_string_equal(rows(db, "SELECT setup FROM experiments"
                                 " WHERE query = 'home'"),
        "x\n\nmpbench experiment 1, query home\n"
        "joints: j\nstart: 0\ngoal (joints): 1\ntolerance: 0.001\n\n");
    sqlite3_close(db);

    /* The log's setup block says the same. */
    mpb_store *s;
    snprintf(dir, sizeof dir, "%s/region-logs", f->dir);
    assert_int_equal(mpb_store_open(path, 1, &s), MPB_OK);
    assert_int_equal(mpb_store_export_ompl_logs(s, dir, NULL, 0, 0, NULL),
                     MPB_OK);
    mpb_store_close(s);
    snprintf(log, sizeof log, "%s/pr.1.shelf.reach.log", dir);
    snprintf(want, sizeof want, "\n<<<|\n%s|>>>\n", reach);
    assert_non_null(strstr(slurp(log), want));
}

static void planner_configs_and_the_status_enum(void **state)
{
    fixture *f = *state;
    int64_t one = 1;
    export_fresh(f, &one, 1, NULL);
    sqlite3 *db = open_out(f);
    assert_string_equal(columns(db, "plannerConfigs", 0), "id name settings");
    /* Settings as OMPL's script keeps a log's sorted "name = value" lines:
     * each followed by "\n;". */
    assert_string_equal(rows(db, "SELECT id, name, replace(settings, char(10),"
                                 " '/') FROM plannerConfigs ORDER BY id"),
        "1|ompl/RRTConnect|algorithm = RRTConnect/;planner = ompl/;"
        "range = 0.5/;\n"
        "2|ara/ARAstar|algorithm = ARAstar/;eps = 100/;planner = ara/;\n");
    assert_string_equal(columns(db, "enums", 0), "name value description");
    assert_string_equal(rows(db, "SELECT name, value, description FROM enums"
                                 " ORDER BY value"),
        "status|0|Unknown status\n"
        "status|1|Invalid start\n"
        "status|2|Invalid goal\n"
        "status|3|Unrecognized goal type\n"
        "status|4|Timeout\n"
        "status|5|Approximate solution\n"
        "status|6|Exact solution\n"
        "status|7|Crash\n"
        "status|8|Abort\n"
        "status|9|Infeasible\n"
        "status|10|Invalid request\n"
        "status|11|Out of memory\n");
    sqlite3_close(db);
}

static void runs_carry_attributes_from_the_fourth_column(void **state)
{
    fixture *f = *state;
    int64_t one = 1;
    export_fresh(f, &one, 1, NULL);
    sqlite3 *db = open_out(f);
    assert_string_equal(columns(db, "runs", 1),
        "id:INTEGER experimentid:INTEGER plannerid:INTEGER "
        "time:REAL time_raw:REAL time_other:REAL wall_time:REAL "
        "verify_time:REAL memory:REAL solved:BOOLEAN claimed_success:BOOLEAN approximate_solution:BOOLEAN "
        "status:ENUM "
        "solution_time:REAL solution_length:REAL solution_smoothness:REAL "
        "solution_clearance:REAL solution_segments:INTEGER "
        "correct_solution:BOOLEAN "
        "shortcut_solution_time:REAL shortcut_solution_length:REAL "
        "shortcut_solution_smoothness:REAL shortcut_solution_clearance:REAL "
        "shortcut_solution_segments:INTEGER shortcut_correct_solution:BOOLEAN "
        "simplified_solution_time:REAL simplified_solution_length:REAL "
        "simplified_solution_smoothness:REAL "
        "simplified_solution_clearance:REAL "
        "simplified_solution_segments:INTEGER "
        "simplified_correct_solution:BOOLEAN "
        "cost_best:REAL graph_states:REAL planner_solved:REAL "
        "planner_time:REAL");
    /* Every "X" with a "simplified X" beside it: Planner Arena's overlay. */
    assert_true(number(db,
        "SELECT count(*) FROM pragma_table_info('runs') a"
        " JOIN pragma_table_info('runs') b ON b.name = 'simplified_' || a.name"
        ) == 6);
    sqlite3_close(db);
}

static void the_doc_lists_every_runs_attribute(void **state)
{
    fixture *f = *state;
    static const char *const scenes[] = {"s"};
    static const mini_query queries[] = {{0, "q", NULL}};
    char path[128];
    int64_t exp;
    snprintf(path, sizeof path, "%s/doc.db", f->dir);
    mini_experiment(path, "doc", scenes, 1, queries, 1, 1, &exp);
    export_store(f, path, 0, NULL);

    /* docs/planner-arena.md's runs table: from "### runs" to the next
     * heading. */
    char *doc = slurp(MPB_SOURCE_DIR "/docs/planner-arena.md");
    char *table = strstr(doc, "\n### runs\n");
    assert_non_null(table);
    char *end = strstr(table + 1, "\n###");
    assert_non_null(end);
    *end = '\0';

    /* Every attribute (the fourth column on: no planner numbers here) in
     * it, by its name in a log. */
    sqlite3 *db = open_out(f);
    sqlite3_stmt *st;
    assert_int_equal(sqlite3_prepare_v2(db, "SELECT name FROM"
                                        " pragma_table_info('runs')"
                                        " WHERE cid >= 3", -1, &st, NULL),
                     SQLITE_OK);
    int n = 0;
    while (sqlite3_step(st) == SQLITE_ROW) {
        char want[128];
        snprintf(want, sizeof want, "`%s`", sqlite3_column_text(st, 0));
        for (char *p = want; *p; p++)
            if (*p == '_')
                *p = ' ';
        if (strstr(table, want) == NULL)
            fprintf(stderr, "docs/planner-arena.md: no %s\n", want);
        n += strstr(table, want) == NULL;
    }
    sqlite3_finalize(st);
    sqlite3_close(db);
    assert_int_equal(n, 0);
}

static void booleans_are_0_or_1_and_status_is_the_enum(void **state)
{
    fixture *f = *state;
    int64_t one = 1;
    export_fresh(f, &one, 1, NULL);
    sqlite3 *db = open_out(f);
    static const char *const booleans[] = {
        "solved", "claimed_success", "approximate_solution",
        "correct_solution", "simplified_correct_solution",
        "shortcut_correct_solution"};
    for (size_t i = 0; i < sizeof booleans / sizeof booleans[0]; i++) {
        char sql[256];
        snprintf(sql, sizeof sql, "SELECT count(*) FROM runs WHERE %s IS NOT"
                 " NULL AND (typeof(%s) != 'integer' OR %s NOT IN (0, 1))",
                 booleans[i], booleans[i], booleans[i]);
        assert_true(number(db, sql) == 0);
    }
    /* One row per finished run, in the order of the runs above; the
     * statuses mapped onto the enum, every enum value described. */
    assert_string_equal(rows(db,
        "SELECT e.query, p.name, r.status, r.solved, r.claimed_success,"
        " r.approximate_solution FROM runs r JOIN experiments e"
        " ON e.id = r.experimentid JOIN plannerConfigs p ON p.id = r.plannerid"
        " ORDER BY r.id"),
        "k1|ompl/RRTConnect|6|1|1|0\n"      /* solved */
        "k1|ompl/RRTConnect|5|0|0|1\n"      /* approximate */
        "k1|ara/ARAstar|8|0|0|0\n"          /* failed: Abort */
        "k2|ompl/RRTConnect|4|0|0|0\n"      /* timeout */
        "k2|ara/ARAstar|7|0|0|0\n"          /* crash */
        "t1|ompl/RRTConnect|6|1|1|0\n"
        "t1|ara/ARAstar|10|0|0|0\n");       /* invalid request */
    assert_true(number(db, "SELECT count(*) FROM runs r LEFT JOIN enums e"
                           " ON e.name = 'status' AND e.value = r.status"
                           " WHERE e.description IS NULL") == 0);
    sqlite3_close(db);
}

static void stage_values_by_hand(void **state)
{
    fixture *f = *state;
    int64_t one = 1;
    export_fresh(f, &one, 1, NULL);
    sqlite3 *db = open_out(f);
    /* Run 0: raw (0.5 s, l 10, 11 waypoints), shortcut (l 6, 5),
     * smoothed (l 5, 50 waypoints, clearance 0.05); times 1.5 = 1.25 +
     * 0.25; wall 1.0; verified in 0.125 s; the planner's numbers. */
    assert_string_equal(rows(db,
        "SELECT time, time_raw, time_other, wall_time, solution_time,"
        " solution_length, solution_smoothness, solution_clearance,"
        " solution_segments, correct_solution, shortcut_solution_time,"
        " shortcut_solution_length, shortcut_solution_segments,"
        " simplified_solution_time, simplified_solution_length,"
        " simplified_solution_smoothness, simplified_solution_clearance,"
        " simplified_solution_segments, simplified_correct_solution,"
        " graph_states, planner_solved, planner_time, cost_best, verify_time,"
        " memory FROM runs WHERE id = 1"),
        "1.5|1.25|0.25|1.0|0.5|10.0|0.4|0.02|10|1|0.1|6.0|4|"
        "0.2|5.0|0.1|0.05|49|1|24.0|1.0|9.0|5.0|0.125|40.25\n");
    /* Run 1: one stage, invalid, no clearance: first and final alike. */
    assert_string_equal(rows(db,
        "SELECT solution_length, simplified_solution_length,"
        " solution_segments, correct_solution, simplified_correct_solution,"
        " solution_clearance IS NULL, shortcut_solution_length IS NULL,"
        " graph_states IS NULL FROM runs WHERE id = 2"),
        "3.0|3.0|3|0|0|1|1|1\n");
    /* No stage (timeout), no time (crash): NULLs, not zeros. */
    assert_string_equal(rows(db,
        "SELECT id, time IS NULL, solution_length IS NULL,"
        " simplified_correct_solution IS NULL FROM runs WHERE id IN (4, 5)"
        " ORDER BY id"),
        "4|0|1|1\n5|1|1|1\n");
    /* Run 6 (t1): raw and smoothed, no shortcut. */
    assert_string_equal(rows(db,
        "SELECT solution_length, shortcut_solution_length IS NULL,"
        " simplified_solution_length, simplified_solution_segments"
        " FROM runs WHERE id = 6"),
        "9.0|1|8.0|19\n");
    sqlite3_close(db);
}

static void progress_samples_and_the_views(void **state)
{
    fixture *f = *state;
    int64_t one = 1;
    export_fresh(f, &one, 1, NULL);
    sqlite3 *db = open_out(f);
    /* runid, time, then the attributes; one row per sample. */
    assert_string_equal(columns(db, "progress", 0),
                        "runid time best_cost iterations");
    assert_string_equal(rows(db, "SELECT * FROM progress ORDER BY time"),
                        "1|0.1|12.0|10.0\n1|0.2|11.0|20.0\n1|0.3||30.0\n");
    /* OMPL's views: by average solved, then average time. A solved 2 of
     * 4 (times 1.5, 2, 4, 7: 3.625), B 0 of 3. */
    assert_string_equal(rows(db, "SELECT plannerid, avg_solved,"
                                 " avg_total_time FROM bestPlannerConfigs"),
                        "1|0.5|3.625\n2|0.0|0.25\n");
    assert_string_equal(rows(db,
        "SELECT plannerid, experimentid, avg_solved"
        " FROM bestPlannerConfigsPerExperiment ORDER BY experimentid,"
        " plannerid"),
        "1|1|0.5\n2|1|0.0\n1|2|0.0\n2|2|0.0\n1|3|1.0\n2|3|0.0\n");
    sqlite3_close(db);
}

static void append_adds_and_reuses_configurations(void **state)
{
    fixture *f = *state;
    int64_t one = 1, two = 2;
    mpb_store *s;
    mpb_export_counts c;
    export_fresh(f, &one, 1, NULL);

    assert_int_equal(mpb_store_open(f->db, 1, &s), MPB_OK);
    /* Without the flag an existing file is left alone. */
    assert_int_equal(mpb_store_export_planner_arena(s, f->out, &two, 1, 0, &c),
                     MPB_EEXISTS);
    assert_non_null(strstr(mpb_store_errmsg(s), "exists"));
    assert_int_equal(mpb_store_export_planner_arena(s, f->out, &two, 1,
                                                    MPB_EXPORT_APPEND, &c),
                     MPB_OK);
    mpb_store_close(s);
    /* Its one query, its one run; A has the same name and settings: no new
     * configuration. */
    assert_int_equal(c.experiments, 1);
    assert_int_equal(c.runs, 1);
    assert_int_equal(c.planner_configs, 0);
    sqlite3 *db = open_out(f);
    assert_string_equal(rows(db, "SELECT count(*) FROM plannerConfigs"), "2\n");
    assert_string_equal(rows(db, "SELECT e.name, e.query, r.plannerid,"
                                 " r.solution_length FROM runs r JOIN"
                                 " experiments e ON e.id = r.experimentid"
                                 " WHERE e.mpbench_experiment = 2"),
                        "second/KITCHEN|k9|1|2.0\n");
    assert_string_equal(rows(db, "SELECT count(*) FROM runs"), "8\n");
    sqlite3_close(db);

    /* The same again adds nothing: each query is there already. */
    int64_t both[] = {1, 2, 1};
    assert_int_equal(mpb_store_open(f->db, 1, &s), MPB_OK);
    assert_int_equal(mpb_store_export_planner_arena(s, f->out, both, 3,
                                                    MPB_EXPORT_APPEND, &c),
                     MPB_OK);
    mpb_store_close(s);
    assert_int_equal(c.experiments, 0);
    assert_int_equal(c.runs, 0);
    assert_int_equal(c.skipped, 4);
    db = open_out(f);
    assert_string_equal(rows(db, "SELECT count(*) FROM experiments"), "4\n");
    assert_string_equal(rows(db, "SELECT count(*) FROM runs"), "8\n");
    sqlite3_close(db);

    /* Everything at once gives the same; an id twice counts once. */
    export_fresh(f, NULL, 0, &c);
    assert_int_equal(c.experiments, 4);
    assert_int_equal(c.runs, 8);
    export_fresh(f, both, 3, &c);
    assert_int_equal(c.experiments, 4);
    assert_int_equal(c.runs, 8);
    assert_int_equal(c.skipped, 0);
}

static void scenes_of_one_word_name_stay_apart(void **state)
{
    fixture *f = *state;
    /* "a b" and "a_b" are one word alike, and a scene may be called what
     * a told-apart name would be. */
    static const char *const scenes[] = {"a b", "a_b", "a_b#1"};
    static const mini_query queries[] = {{0, "q 1", NULL}, {0, "q_1", NULL},
                                         {1, "q 1", NULL}, {2, "q 1", NULL}};
    char path[128];
    int64_t exp;
    mpb_export_counts c;
    snprintf(path, sizeof path, "%s/clash.db", f->dir);
    mini_experiment(path, "clash", scenes, 3, queries, 4, 2, &exp);

    /* Into a new file every query goes, its runs with it, each scene
     * under a name of its own (#N: its place in the experiment). */
    export_store(f, path, 0, &c);
    assert_int_equal(c.experiments, 4);
    assert_int_equal(c.runs, 8);
    assert_int_equal(c.skipped, 0);
    sqlite3 *db = open_out(f);
    assert_string_equal(rows(db, "SELECT e.name, e.query, count(r.id)"
                                 " FROM experiments e JOIN runs r"
                                 " ON r.experimentid = e.id"
                                 " GROUP BY e.id ORDER BY e.id"),
                        "clash/a_b#1#1|q 1|2\n"
                        "clash/a_b#1#1|q_1|2\n"
                        "clash/a_b#2|q 1|2\n"
                        "clash/a_b#1#3|q 1|2\n");
    sqlite3_close(db);

    /* Appended again, each is found there, none for another. */
    export_store(f, path, MPB_EXPORT_APPEND, &c);
    assert_int_equal(c.experiments, 0);
    assert_int_equal(c.runs, 0);
    assert_int_equal(c.skipped, 4);
}

static void one_export_skips_only_what_was_there(void **state)
{
    fixture *f = *state;
    static const char *const scenes[] = {"s"};
    static const mini_query queries[] = {{0, "q", NULL}};
    char path[128];
    int64_t exp[2];
    mpb_export_counts c;
    snprintf(path, sizeof path, "%s/twice.db", f->dir);
    /* Two experiments of one name, host, run count and start second:
     * alike to a query of the file, but not the same. */
    mini_experiment(path, "twice", scenes, 1, queries, 1, 1, &exp[0]);
    mini_experiment(path, "twice", scenes, 1, queries, 1, 1, &exp[1]);
    sqlite3 *db;
    assert_int_equal(sqlite3_open(path, &db), SQLITE_OK);
    assert_int_equal(sqlite3_exec(db, "UPDATE experiments SET"
                                  " created = 1700000000", NULL, NULL, NULL),
                     SQLITE_OK);
    sqlite3_close(db);

    export_store(f, path, 0, &c);
    assert_int_equal(c.experiments, 2);
    assert_int_equal(c.runs, 2);
    assert_int_equal(c.skipped, 0);
    db = open_out(f);
    assert_string_equal(rows(db, "SELECT name, query, mpbench_experiment"
                                 " FROM experiments ORDER BY id"),
                        "twice/s|q|1\ntwice/s|q|2\n");
    sqlite3_close(db);
    export_store(f, path, MPB_EXPORT_APPEND, &c);
    assert_int_equal(c.experiments, 0);
    assert_int_equal(c.skipped, 2);
}

static void append_refuses_other_databases(void **state)
{
    fixture *f = *state;
    mpb_store *s;
    sqlite3 *db;
    unlink(f->out);
    assert_int_equal(sqlite3_open(f->out, &db), SQLITE_OK);
    assert_int_equal(sqlite3_exec(db, "CREATE TABLE x (a); INSERT INTO x"
                                  " VALUES (1)", NULL, NULL, NULL), SQLITE_OK);
    sqlite3_close(db);
    assert_int_equal(mpb_store_open(f->db, 1, &s), MPB_OK);
    assert_int_equal(mpb_store_export_planner_arena(s, f->out, NULL, 0,
                                                    MPB_EXPORT_APPEND, NULL),
                     MPB_EINVAL);
    char want[160];
    snprintf(want, sizeof want, "%s is no Planner Arena database (no table "
             "experiments)", f->out);
    assert_string_equal(mpb_store_errmsg(s), want);
    mpb_store_close(s);
    db = open_out(f);
    assert_string_equal(rows(db, "SELECT group_concat(name) FROM"
                                 " sqlite_master"), "x\n");
    sqlite3_close(db);
    unlink(f->out);
}

static void failures_leave_nothing_behind(void **state)
{
    fixture *f = *state;
    int64_t nine = 9;
    mpb_store *s;
    struct stat sb;
    unlink(f->out);
    assert_int_equal(mpb_store_open(f->db, 1, &s), MPB_OK);
    assert_int_equal(mpb_store_export_planner_arena(s, f->out, &nine, 1, 0,
                                                    NULL), MPB_ENOTFOUND);
    assert_string_equal(mpb_store_errmsg(s), "no experiment 9");
    assert_int_equal(stat(f->out, &sb), -1);
    char bad[160];
    snprintf(bad, sizeof bad, "%s/no/such/dir/out.db", f->dir);
    assert_int_not_equal(mpb_store_export_planner_arena(s, bad, NULL, 0, 0,
                                                        NULL), MPB_OK);
    mpb_store_close(s);
}

/* ---- OMPL logs ------------------------------------------------------------------ */

static int count_lines_starting(const char *text, const char *start)
{
    int n = 0;
    size_t len = strlen(start);
    for (const char *p = text; p && *p; p = strchr(p, '\n'), p = p ? p + 1 : p)
        if (strncmp(p, start, len) == 0 && p[len] == '\n')
            n++;
    return n;
}

static void ompl_logs_one_per_query(void **state)
{
    fixture *f = *state;
    int64_t one = 1;
    mpb_store *s;
    mpb_export_counts c;
    char dir[128], path[256];
    snprintf(dir, sizeof dir, "%s/logs", f->dir);
    assert_int_equal(mpb_store_open(f->db, 1, &s), MPB_OK);
    assert_int_equal(mpb_store_export_ompl_logs(s, dir, &one, 1, 0, &c),
                     MPB_OK);
    assert_int_equal(c.experiments, 3);
    assert_int_equal(c.runs, 7);

    snprintf(path, sizeof path, "%s/paper.1.KITCHEN.k1.log", dir);
    const char *log = slurp(path);
    /* OMPL's header; the version as "NAME version X" makes the script's
     * version column "mpbench X". */
    assert_non_null(strstr(log,
        "mpbench version " MPB_VERSION_STRING "\n"
        "Experiment paper/KITCHEN\n"
        "2 experiment properties\n"
        "query VARCHAR(512) = k1\n"
        "mpbench_experiment INTEGER = 1\n"
        "Running on "));
    assert_non_null(strstr(log, "\n<<<|\nexperiment: {name: paper}\n\n"
                                "mpbench experiment 1, query k1\n"));
    assert_non_null(strstr(log,
        "|>>>\n"
        "0 is the random seed\n"
        "60 seconds per run\n"
        "0 MB per run\n"
        "3 runs per planner\n"
        "3.5 seconds spent to collect the data\n"
        "1 enum type\n"
        "status|Unknown status|Invalid start|Invalid goal|"
        "Unrecognized goal type|Timeout|Approximate solution|Exact solution|"
        "Crash|Abort|Infeasible|Invalid request|Out of memory\n"
        "2 planners\n"
        "ompl/RRTConnect\n"
        "3 common properties\n"
        "algorithm = RRTConnect\n"
        "planner = ompl\n"
        "range = 0.5\n"
        "32 properties for each run\n"
        "time REAL\n"
        "time raw REAL\n"));
    assert_non_null(strstr(log, "\nsimplified correct solution BOOLEAN\n"
                                "cost best REAL\n"
                                "graph states REAL\n"
                                "planner solved REAL\n"
                                "planner time REAL\n"
                                "2 runs\n"));
    /* Run 1 (approximate, one stage, no verify time, no memory): "v; "
     * each, empty for NULL, REALs exact. */
    assert_non_null(strstr(log,
        "\n2; 1.75; 0.25; 2; ; ; 0; 0; 1; 5; 1.8999999999999999; 3; "
        "0.20000000000000001; ; 3; 0; ; ; ; ; ; ; 1.8999999999999999; 3; "
        "0.20000000000000001; ; 3; 0; ; ; ; ; \n"));
    /* Run 0's progress, then none for run 1; B's block has an empty line. */
    assert_non_null(strstr(log,
        "3 progress properties for each run\n"
        "time REAL\n"
        "best cost REAL\n"
        "iterations REAL\n"
        "2 runs\n"
        "0.10000000000000001,12,10,;0.20000000000000001,11,20,;"
        "0.29999999999999999,,30,;\n"
        "\n"
        ".\n"
        "ara/ARAstar\n"));
    assert_non_null(strstr(log, "1 runs\n\n.\n"));
    assert_int_equal(count_lines_starting(log, "."), 2);

    snprintf(path, sizeof path, "%s/paper.1.TABLE_TOP.t1.log", dir);
    assert_non_null(strstr(slurp(path), "Experiment paper/TABLE_TOP\n"));

    /* Logs are not overwritten unless asked. */
    assert_int_equal(mpb_store_export_ompl_logs(s, dir, &one, 1, 0, &c),
                     MPB_EEXISTS);
    assert_int_equal(mpb_store_export_ompl_logs(s, dir, &one, 1,
                                                MPB_EXPORT_REPLACE, &c),
                     MPB_OK);
    mpb_store_close(s);
}

/*
 * An imported log's integers and the properties it declares (what mpb
 * import -d stores): an INTEGER planner value past 2^53, and INT64_MIN,
 * come out exactly in an INTEGER column and in the log; a property the
 * log declares that no run measured is a column of NULLs of its type. A
 * database made before planner_values.exact and log_properties is read
 * as before (the REALs), and gets both when a writer opens it.
 */
static void an_imported_logs_integers_and_unmeasured_properties(void **state)
{
    fixture *f = *state;
    char db[128], dir[128];
    snprintf(db, sizeof db, "%s/imported.db", f->dir);
    snprintf(dir, sizeof dir, "%s/imported-logs", f->dir);
    mpb_store *s;
    int64_t exp, cfg, scene, query, ids[2] = {0, 0};
    static const char *const none[] = {NULL};
    static const double zero[] = {0.0};
    assert_int_equal(mpb_store_open(db, 0, &s), MPB_OK);
    mpb_log_header h = {.host = "h", .version = "OMPL 1.5.2",
                        .started = "2026-01-02 03:04:05", .seed = "1",
                        .total_time = 1.0, .memory_limit = 0.0};
    mpb_experiment_info e = {"log", "log.log", "x", "x", 2, 1.0, &h, 0};
    assert_int_equal(mpb_store_experiment_create(s, &e, &exp), MPB_OK);
    assert_int_equal(mpb_store_planner_config_add(s, exp, "ompl/RRT", "ompl",
                                                  "RRT", "", &cfg), MPB_OK);
    mpb_scene_info sc = {"log", "ompl-log", "x", "", "ompl-log", "x", ""};
    assert_int_equal(mpb_store_scene_add(s, exp, &sc, &scene), MPB_OK);
    mpb_query_info q = {"log", 0, none, zero, MPB_GOAL_JOINTS, NULL, 0.0,
                        NULL, NULL};
    assert_int_equal(mpb_store_query_add(s, scene, &q, &query), MPB_OK);
    static const mpb_log_property run_props[] = {
        {"graph states", "INTEGER"}, {"time", "REAL"}, {"never", "BOOLEAN"}};
    static const mpb_log_property progress_props[] = {
        {"time", "REAL"}, {"nothing", "INTEGER"}};
    assert_int_equal(mpb_store_log_properties(s, cfg, 0, 3, run_props), MPB_OK);
    assert_int_equal(mpb_store_log_properties(s, cfg, 1, 2, progress_props),
                     MPB_OK);
    for (int r = 0; r < 2; r++) {
        assert_int_equal(mpb_store_run_add(s, exp, cfg, query, r, 0), MPB_OK);
        assert_int_equal(mpb_store_runs_unfinished(s, exp, first_id, &ids[r]),
                         1);
        assert_int_equal(mpb_store_run_sent(s, ids[r], "u", "imported"),
                         MPB_OK);
        const mpb_named values[] = {
            {"graph states", r == 0 ? 9007199254740993.0 : (double)INT64_MIN}};
        const mpb_exact_value exact[] = {
            {0, r == 0 ? INT64_C(9007199254740993) : INT64_MIN}};
        mpb_run_record rec = {
            .run_id = ids[r], .run_uid = "u", .planner_id = "imported",
            .status = "timeout", .message = "", .time_total = 0.5,
            .time_raw = 0.5, .wall_time = NAN, .verify_time = NAN,
            .memory = NAN, .num_values = 1, .values = values,
            .num_exact = 1, .exact = exact};
        assert_int_equal(mpb_store_run_finish(s, &rec), MPB_OK);
    }
    mpb_store_close(s);

    export_store(f, db, 0, NULL);
    sqlite3 *out = open_out(f);
    assert_string_equal(rows(out, "SELECT typeof(graph_states), graph_states,"
                                  " typeof(never) FROM runs ORDER BY id"),
                        "integer|9007199254740993|null\n"
                        "integer|-9223372036854775808|null\n");
    assert_non_null(strstr(columns(out, "runs", 1),
                           " graph_states:INTEGER never:BOOLEAN"));
    assert_string_equal(columns(out, "progress", 1),
                        "runid:INTEGER time:REAL nothing:INTEGER");
    sqlite3_close(out);
    assert_int_equal(mpb_store_open(db, 1, &s), MPB_OK);
    assert_int_equal(mpb_store_export_ompl_logs(s, dir, NULL, 0, 0, NULL),
                     MPB_OK);
    mpb_store_close(s);
    char pattern[160];
    glob_t g;
    snprintf(pattern, sizeof pattern, "%s/*.log", dir);
    assert_int_equal(glob(pattern, 0, NULL, &g), 0);
    assert_int_equal(g.gl_pathc, 1);
    const char *log = slurp(g.gl_pathv[0]);
    globfree(&g);
    assert_non_null(strstr(log, "\ngraph states INTEGER\nnever BOOLEAN\n"
                                "2 runs\n"));
    assert_non_null(strstr(log, "; 9007199254740993; ; \n"));
    assert_non_null(strstr(log, "; -9223372036854775808; ; \n"));
    assert_non_null(strstr(log, "2 progress properties for each run\n"
                                "time REAL\nnothing INTEGER\n"));

    /* A database of an mpbench before them, read as it was. */
    sqlite3 *old;
    assert_int_equal(sqlite3_open(db, &old), SQLITE_OK);
    assert_int_equal(sqlite3_exec(old, "ALTER TABLE planner_values DROP COLUMN"
                                       " exact; DROP TABLE log_properties",
                                  NULL, NULL, NULL), SQLITE_OK);
    sqlite3_close(old);
    export_store(f, db, 0, NULL);
    out = open_out(f);
    assert_string_equal(rows(out, "SELECT typeof(graph_states), graph_states"
                                  " = 9007199254740992.0 FROM runs ORDER BY"
                                  " id LIMIT 1"), "real|1\n");
    assert_null(strstr(columns(out, "runs", 0), "never"));
    sqlite3_close(out);
    /* A writer adds them back: NULL, none, for what was there. */
    assert_int_equal(mpb_store_open(db, 0, &s), MPB_OK);
    mpb_store_close(s);
    assert_int_equal(sqlite3_open(db, &old), SQLITE_OK);
    assert_string_equal(rows(old, "SELECT count(*) FROM planner_values WHERE"
                                  " exact IS NULL"), "2\n");
    assert_string_equal(rows(old, "SELECT count(*) FROM log_properties"),
                        "0\n");
    sqlite3_close(old);
}

/* The number of files in dir. */
static int count_files(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *ent;
    int n = 0;
    assert_non_null(d);
    while ((ent = readdir(d)) != NULL)
        n += ent->d_name[0] != '.';
    closedir(d);
    return n;
}

static void ompl_logs_of_names_alike_are_files_of_their_own(void **state)
{
    fixture *f = *state;
    /* Scenes "tai dokoro" and "souko" (kitchen and storehouse, two CJK
     * characters each) are "______" in a file name, "q 1" and "q_1" are
     * "q_1"; "K" and "k" are one file where case is ignored. */
    static const char *const scenes[] = {"\xe5\x8f\xb0\xe6\x89\x80",
                                         "\xe5\x80\x89\xe5\xba\xab", "K", "k"};
    static const mini_query queries[] = {{0, "q 1", NULL}, {0, "q_1", NULL},
                                         {1, "q 1", NULL}, {2, "a", NULL},
                                         {3, "a", NULL}, {2, "b", NULL}};
    static const struct { const char *file, *experiment, *query; } logs[] = {
        {"x.1.______.q_1+1.log", "x/\xe5\x8f\xb0\xe6\x89\x80", "q 1"},
        {"x.1.______.q_1+2.log", "x/\xe5\x8f\xb0\xe6\x89\x80", "q_1"},
        {"x.1.______.q_1+3.log", "x/\xe5\x80\x89\xe5\xba\xab", "q 1"},
        {"x.1.K.a+4.log", "x/K", "a"},
        {"x.1.k.a+5.log", "x/k", "a"},
        {"x.1.K.b.log", "x/K", "b"},
    };
    char path[128], dir[128], log[256], want[256];
    int64_t exp;
    mpb_store *s;
    mpb_export_counts c;
    snprintf(path, sizeof path, "%s/alike.db", f->dir);
    snprintf(dir, sizeof dir, "%s/alike-logs", f->dir);
    mini_experiment(path, "x", scenes, 4, queries, 6, 2, &exp);

    /* A file per query, each with its query's runs; the counts are what
     * is there. */
    assert_int_equal(mpb_store_open(path, 1, &s), MPB_OK);
    assert_int_equal(mpb_store_export_ompl_logs(s, dir, NULL, 0, 0, &c),
                     MPB_OK);
    assert_int_equal(c.experiments, 6);
    assert_int_equal(c.runs, 12);
    assert_int_equal(count_files(dir), 6);
    for (size_t i = 0; i < sizeof logs / sizeof logs[0]; i++) {
        snprintf(log, sizeof log, "%s/%s", dir, logs[i].file);
        snprintf(want, sizeof want, "\nExperiment %s\n2 experiment "
                 "properties\nquery VARCHAR(512) = %s\n", logs[i].experiment,
                 logs[i].query);
        const char *text = slurp(log);
        assert_non_null(strstr(text, want));
        assert_non_null(strstr(text, "\n2 runs\n"));
    }

    /* Again without replacing: one log there stops it before it writes
     * any (the one removed is not made again). */
    snprintf(log, sizeof log, "%s/%s", dir, logs[0].file);
    assert_int_equal(unlink(log), 0);
    assert_int_equal(mpb_store_export_ompl_logs(s, dir, NULL, 0, 0, &c),
                     MPB_EEXISTS);
    assert_int_equal(c.experiments, 0);
    assert_int_equal(count_files(dir), 5);
    assert_int_equal(mpb_store_export_ompl_logs(s, dir, NULL, 0,
                                                MPB_EXPORT_REPLACE, &c),
                     MPB_OK);
    assert_int_equal(c.experiments, 6);
    assert_int_equal(count_files(dir), 6);
    mpb_store_close(s);
}

/* ---- the command line --------------------------------------------------------- */

typedef struct output {
    char text[8192];
    int  status;
} output;

static void run(output *o, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
static void run(output *o, const char *fmt, ...)
{
    char args[1024], cmd[6144];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(args, sizeof args, fmt, ap);
    va_end(ap);
    snprintf(cmd, sizeof cmd, "'%s' %s 2>&1", mpb_tool, args);
    FILE *p = popen(cmd, "r");
    assert_non_null(p);
    size_t n = fread(o->text, 1, sizeof o->text - 1, p);
    o->text[n] = '\0';
    int st = pclose(p);
    assert_true(WIFEXITED(st));
    o->status = WEXITSTATUS(st);
}

static void mpb_export_writes_and_refuses_to_overwrite(void **state)
{
    fixture *f = *state;
    output o;
    char want[512];
    unlink(f->out);
    run(&o, "export --planner-arena '%s' '%s'", f->db, f->out);
    assert_int_equal(o.status, 0);
    snprintf(want, sizeof want, "%s: 4 Planner Arena experiments, 8 runs, "
             "2 planner configurations added, 3 progress samples\n", f->out);
    assert_string_equal(o.text, want);

    run(&o, "export --planner-arena '%s' '%s'", f->db, f->out);
    assert_int_equal(o.status, 1);
    snprintf(want, sizeof want, "mpb export: %s exists (--append adds to it, "
             "--force replaces it)\n", f->out);
    assert_string_equal(o.text, want);

    run(&o, "export --planner-arena --force -e 2 '%s' '%s'", f->db, f->out);
    assert_int_equal(o.status, 0);
    sqlite3 *db = open_out(f);
    assert_string_equal(rows(db, "SELECT count(*) FROM runs"), "1\n");
    sqlite3_close(db);
    run(&o, "export --planner-arena --append -e 1 '%s' '%s'", f->db, f->out);
    assert_int_equal(o.status, 0);
    db = open_out(f);
    assert_string_equal(rows(db, "SELECT count(*) FROM runs"), "8\n");
    sqlite3_close(db);
    run(&o, "export --planner-arena --append -e 1 -e 1 '%s' '%s'", f->db,
        f->out);
    assert_int_equal(o.status, 0);
    snprintf(want, sizeof want, "%s: 0 Planner Arena experiments, 0 runs, "
             "0 planner configurations added, 0 progress samples; 3 there "
             "already, skipped\n", f->out);
    assert_string_equal(o.text, want);

    run(&o, "export --planner-arena -e 5 '%s' '%s.new'", f->db, f->out);
    assert_int_equal(o.status, 1);
    assert_string_equal(o.text, "mpb export: no experiment 5\n");
    /* The library's message says what failed once, after the tool's name. */
    run(&o, "export --planner-arena '%s' '%s.none/x.db'", f->db, f->out);
    assert_int_equal(o.status, 1);
    snprintf(want, sizeof want, "mpb export: cannot open %s.none/x.db: ",
             f->out);
    assert_memory_equal(o.text, want, strlen(want));

    /* The database itself, by another name, is never the output: refused
     * before --force removes anything. */
    char alias[160];
    snprintf(alias, sizeof alias, "%s/alias.db", f->dir);
    unlink(alias);
    assert_int_equal(symlink(f->db, alias), 0);
    run(&o, "export --planner-arena --force '%s' '%s'", f->db, alias);
    assert_int_equal(o.status, 2);
    snprintf(want, sizeof want, "mpb export: %s is the database %s itself; "
             "write to another file\n", alias, f->db);
    assert_string_equal(o.text, want);
    run(&o, "export --planner-arena --append '%s' '%s'", f->db, alias);
    assert_int_equal(o.status, 2);
    mpb_store *s;
    int64_t n = 0;
    assert_int_equal(mpb_store_open(f->db, 1, &s), MPB_OK);
    assert_int_equal(mpb_store_export_planner_arena(s, alias, NULL, 0,
                                                    MPB_EXPORT_APPEND, NULL),
                     MPB_EINVAL);
    assert_non_null(strstr(mpb_store_errmsg(s), "is the database being "
                                                "exported"));
    mpb_store_close(s);
    sqlite3 *in;
    assert_int_equal(sqlite3_open_v2(f->db, &in, SQLITE_OPEN_READONLY, NULL),
                     SQLITE_OK);
    assert_string_equal(rows(in, "SELECT count(*) FROM sqlite_master"
                                 " WHERE name = 'plannerConfigs'"), "0\n");
    n = atoll(rows(in, "SELECT count(*) FROM experiments"));
    assert_true(n >= 2);
    sqlite3_close(in);
    unlink(alias);

    run(&o, "export '%s' '%s'", f->db, f->out);
    assert_int_equal(o.status, 2);
    run(&o, "export --planner-arena '%s'", f->db);
    assert_int_equal(o.status, 2);
    run(&o, "export --planner-arena --append --force '%s' '%s'", f->db, f->out);
    assert_int_equal(o.status, 2);
    run(&o, "export --planner-arena -e x '%s' '%s'", f->db, f->out);
    assert_int_equal(o.status, 2);
    run(&o, "export --help");
    assert_int_equal(o.status, 0);
    assert_non_null(strstr(o.text, "usage: mpb export --planner-arena"));
    assert_non_null(strstr(o.text, "mpb export --ompl-log"));

    char dir[128];
    snprintf(dir, sizeof dir, "%s/cli-logs", f->dir);
    run(&o, "export --ompl-log '%s' '%s'", f->db, dir);
    assert_int_equal(o.status, 0);
    snprintf(want, sizeof want, "%s: 4 OMPL logs, 8 runs\n", dir);
    assert_string_equal(o.text, want);
    run(&o, "export --ompl-log '%s' '%s'", f->db, dir);
    assert_int_equal(o.status, 1);
    assert_non_null(strstr(o.text, "exists (--force replaces it)"));
    run(&o, "export --ompl-log --force '%s' '%s'", f->db, dir);
    assert_int_equal(o.status, 0);
    run(&o, "export --ompl-log --append '%s' '%s'", f->db, dir);
    assert_int_equal(o.status, 2);
    run(&o, "export --ompl-log --planner-arena '%s' '%s'", f->db, dir);
    assert_int_equal(o.status, 2);
}

int main(void)
{
    const char *build = getenv("MPB_BUILD");
    if (build != NULL) {
        snprintf(mpb_tool, sizeof mpb_tool, "%s/tools/mpb", build);
    } else {
        char self[2048];
        ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
        if (n <= 0) {
            fprintf(stderr, "test_export: cannot find myself; set MPB_BUILD\n");
            return 1;
        }
        self[n] = '\0';
        snprintf(mpb_tool, sizeof mpb_tool, "%s/../tools/mpb", dirname(self));
    }
    if (access(mpb_tool, X_OK) != 0) {
        fprintf(stderr, "test_export: no mpb at %s (build it first)\n",
                mpb_tool);
        return 1;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(experiments_keep_planner_arenas_twelve_columns),
        cmocka_unit_test(setup_shows_a_pose_regions_goal),
        cmocka_unit_test(planner_configs_and_the_status_enum),
        cmocka_unit_test(runs_carry_attributes_from_the_fourth_column),
        cmocka_unit_test(the_doc_lists_every_runs_attribute),
        cmocka_unit_test(booleans_are_0_or_1_and_status_is_the_enum),
        cmocka_unit_test(stage_values_by_hand),
        cmocka_unit_test(progress_samples_and_the_views),
        cmocka_unit_test(append_adds_and_reuses_configurations),
        cmocka_unit_test(scenes_of_one_word_name_stay_apart),
        cmocka_unit_test(one_export_skips_only_what_was_there),
        cmocka_unit_test(append_refuses_other_databases),
        cmocka_unit_test(failures_leave_nothing_behind),
        cmocka_unit_test(ompl_logs_one_per_query),
        cmocka_unit_test(ompl_logs_of_names_alike_are_files_of_their_own),
        cmocka_unit_test(mpb_export_writes_and_refuses_to_overwrite),
        cmocka_unit_test(an_imported_logs_integers_and_unmeasured_properties),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
