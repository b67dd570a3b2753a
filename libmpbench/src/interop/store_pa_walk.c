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

typedef struct stage_info {
    char  *name;
    double time;
    int    num_waypoints;
    int    valid;
} stage_info;

typedef struct metric_info {
    char  *stage, *name;
    double value;
} metric_info;

typedef struct named_value {
    char   *name;
    double  value;
    int     is_int;     /* value is the integer exact (planner_values.exact) */
    int64_t exact;
} named_value;

struct pa_walker {
    mpb_store       *s;
    const prop_list *props, *progress;
    sqlite3_stmt    *runs, *stages, *metrics, *values, *samples;
    double          *row;
    int64_t         *ints;      /* the row's integers, where is_int */
    unsigned char   *is_int;
    stage_info      *st;
    int              num_st, st_cap;
    metric_info     *m;
    int              num_m, m_cap;
    named_value     *v;
    int              num_v, v_cap;
    double          *smp;
    int              num_smp, smp_cap;
};

static void walker_clear_run(pa_walker *w)
{
    for (int i = 0; i < w->num_st; i++)
        free(w->st[i].name);
    for (int i = 0; i < w->num_m; i++) {
        free(w->m[i].stage);
        free(w->m[i].name);
    }
    for (int i = 0; i < w->num_v; i++)
        free(w->v[i].name);
    w->num_st = w->num_m = w->num_v = w->num_smp = 0;
}

void mpb__pa_walker_close(pa_walker *w)
{
    if (w == NULL)
        return;
    walker_clear_run(w);
    sqlite3_finalize(w->runs);
    sqlite3_finalize(w->stages);
    sqlite3_finalize(w->metrics);
    sqlite3_finalize(w->values);
    sqlite3_finalize(w->samples);
    free(w->row);
    free(w->ints);
    free(w->is_int);
    free(w->st);
    free(w->m);
    free(w->v);
    free(w->smp);
    free(w);
}

int mpb__pa_walker_open(pa_walker **out, mpb_store *s, int64_t experiment_id,
                        int64_t query_id, const prop_list *props,
                        const prop_list *progress)
{
    pa_walker *w = calloc(1, sizeof *w);
    *out = NULL;
    if (w == NULL)
        return mpb__store_fail(s, MPB_ENOMEM, "out of memory");
    *w = (pa_walker){.s = s, .props = props, .progress = progress};
#define RUNS_SQL(verify)                                                    \
        "SELECT r.id, r.planner_config_id, r.query_id, r.status, r.success,"\
        " r.claimed_success, r.time_total, r.time_raw, r.time_other,"      \
        " r.wall_time, r.final_stage, " verify                              \
        " FROM runs r JOIN queries q ON q.id = r.query_id"                 \
        " WHERE r.experiment_id = ?1 AND r.state = 'done'"                 \
        " AND (?2 = 0 OR r.query_id = ?2)"                                 \
        " ORDER BY q.scene_id, r.query_id, r.planner_config_id, r.repetition"
    /* Without runs.memory, or runs.verify_time too (a database made
     * before them, opened read-only), NULL. */
    static const char *const runs_sql[4] = {
        RUNS_SQL("r.verify_time, r.memory"), RUNS_SQL("r.verify_time, NULL"),
        RUNS_SQL("NULL, r.memory"), RUNS_SQL("NULL, NULL"),
    };
    w->runs = mpb__store_prepare(s, runs_sql[
        2 * !mpb__store_has_column(s, "runs", "verify_time") +
        !mpb__store_has_column(s, "runs", "memory")]);
#undef RUNS_SQL
    w->stages = mpb__store_prepare(s,
        "SELECT name, time, num_waypoints, valid FROM stages WHERE run_id = ?"
        " ORDER BY idx");
    w->metrics = mpb__store_prepare(s,
        "SELECT stage, name, value FROM metrics WHERE run_id = ?");
    /* Without planner_values.exact (a database made before it, opened
     * read-only), the REAL only. */
    w->values = mpb__store_prepare(s,
        mpb__store_has_column(s, "planner_values", "exact")
            ? "SELECT name, value, exact FROM planner_values WHERE run_id = ?"
            : "SELECT name, value, NULL FROM planner_values WHERE run_id = ?");
    w->samples = mpb__store_prepare(s,
        "SELECT seq, time, name, value FROM progress WHERE run_id = ?"
        " ORDER BY seq");
    if (!w->runs || !w->stages || !w->metrics || !w->values || !w->samples) {
        mpb__pa_walker_close(w);
        return MPB_EDB;
    }
    if ((w->row = malloc(sizeof *w->row * (size_t)(props->n + 1))) == NULL ||
        (w->ints = malloc(sizeof *w->ints * (size_t)(props->n + 1))) == NULL ||
        (w->is_int = malloc((size_t)props->n + 1)) == NULL) {
        mpb__pa_walker_close(w);
        return mpb__store_fail(s, MPB_ENOMEM, "out of memory");
    }
    sqlite3_bind_int64(w->runs, 1, experiment_id);
    sqlite3_bind_int64(w->runs, 2, query_id);
    *out = w;
    return MPB_OK;
}

double mpb__pa_col_num(sqlite3_stmt *st, int i)
{
    if (sqlite3_column_type(st, i) == SQLITE_NULL)
        return NAN;
    double v = sqlite3_column_double(st, i);
    return isfinite(v) ? v : NAN;
}

char *mpb__pa_col_dup(sqlite3_stmt *st, int i)
{
    const char *t = (const char *)sqlite3_column_text(st, i);
    return strdup(t ? t : "");
}

/* Read the stages, metrics, planner values and progress of run_id. */
static int read_run_parts(pa_walker *w, int64_t run_id)
{
    int step;
    sqlite3_stmt *st;

    st = w->stages;
    sqlite3_reset(st);
    sqlite3_bind_int64(st, 1, run_id);
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        if (mpb__grow((void **)&w->st, &w->st_cap, w->num_st + 1, sizeof *w->st))
            return MPB_ENOMEM;
        stage_info *si = &w->st[w->num_st];
        if ((si->name = mpb__pa_col_dup(st, 0)) == NULL)
            return MPB_ENOMEM;
        si->time = mpb__pa_col_num(st, 1);
        si->num_waypoints = sqlite3_column_int(st, 2);
        si->valid = sqlite3_column_int(st, 3) != 0;
        w->num_st++;
    }
    if (step != SQLITE_DONE)
        return mpb__store_db_fail(w->s, "read stages");

    st = w->metrics;
    sqlite3_reset(st);
    sqlite3_bind_int64(st, 1, run_id);
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        if (mpb__grow((void **)&w->m, &w->m_cap, w->num_m + 1, sizeof *w->m))
            return MPB_ENOMEM;
        metric_info *mi = &w->m[w->num_m];
        mi->stage = mpb__pa_col_dup(st, 0);
        mi->name = mpb__pa_col_dup(st, 1);
        w->num_m++;
        if (mi->stage == NULL || mi->name == NULL)
            return MPB_ENOMEM;
        mi->value = mpb__pa_col_num(st, 2);
    }
    if (step != SQLITE_DONE)
        return mpb__store_db_fail(w->s, "read metrics");

    st = w->values;
    sqlite3_reset(st);
    sqlite3_bind_int64(st, 1, run_id);
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        if (mpb__grow((void **)&w->v, &w->v_cap, w->num_v + 1, sizeof *w->v))
            return MPB_ENOMEM;
        named_value *nv = &w->v[w->num_v];
        if ((nv->name = mpb__pa_col_dup(st, 0)) == NULL)
            return MPB_ENOMEM;
        nv->value = mpb__pa_col_num(st, 1);
        nv->is_int = sqlite3_column_type(st, 2) == SQLITE_INTEGER;
        nv->exact = sqlite3_column_int64(st, 2);
        w->num_v++;
    }
    if (step != SQLITE_DONE)
        return mpb__store_db_fail(w->s, "read planner values");

    /* Progress: the store keeps one row per (sample, name), in the order
     * received; consecutive rows at one time are one sample: a row here,
     * a column per name. */
    int np = w->progress->n;
    double last_time = NAN;
    st = w->samples;
    sqlite3_reset(st);
    sqlite3_bind_int64(st, 1, run_id);
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        double t = mpb__pa_col_num(st, 1);
        if (w->num_smp == 0 || !(t == last_time)) {
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
            row[0] = t;
            w->num_smp++;
            last_time = t;
        }
        const char *name = (const char *)sqlite3_column_text(st, 2);
        double *row = w->smp + (size_t)(w->num_smp - 1) * (size_t)np;
        for (int k = 1; name && k < np; k++)
            if (strcmp(w->progress->v[k].source, name) == 0)
                row[k] = mpb__pa_col_num(st, 3);
    }
    if (step != SQLITE_DONE)
        return mpb__store_db_fail(w->s, "read progress");
    return MPB_OK;
}

static double metric_of(const pa_walker *w, const stage_info *si,
                        const char *name)
{
    for (int i = 0; si && i < w->num_m; i++)
        if (strcmp(w->m[i].stage, si->name) == 0 &&
            strcmp(w->m[i].name, name) == 0)
            return w->m[i].value;
    return NAN;
}

int mpb__pa_walker_next(pa_walker *w, run_view *out)
{
    int step = sqlite3_step(w->runs), rc;
    if (step == SQLITE_DONE)
        return 0;
    if (step != SQLITE_ROW)
        return mpb__store_db_fail(w->s, "read runs");
    walker_clear_run(w);
    sqlite3_stmt *r = w->runs;
    int64_t run_id = sqlite3_column_int64(r, 0);
    if ((rc = read_run_parts(w, run_id)) != MPB_OK) {
        if (rc == MPB_ENOMEM)
            mpb__store_fail(w->s, rc, "out of memory");
        return rc;
    }
    const char *status = (const char *)sqlite3_column_text(r, 3);
    const char *final_name = (const char *)sqlite3_column_text(r, 10);
    const stage_info *first = w->num_st > 0 ? &w->st[0] : NULL;
    const stage_info *final = w->num_st > 0 ? &w->st[w->num_st - 1] : NULL;
    for (int i = 0; final_name && i < w->num_st; i++)
        if (strcmp(w->st[i].name, final_name) == 0)
            final = &w->st[i];

    for (int k = 0; k < w->props->n; k++) {
        const prop *p = &w->props->v[k];
        const stage_info *si = p->role == ROLE_FIRST ? first
                             : p->role == ROLE_FINAL ? final
                             : p->role == ROLE_SIMPLIFIED && final != first
                                 ? final : NULL;
        if (p->role == ROLE_MID)
            for (int i = 0; i < w->num_st; i++)
                if (&w->st[i] != first && &w->st[i] != final &&
                    strcmp(w->st[i].name, p->stage) == 0)
                    si = &w->st[i];
        double v = NAN;
        w->is_int[k] = 0;
        switch (p->kind) {
        case K_TIME:       v = mpb__pa_col_num(r, 6); break;
        case K_TIME_RAW:   v = mpb__pa_col_num(r, 7); break;
        case K_TIME_OTHER: v = mpb__pa_col_num(r, 8); break;
        case K_WALL:       v = mpb__pa_col_num(r, 9); break;
        case K_VERIFY:     v = mpb__pa_col_num(r, 11); break;
        case K_MEMORY:     v = mpb__pa_col_num(r, 12); break;
        case K_SOLVED:     v = mpb__pa_col_num(r, 4); break;
        case K_CLAIMED:    v = mpb__pa_col_num(r, 5); break;
        case K_APPROX:
            v = status ? strcmp(status, "approximate") == 0 : NAN;
            break;
        case K_STATUS:
            v = status_value(status);
            /* An imported run keeps the log's own number as its value
             * "status": OMPL's 0, 8 and 9 are all mpbench's "failed". */
            for (int i = 0; status && i < w->num_v; i++)
                if (strcmp(w->v[i].name, "status") == 0 &&
                    mpb_ompl_status_name(w->v[i].value) != NULL &&
                    strcmp(mpb_ompl_status_name(w->v[i].value), status) == 0)
                    v = w->v[i].value;
            break;
        case K_STAGE_TIME: v = si ? si->time : NAN; break;
        case K_STAGE_METRIC: v = metric_of(w, si, p->source); break;
        case K_STAGE_SEGMENTS:
            /* An imported run's stages have no waypoints, only the log's
             * count as the metric "waypoints" (mpb import). */
            v = si && si->num_waypoints > 0
                    ? si->num_waypoints - 1
                    : metric_of(w, si, mpb_metric_info_of(
                                           MPB_METRIC_WAYPOINTS)->name) - 1;
            break;
        case K_STAGE_VALID: v = si ? si->valid : NAN; break;
        case K_VALUE:
            for (int i = 0; i < w->num_v; i++)
                if (strcmp(w->v[i].name, p->source) == 0) {
                    v = w->v[i].value;
                    w->is_int[k] = (unsigned char)w->v[i].is_int;
                    w->ints[k] = w->v[i].exact;
                }
            break;
        }
        if ((p->kind == K_SOLVED || p->kind == K_CLAIMED) && !isnan(v))
            v = v != 0.0;   /* booleans as 0/1, whatever was stored */
        w->row[k] = v;
    }
    *out = (run_view){
        .run_id = run_id,
        .config_id = sqlite3_column_int64(r, 1),
        .query_id = sqlite3_column_int64(r, 2),
        .values = w->row,
        .ints = w->ints,
        .is_int = w->is_int,
        .samples = w->smp,
        .num_samples = w->num_smp,
    };
    return 1;
}

