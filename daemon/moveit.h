/*
 * moveit.h - MoveIt's PlanningScene and MotionPlanRequest messages written
 * as YAML (MotionBenchMaker's sceneNNNN.yaml and requestNNNN.yaml), read
 * into what an experiment holds: a scene in the "moveit-scene" text format
 * (scene.h), allowed link pairs, joint values and a goal. The reader does
 * not know the robot: the experiment checks joint and link names against
 * it, naming the place each was read from (mpbd_mark). The formats, and
 * what is refused, are in docs/moveit-problems.md.
 */
#ifndef MPBD_MOVEIT_H
#define MPBD_MOVEIT_H

#include <stddef.h>

#include "mpbench/mpbench.h"
#include "yamldoc.h"

/* A robot_state's joint_state: names and positions, in file order. */
typedef struct mpbd_moveit_joints {
    int        n;
    char     **names;
    double    *values;
    mpbd_mark *at;             /* where each name is */
} mpbd_moveit_joints;

typedef struct mpbd_moveit_scene {
    char      *text;           /* the world's objects as a moveit-scene */
    int        num_objects;
    int        num_pairs;      /* allowed_collision_matrix: the pairs of
                                  entries whose value is true */
    char     **pairs;          /* 2 * num_pairs names */
    mpbd_mark *pair_at;        /* where each name is, 2 * num_pairs */
    mpbd_moveit_joints state;  /* robot_state.joint_state */
} mpbd_moveit_scene;

typedef struct mpbd_moveit_request {
    char      *group_name;     /* NULL if absent */
    mpbd_mark  group_at;
    double     allowed_planning_time;   /* s; 0 if absent */
    mpbd_moveit_joints start;  /* start_state.joint_state */
    mpbd_mark  start_at;       /* start_state; 1:1 if absent */

    mpb_goal_kind goal_kind;
    /* MPB_GOAL_JOINTS: joint_constraints, in file order; a tolerance NaN
     * where the file gives none */
    mpbd_moveit_joints goal;
    double    *tolerance_above, *tolerance_below;
    mpbd_mark  goal_at;        /* the goal_constraints entry */
    /* MPB_GOAL_POSE_REGION: position + orientation constraints */
    char      *link;
    mpbd_mark  link_at;
    double     position[3], position_tolerance[3];  /* box centre, half */
    double     rpy[3], rpy_tolerance[3];            /* rad; pi: free */
    /* The orientation constraint's quaternion was not of unit norm
     * (within 1e-3): identity was assumed, as MoveIt does, and the
     * caller warns. Where it is. */
    int        orientation_identity;
    mpbd_mark  orientation_at;
} mpbd_moveit_request;

/*
 * Read the PlanningScene YAML file at path named `name` (the first line
 * of the scene text) into *s (zeroed first). MPB_OK; else MPB_EIO /
 * MPB_EPARSE / MPB_ENOMEM with one line in err, "<path>:<line>:<column>:
 * <what>", and nothing to free in *s.
 */
int mpbd_moveit_scene_read(const char *path, const char *name,
                           mpbd_moveit_scene *s, char *err, size_t errlen);
void mpbd_moveit_scene_clear(mpbd_moveit_scene *s);

/* As mpbd_moveit_scene_read(), for a MotionPlanRequest. */
int mpbd_moveit_request_read(const char *path, mpbd_moveit_request *r,
                             char *err, size_t errlen);
void mpbd_moveit_request_clear(mpbd_moveit_request *r);

#endif
