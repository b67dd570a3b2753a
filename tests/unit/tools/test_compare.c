/* test_compare.c - `mpb compare`, run as a user runs it: the built tool on
 * a database written through the store, its numbers checked against
 * values worked out by hand (exact signed-rank p values by counting sign
 * patterns), and its errors.
 *
 * One experiment, time limit 10 s, one run per problem, configurations
 * A = a/fast and B = b/slow. Problem set s1 (scenes s1/0001-0008): A
 * solves problem i in i s; B in 2i s for i <= 5 and fails 6-8; both
 * solved paths of 1.0 (A) and 1.5 (B). Set s2 (s2/0001-0003): A fails
 * (at 10 s), B solves in 1 s. */
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
} fixture;

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    mpb_store *s = test_store_new(f->dir, sizeof f->dir, f->db, sizeof f->db,
                                  "compare");
    int64_t exp = test_store_experiment(s, "sets", "sets.yaml", "h", 1, 10.0);
    int64_t cfg[2] = {test_store_config(s, exp, "a", "fast", ""),
                      test_store_config(s, exp, "b", "slow", "")};
    int64_t query[11], run[2][11];
    for (int q = 0; q < 11; q++) {
        char name[32];
        snprintf(name, sizeof name, "s%d/%04d", q < 8 ? 1 : 2,
                 q < 8 ? q + 1 : q - 7);
        query[q] = test_store_query(s, test_store_scene(s, exp, name, "h", "s"),
                                    "q");
        for (int c = 0; c < 2; c++)
            run[c][q] = test_store_run(s, exp, cfg[c], query[q], 0, 2 * q + c);
    }
    for (int q = 0; q < 8; q++) {
        test_store_finish(s, run[0][q], 1, q + 1.0, 1.0);
        if (q < 5)
            test_store_finish(s, run[1][q], 1, 2.0 * (q + 1), 1.5);
        else
            test_store_finish(s, run[1][q], 0, 10.0, NAN);
    }
    for (int q = 8; q < 11; q++) {
        test_store_finish(s, run[0][q], 0, 10.0, NAN);
        test_store_finish(s, run[1][q], 1, 1.0, 1.5);
    }
    mpb_store_close(s);
    *state = f;
    return 0;
}

/* The CSV row of set for the pair; "" if none. */
static const char *row_of(const test_output *o, const char *set)
{
    static char line[1024];
    char key[128];
    snprintf(key, sizeof key, "\n\"%s\",\"a/fast\",\"b/slow\",", set);
    const char *r = strstr(o->text, key);
    line[0] = '\0';
    if (r != NULL) {
        r += 1;
        size_t n = strcspn(r, "\n");
        snprintf(line, sizeof line, "%.*s", (int)n, r);
    }
    return line;
}

/* The signed-rank test's p by the normal approximation with ties (the
 * exact one is for untied differences: test_inference.c): W+ against its
 * mean, the variance with the ties' correction, a continuity correction. */
static double normal_p(double w, double mean, double var)
{
    return erfc((fabs(w - mean) - 0.5) / sqrt(var) / sqrt(2.0));
}

/* s1: ratios A/B 0.5 (x5, tied), 0.6, 0.7, 0.8: median 0.5; 8 samples
 * reach 95 % only with the range [0.5, 0.8]; W+ = 0 of mean 18, variance
 * 8*9*17/24 - (5^3 - 5)/48 = 48.5. Lengths 1/1.5 on the 5 both solved,
 * all tied: W+ = 0 of 7.5, variance 13.75 - 2.5. s2: A/B = 10 on 3
 * problems: W+ = 6 of 3, variance 3.5 - 0.5. All 11: W+ = 30 of 33,
 * variance 126.5 - (120 + 24)/48. */
static void a_pair_per_set_and_overall(void **state)
{
    fixture *f = *state;
    test_output o;
    test_run(&o, mpb_tool, "stdout", "compare -f csv '%s' a/fast b/slow",
             f->db);
    assert_int_equal(o.status, 0);
    double p, q;
    assert_int_equal(sscanf(row_of(&o, "s1"), "\"s1\",\"a/fast\",\"b/slow\","
                            "8,5,3,0,0,8,0.5,0.5,0.8,%lg,%*g,5,0.666666667,"
                            "0.666666667,0.666666667,%lg", &p, &q), 2);
    assert_float_equal(p, normal_p(0, 18, 48.5), 1e-8);
    assert_float_equal(q, normal_p(0, 7.5, 11.25), 1e-8);
    assert_int_equal(sscanf(row_of(&o, "s2"), "\"s2\",\"a/fast\",\"b/slow\","
                            "3,0,0,3,0,3,10,10,10,%lg,%*g,0,nan,nan,nan,nan",
                            &p), 1);
    assert_float_equal(p, normal_p(6, 3, 3), 1e-8);
    assert_int_equal(sscanf(row_of(&o, "all problems"), "\"all problems\","
                            "\"a/fast\",\"b/slow\",11,5,3,3,0,11,0.6,0.5,10,"
                            "%lg", &p), 1);
    assert_float_equal(p, normal_p(30, 33, 123.5), 1e-8);
}

static void the_text_says_who_is_faster_only_where_the_test_does(void **state)
{
    fixture *f = *state;
    test_output o;
    test_run(&o, mpb_tool, "stdout", "compare -s s1 '%s' a/fast b/slow", f->db);
    assert_int_equal(o.status, 0);
    assert_non_null(strstr(o.text, "solved: both 5, only a/fast 3, only "
                                   "b/slow 0, neither 0"));
    assert_non_null(strstr(o.text, "p = 0.012: a/fast faster"));
    assert_non_null(strstr(o.text, "p = 0.037: a/fast shorter"));
    assert_null(strstr(o.text, "s2"));
    test_run(&o, mpb_tool, "stdout", "compare -s s2 '%s'", f->db);
    assert_int_equal(o.status, 0);
    assert_non_null(strstr(o.text, "no significant difference in time"));
}

static void every_pair_with_holms_adjustment(void **state)
{
    fixture *f = *state;
    test_output o;
    test_run(&o, mpb_tool, "stdout", "compare '%s'", f->db);
    assert_int_equal(o.status, 0);
    /* One pair: Holm changes nothing; s1's difference is significant. */
    assert_non_null(strstr(o.text, "s1: time ratio row/column"));
    assert_non_null(strstr(o.text, "a/fast faster than b/slow: time ratio "
                                   "0.5, adjusted p = 0.012 (8 problems)"));
    assert_non_null(strstr(o.text, "0.5*"));
}

static void bad_input_is_one_line(void **state)
{
    fixture *f = *state;
    test_output o;
    test_run(&o, mpb_tool, "stderr", "compare '%s' a/fast c/none", f->db);
    assert_int_equal(o.status, 1);
    assert_non_null(strstr(o.text, "no configuration 'c/none' (a/fast, "
                                   "b/slow)"));
    test_run(&o, mpb_tool, "stderr", "compare -s s9 '%s'", f->db);
    assert_int_equal(o.status, 1);
    assert_non_null(strstr(o.text, "no problem set 's9' (s1, s2)"));
    test_run(&o, mpb_tool, "stderr", "compare '%s' a/fast", f->db);
    assert_int_equal(o.status, 2);
    test_run(&o, mpb_tool, "stderr", "compare -f xml '%s'", f->db);
    assert_int_equal(o.status, 2);
    test_run(&o, mpb_tool, "stderr", "compare '%s/none.db'", f->dir);
    assert_int_equal(o.status, 1);
    assert_int_equal((int)strcspn(o.text, "\n") + 1, (int)strlen(o.text));
}

int main(void)
{
    if (test_built_program("tools/mpb", mpb_tool, sizeof mpb_tool) != 0)
        return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_pair_per_set_and_overall),
        cmocka_unit_test(the_text_says_who_is_faster_only_where_the_test_does),
        cmocka_unit_test(every_pair_with_holms_adjustment),
        cmocka_unit_test(bad_input_is_one_line),
    };
    return cmocka_run_group_tests(tests, setup, test_store_teardown);
}
