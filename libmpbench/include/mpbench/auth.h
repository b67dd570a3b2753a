/*
 * auth.h - optional shared-secret authentication of every message, for
 * benchmarks on a network shared with others. Off unless a secret is given
 * (mpbenchd --secret-file, planners the same); without one, messages go out
 * as their bare LCM encoding.
 *
 * With a secret, every message goes out as its LCM encoding followed by a
 * trailer of MPB_AUTH_TRAILER_SIZE bytes (docs/protocol.md gives the bytes
 * and a test vector):
 *
 *   instance  8 bytes, big-endian: a random number drawn once per process
 *   counter   8 bytes, big-endian: 1, 2, 3, ... over all its messages
 *   echo      8 bytes, big-endian: the instance of the process it answers
 *             (a planner: the daemon's; the daemon: the planner's), or 0
 *   tag       32 bytes: HMAC-SHA-512, truncated to 32 bytes, keyed with
 *             the BLAKE2b-256 hash of the secret file, over the channel
 *             name, a NUL, the encoding and the 24 bytes above
 *
 * A receiver drops a message whose tag is missing or wrong before decoding
 * it. Decoders of other tools (lcm-spy, a plain subscriber) ignore the
 * trailer, so authenticated traffic stays readable.
 *
 * A tag alone would let a recorded message be played again. So a receiver
 * also keeps, for every sender instance it believes, the highest counter
 * seen and which of the 64 below it arrived: a message it has had already
 * is a replay. A sender instance it has never believed is believed from
 * the first message that echoes the receiver's own instance (which only
 * a process that heard the receiver lately can send); until then its
 * messages are unproven, and a receiver acts on them only where a replay
 * would do no harm. A replay of any recorded message therefore changes
 * nothing: to the process that received it first it repeats a counter,
 * and to any later process it is from an instance that echoes another.
 */
#ifndef MPBENCH_AUTH_H
#define MPBENCH_AUTH_H

#include <stddef.h>
#include <stdint.h>

#include <lcm/lcm.h>

#include "mpbench/messages.h"
#include "mpb_lcmtypes.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MPB_AUTH_TAG_SIZE 32
/* instance, counter, echo (8 bytes each), then the tag. */
#define MPB_AUTH_TRAILER_SIZE (24 + MPB_AUTH_TAG_SIZE)

/* A secret, this process's instance and counter, and the senders it
 * believes. Publishing is safe from any thread; mpb_auth_check() is to be
 * called from one thread only. */
typedef struct mpb_auth mpb_auth;

/*
 * Read a shared secret from the file at path (at least 16 bytes, e.g. from
 * `head -c 32 /dev/urandom`); the key is the BLAKE2b-256 hash of all the
 * file's bytes. Draws this process's instance. MPB_OK; on failure
 * (MPB_EIO, MPB_EINVAL for a secret too short, MPB_ENOMEM) *out is NULL
 * and err holds one line naming the file. Release with mpb_auth_close().
 */
int mpb_auth_open(const char *path, mpb_auth **out, char *err, size_t errlen);
void mpb_auth_close(mpb_auth *a);

/* This process's instance (never 0), or 0 when a is NULL. */
uint64_t mpb_auth_instance(const mpb_auth *a);

/* What a received message's trailer says of its sender. */
typedef struct mpb_auth_info {
    uint64_t instance;      /* the sender's instance */
    uint64_t counter;       /* its number among the sender's messages */
    uint64_t echo;          /* the instance it answers, 0 if none */
} mpb_auth_info;

/* What mpb_auth_check() made of a message. */
typedef enum mpb_auth_verdict {
    MPB_AUTH_FRESH = 0,     /* authentic and new: from a sender believed
                               (or believed from now on, as it echoes this
                               process's instance), with a counter not had
                               before; also every message when a is NULL */
    MPB_AUTH_UNPROVEN = 1,  /* authentic, from a sender not believed yet
                               that echoes another instance: as likely a
                               replay as not */
    MPB_AUTH_REPLAYED = 2,  /* authentic, but had already (or more than 64
                               messages behind the sender's newest) */
    MPB_AUTH_BAD_TAG = 3,   /* too short for a trailer, or a wrong tag */
} mpb_auth_verdict;

/*
 * Check a received message's trailer and give the length of the message
 * without it in *msg_len and the trailer's fields in *info (zero when a is
 * NULL, when every message passes whole as MPB_AUTH_FRESH). A fresh message
 * is remembered, so that the same bytes again are MPB_AUTH_REPLAYED. Only
 * MPB_AUTH_FRESH and MPB_AUTH_UNPROVEN messages may be decoded.
 */
mpb_auth_verdict mpb_auth_check(mpb_auth *a, const char *channel,
                                const void *buf, size_t len, size_t *msg_len,
                                mpb_auth_info *info);

/* A few words on a verdict, for a log line ("a replay", ...); static. */
const char *mpb_auth_verdict_text(mpb_auth_verdict v);

/*
 * The trailer for a message of len bytes at buf on channel, as publishing
 * writes it (for tests and the test vector of docs/protocol.md): out gets
 * instance, counter and echo as given, then the tag.
 */
void mpb_auth_trailer(const mpb_auth *a, const char *channel, const void *buf,
                      size_t len, uint64_t instance, uint64_t counter,
                      uint64_t echo, unsigned char out[MPB_AUTH_TRAILER_SIZE]);

/*
 * Seal one message this process sends on channel through an LCM binding
 * of its own (the Python kit's, planners/python/mpbplanner/auth.py): out
 * gets the trailer the mpb_publish_... functions would append to the len
 * bytes at buf, with this process's instance, its next counter (counted
 * with those functions', safe from any thread as they are) and echo;
 * the caller sends buf then out as one message. The library keeps
 * nothing of buf or out. MPB_OK, or MPB_EINVAL if a or channel is NULL
 * (out is then untouched).
 */
int mpb_auth_seal(mpb_auth *a, const char *channel, const void *buf,
                  size_t len, uint64_t echo,
                  unsigned char out[MPB_AUTH_TRAILER_SIZE]);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_AUTH_H */
