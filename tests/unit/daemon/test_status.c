/* test_status.c - the daemon's status (status.c): the start time any
 * reader derives from it, utime less elapsed_s, is exactly the daemon's
 * own in every status, however long apart they go out and however slow
 * the process. Two daemons started together on one URL once both
 * stopped, each judging the other older from a start that wobbled by as
 * long as two clock reads were apart. Published on a real LCM instance
 * (memq://, in this process) and read back through the receive gate. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <cmocka.h>

#include "daemon.h"
#include "mpb_daemon_status_t.h"

void mpbd_log(const char *fmt, ...)
{
    (void)fmt;
}

typedef struct heard {
    int                 n;
    int64_t             started[8];
    mpb_daemon_status_t last;
} heard;

static void on_status(const lcm_recv_buf_t *rbuf, const char *channel,
                      void *ud)
{
    heard *h = ud;
    mpb_daemon_status_t st;
    mpb_received r;
    if (mpb_receive(NULL, MPB_RECEIVE_FRESH, MPB_WIRE_DAEMON_STATUS, channel,
                    rbuf->data, (size_t)rbuf->data_size, &st, &r) != MPB_OK)
        return;
    if (h->n < 8)
        h->started[h->n] = mpb_daemon_started_utime(&st);
    h->n++;
    mpb_receive_done(MPB_WIRE_DAEMON_STATUS, &st);
}

static void nap(long ns)
{
    struct timespec t = {0, ns};
    nanosleep(&t, NULL);
}

static void test_start_is_exact_in_every_status(void **state)
{
    (void)state;
    mpbd *d = calloc(1, sizeof *d);
    mpbd_experiment exp = {.name = "e"};
    assert_non_null(d);
    d->exp = &exp;
    strcpy(d->daemon_id, "mpbenchd@test:1");
    d->lcm = mpb_lcm_create("memq://", NULL, 0, NULL);
    assert_non_null(d->lcm);
    heard h = {0};
    lcm_subscribe(d->lcm, MPB_CHANNEL_STATUS, on_status, &h);
    /* Started a while ago, at a wall time with microseconds in it. */
    d->started = mpb_monotonic_s() - 0.123456789;
    d->started_utime = 1764000000123457;
    for (int i = 0; i < 8; i++) {
        mpbd_status_publish(d, "running", mpb_monotonic_s());
        nap(1000000L * (i + 1) + 333);   /* 1-8 ms and odd microseconds */
    }
    while (lcm_handle_timeout(d->lcm, 0) > 0)
        ;
    assert_int_equal(h.n, 8);
    for (int i = 0; i < 8; i++)
        assert_int_equal(h.started[i], d->started_utime);
    mpb_lcm_destroy(d->lcm);
    free(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_start_is_exact_in_every_status),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
