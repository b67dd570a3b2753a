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
#include <stdint.h>

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

/*
 * Layouts. A message is taken in today's layout (0, its .lcm file) and in
 * older ones that planners built before still send or take (1 ..
 * MPB_WIRE_LAYOUTS - 1; lcmtypes/<type>_v<n>_t.lcm, listed in wire.c):
 * LCM's fingerprint is made of the field names and types, so a renamed
 * field is a new fingerprint. docs/protocol.md lists them.
 */
#define MPB_WIRE_LAYOUTS 3

/* The layout of plan_request_t and of run_ack_t that planners built
 * before attempt_id take (the attempt's id named run_id): the daemon
 * sends it to a planner that announced in an older layout. */
#define MPB_WIRE_BEFORE_ATTEMPT_ID 1

/* Which layout of type the encoding at buf is (by its fingerprint): 0
 * today's, 1.. an older one; -1 none (or shorter than a fingerprint). */
int mpb_wire_layout(mpb_wire_type type, const void *buf, size_t len);

/* The fingerprint of layout n of type; 0 if it has no such layout. */
int64_t mpb_wire_fingerprint(mpb_wire_type type, int n);

/*
 * Put layout n's fingerprint on the encoding at buf (len bytes, at least
 * the fingerprint's 8), so that today's bytes become that layout's or an
 * older layout's become today's. Only for a layout whose bytes are
 * today's, its fields renamed alone; MPB_OK, else MPB_EINVAL with buf
 * untouched.
 */
int mpb_wire_stamp(mpb_wire_type type, void *buf, size_t len, int n);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_WIRE_H */
