/*
 * store_pa_walk.c - the walk over an experiment's finished runs
 * (store_pa.h): each run read from the store (its stages, metrics, the
 * planner's own numbers and progress samples) and turned into a row of
 * the run properties store_pa_props.c names. The database writer and the
 * log writer both consume it.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/grow.h"
#include "interop/store_pa.h"

/* mpbench's status name (runs.status) as a value of the status enum. */
static int status_value(const char *status)
{
    static const struct { const char *name; int value; } map[] = {
        {"solved", 6}, {"approximate", 5}, {"timeout", 4}, {"crash", 7},
        {"failed", 8}, {"invalid_request", 10}, {"memory", 11},
    };
    for (size_t i = 0; status && i < sizeof map / sizeof map[0]; i++)
        if (strcmp(status, map[i].name) == 0)
            return map[i].value;
    return 0;
}

struct pa_walker {
    mpb_store       *s;
    const prop_list *props, *progress;
    mpb__run_cursor *runs;
    const mpb__done_run *run;   /* the current one, the cursor's */
    double          *row;
    int64_t         *ints;      /* the row's integers, where is_int */
    unsigned char   *is_int;
    double          *smp;
    int              num_smp, smp_cap;
};

void mpb__pa_walker_close(pa_walker *w)
{
    if (w == NULL)
        return;
    mpb__run_cursor_close(w->runs);
    free(w->row);
    free(w->ints);
    free(w->is_int);
    free(w->smp);
    free(w);
}

int mpb__pa_walker_open(pa_walker **out, mpb_store *s, int64_t experiment_id,
                        int64_t query_id, const prop_list *props,
                        const prop_list *progress)
{
    pa_walker *w = calloc(1, sizeof *w);
    int rc;
    *out = NULL;
    if (w == NULL)
        return mpb__store_fail(s, MPB_ENOMEM, "out of memory");
    *w = (pa_walker){.s = s, .props = props, .progress = progress};
    if ((rc = mpb__run_cursor_open(s, experiment_id, query_id, &w->runs))) {
        mpb__pa_walker_close(w);
        return rc;
    }
    if ((w->row = malloc(sizeof *w->row * (size_t)(props->n + 1))) == NULL ||
        (w->ints = malloc(sizeof *w->ints * (size_t)(props->n + 1))) == NULL ||
        (w->is_int = malloc((size_t)props->n + 1)) == NULL) {
        mpb__pa_walker_close(w);
        return mpb__store_fail(s, MPB_ENOMEM, "out of memory");
    }
    *out = w;
    return MPB_OK;
}

/* Progress: the store keeps one row per (sample, name), in the order
 * received; consecutive rows at one time are one sample: a row here, a
 * column per name. */
static int gather_samples(pa_walker *w)
{
    const mpb__done_run *r = w->run;
    int np = w->progress->n;
    double last_time = NAN;
    w->num_smp = 0;
    for (int i = 0; i < r->num_samples; i++) {
        const mpb__done_sample *p = &r->samples[i];
        if (w->num_smp == 0 || !(p->time == last_time)) {
            int cap = w->smp_cap / np;
            if (w->num_smp >= cap) {
                int ncap = cap ? 2 * cap : 64;
                double *v = realloc(w->smp, sizeof *v * (size_t)ncap *
                                                (size_t)np);
                if (v == NULL)
                    return MPB_ENOMEM;
                w->smp = v;
                w->smp_cap = ncap * np;
            }
            double *row = w->smp + (size_t)w->num_smp * (size_t)np;
            for (int k = 0; k < np; k++)
                row[k] = NAN;
            row[0] = p->time;
            w->num_smp++;
            last_time = p->time;
        }
        double *row = w->smp + (size_t)(w->num_smp - 1) * (size_t)np;
        for (int k = 1; p->name && k < np; k++)
            if (strcmp(w->progress->v[k].source, p->name) == 0)
                row[k] = p->value;
    }
    return MPB_OK;
}

static double metric_of(const mpb__done_run *r, const mpb__done_stage *si,
                        const char *name)
{
    for (int i = 0; si && i < r->num_metrics; i++)
        if (strcmp(r->metrics[i].stage, si->name) == 0 &&
            strcmp(r->metrics[i].name, name) == 0)
            return r->metrics[i].value;
    return NAN;
}

int mpb__pa_walker_next(pa_walker *w, run_view *out)
{
    int rc = mpb__run_cursor_next(w->runs, &w->run);
    if (rc <= 0)
        return rc;
    const mpb__done_run *r = w->run;
    if (gather_samples(w) != MPB_OK)
        return mpb__store_fail(w->s, MPB_ENOMEM, "out of memory");
    const char *status = r->status;
    const char *final_name = r->final_stage;
    const mpb__done_stage *first = r->num_stages > 0 ? &r->stages[0] : NULL;
    const mpb__done_stage *final =
        r->num_stages > 0 ? &r->stages[r->num_stages - 1] : NULL;
    for (int i = 0; final_name && i < r->num_stages; i++)
        if (strcmp(r->stages[i].name, final_name) == 0)
            final = &r->stages[i];

    for (int k = 0; k < w->props->n; k++) {
        const prop *p = &w->props->v[k];
        const mpb__done_stage *si = p->role == ROLE_FIRST ? first
                             : p->role == ROLE_FINAL ? final
                             : p->role == ROLE_SIMPLIFIED && final != first
                                 ? final : NULL;
        if (p->role == ROLE_MID)
            for (int i = 0; i < r->num_stages; i++)
                if (&r->stages[i] != first && &r->stages[i] != final &&
                    strcmp(r->stages[i].name, p->stage) == 0)
                    si = &r->stages[i];
        double v = NAN;
        w->is_int[k] = 0;
        switch (p->kind) {
        case K_TIME:       v = r->time_total; break;
        case K_TIME_RAW:   v = r->time_raw; break;
        case K_TIME_OTHER: v = r->time_other; break;
        case K_WALL:       v = r->wall_time; break;
        case K_VERIFY:     v = r->verify_time; break;
        case K_MEMORY:     v = r->memory; break;
        case K_SOLVED:     v = r->success; break;
        case K_CLAIMED:    v = r->claimed_success; break;
        case K_APPROX:
            v = status ? strcmp(status, "approximate") == 0 : NAN;
            break;
        case K_STATUS:
            v = status_value(status);
            /* An imported run keeps the log's own number as its value
             * "status": OMPL's 0, 8 and 9 are all mpbench's "failed". */
            for (int i = 0; status && i < r->num_values; i++)
                if (strcmp(r->values[i].name, "status") == 0 &&
                    mpb_ompl_status_name(r->values[i].value) != NULL &&
                    strcmp(mpb_ompl_status_name(r->values[i].value), status) == 0)
                    v = r->values[i].value;
            break;
        case K_STAGE_TIME: v = si ? si->time : NAN; break;
        case K_STAGE_METRIC: v = metric_of(r, si, p->source); break;
        case K_STAGE_SEGMENTS:
            /* An imported run's stages have no waypoints, only the log's
             * count as the metric "waypoints" (mpb import). */
            v = si && si->num_waypoints > 0
                    ? si->num_waypoints - 1
                    : metric_of(r, si, mpb_metric_info_of(
                                           MPB_METRIC_WAYPOINTS)->name) - 1;
            break;
        case K_STAGE_VALID: v = si ? si->valid : NAN; break;
        case K_VALUE:
            for (int i = 0; i < r->num_values; i++)
                if (strcmp(r->values[i].name, p->source) == 0) {
                    v = r->values[i].value;
                    w->is_int[k] = (unsigned char)r->values[i].is_int;
                    w->ints[k] = r->values[i].exact;
                }
            break;
        }
        if ((p->kind == K_SOLVED || p->kind == K_CLAIMED) && !isnan(v))
            v = v != 0.0;   /* booleans as 0/1, whatever was stored */
        w->row[k] = v;
    }
    *out = (run_view){
        .run_id = r->id,
        .config_id = r->config_id,
        .query_id = r->query_id,
        .values = w->row,
        .ints = w->ints,
        .is_int = w->is_int,
        .samples = w->smp,
        .num_samples = w->num_smp,
    };
    return 1;
}

