/*
 * metrics.h - measures of one path, computed by mpbench itself (never taken
 * from the planner). A path is num_waypoints joint vectors of num_joints
 * values each, stored row after row: waypoint i, joint j is
 * wp[i * num_joints + j]. Definitions, units and edge cases are in
 * docs/metrics.md; they follow Table I of Cohen, Sucan and Chitta, "A
 * Generic Infrastructure for Benchmarking Motion Planners" (IROS 2012).
 */
#ifndef MPBENCH_METRICS_H
#define MPBENCH_METRICS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/*
 * The metrics mpbench computes for every stage a planner returns, one line
 * each: the daemon stores them (metrics.name), `mpb report` tabulates them,
 * `mpb plot` draws them and the Planner Arena export names them from this
 * list alone. Adding a metric is a line here and a function
 * "static double metric_<ID>(mpb__measure *m)" in
 * libmpbench/src/verify/measure.c; nothing else.
 *
 *   X(ID, name, unit, flags, rank, symbol, latex, title, axis, better, word)
 *
 * ID      MPB_METRIC_<ID>, the metric's index in this list
 * name    as stored and in machine-readable reports ("path_length")
 * unit    "s", "m", "rad", "rad^2", "rad/s", "rad/s^2"; "" for a count or
 *         a ratio
 * flags   MPB_METRIC_F_* below
 * rank    its place in Planner Arena's property lists and in `mpb plot`
 *         (1, 2, ...); 0: not plotted, listed after the ranked ones by name
 * symbol  the report's row label ("l_p"), latex the same in LaTeX
 * title, axis, better   a plot's title, y axis (with the unit) and what a
 *         better value is
 * word    its word in OMPL's property names ("solution length"); NULL
 *         when the stage's time or segments already say it
 *
 * The list is in the order of the paper's tables.
 */
#define MPB_METRIC_MAP(X)                                                    \
    X(CLEARANCE, "clearance", "m",                                           \
      MPB_METRIC_F_PATH | MPB_METRIC_F_TABLE | MPB_METRIC_F_SIGMA |          \
          MPB_METRIC_F_OPTIONAL, 3, "d_n", "$d_n$",                          \
      "Mean clearance from obstacles",                                       \
      "mean distance to the nearest obstacle (m)",                           \
      "higher keeps further away", "clearance")                              \
    X(PATH_LENGTH, "path_length", "rad",                                     \
      MPB_METRIC_F_PATH | MPB_METRIC_F_TABLE | MPB_METRIC_F_SIGMA, 1,        \
      "l_p", "$l_p$", "Joint-space path length",                             \
      "joint-space path length (rad)", "shorter is better", "length")        \
    X(EE_PATH_LENGTH, "ee_path_length", "m",                                 \
      MPB_METRIC_F_PATH | MPB_METRIC_F_TABLE | MPB_METRIC_F_SIGMA |          \
          MPB_METRIC_F_OPTIONAL, 4, "l_e", "$l_e$",                          \
      "End-effector path length",                                            \
      "distance travelled by the end-effector (m)", "shorter is better",     \
      "ee length")                                                           \
    X(SMOOTHNESS, "smoothness", "rad^2",                                     \
      MPB_METRIC_F_PATH | MPB_METRIC_F_TABLE | MPB_METRIC_F_SIGMA, 2,        \
      "kappa'", "$\\kappa'$",                                                \
      "Smoothness: mean squared turning angle between segments",             \
      "smoothness (rad^2)", "lower is smoother", "smoothness")               \
    X(SMOOTHNESS_RESAMPLED, "smoothness_resampled", "rad^2",                 \
      MPB_METRIC_F_PATH | MPB_METRIC_F_TABLE | MPB_METRIC_F_SIGMA |          \
          MPB_METRIC_F_OPTIONAL, 0, "kappa'_r", "$\\kappa'_r$",              \
      "Smoothness of the path cut into equal pieces",                        \
      "smoothness, resampled (rad^2)", "lower is smoother",                  \
      "smoothness_resampled")                                                \
    X(WAYPOINTS, "waypoints", "", MPB_METRIC_F_TABLE | MPB_METRIC_F_COUNT,   \
      0, "waypoints", "waypoints", "Waypoints", "waypoints",                 \
      "fewer is simpler", NULL)                                              \
    X(MIN_CLEARANCE, "min_clearance", "m", MPB_METRIC_F_PATH, 0,             \
      "d_min", "$d_{min}$", "Least clearance from obstacles",                \
      "least distance to the nearest obstacle (m)",                          \
      "higher keeps further away", "min_clearance")                          \
    X(TIME, "time", "s", 0, 0, "tau_s", "$\\tau_s$", "Stage time",           \
      "the stage's time as the planner reported it (s)",                     \
      "shorter is better", NULL)                                             \
    X(DURATION, "duration", "s", MPB__METRIC_F_TIMED_ROW, 0, "t_d",          \
      "$t_d$", "Trajectory duration",                                        \
      "duration of the timed trajectory (s)", "shorter is faster",           \
      "duration")                                                            \
    X(MAX_VELOCITY, "max_velocity", "rad/s", MPB__METRIC_F_TIMED_ROW, 0,     \
      "v_max", "$v_{max}$", "Largest joint velocity",                        \
      "largest joint velocity between waypoints (rad/s)",                    \
      "lower is gentler", "max velocity")                                    \
    X(VELOCITY_RATIO, "velocity_limit_ratio", "",                            \
      MPB_METRIC_F_PATH | MPB_METRIC_F_TIMED, 0, "v/v_lim", "$v/v_{lim}$",  \
      "Largest joint velocity over the joint's limit",                       \
      "largest joint velocity over its URDF limit",                          \
      "at most 1 keeps to the limits", "velocity limit ratio")               \
    X(MAX_ACCELERATION, "max_acceleration", "rad/s^2",                       \
      MPB__METRIC_F_TIMED_ROW, 0, "a_max", "$a_{max}$",                      \
      "Largest joint acceleration",                                          \
      "largest joint acceleration between segments (rad/s^2)",               \
      "lower is gentler", "max acceleration")

/* A metric's flags. */
#define MPB_METRIC_F_PATH     1  /* measured only on a path of the right
                                    size whose values are all finite */
#define MPB_METRIC_F_TABLE    2  /* a row of `mpb report`: its mean */
#define MPB_METRIC_F_SIGMA    4  /* and a row of its standard deviation */
#define MPB_METRIC_F_OPTIONAL 8  /* a row only where some run has it */
#define MPB_METRIC_F_COUNT   16  /* a count: its mean shows one decimal */
#define MPB_METRIC_F_TIMED   32  /* measured only on a stage that has
                                    waypoint times (stage_t.times), and
                                    left out where its value is NaN (no
                                    joint has a limit to compare with) */
/* A timed metric that is a row of `mpb report` where some run has it. */
#define MPB__METRIC_F_TIMED_ROW                                             \
    (MPB_METRIC_F_PATH | MPB_METRIC_F_TIMED | MPB_METRIC_F_TABLE |           \
     MPB_METRIC_F_OPTIONAL)

typedef enum mpb_metric_id {
#define MPB__METRIC_ENUM(id, ...) MPB_METRIC_##id,
    MPB_METRIC_MAP(MPB__METRIC_ENUM)
#undef MPB__METRIC_ENUM
    MPB_NUM_METRICS
} mpb_metric_id;

/* One line of the list. */
typedef struct mpb_metric_info {
    const char *name, *unit;
    unsigned    flags;
    int         rank;
    const char *symbol, *latex, *title, *axis, *better, *word;
} mpb_metric_info;

/* The line of metric id, static; NULL outside 0..MPB_NUM_METRICS-1. */
const mpb_metric_info *mpb_metric_info_of(int id);

/* The id of the metric stored as name, or -1 if the list has none. */
int mpb_metric_find(const char *name);

/*
 * Which joints wrap around (continuous joints): continuous[j] != 0 means the
 * difference between two values of joint j is taken the short way round, in
 * (-pi, pi]. NULL means no joint wraps.
 */
typedef const unsigned char *mpb_joint_wrap;

/*
 * Joint-space difference b - a of one joint; if it wraps, the short way
 * round, in (-pi, pi] (so a difference of exactly pi is +pi).
 */
double mpb_joint_delta(double a, double b, int wraps);

/*
 * l_p: the sum of the Euclidean joint-space lengths of the segments (rad,
 * or m for prismatic joints). 0 for fewer than two waypoints; NaN if a
 * value is NaN.
 */
double mpb_path_length(const double *wp, int num_waypoints, int num_joints,
                       mpb_joint_wrap continuous);

/*
 * kappa': (1/n) * sum over i = 2..n of alpha_i^2, where alpha_i is the angle
 * (rad, in [0, pi]) between segments i-1 and i of the path's n segments,
 * taken as joint-space vectors (continuous joints the short way round).
 * Zero-length segments (joint-space norm <= 1e-12) have no direction: they
 * are dropped first, and n counts the segments that remain. 0 for a path of
 * fewer than two such segments; NaN if a value is NaN.
 */
double mpb_smoothness(const double *wp, int num_waypoints, int num_joints,
                      mpb_joint_wrap continuous);

/* The number of equal pieces mpb_smoothness_resampled() cuts a path into. */
#define MPB_SMOOTHNESS_SEGMENTS 100

/*
 * kappa'_r: kappa' of the path cut into MPB_SMOOTHNESS_SEGMENTS pieces of
 * equal joint-space length, so that it does not depend on how densely the
 * planner placed its waypoints. kappa' falls by the factor by which
 * collinear waypoints multiply n; kappa'_r does not change. A corner of
 * angle alpha adds between alpha^2 / 2 and alpha^2 to the sum (all of it
 * when it falls on a piece's end, split in two otherwise), divided by
 * MPB_SMOOTHNESS_SEGMENTS. Turns below 1e-9 rad count as 0 here and in
 * mpb_smoothness() (rounding, not turning). 0 for a path of fewer than
 * two nonzero segments; NaN if a value is NaN or memory runs out.
 */
double mpb_smoothness_resampled(const double *wp, int num_waypoints,
                                int num_joints, mpb_joint_wrap continuous);

/*
 * How a timed trajectory moves (docs/metrics.md, "Timed trajectories"):
 * num_waypoints waypoints wp with the time of each, times (s, finite,
 * non-decreasing: mpb_times_ok()). By finite differences between
 * waypoints: segment i (waypoints i, i+1) moves joint j at
 * v_ij = delta_j / (t_{i+1} - t_i) (continuous joints the short way);
 * a segment of no time and no motion (a waypoint repeated) is dropped, one
 * of no time that moves has an infinite velocity. The acceleration
 * between consecutive segments that remain is
 * (v_{i+1,j} - v_ij) / ((dt_i + dt_{i+1}) / 2), the change of velocity
 * between the segments' midpoints.
 */
typedef struct mpb_timing {
    double duration;          /* s: the last time less the first */
    double max_velocity;      /* the largest |v_ij| (rad/s or m/s); 0 for
                                 fewer than two waypoints */
    double max_acceleration;  /* the largest |a_ij|; 0 with fewer than two
                                 segments that move */
    double velocity_ratio;    /* the largest |v_ij| / limit_j over the
                                 joints with a limit; NaN if none has one */
    int    ratio_segment;     /* where velocity_ratio is: its segment and */
    int    ratio_joint;       /* joint; -1 and -1 when it is NaN */
} mpb_timing;

/* A timed stage whose velocity_ratio is above 1 + this is refused with
 * MPB_VERDICT_VELOCITY_LIMIT (verify.h): 1% for the rounding of a time
 * parameterisation (a planner's finite-difference velocity is a chord of
 * its true velocity, never above the true peak). */
#define MPB_VELOCITY_TOLERANCE 0.01

/*
 * Fill *out with the timing of path wp at times; max_velocity (NULL: no
 * limits) holds each joint's limit, 0 where it has none
 * (mpb_world_joint_max_velocity()). MPB_OK; MPB_EINVAL for NULL wp,
 * times or out, or num_waypoints < 1 or num_joints < 1 (*out then NaN).
 */
int mpb_path_timing(const double *wp, const double *times, int num_waypoints,
                    int num_joints, mpb_joint_wrap continuous,
                    const double *max_velocity, mpb_timing *out);

/*
 * 1 if times is a timing of a stage of num_waypoints waypoints:
 * num_times == num_waypoints, every time finite, the first >= 0, none
 * below the one before. Else 0 with a one-line reason in why (if not
 * NULL), e.g. "time 3 (0.25 s) is below time 2 (0.5 s)". num_times 0
 * (an untimed stage) is not a timing: callers check it first.
 */
int mpb_times_ok(const double *times, int num_times, int num_waypoints,
                 char *why, size_t whylen);

struct mpb_world;

/*
 * d_n: the mean over the waypoints of mpb_world_clearance() (m), the
 * smallest distance from the robot to the environment at each waypoint.
 * NaN when w or wp is NULL, num_waypoints < 1 or num_joints is not the
 * world's; +INFINITY in an empty scene.
 */
double mpb_path_clearance(struct mpb_world *w, const double *wp,
                          int num_waypoints, int num_joints);

/*
 * The smallest of those per-waypoint clearances (m): how close the path
 * comes to the environment at its waypoints. NaN as above.
 */
double mpb_path_min_clearance(struct mpb_world *w, const double *wp,
                              int num_waypoints, int num_joints);

/*
 * Both at once, for the price of one: each waypoint's clearance is a
 * distance query to the collision world, the dearest part of measuring a
 * path. *mean and *least (either may be NULL) get NaN as above.
 */
void mpb_path_clearances(struct mpb_world *w, const double *wp,
                         int num_waypoints, int num_joints, double *mean,
                         double *least);

/*
 * l_e: the distance the end effector travels (m, mpb_world_ee_position()),
 * each segment followed in straight joint-space steps of at most resolution
 * (continuous joints the short way), since the end effector moves along a
 * curve between waypoints. NaN as above or for a resolution <= 0.
 */
double mpb_ee_path_length(struct mpb_world *w, const double *wp,
                          int num_waypoints, int num_joints,
                          double resolution);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_METRICS_H */
