/*
 * test_ee_sweep.c - the end effector's path length (mpb_ee_path_length())
 * from the world's sweep of each segment (forward kinematics of the end
 * effector alone, its joints' rotations carried from point to point)
 * equals the sum of the chords between mpb_world_ee_position() at the
 * same points, to 1e-12 m: on the PR2 arm (continuous joints, axes along
 * x, y, z), on a chain with an oblique axis, a prismatic joint, a mimic
 * joint and rotated origins, and on the Panda where its data is fetched.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "test_files.h"
#include "test_panda.h"

/* An oblique revolute axis, a prismatic joint, a revolute joint that
 * mimics the first (2 x + 0.1), origins turned by rpy, a fixed tip. */
static const char CHAIN[] =
    "<robot name='chain'>"
    "<link name='base'/><link name='a'/><link name='b'/><link name='c'/>"
    "<link name='tip'/>"
    "<joint name='j1' type='revolute'><parent link='base'/><child link='a'/>"
    "<origin xyz='0.1 0 0.3' rpy='0.2 -0.1 0.3'/><axis xyz='0.6 0 0.8'/>"
    "<limit lower='-3' upper='3' effort='1' velocity='1'/></joint>"
    "<joint name='j2' type='prismatic'><parent link='a'/><child link='b'/>"
    "<origin xyz='0 0.2 0.1' rpy='0 0.4 0'/><axis xyz='0 1 0'/>"
    "<limit lower='-1' upper='1' effort='1' velocity='1'/></joint>"
    "<joint name='j3' type='revolute'><parent link='b'/><child link='c'/>"
    "<origin xyz='0.3 0 0' rpy='0.1 0 -0.2'/><axis xyz='0 0 -1'/>"
    "<mimic joint='j1' multiplier='2' offset='0.1'/>"
    "<limit lower='-7' upper='7' effort='1' velocity='1'/></joint>"
    "<joint name='t' type='fixed'><parent link='c'/><child link='tip'/>"
    "<origin xyz='0.25 0.05 -0.1' rpy='0.3 0.2 0.1'/></joint>"
    "</robot>";

static uint64_t rng = 99;

static double uniform(double lo, double hi)
{
    rng = rng * 6364136223846793005ull + 1442695040888963407ull;
    return lo + (hi - lo) * (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

/* The end effector's path length point by point, as it was computed
 * before the sweep: a chord between mpb_world_ee_position() at every
 * a + (k / steps) d. */
static double chords(mpb_world *w, const double *wp, int n, int nj,
                     double resolution)
{
    const unsigned char *wraps = mpb_world_joint_wraps(w);
    double q[64], prev[3], cur[3], total = 0.0;
    assert_int_equal(mpb_world_ee_position(w, wp, prev), MPB_OK);
    for (int i = 0; i + 1 < n; i++) {
        const double *a = wp + (size_t)i * nj, *b = a + nj;
        double d[64], sq = 0.0;
        for (int j = 0; j < nj; j++) {
            d[j] = mpb_joint_delta(a[j], b[j], wraps && wraps[j]);
            sq += d[j] * d[j];
        }
        int steps = (int)ceil(sqrt(sq) / resolution);
        if (steps < 1)
            steps = 1;
        for (int k = 1; k <= steps; k++) {
            double s = (double)k / steps;
            for (int j = 0; j < nj; j++)
                q[j] = a[j] + s * d[j];
            assert_int_equal(mpb_world_ee_position(w, q, cur), MPB_OK);
            total += sqrt((cur[0] - prev[0]) * (cur[0] - prev[0]) +
                          (cur[1] - prev[1]) * (cur[1] - prev[1]) +
                          (cur[2] - prev[2]) * (cur[2] - prev[2]));
            memcpy(prev, cur, sizeof prev);
        }
    }
    return total;
}

/* Random paths of n waypoints inside [lo, hi] (wider for continuous
 * joints, so they wrap), long segments among them (hundreds of steps,
 * past the recurrence's re-seeding). */
static void check_paths(mpb_world *w, int paths, int n)
{
    int nj = mpb_world_num_joints(w);
    const unsigned char *wraps = mpb_world_joint_wraps(w);
    double *wp = calloc((size_t)n * nj, sizeof *wp);
    assert_non_null(wp);
    for (int p = 0; p < paths; p++) {
        for (int i = 0; i < n; i++)
            for (int j = 0; j < nj; j++) {
                double lo, hi;
                mpb_world_joint_limits(w, j, &lo, &hi);
                if (wraps && wraps[j]) {
                    lo = -4.0;
                    hi = 4.0;
                }
                wp[(size_t)i * nj + j] = uniform(lo, hi);
            }
        for (int r = 0; r < 3; r++) {
            double res = r == 0 ? 0.01 : r == 1 ? 0.003 : 0.5;
            double fast = mpb_ee_path_length(w, wp, n, nj, res);
            double slow = chords(w, wp, n, nj, res);
            assert_true(isfinite(fast));
            assert_true(fabs(fast - slow) <= 1e-12 * fmax(1.0, slow));
            assert_true(slow > 0.0);
        }
    }
    free(wp);
}

static void test_pr2_arm(void **state)
{
    (void)state;
    static const char *const joints[] = {
        "r_shoulder_pan_joint", "r_shoulder_lift_joint",
        "r_upper_arm_roll_joint", "r_elbow_flex_joint",
        "r_forearm_roll_joint", "r_wrist_flex_joint", "r_wrist_roll_joint"};
    char *urdf = test_read_robot(MPB_TEST_DATA "/pr2_right_arm.urdf",
                                 MPB_TEST_DATA "/pr2_right_arm.srdf");
    mpb_world *w = NULL;
    char err[256];
    int rc = mpb_world_open_group("urdf", urdf, "moveit-scene", "empty\n.\n",
                                  joints, 7, &w, err, sizeof err);
    free(urdf);
    if (rc != MPB_OK)
        fail_msg("open: %s", err);
    check_paths(w, 20, 6);
    mpb_world_close(w);
}

static void test_oblique_prismatic_mimic(void **state)
{
    (void)state;
    static const char *const joints[] = {"j1", "j2"};
    mpb_world *w = NULL;
    char err[256];
    int rc = mpb_world_open_group("urdf", CHAIN, "moveit-scene", "empty\n.\n",
                                  joints, 2, &w, err, sizeof err);
    if (rc != MPB_OK)
        fail_msg("open: %s", err);
    check_paths(w, 20, 5);
    mpb_world_close(w);
}

static void test_panda(void **state)
{
    (void)state;
    mpb_world *w = test_open_panda("empty\n.\n");
    if (w == NULL)
        skip();
    check_paths(w, 10, 8);
    mpb_world_close(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pr2_arm),
        cmocka_unit_test(test_oblique_prismatic_mimic),
        cmocka_unit_test(test_panda),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
