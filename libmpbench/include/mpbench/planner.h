/*
 * planner.h - the protocol side of a planner process written in C or C++,
 * so that the planner itself is only a solve function.
 *
 * mpb_planner_serve() joins LCM, announces the planner every heartbeat (from
 * a thread of its own, so a long solve does not look like a crash), takes
 * requests addressed to it, acknowledges each, calls solve() once per run id,
 * publishes the result and re-sends it until the daemon acknowledges it. A
 * request seen again is answered from the results it remembers, never solved
 * twice.
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
 * Fill res for req. res arrives zeroed with run_id, planner_id and utime
 * set; fill status, message and times, and add stages and values with the
 * mpb_result_add_* functions (which own what they allocate). Return 0, or a
 * negative code to report INVALID_REQUEST with res->message if set.
 */
typedef int (*mpb_solve_fn)(void *user, const mpb_plan_request_t *req,
                            mpb_plan_result_t *res);

typedef struct mpb_planner_def {
    const char *name;            /* family named in experiments, e.g. "ompl" */
    const char *language;        /* "c", "c++", ... */
    const char *version;
    const char *const *algorithms;
    int         num_algorithms;
    mpb_solve_fn solve;
    void       *user;
    int         heartbeat_ms;    /* 0: 500 */
} mpb_planner_def;

/*
 * Serve requests until *stop becomes nonzero (set it from a signal handler)
 * or, when max_runs > 0, after that many runs. id_out, if not NULL, receives
 * the planner id ("name@host:pid") as soon as it is known. Returns MPB_OK,
 * or MPB_ELCM if LCM cannot start (the message goes to err).
 */
int mpb_planner_serve(const mpb_planner_def *def, const char *lcm_url,
                      volatile sig_atomic_t *stop, long max_runs,
                      char *err, size_t errlen);

/* Append a stage of num_waypoints x num_joints values (copied) to res. */
int mpb_result_add_stage(mpb_plan_result_t *res, const char *name,
                         double time, const double *waypoints,
                         int num_waypoints, int num_joints);

/* Append one of the planner's own named numbers to res. */
int mpb_result_add_value(mpb_plan_result_t *res, const char *name,
                         double value);

/* Set res->message (copied, printf-style). */
int mpb_result_set_message(mpb_plan_result_t *res, const char *fmt, ...);

/* Free everything res points to (not res itself) and zero it. */
void mpb_result_clear(mpb_plan_result_t *res);

/* The value of a request parameter, or NULL when absent. */
const char *mpb_request_param(const mpb_plan_request_t *req, const char *key);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_PLANNER_H */
