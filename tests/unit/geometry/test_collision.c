/*
 * test_collision.c - the FCL collision world: distances against closed
 * forms (sphere to box in its face, edge and corner regions, capsules and
 * cylinders beside a box, a sphere above a plane), a triangle-mesh box that
 * collides exactly where its primitive twin does, bodies of several shapes,
 * allowed pairs, enabling, errors, and the time of a query for a 7-link arm
 * among 20 boxes (printed, not asserted).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "mpbench/collision.h"
#include "geometry/collision_internal.h"
#include "mpbench/mesh.h"
#include "mpbench/pose.h"
#include "geometry/mesh.h"

#define assert_near(a, b, eps)                                              \
    do {                                                                    \
        double a_ = (a), b_ = (b);                                          \
        if (!(fabs(a_ - b_) <= (eps)))                                      \
            fail_msg("%s = %.17g, expected %.17g (line %d)", #a, a_, b_,    \
                     __LINE__);                                             \
    } while (0)

/* ---- helpers ------------------------------------------------------------ */

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;

static double uniform(double lo, double hi)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return lo + (hi - lo) * (double)(rng_state >> 11) / 9007199254740992.0;
}

static mpb_pose random_pose(double spread)
{
    mpb_pose p;
    mpb_pose_set_quat(&p, uniform(-1, 1), uniform(-1, 1), uniform(-1, 1),
                      uniform(-1, 1));
    for (int i = 0; i < 3; i++)
        p.t[i] = uniform(-spread, spread);
    return p;
}

static mpb_pose at(double x, double y, double z)
{
    mpb_pose p;
    mpb_pose_identity(&p);
    p.t[0] = x;
    p.t[1] = y;
    p.t[2] = z;
    return p;
}

static mpb_geometry box(double x, double y, double z)
{
    mpb_geometry g = { .type = MPB_SHAPE_BOX, .dims = { x, y, z } };
    return g;
}

static mpb_geometry sphere(double r)
{
    mpb_geometry g = { .type = MPB_SHAPE_SPHERE, .dims = { r } };
    return g;
}

static mpb_geometry capsule(double r, double l)
{
    mpb_geometry g = { .type = MPB_SHAPE_CAPSULE, .dims = { r, l } };
    return g;
}

static mpb_geometry cylinder(double r, double l)
{
    mpb_geometry g = { .type = MPB_SHAPE_CYLINDER, .dims = { r, l } };
    return g;
}

/* A closed box of half sizes h as 8 vertices and 12 outward triangles. */
static mpb_mesh *box_mesh(const double h[3])
{
    static const int tri[12][3] = {
        { 0, 2, 1 }, { 0, 3, 2 },   /* z- */
        { 4, 5, 6 }, { 4, 6, 7 },   /* z+ */
        { 0, 1, 5 }, { 0, 5, 4 },   /* y- */
        { 3, 7, 6 }, { 3, 6, 2 },   /* y+ */
        { 0, 4, 7 }, { 0, 7, 3 },   /* x- */
        { 1, 2, 6 }, { 1, 6, 5 },   /* x+ */
    };
    mpb_mesh *m = mpb__mesh_create(8, 12);
    assert_non_null(m);
    for (int i = 0; i < 8; i++) {
        int bits[3] = { (i == 1 || i == 2 || i == 5 || i == 6),
                        (i == 2 || i == 3 || i == 6 || i == 7), i >= 4 };
        for (int k = 0; k < 3; k++)
            m->vertices[3 * i + k] = bits[k] ? h[k] : -h[k];
    }
    for (int t = 0; t < 12; t++)
        for (int k = 0; k < 3; k++)
            m->triangles[3 * t + k] = tri[t][k];
    return m;
}

/*
 * Signed distance from point p (box frame) to the box of half sizes h:
 * positive outside, minus the depth inside. Also the nearest point of the
 * surface's closure for an outside p.
 */
static double box_sd(const double h[3], const double p[3], double near[3])
{
    double out2 = 0, inside = -INFINITY;
    for (int k = 0; k < 3; k++) {
        double q = fabs(p[k]) - h[k];
        if (q > 0)
            out2 += q * q;
        if (q > inside)
            inside = q;
        if (near)
            near[k] = fmax(-h[k], fmin(h[k], p[k]));
    }
    return out2 > 0 ? sqrt(out2) : inside;
}

static mpb_collision *new_world(void)
{
    mpb_collision *c = NULL;
    assert_int_equal(mpb_collision_create(&c), MPB_OK);
    assert_non_null(c);
    return c;
}

static void ok(mpb_collision *c, int rc)
{
    if (rc != MPB_OK)
        fail_msg("%s: %s", mpb_err_name(rc), mpb_collision_errmsg(c));
}

static double distance_of(mpb_collision *c, mpb_collision_distance_result *r)
{
    mpb_collision_distance_result tmp;
    if (!r)
        r = &tmp;
    ok(c, mpb_collision_distance(c, 1, r));
    return r->distance;
}

/* ---- pose.h ------------------------------------------------------------- */

static void test_pose_helpers(void **state)
{
    (void)state;
    /* URDF rpy: yaw 90 degrees turns x into y; pitch 90 turns x into -z */
    mpb_pose p;
    mpb_pose_identity(&p);
    double x[3] = { 1, 0, 0 }, y[3];
    mpb_pose_set_rpy(&p, 0, 0, M_PI / 2);
    mpb_pose_apply(&p, x, y);
    assert_near(y[0], 0, 1e-15);
    assert_near(y[1], 1, 1e-15);
    mpb_pose_set_rpy(&p, 0, M_PI / 2, 0);
    mpb_pose_apply(&p, x, y);
    assert_near(y[2], -1, 1e-15);
    /* the same rotation as a quaternion: 90 degrees about y */
    mpb_pose q;
    mpb_pose_identity(&q);
    assert_int_equal(mpb_pose_set_quat(&q, 0, sin(M_PI / 4), 0, cos(M_PI / 4)), 0);
    for (int i = 0; i < 9; i++)
        assert_near(q.R[i], p.R[i], 1e-15);
    assert_int_equal(mpb_pose_set_quat(&q, 0, 0, 0, 0), -1);
    assert_int_equal(mpb_pose_set_quat(&q, NAN, 0, 0, 1), -1);
    assert_true(mpb_pose_is_rigid(&q));     /* the identity, then */
    /* round trips over random rotations */
    for (int n = 0; n < 1000; n++) {
        mpb_pose a = random_pose(2), b = random_pose(2), ab, back, inv;
        assert_true(mpb_pose_is_rigid(&a));
        double quat[4], rpy[3];
        mpb_pose_get_quat(&a, quat);
        assert_true(quat[3] >= 0);
        mpb_pose_identity(&back);
        mpb_pose_set_quat(&back, quat[0], quat[1], quat[2], quat[3]);
        for (int i = 0; i < 9; i++)
            assert_near(back.R[i], a.R[i], 1e-12);
        mpb_pose_get_rpy(&a, rpy);
        mpb_pose_set_rpy(&back, rpy[0], rpy[1], rpy[2]);
        for (int i = 0; i < 9; i++)
            assert_near(back.R[i], a.R[i], 1e-12);
        /* (a b) b^-1 = a; a^-1 a = identity */
        mpb_pose_mul(&a, &b, &ab);
        mpb_pose_inverse(&b, &inv);
        mpb_pose_mul(&ab, &inv, &back);
        for (int i = 0; i < 9; i++)
            assert_near(back.R[i], a.R[i], 1e-12);
        for (int i = 0; i < 3; i++)
            assert_near(back.t[i], a.t[i], 1e-12);
        mpb_pose_inverse(&a, &inv);
        mpb_pose_mul(&inv, &a, &inv);       /* out aliasing a factor */
        for (int i = 0; i < 9; i++)
            assert_near(inv.R[i], i % 4 == 0, 1e-12);
    }
    /* gimbal lock: pitch +-90 degrees keeps the rotation */
    for (int sgn = -1; sgn <= 1; sgn += 2) {
        double rpy[3];
        mpb_pose_set_rpy(&p, 0.3, sgn * M_PI / 2, -0.4);
        mpb_pose_get_rpy(&p, rpy);
        mpb_pose_set_rpy(&q, rpy[0], rpy[1], rpy[2]);
        assert_near(rpy[2], 0, 0);
        for (int i = 0; i < 9; i++)
            assert_near(q.R[i], p.R[i], 1e-12);
    }
    p.R[0] = 1.01;
    assert_false(mpb_pose_is_rigid(&p));
    mpb_pose_identity(&p);
    p.R[0] = p.R[4] = -1;       /* a reflection pair is a rotation (z 180) */
    assert_true(mpb_pose_is_rigid(&p));
    p.R[8] = -1;                /* det -1: a reflection */
    assert_false(mpb_pose_is_rigid(&p));
}

/* ---- closed forms ------------------------------------------------------- */

/*
 * A sphere of radius r around a box of half sizes h at a random pose: the
 * distance is |max(|p| - h, 0)| - r in the box frame, with the nearest
 * points the clamp of p onto the box and the point of the sphere towards
 * it. Placements are drawn in each Voronoi region: face (one coordinate
 * outside), edge (two), corner (three).
 */
static void test_sphere_box_distance(void **state)
{
    (void)state;
    const double h[3] = { 0.3, 0.2, 0.5 }, r = 0.07;
    int regions[4] = { 0 };
    for (int trial = 0; trial < 300; trial++) {
        mpb_pose bp = random_pose(1.0);
        mpb_collision *c = new_world();
        mpb_geometry b = box(2 * h[0], 2 * h[1], 2 * h[2]), s = sphere(r);
        ok(c, mpb_collision_add_static(c, 7, &b, &bp));
        ok(c, mpb_collision_add_movable(c, 3, &s, NULL));

        /* A centre in the box frame: k coordinates outside the box, the
           axes first .. first+k-1 (mod 3). */
        int k = 1 + trial % 3, first = (trial / 3) % 3;
        double p[3];
        for (int i = 0; i < 3; i++) {
            double side = uniform(0, 1) < 0.5 ? -1 : 1;
            p[i] = (i - first + 3) % 3 < k ? side * (h[i] + uniform(0.001, 0.4))
                                           : uniform(-h[i] * 0.99, h[i] * 0.99);
        }
        double near[3];
        double sd = box_sd(h, p, near);
        int outside = 0;
        for (int i = 0; i < 3; i++)
            outside += fabs(p[i]) > h[i];
        regions[outside]++;
        double expected = fmax(sd - r, 0.0);

        mpb_pose sp = bp;           /* sphere centre in the world */
        mpb_pose_apply(&bp, p, sp.t);
        ok(c, mpb_collision_set_pose(c, 3, &sp));
        mpb_collision_distance_result res;
        assert_near(distance_of(c, &res), expected, 1e-9);
        assert_int_equal(res.movable, 3);
        assert_int_equal(res.static_id, 7);
        int m = -2, st = -2;
        int hit = mpb_collision_check(c, &m, &st);
        assert_int_equal(hit, sd - r <= 0 ? 1 : 0);
        if (hit) {
            assert_int_equal(m, 3);
            assert_int_equal(st, 7);
        } else {
            assert_int_equal(m, -1);
            assert_int_equal(st, -1);
        }
        if (sd > r) {               /* nearest points, world frame */
            double nb[3], ns[3], dir[3], len = 0;
            mpb_pose_apply(&bp, near, nb);
            for (int i = 0; i < 3; i++) {
                dir[i] = nb[i] - sp.t[i];
                len += dir[i] * dir[i];
            }
            len = sqrt(len);
            for (int i = 0; i < 3; i++)
                ns[i] = sp.t[i] + r * dir[i] / len;
            for (int i = 0; i < 3; i++) {
                assert_near(res.point_static[i], nb[i], 1e-9);
                assert_near(res.point_movable[i], ns[i], 1e-9);
            }
        }
        mpb_collision_destroy(c);
    }
    assert_true(regions[1] > 50 && regions[2] > 50 && regions[3] > 50);

    /* Inside the box, and touching within 1e-12: distance 0, a collision. */
    mpb_collision *c = new_world();
    mpb_geometry b = box(2 * h[0], 2 * h[1], 2 * h[2]), s = sphere(r);
    ok(c, mpb_collision_add_static(c, 0, &b, NULL));
    ok(c, mpb_collision_add_movable(c, 0, &s, NULL));
    mpb_pose p = at(0.1, 0, 0);
    ok(c, mpb_collision_set_pose(c, 0, &p));
    assert_near(distance_of(c, NULL), 0.0, 0);
    assert_int_equal(mpb_collision_check(c, NULL, NULL), 1);
    p = at(h[0] + r + 1e-3, 0, 0);
    ok(c, mpb_collision_set_pose(c, 0, &p));
    assert_near(distance_of(c, NULL), 1e-3, 1e-12);
    assert_int_equal(mpb_collision_check(c, NULL, NULL), 0);
    mpb_collision_destroy(c);
}

/*
 * Robot-like links beside a box of half sizes (0.5, 0.5, 0.5) at the
 * origin: a capsule or cylinder standing along z at x = 0.5 + r + g has
 * distance g (the side faces are parallel); a capsule lying along x above
 * the top face at height 0.5 + r + g too; a capsule whose lower sphere
 * centre sits diagonally off a top corner at (0.5 + e, 0.5 + e, 0.5 + e)
 * has distance sqrt(3) e - r. These pairs go through GJK: 1e-6.
 */
static void test_links_beside_box(void **state)
{
    (void)state;
    const double r = 0.05, len = 0.4;
    mpb_collision *c = new_world();
    mpb_geometry b = box(1, 1, 1);
    ok(c, mpb_collision_add_static(c, 1, &b, NULL));
    mpb_geometry cap = capsule(r, len), cyl = cylinder(r, len);
    ok(c, mpb_collision_add_movable(c, 10, &cap, NULL));
    ok(c, mpb_collision_add_movable(c, 11, &cyl, NULL));

    const double gaps[] = { 0.2, 0.03, 1e-3 };
    for (int i = 0; i < 3; i++) {
        double g = gaps[i];
        mpb_pose p = at(0.5 + r + g, 0.1, 0.2);
        ok(c, mpb_collision_set_pose(c, 10, &p));
        ok(c, mpb_collision_set_enabled(c, 11, 0));
        assert_near(distance_of(c, NULL), g, 1e-6);
        ok(c, mpb_collision_set_enabled(c, 10, 0));
        ok(c, mpb_collision_set_enabled(c, 11, 1));
        ok(c, mpb_collision_set_pose(c, 11, &p));
        assert_near(distance_of(c, NULL), g, 1e-6);
        ok(c, mpb_collision_set_enabled(c, 10, 1));

        /* lying along x over the top face */
        mpb_pose lying;
        mpb_pose_identity(&lying);
        mpb_pose_set_rpy(&lying, 0, M_PI / 2, 0);
        lying.t[0] = 0.1;
        lying.t[2] = 0.5 + r + g;
        ok(c, mpb_collision_set_pose(c, 10, &lying));
        p = at(5, 5, 5);
        ok(c, mpb_collision_set_pose(c, 11, &p));
        mpb_collision_distance_result res;
        assert_near(distance_of(c, &res), g, 1e-6);
        assert_int_equal(res.movable, 10);
        assert_int_equal(mpb_collision_check(c, NULL, NULL), 0);

        /* diagonally off a corner: the capsule points along (1,1,1) */
        double e = g + r / sqrt(3.0);
        mpb_pose diag;
        double ax[3] = { 1 / sqrt(3.0), 1 / sqrt(3.0), 1 / sqrt(3.0) };
        /* rotation taking z to ax: about (z x ax) by acos(ax.z) */
        double kx = -ax[1], ky = ax[0], kn = sqrt(kx * kx + ky * ky);
        double th = acos(ax[2]);
        mpb_pose_set_quat(&diag, kx / kn * sin(th / 2), ky / kn * sin(th / 2), 0,
                          cos(th / 2));
        for (int k = 0; k < 3; k++)
            diag.t[k] = 0.5 + e + ax[k] * len / 2;
        ok(c, mpb_collision_set_pose(c, 10, &diag));
        assert_near(distance_of(c, NULL), sqrt(3.0) * e - r, 1e-6);
    }
    /* overlapping: distance 0 and a collision */
    mpb_pose p = at(0.5 + r - 0.01, 0, 0);
    ok(c, mpb_collision_set_pose(c, 10, &p));
    assert_near(distance_of(c, NULL), 0.0, 0);
    int m, s;
    assert_int_equal(mpb_collision_check(c, &m, &s), 1);
    assert_int_equal(m, 10);
    assert_int_equal(s, 1);
    mpb_collision_destroy(c);
}

/* A plane z = 0.25 (0 0 2 0.5) and a cone pointing up. */
static void test_plane_and_cone(void **state)
{
    (void)state;
    mpb_collision *c = new_world();
    mpb_geometry plane = { .type = MPB_SHAPE_PLANE, .dims = { 0, 0, 2, 0.5 } };
    ok(c, mpb_collision_add_static(c, 5, &plane, NULL));
    mpb_geometry s = sphere(0.1);
    ok(c, mpb_collision_add_movable(c, 0, &s, NULL));
    mpb_pose p = at(3, -2, 0.25 + 0.3);
    ok(c, mpb_collision_set_pose(c, 0, &p));
    assert_near(distance_of(c, NULL), 0.2, 1e-9);
    assert_int_equal(mpb_collision_check(c, NULL, NULL), 0);
    p = at(3, -2, 0.25 - 0.3);  /* below, as far: a plane has two sides */
    ok(c, mpb_collision_set_pose(c, 0, &p));
    assert_near(distance_of(c, NULL), 0.2, 1e-9);
    p = at(3, -2, 0.25 + 0.05);
    ok(c, mpb_collision_set_pose(c, 0, &p));
    assert_int_equal(mpb_collision_check(c, NULL, NULL), 1);
    assert_near(distance_of(c, NULL), 0.0, 0);
    /* a plane cannot move */
    assert_int_equal(mpb_collision_add_movable(c, 1, &plane, NULL), MPB_EINVAL);
    mpb_collision_destroy(c);

    /* The same plane at any scale: squaring 1e-300 gave a zero normal and
     * NaN distances, squaring 1e300 an infinite one. */
    static const double scales[] = {1e-300, 1e300};
    for (int i = 0; i < 2; i++) {
        c = new_world();
        plane.dims[2] = 2 * scales[i];
        plane.dims[3] = 0.5 * scales[i];
        ok(c, mpb_collision_add_static(c, 5, &plane, NULL));
        ok(c, mpb_collision_add_movable(c, 0, &s, NULL));
        p = at(3, -2, 0.25 + 0.3);
        ok(c, mpb_collision_set_pose(c, 0, &p));
        assert_near(distance_of(c, NULL), 0.2, 1e-9);
        mpb_collision_destroy(c);
    }
    /* Its coefficients are not lengths; where it lies is bounded. */
    char why[160];
    plane = (mpb_geometry){ .type = MPB_SHAPE_PLANE, .dims = { 0, 0, 1e-3, 1e3 } };
    assert_int_equal(mpb__geometry_check(&plane, why, sizeof why), MPB_EINVAL);
    assert_string_equal(why, "plane: 1e+06 m from the origin, beyond 100000 m");
    plane.dims[3] = INFINITY;
    assert_int_equal(mpb__geometry_check(&plane, why, sizeof why), MPB_EINVAL);
    assert_string_equal(why, "plane: coefficient d is not finite");

    /*
     * Cone radius 1, length 2 at the origin, apex at z = +1: its radius at
     * height z is (1 - z) / 2. A small sphere at (0.9, 0, 0.9) is far from
     * it (radius 0.05 there); at (0.9, 0, -0.9) inside it (radius 0.95).
     */
    c = new_world();
    mpb_geometry cone = { .type = MPB_SHAPE_CONE, .dims = { 1, 2 } };
    mpb_geometry tiny = sphere(0.01);
    ok(c, mpb_collision_add_static(c, 0, &cone, NULL));
    ok(c, mpb_collision_add_movable(c, 0, &tiny, NULL));
    p = at(0.9, 0, 0.9);
    ok(c, mpb_collision_set_pose(c, 0, &p));
    assert_int_equal(mpb_collision_check(c, NULL, NULL), 0);
    p = at(0.9, 0, -0.9);
    ok(c, mpb_collision_set_pose(c, 0, &p));
    assert_int_equal(mpb_collision_check(c, NULL, NULL), 1);
    p = at(0, 0, 1.5);          /* above the apex: 0.5 - 0.01 */
    ok(c, mpb_collision_set_pose(c, 0, &p));
    assert_near(distance_of(c, NULL), 0.49, 1e-6);
    mpb_collision_destroy(c);
}

/* ---- a mesh and its primitive twin -------------------------------------- */

/*
 * The same box as 12 triangles and as a primitive, at the same random pose,
 * in two worlds. Spheres are placed near the boundary: centres drawn around
 * the box and kept where the sphere reaches the surface or stays outside
 * (a sphere wholly inside a mesh touches no triangle; see collision.h),
 * leaving out those within 1e-6 of touching. Both worlds must agree on
 * every collision, and on the distance of every free sphere.
 */
static void test_mesh_twin(void **state)
{
    (void)state;
    const double h[3] = { 0.25, 0.4, 0.1 };
    mpb_mesh *mesh = box_mesh(h);
    mpb_geometry gm = { .type = MPB_SHAPE_MESH, .mesh = mesh };
    mpb_geometry gb = box(2 * h[0], 2 * h[1], 2 * h[2]);
    int compared = 0, hits = 0;
    for (int pose_i = 0; pose_i < 10; pose_i++) {
        mpb_pose bp = random_pose(0.5);
        mpb_collision *cm = new_world(), *cb = new_world();
        ok(cm, mpb_collision_add_static(cm, 0, &gm, &bp));
        ok(cb, mpb_collision_add_static(cb, 0, &gb, &bp));
        for (int i = 0; i < 400; i++) {
            double r = uniform(0.005, 0.08);
            double p[3];
            for (int k = 0; k < 3; k++)
                p[k] = uniform(-h[k] - 1.5 * r, h[k] + 1.5 * r);
            double sd = box_sd(h, p, NULL);
            if (sd < -r + 1e-6 || fabs(sd - r) < 1e-6)
                continue;
            mpb_geometry s = sphere(r);
            mpb_pose sp = bp;
            mpb_pose_apply(&bp, p, sp.t);
            mpb_collision *w[2] = { cm, cb };
            int hit[2];
            double d[2];
            for (int k = 0; k < 2; k++) {
                ok(w[k], mpb_collision_add_movable(w[k], i, &s, NULL));
                ok(w[k], mpb_collision_set_pose(w[k], i, &sp));
                hit[k] = mpb_collision_check(w[k], NULL, NULL);
                d[k] = distance_of(w[k], NULL);
                ok(w[k], mpb_collision_set_enabled(w[k], i, 0));
            }
            if (hit[0] != hit[1])
                fail_msg("pose %d sample %d: mesh says %d, box says %d (sd %.9g, r %.9g)",
                         pose_i, i, hit[0], hit[1], sd, r);
            assert_int_equal(hit[1], sd <= r);
            assert_near(d[0], d[1], 1e-9);
            assert_near(d[1], fmax(sd - r, 0), 1e-9);
            compared++;
            hits += hit[0];
        }
        mpb_collision_destroy(cm);
        mpb_collision_destroy(cb);
    }
    print_message("mesh twin: %d spheres compared, %d colliding\n", compared, hits);
    assert_true(compared > 2000);
    assert_true(hits > 500 && hits < compared - 500);

    /* A moving mesh against a static primitive, and the nearest points. */
    mpb_collision *c = new_world();
    mpb_geometry s = sphere(0.1);
    mpb_pose sp = at(0, 0, 1);
    ok(c, mpb_collision_add_static(c, 4, &s, &sp));
    ok(c, mpb_collision_add_movable(c, 2, &gm, NULL));
    mpb_collision_distance_result res;
    assert_near(distance_of(c, &res), 1 - h[2] - 0.1, 1e-9);
    assert_near(res.point_static[2], 0.9, 1e-9);
    assert_near(res.point_movable[2], h[2], 1e-9);
    assert_near(res.point_movable[0], 0, 1e-9);
    mpb_pose up = at(0, 0, 0.85);
    ok(c, mpb_collision_set_pose(c, 2, &up));
    assert_int_equal(mpb_collision_check(c, NULL, NULL), 1);
    mpb_collision_destroy(c);

    /* A static mesh against a moving sphere: the points are not swapped. */
    c = new_world();
    ok(c, mpb_collision_add_static(c, 4, &gm, NULL));
    ok(c, mpb_collision_add_movable(c, 2, &s, &sp));
    assert_near(distance_of(c, &res), 1 - h[2] - 0.1, 1e-9);
    assert_near(res.point_movable[2], 0.9, 1e-9);
    assert_near(res.point_static[2], h[2], 1e-9);
    mpb_collision_destroy(c);
    mpb__mesh_destroy(mesh);
}

/* ---- bodies, pairs, errors ---------------------------------------------- */

/* A body of two spheres at offsets moves as one. */
static void test_bodies(void **state)
{
    (void)state;
    mpb_collision *c = new_world();
    mpb_geometry s = sphere(0.1), b = box(0.2, 0.2, 0.2);
    mpb_pose off1 = at(1, 0, 0), off2 = at(-1, 0, 0);
    ok(c, mpb_collision_add_movable(c, 0, &s, &off1));
    ok(c, mpb_collision_add_movable(c, 0, &s, &off2));
    assert_int_equal(mpb__collision_num_movable_shapes(c), 2);
    mpb_pose bp = at(0, 3, 0);
    ok(c, mpb_collision_add_static(c, 9, &b, &bp));
    assert_int_equal(mpb__collision_num_static_shapes(c), 1);
    /* body at identity: spheres at x = +-1, the box's nearest corner edge
       at (+-0.1, 2.9) */
    assert_near(distance_of(c, NULL), sqrt(0.9 * 0.9 + 2.9 * 2.9) - 0.1, 1e-9);
    /* rotate the body 90 degrees about z and lift it: a sphere lands at
       (0, 1, 0) + (0, 1.8, 0) = (0, 2.8, 0), 0.1 from the box's face at 2.9 */
    mpb_pose q;
    mpb_pose_set_rpy(&q, 0, 0, M_PI / 2);
    q.t[0] = 0;
    q.t[1] = 1.8;
    q.t[2] = 0;
    ok(c, mpb_collision_set_pose(c, 0, &q));
    mpb_collision_distance_result res;
    assert_near(distance_of(c, &res), 0.0, 1e-9);   /* touching: 2.8+0.1 = 2.9 */
    q.t[1] = 1.7;
    ok(c, mpb_collision_set_pose(c, 0, &q));
    assert_near(distance_of(c, &res), 0.1, 1e-9);
    assert_near(res.point_movable[1], 2.8, 1e-9);
    assert_near(res.point_static[1], 2.9, 1e-9);
    /* statics added after a query are found by the next one: the other
       sphere is at (0, 0.7, 0) */
    mpb_pose bp2 = at(0, 0.75, 0);
    ok(c, mpb_collision_add_static(c, 10, &b, &bp2));
    int m, st;
    assert_int_equal(mpb_collision_check(c, &m, &st), 1);
    assert_int_equal(m, 0);
    assert_int_equal(st, 10);
    mpb_collision_destroy(c);
}

static void test_allowed_pairs(void **state)
{
    (void)state;
    mpb_collision *c = new_world();
    mpb_geometry s = sphere(0.2);
    /* three links in a row, each overlapping the next */
    for (int i = 0; i < 3; i++) {
        mpb_pose p = at(0.3 * i, 0, 0);
        ok(c, mpb_collision_add_movable(c, 10 + i, &s, NULL));
        ok(c, mpb_collision_set_pose(c, 10 + i, &p));
    }
    int a, b;
    assert_int_equal(mpb__collision_check_self(c, &a, &b), 1);
    assert_int_equal(a, 10);
    assert_int_equal(b, 11);
    ok(c, mpb__collision_allow_pair(c, 11, 10));
    assert_int_equal(mpb__collision_check_self(c, &a, &b), 1);
    assert_int_equal(a, 11);
    assert_int_equal(b, 12);
    ok(c, mpb__collision_allow_pair(c, 11, 12));
    assert_int_equal(mpb__collision_check_self(c, &a, &b), 0);
    assert_int_equal(a, -1);
    assert_int_equal(b, -1);
    /* 10 and 12 are 0.6 apart, radius 0.2 each: free; move 12 closer */
    mpb_pose p = at(0.35, 0.1, 0);
    ok(c, mpb_collision_set_pose(c, 12, &p));
    assert_int_equal(mpb__collision_check_self(c, &a, &b), 1);
    assert_int_equal(a, 10);
    assert_int_equal(b, 12);
    ok(c, mpb_collision_set_enabled(c, 12, 0));
    assert_int_equal(mpb__collision_check_self(c, NULL, NULL), 0);
    ok(c, mpb_collision_set_enabled(c, 12, 1));
    /* a body added later, at the identity, overlaps 10 */
    ok(c, mpb_collision_add_movable(c, 3, &s, NULL));
    ok(c, mpb__collision_allow_pair(c, 10, 12));
    assert_int_equal(mpb__collision_check_self(c, &a, &b), 1);
    assert_int_equal(a, 3);
    assert_int_equal(b, 10);
    assert_int_equal(mpb__collision_allow_pair(c, 3, 3), MPB_EINVAL);
    assert_int_equal(mpb__collision_allow_pair(c, 3, 99), MPB_ENOTFOUND);
    assert_string_equal(mpb_collision_errmsg(c), "collision: no movable body 99");
    assert_int_equal(mpb__collision_allow_pair(c, 98, 3), MPB_ENOTFOUND);
    assert_string_equal(mpb_collision_errmsg(c), "collision: no movable body 98");

    /* a link allowed to touch the floor, not a wall */
    mpb_geometry floor = box(10, 10, 0.1), wall = box(0.1, 10, 10);
    mpb_pose fp = at(0, 0, -0.2), wp = at(2, 0, 0);
    ok(c, mpb_collision_add_static(c, 0, &floor, &fp));
    ok(c, mpb_collision_add_static(c, 1, &wall, &wp));
    ok(c, mpb__collision_allow_pair(c, 3, 10));
    ok(c, mpb_collision_set_enabled(c, 11, 0));
    ok(c, mpb_collision_set_enabled(c, 12, 0));
    ok(c, mpb_collision_set_enabled(c, 3, 0));
    int m, st;
    assert_int_equal(mpb_collision_check(c, &m, &st), 1);
    assert_int_equal(m, 10);
    assert_int_equal(st, 0);
    ok(c, mpb__collision_allow_static(c, 10, 0));
    ok(c, mpb__collision_allow_static(c, 10, 0));   /* twice is fine */
    assert_int_equal(mpb_collision_check(c, &m, &st), 0);
    mpb_collision_distance_result res;
    /* sphere 10 at x = 0 radius 0.2; the wall's face at x = 1.95 */
    assert_near(distance_of(c, &res), 1.75, 1e-9);
    assert_int_equal(res.static_id, 1);
    assert_int_equal(res.movable, 10);
    /* no movable enabled: nothing to measure */
    ok(c, mpb_collision_set_enabled(c, 10, 0));
    assert_int_equal(mpb_collision_check(c, NULL, NULL), 0);
    assert_true(isinf(distance_of(c, &res)));
    assert_int_equal(res.movable, -1);
    mpb_collision_destroy(c);
}

/* A self-only body (a robot's fixed link): in self checks, not against
 * the statics nor in the distance; a pair checked whatever is allowed. */
static void test_self_only_bodies(void **state)
{
    (void)state;
    mpb_collision *c = new_world();
    mpb_geometry base = box(0.6, 0.6, 0.3), s = sphere(0.1);
    mpb_geometry floor = box(10, 10, 0.1);
    mpb_pose fp = at(0, 0, -0.05), bp = at(0, 0, 0.15), sp = at(0.35, 0, 0.15);
    ok(c, mpb_collision_add_static(c, 0, &floor, &fp));
    ok(c, mpb_collision_add_movable(c, 1, &base, NULL));   /* on the floor */
    ok(c, mpb_collision_set_pose(c, 1, &bp));
    ok(c, mpb_collision_add_movable(c, 2, &s, NULL));      /* in the base */
    ok(c, mpb_collision_set_pose(c, 2, &sp));
    mpb_collision_distance_result res;
    int m, st, a, b;
    assert_int_equal(mpb_collision_check(c, &m, &st), 1);  /* base on floor */
    assert_int_equal(m, 1);
    ok(c, mpb__collision_set_self_only(c, 1, 1));
    assert_int_equal(mpb_collision_check(c, NULL, NULL), 0);
    /* the sphere's bottom at z 0.05, the floor's top at 0 */
    assert_near(distance_of(c, &res), 0.05, 1e-9);
    assert_int_equal(res.movable, 2);
    assert_int_equal(mpb__collision_check_brute(c), 1);  /* the self pair */
    assert_near(mpb__collision_distance_brute(c), 0.05, 1e-9);
    assert_int_equal(mpb__collision_check_self(c, &a, &b), 1);
    assert_int_equal(a, 1);
    assert_int_equal(b, 2);
    ok(c, mpb__collision_allow_pair(c, 1, 2));
    assert_int_equal(mpb__collision_check_self(c, NULL, NULL), 0);
    assert_int_equal(mpb__collision_check_brute(c), 0);
    assert_int_equal(mpb__collision_check_pair(c, 2, 1), 1);
    mpb_pose away = at(1, 0, 0.5);
    ok(c, mpb_collision_set_pose(c, 2, &away));
    assert_int_equal(mpb__collision_check_pair(c, 1, 2), 0);
    assert_int_equal(mpb__collision_check_pair(c, 1, 1), MPB_EINVAL);
    assert_int_equal(mpb__collision_check_pair(c, 1, 7), MPB_ENOTFOUND);
    assert_int_equal(mpb__collision_set_self_only(c, 7, 1), MPB_ENOTFOUND);
    /* back in every query */
    ok(c, mpb__collision_set_self_only(c, 1, 0));
    assert_int_equal(mpb_collision_check(c, &m, &st), 1);
    assert_int_equal(m, 1);
    mpb_collision_destroy(c);
}

static void test_errors(void **state)
{
    (void)state;
    mpb_collision_destroy(NULL);
    assert_int_equal(mpb_collision_create(NULL), MPB_EINVAL);
    assert_non_null(mpb_collision_errmsg(NULL));
    mpb_collision *c = new_world();
    mpb_geometry s = sphere(0.1);
    assert_string_equal(mpb_collision_errmsg(c), "");
    assert_int_equal(mpb_collision_add_static(c, -1, &s, NULL), MPB_EINVAL);
    assert_non_null(strstr(mpb_collision_errmsg(c), "id -1"));
    assert_int_equal(mpb_collision_add_movable(c, MPB_COLLISION_MAX_ID + 1, &s, NULL),
                     MPB_EINVAL);
    mpb_geometry bad = sphere(-1);
    assert_int_equal(mpb_collision_add_static(c, 0, &bad, NULL), MPB_EINVAL);
    assert_non_null(strstr(mpb_collision_errmsg(c), "negative"));
    bad = box(1, NAN, 1);
    assert_int_equal(mpb_collision_add_static(c, 0, &bad, NULL), MPB_EINVAL);
    bad = (mpb_geometry){ .type = MPB_SHAPE_PLANE };
    assert_int_equal(mpb_collision_add_static(c, 0, &bad, NULL), MPB_EINVAL);
    bad = (mpb_geometry){ .type = (mpb_shape_type)42 };
    assert_int_equal(mpb_collision_add_static(c, 0, &bad, NULL), MPB_EINVAL);
    bad = (mpb_geometry){ .type = MPB_SHAPE_MESH };
    assert_int_equal(mpb_collision_add_static(c, 0, &bad, NULL), MPB_EINVAL);
    mpb_mesh *m = mpb__mesh_create(3, 1);
    m->triangles[2] = 3;        /* out of range */
    bad.mesh = m;
    assert_int_equal(mpb_collision_add_static(c, 0, &bad, NULL), MPB_EINVAL);
    assert_non_null(strstr(mpb_collision_errmsg(c), "out of range"));
    mpb__mesh_destroy(m);
    mpb_pose skew = at(0, 0, 0);
    skew.R[1] = 0.5;            /* not a rotation */
    assert_int_equal(mpb_collision_add_static(c, 0, &s, &skew), MPB_EINVAL);
    assert_non_null(strstr(mpb_collision_errmsg(c), "rotation"));
    mpb_pose far = at(0, 0, 2e9);   /* beyond MPB_COLLISION_MAX_COORD */
    assert_int_equal(mpb_collision_add_static(c, 0, &s, &far), MPB_EINVAL);
    bad = box(1, 1, 2e9);
    assert_int_equal(mpb_collision_add_static(c, 0, &bad, NULL), MPB_EINVAL);
    assert_non_null(strstr(mpb_collision_errmsg(c), "beyond"));
    mpb_pose p = at(0, 0, 0);
    assert_int_equal(mpb_collision_set_pose(c, 4, &p), MPB_ENOTFOUND);
    assert_int_equal(mpb_collision_set_enabled(c, 4, 1), MPB_ENOTFOUND);
    assert_string_equal(mpb_collision_errmsg(c), "collision: no movable body 4");
    assert_int_equal(mpb__collision_allow_static(c, 4, 1), MPB_ENOTFOUND);
    ok(c, mpb_collision_add_movable(c, 4, &s, NULL));
    assert_int_equal(mpb__collision_allow_static(c, 4, -3), MPB_EINVAL);
    p.t[1] = NAN;
    assert_int_equal(mpb_collision_set_pose(c, 4, &p), MPB_EINVAL);
    p.t[1] = -1e10;
    assert_int_equal(mpb_collision_set_pose(c, 4, &p), MPB_EINVAL);
    assert_int_equal(mpb_collision_set_pose(c, 4, NULL), MPB_EINVAL);
    assert_null(strchr(mpb_collision_errmsg(c), '\n'));
    /* an empty world */
    assert_int_equal(mpb_collision_check(c, NULL, NULL), 0);
    assert_int_equal(mpb__collision_check_self(c, NULL, NULL), 0);
    mpb_collision_distance_result res;
    ok(c, mpb_collision_distance(c, 0, &res));
    assert_true(isinf(res.distance));
    assert_true(isnan(res.point_movable[0]));
    assert_int_equal(mpb_collision_check(NULL, NULL, NULL), MPB_EINVAL);
    assert_int_equal(mpb_collision_distance(NULL, 0, &res), MPB_EINVAL);
    assert_true(isnan(res.distance));
    assert_string_equal(mpb_shape_type_name(MPB_SHAPE_CAPSULE), "capsule");
    assert_string_equal(mpb_shape_type_name((mpb_shape_type)99), "unknown");
    mpb_collision_destroy(c);
}

/* ---- timing ------------------------------------------------------------- */

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/*
 * A 7-link arm (capsules and cylinders, 0.3 m apart, reach 2.1 m) among 20
 * boxes (0.1-0.4 m) scattered in a 3 m x 3 m x 1.5 m block around it, none
 * within 0.6 m of its base axis: time
 * per full query (7 set_pose + check, 7 set_pose + distance, self-check)
 * over 4000 random configurations, free and colliding ones apart. Printed
 * for docs; no bound asserted (sanitizer builds are slow).
 */
static void test_timing(void **state)
{
    (void)state;
    mpb_collision *c = new_world();
    for (int i = 0; i < 20; i++) {
        mpb_geometry b = box(uniform(0.1, 0.4), uniform(0.1, 0.4), uniform(0.1, 0.4));
        mpb_pose p = random_pose(1.5);
        p.t[2] = uniform(0, 1.5);
        if (hypot(p.t[0], p.t[1]) < 0.6) {   /* keep clear of the base */
            i--;
            continue;
        }
        ok(c, mpb_collision_add_static(c, i, &b, &p));
    }
    for (int l = 0; l < 7; l++) {
        mpb_geometry g = l % 2 ? cylinder(0.06, 0.25) : capsule(0.05, 0.2);
        mpb_pose off = at(0, 0, 0.15);
        ok(c, mpb_collision_add_movable(c, l, &g, &off));
    }
    for (int l = 0; l + 1 < 7; l++)
        ok(c, mpb__collision_allow_pair(c, l, l + 1));
    const int N = 4000;
    for (int walk = 0; walk < 2; walk++) {
        int n_hit = 0, n_free = 0, self_hits = 0;
        double t_hit = 0, t_free = 0, t_dist = 0, t_self = 0, t_pose = 0;
        double q[7] = { 0 };
        for (int n = 0; n < N; n++) {
            /* random configurations, or a random walk of 0.01 rad steps
               (a path sampled finely, as verification does) */
            for (int l = 1; l < 7; l++)
                q[l] = walk ? fmax(-2.5, fmin(2.5, q[l] + uniform(-0.01, 0.01)))
                            : uniform(-2.5, 2.5);
            mpb_pose link[7];
            mpb_pose_identity(&link[0]);
            link[0].t[2] = 0.5;
            for (int l = 1; l < 7; l++) {
                mpb_pose j;
                mpb_pose_set_rpy(&j, l % 2 ? q[l] : 0, l % 2 ? 0 : q[l], 0);
                j.t[0] = 0;
                j.t[1] = 0;
                j.t[2] = 0.3;
                mpb_pose_mul(&link[l - 1], &j, &link[l]);
            }
            double t0 = now();
            for (int l = 0; l < 7; l++)
                mpb_collision_set_pose(c, l, &link[l]);
            int hit = mpb_collision_check(c, NULL, NULL);
            double t1 = now();
            for (int l = 0; l < 7; l++)
                mpb_collision_set_pose(c, l, &link[l]);
            mpb_collision_distance_result res;
            mpb_collision_distance(c, 0, &res);
            double t2 = now();
            self_hits += mpb__collision_check_self(c, NULL, NULL);
            double t3 = now();
            for (int l = 0; l < 7; l++)
                mpb_collision_set_pose(c, l, &link[l]);
            t_pose += now() - t3;
            assert_int_equal(hit, res.distance <= 0);
            if (hit) {
                n_hit++;
                t_hit += t1 - t0;
            } else {
                n_free++;
                t_free += t1 - t0;
                t_dist += t2 - t1;
            }
            t_self += t3 - t2;
        }
        print_message("7 links vs 20 boxes, %d %s: free %d, colliding %d, "
                      "self-colliding %d\n", N, walk ? "steps of a random walk"
                      : "random configurations", n_free, n_hit, self_hits);
        print_message("  per configuration: check %.2f us (free) %.2f us "
                      "(colliding), distance %.2f us (free), self-check %.2f us; "
                      "of these, the 7 set_pose calls take %.2f us\n",
                      n_free ? 1e6 * t_free / n_free : NAN,
                      n_hit ? 1e6 * t_hit / n_hit : NAN,
                      n_free ? 1e6 * t_dist / n_free : NAN, 1e6 * t_self / N,
                      1e6 * t_pose / N);
        if (!walk)
            assert_true(n_hit > 0 && n_free > 0);
    }
    mpb_collision_destroy(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pose_helpers),
        cmocka_unit_test(test_sphere_box_distance),
        cmocka_unit_test(test_links_beside_box),
        cmocka_unit_test(test_plane_and_cone),
        cmocka_unit_test(test_mesh_twin),
        cmocka_unit_test(test_bodies),
        cmocka_unit_test(test_allowed_pairs),
        cmocka_unit_test(test_self_only_bodies),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_timing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
