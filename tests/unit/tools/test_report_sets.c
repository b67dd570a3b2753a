/* test_report_sets.c - `mpb report` by problem set, run as a user runs
 * it: the built tool on a database written through the store; its set
 * tables' intervals and quantiles against values worked out by hand, and
 * --findings' paired tests naming a configuration only where the
 * difference is significant.
 *
 * Experiment "ten" (time limit 10 s, one run per problem): set s, scenes
 * s/0001-0010, configurations a/x and b/y. a/x solves problem i (0-9) in
 * 1 + 0.1 i s; b/y the same, but fails problem 0: one run out of ten.
 * Experiment "hundred": set t, scenes t/0001-0100; a/x solves problem i
 * in 0.01 (1 + i % 10) s, b/y in ten times that; paths of 2 rad each. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "test_store.h"
#include "test_tool.h"

static char mpb_tool[4096];

typedef struct fixture {
    char dir[64];               /* first: test_store_teardown() */
    char db[128];
    int64_t ten, hundred;
} fixture;

#define MAX_PROBLEMS 100

/* An experiment of n problems in set `set`; runs as the top says. */
static int64_t experiment(mpb_store *s, const char *name, const char *set,
                          int n)
{
    int64_t exp = test_store_experiment(s, name, "sets.yaml", "h", 1, 10.0);
    int64_t cfg[2] = {test_store_config(s, exp, "a", "x", ""),
                      test_store_config(s, exp, "b", "y", "")};
    static int64_t query[MAX_PROBLEMS], run[2][MAX_PROBLEMS];
    for (int q = 0; q < n; q++) {
        char scene_name[32];
        snprintf(scene_name, sizeof scene_name, "%s/%04d", set, q + 1);
        query[q] = test_store_query(
            s, test_store_scene(s, exp, scene_name, "h", "s"), "q");
        for (int c = 0; c < 2; c++)
            run[c][q] = test_store_run(s, exp, cfg[c], query[q], 0, 2 * q + c);
    }
    for (int q = 0; q < n; q++) {
        int64_t a = run[0][q], b = run[1][q];
        if (n == 10) {
            test_store_finish(s, a, 1, 1.0 + 0.1 * q, 2.0);
            test_store_finish(s, b, q != 0, q != 0 ? 1.0 + 0.1 * q : 10.0,
                              2.0);
        } else {
            double t = 0.01 * (1 + q % 10);
            test_store_finish(s, a, 1, t, 2.0);
            test_store_finish(s, b, 1, 10 * t, 2.0);
        }
    }
    return exp;
}

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    mpb_store *s = test_store_new(f->dir, sizeof f->dir, f->db, sizeof f->db,
                                  "report_sets");
    f->ten = experiment(s, "ten", "s", 10);
    f->hundred = experiment(s, "hundred", "t", 100);
    mpb_store_close(s);
    *state = f;
    return 0;
}

static void says(const test_output *o, const char *text)
{
    if (strstr(o->text, text) == NULL) {
        fprintf(stderr, "%s", o->text);
        fail_msg("expected \"%s\" in the output above", text);
    }
}

/* The row of label in the output, its cells after the label. */
static void row_is(const test_output *o, const char *label, const char *a,
                   const char *b)
{
    char want[256];
    snprintf(want, sizeof want, "\n%-19s", label);
    const char *at = strstr(o->text, want);
    if (at == NULL) {
        fprintf(stderr, "%s", o->text);
        fail_msg("no row \"%s\"", label);
    }
    char ca[64], cb[64];
    assert_int_equal(sscanf(at + 1 + strlen(label), "%63s %63s", ca, cb), 2);
    assert_string_equal(ca, a);
    assert_string_equal(cb, b);
}

/*
 * Ten scenes in one set: by set unasked. s_r 100 % and 90 %: Wilson's
 * intervals 72.2-100.0 and 59.6-98.2. a/x's times 1.0-1.9: median 1.45,
 * p95 1.8 + 0.55 * 0.1 = 1.855, the median's interval the 2nd and 9th
 * (coverage 1 - 2 * 11/1024 = 97.9 %; the 3rd and 8th reach 89 %). b/y's
 * nine: median 1.5, 2nd and 8th of nine (96.1 %).
 */
static void a_set_table_with_intervals(void **state)
{
    fixture *f = *state;
    test_output o;
    test_run(&o, mpb_tool, "stdout", "report -e %lld '%s'",
             (long long)f->ten, f->db);
    assert_int_equal(o.status, 0);
    says(&o, "\nProblem set s (10 scenes) - experiment ten (1), 20 runs\n");
    assert_null(strstr(o.text, "Scene s/0001"));
    /* One set: no second table over all problems, the same numbers. */
    assert_null(strstr(o.text, "All problems"));
    row_is(&o, "s_r (%)", "100.0", "90.0");
    row_is(&o, "s_r 95% CI (%)", "72.2-100.0", "59.6-98.2");
    row_is(&o, "claimed s_r (%)", "100.0", "90.0");
    row_is(&o, "tau_t (Mean, s)", "1.450", "1.500");
    row_is(&o, "tau_t (median, s)", "1.450", "1.500");
    row_is(&o, "tau_t median 95% CI", "1.100-1.800", "1.200-1.800");
    row_is(&o, "tau_t (p95, s)", "1.855", "1.860");
}

static void by_scene_is_the_table_of_before(void **state)
{
    fixture *f = *state;
    test_output o;
    test_run(&o, mpb_tool, "stdout", "report --by scene -e %lld '%s'",
             (long long)f->ten, f->db);
    assert_int_equal(o.status, 0);
    says(&o, "\nScene s/0001 - experiment ten (1), 2 runs\n");
    says(&o, "\nScene s/0010 - experiment ten (1), 2 runs\n");
    assert_null(strstr(o.text, "Problem set"));
    assert_null(strstr(o.text, "tau_t (median, s)"));
    assert_null(strstr(o.text, "s_r 95% CI"));
    test_run(&o, mpb_tool, "stdout", "report --by all -e %lld '%s'",
             (long long)f->ten, f->db);
    assert_int_equal(o.status, 0);
    says(&o, "\nAll problems (10 scenes) - experiment ten (1), 20 runs\n");
    assert_null(strstr(o.text, "Problem set s "));
}

static void bad_by(void **state)
{
    fixture *f = *state;
    test_output o;
    test_run(&o, mpb_tool, "stderr", "report --by query '%s'", f->db);
    assert_int_equal(o.status, 2);
    assert_string_equal(o.text, "mpb report: --by wants set, scene or all, "
                                "not 'query'\n");
    test_run(&o, mpb_tool, "stderr", "report --by set --format csv '%s'",
             f->db);
    assert_int_equal(o.status, 2);
    assert_string_equal(o.text, "mpb report: --format csv is per scene; --by "
                                "set is for text and html\n");
}

/* One run out of ten: a single nonzero difference, p = 1. */
static void one_run_in_ten_is_no_finding(void **state)
{
    fixture *f = *state;
    test_output o;
    test_run(&o, mpb_tool, "stdout", "report --findings -e %lld '%s'",
             (long long)f->ten, f->db);
    assert_int_equal(o.status, 0);
    says(&o, "\n  s:\n    all configurations, fastest: no significant "
             "difference\n    all configurations, best paths: no significant "
             "difference\n");
    assert_null(strstr(o.text, "fastest: a/x"));
    assert_null(strstr(o.text, "fastest: b/y"));
}

/* Ten times as fast on every one of 100 problems: named, beside its
 * ratio; the same paths: no best. */
static void ten_times_faster_on_a_hundred_is(void **state)
{
    fixture *f = *state;
    test_output o;
    test_run(&o, mpb_tool, "stdout", "report --findings -e %lld '%s'",
             (long long)f->hundred, f->db);
    assert_int_equal(o.status, 0);
    says(&o, "\n  t:\n    all configurations, fastest: a/x (time ratio 0.1 "
             "to b/y on 100 problems, adjusted p = ");
    says(&o, ")\n    all configurations, best paths: no significant "
             "difference\n");
    /* The p value: all 100 log ratios tie, W+ = 0 against a mean of 2525
     * (normal approximation): far below 1e-10. */
    const char *p = strstr(o.text, "adjusted p = ");
    assert_non_null(p);
    double v = strtod(p + strlen("adjusted p = "), NULL);
    assert_true(v > 0 && v < 1e-10);
}

int main(void)
{
    if (test_built_program("tools/mpb", mpb_tool, sizeof mpb_tool) != 0)
        return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_set_table_with_intervals),
        cmocka_unit_test(by_scene_is_the_table_of_before),
        cmocka_unit_test(bad_by),
        cmocka_unit_test(one_run_in_ten_is_no_finding),
        cmocka_unit_test(ten_times_faster_on_a_hundred_is),
    };
    return cmocka_run_group_tests(tests, setup, test_store_teardown);
}
