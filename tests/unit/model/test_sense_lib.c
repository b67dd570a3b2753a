/*
 * test_sense_lib.c - sensing a scene with depth cameras through the
 * library (sense.h): the same seed gives the same text, another seed
 * another; the cells lie on the true box surfaces and the face towards
 * the cameras is seen; the text is a scene; each bad option is refused
 * with one line naming it; an octree overflow names its camera; the
 * default cameras look at the centre of the world objects.
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
#include "mpbench/sense.h"

/* A 0.4 m cube centred at x 1, z 0.7 on a 1 m table top (a thin box):
 * the boxes' centres and half sides. */
static const char CUBE[] =
    "cube\n* cube\n1 0 0.7\n0 0 0 1\n1\nbox\n0.4 0.4 0.4\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n"
    "* top\n1 0 0.48\n0 0 0 1\n1\nbox\n1 1 0.04\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n.\n";
static const double BOX_C[2][3] = {{1, 0, 0.7}, {1, 0, 0.48}};
static const double BOX_H[2][3] = {{0.2, 0.2, 0.2}, {0.5, 0.5, 0.02}};

static mpb_scene *parse(const char *text)
{
    char err[300];
    mpb_scene *s = NULL;
    if (mpb_scene_open_text(text, &s, err, sizeof err) != MPB_OK)
        fail_msg("scene: %s", err);
    return s;
}

static char *sense_text(const mpb_scene *s, const mpb_sense_options *o, long *hits,
                        int *cells)
{
    char why[300], *t = NULL;
    int rc = mpb_scene_sense_text(s, o, &t, hits, cells, why, sizeof why);
    if (rc != MPB_OK)
        fail_msg("sense: %s", why);
    assert_non_null(t);
    return t;
}

static void test_defaults(void **state)
{
    (void)state;
    mpb_sense_options o;
    memset(&o, 0x5a, sizeof o);
    mpb_sense_options_init(&o);
    assert_int_equal(o.num_cameras, 0);
    assert_int_equal(o.width, 160);
    assert_int_equal(o.height, 120);
    assert_true(o.fov == 60 && o.near == 0.3 && o.far == 4);
    assert_true(o.noise == 0.002 && o.resolution == 0.01);
    assert_true(o.seed == 1);
    assert_int_equal(mpb_sense_options_check(&o, NULL, 0), MPB_OK);
}

/* The same options give the same bytes, another seed others; the text is
 * a scene of one octree object holding what mpb_scene_sense() gives. */
static void test_same_seed_same_text(void **state)
{
    (void)state;
    mpb_scene *s = parse(CUBE);
    mpb_sense_options o;
    mpb_sense_options_init(&o);
    o.seed = 7;
    long ha, hb, hc;
    int ca, cb, cc;
    char *a = sense_text(s, &o, &ha, &ca), *b = sense_text(s, &o, &hb, &cb);
    assert_int_equal(o.num_cameras, 0);          /* o is not changed */
    o.seed = 8;
    char *c = sense_text(s, &o, &hc, &cc);
    assert_string_equal(a, b);
    assert_true(ha == hb && ca == cb);
    /* the cells differ, not just the seed in the comment line */
    assert_true(strstr(a, "\noctree ") && strstr(c, "\noctree "));
    assert_string_not_equal(strstr(a, "\noctree "), strstr(c, "\noctree "));
    assert_true(ha > 1000 && ca > 1000);

    /* the text's first lines, and a scene any reader takes */
    char head[300];
    snprintf(head, sizeof head, "cube (sensed)\n.\n# mpb sense: 2 camera(s) 160x120, fov 60, "
             "range 0.3 .. 4 m, noise 0.002 m, seed 7, resolution 0.01 m: %ld hits, %d "
             "cells\n# camera 1 at -0.5 1 1.59 looking at 1 0 0.59\n# camera 2 at -0.5 -1 "
             "1.59 looking at 1 0 0.59\noctree sensed binary 0.01 ", ha, ca);
    assert_memory_equal(a, head, strlen(head));
    mpb_scene *t = parse(a);
    assert_string_equal(mpb_scene_name(t), "cube (sensed)");
    assert_int_equal(mpb_scene_num_objects(t), 1);
    const mpb_scene_object *ob = mpb_scene_object_at(t, 0);
    assert_string_equal(ob->id, "sensed");
    assert_int_equal(ob->kind, MPB_SCENE_OCTREE);
    assert_true(ob->num_shapes > 20);

    /* mpb_scene_sense(): the same tree */
    o.seed = 7;
    mpb_octree *tree = NULL;
    long h;
    char why[300];
    assert_int_equal(mpb_scene_sense(s, &o, &tree, &h, why, sizeof why), MPB_OK);
    assert_int_equal(h, ha);
    assert_int_equal(mpb_octree_num_cells(tree), ca);
    assert_true(mpb_octree_resolution(tree) == 0.01);
    mpb_octree_destroy(tree);

    /* num_cameras 0 is the default cameras given by hand */
    mpb_sense_default_cameras(s, &o);
    assert_int_equal(o.num_cameras, 2);
    char *d = sense_text(s, &o, NULL, NULL);
    assert_string_equal(a, d);
    free(a);
    free(b);
    free(c);
    free(d);
    mpb_scene_close(t);
    mpb_scene_close(s);
}

/* How far p is from the surface of the box at c with half sides h. */
static double box_surface_distance(const double p[3], const double c[3], const double h[3])
{
    double q[3], out = 0, in = -INFINITY;
    for (int k = 0; k < 3; k++) {
        q[k] = fabs(p[k] - c[k]) - h[k];
        out += q[k] > 0 ? q[k] * q[k] : 0;
        in = fmax(in, q[k]);
    }
    return out > 0 ? sqrt(out) : -in;
}

/* Every cell's centre is within half its diagonal and five noise
 * deviations of a true surface, and the cube's face towards the cameras
 * (x 0.8) is seen. */
static void test_cells_lie_on_the_truth(void **state)
{
    (void)state;
    mpb_scene *s = parse(CUBE);
    mpb_sense_options o;
    mpb_sense_options_init(&o);
    o.noise = 0.001;
    o.width = 120;
    o.height = 90;
    mpb_octree *t = NULL;
    char why[300];
    long hits;
    assert_int_equal(mpb_scene_sense(s, &o, &t, &hits, why, sizeof why), MPB_OK);
    int n = mpb_octree_num_cells(t);
    assert_true(n > 1000);
    assert_true(hits >= n);
    int front = 0;
    for (int i = 0; i < n; i++) {
        double c[3], side;
        assert_int_equal(mpb_octree_cell(t, i, c, &side), MPB_OK);
        double d = fmin(box_surface_distance(c, BOX_C[0], BOX_H[0]),
                        box_surface_distance(c, BOX_C[1], BOX_H[1]));
        if (!(d <= side * sqrt(3) / 2 + 5 * o.noise))
            fail_msg("cell %d at %g %g %g is %g m from the boxes", i, c[0], c[1], c[2], d);
        if (fabs(c[0] - 0.8) < 0.011 && fabs(c[1]) < 0.2 && fabs(c[2] - 0.7) < 0.2)
            front++;
    }
    /* the face is 40 x 40 cells; from 2 m at 120 x 90 pixels the rays
       fall about 2 cm apart, two cameras: more than an eighth */
    assert_true(front > 40 * 40 / 8);
    mpb_octree_destroy(t);
    mpb_scene_close(s);
}

/* Each bad option, alone, refused with one line naming it; by the check
 * and by both sensing calls, which leave their outputs NULL. */
static void test_bad_options(void **state)
{
    (void)state;
    static const struct {
        int         field;
        double      value;
        const char *why;
    } bad[] = {
        {0, -1, "num_cameras -1 is outside 0 .. 16"},
        {0, 17, "num_cameras 17 is outside 0 .. 16"},
        {1, 0, "width 0 is outside 1 .. 4096 pixels"},
        {1, 4097, "width 4097 is outside 1 .. 4096 pixels"},
        {2, -3, "height -3 is outside 1 .. 4096 pixels"},
        {3, 0, "fov 0 is outside (0, 170) degrees"},
        {3, 170, "fov 170 is outside (0, 170) degrees"},
        {3, NAN, "fov nan is outside (0, 170) degrees"},
        {4, -0.1, "near -0.1 and far 4 need 0 <= near < far (m)"},
        {4, 4, "near 4 and far 4 need 0 <= near < far (m)"},
        {5, INFINITY, "near 0.3 and far inf need 0 <= near < far (m)"},
        {6, -0.001, "noise -0.001 is not a standard deviation >= 0 m"},
        {6, INFINITY, "noise inf is not a standard deviation >= 0 m"},
        {7, 0, "resolution 0 is outside 0.0001 .. 1 m"},
        {7, 2, "resolution 2 is outside 0.0001 .. 1 m"},
        {8, 0, "camera 2: eye and at are the same point"},
        {9, NAN, "camera 1: a coordinate is not finite"},
    };
    mpb_scene *s = parse(CUBE);
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        mpb_sense_options o;
        mpb_sense_options_init(&o);
        double v = bad[i].value;
        switch (bad[i].field) {
        case 0: o.num_cameras = (int)v; break;
        case 1: o.width = (int)v; break;
        case 2: o.height = (int)v; break;
        case 3: o.fov = v; break;
        case 4: o.near = v; break;
        case 5: o.far = v; break;
        case 6: o.noise = v; break;
        case 7: o.resolution = v; break;
        case 8:
            mpb_sense_default_cameras(s, &o);
            memcpy(o.cameras[1].eye, o.cameras[1].at, sizeof o.cameras[1].at);
            break;
        case 9:
            mpb_sense_default_cameras(s, &o);
            o.cameras[0].at[2] = v;
            break;
        }
        char why[300] = "";
        assert_int_equal(mpb_sense_options_check(&o, why, sizeof why), MPB_EINVAL);
        assert_string_equal(why, bad[i].why);
        mpb_octree *t = (mpb_octree *)&o;
        char *text = (char *)&o;
        why[0] = '\0';
        assert_int_equal(mpb_scene_sense(s, &o, &t, NULL, why, sizeof why), MPB_EINVAL);
        assert_null(t);
        assert_string_equal(why, bad[i].why);
        why[0] = '\0';
        assert_int_equal(mpb_scene_sense_text(s, &o, &text, NULL, NULL, why, sizeof why),
                         MPB_EINVAL);
        assert_null(text);
        assert_string_equal(why, bad[i].why);
    }
    /* NULL arguments, and a NULL why */
    mpb_sense_options o;
    mpb_sense_options_init(&o);
    mpb_octree *t;
    char *text, why[300] = "";
    assert_int_equal(mpb_sense_options_check(NULL, why, sizeof why), MPB_EINVAL);
    assert_true(why[0] != '\0');
    assert_int_equal(mpb_scene_sense(NULL, &o, &t, NULL, NULL, 0), MPB_EINVAL);
    assert_null(t);
    assert_int_equal(mpb_scene_sense(s, NULL, &t, NULL, NULL, 0), MPB_EINVAL);
    assert_int_equal(mpb_scene_sense(s, &o, NULL, NULL, NULL, 0), MPB_EINVAL);
    assert_int_equal(mpb_scene_sense_text(s, NULL, &text, NULL, NULL, NULL, 0), MPB_EINVAL);
    assert_null(text);
    assert_int_equal(mpb_scene_sense_text(s, &o, NULL, NULL, NULL, NULL, 0), MPB_EINVAL);
    mpb_scene_close(s);
}

/* More occupied cells than an octree may hold: MPB_EPARSE naming the
 * camera whose hits went over. A plane seen from 1 m at 0.1 mm cells
 * gives each ray a cell of its own: 600 x 600 from each of two cameras
 * over parts of it far apart, 360,000 cells after the first, 720,000
 * after the second. */
static void test_overflow_names_the_camera(void **state)
{
    (void)state;
    mpb_scene *s = parse("floor\n* floor\n0 0 0\n0 0 0 1\n1\nplane\n0 0 1 0\n0 0 0\n"
                         "0 0 0 1\n0 0 0 0\n0\n.\n");
    mpb_sense_options o;
    mpb_sense_options_init(&o);
    o.width = o.height = 600;
    o.noise = 0;
    o.resolution = MPB_OCTREE_MIN_RESOLUTION;
    o.num_cameras = 1;
    o.cameras[0] = (mpb_camera){{0, 0, 1}, {0, 0, 0}};
    mpb_octree *t = NULL;
    long hits;
    char why[300];
    assert_int_equal(mpb_scene_sense(s, &o, &t, &hits, why, sizeof why), MPB_OK);
    assert_int_equal(hits, 600 * 600);
    assert_int_equal(mpb_octree_num_cells(t), 600 * 600);
    mpb_octree_destroy(t);
    o.num_cameras = 2;
    o.cameras[1] = (mpb_camera){{2, 0, 1}, {2, 0, 0}};
    t = (mpb_octree *)&o;
    assert_int_equal(mpb_scene_sense(s, &o, &t, &hits, why, sizeof why), MPB_EPARSE);
    assert_null(t);
    assert_string_equal(why, "camera 2: more occupied cells than an octree may hold");
    char *text = (char *)&o;
    assert_int_equal(mpb_scene_sense_text(s, &o, &text, NULL, NULL, why, sizeof why),
                     MPB_EPARSE);
    assert_null(text);
    assert_string_equal(why, "camera 2: more occupied cells than an octree may hold");
    mpb_scene_close(s);
}

/* The default cameras look at the mean of the world objects' shape
 * positions: planes and carried objects left out; the origin without
 * any. */
static void test_default_cameras(void **state)
{
    (void)state;
    /* the cube and the top (centres x 1, z 0.7 and 0.48), a cup of two
       shapes at y 0.3 and 0.5, z 0.5 (rotated a quarter turn about z: its
       shape at x 0.2 in its frame is at y 0.2 beyond it), a floor plane
       and a carried box far away */
    static const char text[] =
        "mix\n* cube\n1 0 0.7\n0 0 0 1\n1\nbox\n0.4 0.4 0.4\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n"
        "* top\n1 0 0.48\n0 0 0 1\n1\nbox\n1 1 0.04\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n"
        "* cup\n1 0.3 0.5\n0 0 0.7071067811865476 0.7071067811865476\n2\n"
        "cylinder\n0.04 0.1\n0 0 0\n0 0 0 1\n0 0 0 0\n"
        "sphere\n0.02\n0.2 0 0\n0 0 0 1\n0 0 0 0\n0\n"
        "* floor\n0 0 0\n0 0 0 1\n1\nplane\n0 0 1 0\n5 5 5\n0 0 0 1\n0 0 0 0\n0\n"
        "* held\n9 9 9\n0 0 0 1\n1\nbox\n0.1 0.1 0.1\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n"
        ".\nattach held hand\n";
    mpb_scene *s = parse(text);
    mpb_sense_options o;
    mpb_sense_options_init(&o);
    o.width = 33;           /* left alone */
    mpb_sense_default_cameras(s, &o);
    assert_int_equal(o.num_cameras, 2);
    assert_int_equal(o.width, 33);
    const double c[3] = {1, (0.3 + 0.5) / 4, (0.7 + 0.48 + 0.5 + 0.5) / 4};
    for (int i = 0; i < 2; i++) {
        const double eye[3] = {c[0] - 1.5, c[1] + (i ? -1 : 1), c[2] + 1};
        for (int k = 0; k < 3; k++) {
            assert_true(fabs(o.cameras[i].at[k] - c[k]) < 1e-12);
            assert_true(fabs(o.cameras[i].eye[k] - eye[k]) < 1e-12);
        }
    }
    mpb_scene_close(s);

    /* an empty scene: the origin */
    s = parse("empty\n.\n");
    mpb_sense_default_cameras(s, &o);
    assert_int_equal(o.num_cameras, 2);
    for (int k = 0; k < 3; k++)
        assert_true(o.cameras[0].at[k] == 0 && o.cameras[1].at[k] == 0);
    assert_true(o.cameras[0].eye[0] == -1.5 && o.cameras[0].eye[1] == 1 &&
                o.cameras[0].eye[2] == 1 && o.cameras[1].eye[1] == -1);
    /* and what they see of it: nothing, an empty octree, still a scene */
    long hits = -1;
    int cells = -1;
    char *t = sense_text(s, &o, &hits, &cells);
    assert_int_equal(hits, 0);
    assert_int_equal(cells, 0);
    mpb_scene *back = parse(t);
    assert_int_equal(mpb_scene_num_objects(back), 1);
    assert_int_equal(mpb_scene_object_at(back, 0)->num_shapes, 0);
    free(t);
    mpb_scene_close(back);
    mpb_scene_close(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults),
        cmocka_unit_test(test_same_seed_same_text),
        cmocka_unit_test(test_cells_lie_on_the_truth),
        cmocka_unit_test(test_bad_options),
        cmocka_unit_test(test_overflow_names_the_camera),
        cmocka_unit_test(test_default_cameras),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
