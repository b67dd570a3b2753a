/*
 * test_certify_rates.c - certified verification's motion bounds
 * (model/world_sweep.c) are upper bounds: on random straight joint-space
 * motions of the PR2 arm (primitives) and the Panda (meshes), no point of
 * a body moves faster than its rate, over the whole horizon the rate was
 * taken for, and no two bodies approach faster than their pair rate (each
 * body's speed seen from their common ancestor link, summed).
 *
 * The points: random points of each shape's bounding sphere that lie in
 * its capsule too (a mesh's), which hold the shape (collision_internal.h);
 * speeds by central differences of forward kinematics at 40 places of
 * the horizon. A bound computed as if the rate held everywhere (the
 * horizon ignored) or from the distance to the joint's origin along the
 * axis only would fail here: the motions are long (up to 3 rad a joint)
 * and the horizons short and long.
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
#include "model/world_urdf.h"
#include "test_files.h"
#include "test_panda.h"

#define MAX_IDS 64
#define POINTS 12               /* per shape */
#define PLACES 40               /* per horizon */

static const char *const pr2_joints[] = {
    "r_shoulder_pan_joint", "r_shoulder_lift_joint", "r_upper_arm_roll_joint",
    "r_elbow_flex_joint", "r_forearm_roll_joint", "r_wrist_flex_joint",
    "r_wrist_roll_joint"};

static mpb_world *open_pr2(void)
{
    char *urdf = test_read_robot(MPB_TEST_DATA "/pr2_right_arm.urdf",
                                 MPB_TEST_DATA "/pr2_right_arm.srdf");
    mpb_world *w = NULL;
    char err[256];
    int rc = mpb_world_open_group("urdf", urdf, "moveit-scene", "empty\n.\n", pr2_joints,
                                  7, &w, err, sizeof err);
    free(urdf);
    if (rc != MPB_OK)
        fail_msg("open: %s", err);
    return w;
}

static uint64_t rng = 12345;

static double uniform(double lo, double hi)
{
    rng = rng * 6364136223846793005ull + 1442695040888963407ull;
    return lo + (hi - lo) * (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

/* The squared distance from p to segment a b. */
static double seg_dist2(const double p[3], const double a[3], const double b[3])
{
    double ab[3], ap[3], t = 0, ll = 0;
    for (int k = 0; k < 3; k++) {
        ab[k] = b[k] - a[k];
        ap[k] = p[k] - a[k];
        t += ab[k] * ap[k];
        ll += ab[k] * ab[k];
    }
    t = ll > 0 ? fmin(1.0, fmax(0.0, t / ll)) : 0.0;
    double d2 = 0;
    for (int k = 0; k < 3; k++) {
        double e = ap[k] - t * ab[k];
        d2 += e * e;
    }
    return d2;
}

/* Points of body id (its frame): in a shape's sphere and capsule. */
static int body_points(mpb_collision *c, int id, double (*pts)[3], int max)
{
    mpb__body_bound b[16];
    int ns = mpb__collision_body_bounds(c, id, b, 16), n = 0;
    assert_true(ns >= 0 && ns <= 16);
    for (int k = 0; k < ns; k++)
        for (int tries = 0, got = 0; got < POINTS && tries < 4000 && n < max; tries++) {
            /* on the sphere's surface half of the time: the far points */
            double u[3], uu = 0;
            for (int i = 0; i < 3; i++) {
                u[i] = uniform(-1, 1);
                uu += u[i] * u[i];
            }
            if (uu > 1 || uu < 1e-6)
                continue;
            double scale = got % 2 ? 1.0 / sqrt(uu) : 1.0;
            double p[3];
            for (int i = 0; i < 3; i++)
                p[i] = b[k].centre[i] + b[k].radius * scale * u[i];
            if (b[k].cap_radius >= 0 &&
                seg_dist2(p, b[k].cap[0], b[k].cap[1]) > b[k].cap_radius * b[k].cap_radius)
                continue;
            memcpy(pts[n++], p, sizeof p);
            got++;
        }
    return n;
}

/* Point x of link l's frame in the frame of link f (-1: the robot's) at
 * configuration q. */
static void point_at(const mpb_robot *r, const double *q, int l, int f,
                     const double x[3], double out[3])
{
    mpb_pose pl, pf;
    assert_int_equal(mpb_robot_link_pose(r, q, l, &pl), MPB_OK);
    double y[3];
    mpb_pose_apply(&pl, x, y);
    if (f < 0) {
        memcpy(out, y, sizeof y);
        return;
    }
    assert_int_equal(mpb_robot_link_pose(r, q, f, &pf), MPB_OK);
    double t[3] = { y[0] - pf.t[0], y[1] - pf.t[1], y[2] - pf.t[2] };
    for (int i = 0; i < 3; i++)     /* R^T t */
        out[i] = pf.R[i] * t[0] + pf.R[3 + i] * t[1] + pf.R[6 + i] * t[2];
}

/* The largest speed (m per unit s) of body id's points seen from link f,
 * over s in [0, h] of q0 + s d. */
static double max_speed(const mpb_robot *r, int nj, const double *q0,
                        const double *d, double h, int l, int f,
                        double (*pts)[3], int np)
{
    const double eps = 1e-6;
    double best = 0, qa[16], qb[16];
    for (int k = 0; k <= PLACES; k++) {
        double s = h * k / PLACES;
        for (int j = 0; j < nj; j++) {
            qa[j] = q0[j] + (s - eps) * d[j];
            qb[j] = q0[j] + (s + eps) * d[j];
        }
        for (int i = 0; i < np; i++) {
            double xa[3], xb[3];
            point_at(r, qa, l, f, pts[i], xa);
            point_at(r, qb, l, f, pts[i], xb);
            double v = sqrt((xb[0] - xa[0]) * (xb[0] - xa[0]) +
                            (xb[1] - xa[1]) * (xb[1] - xa[1]) +
                            (xb[2] - xa[2]) * (xb[2] - xa[2])) / (2 * eps);
            best = fmax(best, v);
        }
    }
    return best;
}

/* The lowest link above both a and b. */
static int common(const mpb_robot *r, int a, int b)
{
    for (int x = a; x >= 0; x = mpb_robot_get_link(r, x)->parent)
        for (int y = b; y >= 0; y = mpb_robot_get_link(r, y)->parent)
            if (x == y)
                return x;
    return -1;
}

static void check_world(mpb_world *w, int motions)
{
    urdf_world *u = w->impl;
    const mpb_robot *r = u->robot;
    int nj = mpb_world_num_joints(w), ids = u->num_links;
    assert_true(nj <= 16 && ids <= MAX_IDS);
    assert_int_equal(mpb_robot_num_joints(r), nj);  /* q is the robot's */
    static double pts[MAX_IDS][16 * POINTS][3];
    int np[MAX_IDS] = { 0 };
    for (int id = 0; id < ids; id++)
        if (has_body(u, id))
            np[id] = body_points(u->coll, id, pts[id], 16 * POINTS);
    double lo[16], hi[16];
    for (int j = 0; j < nj; j++)
        mpb_world_joint_limits(w, j, &lo[j], &hi[j]);
    static double rate[MAX_IDS], pair[MAX_IDS * MAX_IDS];
    int tight = 0, checked = 0;
    for (int m = 0; m < motions; m++) {
        double q0[16], d[16];
        double span = m % 3 == 0 ? 3.0 : m % 3 == 1 ? 0.5 : 0.05;
        for (int j = 0; j < nj; j++) {
            q0[j] = uniform(fmax(lo[j], -3), fmin(hi[j], 3));
            d[j] = uniform(-span, span);
        }
        double h = m % 2 ? 1.0 : uniform(0.01, 0.5);
        assert_int_equal(mpb__urdf_rates(w, q0, d, h, rate, pair, ids), MPB_OK);
        double speed[MAX_IDS];
        for (int id = 0; id < ids; id++) {
            if (np[id] == 0)
                continue;
            speed[id] = max_speed(r, nj, q0, d, h, id, -1, pts[id], np[id]);
            if (speed[id] > rate[id] * (1 + 1e-6) + 1e-9)
                fail_msg("motion %d: link %d moves at %.9g > its rate %.9g", m, id,
                         speed[id], rate[id]);
            checked++;
            tight += speed[id] > 0.5 * rate[id];
        }
        for (int a = 0; a < ids; a++)
            for (int b = a + 1; b < ids && m % 4 == 0; b++) {
                if (np[a] == 0 || np[b] == 0)
                    continue;
                int c = common(r, a, b);
                double va = max_speed(r, nj, q0, d, h, a, c, pts[a], np[a]);
                double vb = max_speed(r, nj, q0, d, h, b, c, pts[b], np[b]);
                double pr = pair[(size_t)a * (size_t)ids + (size_t)b];
                if (va + vb > pr * (1 + 1e-6) + 1e-9)
                    fail_msg("motion %d: links %d and %d approach at %.9g > "
                             "their rate %.9g", m, a, b, va + vb, pr);
            }
    }
    /* the check can tell: many bounds are within 2x of the truth */
    assert_true(checked > 0 && tight * 4 > checked);
}

static void pr2_rates_are_upper_bounds(void **state)
{
    (void)state;
    mpb_world *w = open_pr2();
    check_world(w, 40);
    mpb_world_close(w);
}

static void panda_rates_are_upper_bounds(void **state)
{
    (void)state;
    mpb_world *w = test_open_panda("empty\n.\n");
    if (!w)
        skip();
    check_world(w, 24);
    mpb_world_close(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(pr2_rates_are_upper_bounds),
        cmocka_unit_test(panda_rates_are_upper_bounds),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
