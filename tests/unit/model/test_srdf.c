/*
 * test_srdf.c - SRDF semantics (mpbench/srdf.h): groups by MoveIt's rules
 * on the field's robots (the Panda, UR5, Fetch and Baxter of
 * tools/robot_data.sh, fetched if missing, and the shipped PR2 arm), group
 * states, virtual and passive joints, end effectors; each bad SRDF refused
 * in one line naming its line.
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

static mpb_srdf *load_robot(const char *name)
{
    char *urdf, *srdf, err[512];
    mpb_srdf *s = NULL;
    test_read_robot_data(name, &urdf, &srdf);
    int rc = mpb_srdf_open(urdf, srdf, &s, err, sizeof err);
    if (rc != MPB_OK)
        fail_msg("%s: %s", name, err);
    free(urdf);
    free(srdf);
    return s;
}

static const mpb_srdf_group *group(const mpb_srdf *s, const char *name)
{
    int g = mpb_srdf_group_index(s, name);
    if (g < 0)
        fail_msg("no group %s", name);
    return mpb_srdf_get_group(s, g);
}

/* The group's active joints, comma-separated. */
static void active_list(const mpb_srdf_group *g, char *out, size_t len)
{
    size_t used = 0;
    out[0] = '\0';
    for (int j = 0; j < g->num_active; j++)
        used += (size_t)snprintf(out + used, len - used, "%s%s", j ? "," : "",
                                 g->active[j]);
}

static void assert_active(const mpb_srdf *s, const char *name, const char *want)
{
    char got[1024];
    active_list(group(s, name), got, sizeof got);
    if (strcmp(got, want) != 0)
        fail_msg("group %s: active %s, expected %s", name, got, want);
}

/* ---- the field's robots -------------------------------------------------- */

static void test_panda(void **state)
{
    (void)state;
    mpb_srdf *s = load_robot("panda");
    char err[512];
    assert_string_equal(mpb_srdf_robot_name(s), "panda");
    assert_int_equal(mpb_srdf_num_groups(s), 3);
    /* A chain from panda_link0 to panda_link8: the seven arm joints, and
     * not the fixed panda_joint8 as an active one. */
    assert_active(s, "panda_arm", "panda_joint1,panda_joint2,panda_joint3,"
                  "panda_joint4,panda_joint5,panda_joint6,panda_joint7");
    const mpb_srdf_group *arm = group(s, "panda_arm");
    assert_int_equal(arm->num_joints, 8);
    assert_string_equal(arm->joints[7], "panda_joint8");
    assert_string_equal(arm->chain_base, "panda_link0");
    assert_string_equal(arm->chain_tip, "panda_link8");
    int g = mpb_srdf_group_index(s, "panda_arm");
    assert_int_equal(mpb_srdf_group_check(s, g, err, sizeof err), MPB_OK);

    /* The hand: VAMP's Panda has its fingers fixed (open), so nothing to
     * plan; the <passive_joint> inside the group is no group element
     * (MoveIt skips it too). */
    const mpb_srdf_group *hand = group(s, "hand");
    assert_int_equal(hand->num_joints, 3);
    assert_int_equal(hand->num_active, 0);
    assert_int_equal(mpb_srdf_is_passive(s, "panda_finger_joint2"), 0);
    g = mpb_srdf_group_index(s, "hand");
    assert_int_equal(mpb_srdf_group_check(s, g, err, sizeof err),
                     MPB_EUNSUPPORTED);
    assert_string_equal(err, "group 'hand' has no joint to plan: its joints "
                        "are fixed, mimic, passive or virtual");
    /* The arm and the hand: the arm's chain. */
    const mpb_srdf_group *both = group(s, "panda_arm_hand");
    assert_int_equal(both->num_subgroups, 2);
    assert_string_equal(both->subgroups[0], "panda_arm");
    assert_string_equal(both->subgroups[1], "hand");
    assert_int_equal(both->num_active, 7);
    g = mpb_srdf_group_index(s, "panda_arm");

    /* "ready" as the SRDF writes it. */
    double q[7], want[7] = {0, -0.785, 0, -2.356, 0, 1.571, 0.785};
    assert_int_equal(mpb_srdf_state_values(s, g, "ready", q, err, sizeof err),
                     MPB_OK);
    for (int j = 0; j < 7; j++)
        assert_near(q[j], want[j], 0);
    assert_int_equal(mpb_srdf_state_values(s, g, "open", q, err, sizeof err),
                     MPB_EINVAL);
    assert_string_equal(err, "group_state 'open' is for group 'hand', not "
                        "'panda_arm'");
    assert_int_equal(mpb_srdf_state_values(s, g, "redy", q, err, sizeof err),
                     MPB_ENOTFOUND);
    assert_string_equal(err, "group 'panda_arm' has no group_state 'redy' (it "
                        "has ready, extended, transport)");

    /* The floating virtual joint and the end effector. */
    assert_int_equal(mpb_srdf_num_virtual_joints(s), 1);
    const mpb_srdf_virtual_joint *v = mpb_srdf_get_virtual_joint(s, 0);
    assert_string_equal(v->type, "floating");
    assert_string_equal(v->child_link, "panda_link0");
    assert_string_equal(v->parent_frame, "world");
    assert_int_equal(mpb_srdf_num_end_effectors(s), 1);
    const mpb_srdf_end_effector *e = mpb_srdf_get_end_effector(s, 0);
    assert_string_equal(e->name, "hand");
    assert_string_equal(e->parent_link, "panda_link8");
    assert_string_equal(e->parent_group, "panda_arm");
    mpb_srdf_close(s);
}

static void test_other_robots(void **state)
{
    (void)state;
    char err[512];
    /* UR5: a chain; "home" lists its joints out of chain order. */
    mpb_srdf *s = load_robot("ur5");
    assert_active(s, "manipulator", "shoulder_pan_joint,shoulder_lift_joint,"
                  "elbow_joint,wrist_1_joint,wrist_2_joint,wrist_3_joint");
    int g = mpb_srdf_group_index(s, "manipulator");
    double q[16];
    assert_int_equal(mpb_srdf_state_values(s, g, "home", q, err, sizeof err),
                     MPB_OK);
    assert_near(q[0], 0, 0);
    assert_near(q[1], -1.57, 0);
    assert_near(q[3], -1.57, 0);
    assert_int_equal(mpb_srdf_num_passive_joints(s), 5);
    assert_true(mpb_srdf_is_passive(s, "robotiq_85_right_knuckle_joint") > 0);
    mpb_srdf_close(s);

    /* Fetch: VAMP's has its head fixed; the arm with the torso below it. */
    s = load_robot("fetch");
    g = mpb_srdf_group_index(s, "head");
    assert_int_equal(mpb_srdf_group_check(s, g, err, sizeof err),
                     MPB_EUNSUPPORTED);
    assert_string_equal(err, "group 'head' has no joint to plan: its joints "
                        "are fixed, mimic, passive or virtual");
    assert_active(s, "arm_with_torso", "torso_lift_joint,shoulder_pan_joint,"
                  "shoulder_lift_joint,upperarm_roll_joint,elbow_flex_joint,"
                  "forearm_roll_joint,wrist_flex_joint,wrist_roll_joint");
    mpb_srdf_close(s);

    /* Baxter: each arm a chain; both arms are two branches; its virtual
     * joint is passive. */
    s = load_robot("baxter");
    assert_active(s, "right_arm", "right_s0,right_s1,right_e0,right_e1,"
                  "right_w0,right_w1,right_w2");
    g = mpb_srdf_group_index(s, "both_arms");
    assert_int_equal(mpb_srdf_group_check(s, g, err, sizeof err),
                     MPB_EUNSUPPORTED);
    assert_non_null(strstr(err, "group 'both_arms' is not a serial chain"));
    assert_true(mpb_srdf_is_passive(s, "virtual_joint") > 0);
    g = mpb_srdf_group_index(s, "right_arm");
    assert_int_equal(mpb_srdf_state_values(s, g, "right_neutral", q, err,
                                           sizeof err), MPB_OK);
    assert_near(q[1], -0.55, 0);        /* right_s1 */
    assert_near(q[3], 0.75, 0);         /* right_e1 */
    assert_near(q[5], 1.26, 0);         /* right_w1 */
    mpb_srdf_close(s);
}

/* ---- bad SRDFs: one line, naming the line -------------------------------- */

static const char *const PR2 = MPB_TEST_DATA "/pr2_right_arm.urdf";

/* Load srdf against the shipped PR2 arm; expect a failure saying want. */
static void refused(const char *srdf, int code, const char *want)
{
    char *urdf = test_read_file(PR2), err[512];
    mpb_srdf *s = (mpb_srdf *)1;
    int rc = mpb_srdf_open(urdf, srdf, &s, err, sizeof err);
    free(urdf);
    if (rc != code || s != NULL || strcmp(err, want) != 0)
        fail_msg("rc %d (expected %d): '%s', expected '%s'", rc, code, err,
                 want);
}

#define HEAD "<robot name=\"pr2\">\n"

static void test_bad_srdf(void **state)
{
    (void)state;
    /* An internal DTD, which TinyXML cannot read: at its place, not "no
     * root element". */
    refused("<?xml version=\"1.0\"?>\n<!DOCTYPE robot [\n  <!ELEMENT robot "
            "ANY>\n]>\n" HEAD "</robot>\n", MPB_EPARSE, "srdf line 2, column "
            "1: a <!DOCTYPE> with an internal DTD ([...]) is not read: remove "
            "it");
    refused(HEAD "  <group name=\"arm\">\n    <chain base_link=\"torso_lift_li",
            MPB_EPARSE, "srdf line 3, column 12: not well-formed XML: Error "
            "parsing Element.");
    refused(HEAD "  <group name=\"arm\">\n    <joint name=\"r_elbow\"/>\n"
            "  </group>\n</robot>\n", MPB_EPARSE, "srdf line 3: group 'arm' "
            "names joint 'r_elbow', which is not a joint of the URDF");
    refused(HEAD "  <group name=\"arm\">\n    <link name=\"r_hand\"/>\n"
            "  </group>\n</robot>\n", MPB_EPARSE, "srdf line 3: group 'arm' "
            "names link 'r_hand', which is not a link of the URDF");
    refused(HEAD "  <group name=\"arm\">\n    <chain base_link=\"torso_lift_link\" "
            "tip_link=\"r_hand\"/>\n  </group>\n</robot>\n", MPB_EPARSE,
            "srdf line 3: group 'arm': chain names tip link 'r_hand', which is "
            "not a link of the URDF");
    refused(HEAD "\n  <group name=\"arm\">\n  </group>\n</robot>\n", MPB_EPARSE,
            "srdf line 3: group 'arm' has no joints");
    refused(HEAD "  <group name=\"a\"><group name=\"b\"/></group>\n"
            "  <group name=\"b\"><group name=\"c\"/></group>\n"
            "  <group name=\"c\"><group name=\"a\"/></group>\n</robot>\n",
            MPB_EPARSE, "srdf line 4: group 'a' contains itself through its "
            "subgroups (a -> b -> c -> a)");
    refused(HEAD "  <group name=\"a\"><group name=\"arm\"/></group>\n</robot>\n",
            MPB_EPARSE, "srdf line 2: group 'a' names subgroup 'arm', which "
            "is no group of the SRDF");
    refused(HEAD "  <group name=\"a\"><joint name=\"r_elbow_flex_joint\"/></group>\n"
            "  <group name=\"a\"><joint name=\"r_elbow_flex_joint\"/></group>\n"
            "</robot>\n", MPB_EPARSE, "srdf line 3: group 'a' is defined twice "
            "(first at line 2)");
    refused(HEAD "  <group name=\"a\"><joint name=\"r_elbow_flex_joint\"/></group>\n"
            "  <group_state name=\"s\" group=\"a\">\n"
            "    <joint name=\"r_wrist_flex_joint\" value=\"0\"/>\n"
            "  </group_state>\n</robot>\n", MPB_EPARSE, "srdf line 4: "
            "group_state 's' gives joint 'r_wrist_flex_joint', which is not in "
            "group 'a'");
    refused(HEAD "  <group name=\"a\"><joint name=\"r_elbow_flex_joint\"/></group>\n"
            "  <group_state name=\"s\" group=\"a\">\n"
            "    <joint name=\"r_elbow_flex_joint\" value=\"up\"/>\n"
            "  </group_state>\n</robot>\n", MPB_EPARSE, "srdf line 4: "
            "group_state 's': joint 'r_elbow_flex_joint' has value 'up', not a "
            "number (a multi-variable joint's values are not read)");
    refused(HEAD "  <group_state name=\"s\" group=\"arm\"/>\n</robot>\n",
            MPB_EPARSE, "srdf line 2: group_state 's' is for group 'arm', "
            "which is no group of the SRDF");
    refused(HEAD "  <virtual_joint name=\"v\" type=\"floating\" parent_frame=\"w\" "
            "child_link=\"torso_lift_link\"/>\n</robot>\n", MPB_EPARSE,
            "srdf line 2: virtual_joint 'v' attaches to 'torso_lift_link', "
            "which is not the URDF's root link 'base_link'");
    refused(HEAD "  <virtual_joint name=\"v\" type=\"spherical\" parent_frame=\"w\" "
            "child_link=\"base_link\"/>\n</robot>\n", MPB_EPARSE,
            "srdf line 2: virtual_joint 'v' has type 'spherical'; it must be "
            "fixed, floating or planar");
    refused(HEAD "  <passive_joint name=\"torso\"/>\n</robot>\n", MPB_EPARSE,
            "srdf line 2: passive_joint 'torso' is not a joint of the URDF");
    refused(HEAD "  <end_effector name=\"e\" group=\"g\" parent_link=\"r_wrist_roll_link\"/>\n"
            "</robot>\n", MPB_EPARSE, "srdf line 2: end_effector 'e' has group "
            "'g', which is not a group of the SRDF");
    refused(HEAD "  <group name=\"arm\"/>\n  <group_state name=\"s\"/>\n</robot>\n",
            MPB_EPARSE, "srdf line 3: group_state has no group");
    refused("<robt/>\n", MPB_EPARSE, "srdf line 1: the root element is <robt>, "
            "not <robot>");
    /* A broken URDF is the URDF's fault, said so. */
    char err[512];
    mpb_srdf *s = NULL;
    assert_int_equal(mpb_srdf_open("<robot name=\"r\">\n<link name=\"a\">\n</robot>\n",
                                   HEAD "</robot>\n", &s, err, sizeof err),
                     MPB_EPARSE);
    assert_null(s);
    assert_true(strncmp(err, "urdf: line 3", 12) == 0);
}

/* What mpbench will not plan, though MoveIt's SRDF allows it. */
static void test_unplannable(void **state)
{
    (void)state;
    char *urdf = test_read_file(PR2), err[512];
    mpb_srdf *s = NULL;
    const char *srdf = HEAD
        "  <virtual_joint name=\"v\" type=\"planar\" parent_frame=\"odom\" child_link=\"base_link\"/>\n"
        "  <passive_joint name=\"torso_lift_joint\"/>\n"
        "  <group name=\"torso\"><joint name=\"torso_lift_joint\"/></group>\n"
        "  <group name=\"base\"><joint name=\"v\"/><link name=\"base_link\"/></group>\n"
        "  <group name=\"arm\"><chain base_link=\"base_link\" tip_link=\"r_wrist_roll_link\"/></group>\n"
        "  <group name=\"rev\"><joint name=\"r_wrist_flex_joint\"/><joint name=\"r_elbow_flex_joint\"/>"
        "<joint name=\"r_shoulder_pan_joint\"/></group>\n"
        "</robot>\n";
    assert_int_equal(mpb_srdf_open(urdf, srdf, &s, err, sizeof err), MPB_OK);
    int g = mpb_srdf_group_index(s, "torso");
    assert_int_equal(mpb_srdf_group_check(s, g, err, sizeof err), MPB_EUNSUPPORTED);
    assert_string_equal(err, "group 'torso' names joint 'torso_lift_joint', "
                        "which is passive (srdf line 3); a passive joint is "
                        "never planned");
    g = mpb_srdf_group_index(s, "base");
    assert_int_equal(group(s, "base")->num_joints, 1);
    assert_int_equal(mpb_srdf_group_check(s, g, err, sizeof err), MPB_EUNSUPPORTED);
    assert_string_equal(err, "group 'base' names virtual joint 'v', which "
                        "mpbench holds at the identity; it cannot be planned");
    /* The chain from the base passes the passive torso: the arm's seven. */
    g = mpb_srdf_group_index(s, "arm");
    assert_int_equal(mpb_srdf_group_check(s, g, err, sizeof err), MPB_OK);
    assert_int_equal(group(s, "arm")->num_active, 7);
    assert_string_equal(group(s, "arm")->active[0], "r_shoulder_pan_joint");
    /* Joints named tip first are planned base first. */
    assert_active(s, "rev", "r_shoulder_pan_joint,r_elbow_flex_joint,"
                  "r_wrist_flex_joint");
    mpb_srdf_close(s);
    free(urdf);
}

/* A world opened with an SRDF checks it as mpb_srdf_open() does. */
static void test_world_checks(void **state)
{
    (void)state;
    char *urdf = test_read_file(PR2), err[512];
    const char *joints[] = {"r_shoulder_pan_joint", "r_shoulder_lift_joint",
                            "r_upper_arm_roll_joint", "r_elbow_flex_joint"};
    struct { const char *srdf, *want; } cases[] = {
        {HEAD "  <passive_joint name=\"r_elbow_flex_joint\"/>\n</robot>\n",
         "srdf line 2: joint 'r_elbow_flex_joint' is passive; a passive joint "
         "cannot be in the group"},
        {HEAD "\n  <group name=\"arm\"><joint name=\"elbow\"/></group>\n</robot>\n",
         "srdf line 3: group 'arm' names joint 'elbow', which is not a joint "
         "of the URDF"},
        {HEAD "  <group name=\"arm\"/>\n</robot>\n",
         "srdf line 2: group 'arm' has no joints"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char *text = malloc(strlen(urdf) + strlen(cases[i].srdf) + 1);
        assert_non_null(text);
        sprintf(text, "%s%s", urdf, cases[i].srdf);
        mpb_world *w = (mpb_world *)1;
        assert_int_equal(mpb_world_open_group("urdf", text, "moveit-scene",
                                              "(empty)\n.\n", joints, 4, &w,
                                              err, sizeof err), MPB_EPARSE);
        assert_null(w);
        assert_string_equal(err, cases[i].want);
        free(text);
    }
    free(urdf);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_panda),
        cmocka_unit_test(test_other_robots),
        cmocka_unit_test(test_bad_srdf),
        cmocka_unit_test(test_unplannable),
        cmocka_unit_test(test_world_checks),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
