/*
 * messages.h - every message of mpbench's protocol, listed once.
 *
 * A message is its lcmtypes/<type>.lcm file and one line here. From the
 * line come its tag for the receive gate (MPB_WIRE_<ID>, wire.h), its
 * bounds walk (generated from the .lcm file at build time by
 * lcmtypes/gen_walks.py), its decoding and freeing (link.h) and its
 * sealed publish function mpb_publish_<name>() (link.h); its channel is
 * the name the daemon and the planners use. docs/protocol.md describes
 * each; CONTRIBUTING.md says how to add one.
 *
 *   X(ID, name, type, channel)
 *     ID       MPB_WIRE_<ID>
 *     name     mpb_publish_<name>()
 *     type     the generated struct mpb_<type>, from lcmtypes/<type>.lcm
 *     channel  its channel, or for a message to one process the prefix
 *              its id follows (proto.h: mpb_request_channel())
 */
#ifndef MPBENCH_MESSAGES_H
#define MPBENCH_MESSAGES_H

#include "mpbench/proto.h"

#define MPB_MESSAGES(X)                                                     \
    X(PLANNER_ANNOUNCE, announce, planner_announce_t, MPB_CHANNEL_ANNOUNCE) \
    X(PLAN_REQUEST, request, plan_request_t, MPB_CHANNEL_REQUEST_PREFIX)    \
    X(PLAN_RESULT, result, plan_result_t, MPB_CHANNEL_RESULT)              \
    X(RUN_ACK, ack, run_ack_t, MPB_CHANNEL_ACK)                            \
    X(DAEMON_STATUS, status, daemon_status_t, MPB_CHANNEL_STATUS)          \
    MPB_MESSAGES_EXTRA(X)

/* A build of libmpbench's net layer may add messages of its own here
 * (tests/unit/net/test_messages.c adds one, as a new message would be
 * added above). */
#ifndef MPB_MESSAGES_EXTRA
#define MPB_MESSAGES_EXTRA(X)
#endif

#endif /* MPBENCH_MESSAGES_H */
