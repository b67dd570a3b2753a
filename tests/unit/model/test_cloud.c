/*
 * test_cloud.c - point clouds (cloud.h) in PLY and PCD, ASCII and
 * binary, as octrees and spheres in scenes; and bad input of every
 * format (truncated, corrupt, NaN, resolution 0, absurd counts), each
 * refused with one line naming the file and the place.
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
#include "mpbench/cloud.h"
#include "mpbench/octree.h"
#include "mpbench/scene.h"

#include "test_octree_box.h"

static char *dir;
static char err[512];

static int setup(void **state)
{
    (void)state;
    dir = test_tmpdir();
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    free(dir);
    return system(cmd) == 0 ? 0 : -1;
}

static const char *file(const char *name, const void *b, size_t n)
{
    static char path[256];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    test_write_bytes(path, b, n);
    return path;
}

static const char *text_file(const char *name, const char *t)
{
    return file(name, t, strlen(t));
}

/* err is "<dir>/<name>: <what>" */
static void assert_err(const char *name, const char *what)
{
    char want[600];
    snprintf(want, sizeof want, "%s/%s: %s", dir, name, what);
    assert_string_equal(err, want);
}

static const double PTS[3][3] = {{0.001, 0.002, 0.003}, {0.5, -0.25, 1.0}, {0.504, -0.246, 1.009}};

static void put_be(unsigned char *p, const void *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        p[i] = ((const unsigned char *)v)[n - 1 - i];
}

/* The same three points in five files: all give the same two cells at 1 cm. */
static void test_formats_agree(void **state)
{
    (void)state;
    char t[1024];
    int h;
    const char *paths[5];
    snprintf(t, sizeof t, "ply\nformat ascii 1.0\ncomment c\nelement vertex 3\n"
             "property float x\nproperty float y\nproperty float z\nproperty uchar red\n"
             "element face 0\nproperty list uchar int vertex_indices\nend_header\n"
             "%g %g %g 255\n%g %g %g 0\n%g %g %g 7\n", PTS[0][0], PTS[0][1], PTS[0][2],
             PTS[1][0], PTS[1][1], PTS[1][2], PTS[2][0], PTS[2][1], PTS[2][2]);
    paths[0] = strdup(text_file("a.ply", t));
    unsigned char b[1024];
    for (int be = 0; be < 2; be++) {
        h = snprintf((char *)b, sizeof b, "ply\nformat %s 1.0\nelement vertex 3\n"
                     "property double x\nproperty uchar i\nproperty double y\n"
                     "property double z\nend_header\n",
                     be ? "binary_big_endian" : "binary_little_endian");
        size_t at = (size_t)h;
        for (int i = 0; i < 3; i++) {
            for (int k = 0; k < 3; k++) {
                if (be)
                    put_be(b + at, &PTS[i][k], 8);
                else
                    memcpy(b + at, &PTS[i][k], 8);
                at += 8;
                if (k == 0)
                    b[at++] = 9;
            }
        }
        paths[1 + be] = strdup(file(be ? "be.ply" : "le.ply", b, at));
    }
    snprintf(t, sizeof t, "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z rgb\nSIZE 4 4 4 4\n"
             "TYPE F F F F\nCOUNT 1 1 1 1\nWIDTH 3\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\n"
             "POINTS 3\nDATA ascii\n%g %g %g 0\n%g %g %g 0\n%g %g %g 0\n", PTS[0][0],
             PTS[0][1], PTS[0][2], PTS[1][0], PTS[1][1], PTS[1][2], PTS[2][0], PTS[2][1],
             PTS[2][2]);
    paths[3] = strdup(text_file("a.pcd", t));
    h = snprintf((char *)b, sizeof b, "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\n"
                 "TYPE F F F\nCOUNT 1 1 1\nWIDTH 3\nHEIGHT 1\nPOINTS 3\nDATA binary\n");
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++) {
            float f = (float)PTS[i][k];
            memcpy(b + h + 12 * i + 4 * k, &f, 4);
        }
    paths[4] = strdup(file("b.pcd", b, (size_t)h + 36));
    for (int i = 0; i < 5; i++) {
        mpb_octree *o;
        if (mpb_cloud_load_octree(paths[i], 0.01, &o, err, sizeof err) != MPB_OK)
            fail_msg("%s", err);
        assert_int_equal(mpb_octree_num_cells(o), 2);
        int found = 0;
        for (int j = 0; j < 2; j++) {
            double c[3], side;
            assert_int_equal(mpb_octree_cell(o, j, c, &side), MPB_OK);
            found += fabs(c[0] - 0.005) < 1e-9 && fabs(c[1] - 0.005) < 1e-9 &&
                     fabs(c[2] - 0.005) < 1e-9;
            found += fabs(c[0] - 0.505) < 1e-9 && fabs(c[1] + 0.245) < 1e-9 &&
                     fabs(c[2] - 1.005) < 1e-9;
        }
        assert_int_equal(found, 2);
        mpb_octree_destroy(o);
        double *xyz;
        long n;
        assert_int_equal(mpb_cloud_load_points(paths[i], 10, &xyz, &n, err, sizeof err),
                         MPB_OK);
        assert_int_equal(n, 3);
        assert_true(fabs(xyz[3] - 0.5) < 1e-6 && fabs(xyz[8] - 1.009) < 1e-6);
        free(xyz);
        free((char *)paths[i]);
    }
}

/* A scene names a cloud: as voxels an octree object, as a radius spheres. */
static void test_scene_clouds(void **state)
{
    (void)state;
    char t[600];
    snprintf(t, sizeof t, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
             "property float y\nproperty float z\nend_header\n%g %g %g\n%g %g %g\n"
             "%g %g %g\n", PTS[0][0], PTS[0][1], PTS[0][2], PTS[1][0], PTS[1][1],
             PTS[1][2], PTS[2][0], PTS[2][1], PTS[2][2]);
    text_file("c.ply", t);
    const char *sc = text_file("c.scene", "c\n.\ncloud vox file c.ply voxel 0.01\n"
                               "cloud balls file c.ply radius 0.02 0 0 1 0 0 0 1\n");
    mpb_scene *s;
    if (mpb_scene_open(sc, &s, err, sizeof err) != MPB_OK)
        fail_msg("%s", err);
    assert_int_equal(mpb_scene_num_objects(s), 2);
    const mpb_scene_object *v = mpb_scene_object_at(s, 0), *b = mpb_scene_object_at(s, 1);
    assert_int_equal(v->kind, MPB_SCENE_OCTREE);
    assert_int_equal(v->num_shapes, 2);
    assert_int_equal(b->kind, MPB_SCENE_SPHERES);
    assert_int_equal(b->num_shapes, 3);
    assert_true(b->shapes[1].geometry.dims[0] == 0.02 && b->pose.t[2] == 1.0);
    mpb_scene_close(s);
}

typedef struct bad {
    const char *name;
    const char *head;       /* the file's text part */
    size_t      zeros;      /* then this many bytes of value `fill` */
    int         fill;
    int         rc;
    const char *what;       /* the message after "<path>: " */
} bad;

static void test_bad_clouds(void **state)
{
    (void)state;
    static const bad B[] = {
        {"trunc.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 10\n"
         "property float x\nproperty float y\nproperty float z\nend_header\n", 100, 0,
         MPB_EPARSE, "line 7: the header says 10 vertex of 12 bytes, but the file holds "
         "100 bytes of data: truncated or a wrong count"},
        {"billion.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\n"
         "property float x\nproperty float y\nproperty float z\nend_header\n", 12, 0,
         MPB_EPARSE, "line 7: more than 100000000 points"},
        {"many.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 50000000\n"
         "property float x\nproperty float y\nproperty float z\nend_header\n", 12, 0,
         MPB_EPARSE, "line 7: the header says 50000000 vertex of 12 bytes, but the file "
         "holds 12 bytes of data: truncated or a wrong count"},
        {"nan.ply", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\n"
         "property float y\nproperty float z\nend_header\n0 0 0\n1 nan 2\n", 0, 0,
         MPB_EPARSE, "vertex 1 (line 9): y is not finite"},
        {"nanbin.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1\n"
         "property float x\nproperty float y\nproperty float z\nend_header\n", 12, 0xff,
         MPB_EPARSE, "vertex 0 (data byte 115): x is not finite"},
        {"cut.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
         "property float y\nproperty float z\nend_header\n0 0 0\n1 1 1\n", 0, 0,
         MPB_EPARSE, "line 10: the file ends at vertex 2 of 3: truncated"},
        {"word.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
         "property float y\nproperty float z\nend_header\n0 zero 0\n", 0, 0, MPB_EPARSE,
         "vertex 0 (line 8): y is not a number: 'zero'"},
        {"noxyz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
         "end_header\n0\n", 0, 0, MPB_EPARSE,
         "line 5: no 'vertex' element with x, y and z"},
        {"head.ply", "ply\nformat ascii 1.0\nelement vertex 1\n", 0, 0, MPB_EPARSE,
         "line 4: the header ends before 'end_header'"},
        {"nan.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\n"
         "HEIGHT 1\nPOINTS 2\nDATA ascii\n0 0 0\nnan nan nan\n", 0, 0, MPB_EPARSE,
         "point 1 (line 10): x is not finite"},
        {"huge.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 90000000\n"
         "HEIGHT 1\nPOINTS 90000000\nDATA binary\n", 24, 0, MPB_EPARSE,
         "line 8: the header says 90000000 point of 12 bytes, but the file holds 24 bytes "
         "of data: truncated or a wrong count"},
        {"comp.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nPOINTS 1\n"
         "DATA binary_compressed\n", 8, 0, MPB_EUNSUPPORTED,
         "line 6: DATA binary_compressed is not supported (save it as binary or ascii)"},
        {"type.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F X F\n", 0, 0, MPB_EPARSE,
         "line 3: TYPE 'X' is none of I U F"},
    };
    for (size_t i = 0; i < sizeof B / sizeof B[0]; i++) {
        size_t h = strlen(B[i].head);
        unsigned char *b = malloc(h + B[i].zeros + 1);
        memcpy(b, B[i].head, h);
        memset(b + h, B[i].fill, B[i].zeros);
        file(B[i].name, b, h + B[i].zeros);
        free(b);
        char path[300];
        snprintf(path, sizeof path, "%s/%s", dir, B[i].name);
        mpb_octree *o = NULL;
        int rc = mpb_cloud_load_octree(path, 0.01, &o, err, sizeof err);
        if (rc != B[i].rc)
            fail_msg("%s: %d (%s)", B[i].name, rc, err);
        assert_null(o);
        assert_err(B[i].name, B[i].what);
        assert_null(strchr(err, '\n'));
    }
    /* a voxel of 0 */
    char path[300];
    snprintf(path, sizeof path, "%s/nan.ply", dir);
    mpb_octree *o = NULL;
    assert_int_equal(mpb_cloud_load_octree(path, 0, &o, err, sizeof err), MPB_EINVAL);
    assert_err("nan.ply", "voxel size 0 is outside 0.0001 .. 1 m");
}

/* A .bt's bytes with its data part changed by f. */
static size_t box_bt(unsigned char **b)
{
    mpb_octree *o = test_box_octree();
    size_t n;
    assert_int_equal(mpb_octree_write(o, 1, b, &n), MPB_OK);
    mpb_octree_destroy(o);
    return n;
}

static void test_bad_octrees(void **state)
{
    (void)state;
    unsigned char *b;
    size_t n = box_bt(&b);
    const char *data = strstr((const char *)b, "data\n") + 5;
    size_t head = (size_t)(data - (const char *)b);
    mpb_octree *o = NULL;
    /* truncated */
    const char *p = file("cut.bt", b, n - 10);
    assert_int_equal(mpb_octree_create_from_file(p, &o, err, sizeof err), MPB_EPARSE);
    assert_null(o);
    char want[200];
    snprintf(want, sizeof want, "data byte %zu: truncated: the tree needs more bytes",
             n - 10 - head);
    assert_err("cut.bt", want);
    /* corrupt: every child an inner node, deeper than 16 levels */
    unsigned char *c = malloc(n);
    memcpy(c, b, n);
    memset(c + head, 0xff, n - head);
    p = file("deep.bt", c, n);
    assert_int_equal(mpb_octree_create_from_file(p, &o, err, sizeof err), MPB_EPARSE);
    assert_err("deep.bt", "data byte 30: corrupt: a leaf cell has children (deeper "
               "than OctoMap's 16 levels)");
    /* trailing bytes */
    memcpy(c, b, n);
    p = file("tail.bt", c, n);     /* the good file, then one byte more */
    FILE *f = fopen(p, "ab");
    fputc(0, f);
    fclose(f);
    assert_int_equal(mpb_octree_create_from_file(p, &o, err, sizeof err), MPB_EPARSE);
    snprintf(want, sizeof want, "data byte %zu: corrupt: 1 bytes after the tree", n - head);
    assert_err("tail.bt", want);
    free(c);
    /* resolution 0 in the header; no header; another tree type */
    p = text_file("r0.bt", "# Octomap OcTree binary file\nid OcTree\nsize 1\nres 0\ndata\n");
    assert_int_equal(mpb_octree_create_from_file(p, &o, err, sizeof err), MPB_EPARSE);
    assert_err("r0.bt", "line 4: resolution 0 is outside 0.0001 .. 1 m");
    p = text_file("x.bt", "hello\n");
    assert_int_equal(mpb_octree_create_from_file(p, &o, err, sizeof err), MPB_EPARSE);
    assert_err("x.bt", "line 1: not an OctoMap file (expected '# Octomap OcTree binary "
               "file' or '# Octomap OcTree file')");
    p = text_file("color.ot", "# Octomap OcTree file\nid ColorOcTree\nres 0.1\ndata\n");
    assert_int_equal(mpb_octree_create_from_file(p, &o, err, sizeof err), MPB_EUNSUPPORTED);
    assert_err("color.ot", "line 2: tree type 'ColorOcTree' is not supported (only OcTree)");
    /* .ot: a NaN log-odds, cut short */
    unsigned char ot[64];
    int h = snprintf((char *)ot, sizeof ot, "# Octomap OcTree file\nres 0.1\ndata\n");
    float nanf_ = NAN;
    memcpy(ot + h, &nanf_, 4);
    ot[h + 4] = 0;
    p = file("nan.ot", ot, (size_t)h + 5);
    assert_int_equal(mpb_octree_create_from_file(p, &o, err, sizeof err), MPB_EPARSE);
    assert_err("nan.ot", "data byte 0: corrupt: a log-odds value is not finite");
    float one = 1;
    memcpy(ot + h, &one, 4);
    ot[h + 4] = 0x01;
    p = file("cut.ot", ot, (size_t)h + 7);
    assert_int_equal(mpb_octree_create_from_file(p, &o, err, sizeof err), MPB_EPARSE);
    assert_err("cut.ot", "data byte 5: truncated: the tree needs more bytes");
    free(b);
}

/* The scene's own octree and spheres lines, bad: named by scene line. */
static void test_bad_scene_lines(void **state)
{
    (void)state;
    static const struct { const char *text, *what; } B[] = {
        {"s\n.\noctree m binary 0 4 0 0 0 0 0 0 1\nAAAAAA==\n",
         "scene line 3: octree resolution 0 is outside 0.0001 .. 1 m"},
        {"s\n.\noctree m binary 0.01 1000000000 0 0 0 0 0 0 1\nAAAA\n",
         "scene line 3: octree of 1000000000 bytes: more than the rest of the text holds"},
        {"s\n.\noctree m binary 0.01 4 0 0 0 0 0 0 1\nAA!A\nAAAA\n",
         "scene line 5: octree 'm': bad base64 at character 2 of its data"},
        {"s\n.\noctree m binary 0.01 2 0 0 0 0 0 0 1\nAMA=\n",
         "scene line 3: octree 'm': data byte 2: truncated: the tree needs more bytes"},
        {"s\n.\noctree m binary 0.01 2 0 0 0 0 0 0 1\nAM    \n",
         "scene line 4: octree 'm': the text ends after 2 of its 4 base64 characters"},
        {"s\n.\nspheres c 0.01 900000 0 0 0 0 0 0 1\n0 0 0\n",
         "scene line 3: spheres: 900000 points, more than 200000 (give the cloud a voxel "
         "size instead)"},
        {"s\n.\nspheres c 0.01 2 0 0 0 0 0 0 1\n0 0 0\n1 nan 0\n",
         "scene line 5: spheres point 1 needs <x> <y> <z>, found 'nan'"},
        {"s\n.\ncloud c file x.ply voxel 0.01\n",
         "scene line 3: cloud 'c' names a file: a scene file's cloud is read by "
         "mpb_scene_open() or mpb_scene_resolve()"},
    };
    for (size_t i = 0; i < sizeof B / sizeof B[0]; i++) {
        mpb_scene *s = NULL;
        assert_int_equal(mpb_scene_open_text(B[i].text, &s, err, sizeof err), MPB_EPARSE);
        assert_null(s);
        assert_string_equal(err, B[i].what);
    }
    /* a scene file naming a missing or bad file says both places */
    const char *sc = text_file("m.scene", "m\n.\n\noctree map file none.bt\n");
    mpb_scene *s = NULL;
    assert_int_equal(mpb_scene_open(sc, &s, err, sizeof err), MPB_EIO);
    assert_non_null(strstr(err, "m.scene: scene line 4: "));
    assert_non_null(strstr(err, "none.bt: cannot open"));
    text_file("r0.bt", "# Octomap OcTree binary file\nres 0\ndata\n");
    sc = text_file("r.scene", "r\n.\noctree map file r0.bt\n");
    assert_int_equal(mpb_scene_open(sc, &s, err, sizeof err), MPB_EPARSE);
    char want[400];
    snprintf(want, sizeof want, "%s/r.scene: scene line 3: %s/r0.bt: line 2: resolution 0 "
             "is outside 0.0001 .. 1 m", dir, dir);
    assert_string_equal(err, want);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_formats_agree),
        cmocka_unit_test(test_scene_clouds),
        cmocka_unit_test(test_bad_clouds),
        cmocka_unit_test(test_bad_octrees),
        cmocka_unit_test(test_bad_scene_lines),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
