/*
 * test_mesh.c - meshes through assimp: a box written by the test as ASCII
 * STL, binary STL, OBJ and COLLADA loads with the right counts and bounds;
 * scale; package://, file://, absolute and relative URIs against a search
 * path; one-line errors naming the file; a loaded mesh in the collision
 * world. Every mesh file is generated here, in a fresh temporary directory.
 */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "mpbench/collision.h"
#include "mpbench/mesh.h"
#include "geometry/mesh.h"

#define assert_near(a, b, eps)                                              \
    do {                                                                    \
        double a_ = (a), b_ = (b);                                          \
        if (!(fabs(a_ - b_) <= (eps)))                                      \
            fail_msg("%s = %.17g, expected %.17g (line %d)", #a, a_, b_,    \
                     __LINE__);                                             \
    } while (0)

static char root[256];          /* the temporary directory */

/* The 8 corners of the box [-hx, hx] x [-hy, hy] x [-hz, hz], index bits
   x = 1, y = 2, z = 4, and its 6 faces as outward quads. */
static const double H[3] = { 0.5, 0.25, 0.125 };
static const int QUAD[6][4] = {
    { 0, 2, 3, 1 }, { 4, 5, 7, 6 },     /* z-, z+ */
    { 0, 1, 5, 4 }, { 2, 6, 7, 3 },     /* y-, y+ */
    { 0, 4, 6, 2 }, { 1, 3, 7, 5 },     /* x-, x+ */
};

static void corner(int i, double p[3])
{
    p[0] = (i & 1) ? H[0] : -H[0];
    p[1] = (i & 2) ? H[1] : -H[1];
    p[2] = (i & 4) ? H[2] : -H[2];
}

static void path_of(char *out, size_t len, const char *rel)
{
    snprintf(out, len, "%s/%s", root, rel);
}

/* mkdir -p for the directories of rel (relative to root). */
static void make_dirs(const char *rel)
{
    char p[512];
    path_of(p, sizeof p, rel);
    for (char *s = p + strlen(root) + 1; *s; s++)
        if (*s == '/') {
            *s = '\0';
            if (mkdir(p, 0700) != 0 && errno != EEXIST)
                fail_msg("mkdir %s: %s", p, strerror(errno));
            *s = '/';
        }
}

static FILE *create(const char *rel, const char *mode)
{
    make_dirs(rel);
    char p[512];
    path_of(p, sizeof p, rel);
    FILE *f = fopen(p, mode);
    if (!f)
        fail_msg("fopen %s: %s", p, strerror(errno));
    return f;
}

static void write_text(const char *rel, const char *text)
{
    FILE *f = create(rel, "w");
    fputs(text, f);
    fclose(f);
}

/* Each quad as two triangles, with a facet normal, in ASCII STL. */
static void write_ascii_stl(const char *rel)
{
    FILE *f = create(rel, "w");
    fprintf(f, "solid box\n");
    for (int q = 0; q < 6; q++)
        for (int t = 0; t < 2; t++) {
            int v[3] = { QUAD[q][0], QUAD[q][1 + t], QUAD[q][2 + t] };
            fprintf(f, "  facet normal 0 0 0\n    outer loop\n");
            for (int k = 0; k < 3; k++) {
                double p[3];
                corner(v[k], p);
                fprintf(f, "      vertex %.17g %.17g %.17g\n", p[0], p[1], p[2]);
            }
            fprintf(f, "    endloop\n  endfacet\n");
        }
    fprintf(f, "endsolid box\n");
    fclose(f);
}

/* The same in binary STL: 80-byte header, count, 50 bytes a triangle. */
static void write_binary_stl(const char *rel)
{
    FILE *f = create(rel, "wb");
    char header[80] = "binary box written by test_mesh";
    fwrite(header, 1, sizeof header, f);
    uint32_t n = 12;
    fwrite(&n, 4, 1, f);
    for (int q = 0; q < 6; q++)
        for (int t = 0; t < 2; t++) {
            int v[3] = { QUAD[q][0], QUAD[q][1 + t], QUAD[q][2 + t] };
            float rec[12] = { 0 };
            for (int k = 0; k < 3; k++) {
                double p[3];
                corner(v[k], p);
                for (int j = 0; j < 3; j++)
                    rec[3 + 3 * k + j] = (float)p[j];
            }
            fwrite(rec, sizeof(float), 12, f);
            uint16_t attr = 0;
            fwrite(&attr, 2, 1, f);
        }
    fclose(f);
}

static void write_obj(const char *rel)
{
    FILE *f = create(rel, "w");
    fprintf(f, "# box\no box\n");
    for (int i = 0; i < 8; i++) {
        double p[3];
        corner(i, p);
        fprintf(f, "v %.17g %.17g %.17g\n", p[0], p[1], p[2]);
    }
    for (int q = 0; q < 6; q++)
        fprintf(f, "f %d %d %d %d\n", QUAD[q][0] + 1, QUAD[q][1] + 1,
                QUAD[q][2] + 1, QUAD[q][3] + 1);
    fclose(f);
}

/*
 * A COLLADA box in centimetres (unit meter="0.01"), Z_UP, its node moved
 * by 10 cm along x: loads in metres, Z up as written, moved 0.1 m.
 */
static void write_dae(const char *rel)
{
    FILE *f = create(rel, "w");
    fprintf(f, "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
            "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
            "<asset><unit name=\"centimeter\" meter=\"0.01\"/><up_axis>Z_UP</up_axis></asset>\n"
            "<library_geometries><geometry id=\"g\"><mesh>\n"
            "<source id=\"p\"><float_array id=\"pa\" count=\"24\">");
    for (int i = 0; i < 8; i++) {
        double p[3];
        corner(i, p);
        fprintf(f, "%g %g %g ", 100 * p[0], 100 * p[1], 100 * p[2]);
    }
    fprintf(f, "</float_array><technique_common><accessor source=\"#pa\" count=\"8\" stride=\"3\">"
            "<param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/>"
            "<param name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n"
            "<vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>\n"
            "<triangles count=\"12\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/><p>");
    for (int q = 0; q < 6; q++)
        fprintf(f, "%d %d %d %d %d %d ", QUAD[q][0], QUAD[q][1], QUAD[q][2],
                QUAD[q][0], QUAD[q][2], QUAD[q][3]);
    fprintf(f, "</p></triangles></mesh></geometry></library_geometries>\n"
            "<library_visual_scenes><visual_scene id=\"s\"><node id=\"n\">"
            "<matrix>1 0 0 10 0 1 0 0 0 0 1 0 0 0 0 1</matrix>"
            "<instance_geometry url=\"#g\"/></node></visual_scene></library_visual_scenes>\n"
            "<scene><instance_visual_scene url=\"#s\"/></scene>\n</COLLADA>\n");
    fclose(f);
}

static int setup(void **state)
{
    (void)state;
    snprintf(root, sizeof root, "%s/mpb-test-mesh-XXXXXX",
             getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(root))
        return -1;
    write_ascii_stl("ws2/arm/meshes/box.stl");
    write_binary_stl("ws2/arm/meshes/box_binary.stl");
    write_obj("ws2/arm/meshes/box.obj");
    write_dae("ws2/arm/meshes/box.dae");
    write_text("ws1/other/readme.txt", "not a mesh\n");
    write_text("ws2/arm/meshes/garbage.stl", "solid x\n  facet normal what\nthis is not STL\n");
    write_text("ws2/arm/meshes/broken.dae", "<COLLADA><asset");
    write_text("ws2/arm/meshes/bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    FILE *f = create("ws2/arm/meshes/short.stl", "wb");     /* 100 zero bytes */
    for (int i = 0; i < 100; i++)
        fputc(0, f);
    fclose(f);
    write_text("ws2/arm/meshes/lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n");
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    char cmd[600];
    if (strncmp(root, "/", 1) == 0 && strstr(root, "mpb-test-mesh-")) {
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", root);
        if (system(cmd) != 0)
            return -1;
    }
    return 0;
}

/* The search path: two workspaces, as ROS_PACKAGE_PATH would list them. */
static const char *dirs[2];
static char d1[300], d2[300];

static void set_dirs(void)
{
    path_of(d1, sizeof d1, "ws1");
    path_of(d2, sizeof d2, "ws2");
    dirs[0] = d1;
    dirs[1] = d2;
}

static mpb_mesh *load_ok(const char *uri, const double *scale)
{
    mpb_mesh *m = NULL;
    char err[400];
    int rc = mpb__mesh_create_from_uri(uri, dirs, 2, scale, &m, err, sizeof err);
    if (rc != MPB_OK)
        fail_msg("%s: %s: %s", uri, mpb_err_name(rc), err);
    assert_non_null(m);
    assert_int_equal(mpb__mesh_check(m, NULL, 0), MPB_OK);
    return m;
}

static void expect_box(const mpb_mesh *m, const double shift[3], double eps)
{
    assert_int_equal(m->num_vertices, 8);
    assert_int_equal(m->num_triangles, 12);
    double lo[3], hi[3];
    assert_int_equal(mpb__mesh_bounds(m, lo, hi), MPB_OK);
    for (int k = 0; k < 3; k++) {
        assert_near(lo[k], -H[k] + shift[k], eps);
        assert_near(hi[k], H[k] + shift[k], eps);
    }
}

static void test_formats(void **state)
{
    (void)state;
    set_dirs();
    const double none[3] = { 0, 0, 0 };
    const char *uris[] = { "package://arm/meshes/box.stl",
                           "package://arm/meshes/box_binary.stl",
                           "package://arm/meshes/box.obj" };
    for (int i = 0; i < 3; i++) {
        mpb_mesh *m = load_ok(uris[i], NULL);
        expect_box(m, none, 1e-7);  /* binary STL is float32 */
        mpb__mesh_destroy(m);
    }
    /* COLLADA: centimetres to metres, Z up kept, the node's 10 cm moved */
    const double shift[3] = { 0.1, 0, 0 };
    mpb_mesh *m = load_ok("package://arm/meshes/box.dae", NULL);
    expect_box(m, shift, 1e-6);
    mpb__mesh_destroy(m);
}

static void test_scale_and_copy(void **state)
{
    (void)state;
    set_dirs();
    const double scale[3] = { 2, -1, 0.5 };
    mpb_mesh *m = load_ok("package://arm/meshes/box.stl", scale);
    double lo[3], hi[3];
    mpb__mesh_bounds(m, lo, hi);
    for (int k = 0; k < 3; k++) {
        double s = fabs(scale[k]);
        assert_near(lo[k], -H[k] * s, 1e-12);
        assert_near(hi[k], H[k] * s, 1e-12);
    }
    mpb_mesh *c = mpb__mesh_copy(m);
    assert_non_null(c);
    assert_int_equal(c->num_vertices, m->num_vertices);
    assert_memory_equal(c->vertices, m->vertices, 3 * sizeof(double) * (size_t)m->num_vertices);
    assert_memory_equal(c->triangles, m->triangles, 3 * sizeof(int32_t) * (size_t)m->num_triangles);
    mpb__mesh_destroy(c);
    mpb__mesh_destroy(m);
    mpb__mesh_destroy(NULL);
    assert_null(mpb__mesh_copy(NULL));
    assert_null(mpb__mesh_create(-1, 3));

    const double zero[3] = { 1, 0, 1 };
    char err[300];
    assert_int_equal(mpb__mesh_create_from_uri("package://arm/meshes/box.stl", dirs, 2, zero,
                                              &m, err, sizeof err), MPB_EINVAL);
    assert_null(m);
    assert_non_null(strstr(err, "scale"));
}

static void test_resolve(void **state)
{
    (void)state;
    set_dirs();
    char path[512], want[512], err[300];
    path_of(want, sizeof want, "ws2/arm/meshes/box.stl");

    /* package:// under a workspace listed on the path */
    assert_int_equal(mpb_mesh_resolve("package://arm/meshes/box.stl", dirs, 2,
                                      path, sizeof path, err, sizeof err), MPB_OK);
    assert_string_equal(path, want);
    /* a search directory that is the package itself (trailing slash too) */
    char pkg[320];
    path_of(pkg, sizeof pkg, "ws2/arm/");
    const char *self[1] = { pkg };
    assert_int_equal(mpb_mesh_resolve("package://arm/meshes/box.stl", self, 1,
                                      path, sizeof path, err, sizeof err), MPB_OK);
    assert_non_null(strstr(path, "ws2/arm/meshes/box.stl"));
    /* relative: against each directory in turn */
    assert_int_equal(mpb_mesh_resolve("meshes/box.stl", self, 1, path, sizeof path,
                                      err, sizeof err), MPB_OK);
    assert_non_null(strstr(path, "ws2/arm/meshes/box.stl"));
    assert_int_equal(mpb_mesh_resolve("arm/meshes/box.obj", dirs, 2, path, sizeof path,
                                      err, sizeof err), MPB_OK);
    /* absolute, and file:// */
    assert_int_equal(mpb_mesh_resolve(want, NULL, 0, path, sizeof path, err,
                                      sizeof err), MPB_OK);
    assert_string_equal(path, want);
    char uri[600];
    snprintf(uri, sizeof uri, "file://%s", want);
    assert_int_equal(mpb_mesh_resolve(uri, NULL, 0, path, sizeof path, err,
                                      sizeof err), MPB_OK);
    assert_string_equal(path, want);
    mpb_mesh *m = load_ok(uri, NULL);
    mpb__mesh_destroy(m);

    /* not found: a one-line message naming the URI */
    assert_int_equal(mpb_mesh_resolve("package://arm/meshes/nope.stl", dirs, 2,
                                      path, sizeof path, err, sizeof err),
                     MPB_ENOTFOUND);
    assert_non_null(strstr(err, "package://arm/meshes/nope.stl"));
    assert_null(strchr(err, '\n'));
    assert_int_equal(mpb_mesh_resolve("package://nopkg/meshes/box.stl", dirs, 2,
                                      path, sizeof path, err, sizeof err),
                     MPB_ENOTFOUND);
    assert_int_equal(mpb_mesh_resolve("meshes/box.stl", NULL, 0, path, sizeof path,
                                      err, sizeof err), MPB_ENOTFOUND);
    assert_int_equal(mpb_mesh_resolve("/no/such/file.stl", NULL, 0, path,
                                      sizeof path, err, sizeof err), MPB_ENOTFOUND);
    /* a directory is not a mesh file */
    assert_int_equal(mpb_mesh_resolve("package://arm/meshes", dirs, 2, path,
                                      sizeof path, err, sizeof err), MPB_ENOTFOUND);
    /* malformed and unsupported */
    assert_int_equal(mpb_mesh_resolve("package://arm", dirs, 2, path, sizeof path,
                                      err, sizeof err), MPB_EINVAL);
    assert_int_equal(mpb_mesh_resolve("package:///x.stl", dirs, 2, path, sizeof path,
                                      err, sizeof err), MPB_EINVAL);
    assert_int_equal(mpb_mesh_resolve("", dirs, 2, path, sizeof path, err,
                                      sizeof err), MPB_EINVAL);
    assert_int_equal(mpb_mesh_resolve("http://example.com/box.stl", dirs, 2, path,
                                      sizeof path, err, sizeof err), MPB_EUNSUPPORTED);
    assert_non_null(strstr(err, "http://example.com/box.stl"));
    assert_int_equal(mpb_mesh_resolve("file://relative/box.stl", dirs, 2, path,
                                      sizeof path, err, sizeof err), MPB_EINVAL);
    /* no room for the path */
    char tiny[8];
    assert_int_equal(mpb_mesh_resolve("package://arm/meshes/box.stl", dirs, 2,
                                      tiny, sizeof tiny, err, sizeof err), MPB_EINVAL);
    assert_string_equal(tiny, "");
}

static void test_load_errors(void **state)
{
    (void)state;
    set_dirs();
    mpb_mesh *m = (mpb_mesh *)1;
    char err[400];
    /* missing file */
    assert_int_equal(mpb__mesh_create_from_uri("package://arm/meshes/missing.stl", dirs, 2,
                                              NULL, &m, err, sizeof err), MPB_ENOTFOUND);
    assert_null(m);
    assert_non_null(strstr(err, "missing.stl"));
    /* files assimp cannot read: the message names the file, on one line */
    const char *bad[] = { "broken.dae", "bad_index.obj", "short.stl",
#ifndef __SANITIZE_ADDRESS__
                          /* assimp 5.2 leaks 2.4 kB on a malformed ASCII STL */
                          "garbage.stl",
#endif
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char uri[100], name[100];
        snprintf(uri, sizeof uri, "package://arm/meshes/%s", bad[i]);
        snprintf(name, sizeof name, "ws2/arm/meshes/%s", bad[i]);
        assert_int_equal(mpb__mesh_create_from_uri(uri, dirs, 2, NULL, &m, err, sizeof err),
                         MPB_EPARSE);
        assert_null(m);
        if (!strstr(err, name) || strchr(err, '\n'))
            fail_msg("\"%s\" does not name %s on one line", err, name);
    }
    assert_int_equal(mpb__mesh_create_from_uri("other/readme.txt", dirs, 2, NULL, &m, err,
                                              sizeof err), MPB_EPARSE);
    assert_non_null(strstr(err, "readme.txt"));
    /* lines only: no triangles */
    assert_int_equal(mpb__mesh_create_from_uri("package://arm/meshes/lines.obj", dirs, 2,
                                              NULL, &m, err, sizeof err), MPB_EPARSE);
    assert_non_null(strstr(err, "lines.obj"));
    assert_int_equal(mpb__mesh_create_from_uri("x.stl", dirs, 2, NULL, NULL, err, sizeof err),
                     MPB_EINVAL);
    /* no error buffer is fine */
    assert_int_equal(mpb__mesh_create_from_uri("package://arm/meshes/broken.dae", dirs, 2,
                                              NULL, &m, NULL, 0), MPB_EPARSE);
}

static void test_check_and_bounds(void **state)
{
    (void)state;
    char err[200];
    mpb_mesh *m = mpb__mesh_create(3, 1);
    assert_non_null(m);
    const double v[9] = { 0, 0, 0, 1, 0, 0, 0, 2, -1 };
    memcpy(m->vertices, v, sizeof v);
    m->triangles[0] = 0;
    m->triangles[1] = 1;
    m->triangles[2] = 2;
    assert_int_equal(mpb__mesh_check(m, err, sizeof err), MPB_OK);
    double lo[3], hi[3];
    assert_int_equal(mpb__mesh_bounds(m, lo, hi), MPB_OK);
    assert_near(lo[2], -1, 0);
    assert_near(hi[1], 2, 0);
    m->triangles[1] = 3;
    assert_int_equal(mpb__mesh_check(m, err, sizeof err), MPB_EINVAL);
    assert_non_null(strstr(err, "out of range"));
    m->triangles[1] = 1;
    m->vertices[4] = NAN;
    assert_int_equal(mpb__mesh_check(m, err, sizeof err), MPB_EINVAL);
    assert_non_null(strstr(err, "vertex 1"));
    mpb__mesh_destroy(m);
    m = mpb__mesh_create(0, 0);
    assert_int_equal(mpb__mesh_check(m, err, sizeof err), MPB_EINVAL);
    assert_int_equal(mpb__mesh_bounds(m, lo, hi), MPB_EINVAL);
    mpb__mesh_destroy(m);
    assert_int_equal(mpb__mesh_check(NULL, err, sizeof err), MPB_EINVAL);
}

/* A loaded STL box in the collision world behaves as the box it is. */
static void test_loaded_mesh_collides(void **state)
{
    (void)state;
    set_dirs();
    mpb_mesh *m = load_ok("package://arm/meshes/box.obj", NULL);
    mpb_collision *c = NULL;
    assert_int_equal(mpb_collision_create(&c), MPB_OK);
    mpb_geometry g = { .type = MPB_SHAPE_MESH, .mesh = m };
    mpb_pose p;
    mpb_pose_identity(&p);
    assert_int_equal(mpb_collision_add_static(c, 0, &g, &p), MPB_OK);
    mpb__mesh_destroy(m);           /* the world keeps its own copy */
    mpb_geometry s = { .type = MPB_SHAPE_SPHERE, .dims = { 0.1 } };
    assert_int_equal(mpb_collision_add_movable(c, 0, &s, NULL), MPB_OK);
    p.t[0] = H[0] + 0.3;        /* 0.2 from the x+ face */
    assert_int_equal(mpb_collision_set_pose(c, 0, &p), MPB_OK);
    mpb_collision_distance_result r;
    assert_int_equal(mpb_collision_distance(c, 1, &r), MPB_OK);
    assert_near(r.distance, 0.2, 1e-9);
    assert_near(r.point_static[0], H[0], 1e-9);
    p.t[0] = H[0] + 0.05;
    assert_int_equal(mpb_collision_set_pose(c, 0, &p), MPB_OK);
    assert_int_equal(mpb_collision_check(c, NULL, NULL), 1);
    mpb_collision_destroy(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_formats),
        cmocka_unit_test(test_scale_and_copy),
        cmocka_unit_test(test_resolve),
        cmocka_unit_test(test_load_errors),
        cmocka_unit_test(test_check_and_bounds),
        cmocka_unit_test(test_loaded_mesh_collides),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
