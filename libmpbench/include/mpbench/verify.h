/*
 * verify.h - mpbench's own verdict on a trajectory: does it solve the query?
 * A planner's claim of success is recorded beside this verdict, never
 * instead of it.
 */
#ifndef MPBENCH_VERIFY_H
#define MPBENCH_VERIFY_H

#include <stddef.h>

#include "mpbench/metrics.h"

#ifdef __cplusplus
extern "C" {
#endif

struct mpb_world;

/* Where a run must end; mirrors mpb.goal_t of the protocol. */
typedef enum mpb_goal_kind {
    MPB_GOAL_JOINTS = 0,
    MPB_GOAL_POSE_REGION = 1
} mpb_goal_kind;

typedef struct mpb_goal {
    mpb_goal_kind kind;
    const double *joints;          /* MPB_GOAL_JOINTS: num_joints values */
    double        joint_tolerance; /* per joint, rad or m */
    const char   *link;            /* MPB_GOAL_POSE_REGION */
    double position[3], position_tolerance[3];
    double orientation_rpy[3], orientation_tolerance[3];
} mpb_goal;

/*
 * The goal of a query as the store keeps it (mpb_query_info, mpb_query_row):
 * kind (mpb_goal_kind), the joint goal and its per-joint tolerance, and for
 * a pose region the link and its 12 numbers (box centre, half extents,
 * reference roll pitch yaw, their tolerances; region NULL for a joint
 * goal, read as zeros). The result points at joints and link, copies
 * region: it lives as long as joints and link do.
 */
mpb_goal mpb_query_goal(int kind, const double *joints, double joint_tolerance,
                        const char *link, const double *region);

/* Why a trajectory is not a solution; the first failure found wins.
 * BAD_TIMES is set by the caller for a stage whose waypoint times are not
 * a timing (mpb_times_ok()); VELOCITY_LIMIT is the last check, made on a
 * timed stage that passes every other (mpb_measure_stage_timed()). */
#define MPB_VERDICT_MAP(X)                                              \
    X(VALID,         "valid")                                           \
    X(EMPTY,         "no waypoints")                                    \
    X(WRONG_SIZE,    "waypoints have the wrong number of joints")       \
    X(NOT_FINITE,    "a waypoint value is NaN or infinite")             \
    X(START,         "does not begin at the start state")               \
    X(GOAL,          "does not end in the goal region")                 \
    X(JOINT_LIMIT,   "a waypoint is outside the joint limits")          \
    X(COLLISION,     "collides")                                        \
    X(UNSUPPORTED,   "goal kind not supported by this world")           \
    X(BAD_TIMES,     "waypoint times are not a timing of the waypoints")\
    X(VELOCITY_LIMIT, "a joint moves faster than its velocity limit")

typedef enum mpb_verdict_code {
#define MPB__VERDICT_ENUM(name, text) MPB_VERDICT_##name,
    MPB_VERDICT_MAP(MPB__VERDICT_ENUM)
#undef MPB__VERDICT_ENUM
    MPB_VERDICT_COUNT
} mpb_verdict_code;

typedef struct mpb_verdict {
    mpb_verdict_code code;
    int  segment;          /* COLLISION: the first colliding segment, 0-based,
                              segment i joining waypoints i and i+1;
                              NOT_FINITE, START, GOAL, JOINT_LIMIT: the
                              waypoint, 0-based; -1 otherwise */
    char detail[512];      /* one line, e.g. "segment 3 collides at s=0.42
                              (waypoints 3-4)"; names the joint where one is
                              at fault */
    int  certified;        /* 1 if the collision check was a proof: every
                              segment proved free over its whole continuum
                              (VALID), or a colliding configuration found
                              by the certified search (COLLISION); 0 if any
                              segment was only sampled (mpb_verification) */
    /* COLLISION: how deep the refused segment goes (docs/verification.md),
     * m, at its worst configuration examined, the one whose lower bound is
     * the largest (then the upper): the colliding configuration found and
     * the sampled rule's configurations of the segment, a + (j/k)(b - a),
     * j = 0..k, k = max(1, ceil(L/resolution)) (mpb_world_depth()). lower:
     * the deepest robot point found inside an obstacle or another link;
     * upper: the penetration depth of the shapes' convex hulls as found;
     * lower <= upper. depth_s: that configuration's s in the segment. NaN
     * for any other verdict and in a world that cannot say (planar). */
    double depth_lower, depth_upper, depth_s;
} mpb_verdict;

/*
 * How mpb_verify_path() checks the segments between waypoints for
 * collision (docs/verification.md):
 *   CERTIFIED  each segment is proved collision-free over its whole
 *              continuum (conservative advancement: distance lower bounds
 *              against an upper bound on how far the robot moves), or a
 *              colliding configuration is found; a segment that cannot be
 *              proved down to a step of 1e-6 rad (or in a world that cannot
 *              prove) is also sampled, as SAMPLED does, and the verdict
 *              says so (certified = 0). The default.
 *   SAMPLED    each segment is sampled at the resolution, as before.
 */
typedef enum mpb_verification {
    MPB_VERIFY_CERTIFIED = 0,
    MPB_VERIFY_SAMPLED = 1
} mpb_verification;

/* "certified" or "sampled"; "unknown" out of range. Never NULL. */
const char *mpb_verification_name(mpb_verification mode);

/* Set how mpb_verify_path() checks segments in world w (CERTIFIED when
 * the world is opened). MPB_OK; MPB_EINVAL for NULL w or a bad mode. */
int mpb_world_set_verification(struct mpb_world *w, mpb_verification mode);

/* Lower-case name of a verdict code ("collision"); never NULL. */
const char *mpb_verdict_name(mpb_verdict_code code);

/*
 * How v's collision check was made, for the verdicts that make one (VALID,
 * COLLISION, VELOCITY_LIMIT, checked after it): "certified"
 * (v->certified) or "sampled"; NULL for any other verdict, and for NULL
 * v. As the store keeps it (stages.verification).
 */
const char *mpb_verdict_verification(const mpb_verdict *v);

/*
 * Check a path against its query in world w, in the order of the verdict
 * list, the first failure winning:
 *   EMPTY        num_waypoints == 0;
 *   WRONG_SIZE   num_joints is not the world's;
 *   NOT_FINITE   a value is NaN or infinite;
 *   START        some joint of waypoint 0 is more than start_tolerance from
 *                start;
 *   GOAL         MPB_GOAL_JOINTS: some joint of the last waypoint is more
 *                than goal->joint_tolerance from goal->joints;
 *   JOINT_LIMIT  a waypoint value outside [lo, hi] (continuous joints have
 *                no limits);
 *   COLLISION    waypoint 0 collides, or a configuration inside a segment
 *                does: in CERTIFIED mode the one the proof ran into
 *                (detail "at s=" with 17 digits); sampled, segment a->b of
 *                joint-space length L at a + (s/k)(b - a), s = 1..k,
 *                k = max(1, ceil(L/resolution)), so steps are at most
 *                resolution (Euclidean, rad or m);
 *   UNSUPPORTED  the goal kind cannot be checked in this world. This is the
 *                case of MPB_GOAL_POSE_REGION for now (no world computes
 *                link poses yet): its GOAL check is skipped, the others run,
 *                and a path that passes them all gets UNSUPPORTED.
 * Differences of continuous joints (start, goal, interpolation) are taken
 * the short way round (mpb_joint_delta). Comparisons are <= tolerance.
 *
 * Fills *out and returns MPB_OK, whatever the verdict. A negative code for
 * bad arguments (MPB_EINVAL: NULL w/start/goal/out, NULL wp with waypoints,
 * resolution not finite and > 0, a tolerance < 0 or NaN, a joint goal
 * without joints, a resolution so fine a segment needs over 1e9 samples) or
 * MPB_ENOMEM; *out (if not NULL) is then UNSUPPORTED with the reason in
 * detail, never VALID.
 */
int mpb_verify_path(struct mpb_world *w, const double *start,
                    double start_tolerance, const mpb_goal *goal,
                    const double *wp, int num_waypoints, int num_joints,
                    double resolution, mpb_verdict *out);

/*
 * A stage as mpbench judges it: its verdict and its metrics, the ones of
 * MPB_METRIC_MAP (metrics.h) that apply, in the list's order, each named
 * by the list (static strings). Filled by mpb_measure_stage().
 */
typedef struct mpb_stage_measure {
    mpb_verdict verdict;
    int         num_metrics;
    struct mpb_stage_metric {
        const char *name;
        double      value;
    } metrics[MPB_NUM_METRICS];
} mpb_stage_measure;

/* What mpb_measure_stage() leaves out, or-ed; 0 leaves out nothing. */
#define MPB_MEASURE_NO_METRICS 1  /* the verdict alone (num_metrics 0): for
                                     stored paths checked again, where the
                                     metrics, clearance above all, would
                                     cost many times the verification */

/*
 * Verify and measure one stage, as mpbenchd does with every stage a planner
 * returns, and as `mpb verify` and the benchmarks check stages:
 * mpb_verify_path() with these arguments, then, unless flags has
 * MPB_MEASURE_NO_METRICS, mpb_measure_metrics(). stage_time is the stage's
 * time as the planner reported it (s). Returns what mpb_verify_path()
 * returns; *out is filled whatever it returns.
 */
int mpb_measure_stage(struct mpb_world *w, const double *start,
                      double start_tolerance, const mpb_goal *goal,
                      const double *wp, int num_waypoints, int num_joints,
                      double stage_time, double resolution, unsigned flags,
                      mpb_stage_measure *out);

/*
 * mpb_measure_stage() of a stage with the time of each waypoint, times
 * (NULL: untimed, as mpb_measure_stage()), which the caller has checked
 * (mpb_times_ok()). A stage that passes every check of mpb_verify_path()
 * is then refused with MPB_VERDICT_VELOCITY_LIMIT when a joint's velocity
 * between two waypoints is more than MPB_VELOCITY_TOLERANCE above its URDF
 * limit (mpb_path_timing(), mpb_world_joint_max_velocity()): segment is
 * that segment, detail names the joint, its velocity and its limit. The
 * metrics flagged MPB_METRIC_F_TIMED are measured too.
 */
int mpb_measure_stage_timed(struct mpb_world *w, const double *start,
                            double start_tolerance, const mpb_goal *goal,
                            const double *wp, const double *times,
                            int num_waypoints, int num_joints,
                            double stage_time, double resolution,
                            unsigned flags, mpb_stage_measure *out);

/*
 * The metrics of a stage whose verdict is out->verdict already (set by the
 * caller, e.g. MPB_VERDICT_WRONG_SIZE for a message whose sizes disagree):
 * every metric of the list, except that those flagged MPB_METRIC_F_PATH
 * are left out when wp is NULL or the verdict is NOT_FINITE or
 * WRONG_SIZE (lengths of such a path mean nothing). resolution is the
 * end-effector's step (mpb_ee_path_length()). Sets out->num_metrics and
 * out->metrics.
 */
void mpb_measure_metrics(struct mpb_world *w, const double *wp,
                         int num_waypoints, int num_joints, double stage_time,
                         double resolution, mpb_stage_measure *out);

/* mpb_measure_metrics() with the waypoints' times (NULL: untimed, the
 * metrics flagged MPB_METRIC_F_TIMED left out; else those too, each left
 * out where it is NaN). */
void mpb_measure_metrics_timed(struct mpb_world *w, const double *wp,
                               const double *times, int num_waypoints,
                               int num_joints, double stage_time,
                               double resolution, mpb_stage_measure *out);

/*
 * Where a path collides, as mpb_find_collision() finds it: the
 * configuration itself goes to the caller's array.
 */
typedef struct mpb_collision_at {
    int    segment;     /* segment i joins waypoints i and i+1; 0 for
                           waypoint 0 (of a path of one waypoint too) */
    double s;           /* where in it, 0 .. 1: the configuration is
                           waypoint i + s (waypoint i+1 - waypoint i),
                           continuous joints the short way round; 0 is
                           waypoint i itself */
    int    certified;   /* 1 if the proof's search found it (s exact),
                           0 if a sample of the sampled rule did */
    char   bodies[400]; /* the bodies in contact there as the world names
                           them (mpb_world_contact(): "self-collision
                           between A and B", "A touches scene object B");
                           "" where the world names none (planar) */
} mpb_collision_at;

/*
 * Find again the configuration where path wp collides, by the rule
 * mpb_verify_path() follows in w's verification mode
 * (mpb_world_set_verification()): waypoint 0, then each segment in turn,
 * in CERTIFIED mode proved free or the configuration the proof runs into
 * found, a segment the proof leaves unproved sampled as in SAMPLED mode
 * (a + (s/k)(b - a), s = 1..k, k = max(1, ceil(L/resolution))). It is
 * the configuration of the verdict's "at s=" in the same world and mode,
 * with the bodies touching there: what `mpb view` shows. Only collisions
 * are looked for (not the start, goal or limits).
 *
 * segment < 0 searches the whole path; segment >= 0 that segment alone
 * (and waypoint 0 with segment 0), where a stored verdict points.
 *
 * Returns 1 with the configuration in q (num_joints values, the
 * caller's) and *out filled; 0 if nothing collides there (q and *out
 * then unspecified); MPB_EINVAL for NULL w/q/out, NULL wp with
 * waypoints, num_joints not the world's, a value not finite, resolution
 * not finite and > 0, or a resolution so fine a segment needs over 1e9
 * samples; MPB_ENOMEM.
 */
int mpb_find_collision(struct mpb_world *w, const double *wp,
                       int num_waypoints, int num_joints, double resolution,
                       int segment, double *q, mpb_collision_at *out);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_VERIFY_H */
