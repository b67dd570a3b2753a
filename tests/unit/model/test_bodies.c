/*
 * test_bodies.c - a world's bodies for drawing (bodies.h): the PR2 right
 * arm beside a box (the scene of test_world_urdf.c: at q = 0 the box sits
 * on the forearm, panned to -1.2 rad the arm is clear of it) and a planar
 * arm among a pillar and a box. The bodies are the robot's links with
 * their collision shapes and the scene's objects, placed where forward
 * kinematics puts them, and the pair in contact is the one the world's
 * check finds. A link with a mesh gives the mesh as the world loaded it.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "test_files.h"
#include "model/world_provider.h"
#include "core/mathconst.h"

static const char *const joints[] = {
    "r_shoulder_pan_joint", "r_shoulder_lift_joint", "r_upper_arm_roll_joint",
    "r_elbow_flex_joint", "r_forearm_roll_joint", "r_wrist_flex_joint",
    "r_wrist_roll_joint"};

static const char box_scene[] =
    "box beside the arm\n"
    "* box\n"
    "0.6 -0.188 0.74\n"
    "0 0 0 1\n"
    "1\n"
    "box\n"
    "0.1 0.1 0.1\n"
    "0 0 0\n"
    "0 0 0 1\n"
    "0.5 0.25 0 1\n"
    "0\n"
    ".\n";

static const char planar_robot[] =
    "link_radius 0.03\n"
    "joint shoulder -3.2 3.2 0.5\n"
    "joint elbow -2.8 2.8 0.4\n"
    "joint wrist -2.8 2.8 0.3\n";

/* A pillar straight above the base, a box far to the right. */
static const char planar_scene[] =
    "circle 0.0 0.8 0.15\n"
    "box 2.0 0.0 0.1 0.3\n";

static char *urdf;

static int setup(void **state)
{
    (void)state;
    /* With its SRDF, which allows the pairs its crude shapes make touch
     * (test_world_urdf.c). */
    urdf = test_read_robot(MPB_TEST_DATA "/pr2_right_arm.urdf",
                           MPB_TEST_DATA "/pr2_right_arm.srdf");
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    free(urdf);
    return 0;
}

static int find(const mpb_bodies *b, const char *name)
{
    for (int i = 0; i < mpb_bodies_count(b); i++)
        if (strcmp(mpb_bodies_get(b, i)->name, name) == 0)
            return i;
    return -1;
}

static void assert_pose_equal(const mpb_pose *a, const mpb_pose *b)
{
    for (int k = 0; k < 9; k++)
        assert_float_equal(a->R[k], b->R[k], 1e-12);
    for (int k = 0; k < 3; k++)
        assert_float_equal(a->t[k], b->t[k], 1e-12);
}

static void urdf_bodies_are_the_links_and_objects_where_fk_puts_them(void **state)
{
    (void)state;
    mpb_world *w = NULL;
    mpb_bodies *b = NULL;
    mpb_robot *r = NULL;
    char err[256];
    assert_int_equal(mpb_world_open_group("urdf", urdf, "moveit-scene",
                                          box_scene, joints, 7, &w, err,
                                          sizeof err), MPB_OK);
    assert_int_equal(mpb_bodies_open(w, &b, err, sizeof err), MPB_OK);
    assert_int_equal(mpb_robot_open_urdf_joints(urdf, joints, 7, &r, err,
                                                sizeof err), MPB_OK);

    /* One body per link with shapes, then the box. */
    int links = 0;
    for (int l = 0; l < mpb_robot_num_links(r); l++)
        links += mpb_robot_get_link(r, l)->num_collisions > 0;
    assert_int_equal(mpb_bodies_count(b), links + 1);
    const mpb_body *box = mpb_bodies_get(b, links);
    assert_string_equal(box->name, "box");
    assert_int_equal(box->robot, 0);
    assert_int_equal(box->moves, 0);
    assert_int_equal(box->num_shapes, 1);
    assert_int_equal(box->shapes[0].geometry.type, MPB_SHAPE_BOX);
    assert_float_equal(box->shapes[0].geometry.dims[0], 0.1, 1e-12);
    assert_float_equal(box->shapes[0].color[0], 0.5f, 1e-6);
    assert_null(mpb_bodies_get(b, links + 1));

    /* Each link body: its collisions, at the link's FK pose. */
    double q[7] = {-0.3, 0.4, -1.0, -0.8, 2.0, -0.5, 1.0};
    int n = mpb_bodies_count(b);
    mpb_pose *poses = calloc((size_t)n, sizeof *poses);
    mpb_pose *fk = calloc((size_t)mpb_robot_num_links(r), sizeof *fk);
    assert_int_equal(mpb_bodies_poses(b, q, poses), MPB_OK);
    assert_int_equal(mpb_robot_fk(r, q, fk), MPB_OK);
    int moving = 0;
    for (int i = 0; i < links; i++) {
        const mpb_body *body = mpb_bodies_get(b, i);
        int l = mpb_robot_link_index(r, body->name);
        assert_true(l >= 0);
        const mpb_robot_link *link = mpb_robot_get_link(r, l);
        assert_int_equal(body->robot, 1);
        assert_int_equal(body->moves, link->moves);
        moving += body->moves;
        assert_int_equal(body->num_shapes, link->num_collisions);
        for (int k = 0; k < body->num_shapes; k++) {
            const mpb_robot_collision *c =
                mpb_robot_get_collision(r, link->first_collision + k);
            assert_int_equal(body->shapes[k].geometry.type, c->type);
            assert_pose_equal(&body->shapes[k].offset, &c->origin);
        }
        assert_pose_equal(&poses[i], &fk[l]);
    }
    assert_true(moving >= 7);
    assert_float_equal(poses[links].t[0], 0.6, 1e-12);
    assert_float_equal(poses[links].t[2], 0.74, 1e-12);

    /* A non-finite q is refused, the poses untouched. */
    double bad[7] = {NAN};
    poses[0].t[0] = 42;
    assert_int_equal(mpb_bodies_poses(b, bad, poses), MPB_EINVAL);
    assert_float_equal(poses[0].t[0], 42, 0);
    free(poses);
    free(fk);
    mpb_robot_close(r);
    mpb_bodies_close(b);
    mpb_world_close(w);
}

static void the_urdf_contact_is_a_link_and_the_box(void **state)
{
    (void)state;
    mpb_world *w = NULL;
    mpb_bodies *b = NULL;
    assert_int_equal(mpb_world_open_group("urdf", urdf, "moveit-scene",
                                          box_scene, joints, 7, &w, NULL, 0),
                     MPB_OK);
    assert_int_equal(mpb_bodies_open(w, &b, NULL, 0), MPB_OK);
    double q0[7] = {0}, qa[7] = {-1.2};
    int a = -1, c = -1;
    assert_int_equal(mpb_bodies_contact(b, q0, &a, &c), 1);
    assert_int_equal(mpb_bodies_get(b, a)->robot, 1);
    assert_int_equal(c, find(b, "box"));
    /* The box is on the forearm: the link named is the forearm's or next
     * to it, one the box really touches. */
    const char *link = mpb_bodies_get(b, a)->name;
    assert_true(strstr(link, "forearm") || strstr(link, "elbow") ||
                strstr(link, "wrist"));
    assert_int_equal(mpb_bodies_contact(b, qa, &a, &c), 0);
    mpb_bodies_close(b);
    mpb_world_close(w);
}

static void planar_bodies_are_capsules_and_prisms(void **state)
{
    (void)state;
    mpb_world *w = NULL;
    mpb_bodies *b = NULL;
    char err[256];
    assert_int_equal(mpb_world_open("planar", planar_robot, "planar",
                                    planar_scene, &w, err, sizeof err), MPB_OK);
    assert_int_equal(mpb_bodies_open(w, &b, err, sizeof err), MPB_OK);
    assert_int_equal(mpb_bodies_count(b), 5);
    assert_string_equal(mpb_bodies_get(b, 1)->name, "link 1 (elbow)");
    assert_string_equal(mpb_bodies_get(b, 3)->name, "circle 0");
    assert_string_equal(mpb_bodies_get(b, 4)->name, "box 0");
    const mpb_body_shape *cap = &mpb_bodies_get(b, 1)->shapes[0];
    assert_int_equal(cap->geometry.type, MPB_SHAPE_CAPSULE);
    assert_float_equal(cap->geometry.dims[0], 0.03, 1e-12);
    assert_float_equal(cap->geometry.dims[1], 0.4, 1e-12);
    const mpb_body_shape *box = &mpb_bodies_get(b, 4)->shapes[0];
    assert_float_equal(box->geometry.dims[0], 0.2, 1e-12);
    assert_float_equal(box->geometry.dims[1], 0.6, 1e-12);
    assert_float_equal(box->geometry.dims[2], 0.12, 1e-12);   /* 4 radii */

    /* Each capsule's two ends are the joints the world computes. */
    double q[3] = {0.3, -0.7, 1.1}, xy[8];
    mpb_pose poses[5];
    assert_int_equal(mpb_bodies_poses(b, q, poses), MPB_OK);
    assert_int_equal(mpb__planar_points(w, q, xy), MPB_OK);
    for (int i = 0; i < 3; i++) {
        const mpb_body_shape *s = &mpb_bodies_get(b, i)->shapes[0];
        double half = s->geometry.dims[1] / 2, ends[2][3];
        for (int e = 0; e < 2; e++) {
            double local[3] = {0, 0, e ? half : -half}, in_body[3];
            mpb_pose_apply(&s->offset, local, in_body);
            mpb_pose_apply(&poses[i], in_body, ends[e]);
        }
        /* One end at joint i, the other at joint i + 1, both at z = 0. */
#define NEAR(e, j) (hypot(ends[e][0] - xy[2 * (j)], ends[e][1] - xy[2 * (j) + 1]) < 1e-9)
        assert_true((NEAR(0, i) && NEAR(1, i + 1)) || (NEAR(1, i) && NEAR(0, i + 1)));
#undef NEAR
        assert_float_equal(ends[0][2], 0.0, 1e-12);
        assert_float_equal(ends[1][2], 0.0, 1e-12);
    }
    assert_float_equal(poses[3].t[1], 0.8, 1e-12);
    assert_float_equal(poses[4].t[0], 2.0, 1e-12);

    /* Straight up, the elbow's link reaches into the pillar. */
    double up[3] = {M_PI / 2, 0, 0}, flat[3] = {0, 0, 0};
    int a = -1, c = -1;
    assert_int_equal(mpb_world_in_collision(w, up), 1);
    assert_int_equal(mpb_bodies_contact(b, up, &a, &c), 1);
    assert_int_equal(a, 1);
    assert_int_equal(c, 3);
    assert_int_equal(mpb_bodies_contact(b, flat, &a, &c), 0);
    mpb_bodies_close(b);
    mpb_world_close(w);
}

/* fk3.urdf's l3 has a mesh, package://mpbench_test/meshes/tool.stl scaled
 * by 0.001 0.002 0.003: here a tetrahedron of unit edges, found through
 * MPB_MESH_PATH as mpbenchd finds it. */
static void a_mesh_link_is_its_mesh_as_loaded(void **state)
{
    (void)state;
    char dir[] = "/tmp/test_bodies-XXXXXX", path[256];
    assert_non_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/mpbench_test", dir);
    assert_int_equal(mkdir(path, 0700), 0);
    snprintf(path, sizeof path, "%s/mpbench_test/meshes", dir);
    assert_int_equal(mkdir(path, 0700), 0);
    snprintf(path, sizeof path, "%s/mpbench_test/meshes/tool.stl", dir);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    static const int tri[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    static const double v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    fputs("solid tool\n", f);
    for (int t = 0; t < 4; t++) {
        fputs("facet normal 0 0 0\nouter loop\n", f);
        for (int k = 0; k < 3; k++)
            fprintf(f, "vertex %g %g %g\n", v[tri[t][k]][0], v[tri[t][k]][1],
                    v[tri[t][k]][2]);
        fputs("endloop\nendfacet\n", f);
    }
    fputs("endsolid tool\n", f);
    fclose(f);
    setenv("MPB_MESH_PATH", dir, 1);

    char *fk3 = test_read_file(MPB_TEST_DATA "/fk3.urdf");
    static const char *const fk3_joints[] = {"j1", "j2", "j3"};
    mpb_world *w = NULL;
    mpb_bodies *b = NULL;
    char err[256];
    int rc = mpb_world_open_group("urdf", fk3, "moveit-scene", "", fk3_joints,
                                  3, &w, err, sizeof err);
    if (rc != MPB_OK)
        fail_msg("open: %s", err);
    assert_int_equal(mpb_bodies_open(w, &b, err, sizeof err), MPB_OK);
    int l3 = find(b, "l3");
    assert_true(l3 >= 0);
    const mpb_body *body = mpb_bodies_get(b, l3);
    assert_int_equal(body->num_shapes, 1);
    const mpb_geometry *g = &body->shapes[0].geometry;
    assert_int_equal(g->type, MPB_SHAPE_MESH);
    assert_non_null(g->mesh);
    assert_int_equal(g->mesh->num_triangles, 4);
    /* As checked: scaled, so x <= 0.001, y <= 0.002, z <= 0.003. */
    double hi[3] = {0};
    for (int i = 0; i < g->mesh->num_vertices; i++)
        for (int k = 0; k < 3; k++)
            hi[k] = fmax(hi[k], g->mesh->vertices[3 * i + k]);
    assert_float_equal(hi[0], 0.001, 1e-9);
    assert_float_equal(hi[1], 0.002, 1e-9);
    assert_float_equal(hi[2], 0.003, 1e-9);
    assert_float_equal(body->shapes[0].offset.t[0], 0.1, 1e-12);
    mpb_bodies_close(b);
    mpb_world_close(w);
    free(fk3);
    unsetenv("MPB_MESH_PATH");
    remove(path);
    snprintf(path, sizeof path, "%s/mpbench_test/meshes", dir);
    rmdir(path);
    snprintf(path, sizeof path, "%s/mpbench_test", dir);
    rmdir(path);
    rmdir(dir);
}

static void bad_arguments_are_refused(void **state)
{
    (void)state;
    mpb_bodies *b = (mpb_bodies *)1;
    char err[128];
    assert_int_equal(mpb_bodies_open(NULL, &b, err, sizeof err), MPB_EINVAL);
    assert_null(b);
    assert_string_equal(err, "bodies: no world");
    assert_int_equal(mpb_bodies_open(NULL, NULL, NULL, 0), MPB_EINVAL);
    mpb_bodies_close(NULL);
    assert_int_equal(mpb_bodies_count(NULL), 0);
    assert_null(mpb_bodies_get(NULL, 0));
    int a, c;
    double q[3] = {0};
    assert_int_equal(mpb_bodies_contact(NULL, q, &a, &c), MPB_EINVAL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(urdf_bodies_are_the_links_and_objects_where_fk_puts_them),
        cmocka_unit_test(the_urdf_contact_is_a_link_and_the_box),
        cmocka_unit_test(planar_bodies_are_capsules_and_prisms),
        cmocka_unit_test(a_mesh_link_is_its_mesh_as_loaded),
        cmocka_unit_test(bad_arguments_are_refused),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
