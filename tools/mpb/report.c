/*
 * report.c - `mpb report`: an experiment's results as the paper's Tables
 * II-V. Per scene, one column per planner configuration: the mean and the
 * standard deviation of each metric over successful runs, and the success
 * rate. As in the paper, a scene's standard deviation is computed per query
 * and averaged over the scene's queries.
 *
 * One pass over the experiment's finished runs fills a cell per
 * (configuration, query); a scene's column folds its queries' cells.
 */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpb.h"

#define CMD "report"

/* What is averaged: the run's times, then the stage metrics it reads. */
enum { M_TT, M_TR, M_TO, M_DN, M_LP, M_LE, M_KAPPA, M_WP, M_COUNT };
#define FIRST_STORED M_DN
static const char *const stored_names[M_COUNT - FIRST_STORED] = {
    "clearance", "path_length", "ee_path_length", "smoothness", "waypoints",
};

typedef enum { SHOW_MEAN, SHOW_SIGMA, SHOW_RATE } show;

typedef struct table_row {
    const char *label;
    int         metric;     /* M_..., unused for SHOW_RATE */
    show        what;
    int         optional;   /* printed only if some column has a value */
    int         decimals;   /* fixed decimals, or -1: the general format */
} table_row;

/* The paper's rows, in its order, and the number of waypoints. */
static const table_row table_rows[] = {
    {"tau_t (Mean, s)",       M_TT,    SHOW_MEAN,  0, -1},
    {"tau_t (sigma, s)",      M_TT,    SHOW_SIGMA, 0, -1},
    {"tau_r (Mean, s)",       M_TR,    SHOW_MEAN,  0, -1},
    {"tau_r (sigma, s)",      M_TR,    SHOW_SIGMA, 0, -1},
    {"tau_o (Mean, s)",       M_TO,    SHOW_MEAN,  0, -1},
    {"tau_o (sigma, s)",      M_TO,    SHOW_SIGMA, 0, -1},
    {"d_n (Mean, m)",         M_DN,    SHOW_MEAN,  1, -1},
    {"d_n (sigma, m)",        M_DN,    SHOW_SIGMA, 1, -1},
    {"l_p (Mean, rad)",       M_LP,    SHOW_MEAN,  0, -1},
    {"l_p (sigma, rad)",      M_LP,    SHOW_SIGMA, 0, -1},
    {"l_e (Mean, m)",         M_LE,    SHOW_MEAN,  1, -1},
    {"l_e (sigma, m)",        M_LE,    SHOW_SIGMA, 1, -1},
    {"kappa' (Mean, rad^2)",  M_KAPPA, SHOW_MEAN,  0, -1},
    {"kappa' (sigma, rad^2)", M_KAPPA, SHOW_SIGMA, 0, -1},
    {"waypoints (Mean)",      M_WP,    SHOW_MEAN,  0, 1},
    {"s_r (%)",               0,       SHOW_RATE,  0, 1},
};
#define NUM_TABLE_ROWS ((int)(sizeof table_rows / sizeof table_rows[0]))

/* One planner configuration on one query. */
typedef struct cell {
    long        finished, succeeded;
    mpb_grouped m[M_COUNT];     /* successful runs; one group (the query) */
} cell;

typedef struct id_name {
    int64_t id;
    char   *name;
    int     unfinished;         /* scenes: runs not done yet */
} id_name;

typedef struct query_ref {
    int64_t id;
    int     scene;              /* index into scenes */
} query_ref;

typedef struct id_list {
    id_name *v;
    int      n, cap;
} id_list;

typedef struct report {
    const char *stage;          /* --stage, or NULL: each run's final one */
    int64_t     experiment_id;
    char       *experiment_name;
    id_list     configs, scenes;    /* in id order */
    query_ref  *queries;            /* sorted by id */
    int         num_queries, queries_cap;
    int         scene_index;        /* scene whose queries are being listed */
    cell       *cells;              /* configs.n x num_queries */
    long        staged;             /* successful runs with stage metrics */
    int         nomem;
} report;

static void usage(FILE *out)
{
    fprintf(out,
        "usage: mpb report [--experiment ID] [--stage NAME] DB\n"
        "\n"
        "Print the results of an experiment in the database DB as the tables\n"
        "of Cohen, Sucan and Chitta, \"A Generic Infrastructure for\n"
        "Benchmarking Motion Planners\": one table per scene, one column per\n"
        "planner configuration. Rows:\n"
        "  tau_t, tau_r, tau_o  total, planning and other time (s)\n"
        "  d_n                  clearance (m), when measured\n"
        "  l_p                  joint-space path length (rad)\n"
        "  l_e                  end-effector path length (m), when measured\n"
        "  kappa'               smoothness: mean squared turning angle\n"
        "  waypoints            number of waypoints\n"
        "  s_r                  successful runs / finished runs (%%)\n"
        "Means are over successful runs; sigma is the standard deviation of\n"
        "each query's successful runs, averaged over the scene's queries.\n"
        "'-' marks a value there is nothing to compute from.\n"
        "\n"
        "Options:\n"
        "  -e, --experiment ID  report on experiment ID (default: the newest)\n"
        "  -s, --stage NAME     path metrics of stage NAME (raw, shortcut,\n"
        "                       smoothed, ...) instead of each run's final\n"
        "                       stage\n"
        "  -h, --help           print this help\n"
        "\n"
        "The database is opened read-only; a running mpbenchd may go on\n"
        "writing. Exit status: 0 on success, 1 on an error, 2 on a bad\n"
        "command line.\n");
}

/* ---- gathering ----------------------------------------------------------- */

static int list_add(report *r, id_list *l, int64_t id, const char *name)
{
    if (l->n == l->cap) {
        int cap = l->cap ? 2 * l->cap : 16;
        id_name *v = realloc(l->v, sizeof *v * (size_t)cap);
        if (v == NULL)
            return r->nomem = 1;
        l->v = v;
        l->cap = cap;
    }
    if ((l->v[l->n].name = strdup(name ? name : "?")) == NULL)
        return r->nomem = 1;
    l->v[l->n].unfinished = 0;
    l->v[l->n++].id = id;
    return 0;
}

static void list_free(id_list *l)
{
    for (int i = 0; i < l->n; i++)
        free(l->v[i].name);
    free(l->v);
}

static int on_experiment(void *ud, const mpb_experiment_row *e)
{
    report *r = ud;
    r->experiment_id = e->id;
    if ((r->experiment_name = strdup(e->name)) == NULL)
        return r->nomem = 1;
    return 0;
}

static int on_config(void *ud, const mpb_planner_config_row *c)
{
    report *r = ud;
    return list_add(r, &r->configs, c->id, c->name);
}

static int on_scene(void *ud, const mpb_scene_row *sc)
{
    report *r = ud;
    return list_add(r, &r->scenes, sc->id, sc->name);
}

static int on_query(void *ud, const mpb_query_row *q)
{
    report *r = ud;
    if (r->num_queries == r->queries_cap) {
        int cap = r->queries_cap ? 2 * r->queries_cap : 64;
        query_ref *v = realloc(r->queries, sizeof *v * (size_t)cap);
        if (v == NULL)
            return r->nomem = 1;
        r->queries = v;
        r->queries_cap = cap;
    }
    r->queries[r->num_queries++] = (query_ref){q->id, r->scene_index};
    return 0;
}

static int on_unfinished(void *ud, int64_t scene_id, int unfinished)
{
    report *r = ud;
    for (int i = 0; i < r->scenes.n; i++)
        if (r->scenes.v[i].id == scene_id)
            r->scenes.v[i].unfinished = unfinished;
    return 0;
}

static int cmp_query(const void *a, const void *b)
{
    int64_t x = ((const query_ref *)a)->id, y = ((const query_ref *)b)->id;
    return (x > y) - (x < y);
}

static int find_config(const report *r, int64_t id)
{
    int lo = 0, hi = r->configs.n - 1;
    while (lo <= hi) {
        int mid = lo + (hi - lo) / 2;
        if (r->configs.v[mid].id == id)
            return mid;
        if (r->configs.v[mid].id < id)
            lo = mid + 1;
        else
            hi = mid - 1;
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

static int on_result(void *ud, const mpb_result_row *row)
{
    report *r = ud;
    int ci = find_config(r, row->planner_config_id);
    int qi = find_query(r, row->query_id);
    if (ci < 0 || qi < 0)
        return 0;   /* cannot happen: the database's keys forbid it */
    cell *c = &r->cells[(size_t)ci * (size_t)r->num_queries + (size_t)qi];
    c->finished++;
    if (!row->success)
        return 0;
    c->succeeded++;
    add_sample(&c->m[M_TT], row->time_total);
    add_sample(&c->m[M_TR], row->time_raw);
    add_sample(&c->m[M_TO], row->time_other);
    for (int k = 0; k < M_COUNT - FIRST_STORED; k++)
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
    for (int i = 0; i < r->scenes.n; i++) {
        r->scene_index = i;
        if ((rc = mpb_store_queries(s, r->scenes.v[i].id, on_query, r)))
            return rc;
    }
    qsort(r->queries, (size_t)r->num_queries, sizeof *r->queries, cmp_query);
    if ((rc = mpb_store_unfinished_by_scene(s, r->experiment_id,
                                            on_unfinished, r)))
        return rc;

    size_t n = (size_t)r->configs.n * (size_t)r->num_queries;
    if (n > 0 && (r->cells = calloc(n, sizeof *r->cells)) == NULL)
        return r->nomem = 1;
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < M_COUNT; k++)
            mpb_grouped_init(&r->cells[i].m[k]);
    if (n == 0)
        return 0;
    rc = mpb_store_results(s, r->experiment_id, 0, r->stage, stored_names,
                           M_COUNT - FIRST_STORED, on_result, r);
    if (rc)
        return rc;
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < M_COUNT; k++)
            mpb_grouped_end_group(&r->cells[i].m[k]);
    return 0;
}

/* ---- printing ------------------------------------------------------------ */

/*
 * Fold one query's statistics (a single ended group) into a scene's. The
 * four fields are mpb_grouped's documented running sums; stats.h offers no
 * merge, and runs arrive interleaved, not query by query.
 */
static void grouped_merge(mpb_grouped *into, const mpb_grouped *g)
{
    into->sum += g->sum;
    into->n += g->n;
    into->sd_sum += g->sd_sum;
    into->groups += g->groups;
}

typedef struct column {
    long        finished, succeeded;
    mpb_grouped m[M_COUNT];
} column;

#define CELL_TEXT 32

/*
 * Decimals for a row of the general format: 3, as the paper's 2 would
 * hide today's millisecond plans, or more, up to 6, so that the row's
 * smallest nonzero value keeps 3 significant digits. One count per row
 * keeps a row's numbers aligned on the point.
 */
static int row_decimals(const double *v, int n)
{
    int decimals = 3;
    for (int i = 0; i < n; i++) {
        if (isnan(v[i]) || v[i] == 0.0 || isinf(v[i]))
            continue;
        int d = 2 - (int)floor(log10(fabs(v[i])));
        if (d > decimals)
            decimals = d;
    }
    return decimals < 6 ? decimals : 6;
}

static void format_value(char *buf, int decimals, double v)
{
    if (isnan(v))
        snprintf(buf, CELL_TEXT, "-");
    else if (v != 0.0 && fabs(v) < 0.5e-6 && decimals == 6)
        snprintf(buf, CELL_TEXT, "%.2e", v);    /* would print as 0.000000 */
    else
        snprintf(buf, CELL_TEXT, "%.*f", decimals, v);
}

static double row_value(const table_row *tr, const column *c)
{
    switch (tr->what) {
    case SHOW_MEAN:
        return mpb_grouped_mean(&c->m[tr->metric]);
    case SHOW_SIGMA:
        return mpb_grouped_stddev(&c->m[tr->metric]);
    case SHOW_RATE:
        return c->finished > 0 ? 100.0 * (double)c->succeeded /
                                     (double)c->finished
                               : NAN;
    }
    return NAN;
}

static int print_scene(const report *r, int si, FILE *out)
{
    int nc = r->configs.n;
    column *cols = calloc((size_t)(nc > 0 ? nc : 1), sizeof *cols);
    char (*text)[CELL_TEXT] =
        calloc((size_t)NUM_TABLE_ROWS * (size_t)(nc > 0 ? nc : 1),
               sizeof *text);
    int *width = calloc((size_t)(nc > 0 ? nc : 1), sizeof *width);
    double *value = calloc((size_t)(nc > 0 ? nc : 1), sizeof *value);
    long finished = 0;
    int rc = MPB_OK;

    if (cols == NULL || text == NULL || width == NULL || value == NULL) {
        rc = MPB_ENOMEM;
        goto done;
    }
    for (int c = 0; c < nc; c++) {
        for (int k = 0; k < M_COUNT; k++)
            mpb_grouped_init(&cols[c].m[k]);
        for (int q = 0; q < r->num_queries; q++) {
            if (r->queries[q].scene != si)
                continue;
            const cell *cl = &r->cells[(size_t)c * (size_t)r->num_queries +
                                       (size_t)q];
            cols[c].finished += cl->finished;
            cols[c].succeeded += cl->succeeded;
            for (int k = 0; k < M_COUNT; k++)
                grouped_merge(&cols[c].m[k], &cl->m[k]);
        }
        finished += cols[c].finished;
    }

    /* Every cell's text first, for the column widths. */
    int label_width = (int)strlen("Metric");
    for (int i = 0; i < NUM_TABLE_ROWS; i++) {
        int len = (int)strlen(table_rows[i].label);
        if (len > label_width)
            label_width = len;
    }
    for (int c = 0; c < nc; c++) {
        width[c] = (int)strlen(r->configs.v[c].name);
        if (width[c] < 8)
            width[c] = 8;
    }
    for (int i = 0; i < NUM_TABLE_ROWS; i++) {
        for (int c = 0; c < nc; c++)
            value[c] = row_value(&table_rows[i], &cols[c]);
        int decimals = table_rows[i].decimals >= 0 ? table_rows[i].decimals
                                                   : row_decimals(value, nc);
        for (int c = 0; c < nc; c++) {
            char *t = text[i * nc + c];
            format_value(t, decimals, value[c]);
            if ((int)strlen(t) > width[c])
                width[c] = (int)strlen(t);
        }
    }

    fprintf(out, "Scene %s - experiment %s (%lld), %ld run%s\n",
            r->scenes.v[si].name, r->experiment_name,
            (long long)r->experiment_id, finished, finished == 1 ? "" : "s");
    int rule = label_width;
    fprintf(out, "%-*s", label_width, "Metric");
    for (int c = 0; c < nc; c++) {
        fprintf(out, "  %*s", width[c], r->configs.v[c].name);
        rule += 2 + width[c];
    }
    fputc('\n', out);
    for (int i = 0; i < rule; i++)
        fputc('-', out);
    fputc('\n', out);
    for (int i = 0; i < NUM_TABLE_ROWS; i++) {
        if (table_rows[i].optional) {
            int any = 0;
            for (int c = 0; c < nc; c++)
                any |= strcmp(text[i * nc + c], "-") != 0;
            if (!any)
                continue;
        }
        fprintf(out, "%-*s", label_width, table_rows[i].label);
        for (int c = 0; c < nc; c++)
            fprintf(out, "  %*s", width[c], text[i * nc + c]);
        fputc('\n', out);
    }
    if (r->scenes.v[si].unfinished > 0)
        fprintf(out, "%d more run%s not finished yet, not counted above\n",
                r->scenes.v[si].unfinished,
                r->scenes.v[si].unfinished == 1 ? "" : "s");
done:
    free(cols);
    free(text);
    free(width);
    free(value);
    return rc;
}

/* ---- the command --------------------------------------------------------- */

int cmd_report(int argc, char **argv)
{
    static const struct option longopts[] = {
        {"experiment", required_argument, NULL, 'e'},
        {"stage", required_argument, NULL, 's'},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    report r = {0};
    const char *experiment = NULL, *path;
    int64_t experiment_id = 0;
    int opt, rc, status = MPB_EXIT_ERROR;
    mpb_store *s = NULL;

    optind = 1;
    opterr = 0;
    while ((opt = getopt_long(argc, argv, ":e:s:h", longopts, NULL)) != -1) {
        switch (opt) {
        case 'e':
            experiment = optarg;
            break;
        case 's':
            r.stage = optarg;
            break;
        case 'h':
            usage(stdout);
            return MPB_EXIT_OK;
        case ':':
            fprintf(stderr, "mpb " CMD ": %s needs a value (try 'mpb " CMD
                    " --help')\n", argv[optind - 1]);
            return MPB_EXIT_USAGE;
        default:
            fprintf(stderr, "mpb " CMD ": unknown option '%s' (try 'mpb " CMD
                    " --help')\n", argv[optind - 1]);
            return MPB_EXIT_USAGE;
        }
    }
    if (argc - optind != 1) {
        fprintf(stderr, "mpb " CMD ": %s (try 'mpb " CMD " --help')\n",
                argc - optind < 1 ? "which database?"
                                  : "one database at a time");
        return MPB_EXIT_USAGE;
    }
    path = argv[optind];
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

    if (r.configs.n == 0 || r.scenes.n == 0) {
        printf("Experiment %s (%lld) has no %s.\n", r.experiment_name,
               (long long)r.experiment_id,
               r.configs.n == 0 ? "planner configurations" : "scenes");
        status = MPB_EXIT_OK;
        goto done;
    }
    printf("Means over successful runs; sigma: standard deviation per query, "
           "averaged\nover the scene's queries. Path metrics of %s%s%s.\n",
           r.stage ? "stage '" : "each run's final stage",
           r.stage ? r.stage : "", r.stage ? "'" : "");
    if (r.stage != NULL && r.staged == 0)
        printf("No successful run has metrics for a stage '%s'.\n", r.stage);
    for (int i = 0; i < r.scenes.n; i++) {
        putchar('\n');
        if ((rc = print_scene(&r, i, stdout)) != MPB_OK)
            goto fail;
    }
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "mpb " CMD ": cannot write the report\n");
        goto done;
    }
    status = MPB_EXIT_OK;
    goto done;
fail:
    fprintf(stderr, "mpb " CMD ": %s: %s\n", path,
            rc == MPB_ENOMEM ? "out of memory" : mpb_store_errmsg(s));
done:
    mpb_store_close(s);
    list_free(&r.configs);
    list_free(&r.scenes);
    free(r.queries);
    free(r.cells);
    free(r.experiment_name);
    return status;
}
