/* test_report_errors.c - `mpb report` on bad input, run as a user runs
 * it: a missing file, what is not a results database, bad command lines
 * (one clear line and its exit status each), and its help. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "test_report_paper.h"

static void a_missing_file_is_one_line_and_exit_1(void **state)
{
    (void)state;
    output o;
    run(&o, "stderr", "report /nonexistent/nosuch.db");
    assert_int_equal(o.status, 1);
    assert_string_equal(o.text, "mpb report: cannot open "
                                "/nonexistent/nosuch.db: No such file or "
                                "directory\n");
    run(&o, "stdout", "report /nonexistent/nosuch.db");
    assert_string_equal(o.text, "");
}

static void what_is_not_a_report_says_so(void **state)
{
    fixture *f = *state;
    output o;

    run(&o, "stderr", "report '%s'", f->text);
    assert_int_equal(o.status, 1);
    char want[256];
    snprintf(want, sizeof want, "mpb report: %s is not an mpbench database: "
             "not an SQLite file\n", f->text);
    assert_string_equal(o.text, want);
    assert_int_equal(strchr(o.text, '\n') - o.text + 1, (int)strlen(o.text));

    run(&o, "stderr", "report '%s'", f->empty);
    assert_int_equal(o.status, 1);
    snprintf(want, sizeof want, "mpb report: %s holds no experiment yet\n",
             f->empty);
    assert_string_equal(o.text, want);

    run(&o, "stderr", "report --experiment 99 '%s'", f->db);
    assert_int_equal(o.status, 1);
    snprintf(want, sizeof want, "mpb report: %s has no experiment 99\n", f->db);
    assert_string_equal(o.text, want);
}

static void bad_command_lines_exit_2(void **state)
{
    fixture *f = *state;
    output o;
    run(&o, "stderr", "report");
    assert_int_equal(o.status, 2);
    assert_non_null(strstr(o.text, "mpb report: "));
    run(&o, "stderr", "report --bogus '%s'", f->db);
    assert_int_equal(o.status, 2);
    assert_non_null(strstr(o.text, "--bogus"));
    run(&o, "stderr", "report --experiment");
    assert_int_equal(o.status, 2);
    run(&o, "stderr", "report --experiment one '%s'", f->db);
    assert_int_equal(o.status, 2);
    run(&o, "stderr", "report '%s' '%s'", f->db, f->db);
    assert_int_equal(o.status, 2);
    run(&o, "stderr", "report --format xml '%s'", f->db);
    assert_int_equal(o.status, 2);
    assert_string_equal(o.text, "mpb report: unknown format 'xml' (text, "
                                "markdown, csv, latex, json or html)\n");
    run(&o, "stderr", "report --format");
    assert_int_equal(o.status, 2);
    run(&o, "stderr", "nosuchcommand");
    assert_int_equal(o.status, 2);
    assert_non_null(strstr(o.text, "unknown command 'nosuchcommand'"));
    run(&o, "stderr", "%s", "");
    assert_int_equal(o.status, 2);
}

static void help_is_clear(void **state)
{
    (void)state;
    output o;
    run(&o, "stdout", "--help");
    assert_int_equal(o.status, 0);
    assert_non_null(strstr(o.text, "usage: mpb COMMAND"));
    assert_non_null(strstr(o.text, "  report "));

    run(&o, "stdout", "report --help");
    assert_int_equal(o.status, 0);
    assert_non_null(strstr(o.text, "usage: mpb report [--experiment ID] "
                                   "[--stage NAME] [--format FORMAT]\n"
                                   "                  [--by set|scene|all] "
                                   "[--findings] [-o FILE] DB\n"));
    assert_non_null(strstr(o.text, "  -o, --output FILE    write the report to "
                                   "FILE"));
    assert_non_null(strstr(o.text, "views/run-ID.html"));
    /* Every format is listed, html with what it writes. */
    assert_non_null(strstr(o.text, "scene), json, or html: one self-contained "
                                   "page\n"));
    assert_non_null(strstr(o.text, "mpb plot as SVG"));
    assert_non_null(strstr(o.text, "its mpb view page"));
    assert_non_null(strstr(o.text, "--format FORMAT"));
    assert_non_null(strstr(o.text, "--stage NAME"));

    output h;
    run(&h, "stdout", "help report");
    assert_int_equal(h.status, 0);
    assert_string_equal(h.text, o.text);
}

int main(void)
{
    if (test_built_program("tools/mpb", mpb_tool, sizeof mpb_tool) != 0)
        return 1;

    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_missing_file_is_one_line_and_exit_1),
        cmocka_unit_test(what_is_not_a_report_says_so),
        cmocka_unit_test(bad_command_lines_exit_2),
        cmocka_unit_test(help_is_clear),
    };
    return cmocka_run_group_tests(tests, setup, test_store_teardown);
}
