/*
 * measure.c - one stage verified and measured, as mpbenchd stores it: the
 * metric list of metrics.h (MPB_METRIC_MAP) and the function computing
 * each of its metrics, metric_<ID>().
 */
#include "mpbench/mpbench.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

/* What a metric is computed from; clearances are measured once for both
 * metrics that read them (a distance query per waypoint, the dear part). */
typedef struct mpb__measure {
    mpb_world    *w;
    const double *wp;
    int           n, nj;
    double        time, resolution;
    const unsigned char *wraps;
    int           have_clearances;
    double        mean_clearance, least_clearance;
} mpb__measure;

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
    mpb__measure m = {
        .w = w, .wp = wp, .n = num_waypoints, .nj = num_joints,
        .time = stage_time, .resolution = resolution,
        .wraps = w != NULL ? mpb_world_joint_wraps(w) : NULL,
    };
    mpb_verdict_code v = out->verdict.code;
    int path = wp != NULL && v != MPB_VERDICT_NOT_FINITE &&
               v != MPB_VERDICT_WRONG_SIZE;
    out->num_metrics = 0;
    for (int i = 0; i < MPB_NUM_METRICS; i++) {
        if ((metric_info[i].flags & MPB_METRIC_F_PATH) && !path)
            continue;
        out->metrics[out->num_metrics].name = metric_info[i].name;
        out->metrics[out->num_metrics].value = metric_fn[i](&m);
        out->num_metrics++;
    }
}

int mpb_measure_stage(mpb_world *w, const double *start,
                      double start_tolerance, const mpb_goal *goal,
                      const double *wp, int num_waypoints, int num_joints,
                      double stage_time, double resolution, unsigned flags,
                      mpb_stage_measure *out)
{
    int rc = mpb_verify_path(w, start, start_tolerance, goal, wp,
                             num_waypoints, num_joints, resolution,
                             &out->verdict);
    if (flags & MPB_MEASURE_NO_METRICS)
        out->num_metrics = 0;
    else
        mpb_measure_metrics(w, wp, num_waypoints, num_joints, stage_time,
                            resolution, out);
    return rc;
}
