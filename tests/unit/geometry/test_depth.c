/*
 * test_depth.c - how deep a collision goes (mpb__collision_depth(),
 * geometry/collision_depth.cpp): hand-made worlds whose penetration depth
 * is known exactly, each asserting lower <= true <= upper, and for these
 * shapes both within 1e-9 m of the truth (the deepest point is a corner
 * or an extreme point the search tries; the best direction is an axis).
 *
 *   a box pushed 3 mm into a box (face on), and turned 45 deg about z so
 *   that an edge goes in 3 mm: true depth 3 mm;
 *   a sphere 3 mm into a box's face: 3 mm;
 *   a tetrahedron mesh with one vertex 2 mm inside a box: 2 mm;
 *   a link against a link (self pair): two boxes 2 mm into each other;
 *   two closed mesh cubes whose corners overlap by 2, 1 and 0.5 mm along
 *   x, y, z: 0.5 mm (the winding-number inside test);
 *   a capsule crossing a static plane by 4 mm: 4 mm, both bounds exact;
 *   apart, and a pair allowed to touch: both 0.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "mpbench/collision.h"
#include "mpbench/mesh.h"
#include "mpbench/pose.h"
#include "geometry/mesh.h"
#include "geometry/collision_internal.h"

#define TOL 1e-9

static mpb_pose at(double x, double y, double z)
{
    mpb_pose p;
    mpb_pose_identity(&p);
    p.t[0] = x, p.t[1] = y, p.t[2] = z;
    return p;
}

/* The pose at (x, y, z) turned by angle a about z. */
static mpb_pose turned(double x, double y, double z, double a)
{
    mpb_pose p = at(x, y, z);
    p.R[0] = cos(a), p.R[1] = -sin(a);
    p.R[3] = sin(a), p.R[4] = cos(a);
    return p;
}

static mpb__collision_depth_result depth(mpb_collision *c)
{
    mpb__collision_depth_result r;
    assert_int_equal(mpb__collision_depth(c, 0.0, &r), MPB_OK);
    print_message("depth: lower %.12g upper %.12g m (bodies %d, %d%s)\n",
                  r.lower, r.upper, r.movable, r.other, r.self ? ", self" : "");
    assert_true(r.lower <= r.upper);
    return r;
}

/* lower <= truth <= upper, each within TOL of it. */
static void expect_depth(mpb_collision *c, double truth)
{
    mpb__collision_depth_result r = depth(c);
    assert_true(r.lower <= truth + TOL);
    assert_true(r.upper >= truth - TOL);
    assert_true(fabs(r.lower - truth) < TOL);
    assert_true(fabs(r.upper - truth) < TOL);
}

/* A world with the static box of sides 0.4 0.4 0.2 centred at the origin
 * (top face at z = 0.1). */
static mpb_collision *table_world(void)
{
    mpb_collision *c;
    assert_int_equal(mpb_collision_create(&c), MPB_OK);
    mpb_geometry g = {.type = MPB_SHAPE_BOX, .dims = {0.4, 0.4, 0.2}};
    assert_int_equal(mpb_collision_add_static(c, 7, &g, NULL), MPB_OK);
    return c;
}

static void test_box_into_box(void **state)
{
    (void)state;
    mpb_collision *c = table_world();
    mpb_geometry g = {.type = MPB_SHAPE_BOX, .dims = {0.1, 0.1, 0.1}};
    assert_int_equal(mpb_collision_add_movable(c, 1, &g, NULL), MPB_OK);
    mpb_pose p = at(0.03, -0.02, 0.1 + 0.05 - 0.003);
    assert_int_equal(mpb_collision_set_pose(c, 1, &p), MPB_OK);
    expect_depth(c, 0.003);
    mpb__collision_depth_result r = depth(c);
    assert_int_equal(r.movable, 1);
    assert_int_equal(r.other, 7);
    assert_int_equal(r.self, 0);

    /* Turned 45 deg about z and tipped onto an edge: turned about x by 45
     * deg, its lowest edge 3 mm below the top face. */
    const double h = 0.05 * sqrt(2.0);
    mpb_pose q = turned(0.0, 0.0, 0.1 + h - 0.003, M_PI / 4);
    mpb_pose tip;
    mpb_pose_identity(&tip);
    tip.R[4] = cos(M_PI / 4), tip.R[5] = -sin(M_PI / 4);
    tip.R[7] = sin(M_PI / 4), tip.R[8] = cos(M_PI / 4);
    mpb_pose both;
    mpb_pose_mul(&q, &tip, &both);
    assert_int_equal(mpb_collision_set_pose(c, 1, &both), MPB_OK);
    expect_depth(c, 0.003);

    /* Lifted clear: nothing overlaps. */
    p.t[2] = 0.1 + 0.05 + 0.001;
    assert_int_equal(mpb_collision_set_pose(c, 1, &p), MPB_OK);
    r = depth(c);
    assert_true(r.lower == 0 && r.upper == 0 && r.movable == -1);

    /* Pushed in but allowed to touch: nothing counts. */
    p.t[2] = 0.1;
    assert_int_equal(mpb_collision_set_pose(c, 1, &p), MPB_OK);
    assert_int_equal(mpb__collision_allow_static(c, 1, 7), MPB_OK);
    r = depth(c);
    assert_true(r.lower == 0 && r.upper == 0);
    mpb_collision_destroy(c);
}

static void test_sphere_into_box(void **state)
{
    (void)state;
    mpb_collision *c = table_world();
    mpb_geometry g = {.type = MPB_SHAPE_SPHERE, .dims = {0.04}};
    assert_int_equal(mpb_collision_add_movable(c, 2, &g, NULL), MPB_OK);
    /* into the top face, away from its edges */
    mpb_pose p = at(-0.05, 0.07, 0.1 + 0.04 - 0.003);
    assert_int_equal(mpb_collision_set_pose(c, 2, &p), MPB_OK);
    expect_depth(c, 0.003);
    /* into the side face x = 0.2 */
    p = at(0.2 + 0.04 - 0.003, 0.0, 0.0);
    assert_int_equal(mpb_collision_set_pose(c, 2, &p), MPB_OK);
    expect_depth(c, 0.003);
    mpb_collision_destroy(c);
}

/* A tetrahedron pointing down: apex at the origin, base 5 cm above. */
static mpb_mesh *tetra(void)
{
    static const double v[4][3] = {
        {0, 0, 0}, {0.03, 0, 0.05}, {-0.015, 0.026, 0.05}, {-0.015, -0.026, 0.05},
    };
    static const int t[4][3] = {{0, 2, 1}, {0, 3, 2}, {0, 1, 3}, {1, 2, 3}};
    mpb_mesh *m = mpb__mesh_create(4, 4);
    assert_non_null(m);
    memcpy(m->vertices, v, sizeof v);
    for (int i = 0; i < 12; i++)
        m->triangles[i] = t[i / 3][i % 3];
    return m;
}

static void test_mesh_vertex_into_box(void **state)
{
    (void)state;
    mpb_collision *c = table_world();
    mpb_mesh *m = tetra();
    mpb_geometry g = {.type = MPB_SHAPE_MESH, .mesh = m};
    assert_int_equal(mpb_collision_add_movable(c, 3, &g, NULL), MPB_OK);
    mpb_pose p = at(0.01, 0.02, 0.1 - 0.002);
    assert_int_equal(mpb_collision_set_pose(c, 3, &p), MPB_OK);
    expect_depth(c, 0.002);
    mpb_collision_destroy(c);
    mpb__mesh_destroy(m);
}

/* A closed cube of side s as 8 vertices and 12 outward triangles. */
static mpb_mesh *cube(double s)
{
    static const int tri[12][3] = {
        {0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
        {3, 7, 6}, {3, 6, 2}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5},
    };
    mpb_mesh *m = mpb__mesh_create(8, 12);
    assert_non_null(m);
    for (int i = 0; i < 8; i++) {
        int bits[3] = {(i == 1 || i == 2 || i == 5 || i == 6),
                       (i == 2 || i == 3 || i == 6 || i == 7), i >= 4};
        for (int k = 0; k < 3; k++)
            m->vertices[3 * i + k] = bits[k] ? s / 2 : -s / 2;
    }
    for (int t = 0; t < 12; t++)
        for (int k = 0; k < 3; k++)
            m->triangles[3 * t + k] = tri[t][k];
    return m;
}

static void test_self_pairs(void **state)
{
    (void)state;
    mpb_collision *c;
    assert_int_equal(mpb_collision_create(&c), MPB_OK);
    mpb_geometry g = {.type = MPB_SHAPE_BOX, .dims = {0.1, 0.1, 0.1}};
    assert_int_equal(mpb_collision_add_movable(c, 4, &g, NULL), MPB_OK);
    assert_int_equal(mpb_collision_add_movable(c, 5, &g, NULL), MPB_OK);
    mpb_pose p = at(0.1 - 0.002, 0.01, -0.02);
    assert_int_equal(mpb_collision_set_pose(c, 5, &p), MPB_OK);
    expect_depth(c, 0.002);
    mpb__collision_depth_result r = depth(c);
    assert_int_equal(r.self, 1);
    assert_int_equal(r.movable, 4);
    assert_int_equal(r.other, 5);
    assert_int_equal(mpb__collision_allow_pair(c, 4, 5), MPB_OK);
    r = depth(c);
    assert_true(r.lower == 0 && r.upper == 0);
    mpb_collision_destroy(c);

    /* Two mesh cubes, corner into corner: 2, 1 and 0.5 mm of overlap. */
    assert_int_equal(mpb_collision_create(&c), MPB_OK);
    mpb_mesh *m = cube(0.1);
    mpb_geometry gm = {.type = MPB_SHAPE_MESH, .mesh = m};
    assert_int_equal(mpb_collision_add_movable(c, 1, &gm, NULL), MPB_OK);
    assert_int_equal(mpb_collision_add_movable(c, 2, &gm, NULL), MPB_OK);
    p = at(0.1 - 0.002, 0.1 - 0.001, 0.1 - 0.0005);
    assert_int_equal(mpb_collision_set_pose(c, 2, &p), MPB_OK);
    expect_depth(c, 0.0005);
    mpb_collision_destroy(c);
    mpb__mesh_destroy(m);
}

/* Many overlapping pairs, the worst first or last (a mesh cube among
 * spheres, as a link in a wall of a cloud's spheres): each pair's points
 * are tried only while they can beat the deepest found, and the bounds
 * are those of trying them all; with a floor, lower is max(floor, that)
 * and the upper bound and its pair are unchanged. */
static void test_floor(void **state)
{
    (void)state;
    mpb_collision *c;
    assert_int_equal(mpb_collision_create(&c), MPB_OK);
    mpb_mesh *m = cube(0.1);
    mpb_geometry gm = {.type = MPB_SHAPE_MESH, .mesh = m};
    assert_int_equal(mpb_collision_add_movable(c, 1, &gm, NULL), MPB_OK);
    /* spheres of 1.5 cm along the cube's face x = 0.05, 1 to 9 mm into it */
    for (int i = 0; i < 9; i++) {
        mpb_geometry g = {.type = MPB_SHAPE_SPHERE, .dims = {0.015}};
        mpb_pose p = at(0.05 + 0.015 - 0.001 * (i % 2 ? 9 - i : i + 1),
                        -0.04 + 0.01 * i, 0.01 * (i % 3));
        assert_int_equal(mpb_collision_add_static(c, 20 + i, &g, &p), MPB_OK);
    }
    mpb__collision_depth_result r = depth(c), f;
    assert_true(fabs(r.lower - 0.009) < TOL);
    assert_true(fabs(r.upper - 0.009) < TOL);
    /* a floor under it: the same bounds, bit for bit */
    assert_int_equal(mpb__collision_depth(c, nextafter(r.lower, 0.0), &f), MPB_OK);
    assert_true(f.lower == r.lower && f.upper == r.upper);
    assert_true(f.movable == r.movable && f.other == r.other && f.self == r.self);
    /* a floor over it: lower is the floor, upper and its pair as before */
    assert_int_equal(mpb__collision_depth(c, 0.02, &f), MPB_OK);
    assert_true(f.lower == 0.02 && f.upper == r.upper);
    assert_true(f.movable == r.movable && f.other == r.other);
    mpb_collision_destroy(c);
    mpb__mesh_destroy(m);
}

static void test_plane(void **state)
{
    (void)state;
    mpb_collision *c;
    assert_int_equal(mpb_collision_create(&c), MPB_OK);
    mpb_geometry floor = {.type = MPB_SHAPE_PLANE, .dims = {0, 0, 1, 0}};
    assert_int_equal(mpb_collision_add_static(c, 9, &floor, NULL), MPB_OK);
    mpb_geometry g = {.type = MPB_SHAPE_CAPSULE, .dims = {0.02, 0.2}};
    assert_int_equal(mpb_collision_add_movable(c, 1, &g, NULL), MPB_OK);
    /* upright, its lowest point 4 mm below the floor */
    mpb_pose p = at(0.3, 0.1, 0.1 + 0.02 - 0.004);
    assert_int_equal(mpb_collision_set_pose(c, 1, &p), MPB_OK);
    expect_depth(c, 0.004);
    mpb_collision_destroy(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_box_into_box),
        cmocka_unit_test(test_sphere_into_box),
        cmocka_unit_test(test_mesh_vertex_into_box),
        cmocka_unit_test(test_self_pairs),
        cmocka_unit_test(test_plane),
        cmocka_unit_test(test_floor),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
