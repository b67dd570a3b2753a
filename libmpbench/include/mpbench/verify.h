/*
 * verify.h - mpbench's own verdict on a trajectory: does it solve the query?
 * A planner's claim of success is recorded beside this verdict, never
 * instead of it.
 */
#ifndef MPBENCH_VERIFY_H
#define MPBENCH_VERIFY_H

#include <stddef.h>

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

/* Why a trajectory is not a solution; the first failure found wins. */
#define MPB_VERDICT_MAP(X)                                              \
    X(VALID,         "valid")                                           \
    X(EMPTY,         "no waypoints")                                    \
    X(WRONG_SIZE,    "waypoints have the wrong number of joints")       \
    X(NOT_FINITE,    "a waypoint value is NaN or infinite")             \
    X(START,         "does not begin at the start state")               \
    X(GOAL,          "does not end in the goal region")                 \
    X(JOINT_LIMIT,   "a waypoint is outside the joint limits")          \
    X(COLLISION,     "collides")                                        \
    X(UNSUPPORTED,   "goal kind not supported by this world")

typedef enum mpb_verdict_code {
#define MPB__VERDICT_ENUM(name, text) MPB_VERDICT_##name,
    MPB_VERDICT_MAP(MPB__VERDICT_ENUM)
#undef MPB__VERDICT_ENUM
    MPB_VERDICT_COUNT
} mpb_verdict_code;

typedef struct mpb_verdict {
    mpb_verdict_code code;
    int  segment;          /* first failing segment (or waypoint), -1 if none */
    char detail[160];      /* one line, e.g. "segment 3 collides at s=0.42" */
} mpb_verdict;

/* Lower-case name of a verdict code ("collision"); never NULL. */
const char *mpb_verdict_name(mpb_verdict_code code);

/*
 * Check a path against its query in world w: non-empty and finite, starts
 * at start (within start_tolerance per joint), ends in goal, every waypoint
 * inside the joint limits, and collision-free when each segment is
 * interpolated with steps of at most resolution (joint-space, Euclidean).
 * Fills *out and returns MPB_OK, whatever the verdict; a negative code only
 * for bad arguments.
 */
int mpb_verify_path(struct mpb_world *w, const double *start,
                    double start_tolerance, const mpb_goal *goal,
                    const double *wp, int num_waypoints, int num_joints,
                    double resolution, mpb_verdict *out);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_VERIFY_H */
