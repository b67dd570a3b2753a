/*
 * test_mesh_cache.c - worlds share what is the same between them
 * (mesh_cache.h): a robot's mesh file is read by assimp once and its BVH
 * model built once while any world holds them, and both are freed with
 * the last world; a file of the same name in another folder, the same file
 * at another scale, and a file changed since it was read are other meshes.
 * Worlds opened from several threads at once share one mesh too.
 *
 * The robot is one revolute link "arm" whose collision shape is a
 * tetrahedron (an OBJ file written here) of size s: vertices (0,0,0),
 * (s,0,0), (0,s,0), (0,0,s).
 */
#include <fcntl.h>
#include <math.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "geometry/mesh_cache.h"
#include "model/world_provider.h"
#include "geometry/mesh.h"

static char dir[256];
static const char *const joints[] = {"j"};

static void write_tetra(const char *path, double s)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fprintf(f, "v 0 0 0\nv %g 0 0\nv 0 %g 0\nv 0 0 %g\n"
               "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n", s, s, s);
    assert_int_equal(fclose(f), 0);
}

/* A URDF text whose link "arm" has the mesh filename at scale (NULL: none),
 * twice when twice (two shapes of one file: one mesh, one BVH model). */
static char *robot_text(const char *filename, const char *scale, int twice)
{
    static const char fmt[] =
        "<robot name=\"tetra_arm\"><link name=\"base_link\"/>"
        "<link name=\"arm\">%s%s</link>"
        "<joint name=\"j\" type=\"revolute\"><parent link=\"base_link\"/>"
        "<child link=\"arm\"/><axis xyz=\"0 0 1\"/>"
        "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>"
        "</robot>\n";
    char shape[1024];
    snprintf(shape, sizeof shape, "<collision><origin xyz=\"0.5 0 0\"/><geometry>"
             "<mesh filename=\"%s\"%s%s%s/></geometry></collision>", filename,
             scale ? " scale=\"" : "", scale ? scale : "", scale ? "\"" : "");
    size_t n = sizeof fmt + 2 * strlen(shape);
    char *text = malloc(n);
    assert_non_null(text);
    snprintf(text, n, fmt, shape, twice ? shape : "");
    return text;
}

static mpb_world *open_text(const char *text)
{
    mpb_world *w = NULL;
    char err[512] = "";
    int rc = mpb_world_open_group("urdf", text, "moveit-scene", "(empty)\n.\n",
                                  joints, 1, &w, err, sizeof err);
    if (rc != MPB_OK)
        fail_msg("world: %s", err);
    return w;
}

static mpb_world *open_mesh(const char *filename, const char *scale)
{
    char *text = robot_text(filename, scale, 0);
    mpb_world *w = open_text(text);
    free(text);
    return w;
}

/* The world's first robot mesh, and how far it reaches along x. */
static const mpb_mesh *mesh_of(mpb_world *w)
{
    mpb__urdf_model m;
    assert_int_equal(mpb__urdf_get_model(w, &m), MPB_OK);
    assert_true(m.num_meshes >= 1);
    return m.meshes[0];
}

static double reach_of(mpb_world *w)
{
    double lo[3], hi[3];
    assert_int_equal(mpb__mesh_bounds(mesh_of(w), lo, hi), MPB_OK);
    return hi[0];
}

static void path_in(char *out, size_t len, const char *sub)
{
    snprintf(out, len, "%s/%s", dir, sub);
}

static int setup(void **state)
{
    (void)state;
    snprintf(dir, sizeof dir, "/tmp/mpb-mesh-cache-XXXXXX");
    if (!mkdtemp(dir))
        return -1;
    char p[512];
    const char *sub[] = {"a", "a/pkg", "b", "b/pkg"};
    for (int i = 0; i < 4; i++) {
        path_in(p, sizeof p, sub[i]);
        if (mkdir(p, 0755) != 0)
            return -1;
    }
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    return system(cmd) == 0 ? 0 : -1;
}

static void two_worlds_share_one_mesh_and_one_bvh(void **state)
{
    (void)state;
    char file[512];
    path_in(file, sizeof file, "a/pkg/shared.obj");
    write_tetra(file, 0.1);
    long reads = mpb__mesh_cache_reads(), builds = mpb__bvh_builds();
    assert_int_equal(mpb__mesh_cache_live(), 0);
    assert_int_equal(mpb__bvh_live(), 0);

    char *text = robot_text(file, NULL, 1);
    mpb_world *w1 = open_text(text);
    mpb_world *w2 = open_text(text);
    free(text);
    /* Two worlds, two shapes each: one read, one model. */
    assert_int_equal(mpb__mesh_cache_reads(), reads + 1);
    assert_int_equal(mpb__bvh_builds(), builds + 1);
    assert_int_equal(mpb__mesh_cache_live(), 1);
    assert_int_equal(mpb__bvh_live(), 1);
    assert_ptr_equal(mesh_of(w1), mesh_of(w2));

    /* Both still collide where the tetrahedron is, each on its own. */
    double q[1] = {0};
    assert_int_equal(mpb_world_in_collision(w1, q), 0);
    mpb_world_close(w1);
    assert_int_equal(mpb_world_in_collision(w2, q), 0);
    assert_int_equal(mpb__mesh_cache_live(), 1);
    assert_int_equal(mpb__bvh_live(), 1);
    mpb_world_close(w2);
    /* Freed with the last world. */
    assert_int_equal(mpb__mesh_cache_live(), 0);
    assert_int_equal(mpb__bvh_live(), 0);
}

static void a_changed_file_is_read_again(void **state)
{
    (void)state;
    char file[512];
    path_in(file, sizeof file, "a/pkg/changing.obj");
    write_tetra(file, 0.1);
    long reads = mpb__mesh_cache_reads(), builds = mpb__bvh_builds();
    mpb_world *w1 = open_mesh(file, NULL);
    assert_true(fabs(reach_of(w1) - 0.1) < 1e-6);

    /* The same size of file, other contents, a later modification time
     * (set: the file system's clock may not have ticked yet). */
    struct stat before;
    assert_int_equal(stat(file, &before), 0);
    write_tetra(file, 0.3);
    struct timespec times[2] = {before.st_atim, before.st_mtim};
    times[1].tv_sec += 1;
    assert_int_equal(utimensat(AT_FDCWD, file, times, 0), 0);
    struct stat after;
    assert_int_equal(stat(file, &after), 0);
    assert_int_equal(after.st_size, before.st_size);
    mpb_world *w2 = open_mesh(file, NULL);
    assert_int_equal(mpb__mesh_cache_reads(), reads + 2);
    assert_int_equal(mpb__bvh_builds(), builds + 2);
    assert_true(fabs(reach_of(w2) - 0.3) < 1e-6);
    assert_true(fabs(reach_of(w1) - 0.1) < 1e-6);      /* the old one, still held */
    assert_int_equal(mpb__mesh_cache_live(), 2);

    /* A third world gets the new file's mesh, not read again. */
    mpb_world *w3 = open_mesh(file, NULL);
    assert_ptr_equal(mesh_of(w3), mesh_of(w2));
    assert_int_equal(mpb__mesh_cache_reads(), reads + 2);
    mpb_world_close(w1);
    mpb_world_close(w2);
    mpb_world_close(w3);
    assert_int_equal(mpb__mesh_cache_live(), 0);
    assert_int_equal(mpb__bvh_live(), 0);
}

static void same_name_elsewhere_or_scaled_is_another_mesh(void **state)
{
    (void)state;
    char fa[512], fb[512], root_a[512], root_b[512];
    path_in(fa, sizeof fa, "a/pkg/link.obj");
    path_in(fb, sizeof fb, "b/pkg/link.obj");
    path_in(root_a, sizeof root_a, "a");
    path_in(root_b, sizeof root_b, "b");
    write_tetra(fa, 0.1);
    write_tetra(fb, 0.2);
    long reads = mpb__mesh_cache_reads();

    /* One URI, resolved through MPB_MESH_PATH to two folders. */
    setenv("MPB_MESH_PATH", root_a, 1);
    mpb_world *wa = open_mesh("package://pkg/link.obj", NULL);
    setenv("MPB_MESH_PATH", root_b, 1);
    mpb_world *wb = open_mesh("package://pkg/link.obj", NULL);
    unsetenv("MPB_MESH_PATH");
    assert_int_equal(mpb__mesh_cache_reads(), reads + 2);
    assert_true(fabs(reach_of(wa) - 0.1) < 1e-6);
    assert_true(fabs(reach_of(wb) - 0.2) < 1e-6);

    /* The same file at another scale. */
    mpb_world *ws = open_mesh(fa, "2 1 1");
    assert_int_equal(mpb__mesh_cache_reads(), reads + 3);
    assert_true(fabs(reach_of(ws) - 0.2) < 1e-6);
    assert_true(fabs(reach_of(wa) - 0.1) < 1e-6);
    /* The same file by its path: the package one's mesh. */
    mpb_world *wp = open_mesh(fa, NULL);
    assert_int_equal(mpb__mesh_cache_reads(), reads + 3);
    assert_ptr_equal(mesh_of(wp), mesh_of(wa));
    /* Scaled 2 1 1 and the 0.2 file differ in y and z only: two models. */
    assert_int_equal(mpb__bvh_live(), 3);
    mpb_world_close(wa);
    mpb_world_close(wb);
    mpb_world_close(ws);
    mpb_world_close(wp);
    assert_int_equal(mpb__mesh_cache_live(), 0);
}

#define THREADS 4
#define PER_THREAD 6

struct opener {
    const char *text;
    mpb_world  *worlds[PER_THREAD];
};

/* A robot without an SRDF has its matrix made again when a held value
 * changes (world_urdf.c, ensure_acm()), and its collision world with it:
 * the meshes go back to the cache and are taken again, never freed under
 * it. An arm with a mesh, and a block on the passive joint "slide". */
static void a_matrix_made_again_gives_meshes_back(void **state)
{
    (void)state;
    char file[512];
    path_in(file, sizeof file, "a/pkg/held.obj");
    write_tetra(file, 0.1);
    char text[2048];
    snprintf(text, sizeof text,
        "<robot name=\"held_arm\"><link name=\"base_link\"/>"
        "<link name=\"arm\"><collision><origin xyz=\"0.5 0 0\"/><geometry>"
        "<mesh filename=\"%s\"/></geometry></collision></link>"
        "<link name=\"block\"><collision><origin xyz=\"0.5 0 -1\"/><geometry>"
        "<box size=\"0.2 0.2 0.2\"/></geometry></collision></link>"
        "<joint name=\"j\" type=\"revolute\"><parent link=\"base_link\"/>"
        "<child link=\"arm\"/><axis xyz=\"0 0 1\"/>"
        "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>"
        "<joint name=\"slide\" type=\"prismatic\"><parent link=\"base_link\"/>"
        "<child link=\"block\"/><axis xyz=\"0 0 1\"/>"
        "<limit lower=\"0\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>"
        "</robot>\n", file);
    static const char *const slide[] = {"slide"};
    long reads = mpb__mesh_cache_reads();
    mpb_world *w = open_text(text);
    double q[1] = {0};
    assert_int_equal(mpb_world_in_collision(w, q), 0);
    char err[256];
    for (int i = 1; i <= 3; i++) {
        double at = 0.25 * i;
        assert_int_equal(mpb_world_hold(w, slide, &at, 1, err, sizeof err),
                         MPB_OK);
        assert_int_equal(mpb_world_in_collision(w, q), 0);
        /* One mesh held, read once: the rebuild took it from the cache. */
        assert_int_equal(mpb__mesh_cache_live(), 1);
        assert_int_equal(mpb__bvh_live(), 1);
        assert_int_equal(mpb__mesh_cache_reads(), reads + 1);
    }
    mpb_world_close(w);
    assert_int_equal(mpb__mesh_cache_live(), 0);
    assert_int_equal(mpb__bvh_live(), 0);
}

static void *open_many(void *arg)
{
    struct opener *o = arg;
    for (int i = 0; i < PER_THREAD; i++) {
        char err[256];
        if (mpb_world_open_group("urdf", o->text, "moveit-scene", "(empty)\n.\n",
                                 joints, 1, &o->worlds[i], err, sizeof err) != MPB_OK)
            o->worlds[i] = NULL;
    }
    return NULL;
}

static void worlds_opened_in_threads_share_too(void **state)
{
    (void)state;
    char file[512];
    path_in(file, sizeof file, "b/pkg/threads.obj");
    write_tetra(file, 0.1);
    char *text = robot_text(file, NULL, 1);
    long reads = mpb__mesh_cache_reads();
    struct opener o[THREADS];
    pthread_t t[THREADS];
    for (int i = 0; i < THREADS; i++) {
        o[i].text = text;
        assert_int_equal(pthread_create(&t[i], NULL, open_many, &o[i]), 0);
    }
    for (int i = 0; i < THREADS; i++)
        assert_int_equal(pthread_join(t[i], NULL), 0);
    /* Threads that missed the cache together may each have read the file
     * once; all but one copy were dropped. */
    long read = mpb__mesh_cache_reads() - reads;
    assert_true(read >= 1 && read <= THREADS);
    assert_int_equal(mpb__mesh_cache_live(), 1);
    const mpb_mesh *first = NULL;
    double q[1] = {0};
    for (int i = 0; i < THREADS; i++)
        for (int k = 0; k < PER_THREAD; k++) {
            assert_non_null(o[i].worlds[k]);
            if (!first)
                first = mesh_of(o[i].worlds[k]);
            assert_ptr_equal(mesh_of(o[i].worlds[k]), first);
            assert_int_equal(mpb_world_in_collision(o[i].worlds[k], q), 0);
        }
    for (int i = 0; i < THREADS; i++)
        for (int k = 0; k < PER_THREAD; k++)
            mpb_world_close(o[i].worlds[k]);
    free(text);
    assert_int_equal(mpb__mesh_cache_live(), 0);
    assert_int_equal(mpb__bvh_live(), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(two_worlds_share_one_mesh_and_one_bvh),
        cmocka_unit_test(a_changed_file_is_read_again),
        cmocka_unit_test(same_name_elsewhere_or_scaled_is_another_mesh),
        cmocka_unit_test(worlds_opened_in_threads_share_too),
        cmocka_unit_test(a_matrix_made_again_gives_meshes_back),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
