/* test_latency.c - the daemon's histogram of run latencies (latency.c):
 * quantiles exact to the microsecond below 65.536 ms and to the unit of
 * their tier above, where it once saturated at 65536 us. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "daemon.h"

static void test_microseconds_exact(void **state)
{
    (void)state;
    mpbd_latency l;
    assert_int_equal(mpbd_latency_init(&l), MPB_OK);
    assert_int_equal(mpbd_latency_quantile_us(&l, 0.5), -1);
    for (int i = 1; i <= 99; i++)
        mpbd_latency_add(&l, i * 1e-6 + 1e-9);
    assert_int_equal(mpbd_latency_quantile_us(&l, 0.5), 50);
    assert_int_equal(mpbd_latency_quantile_us(&l, 0.99), 98);
    mpbd_latency_free(&l);
}

/* Runs that plan for a second: the median is said, not "over 65536 us". */
static void test_long_runs_are_not_saturated(void **state)
{
    (void)state;
    mpbd_latency l;
    assert_int_equal(mpbd_latency_init(&l), MPB_OK);
    mpbd_latency_add(&l, 0.5);          /* 500 ms */
    mpbd_latency_add(&l, 1.2345);       /* 1234 ms */
    mpbd_latency_add(&l, 2.0);          /* 2000 ms */
    assert_int_equal(mpbd_latency_quantile_us(&l, 0.5), 1234000);
    mpbd_latency_add(&l, 90.0);         /* past 65.536 s: seconds */
    mpbd_latency_add(&l, 3600.7);
    assert_int_equal(mpbd_latency_quantile_us(&l, 0.99), 3600000000L);
    /* Just past the microsecond tier: no lower than where it ends. */
    mpbd_latency l2;
    assert_int_equal(mpbd_latency_init(&l2), MPB_OK);
    mpbd_latency_add(&l2, 0.0655361);
    assert_int_equal(mpbd_latency_quantile_us(&l2, 0.5), 65536);
    /* Beyond the last tier: "longer". */
    mpbd_latency_add(&l2, 1e6);
    mpbd_latency_add(&l2, 1e6);
    assert_int_equal(mpbd_latency_quantile_us(&l2, 0.5), MPBD_LATENCY_MAX_US);
    mpbd_latency_free(&l2);
    mpbd_latency_free(&l);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_microseconds_exact),
        cmocka_unit_test(test_long_runs_are_not_saturated),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
