/*
 * test_robot.c - the robot model: URDF loading (its errors are
 * test_robot_malformed.c's), forward
 * kinematics against poses worked out by hand in the comments, continuous
 * joints, the IK round trip over 1,000 random poses of the PR2 right arm
 * (success rate and times printed), goal regions (contains, distance,
 * sampling), and groups given as joint lists. Test robots are in
 * tests/support/data/.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "mpbench/robot.h"
#include "core/mathconst.h"

#define assert_near(a, b, eps)                                              \
    do {                                                                    \
        double a_ = (a), b_ = (b);                                          \
        if (!(fabs(a_ - b_) <= (eps)))                                      \
            fail_msg("%s = %.17g, expected %.17g (line %d)", #a, a_, b_,    \
                     __LINE__);                                             \
    } while (0)

#define EPS 1e-12

/* ---- helpers ------------------------------------------------------------ */

/* tests/support/data/<name> (MPB_TEST_DATA). */
static void data_path(const char *name, char *out, size_t len)
{
    snprintf(out, len, "%s/%s", MPB_TEST_DATA, name);
}

static char *read_data(const char *name)
{
    char path[1024];
    data_path(name, path, sizeof path);
    FILE *f = fopen(path, "rb");
    if (!f)
        fail_msg("cannot open %s", path);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *s = malloc((size_t)n + 1);
    assert_non_null(s);
    assert_int_equal(fread(s, 1, (size_t)n, f), (size_t)n);
    s[n] = '\0';
    fclose(f);
    return s;
}

static mpb_robot *load_ok(const char *file, const char *base, const char *tip)
{
    char *text = read_data(file);
    mpb_robot *r = NULL;
    char err[256];
    int rc = mpb_robot_open_urdf(text, base, tip, &r, err, sizeof err);
    free(text);
    if (rc != MPB_OK)
        fail_msg("load %s: %s: %s", file, mpb_err_name(rc), err);
    return r;
}

/* The 7-joint PR2 arm, from the torso (torso_lift_joint passive, at 0). */
static mpb_robot *pr2(void)
{
    return load_ok("pr2_right_arm.urdf", "torso_lift_link", "r_wrist_roll_link");
}

static void expect_pose(const mpb_pose *p, const double R[9], double x,
                        double y, double z, double eps, const char *what)
{
    for (int i = 0; i < 9; i++)
        if (!(fabs(p->R[i] - R[i]) <= eps))
            fail_msg("%s: R[%d] = %.17g, expected %g", what, i, p->R[i], R[i]);
    double t[3] = { x, y, z };
    for (int i = 0; i < 3; i++)
        if (!(fabs(p->t[i] - t[i]) <= eps))
            fail_msg("%s: t[%d] = %.17g, expected %g", what, i, p->t[i], t[i]);
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Rotation angle between two rotations, computed here from scratch. */
static double angle_between(const double A[9], const double B[9])
{
    double tr = 0.0;    /* trace(A^T B) */
    for (int i = 0; i < 9; i++)
        tr += A[i] * B[i];
    double c = 0.5 * (tr - 1.0);
    c = c > 1 ? 1 : c < -1 ? -1 : c;
    /* acos loses precision near 0: use the norm of the skew part too. */
    double M[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            M[3 * i + j] = A[i] * B[j] + A[3 + i] * B[3 + j] + A[6 + i] * B[6 + j];
    double v0 = M[7] - M[5], v1 = M[2] - M[6], v2 = M[3] - M[1];
    return atan2(0.5 * sqrt(v0 * v0 + v1 * v1 + v2 * v2), c);
}

static double dist3(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1])
                + (a[2] - b[2]) * (a[2] - b[2]));
}

/* ---- fk3: structure ------------------------------------------------------ */

static void test_fk3_structure(void **state)
{
    (void)state;
    mpb_robot *r = load_ok("fk3.urdf", "base", "tool");
    assert_string_equal(mpb_robot_name(r), "fk3");

    assert_int_equal(mpb_robot_num_joints(r), 3);
    const mpb_robot_joint *j1 = mpb_robot_get_joint(r, 0);
    const mpb_robot_joint *j2 = mpb_robot_get_joint(r, 1);
    const mpb_robot_joint *j3 = mpb_robot_get_joint(r, 2);
    assert_string_equal(j1->name, "j1");
    assert_string_equal(j2->name, "j2");
    assert_string_equal(j3->name, "j3");
    assert_int_equal(j1->type, MPB_JOINT_REVOLUTE);
    assert_int_equal(j2->type, MPB_JOINT_PRISMATIC);
    assert_int_equal(j3->type, MPB_JOINT_CONTINUOUS);
    assert_near(j1->lo, -3.14159, EPS);
    assert_near(j1->hi, 3.14159, EPS);
    assert_near(j1->max_velocity, 1.5, EPS);
    assert_near(j2->lo, 0.0, EPS);
    assert_near(j2->hi, 0.5, EPS);
    assert_near(j3->lo, -M_PI, EPS);      /* continuous: reported as -pi .. pi */
    assert_near(j3->hi, M_PI, EPS);
    assert_near(j3->axis[0], 1.0, EPS);
    assert_null(mpb_robot_get_joint(r, 3));
    assert_null(mpb_robot_get_joint(r, -1));
    const unsigned char *wraps = mpb_robot_joint_wraps(r);
    assert_int_equal(wraps[0], 0);
    assert_int_equal(wraps[1], 0);
    assert_int_not_equal(wraps[2], 0);
    assert_int_equal(mpb_robot_joint_index(r, "j2"), 1);
    assert_int_equal(mpb_robot_joint_index(r, "tool_joint"), MPB_ENOTFOUND);

    /* Six links, the root first, every parent before its children. */
    int n = mpb_robot_num_links(r);
    assert_int_equal(n, 6);
    assert_string_equal(mpb_robot_get_link(r, 0)->name, "base");
    assert_int_equal(mpb_robot_get_link(r, 0)->parent, -1);
    assert_null(mpb_robot_get_link(r, 0)->joint);
    for (int i = 1; i < n; i++) {
        const mpb_robot_link *l = mpb_robot_get_link(r, i);
        assert_true(l->parent >= 0 && l->parent < i);
        assert_non_null(l->joint);
    }
    int base = mpb_robot_link_index(r, "base"), l1 = mpb_robot_link_index(r, "l1");
    int l2 = mpb_robot_link_index(r, "l2"), l3 = mpb_robot_link_index(r, "l3");
    int tool = mpb_robot_link_index(r, "tool");
    int cam = mpb_robot_link_index(r, "camera");
    assert_int_equal(mpb_robot_link_index(r, "nope"), MPB_ENOTFOUND);
    assert_int_equal(mpb_robot_base_link(r), base);
    assert_int_equal(mpb_robot_tip_link(r), tool);
    assert_int_equal(j1->parent_link, base);
    assert_int_equal(j1->child_link, l1);
    assert_int_equal(j3->child_link, l3);

    /* Which links move, and with how many joints. */
    assert_int_equal(mpb_robot_get_link(r, base)->moves, 0);
    assert_int_equal(mpb_robot_get_link(r, cam)->moves, 0);
    assert_int_equal(mpb_robot_get_link(r, cam)->num_chain_joints, 0);
    assert_int_equal(mpb_robot_get_link(r, l1)->moves, 1);
    assert_int_equal(mpb_robot_get_link(r, l1)->num_chain_joints, 1);
    assert_int_equal(mpb_robot_get_link(r, l2)->num_chain_joints, 2);
    assert_int_equal(mpb_robot_get_link(r, l3)->num_chain_joints, 3);
    assert_int_equal(mpb_robot_get_link(r, tool)->num_chain_joints, 3);
    assert_int_equal(mpb_robot_get_link(r, tool)->moves, 1);
    assert_int_equal(mpb_robot_get_link(r, tool)->chain_joint, -1);
    assert_int_equal(mpb_robot_get_link(r, tool)->joint_type, MPB_JOINT_FIXED);
    assert_int_equal(mpb_robot_get_link(r, l2)->chain_joint, 1);
    assert_string_equal(mpb_robot_get_link(r, l2)->joint, "j2");

    /* Collision shapes: base box, l1 box, l2 cylinder + sphere, l3 mesh,
     * camera sphere; grouped by link. */
    assert_int_equal(mpb_robot_num_collisions(r), 6);
    assert_null(mpb_robot_get_collision(r, 6));
    const mpb_robot_link *L2 = mpb_robot_get_link(r, l2);
    assert_int_equal(L2->num_collisions, 2);
    const mpb_robot_collision *cyl = mpb_robot_get_collision(r, L2->first_collision);
    const mpb_robot_collision *sph = mpb_robot_get_collision(r, L2->first_collision + 1);
    assert_int_equal(cyl->link, l2);
    assert_int_equal(cyl->type, MPB_SHAPE_CYLINDER);
    assert_near(cyl->dims[0], 0.05, EPS);
    assert_near(cyl->dims[1], 0.5, EPS);
    /* origin rpy (pi/2, 0, 0): Rx(90) = [1 0 0; 0 0 -1; 0 1 0], at (0, .25, 0) */
    const double Rx90[9] = { 1, 0, 0, 0, 0, -1, 0, 1, 0 };
    expect_pose(&cyl->origin, Rx90, 0, 0.25, 0, 1e-12, "l2 cylinder origin");
    assert_null(cyl->mesh_uri);
    assert_int_equal(sph->type, MPB_SHAPE_SPHERE);
    assert_near(sph->dims[0], 0.07, EPS);

    const mpb_robot_link *L1 = mpb_robot_get_link(r, l1);
    const mpb_robot_collision *box = mpb_robot_get_collision(r, L1->first_collision);
    assert_int_equal(box->type, MPB_SHAPE_BOX);
    assert_near(box->dims[0], 1.0, EPS);     /* full side lengths */
    assert_near(box->dims[1], 0.1, EPS);
    assert_near(box->dims[2], 0.1, EPS);
    assert_string_equal(box->name, "l1_box");

    const mpb_robot_link *L3 = mpb_robot_get_link(r, l3);
    assert_int_equal(L3->num_collisions, 1);
    const mpb_robot_collision *mesh = mpb_robot_get_collision(r, L3->first_collision);
    assert_int_equal(mesh->type, MPB_SHAPE_MESH);
    assert_string_equal(mesh->mesh_uri, "package://mpbench_test/meshes/tool.stl");
    assert_near(mesh->mesh_scale[0], 0.001, EPS);
    assert_near(mesh->mesh_scale[1], 0.002, EPS);
    assert_near(mesh->mesh_scale[2], 0.003, EPS);
    assert_near(mesh->origin.t[0], 0.1, EPS);
    assert_null(mesh->name);
    assert_int_equal(mpb_robot_get_link(r, tool)->num_collisions, 0);

    mpb_robot_close(r);
    mpb_robot_close(NULL);
}

/* ---- fk3: poses by hand --------------------------------------------------- */

/*
 * fk3 (tests/support/data/fk3.urdf). Notation: Rz(90) = [0 -1 0; 1 0 0; 0 0 1]
 * maps (x, y, z) to (-y, x, z); Rx(90) = [1 0 0; 0 0 -1; 0 1 0] maps z to
 * -y; a pose is (R, t) with p_world = R p + t.
 *   base -> l1:   Trans(0 0 1) Rz(q1)
 *   l1 -> l2:     Trans(1 0 0) Rx(90) Trans(0 0 q2)   (axis z of the joint)
 *   l2 -> l3:     Trans(0 .5 0) Rx(q3)
 *   l3 -> tool:   Trans(.2 0 0) Rz(180), Rz(180) = diag(-1 -1 1)
 *   base -> camera: Trans(.1 .2 .3) Rz(90) Rx(90)     (URDF rpy order:
 *                 R = Rz(yaw) Ry(pitch) Rx(roll))
 *
 * Rz(90) Rx(90) = [0 0 1; 1 0 0; 0 1 0]  (row i of Rz(90) times Rx(90):
 *   [0 -1 0] -> [0 0 1]; [1 0 0] -> [1 0 0]; [0 0 1] -> [0 1 0]).
 */
static const double I3[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
static const double RCAM[9] = { 0, 0, 1, 1, 0, 0, 0, 1, 0 };

static void check_all_ways(const mpb_robot *r, const double *q,
                           mpb_pose *poses)
{
    /* mpb_robot_fk, mpb_robot_fk_moving and mpb_robot_link_pose agree. */
    int n = mpb_robot_num_links(r);
    assert_int_equal(mpb_robot_fk(r, q, poses), MPB_OK);
    mpb_pose moving[16];
    assert_true(n <= 16);
    assert_int_equal(mpb_robot_fk(r, q, moving), MPB_OK);   /* statics once */
    double q0[8] = { 0 };
    assert_int_equal(mpb_robot_fk_moving(r, q0, moving), MPB_OK);
    assert_int_equal(mpb_robot_fk_moving(r, q, moving), MPB_OK);
    for (int i = 0; i < n; i++) {
        mpb_pose one;
        assert_int_equal(mpb_robot_link_pose(r, q, i, &one), MPB_OK);
        assert_memory_equal(&one, &poses[i], sizeof one);
        assert_memory_equal(&moving[i], &poses[i], sizeof one);
    }
}

static void test_fk3_poses(void **state)
{
    (void)state;
    mpb_robot *r = load_ok("fk3.urdf", "base", "tool");
    int base = mpb_robot_link_index(r, "base"), l1 = mpb_robot_link_index(r, "l1");
    int l2 = mpb_robot_link_index(r, "l2"), l3 = mpb_robot_link_index(r, "l3");
    int tool = mpb_robot_link_index(r, "tool");
    int cam = mpb_robot_link_index(r, "camera");
    mpb_pose P[6];
    const double eps = 1e-12;

    /*
     * q = (0, 0, 0).
     *   l1:   R = I, t = (0 0 1)
     *   l2:   R = Rx(90), t = (1 0 1)
     *   l3:   R = Rx(90), t = (1 0 1) + Rx(90)(0 .5 0) = (1 0 1) + (0 0 .5)
     *   tool: R = Rx(90) diag(-1 -1 1) = [-1 0 0; 0 0 -1; 0 -1 0],
     *         t = (1 0 1.5) + Rx(90)(.2 0 0) = (1.2 0 1.5)
     */
    double q[3] = { 0, 0, 0 };
    check_all_ways(r, q, P);
    expect_pose(&P[base], I3, 0, 0, 0, eps, "q0 base");
    expect_pose(&P[l1], I3, 0, 0, 1, eps, "q0 l1");
    const double Rx90[9] = { 1, 0, 0, 0, 0, -1, 0, 1, 0 };
    expect_pose(&P[l2], Rx90, 1, 0, 1, eps, "q0 l2");
    expect_pose(&P[l3], Rx90, 1, 0, 1.5, eps, "q0 l3");
    const double Rt0[9] = { -1, 0, 0, 0, 0, -1, 0, -1, 0 };
    expect_pose(&P[tool], Rt0, 1.2, 0, 1.5, eps, "q0 tool");
    expect_pose(&P[cam], RCAM, 0.1, 0.2, 0.3, eps, "q0 camera");

    /*
     * q = (pi/2, 0.3, pi/2).
     *   l1:   R = Rz(90), t = (0 0 1)
     *   l2:   in l1, (1 0 0) + Rx(90)(0 0 .3) = (1 -.3 0); in the world
     *         Rz(90)(1 -.3 0) + (0 0 1) = (.3 1 1);
     *         R = Rz(90) Rx(90) = [0 0 1; 1 0 0; 0 1 0]
     *   l3:   t = (.3 1 1) + R_l2 (0 .5 0) = (.3 1 1) + .5 * column 1 of R_l2
     *         = (.3 1 1.5); R = R_l2 Rx(90): rows [0 0 1] -> [0 1 0],
     *         [1 0 0] -> [1 0 0], [0 1 0] -> [0 0 -1]
     *   tool: t = (.3 1 1.5) + .2 * column 0 of R_l3 = (.3 1.2 1.5);
     *         R = R_l3 diag(-1 -1 1) = [0 -1 0; -1 0 0; 0 0 -1]
     */
    double qa[3] = { M_PI / 2, 0.3, M_PI / 2 };
    check_all_ways(r, qa, P);
    const double Rz90[9] = { 0, -1, 0, 1, 0, 0, 0, 0, 1 };
    expect_pose(&P[l1], Rz90, 0, 0, 1, eps, "qa l1");
    const double Rl2[9] = { 0, 0, 1, 1, 0, 0, 0, 1, 0 };
    expect_pose(&P[l2], Rl2, 0.3, 1, 1, eps, "qa l2");
    const double Rl3[9] = { 0, 1, 0, 1, 0, 0, 0, 0, -1 };
    expect_pose(&P[l3], Rl3, 0.3, 1, 1.5, eps, "qa l3");
    const double Rta[9] = { 0, -1, 0, -1, 0, 0, 0, 0, -1 };
    expect_pose(&P[tool], Rta, 0.3, 1.2, 1.5, eps, "qa tool");
    expect_pose(&P[cam], RCAM, 0.1, 0.2, 0.3, eps, "qa camera");  /* static */

    /*
     * q = (-pi/2, 0.5, pi).
     *   l1:   R = Rz(-90) = [0 1 0; -1 0 0; 0 0 1] ((x y z) -> (y -x z))
     *   l2:   in l1 (1 -.5 0); world Rz(-90)(1 -.5 0) + (0 0 1) = (-.5 -1 1);
     *         R = Rz(-90) Rx(90) = [0 0 -1; -1 0 0; 0 1 0]
     *   l3:   t = (-.5 -1 1) + .5 * column 1 of R_l2 = (-.5 -1 1.5);
     *         R = R_l2 Rx(180) = R_l2 diag(1 -1 -1) = [0 0 1; -1 0 0; 0 -1 0]
     *   tool: t = (-.5 -1 1.5) + .2 * (0 -1 0) = (-.5 -1.2 1.5);
     *         R = R_l3 diag(-1 -1 1) = [0 0 1; 1 0 0; 0 1 0]
     */
    double qb[3] = { -M_PI / 2, 0.5, M_PI };
    check_all_ways(r, qb, P);
    const double Rzm90[9] = { 0, 1, 0, -1, 0, 0, 0, 0, 1 };
    expect_pose(&P[l1], Rzm90, 0, 0, 1, eps, "qb l1");
    const double Rl2b[9] = { 0, 0, -1, -1, 0, 0, 0, 1, 0 };
    expect_pose(&P[l2], Rl2b, -0.5, -1, 1, eps, "qb l2");
    const double Rl3b[9] = { 0, 0, 1, -1, 0, 0, 0, -1, 0 };
    expect_pose(&P[l3], Rl3b, -0.5, -1, 1.5, eps, "qb l3");
    const double Rtb[9] = { 0, 0, 1, 1, 0, 0, 0, 1, 0 };
    expect_pose(&P[tool], Rtb, -0.5, -1.2, 1.5, eps, "qb tool");

    /* Bad arguments. */
    double qnan[3] = { 0, NAN, 0 };
    assert_int_equal(mpb_robot_fk(r, qnan, P), MPB_EINVAL);
    assert_int_equal(mpb_robot_fk(NULL, q, P), MPB_EINVAL);
    assert_int_equal(mpb_robot_fk(r, NULL, P), MPB_EINVAL);
    assert_int_equal(mpb_robot_link_pose(r, q, 6, &P[0]), MPB_EINVAL);
    assert_int_equal(mpb_robot_link_pose(r, q, -1, &P[0]), MPB_EINVAL);
    mpb_robot_close(r);
}

/* ---- axes that are not x, y or z ---------------------------------------- */

/*
 * One revolute joint about (0 3 4) (unit: (0 .6 .8)) at the origin, one
 * about -z at (0 0 1), and a fixed point 1 m along x of each child.
 * Rodrigues: v' = v cos q + (a x v) sin q + a (a . v)(1 - cos q).
 *   v = (1 0 0), a = (0 .6 .8): a x v = (0, .8, -.6), a . v = 0, so at
 *   q = pi/2 v' = (0 .8 -.6) and at q = pi v' = (-1 0 0).
 *   About -z by pi/2: x turns to -y.
 */
static const char *const SKEW =
    "<robot name='skew'><link name='a'/><link name='b'/><link name='bp'/>"
    "<link name='c'/><link name='d'/><link name='dp'/>"
    "<joint name='j1' type='revolute'><parent link='a'/><child link='b'/>"
    "<axis xyz='0 3 4'/><limit lower='-4' upper='4' effort='1' velocity='1'/></joint>"
    "<joint name='fb' type='fixed'><parent link='b'/><child link='bp'/>"
    "<origin xyz='1 0 0'/></joint>"
    "<joint name='fc' type='fixed'><parent link='a'/><child link='c'/>"
    "<origin xyz='0 0 1'/></joint>"
    "<joint name='j2' type='continuous'><parent link='c'/><child link='d'/>"
    "<axis xyz='0 0 -1'/></joint>"
    "<joint name='fd' type='fixed'><parent link='d'/><child link='dp'/>"
    "<origin xyz='1 0 0'/></joint>"
    "</robot>";

static void test_general_axis(void **state)
{
    (void)state;
    mpb_robot *r = NULL;
    char err[256];
    if (mpb_robot_open_urdf(SKEW, "a", "bp", &r, err, sizeof err) != MPB_OK)
        fail_msg("%s", err);
    const mpb_robot_joint *j = mpb_robot_get_joint(r, 0);
    assert_near(j->axis[0], 0.0, EPS);
    assert_near(j->axis[1], 0.6, EPS);
    assert_near(j->axis[2], 0.8, EPS);
    int bp = mpb_robot_link_index(r, "bp"), dp = mpb_robot_link_index(r, "dp");
    assert_int_equal(mpb_robot_get_link(r, dp)->moves, 0);   /* not in group */
    mpb_pose p;
    double q = M_PI / 2;
    assert_int_equal(mpb_robot_link_pose(r, &q, bp, &p), MPB_OK);
    assert_near(p.t[0], 0.0, EPS);
    assert_near(p.t[1], 0.8, EPS);
    assert_near(p.t[2], -0.6, EPS);
    q = M_PI;
    assert_int_equal(mpb_robot_link_pose(r, &q, bp, &p), MPB_OK);
    assert_near(p.t[0], -1.0, EPS);
    assert_near(p.t[1], 0.0, EPS);
    assert_near(p.t[2], 0.0, EPS);
    /* IK through the general axis. */
    mpb_pose target;
    q = 0.7;
    mpb_robot_link_pose(r, &q, bp, &target);
    uint64_t rng = 1;
    double qs;
    assert_int_equal(mpb_robot_ik(r, bp, NULL, &target, NULL, NULL, &rng, &qs, NULL),
                     MPB_OK);
    assert_near(qs, 0.7, 1e-6);
    mpb_robot_close(r);

    if (mpb_robot_open_urdf(SKEW, "c", "dp", &r, err, sizeof err) != MPB_OK)
        fail_msg("%s", err);
    q = M_PI / 2;
    assert_int_equal(mpb_robot_link_pose(r, &q, dp, &p), MPB_OK);
    assert_near(p.t[0], 0.0, EPS);
    assert_near(p.t[1], -1.0, EPS);
    assert_near(p.t[2], 1.0, EPS);
    mpb_robot_close(r);
}

/* ---- continuous joints ------------------------------------------------- */

static void test_continuous(void **state)
{
    (void)state;
    mpb_robot *r = load_ok("fk3.urdf", "base", "tool");
    int tool = mpb_robot_link_index(r, "tool");

    /* j3 at a and a + 2 pi k: the same poses. */
    double qa[3] = { 0.3, 0.2, 2.5 }, qb[3] = { 0.3, 0.2, 2.5 - 6 * M_PI };
    mpb_pose a, b;
    assert_int_equal(mpb_robot_link_pose(r, qa, tool, &a), MPB_OK);
    assert_int_equal(mpb_robot_link_pose(r, qb, tool, &b), MPB_OK);
    for (int i = 0; i < 9; i++)
        assert_near(a.R[i], b.R[i], 1e-12);
    for (int i = 0; i < 3; i++)
        assert_near(a.t[i], b.t[i], 1e-12);

    /* Limits: a continuous joint takes any finite value. */
    assert_true(mpb_robot_within_limits(r, qb));
    double qout[3] = { 0.3, 0.6, 0 };    /* j2 above its 0.5 */
    assert_false(mpb_robot_within_limits(r, qout));
    double qinf[3] = { 0.3, 0.2, INFINITY };
    assert_false(mpb_robot_within_limits(r, qinf));

    /*
     * IK from a seed near 2.5 - 4 pi, far outside (-pi, pi]: the answer is
     * wrapped into (-pi, pi] and reproduces the pose.
     */
    double seed[3] = { 0.25, 0.25, 2.4 - 4 * M_PI }, q[3];
    uint64_t rng = 7;
    mpb_ik_info info;
    assert_int_equal(mpb_robot_ik(r, tool, NULL, &a, seed, NULL, &rng, q, &info),
                     MPB_OK);
    assert_true(q[2] > -M_PI && q[2] <= M_PI);
    assert_near(q[2], 2.5, 1e-5);
    assert_near(q[0], 0.3, 1e-5);
    assert_near(q[1], 0.2, 1e-5);
    assert_true(info.position_error <= 1e-6);
    assert_true(info.orientation_error <= 1e-6);

    /* Random configurations stay inside the limits, j3 in [-pi, pi). */
    uint64_t s = 99;
    for (int k = 0; k < 1000; k++) {
        assert_int_equal(mpb_robot_random_config(r, &s, q), MPB_OK);
        assert_true(mpb_robot_within_limits(r, q));
        assert_true(q[2] >= -M_PI && q[2] < M_PI);
    }
    mpb_robot_close(r);
}

/* ---- PR2 arm: FK by hand, passive torso ---------------------------------- */

/*
 * The PR2 right arm (shared/DESIGN.md table), group torso_lift_link ->
 * r_wrist_roll_link, torso_lift_joint passive at 0. Joints in order: pan
 * (z), lift (y), upper arm roll (x), elbow flex (y), forearm roll (x,
 * continuous), wrist flex (y), wrist roll (x, continuous).
 * The tool frame is 0.18 m along x of the wrist roll link.
 */
static void test_pr2_fk(void **state)
{
    (void)state;
    mpb_robot *r = pr2();
    assert_int_equal(mpb_robot_num_joints(r), 7);
    const char *names[7] = { "r_shoulder_pan_joint", "r_shoulder_lift_joint",
                             "r_upper_arm_roll_joint", "r_elbow_flex_joint",
                             "r_forearm_roll_joint", "r_wrist_flex_joint",
                             "r_wrist_roll_joint" };
    for (int j = 0; j < 7; j++)
        assert_string_equal(mpb_robot_get_joint(r, j)->name, names[j]);
    assert_int_equal(mpb_robot_get_joint(r, 4)->type, MPB_JOINT_CONTINUOUS);
    assert_int_equal(mpb_robot_get_joint(r, 6)->type, MPB_JOINT_CONTINUOUS);
    int tool = mpb_robot_link_index(r, "r_gripper_tool_frame");
    int torso = mpb_robot_link_index(r, "torso_lift_link");
    int palm = mpb_robot_link_index(r, "r_gripper_palm_link");
    assert_int_equal(mpb_robot_get_link(r, torso)->moves, 0);  /* passive */
    assert_int_equal(mpb_robot_get_link(r, palm)->moves, 1);   /* fixed child */
    assert_int_equal(mpb_robot_get_link(r, palm)->num_chain_joints, 7);
    assert_int_equal(mpb_robot_num_links(r), 13);
    assert_int_equal(mpb_robot_num_collisions(r), 10);

    /*
     * q = 0: everything lies along x. Tool at
     *   x = -0.05 (torso) + 0.1 (lift) + 0.4 (elbow) + 0.321 (wrist)
     *       + 0.18 (tool) = 0.951,  y = -0.188,  z = 0.739675.
     */
    double q[7] = { 0 };
    mpb_pose p;
    assert_int_equal(mpb_robot_link_pose(r, q, tool, &p), MPB_OK);
    expect_pose(&p, I3, 0.951, -0.188, 0.739675, 1e-12, "pr2 q0 tool");

    /*
     * Pan -pi/2: the arm points along -y from the pan axis at
     * (-0.05, -0.188): tool at (-0.05, -0.188 - 0.1 - 0.901, 0.739675) =
     * (-0.05, -1.189, 0.739675), R = Rz(-90) = [0 1 0; -1 0 0; 0 0 1].
     */
    q[0] = -M_PI / 2;
    assert_int_equal(mpb_robot_link_pose(r, q, tool, &p), MPB_OK);
    const double Rzm90[9] = { 0, 1, 0, -1, 0, 0, 0, 0, 1 };
    expect_pose(&p, Rzm90, -0.05, -1.189, 0.739675, 1e-12, "pr2 pan tool");

    /*
     * Elbow flex -pi/2 about y: Ry(-90) = [0 0 -1; 0 1 0; 1 0 0] turns x
     * into +z, so the forearm points up from the elbow at
     * (-0.05 + 0.1 + 0.4, -0.188, 0.739675): tool at
     * (0.45, -0.188, 0.739675 + 0.321 + 0.18) = (0.45, -0.188, 1.240675).
     */
    q[0] = 0;
    q[3] = -M_PI / 2;
    assert_int_equal(mpb_robot_link_pose(r, q, tool, &p), MPB_OK);
    const double Rym90[9] = { 0, 0, -1, 0, 1, 0, 1, 0, 0 };
    expect_pose(&p, Rym90, 0.45, -0.188, 1.240675, 1e-12, "pr2 elbow tool");

    /* The torso up by 0.2: static links and the arm move up with it. */
    assert_int_equal(mpb_robot_set_passive(r, "torso_lift_joint", 0.2), MPB_OK);
    assert_int_equal(mpb_robot_link_pose(r, q, tool, &p), MPB_OK);
    expect_pose(&p, Rym90, 0.45, -0.188, 1.440675, 1e-12, "pr2 torso tool");
    assert_int_equal(mpb_robot_link_pose(r, q, torso, &p), MPB_OK);
    expect_pose(&p, I3, -0.05, 0, 0.939675, 1e-12, "pr2 torso");
    assert_int_equal(mpb_robot_set_passive(r, "torso_lift_joint", 0.5), MPB_EINVAL);
    assert_int_equal(mpb_robot_set_passive(r, "r_elbow_flex_joint", 0.0), MPB_EINVAL);
    assert_int_equal(mpb_robot_set_passive(r, "r_gripper_palm_joint", 0.0), MPB_EINVAL);
    assert_int_equal(mpb_robot_set_passive(r, "nope", 0.0), MPB_ENOTFOUND);
    assert_int_equal(mpb_robot_set_passive(r, "torso_lift_joint", NAN), MPB_EINVAL);

    /* The group from the root instead: 8 joints, the torso first. */
    mpb_robot *r8 = load_ok("pr2_right_arm.urdf", NULL, "r_gripper_tool_frame");
    assert_int_equal(mpb_robot_num_joints(r8), 8);
    assert_string_equal(mpb_robot_get_joint(r8, 0)->name, "torso_lift_joint");
    assert_int_equal(mpb_robot_get_joint(r8, 0)->type, MPB_JOINT_PRISMATIC);
    double q8[8] = { 0.2, 0, 0, 0, -M_PI / 2, 0, 0, 0 };
    assert_int_equal(mpb_robot_link_pose(r8, q8, mpb_robot_tip_link(r8), &p), MPB_OK);
    expect_pose(&p, Rym90, 0.45, -0.188, 1.440675, 1e-12, "pr2 8-joint tool");
    mpb_robot_close(r8);
    mpb_robot_close(r);
}

/* ---- PR2 arm: IK round trip ------------------------------------------- */

static void test_pr2_ik_roundtrip(void **state)
{
    (void)state;
    mpb_robot *r = pr2();
    int tool = mpb_robot_link_index(r, "r_gripper_tool_frame");
    const int trials = 1000;
    uint64_t gen = 12345, rng = 777;
    int ok = 0, attempts = 0, iterations = 0;
    double t_ik = 0.0, worst_p = 0.0, worst_r = 0.0;

    for (int k = 0; k < trials; k++) {
        double qr[7], q[7];
        mpb_pose target, got;
        assert_int_equal(mpb_robot_random_config(r, &gen, qr), MPB_OK);
        assert_int_equal(mpb_robot_link_pose(r, qr, tool, &target), MPB_OK);
        mpb_ik_info info;
        double t0 = now();
        int rc = mpb_robot_ik(r, tool, NULL, &target, NULL, NULL, &rng, q, &info);
        t_ik += now() - t0;
        attempts += info.attempts;
        iterations += info.iterations;
        if (rc != MPB_OK) {
            assert_int_equal(rc, MPB_ENOTFOUND);
            continue;
        }
        ok++;
        /* Checked here, independently of the solver's own numbers. */
        assert_true(mpb_robot_within_limits(r, q));
        for (int j = 0; j < 7; j++)
            if (mpb_robot_joint_wraps(r)[j])
                assert_true(q[j] > -M_PI && q[j] <= M_PI);
        assert_int_equal(mpb_robot_link_pose(r, q, tool, &got), MPB_OK);
        double dp = dist3(got.t, target.t), dr = angle_between(got.R, target.R);
        if (dp > worst_p)
            worst_p = dp;
        if (dr > worst_r)
            worst_r = dr;
        assert_true(dp <= 1e-4);
        assert_true(dr <= 1e-3);
    }
    printf("[ robot    ] IK round trip, PR2 right arm (7 joints), %d random "
           "reachable tool poses: %d solved (%.1f%%), %.3f ms per solve, "
           "%.2f starts and %.1f steps per solve; worst error %.2g m, %.2g rad\n",
           trials, ok, 100.0 * ok / trials, 1e3 * t_ik / trials,
           (double)attempts / trials, (double)iterations / trials, worst_p,
           worst_r);
    assert_true(ok >= trials * 95 / 100);

    /* Deterministic: the same seed, the same answer. */
    double qr[7], q1[7], q2[7];
    mpb_pose target;
    uint64_t g2 = 5;
    mpb_robot_random_config(r, &g2, qr);
    mpb_robot_link_pose(r, qr, tool, &target);
    uint64_t s1 = 42, s2 = 42;
    assert_int_equal(mpb_robot_ik(r, tool, NULL, &target, NULL, NULL, &s1, q1, NULL), MPB_OK);
    assert_int_equal(mpb_robot_ik(r, tool, NULL, &target, NULL, NULL, &s2, q2, NULL), MPB_OK);
    assert_memory_equal(q1, q2, sizeof q1);
    assert_true(s1 == s2);

    /* FK timing: the fast path, every link. */
    mpb_pose poses[13];
    double q[7] = { 0 };
    mpb_robot_fk(r, q, poses);
    const int calls = 200000;
    double t0 = now(), sink = 0.0;
    for (int k = 0; k < calls; k++) {
        q[k % 7] = 1e-6 * (double)(k % 1000);
        mpb_robot_fk_moving(r, q, poses);
        sink += poses[12].t[0];
    }
    double t_fk = now() - t0;
    t0 = now();
    for (int k = 0; k < calls; k++) {
        q[k % 7] = 1e-6 * (double)(k % 1000);
        mpb_robot_fk(r, q, poses);
        sink += poses[12].t[0];
    }
    double t_fk_all = now() - t0;
    printf("[ robot    ] FK, PR2 arm, 13 links (11 moving): %.0f ns per "
           "mpb_robot_fk_moving, %.0f ns per mpb_robot_fk (%g)\n",
           1e9 * t_fk / calls, 1e9 * t_fk_all / calls, sink > 0 ? 1.0 : 0.0);
    mpb_robot_close(r);
}

/* IK details: an offset point, position only, unreachable, bad arguments. */
static void test_ik_modes(void **state)
{
    (void)state;
    mpb_robot *r = pr2();
    int wrist = mpb_robot_link_index(r, "r_wrist_roll_link");
    int tool = mpb_robot_link_index(r, "r_gripper_tool_frame");
    uint64_t gen = 3, rng = 4;
    double qr[7], q[7];
    mpb_pose target, got;
    mpb_robot_random_config(r, &gen, qr);

    /* The wrist link with offset (0.18 0 0) is the tool frame. */
    const double off[3] = { 0.18, 0, 0 };
    mpb_robot_link_pose(r, qr, tool, &target);
    assert_int_equal(mpb_robot_ik(r, wrist, off, &target, NULL, NULL, &rng, q, NULL),
                     MPB_OK);
    mpb_robot_link_pose(r, q, tool, &got);
    assert_true(dist3(got.t, target.t) <= 1e-5);
    assert_true(angle_between(got.R, target.R) <= 1e-5);

    /* Position only: the point matches, whatever the rotation. */
    mpb_ik_options opt;
    mpb_ik_options_init(&opt);
    opt.position_only = 1;
    mpb_pose_set_rpy(&target, 1.0, 0.5, -2.0);
    assert_int_equal(mpb_robot_ik(r, tool, NULL, &target, NULL, &opt, &rng, q, NULL),
                     MPB_OK);
    mpb_robot_link_pose(r, q, tool, &got);
    assert_true(dist3(got.t, target.t) <= 1e-5);

    /* Out of reach (3 m away): ENOTFOUND, q_out still within limits. */
    mpb_pose far;
    mpb_pose_identity(&far);
    far.t[0] = 3.0;
    mpb_ik_info info;
    opt.position_only = 0;
    opt.max_attempts = 5;
    assert_int_equal(mpb_robot_ik(r, tool, NULL, &far, NULL, &opt, &rng, q, &info),
                     MPB_ENOTFOUND);
    assert_int_equal(info.attempts, 5);
    assert_true(info.position_error > 1.5);
    assert_true(mpb_robot_within_limits(r, q));

    /* A link the chain does not move: solved only where it already is. */
    int torso = mpb_robot_link_index(r, "torso_lift_link");
    mpb_robot_link_pose(r, qr, torso, &target);
    assert_int_equal(mpb_robot_ik(r, torso, NULL, &target, qr, NULL, &rng, q, NULL),
                     MPB_OK);
    assert_memory_equal(q, qr, sizeof q);

    /* Bad arguments. */
    mpb_pose bad = target;
    bad.R[0] = 2.0;
    assert_int_equal(mpb_robot_ik(r, tool, NULL, &bad, NULL, NULL, &rng, q, NULL),
                     MPB_EINVAL);
    assert_int_equal(mpb_robot_ik(r, 99, NULL, &target, NULL, NULL, &rng, q, NULL),
                     MPB_EINVAL);
    assert_int_equal(mpb_robot_ik(r, tool, NULL, &target, NULL, NULL, NULL, q, NULL),
                     MPB_EINVAL);
    opt.max_attempts = 0;
    assert_int_equal(mpb_robot_ik(r, tool, NULL, &target, NULL, &opt, &rng, q, NULL),
                     MPB_EINVAL);
    mpb_robot_close(r);
}

/* ---- goal regions ------------------------------------------------------ */

static void test_goal_contains(void **state)
{
    (void)state;
    mpb_robot *r = pr2();
    int tool = mpb_robot_link_index(r, "r_gripper_tool_frame");
    int wrist = mpb_robot_link_index(r, "r_wrist_roll_link");
    double q[7] = { 0 };
    mpb_goal_distance d;

    /* At q = 0 the tool is at (0.951, -0.188, 0.739675), R = I (see above). */
    mpb_goal_region g = {
        .link = tool,
        .center = { 0.951, -0.188, 0.739675 },
        .half_extents = { 0.01, 0.01, 0.01 },   /* the paper's 2 cm cube */
        .rpy_tolerance = { 0.05, 0.05, 0.05 },
    };
    assert_int_equal(mpb_goal_region_check(r, &g, NULL, 0), MPB_OK);
    assert_int_equal(mpb_goal_region_contains(r, &g, q), 1);
    assert_int_equal(mpb_goal_region_distance(r, &g, q, &d), MPB_OK);
    assert_near(d.position, 0.0, 0.0);
    assert_near(d.orientation, 0.0, 0.0);
    assert_near(d.point[0], 0.951, 1e-12);

    /* The wrist link with the tool offset is the same point. */
    mpb_goal_region gw = g;
    gw.link = wrist;
    gw.offset[0] = 0.18;
    assert_int_equal(mpb_goal_region_contains(r, &gw, q), 1);
    gw.offset[0] = 0.0;     /* the wrist itself is 0.18 short: 0.17 outside */
    assert_int_equal(mpb_goal_region_contains(r, &gw, q), 0);
    assert_int_equal(mpb_goal_region_distance(r, &gw, q, &d), MPB_OK);
    assert_near(d.position, 0.17, 1e-12);

    /* Centre moved by (0.03, 0, -0.04): outside by (0.02, 0, 0.03), 0.036. */
    mpb_goal_region g2 = g;
    g2.center[0] += 0.03;
    g2.center[2] -= 0.04;
    assert_int_equal(mpb_goal_region_contains(r, &g2, q), 0);
    mpb_goal_region_distance(r, &g2, q, &d);
    assert_near(d.position, sqrt(0.02 * 0.02 + 0.03 * 0.03), 1e-12);

    /* Exactly on the face: inside (comparisons are <=). */
    g2 = g;
    g2.center[1] = -0.188 + 0.01;
    g2.half_extents[1] = 0.015;
    assert_int_equal(mpb_goal_region_contains(r, &g2, q), 1);

    /*
     * Reference yaw 0.1: R_rel = Rz(0.1)^T I = Rz(-0.1), rpy (0, 0, -0.1),
     * 0.05 over the tolerance.
     */
    g2 = g;
    g2.ref_rpy[2] = 0.1;
    assert_int_equal(mpb_goal_region_contains(r, &g2, q), 0);
    mpb_goal_region_distance(r, &g2, q, &d);
    assert_near(d.rpy_rel[2], -0.1, 1e-12);
    assert_near(d.orientation, 0.05, 1e-12);
    assert_near(d.angle, 0.1, 1e-12);
    g2.rpy_tolerance[2] = 0.1;
    assert_int_equal(mpb_goal_region_contains(r, &g2, q), 1);

    /*
     * Gimbal lock of the reference. With the elbow at -pi/2 the tool points
     * up, R = Ry(-90) = [0 0 -1; 0 1 0; 1 0 0] (see test_pr2_fk), which is
     * rpy (0, -pi/2, 0). At pitch -pi/2, Ry(-90) Rx(r) has rows
     * [0 -sin r -cos r], [0 cos r -sin r], [1 0 0], and Rz(y) times it has
     * first row [0 -sin(r+y) -cos(r+y)]: only r + y counts, so
     * (0.3, -pi/2, -0.3) is the same rotation. Both references must contain
     * the configuration; a difference of rpy triples would see 0.3 rad of
     * roll and 0.3 of yaw.
     */
    double qe[7] = { 0, 0, 0, -M_PI / 2, 0, 0, 0 };
    mpb_pose A, B;
    mpb_pose_identity(&A);
    mpb_pose_identity(&B);
    mpb_pose_set_rpy(&A, 0, -M_PI / 2, 0);
    mpb_pose_set_rpy(&B, 0.3, -M_PI / 2, -0.3);
    assert_true(angle_between(A.R, B.R) < 1e-12);
    const double same = -0.3;
    mpb_goal_region gl = g;
    gl.center[0] = 0.45;
    gl.center[2] = 1.240675;
    gl.ref_rpy[0] = 0.0;
    gl.ref_rpy[1] = -M_PI / 2;
    gl.ref_rpy[2] = 0.0;
    assert_int_equal(mpb_goal_region_contains(r, &gl, qe), 1);
    gl.ref_rpy[0] = 0.3;
    gl.ref_rpy[2] = same;
    assert_int_equal(mpb_goal_region_contains(r, &gl, qe), 1);
    mpb_goal_region_distance(r, &gl, qe, &d);
    assert_true(d.angle < 1e-9);

    /* Bad regions. */
    mpb_goal_region bad = g;
    char err[128];
    bad.half_extents[0] = -1;
    assert_int_equal(mpb_goal_region_check(r, &bad, err, sizeof err), MPB_EINVAL);
    assert_non_null(strstr(err, "negative"));
    assert_int_equal(mpb_goal_region_contains(r, &bad, q), MPB_EINVAL);
    bad = g;
    bad.center[1] = NAN;
    assert_int_equal(mpb_goal_region_contains(r, &bad, q), MPB_EINVAL);
    bad = g;
    bad.link = 13;
    assert_int_equal(mpb_goal_region_check(r, &bad, err, sizeof err), MPB_EINVAL);
    double qn[7] = { 0, 0, NAN, 0, 0, 0, 0 };
    assert_int_equal(mpb_goal_region_contains(r, &g, qn), MPB_EINVAL);
    mpb_robot_close(r);
}

static void test_goal_sample(void **state)
{
    (void)state;
    mpb_robot *r = pr2();
    int tool = mpb_robot_link_index(r, "r_gripper_tool_frame");
    uint64_t gen = 2024;
    int ok = 0;
    double t = 0.0;
    for (int k = 0; k < 20; k++) {
        /* A region around a reachable pose: the paper's sizes. */
        double qr[7], q[7];
        mpb_pose p;
        mpb_robot_random_config(r, &gen, qr);
        mpb_robot_link_pose(r, qr, tool, &p);
        mpb_goal_region g = {
            .link = tool,
            .half_extents = { 0.01, 0.01, 0.01 },
            .rpy_tolerance = { 0.05, 0.05, 0.05 },
        };
        memcpy(g.center, p.t, sizeof g.center);
        mpb_pose_get_rpy(&p, g.ref_rpy);
        uint64_t rng = (uint64_t)k;
        double t0 = now();
        int rc = mpb_goal_region_sample(r, &g, NULL, NULL, 0, &rng, q);
        t += now() - t0;
        if (rc == MPB_OK) {
            ok++;
            assert_int_equal(mpb_goal_region_contains(r, &g, q), 1);
            assert_true(mpb_robot_within_limits(r, q));
            /* Same seed, same sample. */
            double q2[7];
            uint64_t rng2 = (uint64_t)k;
            assert_int_equal(mpb_goal_region_sample(r, &g, NULL, NULL, 0, &rng2, q2),
                             MPB_OK);
            assert_memory_equal(q, q2, sizeof q);
        } else {
            assert_int_equal(rc, MPB_ENOTFOUND);
        }
    }
    printf("[ robot    ] goal region sampling (2 cm cube, 0.05 rad): %d of 20 "
           "regions, %.3f ms per call\n", ok, 1e3 * t / 20);
    assert_true(ok >= 19);

    /* Position only when every angle is free. */
    mpb_goal_region free_rot = {
        .link = tool,
        .center = { 0.6, -0.4, 0.8 },
        .half_extents = { 0.01, 0.01, 0.01 },
        .rpy_tolerance = { M_PI, M_PI, M_PI },
    };
    double q[7];
    uint64_t rng = 11;
    assert_int_equal(mpb_goal_region_sample(r, &free_rot, NULL, NULL, 0, &rng, q),
                     MPB_OK);
    assert_int_equal(mpb_goal_region_contains(r, &free_rot, q), 1);

    /* Out of reach. */
    mpb_goal_region far = free_rot;
    far.center[0] = 5.0;
    mpb_ik_options opt;
    mpb_ik_options_init(&opt);
    opt.max_attempts = 2;
    assert_int_equal(mpb_goal_region_sample(r, &far, NULL, &opt, 3, &rng, q),
                     MPB_ENOTFOUND);
    assert_int_equal(mpb_goal_region_sample(r, &far, NULL, NULL, 0, NULL, q),
                     MPB_EINVAL);
    mpb_robot_close(r);
}

/* ---- groups as joint lists ------------------------------------------------ */

static void test_joint_list(void **state)
{
    (void)state;
    char *text = read_data("pr2_right_arm.urdf");
    char err[256];
    mpb_robot *r = NULL;
    const char *arm[7] = { "r_shoulder_pan_joint", "r_shoulder_lift_joint",
                           "r_upper_arm_roll_joint", "r_elbow_flex_joint",
                           "r_forearm_roll_joint", "r_wrist_flex_joint",
                           "r_wrist_roll_joint" };
    assert_int_equal(mpb_robot_open_urdf_joints(text, arm, 7, &r, err, sizeof err),
                     MPB_OK);
    assert_int_equal(mpb_robot_num_joints(r), 7);
    assert_string_equal(mpb_robot_get_link(r, mpb_robot_base_link(r))->name,
                        "torso_lift_link");
    assert_string_equal(mpb_robot_get_link(r, mpb_robot_tip_link(r))->name,
                        "r_wrist_roll_link");
    double q[7] = { 0 };
    mpb_pose p;
    mpb_robot_link_pose(r, q, mpb_robot_link_index(r, "r_gripper_tool_frame"), &p);
    assert_near(p.t[0], 0.951, 1e-12);
    mpb_robot_close(r);

    /* Skipping joints makes them passive: the upper arm roll holds 0. */
    const char *some[3] = { "r_shoulder_pan_joint", "r_elbow_flex_joint",
                            "r_wrist_roll_joint" };
    assert_int_equal(mpb_robot_open_urdf_joints(text, some, 3, &r, err, sizeof err),
                     MPB_OK);
    assert_int_equal(mpb_robot_num_joints(r), 3);
    assert_int_equal(mpb_robot_get_link(r, mpb_robot_link_index(
                         r, "r_upper_arm_roll_link"))->chain_joint, -1);
    mpb_robot_close(r);

    /* Out of order, unknown, fixed, twice. */
    const char *rev[2] = { "r_elbow_flex_joint", "r_shoulder_pan_joint" };
    assert_int_equal(mpb_robot_open_urdf_joints(text, rev, 2, &r, err, sizeof err),
                     MPB_EPARSE);
    assert_null(r);
    assert_non_null(strstr(err, "not below"));
    const char *unk[1] = { "r_elbow_joint" };
    assert_int_equal(mpb_robot_open_urdf_joints(text, unk, 1, &r, err, sizeof err),
                     MPB_EPARSE);
    assert_non_null(strstr(err, "'r_elbow_joint' not found"));
    const char *fix[1] = { "r_gripper_palm_joint" };
    assert_int_equal(mpb_robot_open_urdf_joints(text, fix, 1, &r, err, sizeof err),
                     MPB_EPARSE);
    assert_non_null(strstr(err, "fixed"));
    const char *twice[2] = { "r_elbow_flex_joint", "r_elbow_flex_joint" };
    assert_int_equal(mpb_robot_open_urdf_joints(text, twice, 2, &r, err, sizeof err),
                     MPB_EPARSE);
    assert_non_null(strstr(err, "twice"));
    assert_int_equal(mpb_robot_open_urdf_joints(text, arm, 0, &r, err, sizeof err),
                     MPB_EPARSE);
    free(text);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fk3_structure),
        cmocka_unit_test(test_fk3_poses),
        cmocka_unit_test(test_general_axis),
        cmocka_unit_test(test_continuous),
        cmocka_unit_test(test_pr2_fk),
        cmocka_unit_test(test_pr2_ik_roundtrip),
        cmocka_unit_test(test_ik_modes),
        cmocka_unit_test(test_goal_contains),
        cmocka_unit_test(test_goal_sample),
        cmocka_unit_test(test_joint_list),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
