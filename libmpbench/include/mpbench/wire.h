/*
 * wire.h - checking an encoded LCM message before it is decoded.
 *
 * The decoders lcm-gen 1.3 writes trust the sizes in a message: they
 * allocate what a length field claims before reading it (a few bytes can ask
 * for gigabytes), leak what they allocated when a message ends early, and
 * copy strings without making sure they end in NUL. A message from the
 * network is therefore checked here first, without allocating: every
 * length non-negative and within the bytes that remain, every string
 * NUL-terminated, the type's fingerprint right, nothing left over. Only a
 * message that passes is given to the generated decoder.
 */
#ifndef MPBENCH_WIRE_H
#define MPBENCH_WIRE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mpb_wire_type {
    MPB_WIRE_PLANNER_ANNOUNCE,
    MPB_WIRE_PLAN_REQUEST,
    MPB_WIRE_PLAN_RESULT,
    MPB_WIRE_RUN_ACK,
    MPB_WIRE_DAEMON_STATUS
} mpb_wire_type;

/*
 * 1 if the len bytes at buf are a well-formed encoding of a message of the
 * given type; else 0 with a one-line reason in why (if not NULL), e.g.
 * "string at byte 40 is not NUL-terminated".
 */
int mpb_wire_check(mpb_wire_type type, const void *buf, size_t len,
                   char *why, size_t whylen);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_WIRE_H */
