/*
 * store_export_read.c - the store's reads for the exporters of interop/
 * (store_export.h): experiments, scenes, queries, configurations and
 * finished runs whole. A database made by an earlier mpbench and opened
 * read-only may lack a column a writer would add: each reader says what
 * it reads then (NULL, or nothing).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/grow.h"
#include "store/store_export.h"
#include "store/store_columns.h"
#include "store/store_internal.h"

mpb_store *mpb__store_errors_create(void)
{
    mpb_store *s = calloc(1, sizeof *s);
    if (s != NULL)
        s->fd = -1;
    return s;
}

const char *mpb__store_filename(mpb_store *s)
{
    const char *f = sqlite3_db_filename(s->db, "main");
    return f ? f : "";
}

/* A column's text, copied, NULL for NULL; *oom set when out of memory. */
static char *col_dup_or_null(sqlite3_stmt *st, int i, int *oom)
{
    if (mpb__col_is_null(st, i))
        return NULL;
    char *c = mpb__col_dup(st, i);
    *oom |= c == NULL;
    return c;
}

static int oom(mpb_store *s)
{
    return mpb__store_fail(s, MPB_ENOMEM, "out of memory");
}

/* ---- experiments ------------------------------------------------------ */

void mpb__store_exp_info_free(exp_info *e)
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
    int no_mem = 0, rc = MPB_OK;
    if (sqlite3_step(st) == SQLITE_ROW) {
        e->started = col_dup_or_null(st, 0, &no_mem);
        e->seed = col_dup_or_null(st, 1, &no_mem);
        e->cpuinfo = col_dup_or_null(st, 2, &no_mem);
        e->total_time = mpb__col_finite(st, 3);
        e->memory_limit = mpb__col_finite(st, 4);
    }
    sqlite3_finalize(st);
    if (!no_mem && mpb__store_has_column(s, "experiment_params", "name")) {
        st = mpb__store_prepare(s, "SELECT name, type, value FROM"
                                " experiment_params WHERE experiment_id = ?"
                                " ORDER BY idx");
        if (st == NULL)
            return MPB_EDB;
        sqlite3_bind_int64(st, 1, e->id);
        int cap = 0, step;
        while (!no_mem && (step = sqlite3_step(st)) == SQLITE_ROW) {
            if (mpb__grow((void **)&e->params, &cap, e->num_params + 1,
                          sizeof *e->params)) {
                no_mem = 1;
                break;
            }
            exp_param *p = &e->params[e->num_params++];
            *p = (exp_param){mpb__col_dup(st, 0), mpb__col_dup(st, 1), mpb__col_dup(st, 2)};
            no_mem |= !p->name || !p->type || !p->value;
        }
        if (!no_mem && step != SQLITE_DONE)
            rc = mpb__store_db_fail(s, "read experiment parameters");
        sqlite3_finalize(st);
    }
    return no_mem ? oom(s) : rc;
}

int mpb__store_exp_info_read(mpb_store *s, int64_t id, exp_info *e)
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
        e->name = mpb__col_dup(st, 0);
        e->config_text = mpb__col_dup(st, 1);
        e->host = mpb__col_dup(st, 2);
        e->version = mpb__col_dup(st, 3);
        e->runs_per_query = sqlite3_column_int(st, 4);
        e->time_limit = mpb__col_finite(st, 5);
        e->created = mpb__col_finite(st, 6);
        if (!e->name || !e->config_text || !e->host || !e->version)
            rc = oom(s);
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

int mpb__store_experiment_ids(mpb_store *s, const int64_t *ids, int num_ids,
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
            return oom(s);
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
            return oom(s);
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

int mpb__store_experiment_completion(mpb_store *s, int64_t id, char **text,
                                     size_t *len, int64_t *runs,
                                     int64_t *done)
{
    *text = NULL;
    *len = 0;
    *runs = *done = 0;
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT config_text,"
        " (SELECT count(*) FROM runs WHERE experiment_id = ?1),"
        " (SELECT count(*) FROM runs WHERE experiment_id = ?1"
        "  AND state = 'done')"
        " FROM experiments WHERE id = ?1");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, id);
    int rc = MPB_OK, step = sqlite3_step(st);
    if (step == SQLITE_ROW) {
        const void *t = sqlite3_column_blob(st, 0);
        size_t n = (size_t)sqlite3_column_bytes(st, 0);
        if (t != NULL) {
            if ((*text = malloc(n + 1)) == NULL) {
                rc = oom(s);
            } else {
                memcpy(*text, t, n);
                (*text)[n] = '\0';
                *len = n;
            }
        }
        *runs = sqlite3_column_int64(st, 1);
        *done = sqlite3_column_int64(st, 2);
    } else if (step != SQLITE_DONE) {
        rc = mpb__store_db_fail(s, "read experiment");
    }
    sqlite3_finalize(st);
    return rc;
}

int mpb__store_experiment_imported(mpb_store *s, int64_t id, int *yes)
{
    sqlite3_stmt *st = mpb__store_prepare(s, "SELECT 1 FROM scenes WHERE"
                                          " experiment_id = ?1 AND"
                                          " robot_format = 'ompl-log'");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, id);
    int step = sqlite3_step(st);
    sqlite3_finalize(st);
    if (step != SQLITE_ROW && step != SQLITE_DONE)
        return mpb__store_db_fail(s, "read scenes");
    *yes = step == SQLITE_ROW;
    return MPB_OK;
}

/* ---- scenes, queries, configurations ---------------------------------- */

int mpb__store_each_scene(mpb_store *s, int64_t experiment_id,
                          int (*fn)(void *ud, int64_t id, const char *name),
                          void *ud)
{
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT id, name FROM scenes WHERE experiment_id = ?1 ORDER BY id");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, experiment_id);
    int step, rc = MPB_OK;
    while (rc == MPB_OK && (step = sqlite3_step(st)) == SQLITE_ROW)
        rc = fn(ud, sqlite3_column_int64(st, 0), mpb__col_text_or_empty(st, 1));
    if (rc == MPB_OK && step != SQLITE_DONE)
        rc = mpb__store_db_fail(s, "read scenes");
    sqlite3_finalize(st);
    return rc;
}

int mpb__store_scene_robot(mpb_store *s, int64_t scene_id, char **robot)
{
    *robot = NULL;
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT robot FROM scenes WHERE id = ?");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, scene_id);
    int rc = MPB_OK, step = sqlite3_step(st);
    if (step == SQLITE_ROW && (*robot = mpb__col_dup(st, 0)) == NULL)
        rc = oom(s);
    else if (step != SQLITE_ROW && step != SQLITE_DONE)
        rc = mpb__store_db_fail(s, "read scenes");
    sqlite3_finalize(st);
    return rc;
}

int mpb__store_each_done_query(mpb_store *s, int64_t experiment_id,
                               int (*fn)(void *ud, const mpb__done_query *q),
                               void *ud)
{
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
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, experiment_id);
    int step, rc = MPB_OK;
    while (rc == MPB_OK && (step = sqlite3_step(st)) == SQLITE_ROW) {
        mpb__done_query q = {
            .id = sqlite3_column_int64(st, 0),
            .name = mpb__col_text_or_empty(st, 1),
            .scene_id = sqlite3_column_int64(st, 2),
            .runs = sqlite3_column_int(st, 3),
            .total_time = sqlite3_column_double(st, 4),
            .joint_names = mpb__col_text_or_empty(st, 5),
            .start = mpb__col_text_or_empty(st, 6),
            .goal_kind = mpb__col_text_or_empty(st, 7),
            .goal_joints = mpb__col_text_or_empty(st, 8),
            .goal_tolerance = mpb__col_text_or_empty(st, 9),
            .goal_link = mpb__col_text_or_empty(st, 10),
            .goal_region = mpb__col_text_or_empty(st, 11),
        };
        rc = fn(ud, &q);
    }
    if (rc == MPB_OK && step != SQLITE_DONE)
        rc = mpb__store_db_fail(s, "read queries");
    sqlite3_finalize(st);
    return rc;
}

int mpb__store_each_config_count(mpb_store *s, int64_t experiment_id,
                                 int64_t query_id,
                                 int (*fn)(void *ud, int64_t config_id,
                                           long runs),
                                 void *ud)
{
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT planner_config_id, count(*) FROM runs WHERE experiment_id = ?1"
        " AND query_id = ?2 AND state = 'done' GROUP BY planner_config_id"
        " ORDER BY planner_config_id");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, experiment_id);
    sqlite3_bind_int64(st, 2, query_id);
    int step, rc = MPB_OK;
    while (rc == MPB_OK && (step = sqlite3_step(st)) == SQLITE_ROW)
        rc = fn(ud, sqlite3_column_int64(st, 0),
                (long)sqlite3_column_int64(st, 1));
    if (rc == MPB_OK && step != SQLITE_DONE)
        rc = mpb__store_db_fail(s, "count runs");
    sqlite3_finalize(st);
    return rc;
}

int mpb__store_config_read(mpb_store *s, int64_t config_id, char **name,
                           char **planner, char **algorithm, char **params)
{
    *name = *planner = *algorithm = *params = NULL;
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT name, planner, algorithm, params FROM planner_configs"
        " WHERE id = ?");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, config_id);
    int rc = MPB_OK, step = sqlite3_step(st);
    if (step == SQLITE_ROW) {
        *name = mpb__col_dup(st, 0);
        *planner = mpb__col_dup(st, 1);
        *algorithm = mpb__col_dup(st, 2);
        *params = mpb__col_dup(st, 3);
        if (!*name || !*planner || !*algorithm || !*params) {
            free(*name);
            free(*planner);
            free(*algorithm);
            free(*params);
            *name = *planner = *algorithm = *params = NULL;
            rc = oom(s);
        }
    } else if (step == SQLITE_DONE) {
        rc = mpb__store_fail(s, MPB_ENOTFOUND, "no planner configuration %lld",
                             (long long)config_id);
    } else {
        rc = mpb__store_db_fail(s, "read a planner configuration");
    }
    sqlite3_finalize(st);
    return rc;
}

int mpb__store_each_run_name(mpb_store *s, int64_t experiment_id,
                             mpb__run_names which,
                             int (*fn)(void *ud, const char *name), void *ud)
{
    static const char *const sql[] = {
        [MPB__NAMES_METRICS] =
            "SELECT DISTINCT m.name FROM runs r JOIN metrics m"
            " ON m.run_id = r.id WHERE r.experiment_id = ?1"
            " AND r.state = 'done'",
        [MPB__NAMES_MID_STAGES] =
            "SELECT st.name FROM runs r JOIN stages st ON st.run_id = r.id"
            " WHERE r.experiment_id = ?1 AND r.state = 'done' AND st.idx > 0"
            " AND st.name IS NOT coalesce(r.final_stage, '')"
            " GROUP BY st.name ORDER BY min(st.idx), st.name",
        [MPB__NAMES_VALUES] =
            "SELECT DISTINCT v.name FROM runs r JOIN planner_values v"
            " ON v.run_id = r.id WHERE r.experiment_id = ?1"
            " AND r.state = 'done' ORDER BY v.name",
        [MPB__NAMES_PROGRESS] =
            "SELECT DISTINCT p.name FROM runs r JOIN progress p"
            " ON p.run_id = r.id WHERE r.experiment_id = ?1"
            " AND r.state = 'done' ORDER BY p.name",
    };
    if ((unsigned)which >= sizeof sql / sizeof sql[0])
        return mpb__store_fail(s, MPB_EINVAL, "no such list of names");
    sqlite3_stmt *st = mpb__store_prepare(s, sql[which]);
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, experiment_id);
    int step, rc = MPB_OK;
    while (rc == MPB_OK && (step = sqlite3_step(st)) == SQLITE_ROW) {
        const char *name = mpb__col_text(st, 0);
        if (name != NULL)
            rc = fn(ud, name);
    }
    if (rc == MPB_OK && step != SQLITE_DONE)
        rc = mpb__store_db_fail(s, "read names");
    sqlite3_finalize(st);
    return rc;
}

int mpb__store_each_log_property(mpb_store *s, int64_t experiment_id,
                                 int progress,
                                 int (*fn)(void *ud, const char *name,
                                           const char *type),
                                 void *ud)
{
    if (!mpb__store_has_column(s, "log_properties", "name"))
        return MPB_OK;
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT p.name, p.type FROM log_properties p JOIN planner_configs c"
        " ON c.id = p.planner_config_id WHERE c.experiment_id = ?1"
        " AND p.progress = ?2 ORDER BY c.id, p.idx");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, experiment_id);
    sqlite3_bind_int(st, 2, progress);
    int step, rc = MPB_OK;
    while (rc == MPB_OK && (step = sqlite3_step(st)) == SQLITE_ROW) {
        const char *name = mpb__col_text(st, 0);
        if (name != NULL)
            rc = fn(ud, name, mpb__col_text(st, 1));
    }
    if (rc == MPB_OK && step != SQLITE_DONE)
        rc = mpb__store_db_fail(s, "read a log's properties");
    sqlite3_finalize(st);
    return rc;
}

/* ---- finished runs, whole ---------------------------------------------- */

struct mpb__run_cursor {
    mpb_store    *s;
    sqlite3_stmt *runs, *stages, *metrics, *values, *samples;
    mpb__done_run run;
    int           stage_cap, metric_cap, value_cap, sample_cap;
};

static void clear_run(mpb__run_cursor *c)
{
    mpb__done_run *r = &c->run;
    free(r->status);
    free(r->final_stage);
    for (int i = 0; i < r->num_stages; i++)
        free(r->stages[i].name);
    for (int i = 0; i < r->num_metrics; i++) {
        free(r->metrics[i].stage);
        free(r->metrics[i].name);
    }
    for (int i = 0; i < r->num_values; i++)
        free(r->values[i].name);
    for (int i = 0; i < r->num_samples; i++)
        free(r->samples[i].name);
    r->status = r->final_stage = NULL;
    r->num_stages = r->num_metrics = r->num_values = r->num_samples = 0;
}

void mpb__run_cursor_close(mpb__run_cursor *c)
{
    if (c == NULL)
        return;
    clear_run(c);
    sqlite3_finalize(c->runs);
    sqlite3_finalize(c->stages);
    sqlite3_finalize(c->metrics);
    sqlite3_finalize(c->values);
    sqlite3_finalize(c->samples);
    free(c->run.stages);
    free(c->run.metrics);
    free(c->run.values);
    free(c->run.samples);
    free(c);
}

int mpb__run_cursor_open(mpb_store *s, int64_t experiment_id,
                         int64_t query_id, mpb__run_cursor **out)
{
    mpb__run_cursor *c = calloc(1, sizeof *c);
    *out = NULL;
    if (c == NULL)
        return oom(s);
    c->s = s;
#define RUNS_SQL(verify)                                                    \
        "SELECT r.id, r.planner_config_id, r.query_id, r.status, r.success,"\
        " r.claimed_success, r.time_total, r.time_raw, r.time_other,"      \
        " r.wall_time, r.final_stage, " verify                              \
        " FROM runs r JOIN queries q ON q.id = r.query_id"                 \
        " WHERE r.experiment_id = ?1 AND r.state = 'done'"                 \
        " AND (?2 = 0 OR r.query_id = ?2)"                                 \
        " ORDER BY q.scene_id, r.query_id, r.planner_config_id, r.repetition"
    /* Without runs.memory, or runs.verify_time too: NULL. */
    static const char *const runs_sql[4] = {
        RUNS_SQL("r.verify_time, r.memory"), RUNS_SQL("r.verify_time, NULL"),
        RUNS_SQL("NULL, r.memory"), RUNS_SQL("NULL, NULL"),
    };
    c->runs = mpb__store_prepare(s, runs_sql[
        2 * !mpb__store_has_column(s, "runs", "verify_time") +
        !mpb__store_has_column(s, "runs", "memory")]);
#undef RUNS_SQL
    c->stages = mpb__store_prepare(s,
        "SELECT name, time, num_waypoints, valid FROM stages WHERE run_id = ?"
        " ORDER BY idx");
    c->metrics = mpb__store_prepare(s,
        "SELECT stage, name, value FROM metrics WHERE run_id = ?");
    /* Without planner_values.exact: the REAL only. */
    c->values = mpb__store_prepare(s,
        mpb__store_has_column(s, "planner_values", "exact")
            ? "SELECT name, value, exact FROM planner_values WHERE run_id = ?"
            : "SELECT name, value, NULL FROM planner_values WHERE run_id = ?");
    c->samples = mpb__store_prepare(s,
        "SELECT time, name, value FROM progress WHERE run_id = ?"
        " ORDER BY seq");
    if (!c->runs || !c->stages || !c->metrics || !c->values || !c->samples) {
        mpb__run_cursor_close(c);
        return MPB_EDB;
    }
    sqlite3_bind_int64(c->runs, 1, experiment_id);
    sqlite3_bind_int64(c->runs, 2, query_id);
    *out = c;
    return MPB_OK;
}

/* Step st (bound to the run) through its rows: 0, MPB_ENOMEM from a
 * row, or MPB_EDB. */
#define EACH_ROW(c, st, run_id, what, body)                                 \
    do {                                                                    \
        int step_;                                                          \
        sqlite3_reset(st);                                                  \
        sqlite3_bind_int64(st, 1, run_id);                                  \
        while ((step_ = sqlite3_step(st)) == SQLITE_ROW) {                  \
            body                                                            \
        }                                                                   \
        if (step_ != SQLITE_DONE)                                           \
            return mpb__store_db_fail((c)->s, what);                        \
    } while (0)

static int read_parts(mpb__run_cursor *c, int64_t run_id)
{
    mpb__done_run *r = &c->run;
    sqlite3_stmt *st = c->stages;
    EACH_ROW(c, st, run_id, "read stages", {
        if (mpb__grow((void **)&r->stages, &c->stage_cap, r->num_stages + 1,
                      sizeof *r->stages))
            return MPB_ENOMEM;
        mpb__done_stage *d = &r->stages[r->num_stages];
        if ((d->name = mpb__col_dup(st, 0)) == NULL)
            return MPB_ENOMEM;
        d->time = mpb__col_finite(st, 1);
        d->num_waypoints = sqlite3_column_int(st, 2);
        d->valid = sqlite3_column_int(st, 3) != 0;
        r->num_stages++;
    });
    st = c->metrics;
    EACH_ROW(c, st, run_id, "read metrics", {
        if (mpb__grow((void **)&r->metrics, &c->metric_cap,
                      r->num_metrics + 1, sizeof *r->metrics))
            return MPB_ENOMEM;
        mpb__done_metric *m = &r->metrics[r->num_metrics++];
        m->stage = mpb__col_dup(st, 0);
        m->name = mpb__col_dup(st, 1);
        if (m->stage == NULL || m->name == NULL)
            return MPB_ENOMEM;
        m->value = mpb__col_finite(st, 2);
    });
    st = c->values;
    EACH_ROW(c, st, run_id, "read planner values", {
        if (mpb__grow((void **)&r->values, &c->value_cap, r->num_values + 1,
                      sizeof *r->values))
            return MPB_ENOMEM;
        mpb__done_value *v = &r->values[r->num_values];
        if ((v->name = mpb__col_dup(st, 0)) == NULL)
            return MPB_ENOMEM;
        v->value = mpb__col_finite(st, 1);
        v->is_int = sqlite3_column_type(st, 2) == SQLITE_INTEGER;
        v->exact = sqlite3_column_int64(st, 2);
        r->num_values++;
    });
    st = c->samples;
    EACH_ROW(c, st, run_id, "read progress", {
        if (mpb__grow((void **)&r->samples, &c->sample_cap,
                      r->num_samples + 1, sizeof *r->samples))
            return MPB_ENOMEM;
        mpb__done_sample *p = &r->samples[r->num_samples++];
        int no_mem = 0;
        p->time = mpb__col_finite(st, 0);
        p->name = col_dup_or_null(st, 1, &no_mem);
        p->value = mpb__col_finite(st, 2);
        if (no_mem)
            return MPB_ENOMEM;
    });
    return MPB_OK;
}
#undef EACH_ROW

int mpb__run_cursor_next(mpb__run_cursor *c, const mpb__done_run **out)
{
    int step = sqlite3_step(c->runs), rc, no_mem = 0;
    if (step == SQLITE_DONE)
        return 0;
    if (step != SQLITE_ROW)
        return mpb__store_db_fail(c->s, "read runs");
    clear_run(c);
    sqlite3_stmt *st = c->runs;
    mpb__done_run *r = &c->run;
    r->id = sqlite3_column_int64(st, 0);
    r->config_id = sqlite3_column_int64(st, 1);
    r->query_id = sqlite3_column_int64(st, 2);
    r->status = col_dup_or_null(st, 3, &no_mem);
    r->success = mpb__col_finite(st, 4);
    r->claimed_success = mpb__col_finite(st, 5);
    r->time_total = mpb__col_finite(st, 6);
    r->time_raw = mpb__col_finite(st, 7);
    r->time_other = mpb__col_finite(st, 8);
    r->wall_time = mpb__col_finite(st, 9);
    r->final_stage = col_dup_or_null(st, 10, &no_mem);
    r->verify_time = mpb__col_finite(st, 11);
    r->memory = mpb__col_finite(st, 12);
    if (no_mem)
        return oom(c->s);
    if ((rc = read_parts(c, r->id)) != MPB_OK)
        return rc == MPB_ENOMEM ? oom(c->s) : rc;
    *out = r;
    return 1;
}
