/*
 * test_simplex.c - mpb__simplex_nearest() (simplex.h): the point found is
 * in the hull of the points kept (positive weights), and nearest the
 * origin of the whole simplex: v . (p - v) >= 0 for every input point p.
 * Random simplices of 1 to 4 points, tetrahedra around the origin,
 * doubled, collinear and flat points.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "geometry/simplex.h"

static uint64_t rng = 0x853c49e6748fea9bull;

/* Uniform in [-1, 1). */
static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 4503599627370496.0 - 1.0;
}

static double dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* v is nearest the origin over the hull of in[0 .. m), within tol; the
 * kept points are input points. */
static void check_nearest(double in[][3], int m, double tol)
{
    double p[4][3], v[3];
    memcpy(p, in, (size_t)m * sizeof p[0]);
    int k = mpb__simplex_nearest(p, m, v);
    assert_true(k >= 1 && k <= 3);
    for (int i = 0; i < k; i++) {
        int found = 0;
        for (int j = 0; j < m; j++)
            found |= memcmp(p[i], in[j], sizeof p[0]) == 0;
        assert_true(found);
    }
    for (int j = 0; j < m; j++) {
        double d[3] = {in[j][0] - v[0], in[j][1] - v[1], in[j][2] - v[2]};
        assert_true(dot(v, d) >= -tol);
    }
    /* v is in the hull of the kept points: nearer than none of them is
     * wrong, and no farther than the nearest kept one */
    double nearest = INFINITY;
    for (int i = 0; i < k; i++)
        nearest = fmin(nearest, dot(p[i], p[i]));
    assert_true(dot(v, v) <= nearest + tol);
}

static void test_random(void **state)
{
    (void)state;
    for (int t = 0; t < 20000; t++) {
        int m = 1 + t % 4;
        double in[4][3];
        for (int i = 0; i < m; i++)
            for (int j = 0; j < 3; j++)
                in[i][j] = urand() + (t % 3 == 0 ? 2.0 : 0.0);
        double p[4][3], v[3];
        memcpy(p, in, sizeof p);
        if (m == 4 && mpb__simplex_nearest(p, m, v) == 0) {
            assert_true(v[0] == 0 && v[1] == 0 && v[2] == 0);
            continue;           /* the origin inside: checked below */
        }
        check_nearest(in, m, 1e-12);
    }
}

static void test_origin_inside(void **state)
{
    (void)state;
    double p[4][3] = {{1, 0, -0.5}, {-1, 1, -0.5}, {-1, -1, -0.5}, {0, 0, 1}}, v[3];
    assert_int_equal(mpb__simplex_nearest(p, 4, v), 0);
    double q[4][3] = {{1, 0, 0.5}, {-1, 1, 0.5}, {-1, -1, 0.5}, {0, 0, 1}};
    double in[4][3];
    memcpy(in, q, sizeof q);
    assert_int_equal(mpb__simplex_nearest(q, 4, v), 3);     /* the bottom */
    assert_true(fabs(v[2] - 0.5) < 1e-15 && fabs(v[0]) < 1e-15);
    check_nearest(in, 4, 1e-12);
}

static void test_degenerate(void **state)
{
    (void)state;
    double doubled[4][3] = {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}};
    check_nearest(doubled, 4, 1e-12);
    double line[4][3] = {{1, -1, 1}, {1, 0, 1}, {1, 1, 1}, {1, 2, 1}};
    check_nearest(line, 4, 1e-12);
    double flat[4][3] = {{1, -1, -1}, {1, 1, -1}, {1, 0, 1}, {1, 0.2, 0.1}};
    check_nearest(flat, 4, 1e-12);
    double segment[2][3] = {{-1, 1, 0}, {1, 1, 0}};
    double v[3];
    assert_int_equal(mpb__simplex_nearest(segment, 2, v), 2);
    assert_true(fabs(v[0]) < 1e-15 && v[1] == 1 && v[2] == 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random),
        cmocka_unit_test(test_origin_inside),
        cmocka_unit_test(test_degenerate),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
