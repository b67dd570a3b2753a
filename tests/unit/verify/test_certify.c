/*
 * test_certify.c - certified segment verification (verify/certify.c,
 * docs/verification.md): thin obstacles that a segment sweeps through
 * between the samples of the sampled check are collisions, with the
 * configuration found; an obstacle grazed at 1e-4 m is proved free.
 *
 * The planar arm is scenes/planar/arm3.robot with zero-radius links (1.2 m
 * when straight); its shoulder swings from -0.5045 to +0.5045 rad through
 * a wall across y = 0 at x 0.6 .. 1.1: the sampled check (0.01 rad) steps
 * over it (its samples nearest 0 are at -0.005 and +0.005 rad, where the
 * links clear 2 mm walls).
 *
 * The PR2 (tests/support/data/pr2_right_arm.urdf, as test_world_urdf.c): at
 * q = 0 the forearm is a cylinder of radius 0.05 along x from x = 0.47 to
 * 0.75 whose axis lies at y = -0.188, z = 0.739675, the shoulder pan axis
 * at x = -0.05. A 0.1 mm plate across y, over x 0.58 .. 0.62, whose lower
 * edge lies 1e-5 m below the cylinder's top, touches the forearm only
 * while pan is within 1.6e-3 rad of 0; the segment's samples are at
 * -0.005 and +0.005 rad.
 *
 * The steps of a path form one chain: each pair's distance bound is kept
 * from step to step and segment to segment, lowered by what the motion
 * may have closed, and measured again only when it runs out. A path that
 * reaches the plate only in its third segment, after its bounds were
 * taken far from it, still collides there; a world changed between two
 * verifications (a joint held elsewhere) is measured afresh.
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
#include "test_certify_worlds.h"

/* Verify the straight path a -> b (nj joints) at resolution 0.01. */
static mpb_verdict verify(mpb_world *w, const double *a, const double *b, int nj)
{
    double wp[14];
    memcpy(wp, a, (size_t)nj * sizeof *wp);
    memcpy(wp + nj, b, (size_t)nj * sizeof *wp);
    mpb_goal g = { .kind = MPB_GOAL_JOINTS, .joints = b, .joint_tolerance = 1e-9 };
    mpb_verdict v;
    assert_int_equal(mpb_verify_path(w, a, 1e-9, &g, wp, 2, nj, 0.01, &v), MPB_OK);
    return v;
}

/* Collision with a colliding configuration at s in the segment a -> b. */
static void expect_collision_found(mpb_world *w, const double *a, const double *b,
                                   int nj)
{
    mpb_verdict v = verify(w, a, b, nj);
    assert_int_equal(v.code, MPB_VERDICT_COLLISION);
    assert_int_equal(v.certified, 1);
    assert_int_equal(v.segment, 0);
    double s = test_verdict_s(&v), q[7];
    assert_true(s > 0 && s < 1);
    for (int j = 0; j < nj; j++)
        q[j] = a[j] + s * (b[j] - a[j]);
    assert_int_equal(mpb_world_in_collision(w, q), 1);
    /* the sampled check misses it */
    assert_int_equal(mpb_world_set_verification(w, MPB_VERIFY_SAMPLED), MPB_OK);
    v = verify(w, a, b, nj);
    assert_int_equal(v.code, MPB_VERDICT_VALID);
    assert_int_equal(v.certified, 0);
    assert_int_equal(mpb_world_set_verification(w, MPB_VERIFY_CERTIFIED), MPB_OK);
}

static void planar_wall_and_foil_are_collisions(void **state)
{
    (void)state;
    const double a[3] = { -0.5045, 0, 0 }, b[3] = { 0.5045, 0, 0 };
    const char *const scenes[] = { "box 0.85 0 0.25 0.001\n",     /* 2 mm */
                                   "box 0.85 0 0.25 0.00005\n" }; /* 0.1 mm */
    for (int i = 0; i < 2; i++) {
        mpb_world *w = test_planar_arm(scenes[i]);
        expect_collision_found(w, a, b, 3);
        mpb_world_close(w);
    }
}

static void planar_graze_at_1e4_is_certified_free(void **state)
{
    (void)state;
    /* The tip passes (1.2, 0) at shoulder 0: 1e-4 m from the circle. */
    mpb_world *w = test_planar_arm("circle 1.3001 0 0.1\n");
    const double a[3] = { -0.5045, 0, 0 }, b[3] = { 0.5045, 0, 0 };
    mpb_verdict v = verify(w, a, b, 3);
    assert_int_equal(v.code, MPB_VERDICT_VALID);
    assert_int_equal(v.certified, 1);
    /* and nearer still: 2e-6 m is within no step the floor allows to
       prove; sampled there, valid, and said so */
    mpb_world_close(w);
    w = test_planar_arm("circle 1.300002 0 0.1\n");
    v = verify(w, a, b, 3);
    assert_int_equal(v.code, MPB_VERDICT_VALID);
    mpb_world_close(w);
}

static void pr2_forearm_through_a_plate_is_a_collision(void **state)
{
    (void)state;
    const double top = TEST_PR2_FOREARM_TOP;
    const double a[7] = { -0.105 }, b[7] = { 0.095 };
    mpb_world *w = test_pr2_with_plate(top - 1e-5);
    double q0[7] = { 0 };
    assert_int_equal(mpb_world_in_collision(w, q0), 1);
    expect_collision_found(w, a, b, 7);
    mpb_world_close(w);

    /* Grazed at 1e-4 m: proved free. */
    w = test_pr2_with_plate(top + 1e-4);
    assert_int_equal(mpb_world_in_collision(w, q0), 0);
    mpb_verdict v = verify(w, a, b, 7);
    assert_int_equal(v.code, MPB_VERDICT_VALID);
    assert_int_equal(v.certified, 1);
    mpb_world_close(w);
}

/* Verify the path wp (n waypoints of 7 joints) at resolution 0.01. */
static mpb_verdict verify_path7(mpb_world *w, const double *wp, int n)
{
    const double *b = wp + (size_t)(n - 1) * 7;
    mpb_goal g = { .kind = MPB_GOAL_JOINTS, .joints = b, .joint_tolerance = 1e-9 };
    mpb_verdict v;
    assert_int_equal(mpb_verify_path(w, wp, 1e-9, &g, wp, n, 7, 0.01, &v), MPB_OK);
    return v;
}

static void pr2_chain_reaches_the_plate_in_its_third_segment(void **state)
{
    (void)state;
    const double top = TEST_PR2_FOREARM_TOP;
    /* pan -0.9 -> -0.6 -> -0.3 -> +0.095 (through 0) -> 0.3; the first
       two segments keep far from the plate, the elbow and wrist move */
    double wp[5 * 7] = { 0 };
    const double pan[5] = { -0.9, -0.6, -0.3, 0.095, 0.3 };
    for (int i = 0; i < 5; i++)
        wp[i * 7] = pan[i];
    wp[1 * 7 + 3] = -0.2;       /* elbow flexed, then back straight */
    wp[1 * 7 + 5] = -0.3;
    mpb_world *w = test_pr2_with_plate(top - 1e-5);
    mpb_verdict v = verify_path7(w, wp, 5);
    assert_int_equal(v.code, MPB_VERDICT_COLLISION);
    assert_int_equal(v.certified, 1);
    assert_int_equal(v.segment, 2);
    double s = test_verdict_s(&v), q[7];
    assert_true(s > 0 && s < 1);
    for (int j = 0; j < 7; j++)
        q[j] = wp[2 * 7 + j] + s * (wp[3 * 7 + j] - wp[2 * 7 + j]);
    assert_int_equal(mpb_world_in_collision(w, q), 1);
    /* the same path a second time, and its first three waypoints alone:
       a new chain each time, no bound carried from the last */
    v = verify_path7(w, wp, 5);
    assert_int_equal(v.code, MPB_VERDICT_COLLISION);
    assert_int_equal(v.segment, 2);
    v = verify_path7(w, wp, 3);
    assert_int_equal(v.code, MPB_VERDICT_VALID);
    assert_int_equal(v.certified, 1);
    /* a path that starts where the last one did not end (its bounds
       taken far from the plate, in one step) and crosses it at once */
    v = verify_path7(w, wp, 2);
    assert_int_equal(v.code, MPB_VERDICT_VALID);
    const double a2[7] = { -0.105 }, b2[7] = { 0.095 };
    expect_collision_found(w, a2, b2, 7);
    mpb_world_close(w);
}

static void pr2_bounds_do_not_outlive_a_changed_world(void **state)
{
    (void)state;
    /* The plate 1 cm over the forearm's top: the path clears it. Lift
       the torso 2 cm and the same path sweeps the forearm through it. */
    const double top = TEST_PR2_FOREARM_TOP;
    double wp[3 * 7] = { 0 };
    wp[0] = -0.3;
    wp[7] = 0.0;
    wp[14] = 0.3;
    mpb_world *w = test_pr2_with_plate(top + 0.01);
    mpb_verdict v = verify_path7(w, wp, 3);
    assert_int_equal(v.code, MPB_VERDICT_VALID);
    assert_int_equal(v.certified, 1);
    const char *torso[] = { "torso_lift_joint" };
    double lift = 0.02;
    char err[200];
    assert_int_equal(mpb_world_hold(w, torso, &lift, 1, err, sizeof err), MPB_OK);
    wp[7] = -0.2;               /* cross the plate within segment 1 */
    v = verify_path7(w, wp, 3);
    assert_int_equal(v.code, MPB_VERDICT_COLLISION);
    assert_int_equal(v.certified, 1);
    assert_int_equal(v.segment, 1);
    /* and back down: free again */
    lift = 0;
    assert_int_equal(mpb_world_hold(w, torso, &lift, 1, err, sizeof err), MPB_OK);
    v = verify_path7(w, wp, 3);
    assert_int_equal(v.code, MPB_VERDICT_VALID);
    assert_int_equal(v.certified, 1);
    mpb_world_close(w);
}

static void modes_have_names(void **state)
{
    (void)state;
    assert_string_equal(mpb_verification_name(MPB_VERIFY_CERTIFIED), "certified");
    assert_string_equal(mpb_verification_name(MPB_VERIFY_SAMPLED), "sampled");
    assert_string_equal(mpb_verification_name((mpb_verification)7), "unknown");
    assert_int_equal(mpb_world_set_verification(NULL, MPB_VERIFY_SAMPLED), MPB_EINVAL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(planar_wall_and_foil_are_collisions),
        cmocka_unit_test(planar_graze_at_1e4_is_certified_free),
        cmocka_unit_test(pr2_forearm_through_a_plate_is_a_collision),
        cmocka_unit_test(pr2_chain_reaches_the_plate_in_its_third_segment),
        cmocka_unit_test(pr2_bounds_do_not_outlive_a_changed_world),
        cmocka_unit_test(modes_have_names),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
