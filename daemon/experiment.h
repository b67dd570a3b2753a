/*
 * experiment.h - an experiment file, read and checked: the robot, the scenes
 * and their queries, the planner configurations, runs and time limit. The
 * format is described in docs/experiment-format.md.
 */
#ifndef MPBD_EXPERIMENT_H
#define MPBD_EXPERIMENT_H

#include <stddef.h>
#include <stdio.h>
#include <stdint.h>

#include "mpbench/mpbench.h"
#include "mpb_param_t.h"

/* Most requests that may wait at one planner: the C planner kit's LCM
 * queue holds 8, and the request in flight may be re-sent meanwhile. */
#define MPBD_QUEUE_AT_PLANNER_MAX 4
/* Most runs one experiment may have (runs x configurations x queries): the
 * daemon inserts them in one transaction, and beyond this the disk fills. */
#define MPBD_RUNS_TOTAL_MAX 100000000

typedef struct mpbd_config {
    char       *name;        /* "ompl/RRTConnect", unique in the experiment */
    char       *planner;     /* planner family, as planners announce it */
    char       *algorithm;
    mpb_param_t *params;      /* as sent in requests */
    int         num_params;
    char       *params_text; /* "key=value;key=value", for the database */
    int         runs;        /* per query */
    int64_t     db_id;
    char       *approach;    /* the experiment file's `approach:`, or
                                NULL: the planner's announcement says */
    int         approach_known; /* stored: the file's word, or one a
                                   planner announced (planners.c) */
} mpbd_config;

typedef struct mpbd_scene {
    char      *name;
    char      *robot_format, *robot, robot_hash[MPB_HASH_SIZE];
    char      *scene_format, *scene, scene_hash[MPB_HASH_SIZE];
    char      *scene_file;   /* where the scene was read from, or NULL */
    char      *problem_set;  /* the entry's `set:`, or NULL: the store's
                                default (the name before its last '/') */
    mpb_world *world;        /* for verification */
    /* What its planners are given instead, where the entry says `seen:`
     * (experiment_seen.c): a scene file, or what cameras would see of
     * this one. NULL: the planners get the scene itself. */
    char      *seen_format, *seen, seen_hash[MPB_HASH_SIZE];
    char      *seen_how;     /* one line: the file, or the cameras */
    mpb_world *seen_world;   /* paths judged on what was seen, too */
    int64_t    db_id;
} mpbd_scene;

/* The scene text its planners are given: what was seen, or the scene. */
static inline const char *mpbd_scene_given(const mpbd_scene *s)
{
    return s->seen != NULL ? s->seen : s->scene;
}
static inline const char *mpbd_scene_given_format(const mpbd_scene *s)
{
    return s->seen != NULL ? s->seen_format : s->scene_format;
}
static inline const char *mpbd_scene_given_hash(const mpbd_scene *s)
{
    return s->seen != NULL ? s->seen_hash : s->scene_hash;
}

/* Where a query must end: a configuration, or a region for one link (the
 * paper's goals: a box for its position, roll/pitch/yaw tolerances). */
typedef struct mpbd_query {
    char   *name;
    int     scene;           /* index into scenes */
    double *start;           /* num_joints values */
    mpb_goal_kind goal_kind;
    double *goal;            /* MPB_GOAL_JOINTS: num_joints values; else NULL */
    double  tolerance;       /* per joint, at the start and a joint goal */
    char   *goal_link;       /* MPB_GOAL_POSE_REGION: the link, else NULL */
    double  position[3], position_tolerance[3];  /* box centre, half sizes (m) */
    double  rpy[3], rpy_tolerance[3];            /* rad; a tolerance >= pi
                                                    leaves that angle free */
    double *held;            /* e->num_held values, one per held joint:
                                what the query holds them at */
    int     num_held_set;    /* while loading: how many of held are set */
    /* From a MoveIt request (docs/moveit-problems.md), else NULL / 0: */
    char   *moveit_group;    /* its group_name */
    double  planning_time;   /* its allowed_planning_time, s (reported;
                                the experiment's time_limit rules) */
    int64_t db_id;
} mpbd_query;

/* How far outside its limits a MoveIt start value may be and still be
 * moved onto the limit with clamp_joint_values (rad or m): MoveIt's
 * FixStartStateBounds default, start_state_max_bounds_error. */
#define MPBD_START_BOUNDS_ERROR 0.05

typedef struct mpbd_experiment {
    char   *name;
    char   *file;            /* path as given */
    char   *text;            /* the file's bytes */
    char    hash[MPB_HASH_SIZE];
    int     runs;            /* default runs per query and configuration */
    double  time_limit;      /* s */
    uint64_t seed;
    int     retries;         /* extra attempts for a run whose planner crashed */
    int     runs_per_host;   /* runs at once on one host (timings skew otherwise) */
    int     queue_at_planner;/* requests waiting at each busy planner */
    double  memory_limit;    /* MB a run's planning may add, 0: none */
    int     verification;    /* mpb_verification of its worlds: certified
                                (0) unless `verification: sampled` */

    char   *robot_file;      /* where the robot was read from, or NULL */
    char   *srdf_file;       /* robot.srdf, resolved, or NULL */
    char   *srdf_warning;    /* one line: its disable_collisions pairs
                                that name links the URDF lacks, skipped
                                as MoveIt does (srdf.h); or NULL */
    char  **group;           /* the planning group's joints: robot.joints
                                as written, or robot.group's active
                                joints base first; NULL if neither */
    int     num_group;
    char   *group_name;      /* robot.group, the SRDF group planned; NULL
                                when the joints were listed */
    int     num_joints;
    char  **joint_names;
    unsigned char *wraps;    /* per joint, nonzero for continuous joints */

    /* Joints outside the group that some query or robot.joint_values
     * names: each query holds every one (its own value, the robot's, or
     * the world's default), so that all worlds of a run agree. */
    int     num_held;
    char  **held_names;
    double *held_default;    /* robot.joint_values, else the world's */
    int     held_clamped;    /* MoveIt joint values moved into their
                                limits (clamp_joint_values: true) */
    int     held_ignored;    /* and values of fixed joints skipped */
    int     held_unknown;    /* and values of joints the URDF lacks */
    char    held_unknown_names[256]; /* "a, b, ..." */
    int     goal_clamped;    /* joint goal values just outside a limit,
                                within their tolerance, moved onto it */
    int     start_clamped;   /* start values of the group within
                                MPBD_START_BOUNDS_ERROR outside a limit,
                                moved onto it */
    /* MoveIt scenes' allowed_collision_matrix pairs naming links the
     * robot lacks, skipped as MoveIt does: how many, in how many scenes,
     * where the first is ("file:line:column") and the names. */
    int     acm_skipped;
    int     acm_skipped_scenes;
    char   *acm_skipped_at;
    char    acm_skipped_names[256];
    /* MoveIt orientation constraints whose quaternion is not of unit
     * norm: identity assumed, as MoveIt does. How many; the first's
     * place ("file:line:column"). */
    int     orientation_identity;
    char   *orientation_identity_at;

    mpbd_scene  *scenes;
    int          num_scenes;
    mpbd_query  *queries;
    int          num_queries;
    mpbd_config *configs;
    int          num_configs;
} mpbd_experiment;

/*
 * Read and check the experiment file at path. On failure returns NULL and
 * writes one line to err: "<file>:<line>:<column>: <what is wrong>".
 * Free the result with mpbd_experiment_free().
 */
mpbd_experiment *mpbd_experiment_load(const char *path, char *err, size_t errlen);

void mpbd_experiment_free(mpbd_experiment *e);

/*
 * When the robot has no SRDF and its allowed-collision matrix was
 * generated (world.h): 1 and one line in buf saying how many pairs were
 * allowed for which reason and how to write them out for review; else 0.
 */
int mpbd_experiment_acm_note(const mpbd_experiment *e, char *buf, size_t len);

/*
 * 1 and one line in buf when queries came from MoveIt problem files and
 * something of them is worth saying (values clamped into their limits,
 * planning times that differ from the time limit); else 0.
 */
int mpbd_experiment_moveit_note(const mpbd_experiment *e, char *buf,
                                size_t len);

/*
 * When MoveIt scenes' allowed_collision_matrix pairs named links the robot
 * lacks (skipped, as MoveIt does): 1 and one line in buf saying how many,
 * in how many scenes, which names and where the first is; else 0.
 */
int mpbd_experiment_scene_acm_note(const mpbd_experiment *e, char *buf,
                                   size_t len);

/*
 * When MoveIt orientation constraints were not unit quaternions (identity
 * assumed, as MoveIt does): 1 and one line in buf saying how many and
 * where the first is; else 0.
 */
int mpbd_experiment_orientation_note(const mpbd_experiment *e, char *buf,
                                     size_t len);

/*
 * When scenes' planners are given what was seen of them (`seen:`,
 * experiment_seen.c): 1 and one line in buf saying how many and how the
 * first was made; else 0.
 */
int mpbd_experiment_seen_note(const mpbd_experiment *e, char *buf,
                              size_t len);

/*
 * The goal of q as verify.h describes goals (mpb_query_goal()), for
 * mpb_measure_stage(). The result points into q: it lives as long as q
 * does.
 */
mpb_goal mpbd_query_goal(const mpbd_query *q);

/* q's pose region as the store keeps it: centre, half sizes, rpy, their
 * tolerances (mpb_query_info.goal_region). */
void mpbd_query_region(const mpbd_query *q, double region[12]);

/*
 * Make the world of q's scene hold q's values of the joints outside the
 * group (world.h: mpb_world_hold()), before it checks q's paths. MPB_OK,
 * or the world's code (the values were checked at loading).
 */
int mpbd_query_hold(const mpbd_experiment *e, const mpbd_query *q);
/* The same, in world w: a copy of q's scene's world (mpbd_scene_world_copy). */
int mpbd_query_hold_in(const mpbd_experiment *e, const mpbd_query *q,
                       mpb_world *w);

/*
 * A world of its own for scene `scene` (seen 0) or for what its planners
 * were given (seen 1: its `seen:` scene), opened as the experiment opened
 * the scene's (experiment_robot.c), into *out (close it with
 * mpb_world_close()): for a thread that verifies while another uses the
 * scene's. Held joints are set by mpbd_query_hold_in() before each use.
 * MPB_OK, or the world's code and one line in why.
 */
int mpbd_scene_world_copy(const mpbd_experiment *e, int scene, int seen,
                          mpb_world **out, char *why, size_t len);

/* The seed of one run, derived from the experiment seed and the run's place. */
int64_t mpbd_run_seed(const mpbd_experiment *e, int config, int query,
                      int repetition);

/*
 * Whether some of the robot's meshes are found only beside its URDF, where
 * mpbenchd looks but planners do not (they search MPB_MESH_PATH and
 * ROS_PACKAGE_PATH of their own environment, taken here to be this
 * process's): 1 with one line in buf saying so and what to do, else 0.
 * check_meshes.c.
 */
int mpbd_mesh_note(const mpbd_experiment *e, char *buf, size_t len);

/*
 * The folder (absolute) planners need in MPB_MESH_PATH to find the meshes
 * of the robot of the experiment file at path as mpbenchd does: its URDF's
 * folder; "" for a robot with no URDF file. Reads only the file's YAML.
 * 0, or -1 with one line in err.
 */
int mpbd_mesh_path(const char *path, char *out, size_t n, char *err,
                   size_t errlen);

/*
 * The planner families (each configuration's `planner:`) the experiment
 * file at path names, each once, one per line to out, in the file's
 * order. Reads only the file's YAML. 0, or -1 with one line in err.
 * experiment_families.c.
 */
int mpbd_planner_families(const char *path, FILE *out, char *err,
                          size_t errlen);

#endif
