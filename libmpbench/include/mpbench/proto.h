/*
 * proto.h - the LCM protocol shared by the daemon and planners written in C
 * or C++: channel names, attempt ids, content hashes, and building and
 * checking messages. The messages themselves are generated from lcmtypes/
 * (C types mpb_*_t); docs/protocol.md is the full description.
 */
#ifndef MPBENCH_PROTO_H
#define MPBENCH_PROTO_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Channels. A request goes to one planner: MPB_CHANNEL_REQUEST_PREFIX + id.
 * Planners acknowledge requests on MPB_CHANNEL_ACK; the daemon acknowledges
 * a planner's results to it alone, on MPB_CHANNEL_ACK_PREFIX + id, so that
 * no other process handles them (every process in the multicast group
 * receives every message: docs/performance.md). */
#define MPB_CHANNEL_ANNOUNCE        "MPB_ANNOUNCE"
#define MPB_CHANNEL_REQUEST_PREFIX  "MPB_REQUEST_"
#define MPB_CHANNEL_RESULT          "MPB_RESULT"
#define MPB_CHANNEL_ACK             "MPB_ACK"
#define MPB_CHANNEL_ACK_PREFIX      "MPB_ACK_"
#define MPB_CHANNEL_STATUS          "MPB_STATUS"

/* The LCM URL used when none is given: loopback-only multicast (ttl=0). */
#define MPB_DEFAULT_LCM_URL "udpm://239.255.76.67:7667?ttl=0"

/* Hex attempt id (plan_request_t.attempt_id: names one attempt of a run;
 * a retry is a new attempt with a new id): 128 random bits, 32 hex digits
 * and a NUL. */
#define MPB_ATTEMPT_ID_SIZE 33
/* Hex content hash: 128-bit BLAKE2b, 32 hex digits and a NUL. */
#define MPB_HASH_SIZE 33

/* LCM's longest channel name (LCM_MAX_CHANNEL_NAME_LENGTH). */
#define MPB_CHANNEL_MAX 63

/* Longest planner id accepted; an id must be a channel-safe word, and
 * the longest channel named after one, MPB_REQUEST_<id>, must fit in
 * MPB_CHANNEL_MAX. */
#define MPB_PLANNER_ID_MAX (MPB_CHANNEL_MAX - (int)sizeof MPB_CHANNEL_REQUEST_PREFIX + 1)

/* Fill out with a new unguessable attempt id. Returns MPB_OK or MPB_EIO. */
int mpb_attempt_id_new(char out[MPB_ATTEMPT_ID_SIZE]);

/* 1 if s is 32 lower-case hex digits, else 0. */
int mpb_attempt_id_is_valid(const char *s);

/* Hex BLAKE2b-128 digest of len bytes at data. */
void mpb_hash_hex(const void *data, size_t len, char out[MPB_HASH_SIZE]);

/*
 * 1 if id may name a planner (and so a channel): 1..MPB_PLANNER_ID_MAX
 * characters from [A-Za-z0-9_.:@-], else 0.
 */
int mpb_planner_id_is_valid(const char *id);

/*
 * Write the id of process pid of planner family name on host into out
 * (size outlen, at least MPB_PLANNER_ID_MAX + 1): name@host:pid, every
 * character of host outside [A-Za-z0-9_.-] as '-' (an empty host as
 * "localhost"). A host too long for the id to fit MPB_PLANNER_ID_MAX keeps
 * as many of its first characters as fit, then '-' and the first 8 hex
 * digits of mpb_hash_hex() of the whole host name as given, so that ids
 * stay readable and two long hosts with the same beginning still differ.
 * MPB_EINVAL if name is empty, holds a character outside [A-Za-z0-9_.-],
 * or is longer than 32 characters; out is then "".
 */
int mpb_planner_id_make(const char *name, const char *host, long pid,
                        char *out, size_t outlen);

/* Write MPB_CHANNEL_REQUEST_PREFIX + planner_id into out (size outlen). */
int mpb_request_channel(const char *planner_id, char *out, size_t outlen);

/* Write MPB_CHANNEL_ACK_PREFIX + planner_id into out (size outlen). */
int mpb_ack_channel(const char *planner_id, char *out, size_t outlen);

/*
 * Copy text from the network into out (size outlen) for a log line or a
 * terminal: valid UTF-8 as it is, but control characters (C0, DEL, C1),
 * backslash and bytes that are not valid UTF-8 as \xNN (a code point
 * U+0080..U+009F as the \xNN of each of its two bytes), so that what a
 * peer sent can add no line, colour or cursor move. Text that does not fit
 * ends in "..." (an escape is never cut). An out of 4 * strlen(s) + 1
 * bytes always holds it whole. Returns out.
 */
char *mpb_escape(const char *s, char *out, size_t outlen);

/* Microseconds since the epoch (CLOCK_REALTIME), for utime fields. */
int64_t mpb_utime_now(void);

/* Seconds on a monotonic clock, for measuring durations. */
double mpb_monotonic_s(void);

/* Lower-case name of a plan_result_t status ("solved", "timeout", ...). */
const char *mpb_status_name(int status);

/*
 * 1 if a planner may send status: SOLVED..MEMORY, except CRASH, which the
 * daemon alone records. Any other status, received or set by solve(), is
 * taken as FAILED, with a note saying so.
 */
int mpb_status_is_planners(int status);

/*
 * A planner configuration's approach: the paper's word for its kind of
 * planner, declared per algorithm by a planner's announcement or by an
 * experiment file's `approach:` (docs/protocol.md). Not the planner's
 * name, which is its family ("ompl"). MPB_APPROACHES lists the words in
 * the order reports group them.
 */
#define MPB_APPROACHES "sampling", "search", "optimisation", "hybrid"
#define MPB_NUM_APPROACHES 4
#define MPB_APPROACHES_TEXT "sampling, search, optimisation or hybrid"

/* The place of approach among MPB_APPROACHES (0 ..), or -1 for a word
 * that is none of them (NULL and "" too). */
int mpb_approach_index(const char *approach);

struct _mpb_stage_t;

/*
 * 1 if a received stage's sizes agree with each other (num_values ==
 * num_waypoints * num_joints, none negative) and with a robot of num_joints
 * joints; else 0, with a one-line reason in why (if not NULL). Only a stage
 * that passes may be read as waypoints.
 */
int mpb_stage_sizes_ok(const struct _mpb_stage_t *st, int num_joints,
                       char *why, size_t whylen);

struct _mpb_daemon_status_t;

/*
 * One daemon runs on an LCM URL: the one that started first (two would
 * share its planners; docs/protocol.md). When the daemon that sent a
 * status started, on the wall clock in microseconds: its utime less its
 * elapsed_s, the same reckoning for every daemon, a daemon's own included.
 */
int64_t mpb_daemon_started_utime(const struct _mpb_daemon_status_t *st);

/*
 * 1 if daemon a_id, started at a_utime, came before daemon b_id, started
 * at b_utime, else 0; the ids break a tie, so that of two daemons exactly
 * one is first.
 */
int mpb_daemon_started_before(int64_t a_utime, const char *a_id,
                              int64_t b_utime, const char *b_id);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_PROTO_H */
