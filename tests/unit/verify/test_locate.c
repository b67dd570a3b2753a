/*
 * test_locate.c - mpb_find_collision() (verify/locate.c): the
 * configuration of a collision verdict found again, by the rule the
 * verdict was made with. The planar arm of test_certify.c (zero-radius
 * links) swings its shoulder from -0.5045 to +0.5045 rad through a 2 mm
 * wall that the sampled check (0.01 rad) steps over: certified, the
 * configuration is the verdict's "at s=" exactly; sampled, there is none.
 * A thick wall is found by both rules, sampled at the verdict's sample.
 * The PR2's forearm through a plate names the bodies in contact.
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

/* A path of three waypoints: still, then through the wall, then still. */
static const double PATH[9] = { -0.5045, 0, 0,  -0.5045, 0, 0,  0.5045, 0, 0 };

static mpb_verdict verify(mpb_world *w, const double *wp, int n)
{
    const double *last = wp + 3 * (n - 1);
    mpb_goal g = { .kind = MPB_GOAL_JOINTS, .joints = last, .joint_tolerance = 1e-9 };
    mpb_verdict v;
    assert_int_equal(mpb_verify_path(w, wp, 1e-9, &g, wp, n, 3, 0.01, &v), MPB_OK);
    return v;
}

static void thin_wall_certified_is_the_verdicts_configuration(void **state)
{
    (void)state;
    mpb_world *w = test_planar_arm("box 0.85 0 0.25 0.001\n");
    mpb_verdict v = verify(w, PATH, 3);
    assert_int_equal(v.code, MPB_VERDICT_COLLISION);
    assert_int_equal(v.segment, 1);
    double q[3];
    mpb_collision_at at;
    /* the whole path, and the verdict's segment alone: the same */
    for (int seg = -1; seg <= 1; seg += 2) {
        memset(q, 0, sizeof q);
        assert_int_equal(mpb_find_collision(w, PATH, 3, 3, 0.01, seg, q, &at), 1);
        assert_int_equal(at.segment, 1);
        assert_int_equal(at.certified, 1);
        assert_true(at.s == test_verdict_s(&v));
        assert_true(q[0] == -0.5045 + at.s * 1.009);
        assert_int_equal(mpb_world_in_collision(w, q), 1);
        assert_string_equal(at.bodies, "");     /* planar names none */
    }
    /* segment 0 is free (still), and so is a segment past the end */
    assert_int_equal(mpb_find_collision(w, PATH, 3, 3, 0.01, 0, q, &at), 0);
    assert_int_equal(mpb_find_collision(w, PATH, 3, 3, 0.01, 2, q, &at), 0);

    /* sampled: the verdict is valid, and there is nothing to find */
    assert_int_equal(mpb_world_set_verification(w, MPB_VERIFY_SAMPLED), MPB_OK);
    assert_int_equal(verify(w, PATH, 3).code, MPB_VERDICT_VALID);
    assert_int_equal(mpb_find_collision(w, PATH, 3, 3, 0.01, -1, q, &at), 0);
    assert_int_equal(mpb_find_collision(w, PATH, 3, 3, 0.01, 1, q, &at), 0);
    mpb_world_close(w);
}

static void thick_wall_sampled_is_the_verdicts_sample(void **state)
{
    (void)state;
    mpb_world *w = test_planar_arm("box 0.85 0 0.25 0.1\n");
    assert_int_equal(mpb_world_set_verification(w, MPB_VERIFY_SAMPLED), MPB_OK);
    mpb_verdict v = verify(w, PATH, 3);
    assert_int_equal(v.code, MPB_VERDICT_COLLISION);
    double q[3];
    mpb_collision_at at;
    assert_int_equal(mpb_find_collision(w, PATH, 3, 3, 0.01, -1, q, &at), 1);
    assert_int_equal(at.segment, v.segment);
    assert_int_equal(at.certified, 0);
    /* the verdict prints the sample's s with 4 digits; it is sample s/k
       of k = ceil(1.009 / 0.01) = 101 */
    assert_true(fabs(at.s - test_verdict_s(&v)) < 1e-4);
    assert_true(fabs(at.s * 101 - round(at.s * 101)) < 1e-9);
    assert_int_equal(mpb_world_in_collision(w, q), 1);
    /* certified finds it too, no later than the sample */
    assert_int_equal(mpb_world_set_verification(w, MPB_VERIFY_CERTIFIED), MPB_OK);
    mpb_collision_at c;
    assert_int_equal(mpb_find_collision(w, PATH, 3, 3, 0.01, -1, q, &c), 1);
    assert_int_equal(c.segment, at.segment);
    assert_int_equal(c.certified, 1);
    assert_true(c.s <= at.s);
    mpb_world_close(w);
}

static void waypoint_zero_and_bad_arguments(void **state)
{
    (void)state;
    mpb_world *w = test_planar_arm("box 0.85 0 0.25 0.1\n");
    const double in[3] = { 0, 0, 0 };            /* inside the wall */
    double q[3] = { 9, 9, 9 };
    mpb_collision_at at;
    assert_int_equal(mpb_find_collision(w, in, 1, 3, 0.01, -1, q, &at), 1);
    assert_int_equal(at.segment, 0);
    assert_true(at.s == 0 && q[0] == 0 && q[1] == 0 && q[2] == 0);
    assert_int_equal(mpb_find_collision(w, in, 1, 3, 0.01, 0, q, &at), 1);
    assert_int_equal(mpb_find_collision(w, in, 0, 3, 0.01, -1, q, &at), 0);

    assert_int_equal(mpb_find_collision(NULL, in, 1, 3, 0.01, -1, q, &at), MPB_EINVAL);
    assert_int_equal(mpb_find_collision(w, NULL, 1, 3, 0.01, -1, q, &at), MPB_EINVAL);
    assert_int_equal(mpb_find_collision(w, in, 1, 2, 0.01, -1, q, &at), MPB_EINVAL);
    assert_int_equal(mpb_find_collision(w, in, 1, 3, 0, -1, q, &at), MPB_EINVAL);
    assert_int_equal(mpb_find_collision(w, in, 1, 3, 0.01, -1, NULL, &at), MPB_EINVAL);
    assert_int_equal(mpb_find_collision(w, in, 1, 3, 0.01, -1, q, NULL), MPB_EINVAL);
    const double nan3[3] = { 0, NAN, 0 };
    assert_int_equal(mpb_find_collision(w, nan3, 1, 3, 0.01, -1, q, &at), MPB_EINVAL);
    assert_int_equal(mpb_find_collision(w, PATH, 3, 3, 1e-12, -1, q, &at), MPB_EINVAL);
    mpb_world_close(w);
}

static void pr2_plate_names_the_bodies(void **state)
{
    (void)state;
    /* test_certify.c's plate, its lower edge 1e-5 m into the forearm's top */
    mpb_world *w = test_pr2_with_plate(TEST_PR2_FOREARM_TOP - 1e-5);
    const double wp[14] = { -0.105, 0, 0, 0, 0, 0, 0,  0.095, 0, 0, 0, 0, 0, 0 };
    double q[7];
    mpb_collision_at at;
    assert_int_equal(mpb_find_collision(w, wp, 2, 7, 0.01, -1, q, &at), 1);
    assert_int_equal(at.certified, 1);
    assert_true(fabs(q[0]) < 2e-3);      /* near pan 0, as the plate is */
    assert_string_equal(at.bodies, "r_forearm_link touches scene object plate");
    assert_int_equal(mpb_world_set_verification(w, MPB_VERIFY_SAMPLED), MPB_OK);
    assert_int_equal(mpb_find_collision(w, wp, 2, 7, 0.01, -1, q, &at), 0);
    mpb_world_close(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(thin_wall_certified_is_the_verdicts_configuration),
        cmocka_unit_test(thick_wall_sampled_is_the_verdicts_sample),
        cmocka_unit_test(waypoint_zero_and_bad_arguments),
        cmocka_unit_test(pr2_plate_names_the_bodies),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
