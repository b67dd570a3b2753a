/* test_hub.c - the library's hub link (link.h) against a hub played by
 * the test on loopback: greeting and subscriptions (each channel escaped
 * as a Java regular expression), messages both ways, a frame over each
 * length bound read past and dropped, a frame that is no message closing
 * the connection, reconnecting, URLs refused. With lcm-java's real hub:
 * tests/integration/test_hub*.sh. */
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"

static void put32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

static uint32_t get32(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static void read_all(int fd, void *buf, size_t n)
{
    size_t got = 0;
    while (got < n) {
        struct pollfd p = {.fd = fd, .events = POLLIN};
        assert_true(poll(&p, 1, 5000) == 1);
        ssize_t r = recv(fd, (char *)buf + got, n - got, 0);
        assert_true(r > 0);
        got += (size_t)r;
    }
}

static void write_all(int fd, const void *buf, size_t n)
{
    assert_int_equal(send(fd, buf, n, MSG_NOSIGNAL), (ssize_t)n);
}

/* A listening socket on a free loopback port. */
static int listen_on(int *port)
{
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    struct sockaddr_in a = {.sin_family = AF_INET,
                            .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    socklen_t len = sizeof a;
    assert_true(fd >= 0);
    assert_int_equal(bind(fd, (struct sockaddr *)&a, sizeof a), 0);
    assert_int_equal(listen(fd, 4), 0);
    assert_int_equal(getsockname(fd, (struct sockaddr *)&a, &len), 0);
    *port = ntohs(a.sin_port);
    return fd;
}

/* Accept the link's connection and greet it as the hub does. */
static int accept_link(int ls)
{
    struct pollfd p = {.fd = ls, .events = POLLIN};
    assert_true(poll(&p, 1, 5000) == 1);
    int c = accept(ls, NULL, NULL);
    unsigned char hello[8];
    assert_true(c >= 0);
    read_all(c, hello, 8);
    assert_int_equal(get32(hello), 0x287617fbu);
    put32(hello, 0x287617fau);
    put32(hello + 4, 0x0100);
    write_all(c, hello, 8);
    return c;
}

/* Read one frame of type want, its first string into name. */
static void read_frame(int c, uint32_t want, char *name, size_t cap)
{
    unsigned char w[8];
    read_all(c, w, 8);
    assert_int_equal(get32(w), want);
    uint32_t n = get32(w + 4);
    assert_true(n < cap);
    read_all(c, name, n);
    name[n] = '\0';
}

/* Send a message frame whose lengths may claim more than is sent. */
static void send_frame(int c, const char *channel, uint32_t channel_len,
                       const void *data, uint32_t data_len, size_t sent)
{
    unsigned char w[8];
    put32(w, 1);
    put32(w + 4, channel_len);
    write_all(c, w, 8);
    write_all(c, channel, channel_len);
    put32(w, data_len);
    write_all(c, w, 4);
    if (sent > 0)
        write_all(c, data, sent);
}

typedef struct heard {
    int n;
    char last[64];
} heard;

static void on_b(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    heard *h = user;
    (void)channel;
    h->n++;
    snprintf(h->last, sizeof h->last, "%.*s", (int)rbuf->data_size,
             (const char *)rbuf->data);
}

/* A message handed over, whatever was dropped before it. */
static void expect(lcm_t *lcm, heard *h, const char *what)
{
    int before = h->n;
    while (h->n == before)
        assert_true(lcm_handle_timeout(lcm, 5000) > 0);
    assert_string_equal(h->last, what);
}

static void test_both_ways(void **state)
{
    (void)state;
    int port, ls = listen_on(&port);
    char url[64], name[256];
    snprintf(url, sizeof url, "tcpq://127.0.0.1:%d", port);
    const char *keep[] = {"MPB_REQUEST_null@vm-1.x:12", "B"};
    int filtered = 0;
    lcm_t *lcm = mpb_lcm_create(url, keep, 2, &filtered);
    assert_non_null(lcm);
    assert_int_equal(filtered, 1);
    heard h = {0};
    lcm_subscription_t *sub = lcm_subscribe(lcm, "B", on_b, &h);

    int c = accept_link(ls);
    read_frame(c, 2, name, sizeof name);
    assert_string_equal(name, "MPB_REQUEST_null\\@vm\\-1\\.x\\:12");
    read_frame(c, 2, name, sizeof name);
    assert_string_equal(name, "B");
    assert_int_equal(mpb_lcm_hub_wait(lcm, 5.0), 1);

    send_frame(c, "B", 1, "hello", 5, 5);
    expect(lcm, &h, "hello");

    assert_int_equal(mpb_lcm_publish(lcm, "C", "xyz", 3), MPB_OK);
    read_frame(c, 1, name, sizeof name);
    assert_string_equal(name, "C");
    unsigned char w[4], data[3];
    read_all(c, w, 4);
    assert_int_equal(get32(w), 3);
    read_all(c, data, 3);
    assert_memory_equal(data, "xyz", 3);

    mpb_hub_stats st;
    mpb_lcm_hub_stats(lcm, &st);
    assert_int_equal(st.is_hub, 1);
    assert_int_equal(st.connected, 1);
    assert_int_equal(st.connects, 1);
    lcm_unsubscribe(lcm, sub);
    mpb_lcm_destroy(lcm);
    close(c);
    close(ls);
}

static void test_hostile_frames(void **state)
{
    (void)state;
    int port, ls = listen_on(&port);
    char url[64], name[256];
    snprintf(url, sizeof url, "tcpq://127.0.0.1:%d", port);
    const char *keep[] = {"B"};
    lcm_t *lcm = mpb_lcm_create(url, keep, 1, NULL);
    heard h = {0};
    lcm_subscription_t *sub = lcm_subscribe(lcm, "B", on_b, &h);
    int c = accept_link(ls);
    read_frame(c, 2, name, sizeof name);

    /* A message one byte over the bound, sent whole: read past. */
    size_t big = MPB_LCM_MESSAGE_MAX + 1;
    char *junk = calloc(1, big);
    assert_non_null(junk);
    send_frame(c, "B", 1, junk, (uint32_t)big, big);
    free(junk);
    /* A channel of 64 characters: read past. */
    char ch64[65];
    memset(ch64, 'B', 64);
    send_frame(c, ch64, 64, "abc", 3, 3);
    /* A NUL inside the channel: dropped. */
    send_frame(c, "B\0x", 3, "nul", 3, 3);
    send_frame(c, "B", 1, "ok", 2, 2);
    expect(lcm, &h, "ok");
    assert_int_equal(h.n, 1);
    mpb_hub_stats st;
    mpb_lcm_hub_stats(lcm, &st);
    assert_int_equal(st.oversized, 3);

    /* A frame that is no message: the link closes and comes back. */
    unsigned char w[8];
    put32(w, 9);
    put32(w + 4, 0);
    write_all(c, w, 8);
    close(c);
    c = accept_link(ls);
    read_frame(c, 2, name, sizeof name);
    assert_string_equal(name, "B");
    assert_int_equal(mpb_lcm_hub_wait(lcm, 5.0), 1);
    mpb_lcm_hub_stats(lcm, &st);
    assert_int_equal(st.malformed, 1);
    assert_int_equal(st.connects, 2);

    /* 4 GiB claimed, 10 bytes sent, then the hub goes: nothing is
     * allocated for it, and the link comes back. */
    send_frame(c, "B", 1, "0123456789", 0xffffffffu, 10);
    close(c);
    c = accept_link(ls);
    read_frame(c, 2, name, sizeof name);
    send_frame(c, "B", 1, "again", 5, 5);
    expect(lcm, &h, "again");
    mpb_lcm_hub_stats(lcm, &st);
    assert_int_equal(st.connects, 3);

    lcm_unsubscribe(lcm, sub);
    mpb_lcm_destroy(lcm);
    close(c);
    close(ls);
}

static void test_urls(void **state)
{
    (void)state;
    assert_true(mpb_lcm_url_is_hub("tcpq://h:1"));
    assert_false(mpb_lcm_url_is_hub("udpm://239.255.76.67:7667"));
    assert_false(mpb_lcm_url_is_hub(NULL));
    assert_null(mpb_lcm_create("tcpq://127.0.0.1:99999", NULL, 0, NULL));
    assert_null(mpb_lcm_create("tcpq://127.0.0.1:7x", NULL, 0, NULL));
    assert_null(mpb_lcm_create("tcpq://127.0.0.1:", NULL, 0, NULL));

    /* No hub there: publishing fails at once, nothing waits. */
    int port, ls = listen_on(&port);
    close(ls);
    char url[64];
    snprintf(url, sizeof url, "tcpq://127.0.0.1:%d", port);
    lcm_t *lcm = mpb_lcm_create(url, NULL, 0, NULL);
    assert_non_null(lcm);
    assert_int_equal(mpb_lcm_hub_wait(lcm, 0.2), 0);
    assert_int_equal(mpb_lcm_publish(lcm, "C", "x", 1), MPB_ELCM);
    mpb_lcm_destroy(lcm);
    mpb_lcm_destroy(NULL);

    /* Not a hub: the same calls are liblcm's. */
    lcm = lcm_create("memq://");
    mpb_hub_stats st;
    mpb_lcm_hub_stats(lcm, &st);
    assert_int_equal(st.is_hub, 0);
    assert_int_equal(mpb_lcm_hub_wait(lcm, 0), 1);
    assert_int_equal(mpb_lcm_publish(lcm, "C", "x", 1), MPB_OK);
    mpb_lcm_destroy(lcm);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_both_ways),
        cmocka_unit_test(test_hostile_frames),
        cmocka_unit_test(test_urls),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
