/* receive.c - the receive gate: trailer, bytes, decoding (receive.h). */
#include <limits.h>
#include <stdio.h>

#include "mpbench/mpbench.h"
#include "mpbench/receive.h"

/* The generated decoder of each type, through one signature. */
static int decode(mpb_wire_type type, const void *data, int len, void *msg)
{
    switch (type) {
    case MPB_WIRE_PLANNER_ANNOUNCE:
        return mpb_planner_announce_t_decode(data, 0, len, msg);
    case MPB_WIRE_PLAN_REQUEST:
        return mpb_plan_request_t_decode(data, 0, len, msg);
    case MPB_WIRE_PLAN_RESULT:
        return mpb_plan_result_t_decode(data, 0, len, msg);
    case MPB_WIRE_RUN_ACK:
        return mpb_run_ack_t_decode(data, 0, len, msg);
    case MPB_WIRE_DAEMON_STATUS:
        return mpb_daemon_status_t_decode(data, 0, len, msg);
    }
    return -1;
}

void mpb_receive_done(mpb_wire_type type, void *msg)
{
    if (msg == NULL)
        return;
    switch (type) {
    case MPB_WIRE_PLANNER_ANNOUNCE: mpb_planner_announce_t_decode_cleanup(msg); break;
    case MPB_WIRE_PLAN_REQUEST:     mpb_plan_request_t_decode_cleanup(msg); break;
    case MPB_WIRE_PLAN_RESULT:      mpb_plan_result_t_decode_cleanup(msg); break;
    case MPB_WIRE_RUN_ACK:          mpb_run_ack_t_decode_cleanup(msg); break;
    case MPB_WIRE_DAEMON_STATUS:    mpb_daemon_status_t_decode_cleanup(msg); break;
    }
}

int mpb_receive(mpb_auth *auth, unsigned accept, mpb_wire_type type,
                const char *channel, const void *data, size_t size,
                void *msg, mpb_received *r)
{
    size_t len = 0;
    r->why[0] = '\0';
    r->verdict = mpb_auth_open(auth, channel, data, size, &len, &r->info);
    if (!(accept & (1u << r->verdict))) {
        snprintf(r->why, sizeof r->why, "%s", mpb_auth_verdict_text(r->verdict));
        return 0;
    }
    if (!mpb_wire_check(type, data, len, r->why, sizeof r->why))
        return 0;
    if (len > INT_MAX || decode(type, data, (int)len, msg) < 0) {
        snprintf(r->why, sizeof r->why, "the decoder refused it");
        return 0;
    }
    return 1;
}
