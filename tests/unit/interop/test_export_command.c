/* test_export_command.c - `mpb export`, run as a user runs it: the built
 * tool writes Planner Arena databases and OMPL logs, refuses to overwrite,
 * and says what is wrong with a bad command line. */
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
#include "test_tool.h"

static char mpb_tool[4096];     /* the built mpb */

/* `mpb ARGS` run as a user runs it (test_tool.h), stdout and stderr
 * together. */
typedef test_output output;
#define run(o, ...) test_run((o), mpb_tool, "both", __VA_ARGS__)

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
    if (test_built_program("tools/mpb", mpb_tool, sizeof mpb_tool) != 0)
        return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(mpb_export_writes_and_refuses_to_overwrite),
    };
    return cmocka_run_group_tests(tests, setup, test_store_teardown);
}
