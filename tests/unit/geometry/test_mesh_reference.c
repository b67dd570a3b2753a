/*
 * test_mesh_reference.c - the fast queries of the collision world on a
 * robot made of meshes, against references that put every pair through
 * FCL's narrow phase (collision_internal.h): the Panda with its SRDF and
 * collision meshes (tools/robot_data.sh; skipped when they are not
 * fetched) among boxes, cylinders and a mesh, at a few thousand
 * fixed-seed random states, at states within 1e-9 rad of a contact and
 * along fine paths. Whatever skips a pair before FCL (the allowed-collision
 * matrix, boxes, spheres, the capsules around meshes, planes between
 * vertex sets, the best-first order of the distance query) and the
 * traversal that replaces FCL's for mesh pairs (bvh_collide.cpp; compared
 * pair by pair in test_bvh_collide.c) must not change a verdict: a wrong
 * skip fails here. Clearances the same to 1e-9 m. The mesh extents
 * those planes use are the same to the bit as over every vertex.
 */
#include <limits.h>
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
#include "geometry/collision_internal.h"
#include "model/world_provider.h"
#include "test_files.h"
#include "test_panda.h"

#define NJ 7

/* A table, a shelf with two boards, a can and an octahedron mesh, in
 * reach of the arm: about half the random states touch something. */
static const char scene_text[] =
    "workspace\n"
    "* table\n0.55 0 -0.03\n0 0 0 1\n1\nbox\n0.7 1.2 0.06\n0 0 0\n0 0 0 1\n"
    "0 0 0 0\n0\n"
    "* shelf\n0.75 0 0.45\n0 0 0.2588 0.9659\n3\n"
    "box\n0.3 0.8 0.02\n0 0 -0.2\n0 0 0 1\n0 0 0 0\n"
    "box\n0.3 0.8 0.02\n0 0 0.2\n0 0 0 1\n0 0 0 0\n"
    "box\n0.3 0.02 0.5\n0 0.4 0\n0 0 0 1\n0 0 0 0\n0\n"
    "* can\n0.4 -0.35 0.1\n0 0 0 1\n1\ncylinder\n0.04 0.2\n0 0 0\n0 0 0 1\n"
    "0 0 0 0\n0\n"
    "* gem\n0.3 0.45 0.5\n0.1 0.2 0.3 0.927\n1\nmesh\n6 8\n"
    "0.1 0 0\n-0.1 0 0\n0 0.1 0\n0 -0.1 0\n0 0 0.15\n0 0 -0.15\n"
    "0 2 4\n2 1 4\n1 3 4\n3 0 4\n2 0 5\n1 2 5\n3 1 5\n0 3 5\n"
    "0 0 0\n0 0 0 1\n0 0 0 0\n0\n"
    ".\n";

static mpb_world *open_panda(void)
{
    return test_open_panda(scene_text);
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

/* The fast verdict at q (collision, and contact's), checked against the
 * reference; returns it. */
static int agree_collision(mpb_world *w, const double *q)
{
    char what[256];
    int fast = mpb_world_in_collision(w, q);    /* places the robot */
    int ref = mpb__collision_check_brute(mpb__urdf_collision(w));
    /* A contact of either kind (MPB_CONTACT_SCENE or _SELF). */
    int named = mpb_world_contact(w, q, what, sizeof what) > 0;
    assert_true(fast == 0 || fast == 1);
    assert_true(ref == 0 || ref == 1);
    if (fast != ref || named != ref)
        fail_msg("in_collision %d, contact %d, reference %d at %g %g %g %g "
                 "%g %g %g", fast, named, ref, q[0], q[1], q[2], q[3], q[4],
                 q[5], q[6]);
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
    OPEN_OR_SKIP(w);
    uint64_t x = 7;
    double q[NJ];
    int hits = 0;
    for (int i = 0; i < 3000; i++) {
        random_state(w, &x, q);
        hits += agree_collision(w, q);
        if (i % 10 == 0)        /* the reference distance is slow */
            agree_clearance(w, q);
    }
    /* both verdicts are exercised */
    assert_true(hits > 300 && hits < 2700);
    mpb_world_close(w);
}

/* Between a free state and a colliding one, bisected to 1e-9 rad apart:
 * states on either side of a first contact, the self-contacts included. */
static void states_at_contact_agree(void **state)
{
    (void)state;
    OPEN_OR_SKIP(w);
    uint64_t x = 11;
    double a[NJ], b[NJ], m[NJ];
    for (int pairs = 0; pairs < 40;) {
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
        }
        agree_clearance(w, m);
        pairs++;
    }
    mpb_world_close(w);
}

/* Fine paths, as verification and the clearance metric walk them: the
 * distance query starts from the last nearest pair. */
static void fine_paths_agree(void **state)
{
    (void)state;
    OPEN_OR_SKIP(w);
    uint64_t x = 13;
    double a[NJ], b[NJ], q[NJ];
    for (int path = 0; path < 10; path++) {
        random_state(w, &x, a);
        random_state(w, &x, b);
        for (int k = 0; k <= 50; k++) {
            for (int j = 0; j < NJ; j++)
                q[j] = a[j] + (k / 50.0) * (b[j] - a[j]);
            agree_collision(w, q);
            agree_clearance(w, q);
        }
    }
    mpb_world_close(w);
}

/* The extents the mesh shortcuts rest on (the hull's vertices, a few of
 * them by direction): along random directions, short and long, and
 * along axes, the same to the bit as over every vertex. */
static void mesh_extents_exact(void **state)
{
    (void)state;
    OPEN_OR_SKIP(w);
    mpb_collision *c = mpb__urdf_collision(w);
    uint64_t x = 17;
    double q[NJ];
    int meshes = 0;
    for (int i = 0; i < 300; i++) {
        random_state(w, &x, q);
        mpb_world_in_collision(w, q);           /* places the robot */
        int n = mpb__collision_num_movable_shapes(c);
        for (int s = 0; s < n; s++) {
            for (int k = 0; k < 40; k++) {
                double d[3], fast, all;
                for (int j = 0; j < 3; j++)
                    d[j] = (rnd(&x) - 0.5) * (k % 2 ? 1e-3 : 2.0);
                if (k % 8 == 0)                 /* along an axis */
                    d[(k / 8) % 3] = 0, d[(k / 8 + 1) % 3] = 0;
                if (mpb__collision_mesh_reach(c, s, d, &fast, &all) != MPB_OK)
                    break;
                meshes += k == 0;
                if (fast != all)
                    fail_msg("shape %d: reach %.17g, over every vertex %.17g",
                             s, fast, all);
            }
        }
    }
    assert_true(meshes >= 300 * 8);             /* the links' meshes */
    mpb_world_close(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(mesh_extents_exact),
        cmocka_unit_test(random_states_agree),
        cmocka_unit_test(states_at_contact_agree),
        cmocka_unit_test(fine_paths_agree),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
