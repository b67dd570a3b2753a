/*
 * test_stats.c - summaries and the paper's grouped standard deviation,
 * against values worked out by hand (numpy's default percentile, type 7).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <cmocka.h>

#include "mpbench/mpbench.h"

#define assert_near(a, b, eps)                                              \
    do {                                                                    \
        double a_ = (a), b_ = (b);                                          \
        if (!(fabs(a_ - b_) <= (eps)))                                      \
            fail_msg("%s = %.17g, expected %.17g", #a, a_, b_);             \
    } while (0)

#define EPS 1e-12

static void test_summarize_six(void **state)
{
    (void)state;
    /*
     * x = 7 1 3 9 5 2, sorted 1 2 3 5 7 9, n = 6. Type 7: h = (n - 1) p.
     *   q1:     h = 1.25 -> x[1] + 0.25 (x[2] - x[1]) = 2 + 0.25 = 2.25
     *   median: h = 2.5  -> 3 + 0.5 (5 - 3) = 4
     *   q3:     h = 3.75 -> 5 + 0.75 (7 - 5) = 6.5
     * (np.percentile([7,1,3,9,5,2], [25,50,75]) = [2.25, 4.0, 6.5].)
     * mean 27/6 = 4.5; squared deviations 12.25 6.25 2.25 0.25 6.25 20.25
     * sum 47.5, / (n - 1) = 9.5, stddev sqrt(9.5) = 3.0822070015.
     */
    const double x[] = { 7, 1, 3, 9, 5, 2 };
    mpb_summary s;
    assert_int_equal(mpb_summarize(x, 6, &s), MPB_OK);
    assert_int_equal(s.n, 6);
    assert_near(s.mean, 4.5, EPS);
    assert_near(s.stddev, sqrt(9.5), EPS);
    assert_near(s.min, 1, 0);
    assert_near(s.q1, 2.25, EPS);
    assert_near(s.median, 4.0, EPS);
    assert_near(s.q3, 6.5, EPS);
    assert_near(s.max, 9, 0);
    /* x is not modified. */
    assert_near(x[0], 7, 0);
    assert_near(x[5], 2, 0);
}

static void test_summarize_small(void **state)
{
    (void)state;
    mpb_summary s;
    /*
     * x = 3.5 1 2, sorted 1 2 3.5. q1: h = 0.5 -> 1.5; median h = 1 -> 2;
     * q3: h = 1.5 -> 2 + 0.5 (1.5) = 2.75. mean 6.5/3; sum of squares
     * 1 + 4 + 12.25 - 3 (6.5/3)^2 = 17.25 - 42.25/3 = 19/6; var 19/12;
     * stddev sqrt(19/12) = 1.2583057.
     */
    const double x[] = { 3.5, 1, 2 };
    assert_int_equal(mpb_summarize(x, 3, &s), MPB_OK);
    assert_near(s.q1, 1.5, EPS);
    assert_near(s.median, 2.0, EPS);
    assert_near(s.q3, 2.75, EPS);
    assert_near(s.mean, 6.5 / 3, EPS);
    assert_near(s.stddev, sqrt(19.0 / 12), EPS);

    /* x = 1 2 3 4: q1 h = 0.75 -> 1.75; median 2.5; q3 h = 2.25 -> 3.25. */
    const double y[] = { 4, 3, 2, 1 };
    assert_int_equal(mpb_summarize(y, 4, &s), MPB_OK);
    assert_near(s.q1, 1.75, EPS);
    assert_near(s.median, 2.5, EPS);
    assert_near(s.q3, 3.25, EPS);

    /* One sample: every statistic is it, stddev 0. */
    const double one = 0.25;
    assert_int_equal(mpb_summarize(&one, 1, &s), MPB_OK);
    assert_int_equal(s.n, 1);
    assert_near(s.mean, 0.25, 0);
    assert_near(s.stddev, 0.0, 0);
    assert_near(s.q1, 0.25, 0);
    assert_near(s.median, 0.25, 0);
    assert_near(s.q3, 0.25, 0);
}

static void test_summarize_empty_and_bad(void **state)
{
    (void)state;
    mpb_summary s;
    assert_int_equal(mpb_summarize(NULL, 0, &s), MPB_OK);
    assert_int_equal(s.n, 0);
    assert_true(isnan(s.mean) && isnan(s.stddev) && isnan(s.min));
    assert_true(isnan(s.q1) && isnan(s.median) && isnan(s.q3) && isnan(s.max));

    const double x[] = { 1, NAN, 2 };
    assert_int_equal(mpb_summarize(x, 3, &s), MPB_EINVAL);
    assert_int_equal(mpb_summarize(x, -1, &s), MPB_EINVAL);
    assert_int_equal(mpb_summarize(NULL, 2, &s), MPB_EINVAL);
    assert_int_equal(mpb_summarize(x, 1, NULL), MPB_EINVAL);
}

static void test_grouped(void **state)
{
    (void)state;
    /*
     * Group A = 1 2 3: mean 2, sample sd sqrt((1 + 0 + 1) / 2) = 1.
     * Group B = 10 14: mean 12, sd sqrt((4 + 4) / 1) = sqrt(8) = 2.8284271.
     * Group C = 5: one sample, sd 0 (as one deterministic run).
     * Group D: no sample (a query with no successful run): not counted.
     * Mean over all samples: (6 + 24 + 5) / 6 = 35/6 = 5.8333333.
     * Std dev: (1 + sqrt(8) + 0) / 3 = 1.2761424.
     * (Pooling all six would give sqrt((335 - 1225/6) / 5) = 5.12: not the
     * paper's convention.)
     */
    mpb_grouped g;
    mpb_grouped_init(&g);
    assert_true(isnan(mpb_grouped_mean(&g)));
    assert_true(isnan(mpb_grouped_stddev(&g)));

    mpb_grouped_add(&g, 1);
    mpb_grouped_add(&g, 2);
    mpb_grouped_add(&g, 3);
    mpb_grouped_end_group(&g);
    assert_near(mpb_grouped_stddev(&g), 1.0, EPS);
    mpb_grouped_add(&g, 10);
    mpb_grouped_add(&g, 14);
    mpb_grouped_end_group(&g);
    mpb_grouped_add(&g, 5);
    mpb_grouped_end_group(&g);
    mpb_grouped_end_group(&g);            /* D, empty */

    assert_int_equal(g.groups, 3);
    assert_int_equal(mpb_grouped_measured(&g), 2);    /* A and B */
    assert_near(mpb_grouped_mean(&g), 35.0 / 6, EPS);
    assert_near(mpb_grouped_stddev(&g), (1 + sqrt(8.0)) / 3, EPS);
}

static void test_grouped_open_group_and_single_runs(void **state)
{
    (void)state;
    /*
     * Deterministic planner, one run per query (the paper's ARA* column):
     * 0.46, 0.50 in two groups. Mean 0.48, std dev (0 + 0) / 2 = 0.
     */
    mpb_grouped g;
    mpb_grouped_init(&g);
    mpb_grouped_add(&g, 0.46);
    mpb_grouped_end_group(&g);
    mpb_grouped_add(&g, 0.50);
    mpb_grouped_end_group(&g);
    assert_near(mpb_grouped_mean(&g), 0.48, EPS);
    assert_near(mpb_grouped_stddev(&g), 0.0, 0);
    assert_int_equal(mpb_grouped_measured(&g), 0);    /* 0 by convention */

    /*
     * A last group left open counts as ended: groups 2 4 (sd sqrt(2)) and
     * 1 3 (sd sqrt(2), still open): (sqrt 2 + sqrt 2) / 2 = sqrt 2.
     */
    mpb_grouped_init(&g);
    mpb_grouped_add(&g, 2);
    mpb_grouped_add(&g, 4);
    mpb_grouped_end_group(&g);
    mpb_grouped_add(&g, 1);
    assert_int_equal(mpb_grouped_measured(&g), 1);
    mpb_grouped_add(&g, 3);
    assert_int_equal(mpb_grouped_measured(&g), 2);    /* the open group too */
    assert_near(mpb_grouped_stddev(&g), sqrt(2.0), EPS);
    assert_near(mpb_grouped_mean(&g), 2.5, EPS);
    mpb_grouped_end_group(&g);
    assert_near(mpb_grouped_stddev(&g), sqrt(2.0), EPS);
}

/* Groups kept apart and merged give what adding them in turn gives. */
static void test_grouped_merge(void **state)
{
    (void)state;
    static const double a[] = {1, 2, 3}, b[] = {10, 14}, c[] = {5};
    mpb_grouped whole, part[3], merged;
    mpb_grouped_init(&whole);
    mpb_grouped_init(&merged);
    const double *groups[] = {a, b, c};
    const int sizes[] = {3, 2, 1};
    for (int i = 0; i < 3; i++) {
        mpb_grouped_init(&part[i]);
        for (int k = 0; k < sizes[i]; k++) {
            mpb_grouped_add(&whole, groups[i][k]);
            mpb_grouped_add(&part[i], groups[i][k]);
        }
        mpb_grouped_end_group(&whole);
        if (i < 2)                      /* the last stays open */
            mpb_grouped_end_group(&part[i]);
        mpb_grouped_merge(&merged, &part[i]);
    }
    assert_int_equal(merged.n, 6);
    assert_int_equal(merged.groups, 3);
    assert_int_equal(mpb_grouped_measured(&merged), 2);
    assert_near(mpb_grouped_mean(&merged), mpb_grouped_mean(&whole), EPS);
    assert_near(mpb_grouped_stddev(&merged), (1 + sqrt(8.0)) / 3, EPS);
}

static int cmp_double(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

/* mpb_sort_doubles() orders as qsort() with < does, on values of every
 * kind (negatives, both zeros, infinities, repeats, subnormals, values
 * that share their high bytes), for sizes from none to a hundred
 * thousand; -0 comes before +0. */
static void test_sort_doubles(void **state)
{
    (void)state;
    static const size_t sizes[] = {0, 1, 2, 3, 17, 1000, 100000};
    uint64_t seed = 7;
    for (size_t k = 0; k < sizeof sizes / sizeof *sizes; k++) {
        size_t n = sizes[k];
        double *x = malloc((n + 1) * sizeof *x), *y = malloc((n + 1) * sizeof *y);
        assert_non_null(x);
        assert_non_null(y);
        for (size_t i = 0; i < n; i++) {
            seed = seed * 6364136223846793005ull + 1442695040888963407ull;
            double u = (double)(seed >> 11) / 9007199254740992.0;
            switch ((seed >> 3) % 8) {
            case 0: x[i] = -u * 1e6; break;
            case 1: x[i] = u < 0.5 ? 0.0 : -0.0; break;
            case 2: x[i] = u < 0.5 ? INFINITY : -INFINITY; break;
            case 3: x[i] = 1.25; break;
            case 4: x[i] = u * 1e-310; break;
            case 5: x[i] = 1.0 + u * 1e-12; break;
            default: x[i] = u * 100.0; break;
            }
            y[i] = x[i];
        }
        assert_int_equal(mpb_sort_doubles(x, n), MPB_OK);
        qsort(y, n, sizeof *y, cmp_double);
        for (size_t i = 0; i < n; i++) {
            assert_true(x[i] == y[i]);
            if (i > 0 && x[i - 1] == 0.0 && x[i] == 0.0)
                assert_false(signbit(x[i]) && !signbit(x[i - 1]));
        }
        free(x);
        free(y);
    }
    assert_int_equal(mpb_sort_doubles(NULL, 0), MPB_OK);
    assert_int_equal(mpb_sort_doubles(NULL, 3), MPB_EINVAL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sort_doubles),
        cmocka_unit_test(test_summarize_six),
        cmocka_unit_test(test_grouped_merge),
        cmocka_unit_test(test_summarize_small),
        cmocka_unit_test(test_summarize_empty_and_bad),
        cmocka_unit_test(test_grouped),
        cmocka_unit_test(test_grouped_open_group_and_single_runs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
