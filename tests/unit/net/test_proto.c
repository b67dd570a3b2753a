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
    char a[MPB_ATTEMPT_ID_SIZE], b[MPB_ATTEMPT_ID_SIZE];
    assert_int_equal(mpb_attempt_id_new(a), MPB_OK);
    assert_int_equal(mpb_attempt_id_new(b), MPB_OK);
    assert_int_equal(strlen(a), 32);
    assert_true(mpb_attempt_id_is_valid(a));
    assert_string_not_equal(a, b);
    assert_false(mpb_attempt_id_is_valid("0123456789ABCDEF0123456789abcdef")); /* upper case */
    assert_false(mpb_attempt_id_is_valid("0123456789abcdef0123456789abcde"));  /* 31 */
    assert_false(mpb_attempt_id_is_valid("0123456789abcdef0123456789abcdef0")); /* 33 */
    assert_false(mpb_attempt_id_is_valid("0123456789abcdef0123456789abcdeg"));
    assert_false(mpb_attempt_id_is_valid(NULL));
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
    long_id[sizeof long_id - 1] = '\0';             /* 52 characters */
    assert_false(mpb_planner_id_is_valid(long_id));
    long_id[MPB_PLANNER_ID_MAX] = '\0';             /* 51 */
    assert_true(mpb_planner_id_is_valid(long_id));
    /* The longest id's channel is as long as LCM takes. */
    assert_int_equal(mpb_request_channel(long_id, ch, sizeof ch), MPB_OK);
    assert_int_equal(strlen(ch), MPB_CHANNEL_MAX);

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

/* Ids for any host name: within LCM's channel limit, readable, and
 * different for two long hosts that begin alike. */
static void planner_ids_fit_any_host(void **state)
{
    (void)state;
    char a[MPB_PLANNER_ID_MAX + 1], b[MPB_PLANNER_ID_MAX + 1], ch[80];
    const char *vm = "ip-172-31-10-20.eu-central-1.compute.internal";
    assert_int_equal(mpb_planner_id_make("ompl", "lab-1", 1234, a, sizeof a),
                     MPB_OK);
    assert_string_equal(a, "ompl@lab-1:1234");
    assert_int_equal(mpb_planner_id_make("null", "a b", 7, a, sizeof a), MPB_OK);
    assert_string_equal(a, "null@a-b:7");
    assert_int_equal(mpb_planner_id_make("null", "", 7, a, sizeof a), MPB_OK);
    assert_string_equal(a, "null@localhost:7");
    /* The longest name and pid with a cloud VM's host: its first
     * characters, then 8 hex digits of the hash of all of it. */
    const char *name32 = "abcdefghijklmnopqrstuvwxyz012345";
    assert_int_equal(mpb_planner_id_make(name32, vm, 4194304, a, sizeof a),
                     MPB_OK);
    assert_true(mpb_planner_id_is_valid(a));
    assert_int_equal(strlen(a), MPB_PLANNER_ID_MAX);
    char hash[MPB_HASH_SIZE], want[128];
    mpb_hash_hex(vm, strlen(vm), hash);
    snprintf(want, sizeof want, "%s@ip-172-31-10-20.eu-central-1.-%.8s"
             ":4194304", "ompl", hash);
    assert_int_equal(mpb_planner_id_make("ompl", vm, 4194304, a, sizeof a),
                     MPB_OK);
    assert_string_equal(a, want);
    assert_int_equal(mpb_request_channel(a, ch, sizeof ch), MPB_OK);
    assert_true(strlen(ch) <= MPB_CHANNEL_MAX);
    /* Two hosts alike but for their ends. */
    assert_int_equal(mpb_planner_id_make("ompl", "ip-172-31-10-20.eu-central-1."
                     "compute.internal.other", 4194304, b, sizeof b), MPB_OK);
    assert_string_not_equal(a, b);
    assert_int_equal(mpb_planner_id_make("", "h", 1, a, sizeof a), MPB_EINVAL);
    assert_int_equal(mpb_planner_id_make("a b", "h", 1, a, sizeof a), MPB_EINVAL);
    assert_string_equal(a, "");
}

/* Text from the network, as a log shows it. */
static void text_is_escaped_for_a_log(void **state)
{
    (void)state;
    char out[128];
    assert_string_equal(mpb_escape("c++", out, sizeof out), "c++");
    assert_string_equal(mpb_escape("\x1b[31mred\nfake", out, sizeof out),
                        "\\x1b[31mred\\x0afake");
    assert_string_equal(mpb_escape("a\\b\x7f", out, sizeof out),
                        "a\\x5cb\\x7f");
    /* UTF-8 kept; C1 controls, invalid bytes, overlong forms escaped. */
    assert_string_equal(mpb_escape("\xe8\xa1\x8c \xc2\x9b \xff \xc0\xaf", out,
                                   sizeof out),
                        "\xe8\xa1\x8c \\xc2\\x9b \\xff \\xc0\\xaf");
    /* Cut before an escape, never inside one. */
    assert_string_equal(mpb_escape("abcdef", out, 7), "abcdef");
    assert_string_equal(mpb_escape("abcdefg", out, 7), "abc...");
    assert_string_equal(mpb_escape("ab\ncd", out, 8), "ab...");
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
        cmocka_unit_test(planner_ids_fit_any_host),
        cmocka_unit_test(text_is_escaped_for_a_log),
        cmocka_unit_test(hashes_are_blake2b_128),
        cmocka_unit_test(stage_sizes_must_agree),
        cmocka_unit_test(statuses_have_names),
        cmocka_unit_test(the_first_daemon_is_the_earliest_started),
    };
    return cmocka_run_group_tests_name("proto", tests, NULL, NULL);
}
