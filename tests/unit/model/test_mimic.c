/*
 * test_mimic.c - mimic joints (URDF <mimic joint= multiplier= offset=>,
 * robot.h): a mimic joint follows its leader in forward kinematics,
 * whether the leader is planned or holds a value, through a mimic of a
 * mimic too (tests/support/data/mimic_gripper.urdf, poses worked by hand),
 * and the world's collision checks with it; a mimic joint is never in the
 * group; the Panda's second finger follows
 * the first (the Panda of tools/robot_data.sh, fetched if missing).
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
#include "test_files.h"
#include "core/mathconst.h"

#define assert_near(a, b, eps)                                              \
    do {                                                                    \
        double a_ = (a), b_ = (b);                                          \
        if (!(fabs(a_ - b_) <= (eps)))                                      \
            fail_msg("%s = %.17g, expected %.17g (line %d)", #a, a_, b_,    \
                     __LINE__);                                             \
    } while (0)

static mpb_robot *load_mimic(const char *const *joints, int n)
{
    char *urdf = test_read_file(MPB_TEST_DATA "/mimic_gripper.urdf"), err[512];
    mpb_robot *r = NULL;
    int rc = mpb_robot_open_urdf_joints(urdf, joints, n, &r, err, sizeof err);
    free(urdf);
    if (rc != MPB_OK)
        fail_msg("%s", err);
    return r;
}

static const double *link_t(const mpb_robot *r, const mpb_pose *P,
                            const char *name)
{
    int l = mpb_robot_link_index(r, name);
    assert_true(l >= 0);
    return P[l].t;
}

static void test_mimic_fk(void **state)
{
    (void)state;
    /* The leader planned: finger_r at y = -0.02 + (0.01 - q1), and tip_r
     * 0.06 + 2 (0.01 - q1) further along x. */
    const char *const both[] = {"shoulder", "finger_l_joint"};
    mpb_robot *r = load_mimic(both, 2);
    mpb_pose P[6];
    double q[2] = {0, 0.03};
    int fr = mpb_robot_link_index(r, "finger_r");
    assert_true(mpb_robot_get_link(r, fr)->moves);
    assert_int_equal(mpb_robot_get_link(r, fr)->mimic_link,
                     mpb_robot_link_index(r, "finger_l"));
    assert_near(mpb_robot_get_link(r, fr)->mimic_multiplier, -1, 0);
    assert_near(mpb_robot_get_link(r, fr)->mimic_offset, 0.01, 0);
    assert_int_equal(mpb_robot_fk(r, q, P), MPB_OK);
    assert_near(link_t(r, P, "finger_l")[1], 0.05, 1e-12);
    assert_near(link_t(r, P, "finger_r")[0], 0.51, 1e-12);
    assert_near(link_t(r, P, "finger_r")[1], -0.04, 1e-12);
    assert_near(link_t(r, P, "tip_r")[0], 0.53, 1e-12);
    assert_near(link_t(r, P, "tip_r")[2], 0.1, 1e-12);
    q[1] = 0.0;
    assert_int_equal(mpb_robot_fk(r, q, P), MPB_OK);
    assert_near(link_t(r, P, "finger_r")[1], -0.01, 1e-12);
    assert_near(link_t(r, P, "tip_r")[0], 0.59, 1e-12);
    /* The shoulder turned a quarter: (x, y) -> (-y, x). */
    q[0] = M_PI / 2;
    q[1] = 0.03;
    mpb_pose one;
    assert_int_equal(mpb_robot_link_pose(r, q, fr, &one), MPB_OK);
    assert_near(one.t[0], 0.04, 1e-12);
    assert_near(one.t[1], 0.51, 1e-12);
    /* fk_moving writes the mimic links too. */
    memset(P, 0, sizeof P);
    assert_int_equal(mpb_robot_fk_moving(r, q, P), MPB_OK);
    assert_near(P[fr].t[1], 0.51, 1e-12);
    mpb_robot_close(r);

    /* The leader held: the mimic follows its value, and set_passive. */
    const char *const arm[] = {"shoulder"};
    r = load_mimic(arm, 1);
    fr = mpb_robot_link_index(r, "finger_r");
    double q0 = 0;
    assert_int_equal(mpb_robot_fk(r, &q0, P), MPB_OK);
    assert_near(link_t(r, P, "finger_r")[1], -0.01, 1e-12);  /* leader 0 */
    assert_int_equal(mpb_robot_set_passive(r, "finger_l_joint", 0.03), MPB_OK);
    assert_int_equal(mpb_robot_fk(r, &q0, P), MPB_OK);
    assert_near(link_t(r, P, "finger_l")[1], 0.05, 1e-12);
    assert_near(link_t(r, P, "finger_r")[1], -0.04, 1e-12);
    assert_near(link_t(r, P, "tip_r")[0], 0.53, 1e-12);
    /* A mimic joint is set through its leader only. */
    assert_int_equal(mpb_robot_set_passive(r, "finger_r_joint", 0.0), MPB_EINVAL);
    mpb_robot_close(r);
}

/* The world moves the mimic's link too: a block beside the right finger
 * is hit when the left finger opens. */
static void test_mimic_world(void **state)
{
    (void)state;
    char *urdf = test_read_file(MPB_TEST_DATA "/mimic_gripper.urdf"), err[512];
    /* A 1 cm cube centred where finger_r's box is at q1 = 0.03. */
    const char *scene = "block\n* block\n0 0 0\n0 0 0 1\n1\nbox\n"
                        "0.01 0.01 0.01\n0.54 -0.04 0.1\n0 0 0 1\n0 0 0 0\n0\n.\n";
    const char *const joints[] = {"shoulder", "finger_l_joint"};
    mpb_world *w = NULL;
    if (mpb_world_open_group("urdf", urdf, "moveit-scene", scene, joints, 2,
                             &w, err, sizeof err) != MPB_OK)
        fail_msg("%s", err);
    char what[200];
    double closed[2] = {0, 0}, open[2] = {0, 0.03};
    assert_int_equal(mpb_world_contact(w, closed, what, sizeof what), 0);
    assert_int_equal(mpb_world_contact(w, open, what, sizeof what), 1);
    assert_string_equal(what, "finger_r touches scene object block");
    mpb_world_close(w);
    free(urdf);
}

static void test_mimic_refused(void **state)
{
    (void)state;
    char *urdf = test_read_file(MPB_TEST_DATA "/mimic_gripper.urdf"), err[512];
    mpb_robot *r = NULL;
    const char *const names[] = {"shoulder", "finger_r_joint"};
    assert_int_equal(mpb_robot_open_urdf_joints(urdf, names, 2, &r, err,
                                                sizeof err), MPB_EPARSE);
    assert_string_equal(err, "urdf: joint 'finger_r_joint' mimics "
                        "'finger_l_joint' and follows it; a mimic joint cannot "
                        "be in the group");
    /* Base to tip: the mimics on the way are not active. */
    assert_int_equal(mpb_robot_open_urdf(urdf, "base", "tip_r", &r, err,
                                         sizeof err), MPB_OK);
    assert_int_equal(mpb_robot_num_joints(r), 1);
    mpb_robot_close(r);
    /* A mimic of no joint, and a loop of mimics. */
    char *bad = malloc(strlen(urdf) + 64);
    assert_non_null(bad);
    char *at = strstr(urdf, "<mimic joint=\"finger_l_joint\"");
    assert_non_null(at);
    sprintf(bad, "%.*s<mimic joint=\"finger_x\"%s", (int)(at - urdf), urdf,
            at + strlen("<mimic joint=\"finger_l_joint\""));
    assert_int_equal(mpb_robot_open_urdf(bad, NULL, NULL, &r, err, sizeof err),
                     MPB_EPARSE);
    assert_string_equal(err, "urdf: joint 'finger_r_joint' mimics 'finger_x', "
                        "which is not a joint of the URDF");
    sprintf(bad, "%.*s<mimic joint=\"tip_r_joint\"%s", (int)(at - urdf), urdf,
            at + strlen("<mimic joint=\"finger_l_joint\""));
    assert_int_equal(mpb_robot_open_urdf(bad, NULL, NULL, &r, err, sizeof err),
                     MPB_EPARSE);
    assert_non_null(strstr(err, "mimics itself through other mimic joints"));
    free(bad);
    free(urdf);
}

/* s with the one occurrence of `from` replaced by `to`; the caller frees. */
static char *replace_once(const char *s, const char *from, const char *to)
{
    const char *at = strstr(s, from);
    if (!at || strstr(at + 1, from))
        fail_msg("'%s' is not in the text exactly once", from);
    char *out = malloc(strlen(s) + strlen(to) + 1);
    assert_non_null(out);
    sprintf(out, "%.*s%s%s", (int)(at - s), s, to, at + strlen(from));
    return out;
}

/*
 * The Panda's second finger follows the first when the hand is planned.
 * VAMP's Panda has both finger joints fixed (with the mimic element the
 * real one has): made prismatic here, with the real limits (0 .. 4 cm).
 */
static void test_panda_fingers(void **state)
{
    (void)state;
    char *orig, *srdf, err[512];
    test_read_robot_data("panda", &orig, &srdf);
    static const char *const edits[][2] = {
        {"<joint name=\"panda_finger_joint1\" type=\"fixed\">",
         "<joint name=\"panda_finger_joint1\" type=\"prismatic\">"},
        {"<joint name=\"panda_finger_joint2\" type=\"fixed\">",
         "<joint name=\"panda_finger_joint2\" type=\"prismatic\">"},
        {"<axis xyz=\"0 1 0\"></axis>",
         "<axis xyz=\"0 1 0\"/><limit lower=\"0\" upper=\"0.04\" effort=\"20\" velocity=\"0.2\"/>"},
        {"<axis xyz=\"0 -1 0\"></axis>",
         "<axis xyz=\"0 -1 0\"/><limit lower=\"0\" upper=\"0.04\" effort=\"20\" velocity=\"0.2\"/>"},
    };
    char *urdf = orig;
    for (size_t i = 0; i < sizeof edits / sizeof edits[0]; i++) {
        char *next = replace_once(urdf, edits[i][0], edits[i][1]);
        free(urdf);
        urdf = next;
    }
    mpb_srdf *s = NULL;
    assert_int_equal(mpb_srdf_open(urdf, srdf, &s, err, sizeof err), MPB_OK);
    /* Now the hand has finger_joint1 to plan, below the arm's chain; its
     * mimic finger_joint2 follows and is not active. */
    const mpb_srdf_group *g =
        mpb_srdf_get_group(s, mpb_srdf_group_index(s, "panda_arm_hand"));
    assert_non_null(g);
    assert_int_equal(g->num_active, 8);
    assert_string_equal(g->active[7], "panda_finger_joint1");
    assert_int_equal(mpb_srdf_group_check(s, mpb_srdf_group_index(s,
                     "panda_arm_hand"), err, sizeof err), MPB_OK);
    mpb_robot *r = NULL;
    if (mpb_robot_open_urdf_joints(urdf, g->active, g->num_active, &r, err,
                                   sizeof err) != MPB_OK)
        fail_msg("%s", err);
    double q[8] = {0, -0.785, 0, -2.356, 0, 1.571, 0.785, 0.0};
    int lf = mpb_robot_link_index(r, "panda_leftfinger");
    int rf = mpb_robot_link_index(r, "panda_rightfinger");
    mpb_pose a0, b0, a1, b1;
    assert_int_equal(mpb_robot_link_pose(r, q, lf, &a0), MPB_OK);
    assert_int_equal(mpb_robot_link_pose(r, q, rf, &b0), MPB_OK);
    q[7] = 0.03;
    assert_int_equal(mpb_robot_link_pose(r, q, lf, &a1), MPB_OK);
    assert_int_equal(mpb_robot_link_pose(r, q, rf, &b1), MPB_OK);
    /* Each finger moved 3 cm, apart: 6 cm more between them. */
    double d0 = 0, d1 = 0, ma = 0, mb = 0;
    for (int i = 0; i < 3; i++) {
        d0 += (a0.t[i] - b0.t[i]) * (a0.t[i] - b0.t[i]);
        d1 += (a1.t[i] - b1.t[i]) * (a1.t[i] - b1.t[i]);
        ma += (a1.t[i] - a0.t[i]) * (a1.t[i] - a0.t[i]);
        mb += (b1.t[i] - b0.t[i]) * (b1.t[i] - b0.t[i]);
    }
    assert_near(sqrt(ma), 0.03, 1e-9);
    assert_near(sqrt(mb), 0.03, 1e-9);
    assert_near(sqrt(d1) - sqrt(d0), 0.06, 1e-9);
    mpb_robot_close(r);
    mpb_srdf_close(s);
    free(urdf);
    free(srdf);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mimic_fk),
        cmocka_unit_test(test_mimic_world),
        cmocka_unit_test(test_mimic_refused),
        cmocka_unit_test(test_panda_fingers),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
