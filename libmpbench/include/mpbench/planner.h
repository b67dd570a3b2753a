/*
 * planner.h - the protocol side of a planner process written in C or C++,
 * so that the planner itself is only a solve function.
 *
 * mpb_planner_serve() joins LCM, announces the planner every heartbeat (from
 * a thread of its own, so a long solve does not look like a crash), takes
 * requests addressed to it, acknowledges each, calls solve() once per
 * attempt id, publishes the result and re-sends it until the daemon acknowledges it. A
 * request seen again is answered from the results it remembers (the last
 * 64 runs), never solved twice.
 *
 * Through a hub (tcpq://, link.h) each heartbeat also goes to the planner
 * itself, on its own acknowledgement channel, and the hub relays it back.
 * With none back for 5 s (or three heartbeats) while the link is
 * connected, the hub is stalled (a client that never reads blocks it):
 * the kit says so through on_warning, in one line, sends nothing but that
 * echo meanwhile (its results are held, and the time counts against
 * neither a run nor max_runs' wait for acknowledgements), and when an
 * echo is back says so in one line and sends every result not yet stored.
 * A hub away (the link closed: killed, restarted, out of reach) is an
 * outage instead: one line as it goes, one as it is back, and then every
 * result not yet stored goes again.
 *
 * Solving is synchronous, in the thread that called mpb_planner_serve()
 * (capacity 1): requests that arrive meanwhile wait in LCM's queue and are
 * taken when solve() returns. solve() gets the run's deadline and the
 * stop flag from the kit (mpb_solve_limits), as OMPL's solve() gets a
 * termination condition: a long solve checks mpb_solve_should_stop().
 *
 * Include the generated message headers (mpb_plan_request_t.h,
 * mpb_plan_result_t.h) before this one, or let it include them.
 */
#ifndef MPBENCH_PLANNER_H
#define MPBENCH_PLANNER_H

#include <signal.h>
#include <stddef.h>

#include "mpb_plan_request_t.h"
#include "mpb_plan_result_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * Fill res for req, by lim->deadline; stop early when
 * mpb_solve_should_stop(lim) says so. res arrives zeroed with attempt_id,
 * planner_id and utime set; fill status, message and times, and add stages and values with the
 * mpb_result_add_* functions (which own what they allocate). Return 0, or a
 * negative code to report INVALID_REQUEST with res->message if set;
 * MPB_ENOMEM (an allocation failed) reports MEMORY instead.
 *
 * Before solve() is called the request has been checked: a valid attempt
 * id, addressed to this planner, an algorithm from def->algorithms, and for a
 * JOINTS goal as many goal joints as start joints; a request failing these
 * never reaches solve(). utime is set again when the result is published.
 * A status outside SOLVED..MEMORY, or CRASH (the daemon's), is published
 * as FAILED.
 *
 * Memory (docs/protocol.md, "Memory"): around solve() alone, the kit
 * resets the process's peak resident size and reports it after in
 * res->memory (MB), unless solve() set it above 0. With a request's
 * memory_limit above 0 it lowers RLIMIT_DATA to the process's data size
 * plus that many MB for the solve, so that an allocation past it fails
 * (malloc returns NULL, new throws std::bad_alloc: catch it and return
 * MPB_ENOMEM or set MEMORY); a process that dies of it anyway (SIGABRT,
 * SIGSEGV, SIGBUS, a sanitizer's death) having used at least half the
 * limit publishes a MEMORY result for the run as its last words.
 */
typedef struct mpb_solve_limits {
    double start;       /* mpb_monotonic_s() when the kit called solve() */
    double deadline;    /* start + req->time_limit: by then the run must
                           have ended (the planner keeps its own margin
                           for work after the search) */
    volatile sig_atomic_t *stop;    /* mpb_planner_serve()'s stop flag,
                                       nonzero when the process is asked
                                       to stop (a signal); NULL: none */
    void *kit;          /* the kit's own, for mpb_solve_setting_up() and
                           mpb_solve_planning(); NULL: they do nothing */
} mpb_solve_limits;

/*
 * 1 when solve() should give up now: *lim->stop is set or the deadline
 * has passed (one read of the monotonic clock); 0 otherwise.
 */
int mpb_solve_should_stop(const mpb_solve_limits *lim);

/*
 * A copy of lim with its deadline seconds later (earlier when negative),
 * the stop flag the same: a planner's own budget inside the run's, e.g.
 * the deadline moved by the world's setup, which mpbenchd leaves out of
 * the run's time, less a margin for work after the search. Check it with
 * mpb_solve_should_stop(), the one stop check of every planner.
 */
mpb_solve_limits mpb_solve_limits_moved(const mpb_solve_limits *lim,
                                        double seconds);

/*
 * Tell mpbenchd that solve() first builds its model of a new robot and
 * scene (outside the run's time: report it as MPB_WORLD_SETUP_TIME), then
 * that planning starts (run_ack_t SETTING_UP, PLANNING): the daemon's
 * deadline waits for the build, up to 120 s, instead of counting it in
 * the time limit and its 5 s of grace, which run from
 * mpb_solve_planning(). Each is sent once per run, copies from
 * mpb_solve_limits_moved() sharing it. Call both, or neither (a cached
 * world). No return value: a message the daemon misses is no failure of
 * the run's (it then keeps the deadline it had).
 */
void mpb_solve_setting_up(const mpb_solve_limits *lim);
void mpb_solve_planning(const mpb_solve_limits *lim);

typedef int (*mpb_solve_fn)(void *user, const mpb_plan_request_t *req,
                            const mpb_solve_limits *lim,
                            mpb_plan_result_t *res);

typedef struct mpb_planner_def {
    const char *name;            /* family named in experiments, e.g. "ompl" */
    const char *language;        /* "c", "c++", ... */
    const char *version;
    const char *const *algorithms;
    int         num_algorithms;
    mpb_solve_fn solve;
    void       *user;
    int         heartbeat_ms;    /* 0: 500; at least 50 */
    /*
     * Optional: called once, in the serving thread, when LCM is joined and
     * the planner id ("name@host:pid") is known, before the first request
     * is taken; the id string lives until mpb_planner_serve() returns.
     */
    void      (*on_ready)(void *user, const char *planner_id);
    /*
     * Optional: a file holding the secret every message is authenticated
     * with (auth.h); the daemon must use the same. NULL: no authentication.
     */
    const char *secret_file;
    /*
     * Optional: called in the serving thread with one line for the user,
     * e.g. MPB_LCM_UNFILTERED when LCM's socket could not be filtered
     * (lcm_filter.h), or a hub stalled and relaying again (above); print
     * it. NULL: the line is lost.
     */
    void      (*on_warning)(void *user, const char *line);
    /*
     * Optional: each algorithm's approach, the paper's word for the kind
     * of planner ("sampling", "search", "optimisation", "hybrid"; "" for
     * none), approaches[i] for algorithms[i], announced with them
     * (docs/protocol.md). NULL: the planner declares none. Not to be
     * confused with name, the planner's family.
     */
    const char *const *approaches;
} mpb_planner_def;

/*
 * Serve requests until *stop becomes nonzero (set it from a signal handler)
 * or, when max_runs > 0, after that many runs have been solved and their
 * results acknowledged (or re-sent for 10 s without an acknowledgement).
 * From the start of the last of them the planner announces capacity 0 and
 * declines any further request (REQUEST_DECLINED), so that the daemon
 * gives those runs to other planners, with no crash counted.
 * lcm_url NULL means MPB_DEFAULT_LCM_URL. def->name must be a word of
 * [A-Za-z0-9_.-]; the host part of the id is the host name with other
 * characters replaced by '-'. Returns MPB_OK; MPB_EINVAL for a bad def;
 * MPB_ELCM if LCM cannot start or fails; MPB_ENOMEM. On failure err (if not
 * NULL) holds one line saying why.
 */
int mpb_planner_serve(const mpb_planner_def *def, const char *lcm_url,
                      volatile sig_atomic_t *stop, long max_runs,
                      char *err, size_t errlen);

struct mpb_world;
struct mpb_robot;

/*
 * Make a planner's world w and its robot r (for IK; either may be NULL)
 * hold the request's joints outside the planning group at their values
 * (req->held_names, held_values), as the daemon's verifier holds them:
 * call it on every request, since a cached world keeps the values of the
 * last one. MPB_OK; else world.h's codes (mpb_world_hold(),
 * mpb_robot_set_passive()) with one line in err naming the joint.
 */
int mpb_request_hold(const mpb_plan_request_t *req, struct mpb_world *w,
                     struct mpb_robot *r, char *err, size_t errlen);

/*
 * The options every planner process of this kit takes, so that all of them
 * are started alike:
 *   --lcm-url URL   the LCM URL (the daemon's)
 *   --name NAME     the planner family experiment files name
 *   --max-runs N    exit after N runs (0: no limit)
 *   --secret-file F authenticate messages with the secret in F
 */
typedef struct mpb_planner_options {
    const char *lcm_url;         /* NULL: MPB_DEFAULT_LCM_URL */
    const char *name;            /* the planner's default until given */
    const char *secret_file;     /* NULL: no authentication */
    long        max_runs;        /* 0: no limit */
} mpb_planner_options;

/*
 * If argv[*i] is one of those options, store it (and its value, argv[*i+1])
 * in o, step *i past the value and return 1; return 0 for any other
 * argument, left to the caller; -1 with one line in err for a missing
 * value or a bad count ("--max-runs wants a number >= 0, not 'x'"). Meant
 * for the caller's loop over argv:
 *     for (int i = 1; i < argc; i++) {
 *         int took = mpb_planner_option(argc, argv, &i, &o, err, sizeof err);
 *         if (took < 0) ... print err, exit 2
 *         if (took) continue;
 *         ... the planner's own options ...
 *     }
 */
int mpb_planner_option(int argc, char **argv, int *i, mpb_planner_options *o,
                       char *err, size_t errlen);

/*
 * A planner process's main() after its options: SIGINT and SIGTERM set
 * the stop flag (the run in hand ends as mpb_planner_serve() says), then
 * def is served with o's URL and run count, and o's name and secret file
 * where def has none. Where def has no on_ready or on_warning, "PROG:
 * serving as ID" goes to stdout and "PROG: LINE" to stderr. Returns the
 * process's exit status: 0 when it stopped as asked, 1 after one line on
 * stderr saying why it could not serve. One call a process (the signal
 * handler's flag is the kit's).
 */
int mpb_planner_main(const mpb_planner_def *def, const mpb_planner_options *o,
                     const char *prog);

/*
 * Append a stage of num_waypoints x num_joints values (copied, row after
 * row) to res. These five return MPB_OK, MPB_EINVAL or MPB_ENOMEM.
 */
int mpb_result_add_stage(mpb_plan_result_t *res, const char *name,
                         double time, const double *waypoints,
                         int num_waypoints, int num_joints);

/*
 * Give stage (0-based, added already) of res the time of each of its
 * waypoints (copied; s from the trajectory's start, finite, the first
 * >= 0, non-decreasing, num_times its num_waypoints: what the daemon
 * checks), for a planner whose output is time-parameterised; num_times 0
 * makes it untimed again. The daemon then measures the trajectory's
 * duration, velocities and accelerations and refuses one faster than the
 * URDF's velocity limits (docs/metrics.md, "Timed trajectories").
 */
int mpb_result_set_times(mpb_plan_result_t *res, int stage,
                         const double *times, int num_times);

/*
 * The value a planner reports the preparation of a world in (s): parsing
 * its robot and scene, meshes included, when a request brings one the
 * planner has not built yet. That time is the world's, not the run's: it
 * is left out of time_total and time_other (tau_t, tau_o), as OMPL's
 * Benchmark leaves out its setup, and mpb report shows it on its own.
 */
#define MPB_WORLD_SETUP_TIME "world_setup_time"

/* Append one of the planner's own named numbers to res. */
int mpb_result_add_value(mpb_plan_result_t *res, const char *name,
                         double value);

/* Set res->message (copied, printf-style), replacing any message before. */
int mpb_result_set_message(mpb_plan_result_t *res, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Free everything res points to (not res itself) and zero it. */
void mpb_result_clear(mpb_plan_result_t *res);

/* The value of a request parameter (the first with that key), or NULL;
 * it points into req and lives as long as req does. */
const char *mpb_request_param(const mpb_plan_request_t *req, const char *key);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_PLANNER_H */
