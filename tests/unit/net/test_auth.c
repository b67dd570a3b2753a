/* test_auth.c - the authenticated trailer (auth.h): the test vector of
 * docs/protocol.md, which messages a receiver believes, and sealing a
 * message sent through another binding. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"

/* A secret file with these bytes, loaded. */
static mpb_auth *load(const char *bytes)
{
    char path[] = "/tmp/mpb-test-auth-XXXXXX", err[256];
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, bytes, strlen(bytes)), (ssize_t)strlen(bytes));
    close(fd);
    mpb_auth *a = NULL;
    assert_int_equal(mpb_auth_open(path, &a, err, sizeof err), MPB_OK);
    unlink(path);
    return a;
}

static void hex(const unsigned char *b, size_t n, char *out)
{
    for (size_t i = 0; i < n; i++)
        sprintf(out + 2 * i, "%02x", b[i]);
}

/* The value of key in tests/support/data/auth_vector.txt, into out. */
static void vector(const char *key, char *out, size_t len)
{
    char path[1024], line[1024];
    snprintf(path, sizeof path, "%s/auth_vector.txt", MPB_TEST_DATA);
    FILE *f = fopen(path, "r");
    if (f == NULL)
        fail_msg("cannot open %s", path);
    size_t k = strlen(key);
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, key, k) == 0 && line[k] == ' ') {
            line[strcspn(line, "\n")] = '\0';
            snprintf(out, len, "%s", line + k + 1);
            fclose(f);
            return;
        }
    }
    fclose(f);
    fail_msg("%s: no '%s'", path, key);
}

/* The example of docs/protocol.md, "Authentication", kept in
 * tests/support/data/auth_vector.txt, which the Python kit's test reads
 * too: computed with Python's hashlib and hmac, so that it checks
 * libsodium's crypto_auth_hmacsha512256 is HMAC-SHA-512 cut to 32 bytes. */
static void the_protocol_test_vector(void **state)
{
    (void)state;
    char secret[256], channel[64], message[1024], want[1024], v[64];
    vector("secret", secret, sizeof secret);
    vector("channel", channel, sizeof channel);
    vector("message", message, sizeof message);
    vector("trailer", want, sizeof want);
    mpb_auth *a = load(secret);
    mpb_run_ack_t ack = {.utime = 1,
                         .attempt_id = "0123456789abcdef0123456789abcdef",
                         .sender_id = "null@h:1", .kind = 0};
    unsigned char enc[256], trailer[MPB_AUTH_TRAILER_SIZE];
    char text[2 * sizeof enc + 1];
    int n = mpb_run_ack_t_encode(enc, 0, sizeof enc, &ack);
    assert_int_equal(n, 67);
    hex(enc, (size_t)n, text);
    assert_string_equal(text, message);
    vector("instance", v, sizeof v);
    uint64_t instance = strtoull(v, NULL, 16);
    vector("counter", v, sizeof v);
    uint64_t counter = strtoull(v, NULL, 10);
    vector("echo", v, sizeof v);
    uint64_t echo = strtoull(v, NULL, 16);
    mpb_auth_trailer(a, channel, enc, (size_t)n, instance, counter, echo,
                     trailer);
    hex(trailer, sizeof trailer, text);
    assert_string_equal(text, want);
    mpb_auth_close(a);
}

/* A message as a peer with auth b sends it, into buf; its length. */
static size_t sealed(mpb_auth *b, uint64_t counter, uint64_t echo,
                     unsigned char *buf)
{
    memcpy(buf, "message", 7);
    mpb_auth_trailer(b, "CH", buf, 7, mpb_auth_instance(b), counter, echo,
                     buf + 7);
    return 7 + MPB_AUTH_TRAILER_SIZE;
}

static void a_sender_is_believed_once_it_echoes_the_receiver(void **state)
{
    (void)state;
    mpb_auth *me = load("the same secret, 32 bytes long..");
    mpb_auth *peer = load("the same secret, 32 bytes long..");
    mpb_auth *other = load("another secret of 32 bytes......");
    unsigned char buf[128];
    size_t len, n;
    mpb_auth_info info;
    uint64_t mine = mpb_auth_instance(me);
    assert_true(mine != 0);
    assert_true(mine != mpb_auth_instance(peer));

    /* Echoing another process (a recorded message played again to a new
     * one), or none: not believed, nor remembered. */
    n = sealed(peer, 1, 12345, buf);
    assert_int_equal(mpb_auth_check(me, "CH", buf, n, &len, &info),
                     MPB_AUTH_UNPROVEN);
    assert_int_equal(len, 7);
    assert_true(info.instance == mpb_auth_instance(peer));
    assert_true(info.counter == 1 && info.echo == 12345);
    n = sealed(peer, 2, 0, buf);
    assert_int_equal(mpb_auth_check(me, "CH", buf, n, &len, &info),
                     MPB_AUTH_UNPROVEN);
    /* Echoing this one: believed, and from then on by its counter. */
    n = sealed(peer, 5, mine, buf);
    assert_int_equal(mpb_auth_check(me, "CH", buf, n, &len, &info),
                     MPB_AUTH_FRESH);
    assert_int_equal(mpb_auth_check(me, "CH", buf, n, &len, &info),
                     MPB_AUTH_REPLAYED);
    n = sealed(peer, 7, 0, buf);
    assert_int_equal(mpb_auth_check(me, "CH", buf, n, &len, &info),
                     MPB_AUTH_FRESH);
    /* Reordered by UDP: 6 comes after 7, once; 2 was sent before 5. */
    n = sealed(peer, 6, 0, buf);
    assert_int_equal(mpb_auth_check(me, "CH", buf, n, &len, &info),
                     MPB_AUTH_FRESH);
    assert_int_equal(mpb_auth_check(me, "CH", buf, n, &len, &info),
                     MPB_AUTH_REPLAYED);
    n = sealed(peer, 2, mine, buf);
    assert_int_equal(mpb_auth_check(me, "CH", buf, n, &len, &info),
                     MPB_AUTH_FRESH);
    assert_int_equal(mpb_auth_check(me, "CH", buf, n, &len, &info),
                     MPB_AUTH_REPLAYED);
    /* More than 64 behind the newest: too old to tell, so refused. */
    n = sealed(peer, 100, 0, buf);
    assert_int_equal(mpb_auth_check(me, "CH", buf, n, &len, &info),
                     MPB_AUTH_FRESH);
    n = sealed(peer, 36, 0, buf);
    assert_int_equal(mpb_auth_check(me, "CH", buf, n, &len, &info),
                     MPB_AUTH_REPLAYED);
    /* Another secret, another channel, a changed byte, a short message. */
    n = sealed(other, 200, mine, buf);
    assert_int_equal(mpb_auth_check(me, "CH", buf, n, &len, &info),
                     MPB_AUTH_BAD_TAG);
    n = sealed(peer, 201, 0, buf);
    assert_int_equal(mpb_auth_check(me, "CX", buf, n, &len, &info),
                     MPB_AUTH_BAD_TAG);
    buf[8] ^= 1;        /* the instance */
    assert_int_equal(mpb_auth_check(me, "CH", buf, n, &len, &info),
                     MPB_AUTH_BAD_TAG);
    assert_int_equal(mpb_auth_check(me, "CH", buf, MPB_AUTH_TRAILER_SIZE - 1,
                                    &len, &info), MPB_AUTH_BAD_TAG);
    /* Without a secret, everything passes whole. */
    assert_int_equal(mpb_auth_check(NULL, "CH", buf, 9, &len, &info),
                     MPB_AUTH_FRESH);
    assert_int_equal(len, 9);
    assert_true(mpb_auth_instance(NULL) == 0);
    mpb_auth_close(me);
    mpb_auth_close(peer);
    mpb_auth_close(other);
    mpb_auth_close(NULL);
}

/* What a memq:// subscriber received last. */
typedef struct received {
    unsigned char data[256];
    size_t len;
} received;

static void on_message(const lcm_recv_buf_t *rbuf, const char *channel,
                       void *user)
{
    (void)channel;
    received *r = user;
    assert_true(rbuf->data_size <= sizeof r->data);
    memcpy(r->data, rbuf->data, rbuf->data_size);
    r->len = rbuf->data_size;
}

static uint64_t be64(const unsigned char *p)
{
    uint64_t v = 0;
    for (int i = 0; i < 8; i++)
        v = v << 8 | p[i];
    return v;
}

/* mpb_auth_seal(), for a sender that publishes through its own binding:
 * this process's instance, the counter it shares with the mpb_publish_...
 * functions, and a tag a receiver with the secret believes. */
static void a_seal_counts_with_publishing_and_is_believed(void **state)
{
    (void)state;
    mpb_auth *me = load("the same secret, 32 bytes long..");
    mpb_auth *peer = load("the same secret, 32 bytes long..");
    unsigned char buf[128], want[MPB_AUTH_TRAILER_SIZE];
    size_t len;
    mpb_auth_info info;

    memcpy(buf, "message", 7);
    assert_int_equal(mpb_auth_seal(peer, "CH", buf, 7, mpb_auth_instance(me),
                                   buf + 7), MPB_OK);
    mpb_auth_trailer(peer, "CH", buf, 7, mpb_auth_instance(peer), 1,
                     mpb_auth_instance(me), want);
    assert_memory_equal(buf + 7, want, sizeof want);
    assert_int_equal(mpb_auth_check(me, "CH", buf, 7 + MPB_AUTH_TRAILER_SIZE,
                                    &len, &info), MPB_AUTH_FRESH);
    assert_int_equal(len, 7);
    assert_true(info.instance == mpb_auth_instance(peer) && info.counter == 1);

    /* A message published in between takes counter 2, the next seal 3. */
    lcm_t *lcm = lcm_create("memq://");
    assert_non_null(lcm);
    received r = {.len = 0};
    lcm_subscribe(lcm, "MPB_ACK", on_message, &r);
    mpb_run_ack_t ack = {.utime = 1, .attempt_id = "r", .sender_id = "s",
                         .kind = 0};
    assert_int_equal(mpb_publish_ack(lcm, peer, 0, "MPB_ACK", &ack), MPB_OK);
    assert_int_equal(lcm_handle(lcm), 0);
    assert_true(r.len > MPB_AUTH_TRAILER_SIZE);
    assert_true(be64(r.data + r.len - MPB_AUTH_TRAILER_SIZE + 8) == 2);
    lcm_destroy(lcm);
    assert_int_equal(mpb_auth_seal(peer, "CH", buf, 7, 0, buf + 7), MPB_OK);
    assert_true(be64(buf + 7) == mpb_auth_instance(peer));
    assert_true(be64(buf + 15) == 3 && be64(buf + 23) == 0);
    /* Believed already: the same bytes again are a replay. */
    assert_int_equal(mpb_auth_check(me, "CH", buf, 7 + MPB_AUTH_TRAILER_SIZE,
                                    &len, &info), MPB_AUTH_FRESH);
    assert_int_equal(mpb_auth_check(me, "CH", buf, 7 + MPB_AUTH_TRAILER_SIZE,
                                    &len, &info), MPB_AUTH_REPLAYED);

    /* No secret, no channel: refused, out untouched. */
    memset(want, 0xab, sizeof want);
    assert_int_equal(mpb_auth_seal(NULL, "CH", buf, 7, 0, want), MPB_EINVAL);
    assert_int_equal(mpb_auth_seal(peer, NULL, buf, 7, 0, want), MPB_EINVAL);
    for (size_t i = 0; i < sizeof want; i++)
        assert_int_equal(want[i], 0xab);
    mpb_auth_close(me);
    mpb_auth_close(peer);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(the_protocol_test_vector),
        cmocka_unit_test(a_sender_is_believed_once_it_echoes_the_receiver),
        cmocka_unit_test(a_seal_counts_with_publishing_and_is_believed),
    };
    return cmocka_run_group_tests_name("auth", tests, NULL, NULL);
}
