/* test_export_ompl_log.c - the OMPL benchmark log export
 * (mpb_store_export_ompl_logs): one log per query, in the format OMPL's
 * ompl_benchmark_statistics.py reads, with names that stay apart. */
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
            .run_id = ids[r], .attempt_id = "u", .planner_id = "imported",
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(ompl_logs_one_per_query),
        cmocka_unit_test(ompl_logs_of_names_alike_are_files_of_their_own),
        cmocka_unit_test(an_imported_logs_integers_and_unmeasured_properties),
    };
    return cmocka_run_group_tests(tests, setup, test_store_teardown);
}
