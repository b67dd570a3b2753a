/*
 * receive.h - the receive gate: the one way a message from the network
 * becomes a decoded struct, in the daemon and the planner kit alike.
 *
 * A message passes three checks in this order, and is decoded only if it
 * passes all of them: its trailer (auth.h: a right tag, from a sender
 * believed, not had before; the caller says which verdicts it takes), its
 * bytes (wire.h: every length within the message, every string ended),
 * and the generated decoder. Nothing is allocated for a message that
 * fails.
 */
#ifndef MPBENCH_RECEIVE_H
#define MPBENCH_RECEIVE_H

#include <stddef.h>

#include "mpbench/auth.h"
#include "mpbench/wire.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Verdicts a caller takes, as bits of its accept argument. */
#define MPB_RECEIVE_FRESH (1u << MPB_AUTH_FRESH)
#define MPB_RECEIVE_UNPROVEN (1u << MPB_AUTH_UNPROVEN)
#define MPB_RECEIVE_REPLAYED (1u << MPB_AUTH_REPLAYED)
/* Every authentic message: a log played back, or a daemon's status from
 * another daemon, where freshness cannot be asked for. */
#define MPB_RECEIVE_AUTHENTIC \
    (MPB_RECEIVE_FRESH | MPB_RECEIVE_UNPROVEN | MPB_RECEIVE_REPLAYED)

/* What the gate made of a message. */
typedef struct mpb_received {
    mpb_auth_verdict verdict;   /* mpb_auth_check()'s */
    mpb_auth_info info;         /* the trailer's fields (zero without one) */
    char why[160];              /* why it was refused, one line; "" if not */
} mpb_received;

/*
 * Pass the size bytes at data, received on channel, through the gate: with
 * auth (NULL: no authentication, every message fresh), taking the verdicts
 * in accept (MPB_RECEIVE_...), as a message of the given type. On success
 * return MPB_OK with the message decoded into *msg, which must point to
 * the generated struct of that type (mpb_plan_request_t for
 * MPB_WIRE_PLAN_REQUEST, ...); free its contents with mpb_receive_done().
 * Otherwise return MPB_EREJECTED with nothing allocated and r->why saying
 * why. r (not NULL) gets the verdict and the trailer's fields either way.
 */
int mpb_receive(mpb_auth *auth, unsigned accept, mpb_wire_type type,
                const char *channel, const void *data, size_t size,
                void *msg, mpb_received *r);

/*
 * Decode a result that mpb_wire_check(MPB_WIRE_PLAN_RESULT) passed, in
 * either layout it takes: plan_result_t, or plan_result_v1_t (from a
 * planner built before waypoint times), read as a plan_result_t whose
 * stages have no times (num_times 0). Returns the bytes decoded, or < 0
 * as the generated decoder does; free with
 * mpb_plan_result_t_decode_cleanup(). mpb_receive() decodes results so.
 */
struct _mpb_plan_result_t;
int mpb_receive_decode_result(const void *data, int len,
                              struct _mpb_plan_result_t *out);

/* Free what mpb_receive() decoded into *msg, a message of type. */
void mpb_receive_done(mpb_wire_type type, void *msg);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_RECEIVE_H */
