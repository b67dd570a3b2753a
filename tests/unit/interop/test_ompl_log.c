/*
 * test_ompl_log.c - the OMPL benchmark log reader (ompl_log.c): a log
 * OMPL's own Benchmark wrote is read, and each damage done to it is
 * refused with the line and what is wrong; logs written one at a time
 * into one Planner Arena database (ompl_log_pa.c), whole or not at all.
 */
#include <dirent.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <sqlite3.h>

#include "mpbench/mpbench.h"
#include "test_files.h"

#define WALL_LOG MPB_TEST_DATA "/../../fuzz/corpus/ompl_log/wall.log"

/* wall.log with the first occurrence of old replaced by new (the whole
 * text when old is NULL), parsed; the log is freed, err holds the error. */
static int parse_edited(const char *old, const char *new, char *err, size_t errlen)
{
    char *text = test_read_file(WALL_LOG);
    size_t len = strlen(text);
    char *edited = text;
    if (old != NULL) {
        char *at = strstr(text, old);
        assert_non_null(at);
        size_t nold = strlen(old), nnew = strlen(new);
        edited = malloc(len - nold + nnew + 1);
        assert_non_null(edited);
        memcpy(edited, text, (size_t)(at - text));
        memcpy(edited + (at - text), new, nnew);
        strcpy(edited + (at - text) + nnew, at + nold);
        len = len - nold + nnew;
    }
    mpb_ompl_log *log = NULL;
    err[0] = '\0';
    int rc = mpb_ompl_log_open(edited, len, &log, err, errlen);
    assert_true((rc == MPB_OK) == (log != NULL));
    mpb_ompl_log_close(log);
    if (edited != text)
        free(edited);
    free(text);
    return rc;
}

/* wall.log with tail after its end, parsed; err holds the error. */
static int parse_appended(const char *tail, char *err, size_t errlen)
{
    char *text = test_read_file(WALL_LOG);
    size_t n = strlen(text), k = strlen(tail);
    char *all = malloc(n + k + 1);
    assert_non_null(all);
    memcpy(all, text, n);
    memcpy(all + n, tail, k + 1);
    mpb_ompl_log *log = NULL;
    err[0] = '\0';
    int rc = mpb_ompl_log_open(all, n + k, &log, err, errlen);
    assert_true((rc == MPB_OK) == (log != NULL));
    mpb_ompl_log_close(log);
    free(all);
    free(text);
    return rc;
}

/* The edit is refused with exactly that message. */
static void refused(const char *old, const char *new, const char *message)
{
    char err[256];
    assert_int_equal(parse_edited(old, new, err, sizeof err), MPB_EPARSE);
    assert_string_equal(err, message);
}

/* The edit is read. */
static void read_ok(const char *old, const char *new)
{
    char err[256];
    int rc = parse_edited(old, new, err, sizeof err);
    if (rc != MPB_OK)
        fail_msg("%s", err);
}

static void ompls_own_log_is_read(void **state)
{
    (void)state;
    read_ok(NULL, NULL);
    char err[256];
    assert_int_equal(parse_appended("\n  \n", err, sizeof err), MPB_OK);
}

static void planner_count_must_match(void **state)
{
    (void)state;
    refused("\n3 planners\n", "\n2 planners\n",
            "line 102: text after the last planner");
    refused("\n3 planners\n", "\n0 planners\n",
            "line 20: text after the last planner");
    char err[256];
    assert_int_equal(parse_appended("\njunk\n", err, sizeof err), MPB_EPARSE);
    assert_string_equal(err, "line 159: text after the last planner");
}

/* Run 1 of geometric_RRTConnect (line 54), its values in the order of
 * the properties: ... graph motions INTEGER (5th) ... solved BOOLEAN
 * (20th), status ENUM, time REAL, valid segment fraction REAL. */
static void values_must_be_of_their_type(void **state)
{
    (void)state;
    const char *e = "line 54: run 1 of geometric_RRTConnect: ";
    char want[256];
    static const struct { const char *old, *new, *bad; } cases[] = {
        {"0; 0; 1; 1; 13; ", "0; 0; 1; 1; abc; ", "'abc' is not an INTEGER"},
        {"0; 0; 1; 1; 13; ", "0; 0; 1; 1; 99999999999999999999999; ",
         "'99999999999999999999999' is not an INTEGER"},
        {"0; 0; 1; 1; 13; ", "0; 0; 1; 1; 1.5; ", "'1.5' is not an INTEGER"},
        {"0; 0; 1; 1; 13; ", "0; 0; 7; 1; 13; ", "'7' is not a BOOLEAN"},
        {"9.56641; ", "abc; ", "'abc' is not a REAL"},
        {"9.56641; ", "1.5x; ", "'1.5x' is not a REAL"},
        {"125.645; 1; 6; ", "125.645; 1; 99; ",
         "'99' is not a value of the ENUM 'status' (0 to 8)"},
        {"125.645; 1; 6; ", "125.645; 1; -1; ",
         "'-1' is not a value of the ENUM 'status' (0 to 8)"},
        {"0.000195201; 0.444444", "-5; 0.444444",
         "'-5' is not a time (a number of seconds, not negative)"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        snprintf(want, sizeof want, "%s%s", e, cases[i].bad);
        refused(cases[i].old, cases[i].new, want);
    }
    /* A run's progress too (the last planner's: best cost, edge count,
     * iterations, milestone count, time). */
    read_ok("time REAL\n6 runs\n\n", "time REAL\n6 runs\n1.5,3,4,2,0.01,;"
            "1.25,5,9,3,0.02,;\n");
    refused("time REAL\n6 runs\n\n", "time REAL\n6 runs\n1.5,3,x,2,0.01,;\n",
            "line 151: the progress of run 1 of geometric_PRM: 'x' is not an "
            "INTEGER");
    refused("time REAL\n6 runs\n\n", "time REAL\n6 runs\n1.5,3,4,2,-1,;\n",
            "line 151: the progress of run 1 of geometric_PRM: '-1' is not a "
            "time (a number of seconds, not negative)");
    /* A sample's time must be there: the databases cannot store it else. */
    refused("time REAL\n6 runs\n\n", "time REAL\n6 runs\n1.5,3,4,2,inf,;\n",
            "line 151: the progress of run 1 of geometric_PRM: 'inf' is not a "
            "time (a number of seconds, not negative)");
    refused("time REAL\n6 runs\n\n", "time REAL\n6 runs\n1,,,,,;\n",
            "line 151: the progress of run 1 of geometric_PRM: '' is not a "
            "time (a number of seconds, not negative)");
    read_ok("time REAL\n6 runs\n\n", "time REAL\n6 runs\n,,,,0.5,;\n");
    refused("status ENUM\n", "status FLOAT\n", "line 50: unknown property type "
            "'FLOAT' (not REAL, INTEGER, BOOLEAN or ENUM)");
    refused("42 is the random seed", "x is the random seed",
            "line 12: 'x' is not a random seed (a number)");
    refused("Starting at 2026-11-22 11:22:29", "Starting at yesterday",
            "line 5: 'yesterday' is not a date (YYYY-MM-DD ...)");
}

/* What OMPL's own Benchmark writes stays readable: empty values for what
 * a run did not measure, nan and inf for reals, true and false. */
static void what_ompl_writes_is_read(void **state)
{
    (void)state;
    read_ok("0; 0; 1; 1; 13; 14; 9.56641; 7.6093e-05; ",
            "0; 0; 1; 1; ; 14; nan; inf; ");
    read_ok("0; 0; 1; 1; 13; 14; 9.56641; 7.6093e-05; ",
            "0; false; true; 1; -13; +14; -inf; -nan; ");
    read_ok("0; 0; 1; 1; 13; 14; 9.56641; 7.6093e-05; ",
            "0; 0; 1; 1; 13; 14; 1e300; 0.10000000000000001; ");
    read_ok("125.645; 1; 6; 0.000195201", "125.645; 1; 8; 0");
    read_ok("Starting at 2026-11-22 11:22:29", "Starting at 2026-Nov-22 11:22:29");
}

/* What OMPL's script keeps, the reader keeps for mpb import: the
 * experiment properties and the enums as written, the common properties
 * each as its line, then "\n;", and integers past 2^53 exactly. */
static void what_the_script_keeps_is_kept(void **state)
{
    (void)state;
    char *text = test_read_file(WALL_LOG);
    const char *old = "0 experiment properties\n";
    char *at = strstr(text, old);
    assert_non_null(at);
    const char *params = "3 experiment properties\nwall width REAL = 0.6\n"
                         "max-speed INTEGER = 7\nnote VARCHAR(16) =\n";
    char *big = strstr(text, "0; 0; 1; 1; 13; 14; ");
    assert_non_null(big);
    size_t n = strlen(text) + strlen(params) + 64;
    char *edited = malloc(n);
    assert_non_null(edited);
    snprintf(edited, n, "%.*s%s%.*s0; 0; 1; 1; 9007199254740993; "
             "-9223372036854775807; %s", (int)(at - text), text, params,
             (int)(big - at - strlen(old)), at + strlen(old),
             big + strlen("0; 0; 1; 1; 13; 14; "));
    mpb_ompl_log *log = NULL;
    char err[256] = "";
    if (mpb_ompl_log_open(edited, strlen(edited), &log, err, sizeof err) !=
        MPB_OK)
        fail_msg("%s", err);
    assert_int_equal(log->num_params, 3);
    assert_string_equal(log->params[0].name, "wall width");
    assert_string_equal(log->params[0].type, "REAL");
    assert_string_equal(log->params[0].value, "0.6");
    assert_string_equal(log->params[1].name, "max-speed");
    assert_string_equal(log->params[2].type, "VARCHAR(16)");
    assert_string_equal(log->params[2].value, "");
    assert_int_equal(log->num_enums, 1);
    assert_string_equal(log->enums[0].name, "status");
    assert_int_equal(log->enums[0].num_values, 9);
    assert_string_equal(log->enums[0].values[6], "Exact solution");
    const mpb_ompl_planner *p = &log->planners[0];
    assert_non_null(strstr(p->settings_text, "intermediate_states = 0\n;"
                                             "longest_valid_segment_fraction"));
    assert_int_equal(p->num_exact, 2);
    assert_int_equal(p->exact[0].cell, 4);
    assert_true(p->exact[0].value == 9007199254740993LL);
    assert_int_equal(p->exact[1].cell, 5);
    assert_true(p->exact[1].value == -9223372036854775807LL);
    mpb_ompl_log_close(log);
    free(edited);
    free(text);
    refused("0 experiment properties\n", "1 experiment properties\nwidth 0.6\n",
            "line 4: expected an experiment property 'name TYPE = value', "
            "found 'width 0.6'");
    refused("0 experiment properties\n",
            "1 experiment properties\nwidth REAL); = 0.6\n",
            "line 4: 'REAL);' is not a type (the experiment property 'width')");
    refused("0 experiment properties\n",
            "2 experiment properties\nw REAL = 1\nw REAL = 2\n",
            "line 5: the experiment property 'w' a second time");
}

/* What the mpbench and the Planner Arena paths of mpb import took
 * differently is refused here, once, for both. */
static void what_the_databases_would_refuse(void **state)
{
    (void)state;
    refused("0.05 seconds per run", "nan seconds per run",
            "line 13: 'nan seconds per run': X must be a number no less than 0");
    refused("0.05 seconds per run", "-1 seconds per run",
            "line 13: '-1 seconds per run': X must be a number no less than 0");
    refused("\ngeometric_RRT\n", "\ngeometric_RRTConnect\n",
            "line 61: the planner 'geometric_RRTConnect' a second time");
    refused("approximate solution BOOLEAN\n", "approx goal distance REAL\n",
            "line 31: the property 'approx goal distance' a second time");
    refused("1 enum type\n", "-1 enum type\n", "line 17: '-1 enum type': not a count");
    refused("0 experiment properties\n", "-2 experiment properties\n",
            "line 3: '-2 experiment properties': not a count");
    /* Counts past what any log holds are said as such, not as a format. */
    refused("\n3 planners\n", "\n20000 planners\n",
            "line 19: 20000 planners is more than a log holds");
    refused("\n6 runs\n", "\n2000000000 runs\n",
            "line 53: 2000000000 runs is more than a log holds");
    char err[256];
    assert_int_equal(parse_edited("\ngeometric_RRT\n", "\ngeometric_\001RRT\n",
                                  err, sizeof err), MPB_OK);
    /* A NUL in a planner's name (the edit cannot hold one: done by hand). */
    char *text = test_read_file(WALL_LOG);
    size_t n = strlen(text);
    char *at = strstr(text, "\ngeometric_RRT\n");
    assert_non_null(at);
    at[11] = '\0';
    mpb_ompl_log *log = NULL;
    assert_int_equal(mpb_ompl_log_open(text, n, &log, err, sizeof err), MPB_EPARSE);
    assert_null(log);
    assert_string_equal(err, "line 61: a NUL byte: not a benchmark log");
    free(text);
}

/* next() for the Planner Arena writer: the same log `count` times, then
 * the end; or, at call number fail_at, MPB_EPARSE. */
typedef struct feed {
    const mpb_ompl_log *log;
    int count, given, fail_at, calls;
} feed;

static int feed_next(void *ud, const mpb_ompl_log **log)
{
    feed *f = ud;
    if (++f->calls == f->fail_at)
        return MPB_EPARSE;
    *log = f->given < f->count ? f->log : NULL;
    f->given += *log != NULL;
    return MPB_OK;
}

static int entries(const char *dir)
{
    DIR *d = opendir(dir);
    assert_non_null(d);
    int n = 0;
    for (struct dirent *e; (e = readdir(d)) != NULL;)
        n += e->d_name[0] != '.';
    closedir(d);
    return n;
}

static void logs_are_written_one_at_a_time_whole_or_not_at_all(void **state)
{
    (void)state;
    char *text = test_read_file(WALL_LOG), err[256];
    mpb_ompl_log *log = NULL;
    assert_int_equal(mpb_ompl_log_open(text, strlen(text), &log, err,
                                       sizeof err), MPB_OK);
    long runs = 0;
    for (int i = 0; i < log->num_planners; i++)
        runs += log->planners[i].num_runs;
    char dir[] = "/tmp/mpb-test-pa-XXXXXX", path[64];
    assert_non_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/pa.db", dir);

    /* The second log fails to come: nothing at path, nothing beside it. */
    feed f = {.log = log, .count = 3, .fail_at = 2};
    assert_int_equal(mpb_ompl_logs_to_planner_arena(path, 0, feed_next, &f,
                                                    NULL, err, sizeof err),
                     MPB_EPARSE);
    assert_int_equal(f.given, 1);
    assert_non_null(strstr(err, "nothing written"));
    assert_int_equal(entries(dir), 0);

    /* Three logs, each given as the one before is written: one file. */
    f = (feed){.log = log, .count = 3};
    mpb_export_counts n;
    assert_int_equal(mpb_ompl_logs_to_planner_arena(path, 0, feed_next, &f,
                                                    &n, err, sizeof err),
                     MPB_OK);
    assert_int_equal(n.experiments, 3);
    assert_int_equal(n.runs, 3 * runs);
    assert_int_equal(entries(dir), 1);
    sqlite3 *db;
    sqlite3_stmt *st;
    assert_int_equal(sqlite3_open_v2(path, &db, SQLITE_OPEN_READONLY, NULL),
                     SQLITE_OK);
    assert_int_equal(sqlite3_prepare_v2(db, "SELECT (SELECT count(*) FROM "
                                        "experiments), (SELECT count(*) FROM "
                                        "runs)", -1, &st, NULL), SQLITE_OK);
    assert_int_equal(sqlite3_step(st), SQLITE_ROW);
    assert_int_equal(sqlite3_column_int(st, 0), 3);
    assert_int_equal(sqlite3_column_int64(st, 1), 3 * runs);
    sqlite3_finalize(st);
    sqlite3_close(db);

    /* Added to, with the failure: the database is as it was. */
    f = (feed){.log = log, .count = 2, .fail_at = 2};
    assert_int_equal(mpb_ompl_logs_to_planner_arena(path, MPB_EXPORT_APPEND,
                                                    feed_next, &f, NULL, err,
                                                    sizeof err), MPB_EPARSE);
    assert_int_equal(sqlite3_open_v2(path, &db, SQLITE_OPEN_READONLY, NULL),
                     SQLITE_OK);
    assert_int_equal(sqlite3_prepare_v2(db, "SELECT count(*) FROM experiments",
                                        -1, &st, NULL), SQLITE_OK);
    assert_int_equal(sqlite3_step(st), SQLITE_ROW);
    assert_int_equal(sqlite3_column_int(st, 0), 3);
    sqlite3_finalize(st);
    sqlite3_close(db);

    unlink(path);
    rmdir(dir);
    mpb_ompl_log_close(log);
    free(text);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(ompls_own_log_is_read),
        cmocka_unit_test(planner_count_must_match),
        cmocka_unit_test(values_must_be_of_their_type),
        cmocka_unit_test(what_ompl_writes_is_read),
        cmocka_unit_test(what_the_script_keeps_is_kept),
        cmocka_unit_test(what_the_databases_would_refuse),
        cmocka_unit_test(logs_are_written_one_at_a_time_whole_or_not_at_all),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
