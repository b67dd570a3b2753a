/* test_inference.c - the intervals and tests of stats.h (inference.c),
 * against values computed independently: the signed-rank test's exact p
 * by enumerating all 2^n sign patterns, the others from their formulas
 * by hand (Python, double precision). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "mpbench/stats.h"

static void wilsons_interval(void **state)
{
    (void)state;
    double lo, hi;
    assert_int_equal(mpb_wilson_interval(7, 10, &lo, &hi), MPB_OK);
    assert_float_equal(lo, 0.39677814746114537, 1e-12);
    assert_float_equal(hi, 0.8922087325936989, 1e-12);
    assert_int_equal(mpb_wilson_interval(0, 20, &lo, &hi), MPB_OK);
    assert_float_equal(lo, 0.0, 0);
    assert_float_equal(hi, 0.16112515805281938, 1e-12);
    assert_int_equal(mpb_wilson_interval(35, 35, &lo, &hi), MPB_OK);
    assert_float_equal(lo, 0.9010990076755959, 1e-12);
    assert_float_equal(hi, 1.0, 0);
    assert_int_equal(mpb_wilson_interval(0, 0, &lo, &hi), MPB_OK);
    assert_true(isnan(lo) && isnan(hi));
    assert_int_equal(mpb_wilson_interval(3, 2, &lo, &hi), MPB_EINVAL);
}

static void quantiles_interpolate(void **state)
{
    (void)state;
    const double x[] = {1, 2, 3, 4, 10};
    assert_float_equal(mpb_quantile(x, 5, 0.5), 3, 0);
    assert_float_equal(mpb_quantile(x, 5, 0.95), 8.8, 1e-12);
    assert_float_equal(mpb_quantile(x, 5, 1), 10, 0);
    assert_true(isnan(mpb_quantile(x, 0, 0.5)));
}

/* n = 10: P(X <= 1) = 11/1024 <= 2.5 % < P(X <= 2) for X ~ B(10, 1/2):
 * ranks 2 and 9, coverage 1 - 22/1024. */
static void the_medians_interval_by_order_statistics(void **state)
{
    (void)state;
    const double x[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
    double lo, hi, cover;
    assert_int_equal(mpb_median_interval(x, 10, &lo, &hi, &cover), MPB_OK);
    assert_float_equal(lo, 2, 0);
    assert_float_equal(hi, 9, 0);
    assert_float_equal(cover, 1 - 22.0 / 1024, 1e-12);
    /* Two samples: the range, which holds the median half the time. */
    assert_int_equal(mpb_median_interval(x, 2, &lo, &hi, &cover), MPB_OK);
    assert_float_equal(lo, 1, 0);
    assert_float_equal(hi, 2, 0);
    assert_float_equal(cover, 0.5, 1e-12);
}

static void the_signed_rank_test_exact(void **state)
{
    (void)state;
    double p;
    int used;
    const double a[] = {1.5, -0.2, 3.1, 2.2, 0.7, -1.1, 4.0, 2.5};
    assert_int_equal(mpb_signed_rank_test(a, 8, &used, &p), MPB_OK);
    assert_int_equal(used, 8);
    assert_float_equal(p, 0.0546875, 1e-12);            /* W+ = 32 */
    const double b[] = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
    assert_int_equal(mpb_signed_rank_test(b, 10, NULL, &p), MPB_OK);
    assert_float_equal(p, 2.0 / 1024, 1e-12);           /* all positive */
    const double c[] = {1, -2, 3, -4, 5, -6, 0, 0};
    assert_int_equal(mpb_signed_rank_test(c, 8, &used, &p), MPB_OK);
    assert_int_equal(used, 6);                          /* zeros left out */
    assert_float_equal(p, 0.84375, 1e-12);
    const double none[] = {0, 0};
    assert_int_equal(mpb_signed_rank_test(none, 2, &used, &p), MPB_OK);
    assert_int_equal(used, 0);
    assert_float_equal(p, 1, 0);
    const double bad[] = {1, NAN};
    assert_int_equal(mpb_signed_rank_test(bad, 2, NULL, &p), MPB_EINVAL);
}

/* Ties: W+ = 71, variance 12*13*25/24 - 72/48 = 160.875. */
static void the_signed_rank_test_with_ties(void **state)
{
    (void)state;
    const double d[] = {1, 1, 2, 2, -1, 3, 3, 3, 4, -2, 5, 5};
    double p;
    assert_int_equal(mpb_signed_rank_test(d, 12, NULL, &p), MPB_OK);
    assert_float_equal(p, 0.013009392806716544, 1e-12);
}

static void holms_adjustment(void **state)
{
    (void)state;
    double p[] = {0.01, 0.04, 0.03, 0.005};
    assert_int_equal(mpb_holm(p, 4, p), MPB_OK);        /* in place */
    assert_float_equal(p[0], 0.03, 1e-12);
    assert_float_equal(p[1], 0.06, 1e-12);
    assert_float_equal(p[2], 0.06, 1e-12);
    assert_float_equal(p[3], 0.02, 1e-12);
    double q[] = {0.5, 1.5};
    assert_int_equal(mpb_holm(q, 2, q), MPB_EINVAL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(wilsons_interval),
        cmocka_unit_test(quantiles_interpolate),
        cmocka_unit_test(the_medians_interval_by_order_statistics),
        cmocka_unit_test(the_signed_rank_test_exact),
        cmocka_unit_test(the_signed_rank_test_with_ties),
        cmocka_unit_test(holms_adjustment),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
