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
 * message that passes is given to the generated decoder. The walk of
 * each type is generated from its .lcm file (lcmtypes/gen_walks.py).
 */
#ifndef MPBENCH_WIRE_H
#define MPBENCH_WIRE_H

#include <stddef.h>

#include "mpbench/messages.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Each message of messages.h: MPB_WIRE_PLANNER_ANNOUNCE, ... */
typedef enum mpb_wire_type {
#define MPB__WIRE_TAG(ID, name, type, channel) MPB_WIRE_##ID,
    MPB_MESSAGES(MPB__WIRE_TAG)
#undef MPB__WIRE_TAG
    MPB_WIRE_COUNT                  /* how many; not a message */
} mpb_wire_type;

/* The message's type name ("plan_request_t"), static; "?" for no
 * message. */
const char *mpb_wire_type_name(mpb_wire_type type);

/* The message's channel (messages.h), or for a message to one process
 * the prefix its id follows; NULL for no message. For other languages'
 * kits, which check their own list against this one. */
const char *mpb_wire_channel(mpb_wire_type type);

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
