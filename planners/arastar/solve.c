/*
 * solve.c - one request: read the parameters, build the world, the voxel
 * grid and its BFS (tau_other), run ARA*, and fill the result.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bfs_grid.h"
#include "motion.h"
#include "mpbench/mpbench.h"
#include "mpbench/robot.h"
#include "mpbench/scene.h"
#include "mpbench/world.h"
#include "search.h"
#include "solve.h"
#include "voxelize.h"

#define DEG (M_PI / 180.0)

/* The request's parameters, with the paper's settings as defaults. */
typedef struct params {
    double epsilon, epsilon_decay, step, long_step, improve, h_position,
           h_rotation, snap_distance, resolution, grid_resolution,
           grid_cells, max_states, ik_seed;
} params;

typedef struct param_def {
    const char *key;
    size_t      off;
    double      lo, hi;
} param_def;

#define P(name, lo, hi) {#name, offsetof(params, name), lo, hi}
static const param_def PARAMS[] = {
    P(epsilon, 1, 1e6),        P(epsilon_decay, 0.01, 0.99),
    P(step, 1e-3, 1),          P(long_step, 0, 16),
    P(improve, 0, 1),          P(h_position, 0, 1e3),
    P(h_rotation, 0, 1e3),     P(snap_distance, 0, 10),
    P(resolution, 1e-4, 1),    P(grid_resolution, 0.005, 0.5),
    P(grid_cells, 8, 512),     P(max_states, 1000, 5e7),
    P(ik_seed, 0, 4e9),
};
#undef P

static int read_params(const mpb_plan_request_t *req, params *p,
                       mpb_plan_result_t *res)
{
    *p = (params){.epsilon = 100, .epsilon_decay = 0.5, .step = 4 * DEG,
                  .long_step = 2, .improve = 0, .h_position = 5,
                  .h_rotation = 1, .snap_distance = -1, .resolution = 0.01,
                  .grid_resolution = 0.02, .grid_cells = 128,
                  .max_states = 1e6, .ik_seed = 1};
    for (int i = 0; i < req->num_params; i++) {
        const mpb_param_t *kv = &req->params[i];
        const param_def *d = NULL;
        for (size_t k = 0; k < sizeof PARAMS / sizeof *PARAMS; k++)
            if (strcmp(PARAMS[k].key, kv->key) == 0)
                d = &PARAMS[k];
        if (!d) {
            mpb_result_set_message(res, "unknown parameter '%.40s'", kv->key);
            return MPB_EINVAL;
        }
        char *end;
        double v = strtod(kv->value, &end);
        if (*end != '\0' || end == kv->value || !(v >= d->lo && v <= d->hi)) {
            mpb_result_set_message(res, "%s must be a number in [%g, %g], "
                                   "not '%.40s'", d->key, d->lo, d->hi,
                                   kv->value);
            return MPB_EINVAL;
        }
        *(double *)((char *)p + d->off) = v;
    }
    int n = (int)p->grid_cells;
    if ((n & (n - 1)) != 0 || n != p->grid_cells) {
        mpb_result_set_message(res, "grid_cells must be a power of two");
        return MPB_EINVAL;
    }
    if (p->snap_distance < 0)   /* m for regions, rad for joint goals */
        p->snap_distance = req->goal.kind == MPB_GOAL_T_POSE_REGION ? 0.1 : 0.5;
    return MPB_OK;
}

/* Everything a run owns, freed in one place. */
typedef struct run {
    mpb_world  *world;
    mpb_robot  *robot;
    mpb_scene  *scene;
    ara_motion  motion;
    ara_grid    grid;
    ara_solution sol;
} run;

static void run_free(run *r)
{
    free(r->sol.waypoints);
    ara_grid_free(&r->grid);
    ara_motion_free(&r->motion);
    mpb_scene_close(r->scene);
    mpb_robot_close(r->robot);
    mpb_world_close(r->world);
}

static int fail(mpb_plan_result_t *res, int status, const char *msg)
{
    res->status = (int8_t)status;
    mpb_result_set_message(res, "%s", msg);
    return MPB_OK;
}

/* Build the voxel grid around the arm's base and run the BFS from goal_xyz. */
static int build_grid(run *r, const params *p, const double *start,
                      const double goal_xyz[3], long *tests, long *reached,
                      char *err, size_t errlen)
{
    mpb_pose base;
    int rc = mpb_robot_link_pose(r->robot, start, mpb_robot_base_link(r->robot),
                                 &base);
    if (rc != MPB_OK) {
        snprintf(err, errlen, "forward kinematics failed at the start");
        return rc;
    }
    int n = (int)p->grid_cells;
    double half = 0.5 * n * p->grid_resolution, origin[3];
    for (int i = 0; i < 3; i++)
        origin[i] = base.t[i] - half;
    if (ara_grid_init(&r->grid, n, n, n, origin, p->grid_resolution) != 0) {
        snprintf(err, errlen, "out of memory for the voxel grid");
        return MPB_ENOMEM;
    }
    *tests = ara_voxelize(&r->grid, r->scene, r->robot, start, err, errlen);
    if (*tests < 0)
        return (int)*tests;
    int cell[3];
    if (ara_grid_cell_of(&r->grid, goal_xyz, cell) != 0) {
        snprintf(err, errlen, "the goal is outside the voxel grid (%.2f m "
                 "around the arm's base)", half);
        return MPB_EINVAL;
    }
    *reached = ara_grid_bfs(&r->grid, cell);
    if (*reached < 0) {
        snprintf(err, errlen, "out of memory for the BFS");
        return MPB_ENOMEM;
    }
    return MPB_OK;
}

static void on_solution(void *user, double t, double cost, double eps,
                        long expansions)
{
    mpb_plan_result_t *res = user;
    mpb_progress_t *pr = realloc(res->progress,
                                 (size_t)(res->num_progress + 1) * sizeof *pr);
    if (!pr)
        return;
    res->progress = pr;
    static const char *const names[] = {"best cost", "epsilon", "expansions"};
    const double vals[] = {cost, eps, (double)expansions};
    mpb_named_value_t *v = calloc(3, sizeof *v);
    if (!v)
        return;
    int n = 0;
    for (int i = 0; i < 3; i++) {
        v[n].name = strdup(names[i]);
        if (!v[n].name)
            break;
        v[n].value = vals[i];
        n++;
    }
    pr[res->num_progress] = (mpb_progress_t){.time = t, .num_values =
                                             (int16_t)n, .values = v};
    res->num_progress++;
}

static int solve_run(run *r, const mpb_solve_limits *lim,
                     const mpb_plan_request_t *req, mpb_plan_result_t *res)
{
    double t0 = mpb_monotonic_s();
    params p;
    char err[256] = "";
    int rc = read_params(req, &p, res);
    if (rc != MPB_OK)
        return rc;
    if (strcmp(req->robot_format, "urdf") != 0) {
        mpb_result_set_message(res, "ARAstar needs a urdf robot, not '%.20s'",
                               req->robot_format);
        return MPB_EUNSUPPORTED;
    }
    int nj = req->num_joints;
    const char *const *names = (const char *const *)req->joint_names;
    const double t_world = mpb_monotonic_s();
    rc = mpb_world_open_group(req->robot_format, req->robot, req->scene_format,
                              req->scene, names, nj, &r->world, err, sizeof err);
    if (rc == MPB_OK)
        rc = mpb_robot_open_urdf_joints(req->robot, names, nj, &r->robot, err,
                                        sizeof err);
    if (rc == MPB_OK)
        rc = mpb_scene_open_text(req->scene, &r->scene, err, sizeof err);
    if (rc == MPB_OK)
        rc = mpb_request_hold(req, r->world, r->robot, err, sizeof err);
    if (rc != MPB_OK) {
        mpb_result_set_message(res, "%s", err[0] ? err : mpb_strerror(rc));
        return rc;
    }
    /* Parsing the robot and scene (every run: nothing is cached) is the
     * world's time, not the run's: reported on its own, outside tau_t. The
     * distance field below is the run's (the paper's tau_o). */
    const double setup = mpb_monotonic_s() - t_world;
    if ((rc = mpb_result_add_value(res, MPB_WORLD_SETUP_TIME, setup)) != MPB_OK)
        return rc;
    t0 += setup;
    if (ara_motion_init(&r->motion, r->world, p.resolution) != 0)
        return MPB_ENOMEM;

    /* The goal, and the point the BFS starts from. */
    mpb_goal_region region;
    double goal_xyz[3];
    int ee_link = mpb_robot_tip_link(r->robot);
    const mpb_goal_t *g = &req->goal;
    if (g->kind == MPB_GOAL_T_POSE_REGION) {
        memset(&region, 0, sizeof region);
        region.link = mpb_robot_link_index(r->robot, g->link);
        for (int i = 0; i < 3; i++) {
            region.center[i] = g->position[i];
            region.half_extents[i] = g->position_tolerance[i];
            region.ref_rpy[i] = g->orientation_rpy[i];
            region.rpy_tolerance[i] = g->orientation_tolerance[i];
        }
        if (mpb_goal_region_check(r->robot, &region, err, sizeof err) != 0) {
            mpb_result_set_message(res, "goal: %s", err);
            return MPB_EINVAL;
        }
        memcpy(goal_xyz, region.center, sizeof goal_xyz);
    } else {
        mpb_pose tip;
        if (mpb_robot_link_pose(r->robot, g->joints, ee_link, &tip) != MPB_OK) {
            mpb_result_set_message(res, "goal joints are not finite");
            return MPB_EINVAL;
        }
        memcpy(goal_xyz, tip.t, sizeof goal_xyz);
    }
    if (!mpb_robot_within_limits(r->robot, req->start)) {
        /* Clamped starts would not begin where the verifier wants. */
        return fail(res, MPB_PLAN_RESULT_T_FAILED,
                    "the start state is outside the joint limits");
    }
    long tests = 0, reached = 0;
    rc = build_grid(r, &p, req->start, goal_xyz, &tests, &reached, err,
                    sizeof err);
    if (rc != MPB_OK) {
        mpb_result_set_message(res, "%s", err);
        return rc;
    }
    const double t_search = mpb_monotonic_s();
    res->time_other = t_search - t0;

    ara_problem prob = {
        .motion = &r->motion, .robot = r->robot, .start = req->start,
        .region = g->kind == MPB_GOAL_T_POSE_REGION ? &region : NULL,
        .goal_joints = g->kind == MPB_GOAL_T_JOINTS ? g->joints : NULL,
        .joint_tolerance = g->joint_tolerance, .grid = &r->grid,
        .ee_link = ee_link, .step = p.step, .long_step = (int)p.long_step,
        .epsilon = p.epsilon, .epsilon_decay = p.epsilon_decay,
        .improve = p.improve != 0, .h_position = p.h_position,
        .h_rotation = p.h_rotation, .snap_distance = p.snap_distance,
        .ik_seed = (uint64_t)p.ik_seed, .max_states = (int)p.max_states,
        /* The kit's deadline, moved by the world's setup as t0 is. */
        .deadline = lim->deadline + setup, .stop = lim->stop,
        .on_solution = p.improve != 0 ? on_solution : NULL, .user = res,
    };
    ara_search(&prob, &r->sol);
    const double t_end = mpb_monotonic_s();
    res->time_total = t_end - t0;

    const ara_solution *s = &r->sol;
    mpb_result_add_value(res, "expansions", (double)s->expansions);
    mpb_result_add_value(res, "states generated", (double)s->generated);
    mpb_result_add_value(res, "collision checks", (double)r->motion.checks);
    mpb_result_add_value(res, "snaps tried", (double)s->snaps_tried);
    mpb_result_add_value(res, "snaps with ik", (double)s->snaps_ik);
    mpb_result_add_value(res, "snaps found", (double)s->snaps_found);
    mpb_result_add_value(res, "voxel box tests", (double)tests);
    mpb_result_add_value(res, "bfs cells reached", (double)reached);
    switch (s->outcome) {
    case ARA_SOLVED:
        rc = mpb_result_add_stage(res, "raw", t_end - t_search, s->waypoints,
                                  s->num_waypoints, nj);
        if (rc != MPB_OK)
            return fail(res, MPB_PLAN_RESULT_T_FAILED, mpb_strerror(rc));
        mpb_result_add_value(res, "cost", s->cost);
        mpb_result_add_value(res, "epsilon", s->epsilon);
        res->status = MPB_PLAN_RESULT_T_SOLVED;
        return MPB_OK;
    case ARA_TIMEOUT:
        return fail(res, MPB_PLAN_RESULT_T_TIMEOUT, "no solution within the "
                    "time limit");
    case ARA_NO_PATH:
        return fail(res, MPB_PLAN_RESULT_T_FAILED, "the lattice has no path "
                    "to the goal");
    case ARA_STATE_LIMIT:
        return fail(res, MPB_PLAN_RESULT_T_FAILED, "state limit (max_states) "
                    "reached");
    case ARA_START_INVALID:
        return fail(res, MPB_PLAN_RESULT_T_FAILED, "the start state collides");
    case ARA_NOMEM:
        /* Past the request's memory_limit, or the machine's. */
        return fail(res, MPB_PLAN_RESULT_T_MEMORY, "out of memory: the "
                    "search's states could not be allocated");
    default:
        return fail(res, MPB_PLAN_RESULT_T_FAILED, "unknown outcome");
    }
}

int ara_solve(void *user, const mpb_plan_request_t *req,
              const mpb_solve_limits *lim, mpb_plan_result_t *res)
{
    const ara_context *ctx = user;
    run r;
    memset(&r, 0, sizeof r);
    int rc = solve_run(&r, lim, req, res);
    if (ctx->verbose)
        fprintf(stderr, "mpb-planner-arastar: run %s: status %d, %.3f s "
                "(other %.3f s) %s\n", req->attempt_id, res->status,
                res->time_total, res->time_other,
                res->message ? res->message : "");
    run_free(&r);
    return rc;
}
