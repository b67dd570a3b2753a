/*
 * test_mesh_disk.c - meshes kept in the cache on disk (mesh_disk.c,
 * mesh_cache.h): a mesh file read by assimp once is read from the disk by
 * the next load the process's own cache does not hold; a file changed by
 * one byte, or read at another scale, is read by assimp again and gives
 * its own mesh, never the stored one; a corrupt cache file, and a
 * well-formed one whose mesh is broken, read as misses; without a usable
 * cache directory meshes still load.
 *
 * The mesh is a tetrahedron (an OBJ file written here) of size s:
 * vertices (0,0,0), (s,0,0), (0,s,0), (0,0,s). The cache is a directory
 * of the test's own (MPB_CACHE_DIR).
 */
#include <dirent.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "geometry/mesh_cache.h"
#include "geometry/mesh.h"

static char dir[256], cache_dir[300], mesh_path[300];

static void write_tetra(const char *path, double s)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fprintf(f, "v 0 0 0\nv %g 0 0\nv 0 %g 0\nv 0 0 %g\n"
               "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n", s, s, s);
    assert_int_equal(fclose(f), 0);
}

/* How far the mesh at mesh_path, loaded at scale (1 1 1 when k is 1),
 * reaches along x; the mesh is released before returning. */
static double reach(double k)
{
    const double scale[3] = {k, k, k};
    const mpb_mesh *m = NULL;
    char err[512];
    if (mpb__mesh_load_shared(mesh_path, NULL, 0, scale, &m, err, sizeof err) != MPB_OK)
        fail_msg("load: %s", err);
    double lo[3], hi[3];
    assert_int_equal(mpb__mesh_bounds(m, lo, hi), MPB_OK);
    assert_int_equal(m->num_triangles, 4);
    mpb__mesh_release(m);
    assert_int_equal(mpb__mesh_cache_live(), 0);
    return hi[0];
}

/* The one file in the cache's mesh directory, into out. */
static void the_cache_file(char *out, size_t n)
{
    char sub[400];
    snprintf(sub, sizeof sub, "%s/mesh", cache_dir);
    DIR *d = opendir(sub);
    assert_non_null(d);
    int found = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        if (e->d_name[0] != '.') {
            snprintf(out, n, "%s/%s", sub, e->d_name);
            found++;
        }
    closedir(d);
    assert_int_equal(found, 1);
}

static void empty_the_cache(void)
{
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf '%s/mesh'", cache_dir);
    assert_int_equal(system(cmd), 0);
}

static int setup(void **state)
{
    (void)state;
    snprintf(dir, sizeof dir, "/tmp/mpb-mesh-disk-XXXXXX");
    if (!mkdtemp(dir))
        return -1;
    snprintf(cache_dir, sizeof cache_dir, "%s/cache", dir);
    snprintf(mesh_path, sizeof mesh_path, "%s/tetra.obj", dir);
    return setenv("MPB_CACHE_DIR", cache_dir, 1);
}

static int teardown(void **state)
{
    (void)state;
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    return system(cmd) == 0 ? 0 : -1;
}

static void the_second_load_comes_from_the_disk(void **state)
{
    (void)state;
    empty_the_cache();
    write_tetra(mesh_path, 0.25);
    long disk = mpb__mesh_disk_loads(), reads = mpb__mesh_cache_reads();
    assert_true(reach(1) == 0.25);
    assert_int_equal(mpb__mesh_disk_loads() - disk, 0);
    assert_true(reach(1) == 0.25);
    assert_int_equal(mpb__mesh_disk_loads() - disk, 1);
    assert_int_equal(mpb__mesh_cache_reads() - reads, 2);
}

static void a_changed_file_or_scale_is_read_again(void **state)
{
    (void)state;
    empty_the_cache();
    write_tetra(mesh_path, 0.25);
    assert_true(reach(1) == 0.25);
    long disk = mpb__mesh_disk_loads();
    /* One byte changed: 0.25 -> 0.75. */
    write_tetra(mesh_path, 0.75);
    assert_true(reach(1) == 0.75);
    assert_int_equal(mpb__mesh_disk_loads() - disk, 0);
    /* Another scale of the same bytes. */
    assert_true(reach(2) == 1.5);
    assert_int_equal(mpb__mesh_disk_loads() - disk, 0);
    /* Each is stored under its own key. */
    assert_true(reach(1) == 0.75);
    assert_true(reach(2) == 1.5);
    write_tetra(mesh_path, 0.25);
    assert_true(reach(1) == 0.25);
    assert_int_equal(mpb__mesh_disk_loads() - disk, 3);
}

static void a_corrupt_cache_file_is_a_miss(void **state)
{
    (void)state;
    empty_the_cache();
    write_tetra(mesh_path, 0.25);
    assert_true(reach(1) == 0.25);
    char file[700];
    the_cache_file(file, sizeof file);
    /* The first vertex's x, 0.0, made 9.0 in the payload (after the
     * 96-byte header and the two counts): the checksum no longer holds. */
    FILE *f = fopen(file, "r+b");
    assert_non_null(f);
    const double nine = 9.0;
    assert_int_equal(fseek(f, 96 + 8, SEEK_SET), 0);
    assert_int_equal(fwrite(&nine, sizeof nine, 1, f), 1);
    assert_int_equal(fclose(f), 0);
    long disk = mpb__mesh_disk_loads();
    assert_true(reach(1) == 0.25);
    assert_int_equal(mpb__mesh_disk_loads() - disk, 0);
    /* A file that is not one of the cache's at all. */
    f = fopen(file, "wb");
    assert_non_null(f);
    fputs("not a cache file\n", f);
    assert_int_equal(fclose(f), 0);
    assert_true(reach(1) == 0.25);
    assert_int_equal(mpb__mesh_disk_loads() - disk, 0);
}

static void a_broken_mesh_in_the_cache_is_a_miss(void **state)
{
    (void)state;
    empty_the_cache();
    write_tetra(mesh_path, 0.25);
    const double one[3] = {1, 1, 1};
    mpb__mesh_disk_id id;
    /* The key the loader uses names assimp; any reader text works here,
     * as long as put and get agree. */
    assert_int_equal(mpb__mesh_disk_key(mesh_path, one, "test", &id), MPB_OK);
    mpb_mesh *bad = mpb__mesh_create(3, 1);
    assert_non_null(bad);
    bad->triangles[0] = 0;
    bad->triangles[1] = 1;
    bad->triangles[2] = 7;              /* no vertex 7 */
    mpb__mesh_disk_put(&id, bad);
    assert_null(mpb__mesh_disk_get(&id));
    bad->triangles[2] = 2;
    bad->vertices[0] = 0.5;
    mpb__mesh_disk_put(&id, bad);
    mpb_mesh *good = mpb__mesh_disk_get(&id);
    assert_non_null(good);
    assert_true(good->vertices[0] == 0.5);
    mpb__mesh_destroy(good);
    mpb__mesh_destroy(bad);
}

static void without_a_cache_meshes_still_load(void **state)
{
    (void)state;
    char file[400];
    snprintf(file, sizeof file, "%s/a-file", dir);
    FILE *f = fopen(file, "w");
    assert_non_null(f);
    assert_int_equal(fclose(f), 0);
    char below[500];
    snprintf(below, sizeof below, "%s/cache", file);    /* cannot be made */
    assert_int_equal(setenv("MPB_CACHE_DIR", below, 1), 0);
    write_tetra(mesh_path, 0.5);
    long disk = mpb__mesh_disk_loads();
    assert_true(reach(1) == 0.5);
    assert_true(reach(1) == 0.5);
    assert_int_equal(mpb__mesh_disk_loads() - disk, 0);
    assert_int_equal(setenv("MPB_CACHE_DIR", cache_dir, 1), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(the_second_load_comes_from_the_disk),
        cmocka_unit_test(a_changed_file_or_scale_is_read_again),
        cmocka_unit_test(a_corrupt_cache_file_is_a_miss),
        cmocka_unit_test(a_broken_mesh_in_the_cache_is_a_miss),
        cmocka_unit_test(without_a_cache_meshes_still_load),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
