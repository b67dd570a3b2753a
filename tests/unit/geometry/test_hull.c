/*
 * test_hull.c - mpb__hull_keep() (hull.h): along thousands of random
 * directions, and along the direction of every point that is extreme by
 * construction, the extent of the kept points is exactly that of all the
 * points; points well inside are dropped; flat, collinear, tiny and
 * non-finite sets are kept whole. Also the Panda's collision meshes
 * (skipped when they are not fetched), whose kept counts are printed.
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
#include "geometry/hull.h"
#include "geometry/mesh.h"

#define PANDA MPB_TEST_DATA "/../../../.cache/robots/vamp-planner-0.6.4/panda"

static uint64_t rng = 0x9e3779b97f4a7c15ull;

/* Uniform in [-1, 1). */
static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 4503599627370496.0 - 1.0;
}

static void unit_dir(double d[3])
{
    double n;
    do {
        d[0] = urand(), d[1] = urand(), d[2] = urand();
        n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    } while (!(n > 1e-3 && n <= 1));
    d[0] /= n, d[1] /= n, d[2] /= n;
}

/* Max of d . p over the points (all when keep is NULL). */
static double extent(const double *p, int n, const unsigned char *keep,
                     const double d[3])
{
    double hi = -INFINITY;
    for (int i = 0; i < n; i++)
        if (!keep || keep[i])
            hi = fmax(hi, d[0] * p[3 * i] + d[1] * p[3 * i + 1] + d[2] * p[3 * i + 2]);
    return hi;
}

/* The kept extent equals the full one along dirs random directions (both
 * signs: min and max), and along each point's own direction from centre
 * c (for points on a sphere about c: the point is then the only maximum).
 * Returns the number kept. */
static int check_extents(const double *p, int n, int dirs, const double *c)
{
    unsigned char *keep = malloc((size_t)n);
    assert_non_null(keep);
    int kept = mpb__hull_keep(p, n, keep);
    int count = 0;
    for (int i = 0; i < n; i++)
        count += keep[i] != 0;
    assert_int_equal(kept, count);
    for (int k = 0; k < dirs; k++) {
        double d[3];
        unit_dir(d);
        assert_true(extent(p, n, keep, d) == extent(p, n, NULL, d));
        d[0] = -d[0], d[1] = -d[1], d[2] = -d[2];
        assert_true(extent(p, n, keep, d) == extent(p, n, NULL, d));
    }
    for (int i = 0; c && i < n; i++) {
        double d[3];
        for (int k = 0; k < 3; k++)
            d[k] = p[3 * i + k] - c[k];
        assert_true(extent(p, n, keep, d) == extent(p, n, NULL, d));
    }
    free(keep);
    return kept;
}

/* Random clouds in a ball and in a box, at several sizes and offsets: exact
 * extents, and most of the points dropped. */
static void test_random_clouds(void **state)
{
    (void)state;
    const int sizes[] = {4, 5, 10, 100, 1000, 3000};
    for (int s = 0; s < 6; s++)
        for (int shape = 0; shape < 2; shape++) {
            int n = sizes[s];
            double *p = malloc((size_t)n * 3 * sizeof *p);
            assert_non_null(p);
            double scale = shape ? 1e-3 : 5.0, off = shape ? 0.2 : -3.0;
            for (int i = 0; i < n; i++) {
                double d[3];
                if (shape)
                    d[0] = urand(), d[1] = urand(), d[2] = urand();
                else
                    unit_dir(d);
                double r = shape ? 1 : cbrt(fabs(urand()));
                for (int k = 0; k < 3; k++)
                    p[3 * i + k] = off + scale * r * d[k];
            }
            int kept = check_extents(p, n, 2000, NULL);
            if (n >= 1000)
                assert_true(kept < n / 2);
            free(p);
        }
}

/* Points on a sphere are all extreme: none may be dropped, and each is the
 * only maximum along its own direction. */
static void test_sphere_all_kept(void **state)
{
    (void)state;
    int n = 2000;
    double *p = malloc((size_t)n * 3 * sizeof *p), c[3] = {0.3, -0.1, 0.7};
    assert_non_null(p);
    for (int i = 0; i < n; i++) {
        double d[3];
        unit_dir(d);
        for (int k = 0; k < 3; k++)
            p[3 * i + k] = c[k] + 0.05 * d[k];
    }
    assert_int_equal(check_extents(p, n, 1000, c), n);
    free(p);
}

/* A cube's corners, points on its faces and edges (coplanar with facets)
 * and inside: extents exact, every corner kept, every point well inside
 * dropped. */
static void test_cube(void **state)
{
    (void)state;
    enum { CORNERS = 8, FACE = 600, INSIDE = 1000, N = CORNERS + FACE + INSIDE };
    double p[3 * N];
    int i = 0;
    for (int c = 0; c < 8; c++, i++)
        for (int k = 0; k < 3; k++)
            p[3 * i + k] = (c >> k & 1) ? 1.0 : -1.0;
    for (int f = 0; f < FACE; f++, i++) {
        int ax = f % 3;                /* on a face; every 4th on an edge */
        for (int k = 0; k < 3; k++)
            p[3 * i + k] = urand();
        p[3 * i + ax] = f % 2 ? 1.0 : -1.0;
        if (f % 4 == 0)
            p[3 * i + (ax + 1) % 3] = 1.0;
    }
    for (int f = 0; f < INSIDE; f++, i++)
        for (int k = 0; k < 3; k++)
            p[3 * i + k] = 0.999 * urand();
    unsigned char keep[N];
    mpb__hull_keep(p, N, keep);
    for (int c = 0; c < CORNERS; c++)
        assert_true(keep[c]);
    for (int f = CORNERS + FACE; f < N; f++)
        assert_false(keep[f]);
    check_extents(p, N, 3000, NULL);
}

/* Sets without a volume, or too small, or not finite: everything kept. */
static void test_degenerate_kept_whole(void **state)
{
    (void)state;
    enum { N = 200 };
    double p[3 * N];
    unsigned char keep[N];
    for (int kind = 0; kind < 5; kind++) {
        for (int i = 0; i < N; i++) {
            double a = urand(), b = urand();
            switch (kind) {
            case 0:         /* flat: a tilted plane */
                p[3 * i] = a, p[3 * i + 1] = b, p[3 * i + 2] = 0.3 * a - 0.2 * b + 1;
                break;
            case 1:         /* collinear */
                p[3 * i] = a, p[3 * i + 1] = 2 * a, p[3 * i + 2] = -a;
                break;
            case 2:         /* one point, many times */
                p[3 * i] = 1, p[3 * i + 1] = 2, p[3 * i + 2] = 3;
                break;
            case 3:         /* all at the origin */
                p[3 * i] = p[3 * i + 1] = p[3 * i + 2] = 0;
                break;
            default:        /* a ball with one NaN */
                p[3 * i] = a, p[3 * i + 1] = b, p[3 * i + 2] = urand();
                if (i == N / 2)
                    p[3 * i + 1] = NAN;
                break;
            }
        }
        assert_int_equal(mpb__hull_keep(p, N, keep), N);
        for (int i = 0; i < N; i++)
            assert_true(keep[i]);
    }
    double three[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    assert_int_equal(mpb__hull_keep(three, 3, keep), 3);
    assert_int_equal(mpb__hull_keep(three, 0, keep), 0);
    /* nearly flat: a plane with one point 1e-12 above it */
    for (int i = 0; i < N; i++)
        p[3 * i] = urand(), p[3 * i + 1] = urand(), p[3 * i + 2] = 0;
    p[3 * 7 + 2] = 1e-12;
    assert_int_equal(mpb__hull_keep(p, N, keep), N);
}

/* The Panda's collision meshes: exact extents; the kept counts (all but
 * link6 are convex: every vertex is on the hull). */
static void test_panda_meshes(void **state)
{
    (void)state;
    static const char *const names[] = {"link0", "link1", "link2", "link3",
                                        "link4", "link5", "link6", "link7",
                                        "hand", "finger"};
    char dir[4096], uri[4200];
    /* assimp reads "a/../b" as written: the folder without its ".." */
    if (access(PANDA "/meshes/collision/link0.obj", R_OK) != 0 || !realpath(PANDA, dir))
        skip();
    for (size_t k = 0; k < sizeof names / sizeof *names; k++) {
        snprintf(uri, sizeof uri, "%s/meshes/collision/%s.obj", dir, names[k]);
        mpb_mesh *m = NULL;
        char err[512];
        if (mpb__mesh_create_from_uri(uri, NULL, 0, NULL, &m, err, sizeof err) != MPB_OK)
            fail_msg("%s", err);
        int kept = check_extents(m->vertices, m->num_vertices, 5000, NULL);
        printf("# %s: %d of %d vertices kept\n", names[k], kept, m->num_vertices);
        if (strcmp(names[k], "link6") == 0)   /* the others are convex */
            assert_true(kept < m->num_vertices / 2);
        mpb__mesh_destroy(m);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_clouds),
        cmocka_unit_test(test_sphere_all_kept),
        cmocka_unit_test(test_cube),
        cmocka_unit_test(test_degenerate_kept_whole),
        cmocka_unit_test(test_panda_meshes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
