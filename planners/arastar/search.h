/*
 * search.h - ARA* (Anytime Repairing A*) over a lattice of joint-space
 * motion primitives. States are the start plus whole numbers of `step`
 * per joint; a primitive moves one joint by +-1 or +-long_step cells and
 * costs its joint-space length. The heuristic is the end-effector's BFS
 * distance to the goal (bfs_grid.h) plus its rotation from the goal
 * orientation, inflated by epsilon. The goal is reached through a final
 * "snap" motion (see search.c); the first iteration's solution is returned
 * unless `improve` asks ARA* to lower epsilon until the time runs out.
 */
#ifndef ARASTAR_SEARCH_H
#define ARASTAR_SEARCH_H

#include <signal.h>
#include <stdint.h>

#include "bfs_grid.h"
#include "motion.h"
#include "mpbench/robot.h"

typedef struct ara_problem {
    ara_motion            *motion;     /* world and segment checks */
    const mpb_robot       *robot;      /* FK and IK, same joints as world */
    const double          *start;
    /* Exactly one goal: a region, or joints with a tolerance. */
    const mpb_goal_region *region;
    const double          *goal_joints;
    double                 joint_tolerance;
    const ara_grid        *grid;       /* BFS distances to the goal; NULL: none */
    int                    ee_link;    /* link whose point the grid measures */
    double                 ee_offset[3];

    double  step;          /* lattice step, rad (m for prismatic joints) */
    int     long_step;     /* cells of the long primitives; 0: none */
    double  epsilon;       /* initial inflation, >= 1 */
    double  epsilon_decay; /* epsilon is multiplied by it per iteration */
    int     improve;       /* nonzero: keep improving until the deadline */
    double  h_position;    /* joint-cost units per metre of BFS distance */
    double  h_rotation;    /* joint-cost units per radian of orientation */
    double  snap_distance; /* m (region) or rad (joints): try the snap within */
    uint64_t ik_seed;
    int     max_states;
    double  deadline;      /* mpb_monotonic_s() time */
    volatile sig_atomic_t *stop;

    /* Optional: called with each new solution (anytime progress). */
    void  (*on_solution)(void *user, double time, double cost, double eps,
                         long expansions);
    void   *user;
} ara_problem;

typedef enum ara_outcome {
    ARA_SOLVED = 0,
    ARA_NO_PATH,       /* OPEN ran empty */
    ARA_TIMEOUT,       /* deadline or stop before any solution */
    ARA_STATE_LIMIT,   /* max_states reached before any solution */
    ARA_START_INVALID, /* start collides or is outside the limits */
    ARA_NOMEM
} ara_outcome;

typedef struct ara_solution {
    ara_outcome outcome;
    double *waypoints;     /* num_waypoints x num_joints, caller frees */
    int     num_waypoints;
    double  cost;
    double  epsilon;       /* the bound of the returned solution */
    long    expansions, generated, snaps_tried, snaps_ik, snaps_found,
            iterations;
} ara_solution;

/* Run the search; fills *out (free out->waypoints). */
void ara_search(const ara_problem *p, ara_solution *out);

#endif
