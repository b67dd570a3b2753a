/* test_wire.c - the pre-decode check of encoded messages: real encodings of
 * every type pass (a result in either layout: with waypoint times, and
 * plan_result_v1_t as planners built before them send it); truncated,
 * padded, mistyped and hostile ones do not; and whatever passes decodes.
 * Every older layout (wire.c) is taken and decoded as today's, its
 * fingerprint its own; those of today's bytes are written by a
 * fingerprint alone. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "mpb_daemon_status_t.h"
#include "mpb_plan_request_t.h"
#include "mpb_plan_result_t.h"
#include "mpb_plan_result_v1_t.h"
#include "mpb_planner_announce_t.h"
#include "mpb_planner_announce_v1_t.h"
#include "mpb_run_ack_t.h"
#include "mpb_plan_request_v1_t.h"
#include "mpb_plan_result_v2_t.h"
#include "mpb_planner_announce_v2_t.h"
#include "mpb_run_ack_v1_t.h"

typedef struct sample {
    mpb_wire_type type;
    unsigned char *buf;
    int len;
} sample;

/* One per type, and a sixth: a result in the layout before waypoint
 * times (plan_result_v1_t). */
#define NUM_SAMPLES 6
static sample samples[NUM_SAMPLES];

#define ENCODE(i, wtype, T, msg)                                             \
    do {                                                                     \
        samples[i].type = wtype;                                             \
        samples[i].len = T##_encoded_size(&(msg));                           \
        samples[i].buf = malloc((size_t)samples[i].len);                     \
        assert_int_equal(T##_encode(samples[i].buf, 0, samples[i].len,       \
                                    &(msg)), samples[i].len);                \
    } while (0)

static int decodes(mpb_wire_type t, const void *buf, int len)
{
    int rc = -1;
    switch (t) {
#define TRY(wt, T)                                                           \
    case wt: {                                                               \
        T m;                                                                 \
        rc = T##_decode(buf, 0, len, &m);                                    \
        if (rc >= 0)                                                         \
            T##_decode_cleanup(&m);                                          \
        break;                                                               \
    }
    TRY(MPB_WIRE_PLANNER_ANNOUNCE, mpb_planner_announce_t)
    TRY(MPB_WIRE_PLAN_REQUEST, mpb_plan_request_t)
    case MPB_WIRE_PLAN_RESULT: {    /* either layout, as mpb_receive() */
        mpb_plan_result_t m;
        rc = mpb_receive_decode_result(buf, len, &m);
        if (rc >= 0)
            mpb_plan_result_t_decode_cleanup(&m);
        break;
    }
    TRY(MPB_WIRE_RUN_ACK, mpb_run_ack_t)
    TRY(MPB_WIRE_DAEMON_STATUS, mpb_daemon_status_t)
#undef TRY
    case MPB_WIRE_COUNT:
        break;
    }
    return rc >= 0;
}

static int setup(void **state)
{
    (void)state;
    char *names[] = {"a", "b"};
    double start[] = {0, 1}, goal[] = {1, 0};
    double wp[] = {0, 1, 0.5, 0.5, 1, 0};
    mpb_named_value_t v = {"graph states", 3};
    mpb_progress_t prog = {0.1, 1, &v};
    double times[] = {0, 0.5, 1.25};
    mpb_stage_t st[] = {{"raw", 0.01, 3, 2, 6, wp, 3, times},
                        {"empty", 0, 0, 2, 0, NULL, 0, NULL}};
    mpb_plan_result_t res = {1, "0123456789abcdef0123456789abcdef", "p@h:1", 0,
                             "ok", 0.02, 0.001, 12.5, 2, st, 1, &v, 1, &prog};
    mpb_stage_v1_t st1[] = {{"raw", 0.01, 3, 2, 6, wp},
                            {"empty", 0, 0, 2, 0, NULL}};
    mpb_plan_result_v1_t res1 = {1, "0123456789abcdef0123456789abcdef",
                                 "p@h:1", 0, "ok", 0.02, 0.001, 12.5, 2, st1,
                                 1, &v, 1, &prog};
    char *algos[] = {"RRT", "RRTConnect"};
    char *approaches[] = {"sampling", ""};
    mpb_planner_announce_t ann = {1, "p@h:1", "p", "h", 7, "c", "1", 500,
                                  2, algos, 1, 0, NULL, 2, approaches};
    mpb_run_ack_t ack = {1, "0123456789abcdef0123456789abcdef", "p@h:1", 1};
    mpb_param_t par = {"range", "0.3"};
    char *stored[] = {"00000000000000000000000000000001",
                      "00000000000000000000000000000002"};
    char *held_names[] = {"finger_joint1", "finger_joint2"};
    double held_values[] = {0.04, 0.035};
    mpb_plan_request_t req = {
        .utime = 1, .attempt_id = "0123456789abcdef0123456789abcdef",
        .planner_id = "p@h:1", .algorithm = "RRT", .num_params = 1,
        .params = &par, .time_limit = 1, .seed = 2, .robot_format = "planar",
        .robot_hash = "x", .robot = "r", .scene_format = "planar",
        .scene_hash = "y", .scene = "s", .num_joints = 2, .joint_names = names,
        .start = start,
        .goal = {.kind = 0, .num_joints = 2, .joints = goal, .link = ""},
        .num_held = 2, .held_names = held_names, .held_values = held_values,
        .num_stored = 2, .stored = stored,   /* acknowledgements riding along */
    };
    mpb_planner_seen_t seen = {"p@h:1", "p", 1, 10, 0.2};
    mpb_daemon_status_t status = {1, "d@h:2", "exp", "running", 10, 5, 4, 1,
                                  0, 1, 0, 2.0, 2.5, 1, &seen};
    ENCODE(0, MPB_WIRE_PLANNER_ANNOUNCE, mpb_planner_announce_t, ann);
    ENCODE(1, MPB_WIRE_PLAN_REQUEST, mpb_plan_request_t, req);
    ENCODE(2, MPB_WIRE_PLAN_RESULT, mpb_plan_result_t, res);
    ENCODE(3, MPB_WIRE_RUN_ACK, mpb_run_ack_t, ack);
    ENCODE(4, MPB_WIRE_DAEMON_STATUS, mpb_daemon_status_t, status);
    ENCODE(5, MPB_WIRE_PLAN_RESULT, mpb_plan_result_v1_t, res1);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    for (int i = 0; i < NUM_SAMPLES; i++)
        free(samples[i].buf);
    return 0;
}

static void real_encodings_pass(void **state)
{
    (void)state;
    char why[128];
    for (int i = 0; i < NUM_SAMPLES; i++) {
        assert_true(mpb_wire_check(samples[i].type, samples[i].buf,
                                   (size_t)samples[i].len, why, sizeof why));
    }
}

static void each_type_is_told_apart(void **state)
{
    (void)state;
    char why[128];
    for (int i = 0; i < NUM_SAMPLES; i++)
        for (int t = 0; t < 5; t++)
            if (t != (int)samples[i].type) {
                assert_false(mpb_wire_check((mpb_wire_type)t, samples[i].buf,
                                            (size_t)samples[i].len, why,
                                            sizeof why));
                assert_non_null(strstr(why, "fingerprint"));
            }
}

/*
 * An announcement of an older planner (planner_announce_v1_t: before
 * approaches, the fingerprint it had then) passes the check, and the
 * receive gate decodes it as a planner_announce_t declaring no approach;
 * the two fields of today's message are not taken from it, and it is
 * checked as strictly as today's (cut short, it fails).
 */
static void an_older_planners_announcement_is_taken(void **state)
{
    (void)state;
    char *algos[] = {"line", "arc"};
    char *active[] = {"0123456789abcdef0123456789abcdef"};
    mpb_planner_announce_v1_t old = {2, "old@h:3", "old", "h", 3, "python",
                                     "0.0.9", 500, 2, algos, 1, 1, active};
    int len = mpb_planner_announce_v1_t_encoded_size(&old);
    unsigned char *buf = malloc((size_t)len);
    assert_int_equal(mpb_planner_announce_v1_t_encode(buf, 0, len, &old), len);
    char why[160];
    assert_true(mpb_wire_check(MPB_WIRE_PLANNER_ANNOUNCE, buf, (size_t)len,
                               why, sizeof why));
    for (int n = 0; n < len; n++)
        assert_false(mpb_wire_check(MPB_WIRE_PLANNER_ANNOUNCE, buf, (size_t)n,
                                    NULL, 0));
    mpb_planner_announce_t m;
    mpb_received r;
    assert_int_equal(mpb_receive(NULL, MPB_RECEIVE_FRESH,
                                 MPB_WIRE_PLANNER_ANNOUNCE, "MPB_ANNOUNCE",
                                 buf, (size_t)len, &m, &r), MPB_OK);
    assert_int_equal(r.layout, 1);
    assert_string_equal(m.planner_id, "old@h:3");
    assert_string_equal(m.name, "old");
    assert_int_equal(m.num_algorithms, 2);
    assert_string_equal(m.algorithms[1], "arc");
    assert_int_equal(m.capacity, 1);
    assert_int_equal(m.num_active, 1);
    assert_string_equal(m.active_attempts[0], active[0]);
    assert_int_equal(m.num_approaches, 0);
    assert_null(m.approaches);
    mpb_receive_done(MPB_WIRE_PLANNER_ANNOUNCE, &m);
    /* Today's, with approaches, decodes with them. */
    assert_int_equal(mpb_receive(NULL, MPB_RECEIVE_FRESH,
                                 MPB_WIRE_PLANNER_ANNOUNCE, "MPB_ANNOUNCE",
                                 samples[0].buf, (size_t)samples[0].len, &m,
                                 &r), MPB_OK);
    assert_int_equal(r.layout, 0);
    assert_int_equal(m.num_approaches, 2);
    assert_string_equal(m.approaches[0], "sampling");
    assert_string_equal(m.approaches[1], "");
    mpb_receive_done(MPB_WIRE_PLANNER_ANNOUNCE, &m);
    free(buf);
}

static void every_truncation_and_padding_fails(void **state)
{
    (void)state;
    for (int i = 0; i < NUM_SAMPLES; i++) {
        for (int n = 0; n < samples[i].len; n++)
            assert_false(mpb_wire_check(samples[i].type, samples[i].buf,
                                        (size_t)n, NULL, 0));
        unsigned char *longer = calloc((size_t)samples[i].len + 1, 1);
        memcpy(longer, samples[i].buf, (size_t)samples[i].len);
        assert_false(mpb_wire_check(samples[i].type, longer,
                                    (size_t)samples[i].len + 1, NULL, 0));
        free(longer);
    }
}

/* Byte offsets in the result sample: 8 fingerprint + 8 utime, then the
 * run id string: its 4-byte length at 16, 33 bytes (32 hex digits + NUL). */
static void hostile_lengths_fail(void **state)
{
    (void)state;
    sample *r = &samples[2];
    unsigned char *b = malloc((size_t)r->len);
    char why[128];

    memcpy(b, r->buf, (size_t)r->len);
    b[16 + 4 + 32] = 'x';                                  /* no NUL */
    assert_false(mpb_wire_check(r->type, b, (size_t)r->len, why, sizeof why));
    assert_non_null(strstr(why, "not NUL-terminated"));

    memcpy(b, r->buf, (size_t)r->len);
    b[16] = 0xff; b[17] = 0xff; b[18] = 0xff; b[19] = 0xf0;  /* length -16 */
    assert_false(mpb_wire_check(r->type, b, (size_t)r->len, why, sizeof why));
    assert_non_null(strstr(why, "below 1"));

    memcpy(b, r->buf, (size_t)r->len);
    b[16] = 0x7f;                                          /* ~2 GB string */
    assert_false(mpb_wire_check(r->type, b, (size_t)r->len, why, sizeof why));
    assert_non_null(strstr(why, "ends early"));
    free(b);
}

/* Whatever the check lets through, the generated decoder must read. */
static void whatever_passes_decodes(void **state)
{
    (void)state;
    unsigned seed = 12345;
    for (int i = 0; i < NUM_SAMPLES; i++) {
        sample *s = &samples[i];
        unsigned char *b = malloc((size_t)s->len);
        int passed = 0;
        for (int k = 0; k < 20000; k++) {
            memcpy(b, s->buf, (size_t)s->len);
            for (int m = 0; m < 3; m++) {
                seed = seed * 1103515245u + 12345u;
                b[(seed >> 8) % (unsigned)s->len] = (unsigned char)(seed >> 20);
            }
            if (mpb_wire_check(s->type, b, (size_t)s->len, NULL, 0)) {
                passed++;
                assert_true(decodes(s->type, b, s->len));
            }
        }
        assert_true(passed > 0); /* mutating numbers only keeps it valid */
        free(b);
    }
}

/* A result in either layout reads the same through the gate, the old one
 * as stages without times; a result whose fingerprint is neither is
 * refused. */
static void both_result_layouts_decode(void **state)
{
    (void)state;
    for (int i = 2; i <= 5; i += 3) {
        mpb_plan_result_t m;
        mpb_received r;
        assert_int_equal(mpb_receive(NULL, MPB_RECEIVE_FRESH,
                                     MPB_WIRE_PLAN_RESULT, "MPB_RESULT",
                                     samples[i].buf, (size_t)samples[i].len,
                                     &m, &r), MPB_OK);
        assert_string_equal(m.attempt_id, "0123456789abcdef0123456789abcdef");
        assert_string_equal(m.message, "ok");
        assert_int_equal(m.num_stages, 2);
        assert_string_equal(m.stages[0].name, "raw");
        assert_int_equal(m.stages[0].num_waypoints, 3);
        assert_int_equal(m.stages[0].num_values, 6);
        assert_true(m.stages[0].waypoints[2] == 0.5);
        assert_string_equal(m.stages[1].name, "empty");
        assert_int_equal(m.num_values, 1);
        assert_string_equal(m.values[0].name, "graph states");
        assert_int_equal(m.num_progress, 1);
        if (i == 2) {
            assert_int_equal(m.stages[0].num_times, 3);
            assert_true(m.stages[0].times[2] == 1.25);
        } else {
            assert_int_equal(m.stages[0].num_times, 0);
            assert_null(m.stages[0].times);
        }
        assert_int_equal(m.stages[1].num_times, 0);
        mpb_receive_done(MPB_WIRE_PLAN_RESULT, &m);
    }
    /* The two fingerprints differ: each is the layout it says. */
    assert_true(__mpb_plan_result_t_get_hash() !=
                __mpb_plan_result_v1_t_get_hash());
    unsigned char *b = malloc((size_t)samples[5].len);
    memcpy(b, samples[5].buf, (size_t)samples[5].len);
    b[7] ^= 1;
    char why[128];
    assert_false(mpb_wire_check(MPB_WIRE_PLAN_RESULT, b,
                                (size_t)samples[5].len, why, sizeof why));
    assert_non_null(strstr(why, "fingerprint"));
    free(b);
}

/* The older layouts of today's bytes, each with its generated struct:
 * decode bytes in it and encode them again into out; the bytes encoded,
 * or -1 if its decoder refused them. */
#define REENCODE(T)                                                         \
    static int reencode_##T(const void *buf, int len, unsigned char *out,   \
                            int cap)                                        \
    {                                                                       \
        mpb_##T m;                                                          \
        if (mpb_##T##_decode(buf, 0, len, &m) < 0)                          \
            return -1;                                                      \
        int n = mpb_##T##_encoded_size(&m) <= cap                           \
                    ? mpb_##T##_encode(out, 0, cap, &m) : -1;               \
        mpb_##T##_decode_cleanup(&m);                                       \
        return n;                                                           \
    }
REENCODE(planner_announce_v2_t)
REENCODE(plan_request_v1_t)
REENCODE(plan_result_v2_t)
REENCODE(run_ack_v1_t)
#undef REENCODE

static const struct renamed {
    mpb_wire_type type;
    int layout, sample;
    int (*reencode)(const void *, int, unsigned char *, int);
} renamed[] = {
    {MPB_WIRE_PLANNER_ANNOUNCE, 2, 0, reencode_planner_announce_v2_t},
    {MPB_WIRE_PLAN_REQUEST, MPB_WIRE_BEFORE_ATTEMPT_ID, 1,
     reencode_plan_request_v1_t},
    {MPB_WIRE_PLAN_RESULT, 2, 2, reencode_plan_result_v2_t},
    {MPB_WIRE_RUN_ACK, MPB_WIRE_BEFORE_ATTEMPT_ID, 3, reencode_run_ack_v1_t},
};

/*
 * Planners built before attempt_id: each layout they send or take
 * (run_id, active_runs) has a fingerprint of its own, differing from
 * today's and from every other layout of any message; today's bytes
 * under it are what that layout's own struct encodes (so the daemon can
 * send it); and the gate takes it, says which layout it was, and decodes
 * it as today's struct, every field kept.
 */
static void the_layouts_before_attempt_id_are_taken(void **state)
{
    (void)state;
    /* Every fingerprint of every layout differs from every other. */
    for (int t = 0; t < MPB_WIRE_COUNT; t++)
        for (int n = 0; n < MPB_WIRE_LAYOUTS; n++) {
            int64_t fp = mpb_wire_fingerprint((mpb_wire_type)t, n);
            if (fp == 0)
                continue;
            for (int u = 0; u < MPB_WIRE_COUNT; u++)
                for (int k = 0; k < MPB_WIRE_LAYOUTS; k++)
                    if (u != t || k != n)
                        assert_true(fp != mpb_wire_fingerprint(
                                              (mpb_wire_type)u, k));
        }
    assert_true(__mpb_plan_request_t_get_hash() !=
                __mpb_plan_request_v1_t_get_hash());
    assert_true(__mpb_run_ack_t_get_hash() != __mpb_run_ack_v1_t_get_hash());

    for (size_t i = 0; i < sizeof renamed / sizeof renamed[0]; i++) {
        const struct renamed *c = &renamed[i];
        const sample *s = &samples[c->sample];
        unsigned char *old = malloc((size_t)s->len);
        unsigned char *again = malloc((size_t)s->len);
        memcpy(old, s->buf, (size_t)s->len);
        assert_int_equal(mpb_wire_stamp(c->type, old, (size_t)s->len,
                                        c->layout), MPB_OK);
        assert_int_equal(mpb_wire_layout(c->type, old, (size_t)s->len),
                         c->layout);
        /* That layout's own decoder reads it, and its encoder gives the
         * same bytes back: the layout is today's bytes, renamed. */
        assert_int_equal(c->reencode(old, s->len, again, s->len), s->len);
        assert_memory_equal(old, again, (size_t)s->len);
        /* Today's generated decoder refuses it (decodes() reads a result
         * as the gate does); the gate takes it, as today's. */
        if (c->type != MPB_WIRE_PLAN_RESULT)
            assert_false(decodes(c->type, old, s->len));
        char why[160];
        assert_true(mpb_wire_check(c->type, old, (size_t)s->len, why,
                                   sizeof why));
        union {
            mpb_planner_announce_t ann;
            mpb_plan_request_t req;
            mpb_plan_result_t res;
            mpb_run_ack_t ack;
        } m;
        mpb_received r;
        assert_int_equal(mpb_receive(NULL, MPB_RECEIVE_FRESH, c->type, "CH",
                                     old, (size_t)s->len, &m, &r), MPB_OK);
        assert_int_equal(r.layout, c->layout);
        int n = -1;
        switch (c->type) {
        case MPB_WIRE_PLANNER_ANNOUNCE:
            n = mpb_planner_announce_t_encode(again, 0, s->len, &m.ann);
            break;
        case MPB_WIRE_PLAN_REQUEST:
            assert_string_equal(m.req.attempt_id,
                                "0123456789abcdef0123456789abcdef");
            n = mpb_plan_request_t_encode(again, 0, s->len, &m.req);
            break;
        case MPB_WIRE_PLAN_RESULT:
            assert_string_equal(m.res.attempt_id,
                                "0123456789abcdef0123456789abcdef");
            n = mpb_plan_result_t_encode(again, 0, s->len, &m.res);
            break;
        case MPB_WIRE_RUN_ACK:
            assert_string_equal(m.ack.attempt_id,
                                "0123456789abcdef0123456789abcdef");
            n = mpb_run_ack_t_encode(again, 0, s->len, &m.ack);
            break;
        default: break;
        }
        /* Decoded as today's, every field kept: today's bytes again. */
        assert_int_equal(n, s->len);
        assert_memory_equal(again, s->buf, (size_t)s->len);
        mpb_receive_done(c->type, &m);
        /* Stamped back, today's again. */
        assert_int_equal(mpb_wire_stamp(c->type, old, (size_t)s->len, 0),
                         MPB_OK);
        assert_memory_equal(old, s->buf, (size_t)s->len);
        free(old);
        free(again);
    }

    /* An ack as such a planner builds it, with run_id, reads as today's. */
    mpb_run_ack_v1_t a1 = {5, "fedcba9876543210fedcba9876543210", "old@h:3",
                           MPB_RUN_ACK_V1_T_REQUEST_RECEIVED};
    unsigned char buf[128];
    int len = mpb_run_ack_v1_t_encode(buf, 0, sizeof buf, &a1);
    assert_true(len > 0);
    mpb_run_ack_t ack;
    mpb_received r;
    assert_int_equal(mpb_receive(NULL, MPB_RECEIVE_FRESH, MPB_WIRE_RUN_ACK,
                                 "MPB_ACK", buf, (size_t)len, &ack, &r),
                     MPB_OK);
    assert_int_equal(r.layout, MPB_WIRE_BEFORE_ATTEMPT_ID);
    assert_string_equal(ack.attempt_id, a1.run_id);
    assert_string_equal(ack.sender_id, "old@h:3");
    mpb_receive_done(MPB_WIRE_RUN_ACK, &ack);

    /* A layout whose bytes are not today's is never written by its
     * fingerprint: the result before waypoint times, the announcement
     * before approaches; nor a layout a message does not have. */
    unsigned char *b = malloc((size_t)samples[2].len);
    memcpy(b, samples[2].buf, (size_t)samples[2].len);
    assert_int_equal(mpb_wire_stamp(MPB_WIRE_PLAN_RESULT, b,
                                    (size_t)samples[2].len, 1), MPB_EINVAL);
    assert_int_equal(mpb_wire_stamp(MPB_WIRE_PLANNER_ANNOUNCE, b,
                                    (size_t)samples[2].len, 1), MPB_EINVAL);
    assert_int_equal(mpb_wire_stamp(MPB_WIRE_DAEMON_STATUS, b,
                                    (size_t)samples[2].len, 1), MPB_EINVAL);
    assert_memory_equal(b, samples[2].buf, (size_t)samples[2].len);
    assert_int_equal(mpb_wire_fingerprint(MPB_WIRE_DAEMON_STATUS, 1), 0);
    assert_int_equal(mpb_wire_layout(MPB_WIRE_PLAN_RESULT, b, 7), -1);
    free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(real_encodings_pass),
        cmocka_unit_test(each_type_is_told_apart),
        cmocka_unit_test(an_older_planners_announcement_is_taken),
        cmocka_unit_test(every_truncation_and_padding_fails),
        cmocka_unit_test(hostile_lengths_fail),
        cmocka_unit_test(whatever_passes_decodes),
        cmocka_unit_test(both_result_layouts_decode),
        cmocka_unit_test(the_layouts_before_attempt_id_are_taken),
    };
    return cmocka_run_group_tests_name("wire", tests, setup, teardown);
}
