/*
 * store_pa_props.c - an mpbench experiment as the run properties of OMPL's
 * formats (store_pa.h): their names and types (time, solved, status, the
 * first and final stage's path metrics as "solution ..." and "simplified
 * solution ...", the stages between as "<stage> solution ...", the
 * planner's own numbers), a walk that turns each finished run into a row
 * of them and its progress samples, and what every writer says of an
 * experiment. The database writer and the log writer both consume them.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/grow.h"
#include "interop/store_pa.h"

/* ---- the run properties ---------------------------------------------------- */

/* The header gives the sizes of these two: a definition of another
 * length does not compile. */
const char *const mpb__pa_status_enum[] = {
    "Unknown status", "Invalid start", "Invalid goal",
    "Unrecognized goal type", "Timeout", "Approximate solution",
    "Exact solution", "Crash", "Abort", "Infeasible", "Invalid request",
    "Out of memory",
};

const char *const mpb__pa_exp_params[][2] = {
    {"query", "VARCHAR(512)"},
    {"mpbench experiment", "INTEGER"},
};

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

/* Names a run property must not take: the runs table's own columns and
 * what Planner Arena joins onto each run. */
static const char *const reserved[] = {
    "id", "experimentid", "plannerid", "planner", "experiment", "version",
    "query", "mpbench experiment",
};

void mpb__pa_props_free(prop_list *l)
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

int mpb__pa_same_column(const char *a, const char *b)
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
        if (mpb__pa_same_column(reserved[i], name))
            return 1;
    for (int i = 0; i < l->n; i++)
        if (mpb__pa_same_column(l->v[i].name, name))
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
    if (mpb__grow((void **)&l->v, &l->cap, l->n + 1, sizeof *l->v)) {
        free(name);
        return MPB_ENOMEM;
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

void mpb__pa_names_free(name_list *l)
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
        if (mpb__grow((void **)&out->v, &out->cap, out->n + 1,
                      sizeof *out->v) ||
            (out->v[out->n] = strdup(name)) == NULL) {
            rc = MPB_ENOMEM;
            break;
        }
        out->n++;
    }
    if (rc == MPB_OK && step != SQLITE_DONE)
        rc = mpb__store_db_fail(s, "read names");
    sqlite3_finalize(st);
    if (rc == MPB_ENOMEM)
        mpb__store_fail(s, rc, "out of memory");
    return rc;
}

/* The metrics of a stage, in the order the properties list them: those
 * the metric list ranks (path length, smoothness, clearance, ...) first,
 * then any other alphabetically. */
static int metric_rank(const char *name)
{
    const mpb_metric_info *mi = mpb_metric_info_of(mpb_metric_find(name));
    return mi != NULL && mi->rank > 0 ? mi->rank : MPB_NUM_METRICS + 1;
}

static int cmp_metric(const void *a, const void *b)
{
    const char *x = *(const char *const *)a, *y = *(const char *const *)b;
    int rx = metric_rank(x), ry = metric_rank(y);
    return rx != ry ? rx - ry : strcmp(x, y);
}

/* The property word of a stage metric: "length" for path_length, ...;
 * NULL for those the stage's time and segments say. */
static const char *metric_word(const char *metric)
{
    const mpb_metric_info *mi = mpb_metric_info_of(mpb_metric_find(metric));
    return mi != NULL ? mi->word : metric;
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
        const char *m = metrics->v[i], *word = metric_word(m);
        if (word == NULL)
            continue;   /* the stage's time and segments say it */
        snprintf(buf, sizeof buf, "%ssolution %s", prefix, word);
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

/* One of the four property types of OMPL's logs (static text), REAL for
 * any other. */
static const char *log_type(const char *type)
{
    static const char *const known[] = {"INTEGER", "BOOLEAN", "ENUM"};
    for (int i = 0; type && i < 3; i++)
        if (strcmp(type, known[i]) == 0)
            return known[i];
    return "REAL";
}

/* A property an imported log declares (log_properties). */
typedef struct declared {
    char *name;
    const char *type;   /* log_type()'s */
} declared;

typedef struct declared_list {
    declared *v;
    int       n, cap;
} declared_list;

static void declared_free(declared_list *l)
{
    for (int i = 0; i < l->n; i++)
        free(l->v[i].name);
    free(l->v);
    *l = (declared_list){0};
}

/* The run (progress 0) or progress (1) properties the imported logs of an
 * experiment declare, each name once (its first planner's type), in their
 * planners' and the logs' order; none for a database made before they
 * were kept. */
static int read_declared(mpb_store *s, int64_t experiment_id, int progress,
                         declared_list *out)
{
    if (!mpb__store_has_column(s, "log_properties", "name"))
        return MPB_OK;
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT p.name, p.type FROM log_properties p JOIN planner_configs c"
        " ON c.id = p.planner_config_id WHERE c.experiment_id = ?1"
        " AND p.progress = ?2 ORDER BY c.id, p.idx");
    int step, rc = MPB_OK;
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, experiment_id);
    sqlite3_bind_int(st, 2, progress);
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        const char *name = (const char *)sqlite3_column_text(st, 0);
        int seen = name == NULL;
        for (int i = 0; i < out->n && !seen; i++)
            seen = strcmp(out->v[i].name, name) == 0;
        if (seen)
            continue;
        if (mpb__grow((void **)&out->v, &out->cap, out->n + 1,
                      sizeof *out->v) ||
            (out->v[out->n].name = strdup(name)) == NULL) {
            rc = MPB_ENOMEM;
            break;
        }
        out->v[out->n++].type =
            log_type((const char *)sqlite3_column_text(st, 1));
    }
    if (rc == MPB_OK && step != SQLITE_DONE)
        rc = mpb__store_db_fail(s, "read a log's properties");
    sqlite3_finalize(st);
    return rc;
}

/*
 * What the declared properties d add to l: the type of each planner value
 * a log declared (its K_VALUE property of that source), and a property of
 * its own for each that is not a column of l yet (no run measured it):
 * NULL in every run, as in OMPL's script's database.
 */
static int add_declared(prop_list *l, const declared_list *d,
                        const char *fallback_prefix)
{
    int rc = MPB_OK;
    for (int i = 0; i < d->n && rc == MPB_OK; i++) {
        char *name = prop_name("", d->v[i].name);
        if (name == NULL)
            return MPB_ENOMEM;
        int present = 0;
        for (int k = 0; k < l->n; k++) {
            prop *p = &l->v[k];
            if (p->kind == K_VALUE && p->source &&
                strcmp(p->source, d->v[i].name) == 0) {
                p->type = d->v[i].type;
                present = 1;
            } else if (mpb__pa_same_column(p->name, name)) {
                present = 1;
            }
        }
        if (present)
            free(name);
        else
            rc = prop_add(l, name, d->v[i].type, K_VALUE, ROLE_FIRST, NULL,
                          d->v[i].name, fallback_prefix);
    }
    return rc;
}

/*
 * An imported log's runs: the properties that mpbench works out from what
 * it keeps (the claim, the status, whether approximate, whether a stage
 * is valid) give back the log's own cell instead, NULL where the run has
 * none (its planner's block does not declare the property, or the run
 * left it empty), if the log declares it (mpb import keeps such cells as
 * planner values); and the simplified stage's properties are NULL for a
 * run without one, not the first stage's.
 */
static int log_cells(prop_list *l, const declared_list *d)
{
    static const struct { prop_kind kind; stage_role role; const char *name; }
        own[] = {
        {K_CLAIMED, ROLE_FIRST, "solved"},
        {K_STATUS, ROLE_FIRST, "status"},
        {K_APPROX, ROLE_FIRST, "approximate solution"},
        {K_STAGE_VALID, ROLE_FIRST, "correct solution"},
        {K_STAGE_VALID, ROLE_FINAL, "simplified correct solution"},
    };
    for (int k = 0; k < l->n; k++) {
        prop *p = &l->v[k];
        for (size_t i = 0; i < sizeof own / sizeof own[0]; i++) {
            int said = 0;
            for (int j = 0; j < d->n && !said; j++)
                said = strcmp(d->v[j].name, own[i].name) == 0;
            if (!said || p->kind != own[i].kind || p->role != own[i].role)
                continue;
            free(p->source);
            if ((p->source = strdup(own[i].name)) == NULL)
                return MPB_ENOMEM;
            p->kind = K_VALUE;
            p->role = ROLE_FIRST;
            break;
        }
        if (p->role == ROLE_FINAL)
            p->role = ROLE_SIMPLIFIED;
    }
    return MPB_OK;
}

int mpb__pa_experiment_props(mpb_store *s, int64_t experiment_id,
                             prop_list *props, prop_list *progress)
{
    static const struct { const char *name, *type; prop_kind kind; } fixed[] = {
        {"time", "REAL", K_TIME},
        {"time raw", "REAL", K_TIME_RAW},
        {"time other", "REAL", K_TIME_OTHER},
        {"wall time", "REAL", K_WALL},
        {"verify time", "REAL", K_VERIFY},
        /* OMPL's Benchmark's name, which Planner Arena plots. */
        {"memory", "REAL", K_MEMORY},
        {"solved", "BOOLEAN", K_SOLVED},
        {"claimed success", "BOOLEAN", K_CLAIMED},
        {"approximate solution", "BOOLEAN", K_APPROX},
        {"status", "ENUM", K_STATUS},
    };
    name_list metrics = {0}, mids = {0}, values = {0}, samples = {0};
    declared_list run_decl = {0}, progress_decl = {0};
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
            &samples)) ||
        (rc = read_declared(s, experiment_id, 0, &run_decl)) ||
        (rc = read_declared(s, experiment_id, 1, &progress_decl)))
        goto done;
    if (metrics.n > 1) /* qsort with NULL is undefined, even for 0 */
        qsort(metrics.v, (size_t)metrics.n, sizeof *metrics.v, cmp_metric);

    /* An imported log's runs give back the log's own properties: its
     * "time" (tau_r: tau_t has the simplification too), its "solved" (the
     * claim) and its "simplification time" (the final stage's). */
    int imported = 0;
    sqlite3_stmt *st = mpb__store_prepare(s, "SELECT 1 FROM scenes WHERE"
                                          " experiment_id = ?1 AND"
                                          " robot_format = 'ompl-log'");
    if (st == NULL) {
        rc = MPB_EDB;
        goto done;
    }
    sqlite3_bind_int64(st, 1, experiment_id);
    imported = sqlite3_step(st) == SQLITE_ROW;
    sqlite3_finalize(st);
    for (size_t i = 0; i < sizeof fixed / sizeof fixed[0]; i++) {
        prop_kind kind = fixed[i].kind;
        if (imported && kind == K_TIME)
            kind = K_TIME_RAW;
        else if (imported && kind == K_SOLVED)
            kind = K_CLAIMED;
        if ((rc = prop_add(props, prop_name("", fixed[i].name), fixed[i].type,
                           kind, ROLE_FIRST, NULL, NULL, NULL)))
            goto done;
    }
    if (imported && (rc = prop_add(props, prop_name("", "simplification time"),
                                   "REAL", K_STAGE_TIME, ROLE_FINAL, NULL,
                                   NULL, NULL)))
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
    if (imported && (rc = log_cells(props, &run_decl)))
        goto done;
    for (int i = 0; i < values.n; i++) {
        int taken = 0;  /* read by a property above (log_cells()) */
        for (int k = 0; k < props->n && !taken; k++)
            taken = props->v[k].kind == K_VALUE &&
                    strcmp(props->v[k].source, values.v[i]) == 0;
        if (!taken && (rc = prop_add(props, prop_name("", values.v[i]), "REAL",
                                     K_VALUE, ROLE_FIRST, NULL, values.v[i],
                                     "planner ")))
            goto done;
    }
    if ((rc = add_declared(props, &run_decl, "planner ")))
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
        if (rc == MPB_OK)
            rc = add_declared(progress, &progress_decl, "progress ");
    } else {
        mpb__pa_props_free(&taken);
    }
done:
    if (rc == MPB_ENOMEM)
        mpb__store_fail(s, rc, "out of memory");
    mpb__pa_names_free(&metrics);
    mpb__pa_names_free(&mids);
    mpb__pa_names_free(&values);
    mpb__pa_names_free(&samples);
    declared_free(&run_decl);
    declared_free(&progress_decl);
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

static double col_num(sqlite3_stmt *st, int i)
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
        si->time = col_num(st, 1);
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
        mi->value = col_num(st, 2);
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
        nv->value = col_num(st, 1);
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
        case K_TIME:       v = col_num(r, 6); break;
        case K_TIME_RAW:   v = col_num(r, 7); break;
        case K_TIME_OTHER: v = col_num(r, 8); break;
        case K_WALL:       v = col_num(r, 9); break;
        case K_VERIFY:     v = col_num(r, 11); break;
        case K_MEMORY:     v = col_num(r, 12); break;
        case K_SOLVED:     v = col_num(r, 4); break;
        case K_CLAIMED:    v = col_num(r, 5); break;
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

/* ---- what every writer says of an experiment ------------------------------- */

void mpb__pa_exp_info_free(exp_info *e)
{
    free(e->name);
    free(e->config_text);
    free(e->host);
    free(e->version);
    free(e->started);
    free(e->seed);
    free(e->cpuinfo);
    for (int i = 0; e->params && i < e->num_params; i++) {
        free(e->params[i].name);
        free(e->params[i].type);
        free(e->params[i].value);
    }
    free(e->params);
    *e = (exp_info){0};
}

char *mpb__pa_param_column(const char *name)
{
    char *c = malloc(strlen(name) + 1), *d = c;
    for (; c && *name; name++)
        if (*name != ' ')
            *d++ = *name == '-' ? '_' : *name;
    if (c)
        *d = '\0';
    return c;
}

const char *mpb__pa_exp_param(const exp_info *e, const char *column)
{
    for (int i = 0; i < e->num_params; i++) {
        char *c = mpb__pa_param_column(e->params[i].name);
        int same = c && mpb__pa_same_column(c, column);
        free(c);
        if (same)
            return e->params[i].value;
    }
    return NULL;
}

/* A text column copied, NULL for NULL; *oom set when out of memory. */
static char *col_dup_or_null(sqlite3_stmt *st, int i, int *oom)
{
    if (sqlite3_column_type(st, i) == SQLITE_NULL)
        return NULL;
    char *c = mpb__pa_col_dup(st, i);
    *oom |= c == NULL;
    return c;
}

/* An imported log's header and experiment properties into e; nothing
 * for a database made before they were kept. */
static int read_log_header(mpb_store *s, exp_info *e)
{
    e->total_time = e->memory_limit = NAN;
    if (!mpb__store_has_column(s, "experiments", "started"))
        return MPB_OK;
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT started, seed, cpuinfo, total_time, memory_limit"
        " FROM experiments WHERE id = ?");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, e->id);
    int oom = 0, rc = MPB_OK;
    if (sqlite3_step(st) == SQLITE_ROW) {
        e->started = col_dup_or_null(st, 0, &oom);
        e->seed = col_dup_or_null(st, 1, &oom);
        e->cpuinfo = col_dup_or_null(st, 2, &oom);
        e->total_time = col_num(st, 3);
        e->memory_limit = col_num(st, 4);
    }
    sqlite3_finalize(st);
    if (!oom && mpb__store_has_column(s, "experiment_params", "name")) {
        st = mpb__store_prepare(s, "SELECT name, type, value FROM"
                                " experiment_params WHERE experiment_id = ?"
                                " ORDER BY idx");
        if (st == NULL)
            return MPB_EDB;
        sqlite3_bind_int64(st, 1, e->id);
        int cap = 0, step;
        while (!oom && (step = sqlite3_step(st)) == SQLITE_ROW) {
            if (mpb__grow((void **)&e->params, &cap, e->num_params + 1,
                          sizeof *e->params)) {
                oom = 1;
                break;
            }
            exp_param *p = &e->params[e->num_params++];
            *p = (exp_param){mpb__pa_col_dup(st, 0), mpb__pa_col_dup(st, 1),
                             mpb__pa_col_dup(st, 2)};
            oom |= !p->name || !p->type || !p->value;
        }
        if (!oom && step != SQLITE_DONE)
            rc = mpb__store_db_fail(s, "read experiment parameters");
        sqlite3_finalize(st);
    }
    return oom ? mpb__store_fail(s, MPB_ENOMEM, "out of memory") : rc;
}

int mpb__pa_exp_info_read(mpb_store *s, int64_t id, exp_info *e)
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
        e->name = mpb__pa_col_dup(st, 0);
        e->config_text = mpb__pa_col_dup(st, 1);
        e->host = mpb__pa_col_dup(st, 2);
        e->version = mpb__pa_col_dup(st, 3);
        e->runs_per_query = sqlite3_column_int(st, 4);
        e->time_limit = col_num(st, 5);
        e->created = col_num(st, 6);
        if (!e->name || !e->config_text || !e->host || !e->version)
            rc = mpb__store_fail(s, MPB_ENOMEM, "out of memory");
        else
            rc = read_log_header(s, e);
    } else if (step == SQLITE_DONE) {
        rc = mpb__store_fail(s, MPB_ENOTFOUND, "no experiment %lld",
                             (long long)id);
    } else {
        rc = mpb__store_db_fail(s, "read experiment");
    }
    sqlite3_finalize(st);
    return rc;
}

void mpb__pa_one_word(char *s)
{
    for (; *s; s++)
        if (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r')
            *s = '_';
}

const char *mpb__pa_version_of(const exp_info *e)
{
    return e->version[0] ? e->version : "mpbench " MPB_VERSION_STRING;
}

void mpb__pa_queries_free(pa_query_list *l)
{
    for (int i = 0; i < l->n; i++) {
        free(l->v[i].problem);
        free(l->v[i].query);
        free(l->v[i].setup);
    }
    free(l->v);
    *l = (pa_query_list){0};
}

/* A scene's Planner Arena experiment name. */
typedef struct scene_problem {
    int64_t id;
    char   *problem;
    int     clash;
} scene_problem;

static void scene_problems_free(scene_problem *v, int n)
{
    for (int i = 0; i < n; i++)
        free(v[i].problem);
    free(v);
}

/*
 * The Planner Arena experiment name of each scene of experiment e, by
 * scene id: "<experiment>/<scene>", one word. Scenes whose names become
 * the same word ("a b", "a_b") are told apart by "#N", N the scene's place
 * in the experiment (1, 2, ...), so that reruns of an experiment file get
 * the same names; again while names are the same (a scene may be called
 * "a_b#1"). That ends: two names that end in "#N" differ in N, so each
 * round gives a suffix to at least one scene that had none.
 */
static int scene_problems(mpb_store *s, const exp_info *e,
                          scene_problem **out, int *num)
{
    scene_problem *v = NULL;
    int n = 0, cap = 0, step, rc = MPB_OK;
    *out = NULL;
    *num = 0;
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT id, name FROM scenes WHERE experiment_id = ?1 ORDER BY id");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, e->id);
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        const char *name = (const char *)sqlite3_column_text(st, 1);
        size_t len = strlen(e->name) + strlen(name ? name : "") + 2;
        if (mpb__grow((void **)&v, &cap, n + 1, sizeof *v)) {
            rc = MPB_ENOMEM;
            break;
        }
        v[n] = (scene_problem){.id = sqlite3_column_int64(st, 0),
                               .problem = malloc(len)};
        if (v[n++].problem == NULL) {
            rc = MPB_ENOMEM;
            break;
        }
        snprintf(v[n - 1].problem, len, "%s/%s", e->name, name ? name : "");
        mpb__pa_one_word(v[n - 1].problem);
    }
    if (rc == MPB_OK && step != SQLITE_DONE)
        rc = mpb__store_db_fail(s, "read scenes");
    sqlite3_finalize(st);
    for (int clashes = 1; rc == MPB_OK && clashes;) {
        clashes = 0;
        for (int i = 0; i < n; i++) {
            v[i].clash = 0;
            for (int j = 0; j < n && !v[i].clash; j++)
                v[i].clash = j != i && strcmp(v[i].problem, v[j].problem) == 0;
            clashes |= v[i].clash;
        }
        for (int i = 0; i < n && rc == MPB_OK; i++) {
            if (!v[i].clash)
                continue;
            size_t len = strlen(v[i].problem) + 16;
            char *p = malloc(len);
            if (p == NULL) {
                rc = MPB_ENOMEM;
                break;
            }
            snprintf(p, len, "%s#%d", v[i].problem, i + 1);
            free(v[i].problem);
            v[i].problem = p;
        }
    }
    if (rc != MPB_OK) {
        scene_problems_free(v, n);
        return rc;
    }
    *out = v;
    *num = n;
    return MPB_OK;
}

/*
 * The goal lines of a query's setup. A joint goal: its joints and the
 * tolerance (the start's and the goal's). A pose region: its link, the
 * 12 stored numbers under their experiment file keys (box centre and half
 * sizes, reference rpy and tolerances), and the tolerance, the start's
 * only. Caller frees; NULL when out of memory.
 */
static char *goal_text(const char *kind, const char *joints,
                       const char *tolerance, const char *link,
                       const char *region)
{
    static const char *const keys[] = {"position", "position_tolerance",
                                       "rpy", "rpy_tolerance"};
    char *text = NULL;
    size_t len = 0;
    FILE *out = open_memstream(&text, &len);
    if (out == NULL)
        return NULL;
    if (strcmp(kind, "pose_region") != 0) {
        fprintf(out, "goal (%s): %s\ntolerance: %s\n", kind, joints,
                tolerance);
    } else {
        const char *num[12];
        size_t num_len[12];
        int n = 0;
        for (const char *p = region; n < 13;) {
            p += strspn(p, " ");
            if (*p == '\0')
                break;
            size_t k = strcspn(p, " ");
            if (n < 12) {
                num[n] = p;
                num_len[n] = k;
            }
            n++;
            p += k;
        }
        fprintf(out, "goal (%s): link %s\n", kind, link);
        if (n == 12)
            for (int i = 0; i < 4; i++)
                fprintf(out, "  %s: %.*s %.*s %.*s\n", keys[i],
                        (int)num_len[3 * i], num[3 * i],
                        (int)num_len[3 * i + 1], num[3 * i + 1],
                        (int)num_len[3 * i + 2], num[3 * i + 2]);
        else
            fprintf(out, "  region: %s\n", region);  /* not 12 numbers */
        fprintf(out, "start tolerance: %s\n", tolerance);
    }
    if (fclose(out) != 0) {
        free(text);
        return NULL;
    }
    return text;
}

/* q as the imported log e had it: its experiment's name and setup. */
static int log_problem(mpb_store *s, const exp_info *e, int64_t scene_id,
                       pa_query *q)
{
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT robot FROM scenes WHERE id = ?");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, scene_id);
    int rc = MPB_OK;
    if (sqlite3_step(st) == SQLITE_ROW) {
        char *setup = mpb__pa_col_dup(st, 0), *name = strdup(e->name);
        if (setup == NULL || name == NULL) {
            free(setup);
            free(name);
            rc = MPB_ENOMEM;
        } else {
            mpb__pa_one_word(name);
            free(q->setup);
            free(q->problem);
            q->setup = setup;
            q->problem = name;
        }
    }
    sqlite3_finalize(st);
    return rc;
}

int mpb__pa_read_queries(mpb_store *s, const exp_info *e, pa_query_list *out)
{
    scene_problem *scenes = NULL;
    int step, rc, num_scenes = 0, si = 0;
    if ((rc = scene_problems(s, e, &scenes, &num_scenes)) != MPB_OK)
        goto done;
    /* A database made before pose-region goals, opened read-only, has no
     * columns for them (a writer adds them): NULLs instead. */
    int has_region = mpb__store_has_column(s, "queries", "goal_region");
    sqlite3_stmt *st = mpb__store_prepare(s, has_region
        ? "SELECT q.id, q.name, q.scene_id, count(r.id), total(r.wall_time),"
          " q.joint_names, q.start, q.goal_kind, q.goal_joints,"
          " q.goal_tolerance, q.goal_link, q.goal_region"
          " FROM queries q JOIN scenes sc ON sc.id = q.scene_id"
          " JOIN runs r ON r.query_id = q.id AND r.state = 'done'"
          " WHERE sc.experiment_id = ?1 GROUP BY q.id ORDER BY sc.id, q.id"
        : "SELECT q.id, q.name, q.scene_id, count(r.id), total(r.wall_time),"
          " q.joint_names, q.start, q.goal_kind, q.goal_joints,"
          " q.goal_tolerance, NULL, NULL"
          " FROM queries q JOIN scenes sc ON sc.id = q.scene_id"
          " JOIN runs r ON r.query_id = q.id AND r.state = 'done'"
          " WHERE sc.experiment_id = ?1 GROUP BY q.id ORDER BY sc.id, q.id");
    if (st == NULL) {
        rc = MPB_EDB;
        goto done;
    }
    sqlite3_bind_int64(st, 1, e->id);
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        if ((rc = mpb__grow((void **)&out->v, &out->cap, out->n + 1,
                            sizeof *out->v)))
            break;
        pa_query *q = &out->v[out->n++];
        *q = (pa_query){.query_id = sqlite3_column_int64(st, 0),
                        .runs = sqlite3_column_int(st, 3),
                        .total_time = sqlite3_column_double(st, 4)};
        /* By scene, as the scenes are. */
        int64_t scene_id = sqlite3_column_int64(st, 2);
        while (si < num_scenes && scenes[si].id != scene_id)
            si++;
        if (si == num_scenes) {
            rc = mpb__store_fail(s, MPB_EDB, "query %lld has no scene",
                                 (long long)q->query_id);
            break;
        }
        const char *text[7];
        for (int i = 0; i < 7; i++) {
            text[i] = (const char *)sqlite3_column_text(st, 5 + i);
            if (text[i] == NULL)
                text[i] = "";
        }
        char *goal = goal_text(text[2], text[3], text[4], text[5], text[6]);
        size_t ns = strlen(e->config_text) + 256 + strlen(text[0]) +
                    strlen(text[1]) + (goal ? strlen(goal) : 0) +
                    strlen((const char *)sqlite3_column_text(st, 1));
        q->problem = strdup(scenes[si].problem);
        q->query = mpb__pa_col_dup(st, 1);
        q->setup = malloc(ns);
        if (!q->problem || !q->query || !q->setup || !goal) {
            free(goal);
            rc = MPB_ENOMEM;
            break;
        }
        snprintf(q->setup, ns,
                 "%s%s\nmpbench experiment %lld, query %s\n"
                 "joints: %s\nstart: %s\n%s",
                 e->config_text,
                 e->config_text[0] &&
                         e->config_text[strlen(e->config_text) - 1] != '\n'
                     ? "\n" : "",
                 (long long)e->id, q->query, text[0], text[1], goal);
        free(goal);
        /* An imported log's experiment (one scene, one query) keeps its
         * name and its setup block (the scene's robot text). */
        if (e->started && (rc = log_problem(s, e, scene_id, q)) != MPB_OK)
            break;
    }
    if (rc == MPB_OK && step != SQLITE_DONE)
        rc = mpb__store_db_fail(s, "read queries");
    sqlite3_finalize(st);
done:
    if (rc == MPB_ENOMEM)
        mpb__store_fail(s, rc, "out of memory");
    scene_problems_free(scenes, num_scenes);
    return rc;
}

char *mpb__pa_config_settings(const char *planner, const char *algorithm,
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
        /* An imported log's "k = v" as OMPL writes it, not "k  =  v". */
        char *end = eq, *value = eq + 1;
        while (end > tok && end[-1] == ' ')
            end--;
        while (*value == ' ')
            value++;
        *end = '\0';
        int len = sprintf(kv, "%s = %s", tok, value);
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

void mpb__pa_format_date(double t, char *buf, size_t n)
{
    buf[0] = '\0';
    if (isnan(t))
        return;
    time_t tt = (time_t)t;
    struct tm tm;
    if (gmtime_r(&tt, &tm) != NULL)
        strftime(buf, n, "%Y-%m-%d %H:%M:%S", &tm);
}

int mpb__pa_experiment_ids(mpb_store *s, const int64_t *ids, int num_ids,
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
            return mpb__store_fail(s, MPB_ENOMEM, "out of memory");
        for (int i = 0; i < num_ids; i++) {   /* each id once */
            int seen = 0;
            for (int j = 0; j < *n && !seen; j++)
                seen = (*out)[j] == ids[i];
            if (!seen)
                (*out)[(*n)++] = ids[i];
        }
        return MPB_OK;
    }
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT id FROM experiments ORDER BY id");
    int step, cap = 0;
    if (st == NULL)
        return MPB_EDB;
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        if (mpb__grow((void **)out, &cap, *n + 1, sizeof **out)) {
            sqlite3_finalize(st);
            return mpb__store_fail(s, MPB_ENOMEM, "out of memory");
        }
        (*out)[(*n)++] = sqlite3_column_int64(st, 0);
    }
    sqlite3_finalize(st);
    if (step != SQLITE_DONE)
        return mpb__store_db_fail(s, "list experiments");
    if (*n == 0)
        return mpb__store_fail(s, MPB_ENOTFOUND, "no experiment to export");
    return MPB_OK;
}

