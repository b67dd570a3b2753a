/*
 * test_clearance_reference.c - the clearance query (mpb_collision_distance,
 * robot against scene) against every pair through FCL's distance
 * (collision_internal.h), to 1e-9 m where positive and 0 where the
 * reference is: the Panda with its SRDF and collision meshes
 * (tools/robot_data.sh; skipped when not fetched) in MotionBenchMaker's
 * table_pick scene 1 (data/mbm_table_pick_panda_0001.scene, made by
 * bench/mbm_scene.py) at fixed-seed random states and along fine paths;
 * a mesh against each primitive (box, sphere, cylinder, cone, capsule)
 * at random poses, which is where bvh_distance.cpp stands in for FCL; a
 * mesh bent into a U around a box and a sphere, where no hull proves the
 * nearest point (a proof taken on trust shows); and
 * scenes made so that a wrong cutoff shows: the nearest static has the
 * largest bounding-sphere lower bound, and the nearest triangle of a mesh
 * lies in the node whose box is farthest.
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
#include "geometry/mesh.h"

#define NJ 7

/* Uniform in [0, 1), from a 64-bit LCG. */
static double rnd(uint64_t *x)
{
    *x = *x * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*x >> 11) / 9007199254740992.0;
}

/* The Panda in the MotionBenchMaker scene, or NULL when not fetched. */
static mpb_world *open_panda(void)
{
    char *scene = test_read_file(MPB_TEST_DATA "/mbm_table_pick_panda_0001.scene");
    mpb_world *w = test_open_panda(scene);
    free(scene);
    return w;
}

/* The world's clearance at q against the reference; 1 if positive. */
static int agree_at(mpb_world *w, const double *q)
{
    double fast = mpb_world_clearance(w, q);    /* places the robot */
    double ref = mpb__collision_distance_brute(mpb__urdf_collision(w));
    assert_false(isnan(fast) || isnan(ref));
    if (ref > 0) {
        if (fabs(fast - ref) > 1e-9)
            fail_msg("clearance %.12g, every pair through FCL %.12g", fast, ref);
        return 1;
    }
    assert_true(fast == 0.0);
    return 0;
}

static void panda_random_states(void **state)
{
    (void)state;
    mpb_world *w = open_panda();
    if (!w) {
        print_message("Panda data not fetched (tools/robot_data.sh): skipped\n");
        skip();
    }
    uint64_t x = 37;
    double q[NJ];
    int positive = 0, n = 150;
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < NJ; j++) {
            double lo, hi;
            mpb_world_joint_limits(w, j, &lo, &hi);
            q[j] = lo + rnd(&x) * (hi - lo);
        }
        positive += agree_at(w, q);
    }
    /* both kinds of state were met */
    assert_true(positive > n / 2 && positive < n);
    mpb_world_close(w);
}

/* Fine paths: the last nearest pair seeds each query (temporal coherence). */
static void panda_fine_paths(void **state)
{
    (void)state;
    mpb_world *w = open_panda();
    if (!w)
        skip();
    uint64_t x = 4;
    double a[NJ], b[NJ], q[NJ];
    for (int path = 0; path < 3; path++) {
        for (int j = 0; j < NJ; j++) {
            double lo, hi;
            mpb_world_joint_limits(w, j, &lo, &hi);
            a[j] = lo + rnd(&x) * (hi - lo);
            b[j] = lo + rnd(&x) * (hi - lo);
        }
        for (int s = 0; s <= 40; s++) {
            for (int j = 0; j < NJ; j++)
                q[j] = a[j] + (b[j] - a[j]) * s / 40.0;
            agree_at(w, q);
        }
    }
    mpb_world_close(w);
}

/* A bar along x, length len, square section side, as a mesh of n
 * segments (4 n + 4 vertices, 8 n + 4 triangles): a deep tree. */
static mpb_mesh *bar(double len, double side, int n)
{
    mpb_mesh *m = mpb__mesh_create(4 * (n + 1), 8 * n + 4);
    assert_non_null(m);
    for (int i = 0; i <= n; i++)
        for (int k = 0; k < 4; k++) {
            double *v = &m->vertices[3 * (4 * i + k)];
            v[0] = -len / 2 + len * i / n;
            v[1] = (k == 1 || k == 2 ? 0.5 : -0.5) * side;
            v[2] = (k >= 2 ? 0.5 : -0.5) * side;
        }
    int t = 0;
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 4; k++) {
            int a = 4 * i + k, b = 4 * i + (k + 1) % 4;
            int32_t *p = &m->triangles[3 * t];
            p[0] = a, p[1] = b, p[2] = b + 4;
            p[3] = a, p[4] = b + 4, p[5] = a + 4;
            t += 2;
        }
    int32_t caps[12] = {0, 2, 1, 0, 3, 2};
    for (int k = 0; k < 6; k++)
        caps[6 + k] = 4 * n + caps[k];
    memcpy(&m->triangles[3 * t], caps, sizeof caps);
    return m;
}

/* A rotation by angle about a random axis, with translation t. */
static mpb_pose random_pose(uint64_t *x, double spread)
{
    double u[3], n = 0, ang = 6.283185307179586 * rnd(x);
    for (int k = 0; k < 3; k++) {
        u[k] = rnd(x) - 0.5;
        n += u[k] * u[k];
    }
    n = sqrt(n);
    for (int k = 0; k < 3; k++)
        u[k] /= n;
    double c = cos(ang), s = sin(ang), C = 1 - c;
    mpb_pose p = {{c + u[0] * u[0] * C, u[0] * u[1] * C - u[2] * s,
                   u[0] * u[2] * C + u[1] * s, u[1] * u[0] * C + u[2] * s,
                   c + u[1] * u[1] * C, u[1] * u[2] * C - u[0] * s,
                   u[2] * u[0] * C - u[1] * s, u[2] * u[1] * C + u[0] * s,
                   c + u[2] * u[2] * C},
                  {0, 0, 0}};
    for (int k = 0; k < 3; k++)
        p.t[k] = spread * (rnd(x) - 0.5);
    return p;
}

/* Each primitive against a mesh, at random poses of the mesh. */
static void mesh_against_each_primitive(void **state)
{
    (void)state;
    const mpb_geometry prims[] = {
        {MPB_SHAPE_BOX, {0.4, 0.25, 0.1, 0}, NULL},
        {MPB_SHAPE_SPHERE, {0.15, 0, 0, 0}, NULL},
        {MPB_SHAPE_CYLINDER, {0.1, 0.5, 0, 0}, NULL},
        {MPB_SHAPE_CONE, {0.12, 0.3, 0, 0}, NULL},
        {MPB_SHAPE_CAPSULE, {0.05, 0.4, 0, 0}, NULL},
    };
    mpb_mesh *m = bar(0.8, 0.06, 40);
    mpb_geometry g = {MPB_SHAPE_MESH, {0, 0, 0, 0}, m};
    uint64_t x = 11;
    for (size_t p = 0; p < sizeof prims / sizeof prims[0]; p++) {
        mpb_collision *c;
        assert_int_equal(mpb_collision_create(&c), MPB_OK);
        mpb_pose sp = random_pose(&x, 0.2);
        assert_int_equal(mpb_collision_add_static(c, 1, &prims[p], &sp), MPB_OK);
        assert_int_equal(mpb_collision_add_movable(c, 0, &g, NULL), MPB_OK);
        int positive = 0;
        for (int i = 0; i < 200; i++) {
            mpb_pose pose = random_pose(&x, 1.6);
            assert_int_equal(mpb_collision_set_pose(c, 0, &pose), MPB_OK);
            mpb_collision_distance_result r;
            assert_int_equal(mpb_collision_distance(c, 0, &r), MPB_OK);
            double ref = mpb__collision_distance_brute(c);
            if (ref > 0) {
                positive++;
                if (fabs(r.distance - ref) > 1e-9)
                    fail_msg("%s: %.12g, FCL %.12g", mpb_shape_type_name(prims[p].type),
                             r.distance, ref);
            } else {
                assert_true(r.distance == 0.0);
            }
        }
        assert_true(positive > 100);
        mpb_collision_destroy(c);
    }
    mpb__mesh_destroy(m);
}

/*
 * A mesh whose nearest point lies inside its own hull: the bar bent into
 * a half circle (a U of radius len / pi around the origin), against a box
 * and a sphere held in and around the U. There neither a vertex nor a
 * triangle can be proved nearest by the hull (the hull spans the U's
 * mouth), and the walk must go on to the end of its bounds.
 */
static void concave_mesh_inside(void **state)
{
    (void)state;
    const double len = 1.2, R = len / 3.141592653589793;
    mpb_mesh *m = bar(len, 0.05, 60);
    for (int i = 0; i < m->num_vertices; i++) {
        double *v = &m->vertices[3 * i], th = v[0] / R, r = R - v[1];
        v[0] = r * sin(th);
        v[1] = R - r * cos(th);
    }
    const mpb_geometry prims[] = {
        {MPB_SHAPE_BOX, {0.12, 0.08, 0.2, 0}, NULL},
        {MPB_SHAPE_SPHERE, {0.06, 0, 0, 0}, NULL},
    };
    mpb_geometry g = {MPB_SHAPE_MESH, {0, 0, 0, 0}, m};
    uint64_t x = 5;
    for (size_t p = 0; p < sizeof prims / sizeof prims[0]; p++) {
        mpb_collision *c;
        assert_int_equal(mpb_collision_create(&c), MPB_OK);
        mpb_pose none;
        mpb_pose_identity(&none);
        assert_int_equal(mpb_collision_add_movable(c, 0, &g, &none), MPB_OK);
        assert_int_equal(mpb_collision_add_static(c, 1, &prims[p], &none), MPB_OK);
        int inside = 0;
        for (int i = 0; i < 200; i++) {
            /* the static about the U's centre (0, R), turned at random:
               the U placed by the inverse, the static kept at the origin */
            mpb_pose sp = random_pose(&x, 0.3), up;
            sp.t[1] += R;
            mpb_pose_inverse(&sp, &up);
            assert_int_equal(mpb_collision_set_pose(c, 0, &up), MPB_OK);
            mpb_collision_distance_result r;
            assert_int_equal(mpb_collision_distance(c, 0, &r), MPB_OK);
            double ref = mpb__collision_distance_brute(c);
            if (ref > 0) {
                inside += fabs(sp.t[0]) < 0.1 && sp.t[1] > 0.1;
                if (fabs(r.distance - ref) > 1e-9)
                    fail_msg("%s in the U: %.12g, FCL %.12g",
                             mpb_shape_type_name(prims[p].type), r.distance, ref);
            } else {
                assert_true(r.distance == 0.0);
            }
        }
        assert_true(inside > 30);
        mpb_collision_destroy(c);
    }
    mpb__mesh_destroy(m);
}

/*
 * The nearest static has the largest bounding-sphere lower bound: a small
 * box 5 cm off the bar's tip (its bound ~5 cm), a huge box 20 cm from the
 * bar's side (its sphere's bound far below 0), a sphere 12 cm above the
 * middle. Measured in order of bounds, the huge box comes first; a cutoff
 * taken for the answer, or a bound compared the wrong way, misses the tip.
 * Then the bar turned so that the tip is nearest the huge box instead.
 */
static void cutoff_against_worst_order(void **state)
{
    (void)state;
    mpb_mesh *m = bar(1.0, 0.04, 50);
    mpb_geometry g = {MPB_SHAPE_MESH, {0, 0, 0, 0}, m};
    mpb_collision *c;
    assert_int_equal(mpb_collision_create(&c), MPB_OK);
    assert_int_equal(mpb_collision_add_movable(c, 0, &g, NULL), MPB_OK);
    mpb_geometry small = {MPB_SHAPE_BOX, {0.02, 0.02, 0.02, 0}, NULL};
    mpb_geometry huge = {MPB_SHAPE_BOX, {10, 10, 10, 0}, NULL};
    mpb_geometry ball = {MPB_SHAPE_SPHERE, {0.03, 0, 0, 0}, NULL};
    mpb_pose ps, ph, pb;
    mpb_pose_identity(&ps);
    mpb_pose_identity(&ph);
    mpb_pose_identity(&pb);
    ps.t[0] = 0.5 + 0.05 + 0.01;                /* 5 cm off the tip */
    ph.t[1] = -(0.02 + 0.2 + 5);                /* 20 cm below the side */
    pb.t[2] = 0.02 + 0.12 + 0.03;               /* 12 cm above the middle */
    assert_int_equal(mpb_collision_add_static(c, 1, &small, &ps), MPB_OK);
    assert_int_equal(mpb_collision_add_static(c, 2, &huge, &ph), MPB_OK);
    assert_int_equal(mpb_collision_add_static(c, 3, &ball, &pb), MPB_OK);
    mpb_collision_distance_result r;
    for (int rep = 0; rep < 2; rep++) {        /* the second seeded */
        assert_int_equal(mpb_collision_distance(c, 0, &r), MPB_OK);
        assert_int_equal(r.static_id, 1);
        assert_true(fabs(r.distance - 0.05) < 1e-9);
        assert_true(fabs(r.distance - mpb__collision_distance_brute(c)) < 1e-9);
    }
    /* turn the bar 20 degrees: its -x tip now nearest the huge box
       (the seed, the small box, is no longer the nearest) */
    double a = 20 * 3.141592653589793 / 180;
    mpb_pose tilt = {{cos(a), -sin(a), 0, sin(a), cos(a), 0, 0, 0, 1}, {0, 0, 0}};
    assert_int_equal(mpb_collision_set_pose(c, 0, &tilt), MPB_OK);
    assert_int_equal(mpb_collision_distance(c, 0, &r), MPB_OK);
    double ref = mpb__collision_distance_brute(c);
    assert_int_equal(r.static_id, 2);
    assert_true(ref > 0 && ref < 0.2 && fabs(r.distance - ref) < 1e-9);
    mpb_collision_destroy(c);
    mpb__mesh_destroy(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(panda_random_states),
        cmocka_unit_test(panda_fine_paths),
        cmocka_unit_test(mesh_against_each_primitive),
        cmocka_unit_test(concave_mesh_inside),
        cmocka_unit_test(cutoff_against_worst_order),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
