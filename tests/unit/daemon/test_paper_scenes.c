/*
 * test_paper_scenes.c - the paper's benchmark suite as committed:
 * scenes/experiments/paper.yaml and paper-quick.yaml, read with the
 * daemon's own loader, with the PR2 arm (scenes/robots/) in the four
 * environments (scenes/paper/).
 *
 * What must hold for the suite to be a fair benchmark:
 * - the start state is the same in every environment and collision-free;
 * - every goal region (2 cm cube, 0.05 rad) has a collision-free IK
 *   solution inside it, found here from scratch with a fixed rng;
 * - query k starts inside goal k-1's region, collision-free: "between
 *   successive goals, the first from the start state";
 * - both files hold the same queries, and the planners and run counts of
 *   the paper's protocol.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <cmocka.h>

#include "experiment.h"
#include "mpbench/mpbench.h"

#define PAPER MPB_SOURCE_DIR "/scenes/experiments/paper.yaml"
#define QUICK MPB_SOURCE_DIR "/scenes/experiments/paper-quick.yaml"
#define IK_DRAWS 200          /* IK targets tried per goal before giving up */

typedef struct fixture {
    mpbd_experiment *paper, *quick;
    mpb_robot       *robot;   /* the planning group, for IK */
} fixture;

static mpbd_experiment *load(const char *path)
{
    char err[512];
    mpbd_experiment *e = mpbd_experiment_load(path, err, sizeof err);
    if (e == NULL)
        print_message("%s\n", err);
    return e;
}

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    char err[256];
    assert_non_null(f);
    assert_non_null(f->paper = load(PAPER));
    assert_non_null(f->quick = load(QUICK));
    assert_int_equal(mpb_robot_open_urdf_joints(
                         f->paper->scenes[0].robot,
                         (const char *const *)f->paper->group,
                         f->paper->num_group, &f->robot, err, sizeof err),
                     MPB_OK);
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    mpbd_experiment_free(f->paper);
    mpbd_experiment_free(f->quick);
    mpb_robot_close(f->robot);
    free(f);
    return 0;
}

static const mpbd_scene *scene_named(const mpbd_experiment *e, const char *name)
{
    for (int i = 0; i < e->num_scenes; i++)
        if (strcmp(e->scenes[i].name, name) == 0)
            return &e->scenes[i];
    return NULL;
}

static int queries_of(const mpbd_experiment *e, const mpbd_scene *sc)
{
    int n = 0;
    for (int i = 0; i < e->num_queries; i++)
        n += &e->scenes[e->queries[i].scene] == sc;
    return n;
}

/* The region of a query's goal, as robot.h takes it. */
static mpb_goal_region region_of(const fixture *f, const mpbd_query *q)
{
    mpb_goal_region g = {.link = mpb_robot_link_index(f->robot, q->goal_link)};
    for (int i = 0; i < 3; i++) {
        g.center[i] = q->position[i];
        g.half_extents[i] = q->position_tolerance[i];
        g.ref_rpy[i] = q->rpy[i];
        g.rpy_tolerance[i] = q->rpy_tolerance[i];
    }
    return g;
}

/* The paper's four environments, with its numbers of goals, each a 2 cm
 * cube and 0.05 rad for the gripper's tool frame. */
static void test_the_four_environments(void **state)
{
    const fixture *f = *state;
    static const struct { const char *name; int goals; } envs[] = {
        {"kitchen", 10}, {"industrial", 5}, {"narrow_passage", 5},
        {"tabletop", 10}};
    assert_int_equal(f->paper->num_scenes, 4);
    for (int i = 0; i < 4; i++) {
        const mpbd_scene *sc = scene_named(f->paper, envs[i].name);
        assert_non_null(sc);
        assert_int_equal(queries_of(f->paper, sc), envs[i].goals);
        assert_string_equal(sc->robot_format, "urdf");
        assert_string_equal(sc->scene_format, "moveit-scene");
    }
    for (int i = 0; i < f->paper->num_queries; i++) {
        const mpbd_query *q = &f->paper->queries[i];
        assert_int_equal(q->goal_kind, MPB_GOAL_POSE_REGION);
        assert_string_equal(q->goal_link, "r_gripper_tool_frame");
        for (int k = 0; k < 3; k++) {
            assert_true(fabs(q->position_tolerance[k] - 0.01) < 1e-12);
            assert_true(fabs(q->rpy_tolerance[k] - 0.05) < 1e-12);
        }
    }
}

/* The first query of every environment starts at one fixed state, free of
 * collision there (the loader checks that too; this says why it matters). */
static void test_start_state_is_fixed_and_free(void **state)
{
    const fixture *f = *state;
    const double *start = NULL;
    int firsts = 0;
    for (int i = 0; i < f->paper->num_queries; i++) {
        const mpbd_query *q = &f->paper->queries[i];
        if (i > 0 && f->paper->queries[i - 1].scene == q->scene)
            continue;
        firsts++;
        if (start == NULL)
            start = q->start;
        assert_memory_equal(q->start, start,
                            sizeof *start * (size_t)f->paper->num_joints);
        assert_true(mpb_robot_within_limits(f->robot, q->start));
        assert_int_equal(mpb_world_in_collision(f->paper->scenes[q->scene].world,
                                                q->start), 0);
    }
    assert_int_equal(firsts, 4);
}

/* Every goal region holds a collision-free IK solution: found again here,
 * from random seeds (fixed rng), not read from the file. */
static void test_every_goal_has_a_free_ik_solution(void **state)
{
    const fixture *f = *state;
    int nj = f->paper->num_joints;
    double *q = calloc((size_t)nj, sizeof *q);
    assert_non_null(q);
    for (int i = 0; i < f->paper->num_queries; i++) {
        const mpbd_query *qu = &f->paper->queries[i];
        mpb_world *w = f->paper->scenes[qu->scene].world;
        mpb_goal_region g = region_of(f, qu);
        mpb_goal goal = mpbd_query_goal(qu);
        uint64_t rng = 0x5eed0000u + (uint64_t)i;
        int draws = 0, found = 0;
        struct timespec t0, t1;
        assert_true(g.link >= 0);
        clock_gettime(CLOCK_MONOTONIC, &t0);
        while (!found && draws++ < IK_DRAWS)
            found = mpb_goal_region_sample(f->robot, &g, NULL, NULL, 1, &rng,
                                           q) == MPB_OK &&
                    mpb_robot_within_limits(f->robot, q) &&
                    mpb_world_in_collision(w, q) == 0;
        clock_gettime(CLOCK_MONOTONIC, &t1);
        if (!found)
            print_message("%s/%s: no collision-free IK solution in %d draws\n",
                          f->paper->scenes[qu->scene].name, qu->name, IK_DRAWS);
        assert_true(found);
        /* The verifier agrees the solution is inside the goal. */
        assert_int_equal(mpb_world_goal_contains(w, &goal, q, NULL, 0), 1);
        print_message("%-15s %-20s IK: %3d draws, %6.1f ms\n",
                      f->paper->scenes[qu->scene].name, qu->name, draws,
                      (double)(t1.tv_sec - t0.tv_sec) * 1e3 +
                          (double)(t1.tv_nsec - t0.tv_nsec) / 1e6);
    }
    free(q);
}

/* Query k starts inside goal k-1's region, free of collision. */
static void test_queries_chain_through_the_goals(void **state)
{
    const fixture *f = *state;
    int chained = 0;
    for (int i = 1; i < f->paper->num_queries; i++) {
        const mpbd_query *prev = &f->paper->queries[i - 1];
        const mpbd_query *q = &f->paper->queries[i];
        if (prev->scene != q->scene)
            continue;
        mpb_world *w = f->paper->scenes[q->scene].world;
        mpb_goal goal = mpbd_query_goal(prev);
        char why[256];
        int in = mpb_world_goal_contains(w, &goal, q->start, why, sizeof why);
        if (in != 1)
            print_message("%s: start not in %s's region: %s\n", q->name,
                          prev->name, why);
        assert_int_equal(in, 1);
        assert_true(mpb_robot_within_limits(f->robot, q->start));
        assert_int_equal(mpb_world_in_collision(w, q->start), 0);
        /* And the previous start is not: each query has somewhere to go. */
        assert_int_equal(mpb_world_goal_contains(w, &goal, prev->start, NULL, 0),
                         0);
        chained++;
    }
    assert_int_equal(chained, f->paper->num_queries - f->paper->num_scenes);
}

/* The quick variant runs the same queries, fewer times and shorter. */
static void test_quick_variant_has_the_same_queries(void **state)
{
    const fixture *f = *state;
    const mpbd_experiment *p = f->paper, *k = f->quick;
    assert_int_equal(k->num_queries, p->num_queries);
    for (int i = 0; i < p->num_queries; i++) {
        assert_string_equal(k->queries[i].name, p->queries[i].name);
        assert_string_equal(k->scenes[k->queries[i].scene].name,
                            p->scenes[p->queries[i].scene].name);
        assert_memory_equal(k->queries[i].start, p->queries[i].start,
                            sizeof(double) * (size_t)p->num_joints);
        assert_memory_equal(k->queries[i].position, p->queries[i].position,
                            sizeof p->queries[i].position);
        assert_memory_equal(k->queries[i].rpy, p->queries[i].rpy,
                            sizeof p->queries[i].rpy);
    }
    assert_true(p->time_limit == 60.0);
    assert_int_equal(p->runs, 30);
    assert_true(k->time_limit < p->time_limit);
    assert_true(k->runs < p->runs);
}

static const mpbd_config *config_named(const mpbd_experiment *e,
                                       const char *name)
{
    for (int i = 0; i < e->num_configs; i++)
        if (strcmp(e->configs[i].name, name) == 0)
            return &e->configs[i];
    return NULL;
}

/* The paper's planners: six from OMPL, 30 runs each; ARA* once (it is
 * deterministic); and the Python planner beside them. */
static void test_planners_follow_the_protocol(void **state)
{
    const fixture *f = *state;
    static const char *const ompl[] = {
        "ompl/KPIECE1", "ompl/LBKPIECE1", "ompl/SBL", "ompl/RRT",
        "ompl/RRTConnect", "ompl/RRTstar"};
    const mpbd_experiment *both[] = {f->paper, f->quick};
    for (int e = 0; e < 2; e++) {
        for (int i = 0; i < 6; i++) {
            const mpbd_config *c = config_named(both[e], ompl[i]);
            assert_non_null(c);
            assert_int_equal(c->runs, both[e]->runs);
        }
        const mpbd_config *ara = config_named(both[e], "arastar/ARAstar");
        assert_non_null(ara);
        assert_int_equal(ara->runs, 1);
        assert_non_null(config_named(both[e], "python/RRTConnect"));
    }
    assert_non_null(config_named(f->paper, "ompl/BITstar"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_the_four_environments),
        cmocka_unit_test(test_start_state_is_fixed_and_free),
        cmocka_unit_test(test_every_goal_has_a_free_ik_solution),
        cmocka_unit_test(test_queries_chain_through_the_goals),
        cmocka_unit_test(test_quick_variant_has_the_same_queries),
        cmocka_unit_test(test_planners_follow_the_protocol),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
