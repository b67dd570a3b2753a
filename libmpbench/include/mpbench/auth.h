/*
 * auth.h - optional shared-secret authentication of every message, for
 * benchmarks on a network shared with others. Off unless a secret is given
 * (mpbenchd --secret-file, planners the same).
 *
 * With a secret, every message goes out as its LCM encoding followed by a
 * 32-byte tag: HMAC-SHA-512-256 (libsodium's crypto_auth) over the channel
 * name, a NUL, and the encoding. A receiver that holds the secret drops any
 * message whose tag is missing or wrong before decoding it. Decoders of
 * other tools (lcm-spy, a plain subscriber) ignore the trailing tag, so
 * authenticated traffic stays readable. Replaying a captured message changes
 * nothing, since every message is idempotent by run id (docs/protocol.md).
 */
#ifndef MPBENCH_AUTH_H
#define MPBENCH_AUTH_H

#include <stddef.h>

#include <lcm/lcm.h>

#include "mpb_daemon_status_t.h"
#include "mpb_plan_request_t.h"
#include "mpb_plan_result_t.h"
#include "mpb_planner_announce_t.h"
#include "mpb_run_ack_t.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MPB_AUTH_TAG_SIZE 32

typedef struct mpb_auth mpb_auth;

/*
 * Read a shared secret from the file at path (at least 16 bytes, e.g. from
 * `head -c 32 /dev/urandom`); the key is a hash of the file's bytes. On
 * failure *out is NULL and err holds one line naming the file.
 * Free with mpb_auth_free().
 */
int mpb_auth_load(const char *path, mpb_auth **out, char *err, size_t errlen);
void mpb_auth_free(mpb_auth *a);

/*
 * Check a received message's tag (when a is not NULL) and give the length
 * of the message without it in *msg_len. 1 if it may be decoded, else 0.
 * With a == NULL every message passes whole.
 */
int mpb_auth_check(const mpb_auth *a, const char *channel, const void *buf,
                   size_t len, size_t *msg_len);

/*
 * Publish a message, with its tag when a is not NULL. Return MPB_OK, or
 * MPB_ENOMEM / MPB_ELCM.
 */
int mpb_publish_announce(lcm_t *lcm, const mpb_auth *a, const char *channel,
                         const mpb_planner_announce_t *m);
int mpb_publish_request(lcm_t *lcm, const mpb_auth *a, const char *channel,
                        const mpb_plan_request_t *m);
int mpb_publish_result(lcm_t *lcm, const mpb_auth *a, const char *channel,
                       const mpb_plan_result_t *m);
int mpb_publish_ack(lcm_t *lcm, const mpb_auth *a, const char *channel,
                    const mpb_run_ack_t *m);
int mpb_publish_status(lcm_t *lcm, const mpb_auth *a, const char *channel,
                       const mpb_daemon_status_t *m);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_AUTH_H */
