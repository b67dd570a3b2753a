/*
 * wire.c - a walk over an encoded message that checks every length against
 * the bytes that remain, without allocating (see wire.h for why). The walk
 * of each type is generated from its .lcm file (lcmtypes/gen_walks.py);
 * here are its steps and the layouts each message is taken in.
 * tests/unit/net/test_wire.c checks it against real encodings of every
 * type.
 */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpbench/wire.h"
#include "mpb_lcmtypes.h"

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

/* An integer field that sizes arrays after it: its value, refused when
 * negative (the decoder would allocate by it). */
static int64_t dim(cursor *c, int bytes)
{
    int64_t n = read_int(c, bytes);
    if (!c->bad && n < 0) {
        fail(c, "negative array length");
        return 0;
    }
    return n;
}

/* Whether n elements of at least min_size bytes each can follow. */
static int elems(cursor *c, int64_t n, size_t min_size)
{
    if (c->bad)
        return 0;
    if (min_size > 0 && (uint64_t)n > (c->len - c->pos) / min_size)
        return fail(c, "array longer than the message"), 0;
    return 1;
}

/* walk_<type>() for every type of lcmtypes/, generated from its .lcm
 * file: the fields after the fingerprint, in order. */
#include "mpb_wire_walks.h"

/* The layouts each message is taken in: today's (messages.h) at 0, then
 * the older ones that planners built before still send or take, which
 * receive.c decodes as today's. same: the bytes after the fingerprint are
 * today's (fields renamed only), so one is read or written as the other
 * by its fingerprint alone (mpb_wire_stamp()); test_wire.c checks that
 * each layout so marked is. */
typedef struct layout {
    int64_t (*hash)(void);
    void (*walk)(cursor *c);
    int same;
} layout;

#define MPB__TODAY(ID, name, type, channel)                                 \
    [MPB_WIRE_##ID][0] = {__mpb_##type##_get_hash, walk_##type, 1},
#define MPB__OLDER(ID, n, type, same)                                       \
    [MPB_WIRE_##ID][n] = {__mpb_##type##_get_hash, walk_##type, same},
static const layout layouts[MPB_WIRE_COUNT][MPB_WIRE_LAYOUTS] = {
    MPB_MESSAGES(MPB__TODAY)
    /* Before approaches (issue 49) and before waypoint times. */
    MPB__OLDER(PLANNER_ANNOUNCE, 1, planner_announce_v1_t, 0)
    MPB__OLDER(PLAN_RESULT, 1, plan_result_v1_t, 0)
    /* Before attempt_id (issue 45): the attempt's id named run_id. A
     * planner announcing in either older layout takes requests and acks
     * in these (MPB_WIRE_BEFORE_ATTEMPT_ID). */
    MPB__OLDER(PLANNER_ANNOUNCE, 2, planner_announce_v2_t, 1)
    MPB__OLDER(PLAN_REQUEST, MPB_WIRE_BEFORE_ATTEMPT_ID, plan_request_v1_t, 1)
    MPB__OLDER(PLAN_RESULT, 2, plan_result_v2_t, 1)
    MPB__OLDER(RUN_ACK, MPB_WIRE_BEFORE_ATTEMPT_ID, run_ack_v1_t, 1)
};
#undef MPB__OLDER
#undef MPB__TODAY

static const layout *layout_of(mpb_wire_type type, int n)
{
    if ((unsigned)type >= MPB_WIRE_COUNT || n < 0 || n >= MPB_WIRE_LAYOUTS ||
        layouts[type][n].hash == NULL)
        return NULL;
    return &layouts[type][n];
}

int64_t mpb_wire_fingerprint(mpb_wire_type type, int n)
{
    const layout *l = layout_of(type, n);
    return l != NULL ? l->hash() : 0;
}

int mpb_wire_layout(mpb_wire_type type, const void *buf, size_t len)
{
    cursor c = {.p = buf, .len = len};
    if (buf == NULL)
        return -1;
    int64_t fp = read_int(&c, 8);
    for (int n = 0; !c.bad && n < MPB_WIRE_LAYOUTS; n++) {
        const layout *l = layout_of(type, n);
        if (l != NULL && fp == l->hash())
            return n;
    }
    return -1;
}

int mpb_wire_stamp(mpb_wire_type type, void *buf, size_t len, int n)
{
    const layout *l = layout_of(type, n);
    if (l == NULL || !l->same || buf == NULL || len < 8)
        return MPB_EINVAL;
    uint64_t fp = (uint64_t)l->hash();
    unsigned char *p = buf;
    for (int i = 7; i >= 0; i--, fp >>= 8)
        p[i] = (unsigned char)(fp & 0xff);
    return MPB_OK;
}

const char *mpb_wire_type_name(mpb_wire_type type)
{
#define MPB__NAME(ID, name, type, channel) [MPB_WIRE_##ID] = #type,
    static const char *const names[MPB_WIRE_COUNT] = {MPB_MESSAGES(MPB__NAME)};
#undef MPB__NAME
    return (unsigned)type < MPB_WIRE_COUNT ? names[type] : "?";
}

const char *mpb_wire_channel(mpb_wire_type type)
{
#define MPB__CHANNEL(ID, name, type, channel) [MPB_WIRE_##ID] = channel,
    static const char *const channels[MPB_WIRE_COUNT] = {
        MPB_MESSAGES(MPB__CHANNEL)};
#undef MPB__CHANNEL
    return (unsigned)type < MPB_WIRE_COUNT ? channels[type] : NULL;
}

int mpb_wire_check(mpb_wire_type type, const void *buf, size_t len,
                   char *why, size_t whylen)
{
    cursor c = {.p = buf, .len = len, .why = why, .whylen = whylen};
    if (buf == NULL)
        return fail(&c, "no message"), 0;
    if ((unsigned)type >= MPB_WIRE_COUNT)
        return fail(&c, "unknown type"), 0;
    if (skip(&c, 8) != 0)           /* the fingerprint */
        return 0;
    int n = mpb_wire_layout(type, buf, len);
    if (n < 0)
        return fail(&c, "not this message type (fingerprint differs)"), 0;
    const layout *l = layout_of(type, n);
    l->walk(&c);
    if (!c.bad && c.pos != c.len)
        fail(&c, "bytes left over after the message");
    return !c.bad;
}
