/* test_report_approach.c - `mpb report --findings` by approach, run as
 * a user runs it: columns grouped and labelled by each configuration's
 * approach, and the planners' claims counted against mpbench's verdicts. */
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

/* One run of a configuration of the approach experiment: the planner's
 * status, its final stage's verdict and mpbench's success. */
static void finish_claim(mpb_store *s, int64_t run_id, const char *status,
                         int valid, int success)
{
    char uid[32];
    snprintf(uid, sizeof uid, "uid-%lld", (long long)run_id);
    assert_int_equal(mpb_store_run_sent(s, run_id, uid, "planner-1"), MPB_OK);
    mpb_named m[] = {{"path_length", 1.0}, {"time", 0.01}};
    mpb_stage_record st = {.name = "raw", .valid = valid,
                           .verdict = valid ? "valid" : "collision",
                           .verdict_segment = -1, .num_metrics = 2,
                           .metrics = m};
    mpb_run_record rec = {
        .run_id = run_id, .attempt_id = uid, .planner_id = "planner-1",
        .status = status, .claimed_success = strcmp(status, "solved") == 0,
        .success = success, .time_total = 0.5, .time_raw = 0.5,
        .time_other = 0, .num_stages = 1, .stages = &st,
        .verify_time = NAN, .memory = NAN,
    };
    assert_int_equal(mpb_store_run_finish(s, &rec), MPB_OK);
}

static int each_run(void *ud, const mpb_run_row *row)
{
    int64_t (*ids)[2] = ud;
    ids[row->planner_config_id - 1][row->repetition] = row->id;
    return 0;
}

/*
 * Columns grouped and labelled by approach (sampling, search,
 * optimisation, hybrid, then none), whatever the order of the
 * configurations' ids; the claims counted both ways; the findings name
 * the best configuration of each approach from the data.
 */
static void columns_are_grouped_by_approach_and_claims_counted(void **state)
{
    fixture *f = *state;
    char db[128];
    mpb_store *s;
    int64_t exp, scene, query, cfg[4], ids[4][2] = {{0}};
    snprintf(db, sizeof db, "%s/approach.db", f->dir);
    assert_int_equal(mpb_store_open(db, 0, &s), MPB_OK);
    mpb_experiment_info e = {"kinds", "k.yaml", "h4", "text", 2, 10.0, NULL, 0};
    assert_int_equal(mpb_store_experiment_create(s, &e, &exp), MPB_OK);
    static const char *const names[4][3] = {
        {"null/straight_line", "null", NULL},
        {"srmp/wAstar", "srmp", "search"},
        {"klampt/sbl", "klampt", "sampling"},
        {"drake/KTO", "drake", "optimisation"},
    };
    for (int c = 0; c < 4; c++) {
        assert_int_equal(mpb_store_planner_config_add(s, exp, names[c][0],
                             names[c][1], strchr(names[c][0], '/') + 1, "",
                             &cfg[c]), MPB_OK);
        assert_int_equal(cfg[c], c + 1);
        if (names[c][2] != NULL)
            assert_int_equal(mpb_store_planner_config_set_approach(s, cfg[c],
                                 names[c][2], c == 1), MPB_OK);
    }
    /* A planner's word does not replace the file's: kept. */
    assert_int_equal(mpb_store_planner_config_set_approach(s, cfg[1],
                                                           "hybrid", 1),
                     MPB_OK);
    mpb_scene_info sc = {"wall", "planar", "r", "r", "planar", "w", "w"};
    assert_int_equal(mpb_store_scene_add(s, exp, &sc, &scene), MPB_OK);
    static const char *const joints[] = {"j"};
    static const double zero[] = {0.0}, one[] = {1.0};
    mpb_query_info q = {"w1", 1, joints, zero, MPB_GOAL_JOINTS, one, 0.01,
                        NULL, NULL};
    assert_int_equal(mpb_store_query_add(s, scene, &q, &query), MPB_OK);
    for (int c = 0; c < 4; c++)
        for (int rep = 0; rep < 2; rep++)
            assert_int_equal(mpb_store_run_add(s, exp, cfg[c], query, rep,
                                               rep), MPB_OK);
    assert_int_equal(mpb_store_runs_unfinished(s, exp, each_run, ids), MPB_OK);
    /* null: failed by its word, valid by mpbench's, twice. */
    finish_claim(s, ids[0][0], "failed", 1, 0);
    finish_claim(s, ids[0][1], "approximate", 1, 0);
    /* srmp: verified, then a claim refused. */
    finish_claim(s, ids[1][0], "solved", 1, 1);
    finish_claim(s, ids[1][1], "solved", 0, 0);
    /* klampt: verified twice. */
    finish_claim(s, ids[2][0], "solved", 1, 1);
    finish_claim(s, ids[2][1], "solved", 1, 1);
    /* drake: "infeasible" with a valid path, and a plain failure. */
    finish_claim(s, ids[3][0], "failed", 1, 0);
    finish_claim(s, ids[3][1], "failed", 0, 0);
    mpb_store_close(s);

    output o;
    run(&o, "stdout", "report --findings '%s'", db);
    assert_int_equal(o.status, 0);
    const char *approach = strstr(o.text, "\nApproach ");
    const char *metric = strstr(o.text, "\nMetric ");
    assert_non_null(approach);
    assert_non_null(metric);
    assert_true(approach < metric);
    /* sampling, search, optimisation, then the one that declares none,
     * each label over its column. */
    const char *a1 = strstr(approach, "sampling"), *a2 = strstr(approach, "search"),
               *a3 = strstr(approach, "optimisation"), *a4 = strstr(approach + 1, " -\n");
    assert_true(a1 && a2 && a3 && a4 && a1 < a2 && a2 < a3 && a3 < a4 &&
                a4 < metric);
    const char *m1 = strstr(metric, "klampt/sbl"), *m2 = strstr(metric, "srmp/wAstar"),
               *m3 = strstr(metric, "drake/KTO"), *m4 = strstr(metric, "null/straight_line");
    assert_true(m1 && m2 && m3 && m4 && m1 < m2 && m2 < m3 && m3 < m4);
    /* The counts, in that column order (the text's runs of spaces as
     * one). */
    static char sq[sizeof o.text];
    size_t n = 0;
    for (const char *p = o.text; *p; p++)
        if (!(*p == ' ' && n > 0 && sq[n - 1] == ' '))
            sq[n++] = *p;
    sq[n] = '\0';
    assert_non_null(strstr(sq, "\nclaimed 2 2 0 0\n"));
    assert_non_null(strstr(sq, "\nverified 2 1 0 0\n"));
    assert_non_null(strstr(sq, "\nrefused claims 0 1 0 0\n"));
    assert_non_null(strstr(sq, "\nunclaimed valid 0 0 1 2\n"));
    /* s_r stays the claims confirmed: the unclaimed valid paths are no
     * successes. */
    assert_non_null(strstr(sq, "\ns_r (%) 100.0 50.0 0.0 0.0\n"));
    assert_non_null(strstr(o.text, "best by approach: sampling klampt/sbl "
                                   "(success 100%, tau_t 0.5 s, 2 verified "
                                   "of 2 claimed, 0 unclaimed valid); search "
                                   "srmp/wAstar (success 50%, tau_t 0.5 s, 1 "
                                   "verified of 2 claimed, 0 unclaimed "
                                   "valid); optimisation none solved a run.\n"));
    /* The search-based planner of the paper's findings is the one of
     * approach search, whatever its family. */
    assert_non_null(strstr(o.text, "wall: sigma(l_p) - (no query run twice); "
                                   "l_p 1 rad, next klampt/sbl (1 rad)"));
    run(&o, "stdout", "report -f json '%s'", db);
    assert_int_equal(o.status, 0);
    assert_non_null(strstr(o.text, "\"approach\": \"sampling\""));
    assert_non_null(strstr(o.text, "\"approach\": null"));
    assert_non_null(strstr(o.text, "\"outcomes\": {\"unclaimed\": 1, "
                                   "\"verified\": 0, \"refused\": 0, "
                                   "\"late\": 0, \"unclaimed_valid\": 1}"));
    run(&o, "stdout", "report -f csv '%s'", db);
    assert_non_null(strstr(o.text, "\n1,kinds,wall,null/straight_line,"
                                   "unclaimed_valid_runs,,2,,2,0,\n"));
    run(&o, "stdout", "report -f markdown '%s'", db);
    assert_non_null(strstr(o.text, "| approach | sampling | search | "
                                   "optimisation | - |\n"));
}

int main(void)
{
    if (test_built_program("tools/mpb", mpb_tool, sizeof mpb_tool) != 0)
        return 1;

    const struct CMUnitTest tests[] = {
        cmocka_unit_test(columns_are_grouped_by_approach_and_claims_counted),
    };
    return cmocka_run_group_tests(tests, setup, test_store_teardown);
}
