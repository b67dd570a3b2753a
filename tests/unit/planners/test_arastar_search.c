/*
 * test_arastar_search.c - ARA* on the paper's PR2 arm in its KITCHEN
 * scene (real URDF, scene, FCL): a joint goal and a pose-region goal are
 * reached by paths that mpbench's own verifier accepts, the same problem
 * gives the same path twice, and the limits (states, time, a colliding
 * start) end the search with the right outcome.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "mpbench/verify.h"
#include "search.h"
#include "voxelize.h"
#include "test_files.h"

#define SCENES MPB_TEST_DATA "/../../../scenes"

static const char *const JOINTS[7] = {
    "r_shoulder_pan_joint", "r_shoulder_lift_joint", "r_upper_arm_roll_joint",
    "r_elbow_flex_joint", "r_forearm_roll_joint", "r_wrist_flex_joint",
    "r_wrist_roll_joint"};
static const double START[7] = {-1.2, 1.1, -1.5, -1.9, 0.0, -0.6, 0.0};
/* A free configuration inside the KITCHEN's counter_cup goal region. */
static const double GOAL[7] = {-0.261284, -0.420386, -1.523717, -1.031201,
                               -1.236424, -1.761224, -2.299770};

typedef struct fixture {
    char       *urdf, *scene_text;
    mpb_world  *world;
    mpb_robot  *robot;
    mpb_scene  *scene;
    ara_motion  motion;
    ara_grid    grid;
} fixture;

static int setup(void **state)
{
    fixture *fx = calloc(1, sizeof *fx);
    char err[256];
    fx->urdf = test_read_file(SCENES "/robots/pr2_right_arm.urdf");
    fx->scene_text = test_read_file(SCENES "/paper/kitchen.scene");
    assert_non_null(fx->urdf);
    assert_non_null(fx->scene_text);
    assert_int_equal(mpb_world_open_group("urdf", fx->urdf, "moveit-scene",
                                          fx->scene_text, JOINTS, 7,
                                          &fx->world, err, sizeof err), MPB_OK);
    assert_int_equal(mpb_robot_open_urdf_joints(fx->urdf, JOINTS, 7,
                                                &fx->robot, err, sizeof err),
                     MPB_OK);
    assert_int_equal(mpb_scene_open_text(fx->scene_text, &fx->scene, err,
                                         sizeof err), MPB_OK);
    assert_int_equal(ara_motion_init(&fx->motion, fx->world, 0.01), 0);
    *state = fx;
    return 0;
}

static int teardown(void **state)
{
    fixture *fx = *state;
    ara_grid_free(&fx->grid);
    ara_motion_free(&fx->motion);
    mpb_scene_close(fx->scene);
    mpb_robot_close(fx->robot);
    mpb_world_close(fx->world);
    free(fx->urdf);
    free(fx->scene_text);
    free(fx);
    return 0;
}

/* Voxel grid of the kitchen around the shoulder, BFS from goal_xyz. */
static void build_grid(fixture *fx, const double goal_xyz[3])
{
    mpb_pose base;
    char err[200];
    assert_int_equal(mpb_robot_link_pose(fx->robot, START,
                                         mpb_robot_base_link(fx->robot),
                                         &base), MPB_OK);
    double origin[3];
    for (int i = 0; i < 3; i++)
        origin[i] = base.t[i] - 64 * 0.02;
    ara_grid_free(&fx->grid);
    assert_int_equal(ara_grid_init(&fx->grid, 128, 128, 128, origin, 0.02), 0);
    assert_true(ara_voxelize(&fx->grid, fx->scene, fx->robot, START, err,
                             sizeof err) > 0);
    int cell[3];
    assert_int_equal(ara_grid_cell_of(&fx->grid, goal_xyz, cell), 0);
    assert_true(ara_grid_bfs(&fx->grid, cell) > 0);
}

static ara_problem joint_problem(fixture *fx)
{
    mpb_pose tip;
    int tip_link = mpb_robot_tip_link(fx->robot);
    assert_int_equal(mpb_robot_link_pose(fx->robot, GOAL, tip_link, &tip),
                     MPB_OK);
    build_grid(fx, tip.t);
    return (ara_problem){
        .motion = &fx->motion, .robot = fx->robot, .start = START,
        .goal_joints = GOAL, .joint_tolerance = 1e-3, .grid = &fx->grid,
        .ee_link = tip_link, .step = 4 * M_PI / 180, .long_step = 2,
        .epsilon = 100, .epsilon_decay = 0.5, .h_position = 5,
        .h_rotation = 1, .snap_distance = 0.5, .ik_seed = 1,
        .max_states = 1000000, .deadline = mpb_monotonic_s() + 60};
}

static void assert_verified(fixture *fx, const ara_solution *sol,
                            const mpb_goal *goal)
{
    mpb_verdict v;
    assert_int_equal(mpb_verify_path(fx->world, START, 1e-9, goal,
                                     sol->waypoints, sol->num_waypoints, 7,
                                     0.01, &v), MPB_OK);
    if (v.code != MPB_VERDICT_VALID)
        fail_msg("verifier: %s (%s)", mpb_verdict_name(v.code), v.detail);
    /* The reported cost is the path's joint-space length. */
    double len = 0;
    for (int i = 0; i + 1 < sol->num_waypoints; i++)
        len += ara_motion_distance(&fx->motion, sol->waypoints + 7 * i,
                                   sol->waypoints + 7 * (i + 1));
    assert_true(fabs(len - sol->cost) < 1e-9);
}

static void test_joint_goal_verified_and_repeatable(void **state)
{
    fixture *fx = *state;
    ara_problem p = joint_problem(fx);
    ara_solution a, b;
    ara_search(&p, &a);
    assert_int_equal(a.outcome, ARA_SOLVED);
    assert_true(a.num_waypoints > 2);
    assert_true(a.expansions > 0 && a.generated > a.expansions);
    mpb_goal goal = {.kind = MPB_GOAL_JOINTS, .joints = GOAL,
                     .joint_tolerance = 1e-3};
    assert_verified(fx, &a, &goal);
    /* Never shorter than the straight line. */
    assert_true(a.cost >= ara_motion_distance(&fx->motion, START, GOAL) - 1e-9);

    p.deadline = mpb_monotonic_s() + 60;
    ara_search(&p, &b);
    assert_int_equal(b.outcome, ARA_SOLVED);
    assert_int_equal(a.num_waypoints, b.num_waypoints);
    assert_memory_equal(a.waypoints, b.waypoints,
                        (size_t)a.num_waypoints * 7 * sizeof(double));
    free(a.waypoints);
    free(b.waypoints);
}

static void test_region_goal_verified(void **state)
{
    fixture *fx = *state;
    mpb_goal_region region = {
        .link = mpb_robot_link_index(fx->robot, "r_gripper_tool_frame"),
        .center = {0.62, -0.08, 1.0}, .half_extents = {0.01, 0.01, 0.01},
        .ref_rpy = {0, 1.5708, 0}, .rpy_tolerance = {0.05, 0.05, 0.05}};
    assert_true(region.link >= 0);
    build_grid(fx, region.center);
    ara_problem p = {
        .motion = &fx->motion, .robot = fx->robot, .start = START,
        .region = &region, .grid = &fx->grid, .step = 4 * M_PI / 180,
        .long_step = 2, .epsilon = 100, .epsilon_decay = 0.5,
        .h_position = 5, .h_rotation = 1, .snap_distance = 0.1, .ik_seed = 1,
        .max_states = 1000000, .deadline = mpb_monotonic_s() + 60};
    ara_solution sol;
    ara_search(&p, &sol);
    assert_int_equal(sol.outcome, ARA_SOLVED);
    assert_true(sol.snaps_found >= 1);
    mpb_goal goal = {.kind = MPB_GOAL_POSE_REGION,
                     .link = "r_gripper_tool_frame",
                     .position = {0.62, -0.08, 1.0},
                     .position_tolerance = {0.01, 0.01, 0.01},
                     .orientation_rpy = {0, 1.5708, 0},
                     .orientation_tolerance = {0.05, 0.05, 0.05}};
    assert_verified(fx, &sol, &goal);
    free(sol.waypoints);
}

typedef struct progress_log {
    int    n;
    double cost[64], eps[64];
} progress_log;

static void on_solution(void *user, double t, double cost, double eps,
                        long expansions)
{
    progress_log *log = user;
    (void)t;
    (void)expansions;
    if (log->n < 64) {
        log->cost[log->n] = cost;
        log->eps[log->n] = eps;
        log->n++;
    }
}

/* Anytime: every solution reported is better than the one before, found
   with a smaller epsilon, and the last one is what is returned. */
static void test_improving(void **state)
{
    fixture *fx = *state;
    ara_problem p = joint_problem(fx);
    ara_solution first, best;
    ara_search(&p, &first);
    assert_int_equal(first.outcome, ARA_SOLVED);
    progress_log log = {0};
    p.improve = 1;
    p.on_solution = on_solution;
    p.user = &log;
    p.deadline = mpb_monotonic_s() + 1.5;
    ara_search(&p, &best);
    assert_int_equal(best.outcome, ARA_SOLVED);
    assert_true(log.n >= 1);
    assert_true(fabs(log.cost[0] - first.cost) < 1e-12);  /* same first search */
    for (int i = 1; i < log.n; i++) {
        assert_true(log.cost[i] < log.cost[i - 1]);
        assert_true(log.eps[i] <= log.eps[i - 1]);
    }
    assert_true(fabs(best.cost - log.cost[log.n - 1]) < 1e-12);
    mpb_goal goal = {.kind = MPB_GOAL_JOINTS, .joints = GOAL,
                     .joint_tolerance = 1e-3};
    assert_verified(fx, &best, &goal);
    free(first.waypoints);
    free(best.waypoints);
}

static void test_limits(void **state)
{
    fixture *fx = *state;
    ara_problem p = joint_problem(fx);
    ara_solution sol;

    p.max_states = 1000;                     /* the memory bound */
    ara_search(&p, &sol);
    assert_int_equal(sol.outcome, ARA_STATE_LIMIT);
    assert_null(sol.waypoints);
    assert_true(sol.generated <= 1000);

    p.max_states = 1000000;
    p.deadline = mpb_monotonic_s() - 1;      /* time already up */
    ara_search(&p, &sol);
    assert_int_equal(sol.outcome, ARA_TIMEOUT);
    assert_null(sol.waypoints);

    volatile sig_atomic_t stop = 1;          /* asked to stop */
    p.deadline = mpb_monotonic_s() + 60;
    p.stop = &stop;
    ara_search(&p, &sol);
    assert_int_equal(sol.outcome, ARA_TIMEOUT);

    /* Elbow straight up through the shoulder region: a colliding start. */
    double bad[7];
    memcpy(bad, START, sizeof bad);
    int found = 0;
    for (double pan = -2.2; pan <= 0.7 && !found; pan += 0.1)
        for (double lift = -0.5; lift <= 1.39 && !found; lift += 0.1) {
            bad[0] = pan;
            bad[1] = lift;
            found = mpb_world_in_collision(fx->world, bad) == 1;
        }
    assert_true(found);
    p.stop = NULL;
    p.start = bad;
    ara_search(&p, &sol);
    assert_int_equal(sol.outcome, ARA_START_INVALID);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_joint_goal_verified_and_repeatable),
        cmocka_unit_test(test_region_goal_verified),
        cmocka_unit_test(test_improving),
        cmocka_unit_test(test_limits),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
