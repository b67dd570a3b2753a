/*
 * test_certify_worlds.h - the worlds the tests of certified verification
 * share (test_certify.c, test_locate.c): a planar arm of zero-radius
 * links (1.2 m when straight) whose shoulder sweeps thin walls between
 * the sampled check's points, and the PR2's right arm under a thin plate
 * over its forearm (test_certify.c's top comment gives the geometry).
 * Include it after <cmocka.h> and test_files.h.
 */
#ifndef MPB_TEST_CERTIFY_WORLDS_H
#define MPB_TEST_CERTIFY_WORLDS_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"

/* The top of the PR2's forearm at q = 0 (m): its axis's z plus its
 * radius. */
#define TEST_PR2_FOREARM_TOP (0.739675 + 0.05)

/* The planar arm (scenes/planar/arm3.robot, links of radius 0) in the
 * planar scene text; the test fails if it will not open. */
static inline mpb_world *test_planar_arm(const char *scene)
{
    static const char arm[] =
        "base 0 0\n"
        "link_radius 0\n"
        "joint shoulder -3.14159 3.14159 0.5\n"
        "joint elbow    -2.8 2.8 0.4\n"
        "joint wrist    -2.8 2.8 0.3\n";
    mpb_world *w = NULL;
    char err[200];
    if (mpb_world_open("planar", arm, "planar", scene, &w, err, sizeof err) != MPB_OK)
        fail_msg("open: %s", err);
    return w;
}

/* The PR2's right arm (its seven joints) under a plate 0.04 x 0.0001 x
 * 0.05 across y over the forearm, the plate's lower edge at z. */
static inline mpb_world *test_pr2_with_plate(double z)
{
    static const char *const joints[] = {
        "r_shoulder_pan_joint", "r_shoulder_lift_joint", "r_upper_arm_roll_joint",
        "r_elbow_flex_joint", "r_forearm_roll_joint", "r_wrist_flex_joint",
        "r_wrist_roll_joint"};
    char *urdf = test_read_robot(MPB_TEST_DATA "/pr2_right_arm.urdf",
                                 MPB_TEST_DATA "/pr2_right_arm.srdf");
    char scene[400];
    snprintf(scene, sizeof scene,
             "plate\n* plate\n0.6 -0.188 %.9f\n0 0 0 1\n1\nbox\n"
             "0.04 0.0001 0.05\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n.\n", z + 0.025);
    mpb_world *w = NULL;
    char err[256];
    int rc = mpb_world_open_group("urdf", urdf, "moveit-scene", scene, joints, 7,
                                  &w, err, sizeof err);
    free(urdf);
    if (rc != MPB_OK)
        fail_msg("open: %s", err);
    return w;
}

/* The s of "at s=..." in a collision verdict's detail. */
static inline double test_verdict_s(const mpb_verdict *v)
{
    const char *p = strstr(v->detail, "at s=");
    assert_non_null(p);
    return strtod(p + 5, NULL);
}

#endif /* MPB_TEST_CERTIFY_WORLDS_H */
