/*
 * test_verify.c - mpbench's verdict on planted paths in a planar world whose
 * geometry is worked out by hand:
 *
 *   Arm: two unit links, capsules of radius 0.05, base at the origin;
 *        j1 in [-3, 3], j2 in [-2.5, 2.5]. Obstacle: circle C = (1.5, 0),
 *        r = 0.1.
 *   With j2 = 0 the arm is the segment from (0,0) to 2 (cos j1, sin j1).
 *   C lies 1.5 along x, so for |j1| < pi/2 its distance to that segment is
 *   1.5 |sin j1|: the arm collides iff 1.5 |sin j1| <= 0.1 + 0.05, i.e.
 *   |j1| <= asin(0.1) = 0.1002. At j1 = +-1: 1.5 sin 1 = 1.26, free; for
 *   j1 in [-2, -1] the arm points away (distance >= 1.26), free.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "core/mathconst.h"

static const char *const ROBOT =
    "link_radius 0.05\n"
    "joint j1 -3 3 1\n"
    "joint j2 -2.5 2.5 1\n";
static const char *const SCENE = "circle 1.5 0 0.1\n";

/* The same arm with j1 continuous. */
static const char *const ROBOT_CONT =
    "link_radius 0.05\n"
    "joint j1 continuous 1\n"
    "joint j2 -2.5 2.5 1\n";

static const double START[] = { -1, 0 };
#define TOL 0.01
#define RES 0.05

static mpb_world *open_world(const char *robot, const char *scene)
{
    mpb_world *w = NULL;
    char err[200];
    int rc = mpb_world_open("planar", robot, "planar", scene, &w, err, sizeof err);
    if (rc != MPB_OK)
        fail_msg("mpb_world_open: %s", err);
    return w;
}

static int setup(void **state)
{
    *state = open_world(ROBOT, SCENE);
    return 0;
}

static int teardown(void **state)
{
    mpb_world_close(*state);
    return 0;
}

static mpb_goal joint_goal(const double *q, double tol)
{
    mpb_goal g = { .kind = MPB_GOAL_JOINTS, .joints = q, .joint_tolerance = tol };
    return g;
}

/* Verify wp (n waypoints of 2 joints) from START to goal; returns the verdict. */
static mpb_verdict run(mpb_world *w, const double *goal_q, const double *wp,
                       int n, double res)
{
    mpb_goal g = joint_goal(goal_q, TOL);
    mpb_verdict v;
    memset(&v, 0xAB, sizeof v);
    assert_int_equal(mpb_verify_path(w, START, TOL, &g, wp, n, 2, res, &v), MPB_OK);
    assert_non_null(memchr(v.detail, '\0', sizeof v.detail));
    assert_null(strchr(v.detail, '\n'));
    return v;
}

static void expect(const mpb_verdict *v, mpb_verdict_code code, int segment,
                   const char *needle1, const char *needle2)
{
    if (v->code != code || v->segment != segment)
        fail_msg("got %s at %d (%s), expected %s at %d",
                 mpb_verdict_name(v->code), v->segment, v->detail,
                 mpb_verdict_name(code), segment);
    if ((needle1 && !strstr(v->detail, needle1)) ||
        (needle2 && !strstr(v->detail, needle2)))
        fail_msg("detail \"%s\" lacks \"%s\" / \"%s\"", v->detail,
                 needle1 ? needle1 : "", needle2 ? needle2 : "");
}

static void test_valid(void **state)
{
    /* j1 from -1 to -2 through -1.5, j2 = 0: pointing away from C. */
    const double goal[] = { -2, 0 };
    const double wp[] = { -1, 0,  -1.5, 0,  -2, 0 };
    mpb_verdict v = run(*state, goal, wp, 3, RES);
    expect(&v, MPB_VERDICT_VALID, -1, NULL, NULL);
    assert_string_equal(mpb_verdict_name(v.code), "valid");

    /* One waypoint at the start that is also the goal: valid. */
    v = run(*state, START, START, 1, RES);
    expect(&v, MPB_VERDICT_VALID, -1, NULL, NULL);
}

static void test_collision_between_valid_waypoints(void **state)
{
    /*
     * Segment 0: -1 -> -1.2, free. Segment 1: -1.2 -> 1, length 2.2, crosses
     * j1 = 0 where the arm passes through C. Every waypoint is free on its
     * own; only interpolation finds the collision, on segment 1.
     */
    mpb_world *w = *state;
    const double goal[] = { 1, 0 };
    const double wp[] = { -1, 0,  -1.2, 0,  1, 0 };
    for (int i = 0; i < 3; i++)
        assert_int_equal(mpb_world_in_collision(w, wp + 2 * i), 0);
    mpb_verdict v = run(w, goal, wp, 3, RES);
    expect(&v, MPB_VERDICT_COLLISION, 1, "segment 1", NULL);
    assert_string_equal(mpb_verdict_name(v.code), "collision");
}

static void test_resolution_sets_the_samples(void **state)
{
    /*
     * -1 -> 1 in one segment of length 2. Resolution 0.9: k = ceil(2/0.9)
     * = 3 samples at j1 = -1/3, 1/3, 1; 1.5 sin(1/3) = 0.49 > 0.15, all
     * free: the checker, as specified, misses the collision. Resolution 1:
     * k = 2, the sample s = 1/2 is j1 = 0: collision at s=0.5. That is
     * the sampled check (verification: sampled); the certified one, the
     * default, finds the collision the samples miss.
     */
    const double goal[] = { 1, 0 };
    const double wp[] = { -1, 0,  1, 0 };
    assert_int_equal(mpb_world_set_verification(*state, MPB_VERIFY_SAMPLED), MPB_OK);
    mpb_verdict v = run(*state, goal, wp, 2, 0.9);
    expect(&v, MPB_VERDICT_VALID, -1, NULL, NULL);
    assert_int_equal(v.certified, 0);
    v = run(*state, goal, wp, 2, 1.0);
    expect(&v, MPB_VERDICT_COLLISION, 0, "segment 0", "s=0.5");
    assert_int_equal(mpb_world_set_verification(*state, MPB_VERIFY_CERTIFIED), MPB_OK);
    v = run(*state, goal, wp, 2, 0.9);
    expect(&v, MPB_VERDICT_COLLISION, 0, "segment 0", NULL);
    assert_int_equal(v.certified, 1);
}

static void test_goal(void **state)
{
    /* Ends at j1 = -1.9; the goal is -2 within 0.01: 0.1 off, on j1. */
    const double goal[] = { -2, 0 };
    const double wp[] = { -1, 0,  -1.5, 0,  -1.9, 0 };
    mpb_verdict v = run(*state, goal, wp, 3, RES);
    expect(&v, MPB_VERDICT_GOAL, 2, "waypoint 2", "'j1'");

    /* Ends at (-2, 0.02): j2 is 0.02 off. */
    const double wp2[] = { -1, 0,  -2, 0.02 };
    v = run(*state, goal, wp2, 2, RES);
    expect(&v, MPB_VERDICT_GOAL, 1, "'j2'", NULL);

    /* Within the tolerance is reached: ends at (-2, 0.0078125), 0.0078
     * off on j2, under 0.01. */
    const double wp3[] = { -1, 0,  -2, 0.0078125 };
    v = run(*state, goal, wp3, 2, RES);
    expect(&v, MPB_VERDICT_VALID, -1, NULL, NULL);
}

static void test_not_finite(void **state)
{
    const double goal[] = { -2, 0 };
    const double wp[] = { -1, 0,  NAN, 0,  -2, 0 };
    mpb_verdict v = run(*state, goal, wp, 3, RES);
    expect(&v, MPB_VERDICT_NOT_FINITE, 1, "waypoint 1", "'j1'");

    const double wp2[] = { -1, 0,  -2, INFINITY };
    v = run(*state, goal, wp2, 2, RES);
    expect(&v, MPB_VERDICT_NOT_FINITE, 1, "'j2'", NULL);
}

static void test_joint_limit(void **state)
{
    /* j2 = 2.6 at waypoint 1, above its limit 2.5. */
    const double goal[] = { -2, 0 };
    const double wp[] = { -1, 0,  -1.5, 2.6,  -2, 0 };
    mpb_verdict v = run(*state, goal, wp, 3, RES);
    expect(&v, MPB_VERDICT_JOINT_LIMIT, 1, "waypoint 1", "'j2'");
}

/* A value just past its bound is printed with the digits that tell the
 * two apart, not as the bound itself ("2.5 is outside [-2.5, 2.5]"). */
static void test_numbers_at_the_boundary_differ(void **state)
{
    const double goal[] = { -2, 0 };
    const double wp[] = { -1, 0,  -1.5, nextafter(2.5, 3.0),  -2, 0 };
    mpb_verdict v = run(*state, goal, wp, 3, RES);
    expect(&v, MPB_VERDICT_JOINT_LIMIT, 1,
           "= 2.5000000000000004 is outside [-2.5, 2.5]", NULL);
    /* 1e-9 past the goal tolerance of 0.01. */
    const double wp2[] = { -1, 0,  -2, TOL + 1e-9 };
    v = run(*state, goal, wp2, 2, RES);
    expect(&v, MPB_VERDICT_GOAL, 1, "is 0.010000001 from the goal "
           "(tolerance 0.01)", NULL);
    /* Far apart, six digits as before. */
    const double wp3[] = { -0.9, 0,  -2, 0 };
    v = run(*state, goal, wp3, 2, RES);
    expect(&v, MPB_VERDICT_START, 0, "is 0.1 from the start (tolerance "
           "0.01)", NULL);
}

static void test_start(void **state)
{
    /* Begins at j1 = -0.9, 0.1 from the start -1. */
    const double goal[] = { -2, 0 };
    const double wp[] = { -0.9, 0,  -2, 0 };
    mpb_verdict v = run(*state, goal, wp, 2, RES);
    expect(&v, MPB_VERDICT_START, 0, "waypoint 0", "'j1'");
}

static void test_empty_and_size(void **state)
{
    mpb_world *w = *state;
    const double goal[] = { -2, 0 };
    mpb_goal g = joint_goal(goal, TOL);
    mpb_verdict v;
    assert_int_equal(mpb_verify_path(w, START, TOL, &g, NULL, 0, 2, RES, &v), MPB_OK);
    expect(&v, MPB_VERDICT_EMPTY, -1, NULL, NULL);
    const double wp[] = { -1, 0, 0,  -2, 0, 0 };
    assert_int_equal(mpb_verify_path(w, START, TOL, &g, wp, 2, 3, RES, &v), MPB_OK);
    expect(&v, MPB_VERDICT_WRONG_SIZE, -1, "3", NULL);
}

static void test_order(void **state)
{
    const double goal[] = { -2, 0 };
    /* Wrong start and NaN: NOT_FINITE comes first. */
    const double a[] = { -0.5, 0,  -2, NAN };
    mpb_verdict v = run(*state, goal, a, 2, RES);
    expect(&v, MPB_VERDICT_NOT_FINITE, 1, NULL, NULL);
    /* Wrong start and wrong end: START. */
    const double b[] = { -0.5, 0,  -1.5, 0 };
    v = run(*state, goal, b, 2, RES);
    expect(&v, MPB_VERDICT_START, 0, NULL, NULL);
    /* Wrong end and a collision on the way (through j1 = 0): GOAL. */
    const double c[] = { -1, 0,  1, 0,  -1.5, 0 };
    v = run(*state, goal, c, 3, RES);
    expect(&v, MPB_VERDICT_GOAL, 2, NULL, NULL);
    /* Out of limits and a collision: JOINT_LIMIT. */
    const double d[] = { -1, 0,  1, 2.6,  -2, 0 };
    v = run(*state, goal, d, 3, RES);
    expect(&v, MPB_VERDICT_JOINT_LIMIT, 1, NULL, NULL);
}

static void test_waypoint_0_collides(void **state)
{
    /* Start and goal at q = 0, inside C. */
    const double q0[] = { 0, 0 };
    mpb_goal g = joint_goal(q0, TOL);
    mpb_verdict v;
    assert_int_equal(mpb_verify_path(*state, q0, TOL, &g, q0, 1, 2, RES, &v), MPB_OK);
    expect(&v, MPB_VERDICT_COLLISION, 0, "waypoint 0", NULL);
}

static void test_pose_region_unsupported(void **state)
{
    mpb_goal g = { .kind = MPB_GOAL_POSE_REGION, .link = "tip",
                   .position = { -0.8, -1.8, 0 },
                   .position_tolerance = { 0.01, 0.01, 0.01 } };
    mpb_verdict v;
    /* A free path: nothing else fails, the goal cannot be checked. */
    const double free_wp[] = { -1, 0,  -2, 0 };
    assert_int_equal(mpb_verify_path(*state, START, TOL, &g, free_wp, 2, 2, RES, &v),
                     MPB_OK);
    expect(&v, MPB_VERDICT_UNSUPPORTED, -1, "planar", NULL);
    /* A colliding path is still rejected for its collision. */
    const double hit[] = { -1, 0,  1, 0 };
    assert_int_equal(mpb_verify_path(*state, START, TOL, &g, hit, 2, 2, RES, &v),
                     MPB_OK);
    expect(&v, MPB_VERDICT_COLLISION, 0, NULL, NULL);
}

static void test_continuous_joint(void **state)
{
    (void)state;
    /*
     * j1 continuous. From j1 = 3.0 to the goal pi - 0.01 = 3.1316, the path
     * ends at -pi + 0.01 = -3.1316: 0.02 from the goal the short way round,
     * within 0.05. Interpolated the short way (+0.15 through pi), the arm
     * points along -x, far from C: valid.
     */
    mpb_world *w = open_world(ROBOT_CONT, SCENE);
    const double start[] = { 3.0, 0 }, goal_q[] = { M_PI - 0.01, 0 };
    const double wp[] = { 3.0, 0,  -M_PI + 0.01, 0 };
    mpb_goal g = joint_goal(goal_q, 0.05);
    mpb_verdict v;
    assert_int_equal(mpb_verify_path(w, start, TOL, &g, wp, 2, 2, RES, &v), MPB_OK);
    expect(&v, MPB_VERDICT_VALID, -1, NULL, NULL);
    mpb_world_close(w);

    /*
     * Same path, an obstacle at (0, 1.5) (j1 = pi/2). Continuous, -3 -> 3 is
     * 0.28 the short way, through pi: free. With j1 limited to [-3.2, 3.2]
     * the segment runs 6 rad through 0 and pi/2: collision on segment 0.
     */
    const double s2[] = { -3, 0 }, wp2[] = { -3, 0,  3, 0 };
    mpb_goal g2 = joint_goal(wp2 + 2, TOL);
    w = open_world(ROBOT_CONT, "circle 0 1.5 0.1");
    assert_int_equal(mpb_verify_path(w, s2, TOL, &g2, wp2, 2, 2, RES, &v), MPB_OK);
    expect(&v, MPB_VERDICT_VALID, -1, NULL, NULL);
    mpb_world_close(w);
    w = open_world("link_radius 0.05\njoint j1 -3.2 3.2 1\njoint j2 -2.5 2.5 1\n",
                   "circle 0 1.5 0.1");
    assert_int_equal(mpb_verify_path(w, s2, TOL, &g2, wp2, 2, 2, RES, &v), MPB_OK);
    expect(&v, MPB_VERDICT_COLLISION, 0, "segment 0", NULL);
    mpb_world_close(w);
}

static void test_bad_arguments(void **state)
{
    mpb_world *w = *state;
    const double goal[] = { -2, 0 };
    const double wp[] = { -1, 0,  -2, 0 };
    mpb_goal g = joint_goal(goal, TOL);
    mpb_verdict v;
    assert_int_equal(mpb_verify_path(w, START, TOL, &g, wp, 2, 2, 0.0, &v), MPB_EINVAL);
    assert_int_not_equal(v.code, MPB_VERDICT_VALID);
    assert_int_equal(mpb_verify_path(w, START, TOL, &g, wp, 2, 2, NAN, &v), MPB_EINVAL);
    assert_int_equal(mpb_verify_path(NULL, START, TOL, &g, wp, 2, 2, RES, &v), MPB_EINVAL);
    assert_int_not_equal(v.code, MPB_VERDICT_VALID);
    assert_int_equal(mpb_verify_path(w, START, -1, &g, wp, 2, 2, RES, &v), MPB_EINVAL);
    assert_int_equal(mpb_verify_path(w, START, TOL, &g, NULL, 2, 2, RES, &v), MPB_EINVAL);
    assert_int_equal(mpb_verify_path(w, START, TOL, &g, wp, 2, 2, RES, NULL), MPB_EINVAL);
    assert_int_equal(mpb_verify_path(w, START, TOL, &g, wp, 2, 2, 1e-300, &v), MPB_EINVAL);
}

/* The word the store keeps for how a verdict's collision check was made. */
static void test_verdict_verification(void **state)
{
    (void)state;
    mpb_verdict v = {.code = MPB_VERDICT_VALID, .certified = 1};
    assert_string_equal(mpb_verdict_verification(&v), "certified");
    v.certified = 0;
    assert_string_equal(mpb_verdict_verification(&v), "sampled");
    v.code = MPB_VERDICT_COLLISION;
    assert_string_equal(mpb_verdict_verification(&v), "sampled");
    v.certified = 1;
    assert_string_equal(mpb_verdict_verification(&v), "certified");
    v.code = MPB_VERDICT_START;
    assert_null(mpb_verdict_verification(&v));
    v.code = MPB_VERDICT_WRONG_SIZE;
    assert_null(mpb_verdict_verification(&v));
    assert_null(mpb_verdict_verification(NULL));
}

/* A stored query's goal: the store's 12 region numbers in their places;
 * a joint goal (region NULL) has none. */
static void test_query_goal(void **state)
{
    (void)state;
    const double joints[2] = {0.5, -0.5};
    const double region[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    mpb_goal g = mpb_query_goal(MPB_GOAL_POSE_REGION, NULL, 0.01, "tool",
                                region);
    assert_int_equal(g.kind, MPB_GOAL_POSE_REGION);
    assert_string_equal(g.link, "tool");
    assert_true(g.joint_tolerance == 0.01);
    for (int i = 0; i < 3; i++) {
        assert_true(g.position[i] == region[i]);
        assert_true(g.position_tolerance[i] == region[3 + i]);
        assert_true(g.orientation_rpy[i] == region[6 + i]);
        assert_true(g.orientation_tolerance[i] == region[9 + i]);
    }
    g = mpb_query_goal(MPB_GOAL_JOINTS, joints, 0.02, NULL, NULL);
    assert_int_equal(g.kind, MPB_GOAL_JOINTS);
    assert_ptr_equal(g.joints, joints);
    assert_true(g.joint_tolerance == 0.02);
    assert_null(g.link);
    for (int i = 0; i < 3; i++)
        assert_true(g.position[i] == 0 && g.orientation_tolerance[i] == 0);
}

static void test_verdict_names(void **state)
{
    (void)state;
    for (int c = 0; c < MPB_VERDICT_COUNT; c++) {
        const char *n = mpb_verdict_name((mpb_verdict_code)c);
        assert_non_null(n);
        assert_string_not_equal(n, "unknown");
        for (int d = 0; d < c; d++)
            assert_string_not_equal(n, mpb_verdict_name((mpb_verdict_code)d));
    }
    assert_string_equal(mpb_verdict_name(MPB_VERDICT_JOINT_LIMIT), "joint_limit");
    assert_string_equal(mpb_verdict_name(MPB_VERDICT_COUNT), "unknown");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_valid, setup, teardown),
        cmocka_unit_test_setup_teardown(test_collision_between_valid_waypoints, setup, teardown),
        cmocka_unit_test_setup_teardown(test_resolution_sets_the_samples, setup, teardown),
        cmocka_unit_test_setup_teardown(test_goal, setup, teardown),
        cmocka_unit_test_setup_teardown(test_not_finite, setup, teardown),
        cmocka_unit_test_setup_teardown(test_joint_limit, setup, teardown),
        cmocka_unit_test_setup_teardown(test_numbers_at_the_boundary_differ,
                                        setup, teardown),
        cmocka_unit_test_setup_teardown(test_start, setup, teardown),
        cmocka_unit_test_setup_teardown(test_empty_and_size, setup, teardown),
        cmocka_unit_test_setup_teardown(test_order, setup, teardown),
        cmocka_unit_test_setup_teardown(test_waypoint_0_collides, setup, teardown),
        cmocka_unit_test_setup_teardown(test_pose_region_unsupported, setup, teardown),
        cmocka_unit_test(test_continuous_joint),
        cmocka_unit_test_setup_teardown(test_bad_arguments, setup, teardown),
        cmocka_unit_test(test_verdict_verification),
        cmocka_unit_test(test_query_goal),
        cmocka_unit_test(test_verdict_names),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
