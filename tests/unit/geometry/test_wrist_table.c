/*
 * test_wrist_table.c - the wrist tables (wrist_table.h): on the Panda with
 * its SRDF and collision meshes (tools/robot_data.sh; skipped when they
 * are not fetched), link5 against link7 and the hand are proved apart over
 * joints 6 and 7 where they are, and the world's verdicts, with the hints
 * the tables give the self check, stay those of every pair through FCL:
 * at random states and at states 1e-9 rad either side of a wrist contact
 * reached by turning joints 6 and 7 alone. A table built with too small a
 * bound on how fast the wrist moves fails the same comparison. The PR2's
 * primitive arm has no pair that qualifies, and builds no table.
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
#include "mpbench/robot.h"
#include "geometry/collision_internal.h"
#include "model/world_provider.h"
#include "geometry/wrist_table.h"
#include "test_files.h"
#include "test_panda.h"

#define SRC MPB_TEST_DATA "/../../.."
#define NJ 7

/* No obstacles: a verdict is the self check's. */
static const char empty_scene[] = "empty\n.\n";

static mpb_world *open_panda(void)
{
    return test_open_panda(empty_scene);
}

#define OPEN_OR_SKIP(w)                                                       \
    mpb_world *w = open_panda();                                              \
    if (!w) {                                                                 \
        print_message("Panda data not fetched (tools/robot_data.sh): "      \
                      "skipped\n");                                           \
        skip();                                                               \
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

/* The world's verdict at q against every pair through FCL: 1 if they
 * differ. */
static int differs(mpb_world *w, const double *q)
{
    char what[256];
    int fast = mpb_world_in_collision(w, q);    /* places, sets the hints */
    int ref = mpb__collision_check_brute(mpb__urdf_collision(w));
    /* A contact of either kind (MPB_CONTACT_SCENE or _SELF). */
    int named = mpb_world_contact(w, q, what, sizeof what) > 0;
    assert_true(ref == 0 || ref == 1);
    return fast != ref || named != ref;
}

/* Does the wrist pair i touch at q (FCL, no hints)? */
static int pair_touches(mpb_world *w, int i, const double *q)
{
    int near, far, jt[2];
    const mpb__wrist_table *t;
    assert_int_equal(mpb__urdf_wrist(w, i, &near, &far, jt, &t), MPB_OK);
    mpb_world_in_collision(w, q);
    int hit = mpb__collision_check_pair(mpb__urdf_collision(w), near, far);
    assert_true(hit == 0 || hit == 1);
    return hit;
}

/*
 * Disagreements of the world with the reference: at `states` random
 * states, then, for each wrist pair, at `contacts` pairs of states 1e-9
 * rad apart in joints 6 and 7 on either side of the pair's contact (the
 * other joints random).
 */
static int disagreements(mpb_world *w, int states, int contacts)
{
    uint64_t x = 5;
    double q[NJ], a[NJ], b[NJ];
    int bad = 0;
    for (int i = 0; i < states; i++) {
        random_state(w, &x, q);
        bad += differs(w, q);
    }
    for (int p = 0; p < mpb__urdf_num_wrists(w); p++) {
        int near, far, jt[2];
        const mpb__wrist_table *t;
        assert_int_equal(mpb__urdf_wrist(w, p, &near, &far, jt, &t), MPB_OK);
        for (int found = 0, tries = 0; found < contacts; tries++) {
            assert_true(tries < 100 * contacts);
            random_state(w, &x, a);
            memcpy(b, a, sizeof b);
            random_state(w, &x, q);
            b[jt[0]] = q[jt[0]];
            if (jt[1] >= 0)
                b[jt[1]] = q[jt[1]];
            if (pair_touches(w, p, a) || !pair_touches(w, p, b))
                continue;
            double lo = 0, hi = 1;      /* apart at lo, touching at hi */
            while (hi - lo > 1e-9) {
                double s = 0.5 * (lo + hi);
                for (int j = 0; j < NJ; j++)
                    q[j] = a[j] + s * (b[j] - a[j]);
                if (pair_touches(w, p, q))
                    hi = s;
                else
                    lo = s;
            }
            for (int side = 0; side < 2; side++) {
                for (int j = 0; j < NJ; j++)
                    q[j] = a[j] + (side ? hi : lo) * (b[j] - a[j]);
                bad += differs(w, q);
            }
            found++;
        }
    }
    return bad;
}

/* The Panda's wrist pairs, their tables, and what the tables hold. */
static void panda_has_wrist_tables(void **state)
{
    (void)state;
    OPEN_OR_SKIP(w);
    int n = mpb__urdf_num_wrists(w), l5 = -1, l7 = -1, hand = -1;
    mpb__urdf_model m;
    assert_int_equal(mpb__urdf_get_model(w, &m), MPB_OK);
    l5 = mpb_robot_link_index(m.robot, "panda_link5");
    l7 = mpb_robot_link_index(m.robot, "panda_link7");
    hand = mpb_robot_link_index(m.robot, "panda_hand");
    int seen7 = 0, seen_hand = 0;
    for (int i = 0; i < n; i++) {
        int near, far, jt[2];
        const mpb__wrist_table *t;
        mpb__wrist_stats st;
        assert_int_equal(mpb__urdf_wrist(w, i, &near, &far, jt, &t), MPB_OK);
        mpb__wrist_table_stats(t, &st);
        print_message("%s - %s: joints %d %d, %d cells (%d apart, %d to FCL), "
                      "%d distances, %.3f s CPU, grid %d bytes, R %.4f %.4f m\n",
                      mpb_robot_get_link(m.robot, near)->name,
                      mpb_robot_get_link(m.robot, far)->name, jt[0], jt[1],
                      st.nodes, st.apart_leaves, st.open_leaves, st.distances,
                      st.build_s, st.grid_bytes, st.lipschitz[0], st.lipschitz[1]);
        assert_true(st.apart_leaves > 0);
        if (near == l5 && far == l7 && jt[0] == 5 && jt[1] == 6)
            seen7 = 1;
        if (near == l5 && far == hand && jt[0] == 5 && jt[1] == 6)
            seen_hand = 1;
    }
    assert_true(seen7 && seen_hand);
    /* A second world takes the tables from the cache. */
    long builds = mpb__wrist_builds();
    OPEN_OR_SKIP(w2);
    assert_int_equal(mpb__urdf_num_wrists(w2), n);
    assert_int_equal(mpb__wrist_builds(), builds);
    mpb_world_close(w2);
    mpb_world_close(w);
}

/* Where a table says apart, FCL says so too; and it says so often. */
static void apart_means_apart(void **state)
{
    (void)state;
    OPEN_OR_SKIP(w);
    uint64_t x = 3;
    double q[NJ];
    for (int p = 0; p < mpb__urdf_num_wrists(w); p++) {
        int near, far, jt[2], apart = 0;
        const mpb__wrist_table *t;
        assert_int_equal(mpb__urdf_wrist(w, p, &near, &far, jt, &t), MPB_OK);
        for (int i = 0; i < 1000; i++) {
            random_state(w, &x, q);
            if (!mpb__wrist_table_apart(t, q[jt[0]], jt[1] >= 0 ? q[jt[1]] : 0))
                continue;
            apart++;
            assert_int_equal(pair_touches(w, p, q), 0);
        }
        assert_true(apart > 100);
        /* Outside the joints' range: FCL decides. */
        assert_false(mpb__wrist_table_apart(t, 1e3, 1e3));
        assert_false(mpb__wrist_table_apart(t, NAN, 0));
    }
    mpb_world_close(w);
}

static void verdicts_agree(void **state)
{
    (void)state;
    OPEN_OR_SKIP(w);
    assert_int_equal(disagreements(w, 2000, 30), 0);
    mpb_world_close(w);
}

/* R1 and R2 a tenth of what they are: cells near a contact are "proved"
 * apart, and the verdicts there go wrong. */
static void too_small_a_bound_is_caught(void **state)
{
    (void)state;
    mpb__wrist_set_params(MPB__WRIST_MIN_BOUND, 0.1);
    mpb_world *w = open_panda();
    mpb__wrist_set_params(MPB__WRIST_MIN_BOUND, 1.0);
    if (!w)
        skip();
    assert_true(disagreements(w, 0, 30) > 0);
    mpb_world_close(w);
}

/* Tables only where their FCL distances are cheap: by the product of
 * the two sides' triangles (a primitive counts 12). */
static void affordable_by_triangles(void **state)
{
    (void)state;
    mpb_mesh m[2] = {{0, 300, NULL, NULL}, {0, 200, NULL, NULL}};
    mpb_geometry g[2] = {{MPB_SHAPE_MESH, {0, 0, 0, 0}, &m[0]},
                         {MPB_SHAPE_MESH, {0, 0, 0, 0}, &m[1]}};
    mpb_pose id;
    mpb_pose_identity(&id);
    mpb__wrist_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.side[0] = (mpb__wrist_side){1, &g[0], &id};
    spec.side[1] = (mpb__wrist_side){1, &g[1], &id};
    assert_true(mpb__wrist_affordable(&spec));          /* the Panda's 60k */
    m[0].num_triangles = 578;
    m[1].num_triangles = 1176;                          /* a UR5 pair */
    assert_false(mpb__wrist_affordable(&spec));
    g[0] = (mpb_geometry){MPB_SHAPE_BOX, {0.1, 0.1, 0.1, 0}, NULL};
    m[1].num_triangles = (int)(MPB__WRIST_MAX_TRIANGLE_PAIRS / 12);
    assert_true(mpb__wrist_affordable(&spec));
    m[1].num_triangles++;
    assert_false(mpb__wrist_affordable(&spec));
}

/* A build out of budget leaves its cells to FCL: the tables exist, prove
 * nothing apart, and every verdict is still FCL's. */
static void a_build_out_of_budget_keeps_the_verdicts(void **state)
{
    (void)state;
    mpb__wrist_set_budget(0);
    mpb_world *w = open_panda();
    mpb__wrist_set_budget(MPB__WRIST_MAX_DISTANCES);
    if (!w)
        skip();
    assert_true(mpb__urdf_num_wrists(w) > 0);
    for (int i = 0; i < mpb__urdf_num_wrists(w); i++) {
        int near, far, jt[2];
        const mpb__wrist_table *t;
        mpb__wrist_stats st;
        assert_int_equal(mpb__urdf_wrist(w, i, &near, &far, jt, &t), MPB_OK);
        mpb__wrist_table_stats(t, &st);
        assert_int_equal(st.cut, 1);
        assert_int_equal(st.apart_leaves, 0);
    }
    assert_int_equal(disagreements(w, 300, 3), 0);
    mpb_world_close(w);
}

/* The PR2's arm of primitives: no pair qualifies, no table is built, and
 * the checks work as before. */
static void pr2_has_none(void **state)
{
    (void)state;
    const char *const pj[NJ] = {
        "r_shoulder_pan_joint", "r_shoulder_lift_joint",
        "r_upper_arm_roll_joint", "r_elbow_flex_joint", "r_forearm_roll_joint",
        "r_wrist_flex_joint", "r_wrist_roll_joint"};
    char *robot = test_read_file(SRC "/scenes/robots/pr2_right_arm.urdf");
    char *scene = test_read_file(SRC "/scenes/paper/kitchen.scene");
    mpb_world *w = NULL;
    char err[256];
    long builds = mpb__wrist_builds();
    int rc = mpb_world_open_group("urdf", robot, "moveit-scene", scene, pj, NJ,
                                  &w, err, sizeof err);
    free(robot);
    free(scene);
    if (rc != MPB_OK)
        fail_msg("%s", err);
    assert_int_equal(mpb__urdf_num_wrists(w), 0);
    assert_int_equal(mpb__wrist_builds(), builds);
    uint64_t x = 9;
    double q[NJ];
    int hits = 0;
    for (int i = 0; i < 200; i++) {
        random_state(w, &x, q);
        assert_int_equal(differs(w, q), 0);
        hits += mpb_world_in_collision(w, q);
    }
    assert_true(hits > 0 && hits < 200);
    mpb_world_close(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(panda_has_wrist_tables),
        cmocka_unit_test(apart_means_apart),
        cmocka_unit_test(verdicts_agree),
        cmocka_unit_test(too_small_a_bound_is_caught),
        cmocka_unit_test(affordable_by_triangles),
        cmocka_unit_test(a_build_out_of_budget_keeps_the_verdicts),
        cmocka_unit_test(pr2_has_none),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
