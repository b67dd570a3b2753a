/* test_plot_profile.c - `mpb plot`'s performance profiles, run as a user
 * runs it: the built tool on a database written through the store, its
 * profile.csv checked whole against values worked out by hand, and the
 * images it names.
 *
 * One experiment, configurations A = a/fast and B = b/slow. Problem set
 * s1 (scenes s1/0001-0004, the default set of their names), one query
 * each; s2 the scene "lone", put there by its stored set. Times (s) and
 * path lengths of the runs, "x" a failure:
 *   p1: A 1 (2.0)            B 2 (3.0)
 *   p2: A 4 (1.0)            B 1 (4.0)
 *   p3: A 1 (2.0), 3 (1.0), x    B 6 (1.0), x, x
 *   p4: A x                  B 8 (1.0)
 *   lone: A 5 (1.0)          B 5 (1.0)
 * A's median on p3 is 3 s and 2.0 (x is infinite); B's is infinite, so
 * B has not solved p3. Time ratios to the best: A 1, 4, 1, -, 1; B 2, 1,
 * -, 1, 1. Length ratios: A 1, 1, 1, -, 1; B 1.5, 4, -, 1, 1. */
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

/* A run of one configuration: its time, its length, or a failure (time
 * at the limit, no path) when length is 0. */
typedef struct run_spec {
    double time, length;
} run_spec;

static void finish(mpb_store *s, int64_t run_id, run_spec r)
{
    char uid[32];
    int ok = r.length > 0;
    snprintf(uid, sizeof uid, "uid-%lld", (long long)run_id);
    assert_int_equal(mpb_store_run_sent(s, run_id, uid, "p-1"), MPB_OK);
    mpb_named m[] = {{"path_length", r.length}};
    mpb_stage_record st = {.name = "raw", .valid = ok,
                           .verdict = ok ? "valid" : "collision",
                           .verdict_segment = -1, .num_metrics = ok,
                           .metrics = m};
    mpb_run_record rec = {
        .run_id = run_id, .attempt_id = uid, .planner_id = "p-1",
        .status = ok ? "solved" : "timeout", .claimed_success = ok,
        .success = ok, .time_total = r.time, .time_raw = r.time,
        .num_stages = 1, .stages = &st, .verify_time = NAN, .memory = NAN,
    };
    assert_int_equal(mpb_store_run_finish(s, &rec), MPB_OK);
}

#define FAIL {10.0, 0}
/* [problem][config][repetition]; time 0 ends a list. */
static const run_spec runs[5][2][3] = {
    {{{1, 2.0}}, {{2, 3.0}}},
    {{{4, 1.0}}, {{1, 4.0}}},
    {{{1, 2.0}, {3, 1.0}, FAIL}, {{6, 1.0}, FAIL, FAIL}},
    {{FAIL}, {{8, 1.0}}},
    {{{5, 1.0}}, {{5, 1.0}}},
};

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    mpb_store *s = test_store_new(f->dir, sizeof f->dir, f->db, sizeof f->db,
                                  "plot_profile");
    int64_t exp = test_store_experiment(s, "profiles", "p.yaml", "h", 1, 10.0);
    int64_t cfg[2] = {test_store_config(s, exp, "a", "fast", ""),
                      test_store_config(s, exp, "b", "slow", "")};
    int64_t query[5];
    for (int q = 0; q < 5; q++) {
        char name[32];
        snprintf(name, sizeof name, q < 4 ? "s1/%04d" : "lone", q + 1);
        int64_t scene = test_store_scene(s, exp, name, "h", "s");
        if (q == 4)
            assert_int_equal(mpb_store_scene_set_problem_set(s, scene, "s2"),
                             MPB_OK);
        query[q] = test_store_query(s, scene, "q");
        for (int c = 0; c < 2; c++)
            for (int r = 0; r < 3 && runs[q][c][r].time > 0; r++)
                assert_int_equal(mpb_store_run_add(s, exp, cfg[c], query[q], r,
                                                   7 * q + r),
                                 MPB_OK);
    }
    for (int q = 0; q < 5; q++)
        for (int c = 0; c < 2; c++)
            for (int r = 0; r < 3 && runs[q][c][r].time > 0; r++)
                finish(s, test_store_run_id(s, exp, cfg[c], query[q], r),
                       runs[q][c][r]);
    mpb_store_close(s);
    *state = f;
    return 0;
}

static void the_profiles_are_the_hand_computed_ones(void **state)
{
    fixture *f = *state;
    test_output o;
    test_run(&o, mpb_tool, "both", "plot -o '%s/out' '%s'", f->dir, f->db);
    assert_int_equal(o.status, 0);
    static const char *const images[] = {"s1", "s2", "all"};
    for (int i = 0; i < 3; i++) {
        char line[256];
        snprintf(line, sizeof line, "%s/out/plot-profile-%s.png\n", f->dir,
                 images[i]);
        assert_non_null(strstr(o.text, line));
    }
    char path[256];
    snprintf(path, sizeof path, "%s/out/profile.csv", f->dir);
    assert_non_null(strstr(o.text, path));
    FILE *csv = fopen(path, "r");
    assert_non_null(csv);
    char got[4096];
    size_t n = fread(got, 1, sizeof got - 1, csv);
    got[n] = '\0';
    fclose(csv);
    assert_string_equal(got,
        "set,metric,planner,tau,fraction,problems\n"
        "\"s1\",time,\"a/fast\",1,0.5,4\n"
        "\"s1\",time,\"a/fast\",4,0.75,4\n"
        "\"s1\",time,\"b/slow\",1,0.5,4\n"
        "\"s1\",time,\"b/slow\",2,0.75,4\n"
        "\"s1\",path_length,\"a/fast\",1,0.75,4\n"
        "\"s1\",path_length,\"b/slow\",1,0.25,4\n"
        "\"s1\",path_length,\"b/slow\",1.5,0.5,4\n"
        "\"s1\",path_length,\"b/slow\",4,0.75,4\n"
        "\"s2\",time,\"a/fast\",1,1,1\n"
        "\"s2\",time,\"b/slow\",1,1,1\n"
        "\"s2\",path_length,\"a/fast\",1,1,1\n"
        "\"s2\",path_length,\"b/slow\",1,1,1\n"
        "\"all problems\",time,\"a/fast\",1,0.6,5\n"
        "\"all problems\",time,\"a/fast\",4,0.8,5\n"
        "\"all problems\",time,\"b/slow\",1,0.6,5\n"
        "\"all problems\",time,\"b/slow\",2,0.8,5\n"
        "\"all problems\",path_length,\"a/fast\",1,0.8,5\n"
        "\"all problems\",path_length,\"b/slow\",1,0.4,5\n"
        "\"all problems\",path_length,\"b/slow\",1.5,0.6,5\n"
        "\"all problems\",path_length,\"b/slow\",4,0.8,5\n");
}

int main(void)
{
    if (test_built_program("tools/mpb", mpb_tool, sizeof mpb_tool) != 0)
        return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(the_profiles_are_the_hand_computed_ones),
    };
    return cmocka_run_group_tests(tests, setup, test_store_teardown);
}
