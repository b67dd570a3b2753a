/*
 * daemon.h - the state of mpbenchd, shared by its parts:
 *   main.c       options, signals, the poll loop
 *   experiment.c reading the experiment file: its settings; the parts
 *     experiment_robot.c   the robot, its SRDF and planning group, worlds
 *     experiment_scenes.c  scenes, queries, goals, held joints
 *     experiment_moveit.c  MoveIt problem sets and scene files in it
 *     experiment_planners.c planner configurations and parameters
 *   moveit.c     MoveIt PlanningScene and MotionPlanRequest YAML files
 *   yamldoc.c    the YAML kit of both: one checked document, faults placed
 *   check_meshes.c whether planners will find the robot's meshes
 *   doomed.c     stopping when every configuration's first run failed alike
 *   planners.c   the planner processes seen on MPB_ANNOUNCE
 *   scheduler.c  which run goes to which planner; resends and deadlines;
 *                requests waiting at a busy planner
 *   results.c    checking, verifying, measuring and storing results
 *   verifier.c   the thread that verifies and measures beside the loop
 *   status.c     the MPB_STATUS message
 *   acks.c       acknowledging stored results: on requests, or alone
 *   latency.c    each run's latency, request to commit, as a histogram
 *   thin.c       obstacles thinner than the verification step can see
 *   inbox.c      checking messages before they are decoded
 *   replay.c     --replay: results from an LCM log instead of the network
 *   daemons.c    other daemons on the same LCM URL: the younger one stops
 *   hub.c        a TCP hub's link: logged, waited for while it is away
 *   log.c        the console log
 */
#ifndef MPBD_DAEMON_H
#define MPBD_DAEMON_H

#include <stdint.h>

#include <lcm/lcm.h>

#include "mpbench/mpbench.h"
#include "experiment.h"
#include "mpb_plan_result_t.h"
#include "mpb_planner_announce_t.h"
#include "mpb_run_ack_t.h"

/* How often and how long things are retried or waited for. */
/* A request not acknowledged is re-sent after MPBD_REQUEST_RESEND_S, the
 * wait doubling to MPBD_REQUEST_RESEND_MAX_S, for as long as its run is in
 * flight (its deadline ends it); not while a hub is away, and at once when
 * it is back. */
#define MPBD_REQUEST_RESEND_S   0.25
#define MPBD_REQUEST_RESEND_MAX_S 4.0
#define MPBD_DEADLINE_GRACE_S   5.0    /* beyond the time limit, before crash */
/* A result later than the time limit plus this, by the daemon's clock from
 * the request's last send, is no success whatever time it reports: room
 * for the network both ways and for reading the request. */
#define MPBD_WALL_SLACK_S       1.0
/* At most this much of a planner's reported world_setup_time is left out
 * of the daemon's clock (results.c): as long as the peers' kit allows a
 * model to build (planners/peers/mpbpeers/peer.py, SETUP_MAX_S). */
#define MPBD_SETUP_ALLOWANCE_S  120.0
#define MPBD_PLANNER_MISSED     3      /* heartbeats missed = planner gone */
/* A round of the daemon's loop (at most 20 ms waiting for messages, then
 * handling them) that took longer than this: the daemon did not run
 * meanwhile (SIGSTOP, a suspended machine) or was busy. */
#define MPBD_STALL_S            1.0
/* How long a round of the loop waits for the results it handed to the
 * verifier, so that quick ones are stored in the same round (verifier.c). */
#define MPBD_SETTLE_S           0.0005
/* A result whose verification the scene's last cost per waypoint puts
 * at most this is verified in the loop, the worker being idle. */
#define MPBD_INLINE_S           0.0002
#define MPBD_STATUS_PERIOD_S    1.0
/* No request before this long after the loop starts: time to hear of an
 * older daemon on the same LCM URL (daemons.c). */
#define MPBD_LISTEN_S           0.25
#define MPBD_ACK_HOLD_S         0.02   /* an ack waits this long for a request */
#define MPBD_STORED_MAX         32     /* acks riding on one request */
/* The coarsest verification step --resolution takes (rad): coarser, a
 * segment would pass through an obstacle thinner than the step. */
#define MPBD_RESOLUTION_MAX     0.1
/* Results awaiting verification beyond which no request is sent, until
 * they drain (--backlog, --backlog-mb): the daemon's memory is bounded
 * whatever its verifier's pace. */
#define MPBD_BACKLOG_RESULTS    1000
#define MPBD_BACKLOG_MB         256
/* A hub (tcpq://) away this long: the daemon stops, to be resumed. */
#define MPBD_HUB_AWAY_MAX_S     60.0
/* The hub relays every message to its sender too: a link up over which
 * none of the daemon's own statuses (one a second) has come back for this
 * long is stalled (the hub blocked, as by a client that never reads), and
 * is waited for as if away. */
#define MPBD_HUB_ECHO_MAX_S     5.0
/* Past this without its own status back, the link is not known to work:
 * no planner is counted gone, no run given up on, until it is (hub.c). */
#define MPBD_HUB_ECHO_DUE_S     2.0
enum { MPBD_HUB_UNKNOWN, MPBD_HUB_UP, MPBD_HUB_AWAY, MPBD_HUB_STALLED };

/* The first result of each planner configuration in this session: when
 * every one failed with the same world error, every run would (doomed.c). */
typedef struct mpbd_doomed {
    unsigned char *seen;     /* per configuration: its first result came */
    int   num_seen;
    int   alike;             /* every first so far failed with why */
    int   stop;              /* every configuration's first did: stop */
    char  why[512];
} mpbd_doomed;

/* A run given up on at its deadline, that its planner may still plan. */
typedef struct mpbd_abandoned {
    char    uid[MPB_RUN_ID_SIZE];
    int64_t run_id;          /* runs.id, for the log */
    double  since;           /* monotonic s, when given up on */
    int     named;           /* an announcement named it since */
} mpbd_abandoned;

typedef struct mpbd_planner {
    char    id[MPB_PLANNER_ID_MAX + 1];
    char    host[64];        /* as announced; the per-host limit counts by it */
    char   *name;
    char  **algorithms;
    int     num_algorithms;
    int     capacity;
    int     capacity_seen;   /* it announced a capacity above 0 once */
    int     closing;         /* then 0: takes no more */
    int     active;          /* runs we have in flight on it */
    int     queued;          /* requests waiting at it behind those */
    /* Runs it still plans that the daemon gave up on at their deadline:
     * each holds one of its capacity until an announcement leaves it out
     * (scheduler.c). */
    mpbd_abandoned *abandoned;
    int     num_abandoned, cap_abandoned;
    /* Runs it announces it is planning that this daemon did not send it
     * (given up on by the daemon before a restart): each holds one of
     * its capacity, as a run given up on does. */
    int     unknown;
    /* Requests it declined in a row while announcing room for them; no
     * request goes to it before declined_until (monotonic s). */
    int     declines;
    double  declined_until;
    /* The hub came back at this time (monotonic s) and nothing has been
     * heard from this planner since: its own link may still be away, so
     * its runs' clocks wait until it is heard (mpbd_planner_heard); 0:
     * heard. */
    double  relinked;
    int     runs_done;
    double  heartbeat_s;
    double  last_seen;       /* monotonic s */
    int     gone;
    uint64_t instance;       /* its process's, from its announcements
                                (auth.h): what messages to it echo */
} mpbd_planner;

/* A run not yet done, as the scheduler holds it. */
typedef struct mpbd_run {
    int64_t id;              /* runs.id */
    int     config;          /* index into experiment configs */
    int     query;           /* index into experiment queries */
    int64_t seed;
    int     attempts;        /* requests sent so far, over all attempts */
    char    uid[MPB_RUN_ID_SIZE];   /* current attempt, "" if none yet */
} mpbd_run;

/* A request out on the network, waiting for its result. A queued one was
 * sent to a busy planner, to start as soon as that planner's run in flight
 * ends; until then it is not re-sent, has no deadline, and its times (wall
 * time, latency, deadline) start only when it does. */
typedef struct mpbd_flight {
    mpbd_run run;
    int      planner;        /* index into planners */
    int      queued;
    double   sent_at;        /* monotonic s: first send, or when it left
                                its planner's queue */
    double   last_send;
    int      sends;
    double   next_send;      /* monotonic s: re-send then, if not acked */
    /* Seconds since last_send that the link was away (a hub outage, then
     * until its planner is heard again): not the planner's, so left out
     * of the daemon's clock when its result is judged in time. */
    double   away;
    int      acked;          /* planner said REQUEST_RECEIVED, or named
                                it among its active runs */
    double   deadline;
} mpbd_flight;

/* A stored result to acknowledge, to its planner, once its transaction
 * commits (acks.c). */
typedef struct mpbd_ack_due {
    char    run_uid[MPB_RUN_ID_SIZE];
    char    planner_id[MPB_PLANNER_ID_MAX + 1];
    double  sent_at;         /* the request's first send; < 0: a result
                                sent again, answered alone and at once */
    double  due;             /* committed: when it goes alone, unless a
                                request to its planner takes it first */
} mpbd_ack_due;

/* A run sent whose state is not yet written: the next transaction writes
 * it, before the results it holds. */
typedef struct mpbd_unrecorded {
    int64_t run_id;
    char    run_uid[MPB_RUN_ID_SIZE];
    char    planner_id[MPB_PLANNER_ID_MAX + 1];
} mpbd_unrecorded;

/* Runs' latency, request first sent to result committed (latency.c):
 * 65536 counters of 1 us, then of 1 ms, then of 1 s, then one for all
 * longer than MPBD_LATENCY_MAX_US (about 18 hours). */
#define MPBD_LATENCY_TIER   65536
#define MPBD_LATENCY_TIERS  3
#define MPBD_LATENCY_MAX_US (65536L * 1000000L)
typedef struct mpbd_latency {
    uint32_t *count;         /* MPBD_LATENCY_TIERS tiers, then longer */
    uint64_t  n;
} mpbd_latency;

typedef struct mpbd_counters {
    long done, succeeded, failed, crashed, rejected, retried;
    long unproven;   /* of rejected: right tag, echoing another process */
} mpbd_counters;

typedef struct mpbd {
    lcm_t           *lcm;
    mpb_auth        *auth;           /* NULL: messages are not authenticated */
    uint64_t         msg_from;       /* the sender instance of the message
                                        being handled (mpbd_receive) */
    /* The younger daemon whose status the next status answers (echoes),
     * so that it may believe it (daemons.c); 0 if none. */
    uint64_t         status_echo;
    int              requested;      /* a request has gone out */
    int              hub_state;      /* MPBD_HUB_..., a tcpq:// URL's link */
    double           hub_lost_at;    /* monotonic s, when it went away */
    long             hub_bad;        /* its dropped frames, last logged */
    long             hub_connects;   /* its connections made, last seen */
    double           hub_echo_at;    /* monotonic s: own status heard back
                                        (or the link made), 0 before */
    /* Subscriptions, released before lcm_destroy(). */
    lcm_subscription_t *sub_announce, *sub_ack, *sub_result, *sub_status;
    mpb_store       *store;
    const char      *db_path;        /* as given */
    /* The last database error logged, not logged again until a commit
     * succeeds: a failed transaction fails every write in it alike. */
    char             db_error[256];
    mpbd_experiment *exp;
    int64_t          experiment_id;
    char             daemon_id[MPB_PLANNER_ID_MAX + 1];
    double           resolution;     /* verification step, rad */
    int              verbose;

    mpbd_planner    *planners;
    int              num_planners, cap_planners;

    /* Pending runs per configuration: a queue each, so that any idle
     * planner finds its next run without a search. */
    mpbd_run       **pending;        /* [config] -> array */
    int             *pending_len, *pending_head;
    long             total_pending;

    mpbd_flight     *flights;
    int              num_flights, cap_flights;
    mpbd_unrecorded *unrecorded;
    int              num_unrecorded, cap_unrecorded;

    int              next_config;    /* round-robin starts for dispatch */
    int              next_planner;
    /* --replay: the log's clock, which starts a queued run's times
     * (mpbd_clock()); live, the monotonic clock. */
    int              replaying;
    double           replay_now;
    /* Told of each run taken back (replay.c keeps its own account). */
    void           (*on_take_back)(void *ud, const mpbd_run *run);
    void            *take_back_ud;

    /* Results stored in the open transaction, acknowledged only once it
     * commits: an ack is a promise that the result is on disk. */
    mpbd_ack_due    *acks;
    int              num_acks, cap_acks;
    /* Committed, not yet told: for the next request to their planner. */
    mpbd_ack_due    *owed;
    int              num_owed, cap_owed;
    mpbd_latency     latency;

    /* Runs finished lately, so that a re-sent result is acknowledged
     * again instead of being counted as a stray. */
    char             recent[256][MPB_RUN_ID_SIZE];
    int              recent_next;

    int              runs_total;
    mpbd_counters    count;
    mpbd_doomed      doomed;
    double           started;        /* monotonic s */
    int64_t          started_utime;  /* the same moment, wall clock us */
    /* An older daemon heard on the LCM URL, as the log names it: then
     * this one stops (daemons.c). */
    char             elder[640];
    char             younger_logged[MPB_PLANNER_ID_MAX + 1];
    char             ignored_elder[MPB_PLANNER_ID_MAX + 1];
    struct mpbd_verifier *verifier;  /* verifier.c; NULL: verify inline */
    /* The backlog's bounds: results handed to the verifier, not stored,
     * by count and by their bytes; requests wait while it is over either
     * (backlog_held: logged once each way). */
    long             backlog_max;
    double           backlog_bytes_max;
    int              backlog_held;
    double           backlog_logged; /* monotonic s: at most one line in 10 s */
    double           last_status;
    double           last_wait_log;
    double           last_bad_announce_log;
} mpbd;

/* doomed.c: a stored result of configuration config (its status and
 * runs.message); frees with mpbd_doomed_free(). */
void mpbd_doomed_result(mpbd *d, int config, const char *status,
                        const char *message);
void mpbd_doomed_free(mpbd *d);

/* planners.c */
void mpbd_planners_subscribe(mpbd *d);
/* Mark planners silent for too long as gone; returns how many went. */
int  mpbd_planners_expire(mpbd *d, double now);
int  mpbd_planner_offers(const mpbd_planner *p, const char *name,
                         const char *algorithm);
/* The instance (auth.h) of the planner with this id, 0 if unknown. */
uint64_t mpbd_planner_instance(const mpbd *d, const char *id);
void mpbd_planners_free(mpbd *d);

/* daemons.c */
void mpbd_daemons_subscribe(mpbd *d);

/* scheduler.c */
/* MPB_OK if every plan request of experiment e fits in an LCM message
 * (MPB_LCM_MESSAGE_MAX, with the authentication trailer if authenticated),
 * else MPB_EINVAL and one line in err naming the file, the scene and the
 * sizes: a larger message would be dropped by every receiver. */
int  mpbd_requests_fit(const mpbd_experiment *e, int authenticated, char *err,
                       size_t errlen);
int  mpbd_scheduler_load(mpbd *d);             /* unfinished runs from the store */
int  mpbd_scheduler_dispatch(mpbd *d, double now);
/* Write the runs sent since the last call as sent (attempt, run id,
 * planner), in the open transaction. */
int  mpbd_scheduler_record_sent(mpbd *d);
void mpbd_scheduler_tick(mpbd *d, double now); /* resends, deadlines, lost planners */
/* The daemon did not run for this long: planners' silence and runs'
 * deadlines are counted without it, so that its own absence does not make
 * its planners gone or its runs crashes. */
void mpbd_scheduler_stalled(mpbd *d, double secs);
/* The same, silently: the network was away (hub.c); that time is left
 * out of the runs' time too (mpbd_flight.away). */
void mpbd_scheduler_pause(mpbd *d, double secs);
/* The hub is back: every planner's runs wait until it is heard again, and
 * requests not acknowledged go again at once. */
void mpbd_scheduler_relink(mpbd *d, double now);
/* A message of planner (an index) arrived: if it is the first since the
 * hub came back, its runs' clocks go on, and its runs' requests go again,
 * so that it answers at once what it finished meanwhile. */
void mpbd_planner_heard(mpbd *d, int planner, double now);
/* Queue a run again for a new attempt. */
int  mpbd_requeue(mpbd *d, const mpbd_run *run);
/* A request its planner never started (declined, or left waiting at a
 * planner that closed or went away): pending again, as if never sent. */
int  mpbd_take_back(mpbd *d, mpbd_flight *f, const char *why);
/* A planner that takes no more runs: take back the requests waiting at it,
 * but for the runs it says it is working on (active_runs). */
void mpbd_planner_closing(mpbd *d, int planner, char *const *active_runs,
                          int num_active);
/* A planner says it is working on these runs: any of them queued starts,
 * and a run given up on that it leaves out frees its slot. */
void mpbd_planner_working_on(mpbd *d, int planner, char *const *active_runs,
                             int num_active);
/* A new flight at the end of d->flights, for the caller to fill; NULL
 * when out of memory. Pointers to other flights may move. */
mpbd_flight *mpbd_flight_add(mpbd *d);
mpbd_flight *mpbd_flight_find(mpbd *d, const char *uid);
/* Remove an ended flight; the next request waiting at its planner, if
 * any, starts now. */
void mpbd_flight_remove(mpbd *d, mpbd_flight *f);
/* Now, by the clock flights are timed with: monotonic, or the log's. */
double mpbd_clock(const mpbd *d);
int  mpbd_scheduler_done(const mpbd *d);
void mpbd_scheduler_free(mpbd *d);
void mpbd_scheduler_subscribe(mpbd *d);

/* acks.c */
/* Publish an acknowledgement to a planner now (on its MPB_ACK_<id>). */
void mpbd_ack(mpbd *d, const char *planner_id, const char *run_uid, int kind);
/* Acknowledge a planner's stored result once the transaction commits;
 * sent_at, the request's first send, counts the run's latency then (< 0:
 * a result stored before, sent again: not counted, answered at once). */
int  mpbd_ack_after_commit(mpbd *d, const char *planner_id,
                           const char *run_uid, double sent_at);
/* After a commit: count the runs' latency; what it made true is now owed. */
void mpbd_acks_flush(mpbd *d);
/* Take up to max acknowledgements owed to a planner, for its request. */
int  mpbd_owed_take(mpbd *d, const char *planner_id,
                    char (*ids)[MPB_RUN_ID_SIZE], int max);
/* Send alone those owed acknowledgements whose time is up (all: every one). */
void mpbd_owed_send(mpbd *d, double now, int all);

/* thin.c: the robot's lever arm (m per rad of joint-space motion, an
 * estimate) in scene i, and one line per obstacle part thinner than
 * resolution x that, given to out; returns how many. */
double mpbd_lever_arm(const mpbd_experiment *e, int scene);
int    mpbd_warn_thin(const mpbd_experiment *e, double resolution,
                      void (*out)(void *ud, const char *line), void *ud);

/* latency.c */
int  mpbd_latency_init(mpbd_latency *l);
void mpbd_latency_add(mpbd_latency *l, double seconds);
long mpbd_latency_quantile_us(const mpbd_latency *l, double p);
void mpbd_latency_free(mpbd_latency *l);

/* results.c */
void mpbd_results_subscribe(mpbd *d);
/* A result's stages verified and measured (mpb_measure_stage()); touches
 * the experiment's worlds and nothing else of d, so that the verifier's
 * thread may call it while the loop runs. */
struct mpbd_stage_work;
typedef struct mpbd_measured {
    struct mpbd_stage_work *works;   /* per stage */
    double verify_start, verified;   /* monotonic s */
} mpbd_measured;
int  mpbd_result_measure(const mpbd *d, const mpbd_flight *f,
                         const mpb_plan_result_t *m, mpbd_measured *out);
void mpbd_measured_free(mpbd_measured *ms);
/* Store a measured result in the open transaction and acknowledge it
 * after the commit (or reject it: not the run's current attempt).
 * MPB_OK, or MPBD_RETRY when the store failed: keep it, store it again. */
#define MPBD_RETRY 1
int  mpbd_result_store(mpbd *d, const mpbd_flight *f,
                       const mpb_plan_result_t *m, double recv,
                       const mpbd_measured *ms);

/* verifier.c: a worker thread that verifies and measures results while
 * the loop goes on, so that a planner's next request does not wait for
 * its last result's verification. The loop stores what it finished in
 * order of completion, in its own transaction, and acknowledges each
 * after the commit, as before. */
int  mpbd_verifier_start(mpbd *d);     /* MPB_OK, or an error: verify inline */
void mpbd_verifier_stop(mpbd *d);      /* results not stored are dropped */
/* Hand over a result (copied) of flight f; MPB_OK, or an error when there
 * is no verifier or no memory (then verify it inline). */
int  mpbd_verifier_submit(mpbd *d, const mpbd_flight *f,
                          const mpb_plan_result_t *m, double recv);
int  mpbd_verifier_has(const mpbd *d, const char *uid);  /* handed over, not stored */
/* 1: verify m in the loop (the worker idle, m quick by its scene's last
 * cost), then mpbd_verifier_learn() its cost, as collecting does. */
int  mpbd_verifier_quick(const mpbd *d, const mpbd_flight *f,
                         const mpb_plan_result_t *m);
void mpbd_verifier_learn(mpbd *d, const mpbd_flight *f,
                         const mpb_plan_result_t *m, const mpbd_measured *ms);
int  mpbd_verifier_pending(const mpbd *d);               /* how many */
double mpbd_verifier_bytes(const mpbd *d);  /* their encoded bytes */
int  mpbd_verifier_fd(const mpbd *d);  /* readable when one is done; -1: none */
/* Wait up to max_s for the results handed over since the last call to be
 * measured (once per hand-over: a long one is not waited for again). */
void mpbd_verifier_settle(mpbd *d, double max_s);
/* Store those done, in order, in the open transaction. */
void mpbd_verifier_collect(mpbd *d);
/* A run ended without a result (crash, lost planner): retry it if the
 * experiment allows, else record it as crashed. */
int  mpbd_record_crash(mpbd *d, mpbd_flight *f, const char *why);
/* A run whose result was stored lately (the last 256). */
int  mpbd_recently_done(const mpbd *d, const char *uid);

/* inbox.c: 1 with a received message decoded into *msg (the generated
 * struct of type; free with mpb_receive_done()) if it is authentic, fresh
 * and well-formed; else 0, the message counted and logged as rejected.
 * Its sender's instance (auth.h) in d->msg_from either way. */
int  mpbd_receive(mpbd *d, mpb_wire_type type, const lcm_recv_buf_t *rbuf,
                  const char *channel, void *msg);
/* Count a message received on channel as rejected, and log why. */
void mpbd_reject(mpbd *d, const char *channel, const char *why);

/* hub.c: once a loop round of secs seconds, with a hub link: log its
 * changes; while it is away, pause the clocks of planners and runs. 1 when
 * it has been away over MPBD_HUB_AWAY_MAX_S: stop. */
int  mpbd_hub_watch(mpbd *d, double now, double secs);
/* 1 with a hub link none of whose echoes came lately (MPBD_HUB_ECHO_DUE_S):
 * silence heard then may be the hub's, not a planner's. */
int  mpbd_hub_unproven(const mpbd *d, double now);

/* status.c */
void mpbd_status_publish(mpbd *d, const char *state, double now);

/* replay.c: rebuild the experiment's results from an lcm-logger log
 * (docs/record-and-replay.md); 0 if the whole log was read, 1 if it is
 * missing, damaged or of another experiment (what came before is stored). */
int  mpbd_replay(mpbd *d, const char *log_path);
/* 0 if log_path is a file that can be read; otherwise says why on stderr:
 * checked before the database is opened, so a wrong path creates none. */
int  mpbd_replay_log_readable(const char *log_path);

/* log.c */
void mpbd_log(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
/* Log the store's last error, naming the database, unless it is the one
 * logged last (d->db_error). */
void mpbd_db_error(mpbd *d);

#endif
