/* test_report_findings.c - `mpb report --findings` on a database written
 * through the store, with numbers chosen so that each of the paper's
 * findings holds, holds in part, or cannot be checked; the built tool's
 * verdicts are compared with those worked out by hand. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "test_store.h"

static char mpb_tool[4096];     /* the built mpb */
static char dir[64], db[96];

enum { RRTC, RRT, ARA, NUM_CONFIGS };
enum { KITCHEN, TABLETOP, NARROW, NUM_SCENES };

/* One query per scene; a run's total time and final path length. */
typedef struct run_spec {
    int    cfg, scene, rep, success;
    double time, length;
} run_spec;

/*
 * kitchen:  ARA* shortest (8) with no spread; RRTConnect fastest.
 * tabletop: ARA* shortest; RRT (0.5 s) faster than RRTConnect (1.5 s).
 * narrow:   RRTConnect's path (20) beats ARA*'s (25); 2 of 5 runs succeed,
 *           and the successful ones are the slowest of the experiment;
 *           one path each, so no spread to compare.
 */
static const run_spec runs[] = {
    {RRTC, KITCHEN, 0, 1, 1.0, 10.0},  {RRTC, KITCHEN, 1, 1, 2.0, 12.0},
    {RRT, KITCHEN, 0, 1, 3.0, 9.0},    {RRT, KITCHEN, 1, 1, 5.0, 11.0},
    {ARA, KITCHEN, 0, 1, 4.0, 8.0},    {ARA, KITCHEN, 1, 1, 3.0, 8.0},
    {RRTC, TABLETOP, 0, 1, 1.5, 10.0}, {RRTC, TABLETOP, 1, 1, 1.5, 14.0},
    {RRT, TABLETOP, 0, 1, 0.5, 12.0},  {RRT, TABLETOP, 1, 1, 0.5, 12.0},
    {ARA, TABLETOP, 0, 1, 3.0, 7.0},   {ARA, TABLETOP, 1, 1, 3.0, 7.0},
    {RRTC, NARROW, 0, 1, 10.0, 20.0},  {RRTC, NARROW, 1, 0, 60.0, 0.0},
    {RRT, NARROW, 0, 0, 60.0, 0.0},    {RRT, NARROW, 1, 0, 60.0, 0.0},
    {ARA, NARROW, 0, 1, 6.0, 25.0},
};
#define NUM_RUNS ((int)(sizeof runs / sizeof runs[0]))

static int64_t cfg_id[NUM_CONFIGS], query_id[NUM_SCENES], run_id[NUM_RUNS];

/* Send and finish the run with this id as r says. */
static void finish_run(mpb_store *s, int64_t id, const run_spec *r)
{
    char uid[32];
    snprintf(uid, sizeof uid, "uid-%lld", (long long)id);
    assert_int_equal(mpb_store_run_sent(s, id, uid, "p"), MPB_OK);
    mpb_named m[] = {{"path_length", r->length}};
    mpb_stage_record st = {.name = "raw", .valid = r->success,
                           .verdict = r->success ? "valid" : "collision",
                           .verdict_segment = -1, .num_metrics = 1,
                           .metrics = m};
    mpb_run_record rec = {
        .run_id = id, .attempt_id = uid, .planner_id = "p",
        .status = r->success ? "solved" : "timeout",
        .claimed_success = r->success, .success = r->success,
        .time_total = r->time, .time_raw = r->time,
        .num_stages = r->success, .stages = &st,
    };
    assert_int_equal(mpb_store_run_finish(s, &rec), MPB_OK);
}

/* Every unfinished run in the order the store gives them; [0].attempts
 * counts them. */
static int collect_rows(void *ud, const mpb_run_row *row)
{
    mpb_run_row *out = ud;
    out[++out[0].attempts] = *row;
    out[out[0].attempts].attempt_id = NULL;
    return 0;
}

static void finish(mpb_store *s, int i)
{
    finish_run(s, run_id[i], &runs[i]);
}

static int setup(void **state)
{
    (void)state;
    int64_t exp, scene;
    mpb_store *s = test_store_new(dir, sizeof dir, db, sizeof db, "findings");

    exp = test_store_experiment(s, "paper", "paper.yaml", "h", 2, 60.0);
    static const char *const cfg[NUM_CONFIGS][2] = {
        {"ompl", "RRTConnect"}, {"ompl", "RRT"}, {"arastar", "ARAstar"},
    };
    for (int c = 0; c < NUM_CONFIGS; c++)
        cfg_id[c] = test_store_config(s, exp, cfg[c][0], cfg[c][1], "");
    static const char *const scene_name[NUM_SCENES] = {"kitchen", "tabletop",
                                                       "narrow_passage"};
    for (int k = 0; k < NUM_SCENES; k++) {
        scene = test_store_scene(s, exp, scene_name[k], scene_name[k],
                                 scene_name[k]);
        query_id[k] = test_store_query(s, scene, "g1");
    }
    for (int i = 0; i < NUM_RUNS; i++)
        run_id[i] = test_store_run(s, exp, cfg_id[runs[i].cfg],
                                   query_id[runs[i].scene], runs[i].rep, i);
    for (int i = 0; i < NUM_RUNS; i++)
        finish(s, i);
    mpb_store_close(s);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    test_remove_dir(dir);
    return 0;
}

/* The last run_tool()'s output, stdout and stderr together. */
static test_output last;
static const char *const out = last.text;

/* `mpb report ARGS DB` run as a user runs it (test_tool.h): its exit
 * status. */
static int run_tool(const char *args)
{
    test_run(&last, mpb_tool, "both", "report %s '%s'", args, db);
    return last.status;
}

static void assert_says(const char *line)
{
    if (strstr(out, line) == NULL) {
        /* All of it: cmocka's message would cut it short. */
        fprintf(stderr, "%s", out);
        fail_msg("expected \"%s\" in the output above", line);
    }
}

static void test_paper_findings(void **state)
{
    (void)state;
    assert_int_equal(run_tool("--findings"), 0);
    /* narrow: ARA*'s one path has no spread to speak of. */
    assert_says("[holds] ARA* has zero spread in path length (2 of 2 scenes)");
    assert_says("[holds in part] ARA* has the shortest paths (2 of 3 scenes)");
    assert_says("kitchen: sigma(l_p) 0 rad; l_p 8 rad, next ompl/RRT");
    assert_says("narrow_passage: sigma(l_p) - (no query run twice); l_p 25 rad, beaten by "
                "ompl/RRTConnect (20 rad)");
    assert_says("[holds in part] RRTConnect is the fastest sampling-based "
                "planner outside the narrow passage (1 of 2 scenes)");
    assert_says("kitchen: ompl/RRTConnect 1.5 s (success 100%), next ompl/RRT (4 s, "
                "success 100%)");
    assert_says("tabletop: ompl/RRTConnect 1.5 s (success 100%), beaten by ompl/RRT "
                "(0.5 s, success 100%)");
    assert_says("[holds] the narrow passage is the hardest environment "
                "(2 of 2 measures)");
    assert_says("lowest success rate: narrow_passage (40%; next kitchen 100%)");
    /* narrow: (10 + 6) / 2; next, kitchen: (1 + 2 + 3 + 5 + 4 + 3) / 6. */
    assert_says("longest mean total time tau_t: narrow_passage (8 s; next "
                "kitchen 3 s)");
}

static void test_scene_lines(void **state)
{
    (void)state;
    assert_int_equal(run_tool("--findings"), 0);
    /* kitchen: mean times 1.5 (RRTC), 4 (RRT), 3.5 (ARA*). */
    assert_says("kitchen: success 100%; fastest ompl/RRTConnect (tau_t 1.5 s, "
                "success 100%); shortest paths arastar/ARAstar (l_p 8 rad, "
                "success 100%); least spread in l_p arastar/ARAstar (sigma 0 "
                "rad, success 100%).");
    /* narrow: one path each for RRTConnect and ARA*: no spread named;
     * RRTConnect solved one run of two, ARA* its one. */
    assert_says("narrow_passage: success 40%; fastest arastar/ARAstar (tau_t "
                "6 s, success 100%); shortest paths ompl/RRTConnect (l_p 20 "
                "rad, success 50%).\n");
}

/* Findings are sentences: with another format they would break it. */
static void test_findings_with_text_only(void **state)
{
    (void)state;
    static const char *const other[] = {"json", "csv", "markdown", "latex"};
    for (size_t i = 0; i < sizeof other / sizeof *other; i++) {
        char args[64], want[160];
        snprintf(args, sizeof args, "--findings --format %s", other[i]);
        assert_int_equal(run_tool(args), 2);
        snprintf(want, sizeof want, "mpb report: --findings is plain text, "
                 "not for --format %s (try 'mpb report --help')\n", other[i]);
        assert_string_equal(out, want);
    }
    assert_int_equal(run_tool("--findings --format text"), 0);
    assert_says("The paper's findings, checked here:");
    assert_int_equal(run_tool("--help"), 0);
    assert_says("[--findings] [-o FILE] DB\n");
}

/* An experiment whose one run has not finished: no success rate yet. */
static void test_nothing_finished(void **state)
{
    (void)state;
    mpb_store *s;
    int64_t exp, cfg, scene, query;
    assert_int_equal(mpb_store_open(db, 0, &s), MPB_OK);
    exp = test_store_experiment(s, "waiting", "w.yaml", "h", 1, 60.0);
    cfg = test_store_config(s, exp, "ompl", "RRT", "");
    scene = test_store_scene(s, exp, "empty", "empty", "empty");
    query = test_store_query(s, scene, "g1");
    assert_int_equal(mpb_store_run_add(s, exp, cfg, query, 0, 0), MPB_OK);
    mpb_store_close(s);
    char args[64];
    snprintf(args, sizeof args, "--findings -e %lld", (long long)exp);
    assert_int_equal(run_tool(args), 0);
    assert_says("  empty: no runs finished yet.\n");
    assert_null(strstr(out, "nan"));
}

/*
 * Findings that nothing here could contradict are not checked: ARA* ran
 * once per query (its sigma is 0 by convention, not by measurement), and
 * RRTConnect is the only sampling-based planner (nothing to be faster
 * than). Nor is ARA* named for the least spread: RRTConnect, whose two
 * paths of 10 and 12 rad give sigma sqrt(2), is.
 */
static void test_what_cannot_fail_is_not_checked(void **state)
{
    (void)state;
    mpb_store *s;
    int64_t exp, cfg[2], scene, query[2], id[3];
    assert_int_equal(mpb_store_open(db, 0, &s), MPB_OK);
    exp = test_store_experiment(s, "once", "o.yaml", "h", 2, 60.0);
    cfg[0] = test_store_config(s, exp, "ompl", "RRTConnect", "");
    cfg[1] = test_store_config(s, exp, "arastar", "ARAstar", "");
    scene = test_store_scene(s, exp, "shelf", "shelf", "shelf");
    for (int k = 0; k < 2; k++)
        query[k] = test_store_query(s, scene, k ? "g2" : "g1");
    /* RRTConnect twice on g1; ARA* once on each query. */
    const run_spec spec[3] = {{0, 0, 0, 1, 1.0, 10.0}, {0, 0, 1, 1, 1.0, 12.0},
                              {1, 0, 0, 1, 2.0, 8.0}};
    assert_int_equal(mpb_store_run_add(s, exp, cfg[0], query[0], 0, 1), MPB_OK);
    assert_int_equal(mpb_store_run_add(s, exp, cfg[0], query[0], 1, 2), MPB_OK);
    assert_int_equal(mpb_store_run_add(s, exp, cfg[1], query[0], 0, 3), MPB_OK);
    assert_int_equal(mpb_store_run_add(s, exp, cfg[1], query[1], 0, 4), MPB_OK);
    mpb_run_row rows[5] = {{0}};
    assert_int_equal(mpb_store_runs_unfinished(s, exp, collect_rows, rows),
                     MPB_OK);
    assert_int_equal(rows[0].attempts, 4);
    for (int i = 0; i < 3; i++)
        id[i] = rows[i + 1].id;
    for (int i = 0; i < 3; i++)
        finish_run(s, id[i], &spec[i]);
    finish_run(s, rows[4].id, &spec[2]);
    mpb_store_close(s);

    char args[64];
    snprintf(args, sizeof args, "--findings -e %lld", (long long)exp);
    assert_int_equal(run_tool(args), 0);
    assert_says("[not checked] ARA* has zero spread in path length (0 of 0 "
                "scenes)");
    assert_says("shelf: sigma(l_p) - (no query run twice); l_p 8 rad, next "
                "ompl/RRTConnect (11 rad)");
    assert_says("[not checked] RRTConnect is the fastest sampling-based "
                "planner outside the narrow passage (0 of 0 scenes)");
    assert_says("least spread in l_p ompl/RRTConnect (sigma 1.41 rad, success "
                "100%).");
}

/* A one-scene, one-query experiment "name" of the configurations cfg
 * (name, planner, algorithm; n_cfg of them) and the runs spec (their cfg
 * the index into cfg, scene unused), stored and finished; its id. */
static int64_t one_scene_experiment(const char *name,
                                    const char *const (*cfg)[3], int n_cfg,
                                    const run_spec *spec, int n_spec)
{
    mpb_store *s;
    int64_t exp, cfg_ids[8], scene, query;
    assert_true(n_cfg <= 8 && n_spec <= 16);
    assert_int_equal(mpb_store_open(db, 0, &s), MPB_OK);
    exp = test_store_experiment(s, name, "x.yaml", "h", 3, 60.0);
    for (int c = 0; c < n_cfg; c++)
        assert_int_equal(mpb_store_planner_config_add(s, exp, cfg[c][0],
                         cfg[c][1], cfg[c][2], "", &cfg_ids[c]), MPB_OK);
    scene = test_store_scene(s, exp, "narrow_passage", "narrow", "narrow");
    query = test_store_query(s, scene, "g1");
    for (int i = 0; i < n_spec; i++)
        assert_int_equal(mpb_store_run_add(s, exp, cfg_ids[spec[i].cfg], query,
                                           spec[i].rep, i + 1), MPB_OK);
    mpb_run_row rows[17] = {{0}};
    assert_int_equal(mpb_store_runs_unfinished(s, exp, collect_rows, rows),
                     MPB_OK);
    assert_int_equal(rows[0].attempts, n_spec);
    for (int i = 0; i < n_spec; i++)
        finish_run(s, rows[i + 1].id, &spec[i]);
    mpb_store_close(s);
    return exp;
}

/* ARA* alone: its paths are the shortest of one, which is no finding. */
static void test_shortest_of_one_is_not_checked(void **state)
{
    (void)state;
    static const char *const cfg[][3] = {{"arastar/ARAstar", "arastar",
                                          "ARAstar"}};
    const run_spec spec[] = {{0, 0, 0, 1, 2.0, 8.0}};
    int64_t exp = one_scene_experiment("alone", cfg, 1, spec, 1);
    char args[64];
    snprintf(args, sizeof args, "--findings -e %lld", (long long)exp);
    assert_int_equal(run_tool(args), 0);
    assert_says("[not checked] ARA* has the shortest paths (0 of 0 scenes)");
    assert_says("narrow_passage: sigma(l_p) - (no query run twice); l_p 8 "
                "rad, no other planner's path to compare\n");
    assert_null(strstr(out, "nan"));
}

/*
 * RRT solves 2 of 3 runs, quickly; RRTConnect all 3, more slowly. The
 * fastest is named among the planners with the best success rate, and
 * the faster one that failed runs is said beside it with its rate.
 */
static void test_fastest_among_the_most_successful(void **state)
{
    (void)state;
    static const char *const cfg[][3] = {
        {"ompl/RRT", "ompl", "RRT"}, {"ompl/RRTConnect", "ompl", "RRTConnect"}};
    const run_spec spec[] = {
        {0, 0, 0, 1, 0.5, 9.0}, {0, 0, 1, 1, 0.5, 9.0}, {0, 0, 2, 0, 60.0, 0.0},
        {1, 0, 0, 1, 1.0, 9.0}, {1, 0, 1, 1, 1.0, 9.0}, {1, 0, 2, 1, 1.0, 9.0}};
    int64_t exp = one_scene_experiment("narrow", cfg, 2, spec, 6);
    char args[64];
    snprintf(args, sizeof args, "--findings -e %lld", (long long)exp);
    assert_int_equal(run_tool(args), 0);
    assert_says("narrow_passage: success 83%; fastest ompl/RRTConnect (tau_t "
                "1 s, success 100%; ompl/RRT faster, 0.5 s, at 67% success)");
}

static void test_tables_alone_without_option(void **state)
{
    (void)state;
    assert_int_equal(run_tool(""), 0);
    assert_null(strstr(out, "Findings"));
    assert_non_null(strstr(out, "Scene kitchen"));
}

int main(void)
{
    if (test_built_program("tools/mpb", mpb_tool, sizeof mpb_tool) != 0)
        return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_paper_findings),
        cmocka_unit_test(test_scene_lines),
        cmocka_unit_test(test_tables_alone_without_option),
        cmocka_unit_test(test_nothing_finished),
        cmocka_unit_test(test_what_cannot_fail_is_not_checked),
        cmocka_unit_test(test_findings_with_text_only),
        cmocka_unit_test(test_shortest_of_one_is_not_checked),
        cmocka_unit_test(test_fastest_among_the_most_successful),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
