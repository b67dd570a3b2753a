/*
 * measure.c - one stage verified and measured, as mpbenchd stores it: the
 * metric list of metrics.h (MPB_METRIC_MAP) and the function computing
 * each of its metrics, metric_<ID>().
 */
#include "mpbench/mpbench.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* What a metric is computed from; clearances are measured once for both
 * metrics that read them (a distance query per waypoint, the dear part). */
typedef struct mpb__measure {
    mpb_world    *w;
    const double *wp, *times;     /* times NULL: untimed */
    int           n, nj;
    double        time, resolution;
    const unsigned char *wraps;
    int           have_clearances;
    double        mean_clearance, least_clearance;
    int           have_timing;
    mpb_timing    timing;
} mpb__measure;

/* Each joint's velocity limit, 0 where none, into v (num_joints values);
 * NULL where no joint has one or memory runs out. */
static double *velocity_limits(mpb_world *w, int num_joints)
{
    int any = 0;
    for (int j = 0; j < num_joints; j++)
        any |= mpb_world_joint_max_velocity(w, j) > 0;
    double *v = any ? malloc((size_t)num_joints * sizeof *v) : NULL;
    for (int j = 0; v != NULL && j < num_joints; j++)
        v[j] = mpb_world_joint_max_velocity(w, j);
    return v;
}

static const mpb_timing *timing(mpb__measure *m)
{
    if (!m->have_timing) {
        double *limits = velocity_limits(m->w, m->nj);
        mpb_path_timing(m->wp, m->times, m->n, m->nj, m->wraps, limits,
                        &m->timing);
        free(limits);
    }
    m->have_timing = 1;
    return &m->timing;
}

static void clearances(mpb__measure *m)
{
    if (!m->have_clearances)
        mpb_path_clearances(m->w, m->wp, m->n, m->nj, &m->mean_clearance,
                            &m->least_clearance);
    m->have_clearances = 1;
}

static double metric_CLEARANCE(mpb__measure *m)
{
    clearances(m);
    return m->mean_clearance;
}

static double metric_MIN_CLEARANCE(mpb__measure *m)
{
    clearances(m);
    return m->least_clearance;
}

static double metric_PATH_LENGTH(mpb__measure *m)
{
    return mpb_path_length(m->wp, m->n, m->nj, m->wraps);
}

static double metric_EE_PATH_LENGTH(mpb__measure *m)
{
    return mpb_ee_path_length(m->w, m->wp, m->n, m->nj, m->resolution);
}

static double metric_SMOOTHNESS(mpb__measure *m)
{
    return mpb_smoothness(m->wp, m->n, m->nj, m->wraps);
}

static double metric_SMOOTHNESS_RESAMPLED(mpb__measure *m)
{
    return mpb_smoothness_resampled(m->wp, m->n, m->nj, m->wraps);
}

static double metric_WAYPOINTS(mpb__measure *m)
{
    return m->n;
}

static double metric_TIME(mpb__measure *m)
{
    return m->time;
}

static double metric_DURATION(mpb__measure *m)
{
    return timing(m)->duration;
}

static double metric_MAX_VELOCITY(mpb__measure *m)
{
    return timing(m)->max_velocity;
}

static double metric_VELOCITY_RATIO(mpb__measure *m)
{
    return timing(m)->velocity_ratio;
}

static double metric_MAX_ACCELERATION(mpb__measure *m)
{
    return timing(m)->max_acceleration;
}

static const mpb_metric_info metric_info[MPB_NUM_METRICS] = {
#define MPB__METRIC_INFO(id, name, unit, flags, rank, symbol, latex, title,  \
                         axis, better, word)                                 \
    [MPB_METRIC_##id] = {name, unit, flags, rank, symbol, latex, title,      \
                         axis, better, word},
    MPB_METRIC_MAP(MPB__METRIC_INFO)
#undef MPB__METRIC_INFO
};

static double (*const metric_fn[MPB_NUM_METRICS])(mpb__measure *) = {
#define MPB__METRIC_FN(id, ...) [MPB_METRIC_##id] = metric_##id,
    MPB_METRIC_MAP(MPB__METRIC_FN)
#undef MPB__METRIC_FN
};

const mpb_metric_info *mpb_metric_info_of(int id)
{
    return id >= 0 && id < MPB_NUM_METRICS ? &metric_info[id] : NULL;
}

int mpb_metric_find(const char *name)
{
    for (int i = 0; name != NULL && i < MPB_NUM_METRICS; i++)
        if (strcmp(metric_info[i].name, name) == 0)
            return i;
    return -1;
}

void mpb_measure_metrics(mpb_world *w, const double *wp, int num_waypoints,
                         int num_joints, double stage_time, double resolution,
                         mpb_stage_measure *out)
{
    mpb_measure_metrics_timed(w, wp, NULL, num_waypoints, num_joints,
                              stage_time, resolution, out);
}

void mpb_measure_metrics_timed(mpb_world *w, const double *wp,
                               const double *times, int num_waypoints,
                               int num_joints, double stage_time,
                               double resolution, mpb_stage_measure *out)
{
    mpb__measure m = {
        .w = w, .wp = wp, .times = times, .n = num_waypoints,
        .nj = num_joints,
        .time = stage_time, .resolution = resolution,
        .wraps = w != NULL ? mpb_world_joint_wraps(w) : NULL,
    };
    mpb_verdict_code v = out->verdict.code;
    int path = wp != NULL && v != MPB_VERDICT_NOT_FINITE &&
               v != MPB_VERDICT_WRONG_SIZE;
    out->num_metrics = 0;
    for (int i = 0; i < MPB_NUM_METRICS; i++) {
        unsigned flags = metric_info[i].flags;
        if ((flags & MPB_METRIC_F_PATH) && !path)
            continue;
        if ((flags & MPB_METRIC_F_TIMED) &&
            (times == NULL || num_waypoints < 1))
            continue;
        double value = metric_fn[i](&m);
        if ((flags & MPB_METRIC_F_TIMED) && isnan(value))
            continue;
        out->metrics[out->num_metrics].name = metric_info[i].name;
        out->metrics[out->num_metrics].value = value;
        out->num_metrics++;
    }
}

int mpb_measure_stage(mpb_world *w, const double *start,
                      double start_tolerance, const mpb_goal *goal,
                      const double *wp, int num_waypoints, int num_joints,
                      double stage_time, double resolution, unsigned flags,
                      mpb_stage_measure *out)
{
    return mpb_measure_stage_timed(w, start, start_tolerance, goal, wp, NULL,
                                   num_waypoints, num_joints, stage_time,
                                   resolution, flags, out);
}

/* The last check of a timed stage that passed the others: no joint faster
 * than its limit, beyond MPB_VELOCITY_TOLERANCE. */
static void check_velocity(mpb_world *w, const double *wp,
                           const double *times, int num_waypoints,
                           int num_joints, mpb_verdict *v)
{
    double *limits = velocity_limits(w, num_joints);
    mpb_timing t;
    int rc = mpb_path_timing(wp, times, num_waypoints, num_joints,
                             mpb_world_joint_wraps(w), limits, &t);
    free(limits);
    if (rc != MPB_OK || !(t.velocity_ratio > 1.0 + MPB_VELOCITY_TOLERANCE))
        return;
    int i = t.ratio_segment, j = t.ratio_joint;
    double limit = mpb_world_joint_max_velocity(w, j);
    v->code = MPB_VERDICT_VELOCITY_LIMIT;
    v->segment = i;
    snprintf(v->detail, sizeof v->detail,
             "segment %d (waypoints %d-%d, %.6g s to %.6g s): joint %.80s at "
             "%.6g, %.4g times its URDF velocity limit %.6g", i, i, i + 1,
             times[i], times[i + 1], mpb_world_joint_name(w, j),
             t.velocity_ratio * limit, t.velocity_ratio, limit);
}

int mpb_measure_stage_timed(mpb_world *w, const double *start,
                            double start_tolerance, const mpb_goal *goal,
                            const double *wp, const double *times,
                            int num_waypoints, int num_joints,
                            double stage_time, double resolution,
                            unsigned flags, mpb_stage_measure *out)
{
    int rc = mpb_verify_path(w, start, start_tolerance, goal, wp,
                             num_waypoints, num_joints, resolution,
                             &out->verdict);
    if (rc == MPB_OK && times != NULL &&
        out->verdict.code == MPB_VERDICT_VALID)
        check_velocity(w, wp, times, num_waypoints, num_joints,
                       &out->verdict);
    if (flags & MPB_MEASURE_NO_METRICS)
        out->num_metrics = 0;
    else
        mpb_measure_metrics_timed(w, wp, times, num_waypoints, num_joints,
                                  stage_time, resolution, out);
    return rc;
}
