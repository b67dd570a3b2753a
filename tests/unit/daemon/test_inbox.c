/* test_inbox.c - the daemon's receive gate (inbox.c): what it rejects is
 * counted, and logged ten times per channel of the message list, so that
 * a flood on one channel (forged statuses, ten a second) cannot hide a
 * fault on another; then one in a thousand of all. mpbd_log() is this
 * file's own, to read what the daemon would have said. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "daemon.h"

static char logged[64][256];
static int num_logged;

void mpbd_log(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    if (num_logged < 64)
        vsnprintf(logged[num_logged], sizeof logged[0], fmt, ap);
    num_logged++;
    va_end(ap);
}

/* Lines logged that name channel. */
static int lines_on(const char *channel)
{
    char want[96];
    snprintf(want, sizeof want, "on %s:", channel);
    int n = 0;
    for (int i = 0; i < num_logged && i < 64; i++)
        n += strstr(logged[i], want) != NULL;
    return n;
}

static mpbd *daemon_new(void)
{
    num_logged = 0;
    mpbd *d = calloc(1, sizeof *d);
    assert_non_null(d);
    return d;
}

/* The fault test_authentication once missed: a planner with another
 * secret, its result rejected after a flood of forged statuses. */
static void test_flood_does_not_hide_another_channel(void **state)
{
    (void)state;
    mpbd *d = daemon_new();
    for (int i = 0; i < 25; i++)
        mpbd_reject(d, MPB_CHANNEL_STATUS, "a wrong tag");
    mpbd_reject(d, MPB_CHANNEL_RESULT, "a wrong tag");
    assert_int_equal(d->count.rejected, 26);
    assert_int_equal(lines_on(MPB_CHANNEL_STATUS), 10);
    assert_int_equal(lines_on(MPB_CHANNEL_RESULT), 1);
    assert_non_null(strstr(logged[10], "(26 rejected so far)"));
    free(d);
}

/* A request goes to one planner on MPB_REQUEST_<id>: every planner's
 * channel counts as the request channel, apart from the acks'. */
static void test_channels_by_prefix(void **state)
{
    (void)state;
    mpbd *d = daemon_new();
    char a[64], b[64];
    assert_int_equal(mpb_request_channel("ompl@h:1", a, sizeof a), MPB_OK);
    assert_int_equal(mpb_request_channel("ompl@h:2", b, sizeof b), MPB_OK);
    for (int i = 0; i < 8; i++) {
        mpbd_reject(d, a, "short");
        mpbd_reject(d, b, "short");
    }
    mpbd_reject(d, MPB_CHANNEL_ACK "_ompl@h:1", "short");
    mpbd_reject(d, "SOMEONE_ELSES", "short");
    assert_int_equal(lines_on(a) + lines_on(b), 10);
    assert_int_equal(lines_on(MPB_CHANNEL_ACK "_ompl@h:1"), 1);
    assert_int_equal(lines_on("SOMEONE_ELSES"), 1);
    assert_int_equal(d->count.rejected_on[MPB_WIRE_PLAN_REQUEST], 16);
    assert_int_equal(d->count.rejected_on[MPB_WIRE_RUN_ACK], 1);
    assert_int_equal(d->count.rejected_on[MPB_WIRE_COUNT], 1);
    free(d);
}

/* Past ten on a channel, every thousandth rejection of all is logged. */
static void test_one_in_a_thousand(void **state)
{
    (void)state;
    mpbd *d = daemon_new();
    for (int i = 0; i < 2500; i++)
        mpbd_reject(d, MPB_CHANNEL_ANNOUNCE, "replayed");
    assert_int_equal(lines_on(MPB_CHANNEL_ANNOUNCE), 12);
    assert_non_null(strstr(logged[10], "(1000 rejected so far)"));
    assert_non_null(strstr(logged[11], "(2000 rejected so far)"));
    free(d);
}

/* Through the gate: bytes that are no result are refused, counted, and
 * the reason logged; nothing is decoded. */
static void test_receive_rejects_garbage(void **state)
{
    (void)state;
    mpbd *d = daemon_new();
    unsigned char junk[40];
    memset(junk, 0xa5, sizeof junk);
    lcm_recv_buf_t rbuf = {.data = junk, .data_size = sizeof junk};
    mpb_plan_result_t msg;
    memset(&msg, 0, sizeof msg);
    assert_int_equal(mpbd_receive(d, MPB_WIRE_PLAN_RESULT, &rbuf,
                                  MPB_CHANNEL_RESULT, &msg), 0);
    assert_int_equal(d->count.rejected, 1);
    assert_int_equal(lines_on(MPB_CHANNEL_RESULT), 1);
    assert_null(msg.attempt_id);
    free(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_flood_does_not_hide_another_channel),
        cmocka_unit_test(test_channels_by_prefix),
        cmocka_unit_test(test_one_in_a_thousand),
        cmocka_unit_test(test_receive_rejects_garbage),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
