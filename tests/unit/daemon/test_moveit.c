/*
 * test_moveit.c - MoveIt PlanningScene and MotionPlanRequest YAML files
 * (daemon/moveit.c), on small files written here: what a scene becomes
 * in the moveit-scene format, allowed pairs, joint states, joint and pose
 * goals, and one line naming the file and place for each bad input.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "moveit.h"
#include "mpbench/scene.h"
#include "test_octree_box.h"

static char dir[64];
static char path[128];
static char err[512];

static int make_dir(void **state)
{
    (void)state;
    snprintf(dir, sizeof dir, "/tmp/mpb-test-moveit-XXXXXX");
    return mkdtemp(dir) == NULL ? -1 : 0;
}

static int remove_dir(void **state)
{
    char cmd[128];
    (void)state;
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    return system(cmd) == 0 ? 0 : -1;
}

/* Write text as dir/<name> and return its path. */
static const char *write_file(const char *name, const char *text)
{
    FILE *f;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    assert_non_null(f = fopen(path, "w"));
    assert_int_equal(fputs(text, f) >= 0, 1);
    assert_int_equal(fclose(f), 0);
    return path;
}

/* Write len bytes as dir/<name> and return its path. */
static const char *write_bytes(const char *name, const char *bytes, size_t len)
{
    FILE *f;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    assert_non_null(f = fopen(path, "wb"));
    assert_int_equal(fwrite(bytes, 1, len, f), len);
    assert_int_equal(fclose(f), 0);
    return path;
}

/* err is "<dir>/<file>:<where>: <what>" */
static void assert_error(const char *file, const char *where, const char *what)
{
    char want[640];
    snprintf(want, sizeof want, "%s/%s:%s: %s", dir, file, where, what);
    assert_string_equal(err, want);
}

static const char scene_yaml[] =
    "name: \"\"\n"
    "robot_state:\n"
    "  joint_state:\n"
    "    name: [j1, finger]\n"
    "    position: [0.5, 0.065]\n"
    "allowed_collision_matrix:\n"
    "  entry_names: [a, b, c]\n"
    "  entry_values:\n"
    "    - [false, true, false]\n"
    "    - [true, false, true]\n"
    "    - [false, true, false]\n"
    "world:\n"
    "  collision_objects:\n"
    "    - id: can\n"
    "      primitive_poses:\n"
    "        - position: [1, 2, 3]\n"
    "          orientation: [0, 0, 0, 2]\n"
    "        - {position: [0, 0, 0.5], orientation: [0, 0, 0, 1]}\n"
    "      primitives:\n"
    "        - type: cylinder\n"
    "          dimensions: [0.14, 0.03]\n"
    "        - {type: cone, dimensions: [0.2, 0.05]}\n"
    "      pose: {position: {x: 0.5, y: 0, z: 0}, orientation: {x: 0, y: 0, z: 0, w: 1}}\n"
    "    - id: table top\n"
    "      primitives: [{type: box, dimensions: [1, 2, 0.04]}, {type: sphere, dimensions: [0.1]}]\n"
    "      primitive_poses:\n"
    "        - {position: [0, 0, 0], orientation: [0, 0, 0, 1]}\n"
    "        - {position: [0, 0, 1], orientation: [0, 0, 0, 1]}\n"
    "    - id: tri\n"
    "      meshes:\n"
    "        - vertices: [[0, 0, 0], {x: 1, y: 0, z: 0}, [0, 1, 0]]\n"
    "          triangles: [{vertex_indices: [0, 1, 2]}]\n"
    "      mesh_poses: [{position: [0, 0, 0], orientation: [0, 0, 0, 1]}]\n";

/* The objects become a moveit-scene text that scene.h reads, with
 * shape_msgs' [height, radius] turned round and quaternions normalised. */
static void a_scene_becomes_a_moveit_scene(void **state)
{
    mpbd_moveit_scene s;
    mpb_scene *sc = NULL;
    (void)state;
    if (mpbd_moveit_scene_read(write_file("s.yaml", scene_yaml), "set/0001",
                               &s, err, sizeof err) != MPB_OK)
        fail_msg("%s", err);
    assert_int_equal(s.num_objects, 3);
    if (mpb_scene_open_text(s.text, &sc, err, sizeof err) != MPB_OK)
        fail_msg("%s in:\n%s", err, s.text);
    assert_string_equal(mpb_scene_name(sc), "set/0001");
    assert_int_equal(mpb_scene_num_objects(sc), 3);
    const mpb_scene_object *can = mpb_scene_object_at(sc, 0);
    assert_string_equal(can->id, "can");
    assert_true(can->pose.t[0] == 0.5);
    assert_int_equal(can->num_shapes, 2);
    assert_int_equal(can->shapes[0].geometry.type, MPB_SHAPE_CYLINDER);
    assert_true(can->shapes[0].geometry.dims[0] == 0.03);  /* radius */
    assert_true(can->shapes[0].geometry.dims[1] == 0.14);  /* length */
    assert_int_equal(can->shapes[1].geometry.type, MPB_SHAPE_CONE);
    assert_true(can->shapes[0].pose.t[2] == 3);
    assert_string_equal(mpb_scene_object_at(sc, 1)->id, "table top");
    assert_int_equal(mpb_scene_object_at(sc, 1)->shapes[1].geometry.type,
                     MPB_SHAPE_SPHERE);
    assert_int_equal(mpb_scene_object_at(sc, 2)->shapes[0].geometry.type,
                     MPB_SHAPE_MESH);
    mpb_scene_close(sc);
    /* a-b and b-c are allowed; a-c is not. */
    assert_int_equal(s.num_pairs, 2);
    assert_string_equal(s.pairs[0], "a");
    assert_string_equal(s.pairs[1], "b");
    assert_string_equal(s.pairs[2], "b");
    assert_string_equal(s.pairs[3], "c");
    assert_int_equal(s.pair_at[0].line, 7);
    assert_int_equal(s.state.n, 2);
    assert_string_equal(s.state.names[1], "finger");
    assert_true(s.state.values[1] == 0.065);
    assert_int_equal(s.state.at[1].line, 4);
    mpbd_moveit_scene_clear(&s);
}

static const char request_yaml[] =
    "group_name: arm\n"
    "allowed_planning_time: 60\n"
    "start_state:\n"
    "  joint_state:\n"
    "    name: [j1, j2, finger]\n"
    "    position: [0, -0.785, 0.04]\n"
    "goal_constraints:\n"
    "  - joint_constraints:\n"
    "      - {joint_name: j1, position: 0.45}\n"
    "      - {joint_name: j2, position: 1.5, tolerance_above: 0.01, tolerance_below: 0.02}\n";

static void a_request_gives_start_and_joint_goal(void **state)
{
    mpbd_moveit_request r;
    (void)state;
    assert_int_equal(mpbd_moveit_request_read(write_file("r.yaml",
                                                         request_yaml),
                                              &r, err, sizeof err), MPB_OK);
    assert_string_equal(r.group_name, "arm");
    assert_int_equal(r.group_at.line, 1);
    assert_true(r.allowed_planning_time == 60);
    assert_int_equal(r.start.n, 3);
    assert_true(r.start.values[1] == -0.785);
    assert_int_equal(r.goal_kind, MPB_GOAL_JOINTS);
    assert_int_equal(r.goal.n, 2);
    assert_true(r.goal.values[0] == 0.45);
    assert_true(isnan(r.tolerance_above[0]));
    assert_true(r.tolerance_above[1] == 0.01 && r.tolerance_below[1] == 0.02);
    mpbd_moveit_request_clear(&r);
}

static void a_pose_goal_becomes_a_region(void **state)
{
    mpbd_moveit_request r;
    (void)state;
    const char *p = write_file("p.yaml",
        "group_name: arm\n"
        "goal_constraints:\n"
        "  - position_constraints:\n"
        "      - link_name: hand\n"
        "        target_point_offset: [0, 0, 0]\n"
        "        constraint_region:\n"
        "          primitives: [{type: box, dimensions: [0.02, 0.04, 0.06]}]\n"
        "          primitive_poses: [{position: [0.5, 0, 0.3], orientation: [0, 0, 0, 1]}]\n"
        "    orientation_constraints:\n"
        "      - link_name: hand\n"
        "        orientation: [0, 0, 0, 1]\n"
        "        absolute_x_axis_tolerance: 0.05\n"
        "        absolute_y_axis_tolerance: 0.1\n"
        "        absolute_z_axis_tolerance: 3.2\n");
    assert_int_equal(mpbd_moveit_request_read(p, &r, err, sizeof err), MPB_OK);
    assert_int_equal(r.goal_kind, MPB_GOAL_POSE_REGION);
    assert_string_equal(r.link, "hand");
    assert_true(r.position[0] == 0.5 && r.position[2] == 0.3);
    assert_true(fabs(r.position_tolerance[1] - 0.02) < 1e-15);
    assert_true(r.rpy_tolerance[0] == 0.05 && r.rpy_tolerance[2] == 3.2);
    assert_true(fabs(r.rpy[0]) < 1e-12);
    mpbd_moveit_request_clear(&r);
}

/* Each bad file: one line naming the file, line and column. */
static void bad_files_are_named_at_the_place(void **state)
{
    mpbd_moveit_scene s;
    mpbd_moveit_request r;
    (void)state;
    static const struct {
        const char *text, *where, *what;
        int is_scene;
    } bad[] = {
        {"world:\n  collision_objects:\n    - id: x\n      primitives: [{type: box",
         "5:1", "YAML: did not find expected ',' or '}'", 1},
        {"world: {collision_objects: [{id: x, primitives: [{type: box, dimensions: [1, 1, 1]}],"
         " primitive_poses: [{position: [.nan, 0, 0], orientation: [0, 0, 0, 1]}]}]}\n",
         "1:117", "position must be a finite number, not '.nan'", 1},
        {"world: {collision_objects: [{id: x, primitives: [{type: box, dimensions: [1, 1, 1]}],"
         " primitive_poses: [{position: [0, 0, 0], orientation: [0, 0, 0, 0]}]}]}\n",
         "1:140", "orientation is a zero quaternion", 1},
        {"world: {collision_objects: [{id: x, primitives: [{type: torus, dimensions: [1]}],"
         " primitive_poses: [{position: [0, 0, 0], orientation: [0, 0, 0, 1]}]}]}\n",
         "1:57", "unknown primitive type 'torus' (box, sphere, cylinder, cone)", 1},
        {"allowed_collision_matrix: {entry_names: [a, b], entry_values: [[false, true], [false, false]]}\n",
         "1:72", "entry_values is not symmetric: row 1, column 2", 1},
        {"robot_state: {joint_state: {name: [a, b], position: [1]}}\n",
         "1:53", "joint_state has 2 names and 1 positions", 1},
        {"robot_state: {attached_collision_objects: [{link_name: hand}]}\n",
         "1:43", "attached collision objects are not read (yet): attach the "
         "object in a .scene file instead (docs/scenes.md)", 1},
        {"goal_constraints: []\n", "1:19",
         "goal_constraints must hold one goal (found 0): mpbench's query has one", 0},
        {"goal_constraints: [{joint_constraints: [{joint_name: a}]}]\n", "1:41",
         "joint constraint on 'a' needs a 'position'", 0},
        {"goal_constraints: [{position_constraints: [{link_name: h, constraint_region:"
         " {primitives: [{type: sphere, dimensions: [0.1]}], primitive_poses: [{position: [0, 0, 0],"
         " orientation: [0, 0, 0, 1]}]}}]}]\n", "1:92",
         "the constraint region must be a box (a sphere or cylinder cannot be "
         "mapped to mpbench's box region)", 0},
        {"group_name: [a]\ngoal_constraints: []\n", "1:13",
         "group_name must be a name", 0},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const char *p = write_file("bad.yaml", bad[i].text);
        int rc = bad[i].is_scene
                     ? mpbd_moveit_scene_read(p, "x", &s, err, sizeof err)
                     : mpbd_moveit_request_read(p, &r, err, sizeof err);
        assert_int_equal(rc, MPB_EPARSE);
        assert_error("bad.yaml", bad[i].where, bad[i].what);
        assert_null(strchr(err, '\n'));
    }
    assert_int_equal(mpbd_moveit_scene_read("/nonexistent/s.yaml", "x", &s,
                                            err, sizeof err), MPB_EIO);
}

/* A pose goal as MotionBenchMaker writes one, with the box dimensions and
 * the orientation given. */
static const char *pose_request(const char *dims, const char *orientation)
{
    static char text[1024];
    snprintf(text, sizeof text,
             "group_name: arm\n"
             "goal_constraints:\n"
             "  - position_constraints:\n"
             "      - link_name: hand\n"
             "        constraint_region:\n"
             "          primitives: [{type: box, dimensions: %s}]\n"
             "          primitive_poses: [{position: [0.5, 0, 0.3], orientation: [0, 0, 0, 1]}]\n"
             "    orientation_constraints:\n"
             "      - link_name: hand\n"
             "        orientation: %s\n"
             "        absolute_x_axis_tolerance: 0.05\n"
             "        absolute_y_axis_tolerance: 0.05\n"
             "        absolute_z_axis_tolerance: 0.05\n", dims, orientation);
    return write_file("pose.yaml", text);
}

/* An orientation constraint whose quaternion is not of unit norm: MoveIt
 * warns and assumes identity, and so does the reader (the caller warns);
 * one of unit norm within 1e-3 is used as it is. */
static void a_non_unit_orientation_is_taken_as_identity(void **state)
{
    mpbd_moveit_request r;
    (void)state;
    assert_int_equal(mpbd_moveit_request_read(pose_request("[0.02, 0.02, 0.02]",
                                                           "[1, 0, 0, 1]"),
                                              &r, err, sizeof err), MPB_OK);
    assert_int_equal(r.orientation_identity, 1);
    assert_int_equal(r.orientation_at.line, 10);
    assert_int_equal(r.orientation_at.column, 22);
    for (int i = 0; i < 3; i++)
        assert_true(fabs(r.rpy[i]) < 1e-12);
    mpbd_moveit_request_clear(&r);
    assert_int_equal(mpbd_moveit_request_read(pose_request("[0.02, 0.02, 0.02]",
                                                           "[1, 0, 0, 0.0005]"),
                                              &r, err, sizeof err), MPB_OK);
    assert_int_equal(r.orientation_identity, 0);
    assert_true(fabs(fabs(r.rpy[0]) - M_PI) < 1e-2);
    mpbd_moveit_request_clear(&r);
}

/* What a held-out set of corrupted MotionBenchMaker files found: each is
 * refused in one line at its true place. */
static void corrupted_files_are_refused_at_their_place(void **state)
{
    mpbd_moveit_scene s;
    mpbd_moveit_request r;
    char where[32];
    (void)state;

    /* 200,000 nested lists: refused at the 100th level, not parsed for a
     * minute (libyaml's time grows with the square of the depth). */
    size_t depth = 200000, len = 0;
    char *deep = malloc(2 * depth + 64);
    assert_non_null(deep);
    len += (size_t)sprintf(deep, "fixed_frame_transforms: ");
    memset(deep + len, '[', depth);
    memset(deep + len + depth, ']', depth);
    len += 2 * depth;
    deep[len++] = '\n';
    assert_int_equal(mpbd_moveit_scene_read(write_bytes("deep.yaml", deep, len),
                                            "x", &s, err, sizeof err),
                     MPB_EPARSE);
    free(deep);
    assert_error("deep.yaml", "1:124", "nested too deeply (more than 100 "
                 "levels)");

    /* A file cut after an object's id: no shapes, which MoveIt refuses. */
    assert_int_equal(mpbd_moveit_scene_read(write_file("cut.yaml",
        "world:\n  collision_objects:\n"
        "    - id: side_left\n      primitives: [{type: box, dimensions: [1, 1, 1]}]\n"
        "      primitive_poses: [{position: [0, 0, 0], orientation: [0, 0, 0, 1]}]\n"
        "    - id: side_right\n"), "x", &s, err, sizeof err), MPB_EPARSE);
    assert_error("cut.yaml", "6:11", "object 'side_right' has no shapes "
                 "(primitives, meshes or planes): MoveIt refuses such an "
                 "object");

    /* A goal box without volume: no run could sample a goal in it. */
    assert_int_equal(mpbd_moveit_request_read(pose_request("[0, 0, 0]",
                                                           "[0, 0, 0, 1]"),
                                              &r, err, sizeof err), MPB_EPARSE);
    assert_error("pose.yaml", "6:48", "box dimensions must be above 0 (a "
                 "region without volume holds no reachable pose), not 0");
    assert_int_equal(mpbd_moveit_request_read(pose_request("[0.1, 0.1, 0]",
                                                           "[0, 0, 0, 1]"),
                                              &r, err, sizeof err), MPB_EPARSE);

    /* A NUL byte, and a byte that is not UTF-8, on line 50. */
    char text[2048];
    len = 0;
    for (int i = 1; i < 50; i++)
        len += (size_t)sprintf(text + len, "# line %d\n", i);
    len += (size_t)sprintf(text + len, "name: ab");
    size_t bad_at = len;
    len += (size_t)sprintf(text + len, "c\n");
    text[bad_at] = '\0';
    assert_int_equal(mpbd_moveit_scene_read(write_bytes("nul.yaml", text, len),
                                            "x", &s, err, sizeof err),
                     MPB_EPARSE);
    assert_error("nul.yaml", "50:9", "a NUL byte: not a text file");
    text[bad_at] = (char)0xff;
    assert_int_equal(mpbd_moveit_scene_read(write_bytes("utf8.yaml", text, len),
                                            "x", &s, err, sizeof err),
                     MPB_EPARSE);
    snprintf(where, sizeof where, "50:9");
    assert_error("utf8.yaml", where, "YAML: invalid leading UTF-8 octet");

    /* A folder where a file is named. */
    assert_int_equal(mpbd_moveit_request_read(dir, &r, err, sizeof err),
                     MPB_EIO);
    char want[256];
    snprintf(want, sizeof want, "%s: cannot read: Is a directory", dir);
    assert_string_equal(err, want);
}


/* A PlanningScene YAML whose world holds an octomap of `n` int8 values
 * (OctoMap's binary stream at res, binary: true), into a new string. */
static char *octomap_yaml(const unsigned char *b, size_t n, const char *res)
{
    size_t cap = 64 * 1024 + 6 * n;
    char *y = malloc(cap);
    assert_non_null(y);
    size_t at = (size_t)snprintf(y, cap,
        "name: s\n"
        "world:\n"
        "  octomap:\n"
        "    header: {frame_id: world}\n"
        "    origin: {position: {x: 0, y: 0, z: 0}, orientation: {x: 0, y: 0, z: 0, w: 1}}\n"
        "    octomap:\n"
        "      header: {frame_id: world}\n"
        "      binary: true\n"
        "      id: OcTree\n"
        "      resolution: %s\n"
        "      data: [", res);
    for (size_t i = 0; i < n; i++)
        at += (size_t)snprintf(y + at, cap - at, i ? ", %d" : "%d", (int)(signed char)b[i]);
    snprintf(y + at, cap - at, "]\n");
    return y;
}

/* MoveIt's world.octomap loads, and checks, as the .bt file of the same
 * tree does. */
static void an_octomap_checks_as_its_bt_file(void **state)
{
    (void)state;
    char *bt = test_box_bt(dir);
    mpb_octree *o = test_box_octree();
    unsigned char *raw;
    size_t n;
    assert_int_equal(mpb_octree_write(o, 0, &raw, &n), MPB_OK);
    mpb_octree_destroy(o);
    char *y = octomap_yaml(raw, n, "0.01");
    mpbd_moveit_scene ms;
    if (mpbd_moveit_scene_read(write_file("om.yaml", y), "set/0001", &ms, err,
                               sizeof err) != MPB_OK)
        fail_msg("%s", err);
    char from_bt[300], *resolved;
    snprintf(from_bt, sizeof from_bt, "set/0001\n.\noctree octomap file %s\n", bt);
    assert_int_equal(mpb_scene_resolve(from_bt, NULL, &resolved, err, sizeof err), MPB_OK);
    /* the same text: the same hash, so planners and the store see one scene */
    assert_string_equal(ms.text, resolved);
    mpb_collision *a = test_probe_world(ms.text, 0.004), *b = test_probe_world(resolved, 0.004);
    unsigned seed = 3;
    int hits = 0;
    for (int i = 0; i < 2000; i++) {
        double p[3], da, db;
        for (int k = 0; k < 3; k++) {
            seed = seed * 1103515245u + 12345u;
            p[k] = TEST_BOX_LO[k] - 0.03 + (seed >> 8) / (double)(1u << 24) *
                   (TEST_BOX_HI[k] - TEST_BOX_LO[k] + 0.06);
        }
        int ha = test_probe(a, p, &da);
        assert_int_equal(ha, test_probe(b, p, &db));
        assert_true(da == db);
        hits += ha;
    }
    assert_true(hits > 100 && hits < 1900);
    mpb_collision_destroy(a);
    mpb_collision_destroy(b);
    mpbd_moveit_scene_clear(&ms);
    free(resolved);
    free(y);

    /* resolution 0; the data cut short: each at its place */
    y = octomap_yaml(raw, n, "0");
    assert_int_equal(mpbd_moveit_scene_read(write_file("r0.yaml", y), "x", &ms, err,
                                            sizeof err), MPB_EPARSE);
    assert_error("r0.yaml", "10:19", "octomap resolution 0 is outside 0.0001 .. 1 m");
    free(y);
    y = octomap_yaml(raw, n / 2, "0.01");
    assert_int_equal(mpbd_moveit_scene_read(write_file("cut.yaml", y), "x", &ms, err,
                                            sizeof err), MPB_EPARSE);
    assert_non_null(strstr(err, "cut.yaml:11:13: octomap data: data byte "));
    assert_non_null(strstr(err, "truncated"));
    free(y);
    free(raw);
    unlink(bt);
    free(bt);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_scene_becomes_a_moveit_scene),
        cmocka_unit_test(a_request_gives_start_and_joint_goal),
        cmocka_unit_test(a_pose_goal_becomes_a_region),
        cmocka_unit_test(bad_files_are_named_at_the_place),
        cmocka_unit_test(a_non_unit_orientation_is_taken_as_identity),
        cmocka_unit_test(corrupted_files_are_refused_at_their_place),
        cmocka_unit_test(an_octomap_checks_as_its_bt_file),
    };
    return cmocka_run_group_tests(tests, make_dir, remove_dir);
}
