/*
 * test_sense.c - `mpb sense`, run as a user runs it: the same seed gives
 * the same bytes, another seed others; what it writes is a scene whose
 * octree cells lie on the true geometry and cover the faces the cameras
 * see; bad options get one line.
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
#include "mpbench/collision.h"
#include "mpbench/scene.h"
#include "test_tool.h"

static char mpb_tool[4096];
static char dir[64];

/* A 0.4 m cube at x 1 on a 1 m table top (a thin box). */
static const char SCENE[] =
    "cube\n* cube\n1 0 0.7\n0 0 0 1\n1\nbox\n0.4 0.4 0.4\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n"
    "* top\n1 0 0.48\n0 0 0 1\n1\nbox\n1 1 0.04\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n.\n";

static int setup(void **state)
{
    (void)state;
    if (test_built_program("tools/mpb", mpb_tool, sizeof mpb_tool) != 0)
        return -1;
    test_make_dir(dir, sizeof dir, "sense");
    char path[128];
    snprintf(path, sizeof path, "%s/cube.scene", dir);
    FILE *f = fopen(path, "w");
    if (!f || fputs(SCENE, f) < 0 || fclose(f) != 0)
        return -1;
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    test_remove_dir(dir);
    return 0;
}

static char *slurp(const char *name, size_t *n)
{
    char path[160];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    char *t = mpb_read_file(path, 0, n);
    assert_non_null(t);
    return t;
}

static void same_seed_same_bytes(void **state)
{
    (void)state;
    test_output o;
    const char *seeds[3] = {"7", "7", "8"};
    const char *names[3] = {"a.scene", "b.scene", "c.scene"};
    for (int i = 0; i < 3; i++) {
        test_run(&o, mpb_tool, "both", "sense %s/cube.scene -o %s/%s --seed %s", dir, dir,
                 names[i], seeds[i]);
        if (o.status != 0)
            fail_msg("%s", o.text);
    }
    size_t na, nb, nc;
    char *a = slurp("a.scene", &na), *b = slurp("b.scene", &nb), *c = slurp("c.scene", &nc);
    assert_int_equal(na, nb);
    assert_memory_equal(a, b, na);
    assert_true(na != nc || memcmp(a, c, na) != 0);
    free(a);
    free(b);
    free(c);
}

/* Every sensed cell is on the true surfaces (its centre within half a
 * cell's diagonal and five noise deviations of them), and the cube's
 * face towards the cameras (-x) is seen. */
static void cells_lie_on_the_truth(void **state)
{
    (void)state;
    test_output o;
    test_run(&o, mpb_tool, "both", "sense %s/cube.scene -o %s/s.scene --noise 0.001 "
             "--seed 1 --width 120 --height 90", dir, dir);
    if (o.status != 0)
        fail_msg("%s", o.text);
    char path[160], err[300];
    snprintf(path, sizeof path, "%s/s.scene", dir);
    mpb_scene *sensed, *truth;
    assert_int_equal(mpb_scene_open(path, &sensed, err, sizeof err), MPB_OK);
    assert_int_equal(mpb_scene_open_text(SCENE, &truth, err, sizeof err), MPB_OK);
    assert_int_equal(mpb_scene_num_objects(sensed), 1);
    const mpb_scene_object *oc = mpb_scene_object_at(sensed, 0);
    assert_int_equal(oc->kind, MPB_SCENE_OCTREE);
    assert_true(oc->num_shapes > 20);
    mpb_collision *c;
    assert_int_equal(mpb_collision_create(&c), MPB_OK);
    assert_int_equal(mpb_scene_add_statics(truth, c), MPB_OK);
    mpb_geometry g = {.type = MPB_SHAPE_SPHERE, .dims = {1e-5, 0, 0, 0}};
    assert_int_equal(mpb_collision_add_movable(c, 0, &g, NULL), MPB_OK);
    /* each box is a union of cells whose centres are within half a
       diagonal and the noise of the truth: any point of it, within a
       diagonal more */
    const double near = 0.01 * sqrt(3) * 1.5 + 0.005;
    double front = 0;
    for (int i = 0; i < oc->num_shapes; i++) {
        const mpb_scene_shape *sh = &oc->shapes[i];
        const double *d = sh->geometry.dims;
        for (int corner = 0; corner < 9; corner++) {
            mpb_pose p;
            mpb_pose_identity(&p);
            for (int k = 0; k < 3; k++)
                p.t[k] = sh->pose.t[k] + (corner == 8 ? 0 : ((corner >> k & 1) ? 0.5 : -0.5) * d[k]);
            assert_int_equal(mpb_collision_set_pose(c, 0, &p), MPB_OK);
            mpb_collision_distance_result r;
            assert_int_equal(mpb_collision_distance(c, 0, &r), MPB_OK);
            assert_true(r.distance < near);
        }
        if (fabs(sh->pose.t[0] - 0.8) < 0.011 && fabs(sh->pose.t[1]) < 0.2 &&
            fabs(sh->pose.t[2] - 0.7) < 0.2)
            front += d[1] * d[2];
    }
    /* the face towards the cameras is seen: more than an eighth of it
       (at 120 x 90 pixels from 2 m the rays fall about 2 cm apart) */
    assert_true(front > 0.4 * 0.4 / 8);
    mpb_collision_destroy(c);
    mpb_scene_close(sensed);
    mpb_scene_close(truth);
}

static void bad_options_get_one_line(void **state)
{
    (void)state;
    test_output o;
    test_run(&o, mpb_tool, "stderr", "sense %s/cube.scene -o %s/x.scene --resolution 0",
             dir, dir);
    assert_int_equal(o.status, 2);
    assert_string_equal(o.text, "mpb sense: --resolution needs 0.0001 .. 1 m, not '0'\n");
    test_run(&o, mpb_tool, "stderr", "sense %s/none.scene -o %s/x.scene", dir, dir);
    assert_int_equal(o.status, 1);
    assert_non_null(strstr(o.text, "none.scene: cannot open"));
    assert_ptr_equal(strchr(o.text, '\n'), o.text + strlen(o.text) - 1);   /* one line */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(same_seed_same_bytes),
        cmocka_unit_test(cells_lie_on_the_truth),
        cmocka_unit_test(bad_options_get_one_line),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
