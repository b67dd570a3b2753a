/*
 * test_octree_box.h - what the octree tests share (test_octree.c,
 * test_moveit.c): the octree of a box's surface at 1 cm, written as a .bt
 * file in a fresh temporary folder, and probes of a collision world with
 * a small sphere. Include it after <cmocka.h>.
 *
 * The box: x 0.505 .. 0.795, y -0.195 .. 0.195, z 0.205 .. 0.595, its
 * faces through the middle of 1 cm cells, so that the cells holding its
 * surface reach 5 mm beyond each face: the octree's outside is the box
 * grown by 5 mm (x 0.50 .. 0.80, ...).
 */
#ifndef MPB_TEST_OCTREE_BOX_H
#define MPB_TEST_OCTREE_BOX_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mpbench/mpbench.h"
#include "mpbench/collision.h"
#include "mpbench/octree.h"
#include "mpbench/scene.h"

static const double TEST_BOX_LO[3] = {0.505, -0.195, 0.205};
static const double TEST_BOX_HI[3] = {0.795, 0.195, 0.595};
#define TEST_BOX_RES 0.01

/* Points every 2.5 mm over the box's six faces into o. */
static inline void test_box_surface(mpb_octree *o)
{
    const double step = 0.0025;
    for (int axis = 0; axis < 3; axis++)
        for (int side = 0; side < 2; side++) {
            int u = (axis + 1) % 3, v = (axis + 2) % 3;
            int nu = (int)((TEST_BOX_HI[u] - TEST_BOX_LO[u]) / step + 0.5);
            int nv = (int)((TEST_BOX_HI[v] - TEST_BOX_LO[v]) / step + 0.5);
            for (int i = 0; i <= nu; i++)
                for (int j = 0; j <= nv; j++) {
                    double p[3];
                    p[axis] = side ? TEST_BOX_HI[axis] : TEST_BOX_LO[axis];
                    p[u] = TEST_BOX_LO[u] + (TEST_BOX_HI[u] - TEST_BOX_LO[u]) * i / nu;
                    p[v] = TEST_BOX_LO[v] + (TEST_BOX_HI[v] - TEST_BOX_LO[v]) * j / nv;
                    assert_int_equal(mpb_octree_add_point(o, p), MPB_OK);
                }
        }
}

static inline mpb_octree *test_box_octree(void)
{
    mpb_octree *o = NULL;
    assert_int_equal(mpb_octree_create(TEST_BOX_RES, &o), MPB_OK);
    test_box_surface(o);
    return o;
}

/* A fresh temporary folder (the test removes what it writes there). */
static inline char *test_tmpdir(void)
{
    char *d = strdup("/tmp/mpb_octree_XXXXXX");
    assert_non_null(d);
    assert_non_null(mkdtemp(d));
    return d;
}

static inline void test_write_bytes(const char *path, const void *b, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(b, 1, n, f), n);
    assert_int_equal(fclose(f), 0);
}

/* The box octree as a .bt file at dir/box.bt; its path (free it). */
static inline char *test_box_bt(const char *dir)
{
    mpb_octree *o = test_box_octree();
    unsigned char *b;
    size_t n;
    assert_int_equal(mpb_octree_write(o, 1, &b, &n), MPB_OK);
    char *path = malloc(strlen(dir) + 16);
    assert_non_null(path);
    sprintf(path, "%s/box.bt", dir);
    test_write_bytes(path, b, n);
    free(b);
    mpb_octree_destroy(o);
    return path;
}

/* A collision world of scene text's statics, with a movable sphere 0 of
 * radius r. */
static inline mpb_collision *test_probe_world(const char *scene_text, double r)
{
    mpb_scene *s = NULL;
    char err[300];
    int rc = mpb_scene_open_text(scene_text, &s, err, sizeof err);
    if (rc != MPB_OK)
        fail_msg("scene: %s", err);
    mpb_collision *c = NULL;
    assert_int_equal(mpb_collision_create(&c), MPB_OK);
    assert_int_equal(mpb_scene_add_statics(s, c), MPB_OK);
    mpb_geometry g = {.type = MPB_SHAPE_SPHERE, .dims = {r, 0, 0, 0}};
    assert_int_equal(mpb_collision_add_movable(c, 0, &g, NULL), MPB_OK);
    mpb_scene_close(s);
    return c;
}

/* Does the probe at p collide; its distance in *d (if not NULL). */
static inline int test_probe(mpb_collision *c, const double p[3], double *d)
{
    mpb_pose pose;
    mpb_pose_identity(&pose);
    memcpy(pose.t, p, sizeof pose.t);
    assert_int_equal(mpb_collision_set_pose(c, 0, &pose), MPB_OK);
    int hit = mpb_collision_check(c, NULL, NULL);
    assert_true(hit >= 0);
    if (d) {
        mpb_collision_distance_result r;
        assert_int_equal(mpb_collision_distance(c, 0, &r), MPB_OK);
        *d = r.distance;
    }
    return hit;
}

#endif /* MPB_TEST_OCTREE_BOX_H */
