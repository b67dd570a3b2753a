/*
 * report.c - `mpb report`: an experiment's results as the paper's Tables
 * II-V. Per scene, one column per planner configuration: the mean and the
 * standard deviation of each metric over successful runs, and the success
 * rate. As in the paper, a scene's standard deviation is computed per query
 * and averaged over the scene's queries.
 *
 * One pass over the experiment's finished runs fills a cell per
 * (configuration, query); a scene's column folds its queries' cells. This
 * file gathers and prints the text tables; report_formats.c writes the
 * same numbers as Markdown, CSV, LaTeX and JSON (docs/reports.md).
 */
#include <errno.h>
#include <getopt.h>
#include <libgen.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "report.h"
#include "view.h"

#define CMD "report"

const metric_info report_metrics[M_COUNT] = {
    [M_TT] = {"time_total", "s"},
    [M_TR] = {"time_raw", "s"},
    [M_TO] = {"time_other", "s"},
    [M_WS] = {"world_setup_time", "s"},
    [M_VT] = {"verify_time", "s"},
    [M_MEM] = {"memory", "MB"},
#define METRIC_KEY(id, name, unit, ...) \
    [FIRST_STORED + MPB_METRIC_##id] = {name, unit},
    MPB_METRIC_MAP(METRIC_KEY)
#undef METRIC_KEY
};

int report_metric_shown(int k)
{
    return k < FIRST_STORED ||
           (mpb_metric_info_of(k - FIRST_STORED)->flags & MPB_METRIC_F_TABLE);
}

/* The run's times, rows of their own; the metrics' rows follow. */
static const table_row time_rows[] = {
    {"tau_t (Mean, s)",       "$\\tau_t$ (Mean, s)",            M_TT,    SHOW_MEAN,  0, -1, 0},
    {"tau_t (sigma, s)",      "$\\tau_t$ ($\\sigma$, s)",       M_TT,    SHOW_SIGMA, 0, -1, 0},
    {"tau_r (Mean, s)",       "$\\tau_r$ (Mean, s)",            M_TR,    SHOW_MEAN,  0, -1, 0},
    {"tau_r (sigma, s)",      "$\\tau_r$ ($\\sigma$, s)",       M_TR,    SHOW_SIGMA, 0, -1, 0},
    {"tau_o (Mean, s)",       "$\\tau_o$ (Mean, s)",            M_TO,    SHOW_MEAN,  0, -1, 0},
    {"tau_o (sigma, s)",      "$\\tau_o$ ($\\sigma$, s)",       M_TO,    SHOW_SIGMA, 0, -1, 0},
    {"world setup (Mean, s)", "world setup (Mean, s)",         M_WS,    SHOW_MEAN,  1, -1, 0},
    {"verify (Mean, s)",      "verify (Mean, s)",              M_VT,    SHOW_MEAN,  1, -1, 0},
    {"memory (Mean, MB)",     "memory (Mean, MB)",             M_MEM,   SHOW_MEAN,  1, -1, 0},
};
#define NUM_TIME_ROWS ((int)(sizeof time_rows / sizeof time_rows[0]))

table_row report_rows[REPORT_MAX_ROWS];
int report_num_rows;

/* The labels of the metrics' rows, made once from the list. */
static char row_text[REPORT_MAX_ROWS][2][80];

/* A unit in LaTeX: "rad^2" as "rad$^2$". */
static void latex_unit(char *out, size_t size, const char *unit)
{
    const char *hat = strchr(unit, '^');
    if (hat == NULL)
        snprintf(out, size, "%s", unit);
    else
        snprintf(out, size, "%.*s$^%s$", (int)(hat - unit), unit, hat + 1);
}

static void add_metric_row(int id, show what)
{
    const mpb_metric_info *mi = mpb_metric_info_of(id);
    int i = report_num_rows++;
    const char *kind = what == SHOW_MEAN ? "Mean" : "sigma";
    const char *lkind = what == SHOW_MEAN ? "Mean" : "$\\sigma$";
    char unit[40];
    latex_unit(unit, sizeof unit, mi->unit);
    snprintf(row_text[i][0], sizeof row_text[i][0], "%s (%s%s%s)", mi->symbol,
             kind, mi->unit[0] ? ", " : "", mi->unit);
    snprintf(row_text[i][1], sizeof row_text[i][1], "%s (%s%s%s)", mi->latex,
             lkind, unit[0] ? ", " : "", unit);
    report_rows[i] = (table_row){
        row_text[i][0], row_text[i][1], FIRST_STORED + id, what,
        (mi->flags & MPB_METRIC_F_OPTIONAL) != 0,
        (mi->flags & MPB_METRIC_F_COUNT) ? 1 : -1, 0};
}

void report_rows_init(void)
{
    if (report_num_rows > 0)
        return;
    for (int i = 0; i < NUM_TIME_ROWS; i++) {
        report_rows[report_num_rows++] = time_rows[i];
        /* A problem set's: the median and the tail beside the mean. */
        if (time_rows[i].metric == M_TT && time_rows[i].what == SHOW_SIGMA) {
            report_rows[report_num_rows++] = (table_row){
                "tau_t (median, s)", "$\\tau_t$ (median, s)", M_TT,
                SHOW_MEDIAN, 1, -1, 1};
            report_rows[report_num_rows++] = (table_row){
                "tau_t median 95% CI", "$\\tau_t$ median 95\\% CI", M_TT,
                SHOW_MEDIAN_CI, 1, -1, 1};
            report_rows[report_num_rows++] = (table_row){
                "tau_t (p95, s)", "$\\tau_t$ (p95, s)", M_TT, SHOW_P95, 1,
                -1, 1};
        }
    }
    for (int id = 0; id < MPB_NUM_METRICS; id++) {
        unsigned flags = mpb_metric_info_of(id)->flags;
        if (flags & MPB_METRIC_F_TABLE)
            add_metric_row(id, SHOW_MEAN);
        if ((flags & MPB_METRIC_F_TABLE) && (flags & MPB_METRIC_F_SIGMA))
            add_metric_row(id, SHOW_SIGMA);
    }
    /* The planner's own claim of success beside mpbench's verdict. */
    report_rows[report_num_rows++] = (table_row){
        "claimed s_r (%)", "claimed $s_r$ (\\%)", 0, SHOW_CLAIMED, 0, 1, 0};
    report_rows[report_num_rows++] = (table_row){
        "s_r (%)", "$s_r$ (\\%)", 0, SHOW_RATE, 0, 1, 0};
    report_rows[report_num_rows++] = (table_row){
        "s_r 95% CI (%)", "$s_r$ 95\\% CI (\\%)", 0, SHOW_RATE_CI, 1, 1, 1};
    /* Claims in both directions, as counts of runs (outcome.h). */
    report_rows[report_num_rows++] = (table_row){
        "claimed", "claimed", COUNT_CLAIMED, SHOW_COUNT, 0, 0, 0};
    report_rows[report_num_rows++] = (table_row){
        "verified", "verified", MPB_OUTCOME_VERIFIED, SHOW_COUNT, 0, 0, 0};
    report_rows[report_num_rows++] = (table_row){
        "refused claims", "refused claims", MPB_OUTCOME_REFUSED, SHOW_COUNT,
        0, 0, 0};
    report_rows[report_num_rows++] = (table_row){
        "unclaimed valid", "unclaimed valid", MPB_OUTCOME_UNCLAIMED_VALID,
        SHOW_COUNT, 0, 0, 0};
}

typedef enum {
    FORMAT_TEXT, FORMAT_MARKDOWN, FORMAT_CSV, FORMAT_LATEX, FORMAT_JSON
} format;

static const struct {
    const char *name;
    int (*write)(const report *r, FILE *out);
} formats[] = {
    [FORMAT_TEXT] = {"text", report_write_text},
    [FORMAT_MARKDOWN] = {"markdown", report_write_markdown},
    [FORMAT_CSV] = {"csv", report_write_csv},
    [FORMAT_LATEX] = {"latex", report_write_latex},
    [FORMAT_JSON] = {"json", report_write_json},
    {"html", report_write_html},    /* report_html.c */
};
#define NUM_FORMATS ((int)(sizeof formats / sizeof formats[0]))

static void usage(FILE *out)
{
    fprintf(out,
        "usage: mpb report [--experiment ID] [--stage NAME] [--format FORMAT]\n"
        "                  [--by set|scene|all] [--findings] [-o FILE] DB\n"
        "\n"
        "Print the results of an experiment in the database DB as the tables\n"
        "of Cohen, Sucan and Chitta, \"A Generic Infrastructure for\n"
        "Benchmarking Motion Planners\": one table per scene, one column per\n"
        "planner configuration, grouped by approach (sampling, search,\n"
        "optimisation, hybrid, then those that declare none), each column's\n"
        "approach above its name. Rows:\n"
        "  tau_t, tau_r, tau_o  total, planning and other time (s)\n"
        "  world setup          the planner's loading of the robot and scene,\n"
        "                       outside tau_t, over the runs that loaded one\n"
        "                       (s), when reported\n"
        "  verify               the daemon's verification and metrics of a\n"
        "                       run's stages, outside every planner time,\n"
        "                       over the finished runs (s), when recorded\n"
        "  memory               the planner process's peak resident memory\n"
        "                       during the planning, over the finished runs\n"
        "                       (MB), when reported\n"
        "  d_n                  clearance (m), when measured\n"
        "  l_p                  joint-space path length (rad)\n"
        "  l_e                  end-effector path length (m), when measured\n"
        "  kappa'               smoothness: mean squared turning angle\n"
        "  kappa'_r             the same of the path cut into 100 equal\n"
        "                       pieces, whatever its waypoints, when measured\n"
        "  waypoints            number of waypoints\n"
        "  claimed s_r          runs the planner said it solved / finished\n"
        "                       runs (%%): its own claim, beside s_r\n"
        "  s_r                  successful runs / finished runs (%%)\n"
        "  claimed              runs the planner said it solved\n"
        "  verified             claimed, valid and in time: the successes\n"
        "  refused claims       claimed, and the final stage not valid\n"
        "  unclaimed valid      not claimed (failed, approximate, timeout\n"
        "                       by the planner's word), yet the final stage\n"
        "                       valid by mpbench's verification\n"
        "                       (docs/metrics.md, \"Claims\")\n"
        "Means are over successful runs; sigma is the standard deviation of\n"
        "each query's successful runs, averaged over the scene's queries;\n"
        "a sigma marked * counts a query with one successful run as 0.\n"
        "'-' marks a value there is nothing to compute from (a sigma from\n"
        "fewer than two successful runs, too).\n"
        "\n"
        "Options:\n"
        "  -e, --experiment ID  report on experiment ID (default: the newest)\n"
        "  -s, --stage NAME     path metrics of stage NAME (raw, shortcut,\n"
        "                       smoothed, ...) instead of each run's final\n"
        "                       stage; only where that stage passed\n"
        "                       verification (the others are counted below\n"
        "                       the table)\n"
        "  -f, --format FORMAT  text (the default), markdown, csv (one row per\n"
        "                       scene, planner and metric), latex (a table per\n"
        "                       scene), json, or html: one self-contained page\n"
        "                       with the tables, the findings, the plots of\n"
        "                       mpb plot as SVG (when gnuplot is there) and\n"
        "                       the runs that are no success, each linked to\n"
        "                       its mpb view page (see -o); docs/reports.md\n"
        "                       describes each format\n"
        "  -b, --by BY          set: a table per problem set (the experiment\n"
        "                       file's set:, else a scene's name before its\n"
        "                       last '/') and one over all\n"
        "                       problems, adding s_r's 95%% Wilson interval and\n"
        "                       tau_t's median, its 95%% interval and p95;\n"
        "                       all: that one only; scene: a table per scene.\n"
        "                       Default: set where scenes outnumber sets, else\n"
        "                       scene. Text and html only\n"
        "  -F, --findings       after the tables, what they say: per scene the\n"
        "                       fastest planner (of those with the best success\n"
        "                       rate), the shortest and the steadiest paths,\n"
        "                       each with its success rate, the hardest scene,\n"
        "                       and whether the\n"
        "                       paper's findings hold (ARA* paths, RRTConnect's\n"
        "                       speed, the narrow passage) (--by scene); per\n"
        "                       set and approach the fastest and best only\n"
        "                       where a paired signed-rank test, Holm-adjusted,\n"
        "                       says so at 5%%; with the text\n"
        "                       format only (another --format is refused)\n"
        "  -o, --output FILE    write the report to FILE (replaced if it\n"
        "                       exists) instead of stdout; with html, also\n"
        "                       each linked run's 3-D view into views/ beside\n"
        "                       FILE (views/run-ID.html), as mpb view draws it\n"
        "  -h, --help           print this help\n"
        "\n"
        "The database is opened read-only; a running mpbenchd may go on\n"
        "writing. Exit status: 0 on success, 1 on an error, 2 on a bad\n"
        "command line.\n");
}

/* ---- gathering ----------------------------------------------------------- */

static int grow(report *r, void **v, int *cap, int n, size_t size)
{
    if (n < *cap)
        return 0;
    int ncap = *cap ? 2 * *cap : 16;
    void *nv = realloc(*v, size * (size_t)ncap);
    if (nv == NULL)
        return r->nomem = 1;
    *v = nv;
    *cap = ncap;
    return 0;
}

static char *dup_or(report *r, const char *s, const char *fallback)
{
    char *d = strdup(s ? s : fallback);
    if (d == NULL)
        r->nomem = 1;
    return d;
}

static int on_experiment(void *ud, const mpb_experiment_row *e)
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
    if (grow(r, (void **)&r->configs, &r->configs_cap, r->num_configs,
             sizeof *r->configs))
        return 1;
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
    if (grow(r, (void **)&r->scenes, &r->scenes_cap, r->num_scenes,
             sizeof *r->scenes))
        return 1;
    scene_ref *s = &r->scenes[r->num_scenes];
    *s = (scene_ref){.id = sc->id};
    r->num_scenes++;
    if ((s->name = dup_or(r, sc->name, "?")) == NULL)
        return 1;
    s->set = tool_set_index(&r->sets, &r->num_sets, sc);
    if (s->set < 0)
        return r->nomem = 1;
    return 0;
}

static int on_query(void *ud, const mpb_query_row *q)
{
    report *r = ud;
    if (grow(r, (void **)&r->queries, &r->queries_cap, r->num_queries,
             sizeof *r->queries))
        return 1;
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

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
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
static int gather(report *r, mpb_store *s)
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
        if (r->times[i].n > 1)
            qsort(r->times[i].v, (size_t)r->times[i].n, sizeof *r->times[i].v,
                  by_value);
    return 0;
}

static void report_free(report *r)
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

/* ---- what every format shows ---------------------------------------------- */

long report_scene_columns(const report *r, int si, column *cols)
{
    long finished = 0;
    for (int c = 0; c < r->num_configs; c++) {
        cols[c].finished = cols[c].succeeded = cols[c].stage_invalid = 0;
        cols[c].claimed = 0;
        cols[c].in_set = 0;
        cols[c].times = NULL;
        cols[c].ntimes = 0;
        memset(cols[c].outcomes, 0, sizeof cols[c].outcomes);
        for (int k = 0; k < M_COUNT; k++)
            mpb_grouped_init(&cols[c].m[k]);
        for (int q = 0; q < r->num_queries; q++) {
            if (r->queries[q].scene != si)
                continue;
            const column *cl = &r->cells[(size_t)c * (size_t)r->num_queries +
                                         (size_t)q];
            cols[c].finished += cl->finished;
            cols[c].succeeded += cl->succeeded;
            cols[c].claimed += cl->claimed;
            for (int o = 0; o < MPB_OUTCOME_COUNT; o++)
                cols[c].outcomes[o] += cl->outcomes[o];
            cols[c].stage_invalid += cl->stage_invalid;
            for (int k = 0; k < M_COUNT; k++)
                mpb_grouped_merge(&cols[c].m[k], &cl->m[k]);
        }
        finished += cols[c].finished;
    }
    return finished;
}

long report_set_columns(const report *r, int set, column *cols,
                        int *unfinished)
{
    long finished = 0;
    int waiting = 0;
    for (int c = 0; c < r->num_configs; c++) {
        cols[c] = (column){.in_set = 1};
        for (int k = 0; k < M_COUNT; k++)
            mpb_grouped_init(&cols[c].m[k]);
        if (r->times != NULL) {
            const report_samples *x =
                &r->times[(size_t)(set < 0 ? r->num_sets : set) *
                          (size_t)r->num_configs + (size_t)c];
            cols[c].times = x->v;
            cols[c].ntimes = x->n;
        }
    }
    for (int q = 0; q < r->num_queries; q++) {
        if (set >= 0 && r->scenes[r->queries[q].scene].set != set)
            continue;
        for (int c = 0; c < r->num_configs; c++) {
            const column *cl = &r->cells[(size_t)c * (size_t)r->num_queries +
                                         (size_t)q];
            cols[c].finished += cl->finished;
            cols[c].succeeded += cl->succeeded;
            cols[c].claimed += cl->claimed;
            for (int o = 0; o < MPB_OUTCOME_COUNT; o++)
                cols[c].outcomes[o] += cl->outcomes[o];
            cols[c].stage_invalid += cl->stage_invalid;
            for (int k = 0; k < M_COUNT; k++)
                mpb_grouped_merge(&cols[c].m[k], &cl->m[k]);
            finished += cl->finished;
        }
    }
    for (int i = 0; i < r->num_scenes; i++)
        if (set < 0 || r->scenes[i].set == set)
            waiting += r->scenes[i].unfinished;
    if (unfinished != NULL)
        *unfinished = waiting;
    return finished;
}

const char *report_set_name(const report *r, int set)
{
    return set < 0 ? "all problems" : r->sets[set];
}

int report_set_scenes(const report *r, int set)
{
    int n = 0;
    for (int i = 0; i < r->num_scenes; i++)
        n += set < 0 || r->scenes[i].set == set;
    return n;
}

double report_sigma(const mpb_grouped *g)
{
    return g->n < 2 ? NAN : mpb_grouped_stddev(g);
}

int report_sigma_single(const mpb_grouped *g)
{
    int groups = g->groups + (g->g_n > 0);
    return groups - mpb_grouped_measured(g);
}

double report_row_value(const table_row *tr, const column *c)
{
    switch (tr->what) {
    case SHOW_MEAN:
        return mpb_grouped_mean(&c->m[tr->metric]);
    case SHOW_SIGMA:
        return report_sigma(&c->m[tr->metric]);
    case SHOW_RATE:
        return c->finished > 0 ? 100.0 * (double)c->succeeded /
                                     (double)c->finished
                               : NAN;
    case SHOW_CLAIMED:
        return c->finished > 0 ? 100.0 * (double)c->claimed /
                                     (double)c->finished
                               : NAN;
    case SHOW_COUNT:
        if (c->finished == 0)
            return NAN;
        return tr->metric == COUNT_CLAIMED ? (double)c->claimed
             : (double)c->outcomes[tr->metric];
    case SHOW_MEDIAN:
        return c->ntimes > 0 ? mpb_quantile(c->times, (int)c->ntimes, 0.5)
                             : NAN;
    case SHOW_P95:
        return c->ntimes > 0 ? mpb_quantile(c->times, (int)c->ntimes, 0.95)
                             : NAN;
    case SHOW_RATE_CI:
    case SHOW_MEDIAN_CI: {
        double lo, hi;
        report_row_interval(tr, c, &lo, &hi);
        return lo;
    }
    }
    return NAN;
}

int report_row_interval(const table_row *tr, const column *c, double *lo,
                        double *hi)
{
    double coverage = 0;
    *lo = *hi = NAN;
    if (tr->what == SHOW_RATE_CI && c->finished > 0 &&
        mpb_wilson_interval((int)c->succeeded, (int)c->finished, lo, hi) ==
            MPB_OK) {
        *lo *= 100.0;
        *hi *= 100.0;
    } else if (tr->what == SHOW_MEDIAN_CI && c->ntimes > 0 &&
               (mpb_median_interval(c->times, (int)c->ntimes, lo, hi,
                                    &coverage) != MPB_OK ||
                coverage < 0.95)) {
        *lo = *hi = NAN;    /* too few runs for a 95 % interval */
    }
    return !isnan(*lo);
}

/* A mean or sigma smaller than this in magnitude is the rounding of
 * floating-point arithmetic (a straight path's kappa' of 2e-30 in a
 * database written before it was 0), not a measurement: it prints as 0. */
#define NOISE 1e-12

static double denoise(double v)
{
    return fabs(v) < NOISE ? 0.0 : v;
}

/*
 * Decimals for a row of the general format: 3, as the paper's 2 would
 * hide today's millisecond plans, or more, up to 6, so that the row's
 * smallest nonzero value keeps 3 significant digits. One count per row
 * keeps a row's numbers aligned on the point.
 */
static int row_decimals(const column *cols, int n, const table_row *tr)
{
    int decimals = 3;
    for (int i = 0; i < n; i++) {
        double v = denoise(report_row_value(tr, &cols[i]));
        if (isnan(v) || v == 0.0 || isinf(v))
            continue;
        int d = 2 - (int)floor(log10(fabs(v)));
        if (d > decimals)
            decimals = d;
    }
    return decimals < 6 ? decimals : 6;
}

static void format_value(char *buf, int decimals, double v)
{
    if (isnan(v))
        snprintf(buf, CELL_TEXT, "-");
    else if (v != 0.0 && fabs(v) < 1e-4 && decimals == 6)
        snprintf(buf, CELL_TEXT, "%.2e", v);    /* 3 digits, not 0.00000x */
    else
        snprintf(buf, CELL_TEXT, "%.*f", decimals, v);
}

void report_cells(const report *r, const column *cols, char (*text)[CELL_TEXT],
                  int *visible)
{
    int nc = r->num_configs;
    for (int i = 0; i < report_num_rows; i++) {
        const table_row *tr = &report_rows[i];
        int decimals = tr->decimals >= 0 ? tr->decimals
                                         : row_decimals(cols, nc, tr);
        int any = 0;
        for (int c = 0; c < nc; c++) {
            double v = report_row_value(tr, &cols[c]), lo, hi;
            if (tr->sets_only) {
                any |= cols[c].in_set;
                if (report_row_interval(tr, &cols[c], &lo, &hi)) {
                    char a[CELL_TEXT], b[CELL_TEXT];
                    format_value(a, decimals, denoise(lo));
                    format_value(b, decimals, denoise(hi));
                    snprintf(text[i * nc + c], CELL_TEXT, "%.14s-%.14s", a, b);
                } else {
                    format_value(text[i * nc + c], decimals, denoise(v));
                }
                continue;
            }
            format_value(text[i * nc + c], decimals, denoise(v));
            if (tr->what == SHOW_SIGMA && !isnan(v) &&
                report_sigma_single(&cols[c].m[tr->metric]) > 0)
                strcat(text[i * nc + c], SIGMA_SINGLE_MARK);
            /* Measured: a value, or runs of a metric row (a count row's
             * metric is an outcome, or COUNT_CLAIMED, no index of m). */
            any |= !isnan(v) ||
                   ((tr->what == SHOW_MEAN || tr->what == SHOW_SIGMA) &&
                    cols[c].m[tr->metric].n > 0);
        }
        visible[i] = tr->sets_only ? any : !tr->optional || any;
    }
}

int report_any_single(char (*text)[CELL_TEXT], const int *visible, int nc)
{
    for (int i = 0; i < report_num_rows; i++)
        if (visible[i] && report_rows[i].what == SHOW_SIGMA)
            for (int c = 0; c < nc; c++)
                if (strstr(text[i * nc + c], SIGMA_SINGLE_MARK) != NULL)
                    return 1;
    return 0;
}

/* ---- text ------------------------------------------------------------------ */

/* s right-aligned in width columns. */
static void print_right(FILE *out, const char *s, int width)
{
    for (int pad = width - tool_text_cols(s, NULL); pad > 0; pad--)
        fputc(' ', out);
    fputs(s, out);
}

/* A table: kind "Scene" with index a scene's, "Problem set" a set's,
 * index -1 for all problems. */
static int print_table(const report *r, const char *kind, int index,
                       FILE *out)
{
    int nc = r->num_configs;
    size_t ncols = (size_t)(nc > 0 ? nc : 1);
    column *cols = calloc(ncols, sizeof *cols);
    char (*text)[CELL_TEXT] = calloc((size_t)report_num_rows * ncols,
                                     sizeof *text);
    int *width = calloc(ncols, sizeof *width);
    int *visible = calloc((size_t)report_num_rows, sizeof *visible);
    int rc = MPB_OK;

    if (cols == NULL || text == NULL || width == NULL || visible == NULL) {
        rc = MPB_ENOMEM;
        goto done;
    }
    int scene = strcmp(kind, "Scene") == 0, unfinished;
    long finished = scene ? report_scene_columns(r, index, cols)
                          : report_set_columns(r, index, cols, &unfinished);
    if (scene)
        unfinished = r->scenes[index].unfinished;
    report_cells(r, cols, text, visible);

    int label_width = (int)strlen("Metric");
    for (int i = 0; i < report_num_rows; i++) {
        int len = (int)strlen(report_rows[i].label);
        if (len > label_width)
            label_width = len;
    }
    int approaches = report_any_approach(r);
    for (int c = 0; c < nc; c++) {
        width[c] = tool_text_cols(r->configs[c].name, NULL);
        if (width[c] < 8)
            width[c] = 8;
        if (approaches &&
            (int)strlen(report_approach_label(&r->configs[c])) > width[c])
            width[c] = (int)strlen(report_approach_label(&r->configs[c]));
        for (int i = 0; i < report_num_rows; i++)
            if (tool_text_cols(text[i * nc + c], NULL) > width[c])
                width[c] = tool_text_cols(text[i * nc + c], NULL);
    }

    if (scene) {
        fprintf(out, "Scene %s", r->scenes[index].name);
    } else {
        int n = report_set_scenes(r, index);
        if (index < 0)
            fputs("All problems", out);
        else
            fprintf(out, "%s %s", kind, r->sets[index]);
        fprintf(out, " (%d scene%s)", n, n == 1 ? "" : "s");
    }
    fprintf(out, " - experiment %s (%lld), %ld run%s\n", r->experiment_name,
            (long long)r->experiment_id, finished, finished == 1 ? "" : "s");
    int rule = label_width;
    /* Each column's approach above its name, the columns grouped by it. */
    if (approaches) {
        fprintf(out, "%-*s", label_width, "Approach");
        for (int c = 0; c < nc; c++) {
            fputs("  ", out);
            print_right(out, report_approach_label(&r->configs[c]), width[c]);
        }
        fputc('\n', out);
    }
    fprintf(out, "%-*s", label_width, "Metric");
    for (int c = 0; c < nc; c++) {
        fputs("  ", out);
        print_right(out, r->configs[c].name, width[c]);
        rule += 2 + width[c];
    }
    fputc('\n', out);
    for (int i = 0; i < rule; i++)
        fputc('-', out);
    fputc('\n', out);
    for (int i = 0; i < report_num_rows; i++) {
        if (!visible[i])
            continue;
        fprintf(out, "%-*s", label_width, report_rows[i].label);
        for (int c = 0; c < nc; c++) {
            fputs("  ", out);
            print_right(out, text[i * nc + c], width[c]);
        }
        fputc('\n', out);
    }
    for (int c = 0; c < nc; c++)
        if (cols[c].stage_invalid > 0)
            fprintf(out, "%s: %ld successful run%s whose stage '%s' failed "
                    "verification, its path metrics not counted above\n",
                    r->configs[c].name, cols[c].stage_invalid,
                    cols[c].stage_invalid == 1 ? "" : "s",
                    r->stage ? r->stage : "?");
    if (report_any_single(text, visible, nc))
        fputs(SIGMA_SINGLE_NOTE "\n", out);
    if (unfinished > 0)
        fprintf(out, "%d more run%s not finished yet, not counted above\n",
                unfinished, unfinished == 1 ? "" : "s");
done:
    free(cols);
    free(text);
    free(width);
    free(visible);
    return rc;
}

int report_write_text(const report *r, FILE *out)
{
    int rc;
    if (r->num_configs == 0 || r->num_scenes == 0) {
        fprintf(out, "Experiment %s (%lld) has no %s.\n", r->experiment_name,
                (long long)r->experiment_id,
                r->num_configs == 0 ? "planner configurations" : "scenes");
        return MPB_OK;
    }
    fprintf(out, "Means over successful runs; sigma: standard deviation per "
            "query, averaged\nover the scene's queries. Path metrics of "
            "%s%s%s.\n", r->stage ? "stage '" : "each run's final stage",
            r->stage ? r->stage : "", r->stage ? "'" : "");
    if (r->stage != NULL && r->staged == 0)
        fprintf(out, "No successful run has metrics for a stage '%s'.\n",
                r->stage);
    if (r->certified + r->sampled > 0)
        fprintf(out, "Collision checks: %ld stage%s certified, %ld sampled "
                "(docs/verification.md).\n", r->certified,
                r->certified == 1 ? "" : "s", r->sampled);
    if (r->by == BY_SCENE) {
        for (int i = 0; i < r->num_scenes; i++) {
            fputc('\n', out);
            if ((rc = print_table(r, "Scene", i, out)) != MPB_OK)
                return rc;
        }
        return MPB_OK;
    }
    fputs("Problem sets: s_r's 95% CI is Wilson's; tau_t's median and p95 "
          "are over\nsuccessful runs, the median's 95% CI from order "
          "statistics ('-' with fewer\nthan 6 successful runs).\n", out);
    for (int i = r->by == BY_SET ? 0 : r->num_sets; i <= r->num_sets; i++) {
        if (i == r->num_sets && r->by == BY_SET && r->num_sets < 2)
            break;      /* all problems are the one set */
        fputc('\n', out);
        if ((rc = print_table(r, "Problem set", i < r->num_sets ? i : -1,
                              out)) != MPB_OK)
            return rc;
    }
    return MPB_OK;
}

/* ---- the command --------------------------------------------------------- */

int cmd_report(int argc, char **argv)
{
    static const struct option longopts[] = {
        {"experiment", required_argument, NULL, 'e'},
        {"stage", required_argument, NULL, 's'},
        {"format", required_argument, NULL, 'f'},
        {"findings", no_argument, NULL, 'F'},
        {"by", required_argument, NULL, 'b'},
        {"output", required_argument, NULL, 'o'},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    report r = {0};
    const char *experiment = NULL, *path, *output = NULL, *by = NULL;
    char *three = NULL, *views = NULL, *tmp = NULL;
    FILE *out = stdout;
    int64_t experiment_id = 0;
    int opt, rc, status = MPB_EXIT_ERROR, fmt = FORMAT_TEXT, findings = 0;
    mpb_store *s = NULL;

    report_rows_init();
    optind = 1;
    opterr = 0;
    while ((opt = getopt_long(argc, argv, ":e:s:f:Fb:o:h", longopts, NULL)) != -1) {
        switch (opt) {
        case 'e':
            experiment = optarg;
            break;
        case 's':
            r.stage = optarg;
            break;
        case 'f':
            for (fmt = 0; fmt < NUM_FORMATS; fmt++)
                if (strcmp(optarg, formats[fmt].name) == 0)
                    break;
            if (fmt == NUM_FORMATS) {
                fprintf(stderr, "mpb " CMD ": unknown format '%s' (", optarg);
                for (int k = 0; k < NUM_FORMATS; k++)
                    fprintf(stderr, "%s%s", k == 0 ? "" : k + 1 < NUM_FORMATS
                            ? ", " : " or ", formats[k].name);
                fprintf(stderr, ")\n");
                return MPB_EXIT_USAGE;
            }
            break;
        case 'F':
            findings = 1;
            break;
        case 'b':
            by = optarg;
            if (strcmp(by, "scene") == 0)
                r.by = BY_SCENE;
            else if (strcmp(by, "set") == 0)
                r.by = BY_SET;
            else if (strcmp(by, "all") == 0)
                r.by = BY_ALL;
            else {
                fprintf(stderr, "mpb " CMD ": --by wants set, scene or all, "
                        "not '%s'\n", by);
                return MPB_EXIT_USAGE;
            }
            break;
        case 'o':
            output = optarg;
            break;
        case 'h':
            usage(stdout);
            return MPB_EXIT_OK;
        default:    /* ':' a missing value, '?' an unknown option */
            return tool_option_error(CMD, opt, argv);
        }
    }
    if (findings && fmt != FORMAT_TEXT) {
        fprintf(stderr, "mpb " CMD ": --findings is plain text, not for "
                "--format %s (try 'mpb " CMD " --help')\n", formats[fmt].name);
        return MPB_EXIT_USAGE;
    }
    /* The machine-readable layouts stay per scene (docs/reports.md). */
    int grouped = fmt == FORMAT_TEXT || strcmp(formats[fmt].name, "html") == 0;
    if (by != NULL && r.by != BY_SCENE && !grouped) {
        fprintf(stderr, "mpb " CMD ": --format %s is per scene; --by %s is "
                "for text and html\n", formats[fmt].name, by);
        return MPB_EXIT_USAGE;
    }
    r.by_default = by == NULL && grouped;
    r.want_pairs = findings || strcmp(formats[fmt].name, "html") == 0;
    if (argc - optind != 1) {
        fprintf(stderr, "mpb " CMD ": %s (try 'mpb " CMD " --help')\n",
                argc - optind < 1 ? "which database?"
                                  : "one database at a time");
        return MPB_EXIT_USAGE;
    }
    path = argv[optind];
    r.db_path = path;
    if (experiment != NULL && tool_parse_id(experiment, &experiment_id) != 0) {
        fprintf(stderr, "mpb " CMD ": --experiment wants an experiment id "
                "(a number), not '%s'\n", experiment);
        return MPB_EXIT_USAGE;
    }

    if ((s = tool_open_readonly(CMD, path)) == NULL)
        return MPB_EXIT_ERROR;
    if (experiment_id == 0) {
        rc = mpb_store_experiment_latest(s, &experiment_id);
        if (rc == MPB_ENOTFOUND) {
            fprintf(stderr, "mpb " CMD ": %s holds no experiment yet\n", path);
            goto done;
        }
        if (rc != MPB_OK)
            goto fail;
    }
    rc = mpb_store_experiment_get(s, experiment_id, on_experiment, &r);
    if (rc == MPB_ENOTFOUND) {
        fprintf(stderr, "mpb " CMD ": %s has no experiment %lld\n", path,
                (long long)experiment_id);
        goto done;
    }
    if (rc != MPB_OK && !r.nomem)
        goto fail;
    if (!r.nomem && (rc = gather(&r, s)) != MPB_OK && !r.nomem)
        goto fail;
    if (r.nomem) {
        fprintf(stderr, "mpb " CMD ": out of memory\n");
        goto done;
    }

    if (output) {
        /* Into output.tmp, renamed when whole; an HTML page's failed runs'
         * views into views/ beside it. */
        size_t len = strlen(output) + 8;
        char *copy = strdup(output);
        if ((tmp = malloc(len)) == NULL || copy == NULL ||
            (views = malloc(len + strlen("/views"))) == NULL) {
            free(copy);
            fprintf(stderr, "mpb " CMD ": out of memory\n");
            goto done;
        }
        snprintf(views, len + strlen("/views"), "%s/views", dirname(copy));
        free(copy);
        snprintf(tmp, len, "%s.tmp", output);
        if (strcmp(formats[fmt].name, "html") == 0) {
            char where[4096];
            if ((three = view_load_three(where, sizeof where)) == NULL) {
                fprintf(stderr, "mpb " CMD ": cannot read three.js at %s for "
                        "the failed runs' views: %s (run tools/web_env.sh, or "
                        "set MPB_THREE_JS)\n", where, strerror(errno));
                goto done;
            }
            r.views_dir = views;
            r.three_js = three;
        }
        if ((out = fopen(tmp, "w")) == NULL) {
            fprintf(stderr, "mpb " CMD ": cannot write %s: %s\n", output,
                    strerror(errno));
            out = stdout;
            goto done;
        }
    }
    if ((rc = formats[fmt].write(&r, out)) != MPB_OK ||
        (findings && (rc = report_write_findings(&r, out)) != MPB_OK) ||
        ((fmt == FORMAT_TEXT || fmt == FORMAT_MARKDOWN) &&
         (rc = report_write_depth(s, &r, fmt == FORMAT_MARKDOWN, out)) != MPB_OK)) {
        if (rc == REPORT_SAID)
            goto done;
        goto fail;
    }
    if (fflush(out) != 0 || ferror(out)) {
        fprintf(stderr, "mpb " CMD ": cannot write %s: %s\n",
                output ? output : "the report", strerror(errno));
        goto done;
    }
    if (output) {
        int bad = fclose(out) != 0;
        out = stdout;
        if (bad || rename(tmp, output) != 0) {
            fprintf(stderr, "mpb " CMD ": cannot write %s: %s\n", output,
                    strerror(errno));
            goto done;
        }
    }
    status = MPB_EXIT_OK;
    goto done;
fail:
    fprintf(stderr, "mpb " CMD ": %s: %s\n", path,
            rc == MPB_ENOMEM ? "out of memory" : mpb_store_errmsg(s));
done:
    if (out != stdout)
        fclose(out);
    if (tmp && status != MPB_EXIT_OK)
        remove(tmp);
    free(tmp);
    free(views);
    free(three);
    mpb_store_close(s);
    report_free(&r);
    return status;
}
