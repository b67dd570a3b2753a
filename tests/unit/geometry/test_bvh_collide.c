/*
 * test_bvh_collide.c - the collision world's own test of two meshes
 * (bvh_collide.cpp: a traversal of FCL's trees that drops a node pair only
 * when its boxes are apart by a margin, and FCL's triangle test) against
 * fcl::collide, on every pair of the Panda's collision meshes (fetched by
 * tools/robot_data.sh; skipped without them): random relative poses,
 * poses found by bisection within ~1e-15 m of a contact and a few offsets
 * from there up to beyond the margin, and deep penetrations, a mesh on
 * itself included. Any verdict that differs fails.
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
#include "geometry/collision_internal.h"
#include "model/world_provider.h"
#include "test_files.h"
#include "test_panda.h"


/* The Panda alone, or NULL when its data is not fetched. */
static mpb_world *open_panda(void)
{
    return test_open_panda("workspace\n.\n");
}

#define OPEN_OR_SKIP(w, c, n)                                                 \
    mpb_world *w = open_panda();                                              \
    if (!w) {                                                                 \
        print_message("Panda data not fetched (tools/robot_data.sh): "      \
                      "skipped\n");                                           \
        skip();                                                               \
    }                                                                         \
    mpb_collision *c = mpb__urdf_collision(w);                                \
    int n = mpb__collision_num_movable_shapes(c);                              \
    assert_true(n >= 10)

/* Uniform in [0, 1), from a 64-bit LCG. */
static double rnd(uint64_t *x)
{
    *x = *x * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*x >> 11) / 9007199254740992.0;
}

/* A uniformly random rotation, translation uniform in [-half, half]^3. */
static void random_pose(uint64_t *x, double half, mpb_pose *p)
{
    const double tau = 6.283185307179586;
    double u1 = rnd(x), u2 = rnd(x), u3 = rnd(x);
    double a = sqrt(1 - u1), b = sqrt(u1);
    assert_int_equal(mpb_pose_set_quat(p, a * sin(tau * u2), a * cos(tau * u2),
                                       b * sin(tau * u3), b * cos(tau * u3)),
                     MPB_OK);
    for (int k = 0; k < 3; k++)
        p->t[k] = half * (2 * rnd(x) - 1);
}

/* The verdict of both tests on shapes a at pa and b at pb, which must
 * agree; returns it. */
static int agree(mpb_collision *c, int a, const mpb_pose *pa, int b,
                 const mpb_pose *pb)
{
    int fast = mpb__mesh_pair_collide(c, a, pa, b, pb, 0);
    int ref = mpb__mesh_pair_collide(c, a, pa, b, pb, 1);
    assert_true(ref == 0 || ref == 1);
    if (fast != ref)
        fail_msg("shapes %d and %d: traversal %d, fcl::collide %d; b at "
                 "%.17g %.17g %.17g", a, b, fast, ref, pb->t[0], pb->t[1],
                 pb->t[2]);
    return ref;
}

/* pb moved by s along unit direction u. */
static mpb_pose moved(const mpb_pose *pb, const double u[3], double s)
{
    mpb_pose p = *pb;
    for (int k = 0; k < 3; k++)
        p.t[k] += s * u[k];
    return p;
}

static void random_poses_agree(void **state)
{
    (void)state;
    OPEN_OR_SKIP(w, c, n);
    uint64_t x = 27;
    long hits = 0, total = 0;
    for (int a = 0; a < n; a++)
        for (int b = a; b < n; b++)
            for (int i = 0; i < 200; i++) {
                mpb_pose pa, pb;
                random_pose(&x, 0.02, &pa);
                random_pose(&x, 0.2, &pb);
                hits += agree(c, a, &pa, b, &pb);
                total++;
            }
    print_message("%ld of %ld random poses collide\n", hits, total);
    assert_true(hits > total / 10 && hits < total * 9 / 10);
    mpb_world_close(w);
}

/*
 * From colliding poses, b moved away along a random direction until free,
 * then the contact found by bisection (both tests agreeing at every step):
 * the last colliding and first free offsets, within ~1e-15 m, and offsets
 * from 1e-9 m to twice the traversal's margin (1e-4 m) on either side.
 */
static void contact_poses_agree(void **state)
{
    (void)state;
    OPEN_OR_SKIP(w, c, n);
    uint64_t x = 1027;
    const double off[] = {1e-12, 1e-9, 1e-7, 1e-5, 5e-5, 1e-4, 2e-4};
    int contacts = 0;
    for (int a = 0; a < n; a++)
        for (int b = a; b < n; b++)
            for (int tries = 0, found = 0; tries < 100 && found < 3; tries++) {
                mpb_pose pa, pb;
                random_pose(&x, 0.02, &pa);
                random_pose(&x, 0.15, &pb);
                if (!agree(c, a, &pa, b, &pb))
                    continue;
                double u[3], norm = 0;
                for (int k = 0; k < 3; k++) {
                    u[k] = 2 * rnd(&x) - 1;
                    norm += u[k] * u[k];
                }
                norm = sqrt(norm);
                for (int k = 0; k < 3; k++)
                    u[k] /= norm;
                double lo = 0, hi = 2;      /* colliding at lo, free at hi */
                mpb_pose far = moved(&pb, u, hi);
                assert_int_equal(agree(c, a, &pa, b, &far), 0);
                while (hi - lo > 1e-15) {
                    double mid = 0.5 * (lo + hi);
                    if (mid <= lo || mid >= hi)
                        break;
                    mpb_pose pm = moved(&pb, u, mid);
                    if (agree(c, a, &pa, b, &pm))
                        lo = mid;
                    else
                        hi = mid;
                }
                for (size_t i = 0; i < sizeof off / sizeof off[0]; i++) {
                    mpb_pose p1 = moved(&pb, u, lo - off[i]);
                    mpb_pose p2 = moved(&pb, u, hi + off[i]);
                    agree(c, a, &pa, b, &p1);
                    agree(c, a, &pa, b, &p2);
                }
                found++;
                contacts++;
            }
    print_message("%d contacts\n", contacts);
    assert_true(contacts > 100);
    mpb_world_close(w);
}

/* Meshes deep in each other: the same pose, then small moves and turns. */
static void deep_poses_agree(void **state)
{
    (void)state;
    OPEN_OR_SKIP(w, c, n);
    uint64_t x = 2027;
    long hits = 0, total = 0;
    for (int a = 0; a < n; a++)
        for (int b = a; b < n; b++) {
            mpb_pose pa;
            random_pose(&x, 0.02, &pa);
            hits += agree(c, a, &pa, b, &pa);
            total++;
            for (int i = 0; i < 30; i++) {
                mpb_pose turn, pb;
                double s = 0.02 * rnd(&x), ang = 0.05 * rnd(&x);
                mpb_pose_set_rpy(&turn, ang * (2 * rnd(&x) - 1),
                                 ang * (2 * rnd(&x) - 1), ang * (2 * rnd(&x) - 1));
                for (int k = 0; k < 3; k++)
                    turn.t[k] = s * (2 * rnd(&x) - 1);
                mpb_pose_mul(&pa, &turn, &pb);
                hits += agree(c, a, &pa, b, &pb);
                total++;
            }
        }
    print_message("%ld of %ld deep poses collide\n", hits, total);
    assert_true(hits > total / 2);
    mpb_world_close(w);
}

/* Only meshes are answered; bad arguments are refused. */
static void arguments_checked(void **state)
{
    (void)state;
    OPEN_OR_SKIP(w, c, n);
    mpb_pose p;
    mpb_pose_identity(&p);
    assert_int_equal(mpb__mesh_pair_collide(c, 0, &p, n, &p, 0), MPB_EINVAL);
    assert_int_equal(mpb__mesh_pair_collide(c, -1, &p, 0, &p, 1), MPB_EINVAL);
    assert_int_equal(mpb__mesh_pair_collide(c, 0, NULL, 0, &p, 0), MPB_EINVAL);
    p.t[0] = NAN;
    assert_int_equal(mpb__mesh_pair_collide(c, 0, &p, 0, &p, 0), MPB_EINVAL);
    mpb_world_close(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(random_poses_agree),
        cmocka_unit_test(contact_poses_agree),
        cmocka_unit_test(deep_poses_agree),
        cmocka_unit_test(arguments_checked),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
