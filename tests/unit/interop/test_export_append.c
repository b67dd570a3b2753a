/* test_export_append.c - the Planner Arena export into a database that is
 * there already: appending adds and reuses configurations, skips only what
 * was exported before, refuses what is not Planner Arena's, and a failed
 * export leaves nothing behind. */
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(append_adds_and_reuses_configurations),
        cmocka_unit_test(scenes_of_one_word_name_stay_apart),
        cmocka_unit_test(one_export_skips_only_what_was_there),
        cmocka_unit_test(append_refuses_other_databases),
        cmocka_unit_test(failures_leave_nothing_behind),
    };
    return cmocka_run_group_tests(tests, setup, test_store_teardown);
}
