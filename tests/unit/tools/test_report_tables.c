/* test_report_tables.c - `mpb report`'s text tables, run as a user runs
 * it: the built tool on the databases of test_report_paper.h, its printed
 * numbers, scene by scene, checked against values worked out by hand. */
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

static void the_kitchen_table_matches_the_hand_computed_values(void **state)
{
    fixture *f = *state;
    output o;
    run(&o, "stdout", "report --experiment 1 '%s'", f->db);
    assert_int_equal(o.status, 0);

    /* 6 runs of A and 2 of B are finished; B's k2 repetition 1 is not. */
    assert_non_null(strstr(o.text, KITCHEN "8 runs\n"));
    assert_non_null(strstr(o.text, "1 more run not finished yet"));
    /* One column per configuration, named. */
    assert_non_null(strstr(o.text, "ompl/RRTConnect  ara/ARAstar\n"));

    /*
     * A (ompl/RRTConnect), successful runs only: k1 times 1, 2, 3 and k2
     * times 4, 6; the 60 s failure on k2 is out.
     *   tau_t mean 16/5 = 3.2; sd(k1) = 1, sd(k2) = sqrt(2): (1 + 1.41421)/2
     *   tau_r 0.9, 1.8, 2.7 | 3.6, 5.4: mean 2.88, (0.9 + 1.27279)/2 = 1.08640
     *   tau_o 0.1, 0.2, 0.3 | 0.4, 0.6: mean 0.32, (0.1 + 0.14142)/2 = 0.12071
     *   l_p   2, 4, 6 | 5, 5: mean 4.4, (2 + 0)/2 = 1
     *   kappa' 0.1, 0.2, 0.3 | 0.5, 0.7: mean 0.36, sigma 0.12071
     *   waypoints 10, 20, 30, 40, 50: 30
     *   s_r 5 of 6 finished: 83.3 %
     */
    assert_string_equal(cell(&o, KITCHEN, "tau_t (Mean, s)", A), "3.200");
    assert_string_equal(cell(&o, KITCHEN, "tau_t (sigma, s)", A), "1.207");
    assert_string_equal(cell(&o, KITCHEN, "tau_r (Mean, s)", A), "2.880");
    assert_string_equal(cell(&o, KITCHEN, "tau_r (sigma, s)", A), "1.086");
    assert_string_equal(cell(&o, KITCHEN, "tau_o (Mean, s)", A), "0.320");
    assert_string_equal(cell(&o, KITCHEN, "tau_o (sigma, s)", A), "0.121");
    assert_string_equal(cell(&o, KITCHEN, "l_p (Mean, rad)", A), "4.400");
    assert_string_equal(cell(&o, KITCHEN, "l_p (sigma, rad)", A), "1.000");
    assert_string_equal(cell(&o, KITCHEN, "kappa' (Mean, rad^2)", A), "0.360");
    assert_string_equal(cell(&o, KITCHEN, "kappa' (sigma, rad^2)", A), "0.121");
    assert_string_equal(cell(&o, KITCHEN, "waypoints (Mean)", A), "30.0");
    assert_string_equal(cell(&o, KITCHEN, "s_r (%)", A), "83.3");

    /* B (ara/ARAstar), one run per query: k1 succeeded (0.5 s, l_p 3),
     * k2 failed with l_p 77, which must not show. One successful run:
     * no sigma to compute, '-'. */
    assert_string_equal(cell(&o, KITCHEN, "tau_t (Mean, s)", B), "0.500");
    assert_string_equal(cell(&o, KITCHEN, "tau_t (sigma, s)", B), "-");
    assert_string_equal(cell(&o, KITCHEN, "tau_r (Mean, s)", B), "0.300");
    assert_string_equal(cell(&o, KITCHEN, "tau_o (Mean, s)", B), "0.200");
    assert_string_equal(cell(&o, KITCHEN, "l_p (Mean, rad)", B), "3.000");
    assert_string_equal(cell(&o, KITCHEN, "l_p (sigma, rad)", B), "-");
    assert_string_equal(cell(&o, KITCHEN, "kappa' (Mean, rad^2)", B), "1.500");
    assert_string_equal(cell(&o, KITCHEN, "waypoints (Mean)", B), "8.0");
    assert_string_equal(cell(&o, KITCHEN, "s_r (%)", B), "50.0");

    /* No run in KITCHEN measured clearance: no d_n rows there. */
    assert_string_equal(cell(&o, KITCHEN, "d_n (Mean, m)", A), "");
}

static void a_second_scene_has_its_own_table(void **state)
{
    fixture *f = *state;
    output o;
    run(&o, "stdout", "report -e 1 '%s'", f->db);
    assert_int_equal(o.status, 0);
    assert_non_null(strstr(o.text, TABLETOP "1 run\n"));
    /* KITCHEN's numbers are not in it, nor its unfinished run. */
    assert_string_equal(cell(&o, TABLETOP, "tau_t (Mean, s)", A), "7.000");
    assert_string_equal(cell(&o, TABLETOP, "tau_t (sigma, s)", A), "-");
    assert_string_equal(cell(&o, TABLETOP, "l_p (Mean, rad)", A), "8.000");
    /* 0.05: 3 significant digits, as every row's smallest value keeps. */
    assert_string_equal(cell(&o, TABLETOP, "d_n (Mean, m)", A), "0.0500");
    assert_string_equal(cell(&o, TABLETOP, "s_r (%)", A), "100.0");
    /* B never ran there: nothing to show. */
    assert_string_equal(cell(&o, TABLETOP, "tau_t (Mean, s)", B), "-");
    assert_string_equal(cell(&o, TABLETOP, "d_n (Mean, m)", B), "-");
    assert_string_equal(cell(&o, TABLETOP, "s_r (%)", B), "-");
    const char *t = strstr(o.text, TABLETOP);
    assert_null(strstr(t, "not finished"));
}

static void a_chosen_stage_gives_its_own_metrics(void **state)
{
    fixture *f = *state;
    output o;
    run(&o, "stdout", "report --stage raw --experiment=1 '%s'", f->db);
    assert_int_equal(o.status, 0);
    assert_non_null(strstr(o.text, "stage 'raw'"));
    /* A's raw lengths 10, 20, 30 | 40, and 60 whose raw stage failed
     * verification: mean 25, sigma (10 + 0)/2; times do not depend on the
     * stage. B has no raw stage. */
    assert_string_equal(cell(&o, KITCHEN, "l_p (Mean, rad)", A), "25.000");
    /* k2's one raw path is no spread measured: the sigma is marked. */
    assert_string_equal(cell(&o, KITCHEN, "l_p (sigma, rad)", A), "5.000*");
    assert_non_null(strstr(o.text, "\n* sigma counts a query with one "
                           "successful run as 0 spread\n"));
    /* TABLETOP has no sigma, so no mark. */
    assert_null(strstr(strstr(o.text, "TABLETOP"), "*"));
    assert_non_null(strstr(o.text, "\nompl/RRTConnect: 1 successful run "
                           "whose stage 'raw' failed verification, its path "
                           "metrics not counted above\n"));
    assert_string_equal(cell(&o, KITCHEN, "kappa' (Mean, rad^2)", A), "-");
    assert_string_equal(cell(&o, KITCHEN, "tau_t (Mean, s)", A), "3.200");
    assert_string_equal(cell(&o, KITCHEN, "l_p (Mean, rad)", B), "-");
    assert_string_equal(cell(&o, KITCHEN, "s_r (%)", B), "50.0");
    run(&o, "stdout", "report -f markdown --stage raw -e 1 '%s'", f->db);
    assert_non_null(strstr(o.text, "| l_p (sigma, rad) | 5.000\\* |"));
    assert_non_null(strstr(o.text, "\n\\* sigma counts a query with one "
                           "successful run as 0 spread.\n"));
}

static void the_newest_experiment_is_the_default(void **state)
{
    fixture *f = *state;
    output o;
    run(&o, "stdout", "report '%s'", f->db);
    assert_int_equal(o.status, 0);
    assert_non_null(strstr(o.text,
                           "Scene NARROW_PASSAGE - experiment newer (2), 1 run\n"));
    assert_null(strstr(o.text, "KITCHEN"));
    assert_string_equal(cell(&o, "Scene NARROW_PASSAGE", "tau_t (Mean, s)", 0),
                        "0.250");
    /* Small values keep 3 significant digits rather than print as 0.000. */
    assert_string_equal(cell(&o, "Scene NARROW_PASSAGE", "tau_o (Mean, s)", 0),
                        "0.000400");
}

/*
 * A row whose values span four decades: 0.004895 s and 5.21e-7 s. At the
 * row's 6 decimals the second would keep one digit (0.000001); it keeps
 * three in exponent form. The configuration named with a UTF-8 letter
 * lines up with the rule below it, counted in the columns a terminal
 * gives it (the CJK ones take two), not in bytes.
 */
static void tiny_values_and_wide_names(void **state)
{
    fixture *f = *state;
    char path[128];
    mpb_store *s;
    int64_t exp, cfg[2], scene, query, ids[2];
    snprintf(path, sizeof path, "%s/tiny.db", f->dir);
    assert_int_equal(mpb_store_open(path, 0, &s), MPB_OK);
    exp = test_store_experiment(s, "tiny", "t.yaml", "h4", 1, 10.0);
    /* Named apart from its algorithm, "tuned". */
    assert_int_equal(mpb_store_planner_config_add(s, exp,
                                                  "x/\u8abf\u6574_\u00fc", "x",
                                                  "tuned", "", &cfg[0]),
                     MPB_OK);
    cfg[1] = test_store_config(s, exp, "x", "plain", "");
    scene = test_store_scene(s, exp, "S\u00e4ule", "n", "n");
    query = test_store_query(s, scene, "q");
    for (int c = 0; c < 2; c++) {
        ids[c] = test_store_run(s, exp, cfg[c], query, 0, c);
        /* kappa' 2.17e-30: the rounding a straight path once gave. */
        run_spec r = {0, 0, 0, 1, 1, c ? 5.21e-7 : 0.004895, 0, 0, -1.0, 1.0,
                      c ? 2.17e-30 : 0.0, 2, -1, 0};
        /* The first run of x/plain built the world: 0.508 s, outside its
         * tau_t. */
        if (c == 1)
            next_world_setup = 0.508;
        /* The daemon verified the first configuration's run in 0.25 s. */
        if (c == 0)
            next_verify = 0.25;
        /* ... and its planner peaked at 48.5 MB; the other's said none. */
        if (c == 0)
            next_memory = 48.5;
        finish(s, ids[c], &r);
    }
    mpb_store_close(s);

    output o;
    run(&o, "stdout", "report '%s'", path);
    assert_int_equal(o.status, 0);
    const char *title = "Scene S\u00e4ule - experiment tiny";
    assert_string_equal(cell(&o, title, "tau_t (Mean, s)", 0), "0.004895");
    assert_string_equal(cell(&o, title, "tau_t (Mean, s)", 1), "5.21e-07");
    assert_string_equal(cell(&o, title, "world setup (Mean, s)", 0), "-");
    assert_string_equal(cell(&o, title, "world setup (Mean, s)", 1), "0.508");
    assert_string_equal(cell(&o, title, "verify (Mean, s)", 0), "0.250");
    assert_string_equal(cell(&o, title, "verify (Mean, s)", 1), "-");
    assert_string_equal(cell(&o, title, "memory (Mean, MB)", 0), "48.500");
    assert_string_equal(cell(&o, title, "memory (Mean, MB)", 1), "-");
    /* Rounding noise is no data: 0 beside 0, not 2.17e-30 beside
     * 0.000000. */
    assert_string_equal(cell(&o, title, "kappa' (Mean, rad^2)", 0), "0.000");
    assert_string_equal(cell(&o, title, "kappa' (Mean, rad^2)", 1), "0.000");
    /* The header, the rule and a row: the same number of characters. */
    const char *head = strstr(o.text, "\nMetric");
    assert_non_null(head);
    int widths[3] = {0};
    const char *p = head + 1;
    for (int line = 0; line < 3; line++) {
        for (; *p != '\n'; p++)
            /* A lead byte is a column; U+4000-U+9FFF (E4-E9) two. */
            widths[line] += (((unsigned char)*p & 0xC0) != 0x80) +
                            ((unsigned char)*p >= 0xE4 &&
                             (unsigned char)*p <= 0xE9);
        p++;
    }
    assert_int_equal(widths[0], widths[1]);
    assert_int_equal(widths[2], widths[1]);
}

int main(void)
{
    if (test_built_program("tools/mpb", mpb_tool, sizeof mpb_tool) != 0)
        return 1;

    const struct CMUnitTest tests[] = {
        cmocka_unit_test(the_kitchen_table_matches_the_hand_computed_values),
        cmocka_unit_test(a_second_scene_has_its_own_table),
        cmocka_unit_test(a_chosen_stage_gives_its_own_metrics),
        cmocka_unit_test(the_newest_experiment_is_the_default),
        cmocka_unit_test(tiny_values_and_wide_names),
    };
    return cmocka_run_group_tests(tests, setup, test_store_teardown);
}
