/*
 * test_world_urdf.c - the "urdf" + "moveit-scene" world: the PR2 right arm
 * (tests/support/data/pr2_right_arm.urdf, kinematics of shared/DESIGN.md)
 * beside a box, collision, clearance, pose-region goals, and verification of
 * a planted invalid trajectory.
 *
 * Geometry at q = 0 (torso at 0): the shoulder pan axis is at x = -0.05,
 * y = -0.188, z = 0.7397; the arm points along +x, elbow at x = 0.45,
 * wrist at x = 0.771. A 0.1 m box centred at (0.6, -0.188, 0.74) sits on
 * the forearm. With the shoulder panned to -1.2 rad or +0.5 rad the arm
 * points away from it (its line passes > 0.25 m from the box), but the
 * straight joint-space segment between the two passes pan = 0.
 *
 * The robot text is the URDF followed by its SRDF (pr2_right_arm.srdf),
 * which allows the pairs the test robot's crude shapes make touch.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "mpbench/robot.h"
#include "test_files.h"

static const char *const joints[] = {
    "r_shoulder_pan_joint", "r_shoulder_lift_joint", "r_upper_arm_roll_joint",
    "r_elbow_flex_joint", "r_forearm_roll_joint", "r_wrist_flex_joint",
    "r_wrist_roll_joint"};

static const char box_scene[] =
    "box beside the arm\n"
    "* box\n"
    "0.6 -0.188 0.74\n"
    "0 0 0 1\n"
    "1\n"
    "box\n"
    "0.1 0.1 0.1\n"
    "0 0 0\n"
    "0 0 0 1\n"
    "0 0 0 0\n"
    "0\n"
    ".\n";

static char *urdf;

static int setup(void **state)
{
    (void)state;
    urdf = test_read_robot(MPB_TEST_DATA "/pr2_right_arm.urdf",
                           MPB_TEST_DATA "/pr2_right_arm.srdf");
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    free(urdf);
    return 0;
}

static mpb_world *open_world(const char *scene)
{
    mpb_world *w = NULL;
    char err[256];
    int rc = mpb_world_open_group("urdf", urdf, "moveit-scene", scene, joints,
                                  7, &w, err, sizeof err);
    if (rc != MPB_OK)
        fail_msg("open: %s", err);
    return w;
}

static void joints_and_limits_come_from_the_urdf(void **state)
{
    (void)state;
    mpb_world *w = open_world(box_scene);
    double lo, hi;
    assert_int_equal(mpb_world_num_joints(w), 7);
    assert_string_equal(mpb_world_joint_name(w, 0), "r_shoulder_pan_joint");
    mpb_world_joint_limits(w, 0, &lo, &hi);
    assert_float_equal(lo, -2.2854, 1e-9);
    assert_float_equal(hi, 0.7146, 1e-9);
    assert_true(mpb_world_joint_is_continuous(w, 4));   /* forearm roll */
    assert_false(mpb_world_joint_is_continuous(w, 3));
    mpb_world_close(w);
}

static void the_box_collides_with_the_forearm_only_at_pan_zero(void **state)
{
    (void)state;
    mpb_world *w = open_world(box_scene);
    double q0[7] = {0}, qa[7] = {-1.2}, qb[7] = {0.5};
    assert_int_equal(mpb_world_in_collision(w, q0), 1);
    assert_int_equal(mpb_world_in_collision(w, qa), 0);
    assert_int_equal(mpb_world_in_collision(w, qb), 0);
    /* Clearance: 0 when touching, positive and finite when free. */
    assert_true(mpb_world_clearance(w, q0) <= 0.0);
    double ca = mpb_world_clearance(w, qa);
    assert_true(ca > 0.1 && ca < 1.0);
    mpb_world_close(w);

    /* Without the box nothing collides: no self-collision at rest. */
    w = open_world("empty\n.\n");
    assert_int_equal(mpb_world_in_collision(w, q0), 0);
    assert_true(isinf(mpb_world_clearance(w, q0)));
    mpb_world_close(w);
}

static void a_segment_through_the_box_is_rejected_at_that_segment(void **state)
{
    (void)state;
    mpb_world *w = open_world(box_scene);
    double path[3 * 7] = {0};
    path[0] = -1.2;          /* waypoint 0: pan -1.2 */
    path[7] = -1.2;          /* waypoint 1: pan -1.2, elbow -0.3 */
    path[10] = -0.3;
    path[14] = 0.5;          /* waypoint 2: pan 0.5, elbow 0: the segment
                                crosses pan 0 with the elbow at about -0.12,
                                the forearm still through the box */
    mpb_goal goal = {.kind = MPB_GOAL_JOINTS, .joints = path + 14,
                     .joint_tolerance = 0.01};
    mpb_verdict v;
    assert_int_equal(mpb_world_in_collision(w, path + 7), 0);
    assert_int_equal(mpb_verify_path(w, path, 0.01, &goal, path, 3, 7, 0.01, &v),
                     MPB_OK);
    assert_int_equal(v.code, MPB_VERDICT_COLLISION);
    assert_int_equal(v.segment, 1);          /* 0 is free: pan stays at -1.2 */
    mpb_world_close(w);
}

static void pose_region_goals_are_checked(void **state)
{
    (void)state;
    mpb_world *w = open_world(box_scene);
    mpb_robot *r;
    char err[200];
    assert_int_equal(mpb_robot_open_urdf_joints(urdf, joints, 7, &r, err, sizeof err),
                     MPB_OK);
    double qb[7] = {0.5, 0.3, 0, -0.5, 0, -0.4, 0};
    mpb_pose tool;
    int link = mpb_robot_link_index(r, "r_gripper_tool_frame");
    assert_true(link >= 0);
    assert_int_equal(mpb_robot_link_pose(r, qb, link, &tool), MPB_OK);
    double rpy[3];
    mpb_pose_get_rpy(&tool, rpy);

    /* The paper's goal: a 2 cm cube, roll/pitch/yaw within 0.05 rad. */
    mpb_goal g = {.kind = MPB_GOAL_POSE_REGION, .link = "r_gripper_tool_frame"};
    for (int i = 0; i < 3; i++) {
        g.position[i] = tool.t[i];
        g.position_tolerance[i] = 0.01;
        g.orientation_rpy[i] = rpy[i];
        g.orientation_tolerance[i] = 0.05;
    }
    char why[160];
    assert_int_equal(mpb_world_goal_contains(w, &g, qb, why, sizeof why), 1);
    double qa[7] = {-1.2};
    assert_int_equal(mpb_world_goal_contains(w, &g, qa, why, sizeof why), 0);
    assert_non_null(strstr(why, "outside the goal box"));

    /* A path ending at qb reaches the goal; one ending at qa does not.
     * (Both start at pan 0.7, on qb's side of the box.) */
    double path[2 * 7] = {0.7, 0.3, 0, -0.5, 0, -0.4, 0};
    memcpy(path + 7, qb, sizeof qb);
    mpb_verdict v;
    mpb_verify_path(w, path, 0.01, &g, path, 2, 7, 0.01, &v);
    assert_int_equal(v.code, MPB_VERDICT_VALID);
    double qc[7] = {0.7, 0.3, 0, -0.5, 0, -0.4, 0.3};  /* wrist rolled */
    memcpy(path + 7, qc, sizeof qc);
    mpb_verify_path(w, path, 0.01, &g, path, 2, 7, 0.01, &v);
    assert_int_equal(v.code, MPB_VERDICT_GOAL);
    assert_int_equal(v.segment, 1);

    g.link = "no_such_link";
    assert_true(mpb_world_goal_contains(w, &g, qb, why, sizeof why) < 0);
    assert_non_null(strstr(why, "no_such_link"));
    mpb_robot_close(r);
    mpb_world_close(w);
}

static void bad_input_gets_one_line_naming_where(void **state)
{
    (void)state;
    mpb_world *w;
    char err[256];
    assert_int_equal(mpb_world_open_group("urdf", "<robot name='x'><link",
                                          "moveit-scene", "", joints, 7, &w,
                                          err, sizeof err), MPB_EPARSE);
    assert_null(w);
    assert_non_null(strstr(err, "urdf"));
    assert_null(strchr(err, '\n'));
    /* XML errors name their line. */
    assert_int_equal(mpb_world_open_group("urdf", "<robot name='x'>\n"
                                          "<link name='a'>\n<link name='b'/>\n"
                                          "</robot>\n", "moveit-scene", "",
                                          joints, 7, &w, err, sizeof err),
                     MPB_EPARSE);
    assert_non_null(strstr(err, "urdf: line "));
    assert_int_equal(mpb_world_open_group("urdf", urdf, "moveit-scene",
                                          "s\n* box\n0 0 0\n0 0 0 1\n1\nbox\n"
                                          "0.1 oops 0.1\n", joints, 7, &w,
                                          err, sizeof err), MPB_EPARSE);
    assert_non_null(strstr(err, "line 7"));
    assert_null(strchr(err, '\n'));
    assert_int_not_equal(mpb_world_open_group("urdf", urdf, "moveit-scene", "",
                                              NULL, 0, &w, err, sizeof err),
                         MPB_OK);
    assert_non_null(strstr(err, "joints"));
    const char *bad[] = {"r_shoulder_pan_joint", "nope"};
    assert_int_not_equal(mpb_world_open_group("urdf", urdf, "moveit-scene", "",
                                              bad, 2, &w, err, sizeof err),
                         MPB_OK);
    assert_non_null(strstr(err, "nope"));
}

/* An attach line names a link the arm lacks: the error is on that line,
 * not on the object's, and a misspelt touch link is one too. */
static void a_bad_attachment_is_named_on_its_line(void **state)
{
    (void)state;
    static const struct {
        const char *attach, *want;
    } cases[] = {
        {"attach box r_hand_link\n",
         "scene line 15: object 'box' is attached to 'r_hand_link', which is "
         "not a link of the robot"},
        {"attach box r_wrist_roll_link r_wrist_flex_link r_fingr\n",
         "scene line 15: object 'box' may touch 'r_fingr', which is not a "
         "link of the robot"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char scene[512], err[256];
        mpb_world *w;
        snprintf(scene, sizeof scene, "%s# carried\n\n%s", box_scene,
                 cases[i].attach);
        assert_int_equal(mpb_world_open_group("urdf", urdf, "moveit-scene",
                                              scene, joints, 7, &w, err,
                                              sizeof err), MPB_EPARSE);
        assert_null(w);
        assert_string_equal(err, cases[i].want);
    }
}

/* Open the mesh arm with the two search variables as given (NULL:
 * unset) and the URDF's folder (NULL: not given); the return code, the
 * message in err. */
static int open_mesh_arm_in(const char *mesh_path, const char *ros_path,
                            const char *robot_dir, char *err, size_t errlen)
{
    static const char *const j[] = {"j"};
    char *text = test_read_file(MPB_TEST_DATA "/meshes/mesh_arm.urdf");
    if (mesh_path)
        setenv("MPB_MESH_PATH", mesh_path, 1);
    else
        unsetenv("MPB_MESH_PATH");
    if (ros_path)
        setenv("ROS_PACKAGE_PATH", ros_path, 1);
    else
        unsetenv("ROS_PACKAGE_PATH");
    mpb_world *w = NULL;
    int rc = mpb_world_open_group_in("urdf", text, robot_dir, "moveit-scene",
                                     "(empty)\n.\n", j, 1, &w, err, errlen);
    if (rc == MPB_OK) {
        /* The cube is where the URDF puts it: 0.5 m out along the arm. */
        double q[1] = {0};
        assert_int_equal(mpb_world_in_collision(w, q), 0);
    }
    mpb_world_close(w);
    free(text);
    unsetenv("MPB_MESH_PATH");
    unsetenv("ROS_PACKAGE_PATH");
    return rc;
}

static int open_mesh_arm(const char *mesh_path, const char *ros_path,
                         char *err, size_t errlen)
{
    return open_mesh_arm_in(mesh_path, ros_path, NULL, err, errlen);
}

static void meshes_are_found_through_both_variables(void **state)
{
    (void)state;
    char err[1024];
    const char *root = MPB_TEST_DATA "/meshes";
    const char *pkg = MPB_TEST_DATA "/meshes/mesh_pkg";
    /* A folder that holds the package, or that is the package (as ROS). */
    assert_int_equal(open_mesh_arm(root, NULL, err, sizeof err), MPB_OK);
    assert_int_equal(open_mesh_arm(pkg, NULL, err, sizeof err), MPB_OK);
    assert_int_equal(open_mesh_arm(NULL, root, err, sizeof err), MPB_OK);
    assert_int_equal(open_mesh_arm("/nonexistent", pkg, err, sizeof err), MPB_OK);

    /* Neither: the message names both variables. */
    assert_int_equal(open_mesh_arm(NULL, NULL, err, sizeof err), MPB_ENOTFOUND);
    assert_non_null(strstr(err, "mesh 'package://mesh_pkg/meshes/cube.stl': "
                                "not found"));
    assert_non_null(strstr(err, "looked in MPB_MESH_PATH (not set) and "
                                "ROS_PACKAGE_PATH (not set)"));
    assert_int_equal(open_mesh_arm("/a:/b", "", err, sizeof err), MPB_ENOTFOUND);
    assert_non_null(strstr(err, "looked in MPB_MESH_PATH (/a, /b) and "
                                "ROS_PACKAGE_PATH (empty)"));

    /* No limit on the folders: the package in the 40th is found, and 40
     * folders tried are said as such. */
    char many[4096] = "";
    for (int i = 1; i < 40; i++)
        snprintf(many + strlen(many), sizeof many - strlen(many), "/no/%d:", i);
    assert_int_equal(open_mesh_arm(many, NULL, err, sizeof err), MPB_ENOTFOUND);
    assert_non_null(strstr(err, "MPB_MESH_PATH (/no/1, /no/2, /no/3 and 36 "
                                "more: 39 folders)"));
    snprintf(many + strlen(many), sizeof many - strlen(many), "%s", root);
    assert_int_equal(open_mesh_arm(many, NULL, err, sizeof err), MPB_OK);

    /* Last, the URDF's folder, when the caller knows it (mpbenchd does):
     * it holds mesh_pkg here. */
    assert_int_equal(open_mesh_arm_in(NULL, NULL, root, err, sizeof err), MPB_OK);
    assert_int_equal(open_mesh_arm_in("/a", NULL, MPB_TEST_DATA, err, sizeof err),
                     MPB_ENOTFOUND);
    assert_non_null(strstr(err, "looked in MPB_MESH_PATH (/a) and "
                                "ROS_PACKAGE_PATH (not set) and the URDF's "
                                "folder (" MPB_TEST_DATA ")"));
}

/* The torso is outside the group: held at 0 it puts the forearm in the
 * box; held higher, the arm clears it. Bad joints and values are named. */
static void joints_outside_the_group_hold_values(void **state)
{
    (void)state;
    mpb_world *w = open_world(box_scene);
    double q[7] = {0}, v = -1, lo, hi;
    char err[256];
    const char *torso[] = {"torso_lift_joint"};
    assert_int_equal(mpb_world_held(w, "torso_lift_joint", &v, &lo, &hi),
                     MPB_OK);
    assert_true(v == 0.0 && lo == 0.0 && fabs(hi - 0.33) < 1e-12);
    assert_int_equal(mpb_world_in_collision(w, q), 1);
    double up = 0.3;
    assert_int_equal(mpb_world_hold(w, torso, &up, 1, err, sizeof err), MPB_OK);
    assert_int_equal(mpb_world_in_collision(w, q), 0);
    assert_int_equal(mpb_world_held(w, "torso_lift_joint", &v, NULL, NULL),
                     MPB_OK);
    assert_true(v == 0.3);

    double bad = 0.5;
    assert_int_equal(mpb_world_hold(w, torso, &bad, 1, err, sizeof err),
                     MPB_EINVAL);
    assert_non_null(strstr(err, "outside its limits [0, 0.33]"));
    const char *unknown[] = {"torso_joint"};
    assert_int_equal(mpb_world_hold(w, unknown, &up, 1, err, sizeof err),
                     MPB_ENOTFOUND);
    assert_non_null(strstr(err, "'torso_joint' is not a joint of the robot"));
    const char *group[] = {"r_elbow_flex_joint"};
    assert_int_equal(mpb_world_hold(w, group, &up, 1, err, sizeof err),
                     MPB_EINVAL);
    assert_non_null(strstr(err, "in the planning group"));
    const char *fixed[] = {"r_upper_arm_joint"};
    assert_int_equal(mpb_world_hold(w, fixed, &up, 1, err, sizeof err),
                     MPB_EINVAL);
    assert_non_null(strstr(err, "cannot hold a value"));
    /* A refused value leaves the last one held. */
    assert_int_equal(mpb_world_in_collision(w, q), 0);
    assert_int_equal(mpb_world_hold(w, NULL, NULL, 0, err, sizeof err), MPB_OK);
    mpb_world_close(w);

    mpb_world *p = NULL;
    assert_int_equal(mpb_world_open("planar", "link_radius 0.1\njoint a -1 1 1\n",
                                    "planar", "", &p, err, sizeof err), MPB_OK);
    assert_int_equal(mpb_world_hold(p, torso, &up, 1, err, sizeof err),
                     MPB_EUNSUPPORTED);
    mpb_world_close(p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(meshes_are_found_through_both_variables),
        cmocka_unit_test(joints_and_limits_come_from_the_urdf),
        cmocka_unit_test(the_box_collides_with_the_forearm_only_at_pan_zero),
        cmocka_unit_test(a_segment_through_the_box_is_rejected_at_that_segment),
        cmocka_unit_test(pose_region_goals_are_checked),
        cmocka_unit_test(bad_input_gets_one_line_naming_where),
        cmocka_unit_test(a_bad_attachment_is_named_on_its_line),
        cmocka_unit_test(joints_outside_the_group_hold_values),
    };
    return cmocka_run_group_tests_name("world_urdf", tests, setup, teardown);
}
