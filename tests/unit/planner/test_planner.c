/*
 * test_planner.c - the planner side's helpers (results, parameters) and
 * mpb_planner_serve()'s checks and start-up, over memq:// so that no
 * network is needed. The protocol over UDP (acks, re-sends, repeated
 * requests) is exercised by the integration tests with real processes.
 */
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "mpbench/planner.h"

static void test_add_stage_copies(void **state)
{
    (void)state;
    mpb_plan_result_t res;
    memset(&res, 0, sizeof res);
    double wp[6] = { 0, 1, 2, 3, 4, 5 };

    assert_int_equal(mpb_result_add_stage(&res, "raw", 0.25, wp, 2, 3), MPB_OK);
    wp[0] = 99;     /* the stage holds a copy */
    assert_int_equal(mpb_result_add_stage(&res, "shortcut", 0.5, wp, 3, 2), MPB_OK);
    assert_int_equal(mpb_result_add_stage(&res, "empty", 0, NULL, 0, 3), MPB_OK);

    assert_int_equal(res.num_stages, 3);
    assert_string_equal(res.stages[0].name, "raw");
    assert_true(res.stages[0].time == 0.25);
    assert_int_equal(res.stages[0].num_waypoints, 2);
    assert_int_equal(res.stages[0].num_joints, 3);
    assert_int_equal(res.stages[0].num_values, 6);
    assert_true(res.stages[0].waypoints[0] == 0);
    assert_true(res.stages[0].waypoints[5] == 5);
    assert_true(res.stages[1].waypoints[0] == 99);
    assert_int_equal(res.stages[1].num_values, 6);
    assert_int_equal(res.stages[2].num_values, 0);
    mpb_result_clear(&res);
}

static void test_add_stage_bad_args(void **state)
{
    (void)state;
    mpb_plan_result_t res;
    memset(&res, 0, sizeof res);
    double wp[2] = { 0, 0 };
    assert_int_equal(mpb_result_add_stage(NULL, "raw", 0, wp, 1, 2), MPB_EINVAL);
    assert_int_equal(mpb_result_add_stage(&res, NULL, 0, wp, 1, 2), MPB_EINVAL);
    assert_int_equal(mpb_result_add_stage(&res, "raw", 0, NULL, 1, 2), MPB_EINVAL);
    assert_int_equal(mpb_result_add_stage(&res, "raw", 0, wp, -1, 2), MPB_EINVAL);
    assert_int_equal(mpb_result_add_stage(&res, "raw", 0, wp, 1, 40000), MPB_EINVAL);
    assert_int_equal(mpb_result_add_stage(&res, "raw", 0, wp, INT32_MAX, 2), MPB_EINVAL);
    assert_int_equal(res.num_stages, 0);
    mpb_result_clear(&res);
}

static void test_values_and_message(void **state)
{
    (void)state;
    mpb_plan_result_t res;
    memset(&res, 0, sizeof res);
    assert_int_equal(mpb_result_add_value(&res, "graph states", 42), MPB_OK);
    assert_int_equal(mpb_result_add_value(&res, "best cost", 1.5), MPB_OK);
    assert_int_equal(mpb_result_add_value(&res, NULL, 1), MPB_EINVAL);
    assert_int_equal(res.num_values, 2);
    assert_string_equal(res.values[1].name, "best cost");
    assert_true(res.values[0].value == 42);

    assert_int_equal(mpb_result_set_message(&res, "%d of %s", 3, "four"), MPB_OK);
    assert_string_equal(res.message, "3 of four");
    assert_int_equal(mpb_result_set_message(&res, "%s", "replaced"), MPB_OK);
    assert_string_equal(res.message, "replaced");

    mpb_result_clear(&res);
    assert_null(res.message);
    assert_null(res.values);
    assert_int_equal(res.num_values, 0);
    mpb_result_clear(&res);     /* clearing twice is harmless */
    mpb_result_clear(NULL);
}

/* What the helpers build is what lcm-gen's code encodes and frees. */
static void test_result_round_trip(void **state)
{
    (void)state;
    mpb_plan_result_t res;
    memset(&res, 0, sizeof res);
    double wp[4] = { 0.5, -0.5, 1.5, -1.5 };
    assert_int_equal(mpb_result_add_stage(&res, "raw", 0.125, wp, 2, 2), MPB_OK);
    assert_int_equal(mpb_result_add_stage(&res, "timed", 0.5, wp, 2, 2), MPB_OK);
    double times[2] = { 0.0, 0.75 };
    assert_int_equal(mpb_result_set_times(&res, 1, times, 2), MPB_OK);
    times[1] = 9;                           /* copied: no change */
    assert_int_equal(mpb_result_set_times(&res, 2, times, 2), MPB_EINVAL);
    assert_int_equal(mpb_result_set_times(&res, 0, NULL, 2), MPB_EINVAL);
    assert_int_equal(mpb_result_add_value(&res, "graph states", 7), MPB_OK);
    assert_int_equal(mpb_result_set_message(&res, "ok"), MPB_OK);
    res.attempt_id = strdup("0123456789abcdef0123456789abcdef");
    res.planner_id = strdup("test@host:1");
    res.status = MPB_PLAN_RESULT_T_SOLVED;

    int n = mpb_plan_result_t_encoded_size(&res);
    assert_true(n > 0);
    void *buf = malloc((size_t)n);
    assert_non_null(buf);
    assert_int_equal(mpb_plan_result_t_encode(buf, 0, n, &res), n);
    mpb_plan_result_t back;
    memset(&back, 0, sizeof back);
    assert_int_equal(mpb_plan_result_t_decode(buf, 0, n, &back), n);
    assert_string_equal(back.stages[0].name, "raw");
    assert_true(back.stages[0].waypoints[3] == -1.5);
    assert_int_equal(back.stages[0].num_times, 0);
    assert_int_equal(back.stages[1].num_times, 2);
    assert_true(back.stages[1].times[1] == 0.75);
    assert_true(back.values[0].value == 7);
    assert_string_equal(back.message, "ok");
    mpb_plan_result_t_decode_cleanup(&back);
    free(buf);

    mpb_result_clear(&res);
}

static void test_request_param(void **state)
{
    (void)state;
    mpb_param_t params[3] = {
        { "range", "0.5" }, { "goal_bias", "0.05" }, { "range", "9" },
    };
    mpb_plan_request_t req;
    memset(&req, 0, sizeof req);
    req.num_params = 3;
    req.params = params;
    assert_string_equal(mpb_request_param(&req, "range"), "0.5");
    assert_string_equal(mpb_request_param(&req, "goal_bias"), "0.05");
    assert_null(mpb_request_param(&req, "seed"));
    assert_null(mpb_request_param(NULL, "range"));
    assert_null(mpb_request_param(&req, NULL));
}

static int never_solve(void *user, const mpb_plan_request_t *req,
                       const mpb_solve_limits *lim, mpb_plan_result_t *res)
{
    (void)user;
    (void)req;
    (void)lim;
    (void)res;
    return MPB_OK;
}

static const char *const one_algorithm[] = { "a" };

static mpb_planner_def make_def(const char *name)
{
    mpb_planner_def def;
    memset(&def, 0, sizeof def);
    def.name = name;
    def.language = "c";
    def.version = "0";
    def.algorithms = one_algorithm;
    def.num_algorithms = 1;
    def.solve = never_solve;
    return def;
}

/* The shared options are taken out of argv; the rest is left alone. */
static void test_options(void **state)
{
    (void)state;
    char *argv[] = {"p", "--name", "ara", "-v", "--max-runs", "4",
                    "--lcm-url", "udpm://u", "--secret-file", "f", "--max-runs",
                    NULL};
    int argc = 11, left[11], num_left = 0;
    mpb_planner_options o = {.name = "default"};
    char err[128];
    for (int i = 1; i < argc; i++) {
        int took = mpb_planner_option(argc, argv, &i, &o, err, sizeof err);
        if (took < 0)
            break;
        if (!took)
            left[num_left++] = i;
    }
    assert_string_equal(o.name, "ara");
    assert_int_equal(o.max_runs, 4);
    assert_string_equal(o.lcm_url, "udpm://u");
    assert_string_equal(o.secret_file, "f");
    assert_int_equal(num_left, 1);
    assert_string_equal(argv[left[0]], "-v");
    /* the last --max-runs has no value */
    assert_string_equal(err, "--max-runs needs a value");
    static const char *const bad[] = {"-1", "x", "4x", "", NULL};
    for (int k = 0; bad[k]; k++) {
        char *one[] = {"p", "--max-runs", (char *)bad[k], NULL};
        int i = 1;
        char want[96];
        assert_int_equal(mpb_planner_option(3, one, &i, &o, err, sizeof err), -1);
        snprintf(want, sizeof want, "--max-runs wants a number >= 0, not '%s'",
                 bad[k]);
        assert_string_equal(err, want);
    }
    assert_int_equal(o.max_runs, 4);
}

static void test_serve_rejects_bad_definitions(void **state)
{
    (void)state;
    volatile sig_atomic_t stop = 1;
    char err[200];
    mpb_planner_def def = make_def("ok");

    assert_int_equal(mpb_planner_serve(NULL, "memq://", &stop, 0, err, sizeof err),
                     MPB_EINVAL);
    def.solve = NULL;
    assert_int_equal(mpb_planner_serve(&def, "memq://", &stop, 0, err, sizeof err),
                     MPB_EINVAL);
    const char *bad_names[] = { "", "a b", "a@b", "a:b", "x/y",
                                "a-name-that-is-longer-than-32-chars" };
    for (size_t i = 0; i < sizeof bad_names / sizeof bad_names[0]; i++) {
        def = make_def(bad_names[i]);
        err[0] = '\0';
        assert_int_equal(mpb_planner_serve(&def, "memq://", &stop, 0, err, sizeof err),
                         MPB_EINVAL);
        assert_true(err[0] != '\0');
    }
}

static void test_serve_reports_lcm_failure(void **state)
{
    (void)state;
    volatile sig_atomic_t stop = 1;
    char err[200] = "";
    mpb_planner_def def = make_def("ok");
    assert_int_equal(mpb_planner_serve(&def, "nosuchprovider://", &stop, 0,
                                       err, sizeof err),
                     MPB_ELCM);
    assert_non_null(strstr(err, "nosuchprovider://"));
}

static char g_ready_id[MPB_PLANNER_ID_MAX + 1];
static int g_ready_calls;

static void on_ready(void *user, const char *planner_id)
{
    *(int *)user += 1;
    g_ready_calls++;
    snprintf(g_ready_id, sizeof g_ready_id, "%s", planner_id);
}

/* Started with the stop flag up, serve() joins, says its id, and returns. */
static void test_serve_starts_and_stops(void **state)
{
    (void)state;
    volatile sig_atomic_t stop = 1;
    char err[200] = "";
    int calls = 0;
    mpb_planner_def def = make_def("unit.test_planner-1");
    def.user = &calls;
    def.on_ready = on_ready;
    g_ready_calls = 0;
    assert_int_equal(mpb_planner_serve(&def, "memq://", &stop, 0, err, sizeof err),
                     MPB_OK);
    assert_int_equal(calls, 1);
    assert_int_equal(g_ready_calls, 1);
    assert_true(mpb_planner_id_is_valid(g_ready_id));

    char want_prefix[64], want_suffix[32];
    snprintf(want_prefix, sizeof want_prefix, "%s@", def.name);
    snprintf(want_suffix, sizeof want_suffix, ":%ld", (long)getpid());
    assert_memory_equal(g_ready_id, want_prefix, strlen(want_prefix));
    size_t n = strlen(g_ready_id), m = strlen(want_suffix);
    assert_true(n > strlen(want_prefix) + m);
    assert_string_equal(g_ready_id + n - m, want_suffix);
}

/* The kit's limits: stop when the flag is set or the deadline has passed,
 * not before. */
static void test_solve_should_stop(void **state)
{
    (void)state;
    volatile sig_atomic_t flag = 0;
    double now = mpb_monotonic_s();
    mpb_solve_limits lim = {.start = now, .deadline = now + 60, .stop = &flag};
    assert_int_equal(mpb_solve_should_stop(&lim), 0);
    flag = 1;
    assert_int_equal(mpb_solve_should_stop(&lim), 1);
    flag = 0;
    lim.deadline = now - 1e-3;
    assert_int_equal(mpb_solve_should_stop(&lim), 1);
    lim = (mpb_solve_limits){.start = now, .deadline = now + 60, .stop = NULL};
    assert_int_equal(mpb_solve_should_stop(&lim), 0);
}

/* A planner's own budget: the deadline moved, the flag the same one. */
static void test_solve_limits_moved(void **state)
{
    (void)state;
    volatile sig_atomic_t flag = 0;
    double now = mpb_monotonic_s();
    mpb_solve_limits lim = {.start = now, .deadline = now - 1.0, .stop = &flag};
    mpb_solve_limits later = mpb_solve_limits_moved(&lim, 60.0);
    assert_true(later.deadline == lim.deadline + 60.0);
    assert_true(later.start == lim.start);
    assert_int_equal(mpb_solve_should_stop(&lim), 1);
    assert_int_equal(mpb_solve_should_stop(&later), 0);
    flag = 1;       /* the node's stop reaches the copy */
    assert_int_equal(mpb_solve_should_stop(&later), 1);
    flag = 0;
    mpb_solve_limits earlier = mpb_solve_limits_moved(&later, -120.0);
    assert_int_equal(mpb_solve_should_stop(&earlier), 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_add_stage_copies),
        cmocka_unit_test(test_solve_should_stop),
        cmocka_unit_test(test_solve_limits_moved),
        cmocka_unit_test(test_add_stage_bad_args),
        cmocka_unit_test(test_values_and_message),
        cmocka_unit_test(test_result_round_trip),
        cmocka_unit_test(test_request_param),
        cmocka_unit_test(test_options),
        cmocka_unit_test(test_serve_rejects_bad_definitions),
        cmocka_unit_test(test_serve_reports_lcm_failure),
        cmocka_unit_test(test_serve_starts_and_stops),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
