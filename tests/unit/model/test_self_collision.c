/*
 * test_self_collision.c - whole-body self-collision and the
 * allowed-collision matrix (world.h): the shipped PR2
 * (scenes/robots/pr2_right_arm.urdf) with its gripper inside its own torso,
 * the matrix generated without an SRDF, and one read from an SRDF
 * (tests/support/data/folding_arm.urdf + .srdf, a folding planar arm beside a
 * fixed post), and an arm in a cage it nearly always touches
 * (caged_arm.urdf).
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
#include "test_files.h"

#define PR2 MPB_TEST_DATA "/../../../scenes/robots/pr2_right_arm.urdf"

static const char *const arm[] = {
    "r_shoulder_pan_joint", "r_shoulder_lift_joint", "r_upper_arm_roll_joint",
    "r_elbow_flex_joint", "r_forearm_roll_joint", "r_wrist_flex_joint",
    "r_wrist_roll_joint"};
static const char *const folding[] = {"j1", "j2", "j3"};

static const char empty_scene[] = "(empty)\n.\n";

/*
 * The tool frame at (-0.10, -0.05, 0.42), inside the torso column, and no
 * other pair of links touching: a state the world called free before it
 * checked moving links against fixed ones (found by sampling, the tool
 * frame's place checked below with mpb_world_ee_position).
 */
static const double gripper_in_torso[7] = {-1.5, 1.0, -3.2, -1.7, -0.4, -0.2, -2.1};
/* The arm forward, elbow bent: free. */
static const double arm_forward[7] = {-0.5, 0.2, -1.0, -1.2, 0.0, -0.5, 0.0};

static mpb_world *open_text(const char *robot, const char *const *joints, int n)
{
    mpb_world *w = NULL;
    char err[256];
    int rc = mpb_world_open_group("urdf", robot, "moveit-scene", empty_scene,
                                  joints, n, &w, err, sizeof err);
    if (rc != MPB_OK)
        fail_msg("open: %s", err);
    return w;
}

/* The URDF file, followed by the SRDF file when srdf is not NULL. */
static char *robot_text(const char *urdf, const char *srdf)
{
    char *u = test_read_file(urdf);
    if (!srdf)
        return u;
    char *s = test_read_file(srdf);
    char *both = malloc(strlen(u) + strlen(s) + 1);
    assert_non_null(both);
    strcpy(both, u);
    strcat(both, s);
    free(u);
    free(s);
    return both;
}

/* The matrix as "link1 link2 reason\n" lines. */
static char *matrix_text(mpb_world *w)
{
    int n = mpb_world_num_allowed_pairs(w);
    char *s = calloc((size_t)n * 200 + 1, 1);
    assert_non_null(s);
    for (int i = 0; i < n; i++) {
        mpb_world_acm_pair p;
        assert_int_equal(mpb_world_allowed_pair(w, i, &p), MPB_OK);
        snprintf(s + strlen(s), 200, "%s %s %s\n", p.link1, p.link2, p.reason);
    }
    return s;
}

static void the_gripper_inside_the_torso_collides_naming_both_links(void **state)
{
    (void)state;
    char *urdf = robot_text(PR2, NULL);
    mpb_world *w = open_text(urdf, arm, 7);
    double tool[3];
    assert_int_equal(mpb_world_ee_position(w, gripper_in_torso, tool), MPB_OK);
    /* The torso column: x -0.30 .. 0.00, y -0.12 .. 0.12, z 0.24 .. 1.14. */
    assert_true(tool[0] > -0.25 && tool[0] < -0.05);
    assert_true(fabs(tool[1]) < 0.07);
    assert_true(tool[2] > 0.4 && tool[2] < 0.9);

    assert_int_equal(mpb_world_in_collision(w, gripper_in_torso), 1);
    char what[160];
    assert_int_equal(mpb_world_contact(w, gripper_in_torso, what, sizeof what),
                     MPB_CONTACT_SELF);
    assert_string_equal(what, "self-collision between torso_lift_link and "
                              "r_gripper_palm_link");
    /* Self-collision is no part of the clearance to the (empty) scene. */
    assert_true(isinf(mpb_world_clearance(w, gripper_in_torso)));

    assert_int_equal(mpb_world_in_collision(w, arm_forward), 0);
    assert_int_equal(mpb_world_contact(w, arm_forward, what, sizeof what), 0);
    assert_string_equal(what, "");

    /* A path that ends there fails verification at its last segment, and
     * the verdict names the two links. */
    double path[2 * 7];
    memcpy(path, arm_forward, sizeof arm_forward);
    memcpy(path + 7, gripper_in_torso, sizeof gripper_in_torso);
    mpb_goal goal = {.kind = MPB_GOAL_JOINTS, .joints = gripper_in_torso,
                     .joint_tolerance = 0.01};
    mpb_verdict v;
    assert_int_equal(mpb_verify_path(w, arm_forward, 0.01, &goal, path, 2, 7,
                                     0.01, &v), MPB_OK);
    assert_int_equal(v.code, MPB_VERDICT_COLLISION);
    assert_non_null(strstr(v.detail, "self-collision between torso_lift_link "
                                     "and r_gripper_palm_link"));
    mpb_world_close(w);
    free(urdf);
}

static void the_generated_matrix_keeps_gripper_and_torso_checked(void **state)
{
    (void)state;
    char *urdf = robot_text(PR2, NULL);
    mpb_world *w = open_text(urdf, arm, 7);
    char *m = matrix_text(w);
    /* MoveIt's reasons: the chain's neighbours, the shoulder touching the
     * torso at the default state, pairs that cannot meet. */
    assert_non_null(strstr(m, "base_link torso_lift_link Adjacent\n"));
    assert_non_null(strstr(m, "torso_lift_link r_shoulder_pan_link Adjacent\n"));
    assert_non_null(strstr(m, "torso_lift_link r_shoulder_lift_link Default\n"));
    assert_non_null(strstr(m, "base_link r_shoulder_pan_link Never\n"));
    /* The pairs that can collide stay checked. */
    assert_null(strstr(m, "torso_lift_link r_gripper_palm_link"));
    assert_null(strstr(m, "base_link r_gripper_palm_link"));
    assert_null(strstr(m, "torso_lift_link r_upper_arm_link"));
    mpb_world_acm_pair p;
    assert_int_equal(mpb_world_allowed_pair(w, 0, &p), MPB_OK);
    assert_int_equal(p.from_srdf, 0);
    assert_int_equal(mpb_world_allowed_pair(w, -1, &p), MPB_EINVAL);
    assert_int_equal(mpb_world_allowed_pair(w, mpb_world_num_allowed_pairs(w), &p),
                     MPB_EINVAL);

    /* The same robot gives the same matrix: a fixed seed. */
    mpb_world *again = open_text(urdf, arm, 7);
    char *m2 = matrix_text(again);
    assert_string_equal(m, m2);
    mpb_world_close(again);
    free(m2);
    free(m);
    mpb_world_close(w);
    free(urdf);
}

static void an_srdf_gives_its_pairs_and_the_adjacent_ones(void **state)
{
    (void)state;
    char *text = robot_text(MPB_TEST_DATA "/folding_arm.urdf",
                            MPB_TEST_DATA "/folding_arm.srdf");
    mpb_world *w = open_text(text, folding, 3);
    char *m = matrix_text(w);
    /* Exactly the SRDF's two pairs plus the four adjacent ones (in link
     * order: base_link, arm1, arm2, arm3, post). */
    assert_string_equal(m, "base_link arm1 Adjacent\n"
                           "base_link arm2 Never\n"
                           "base_link post Adjacent\n"
                           "arm1 arm2 Adjacent\n"
                           "arm1 post User\n"
                           "arm2 arm3 Adjacent\n");
    mpb_world_acm_pair p;
    assert_int_equal(mpb_world_allowed_pair(w, 0, &p), MPB_OK);
    assert_int_equal(p.from_srdf, 1);

    /* arm1 through the post: allowed by the SRDF, so free. */
    double through_post[3] = {0.4636, 0, 0}, folded[3] = {0, 2.64, 1.9};
    char what[160];
    assert_int_equal(mpb_world_in_collision(w, through_post), 0);
    /* arm3 across arm1: no line allows it. */
    assert_int_equal(mpb_world_contact(w, folded, what, sizeof what),
                     MPB_CONTACT_SELF);
    assert_string_equal(what, "self-collision between arm1 and arm3");
    mpb_world_close(w);
    free(m);
    free(text);

    /* Without the SRDF the generated matrix checks arm1 against the post
     * (they meet in some states), so the same state collides. */
    text = robot_text(MPB_TEST_DATA "/folding_arm.urdf", NULL);
    w = open_text(text, folding, 3);
    assert_int_equal(mpb_world_contact(w, through_post, what, sizeof what),
                     MPB_CONTACT_SELF);
    assert_string_equal(what, "self-collision between arm1 and post");
    mpb_world_close(w);
    free(text);
}

/* text with every "from" replaced by "to"; malloc'd. */
static char *replace_all(const char *text, const char *from, const char *to)
{
    size_t n = 0, lf = strlen(from), lt = strlen(to);
    for (const char *p = text; (p = strstr(p, from)) != NULL; p += lf)
        n++;
    char *out = malloc(strlen(text) + n * lt + 1), *o = out;
    assert_non_null(out);
    for (const char *p = text, *hit; ; p = hit + lf) {
        hit = strstr(p, from);
        size_t keep = hit ? (size_t)(hit - p) : strlen(p);
        memcpy(o, p, keep);
        o += keep;
        if (!hit)
            break;
        memcpy(o, to, lt);
        o += lt;
    }
    *o = '\0';
    return out;
}

static void long_link_names_come_whole_in_the_verdict(void **state)
{
    (void)state;
    /* Links named as generated URDFs may name them (xacro prefixes): over
     * 120 characters each, both whole in the verdict of a collision (the
     * straight line folds arm2 into the post). */
    char a1[128], a3[128];
    snprintf(a1, sizeof a1, "%0100d_second_segment_link", 2);
    snprintf(a3, sizeof a3, "%0100d_upright_post_link", 0);
    char *u = test_read_file(MPB_TEST_DATA "/folding_arm.urdf");
    char *t1 = replace_all(u, "\"arm2\"", "\"ARM_ONE\"");
    char *t2 = replace_all(t1, "\"post\"", "\"ARM_THREE\"");
    char *t3 = replace_all(t2, "ARM_ONE", a1);
    char *text = replace_all(t3, "ARM_THREE", a3);
    mpb_world *w = open_text(text, folding, 3);
    double start[3] = {0, 0, 0}, folded[3] = {0, 2.64, 1.9}, path[2 * 3];
    memcpy(path, start, sizeof start);
    memcpy(path + 3, folded, sizeof folded);
    mpb_goal goal = {.kind = MPB_GOAL_JOINTS, .joints = folded,
                     .joint_tolerance = 0.01};
    mpb_verdict v;
    assert_int_equal(mpb_verify_path(w, start, 0.01, &goal, path, 2, 3, 0.01,
                                     &v), MPB_OK);
    assert_int_equal(v.code, MPB_VERDICT_COLLISION);
    char want[400];
    snprintf(want, sizeof want, "self-collision between %s and %s", a1, a3);
    if (strstr(v.detail, want) == NULL)
        fail_msg("verdict '%s'", v.detail);
    mpb_world_close(w);
    free(text);
    free(t3);
    free(t2);
    free(t1);
    free(u);
}

static void a_pair_nearly_always_in_collision_is_allowed(void **state)
{
    (void)state;
    static const char *const j[] = {"j"};
    char *text = robot_text(MPB_TEST_DATA "/caged_arm.urdf", NULL);
    mpb_world *w = open_text(text, j, 1);
    char *m = matrix_text(w);
    /* Free at the default state (the arm through the gap), in collision
     * in more than 95 % of random states: MoveIt's "Always". */
    assert_string_equal(m, "base_link frame Adjacent\n"
                           "base_link arm Adjacent\n"
                           "frame arm Always\n");
    double across[1] = {1.0};
    assert_int_equal(mpb_world_in_collision(w, across), 0);
    free(m);
    mpb_world_close(w);
    free(text);
}

/*
 * Pairs naming links the URDF lacks are skipped, as MoveIt does: the SRDF
 * loads with one line saying how many and which (the first three, at
 * their lines), and its other pairs are in the matrix.
 */
static void pairs_naming_unknown_links_are_skipped_with_a_warning(void **state)
{
    (void)state;
    static const char srdf[] =
        "<robot name='f'>\n"
        "  <disable_collisions link1='arm1' link2='pole' reason='Never'/>\n"
        "  <disable_collisions link1='arm1' link2='post' reason='User'/>\n"
        "  <disable_collisions link1='flag' link2='pole' reason='Never'/>\n"
        "  <disable_collisions link1='base_link' link2='arm2' reason='Never'/>\n"
        "  <disable_collisions link1='wheel' link2='arm3' reason='Never'/>\n"
        "  <disable_collisions link1='arm3' link2='lamp' reason='Never'/>\n"
        "</robot>\n";
    char *u = test_read_file(MPB_TEST_DATA "/folding_arm.urdf"), err[256];
    mpb_srdf *s = NULL;
    assert_int_equal(mpb_srdf_open(u, srdf, &s, err, sizeof err), MPB_OK);
    assert_int_equal(mpb_srdf_num_skipped_pairs(s), 4);
    assert_string_equal(mpb_srdf_skipped_pairs(s),
        "4 of 6 disable_collisions pairs name links the URDF lacks and are "
        "skipped, as MoveIt does: line 2 (arm1, pole: no link 'pole'), "
        "line 4 (flag, pole: no link 'flag' nor the other), line 6 (wheel, "
        "arm3: no link 'wheel') and 1 more; the names: pole, flag, wheel, "
        "lamp");
    mpb_srdf_close(s);

    char *text = malloc(strlen(u) + sizeof srdf);
    assert_non_null(text);
    strcpy(text, u);
    strcat(text, srdf);
    mpb_world *w = open_text(text, folding, 3);
    char *m = matrix_text(w);
    assert_string_equal(m, "base_link arm1 Adjacent\n"
                           "base_link arm2 Never\n"
                           "base_link post Adjacent\n"
                           "arm1 arm2 Adjacent\n"
                           "arm1 post User\n"
                           "arm2 arm3 Adjacent\n");
    double through_post[3] = {0.4636, 0, 0};
    assert_int_equal(mpb_world_in_collision(w, through_post), 0);
    mpb_world_close(w);
    free(m);

    /* An SRDF whose pairs all name known links: no warning. */
    s = NULL;
    char *good = test_read_file(MPB_TEST_DATA "/folding_arm.srdf");
    assert_int_equal(mpb_srdf_open(u, good, &s, err, sizeof err), MPB_OK);
    assert_int_equal(mpb_srdf_num_skipped_pairs(s), 0);
    assert_null(mpb_srdf_skipped_pairs(s));
    mpb_srdf_close(s);
    free(good);
    free(text);
    free(u);
}

/*
 * A generated matrix is made for the values the joints outside the group
 * hold (tests/support/data/sliding_block.urdf): at slide = 0 the block is on
 * the arm at the default state, so the pair is allowed; held at 0.5 it is
 * clear at the default state and in the arm's way at j = pi/4, so the
 * pair is checked, whether the value is held before the first check (a
 * planner's world) or after (the daemon's, query by query), and back.
 */
#define ADJ "base_link arm Adjacent\nbase_link block Adjacent\n"
static void held_values_decide_the_generated_matrix(void **state)
{
    (void)state;
    static const char *const j[] = {"j"};
    static const char *const slide[] = {"slide"};
    const double at_0 = 0.0, at_half = 0.5;
    const double straight[1] = {0.0}, diagonal[1] = {0.7854};
    char *text = robot_text(MPB_TEST_DATA "/sliding_block.urdf", NULL), err[256];
    char what[160];

    /* At the default (0): allowed, so the straight arm through it is free. */
    mpb_world *w = open_text(text, j, 1);
    char *m = matrix_text(w);
    assert_string_equal(m, ADJ "arm block Default\n");
    free(m);
    assert_int_equal(mpb_world_in_collision(w, straight), 0);
    assert_int_equal(mpb_world_in_collision(w, diagonal), 0);

    /* Held at 0.5 after checks: made again, the pair checked. */
    assert_int_equal(mpb_world_hold(w, slide, &at_half, 1, err, sizeof err),
                     MPB_OK);
    assert_int_equal(mpb_world_in_collision(w, diagonal), 1);
    assert_int_equal(mpb_world_contact(w, diagonal, what, sizeof what),
                     MPB_CONTACT_SELF);
    assert_string_equal(what, "self-collision between arm and block");
    assert_int_equal(mpb_world_in_collision(w, straight), 0);
    m = matrix_text(w);
    assert_string_equal(m, ADJ);
    free(m);

    /* Holding the same value again changes nothing; back at 0, allowed. */
    assert_int_equal(mpb_world_hold(w, slide, &at_half, 1, err, sizeof err),
                     MPB_OK);
    assert_int_equal(mpb_world_in_collision(w, diagonal), 1);
    assert_int_equal(mpb_world_hold(w, slide, &at_0, 1, err, sizeof err),
                     MPB_OK);
    assert_int_equal(mpb_world_in_collision(w, straight), 0);
    m = matrix_text(w);
    assert_string_equal(m, ADJ "arm block Default\n");
    free(m);
    mpb_world_close(w);

    /* Held before the first check, as a planner's world is: the same. */
    w = open_text(text, j, 1);
    assert_int_equal(mpb_world_hold(w, slide, &at_half, 1, err, sizeof err),
                     MPB_OK);
    m = matrix_text(w);
    assert_string_equal(m, ADJ);
    free(m);
    assert_int_equal(mpb_world_in_collision(w, diagonal), 1);
    mpb_world_close(w);
    free(text);
}
#undef ADJ

/* A bad SRDF: one line, "srdf line N: ...", naming the fault. */
static void expect_bad_srdf(const char *srdf, const char *want)
{
    char *u = test_read_file(MPB_TEST_DATA "/folding_arm.urdf");
    char *text = malloc(strlen(u) + strlen(srdf) + 1);
    assert_non_null(text);
    strcpy(text, u);
    strcat(text, srdf);
    mpb_world *w = NULL;
    char err[256];
    assert_int_equal(mpb_world_open_group("urdf", text, "moveit-scene",
                                          empty_scene, folding, 3, &w, err,
                                          sizeof err), MPB_EPARSE);
    assert_null(w);
    if (!strstr(err, want))
        fail_msg("'%s' does not say '%s'", err, want);
    assert_null(strchr(err, '\n'));
    free(text);
    free(u);
}

static void a_bad_srdf_is_named_with_its_line(void **state)
{
    (void)state;
    /* A group naming a link the URDF lacks is still refused: a planning
     * group cannot be guessed, a pair can be left out. */
    expect_bad_srdf("<robot name='f'>\n"
                    "  <disable_collisions link1='arm1' link2='pole'/>\n"
                    "  <group name='g'>\n    <link name='pole'/>\n  </group>\n"
                    "</robot>\n",
                    "srdf line 4: group 'g' names link 'pole', which is not a "
                    "link of the URDF");
    expect_bad_srdf("<robot name='f'>\n"
                    "  <disable_collisions link1='arm1' link2='po",
                    "srdf line 2, column 36: not well-formed XML");
    expect_bad_srdf("<robot name='f'>\n  <disable_collisions link1='arm1'/>\n"
                    "</robot>\n", "srdf line 2: disable_collisions has no link2");
    expect_bad_srdf("<semantic/>\n", "srdf line 1: the root element is "
                    "<semantic>, not <robot>");

    /* An SRDF on the URDF's last line is read all the same. */
    static const char tail[] = "</robot><robot name='f'><disable_collisions "
                               "link1='arm1' link2='arm3'/></robot>\n";
    char *urdf = test_read_file(MPB_TEST_DATA "/folding_arm.urdf");
    char *u = malloc(strlen(urdf) + sizeof tail);
    assert_non_null(u);
    strcpy(u, urdf);
    free(urdf);
    char *end = strstr(u, "</robot>\n");
    assert_non_null(end);
    strcpy(end, tail);
    mpb_world *w = open_text(u, folding, 3);
    double folded[3] = {0, 2.64, 1.9};
    assert_int_equal(mpb_world_in_collision(w, folded), 0);
    mpb_world_close(w);
    free(u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(the_gripper_inside_the_torso_collides_naming_both_links),
        cmocka_unit_test(the_generated_matrix_keeps_gripper_and_torso_checked),
        cmocka_unit_test(an_srdf_gives_its_pairs_and_the_adjacent_ones),
        cmocka_unit_test(a_pair_nearly_always_in_collision_is_allowed),
        cmocka_unit_test(long_link_names_come_whole_in_the_verdict),
        cmocka_unit_test(a_bad_srdf_is_named_with_its_line),
        cmocka_unit_test(pairs_naming_unknown_links_are_skipped_with_a_warning),
        cmocka_unit_test(held_values_decide_the_generated_matrix),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
