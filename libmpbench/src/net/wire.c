/*
 * wire.c - a walk over an encoded message that checks every length against
 * the bytes that remain, without allocating (see wire.h for why). The walk
 * follows the .lcm files of lcmtypes/ field by field; tests/unit/net/test_wire.c checks it
 * against real encodings of every type, so a change to a .lcm file that is
 * not made here too fails there.
 */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpbench/wire.h"
#include "mpb_daemon_status_t.h"
#include "mpb_plan_request_t.h"
#include "mpb_plan_result_t.h"
#include "mpb_plan_result_v1_t.h"
#include "mpb_planner_announce_t.h"
#include "mpb_planner_announce_v1_t.h"
#include "mpb_run_ack_t.h"

typedef struct cursor {
    const unsigned char *p;
    size_t len, pos;
    char  *why;
    size_t whylen;
    int    bad;
} cursor;

static int fail(cursor *c, const char *what)
{
    if (!c->bad && c->why != NULL)
        snprintf(c->why, c->whylen, "%s at byte %zu of %zu", what, c->pos,
                 c->len);
    c->bad = 1;
    return -1;
}

static int skip(cursor *c, size_t n)
{
    if (c->bad)
        return -1;
    if (n > c->len - c->pos)
        return fail(c, "message ends early");
    c->pos += n;
    return 0;
}

/* A big-endian signed integer of n bytes (LCM's order). */
static int64_t read_int(cursor *c, int n)
{
    uint64_t v = 0;
    if (skip(c, (size_t)n) != 0)
        return 0;
    for (int i = 0; i < n; i++)
        v = (v << 8) | c->p[c->pos - (size_t)n + (size_t)i];
    if (n < 8 && (v >> (8 * n - 1)) & 1)
        v |= ~(uint64_t)0 << (8 * n);     /* sign-extend */
    return (int64_t)v;
}

static void string(cursor *c)
{
    int64_t n = read_int(c, 4);    /* length including the NUL */
    if (c->bad)
        return;
    if (n < 1)
        fail(c, "string length below 1");
    else if (skip(c, (size_t)n) == 0 && c->p[c->pos - 1] != '\0')
        fail(c, "string is not NUL-terminated");
}

/* A count for an array whose elements take at least min_size bytes each. */
static int64_t count(cursor *c, int bytes, size_t min_size)
{
    int64_t n = read_int(c, bytes);
    if (c->bad)
        return 0;
    if (n < 0) {
        fail(c, "negative array length");
        return 0;
    }
    if (min_size > 0 && (uint64_t)n > (c->len - c->pos) / min_size) {
        fail(c, "array longer than the message");
        return 0;
    }
    return n;
}

static void doubles(cursor *c, int64_t n)
{
    skip(c, (size_t)n * 8);
}

static void named_value(cursor *c)
{
    string(c);
    doubles(c, 1);
}

static void fingerprint(cursor *c, int64_t expected)
{
    if (read_int(c, 8) != expected)
        fail(c, "not this message type (fingerprint differs)");
}

/* An announcement: planner_announce_t, or planner_announce_v1_t as older
 * planners send it, the same fields without the approaches. */
static void announce(cursor *c)
{
    int64_t fp = read_int(c, 8);
    int v1 = fp == (int64_t)__mpb_planner_announce_v1_t_get_hash();
    if (!c->bad && !v1 && fp != (int64_t)__mpb_planner_announce_t_get_hash())
        fail(c, "not this message type (fingerprint differs)");
    doubles(c, 1);                         /* utime */
    string(c); string(c); string(c);       /* planner_id, name, host */
    skip(c, 4);                            /* pid */
    string(c); string(c);                  /* language, version */
    skip(c, 4);                            /* heartbeat_ms */
    for (int64_t i = count(c, 2, 5); i > 0 && !c->bad; i--)
        string(c);                         /* algorithms */
    skip(c, 2);                            /* capacity */
    for (int64_t i = count(c, 2, 5); i > 0 && !c->bad; i--)
        string(c);                         /* active_runs */
    if (v1)
        return;
    for (int64_t i = count(c, 2, 5); i > 0 && !c->bad; i--)
        string(c);                         /* approaches */
}

static void goal(cursor *c)
{
    skip(c, 1);                            /* kind */
    doubles(c, count(c, 2, 8));            /* joints */
    doubles(c, 1);                         /* joint_tolerance */
    string(c);                             /* link */
    doubles(c, 12);                        /* position, tolerances, rpy */
}

static void request(cursor *c)
{
    fingerprint(c, (int64_t)__mpb_plan_request_t_get_hash());
    doubles(c, 1);                         /* utime */
    string(c); string(c); string(c);       /* run_id, planner_id, algorithm */
    for (int64_t i = count(c, 2, 10); i > 0 && !c->bad; i--) {
        string(c);                         /* params: key, value */
        string(c);
    }
    doubles(c, 3);                         /* time_limit, seed, memory_limit */
    for (int k = 0; k < 6; k++)
        string(c);                         /* robot and scene: format, hash, text */
    int64_t nj = count(c, 2, 5 + 8);
    for (int64_t i = nj; i > 0 && !c->bad; i--)
        string(c);                         /* joint_names */
    doubles(c, nj);                        /* start */
    goal(c);
    int64_t nh = count(c, 2, 5 + 8);
    for (int64_t i = nh; i > 0 && !c->bad; i--)
        string(c);                         /* held_names */
    doubles(c, nh);                        /* held_values */
    for (int64_t i = count(c, 2, 5); i > 0 && !c->bad; i--)
        string(c);                         /* stored */
}

/* A stage_t, or with timed 0 a stage_v1_t (no num_times, no times). */
static void stage(cursor *c, int timed)
{
    string(c);                             /* name */
    doubles(c, 1);                         /* time */
    skip(c, 4 + 2);                        /* num_waypoints, num_joints */
    doubles(c, count(c, 4, 8));            /* waypoints */
    if (timed)
        doubles(c, count(c, 4, 8));        /* times */
}

/* Either layout of a result: plan_result_t, or plan_result_v1_t as
 * planners built before waypoint times send it (its own fingerprint). */
static void result(cursor *c)
{
    int64_t fp = read_int(c, 8);
    int timed = fp == (int64_t)__mpb_plan_result_t_get_hash();
    if (!c->bad && !timed && fp != (int64_t)__mpb_plan_result_v1_t_get_hash()) {
        fail(c, "not this message type (fingerprint differs)");
        return;
    }
    doubles(c, 1);                         /* utime */
    string(c); string(c);                  /* run_id, planner_id */
    skip(c, 1);                            /* status */
    string(c);                             /* message */
    doubles(c, 3);                         /* time_total, time_other, memory */
    for (int64_t i = count(c, 2, 5 + 8 + (timed ? 14 : 10)); i > 0 && !c->bad;
         i--)
        stage(c, timed);
    for (int64_t i = count(c, 2, 5 + 8); i > 0 && !c->bad; i--)
        named_value(c);
    for (int64_t i = count(c, 4, 8 + 2); i > 0 && !c->bad; i--) {
        doubles(c, 1);                     /* progress: time */
        for (int64_t k = count(c, 2, 5 + 8); k > 0 && !c->bad; k--)
            named_value(c);
    }
}

static void ack(cursor *c)
{
    fingerprint(c, (int64_t)__mpb_run_ack_t_get_hash());
    doubles(c, 1);                         /* utime */
    string(c); string(c);                  /* run_id, sender_id */
    skip(c, 1);                            /* kind */
}

static void status(cursor *c)
{
    fingerprint(c, (int64_t)__mpb_daemon_status_t_get_hash());
    doubles(c, 1);                         /* utime */
    string(c); string(c); string(c);       /* daemon_id, experiment, state */
    skip(c, 7 * 4);                        /* run counters */
    doubles(c, 2);                         /* elapsed_s, runs_per_s */
    for (int64_t i = count(c, 2, 5 + 5 + 2 + 4 + 8); i > 0 && !c->bad; i--) {
        string(c); string(c);              /* planner_id, name */
        skip(c, 2 + 4);                    /* num_active, runs_done */
        doubles(c, 1);                     /* last_seen_s */
    }
}

int mpb_wire_check(mpb_wire_type type, const void *buf, size_t len,
                   char *why, size_t whylen)
{
    cursor c = {.p = buf, .len = len, .why = why, .whylen = whylen};
    if (buf == NULL)
        return fail(&c, "no message"), 0;
    switch (type) {
    case MPB_WIRE_PLANNER_ANNOUNCE: announce(&c); break;
    case MPB_WIRE_PLAN_REQUEST:     request(&c); break;
    case MPB_WIRE_PLAN_RESULT:      result(&c); break;
    case MPB_WIRE_RUN_ACK:          ack(&c); break;
    case MPB_WIRE_DAEMON_STATUS:    status(&c); break;
    default:                        return fail(&c, "unknown type"), 0;
    }
    if (!c.bad && c.pos != c.len)
        fail(&c, "bytes left over after the message");
    return !c.bad;
}
