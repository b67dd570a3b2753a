/*
 * test_collision_reference.c - the fast queries of the collision world (its
 * own static tree, exact boxes, bounding spheres, the seed pair of the last
 * distance query, transforms set only before a narrow phase) against
 * references that put every pair through FCL's narrow phase
 * (collision_internal.h): the PR2 right arm in the paper's kitchen, at
 * random states, at states within 1e-9 rad of a contact, and along fine
 * paths, and among a grid of 512 small boxes (more statics than a check
 * gathers near the robot: each shape then walks the tree). Collision
 * verdicts must be the same; clearances the same to 1e-9 m.
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
#include "geometry/collision_internal.h"
#include "model/world_provider.h"
#include "test_files.h"

#define SRC MPB_TEST_DATA "/../../.."
#define NJ 7

static const char *const joints[NJ] = {
    "r_shoulder_pan_joint", "r_shoulder_lift_joint", "r_upper_arm_roll_joint",
    "r_elbow_flex_joint", "r_forearm_roll_joint", "r_wrist_flex_joint",
    "r_wrist_roll_joint"};

/* The PR2 arm in scene (NULL: the kitchen). */
static mpb_world *open_world(const char *scene_text)
{
    char *robot = test_read_file(SRC "/scenes/robots/pr2_right_arm.urdf");
    char *scene = scene_text ? strdup(scene_text)
                             : test_read_file(SRC "/scenes/paper/kitchen.scene");
    mpb_world *w = NULL;
    char err[256];
    int rc = mpb_world_open_group("urdf", robot, "moveit-scene", scene, joints,
                                  NJ, &w, err, sizeof err);
    if (rc != MPB_OK)
        fail_msg("%s", err);
    free(robot);
    free(scene);
    assert_int_equal(mpb_world_num_joints(w), NJ);
    return w;
}

static mpb_world *open_kitchen(void)
{
    return open_world(NULL);
}

/* 8 x 8 x 8 boxes of 4 cm, 17 cm apart, in front of and around the arm. */
static mpb_world *open_grid(void)
{
    size_t cap = 512 * 120 + 64, len = 0;
    char *t = malloc(cap);
    assert_non_null(t);
    len += (size_t)snprintf(t + len, cap - len, "grid\n");
    for (int i = 0; i < 512; i++)
        len += (size_t)snprintf(t + len, cap - len,
                                "* b%d\n%.3f %.3f %.3f\n0 0 0 1\n1\nbox\n"
                                "0.04 0.04 0.04\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n",
                                i, 0.1 + 0.17 * (i % 8), -1.0 + 0.17 * (i / 8 % 8),
                                0.3 + 0.17 * (i / 64));
    snprintf(t + len, cap - len, ".\n");
    mpb_world *w = open_world(t);
    free(t);
    return w;
}

/* Uniform in [0, 1), from a 64-bit LCG. */
static double rnd(uint64_t *x)
{
    *x = *x * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*x >> 11) / 9007199254740992.0;
}

static void random_state(mpb_world *w, uint64_t *x, double *q)
{
    for (int j = 0; j < NJ; j++) {
        double lo, hi;
        mpb_world_joint_limits(w, j, &lo, &hi);
        q[j] = lo + rnd(x) * (hi - lo);
    }
}

/* The fast verdict at q, checked against the reference; returns it. */
static int agree_collision(mpb_world *w, const double *q)
{
    int fast = mpb_world_in_collision(w, q);    /* places the robot */
    int ref = mpb__collision_check_brute(mpb__urdf_collision(w));
    assert_true(fast == 0 || fast == 1);
    assert_true(ref == 0 || ref == 1);
    assert_int_equal(fast, ref);
    return fast;
}

static void agree_clearance(mpb_world *w, const double *q)
{
    double fast = mpb_world_clearance(w, q);    /* places the robot */
    double ref = mpb__collision_distance_brute(mpb__urdf_collision(w));
    assert_false(isnan(fast));
    assert_false(isnan(ref));
    if (fabs(fast - ref) > 1e-9)
        fail_msg("clearance %.17g, reference %.17g", fast, ref);
}

static void random_states_agree(void **state)
{
    (void)state;
    mpb_world *w = open_kitchen();
    uint64_t x = 7;
    double q[NJ];
    int hits = 0;
    for (int i = 0; i < 3000; i++) {
        random_state(w, &x, q);
        hits += agree_collision(w, q);
        agree_clearance(w, q);
    }
    /* both verdicts are exercised */
    assert_true(hits > 300 && hits < 2700);
    mpb_world_close(w);
}

/* Between a free state and a colliding one, bisected to 1e-9 rad apart:
 * states on either side of a first contact. */
static void states_at_contact_agree(void **state)
{
    (void)state;
    mpb_world *w = open_kitchen();
    uint64_t x = 11;
    double a[NJ], b[NJ], m[NJ];
    int pairs = 0;
    while (pairs < 200) {
        random_state(w, &x, a);
        random_state(w, &x, b);
        if (agree_collision(w, a) || !agree_collision(w, b))
            continue;
        double lo = 0, hi = 1;       /* free at lo, colliding at hi */
        while (hi - lo > 1e-9) {
            double t = 0.5 * (lo + hi);
            for (int j = 0; j < NJ; j++)
                m[j] = a[j] + t * (b[j] - a[j]);
            if (agree_collision(w, m))
                hi = t;
            else
                lo = t;
            agree_clearance(w, m);
        }
        pairs++;
    }
    mpb_world_close(w);
}

/* Fine paths, as verification and the clearance metric walk them: the
 * distance query starts from the last nearest pair. */
static void fine_paths_agree(void **state)
{
    (void)state;
    mpb_world *w = open_kitchen();
    uint64_t x = 13;
    double a[NJ], b[NJ], q[NJ];
    for (int path = 0; path < 40; path++) {
        random_state(w, &x, a);
        random_state(w, &x, b);
        for (int k = 0; k <= 100; k++) {
            for (int j = 0; j < NJ; j++)
                q[j] = a[j] + (k / 100.0) * (b[j] - a[j]);
            agree_collision(w, q);
            agree_clearance(w, q);
        }
    }
    mpb_world_close(w);
}

static void states_among_many_boxes_agree(void **state)
{
    (void)state;
    mpb_world *w = open_grid();
    uint64_t x = 17;
    double a[NJ], b[NJ], q[NJ];
    int hits = 0;
    for (int i = 0; i < 500; i++) {
        random_state(w, &x, q);
        hits += agree_collision(w, q);
        agree_clearance(w, q);
    }
    assert_true(hits > 50 && hits < 450);
    for (int path = 0; path < 5; path++) {
        random_state(w, &x, a);
        random_state(w, &x, b);
        for (int k = 0; k <= 100; k++) {
            for (int j = 0; j < NJ; j++)
                q[j] = a[j] + (k / 100.0) * (b[j] - a[j]);
            agree_collision(w, q);
            agree_clearance(w, q);
        }
    }
    mpb_world_close(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(random_states_agree),
        cmocka_unit_test(states_among_many_boxes_agree),
        cmocka_unit_test(states_at_contact_agree),
        cmocka_unit_test(fine_paths_agree),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
