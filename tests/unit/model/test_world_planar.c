/*
 * test_world_planar.c - the "planar" world: parsing and its errors, forward
 * kinematics, collision and clearance against closed forms worked out by
 * hand in the comments.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "model/world_provider.h"     /* mpb__planar_points(), for FK */
#include "core/mathconst.h"

#define assert_near(a, b, eps)                                              \
    do {                                                                    \
        double a_ = (a), b_ = (b);                                          \
        if (!(fabs(a_ - b_) <= (eps)))                                      \
            fail_msg("%s = %.17g, expected %.17g", #a, a_, b_);             \
    } while (0)

#define EPS 1e-12

/* Two unit links along +x at q = 0, capsules of radius 0.1. */
static const char *const ARM2 =
    "# two links\n"
    "base 0 0\n"
    "link_radius 0.1\n"
    "joint shoulder -3.14 3.14 1.0\n"
    "joint elbow -2.5 2.5 1.0   # elbow\n";

static mpb_world *open_ok(const char *robot, const char *scene)
{
    mpb_world *w = NULL;
    char err[200];
    int rc = mpb_world_open("planar", robot, "planar", scene, &w, err, sizeof err);
    if (rc != MPB_OK)
        fail_msg("mpb_world_open: %s: %s", mpb_err_name(rc), err);
    return w;
}

/* Expect MPB_EPARSE with each of the needles in the message. */
static void expect_parse_error(const char *robot, const char *scene,
                               const char *needle1, const char *needle2)
{
    mpb_world *w = (mpb_world *)1;
    char err[200];
    int rc = mpb_world_open("planar", robot, "planar", scene, &w, err, sizeof err);
    assert_int_equal(rc, MPB_EPARSE);
    assert_null(w);
    assert_null(strchr(err, '\n'));
    if (!strstr(err, needle1) || (needle2 && !strstr(err, needle2)))
        fail_msg("message \"%s\" lacks \"%s\" / \"%s\"", err, needle1,
                 needle2 ? needle2 : "");
}

static void test_joints(void **state)
{
    (void)state;
    mpb_world *w = open_ok("link_radius 0\n"
                           "joint a -1 2 1\n"
                           "joint spin continuous 0.5\n", "");
    assert_int_equal(mpb_world_num_joints(w), 2);
    assert_string_equal(mpb_world_joint_name(w, 0), "a");
    assert_string_equal(mpb_world_joint_name(w, 1), "spin");
    assert_null(mpb_world_joint_name(w, 2));
    assert_null(mpb_world_joint_name(w, -1));
    double lo, hi;
    mpb_world_joint_limits(w, 0, &lo, &hi);
    assert_near(lo, -1, 0);
    assert_near(hi, 2, 0);
    mpb_world_joint_limits(w, 1, &lo, &hi);      /* continuous: -pi .. pi */
    assert_near(lo, -M_PI, 0);
    assert_near(hi, M_PI, 0);
    mpb_world_joint_limits(w, 5, &lo, &hi);
    assert_true(isnan(lo) && isnan(hi));
    assert_int_equal(mpb_world_joint_is_continuous(w, 0), 0);
    assert_int_equal(mpb_world_joint_is_continuous(w, 1), 1);
    const unsigned char *wr = mpb_world_joint_wraps(w);
    assert_int_equal(wr[0], 0);
    assert_int_not_equal(wr[1], 0);
    mpb_world_close(w);
    mpb_world_close(NULL);                       /* harmless */
}

static void test_forward_kinematics(void **state)
{
    (void)state;
    double xy[6];
    mpb_world *w = open_ok(ARM2, NULL);

    /* q = 0: (0,0), (1,0), (2,0). */
    const double q0[] = { 0, 0 };
    assert_int_equal(mpb__planar_points(w, q0, xy), MPB_OK);
    assert_near(xy[2], 1, EPS); assert_near(xy[3], 0, EPS);
    assert_near(xy[4], 2, EPS); assert_near(xy[5], 0, EPS);

    /* q = (pi/2, -pi/2): elbow at (0,1), angles add: tip at (1,1). */
    const double q1[] = { M_PI / 2, -M_PI / 2 };
    mpb__planar_points(w, q1, xy);
    assert_near(xy[2], 0, EPS); assert_near(xy[3], 1, EPS);
    assert_near(xy[4], 1, EPS); assert_near(xy[5], 1, EPS);

    /* q = (pi/6, pi/3): elbow (cos 30, sin 30) = (0.866, 0.5); the second
     * link points at 30 + 60 = 90 degrees: tip (0.866, 1.5). */
    const double q2[] = { M_PI / 6, M_PI / 3 };
    mpb__planar_points(w, q2, xy);
    assert_near(xy[2], sqrt(3.0) / 2, EPS); assert_near(xy[3], 0.5, EPS);
    assert_near(xy[4], sqrt(3.0) / 2, EPS); assert_near(xy[5], 1.5, EPS);
    mpb_world_close(w);

    /* A base at (1, 2) shifts every point: q = 0 tip at (3, 2). */
    w = open_ok("base 1 2\nlink_radius 0.1\njoint a -1 1 1\njoint b -1 1 1\n", "");
    mpb__planar_points(w, q0, xy);
    assert_near(xy[0], 1, EPS); assert_near(xy[1], 2, EPS);
    assert_near(xy[4], 3, EPS); assert_near(xy[5], 2, EPS);
    mpb_world_close(w);
}

static void test_clearance_circles(void **state)
{
    (void)state;
    /*
     * Circle A (3, 0) r 0.5; circle B (1, 2) r 0.5; links radius 0.1.
     * q = (0, 0), arm (0,0)-(2,0): A is 1 beyond the tip -> 1 - 0.5 - 0.1
     * = 0.4; B is 2 above (1,0) -> 2 - 0.6 = 1.4. Clearance 0.4.
     * q = (pi/2, 0), arm (0,0)-(0,2): A is 3 from (0,0) -> 2.4; B is 1
     * from the tip (0,2) -> 0.4. Clearance 0.4.
     */
    mpb_world *w = open_ok(ARM2, "circle 3 0 0.5\ncircle 1 2 0.5\n");
    const double q0[] = { 0, 0 }, q1[] = { M_PI / 2, 0 };
    assert_near(mpb_world_clearance(w, q0), 0.4, EPS);
    assert_near(mpb_world_clearance(w, q1), 0.4, EPS);
    assert_int_equal(mpb_world_in_collision(w, q0), 0);
    mpb_world_close(w);

    /* Only A: 0.4 at q0, 2.4 at q1; the path's mean clearance d_n is 1.4. */
    w = open_ok(ARM2, "circle 3 0 0.5");
    assert_near(mpb_world_clearance(w, q1), 2.4, EPS);
    const double path[] = { 0, 0,  M_PI / 2, 0 };
    assert_near(mpb_path_clearance(w, path, 2, 2), 1.4, EPS);
    assert_true(isnan(mpb_path_clearance(w, path, 2, 3)));
    mpb_world_close(w);

    /*
     * Circle (1, 0.15) r 0.1: 0.15 from the first link's axis, so
     * 0.15 - 0.1 - 0.1 = -0.05: in collision.
     */
    w = open_ok(ARM2, "circle 1 0.15 0.1");
    assert_near(mpb_world_clearance(w, q0), -0.05, EPS);
    assert_int_equal(mpb_world_in_collision(w, q0), 1);
    mpb_world_close(w);
}

static void test_touching_counts(void **state)
{
    (void)state;
    /* A bare segment (radius 0) touching circle (1, 0.5) r 0.5: distance
     * 0.5 - 0.5 - 0 = 0, which is collision. */
    mpb_world *w = open_ok("link_radius 0\njoint a -1 1 2\n", "circle 1 0.5 0.5");
    const double q[] = { 0 };
    assert_near(mpb_world_clearance(w, q), 0.0, EPS);
    assert_int_equal(mpb_world_in_collision(w, q), 1);
    mpb_world_close(w);
}

static void test_clearance_boxes(void **state)
{
    (void)state;
    const double q0[] = { 0, 0 };
    /*
     * Box centre (1, -1), half sizes (0.5, 0.25): y in [-1.25, -0.75]. The
     * arm on y = 0 is 0.75 above its top side: 0.75 - 0.1 = 0.65.
     */
    mpb_world *w = open_ok(ARM2, "box 1 -1 0.5 0.25");
    assert_near(mpb_world_clearance(w, q0), 0.65, EPS);
    mpb_world_close(w);

    /*
     * A thin box across the arm, x in [0.9, 1.1], y in [-1, 1]: both ends of
     * every link are outside it, the links cross it: distance 0, clearance
     * -0.1 (minus the link radius), collision.
     */
    w = open_ok(ARM2, "box 1 0 0.1 1");
    assert_near(mpb_world_clearance(w, q0), -0.1, EPS);
    assert_int_equal(mpb_world_in_collision(w, q0), 1);
    mpb_world_close(w);

    /*
     * Nearest at a box corner: one link of length 2 at 45 degrees,
     * (0,0)-(sqrt 2, sqrt 2); box centre (2, 0) half 0.5: corners at
     * x = 1.5, 2.5, y = -0.5, 0.5. Corner (1.5, 0.5) is |1.5 - 0.5| / sqrt 2
     * = 1/sqrt 2 from the line y = x, its foot (1, 1) lies on the link. The
     * link's ends are farther: (0,0) 1.5; tip (1.414, 1.414) is
     * hypot(0.086, 0.914) = 0.918. Clearance 1/sqrt 2 - 0.1 = 0.6071068.
     */
    w = open_ok("link_radius 0.1\njoint a -3 3 2\n", "box 2 0 0.5 0.5");
    const double q45[] = { M_PI / 4 };
    assert_near(mpb_world_clearance(w, q45), 1 / sqrt(2.0) - 0.1, EPS);
    assert_int_equal(mpb_world_in_collision(w, q45), 0);
    mpb_world_close(w);
}

/* The collision check decides without distances (squared, no roots): it
 * must say what the clearance says, clearance <= 0, everywhere. Random
 * states of a three-link arm among circles and boxes, most near contact
 * (the arm sweeps through them), from a fixed seed. */
static void test_collision_agrees_with_clearance(void **state)
{
    (void)state;
    mpb_world *w = open_ok(
        "base 0 0\nlink_radius 0.05\n"
        "joint a -3.14159 3.14159 0.5\njoint b -3.14159 3.14159 0.4\n"
        "joint c -3.14159 3.14159 0.3\n",
        "circle 0.0 0.8 0.15\ncircle 0.7 -0.5 0.12\ncircle -0.3 -0.3 0.05\n"
        "box -0.7 0.0 0.1 0.3\nbox 0.4 0.4 0.05 0.05\n");
    uint64_t x = 88172645463325252ull;
    int hits = 0, misses = 0, near = 0;
    for (int i = 0; i < 200000; i++) {
        double q[3];
        for (int j = 0; j < 3; j++) {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            q[j] = -3.14159 + 6.28318 * (double)(x >> 11) / 9007199254740992.0;
        }
        double c = mpb_world_clearance(w, q);
        int hit = mpb_world_in_collision(w, q);
        if (hit != (c <= 0.0))
            fail_msg("q = (%.17g, %.17g, %.17g): in collision %d, clearance %.17g",
                     q[0], q[1], q[2], hit, c);
        hits += hit;
        misses += !hit;
        near += fabs(c) < 0.01;
    }
    /* Both answers, and many states within 1 cm of contact. */
    assert_true(hits > 10000 && misses > 10000);
    assert_true(near > 1000);
    mpb_world_close(w);
}

static void test_empty_scene_and_bad_q(void **state)
{
    (void)state;
    mpb_world *w = open_ok(ARM2, "# nothing here\n\n");
    const double q0[] = { 0, 0 };
    assert_true(isinf(mpb_world_clearance(w, q0)) && mpb_world_clearance(w, q0) > 0);
    assert_int_equal(mpb_world_in_collision(w, q0), 0);
    /* Non-finite q: in collision, clearance NaN. */
    const double qn[] = { NAN, 0 }, qi[] = { 0, INFINITY };
    assert_int_equal(mpb_world_in_collision(w, qn), 1);
    assert_int_equal(mpb_world_in_collision(w, qi), 1);
    assert_true(isnan(mpb_world_clearance(w, qn)));
    assert_int_not_equal(mpb_world_in_collision(w, NULL), 0);
    mpb_world_close(w);
}

static void test_text_forms(void **state)
{
    (void)state;
    /* CRLF line ends, tabs, comments after items, no final newline. */
    mpb_world *w = open_ok("link_radius\t0.1\r\njoint a -1 1 1 # c\r\njoint b -1 1 1",
                           "circle 3 0 0.5\r\n# box 0 0 9 9\r\n");
    const double q0[] = { 0, 0 };
    assert_int_equal(mpb_world_num_joints(w), 2);
    assert_near(mpb_world_clearance(w, q0), 0.4, EPS);
    mpb_world_close(w);
}

static void test_robot_parse_errors(void **state)
{
    (void)state;
    expect_parse_error("base 0 0\nlink_radius 0.1\njoint a -1 1\n", "",
                       "robot line 3:", "joint needs <name> <lo> <hi> <length>");
    /* Comments and blank lines still count as lines. */
    expect_parse_error("# c\n\nlink_radius 0.1\n  joint a 1 -1 1 # lo > hi\n", "",
                       "robot line 4:", "lo > hi");
    expect_parse_error("link_radius 0.1\njoint a -1 x 1\n", "",
                       "robot line 2:", "'x' is not a number");
    expect_parse_error("link_radius 0.1\njoint a -1 1 1.5m\n", "",
                       "robot line 2:", "'1.5m' is not a number");
    expect_parse_error("link_radius nan\njoint a -1 1 1\n", "",
                       "robot line 1:", "not a number");
    expect_parse_error("links 3\n", "", "robot line 1:", "unknown item 'links'");
    expect_parse_error("link_radius 0.1\njoint a -1 1 0\n", "",
                       "robot line 2:", "length must be > 0");
    /* Near 1e308 the distances overflowed to NaN: bounded like FCL's. */
    expect_parse_error("link_radius 0.1\njoint a -1 1 1e308\n", "",
                       "robot line 2:", "1e308 is beyond 100000 (m or rad)");
    expect_parse_error("base -2e5 0\nlink_radius 0.1\njoint a -1 1 1\n", "",
                       "robot line 1:", "-2e5 is beyond 100000");
    expect_parse_error("link_radius 0.1\njoint a -1e300 1e300 1\n", "",
                       "robot line 2:", "-1e300 is beyond");
    expect_parse_error("link_radius 0.1\njoint a -1 1 1\njoint a -1 1 1\n", "",
                       "robot line 3:", "declared twice");
    expect_parse_error("link_radius -0.1\njoint a -1 1 1\n", "",
                       "robot line 1:", ">= 0");
    expect_parse_error("link_radius 0.1\nlink_radius 0.2\n", "",
                       "robot line 2:", "second link_radius");
    expect_parse_error("base 0\nlink_radius 0.1\n", "",
                       "robot line 1:", "base needs <x> <y>");
    expect_parse_error("joint a -1 1 1\n", "", "robot:", "link_radius");
    expect_parse_error("link_radius 0.1\n", "", "robot:", "no joints");
    expect_parse_error("", "", "robot:", NULL);
}

static void test_scene_parse_errors(void **state)
{
    (void)state;
    expect_parse_error(ARM2, "circle 0 0 1\ncircle 1 2\n",
                       "scene line 2:", "circle needs <cx> <cy> <r>");
    expect_parse_error(ARM2, "box 0 0 -1 1", "scene line 1:", "half sizes");
    expect_parse_error(ARM2, "box 0 0 1", "scene line 1:", "box needs");
    expect_parse_error(ARM2, "circle 0 0 -1", "scene line 1:", "radius");
    expect_parse_error(ARM2, "circle 0 0 1\ncircle 1e308 1e308 1e308",
                       "scene line 2:", "1e308 is beyond 100000 m");
    expect_parse_error(ARM2, "box 0 0 1 1e6", "scene line 1:",
                       "1e6 is beyond 100000");
    expect_parse_error(ARM2, "\n\n\nsphere 0 0 1", "scene line 4:",
                       "unknown item 'sphere'");
}

static void test_formats(void **state)
{
    (void)state;
    mpb_world *w = (mpb_world *)1;
    char err[200];
    assert_int_equal(mpb_world_open("sdf", "<robot/>", "moveit-scene", "", &w,
                                    err, sizeof err), MPB_EUNSUPPORTED);
    assert_null(w);
    assert_non_null(strstr(err, "sdf"));
    /* A line break in what the message quotes stays off its own line: the
     * message is one line, as the header promises. */
    assert_int_equal(mpb_world_open("s\ndf", "<robot/>", "moveit-scene", "",
                                    &w, err, sizeof err), MPB_EUNSUPPORTED);
    assert_non_null(strstr(err, "s df"));
    assert_null(strchr(err, '\n'));
    /* A urdf world needs its planning group's joints. */
    assert_int_equal(mpb_world_open("urdf", "<robot/>", "moveit-scene", "", &w,
                                    err, sizeof err), MPB_EINVAL);
    assert_null(w);
    assert_non_null(strstr(err, "joints"));
    /* A planar group must be the arm's joints in order. */
    static const char *const wrong[] = {"j2", "j1"};
    assert_int_equal(mpb_world_open_group("planar", ARM2, "planar", "", wrong,
                                          2, &w, err, sizeof err), MPB_EPARSE);
    assert_non_null(strstr(err, "in order"));
    assert_int_equal(mpb_world_open("planar", ARM2, "moveit-scene", "", &w,
                                    err, sizeof err), MPB_EUNSUPPORTED);
    assert_non_null(strstr(err, "moveit-scene"));
    assert_int_equal(mpb_world_open("planar", NULL, "planar", "", &w,
                                    err, sizeof err), MPB_EINVAL);
    /* No error buffer, or a tiny one, is fine. */
    assert_int_equal(mpb_world_open("planar", "joint", "planar", "", &w,
                                    NULL, 0), MPB_EPARSE);
    char tiny[8];
    assert_int_equal(mpb_world_open("planar", "joint", "planar", "", &w,
                                    tiny, sizeof tiny), MPB_EPARSE);
    assert_int_equal(strlen(tiny), sizeof tiny - 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_joints),
        cmocka_unit_test(test_forward_kinematics),
        cmocka_unit_test(test_clearance_circles),
        cmocka_unit_test(test_touching_counts),
        cmocka_unit_test(test_clearance_boxes),
        cmocka_unit_test(test_collision_agrees_with_clearance),
        cmocka_unit_test(test_empty_scene_and_bad_q),
        cmocka_unit_test(test_text_forms),
        cmocka_unit_test(test_robot_parse_errors),
        cmocka_unit_test(test_scene_parse_errors),
        cmocka_unit_test(test_formats),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
