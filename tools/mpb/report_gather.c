/*
 * report_gather.c - `mpb report`'s reading of an experiment: its
 * configurations (grouped by approach), scenes, problem sets and queries,
 * then one walk over its finished runs into a cell per (configuration,
 * query), and the sorted times of each problem set's successful runs.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/grow.h"
#include "report.h"

static char *dup_or(report *r, const char *s, const char *fallback)
{
    char *d = strdup(s ? s : fallback);
    if (d == NULL)
        r->nomem = 1;
    return d;
}

int report_on_experiment(void *ud, const mpb_experiment_row *e)
{
    report *r = ud;
    r->experiment_id = e->id;
    r->runs_per_query = e->runs_per_query;
    r->time_limit = e->time_limit;
    r->created = e->created;
    r->finished = e->finished;
    if ((r->experiment_name = dup_or(r, e->name, "?")) == NULL ||
        (r->host = dup_or(r, e->host, "")) == NULL ||
        (r->version = dup_or(r, e->version, "")) == NULL)
        return 1;
    return 0;
}

static int on_config(void *ud, const mpb_planner_config_row *c)
{
    report *r = ud;
    if (mpb__grow((void **)&r->configs, &r->configs_cap, r->num_configs + 1,
                  sizeof *r->configs) != MPB_OK)
        return r->nomem = 1;
    config_ref *cf = &r->configs[r->num_configs];
    *cf = (config_ref){.id = c->id};
    r->num_configs++;
    if ((cf->name = dup_or(r, c->name, "?")) == NULL ||
        (cf->planner = dup_or(r, c->planner, "")) == NULL ||
        (cf->algorithm = dup_or(r, c->algorithm, "")) == NULL ||
        (cf->params = dup_or(r, c->params, "")) == NULL ||
        (c->approach != NULL && mpb_approach_index(c->approach) >= 0 &&
         (cf->approach = dup_or(r, c->approach, "")) == NULL))
        return 1;
    return 0;
}

int report_approach_group(const config_ref *c)
{
    int i = mpb_approach_index(c->approach);
    return i >= 0 ? i : MPB_NUM_APPROACHES;
}

const char *report_approach_label(const config_ref *c)
{
    return c->approach != NULL ? c->approach : "-";
}

int report_any_approach(const report *r)
{
    for (int c = 0; c < r->num_configs; c++)
        if (r->configs[c].approach != NULL)
            return 1;
    return 0;
}

/* Columns by approach (the paper compares kinds of planner), then id. */
static int cmp_config(const void *a, const void *b)
{
    const config_ref *x = a, *y = b;
    int gx = report_approach_group(x), gy = report_approach_group(y);
    if (gx != gy)
        return gx < gy ? -1 : 1;
    return (x->id > y->id) - (x->id < y->id);
}

static int on_scene(void *ud, const mpb_scene_row *sc)
{
    report *r = ud;
    if (mpb__grow((void **)&r->scenes, &r->scenes_cap, r->num_scenes + 1,
                  sizeof *r->scenes) != MPB_OK)
        return r->nomem = 1;
    scene_ref *s = &r->scenes[r->num_scenes];
    *s = (scene_ref){.id = sc->id};
    r->num_scenes++;
    if ((s->name = dup_or(r, sc->name, "?")) == NULL)
        return 1;
    s->set = tool_set_index(&r->sets, &r->num_sets, sc);
    if (s->set < 0)
        return r->nomem = 1;
    r->any_seen |= sc->seen != NULL;
    return 0;
}

static int on_query(void *ud, const mpb_query_row *q)
{
    report *r = ud;
    if (mpb__grow((void **)&r->queries, &r->queries_cap, r->num_queries + 1,
                  sizeof *r->queries) != MPB_OK)
        return r->nomem = 1;
    r->queries[r->num_queries++] = (query_ref){q->id, r->scene_index};
    return 0;
}

static int on_unfinished(void *ud, int64_t scene_id, int unfinished)
{
    report *r = ud;
    for (int i = 0; i < r->num_scenes; i++)
        if (r->scenes[i].id == scene_id)
            r->scenes[i].unfinished = unfinished;
    return 0;
}

static int cmp_query(const void *a, const void *b)
{
    int64_t x = ((const query_ref *)a)->id, y = ((const query_ref *)b)->id;
    return (x > y) - (x < y);
}

/* The configurations are few and grouped by approach, not id: a walk,
 * from the one found last (a run's neighbours are often its own). */
static int find_config(const report *r, int64_t id)
{
    static int last;
    for (int k = 0; k < r->num_configs; k++) {
        int i = (last + k) % r->num_configs;
        if (r->configs[i].id == id)
            return last = i;
    }
    return -1;
}

static int find_query(const report *r, int64_t id)
{
    query_ref key = {id, 0};
    const query_ref *q = bsearch(&key, r->queries, (size_t)r->num_queries,
                                 sizeof key, cmp_query);
    return q ? (int)(q - r->queries) : -1;
}

static void add_sample(mpb_grouped *g, double x)
{
    if (!isnan(x))
        mpb_grouped_add(g, x);
}

static int push_sample(report_samples *x, double v)
{
    if (x->n == x->cap) {
        long cap = x->cap ? 2 * x->cap : 16;
        double *nv = realloc(x->v, (size_t)cap * sizeof *nv);
        if (nv == NULL)
            return 1;
        x->v = nv;
        x->cap = cap;
    }
    x->v[x->n++] = v;
    return 0;
}

static int on_result(void *ud, const mpb_result_row *row)
{
    report *r = ud;
    int ci = find_config(r, row->planner_config_id);
    int qi = find_query(r, row->query_id);
    if (ci < 0 || qi < 0)
        return 0;   /* cannot happen: the database's keys forbid it */
    column *c = &r->cells[(size_t)ci * (size_t)r->num_queries + (size_t)qi];
    c->finished++;
    /* A world is built before the run, whatever becomes of it. */
    add_sample(&c->m[M_WS], row->world_setup_time);
    /* So is the daemon's verification of whatever came back. */
    add_sample(&c->m[M_VT], row->verify_time);
    /* And the planner's peak memory, a run's cost whatever its end: a
     * run stopped by memory_limit too (as Planner Arena plots it). */
    add_sample(&c->m[M_MEM], row->memory);
    /* The planner's own claim (SOLVED), verified or not. */
    if (row->status && strcmp(row->status, "solved") == 0)
        c->claimed++;
    if (row->outcome >= 0 && row->outcome < MPB_OUTCOME_COUNT)
        c->outcomes[row->outcome]++;
    if (r->want_pairs &&
        pairs_add(&r->pairs, ci, qi, row->success, row->time_total,
                  row->metrics[MPB_METRIC_PATH_LENGTH]) != MPB_OK)
        return r->nomem = 1;
    if (!row->success)
        return 0;
    c->succeeded++;
    add_sample(&c->m[M_TT], row->time_total);
    if (r->times != NULL && !isnan(row->time_total)) {
        int set = r->scenes[r->queries[qi].scene].set;
        if (push_sample(&r->times[(size_t)set * (size_t)r->num_configs +
                                  (size_t)ci], row->time_total) ||
            push_sample(&r->times[(size_t)r->num_sets * (size_t)r->num_configs
                                  + (size_t)ci], row->time_total))
            return r->nomem = 1;
    }
    add_sample(&c->m[M_TR], row->time_raw);
    add_sample(&c->m[M_TO], row->time_other);
    /* A stage that failed verification inside a successful run (a raw
     * path through an obstacle, shortcut afterwards) is no path to
     * measure: counted, not averaged. */
    if (row->stage_valid == 0) {
        c->stage_invalid++;
        return 0;
    }
    for (int k = 0; k < MPB_NUM_METRICS; k++)
        add_sample(&c->m[FIRST_STORED + k], row->metrics[k]);
    if (row->num_named > 0)
        r->staged++;
    return 0;
}

/* Everything the tables need, in a handful of statements: the experiment's
 * configurations, scenes and queries, then one walk over its runs. */
int report_gather(report *r, mpb_store *s)
{
    int rc;
    if ((rc = mpb_store_planner_configs(s, r->experiment_id, on_config, r)) ||
        (rc = mpb_store_scenes(s, r->experiment_id, on_scene, r)))
        return rc;
    if (r->num_configs > 1)
        qsort(r->configs, (size_t)r->num_configs, sizeof *r->configs,
              cmp_config);
    /* By set where sets gather scenes (MotionBenchMaker's), else by
     * scene (the paper's), as the tables have always been. */
    if (r->by_default)
        r->by = r->num_scenes > r->num_sets ? BY_SET : BY_SCENE;
    for (int i = 0; i < r->num_scenes; i++) {
        r->scene_index = i;
        if ((rc = mpb_store_queries(s, r->scenes[i].id, on_query, r)))
            return rc;
    }
    if (r->num_queries > 1)
        qsort(r->queries, (size_t)r->num_queries, sizeof *r->queries,
              cmp_query);
    if ((rc = mpb_store_unfinished_by_scene(s, r->experiment_id,
                                            on_unfinished, r)) ||
        (rc = mpb_store_verification_counts(s, r->experiment_id, &r->certified,
                                            &r->sampled)))
        return rc;

    size_t n = (size_t)r->num_configs * (size_t)r->num_queries;
    if (n > 0 && (r->cells = calloc(n, sizeof *r->cells)) == NULL)
        return r->nomem = 1;
    if ((r->by != BY_SCENE || r->want_pairs) && n > 0 &&
        (r->times = calloc((size_t)(r->num_sets + 1) *
                           (size_t)r->num_configs, sizeof *r->times)) == NULL)
        return r->nomem = 1;
    if (r->want_pairs) {
        if (pairs_init(&r->pairs, r->num_configs, r->num_queries,
                       r->time_limit) != MPB_OK)
            return r->nomem = 1;
        for (int q = 0; q < r->num_queries; q++)
            r->pairs.query_set[q] = r->scenes[r->queries[q].scene].set;
    }
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < M_COUNT; k++)
            mpb_grouped_init(&r->cells[i].m[k]);
    if (n == 0)
        return 0;
    const char *stored_names[MPB_NUM_METRICS];
    for (int k = 0; k < MPB_NUM_METRICS; k++)
        stored_names[k] = mpb_metric_info_of(k)->name;
    rc = mpb_store_results(s, r->experiment_id, 0, r->stage, stored_names,
                           MPB_NUM_METRICS, on_result, r);
    if (rc)
        return rc;
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < M_COUNT; k++)
            mpb_grouped_end_group(&r->cells[i].m[k]);
    for (size_t i = 0; r->times && i < (size_t)(r->num_sets + 1) *
                                        (size_t)r->num_configs; i++)
        if (r->times[i].n > 1 &&
            mpb_sort_doubles(r->times[i].v, (size_t)r->times[i].n) != MPB_OK)
            return MPB_ENOMEM;
    return 0;
}

void report_free(report *r)
{
    for (int i = 0; i < r->num_configs; i++) {
        free(r->configs[i].name);
        free(r->configs[i].planner);
        free(r->configs[i].algorithm);
        free(r->configs[i].params);
        free(r->configs[i].approach);
    }
    for (int i = 0; i < r->num_scenes; i++)
        free(r->scenes[i].name);
    free(r->configs);
    free(r->scenes);
    free(r->queries);
    free(r->cells);
    for (int i = 0; i < r->num_sets; i++)
        free(r->sets[i]);
    free(r->sets);
    for (size_t i = 0; r->times && i < (size_t)(r->num_sets + 1) *
                                        (size_t)r->num_configs; i++)
        free(r->times[i].v);
    free(r->times);
    pairs_free(&r->pairs);
    free(r->experiment_name);
    free(r->host);
    free(r->version);
}
