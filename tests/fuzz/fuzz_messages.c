/*
 * fuzz_messages.c - libFuzzer target: every message the daemon and the
 * planners decode, the way they decode it (mpb_receive(), link.h: wire.h's
 * check, then the decoder of the layout it came in, today's or older), and
 * for a result what the daemon then does with each
 * stage: the size check, verification and metrics. The first byte picks the
 * message type; the rest is the encoded message.
 */
#include <stdint.h>
#include <stdlib.h>

#include "mpbench/mpbench.h"
#include "mpb_daemon_status_t.h"
#include "mpb_plan_request_t.h"
#include "mpb_plan_result_t.h"
#include "mpb_planner_announce_t.h"
#include "mpb_run_ack_t.h"

static mpb_world *world(void)
{
    static mpb_world *w;
    if (w == NULL && mpb_world_open("planar",
            "link_radius 0.03\njoint a -3 3 0.5\njoint b continuous 0.4\n"
            "joint c -2 2 0.3\n", "planar", "circle 0 0.8 0.15\n"
            "box -0.7 0 0.1 0.3\n", &w, NULL, 0) != MPB_OK)
        abort();
    return w;
}

static void check_result(const mpb_plan_result_t *r)
{
    static const double start[3] = {0, 0, 0}, goal[3] = {0.3, -0.2, 0.1};
    mpb_goal g = {.kind = MPB_GOAL_JOINTS, .joints = goal,
                  .joint_tolerance = 0.01};
    mpb_world *w = world();
    mpb_attempt_id_is_valid(r->attempt_id);
    mpb_planner_id_is_valid(r->planner_id);
    mpb_status_name(r->status);
    for (int i = 0; i < r->num_stages; i++) {
        const mpb_stage_t *st = &r->stages[i];
        char why[200];
        mpb_verdict v;
        if (!mpb_stage_sizes_ok(st, 3, why, sizeof why))
            continue;
        mpb_verify_path(w, start, 0.01, &g, st->waypoints, st->num_waypoints,
                        3, 0.05, &v);
        if (st->num_times != 0 &&
            mpb_times_ok(st->times, st->num_times, st->num_waypoints, why,
                         sizeof why) &&
            v.code != MPB_VERDICT_NOT_FINITE) {
            static const double limits[3] = {1.0, 0, 2.0};
            mpb_timing t;
            mpb_path_timing(st->waypoints, st->times, st->num_waypoints, 3,
                            mpb_world_joint_wraps(w), limits, &t);
        }
        mpb_verdict_name(v.code);
        if (v.code != MPB_VERDICT_NOT_FINITE) {
            mpb_path_length(st->waypoints, st->num_waypoints, 3,
                            mpb_world_joint_wraps(w));
            mpb_smoothness(st->waypoints, st->num_waypoints, 3,
                           mpb_world_joint_wraps(w));
            mpb_path_clearance(w, st->waypoints, st->num_waypoints, 3);
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    static const mpb_wire_type types[] = {
        MPB_WIRE_PLAN_RESULT, MPB_WIRE_PLANNER_ANNOUNCE, MPB_WIRE_RUN_ACK,
        MPB_WIRE_PLAN_REQUEST, MPB_WIRE_DAEMON_STATUS};
    mpb_wire_type type = types[data[0] % 5];
    union {
        mpb_plan_result_t result;
        mpb_planner_announce_t announce;
        mpb_run_ack_t ack;
        mpb_plan_request_t request;
        mpb_daemon_status_t status;
    } m;
    mpb_received r;
    /* The one gate the daemon and the planners use: every layout of the
     * type, today's and the older ones, decoded as today's. */
    if (mpb_receive(NULL, MPB_RECEIVE_AUTHENTIC, type, "MPB_FUZZ", data + 1,
                    size - 1, &m, &r) != MPB_OK)
        return 0;
    switch (type) {
    case MPB_WIRE_PLAN_RESULT:
        check_result(&m.result);
        break;
    case MPB_WIRE_PLANNER_ANNOUNCE:
        mpb_planner_id_is_valid(m.announce.planner_id);
        for (int i = 0; i < m.announce.num_active; i++)
            mpb_attempt_id_is_valid(m.announce.active_attempts[i]);
        break;
    case MPB_WIRE_RUN_ACK:
        mpb_attempt_id_is_valid(m.ack.attempt_id);
        break;
    case MPB_WIRE_PLAN_REQUEST:
        mpb_attempt_id_is_valid(m.request.attempt_id);
        break;
    default:
        break;
    }
    mpb_receive_done(type, &m);
    return 0;
}
