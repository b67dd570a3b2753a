/* auth.c - shared-secret tags on messages (auth.h), and publishing. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sodium.h>

#include "mpbench/mpbench.h"
#include "mpbench/auth.h"

struct mpb_auth {
    unsigned char key[crypto_auth_KEYBYTES];
};

int mpb_auth_load(const char *path, mpb_auth **out, char *err, size_t errlen)
{
    unsigned char buf[4096];
    size_t n;
    FILE *f;

    *out = NULL;
    if (sodium_init() < 0) {
        snprintf(err, errlen, "cannot initialise libsodium");
        return MPB_EIO;
    }
    if ((f = fopen(path, "rb")) == NULL) {
        snprintf(err, errlen, "%s: cannot read secret: %s", path, strerror(errno));
        return MPB_EIO;
    }
    n = fread(buf, 1, sizeof buf, f);
    /* A directory opens, and fails only here. */
    int read_error = ferror(f) ? errno : 0;
    fclose(f);
    if (read_error != 0) {
        snprintf(err, errlen, "%s: cannot read secret: %s", path,
                 strerror(read_error));
        sodium_memzero(buf, sizeof buf);
        return MPB_EIO;
    }
    if (n < 16) {
        snprintf(err, errlen, "%s: a secret needs at least 16 bytes, this has "
                 "%zu", path, n);
        sodium_memzero(buf, sizeof buf);
        return MPB_EINVAL;
    }
    mpb_auth *a = sodium_malloc(sizeof *a);
    if (a == NULL) {
        snprintf(err, errlen, "out of memory");
        return MPB_ENOMEM;
    }
    crypto_generichash(a->key, sizeof a->key, buf, n, NULL, 0);
    sodium_memzero(buf, sizeof buf);
    *out = a;
    return MPB_OK;
}

void mpb_auth_free(mpb_auth *a)
{
    if (a != NULL)
        sodium_free(a);  /* zeroes the key */
}

static void tag(const mpb_auth *a, const char *channel, const void *buf,
                size_t len, unsigned char out[MPB_AUTH_TAG_SIZE])
{
    crypto_auth_hmacsha512256_state st;
    crypto_auth_hmacsha512256_init(&st, a->key, sizeof a->key);
    crypto_auth_hmacsha512256_update(&st, (const unsigned char *)channel,
                                     strlen(channel) + 1);
    crypto_auth_hmacsha512256_update(&st, buf, len);
    crypto_auth_hmacsha512256_final(&st, out);
}

int mpb_auth_check(const mpb_auth *a, const char *channel, const void *buf,
                   size_t len, size_t *msg_len)
{
    unsigned char want[MPB_AUTH_TAG_SIZE];
    if (a == NULL) {
        *msg_len = len;
        return 1;
    }
    if (len < MPB_AUTH_TAG_SIZE)
        return 0;
    *msg_len = len - MPB_AUTH_TAG_SIZE;
    tag(a, channel, buf, *msg_len, want);
    return sodium_memcmp(want, (const unsigned char *)buf + *msg_len,
                         MPB_AUTH_TAG_SIZE) == 0;
}

/* Publish len encoded bytes in buf (which has room for a tag), then free. */
static int send_encoded(lcm_t *lcm, const mpb_auth *a, const char *channel,
                        unsigned char *buf, int len)
{
    size_t total = (size_t)len;
    if (a != NULL) {
        tag(a, channel, buf, (size_t)len, buf + len);
        total += MPB_AUTH_TAG_SIZE;
    }
    int rc = lcm_publish(lcm, channel, buf, (unsigned int)total);
    free(buf);
    return rc == 0 ? MPB_OK : MPB_ELCM;
}

#define MPB__PUBLISH(T, lcm, a, channel, m)                                  \
    do {                                                                     \
        int n_ = T##_encoded_size(m);                                        \
        unsigned char *b_ = malloc((size_t)n_ + MPB_AUTH_TAG_SIZE);          \
        if (b_ == NULL)                                                      \
            return MPB_ENOMEM;                                               \
        if (T##_encode(b_, 0, n_, m) != n_) {                                \
            free(b_);                                                        \
            return MPB_EINVAL;                                               \
        }                                                                    \
        return send_encoded(lcm, a, channel, b_, n_);                        \
    } while (0)

int mpb_publish_announce(lcm_t *lcm, const mpb_auth *a, const char *channel,
                         const mpb_planner_announce_t *m)
{
    MPB__PUBLISH(mpb_planner_announce_t, lcm, a, channel, m);
}

int mpb_publish_request(lcm_t *lcm, const mpb_auth *a, const char *channel,
                        const mpb_plan_request_t *m)
{
    MPB__PUBLISH(mpb_plan_request_t, lcm, a, channel, m);
}

int mpb_publish_result(lcm_t *lcm, const mpb_auth *a, const char *channel,
                       const mpb_plan_result_t *m)
{
    MPB__PUBLISH(mpb_plan_result_t, lcm, a, channel, m);
}

int mpb_publish_ack(lcm_t *lcm, const mpb_auth *a, const char *channel,
                    const mpb_run_ack_t *m)
{
    MPB__PUBLISH(mpb_run_ack_t, lcm, a, channel, m);
}

int mpb_publish_status(lcm_t *lcm, const mpb_auth *a, const char *channel,
                       const mpb_daemon_status_t *m)
{
    MPB__PUBLISH(mpb_daemon_status_t, lcm, a, channel, m);
}
