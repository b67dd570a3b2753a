/*
 * store_export.c - an experiment's finished runs as Planner Arena reads
 * them: the SQLite database that OMPL's ompl_benchmark_statistics.py
 * builds, and OMPL's benchmark log format. docs/planner-arena.md is the
 * mapping; shared/reference/planner-arena-format.md the target.
 *
 * One walker turns each run into a row of run properties (time, solved,
 * status, the first and final stage's path metrics as "solution ..." and
 * "simplified solution ...", the stages between as "<stage> solution ...",
 * the planner's own numbers) and its progress samples; the database writer
 * and the log writer both consume it.
 */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "store_internal.h"

/* ---- the run properties ---------------------------------------------------- */

/* What fills a property. */
typedef enum {
    K_TIME, K_TIME_RAW, K_TIME_OTHER, K_WALL, K_SOLVED, K_CLAIMED, K_APPROX,
    K_STATUS, K_STAGE_TIME, K_STAGE_METRIC, K_STAGE_SEGMENTS, K_STAGE_VALID,
    K_VALUE
} prop_kind;

/* Which stage a stage property reads. */
typedef enum { ROLE_FIRST, ROLE_MID, ROLE_FINAL } stage_role;

typedef struct prop {
    char       *name;       /* as in a log: words joined by single spaces */
    const char *type;       /* REAL, INTEGER, BOOLEAN or ENUM */
    prop_kind   kind;
    stage_role  role;
    char       *stage;      /* ROLE_MID: the stage's name */
    char       *source;     /* metric or planner value name */
} prop;

typedef struct prop_list {
    prop *v;
    int   n, cap;
} prop_list;

/*
 * The status enum: OMPL's PlannerStatus values and names (0-9, as OMPL
 * 1.5+ and its Benchmark class write them), and one of mpbench's own.
 */
static const char *const status_enum[] = {
    "Unknown status", "Invalid start", "Invalid goal",
    "Unrecognized goal type", "Timeout", "Approximate solution",
    "Exact solution", "Crash", "Abort", "Infeasible", "Invalid request",
};
#define NUM_STATUS ((int)(sizeof status_enum / sizeof status_enum[0]))

/* mpbench's status name (runs.status) as a value of the status enum. */
static int status_value(const char *status)
{
    static const struct { const char *name; int value; } map[] = {
        {"solved", 6}, {"approximate", 5}, {"timeout", 4}, {"crash", 7},
        {"failed", 8}, {"invalid_request", 10},
    };
    for (size_t i = 0; status && i < sizeof map / sizeof map[0]; i++)
        if (strcmp(status, map[i].name) == 0)
            return map[i].value;
    return 0;
}

/* Experiment parameters added after the twelve columns Planner Arena
 * knows: name (a log's words) and SQL type. */
static const char *const exp_params[][2] = {
    {"query", "VARCHAR(512)"},
    {"mpbench experiment", "INTEGER"},
};
#define NUM_EXP_PARAMS ((int)(sizeof exp_params / sizeof exp_params[0]))

/* Names a run property must not take: the runs table's own columns and
 * what Planner Arena joins onto each run. */
static const char *const reserved[] = {
    "id", "experimentid", "plannerid", "planner", "experiment", "version",
    "query", "mpbench experiment",
};

static void prop_list_free(prop_list *l)
{
    for (int i = 0; i < l->n; i++) {
        free(l->v[i].name);
        free(l->v[i].stage);
        free(l->v[i].source);
    }
    free(l->v);
    *l = (prop_list){0};
}

/*
 * A property name from free text, prefix then text: letters and digits
 * kept, anything else (spaces, '_', punctuation) a single space between
 * words; "value" if nothing is left, "v " before a leading digit. Such a
 * name is a valid SQL column once its spaces are '_', as OMPL's script
 * makes them. Caller frees.
 */
static char *prop_name(const char *prefix, const char *text)
{
    size_t lp = strlen(prefix), lt = strlen(text);
    char *in = malloc(lp + lt + 1), *out = malloc(lp + lt + 8), *o = out;
    if (in == NULL || out == NULL) {
        free(in);
        free(out);
        return NULL;
    }
    memcpy(in, prefix, lp);
    memcpy(in + lp, text, lt + 1);
    int space = 0;
    for (const char *p = in; *p; p++) {
        char ch = *p;
        int word = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                   (ch >= '0' && ch <= '9');
        if (!word) {
            space = 1;
            continue;
        }
        if (o == out && ch >= '0' && ch <= '9') {
            *o++ = 'v';
            *o++ = ' ';
        } else if (space && o > out) {
            *o++ = ' ';
        }
        *o++ = ch;
        space = 0;
    }
    *o = '\0';
    if (o == out)
        strcpy(out, "value");
    free(in);
    return out;
}

/* 1 if a and b name the same SQL column (case-insensitive, ' ' == '_'). */
static int same_column(const char *a, const char *b)
{
    for (;; a++, b++) {
        char x = *a == '_' ? ' ' : *a, y = *b == '_' ? ' ' : *b;
        if (x >= 'A' && x <= 'Z')
            x = (char)(x - 'A' + 'a');
        if (y >= 'A' && y <= 'Z')
            y = (char)(y - 'A' + 'a');
        if (x != y)
            return 0;
        if (x == '\0')
            return 1;
    }
}

static int name_taken(const prop_list *l, const char *name)
{
    for (size_t i = 0; i < sizeof reserved / sizeof reserved[0]; i++)
        if (same_column(reserved[i], name))
            return 1;
    for (int i = 0; i < l->n; i++)
        if (same_column(l->v[i].name, name))
            return 1;
    return 0;
}

/*
 * Add a property; name is taken over (freed on failure). A name already
 * taken gets fallback_prefix ("planner ", "progress "), then " 2", " 3" ...
 */
static int prop_add(prop_list *l, char *name, const char *type, prop_kind kind,
                    stage_role role, const char *stage, const char *source,
                    const char *fallback_prefix)
{
    if (name == NULL)
        return MPB_ENOMEM;
    if (name_taken(l, name) && fallback_prefix != NULL) {
        char *alt = prop_name(fallback_prefix, name);
        free(name);
        if ((name = alt) == NULL)
            return MPB_ENOMEM;
    }
    for (int k = 2; name_taken(l, name); k++) {
        size_t n = strlen(name) + 16;
        char *alt = malloc(n);
        if (alt == NULL) {
            free(name);
            return MPB_ENOMEM;
        }
        snprintf(alt, n, "%s %d", name, k);
        if (!name_taken(l, alt)) {
            free(name);
            name = alt;
            break;
        }
        free(alt);
    }
    if (l->n == l->cap) {
        int cap = l->cap ? 2 * l->cap : 32;
        prop *v = realloc(l->v, sizeof *v * (size_t)cap);
        if (v == NULL) {
            free(name);
            return MPB_ENOMEM;
        }
        l->v = v;
        l->cap = cap;
    }
    prop *p = &l->v[l->n];
    *p = (prop){.name = name, .type = type, .kind = kind, .role = role};
    l->n++;
    if ((stage && (p->stage = strdup(stage)) == NULL) ||
        (source && (p->source = strdup(source)) == NULL))
        return MPB_ENOMEM;
    return MPB_OK;
}

/* ---- what an experiment holds ---------------------------------------------- */

typedef struct name_list {
    char **v;
    int    n, cap;
} name_list;

static void name_list_free(name_list *l)
{
    for (int i = 0; i < l->n; i++)
        free(l->v[i]);
    free(l->v);
    *l = (name_list){0};
}

/* Every value of the first column of sql (bound to experiment_id). */
static int read_names(mpb_store *s, const char *sql, int64_t experiment_id,
                      name_list *out)
{
    sqlite3_stmt *st = mpb__store_prepare(s, sql);
    int step, rc = MPB_OK;
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, experiment_id);
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        const char *name = (const char *)sqlite3_column_text(st, 0);
        if (name == NULL)
            continue;
        if (out->n == out->cap) {
            int cap = out->cap ? 2 * out->cap : 16;
            char **v = realloc(out->v, sizeof *v * (size_t)cap);
            if (v == NULL) {
                rc = MPB_ENOMEM;
                break;
            }
            out->v = v;
            out->cap = cap;
        }
        if ((out->v[out->n] = strdup(name)) == NULL) {
            rc = MPB_ENOMEM;
            break;
        }
        out->n++;
    }
    if (rc == MPB_OK && step != SQLITE_DONE)
        rc = mpb__store_db_fail(s, "export: read names");
    sqlite3_finalize(st);
    if (rc == MPB_ENOMEM)
        mpb__store_fail(s, rc, "export: out of memory");
    return rc;
}

/* The metrics of a stage, in the order the properties list them: path
 * length, smoothness, clearance first, then any other alphabetically. */
static int metric_rank(const char *name)
{
    static const char *const order[] = {"path_length", "smoothness",
                                        "clearance", "ee_path_length"};
    for (int i = 0; i < 4; i++)
        if (strcmp(name, order[i]) == 0)
            return i;
    return 4;
}

static int cmp_metric(const void *a, const void *b)
{
    const char *x = *(const char *const *)a, *y = *(const char *const *)b;
    int rx = metric_rank(x), ry = metric_rank(y);
    return rx != ry ? rx - ry : strcmp(x, y);
}

/* The property word of a stage metric: "length" for path_length, ... */
static const char *metric_word(const char *metric)
{
    if (strcmp(metric, "path_length") == 0)
        return "length";
    if (strcmp(metric, "ee_path_length") == 0)
        return "ee length";
    return metric;
}

/* The properties of one stage role: "<prefix>solution time", ... */
static int add_stage_props(prop_list *l, const char *prefix, stage_role role,
                           const char *stage, const name_list *metrics)
{
    char buf[256];
    int rc;
    snprintf(buf, sizeof buf, "%ssolution time", prefix);
    if ((rc = prop_add(l, prop_name("", buf), "REAL", K_STAGE_TIME, role,
                       stage, NULL, "stage ")))
        return rc;
    for (int i = 0; i < metrics->n; i++) {
        const char *m = metrics->v[i];
        if (strcmp(m, "time") == 0 || strcmp(m, "waypoints") == 0)
            continue;   /* the stage's time and segments say it */
        snprintf(buf, sizeof buf, "%ssolution %s", prefix, metric_word(m));
        if ((rc = prop_add(l, prop_name("", buf), "REAL", K_STAGE_METRIC,
                           role, stage, m, "stage ")))
            return rc;
    }
    snprintf(buf, sizeof buf, "%ssolution segments", prefix);
    if ((rc = prop_add(l, prop_name("", buf), "INTEGER", K_STAGE_SEGMENTS,
                       role, stage, NULL, "stage ")))
        return rc;
    snprintf(buf, sizeof buf, "%scorrect solution", prefix);
    return prop_add(l, prop_name("", buf), "BOOLEAN", K_STAGE_VALID, role,
                    stage, NULL, "stage ");
}

/*
 * The run properties of an experiment, in column order, and the names of
 * its progress properties (after "time"). Property names are unique.
 */
static int experiment_props(mpb_store *s, int64_t experiment_id,
                            prop_list *props, prop_list *progress)
{
    static const struct { const char *name, *type; prop_kind kind; } fixed[] = {
        {"time", "REAL", K_TIME},
        {"time raw", "REAL", K_TIME_RAW},
        {"time other", "REAL", K_TIME_OTHER},
        {"wall time", "REAL", K_WALL},
        {"solved", "BOOLEAN", K_SOLVED},
        {"claimed success", "BOOLEAN", K_CLAIMED},
        {"approximate solution", "BOOLEAN", K_APPROX},
        {"status", "ENUM", K_STATUS},
    };
    name_list metrics = {0}, mids = {0}, values = {0}, samples = {0};
    int rc;

    if ((rc = read_names(s,
            "SELECT DISTINCT m.name FROM runs r JOIN metrics m"
            " ON m.run_id = r.id WHERE r.experiment_id = ?1"
            " AND r.state = 'done'", experiment_id, &metrics)) ||
        (rc = read_names(s,
            "SELECT st.name FROM runs r JOIN stages st ON st.run_id = r.id"
            " WHERE r.experiment_id = ?1 AND r.state = 'done' AND st.idx > 0"
            " AND st.name IS NOT coalesce(r.final_stage, '')"
            " GROUP BY st.name ORDER BY min(st.idx), st.name",
            experiment_id, &mids)) ||
        (rc = read_names(s,
            "SELECT DISTINCT v.name FROM runs r JOIN planner_values v"
            " ON v.run_id = r.id WHERE r.experiment_id = ?1"
            " AND r.state = 'done' ORDER BY v.name", experiment_id,
            &values)) ||
        (rc = read_names(s,
            "SELECT DISTINCT p.name FROM runs r JOIN progress p"
            " ON p.run_id = r.id WHERE r.experiment_id = ?1"
            " AND r.state = 'done' ORDER BY p.name", experiment_id,
            &samples)))
        goto done;
    qsort(metrics.v, (size_t)metrics.n, sizeof *metrics.v, cmp_metric);

    for (size_t i = 0; i < sizeof fixed / sizeof fixed[0]; i++)
        if ((rc = prop_add(props, prop_name("", fixed[i].name), fixed[i].type,
                           fixed[i].kind, ROLE_FIRST, NULL, NULL, NULL)))
            goto done;
    if ((rc = add_stage_props(props, "", ROLE_FIRST, NULL, &metrics)))
        goto done;
    for (int i = 0; i < mids.n; i++) {
        char *prefix = prop_name("", mids.v[i]);
        if (prefix == NULL) {
            rc = MPB_ENOMEM;
            goto done;
        }
        char buf[160];
        snprintf(buf, sizeof buf, "%.150s ", prefix);
        free(prefix);
        if ((rc = add_stage_props(props, buf, ROLE_MID, mids.v[i], &metrics)))
            goto done;
    }
    if ((rc = add_stage_props(props, "simplified ", ROLE_FINAL, NULL,
                              &metrics)))
        goto done;
    for (int i = 0; i < values.n; i++)
        if ((rc = prop_add(props, prop_name("", values.v[i]), "REAL", K_VALUE,
                           ROLE_FIRST, NULL, values.v[i], "planner ")))
            goto done;
    /* Progress: "time" is the x-axis column of the table itself. */
    prop_list taken = {0};
    if ((rc = prop_add(&taken, prop_name("", "time"), "REAL", K_TIME,
                       ROLE_FIRST, NULL, NULL, NULL)) == MPB_OK) {
        *progress = taken;
        for (int i = 0; i < samples.n && rc == MPB_OK; i++)
            rc = prop_add(progress, prop_name("", samples.v[i]), "REAL",
                          K_VALUE, ROLE_FIRST, NULL, samples.v[i],
                          "progress ");
    } else {
        prop_list_free(&taken);
    }
done:
    if (rc == MPB_ENOMEM)
        mpb__store_fail(s, rc, "export: out of memory");
    name_list_free(&metrics);
    name_list_free(&mids);
    name_list_free(&values);
    name_list_free(&samples);
    return rc;
}

/* ---- the walk over the runs ------------------------------------------------ */

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
    char  *name;
    double value;
} named_value;

/* One finished run, as the writers take it. */
typedef struct run_view {
    int64_t       run_id, config_id, query_id;
    const double *values;       /* one per run property; NaN for NULL */
    const double *samples;      /* num_samples rows of one value per
                                   progress property, time first */
    int           num_samples;
} run_view;

typedef struct walker {
    mpb_store       *s;
    const prop_list *props, *progress;
    sqlite3_stmt    *runs, *stages, *metrics, *values, *samples;
    double          *row;
    stage_info      *st;
    int              num_st, st_cap;
    metric_info     *m;
    int              num_m, m_cap;
    named_value     *v;
    int              num_v, v_cap;
    double          *smp;
    int              num_smp, smp_cap;
} walker;

static void walker_clear_run(walker *w)
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

static void walker_close(walker *w)
{
    walker_clear_run(w);
    sqlite3_finalize(w->runs);
    sqlite3_finalize(w->stages);
    sqlite3_finalize(w->metrics);
    sqlite3_finalize(w->values);
    sqlite3_finalize(w->samples);
    free(w->row);
    free(w->st);
    free(w->m);
    free(w->v);
    free(w->smp);
}

/* Make room for one more element of size in *v (n used, *cap allocated). */
static int room(void **v, int n, int *cap, size_t size)
{
    if (n < *cap)
        return MPB_OK;
    int ncap = *cap ? 2 * *cap : 16;
    void *nv = realloc(*v, size * (size_t)ncap);
    if (nv == NULL)
        return MPB_ENOMEM;
    *v = nv;
    *cap = ncap;
    return MPB_OK;
}

/*
 * Walk the finished runs of an experiment (of one query when query_id > 0),
 * by scene, query, planner configuration and repetition.
 */
static int walker_open(walker *w, mpb_store *s, int64_t experiment_id,
                       int64_t query_id, const prop_list *props,
                       const prop_list *progress)
{
    *w = (walker){.s = s, .props = props, .progress = progress};
    w->runs = mpb__store_prepare(s,
        "SELECT r.id, r.planner_config_id, r.query_id, r.status, r.success,"
        " r.claimed_success, r.time_total, r.time_raw, r.time_other,"
        " r.wall_time, r.final_stage"
        " FROM runs r JOIN queries q ON q.id = r.query_id"
        " WHERE r.experiment_id = ?1 AND r.state = 'done'"
        " AND (?2 = 0 OR r.query_id = ?2)"
        " ORDER BY q.scene_id, r.query_id, r.planner_config_id, r.repetition");
    w->stages = mpb__store_prepare(s,
        "SELECT name, time, num_waypoints, valid FROM stages WHERE run_id = ?"
        " ORDER BY idx");
    w->metrics = mpb__store_prepare(s,
        "SELECT stage, name, value FROM metrics WHERE run_id = ?");
    w->values = mpb__store_prepare(s,
        "SELECT name, value FROM planner_values WHERE run_id = ?");
    w->samples = mpb__store_prepare(s,
        "SELECT seq, time, name, value FROM progress WHERE run_id = ?"
        " ORDER BY seq");
    if (!w->runs || !w->stages || !w->metrics || !w->values || !w->samples)
        return MPB_EDB;
    if ((w->row = malloc(sizeof *w->row * (size_t)(props->n + 1))) == NULL)
        return mpb__store_fail(s, MPB_ENOMEM, "export: out of memory");
    sqlite3_bind_int64(w->runs, 1, experiment_id);
    sqlite3_bind_int64(w->runs, 2, query_id);
    return MPB_OK;
}

static double col_num(sqlite3_stmt *st, int i)
{
    if (sqlite3_column_type(st, i) == SQLITE_NULL)
        return NAN;
    double v = sqlite3_column_double(st, i);
    return isfinite(v) ? v : NAN;
}

static char *col_dup(sqlite3_stmt *st, int i)
{
    const char *t = (const char *)sqlite3_column_text(st, i);
    return strdup(t ? t : "");
}

/* Read the stages, metrics, planner values and progress of run_id. */
static int read_run_parts(walker *w, int64_t run_id)
{
    int step;
    sqlite3_stmt *st;

    st = w->stages;
    sqlite3_reset(st);
    sqlite3_bind_int64(st, 1, run_id);
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        if (room((void **)&w->st, w->num_st, &w->st_cap, sizeof *w->st))
            return MPB_ENOMEM;
        stage_info *si = &w->st[w->num_st];
        if ((si->name = col_dup(st, 0)) == NULL)
            return MPB_ENOMEM;
        si->time = col_num(st, 1);
        si->num_waypoints = sqlite3_column_int(st, 2);
        si->valid = sqlite3_column_int(st, 3) != 0;
        w->num_st++;
    }
    if (step != SQLITE_DONE)
        return mpb__store_db_fail(w->s, "export: read stages");

    st = w->metrics;
    sqlite3_reset(st);
    sqlite3_bind_int64(st, 1, run_id);
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        if (room((void **)&w->m, w->num_m, &w->m_cap, sizeof *w->m))
            return MPB_ENOMEM;
        metric_info *mi = &w->m[w->num_m];
        mi->stage = col_dup(st, 0);
        mi->name = col_dup(st, 1);
        w->num_m++;
        if (mi->stage == NULL || mi->name == NULL)
            return MPB_ENOMEM;
        mi->value = col_num(st, 2);
    }
    if (step != SQLITE_DONE)
        return mpb__store_db_fail(w->s, "export: read metrics");

    st = w->values;
    sqlite3_reset(st);
    sqlite3_bind_int64(st, 1, run_id);
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        if (room((void **)&w->v, w->num_v, &w->v_cap, sizeof *w->v))
            return MPB_ENOMEM;
        named_value *nv = &w->v[w->num_v];
        if ((nv->name = col_dup(st, 0)) == NULL)
            return MPB_ENOMEM;
        nv->value = col_num(st, 1);
        w->num_v++;
    }
    if (step != SQLITE_DONE)
        return mpb__store_db_fail(w->s, "export: read planner values");

    /* Progress: the store keeps one row per (sample, name), in the order
     * received; consecutive rows at one time are one sample: a row here,
     * a column per name. */
    int np = w->progress->n;
    double last_time = NAN;
    st = w->samples;
    sqlite3_reset(st);
    sqlite3_bind_int64(st, 1, run_id);
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        double t = col_num(st, 1);
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
                row[k] = col_num(st, 3);
    }
    if (step != SQLITE_DONE)
        return mpb__store_db_fail(w->s, "export: read progress");
    return MPB_OK;
}

static double metric_of(const walker *w, const stage_info *si,
                        const char *name)
{
    for (int i = 0; si && i < w->num_m; i++)
        if (strcmp(w->m[i].stage, si->name) == 0 &&
            strcmp(w->m[i].name, name) == 0)
            return w->m[i].value;
    return NAN;
}

/* The next run into *out: 1, or 0 at the end, or an error. */
static int walker_next(walker *w, run_view *out)
{
    int step = sqlite3_step(w->runs), rc;
    if (step == SQLITE_DONE)
        return 0;
    if (step != SQLITE_ROW)
        return mpb__store_db_fail(w->s, "export: read runs");
    walker_clear_run(w);
    sqlite3_stmt *r = w->runs;
    int64_t run_id = sqlite3_column_int64(r, 0);
    if ((rc = read_run_parts(w, run_id)) != MPB_OK) {
        if (rc == MPB_ENOMEM)
            mpb__store_fail(w->s, rc, "export: out of memory");
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
                             : p->role == ROLE_FINAL ? final : NULL;
        if (p->role == ROLE_MID)
            for (int i = 0; i < w->num_st; i++)
                if (&w->st[i] != first && &w->st[i] != final &&
                    strcmp(w->st[i].name, p->stage) == 0)
                    si = &w->st[i];
        double v = NAN;
        switch (p->kind) {
        case K_TIME:       v = col_num(r, 6); break;
        case K_TIME_RAW:   v = col_num(r, 7); break;
        case K_TIME_OTHER: v = col_num(r, 8); break;
        case K_WALL:       v = col_num(r, 9); break;
        case K_SOLVED:     v = col_num(r, 4); break;
        case K_CLAIMED:    v = col_num(r, 5); break;
        case K_APPROX:
            v = status ? strcmp(status, "approximate") == 0 : NAN;
            break;
        case K_STATUS:     v = status_value(status); break;
        case K_STAGE_TIME: v = si ? si->time : NAN; break;
        case K_STAGE_METRIC: v = metric_of(w, si, p->source); break;
        case K_STAGE_SEGMENTS:
            v = si && si->num_waypoints > 0 ? si->num_waypoints - 1 : NAN;
            break;
        case K_STAGE_VALID: v = si ? si->valid : NAN; break;
        case K_VALUE:
            for (int i = 0; i < w->num_v; i++)
                if (strcmp(w->v[i].name, p->source) == 0)
                    v = w->v[i].value;
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
        .samples = w->smp,
        .num_samples = w->num_smp,
    };
    return 1;
}

/* ---- what both writers say of an experiment ---------------------------------- */

typedef struct exp_info {
    int64_t id;
    char   *name, *config_text, *host, *version;
    int     runs_per_query;
    double  time_limit, created;
} exp_info;

static void exp_info_free(exp_info *e)
{
    free(e->name);
    free(e->config_text);
    free(e->host);
    free(e->version);
    *e = (exp_info){0};
}

static int exp_info_read(mpb_store *s, int64_t id, exp_info *e)
{
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT name, config_text, host, version, runs_per_query, time_limit,"
        " created FROM experiments WHERE id = ?");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, id);
    int step = sqlite3_step(st), rc = MPB_OK;
    if (step == SQLITE_ROW) {
        e->id = id;
        e->name = col_dup(st, 0);
        e->config_text = col_dup(st, 1);
        e->host = col_dup(st, 2);
        e->version = col_dup(st, 3);
        e->runs_per_query = sqlite3_column_int(st, 4);
        e->time_limit = col_num(st, 5);
        e->created = col_num(st, 6);
        if (!e->name || !e->config_text || !e->host || !e->version)
            rc = mpb__store_fail(s, MPB_ENOMEM, "export: out of memory");
    } else if (step == SQLITE_DONE) {
        rc = mpb__store_fail(s, MPB_ENOTFOUND, "no experiment %lld",
                             (long long)id);
    } else {
        rc = mpb__store_db_fail(s, "export: read experiment");
    }
    sqlite3_finalize(st);
    return rc;
}

/* Whitespace to '_': a log's "Experiment NAME" line keeps one word. */
static void one_word(char *s)
{
    for (; *s; s++)
        if (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r')
            *s = '_';
}

/* "mpbench 0.1.0" as the experiment recorded it, never empty (Planner
 * Arena sorts and selects by it). */
static const char *version_of(const exp_info *e)
{
    return e->version[0] ? e->version : "mpbench " MPB_VERSION_STRING;
}

/* A Planner Arena experiment: one query of an mpbench experiment. */
typedef struct pa_query {
    int64_t query_id;
    char   *problem;    /* "<experiment>/<scene>", one word */
    char   *query;      /* the query's name */
    char   *setup;      /* the experiment file and the query */
    long    runs;
    double  total_time; /* sum of the runs' wall times */
} pa_query;

typedef struct pa_query_list {
    pa_query *v;
    int       n, cap;
} pa_query_list;

static void pa_query_list_free(pa_query_list *l)
{
    for (int i = 0; i < l->n; i++) {
        free(l->v[i].problem);
        free(l->v[i].query);
        free(l->v[i].setup);
    }
    free(l->v);
    *l = (pa_query_list){0};
}

/* The queries of experiment e with finished runs, by scene and query. */
static int read_queries(mpb_store *s, const exp_info *e, pa_query_list *out)
{
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT q.id, q.name, sc.name, count(r.id), total(r.wall_time),"
        " q.joint_names, q.start, q.goal_kind, q.goal_joints,"
        " q.goal_tolerance"
        " FROM queries q JOIN scenes sc ON sc.id = q.scene_id"
        " JOIN runs r ON r.query_id = q.id AND r.state = 'done'"
        " WHERE sc.experiment_id = ?1 GROUP BY q.id ORDER BY sc.id, q.id");
    int step, rc = MPB_OK;
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, e->id);
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        if ((rc = room((void **)&out->v, out->n, &out->cap, sizeof *out->v)))
            break;
        pa_query *q = &out->v[out->n++];
        *q = (pa_query){.query_id = sqlite3_column_int64(st, 0),
                        .runs = sqlite3_column_int(st, 3),
                        .total_time = sqlite3_column_double(st, 4)};
        const char *scene = (const char *)sqlite3_column_text(st, 2);
        const char *text[5];
        for (int i = 0; i < 5; i++) {
            text[i] = (const char *)sqlite3_column_text(st, 5 + i);
            if (text[i] == NULL)
                text[i] = "";
        }
        size_t n = strlen(e->name) + strlen(scene ? scene : "") + 2;
        size_t ns = strlen(e->config_text) + 256 + strlen(text[0]) +
                    strlen(text[1]) + strlen(text[3]) + strlen(text[4]) +
                    strlen((const char *)sqlite3_column_text(st, 1));
        q->problem = malloc(n);
        q->query = col_dup(st, 1);
        q->setup = malloc(ns);
        if (!q->problem || !q->query || !q->setup) {
            rc = MPB_ENOMEM;
            break;
        }
        snprintf(q->problem, n, "%s/%s", e->name, scene ? scene : "");
        one_word(q->problem);
        snprintf(q->setup, ns,
                 "%s%s\nmpbench experiment %lld, query %s\n"
                 "joints: %s\nstart: %s\ngoal (%s): %s\ntolerance: %s\n",
                 e->config_text,
                 e->config_text[0] &&
                         e->config_text[strlen(e->config_text) - 1] != '\n'
                     ? "\n" : "",
                 (long long)e->id, q->query, text[0], text[1], text[2],
                 text[3], text[4]);
    }
    if (rc == MPB_OK && step != SQLITE_DONE)
        rc = mpb__store_db_fail(s, "export: read queries");
    if (rc == MPB_ENOMEM)
        mpb__store_fail(s, rc, "export: out of memory");
    sqlite3_finalize(st);
    return rc;
}

/*
 * A planner configuration's common properties, as OMPL's script stores
 * them from a log's "name = value" lines: sorted, each line followed by
 * "\n;". Caller frees.
 */
static char *config_settings(const char *planner, const char *algorithm,
                             const char *params)
{
    size_t cap = strlen(planner) + strlen(algorithm) + 3 * strlen(params) +
                 64;
    char *lines[256];
    int n = 0;
    char *buf = malloc(cap), *text = strdup(params ? params : "");
    if (buf == NULL || text == NULL) {
        free(buf);
        free(text);
        return NULL;
    }
    char alg[256], pl[256];
    snprintf(alg, sizeof alg, "algorithm = %s", algorithm);
    snprintf(pl, sizeof pl, "planner = %s", planner);
    lines[n++] = alg;
    lines[n++] = pl;
    /* params: "key=value;key=value" */
    char *save = NULL;
    char *kv_store = malloc(strlen(text) * 3 + 64);
    char *kv = kv_store;
    if (kv_store == NULL) {
        free(buf);
        free(text);
        return NULL;
    }
    for (char *tok = strtok_r(text, ";", &save); tok && n < 256;
         tok = strtok_r(NULL, ";", &save)) {
        char *eq = strchr(tok, '=');
        if (eq == NULL || eq == tok)
            continue;
        *eq = '\0';
        int len = sprintf(kv, "%s = %s", tok, eq + 1);
        lines[n++] = kv;
        kv += len + 1;
    }
    /* sort (insertion: a handful of lines) */
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && strcmp(lines[j - 1], lines[j]) > 0; j--) {
            char *t = lines[j];
            lines[j] = lines[j - 1];
            lines[j - 1] = t;
        }
    buf[0] = '\0';
    size_t len = 0;
    for (int i = 0; i < n; i++)
        len += (size_t)snprintf(buf + len, cap - len, "%s\n;", lines[i]);
    free(text);
    free(kv_store);
    return buf;
}

/* ---- the Planner Arena database ---------------------------------------------- */

/* The tables as ompl_benchmark_statistics.py (OMPL 1.5) creates them. */
static const char pa_schema[] =
    "CREATE TABLE IF NOT EXISTS experiments"
    " (id INTEGER PRIMARY KEY AUTOINCREMENT, name VARCHAR(512),"
    " totaltime REAL, timelimit REAL, memorylimit REAL, runcount INTEGER,"
    " version VARCHAR(128), hostname VARCHAR(1024), cpuinfo TEXT,"
    " date DATETIME, seed VARCHAR(24), setup TEXT);"
    "CREATE TABLE IF NOT EXISTS plannerConfigs"
    " (id INTEGER PRIMARY KEY AUTOINCREMENT,"
    " name VARCHAR(512) NOT NULL, settings TEXT);"
    "CREATE TABLE IF NOT EXISTS enums"
    " (name VARCHAR(512), value INTEGER, description TEXT,"
    " PRIMARY KEY (name, value));"
    "CREATE TABLE IF NOT EXISTS runs"
    " (id INTEGER PRIMARY KEY AUTOINCREMENT, experimentid INTEGER,"
    " plannerid INTEGER,"
    " FOREIGN KEY (experimentid) REFERENCES experiments(id) ON DELETE CASCADE,"
    " FOREIGN KEY (plannerid) REFERENCES plannerConfigs(id) ON DELETE CASCADE);"
    "CREATE TABLE IF NOT EXISTS progress"
    " (runid INTEGER, time REAL, PRIMARY KEY (runid, time),"
    " FOREIGN KEY (runid) REFERENCES runs(id) ON DELETE CASCADE);";

typedef struct pa_out {
    mpb_store *s;                   /* errors go here */
    sqlite3   *db;
    const char *path;
    mpb_export_counts counts;
    int64_t   *config_map;          /* pairs: mpbench config id, plannerid */
    int        num_configs, configs_cap;
} pa_out;

static int out_fail(pa_out *o, const char *what)
{
    return mpb__store_fail(o->s, MPB_EDB, "export: %s: %s: %s", o->path, what,
                           sqlite3_errmsg(o->db));
}

static int out_exec(pa_out *o, const char *sql, const char *what)
{
    char *msg = NULL;
    if (sqlite3_exec(o->db, sql, NULL, NULL, &msg) != SQLITE_OK) {
        mpb__store_fail(o->s, MPB_EDB, "export: %s: %s: %s", o->path, what,
                        msg ? msg : "?");
        sqlite3_free(msg);
        return MPB_EDB;
    }
    return MPB_OK;
}

/* Column name of a property: its spaces as '_'. Caller frees. */
static char *column_of(const char *prop_name_text)
{
    char *c = strdup(prop_name_text);
    for (char *p = c; p && *p; p++)
        if (*p == ' ')
            *p = '_';
    return c;
}

/* Add the columns of props missing from table (its first skip columns are
 * fixed), as OMPL's script does with ALTER TABLE. */
static int ensure_columns(pa_out *o, const char *table, const prop_list *props,
                          int first)
{
    char sql[1024];
    sqlite3_stmt *st;
    snprintf(sql, sizeof sql, "PRAGMA table_info(%s)", table);
    if (sqlite3_prepare_v2(o->db, sql, -1, &st, NULL) != SQLITE_OK)
        return out_fail(o, "read columns");
    name_list have = {0};
    int step, rc = MPB_OK;
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        if (room((void **)&have.v, have.n, &have.cap, sizeof *have.v) ||
            (have.v[have.n] = col_dup(st, 1)) == NULL) {
            rc = MPB_ENOMEM;
            break;
        }
        have.n++;
    }
    sqlite3_finalize(st);
    for (int k = first; rc == MPB_OK && k < props->n; k++) {
        int found = 0;
        for (int i = 0; i < have.n && !found; i++)
            found = same_column(have.v[i], props->v[k].name);
        if (found)
            continue;
        char *col = column_of(props->v[k].name);
        if (col == NULL) {
            rc = MPB_ENOMEM;
            break;
        }
        snprintf(sql, sizeof sql, "ALTER TABLE %s ADD \"%s\" %s", table, col,
                 props->v[k].type);
        free(col);
        rc = out_exec(o, sql, "add a column");
    }
    name_list_free(&have);
    if (rc == MPB_ENOMEM)
        mpb__store_fail(o->s, rc, "export: out of memory");
    return rc;
}

/* "INSERT [OR IGNORE] INTO table (fixed..., props...) VALUES (?, ...)" */
static int prepare_insert(pa_out *o, const char *verb, const char *table,
                          const char *fixed, int num_fixed,
                          const prop_list *props, int first,
                          sqlite3_stmt **out)
{
    size_t cap = 256 + strlen(fixed);
    for (int k = first; k < props->n; k++)
        cap += strlen(props->v[k].name) + 8;
    char *sql = malloc(cap);
    if (sql == NULL)
        return mpb__store_fail(o->s, MPB_ENOMEM, "export: out of memory");
    size_t len = (size_t)snprintf(sql, cap, "%s INTO %s (%s", verb, table,
                                  fixed);
    for (int k = first; k < props->n; k++) {
        len += (size_t)snprintf(sql + len, cap - len, ", \"");
        for (const char *p = props->v[k].name; *p; p++)
            sql[len++] = *p == ' ' ? '_' : *p;
        len += (size_t)snprintf(sql + len, cap - len, "\"");
    }
    len += (size_t)snprintf(sql + len, cap - len, ") VALUES (");
    int n = num_fixed + props->n - first;
    for (int i = 0; i < n; i++)
        len += (size_t)snprintf(sql + len, cap - len, "%s?", i ? ", " : "");
    snprintf(sql + len, cap - len, ")");
    int rc = sqlite3_prepare_v2(o->db, sql, -1, out, NULL) == SQLITE_OK
                 ? MPB_OK : out_fail(o, "prepare an insert");
    free(sql);
    return rc;
}

/* A number as the script's text becomes in a column of that affinity:
 * NULL, an integer (unless the column is REAL) or a real. */
static void bind_number(sqlite3_stmt *st, int i, int real, double v)
{
    if (isnan(v))
        sqlite3_bind_null(st, i);
    else if (!real && v == floor(v) && fabs(v) < 9e15)
        sqlite3_bind_int64(st, i, (sqlite3_int64)v);
    else
        sqlite3_bind_double(st, i, v);
}

static void bind_value(sqlite3_stmt *st, int i, const prop *p, double v)
{
    bind_number(st, i, strcmp(p->type, "REAL") == 0, v);
}

/* The plannerConfigs id of an mpbench configuration: found by (name,
 * settings), as OMPL's script finds it, or added. */
static int planner_id(pa_out *o, int64_t config_id, int64_t *out)
{
    for (int i = 0; i < o->num_configs; i++)
        if (o->config_map[2 * i] == config_id) {
            *out = o->config_map[2 * i + 1];
            return MPB_OK;
        }
    sqlite3_stmt *st = mpb__store_prepare(o->s,
        "SELECT name, planner, algorithm, params FROM planner_configs"
        " WHERE id = ?");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, config_id);
    if (sqlite3_step(st) != SQLITE_ROW) {
        sqlite3_finalize(st);
        return mpb__store_db_fail(o->s, "export: read a planner configuration");
    }
    char *name = col_dup(st, 0);
    char *settings = NULL;
    {
        char *planner = col_dup(st, 1), *algorithm = col_dup(st, 2),
             *params = col_dup(st, 3);
        if (planner && algorithm && params)
            settings = config_settings(planner, algorithm, params);
        free(planner);
        free(algorithm);
        free(params);
    }
    sqlite3_finalize(st);
    int rc = MPB_OK;
    if (name == NULL || settings == NULL) {
        rc = mpb__store_fail(o->s, MPB_ENOMEM, "export: out of memory");
        goto done;
    }
    sqlite3_stmt *find = NULL, *add = NULL;
    if (sqlite3_prepare_v2(o->db, "SELECT id FROM plannerConfigs"
                           " WHERE name = ? AND settings = ?", -1, &find,
                           NULL) != SQLITE_OK) {
        rc = out_fail(o, "find a planner configuration");
        goto done;
    }
    sqlite3_bind_text(find, 1, name, -1, SQLITE_STATIC);
    sqlite3_bind_text(find, 2, settings, -1, SQLITE_STATIC);
    if (sqlite3_step(find) == SQLITE_ROW) {
        *out = sqlite3_column_int64(find, 0);
    } else if (sqlite3_prepare_v2(o->db, "INSERT INTO plannerConfigs"
                                  " (name, settings) VALUES (?, ?)", -1, &add,
                                  NULL) != SQLITE_OK) {
        rc = out_fail(o, "add a planner configuration");
    } else {
        sqlite3_bind_text(add, 1, name, -1, SQLITE_STATIC);
        sqlite3_bind_text(add, 2, settings, -1, SQLITE_STATIC);
        if (sqlite3_step(add) != SQLITE_DONE)
            rc = out_fail(o, "add a planner configuration");
        *out = sqlite3_last_insert_rowid(o->db);
        o->counts.planner_configs++;
    }
    sqlite3_finalize(find);
    sqlite3_finalize(add);
    if (rc == MPB_OK) {
        if (room((void **)&o->config_map, 2 * o->num_configs,
                 &o->configs_cap, 2 * sizeof *o->config_map)) {
            rc = mpb__store_fail(o->s, MPB_ENOMEM, "export: out of memory");
        } else {
            o->config_map[2 * o->num_configs] = config_id;
            o->config_map[2 * o->num_configs + 1] = *out;
            o->num_configs++;
        }
    }
done:
    free(name);
    free(settings);
    return rc;
}

/* "2024-05-01 12:34:56" (UTC) of a Unix time; "" if there is none. */
static void format_date(double t, char *buf, size_t n)
{
    buf[0] = '\0';
    if (isnan(t))
        return;
    time_t tt = (time_t)t;
    struct tm tm;
    if (gmtime_r(&tt, &tm) != NULL)
        strftime(buf, n, "%Y-%m-%d %H:%M:%S", &tm);
}

/* One mpbench experiment into the open database. */
static int export_experiment(pa_out *o, int64_t experiment_id)
{
    exp_info e = {0};
    prop_list props = {0}, progress = {0};
    pa_query_list queries = {0};
    sqlite3_stmt *add_exp = NULL, *add_run = NULL, *add_progress = NULL;
    int64_t *pa_exp = NULL;
    walker w = {0};
    int rc;

    if ((rc = exp_info_read(o->s, experiment_id, &e)) ||
        (rc = experiment_props(o->s, experiment_id, &props, &progress)) ||
        (rc = read_queries(o->s, &e, &queries)) ||
        (rc = ensure_columns(o, "runs", &props, 0)) ||
        (rc = ensure_columns(o, "progress", &progress, 1)))
        goto done;
    one_word(e.name);
    if (queries.n == 0)
        goto done;      /* no finished run: nothing to show */

    /* A Planner Arena experiment per query with finished runs. */
    if (sqlite3_prepare_v2(o->db,
            "INSERT INTO experiments (name, totaltime, timelimit, memorylimit,"
            " runcount, version, hostname, cpuinfo, date, seed, setup, query,"
            " mpbench_experiment) VALUES (?1, ?2, ?3, NULL, ?4, ?5, ?6, NULL,"
            " ?7, NULL, ?8, ?9, ?10)", -1, &add_exp, NULL) != SQLITE_OK) {
        rc = out_fail(o, "prepare experiments");
        goto done;
    }
    if ((pa_exp = calloc((size_t)queries.n, sizeof *pa_exp)) == NULL) {
        rc = mpb__store_fail(o->s, MPB_ENOMEM, "export: out of memory");
        goto done;
    }
    char date[32];
    format_date(e.created, date, sizeof date);
    for (int i = 0; i < queries.n; i++) {
        const pa_query *q = &queries.v[i];
        sqlite3_reset(add_exp);
        sqlite3_bind_text(add_exp, 1, q->problem, -1, SQLITE_STATIC);
        sqlite3_bind_double(add_exp, 2, q->total_time);
        if (isnan(e.time_limit))
            sqlite3_bind_null(add_exp, 3);
        else
            sqlite3_bind_double(add_exp, 3, e.time_limit);
        sqlite3_bind_int(add_exp, 4, e.runs_per_query);
        sqlite3_bind_text(add_exp, 5, version_of(&e), -1, SQLITE_STATIC);
        sqlite3_bind_text(add_exp, 6, e.host, -1, SQLITE_STATIC);
        sqlite3_bind_text(add_exp, 7, date, -1, SQLITE_STATIC);
        sqlite3_bind_text(add_exp, 8, q->setup, -1, SQLITE_STATIC);
        sqlite3_bind_text(add_exp, 9, q->query, -1, SQLITE_STATIC);
        sqlite3_bind_int64(add_exp, 10, e.id);
        if (sqlite3_step(add_exp) != SQLITE_DONE) {
            rc = out_fail(o, "add an experiment");
            goto done;
        }
        pa_exp[i] = sqlite3_last_insert_rowid(o->db);
        o->counts.experiments++;
    }

    if ((rc = prepare_insert(o, "INSERT", "runs", "experimentid, plannerid",
                             2, &props, 0, &add_run)) ||
        (rc = prepare_insert(o, "INSERT OR IGNORE", "progress", "runid", 1,
                             &progress, 0, &add_progress)) ||
        (rc = walker_open(&w, o->s, experiment_id, 0, &props, &progress)))
        goto done;
    run_view rv = {0};
    int qi = 0;
    while ((rc = walker_next(&w, &rv)) == 1) {
        int64_t pid = 0;
        while (qi < queries.n && queries.v[qi].query_id != rv.query_id)
            qi++;
        if (qi == queries.n) {
            for (qi = 0; qi < queries.n; qi++)
                if (queries.v[qi].query_id == rv.query_id)
                    break;
            if (qi == queries.n) {
                rc = mpb__store_fail(o->s, MPB_EINVAL, "export: run %lld "
                                     "has no query", (long long)rv.run_id);
                goto done;
            }
        }
        if ((rc = planner_id(o, rv.config_id, &pid)) != MPB_OK)
            goto done;
        sqlite3_reset(add_run);
        sqlite3_bind_int64(add_run, 1, pa_exp[qi]);
        sqlite3_bind_int64(add_run, 2, pid);
        for (int k = 0; k < props.n; k++)
            bind_value(add_run, 3 + k, &props.v[k], rv.values[k]);
        if (sqlite3_step(add_run) != SQLITE_DONE) {
            rc = out_fail(o, "add a run");
            goto done;
        }
        int64_t runid = sqlite3_last_insert_rowid(o->db);
        o->counts.runs++;
        for (int i = 0; i < rv.num_samples; i++) {
            const double *smp = rv.samples + (size_t)i * (size_t)progress.n;
            if (isnan(smp[0]))
                continue;   /* no time: no place on the x-axis */
            sqlite3_reset(add_progress);
            sqlite3_bind_int64(add_progress, 1, runid);
            for (int k = 0; k < progress.n; k++)
                bind_value(add_progress, 2 + k, &progress.v[k], smp[k]);
            if (sqlite3_step(add_progress) != SQLITE_DONE) {
                rc = out_fail(o, "add progress");
                goto done;
            }
            o->counts.progress += sqlite3_changes(o->db);
        }
    }
done:
    walker_close(&w);
    sqlite3_finalize(add_exp);
    sqlite3_finalize(add_run);
    sqlite3_finalize(add_progress);
    free(pa_exp);
    pa_query_list_free(&queries);
    prop_list_free(&props);
    prop_list_free(&progress);
    exp_info_free(&e);
    return rc;
}

/* The views of ompl_benchmark_statistics.py's computeViews() (OMPL 1.5, not
 * MoveIt's format): best configurations by average solved, then time. */
static int create_views(pa_out *o)
{
    sqlite3_stmt *st;
    int simplification = 0;
    if (sqlite3_prepare_v2(o->db, "PRAGMA table_info(runs)", -1, &st, NULL) !=
        SQLITE_OK)
        return out_fail(o, "read columns");
    while (sqlite3_step(st) == SQLITE_ROW)
        simplification |= strcmp((const char *)sqlite3_column_text(st, 1),
                                 "simplification_time") == 0;
    sqlite3_finalize(st);
    char s0[512], sql[2048];
    snprintf(s0, sizeof s0,
             "SELECT plannerid, plannerConfigs.name AS plannerName,"
             " experimentid, solved, %s AS total_time"
             " FROM plannerConfigs INNER JOIN experiments INNER JOIN runs"
             " ON plannerConfigs.id=runs.plannerid AND"
             " experiments.id=runs.experimentid",
             simplification ? "time + simplification_time" : "time");
    int rc = out_exec(o, "DROP VIEW IF EXISTS bestPlannerConfigsPerExperiment;"
                         "DROP VIEW IF EXISTS bestPlannerConfigs;",
                      "drop views");
    if (rc)
        return rc;
    snprintf(sql, sizeof sql,
             "CREATE VIEW IF NOT EXISTS bestPlannerConfigsPerExperiment AS"
             " SELECT plannerid, experimentid, MIN(avg_solved) AS avg_solved,"
             " avg_total_time FROM (SELECT plannerid, plannerName,"
             " experimentid, AVG(solved) AS avg_solved, AVG(total_time) AS"
             " avg_total_time FROM (%s) GROUP BY plannerid, experimentid)"
             " GROUP BY plannerName, experimentid ORDER BY avg_solved DESC,"
             " avg_total_time ASC", s0);
    if ((rc = out_exec(o, sql, "create a view")))
        return rc;
    snprintf(sql, sizeof sql,
             "CREATE VIEW IF NOT EXISTS bestPlannerConfigs AS"
             " SELECT plannerid, MIN(avg_solved) AS avg_solved, avg_total_time"
             " FROM (SELECT plannerid, plannerName, AVG(solved) AS avg_solved,"
             " AVG(total_time) AS avg_total_time FROM (%s) GROUP BY"
             " plannerid) GROUP BY plannerName ORDER BY avg_solved DESC,"
             " avg_total_time ASC", s0);
    return out_exec(o, sql, "create a view");
}

/* Ids of every experiment, or the ids given (checked). Caller frees. */
static int experiment_ids(mpb_store *s, const int64_t *ids, int num_ids,
                          int64_t **out, int *n)
{
    *out = NULL;
    *n = 0;
    if (num_ids > 0) {
        sqlite3_stmt *st = mpb__store_prepare(s,
            "SELECT 1 FROM experiments WHERE id = ?");
        if (st == NULL)
            return MPB_EDB;
        for (int i = 0; i < num_ids; i++) {
            sqlite3_reset(st);
            sqlite3_bind_int64(st, 1, ids[i]);
            if (sqlite3_step(st) != SQLITE_ROW) {
                sqlite3_finalize(st);
                return mpb__store_fail(s, MPB_ENOTFOUND, "no experiment %lld",
                                       (long long)ids[i]);
            }
        }
        sqlite3_finalize(st);
        if ((*out = malloc(sizeof **out * (size_t)num_ids)) == NULL)
            return mpb__store_fail(s, MPB_ENOMEM, "export: out of memory");
        memcpy(*out, ids, sizeof **out * (size_t)num_ids);
        *n = num_ids;
        return MPB_OK;
    }
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT id FROM experiments ORDER BY id");
    int step, cap = 0;
    if (st == NULL)
        return MPB_EDB;
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        if (room((void **)out, *n, &cap, sizeof **out)) {
            sqlite3_finalize(st);
            return mpb__store_fail(s, MPB_ENOMEM, "export: out of memory");
        }
        (*out)[(*n)++] = sqlite3_column_int64(st, 0);
    }
    sqlite3_finalize(st);
    if (step != SQLITE_DONE)
        return mpb__store_db_fail(s, "export: list experiments");
    if (*n == 0)
        return mpb__store_fail(s, MPB_ENOTFOUND, "no experiment to export");
    return MPB_OK;
}

int mpb_store_export_planner_arena(mpb_store *s, const char *path,
                                   const int64_t *ids, int num_ids, int flags,
                                   mpb_export_counts *counts)
{
    pa_out o = {.s = s, .path = path};
    struct stat sb;
    int64_t *exps = NULL;
    int num_exps = 0, rc, created = 0;

    if (counts)
        *counts = (mpb_export_counts){0};
    if (path == NULL || num_ids < 0 || (num_ids > 0 && ids == NULL))
        return mpb__store_fail(s, MPB_EINVAL, "export: bad arguments");
    int exists = stat(path, &sb) == 0;
    if (exists && !(flags & MPB_EXPORT_APPEND))
        return mpb__store_fail(s, MPB_EEXISTS, "export: %s exists", path);
    if (!exists && errno != ENOENT)
        return mpb__store_fail(s, MPB_EIO, "export: %s: %s", path,
                               strerror(errno));
    if ((rc = experiment_ids(s, ids, num_ids, &exps, &num_exps)) != MPB_OK)
        return rc;
    if (sqlite3_open_v2(path, &o.db, SQLITE_OPEN_READWRITE |
                        (exists ? 0 : SQLITE_OPEN_CREATE), NULL) != SQLITE_OK) {
        rc = mpb__store_fail(s, MPB_EIO, "export: cannot open %s: %s", path,
                             o.db ? sqlite3_errmsg(o.db) : "out of memory");
        goto done;
    }
    created = !exists;
    sqlite3_busy_timeout(o.db, 5000);
    if ((rc = out_exec(&o, "PRAGMA foreign_keys = ON", "configure")) ||
        (rc = out_exec(&o, "BEGIN IMMEDIATE", "begin")) ||
        (rc = out_exec(&o, pa_schema, "create the tables")))
        goto done;

    /* The experiment parameters after the twelve known columns. */
    for (int i = 0; i < NUM_EXP_PARAMS && rc == MPB_OK; i++) {
        prop p = {.name = (char *)exp_params[i][0], .type = exp_params[i][1]};
        prop_list one = {.v = &p, .n = 1, .cap = 1};
        rc = ensure_columns(&o, "experiments", &one, 0);
    }
    if (rc)
        goto done;

    sqlite3_stmt *en;
    if (sqlite3_prepare_v2(o.db, "INSERT OR IGNORE INTO enums (name, value,"
                           " description) VALUES ('status', ?, ?)", -1, &en,
                           NULL) != SQLITE_OK) {
        rc = out_fail(&o, "prepare enums");
        goto done;
    }
    for (int i = 0; i < NUM_STATUS && rc == MPB_OK; i++) {
        sqlite3_reset(en);
        sqlite3_bind_int(en, 1, i);
        sqlite3_bind_text(en, 2, status_enum[i], -1, SQLITE_STATIC);
        if (sqlite3_step(en) != SQLITE_DONE)
            rc = out_fail(&o, "add the status enum");
    }
    sqlite3_finalize(en);
    for (int i = 0; i < num_exps && rc == MPB_OK; i++)
        rc = export_experiment(&o, exps[i]);
    if (rc == MPB_OK && (rc = create_views(&o)) == MPB_OK)
        rc = out_exec(&o, "COMMIT", "commit");
done:
    if (o.db) {
        if (rc != MPB_OK)
            sqlite3_exec(o.db, "ROLLBACK", NULL, NULL, NULL);
        if (sqlite3_close(o.db) != SQLITE_OK && rc == MPB_OK)
            rc = mpb__store_fail(s, MPB_EIO, "export: cannot close %s", path);
    }
    if (rc != MPB_OK && created) {
        /* Leave nothing half-written behind. */
        size_t n = strlen(path) + 16;
        char *j = malloc(n);
        unlink(path);
        if (j) {
            snprintf(j, n, "%s-journal", path);
            unlink(j);
            free(j);
        }
    }
    if (rc == MPB_OK && counts)
        *counts = o.counts;
    free(exps);
    free(o.config_map);
    return rc;
}

/* ---- an OMPL log straight into a Planner Arena database --------------------- */

/*
 * Rows per INSERT statement of the runs and progress: one statement's own
 * cost (its start and end, the AUTOINCREMENT counter written back) shared
 * by that many rows instead of paid by each.
 */
#define PA_BATCH 64

/* "INSERT [OR IGNORE] INTO table (fixed..., props...) VALUES (values,
 * ?, ...), ...", rows times: the first columns' values written out (for
 * those the same in every row), a parameter for each property. */
static int prepare_rows(pa_out *o, const char *verb, const char *table,
                        const char *fixed, const char *values,
                        const prop_list *props, int rows, sqlite3_stmt **out)
{
    *out = NULL;
    size_t cap = 256 + strlen(fixed) +
                 (size_t)rows * (strlen(values) + 2 * (size_t)props->n + 4);
    for (int k = 0; k < props->n; k++)
        cap += strlen(props->v[k].name) + 8;
    char *sql = malloc(cap);
    if (sql == NULL)
        return mpb__store_fail(o->s, MPB_ENOMEM, "export: out of memory");
    size_t len = (size_t)snprintf(sql, cap, "%s INTO %s (%s", verb, table,
                                  fixed);
    for (int k = 0; k < props->n; k++) {
        sql[len++] = ',';
        sql[len++] = '"';
        for (const char *p = props->v[k].name; *p; p++)
            sql[len++] = *p == ' ' ? '_' : *p;
        sql[len++] = '"';
    }
    len += (size_t)snprintf(sql + len, cap - len, ") VALUES ");
    for (int r = 0; r < rows; r++) {
        len += (size_t)snprintf(sql + len, cap - len, "%s(%s", r ? "," : "",
                                values);
        for (int i = 0; i < props->n; i++)
            len += (size_t)snprintf(sql + len, cap - len, ",?");
        sql[len++] = ')';
    }
    sql[len] = '\0';
    int rc = sqlite3_prepare_v2(o->db, sql, (int)len, out, NULL) == SQLITE_OK
                 ? MPB_OK : out_fail(o, "prepare an insert");
    free(sql);
    return rc;
}

/* How many rows of n values one statement may take (at least 1). */
static int batch_rows(pa_out *o, int n)
{
    int vars = sqlite3_limit(o->db, SQLITE_LIMIT_VARIABLE_NUMBER, -1);
    int rows = n > 0 ? vars / n : PA_BATCH;
    return rows < 1 ? 1 : rows > PA_BATCH ? PA_BATCH : rows;
}

/* One planner block's runs (and progress) as OMPL's script writes them:
 * the runs in the log's order, then their progress samples. */
static int write_log_planner(pa_out *o, int64_t experiment_id,
                             const mpb_ompl_planner *p)
{
    sqlite3_stmt *st = NULL, *many = NULL;
    prop_list props = {0}, tprog = {0}, prog;
    int64_t planner = 0, *run_ids = NULL;
    int *real = NULL;
    int rc = MPB_ENOMEM;
    int np = p->num_properties, q = p->num_progress_properties;
    int has_progress = q > 1 && p->progress_start != NULL &&
                       p->progress_start[p->num_runs] > 0;
    props.v = calloc((size_t)np + 1, sizeof *props.v);
    tprog.v = calloc((size_t)q + 1, sizeof *tprog.v);
    real = calloc((size_t)(np > q ? np : q) + 1, sizeof *real);
    if (props.v == NULL || tprog.v == NULL || real == NULL)
        goto done;
    if (has_progress &&
        (run_ids = malloc(((size_t)p->num_runs + 1) * sizeof *run_ids)) == NULL)
        goto done;
    /* The props borrow the log's names; nothing of them is freed here. */
    for (int k = 0; k < np; k++)
        props.v[props.n++] = (prop){.name = p->properties[k].name,
                                    .type = p->properties[k].type};
    /* The progress columns: the sample's time, then the rest (prog). */
    tprog.v[tprog.n++] = (prop){.name = "time", .type = "REAL"};
    for (int k = 1; k < q; k++)
        tprog.v[tprog.n++] = (prop){.name = p->progress_properties[k].name,
                                    .type = p->progress_properties[k].type};
    prog = (prop_list){.v = tprog.v + 1, .n = tprog.n - 1};
    if (sqlite3_prepare_v2(o->db, "INSERT INTO plannerConfigs (name, settings)"
                           " VALUES (?, ?)", -1, &st, NULL) != SQLITE_OK) {
        rc = out_fail(o, "prepare plannerConfigs");
        goto done;
    }
    sqlite3_bind_text(st, 1, p->name, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 2, p->settings, -1, SQLITE_STATIC);
    if (sqlite3_step(st) != SQLITE_DONE) {
        rc = out_fail(o, "add a planner configuration");
        goto done;
    }
    planner = sqlite3_last_insert_rowid(o->db);
    o->counts.planner_configs++;
    sqlite3_finalize(st);
    st = NULL;

    /* The runs, PA_BATCH a statement, the last few one by one. */
    char ids[64];
    snprintf(ids, sizeof ids, "%lld,%lld", (long long)experiment_id,
             (long long)planner);
    int rows = batch_rows(o, np);
    if ((rc = ensure_columns(o, "runs", &props, 0)) != MPB_OK ||
        (rc = prepare_rows(o, "INSERT", "runs", "experimentid,plannerid", ids,
                           &props, 1, &st)) != MPB_OK ||
        (rows > 1 && p->num_runs >= rows &&
         (rc = prepare_rows(o, "INSERT", "runs", "experimentid,plannerid", ids,
                            &props, rows, &many)) != MPB_OK))
        goto done;
    for (int k = 0; k < np; k++)
        real[k] = strcmp(props.v[k].type, "REAL") == 0;
    for (long r = 0; r < p->num_runs && rc == MPB_OK;) {
        int k = p->num_runs - r >= rows ? rows : 1;
        sqlite3_stmt *ins = k > 1 ? many : st;
        const double *v = p->values + (size_t)r * (size_t)np;
        for (int i = 0; i < k * np; i++)
            bind_number(ins, i + 1, real[i % np], v[i]);
        if (sqlite3_step(ins) != SQLITE_DONE) {
            rc = out_fail(o, "add a run");
            break;
        }
        sqlite3_reset(ins);
        /* AUTOINCREMENT ids: one more than the largest so far, so a
         * statement's rows have consecutive ids, the last one's known. */
        int64_t last = sqlite3_last_insert_rowid(o->db);
        for (int i = 0; run_ids && i < k; i++)
            run_ids[r + i] = last - (k - 1) + i;
        o->counts.runs += k;
        r += k;
    }
    sqlite3_finalize(st);
    sqlite3_finalize(many);
    st = many = NULL;
    if (rc == MPB_OK && prog.n > 0)
        rc = ensure_columns(o, "progress", &prog, 0);
    if (rc != MPB_OK || !has_progress)
        goto done;

    /* The progress samples, in the log's order (a repeated time keeps the
     * first, as the script does), PA_BATCH a statement. */
    int n = 1 + q;
    rows = batch_rows(o, n);
    long total = p->progress_start[p->num_runs];
    if ((rc = prepare_rows(o, "INSERT OR IGNORE", "progress", "runid", "?",
                           &tprog, 1, &st)) != MPB_OK ||
        (rows > 1 && total >= rows &&
         (rc = prepare_rows(o, "INSERT OR IGNORE", "progress", "runid", "?",
                            &tprog, rows, &many)) != MPB_OK))
        goto done;
    for (int k = 0; k < q; k++)
        real[k] = strcmp(tprog.v[k].type, "REAL") == 0;
    long run = 0;
    for (long i = 0; i < total && rc == MPB_OK;) {
        int k = total - i >= rows ? rows : 1;
        sqlite3_stmt *ins = k > 1 ? many : st;
        for (int b = 0; b < k; b++) {
            while (p->progress_start[run + 1] <= i + b)
                run++;
            const double *sample = p->progress + (size_t)(i + b) * (size_t)q;
            sqlite3_bind_int64(ins, b * n + 1, run_ids[run]);
            for (int j = 0; j < q; j++)
                bind_number(ins, b * n + 2 + j, real[j], sample[j]);
        }
        if (sqlite3_step(ins) != SQLITE_DONE) {
            rc = out_fail(o, "add a progress sample");
            break;
        }
        sqlite3_reset(ins);
        o->counts.progress += sqlite3_changes(o->db);
        i += k;
    }
done:
    if (rc == MPB_ENOMEM)
        mpb__store_fail(o->s, rc, "out of memory");
    sqlite3_finalize(st);
    sqlite3_finalize(many);
    free(props.v);
    free(tprog.v);
    free(real);
    free(run_ids);
    return rc;
}

/* A new empty file beside path (same directory, so that it can take
 * path's name), mode 0644 less the umask as SQLite creates files; its
 * name in *tmp, freed by the caller. */
static int create_beside(const char *path, char **tmp)
{
    size_t n = strlen(path) + 48;
    char *t = malloc(n);
    if (t == NULL)
        return MPB_ENOMEM;
    for (int i = 0; i < 1000; i++) {
        snprintf(t, n, "%s.tmp-%ld-%d", path, (long)getpid(), i);
        int fd = open(t, O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
        if (fd >= 0) {
            close(fd);
            *tmp = t;
            return MPB_OK;
        }
        if (errno != EEXIST)
            break;
    }
    int e = errno;
    free(t);
    errno = e;
    return MPB_EIO;
}

/* The complete file tmp on disk, then under the name path, which must
 * not exist: link() refuses to replace a file that appeared meanwhile
 * (rename() where links are not supported). tmp is gone either way. */
static int publish(mpb_store *errs, const char *tmp, const char *path)
{
    int rc = MPB_OK, fd = open(tmp, O_RDWR | O_CLOEXEC);
    if (fd < 0 || fdatasync(fd) != 0)
        rc = mpb__store_fail(errs, MPB_EIO, "cannot write %s: %s", tmp,
                             strerror(errno));
    if (fd >= 0)
        close(fd);
    if (rc == MPB_OK && link(tmp, path) != 0) {
        struct stat sb;
        if (errno == EEXIST || stat(path, &sb) == 0)
            rc = mpb__store_fail(errs, MPB_EEXISTS, "%s exists", path);
        else if (rename(tmp, path) != 0)
            rc = mpb__store_fail(errs, MPB_EIO, "cannot rename %s to %s: %s",
                                 tmp, path, strerror(errno));
        else
            return MPB_OK;
    }
    unlink(tmp);
    return rc;
}

int mpb_ompl_log_to_planner_arena(const mpb_ompl_log *log, const char *path,
                                  int flags, mpb_export_counts *counts,
                                  char *err, size_t errlen)
{
    /* The Planner Arena writer reports through a store's message; this
     * one has nothing else. */
    mpb_store errs;
    memset(&errs, 0, sizeof errs);
    pa_out o = {.s = &errs, .path = path};
    struct stat sb;
    char *tmp = NULL;
    int rc;
    if (counts)
        *counts = (mpb_export_counts){0};
    if (log == NULL || path == NULL) {
        rc = mpb__store_fail(&errs, MPB_EINVAL, "bad arguments");
        goto out;
    }
    int exists = stat(path, &sb) == 0;
    if (exists && !(flags & MPB_EXPORT_APPEND)) {
        rc = mpb__store_fail(&errs, MPB_EEXISTS, "%s exists", path);
        goto out;
    }
    /* A new database is written whole into a file beside path and takes
     * its name only once complete: until then nobody reads it, so it
     * needs no journal, no locks and no syncs but the last (publish()).
     * An existing one is added to in place, with SQLite's defaults. */
    if (!exists && (rc = create_beside(path, &tmp)) != MPB_OK) {
        rc = mpb__store_fail(&errs, rc, "cannot create a file beside %s: %s",
                             path, rc == MPB_ENOMEM ? "out of memory"
                                                    : strerror(errno));
        goto out;
    }
    /* One thread uses the connection: no mutexes. */
    if (sqlite3_open_v2(tmp ? tmp : path, &o.db, SQLITE_OPEN_READWRITE |
                        SQLITE_OPEN_NOMUTEX, NULL) != SQLITE_OK) {
        rc = mpb__store_fail(&errs, MPB_EIO, "cannot open %s: %s", path,
                             o.db ? sqlite3_errmsg(o.db) : "out of memory");
        goto close;
    }
    sqlite3_busy_timeout(o.db, 5000);
    /* No foreign key checks: every id written is one this function has
     * just inserted (the script does not check them either). */
    if ((tmp && (rc = out_exec(&o, "PRAGMA journal_mode = OFF;"
                                   "PRAGMA synchronous = OFF;"
                                   "PRAGMA locking_mode = EXCLUSIVE", "configure"))) ||
        (rc = out_exec(&o, "BEGIN IMMEDIATE", "begin")) ||
        (rc = out_exec(&o, pa_schema, "create the tables")))
        goto close;
    sqlite3_stmt *st;
    if (sqlite3_prepare_v2(o.db, "INSERT OR IGNORE INTO enums (name, value,"
                           " description) VALUES ('status', ?, ?)", -1, &st,
                           NULL) != SQLITE_OK) {
        rc = out_fail(&o, "prepare enums");
        goto close;
    }
    for (int i = 0; i < NUM_STATUS && rc == MPB_OK; i++) {
        sqlite3_reset(st);
        sqlite3_bind_int(st, 1, i);
        sqlite3_bind_text(st, 2, status_enum[i], -1, SQLITE_STATIC);
        if (sqlite3_step(st) != SQLITE_DONE)
            rc = out_fail(&o, "add the status enum");
    }
    sqlite3_finalize(st);
    if (rc)
        goto close;
    if (sqlite3_prepare_v2(o.db, "INSERT INTO experiments (name, totaltime,"
                           " timelimit, memorylimit, runcount, version,"
                           " hostname, cpuinfo, date, seed, setup) VALUES"
                           " (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)", -1, &st,
                           NULL) != SQLITE_OK) {
        rc = out_fail(&o, "prepare experiments");
        goto close;
    }
    sqlite3_bind_text(st, 1, log->experiment, -1, SQLITE_STATIC);
    sqlite3_bind_double(st, 2, log->total_time);
    sqlite3_bind_double(st, 3, log->time_limit);
    sqlite3_bind_double(st, 4, log->memory_limit);
    sqlite3_bind_int64(st, 5, log->runs_per_planner);
    sqlite3_bind_text(st, 6, log->version, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 7, log->host, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 8, log->cpuinfo, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 9, log->date, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 10, log->seed, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 11, log->setup, -1, SQLITE_STATIC);
    if (sqlite3_step(st) != SQLITE_DONE)
        rc = out_fail(&o, "add the experiment");
    sqlite3_finalize(st);
    int64_t experiment = sqlite3_last_insert_rowid(o.db);
    o.counts.experiments = 1;
    for (int i = 0; i < log->num_planners && rc == MPB_OK; i++)
        rc = write_log_planner(&o, experiment, &log->planners[i]);
    if (rc == MPB_OK && (rc = create_views(&o)) == MPB_OK)
        rc = out_exec(&o, "COMMIT", "commit");
close:
    if (o.db) {
        if (rc != MPB_OK)
            sqlite3_exec(o.db, "ROLLBACK", NULL, NULL, NULL);
        if (sqlite3_close(o.db) != SQLITE_OK && rc == MPB_OK)
            rc = mpb__store_fail(&errs, MPB_EIO, "cannot close %s", path);
    }
    if (tmp) {
        /* Leave nothing half-written behind. */
        if (rc == MPB_OK)
            rc = publish(&errs, tmp, path);
        else
            unlink(tmp);
    }
out:
    if (rc == MPB_OK && counts)
        *counts = o.counts;
    if (rc != MPB_OK && err && errlen)
        snprintf(err, errlen, "%s", errs.errmsg);
    free(tmp);
    return rc;
}

/* ---- OMPL benchmark logs ---------------------------------------------------- */

/* A file name part: [A-Za-z0-9._-] kept, anything else '_'. */
static void file_word(char *s)
{
    for (; *s; s++) {
        char ch = *s;
        int ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                 (ch >= '0' && ch <= '9') || ch == '.' || ch == '-';
        if (!ok)
            *s = '_';
    }
}

/* A value of a log's run line: integers for all but REAL, 17 digits for
 * REAL (exact), nothing for NULL. */
static void log_value(FILE *out, const prop *p, double v)
{
    if (isnan(v))
        return;
    if (strcmp(p->type, "REAL") != 0 && v == floor(v) && fabs(v) < 9e15)
        fprintf(out, "%lld", (long long)v);
    else
        fprintf(out, "%.17g", v);
}

/* A line of the log without its line breaks (a name, a setting). */
static void log_line(FILE *out, const char *text)
{
    for (; *text; text++)
        fputc(*text == '\n' || *text == '\r' ? ' ' : *text, out);
    fputc('\n', out);
}

typedef struct config_count {
    int64_t id;
    long    runs;
} config_count;

/* One log: one query of experiment e. */
static int write_log(mpb_store *s, FILE *out, const exp_info *e,
                     const pa_query *q, const prop_list *props,
                     const prop_list *progress)
{
    config_count *cfg = NULL;
    int num_cfg = 0, cap = 0, rc = MPB_OK, step;
    walker w = {0};
    char *prog_text = NULL;
    size_t prog_len = 0;
    FILE *prog = NULL;

    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT planner_config_id, count(*) FROM runs WHERE experiment_id = ?1"
        " AND query_id = ?2 AND state = 'done' GROUP BY planner_config_id"
        " ORDER BY planner_config_id");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, e->id);
    sqlite3_bind_int64(st, 2, q->query_id);
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        if (room((void **)&cfg, num_cfg, &cap, sizeof *cfg)) {
            rc = mpb__store_fail(s, MPB_ENOMEM, "export: out of memory");
            break;
        }
        cfg[num_cfg].id = sqlite3_column_int64(st, 0);
        cfg[num_cfg++].runs = sqlite3_column_int64(st, 1);
    }
    if (rc == MPB_OK && step != SQLITE_DONE)
        rc = mpb__store_db_fail(s, "export: count runs");
    sqlite3_finalize(st);
    if (rc)
        goto done;

    /* The experiment: OMPL's header, our version as "NAME version X". */
    const char *version = version_of(e);
    const char *space = strchr(version, ' ');
    if (space)
        fprintf(out, "%.*s version %s\n", (int)(space - version), version,
                space + 1);
    else
        fprintf(out, "mpbench version %s\n", version);
    fprintf(out, "Experiment %s\n", q->problem);
    fprintf(out, "%d experiment properties\n", NUM_EXP_PARAMS);
    fprintf(out, "query VARCHAR(512) = ");
    log_line(out, q->query);
    fprintf(out, "mpbench_experiment INTEGER = %lld\n", (long long)e->id);
    fprintf(out, "Running on ");
    char host[256];
    snprintf(host, sizeof host, "%s", e->host[0] ? e->host : "UNKNOWN");
    one_word(host);
    log_line(out, host);
    char date[32];
    format_date(e->created, date, sizeof date);
    fprintf(out, "Starting at %s\n", date);
    fprintf(out, "<<<|\n%s", q->setup);
    if (q->setup[0] && q->setup[strlen(q->setup) - 1] != '\n')
        fputc('\n', out);
    fprintf(out, "|>>>\n");
    fprintf(out, "0 is the random seed\n");
    fprintf(out, "%.17g seconds per run\n", isnan(e->time_limit) ? 0.0
                                                                 : e->time_limit);
    fprintf(out, "0 MB per run\n");
    fprintf(out, "%d runs per planner\n", e->runs_per_query);
    fprintf(out, "%.17g seconds spent to collect the data\n", q->total_time);
    fprintf(out, "1 enum type\nstatus");
    for (int i = 0; i < NUM_STATUS; i++)
        fprintf(out, "|%s", status_enum[i]);
    fprintf(out, "\n%d planners\n", num_cfg);

    if ((rc = walker_open(&w, s, e->id, q->query_id, props, progress)))
        goto done;
    run_view rv = {0};
    for (int c = 0; c < num_cfg; c++) {
        /* The planner: its name and settings. */
        sqlite3_stmt *cs = mpb__store_prepare(s,
            "SELECT name, planner, algorithm, params FROM planner_configs"
            " WHERE id = ?");
        if (cs == NULL) {
            rc = MPB_EDB;
            goto done;
        }
        sqlite3_bind_int64(cs, 1, cfg[c].id);
        char *settings = NULL;
        if (sqlite3_step(cs) == SQLITE_ROW) {
            log_line(out, (const char *)sqlite3_column_text(cs, 0));
            settings = config_settings(
                (const char *)sqlite3_column_text(cs, 1),
                (const char *)sqlite3_column_text(cs, 2),
                (const char *)sqlite3_column_text(cs, 3));
        }
        sqlite3_finalize(cs);
        if (settings == NULL) {
            rc = mpb__store_fail(s, MPB_ENOMEM, "export: out of memory");
            goto done;
        }
        int lines = 0;
        for (const char *p = settings; *p; p++)
            lines += *p == ';';
        fprintf(out, "%d common properties\n", lines);
        for (char *p = settings; *p; p++)
            if (*p != ';')
                fputc(*p, out);     /* "name = value\n" lines */
        free(settings);

        fprintf(out, "%d properties for each run\n", props->n);
        for (int k = 0; k < props->n; k++)
            fprintf(out, "%s %s\n", props->v[k].name, props->v[k].type);
        fprintf(out, "%ld runs\n", cfg[c].runs);
        free(prog_text);
        prog_text = NULL;
        if ((prog = open_memstream(&prog_text, &prog_len)) == NULL) {
            rc = mpb__store_fail(s, MPB_ENOMEM, "export: out of memory");
            goto done;
        }
        long any_samples = 0;
        for (long i = 0; i < cfg[c].runs; i++) {
            int got = walker_next(&w, &rv);
            if (got < 0) {
                rc = got;
                goto done;
            }
            if (got == 0 || rv.config_id != cfg[c].id) {
                rc = mpb__store_fail(s, MPB_EDB, "export: runs changed while "
                                     "being read");
                goto done;
            }
            for (int k = 0; k < props->n; k++) {
                log_value(out, &props->v[k], rv.values[k]);
                fputs("; ", out);
            }
            fputc('\n', out);
            for (int j = 0; j < rv.num_samples; j++) {
                const double *smp = rv.samples + (size_t)j * (size_t)progress->n;
                for (int k = 0; k < progress->n; k++) {
                    log_value(prog, &progress->v[k], smp[k]);
                    fputc(',', prog);
                }
                fputc(';', prog);
                any_samples++;
            }
            fputc('\n', prog);
        }
        fclose(prog);
        prog = NULL;
        if (progress->n > 1 || any_samples > 0) {
            fprintf(out, "%d progress properties for each run\n", progress->n);
            for (int k = 0; k < progress->n; k++)
                fprintf(out, "%s %s\n", progress->v[k].name,
                        progress->v[k].type);
            fprintf(out, "%ld runs\n", cfg[c].runs);
            fwrite(prog_text, 1, prog_len, out);
        }
        fprintf(out, ".\n");
    }
done:
    if (prog)
        fclose(prog);
    free(prog_text);
    walker_close(&w);
    free(cfg);
    return rc;
}

int mpb_store_export_ompl_logs(mpb_store *s, const char *dir,
                               const int64_t *ids, int num_ids, int flags,
                               mpb_export_counts *counts)
{
    int64_t *exps = NULL;
    int num_exps = 0, rc;
    mpb_export_counts c = {0};

    if (counts)
        *counts = c;
    if (dir == NULL || num_ids < 0 || (num_ids > 0 && ids == NULL))
        return mpb__store_fail(s, MPB_EINVAL, "export: bad arguments");
    struct stat sb;
    if (stat(dir, &sb) != 0 && errno == ENOENT && mkdir(dir, 0777) != 0)
        return mpb__store_fail(s, MPB_EIO, "export: cannot create %s: %s",
                               dir, strerror(errno));
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode))
        return mpb__store_fail(s, MPB_EIO, "export: %s is not a directory",
                               dir);
    if ((rc = experiment_ids(s, ids, num_ids, &exps, &num_exps)) != MPB_OK)
        return rc;
    for (int i = 0; i < num_exps && rc == MPB_OK; i++) {
        exp_info e = {0};
        prop_list props = {0}, progress = {0};
        pa_query_list queries = {0};
        if ((rc = exp_info_read(s, exps[i], &e)) ||
            (rc = experiment_props(s, exps[i], &props, &progress)) ||
            (rc = read_queries(s, &e, &queries)))
            goto next;
        for (int k = 0; k < queries.n && rc == MPB_OK; k++) {
            const pa_query *q = &queries.v[k];
            size_t n = strlen(dir) + strlen(e.name) + strlen(q->problem) +
                       strlen(q->query) + 64;
            char *path = malloc(n), *base = malloc(n);
            if (path == NULL || base == NULL) {
                free(path);
                free(base);
                rc = mpb__store_fail(s, MPB_ENOMEM, "export: out of memory");
                break;
            }
            /* EXPERIMENT.ID.SCENE.QUERY.log; the scene is the problem
             * name's part after the experiment's. */
            const char *scene = q->problem + strlen(e.name);
            scene += *scene == '/';
            snprintf(base, n, "%s.%lld.%s.%s", e.name, (long long)e.id,
                     scene, q->query);
            file_word(base);
            snprintf(path, n, "%s/%s.log", dir, base);
            free(base);
            FILE *out = fopen(path, (flags & MPB_EXPORT_REPLACE) ? "w" : "wx");
            if (out == NULL) {
                rc = mpb__store_fail(s, errno == EEXIST ? MPB_EEXISTS : MPB_EIO,
                                     "export: %s: %s", path,
                                     errno == EEXIST ? "exists"
                                                     : strerror(errno));
                free(path);
                break;
            }
            rc = write_log(s, out, &e, q, &props, &progress);
            if (fclose(out) != 0 && rc == MPB_OK)
                rc = mpb__store_fail(s, MPB_EIO, "export: cannot write %s",
                                     path);
            if (rc != MPB_OK)
                unlink(path);
            else {
                c.experiments++;
                c.runs += q->runs;
            }
            free(path);
        }
    next:
        exp_info_free(&e);
        prop_list_free(&props);
        prop_list_free(&progress);
        pa_query_list_free(&queries);
    }
    free(exps);
    if (counts)
        *counts = c;
    return rc;
}
