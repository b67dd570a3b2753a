/*
 * test_dirtable.c - mpb__dirtable (dirtable.h): along random directions,
 * directions on the borders of cells and faces, and axes, the farthest
 * point among its cell's candidates is the farthest of all: the same
 * value to the bit and the same (first) index. Random clouds, points on a
 * sphere (every point the farthest somewhere), a cube, and the Panda's
 * collision meshes (skipped when not fetched; mean list sizes printed).
 */
#include <limits.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "geometry/dirtable.h"
#include "geometry/hull.h"
#include "geometry/mesh.h"

#define PANDA MPB_TEST_DATA "/../../../.cache/robots/vamp-planner-0.6.4/panda"

static uint64_t rng = 0x2545f4914f6cdd1dull;

/* Uniform in [-1, 1). */
static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 4503599627370496.0 - 1.0;
}

/* The farthest along d: its value and first index, over the list (all
 * points when list is NULL). */
static double farthest(const double *p, int n, const int *list, int len,
                       const double d[3], int *at)
{
    double hi = -INFINITY;
    *at = -1;
    for (int k = 0; k < (list ? len : n); k++) {
        int i = list ? list[k] : k;
        double x = p[3 * i] * d[0] + p[3 * i + 1] * d[1] + p[3 * i + 2] * d[2];
        if (x > hi)
            hi = x, *at = i;
    }
    return hi;
}

static void check_dir(const mpb__dirtable *t, const double *p, int n,
                      const double d[3])
{
    int c = mpb__dirtable_cell(t, d), a, b;
    assert_true(c >= 0 && c < 6 * t->g * t->g);
    const int *list = &t->idx[t->start[c]];
    int len = t->start[c + 1] - t->start[c];
    for (int k = 1; k < len; k++)
        assert_true(list[k - 1] < list[k]);
    double x = farthest(p, n, list, len, d, &a);
    double y = farthest(p, n, NULL, 0, d, &b);
    assert_true(x == y);
    assert_int_equal(a, b);
}

/* Random directions at random lengths; directions on cell borders (u or v
 * on a grid line, nudged by an ulp or not) and on face borders; the axes
 * and the cube's diagonals. Returns the mean list length. */
static double check_table(const double *p, int n, int g, int dirs)
{
    mpb__dirtable t;
    assert_int_equal(mpb__dirtable_build(&t, p, n, g), MPB_OK);
    for (int k = 0; k < dirs; k++) {
        double d[3] = {urand(), urand(), urand()}, len = ldexp(1.0, k % 40 - 20);
        for (int j = 0; j < 3; j++)
            d[j] *= len;
        check_dir(&t, p, n, d);
        /* a cell border: one coordinate a grid line times the largest */
        int ax = k % 3;
        double big = fabs(d[0]) + fabs(d[1]) + fabs(d[2]) + 1e-3;
        d[ax] = (k % 2 ? -big : big);
        int line = (int)((urand() + 1) / 2 * (g + 1));
        double u = (-1 + 2.0 * line / g) * big;
        d[(ax + 1) % 3] = k % 5 == 0 ? nextafter(u, 0) : k % 5 == 1 ? nextafter(u, 1e9) : u;
        check_dir(&t, p, n, d);
        d[(ax + 2) % 3] = k % 3 ? d[ax] : -d[ax];       /* a face border */
        check_dir(&t, p, n, d);
    }
    for (int s = 0; s < 27; s++) {
        double d[3] = {s % 3 - 1.0, s / 3 % 3 - 1.0, s / 9 - 1.0};
        if (s != 13)
            check_dir(&t, p, n, d);
    }
    double zero[3] = {0, 0, 0}, nan3[3] = {NAN, 0, 0}, inf3[3] = {INFINITY, 1, 0};
    assert_int_equal(mpb__dirtable_cell(&t, zero), -1);
    assert_int_equal(mpb__dirtable_cell(&t, nan3), -1);
    assert_int_equal(mpb__dirtable_cell(&t, inf3), -1);
    double mean = (double)t.start[6 * g * g] / (6 * g * g);
    mpb__dirtable_free(&t);
    return mean;
}

static void test_clouds(void **state)
{
    (void)state;
    const int sizes[] = {1, 2, 7, 100, 1000};
    for (int s = 0; s < 5; s++)
        for (int shape = 0; shape < 3; shape++) {
            int n = sizes[s];
            double *p = malloc((size_t)n * 3 * sizeof *p);
            assert_non_null(p);
            for (int i = 0; i < n; i++) {
                double d[3] = {urand(), urand(), urand()};
                if (shape == 0)     /* a box far from the origin */
                    for (int j = 0; j < 3; j++)
                        d[j] = 10 + 0.01 * d[j];
                else if (shape == 1) { /* a sphere: all extreme */
                    double r = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + 1e-9;
                    for (int j = 0; j < 3; j++)
                        d[j] = 0.05 * d[j] / r;
                } else {            /* a cube's corners and faces */
                    d[i % 3] = i % 2 ? 0.1 : -0.1;
                    if (i % 4 == 0)
                        d[(i + 1) % 3] = 0.1;
                }
                memcpy(&p[3 * i], d, sizeof d);
            }
            for (int g = 1; g <= 12; g += 5)
                check_table(p, n, g, 2000);
            free(p);
        }
}

static void test_bad_input(void **state)
{
    (void)state;
    mpb__dirtable t;
    double p[6] = {0, 0, 0, 1, NAN, 0};
    assert_int_equal(mpb__dirtable_build(&t, p, 2, 4), MPB_EINVAL);
    assert_int_equal(t.g, 0);
    double d[3] = {1, 0, 0};
    assert_int_equal(mpb__dirtable_cell(&t, d), -1);
    assert_int_equal(mpb__dirtable_build(&t, p, 1, 0), MPB_EINVAL);
    assert_int_equal(mpb__dirtable_build(&t, p, 0, 4), MPB_EINVAL);
    mpb__dirtable_free(&t);
}

/* The Panda's meshes, their hull vertices (hull.h) as collision_fcl.cpp
 * keeps them. */
static void test_panda_meshes(void **state)
{
    (void)state;
    static const char *const names[] = {"link0", "link1", "link2", "link3",
                                        "link4", "link5", "link6", "link7",
                                        "hand", "finger"};
    char dir[4096], uri[4200];
    if (access(PANDA "/meshes/collision/link0.obj", R_OK) != 0 || !realpath(PANDA, dir))
        skip();
    for (size_t k = 0; k < sizeof names / sizeof *names; k++) {
        snprintf(uri, sizeof uri, "%s/meshes/collision/%s.obj", dir, names[k]);
        mpb_mesh *m = NULL;
        char err[512];
        if (mpb__mesh_create_from_uri(uri, NULL, 0, NULL, &m, err, sizeof err) != MPB_OK)
            fail_msg("%s", err);
        unsigned char *keep = malloc((size_t)m->num_vertices);
        double *p = malloc((size_t)m->num_vertices * 3 * sizeof *p);
        assert_true(keep && p);
        mpb__hull_keep(m->vertices, m->num_vertices, keep);
        int n = 0;
        for (int i = 0; i < m->num_vertices; i++)
            if (keep[i])
                memcpy(&p[3 * n++], &m->vertices[3 * i], 3 * sizeof *p);
        printf("# %s: %d hull vertices; mean candidates", names[k], n);
        for (int g = 4; g <= 16; g += 4)
            printf(" g=%d %.1f", g, check_table(p, n, g, 3000));
        printf("\n");
        free(keep);
        free(p);
        mpb__mesh_destroy(m);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_clouds),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_panda_meshes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
