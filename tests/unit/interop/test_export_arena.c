/* test_export_arena.c - the Planner Arena export (store_export.c): the
 * database of test_export_paper.h exported and read back with SQLite as
 * Planner Arena and OMPL's script read it: the tables, their columns and
 * order, the status enum, booleans as 0/1, values worked out by hand. */
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

#include "test_export_paper.h"

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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(experiments_keep_planner_arenas_twelve_columns),
        cmocka_unit_test(setup_shows_a_pose_regions_goal),
        cmocka_unit_test(planner_configs_and_the_status_enum),
        cmocka_unit_test(runs_carry_attributes_from_the_fourth_column),
        cmocka_unit_test(the_doc_lists_every_runs_attribute),
        cmocka_unit_test(booleans_are_0_or_1_and_status_is_the_enum),
        cmocka_unit_test(stage_values_by_hand),
        cmocka_unit_test(progress_samples_and_the_views),
    };
    return cmocka_run_group_tests(tests, setup, test_store_teardown);
}
