/* auth.c - shared-secret trailers on messages (auth.h): sealing,
 * checking, the senders believed, and publishing. */
#include <errno.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sodium.h>

#include "mpbench/mpbench.h"
#include "mpbench/auth.h"
#include "mpbench/wire.h"
#include "net/auth_internal.h"
#include "net/hub_internal.h"

/* A sender instance believed, and the counters had from it: bit k of seen
 * is counter top - k. */
typedef struct mpb__peer {
    uint64_t instance, top, seen;
} mpb__peer;

struct mpb_auth {
    unsigned char key[crypto_auth_hmacsha512256_KEYBYTES];
    uint64_t instance;
    _Atomic uint64_t counter;  /* the last one sent */
    mpb__peer *peers;          /* malloc'd: not secret */
    size_t num_peers, cap_peers;
};

int mpb_auth_open(const char *path, mpb_auth **out, char *err, size_t errlen)
{
    unsigned char buf[4096], key[crypto_auth_hmacsha512256_KEYBYTES];
    crypto_generichash_state st;
    size_t n, total = 0;
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
    crypto_generichash_init(&st, NULL, 0, sizeof key);
    while ((n = fread(buf, 1, sizeof buf, f)) > 0) {
        crypto_generichash_update(&st, buf, n);
        total += n;
    }
    /* A directory opens, and fails only here. */
    int read_error = ferror(f) ? errno : 0;
    fclose(f);
    crypto_generichash_final(&st, key, sizeof key);
    sodium_memzero(buf, sizeof buf);
    sodium_memzero(&st, sizeof st);
    if (read_error != 0 || total < 16) {
        if (read_error != 0)
            snprintf(err, errlen, "%s: cannot read secret: %s", path,
                     strerror(read_error));
        else
            snprintf(err, errlen, "%s: a secret needs at least 16 bytes, "
                     "this has %zu", path, total);
        sodium_memzero(key, sizeof key);
        return read_error != 0 ? MPB_EIO : MPB_EINVAL;
    }
    mpb_auth *a = sodium_malloc(sizeof *a);
    if (a == NULL) {
        snprintf(err, errlen, "out of memory");
        sodium_memzero(key, sizeof key);
        return MPB_ENOMEM;
    }
    memcpy(a->key, key, sizeof key);
    sodium_memzero(key, sizeof key);
    do
        randombytes_buf(&a->instance, sizeof a->instance);
    while (a->instance == 0);
    atomic_init(&a->counter, 0);
    a->peers = NULL;
    a->num_peers = a->cap_peers = 0;
    *out = a;
    return MPB_OK;
}

void mpb_auth_close(mpb_auth *a)
{
    if (a == NULL)
        return;
    free(a->peers);
    sodium_free(a);  /* zeroes the key */
}

uint64_t mpb_auth_instance(const mpb_auth *a)
{
    return a != NULL ? a->instance : 0;
}

static void put_be64(unsigned char *p, uint64_t v)
{
    for (int i = 7; i >= 0; i--, v >>= 8)
        p[i] = (unsigned char)(v & 0xff);
}

static uint64_t get_be64(const unsigned char *p)
{
    uint64_t v = 0;
    for (int i = 0; i < 8; i++)
        v = v << 8 | p[i];
    return v;
}

/* The tag of channel, NUL, the len bytes at buf and the 24 trailer bytes
 * at head: HMAC-SHA-512 truncated to 32 bytes (libsodium's
 * crypto_auth_hmacsha512256). */
static void tag(const mpb_auth *a, const char *channel, const void *buf,
                size_t len, const unsigned char head[24],
                unsigned char out[MPB_AUTH_TAG_SIZE])
{
    crypto_auth_hmacsha512256_state st;
    crypto_auth_hmacsha512256_init(&st, a->key, sizeof a->key);
    crypto_auth_hmacsha512256_update(&st, (const unsigned char *)channel,
                                     strlen(channel) + 1);
    crypto_auth_hmacsha512256_update(&st, buf, len);
    crypto_auth_hmacsha512256_update(&st, head, 24);
    crypto_auth_hmacsha512256_final(&st, out);
}

void mpb_auth_trailer(const mpb_auth *a, const char *channel, const void *buf,
                      size_t len, uint64_t instance, uint64_t counter,
                      uint64_t echo, unsigned char out[MPB_AUTH_TRAILER_SIZE])
{
    put_be64(out, instance);
    put_be64(out + 8, counter);
    put_be64(out + 16, echo);
    tag(a, channel, buf, len, out, out + 24);
}

int mpb_auth_seal(mpb_auth *a, const char *channel, const void *buf,
                  size_t len, uint64_t echo,
                  unsigned char out[MPB_AUTH_TRAILER_SIZE])
{
    if (a == NULL || channel == NULL)
        return MPB_EINVAL;
    uint64_t c = atomic_fetch_add(&a->counter, 1) + 1;
    mpb_auth_trailer(a, channel, buf, len, a->instance, c, echo, out);
    return MPB_OK;
}

static mpb__peer *find_peer(mpb_auth *a, uint64_t instance)
{
    for (size_t i = 0; i < a->num_peers; i++)
        if (a->peers[i].instance == instance)
            return &a->peers[i];
    return NULL;
}

/* 1 if counter c of p is new (and now had), 0 if had already or too old. */
static int peer_take(mpb__peer *p, uint64_t c)
{
    if (c > p->top) {
        uint64_t shift = c - p->top;
        p->seen = shift >= 64 ? 1 : (p->seen << shift) | 1;
        p->top = c;
        return 1;
    }
    uint64_t k = p->top - c;
    if (k >= 64 || (p->seen & ((uint64_t)1 << k)))
        return 0;
    p->seen |= (uint64_t)1 << k;
    return 1;
}

mpb_auth_verdict mpb_auth_check(mpb_auth *a, const char *channel,
                                const void *buf, size_t len, size_t *msg_len,
                                mpb_auth_info *info)
{
    unsigned char want[MPB_AUTH_TAG_SIZE];
    memset(info, 0, sizeof *info);
    if (a == NULL) {
        *msg_len = len;
        return MPB_AUTH_FRESH;
    }
    *msg_len = 0;
    if (len < MPB_AUTH_TRAILER_SIZE)
        return MPB_AUTH_BAD_TAG;
    size_t body = len - MPB_AUTH_TRAILER_SIZE;
    const unsigned char *head = (const unsigned char *)buf + body;
    tag(a, channel, buf, body, head, want);
    if (sodium_memcmp(want, head + 24, MPB_AUTH_TAG_SIZE) != 0)
        return MPB_AUTH_BAD_TAG;
    *msg_len = body;
    info->instance = get_be64(head);
    info->counter = get_be64(head + 8);
    info->echo = get_be64(head + 16);

    mpb__peer *p = find_peer(a, info->instance);
    if (p != NULL)
        return peer_take(p, info->counter) ? MPB_AUTH_FRESH : MPB_AUTH_REPLAYED;
    if (info->echo != a->instance)
        return MPB_AUTH_UNPROVEN;
    /* Believed from now on. Only processes holding the secret that heard
     * this one lately get here, so the list grows with those alone. */
    if (a->num_peers == a->cap_peers) {
        size_t cap = a->cap_peers ? a->cap_peers * 2 : 16;
        mpb__peer *np = realloc(a->peers, cap * sizeof *np);
        if (np == NULL)
            return MPB_AUTH_UNPROVEN;   /* believed at a later message */
        a->peers = np;
        a->cap_peers = cap;
    }
    a->peers[a->num_peers++] = (mpb__peer){info->instance, info->counter, 1};
    return MPB_AUTH_FRESH;
}

const char *mpb_auth_verdict_text(mpb_auth_verdict v)
{
    switch (v) {
    case MPB_AUTH_FRESH: return "authentic";
    case MPB_AUTH_UNPROVEN:
        return "not shown to be fresh (from a sender not heard before, "
               "echoing another process: a replay, or a sender that has "
               "not heard this one yet)";
    case MPB_AUTH_REPLAYED: return "a replay (a message received already)";
    case MPB_AUTH_BAD_TAG: return "missing or wrong authentication tag";
    }
    return "?";
}

int mpb__publish_encoded(lcm_t *lcm, mpb_auth *a, uint64_t echo,
                         const char *channel, unsigned char *buf, int len,
                         int dying)
{
    size_t total = (size_t)len;
    if (a != NULL) {
        mpb_auth_seal(a, channel, buf, (size_t)len, echo, buf + len);
        total += MPB_AUTH_TRAILER_SIZE;
    }
    return mpb__hub_publish(lcm, channel, buf, (unsigned int)total, dying) == 0
               ? MPB_OK : MPB_ELCM;
}

/* Publish len encoded bytes in buf (which has room for a trailer), then
 * free it. */
static int send_encoded(lcm_t *lcm, mpb_auth *a, uint64_t echo,
                        const char *channel, unsigned char *buf, int len)
{
    int rc = mpb__publish_encoded(lcm, a, echo, channel, buf, len, 0);
    free(buf);
    return rc;
}

/* Encode m of type T, in layout n of its wire type W (wire.h: today's
 * bytes under that layout's fingerprint), and publish it. */
#define MPB__PUBLISH(T, W, n, lcm, a, echo, channel, m)                      \
    do {                                                                     \
        int n_ = T##_encoded_size(m);                                        \
        unsigned char *b_ = malloc((size_t)n_ + MPB_AUTH_TRAILER_SIZE);      \
        if (b_ == NULL)                                                      \
            return MPB_ENOMEM;                                               \
        if (T##_encode(b_, 0, n_, m) != n_ ||                                \
            ((n) != 0 && mpb_wire_stamp(W, b_, (size_t)n_, (n)) != MPB_OK)) { \
            free(b_);                                                        \
            return MPB_EINVAL;                                               \
        }                                                                    \
        return send_encoded(lcm, a, echo, channel, b_, n_);                  \
    } while (0)

/* mpb_publish_<name>() and mpb_publish_<name>_in() for each message of
 * messages.h. */
#define MPB__PUBLISH_DEF(ID, name, type, channel)                           \
    int mpb_publish_##name(lcm_t *lcm, mpb_auth *a, uint64_t echo,          \
                           const char *ch, const mpb_##type *m)             \
    {                                                                       \
        MPB__PUBLISH(mpb_##type, MPB_WIRE_##ID, 0, lcm, a, echo, ch, m);    \
    }                                                                       \
    int mpb_publish_##name##_in(lcm_t *lcm, mpb_auth *a, uint64_t echo,     \
                                const char *ch, const mpb_##type *m,        \
                                int layout)                                 \
    {                                                                       \
        MPB__PUBLISH(mpb_##type, MPB_WIRE_##ID, layout, lcm, a, echo, ch,   \
                     m);                                                    \
    }
MPB_MESSAGES(MPB__PUBLISH_DEF)
#undef MPB__PUBLISH_DEF
