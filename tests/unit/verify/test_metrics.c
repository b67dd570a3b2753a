/*
 * test_metrics.c - path length and smoothness against values worked out by
 * hand (each in a comment beside it).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "core/mathconst.h"

/* cmocka 1.1.5's assert_float_equal works in float; this one in double. */
#define assert_near(a, b, eps)                                              \
    do {                                                                    \
        double a_ = (a), b_ = (b);                                          \
        if (!(fabs(a_ - b_) <= (eps)))                                      \
            fail_msg("%s = %.17g, expected %.17g", #a, a_, b_);             \
    } while (0)

#define EPS 1e-12

static void test_joint_delta(void **state)
{
    (void)state;
    /* Not wrapping: plain b - a. */
    assert_near(mpb_joint_delta(0.5, 0.25, 0), -0.25, EPS);
    assert_near(mpb_joint_delta(3.0, -3.0, 0), -6.0, EPS);
    /* Wrapping: -6 + 2 pi = 0.28318530717958623 (crossing +pi upwards). */
    assert_near(mpb_joint_delta(3.0, -3.0, 1), 2 * M_PI - 6.0, EPS);
    /* The other way: 6 - 2 pi = -0.28318530717958623. */
    assert_near(mpb_joint_delta(-3.0, 3.0, 1), 6.0 - 2 * M_PI, EPS);
    /* Half a turn is +pi from either side: the range is (-pi, pi]. */
    assert_near(mpb_joint_delta(0.0, M_PI, 1), M_PI, EPS);
    assert_near(mpb_joint_delta(0.0, -M_PI, 1), M_PI, EPS);
    /* Whole turns vanish: (4 pi + 0.5) - 0 -> 0.5; pi vs -pi -> 0. */
    assert_near(mpb_joint_delta(0.0, 4 * M_PI + 0.5, 1), 0.5, EPS);
    assert_near(mpb_joint_delta(M_PI, -M_PI, 1), 0.0, EPS);
}

static void test_path_length_segments(void **state)
{
    (void)state;
    /* (0,0)->(3,4)->(3,4)->(3,0): 5 + 0 (zero-length segment) + 4 = 9. */
    const double wp[] = { 0, 0,  3, 4,  3, 4,  3, 0 };
    assert_near(mpb_path_length(wp, 4, 2, NULL), 9.0, EPS);
}

static void test_path_length_two_waypoints(void **state)
{
    (void)state;
    /* (0,0,0)->(1,2,2): sqrt(1 + 4 + 4) = 3. */
    const double wp[] = { 0, 0, 0,  1, 2, 2 };
    assert_near(mpb_path_length(wp, 2, 3, NULL), 3.0, EPS);
}

static void test_path_length_degenerate(void **state)
{
    (void)state;
    const double wp[] = { 1, 2 };
    assert_near(mpb_path_length(wp, 1, 2, NULL), 0.0, 0.0);  /* one waypoint */
    assert_near(mpb_path_length(wp, 0, 2, NULL), 0.0, 0.0);  /* none */
    assert_near(mpb_path_length(NULL, 0, 2, NULL), 0.0, 0.0);
    const double nan_wp[] = { 0, 0,  NAN, 1 };
    assert_true(isnan(mpb_path_length(nan_wp, 2, 2, NULL)));
}

static void test_path_length_continuous(void **state)
{
    (void)state;
    /*
     * One joint 3.0 -> -3.0 -> -2.5. Wrapping, the first step crosses +pi the
     * short way: (2 pi - 6) + 0.5 = 2 pi - 5.5 = 0.78318530717958623.
     * Not wrapping: 6 + 0.5 = 6.5.
     */
    const double wp[] = { 3.0, -3.0, -2.5 };
    const unsigned char wraps[] = { 1 };
    assert_near(mpb_path_length(wp, 3, 1, wraps), 2 * M_PI - 5.5, EPS);
    assert_near(mpb_path_length(wp, 3, 1, NULL), 6.5, EPS);

    /*
     * Two joints, only joint 0 wraps: (3.0, 0) -> (-3.0, 0.3):
     * sqrt((2 pi - 6)^2 + 0.3^2) = sqrt(0.0801939 + 0.09) = 0.41254566.
     */
    const double wp2[] = { 3.0, 0.0,  -3.0, 0.3 };
    const unsigned char wraps2[] = { 1, 0 };
    double d0 = 2 * M_PI - 6.0;
    assert_near(mpb_path_length(wp2, 2, 2, wraps2), sqrt(d0 * d0 + 0.09), EPS);
    assert_near(mpb_path_length(wp2, 2, 2, wraps2), 0.41254566, 1e-8);
}

static void test_smoothness_right_angles(void **state)
{
    (void)state;
    /*
     * Staircase (0,0)->(1,0)->(1,1)->(2,1): n = 3 segments, directions
     * +x, +y, +x; alpha_2 = alpha_3 = pi/2.
     * kappa' = (1/3) (pi^2/4 + pi^2/4) = pi^2/6 = 1.6449340668.
     */
    const double wp[] = { 0, 0,  1, 0,  1, 1,  2, 1 };
    assert_near(mpb_smoothness(wp, 4, 2, NULL), M_PI * M_PI / 6, EPS);

    /* The same in 3-D: +x, +y, +z, two right angles, n = 3: pi^2/6. */
    const double wp3[] = { 0, 0, 0,  1, 0, 0,  1, 1, 0,  1, 1, 1 };
    assert_near(mpb_smoothness(wp3, 4, 3, NULL), M_PI * M_PI / 6, EPS);
}

static void test_smoothness_zero_length_dropped(void **state)
{
    (void)state;
    /*
     * The staircase with (1,0) repeated: the zero-length segment is dropped,
     * n = 3 remain, the angles are still pi/2, pi/2: pi^2/6. (Counting it
     * would give n = 4 and an undefined angle.)
     */
    const double wp[] = { 0, 0,  1, 0,  1, 0,  1, 1,  2, 1 };
    assert_near(mpb_smoothness(wp, 5, 2, NULL), M_PI * M_PI / 6, EPS);

    /* (0,0)->(1,0)->(1,0): one segment remains, n < 2: 0. */
    const double wp1[] = { 0, 0,  1, 0,  1, 0 };
    assert_near(mpb_smoothness(wp1, 3, 2, NULL), 0.0, 0.0);
}

static void test_smoothness_angles(void **state)
{
    (void)state;
    /* Straight line in 4 waypoints: every alpha is 0. */
    const double line[] = { 0, 0,  1, 1,  2, 2,  3.5, 3.5 };
    assert_near(mpb_smoothness(line, 4, 2, NULL), 0.0, 1e-15);

    /* Out and back (0,0)->(1,0)->(0,0): alpha = pi, n = 2: pi^2/2. */
    const double back[] = { 0, 0,  1, 0,  0, 0 };
    assert_near(mpb_smoothness(back, 3, 2, NULL), M_PI * M_PI / 2, EPS);

    /* (0,0)->(1,0)->(2,1): 45 degrees, n = 2: (pi/4)^2 / 2 = pi^2/32. */
    const double turn45[] = { 0, 0,  1, 0,  2, 1 };
    assert_near(mpb_smoothness(turn45, 3, 2, NULL), M_PI * M_PI / 32, EPS);

    /*
     * (0,0)->(1,0)->(1 + cos 60deg, sin 60deg) = (1.5, sqrt(3)/2): 60 degrees
     * with segments of different lengths (1 and 1), n = 2:
     * (pi/3)^2 / 2 = pi^2/18.
     */
    const double turn60[] = { 0, 0,  1, 0,  1.5, sqrt(3.0) / 2 };
    assert_near(mpb_smoothness(turn60, 3, 2, NULL), M_PI * M_PI / 18, EPS);

    /* Fewer than two segments: 0. */
    assert_near(mpb_smoothness(turn45, 2, 2, NULL), 0.0, 0.0);
    assert_near(mpb_smoothness(turn45, 1, 2, NULL), 0.0, 0.0);
}

static void test_smoothness_continuous(void **state)
{
    (void)state;
    /*
     * One joint 3.0 -> -3.0 -> -2.5. Wrapping, both steps go upwards
     * (+0.283, +0.5): alpha = 0, kappa' = 0. Not wrapping the first goes
     * down (-6) and the second up (+0.5): alpha = pi, n = 2: pi^2/2.
     */
    const double wp[] = { 3.0, -3.0, -2.5 };
    const unsigned char wraps[] = { 1 };
    assert_near(mpb_smoothness(wp, 3, 1, wraps), 0.0, 1e-15);
    assert_near(mpb_smoothness(wp, 3, 1, NULL), M_PI * M_PI / 2, EPS);
}

/* A one-link planar arm of length 1 at the origin, link radius 0.1, and a
 * circle of radius 0.5 at (0, 2). */
static mpb_world *one_link(const char *joint)
{
    mpb_world *w = NULL;
    char robot[128];
    snprintf(robot, sizeof robot, "link_radius 0.1\njoint a %s 1\n", joint);
    assert_int_equal(mpb_world_open("planar", robot, "planar",
                                    "circle 0 2 0.5\n", &w, NULL, 0), MPB_OK);
    return w;
}

/*
 * The same right-angled path, (0,0) (1,0) (1,1), with each segment cut into
 * ten by collinear waypoints: kappa' = (pi/2)^2 / n falls tenfold, from
 * n = 2 to n = 20; kappa'_r does not move. The corner lies at length 1 of
 * 2, the end of piece 50 of 100: the whole (pi/2)^2, over 100.
 */
static void test_smoothness_resampled_ignores_collinear_waypoints(void **state)
{
    (void)state;
    const double sparse[] = {0, 0, 1, 0, 1, 1};
    double dense[21 * 2];
    for (int i = 0; i <= 10; i++) {
        dense[2 * i] = i / 10.0;
        dense[2 * i + 1] = 0.0;
        dense[2 * (10 + i)] = 1.0;
        dense[2 * (10 + i) + 1] = i / 10.0;
    }
    double right = (M_PI / 2) * (M_PI / 2);
    assert_near(mpb_smoothness(sparse, 3, 2, NULL), right / 2, EPS);
    assert_near(mpb_smoothness(dense, 21, 2, NULL), right / 20, EPS);
    assert_near(mpb_smoothness_resampled(sparse, 3, 2, NULL), right / 100,
                EPS);
    assert_near(mpb_smoothness_resampled(dense, 21, 2, NULL), right / 100,
                EPS);
}

/* A corner inside a piece: (0,0) (1.01,0) (1.01,0.99), length 2, pieces of
 * 0.02; the piece from 1.00 to 1.02 is (0.01, 0.01), at pi/4 to both of
 * its neighbours: 2 (pi/4)^2 = (pi/2)^2 / 2, over 100. */
static void test_smoothness_resampled_corner_inside_a_piece(void **state)
{
    (void)state;
    const double wp[] = {0, 0, 1.01, 0, 1.01, 0.99};
    double right = (M_PI / 2) * (M_PI / 2);
    assert_near(mpb_smoothness_resampled(wp, 3, 2, NULL), right / 200, 1e-9);
    /* Degenerate paths, as mpb_smoothness(). */
    assert_near(mpb_smoothness_resampled(wp, 2, 2, NULL), 0.0, 0.0);
    const double still[] = {1, 1, 1, 1, 1, 1};
    assert_near(mpb_smoothness_resampled(still, 3, 2, NULL), 0.0, 0.0);
    const double bad[] = {0, 0, NAN, 0, 1, 1};
    assert_true(isnan(mpb_smoothness_resampled(bad, 3, 2, NULL)));
}

/* A straight 7-joint path cut at 37 waypoints whose values are not exact in
 * binary: the unit vectors differ in their last bits, and the angle between
 * them (about 1e-16 rad) is rounding, not turning. Both measures give 0,
 * not 1e-30 that a report would print as data. */
static void test_smoothness_of_a_straight_path_is_zero(void **state)
{
    (void)state;
    const double a[7] = {0.1, -1.3, 2.7, 0.33, -0.7, 1.9, -2.2};
    const double b[7] = {-0.9, 0.4, -1.1, 1.7, 0.05, -2.3, 1.3};
    double wp[37 * 7];
    for (int i = 0; i < 37; i++)
        for (int j = 0; j < 7; j++)
            wp[i * 7 + j] = a[j] + (b[j] - a[j]) * (i / 36.0);
    assert_true(mpb_smoothness(wp, 37, 7, NULL) == 0.0);
    assert_true(mpb_smoothness_resampled(wp, 37, 7, NULL) == 0.0);
}

static void test_clearance_mean_and_min(void **state)
{
    (void)state;
    mpb_world *w = one_link("-4 4");
    /* q = 0: the link lies on (0,0)-(1,0), 2 from the centre: 2 - 0.5 - 0.1
     * = 1.4. q = pi/2: it reaches (0,1), 1 from the centre: 0.4. */
    double wp[] = {0.0, M_PI / 2};
    assert_float_equal(mpb_path_min_clearance(w, wp, 2, 1), 0.4, 1e-9);
    assert_float_equal(mpb_path_clearance(w, wp, 2, 1), 0.9, 1e-9);
    double mean = 0, least = 0;
    mpb_path_clearances(w, wp, 2, 1, &mean, &least);
    assert_float_equal(mean, 0.9, 1e-9);
    assert_float_equal(least, 0.4, 1e-9);
    mpb_path_clearances(w, wp, 2, 2, &mean, &least);
    assert_true(isnan(mean) && isnan(least));
    assert_true(isnan(mpb_path_min_clearance(w, wp, 2, 2)));  /* wrong size */
    mpb_world_close(w);
}

static void test_ee_path_length_follows_the_arc(void **state)
{
    (void)state;
    mpb_world *w = one_link("-4 4");
    /* The tip of a unit link turning by pi/2 travels a quarter circle,
     * pi/2 m, though the straight line between the ends is sqrt(2). */
    double wp[] = {0.0, M_PI / 2};
    assert_float_equal(mpb_ee_path_length(w, wp, 2, 1, 1e-3), M_PI / 2, 1e-6);
    /* Steps as coarse as the whole segment give the chord. */
    assert_float_equal(mpb_ee_path_length(w, wp, 2, 1, 10.0), sqrt(2.0), 1e-12);
    double there_and_back[] = {0.0, 1.0, 0.0};
    assert_float_equal(mpb_ee_path_length(w, there_and_back, 3, 1, 1e-3), 2.0, 1e-6);
    assert_true(isnan(mpb_ee_path_length(w, wp, 2, 1, 0.0)));
    mpb_world_close(w);

    /* A continuous joint from 3 to -3 turns 2 pi - 6 = 0.2832 rad the
     * short way: an arc of that length. */
    w = one_link("continuous");
    double wrap[] = {3.0, -3.0};
    assert_float_equal(mpb_ee_path_length(w, wrap, 2, 1, 1e-3), 2 * M_PI - 6.0, 1e-6);
    mpb_world_close(w);
}

/* The metric list: names unique and found again; mpb_measure_stage()
 * gives every metric of a sound path, by the list's names, with the
 * values of the functions above, and leaves out the path metrics of a
 * path with a NaN in it; with MPB_MEASURE_NO_METRICS, the same verdict
 * and no metric. */
static void test_measure_stage_follows_the_list(void **state)
{
    (void)state;
    for (int i = 0; i < MPB_NUM_METRICS; i++) {
        const mpb_metric_info *mi = mpb_metric_info_of(i);
        assert_non_null(mi);
        assert_int_equal(mpb_metric_find(mi->name), i);
    }
    assert_null(mpb_metric_info_of(MPB_NUM_METRICS));
    assert_int_equal(mpb_metric_find("no such metric"), -1);

    mpb_world *w = one_link("-4 4");
    double wp[] = {0.0, M_PI / 2}, start[] = {0.0}, end[] = {M_PI / 2};
    mpb_goal goal = {.kind = MPB_GOAL_JOINTS, .joints = end,
                     .joint_tolerance = 1e-6};
    mpb_stage_measure m;
    assert_int_equal(mpb_measure_stage(w, start, 1e-6, &goal, wp, 2, 1, 0.25,
                                       0.01, 0, &m), MPB_OK);
    assert_int_equal(m.verdict.code, MPB_VERDICT_VALID);
    assert_int_equal(m.num_metrics, MPB_NUM_METRICS);
    for (int i = 0; i < m.num_metrics; i++)
        assert_string_equal(m.metrics[i].name, mpb_metric_info_of(i)->name);
    assert_float_equal(m.metrics[MPB_METRIC_CLEARANCE].value, 0.9, 1e-9);
    assert_float_equal(m.metrics[MPB_METRIC_MIN_CLEARANCE].value, 0.4, 1e-9);
    assert_float_equal(m.metrics[MPB_METRIC_PATH_LENGTH].value, M_PI / 2,
                       1e-12);
    assert_float_equal(m.metrics[MPB_METRIC_WAYPOINTS].value, 2, 0);
    assert_float_equal(m.metrics[MPB_METRIC_TIME].value, 0.25, 0);

    double bad[] = {0.0, NAN};
    mpb_verdict valid = m.verdict;
    mpb_measure_stage(w, start, 1e-6, &goal, bad, 2, 1, 0.25, 0.01, 0, &m);
    assert_int_equal(m.verdict.code, MPB_VERDICT_NOT_FINITE);
    int n = 0;
    for (int i = 0; i < MPB_NUM_METRICS; i++)
        n += !(mpb_metric_info_of(i)->flags & MPB_METRIC_F_PATH);
    assert_int_equal(m.num_metrics, n);

    assert_int_equal(mpb_measure_stage(w, start, 1e-6, &goal, wp, 2, 1, 0.25,
                                       0.01, MPB_MEASURE_NO_METRICS, &m),
                     MPB_OK);
    assert_int_equal(m.verdict.code, MPB_VERDICT_VALID);
    assert_int_equal(m.verdict.certified, valid.certified);
    assert_string_equal(m.verdict.detail, valid.detail);
    assert_int_equal(m.num_metrics, 0);
    mpb_world_close(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_joint_delta),
        cmocka_unit_test(test_path_length_segments),
        cmocka_unit_test(test_path_length_two_waypoints),
        cmocka_unit_test(test_path_length_degenerate),
        cmocka_unit_test(test_path_length_continuous),
        cmocka_unit_test(test_smoothness_right_angles),
        cmocka_unit_test(test_smoothness_zero_length_dropped),
        cmocka_unit_test(test_smoothness_angles),
        cmocka_unit_test(test_smoothness_continuous),
        cmocka_unit_test(test_smoothness_resampled_ignores_collinear_waypoints),
        cmocka_unit_test(test_smoothness_resampled_corner_inside_a_piece),
        cmocka_unit_test(test_smoothness_of_a_straight_path_is_zero),
        cmocka_unit_test(test_clearance_mean_and_min),
        cmocka_unit_test(test_ee_path_length_follows_the_arc),
        cmocka_unit_test(test_measure_stage_follows_the_list),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
