/* receive.c - the receive gate: trailer, bytes, decoding (link.h). */
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpbench/link.h"
#include "mpbench/wire.h"
#include "mpb_planner_announce_v1_t.h"
#include "mpb_plan_result_v1_t.h"

/*
 * An announcement of a planner built before approaches
 * (planner_announce_v1_t), decoded as that and handed on as a
 * planner_announce_t that declares no approach, its strings and arrays
 * moved over, so that mpb_planner_announce_t_decode_cleanup() frees them
 * as its own.
 */
static int decode_announce_v1(const void *data, int len,
                              mpb_planner_announce_t *m)
{
    mpb_planner_announce_v1_t v;
    int n = mpb_planner_announce_v1_t_decode(data, 0, len, &v);
    if (n < 0)
        return n;
    *m = (mpb_planner_announce_t){
        .utime = v.utime, .planner_id = v.planner_id, .name = v.name,
        .host = v.host, .pid = v.pid, .language = v.language,
        .version = v.version, .heartbeat_ms = v.heartbeat_ms,
        .num_algorithms = v.num_algorithms, .algorithms = v.algorithms,
        .capacity = v.capacity, .num_active = v.num_active,
        .active_attempts = v.active_runs,
        .num_approaches = 0, .approaches = NULL,
    };
    return n;
}

/* A result of a planner built before waypoint times (plan_result_v1_t),
 * handed on as a plan_result_t whose stages have no times. */
static int decode_result_v1(const void *data, int len, mpb_plan_result_t *out)
{
    mpb_plan_result_v1_t old;
    int rc = mpb_plan_result_v1_t_decode(data, 0, len, &old);
    if (rc < 0)
        return rc;
    mpb_stage_t *stages = old.num_stages > 0
        ? calloc((size_t)old.num_stages, sizeof *stages) : NULL;
    if (old.num_stages > 0 && stages == NULL) {
        mpb_plan_result_v1_t_decode_cleanup(&old);
        return -1;
    }
    /* Every pointer moves over: the strings and arrays the decoder
     * allocated are freed by mpb_plan_result_t_decode_cleanup(). */
    for (int i = 0; i < old.num_stages; i++)
        stages[i] = (mpb_stage_t){
            .name = old.stages[i].name,
            .time = old.stages[i].time,
            .num_waypoints = old.stages[i].num_waypoints,
            .num_joints = old.stages[i].num_joints,
            .num_values = old.stages[i].num_values,
            .waypoints = old.stages[i].waypoints,
        };
    free(old.stages);
    *out = (mpb_plan_result_t){
        .utime = old.utime, .attempt_id = old.run_id,
        .planner_id = old.planner_id, .status = old.status, .message = old.message,
        .time_total = old.time_total, .time_other = old.time_other,
        .memory = old.memory, .num_stages = old.num_stages, .stages = stages,
        .num_values = old.num_values, .values = old.values,
        .num_progress = old.num_progress, .progress = old.progress,
    };
    return rc;
}

/* The generated decoder of each message (messages.h), through one
 * signature, in today's layout. */
static int decode_today(mpb_wire_type type, const void *data, int len,
                        void *msg)
{
    switch (type) {
#define MPB__CASE(ID, name, type, channel)                                  \
    case MPB_WIRE_##ID: return mpb_##type##_decode(data, 0, len, msg);
    MPB_MESSAGES(MPB__CASE)
#undef MPB__CASE
    default: break;
    }
    return -1;
}

/* An older layout whose bytes are today's (wire.h: mpb_wire_stamp()),
 * decoded by today's decoder from a copy under today's fingerprint. */
static int decode_renamed(mpb_wire_type type, const void *data, int len,
                          void *msg)
{
    unsigned char *copy = malloc((size_t)len);
    if (copy == NULL)
        return -1;
    memcpy(copy, data, (size_t)len);
    int rc = mpb_wire_stamp(type, copy, (size_t)len, 0) == MPB_OK
                 ? decode_today(type, copy, len, msg) : -1;
    free(copy);
    return rc;
}

/* A message in layout n of its type (mpb_wire_layout()), decoded as
 * today's: an announcement or a result from before approaches or
 * waypoint times by its own decoder, any other older layout (today's
 * bytes, wire.c) by its fingerprint. */
static int decode(mpb_wire_type type, int n, const void *data, int len,
                  void *msg)
{
    if (n <= 0)
        return decode_today(type, data, len, msg);
    if (type == MPB_WIRE_PLANNER_ANNOUNCE && n == 1)
        return decode_announce_v1(data, len, msg);
    if (type == MPB_WIRE_PLAN_RESULT && n == 1)
        return decode_result_v1(data, len, msg);
    return decode_renamed(type, data, len, msg);
}

int mpb_receive_decode_result(const void *data, int len, mpb_plan_result_t *out)
{
    int n = len > 0 ? mpb_wire_layout(MPB_WIRE_PLAN_RESULT, data, (size_t)len)
                    : -1;
    return decode(MPB_WIRE_PLAN_RESULT, n, data, len, out);
}

void mpb_receive_done(mpb_wire_type type, void *msg)
{
    if (msg == NULL)
        return;
    switch (type) {
#define MPB__CLEANUP(ID, name, type, channel)                               \
    case MPB_WIRE_##ID: mpb_##type##_decode_cleanup(msg); break;
    MPB_MESSAGES(MPB__CLEANUP)
#undef MPB__CLEANUP
    default: break;
    }
}

int mpb_receive(mpb_auth *auth, unsigned accept, mpb_wire_type type,
                const char *channel, const void *data, size_t size,
                void *msg, mpb_received *r)
{
    size_t len = 0;
    r->why[0] = '\0';
    r->layout = -1;
    r->verdict = mpb_auth_check(auth, channel, data, size, &len, &r->info);
    if (!(accept & (1u << r->verdict))) {
        snprintf(r->why, sizeof r->why, "%s", mpb_auth_verdict_text(r->verdict));
        return MPB_EREJECTED;
    }
    if (!mpb_wire_check(type, data, len, r->why, sizeof r->why))
        return MPB_EREJECTED;
    r->layout = mpb_wire_layout(type, data, len);
    if (len > INT_MAX || decode(type, r->layout, data, (int)len, msg) < 0) {
        snprintf(r->why, sizeof r->why, "the decoder refused it");
        return MPB_EREJECTED;
    }
    return MPB_OK;
}
