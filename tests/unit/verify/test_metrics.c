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
#include <string.h>
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
    /* Untimed: every metric but the timed ones, which come last. */
    int untimed = 0;
    for (int i = 0; i < MPB_NUM_METRICS; i++)
        if (!(mpb_metric_info_of(i)->flags & MPB_METRIC_F_TIMED))
            assert_int_equal(i, untimed++);
    assert_true(untimed < MPB_NUM_METRICS);
    assert_int_equal(m.num_metrics, untimed);
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
        n += !(mpb_metric_info_of(i)->flags &
               (MPB_METRIC_F_PATH | MPB_METRIC_F_TIMED));
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

/*
 * Timing by finite differences, worked by hand. Joints x, y; waypoints
 * (0,0) (1,0) (1,0) (1,2) at 0, 1, 1, 2 s: segment 0 moves x at 1 rad/s,
 * segment 1 is the waypoint repeated at its time (dropped), segment 2
 * moves y at 2 rad/s. Duration 2 s; largest velocity 2; between segments
 * 0 and 2 the velocity changes by (-1, 2) over (1 + 1) / 2 = 1 s: largest
 * acceleration 2. With limits (0.5, none): x at 1 is twice its limit, in
 * segment 0; y has none, so the ratio is 2.
 */
static void test_path_timing(void **state)
{
    (void)state;
    const double wp[] = {0, 0, 1, 0, 1, 0, 1, 2};
    const double t[] = {0, 1, 1, 2};
    const double limits[] = {0.5, 0};
    mpb_timing tm;
    assert_int_equal(mpb_path_timing(wp, t, 4, 2, NULL, limits, &tm), MPB_OK);
    assert_near(tm.duration, 2.0, EPS);
    assert_near(tm.max_velocity, 2.0, EPS);
    assert_near(tm.max_acceleration, 2.0, EPS);
    assert_near(tm.velocity_ratio, 2.0, EPS);
    assert_int_equal(tm.ratio_segment, 0);
    assert_int_equal(tm.ratio_joint, 0);
    /* No limits at all: no ratio. */
    assert_int_equal(mpb_path_timing(wp, t, 4, 2, NULL, NULL, &tm), MPB_OK);
    assert_true(isnan(tm.velocity_ratio));
    assert_int_equal(tm.ratio_segment, -1);
    /* A start that is not at 0: the duration is last less first. */
    const double late[] = {5, 6, 6, 7};
    assert_int_equal(mpb_path_timing(wp, late, 4, 2, NULL, NULL, &tm), MPB_OK);
    assert_near(tm.duration, 2.0, EPS);
    /* A continuous joint the short way: 3 -> -3 is 2 pi - 6 rad in 0.5 s. */
    const double wrap[] = {3.0, -3.0};
    const double t2[] = {0, 0.5};
    const unsigned char wraps[] = {1};
    assert_int_equal(mpb_path_timing(wrap, t2, 2, 1, wraps, NULL, &tm), MPB_OK);
    assert_near(tm.max_velocity, (2 * M_PI - 6.0) / 0.5, 1e-12);
    assert_near(tm.max_acceleration, 0.0, 0);   /* one segment: none */
    /* Moving in no time: infinitely fast, and an infinite acceleration. */
    const double jump[] = {0, 1, 2};
    const double t3[] = {0, 1, 1};
    const double lim1[] = {10};
    assert_int_equal(mpb_path_timing(jump, t3, 3, 1, NULL, lim1, &tm), MPB_OK);
    assert_true(isinf(tm.max_velocity));
    assert_true(isinf(tm.max_acceleration));
    assert_true(isinf(tm.velocity_ratio));
    assert_int_equal(tm.ratio_segment, 1);
    /* One waypoint: no motion, no duration. */
    assert_int_equal(mpb_path_timing(wp, t, 1, 2, NULL, NULL, &tm), MPB_OK);
    assert_near(tm.duration, 0.0, 0);
    assert_near(tm.max_velocity, 0.0, 0);
    assert_int_equal(mpb_path_timing(NULL, t, 2, 2, NULL, NULL, &tm),
                     MPB_EINVAL);
    assert_true(isnan(tm.duration));
}

/* What a timing is: one time per waypoint, finite, from 0 or later,
 * non-decreasing (a repeat is fine). */
static void test_times_ok(void **state)
{
    (void)state;
    char why[128];
    const double good[] = {0, 0.5, 0.5, 2};
    assert_true(mpb_times_ok(good, 4, 4, why, sizeof why));
    const double later[] = {1.5, 2};
    assert_true(mpb_times_ok(later, 2, 2, NULL, 0));
    assert_false(mpb_times_ok(good, 3, 4, why, sizeof why));
    assert_string_equal(why, "3 waypoint times for 4 waypoints");
    const double down[] = {0, 0.5, 0.25};
    assert_false(mpb_times_ok(down, 3, 3, why, sizeof why));
    assert_string_equal(why, "time 2 (0.25 s) is below time 1 (0.5 s)");
    const double neg[] = {-0.5, 1};
    assert_false(mpb_times_ok(neg, 2, 2, why, sizeof why));
    assert_string_equal(why, "time 0 (-0.5 s) is negative");
    const double nan[] = {0, NAN};
    assert_false(mpb_times_ok(nan, 2, 2, why, sizeof why));
    assert_string_equal(why, "time 1 is not finite");
    const double inf[] = {0, INFINITY};
    assert_false(mpb_times_ok(inf, 2, 2, NULL, 0));
}

/* A one-joint arm whose URDF limits its joint to 1 rad/s, and a
 * continuous second joint with no limit, in an empty scene. */
static const char ARM[] =
    "<robot name='arm'><link name='base'/>"
    "<link name='l1'><collision><geometry><sphere radius='0.05'/></geometry>"
    "</collision></link>"
    "<link name='l2'><collision><origin xyz='1 0 0'/><geometry>"
    "<sphere radius='0.05'/></geometry></collision></link>"
    "<joint name='j1' type='revolute'><parent link='base'/><child link='l1'/>"
    "<axis xyz='0 0 1'/><limit lower='-3' upper='3' effort='1' velocity='1'/>"
    "</joint>"
    "<joint name='j2' type='continuous'><parent link='l1'/><child link='l2'/>"
    "<origin xyz='0 0 1'/><axis xyz='0 0 1'/></joint></robot>";

/*
 * The verdict of a timed stage: j1 from 0 to 1 rad (j2 from 0 to 3 rad,
 * unlimited) in T seconds. T = 0.5: 2 rad/s, twice the limit: refused
 * (velocity_limit, segment 0, the joint named). T = 2: 0.5 rad/s, valid,
 * with duration, velocities and no acceleration (one segment). T = 0.995:
 * 1.005 times the limit, inside the 1% tolerance: valid. The same path
 * untimed: valid, without the timed metrics. A path that fails another
 * check keeps that verdict.
 */
static void test_velocity_limit_verdict(void **state)
{
    (void)state;
    static const char *const joints[] = {"j1", "j2"};
    mpb_world *w = NULL;
    char err[256];
    if (mpb_world_open_group("urdf", ARM, "moveit-scene", "empty\n.\n", joints,
                             2, &w, err, sizeof err) != MPB_OK)
        fail_msg("open: %s", err);
    assert_near(mpb_world_joint_max_velocity(w, 0), 1.0, 0);
    assert_near(mpb_world_joint_max_velocity(w, 1), 0.0, 0);
    assert_near(mpb_world_joint_max_velocity(w, 2), 0.0, 0);
    double wp[] = {0, 0, 0.5, 1.5, 1, 3}, start[] = {0, 0}, end[] = {1, 3};
    mpb_goal goal = {.kind = MPB_GOAL_JOINTS, .joints = end,
                     .joint_tolerance = 1e-6};
    mpb_stage_measure m;

    double fast[] = {0, 0.25, 0.5};
    assert_int_equal(mpb_measure_stage_timed(w, start, 1e-6, &goal, wp, fast,
                                             3, 2, 0.1, 0.01, 0, &m), MPB_OK);
    assert_int_equal(m.verdict.code, MPB_VERDICT_VELOCITY_LIMIT);
    assert_string_equal(mpb_verdict_name(m.verdict.code), "velocity_limit");
    assert_int_equal(m.verdict.segment, 0);
    assert_non_null(strstr(m.verdict.detail, "joint j1 at 2,"));
    assert_non_null(strstr(m.verdict.detail, "limit 1"));
    assert_non_null(mpb_verdict_verification(&m.verdict));
    int found = 0;
    for (int i = 0; i < m.num_metrics; i++)
        if (strcmp(m.metrics[i].name, "velocity_limit_ratio") == 0) {
            assert_near(m.metrics[i].value, 2.0, 1e-12);
            found = 1;
        }
    assert_true(found);

    double slow[] = {0, 1, 2};
    assert_int_equal(mpb_measure_stage_timed(w, start, 1e-6, &goal, wp, slow,
                                             3, 2, 0.1, 0.01, 0, &m), MPB_OK);
    assert_int_equal(m.verdict.code, MPB_VERDICT_VALID);
    assert_int_equal(m.num_metrics, MPB_NUM_METRICS);
    assert_near(m.metrics[MPB_METRIC_DURATION].value, 2.0, EPS);
    assert_near(m.metrics[MPB_METRIC_MAX_VELOCITY].value, 1.5, EPS);
    assert_near(m.metrics[MPB_METRIC_VELOCITY_RATIO].value, 0.5, EPS);
    assert_near(m.metrics[MPB_METRIC_MAX_ACCELERATION].value, 0.0, EPS);
    assert_string_equal(m.metrics[MPB_METRIC_DURATION].name, "duration");

    double edge[] = {0, 0.4975, 0.995};
    assert_int_equal(mpb_measure_stage_timed(w, start, 1e-6, &goal, wp, edge,
                                             3, 2, 0.1, 0.01, 0, &m), MPB_OK);
    assert_int_equal(m.verdict.code, MPB_VERDICT_VALID);

    assert_int_equal(mpb_measure_stage_timed(w, start, 1e-6, &goal, wp, NULL,
                                             3, 2, 0.1, 0.01, 0, &m), MPB_OK);
    assert_int_equal(m.verdict.code, MPB_VERDICT_VALID);
    for (int i = 0; i < m.num_metrics; i++)
        assert_false(mpb_metric_info_of(mpb_metric_find(m.metrics[i].name))
                         ->flags & MPB_METRIC_F_TIMED);

    double off[] = {0.5, 0};    /* not its start: that verdict first */
    assert_int_equal(mpb_measure_stage_timed(w, off, 1e-6, &goal, wp, fast,
                                             3, 2, 0.1, 0.01, 0, &m), MPB_OK);
    assert_int_equal(m.verdict.code, MPB_VERDICT_START);
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
        cmocka_unit_test(test_path_timing),
        cmocka_unit_test(test_times_ok),
        cmocka_unit_test(test_velocity_limit_verdict),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
