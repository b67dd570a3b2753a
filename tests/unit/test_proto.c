/* test_proto.c - run ids, planner ids, channels, content hashes, stage
 * size checks and the first of two daemons, of the protocol. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "mpb_daemon_status_t.h"
#include "mpb_stage_t.h"

static void run_ids_are_hex_and_distinct(void **state)
{
    (void)state;
    char a[MPB_RUN_ID_SIZE], b[MPB_RUN_ID_SIZE];
    assert_int_equal(mpb_run_id_new(a), MPB_OK);
    assert_int_equal(mpb_run_id_new(b), MPB_OK);
    assert_int_equal(strlen(a), 32);
    assert_true(mpb_run_id_is_valid(a));
    assert_string_not_equal(a, b);
    assert_false(mpb_run_id_is_valid("0123456789ABCDEF0123456789abcdef")); /* upper case */
    assert_false(mpb_run_id_is_valid("0123456789abcdef0123456789abcde"));  /* 31 */
    assert_false(mpb_run_id_is_valid("0123456789abcdef0123456789abcdef0")); /* 33 */
    assert_false(mpb_run_id_is_valid("0123456789abcdef0123456789abcdeg"));
    assert_false(mpb_run_id_is_valid(NULL));
}

static void planner_ids_are_channel_safe(void **state)
{
    (void)state;
    char ch[160], long_id[MPB_PLANNER_ID_MAX + 2];
    assert_true(mpb_planner_id_is_valid("ompl@host-1.lan:1234"));
    assert_false(mpb_planner_id_is_valid(""));
    assert_false(mpb_planner_id_is_valid("a b"));
    assert_false(mpb_planner_id_is_valid("a.*"));   /* a regex in a channel */
    assert_false(mpb_planner_id_is_valid("x\n"));
    memset(long_id, 'a', sizeof long_id - 1);
    long_id[sizeof long_id - 1] = '\0';             /* 97 characters */
    assert_false(mpb_planner_id_is_valid(long_id));
    long_id[MPB_PLANNER_ID_MAX] = '\0';             /* 96 */
    assert_true(mpb_planner_id_is_valid(long_id));

    assert_int_equal(mpb_request_channel("null@h:1", ch, sizeof ch), MPB_OK);
    assert_string_equal(ch, "MPB_REQUEST_null@h:1");
    assert_int_equal(mpb_request_channel("bad id", ch, sizeof ch), MPB_EINVAL);
    assert_int_equal(mpb_request_channel("null@h:1", ch, 10), MPB_EINVAL);
    assert_int_equal(mpb_ack_channel("null@h:1", ch, sizeof ch), MPB_OK);
    assert_string_equal(ch, "MPB_ACK_null@h:1");
    assert_int_equal(mpb_ack_channel("bad id", ch, sizeof ch), MPB_EINVAL);
    assert_int_equal(mpb_ack_channel("null@h:1", ch, 10), MPB_EINVAL);
}

static void hashes_are_blake2b_128(void **state)
{
    (void)state;
    char h[MPB_HASH_SIZE];
    /* Python: hashlib.blake2b(b'abc', digest_size=16).hexdigest() */
    mpb_hash_hex("abc", 3, h);
    assert_string_equal(h, "cf4ab791c62b8d2b2109c90275287816");
    mpb_hash_hex("", 0, h);
    assert_string_equal(h, "cae66941d9efbd404e4d88758ea67670");
}

static void stage_sizes_must_agree(void **state)
{
    (void)state;
    double wp[6] = {0};
    char why[200];
    mpb_stage_t st = {.name = "raw", .num_waypoints = 2, .num_joints = 3,
                      .num_values = 6, .waypoints = wp};
    assert_true(mpb_stage_sizes_ok(&st, 3, why, sizeof why));
    assert_false(mpb_stage_sizes_ok(&st, 2, why, sizeof why));   /* robot differs */
    assert_non_null(strstr(why, "the robot has 2 joints"));
    st.num_values = 5;                                           /* disagree */
    assert_false(mpb_stage_sizes_ok(&st, 3, why, sizeof why));
    st.num_waypoints = -2; st.num_values = -6;                   /* negative */
    assert_false(mpb_stage_sizes_ok(&st, 3, NULL, 0));
    /* A product that overflows 32 bits must not wrap into agreement. */
    st.num_waypoints = 0x40000000; st.num_joints = 4; st.num_values = 0;
    assert_false(mpb_stage_sizes_ok(&st, 4, NULL, 0));
}

static void statuses_have_names(void **state)
{
    (void)state;
    assert_string_equal(mpb_status_name(0), "solved");
    assert_string_equal(mpb_status_name(2), "timeout");
    assert_string_equal(mpb_status_name(5), "crash");
    assert_string_equal(mpb_status_name(99), "unknown");
    assert_string_equal(mpb_strerror(MPB_EPARSE), "malformed input");
    assert_string_equal(mpb_err_name(MPB_EPARSE), "MPB_EPARSE");
}

static void the_first_daemon_is_the_earliest_started(void **state)
{
    (void)state;
    /* Sent 2.5 s apart by daemons that started 0.5 s apart. */
    mpb_daemon_status_t a = {.utime = 10000000, .elapsed_s = 3.0};
    mpb_daemon_status_t b = {.utime = 12500000, .elapsed_s = 5.0};
    int64_t ta = mpb_daemon_started_utime(&a), tb = mpb_daemon_started_utime(&b);
    assert_int_equal(ta, 7000000);
    assert_int_equal(tb, 7500000);
    assert_true(mpb_daemon_started_before(ta, "z", tb, "a"));
    assert_false(mpb_daemon_started_before(tb, "a", ta, "z"));
    /* A tie: exactly one of the two is first, by id. */
    assert_true(mpb_daemon_started_before(ta, "a", ta, "b"));
    assert_false(mpb_daemon_started_before(ta, "b", ta, "a"));
    assert_false(mpb_daemon_started_before(ta, "a", ta, "a"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(run_ids_are_hex_and_distinct),
        cmocka_unit_test(planner_ids_are_channel_safe),
        cmocka_unit_test(hashes_are_blake2b_128),
        cmocka_unit_test(stage_sizes_must_agree),
        cmocka_unit_test(statuses_have_names),
        cmocka_unit_test(the_first_daemon_is_the_earliest_started),
    };
    return cmocka_run_group_tests_name("proto", tests, NULL, NULL);
}
