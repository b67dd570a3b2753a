/* planner_internal.h - what the planner kit's files (planner.c, result.c,
 * planner_link.c) share: its limits, the serving state, the functions
 * one calls of another. Not part of the API. */
#ifndef MPB_PLANNER_INTERNAL_H
#define MPB_PLANNER_INTERNAL_H

#include <pthread.h>
#include <signal.h>
#include <stdint.h>

#include <lcm/lcm.h>

#include "mpbench/mpbench.h"
#include "mpbench/planner.h"
#include "mpbench/auth.h"
#include "mpb_plan_result_t.h"

/* How many finished runs are remembered, to answer a repeated request. */
#define MPB__RESULTS_KEPT 64
/* A result is re-sent until acknowledged, for as long as it is kept:
 * after MPB__RESEND_S, the wait doubling to MPB__RESEND_MAX_S, and at once
 * when a hub link connects again. A planner closing (--max-runs) waits at
 * most MPB__CLOSING_WAIT_S for its last results' acknowledgements. */
#define MPB__RESEND_S 0.2
#define MPB__RESEND_MAX_S 2.0
#define MPB__CLOSING_WAIT_S 10.0
/* Longest wait in select(), so that *stop and re-sends are seen promptly. */
#define MPB__POLL_S 0.05
/* LCM queue lengths: acks are small and may come many at once (a commit
 * of several results); requests are large and few. */
#define MPB__ACK_QUEUE 1000
#define MPB__REQUEST_QUEUE 8
/* Closest two announces may be (ms). */
#define MPB__ANNOUNCE_GAP_MS 50
/* A request is acknowledged (REQUEST_RECEIVED) only if its solve is still
 * running this long after it began; a quicker result acknowledges its own
 * request. Well below the daemon's re-send interval (250 ms). */
#define MPB__ACK_AFTER_S 0.05
/* Through a hub, every heartbeat also goes to the planner itself, on its
 * own acknowledgement channel: the hub relays it back. None back for this
 * long (or three heartbeats, if longer) while connected: the hub is
 * stalled (a client that never reads blocks it), as the daemon judges by
 * its own statuses (MPBD_HUB_ECHO_MAX_S). */
#define MPB__ECHO_MAX_S 5.0
/* A closing planner (max_runs reached) waits through a stall for its last
 * results' acknowledgements as long as the daemon waits for a hub away or
 * stalled before it stops (MPBD_HUB_AWAY_MAX_S), then stops too. */
#define MPB__STALL_CLOSING_MAX_S 60.0

typedef struct mpb__kept {
    int used;
    int acked;
    int sends;                 /* since it was last acknowledged */
    double first_send_s;
    double next_send_s;
    mpb_plan_result_t res;     /* owned; res.attempt_id names the run */
} mpb__kept;

typedef struct mpb__server {
    const mpb_planner_def *def;
    lcm_t *lcm;
    mpb_auth *auth;             /* NULL: messages are not authenticated */
    char id[MPB_PLANNER_ID_MAX + 1];
    char host[256];
    char request_channel[sizeof MPB_CHANNEL_REQUEST_PREFIX + MPB_PLANNER_ID_MAX];
    char ack_channel[sizeof MPB_CHANNEL_ACK_PREFIX + MPB_PLANNER_ID_MAX];
    int heartbeat_ms;

    long solved;                /* runs answered (solve() called) */
    long max_runs;
    int run_error;              /* an MPB_E... code that ends the loop */

    mpb__kept kept[MPB__RESULTS_KEPT];
    int kept_next;              /* ring position of the next result */
    long hub_connects;          /* the hub link's connections, last seen */

    /* Through a hub: the link's echo, watched by the serving thread. */
    int is_hub;
    double stall_s;             /* no echo this long: stalled */
    double echo_back_s;         /* monotonic s: an echo came back, or a
                                   connection began whose echo is to come */
    long echo_connects;         /* the connection that echo_back_s is of */
    double stalled_since;       /* the last echo before the stall */
    int relays_again;           /* the stall ended: every result goes now */
    int link_said;              /* the link's state last told the user:
                                   0 none yet, 1 up, 2 away */
    double link_lost_s;         /* monotonic s: the link went away */

    /* Shared with the heartbeat thread, under mu. */
    pthread_mutex_t mu;
    pthread_cond_t cond;
    char active[MPB_ATTEMPT_ID_SIZE];   /* run being solved, "" if idle */
    double active_since;            /* monotonic s, when its solve began */
    int active_acked;               /* REQUEST_RECEIVED sent for it */
    int active_told;                /* bits 1 << run_ack_t kind: the
                                       SETTING_UP, PLANNING sent for it */
    int closed;                     /* capacity 0: max_runs reached */
    int quit;
    int announce_now;
    double waiting_until;           /* the thread sleeps until; 0: awake */
    int stalled;                    /* the hub relays nothing: send only
                                       the echo (written by the serving
                                       thread alone) */
    /* With a secret: the instance of the daemon last heard (auth.h),
     * which every message echoes; 0 before any, when the planner does
     * not announce (no daemon would believe it). */
    uint64_t daemon;
    volatile sig_atomic_t *stop;    /* mpb_planner_serve()'s, for solve() */
} mpb__server;

/* result.c: LCM cannot encode a NULL string, so every string of res gets
 * a value (MPB_OK, MPB_ENOMEM); and res's stages, values and progress
 * freed, leaving none. */
int mpb__result_fill_strings(mpb_plan_result_t *res);
void mpb__result_clear_lists(mpb_plan_result_t *res);

/* planner_link.c, called by the serving thread: one line to the user
 * (def->on_warning); the heartbeat's echo sent, and one come back; the
 * link looked at when nothing waits to be handled (a stall, an outage). */
void mpb__warn(mpb__server *s, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
void mpb__echo(mpb__server *s);
/* Send run_ack_t kind for the run in hand, once per run (solve_limits.c). */
void mpb__tell_phase(void *kit, int kind);
void mpb__echo_back(mpb__server *s);
void mpb__watch_link(mpb__server *s);

#endif /* MPB_PLANNER_INTERNAL_H */
