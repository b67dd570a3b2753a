/* test_lcm_filter.c - the validity check of LCM datagrams
 * (mpb_lcm_datagram_is_valid): what LCM senders send passes, each
 * malformed field of issue 28 fails alone; the filter program's size and
 * its keep-every-channel cases; attaching it to a socket. Over the network:
 * tests/integration/test_lcm_filter.sh and test_hostile_datagrams.sh;
 * the program against this check: tests/fuzz/fuzz_lcm_filter.c. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"

static unsigned char b[70000];

static void put32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

/* A short message on channel with n payload bytes; its length. */
static size_t short_message(const char *channel, size_t n)
{
    put32(b, 0x4c433032u);
    put32(b + 4, 7);
    memcpy(b + 8, channel, strlen(channel) + 1);
    memset(b + 9 + strlen(channel), 'x', n);
    return 9 + strlen(channel) + n;
}

/* A fragment: header, the channel if not NULL, n payload bytes. */
static size_t fragment(uint32_t size, uint32_t offset, uint32_t number,
                       uint32_t count, const char *channel, size_t n)
{
    size_t at = 20;
    put32(b, 0x4c433033u);
    put32(b + 4, 9);
    put32(b + 8, size);
    put32(b + 12, offset);
    b[16] = (unsigned char)(number >> 8);
    b[17] = (unsigned char)number;
    b[18] = (unsigned char)(count >> 8);
    b[19] = (unsigned char)count;
    if (channel != NULL) {
        memcpy(b + at, channel, strlen(channel) + 1);
        at += strlen(channel) + 1;
    }
    memset(b + at, 'y', n);
    return at + n;
}

static int valid(size_t len)
{
    return mpb_lcm_datagram_is_valid(b, len);
}

static void test_short_messages(void **state)
{
    (void)state;
    char c63[64], c64[65];
    memset(c63, 'c', 63);
    c63[63] = '\0';
    memset(c64, 'c', 64);
    c64[64] = '\0';

    assert_true(valid(short_message("MPB_RESULT", 100)));
    assert_true(valid(short_message("MPB_RESULT", 0)));
    assert_true(valid(short_message(c63, 5)));
    assert_false(valid(short_message(c64, 5)));           /* over 63 */
    size_t n = short_message("MPB_RESULT", 0);
    assert_false(valid(n - 1));                           /* no NUL in it */
    assert_false(valid(8));                               /* no channel */
    assert_false(valid(7));                               /* no header */
    assert_false(mpb_lcm_datagram_is_valid(NULL, 20));
    put32(b, 0x4c433031u);                                /* "LC01" */
    assert_false(valid(n));
}

static void test_fragments(void **state)
{
    (void)state;
    /* A message of 100000 bytes in two fragments, as LCM sends it. */
    size_t first = fragment(100000, 0, 0, 2, "MPB_RESULT", 65476);
    assert_true(valid(first));
    assert_true(valid(fragment(100000, 65476, 1, 2, NULL, 100000 - 65476)));

    /* Issue 28: an offset near 2^32 wraps a 32-bit bounds check. */
    assert_false(valid(fragment(100, 0xfffffff0u, 0, 2, "MPB_RESULT", 40)));
    assert_false(valid(fragment(3000, 0xffffff00u, 1, 2, NULL, 1500)));
    assert_false(valid(fragment(3000, 0xffffff00u, 1, 3, NULL, 1500)));
    assert_false(valid(fragment(3000, 1501, 1, 2, NULL, 1500)));  /* past */
    assert_true(valid(fragment(3000, 1500, 1, 2, NULL, 1500)));

    assert_false(valid(fragment(3000, 1500, 5, 2, NULL, 1500)));  /* number */
    assert_false(valid(fragment(3000, 1500, 2, 2, NULL, 1500)));
    assert_false(valid(fragment(3000, 0, 0, 0, "A", 1500)));      /* count 0 */
    assert_false(valid(fragment(0, 0, 0, 1, "A", 0)));            /* size 0 */
    assert_false(valid(fragment(2, 0, 0, 3, "A", 1)));    /* count > size */
    /* 2 fragments cannot carry 200000 bytes. */
    assert_false(valid(fragment(200000, 0, 0, 2, "A", 1000)));
    assert_true(valid(fragment(200000, 0, 0, 4, "A", 1000)));
    /* Over MPB_LCM_MESSAGE_MAX, under liblcm's own limit. */
    assert_true(valid(fragment(MPB_LCM_MESSAGE_MAX, 0, 0, 300, "A", 1000)));
    assert_false(valid(fragment(MPB_LCM_MESSAGE_MAX + 1, 0, 0, 300, "A", 1000)));
    assert_false(valid(fragment(255u << 20, 0, 0, 4000, "A", 1000)));

    assert_false(valid(fragment(3000, 5, 0, 2, "A", 1000)));  /* 0 not at 0 */
    assert_false(valid(fragment(3000, 0, 0, 2, "A", 0)));     /* no payload */
    assert_false(valid(fragment(3000, 1500, 1, 2, NULL, 0)));
    /* Only the last fragment ends the message, and it does. */
    assert_false(valid(fragment(1000, 0, 0, 2, "A", 1000)));
    assert_true(valid(fragment(1000, 0, 0, 1, "A", 1000)));
    assert_false(valid(fragment(3000, 0, 0, 1, "A", 1000)));
    assert_false(valid(fragment(3000, 1000, 2, 3, NULL, 1000)));

    /* Fragment 0's channel: NUL-ended within the datagram and 63. */
    size_t n = fragment(3000, 0, 0, 2, "MPB_RESULT", 0);
    assert_false(valid(n));                              /* NUL, no payload */
    assert_false(valid(n - 1));                          /* no NUL */
    assert_false(valid(20));
    assert_false(valid(19));
}

static void test_program(void **state)
{
    (void)state;
    static struct sock_filter ops[MPB_LCM_FILTER_PROGRAM_MAX];
    static char names[MPB_LCM_FILTER_CHANNELS + 1][MPB_LCM_CHANNEL_MAX + 2];
    const char *ch[MPB_LCM_FILTER_CHANNELS + 1];
    for (int i = 0; i <= MPB_LCM_FILTER_CHANNELS; i++) {
        memset(names[i], 'a' + i, MPB_LCM_CHANNEL_MAX);
        ch[i] = names[i];
    }
    int all = mpb_lcm_filter_program(NULL, 0, ops, MPB_LCM_FILTER_PROGRAM_MAX);
    assert_true(all > 0);
    /* The most it holds, the longest names: room enough. */
    int most = mpb_lcm_filter_program(ch, MPB_LCM_FILTER_CHANNELS, ops,
                                      MPB_LCM_FILTER_PROGRAM_MAX);
    assert_true(most > all && most <= MPB_LCM_FILTER_PROGRAM_MAX);
    assert_int_equal(mpb_lcm_filter_program(ch, MPB_LCM_FILTER_CHANNELS, ops,
                                            all), -1);
    /* One more channel, or a name LCM cannot carry: every channel kept. */
    assert_int_equal(mpb_lcm_filter_program(ch, MPB_LCM_FILTER_CHANNELS + 1,
                                            ops, MPB_LCM_FILTER_PROGRAM_MAX), all);
    names[0][MPB_LCM_CHANNEL_MAX] = 'a';
    assert_int_equal(mpb_lcm_filter_program(ch, 1, ops,
                                            MPB_LCM_FILTER_PROGRAM_MAX), all);
}

static void test_attach(void **state)
{
    (void)state;
    static const char *const keep[] = {"MPB_STATUS"};
    int udp = socket(AF_INET, SOCK_DGRAM, 0), fds[2];
    assert_true(udp >= 0);
    assert_int_equal(mpb_lcm_filter_socket(udp, keep, 1), MPB_OK);
    assert_int_equal(mpb_lcm_filter_socket(udp, NULL, 0), MPB_OK);
    close(udp);
    assert_int_equal(pipe(fds), 0);
    assert_int_equal(mpb_lcm_filter_socket(fds[0], NULL, 0), MPB_ELCM);
    close(fds[0]);
    close(fds[1]);
    assert_int_equal(mpb_lcm_sockets("memq://", fds, 2), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_short_messages),
        cmocka_unit_test(test_fragments),
        cmocka_unit_test(test_program),
        cmocka_unit_test(test_attach),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
