/* result.c - what a solve() fills in: stages, waypoint times, named
 * values, the message (mpbench/planner.h, mpb_result_*), and a request's
 * parameters. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpbench/planner.h"
#include "planner/planner_internal.h"

int mpb_result_add_stage(mpb_plan_result_t *res, const char *name,
                         double time, const double *waypoints,
                         int num_waypoints, int num_joints)
{
    if (res == NULL || name == NULL || num_waypoints < 0 || num_joints < 0 ||
        num_joints > INT16_MAX || res->num_stages >= INT16_MAX ||
        (num_waypoints > 0 && num_joints > 0 && waypoints == NULL) ||
        (num_joints > 0 && num_waypoints > INT32_MAX / num_joints))
        return MPB_EINVAL;
    size_t nv = (size_t)num_waypoints * (size_t)num_joints;
    mpb_stage_t *stages = realloc(res->stages,
                                  ((size_t)res->num_stages + 1) * sizeof *stages);
    if (stages == NULL)
        return MPB_ENOMEM;
    res->stages = stages;
    mpb_stage_t *st = &stages[res->num_stages];
    memset(st, 0, sizeof *st);
    st->name = strdup(name);
    st->waypoints = nv > 0 ? malloc(nv * sizeof(double)) : NULL;
    if (st->name == NULL || (nv > 0 && st->waypoints == NULL)) {
        free(st->name);
        free(st->waypoints);
        return MPB_ENOMEM;
    }
    if (nv > 0)
        memcpy(st->waypoints, waypoints, nv * sizeof(double));
    st->time = time;
    st->num_waypoints = num_waypoints;
    st->num_joints = (int16_t)num_joints;
    st->num_values = (int32_t)nv;
    res->num_stages++;
    return MPB_OK;
}

int mpb_result_set_times(mpb_plan_result_t *res, int stage,
                         const double *times, int num_times)
{
    if (res == NULL || stage < 0 || stage >= res->num_stages ||
        num_times < 0 || (num_times > 0 && times == NULL))
        return MPB_EINVAL;
    mpb_stage_t *st = &res->stages[stage];
    double *copy = NULL;
    if (num_times > 0) {
        if ((copy = malloc((size_t)num_times * sizeof *copy)) == NULL)
            return MPB_ENOMEM;
        memcpy(copy, times, (size_t)num_times * sizeof *copy);
    }
    free(st->times);
    st->times = copy;
    st->num_times = num_times;
    return MPB_OK;
}

int mpb_result_add_value(mpb_plan_result_t *res, const char *name,
                         double value)
{
    if (res == NULL || name == NULL || res->num_values >= INT16_MAX)
        return MPB_EINVAL;
    mpb_named_value_t *v = realloc(res->values,
                                   ((size_t)res->num_values + 1) * sizeof *v);
    if (v == NULL)
        return MPB_ENOMEM;
    res->values = v;
    v[res->num_values].name = strdup(name);
    if (v[res->num_values].name == NULL)
        return MPB_ENOMEM;
    v[res->num_values].value = value;
    res->num_values++;
    return MPB_OK;
}

int mpb_result_set_message(mpb_plan_result_t *res, const char *fmt, ...)
{
    if (res == NULL || fmt == NULL)
        return MPB_EINVAL;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0)
        return MPB_EINVAL;
    char *m = malloc((size_t)n + 1);
    if (m == NULL)
        return MPB_ENOMEM;
    va_start(ap, fmt);
    vsnprintf(m, (size_t)n + 1, fmt, ap);
    va_end(ap);
    free(res->message);
    res->message = m;
    return MPB_OK;
}

/* Free the stages, values and progress of res, leaving none. */
void mpb__result_clear_lists(mpb_plan_result_t *res)
{
    for (int i = 0; i < res->num_stages; i++) {
        free(res->stages[i].name);
        free(res->stages[i].waypoints);
        free(res->stages[i].times);
    }
    free(res->stages);
    for (int i = 0; i < res->num_values; i++)
        free(res->values[i].name);
    free(res->values);
    for (int i = 0; i < res->num_progress; i++) {
        for (int j = 0; j < res->progress[i].num_values; j++)
            free(res->progress[i].values[j].name);
        free(res->progress[i].values);
    }
    free(res->progress);
    res->stages = NULL;
    res->values = NULL;
    res->progress = NULL;
    res->num_stages = 0;
    res->num_values = 0;
    res->num_progress = 0;
}

void mpb_result_clear(mpb_plan_result_t *res)
{
    if (res == NULL)
        return;
    free(res->attempt_id);
    free(res->planner_id);
    free(res->message);
    mpb__result_clear_lists(res);
    memset(res, 0, sizeof *res);
}

const char *mpb_request_param(const mpb_plan_request_t *req, const char *key)
{
    if (req == NULL || key == NULL)
        return NULL;
    for (int i = 0; i < req->num_params; i++)
        if (req->params[i].key != NULL && strcmp(req->params[i].key, key) == 0)
            return req->params[i].value != NULL ? req->params[i].value : "";
    return NULL;
}

/* LCM cannot encode a NULL string: give every string of res a value. */
int mpb__result_fill_strings(mpb_plan_result_t *res)
{
    if (res->message == NULL && (res->message = strdup("")) == NULL)
        return MPB_ENOMEM;
    for (int i = 0; i < res->num_stages; i++)
        if (res->stages[i].name == NULL &&
            (res->stages[i].name = strdup("")) == NULL)
            return MPB_ENOMEM;
    for (int i = 0; i < res->num_values; i++)
        if (res->values[i].name == NULL &&
            (res->values[i].name = strdup("")) == NULL)
            return MPB_ENOMEM;
    for (int i = 0; i < res->num_progress; i++)
        for (int j = 0; j < res->progress[i].num_values; j++)
            if (res->progress[i].values[j].name == NULL &&
                (res->progress[i].values[j].name = strdup("")) == NULL)
                return MPB_ENOMEM;
    return MPB_OK;
}
