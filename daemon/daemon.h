/*
 * daemon.h - the state of mpbenchd, shared by its parts:
 *   main.c       options, signals, the poll loop
 *   experiment.c reading the experiment file: its settings; the parts
 *     experiment_robot.c   the robot, its SRDF and planning group, worlds
 *     experiment_scenes.c  the scenes: list, plain scenes, their queries
 *     experiment_entry.c   what both kinds of entry share: set, held joints
 *     experiment_moveit.c  MoveIt problem sets and scene files in it
 *     experiment_planners.c planner configurations and parameters
 *   moveit.c     MoveIt PlanningScene and MotionPlanRequest YAML files
 *   yamldoc.c    the YAML kit of both: one checked document, faults placed
 *   check_meshes.c whether planners will find the robot's meshes
 *   doomed.c     stopping when every configuration's first run failed alike
 *   planners.c   the table of planner processes, from their announcements
 *   announce.c   an announcement as it arrives: table, runs, queue
 *   runs.c       a run's life: pending queues, flights, take-back, crashes
 *   scheduler.c  which run goes to which planner; resends and deadlines
 *   results.c    a result as it arrives: for a run in flight, from its planner?
 *   measure.c    a result's stages verified and measured
 *   record.c     a measured result counted and stored
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
 *
 * Calls go one way (tests/tools/daemon_layers.py checks it): the handlers
 * (announce.c, results.c, scheduler.c's acks, daemons.c, status.c) and
 * main.c call down to verifier.c, then measure.c and record.c, then
 * runs.c, then acks.c, planners.c, hub.c and the leaves; nothing below
 * calls back up. Each part of struct mpbd below is one file's, allocated
 * and freed there; the prototypes follow in sections, one per file,
 * lowest first.
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
/* The most verifier threads --verify-threads takes. */
#define MPBD_VERIFY_THREADS_MAX 256
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
    char    attempt_id[MPB_ATTEMPT_ID_SIZE];
    int     planner;         /* index into planners: who still plans it */
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
    /* The layout (wire.h) of the requests and acks it takes: 0, today's;
     * MPB_WIRE_BEFORE_ATTEMPT_ID for a planner built before attempt_id,
     * known by its announcements in an older layout. */
    int      layout;
} mpbd_planner;

/* A run not yet done, as the scheduler holds it. */
typedef struct mpbd_run {
    int64_t id;              /* runs.id */
    int     config;          /* index into experiment configs */
    int     query;           /* index into experiment queries */
    int64_t seed;
    int     attempts;        /* requests sent so far, over all attempts */
    char    attempt_id[MPB_ATTEMPT_ID_SIZE];   /* current attempt, "" if none yet */
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
    int      phase;          /* MPBD_PHASE_*: what its planner said last */
    double   deadline;
} mpbd_flight;

/* A flight's phase by its planner's word (run_ack_t): sent (or nothing
 * said), building its model of a new robot and scene, planning. */
enum { MPBD_PHASE_SENT, MPBD_PHASE_SETTING_UP, MPBD_PHASE_PLANNING };

/* A stored result to acknowledge, to its planner, once its transaction
 * commits (acks.c). */
typedef struct mpbd_ack_due {
    char    attempt_id[MPB_ATTEMPT_ID_SIZE];
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
    char    attempt_id[MPB_ATTEMPT_ID_SIZE];
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
    /* of rejected, by the message list's channel each came on (inbox.c),
     * the last for any other channel: each kind's first ten are logged,
     * so that a flood on one channel hides no other's */
    long rejected_on[MPB_WIRE_COUNT + 1];
} mpbd_counters;

/* runs.c: every run not yet done, from its configuration's queue to its
 * result. */
typedef struct mpbd_runs {
    /* Pending runs per configuration: a queue each, so that any idle
     * planner finds its next run without a search. */
    mpbd_run       **pending;        /* [config] -> array */
    int             *pending_len, *pending_head;
    int              num_configs;
    long             total_pending;
    mpbd_flight     *flights;        /* requests out, waiting for results */
    int              num_flights, cap_flights;
    mpbd_unrecorded *unrecorded;     /* sent, not yet written as sent */
    int              num_unrecorded, cap_unrecorded;
    /* Runs planners still plan that the daemon gave up on at their
     * deadline: each holds one of its planner's capacity until an
     * announcement leaves it out. */
    mpbd_abandoned  *abandoned;
    int              num_abandoned, cap_abandoned;
    /* Runs finished lately, so that a re-sent result is acknowledged
     * again instead of being counted as a stray. */
    char             recent[256][MPB_ATTEMPT_ID_SIZE];
    int              recent_next;
    /* Told of each run taken back (replay.c keeps its own account). */
    void           (*on_take_back)(void *ud, const mpbd_run *run);
    void            *take_back_ud;
} mpbd_runs;

/* acks.c: acknowledgements of stored results, and the runs' latency. */
typedef struct mpbd_acks {
    /* Results stored in the open transaction, acknowledged only once it
     * commits: an ack is a promise that the result is on disk. */
    mpbd_ack_due    *due;
    int              num_due, cap_due;
    /* Committed, not yet told: for the next request to their planner. */
    mpbd_ack_due    *owed;
    int              num_owed, cap_owed;
    mpbd_latency     latency;
} mpbd_acks;

/* hub.c: a tcpq:// URL's link, as the loop last saw it. */
typedef struct mpbd_hub {
    int              state;          /* MPBD_HUB_... */
    double           lost_at;        /* monotonic s, when it went away */
    long             bad;            /* its dropped frames, last logged */
    long             connects;       /* its connections made, last seen */
    double           echo_at;        /* monotonic s: own status heard back
                                        (or the link made), 0 before */
} mpbd_hub;

/* scheduler.c: the backlog's bounds: results handed to the verifier, not
 * stored, by count and by their bytes; requests wait while it is over
 * either (held: logged once each way). */
typedef struct mpbd_backlog {
    long             max;
    double           bytes_max;
    int              held;
    double           logged;         /* monotonic s: one line in 10 s */
} mpbd_backlog;

typedef struct mpbd {
    lcm_t           *lcm;
    mpb_auth        *auth;           /* NULL: messages are not authenticated */
    uint64_t         msg_from;       /* the sender instance of the message
                                        being handled (mpbd_receive) */
    int              msg_layout;     /* and its layout (wire.h), 0 today's */
    /* The younger daemon whose status the next status answers (echoes),
     * so that it may believe it (daemons.c); 0 if none. */
    uint64_t         status_echo;
    int              requested;      /* a request has gone out */
    mpbd_hub         hub;
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

    mpbd_planner    *planners;       /* planners.c */
    int              num_planners, cap_planners;
    mpbd_runs        runs;
    mpbd_acks        acks;

    int              next_config;    /* round-robin starts for dispatch */
    int              next_planner;
    /* --replay: the log's clock, which starts a queued run's times
     * (mpbd_clock()); live, the monotonic clock. */
    int              replaying;
    double           replay_now;

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
    mpbd_backlog     backlog;
    double           last_status;
    double           last_wait_log;
    double           last_bad_announce_log;
} mpbd;

/* ---- log.c ------------------------------------------------------------ */
void mpbd_log(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
/* Log the store's last error, naming the database, unless it is the one
 * logged last (d->db_error). */
void mpbd_db_error(mpbd *d);

/* ---- latency.c -------------------------------------------------------- */
int  mpbd_latency_init(mpbd_latency *l);
void mpbd_latency_add(mpbd_latency *l, double seconds);
long mpbd_latency_quantile_us(const mpbd_latency *l, double p);
void mpbd_latency_free(mpbd_latency *l);

/* ---- doomed.c --------------------------------------------------------- */
/* A stored result of configuration config (its status and runs.message);
 * frees with mpbd_doomed_free(). */
void mpbd_doomed_result(mpbd *d, int config, const char *status,
                        const char *message);
void mpbd_doomed_free(mpbd *d);

/* ---- thin.c ----------------------------------------------------------- */
/* The robot's lever arm (m per rad of joint-space motion, an estimate) in
 * scene i, and one line per obstacle part thinner than resolution x that,
 * given to out; returns how many. */
double mpbd_lever_arm(const mpbd_experiment *e, int scene);
int    mpbd_warn_thin(const mpbd_experiment *e, double resolution,
                      void (*out)(void *ud, const char *line), void *ud);

/* ---- hub.c ------------------------------------------------------------ */
/* What a round of the loop learnt of the hub's link: the caller pauses the
 * clocks of planners and runs for away_s (mpbd_scheduler_pause) and, when
 * relinked, has them wait to be heard again (mpbd_scheduler_relink). */
typedef struct mpbd_hub_news {
    double away_s;           /* network time to leave out of the clocks */
    int    relinked;         /* the link is back, or made again */
    int    stop;             /* away over MPBD_HUB_AWAY_MAX_S */
} mpbd_hub_news;
/* Once a loop round of secs seconds, with a hub link: log its changes and
 * say what they mean in *news. 1 when it has been away over
 * MPBD_HUB_AWAY_MAX_S: stop. Without a hub: 0, *news empty. */
int  mpbd_hub_watch(mpbd *d, double now, double secs, mpbd_hub_news *news);
/* 1 with a hub link none of whose echoes came lately (MPBD_HUB_ECHO_DUE_S):
 * silence heard then may be the hub's, not a planner's. */
int  mpbd_hub_unproven(const mpbd *d, double now);
/* 1 while the hub is away or stalled: a send now would be lost. */
int  mpbd_hub_down(const mpbd *d);
/* 1 without a hub, or if the daemon's own status came back after since
 * (monotonic s): then silence since is the sender's, not the hub's. */
int  mpbd_hub_heard_since(const mpbd *d, double since);
/* The daemon heard its own status back (daemons.c): the link works. */
void mpbd_hub_echo(mpbd *d, double now);

/* ---- inbox.c ---------------------------------------------------------- */
/* 1 with a received message decoded into *msg (the generated struct of
 * type; free with mpb_receive_done()) if it is authentic, fresh and
 * well-formed; else 0, the message counted and logged as rejected. Its
 * sender's instance (auth.h) in d->msg_from either way. */
int  mpbd_receive(mpbd *d, mpb_wire_type type, const lcm_recv_buf_t *rbuf,
                  const char *channel, void *msg);
/* Count a message received on channel as rejected, and log why: the
 * first ten on each channel of the message list (and on any other), then
 * one in a thousand of all. */
void mpbd_reject(mpbd *d, const char *channel, const char *why);

/* ---- planners.c ------------------------------------------------------- */
/* The planner an announcement names, added or updated (its offer, its
 * capacity, closing, heartbeat, last heard now); NULL if the announcement
 * is refused (counted and logged) or there is no memory. */
mpbd_planner *mpbd_planner_learn(mpbd *d, const mpb_planner_announce_t *m,
                                 double now);
/* Mark planners silent for too long as gone; returns how many went. */
int  mpbd_planners_expire(mpbd *d, double now);
int  mpbd_planner_offers(const mpbd_planner *p, const char *name,
                         const char *algorithm);
/* The instance (auth.h) of the planner with this id, 0 if unknown. */
uint64_t mpbd_planner_instance(const mpbd *d, const char *id);
/* The layout (wire.h) of the acks the planner with this id takes; 0
 * (today's) if unknown. */
int  mpbd_planner_layout(const mpbd *d, const char *id);
void mpbd_planners_free(mpbd *d);

/* ---- acks.c ----------------------------------------------------------- */
int  mpbd_acks_init(mpbd *d);          /* MPB_OK, or MPB_ENOMEM */
void mpbd_acks_free(mpbd *d);
/* Publish an acknowledgement to a planner now (on its MPB_ACK_<id>). */
void mpbd_ack(mpbd *d, const char *planner_id, const char *attempt_id, int kind);
/* Acknowledge a planner's stored result once the transaction commits;
 * sent_at, the request's first send, counts the run's latency then (< 0:
 * a result stored before, sent again: not counted, answered at once). */
int  mpbd_ack_after_commit(mpbd *d, const char *planner_id,
                           const char *attempt_id, double sent_at);
/* After a commit: count the runs' latency; what it made true is now owed. */
void mpbd_acks_flush(mpbd *d);
/* The transaction holding them rolled back or nobody waits (a replay):
 * forget the acknowledgements due after it. */
void mpbd_acks_drop(mpbd *d);
int  mpbd_acks_due(const mpbd *d);     /* how many wait for the commit */
/* Take up to max acknowledgements owed to a planner, for its request. */
int  mpbd_owed_take(mpbd *d, const char *planner_id,
                    char (*ids)[MPB_ATTEMPT_ID_SIZE], int max);
/* Send alone those owed acknowledgements whose time is up (all: every one). */
void mpbd_owed_send(mpbd *d, double now, int all);

/* ---- runs.c ----------------------------------------------------------- */
int  mpbd_runs_load(mpbd *d);          /* unfinished runs from the store */
void mpbd_runs_free(mpbd *d);
int  mpbd_runs_done(const mpbd *d);    /* none pending, none in flight */
int  mpbd_runs_waiting(const mpbd *d, int config);  /* pending of config */
/* The next pending run of config put in flight to planner (waiting in its
 * queue if queued), with a new attempt id unless it was sent before a
 * restart; the caller publishes it. NULL if none or out of memory. */
mpbd_flight *mpbd_runs_send(mpbd *d, int config, int planner, int queued);
/* Write the runs sent since the last call as sent (attempts, attempt id,
 * planner), in the open transaction. */
int  mpbd_runs_record_sent(mpbd *d);
/* A flight for run, to planner, timed from now (replay.c's requests, as
 * well as mpbd_runs_send's). NULL when out of memory. Pointers to other
 * flights may move. */
mpbd_flight *mpbd_flight_start(mpbd *d, const mpbd_run *run, int planner,
                               int queued, double now);
mpbd_flight *mpbd_flight_find(mpbd *d, const char *attempt_id);
/* Remove an ended flight; the next request waiting at its planner, if
 * any, starts now. */
void mpbd_flight_remove(mpbd *d, mpbd_flight *f);
void mpbd_runs_each_pending(const mpbd *d,
                            void (*fn)(void *ud, const mpbd_run *run), void *ud);
void mpbd_runs_each_flight(mpbd *d, void (*fn)(void *ud, mpbd_flight *f),
                           void *ud);
/* Now, by the clock flights are timed with: monotonic, or the log's. */
double mpbd_clock(const mpbd *d);
/* Queue a run again for a new attempt. */
int  mpbd_requeue(mpbd *d, const mpbd_run *run);
/* A request its planner never started (declined, or left waiting at a
 * planner that closed or went away): pending again, as if never sent. */
int  mpbd_take_back(mpbd *d, mpbd_flight *f, const char *why);
/* A run ended without a result (crash, lost planner): retry it if the
 * experiment allows, else record it as crashed (mpbd_run_crashed). */
int  mpbd_record_crash(mpbd *d, mpbd_flight *f, const char *why);
/* Store f's run as a crash, why its message, and end its flight. */
int  mpbd_run_crashed(mpbd *d, mpbd_flight *f, const char *why,
                      double wall_time);
/* Its planner builds its model for f (run_ack_t SETTING_UP): the deadline
 * waits MPBD_SETUP_ALLOWANCE_S more. Then it plans (PLANNING): the time
 * limit and grace run from now. Each once per attempt, in this order; a
 * flight waiting in the planner's queue starts first. */
void mpbd_flight_setting_up(mpbd *d, mpbd_flight *f, double now);
void mpbd_flight_planning(mpbd *d, mpbd_flight *f, double now);
/* Given up on at its deadline: its planner may still plan it, and while
 * it names it, the run holds one of its slots. */
void mpbd_runs_abandon(mpbd *d, const mpbd_flight *f);
/* What a planner has on its hands: runs in flight, runs given up on that
 * it still plans, and runs it plans that this daemon did not send it. */
int  mpbd_planner_busy(const mpbd *d, int planner);
/* A planner that takes no more runs: take back the requests waiting at it,
 * but for the runs it says it is working on (active_runs). */
void mpbd_planner_closing(mpbd *d, int planner, char *const *active_runs,
                          int num_active);
/* A planner says it is working on these runs, and on unknown more this
 * daemon does not know (mpbd_runs_knows): any of them queued starts, and
 * a run given up on that it leaves out frees its slot. */
void mpbd_planner_working_on(mpbd *d, int planner, char *const *active_runs,
                             int num_active, int unknown);
/* 1 if attempt_id is a run this daemon knows for planner: in flight, given up on
 * by it, stored lately, or pending to be sent again after a restart. */
int  mpbd_runs_knows(const mpbd *d, int planner, const char *attempt_id);
void mpbd_runs_remember(mpbd *d, const char *attempt_id);      /* just stored */
int  mpbd_recently_done(const mpbd *d, const char *attempt_id); /* the last 256 */

/* ---- measure.c -------------------------------------------------------- */
/* Per stage, what the store needs, owned by the measurement. */
typedef struct mpbd_stage_work {
    mpb_stage_record  rec;
    mpb_named         metrics[MPB_NUM_METRICS];
    mpb_stage_measure m;
} mpbd_stage_work;
/* A result's stages verified and measured (mpb_measure_stage()); where
 * the planner was given a seen scene (experiment_seen.c), its final stage
 * judged there too. */
typedef struct mpbd_measured {
    mpbd_stage_work *works;          /* per stage */
    int              judged_seen;    /* 1: seen holds the final stage's
                                        verdict on what was seen */
    mpb_stage_measure seen;
    double verify_start, verified;   /* monotonic s */
} mpbd_measured;
/* The worlds a verifier thread judges in, per scene: the truth, and what
 * was seen (NULL for a scene without). */
typedef struct mpbd_worlds {
    mpb_world **truth, **seen;
} mpbd_worlds;
/* In worlds (a verifier thread's own copies; NULL: the experiment's),
 * which it changes (held joints, caches); it reads d and changes nothing
 * else, so that verifier threads may call it while the loop runs, each
 * with worlds of its own. */
int  mpbd_result_measure(const mpbd *d, const mpbd_worlds *worlds,
                         const mpbd_flight *f, const mpb_plan_result_t *m,
                         mpbd_measured *out);
void mpbd_measured_free(mpbd_measured *ms);

/* ---- record.c --------------------------------------------------------- */
/* Store a measured result in the open transaction and acknowledge it
 * after the commit (or reject it: not the run's current attempt).
 * MPB_OK, or MPBD_RETRY when the store failed: keep it, store it again. */
#define MPBD_RETRY 1
int  mpbd_result_store(mpbd *d, const mpbd_flight *f,
                       const mpb_plan_result_t *m, double recv,
                       const mpbd_measured *ms);
/* Count a result as rejected, and log why (the first ten, then one in
 * a thousand). */
void mpbd_result_reject(mpbd *d, const char *why, const mpb_plan_result_t *m);

/* ---- verifier.c ------------------------------------------------------- */
/* Worker threads that verify and measure results while the loop goes
 * on, so that a planner's next request does not wait for its last
 * result's verification, and many planners' results are verified at
 * once. The loop stores what they finished in order of completion, in
 * its own transaction, and acknowledges each after the commit. */
/* threads workers (at least 1), each with worlds of its own; MPB_OK, or
 * an error (said in the log): verify inline. */
int  mpbd_verifier_start(mpbd *d, int threads);
/* The host's cores less one (for the loop), at least 1. */
int  mpbd_verifier_threads_default(void);
void mpbd_verifier_stop(mpbd *d);      /* results not stored are dropped */
/* Hand over a result (copied) of flight f; MPB_OK, or an error when there
 * is no verifier or no memory (then verify it inline). */
int  mpbd_verifier_submit(mpbd *d, const mpbd_flight *f,
                          const mpb_plan_result_t *m, double recv);
/* 1 if the attempt is handed to the verifier and not yet stored. */
int  mpbd_verifier_has(const mpbd *d, const char *attempt_id);
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

/* ---- scheduler.c ------------------------------------------------------ */
/* MPB_OK if every plan request of experiment e fits in an LCM message
 * (MPB_LCM_MESSAGE_MAX, with the authentication trailer if authenticated),
 * else MPB_EINVAL and one line in err naming the file, the scene and the
 * sizes: a larger message would be dropped by every receiver. */
int  mpbd_requests_fit(const mpbd_experiment *e, int authenticated, char *err,
                       size_t errlen);
/* Send pending runs to planners with room; returns how many went. */
int  mpbd_scheduler_dispatch(mpbd *d, double now);
void mpbd_scheduler_tick(mpbd *d, double now); /* resends, deadlines, lost planners */
/* The daemon did not run for this long: planners' silence and runs'
 * deadlines are counted without it, so that its own absence does not make
 * its planners gone or its runs crashes. */
void mpbd_scheduler_stalled(mpbd *d, double secs);
/* The same, silently: the network was away (mpbd_hub_news); that time is
 * left out of the runs' time too (mpbd_flight.away). */
void mpbd_scheduler_pause(mpbd *d, double secs);
/* The hub is back: every planner's runs wait until it is heard again, and
 * requests not acknowledged go again at once. */
void mpbd_scheduler_relink(mpbd *d, double now);
/* A message of planner (an index) arrived: if it is the first since the
 * hub came back, its runs' clocks go on, and its runs' requests go again,
 * so that it answers at once what it finished meanwhile. */
void mpbd_planner_heard(mpbd *d, int planner, double now);
/* Planners' acknowledgements of requests (MPB_ACK): received, declined. */
void mpbd_scheduler_subscribe(mpbd *d);

/* ---- announce.c ------------------------------------------------------- */
void mpbd_announce_subscribe(mpbd *d);   /* MPB_ANNOUNCE */

/* ---- results.c -------------------------------------------------------- */
void mpbd_results_subscribe(mpbd *d);    /* MPB_RESULT */

/* ---- daemons.c -------------------------------------------------------- */
void mpbd_daemons_subscribe(mpbd *d);    /* MPB_STATUS of other daemons */

/* ---- status.c --------------------------------------------------------- */
void mpbd_status_publish(mpbd *d, const char *state, double now);

/* ---- replay.c --------------------------------------------------------- */
/* Rebuild the experiment's results from an lcm-logger log
 * (docs/record-and-replay.md); 0 if the whole log was read, 1 if it is
 * missing, damaged or of another experiment (what came before is stored). */
int  mpbd_replay(mpbd *d, const char *log_path);
/* 0 if log_path is a file that can be read; otherwise says why on stderr:
 * checked before the database is opened, so a wrong path creates none. */
int  mpbd_replay_log_readable(const char *log_path);

#endif
