/*
 * test_scene.c - MoveIt .scene files: the newer variant with every shape
 * type, object poses and subframes (data/scene_tabletop.scene), the older
 * one (data/scene_old_format.scene), mpbench's attach lines, the content
 * hash, a scene placed in a collision world, and malformed input giving
 * one-line errors with the right line number.
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
#include "geometry/collision_internal.h"

#define assert_near(a, b, eps)                                              \
    do {                                                                    \
        double a_ = (a), b_ = (b);                                          \
        if (!(fabs(a_ - b_) <= (eps)))                                      \
            fail_msg("%s = %.17g, expected %.17g (line %d)", #a, a_, b_,    \
                     __LINE__);                                             \
    } while (0)

/* tests/support/data/<name> (MPB_TEST_DATA). */
static void data_path(char *out, size_t len, const char *name)
{
    snprintf(out, len, "%s/%s", MPB_TEST_DATA, name);
}

static char *read_all(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        fail_msg("cannot open %s", path);
    static char buf[1 << 16];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    return buf;
}

static mpb_scene *load_ok(const char *name)
{
    char path[512], err[300];
    data_path(path, sizeof path, name);
    mpb_scene *s = NULL;
    int rc = mpb_scene_open(path, &s, err, sizeof err);
    if (rc != MPB_OK)
        fail_msg("%s: %s", mpb_err_name(rc), err);
    return s;
}

static mpb_scene *parse_ok(const char *text)
{
    mpb_scene *s = NULL;
    char err[300];
    int rc = mpb_scene_open_text(text, &s, err, sizeof err);
    if (rc != MPB_OK)
        fail_msg("%s: %s", mpb_err_name(rc), err);
    return s;
}

static void expect_rotation(const mpb_pose *p, double x, double y, double z, double w)
{
    mpb_pose q;
    mpb_pose_set_quat(&q, x, y, z, w);
    for (int i = 0; i < 9; i++)
        assert_near(p->R[i], q.R[i], 1e-12);
}

static void test_new_variant(void **state)
{
    (void)state;
    mpb_scene *s = load_ok("scene_tabletop.scene");
    assert_string_equal(mpb_scene_name(s), "tabletop");
    assert_int_equal(mpb_scene_variant_of(s), MPB_SCENE_NEW);
    assert_int_equal(mpb_scene_num_objects(s), 5);

    /* the hash is of the text as given */
    char path[512], hash[MPB_HASH_SIZE];
    data_path(path, sizeof path, "scene_tabletop.scene");
    const char *text = read_all(path);
    mpb_hash_hex(text, strlen(text), hash);
    assert_string_equal(mpb_scene_hash(s), hash);

    const mpb_scene_object *o = mpb_scene_object_at(s, 0);
    assert_string_equal(o->id, "table");
    assert_int_equal(o->line, 2);
    assert_near(o->pose.t[0], 0.7, 0);
    assert_near(o->pose.t[2], 0.4, 0);
    expect_rotation(&o->pose, 0, 0, 0, 1);
    assert_int_equal(o->num_shapes, 1);
    assert_int_equal(o->shapes[0].geometry.type, MPB_SHAPE_BOX);
    assert_near(o->shapes[0].geometry.dims[1], 1.2, 0);
    assert_near(o->shapes[0].color[0], 0.5, 1e-7);
    assert_near(o->shapes[0].color[3], 1.0, 0);
    assert_int_equal(o->shapes[0].line, 6);
    assert_int_equal(o->num_subframes, 0);
    assert_null(o->attached_link);

    /* an id with a space; a normalised quaternion; two shapes; a subframe */
    assert_int_equal(mpb_scene_find(s, "cup 1"), 1);
    o = mpb_scene_object_at(s, 1);
    expect_rotation(&o->pose, 0, 0, 0.382683, 0.92388);
    assert_near(o->pose.R[0], cos(M_PI / 4), 1e-6);
    assert_int_equal(o->num_shapes, 2);
    assert_int_equal(o->shapes[0].geometry.type, MPB_SHAPE_CYLINDER);
    assert_near(o->shapes[0].geometry.dims[0], 0.04, 0);
    assert_near(o->shapes[0].geometry.dims[1], 0.12, 0);
    assert_int_equal(o->shapes[1].geometry.type, MPB_SHAPE_SPHERE);
    assert_near(o->shapes[1].pose.t[0], 0.05, 0);
    assert_near(o->shapes[1].pose.t[2], 0.04, 0);
    assert_int_equal(o->num_subframes, 1);
    assert_string_equal(o->subframes[0].name, "handle");
    assert_near(o->subframes[0].pose.t[0], 0.05, 0);

    o = mpb_scene_object_at(s, 2);      /* a cone turned upside down */
    assert_int_equal(o->shapes[0].geometry.type, MPB_SHAPE_CONE);
    assert_near(o->pose.t[2], 1e-6, 0);
    expect_rotation(&o->shapes[0].pose, 1, 0, 0, 0);
    assert_near(o->shapes[0].pose.R[8], -1, 1e-15);

    o = mpb_scene_object_at(s, 3);
    assert_int_equal(o->shapes[0].geometry.type, MPB_SHAPE_PLANE);
    assert_near(o->shapes[0].geometry.dims[2], 1, 0);

    o = mpb_scene_object_at(s, 4);
    assert_int_equal(o->shapes[0].geometry.type, MPB_SHAPE_MESH);
    const mpb_mesh *m = o->shapes[0].geometry.mesh;
    assert_non_null(m);
    assert_int_equal(m->num_vertices, 4);
    assert_int_equal(m->num_triangles, 4);
    assert_near(m->vertices[3 * 3 + 2], 0.1, 0);
    assert_int_equal(m->triangles[3 * 3 + 2], 3);
    assert_near(o->shapes[0].color[1], 1, 0);

    assert_null(mpb_scene_object_at(s, 5));
    assert_null(mpb_scene_object_at(s, -1));
    assert_int_equal(mpb_scene_find(s, "cup"), MPB_ENOTFOUND);
    mpb_scene_close(s);
}

static void test_old_variant(void **state)
{
    (void)state;
    mpb_scene *s = load_ok("scene_old_format.scene");
    assert_string_equal(mpb_scene_name(s), "old kitchen");
    assert_int_equal(mpb_scene_variant_of(s), MPB_SCENE_OLD);
    assert_int_equal(mpb_scene_num_objects(s), 2);
    const mpb_scene_object *o = mpb_scene_object_at(s, 1);
    assert_string_equal(o->id, "bottle");
    expect_rotation(&o->pose, 0, 0, 0, 1);
    assert_near(o->pose.t[0], 0, 0);
    assert_near(o->shapes[0].pose.t[0], 0.9, 0);
    assert_near(o->shapes[0].pose.t[2], 1, 0);
    assert_near(o->shapes[0].color[2], 1, 0);
    assert_int_equal(o->num_subframes, 0);
    mpb_scene_close(s);
}

/*
 * The tabletop in a collision world: a sphere of radius 0.05 at (0.9, 0.4,
 * 0.6) is above the table, whose top is at 0.4 + 0.025: 0.125 away. Moved
 * down by 0.15 it touches the table top.
 */
static void test_in_collision_world(void **state)
{
    (void)state;
    mpb_scene *s = load_ok("scene_tabletop.scene");
    mpb_collision *c = NULL;
    assert_int_equal(mpb_collision_create(&c), MPB_OK);
    assert_int_equal(mpb_scene_add_statics(s, c), MPB_OK);
    assert_int_equal(mpb__collision_num_static_shapes(c), 6);
    mpb_geometry g = { .type = MPB_SHAPE_SPHERE, .dims = { 0.05 } };
    assert_int_equal(mpb_collision_add_movable(c, 0, &g, NULL), MPB_OK);
    mpb_pose p;
    mpb_pose_identity(&p);
    p.t[0] = 0.9;
    p.t[1] = 0.4;
    p.t[2] = 0.6;
    assert_int_equal(mpb_collision_set_pose(c, 0, &p), MPB_OK);
    mpb_collision_distance_result r;
    assert_int_equal(mpb_collision_distance(c, 1, &r), MPB_OK);
    assert_near(r.distance, 0.125, 1e-9);
    assert_int_equal(r.static_id, 0);           /* the table */
    assert_near(r.point_static[2], 0.425, 1e-9);
    p.t[2] = 0.45;
    assert_int_equal(mpb_collision_set_pose(c, 0, &p), MPB_OK);
    int m, st;
    assert_int_equal(mpb_collision_check(c, &m, &st), 1);
    assert_int_equal(st, 0);
    /* the cup's sphere: cup at (0.6, -0.2, 0.5) turned 45 degrees about z,
       its sphere 0.05 along the cup's x and 0.04 up */
    p.t[0] = 0.6 + 0.05 * cos(M_PI / 4);
    p.t[1] = -0.2 + 0.05 * sin(M_PI / 4);
    p.t[2] = 0.54 + 0.02 + 0.05 + 0.01;
    assert_int_equal(mpb_collision_set_pose(c, 0, &p), MPB_OK);
    assert_int_equal(mpb_collision_distance(c, 0, &r), MPB_OK);
    assert_near(r.distance, 0.01, 1e-6);
    assert_int_equal(r.static_id, 1);
    mpb_collision_destroy(c);
    mpb_scene_close(s);
}

static const char *const CARRIED =
    "with a tray\r\n"
    "* tray\r\n"
    "0 0 0.1\r\n"
    "0 0 0 1\r\n"
    "1\r\n"
    "box\r\n"
    "0.2 0.2 0.01\r\n"
    "0 0 0\r\n"
    "0 0 0 1\r\n"
    "0 0 0 0\r\n"
    "0\r\n"
    "* wall\r\n"
    "2 0 1\r\n"
    "0 0 0 1\r\n"
    "1\r\n"
    "box 0.1 4 2 0 0 0 0 0 0 1 0 0 0 0\r\n"   /* all on one line: fine */
    "0\r\n"
    ".\r\n"
    "\r\n"
    "# mpbench: the tray is carried by the gripper\r\n"
    "attach tray r_gripper_palm_link r_gripper_l_finger_link r_gripper_r_finger_link\r\n";

static void test_attach(void **state)
{
    (void)state;
    mpb_scene *s = parse_ok(CARRIED);
    assert_string_equal(mpb_scene_name(s), "with a tray");
    const mpb_scene_object *tray = mpb_scene_object_at(s, 0);
    assert_string_equal(tray->attached_link, "r_gripper_palm_link");
    assert_int_equal(tray->num_touch_links, 2);
    assert_string_equal(tray->touch_links[1], "r_gripper_r_finger_link");
    assert_near(tray->pose.t[2], 0.1, 0);   /* in the link's frame now */
    const mpb_scene_object *wall = mpb_scene_object_at(s, 1);
    assert_null(wall->attached_link);
    assert_near(wall->shapes[0].geometry.dims[1], 4, 0);

    /* attached objects are not statics */
    mpb_collision *c = NULL;
    assert_int_equal(mpb_collision_create(&c), MPB_OK);
    assert_int_equal(mpb_scene_add_statics(s, c), MPB_OK);
    assert_int_equal(mpb__collision_num_static_shapes(c), 1);
    mpb_collision_destroy(c);

    /* attach through the API: the wall to a link, at a new pose */
    mpb_pose p;
    mpb_pose_identity(&p);
    p.t[0] = 0.3;
    const char *touch[1] = { "finger" };
    assert_int_equal(mpb_scene_attach(s, "wall", "hand", &p, touch, 1), MPB_OK);
    assert_string_equal(wall->attached_link, "hand");
    assert_near(wall->pose.t[0], 0.3, 0);
    assert_string_equal(wall->touch_links[0], "finger");
    /* again, replacing it, keeping the pose */
    assert_int_equal(mpb_scene_attach(s, "wall", "other", NULL, NULL, 0), MPB_OK);
    assert_string_equal(wall->attached_link, "other");
    assert_int_equal(wall->num_touch_links, 0);
    assert_near(wall->pose.t[0], 0.3, 0);
    assert_int_equal(mpb_scene_attach(s, "nothing", "hand", NULL, NULL, 0), MPB_ENOTFOUND);
    assert_int_equal(mpb_scene_attach(s, "wall", "", NULL, NULL, 0), MPB_EINVAL);
    p.R[0] = 2;
    assert_int_equal(mpb_scene_attach(s, "wall", "hand", &p, NULL, 0), MPB_EINVAL);
    mpb_scene_close(s);
}

static void test_small_texts(void **state)
{
    (void)state;
    mpb_scene *s = parse_ok("");
    assert_int_equal(mpb_scene_num_objects(s), 0);
    assert_string_equal(mpb_scene_name(s), "");
    mpb_scene_close(s);
    s = parse_ok("  \n\n");
    mpb_scene_close(s);
    s = parse_ok("empty\n.\n");
    assert_string_equal(mpb_scene_name(s), "empty");
    assert_int_equal(mpb_scene_num_objects(s), 0);
    mpb_scene_close(s);
    /* an object with no shapes (old variant), and a name with spaces */
    s = parse_ok("  my scene  \n*   thing one  \n0\n.");
    assert_string_equal(mpb_scene_name(s), "my scene");
    assert_string_equal(mpb_scene_object_at(s, 0)->id, "thing one");
    assert_int_equal(mpb_scene_variant_of(s), MPB_SCENE_OLD);
    mpb_scene_close(s);
    /* an un-normalised quaternion is normalised */
    s = parse_ok("q\n* a\n0 0 0\n0 0 2 2\n0\n0\n.\n");
    expect_rotation(&mpb_scene_object_at(s, 0)->pose, 0, 0, M_SQRT1_2, M_SQRT1_2);
    mpb_scene_close(s);
    /* at any scale: the squares of 1e300 overflowed and were called zero */
    s = parse_ok("q\n* a\n0 0 0\n0 0 1e300 1e300\n0\n0\n.\n");
    expect_rotation(&mpb_scene_object_at(s, 0)->pose, 0, 0, M_SQRT1_2, M_SQRT1_2);
    mpb_scene_close(s);
    s = parse_ok("q\n* a\n0 0 0\n0 0 1e-300 0\n0\n0\n.\n");
    expect_rotation(&mpb_scene_object_at(s, 0)->pose, 0, 0, 1, 0);
    assert_near(mpb_scene_object_at(s, 0)->pose.R[0], -1, 1e-15);
    mpb_scene_close(s);
    mpb_scene_close(NULL);
    assert_int_equal(mpb_scene_open_text(NULL, &s, NULL, 0), MPB_EINVAL);
    assert_int_equal(mpb_scene_open_text("x\n.\n", NULL, NULL, 0), MPB_EINVAL);
    assert_int_equal(mpb_scene_num_objects(NULL), 0);
}

/* One malformed text, the line its error must name, a word it must hold. */
typedef struct bad_case {
    const char *text;
    int         line;
    const char *needle;
} bad_case;

static const bad_case BAD[] = {
    { "s\n* a\n0 0 0\n0 0 0 1\n1\nbox\n1 2\n", 7, "box needs" },
    { "s\n* a\n0 0 0\n0 0 0 1\n1\nbox 1 2 x\n", 6, "'x'" },
    { "s\n* a\n0 0 0\n0 0 0 1\n1\ntorus 1 2\n", 6, "shape type" },
    { "s\n* a\n0 0 0\n0 0 0 1\n-1\n", 5, "number of shapes" },
    { "s\n* a\n0 0 0\n0 0 0 1\nthree\n", 5, "number of shapes" },
    /* A bad dimension is on its own line, below the shape's name. */
    { "s\n* a\n0 0 0\n0 0 0 1\n1\nsphere\n-0.5\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n.\n", 7, "negative" },
    { "s\n* a\n0 0 0\n0 0 0 1\n1\nbox\n1 0 1\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n.\n", 7, "below" },
    { "s\n* a\n0 0 0\n0 0 0 1\n1\nplane\n0 0 0 1\n", 7, "normal" },
    { "s\n* a\n0 0 0\n0 0 0 1\n1\nbox 1 0 1\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n.\n", 6, "below" },
    { "s\n* a\n0 0 0\n0 0 0 1\n1\nmesh 3 1\n0 0 0\n1 0 0\n0 1e6 0\n0 1 2\n", 6, "beyond" },
    { "s\n* a\n0 0\n1e7\n0 0 0 1\n", 4, "position: 1e+07 is beyond" },
    { "s\n* a\n0 0 0\n0 0 0 0\n0\n0\n.\n", 4, "quaternion is zero" },
    { "s\n* a\n0 0 0\n0 0 0 1\n0\n0\n", 6, "'.'" },
    { "s\n* a\n0 0 0\n0 0 0 1\n0\n0\n* a\n0 0 0\n0 0 0 1\n0\n0\n.\n", 7, "twice" },
    { "s\n* a\n0 0 0\n0 0 0 1\n1\nmesh 3 1\n0 0 0\n1 0 0\n0 1 0\n0 1 3\n", 10, "out of range" },
    { "s\n* a\n0 0 0\n0 0 0 1\n1\nmesh 3 1\n0 0 0\n1 0 0\n0 1 0\n0 1\n", 10, "triangle 0" },
    { "s\n* a\n0 0 0\n0 0 0 1\n1\nmesh 2 0\n", 6, "at least" },
    { "s\n* a\n0 0 0\n0 0 0 1\n1\nmesh 99999999 1\n0 0 0\n", 6, "more than" },
    { "s\n* a\n0 0 0\n0 0 0 1\n1\nplane 0 0 0 1\n", 6, "normal" },
    { "s\n* a\n0 0 0\n0 0 0 1\n1\nplane 0 1e-300 0 1\n", 6, "1e+300 m from the origin" },
    { "s\n* a\n0 0 0\n0 0 0 1\n1\nbox 1 1 1\n0 0 0\n0 0 0 1\n0 0 0\n", 9, "color" },
    { "s\n* a\n0 0 0\n0 0 0 1\n0\n1\n", 6, "subframe name" },
    { "s\n* a\n0 0 0\n0 0 0 1\n0\n1\ntip 0 0\n", 7, "subframe position" },
    { "s\n# comment\n.\n", 2, "expected '*'" },
    { "s\n*\n0\n.\n", 2, "object id" },
    { "s\n* a\n0\n.\nhello\n", 5, "attach" },
    { "s\n* a\n0\n.\nattach a\n", 5, "attach needs" },
    { "s\n* a\n0\n.\nattach b hand\n", 5, "no object 'b'" },
    { "s\n* a\n0\n.\nattach a hand\nattach a hand\n", 6, "already attached" },
    { "s\n* a\n1 2 3\n4 5 6 7\n", 4, "number of shapes" },
    { "s\n* a\n1 2 3\n1e999 0 0 1\n", 4, "orientation" },
    { "s\n* a\n1\nsphere 1\n0 0 0\n0 0 0 1\n1e300 0 0 1\n.\n", 7, "float" },
};

static void test_errors(void **state)
{
    (void)state;
    for (size_t i = 0; i < sizeof BAD / sizeof BAD[0]; i++) {
        mpb_scene *s = (mpb_scene *)1;
        char err[300], want[32];
        int rc = mpb_scene_open_text(BAD[i].text, &s, err, sizeof err);
        if (rc != MPB_EPARSE)
            fail_msg("case %zu: %s, expected MPB_EPARSE (%s)", i, mpb_err_name(rc), err);
        assert_null(s);
        snprintf(want, sizeof want, "scene line %d: ", BAD[i].line);
        if (strncmp(err, want, strlen(want)) != 0 || !strstr(err, BAD[i].needle) ||
            strchr(err, '\n'))
            fail_msg("case %zu: \"%s\", expected \"%s...%s...\"", i, err, want,
                     BAD[i].needle);
    }
    /* a small error buffer truncates; none at all is fine */
    mpb_scene *s;
    char tiny[10];
    assert_int_equal(mpb_scene_open_text(BAD[0].text, &s, tiny, sizeof tiny), MPB_EPARSE);
    assert_int_equal(strlen(tiny), sizeof tiny - 1);
    assert_int_equal(mpb_scene_open_text(BAD[0].text, &s, NULL, 0), MPB_EPARSE);
}

static void test_load_errors(void **state)
{
    (void)state;
    mpb_scene *s = (mpb_scene *)1;
    char err[300];
    assert_int_equal(mpb_scene_open("/no/such/file.scene", &s, err, sizeof err), MPB_EIO);
    assert_null(s);
    assert_non_null(strstr(err, "/no/such/file.scene"));

    char path[] = "/tmp/mpb-test-scene-XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    fputs("bad\n* a\n0 0 0\n0 0 0 1\n1\nbox 1 1\n", f);
    fclose(f);
    assert_int_equal(mpb_scene_open(path, &s, err, sizeof err), MPB_EPARSE);
    char want[128];
    snprintf(want, sizeof want, "%s: scene line 6: ", path);
    if (strncmp(err, want, strlen(want)) != 0)
        fail_msg("\"%s\", expected \"%s...\"", err, want);
    remove(path);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_new_variant),
        cmocka_unit_test(test_old_variant),
        cmocka_unit_test(test_in_collision_world),
        cmocka_unit_test(test_attach),
        cmocka_unit_test(test_small_texts),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_load_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
