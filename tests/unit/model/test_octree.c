/*
 * test_octree.c - occupancy octrees (octree.h) and their scenes: cells
 * and pruning, OctoMap's .bt and .ot round trips, and the octree of a
 * box's surface in a collision world and under certified verification.
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
#include "mpbench/octree.h"
#include "mpbench/scene.h"
#include "mpbench/verify.h"
#include "mpbench/world.h"

#include "test_octree_box.h"

static const char BOX_SCENE[] =
    "box\n* box\n0.65 0 0.4\n0 0 0 1\n1\nbox\n0.29 0.39 0.39\n0 0 0\n0 0 0 1\n"
    "0 0 0 0\n0\n.\n";

/* The scene text of the octree file at path, resolved. */
static char *octree_scene(const char *path)
{
    char text[600], err[300], *out = NULL;
    snprintf(text, sizeof text, "octree\n.\noctree box file %s\n", path);
    int rc = mpb_scene_resolve(text, NULL, &out, err, sizeof err);
    if (rc != MPB_OK)
        fail_msg("resolve: %s", err);
    return out;
}

static void test_cells_and_pruning(void **state)
{
    (void)state;
    mpb_octree *o;
    assert_int_equal(mpb_octree_create(0.01, &o), MPB_OK);
    double p[3] = {0.013, -0.002, 0.0};
    assert_int_equal(mpb_octree_add_point(o, p), MPB_OK);
    assert_int_equal(mpb_octree_add_point(o, p), MPB_OK);   /* the same cell */
    assert_int_equal(mpb_octree_num_cells(o), 1);
    double c[3], side;
    assert_int_equal(mpb_octree_cell(o, 0, c, &side), MPB_OK);
    assert_true(fabs(c[0] - 0.015) < 1e-12 && fabs(c[1] + 0.005) < 1e-12 &&
                fabs(c[2] - 0.005) < 1e-12);
    assert_true(fabs(side - 0.01) < 1e-15);
    /* the 8 cells of an aligned 2 cm cube are one cell */
    mpb_octree_destroy(o);
    assert_int_equal(mpb_octree_create(0.01, &o), MPB_OK);
    for (int i = 0; i < 8; i++) {
        double q[3] = {0.205 + 0.01 * (i & 1), 0.005 + 0.01 * (i >> 1 & 1),
                       -0.015 + 0.01 * (i >> 2 & 1)};
        assert_int_equal(mpb_octree_add_point(o, q), MPB_OK);
    }
    assert_int_equal(mpb_octree_num_cells(o), 1);
    assert_int_equal(mpb_octree_cell(o, 0, c, &side), MPB_OK);
    assert_true(fabs(side - 0.02) < 1e-15);
    assert_true(fabs(c[0] - 0.21) < 1e-12 && fabs(c[1] - 0.01) < 1e-12 &&
                fabs(c[2] + 0.01) < 1e-12);
    assert_int_equal(mpb_octree_cell(o, 1, c, &side), MPB_EINVAL);
    /* beyond the root cube, not finite */
    double far[3] = {0.01 * 32768, 0, 0}, nan3[3] = {NAN, 0, 0};
    assert_int_equal(mpb_octree_add_point(o, far), MPB_EINVAL);
    assert_int_equal(mpb_octree_add_point(o, nan3), MPB_EINVAL);
    mpb_octree_destroy(o);
    assert_int_equal(mpb_octree_create(0, &o), MPB_EINVAL);
    assert_int_equal(mpb_octree_create(NAN, &o), MPB_EINVAL);
    mpb_octree_destroy(NULL);
}

/* What a tree writes reads back as the same cells and the same bytes,
 * as .bt and as the bare binary stream. */
static void test_bt_round_trip(void **state)
{
    (void)state;
    mpb_octree *o = test_box_octree(), *back;
    int n = mpb_octree_num_cells(o);
    assert_true(n > 4000);
    unsigned char *bt, *bt2, *raw;
    size_t nbt, nbt2, nraw;
    assert_int_equal(mpb_octree_write(o, 1, &bt, &nbt), MPB_OK);
    assert_int_equal(mpb_octree_write(o, 0, &raw, &nraw), MPB_OK);
    assert_true(nbt > nraw);
    assert_memory_equal(bt + nbt - nraw, raw, nraw);
    assert_memory_equal(bt, "# Octomap OcTree binary file\n", 29);
    char err[200];
    assert_int_equal(mpb_octree_create_from_bytes(bt, nbt, "box.bt", &back, err, sizeof err),
                     MPB_OK);
    assert_int_equal(mpb_octree_num_cells(back), n);
    assert_true(mpb_octree_resolution(back) == 0.01);
    assert_int_equal(mpb_octree_write(back, 1, &bt2, &nbt2), MPB_OK);
    assert_int_equal(nbt2, nbt);
    assert_memory_equal(bt2, bt, nbt);
    for (int i = 0; i < n; i += 97) {
        double a[3], b[3], sa, sb;
        assert_int_equal(mpb_octree_cell(o, i, a, &sa), MPB_OK);
        assert_int_equal(mpb_octree_cell(back, i, b, &sb), MPB_OK);
        assert_memory_equal(a, b, sizeof a);
        assert_true(sa == sb);
    }
    mpb_octree_destroy(back);
    assert_int_equal(mpb_octree_create_from_stream(raw, nraw, 0.01, 1, NULL, &back, err,
                                                   sizeof err), MPB_OK);
    assert_int_equal(mpb_octree_num_cells(back), n);
    mpb_octree_destroy(back);
    free(bt);
    free(bt2);
    free(raw);
    mpb_octree_destroy(o);
}

/* A .ot (full data: log-odds per node) of two leaves, one occupied, one
 * free, under a chain of inner nodes, made by hand. */
static void test_ot_file(void **state)
{
    (void)state;
    unsigned char data[16 * 5 + 10];
    size_t n = 0;
    float inner = 1.0f, occ = 2.0f, freev = -2.0f;
    for (int d = 0; d < 15; d++) {  /* the root: child 0; 14 more: child 7 */
        memcpy(data + n, &inner, 4);
        data[n + 4] = d == 0 ? 0x01 : 0x80;
        n += 5;
    }
    memcpy(data + n, &inner, 4);             /* level 1: children 0 and 1 */
    data[n + 4] = 0x03;
    n += 5;
    memcpy(data + n, &occ, 4);
    data[n + 4] = 0;
    n += 5;
    memcpy(data + n, &freev, 4);
    data[n + 4] = 0;
    n += 5;
    char file[400];
    int h = snprintf(file, sizeof file, "# Octomap OcTree file\n# hand made\nid OcTree\n"
                     "size 18\nres 0.05\ndata\n");
    memcpy(file + h, data, n);
    mpb_octree *o;
    char err[200];
    assert_int_equal(mpb_octree_create_from_bytes(file, (size_t)h + n, "t.ot", &o, err,
                                                  sizeof err), MPB_OK);
    assert_int_equal(mpb_octree_num_cells(o), 1);
    double c[3], side;
    assert_int_equal(mpb_octree_cell(o, 0, c, &side), MPB_OK);
    /* child 0, child 7 to level 1, child 0: key 32766 in x, y and z, the
       cell from -0.1 to -0.05 */
    assert_true(fabs(side - 0.05) < 1e-12);
    for (int k = 0; k < 3; k++)
        assert_true(fabs(c[k] - (-0.1 + 0.025)) < 1e-9);
    mpb_octree_destroy(o);
}

/* The octree of the box's surface collides where the box does, and is
 * free 2 cm away, 1.5 cm from its cells. */
static void test_box_surface_collision(void **state)
{
    (void)state;
    char *dir = test_tmpdir(), *bt = test_box_bt(dir);
    char *text = octree_scene(bt);
    mpb_collision *oc = test_probe_world(text, 0.01), *bx = test_probe_world(BOX_SCENE, 0.01);
    mpb_scene *s;
    char err[200];
    assert_int_equal(mpb_scene_open_text(text, &s, err, sizeof err), MPB_OK);
    const mpb_scene_object *ob = mpb_scene_object_at(s, 0);
    assert_int_equal(ob->kind, MPB_SCENE_OCTREE);
    assert_true(ob->resolution == 0.01);
    /* the boxes are the cells: the same volume, far fewer shapes */
    mpb_octree *tree = test_box_octree();
    int cells = mpb_octree_num_cells(tree);
    double vc = 0, vb = 0;
    for (int i = 0; i < cells; i++) {
        double c[3], side;
        assert_int_equal(mpb_octree_cell(tree, i, c, &side), MPB_OK);
        vc += side * side * side;
    }
    for (int i = 0; i < ob->num_shapes; i++) {
        const double *d = ob->shapes[i].geometry.dims;
        assert_int_equal(ob->shapes[i].geometry.type, MPB_SHAPE_BOX);
        vb += d[0] * d[1] * d[2];
    }
    assert_true(cells > 4000 && ob->num_shapes * 10 < cells);
    assert_true(fabs(vb - vc) < 1e-9 * vc);
    mpb_octree_destroy(tree);
    mpb_scene_close(s);
    /* on each face (and 8 mm inside or outside it): both collide */
    unsigned seed = 7;
    for (int i = 0; i < 600; i++) {
        int axis = i % 3, side = (i / 3) % 2;
        double p[3];
        for (int k = 0; k < 3; k++) {
            seed = seed * 1103515245u + 12345u;
            double u = (seed >> 8) / (double)(1u << 24);
            p[k] = TEST_BOX_LO[k] + u * (TEST_BOX_HI[k] - TEST_BOX_LO[k]);
        }
        double off = ((int)(i / 6) % 3 - 1) * 0.008;
        p[axis] = (side ? TEST_BOX_HI[axis] : TEST_BOX_LO[axis]) + off;
        assert_int_equal(test_probe(bx, p, NULL), 1);
        assert_int_equal(test_probe(oc, p, NULL), 1);
    }
    mpb_collision_destroy(oc);
    mpb_collision_destroy(bx);
    /* 2 cm from the middle of each face, a 1 mm probe: free in both, its
       distance to the cells 2 cm - 5 mm - 1 mm */
    oc = test_probe_world(text, 0.001);
    bx = test_probe_world(BOX_SCENE, 0.001);
    for (int axis = 0; axis < 3; axis++)
        for (int side = 0; side < 2; side++) {
            double p[3], d;
            for (int k = 0; k < 3; k++)
                p[k] = (TEST_BOX_LO[k] + TEST_BOX_HI[k]) / 2;
            p[axis] = side ? TEST_BOX_HI[axis] + 0.02 : TEST_BOX_LO[axis] - 0.02;
            assert_int_equal(test_probe(bx, p, &d), 0);
            assert_true(fabs(d - 0.019) < 1e-6);
            assert_int_equal(test_probe(oc, p, &d), 0);
            assert_true(fabs(d - 0.014) < 1e-6);
        }
    mpb_collision_destroy(oc);
    mpb_collision_destroy(bx);
    free(text);
    unlink(bt);
    rmdir(dir);
    free(bt);
    free(dir);
}

/* A ball of radius 1 cm on three prismatic joints x, y, z from the origin. */
static const char BALL_URDF[] =
    "<robot name='ball'><link name='base'/><link name='lx'/><link name='ly'/>"
    "<link name='ball'><collision><geometry><sphere radius='0.01'/></geometry>"
    "</collision></link>"
    "<joint name='x' type='prismatic'><parent link='base'/><child link='lx'/>"
    "<axis xyz='1 0 0'/><limit lower='-2' upper='2' effort='1' velocity='1'/></joint>"
    "<joint name='y' type='prismatic'><parent link='lx'/><child link='ly'/>"
    "<axis xyz='0 1 0'/><limit lower='-2' upper='2' effort='1' velocity='1'/></joint>"
    "<joint name='z' type='prismatic'><parent link='ly'/><child link='ball'/>"
    "<axis xyz='0 0 1'/><limit lower='-2' upper='2' effort='1' velocity='1'/></joint>"
    "</robot>";

static mpb_verdict verify_line(mpb_world *w, double x)
{
    double wp[6] = {x, -0.5, 0.4, x, 0.5, 0.4};
    mpb_goal g = {.kind = MPB_GOAL_JOINTS, .joints = wp + 3, .joint_tolerance = 1e-9};
    mpb_verdict v;
    assert_int_equal(mpb_verify_path(w, wp, 1e-9, &g, wp, 2, 3, 0.05, &v), MPB_OK);
    return v;
}

/* Certified verification over the octree's cells: a sweep past its -x
 * side 5 mm from the cells is proved free; one 1 mm into them (4 mm
 * short of the true box) collides, as the sampled check at 5 cm steps
 * would miss no more than it does here. */
static void test_certified_graze(void **state)
{
    (void)state;
    char *dir = test_tmpdir(), *bt = test_box_bt(dir);
    char *text = octree_scene(bt);
    static const char *const joints[] = {"x", "y", "z"};
    mpb_world *w = NULL;
    char err[300];
    int rc = mpb_world_open_group("urdf", BALL_URDF, "moveit-scene", text, joints, 3,
                                  &w, err, sizeof err);
    if (rc != MPB_OK)
        fail_msg("open: %s", err);
    /* the cells start at x = 0.50; the ball's radius is 1 cm */
    mpb_verdict v = verify_line(w, 0.50 - 0.005 - 0.01);
    assert_int_equal(v.code, MPB_VERDICT_VALID);
    assert_int_equal(v.certified, 1);
    double q[3] = {0.50 - 0.005 - 0.01, 0.0, 0.4};
    double d = mpb_world_clearance(w, q);
    assert_true(fabs(d - 0.005) < 1e-6);
    v = verify_line(w, 0.50 + 0.001 - 0.01);
    assert_int_equal(v.code, MPB_VERDICT_COLLISION);
    mpb_world_close(w);
    /* the true box: that sweep is free, 4 mm from it */
    rc = mpb_world_open_group("urdf", BALL_URDF, "moveit-scene", BOX_SCENE, joints, 3,
                              &w, err, sizeof err);
    assert_int_equal(rc, MPB_OK);
    v = verify_line(w, 0.50 + 0.001 - 0.01);
    assert_int_equal(v.code, MPB_VERDICT_VALID);
    assert_int_equal(v.certified, 1);
    mpb_world_close(w);
    free(text);
    unlink(bt);
    rmdir(dir);
    free(bt);
    free(dir);
}

/* A scene file names its octree beside it; the inline text is what
 * travels, and its hash changes with the octree's bytes. */
static void test_scene_file_names_octree(void **state)
{
    (void)state;
    char *dir = test_tmpdir(), *bt = test_box_bt(dir);
    char path[300], err[300];
    snprintf(path, sizeof path, "%s/s.scene", dir);
    const char *text = "s\n.\n# the map beside this file\n"
                       "octree map file box.bt 1 0 0 0 0 0 1\n";
    test_write_bytes(path, text, strlen(text));
    mpb_scene *s;
    assert_int_equal(mpb_scene_open(path, &s, err, sizeof err), MPB_OK);
    assert_int_equal(mpb_scene_num_objects(s), 1);
    const mpb_scene_object *o = mpb_scene_object_at(s, 0);
    assert_string_equal(o->id, "map");
    assert_true(o->pose.t[0] == 1.0);
    mpb_scene_close(s);
    /* parse alone refuses a file */
    assert_int_equal(mpb_scene_open_text(text, &s, err, sizeof err), MPB_EPARSE);
    assert_non_null(strstr(err, "scene line 4: octree 'map' names a file"));
    unlink(path);
    unlink(bt);
    rmdir(dir);
    free(bt);
    free(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cells_and_pruning),
        cmocka_unit_test(test_bt_round_trip),
        cmocka_unit_test(test_ot_file),
        cmocka_unit_test(test_box_surface_collision),
        cmocka_unit_test(test_certified_graze),
        cmocka_unit_test(test_scene_file_names_octree),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
