/*
 * store_export.c - an experiment's finished runs into the SQLite database
 * that OMPL's ompl_benchmark_statistics.py builds and Planner Arena reads
 * (mpb_store_export_planner_arena(); store_pa.h has the parts it shares
 * with the log writers): a Planner Arena experiment per query, a row of
 * run properties per run, its progress samples, the planner
 * configurations as OMPL's script stores them.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/grow.h"
#include "interop/store_pa.h"

static void bind_value(sqlite3_stmt *st, int i, const prop *p, double v)
{
    mpb__pa_bind_number(st, i, strcmp(p->type, "REAL") == 0, v);
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
    char *name = NULL, *planner = NULL, *algorithm = NULL, *params = NULL;
    int rc = mpb__store_config_read(o->s, config_id, &name, &planner,
                                    &algorithm, &params);
    if (rc != MPB_OK)
        return rc;
    char *settings = mpb__pa_config_settings(planner, algorithm, params);
    free(planner);
    free(algorithm);
    free(params);
    if (settings == NULL) {
        rc = mpb__store_fail(o->s, MPB_ENOMEM, "out of memory");
        goto done;
    }
    sqlite3_stmt *find = NULL, *add = NULL;
    if (sqlite3_prepare_v2(o->db, "SELECT id FROM plannerConfigs"
                           " WHERE name = ? AND settings = ?", -1, &find,
                           NULL) != SQLITE_OK) {
        rc = mpb__pa_fail(o, "find a planner configuration");
        goto done;
    }
    sqlite3_bind_text(find, 1, name, -1, SQLITE_STATIC);
    sqlite3_bind_text(find, 2, settings, -1, SQLITE_STATIC);
    if (sqlite3_step(find) == SQLITE_ROW) {
        *out = sqlite3_column_int64(find, 0);
    } else if (sqlite3_prepare_v2(o->db, "INSERT INTO plannerConfigs"
                                  " (name, settings) VALUES (?, ?)", -1, &add,
                                  NULL) != SQLITE_OK) {
        rc = mpb__pa_fail(o, "add a planner configuration");
    } else {
        sqlite3_bind_text(add, 1, name, -1, SQLITE_STATIC);
        sqlite3_bind_text(add, 2, settings, -1, SQLITE_STATIC);
        if (sqlite3_step(add) != SQLITE_DONE)
            rc = mpb__pa_fail(o, "add a planner configuration");
        *out = sqlite3_last_insert_rowid(o->db);
        o->counts.planner_configs++;
    }
    sqlite3_finalize(find);
    sqlite3_finalize(add);
    if (rc == MPB_OK) {
        if (mpb__grow((void **)&o->config_map, &o->configs_cap,
                      o->num_configs + 1, 2 * sizeof *o->config_map)) {
            rc = mpb__store_fail(o->s, MPB_ENOMEM, "out of memory");
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

/* 1 for the parameters every export writes (mpb__pa_exp_params). */
static int reserved_column(const char *column)
{
    for (int i = 0; i < MPB__PA_NUM_EXP_PARAMS; i++)
        if (mpb__pa_same_column(column, mpb__pa_exp_params[i][0]))
            return 1;
    return 0;
}

static int by_name(const void *a, const void *b)
{
    return strcmp(((const prop *)a)->name, ((const prop *)b)->name);
}

/* The columns of an imported log's experiment properties, named and
 * added (in the order of their names) as OMPL's script adds them. */
static int param_columns(pa_out *o, const exp_info *e)
{
    prop_list l = {.v = calloc((size_t)e->num_params + 1, sizeof(prop))};
    int rc = l.v ? MPB_OK : MPB_ENOMEM;
    for (int i = 0; rc == MPB_OK && i < e->num_params; i++) {
        char *c = mpb__pa_param_column(e->params[i].name);
        if (c == NULL)
            rc = MPB_ENOMEM;
        else if (reserved_column(c))
            free(c);
        else
            l.v[l.n++] = (prop){.name = c, .type = e->params[i].type};
    }
    if (rc == MPB_OK) {
        if (l.n > 1)
            qsort(l.v, (size_t)l.n, sizeof *l.v, by_name);
        rc = mpb__pa_ensure_columns(o, "experiments", &l, 0);
    } else {
        mpb__store_fail(o->s, rc, "out of memory");
    }
    for (int i = 0; i < l.n; i++)
        free(l.v[i].name);
    free(l.v);
    return rc;
}

/* Their values in the experiments row id, as text: the column's affinity
 * makes them what it makes the script's. */
static int param_values(pa_out *o, const exp_info *e, int64_t id)
{
    int rc = MPB_OK;
    for (int i = 0; rc == MPB_OK && i < e->num_params; i++) {
        char *c = mpb__pa_param_column(e->params[i].name), sql[600];
        if (c == NULL)
            return mpb__store_fail(o->s, MPB_ENOMEM, "out of memory");
        int skip = reserved_column(c) || strlen(c) > 500;
        snprintf(sql, sizeof sql, "UPDATE experiments SET \"%s\" = ?"
                 " WHERE id = ?", c);
        free(c);
        if (skip)
            continue;
        sqlite3_stmt *st;
        if (sqlite3_prepare_v2(o->db, sql, -1, &st, NULL) != SQLITE_OK)
            return mpb__pa_fail(o, "prepare a parameter");
        sqlite3_bind_text(st, 1, e->params[i].value, -1, SQLITE_STATIC);
        sqlite3_bind_int64(st, 2, id);
        if (sqlite3_step(st) != SQLITE_DONE)
            rc = mpb__pa_fail(o, "write a parameter");
        sqlite3_finalize(st);
    }
    return rc;
}

/* One mpbench experiment into the open database, whose experiments rows
 * up to id before were there before this export began. */
static int export_experiment(pa_out *o, int64_t experiment_id,
                             int64_t before)
{
    exp_info e = {0};
    prop_list props = {0}, progress = {0};
    pa_query_list queries = {0};
    sqlite3_stmt *add_exp = NULL, *add_run = NULL, *add_progress = NULL,
                 *present = NULL;
    int64_t *pa_exp = NULL;
    pa_walker *w = NULL;
    int rc;

    if ((rc = mpb__store_exp_info_read(o->s, experiment_id, &e)) ||
        (rc = mpb__pa_experiment_props(o->s, experiment_id, &props, &progress)) ||
        (rc = mpb__pa_read_queries(o->s, &e, &queries)) ||
        (rc = mpb__pa_ensure_columns(o, "runs", &props, 0)) ||
        (rc = mpb__pa_ensure_columns(o, "progress", &progress, 1)))
        goto done;
    mpb__pa_one_word(e.name);
    if (queries.n == 0)
        goto done;      /* no finished run: nothing to show */

    /* A Planner Arena experiment per query with finished runs. */
    if (sqlite3_prepare_v2(o->db,
            "INSERT INTO experiments (name, totaltime, timelimit, memorylimit,"
            " runcount, version, hostname, cpuinfo, date, seed, setup, query,"
            " mpbench_experiment) VALUES (?1, ?2, ?3, ?11, ?4, ?5, ?6, ?12,"
            " ?7, ?13, ?8, ?9, ?10)", -1, &add_exp, NULL) != SQLITE_OK) {
        rc = mpb__pa_fail(o, "prepare experiments");
        goto done;
    }
    if ((pa_exp = calloc((size_t)queries.n, sizeof *pa_exp)) == NULL) {
        rc = mpb__store_fail(o->s, MPB_ENOMEM, "out of memory");
        goto done;
    }
    char fdate[32];
    mpb__pa_format_date(e.created, fdate, sizeof fdate);
    /* An imported log's own date, as it had it. */
    const char *date = e.started ? e.started : fdate;
    if ((rc = param_columns(o, &e)) != MPB_OK)
        goto done;
    /* A log's own query and mpbench experiment, if it had them (an
     * exported log imported again). */
    const char *query = mpb__pa_exp_param(&e, "query");
    const char *mpbexp = mpb__pa_exp_param(&e, "mpbench_experiment");
    if (sqlite3_prepare_v2(o->db,
            "SELECT 1 FROM experiments WHERE name = ?1 AND query IS ?2 AND"
            " date IS ?3 AND runcount IS ?4 AND hostname IS ?5 AND id <= ?6",
            -1, &present, NULL) != SQLITE_OK) {
        rc = mpb__pa_fail(o, "prepare experiments");
        goto done;
    }
    for (int i = 0; i < queries.n; i++) {
        const pa_query *q = &queries.v[i];
        /* Exported before this export (same name, query, start, run
         * count and host): kept as it is, its runs not added again. Rows
         * this export wrote are other scenes or experiments. */
        sqlite3_reset(present);
        sqlite3_bind_text(present, 1, q->problem, -1, SQLITE_STATIC);
        sqlite3_bind_text(present, 2, query ? query : q->query, -1,
                          SQLITE_STATIC);
        sqlite3_bind_text(present, 3, date, -1, SQLITE_STATIC);
        sqlite3_bind_int(present, 4, e.runs_per_query);
        sqlite3_bind_text(present, 5, e.host, -1, SQLITE_STATIC);
        sqlite3_bind_int64(present, 6, before);
        int step = sqlite3_step(present);
        if (step == SQLITE_ROW) {
            pa_exp[i] = 0;
            o->counts.skipped++;
            continue;
        }
        if (step != SQLITE_DONE) {
            rc = mpb__pa_fail(o, "find an experiment");
            goto done;
        }
        sqlite3_reset(add_exp);
        sqlite3_bind_text(add_exp, 1, q->problem, -1, SQLITE_STATIC);
        sqlite3_bind_double(add_exp, 2, isnan(e.total_time) ? q->total_time
                                                            : e.total_time);
        if (isnan(e.time_limit))
            sqlite3_bind_null(add_exp, 3);
        else
            sqlite3_bind_double(add_exp, 3, e.time_limit);
        sqlite3_bind_int(add_exp, 4, e.runs_per_query);
        /* An imported log's "OMPL version " without a number: the
         * script's "OMPL version". */
        if (e.started && strchr(e.version, ' ') == NULL)
            sqlite3_bind_text(add_exp, 5, sqlite3_mprintf("%s version",
                              mpb__pa_version_of(&e)), -1, sqlite3_free);
        else
            sqlite3_bind_text(add_exp, 5, mpb__pa_version_of(&e), -1,
                              SQLITE_STATIC);
        sqlite3_bind_text(add_exp, 6, e.host, -1, SQLITE_STATIC);
        sqlite3_bind_text(add_exp, 7, date, -1, SQLITE_STATIC);
        sqlite3_bind_text(add_exp, 8, q->setup, -1, SQLITE_STATIC);
        sqlite3_bind_text(add_exp, 9, query ? query : q->query, -1,
                          SQLITE_STATIC);
        if (mpbexp)
            sqlite3_bind_text(add_exp, 10, mpbexp, -1, SQLITE_STATIC);
        else
            sqlite3_bind_int64(add_exp, 10, e.id);
        if (isnan(e.memory_limit))
            sqlite3_bind_null(add_exp, 11);
        else
            sqlite3_bind_double(add_exp, 11, e.memory_limit);
        sqlite3_bind_text(add_exp, 12, e.cpuinfo, -1, SQLITE_STATIC);
        sqlite3_bind_text(add_exp, 13, e.seed, -1, SQLITE_STATIC);
        if (sqlite3_step(add_exp) != SQLITE_DONE) {
            rc = mpb__pa_fail(o, "add an experiment");
            goto done;
        }
        pa_exp[i] = sqlite3_last_insert_rowid(o->db);
        if ((rc = param_values(o, &e, pa_exp[i])) != MPB_OK)
            goto done;
        o->counts.experiments++;
    }

    if ((rc = mpb__pa_prepare_rows(o, "INSERT", "runs",
                                   "experimentid,plannerid", "?,?", &props, 1,
                                   &add_run)) ||
        (rc = mpb__pa_prepare_rows(o, "INSERT OR IGNORE", "progress",
                                   "runid", "?", &progress, 1, &add_progress)) ||
        (rc = mpb__pa_walker_open(&w, o->s, experiment_id, 0, &props,
                                  &progress)))
        goto done;
    run_view rv = {0};
    int qi = 0;
    while ((rc = mpb__pa_walker_next(w, &rv)) == 1) {
        int64_t pid = 0;
        while (qi < queries.n && queries.v[qi].query_id != rv.query_id)
            qi++;
        if (qi == queries.n) {
            for (qi = 0; qi < queries.n; qi++)
                if (queries.v[qi].query_id == rv.query_id)
                    break;
            if (qi == queries.n) {
                rc = mpb__store_fail(o->s, MPB_EINVAL, "run %lld "
                                     "has no query", (long long)rv.run_id);
                goto done;
            }
        }
        if (pa_exp[qi] == 0)
            continue;   /* its query was there already */
        if ((rc = planner_id(o, rv.config_id, &pid)) != MPB_OK)
            goto done;
        sqlite3_reset(add_run);
        sqlite3_bind_int64(add_run, 1, pa_exp[qi]);
        sqlite3_bind_int64(add_run, 2, pid);
        for (int k = 0; k < props.n; k++)
            if (rv.is_int[k])   /* an INTEGER column keeps it exactly */
                sqlite3_bind_int64(add_run, 3 + k, rv.ints[k]);
            else
                bind_value(add_run, 3 + k, &props.v[k], rv.values[k]);
        if (sqlite3_step(add_run) != SQLITE_DONE) {
            rc = mpb__pa_fail(o, "add a run");
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
                rc = mpb__pa_fail(o, "add progress");
                goto done;
            }
            o->counts.progress += sqlite3_changes(o->db);
        }
    }
done:
    mpb__pa_walker_close(w);
    sqlite3_finalize(add_exp);
    sqlite3_finalize(present);
    sqlite3_finalize(add_run);
    sqlite3_finalize(add_progress);
    free(pa_exp);
    mpb__pa_queries_free(&queries);
    mpb__pa_props_free(&props);
    mpb__pa_props_free(&progress);
    mpb__store_exp_info_free(&e);
    return rc;
}

/* MPB_OK if o->db has the tables of a Planner Arena database, MPB_EINVAL
 * (nothing written) if not. */
static int is_planner_arena(pa_out *o)
{
    static const char *const tables[] = {"experiments", "plannerConfigs",
                                         "runs"};
    sqlite3_stmt *st;
    if (sqlite3_prepare_v2(o->db, "SELECT 1 FROM sqlite_master WHERE"
                           " type = 'table' AND name = ?", -1, &st,
                           NULL) != SQLITE_OK)
        return mpb__pa_fail(o, "read its tables");
    int rc = MPB_OK;
    for (size_t i = 0; i < sizeof tables / sizeof *tables && !rc; i++) {
        sqlite3_reset(st);
        sqlite3_bind_text(st, 1, tables[i], -1, SQLITE_STATIC);
        int step = sqlite3_step(st);
        if (step == SQLITE_DONE)
            rc = mpb__store_fail(o->s, MPB_EINVAL, "%s is no Planner Arena "
                                 "database (no table %s)", o->path,
                                 tables[i]);
        else if (step != SQLITE_ROW)
            rc = mpb__pa_fail(o, "read its tables");
    }
    sqlite3_finalize(st);
    return rc;
}

/* The largest id in o->db's experiments (0 if none) into *out: rows
 * added later have larger ids. */
static int last_experiment(pa_out *o, int64_t *out)
{
    sqlite3_stmt *st;
    int rc = MPB_OK;
    if (sqlite3_prepare_v2(o->db, "SELECT coalesce(max(id), 0) FROM"
                           " experiments", -1, &st, NULL) != SQLITE_OK ||
        sqlite3_step(st) != SQLITE_ROW)
        rc = mpb__pa_fail(o, "read experiments");
    else
        *out = sqlite3_column_int64(st, 0);
    sqlite3_finalize(st);
    return rc;
}

/* Whether out (a stat of the output) is the file of the store s itself. */
/*
 * An experiment imported from an OMPL (or MoveIt) log and nothing else:
 * the log itself, kept as its file (experiments.config_text), parsed into
 * *out when it reads as one and its runs are every run of the experiment,
 * all finished; else *out is NULL and the experiment is mpbench's. Such
 * an experiment goes out as the log said, cell for cell, as OMPL's script
 * (and mpb import -p) writes it: its planners' names and settings, its
 * columns in its order, its enums; nothing mpbench did not measure.
 */
static int imported_log(pa_out *o, int64_t id, mpb_ompl_log **out)
{
    *out = NULL;
    char *text = NULL;
    size_t len = 0;
    int64_t runs = 0, done = 0;
    int rc = mpb__store_experiment_completion(o->s, id, &text, &len, &runs,
                                              &done);
    if (rc == MPB_OK) {
        mpb_ompl_log *log = NULL;
        if (text && runs == done &&
            (strncmp(text, "OMPL version", 12) == 0 ||
             strncmp(text, "MoveIt", 6) == 0)) {
            rc = mpb_ompl_log_open(text, len, &log, NULL, 0);
            if (rc == MPB_EPARSE)
                rc = MPB_OK;        /* not a log after all */
        }
        long total = 0;
        for (int i = 0; log && i < log->num_planners; i++)
            total += log->planners[i].num_runs;
        if (log && total == runs)
            *out = log;
        else
            mpb_ompl_log_close(log);
    }
    free(text);
    if (rc == MPB_ENOMEM)
        return mpb__store_fail(o->s, rc, "out of memory");
    return rc;
}

/* 1 if the log was exported before this export (an experiment of its
 * name, date and host among the first up to before). */
static int log_exported(pa_out *o, const mpb_ompl_log *log, int64_t before)
{
    sqlite3_stmt *st;
    if (before == 0 ||
        sqlite3_prepare_v2(o->db, "SELECT 1 FROM experiments WHERE id <= ?1"
                           " AND name IS ?2 AND date IS ?3 AND hostname IS ?4",
                           -1, &st, NULL) != SQLITE_OK)
        return 0;
    sqlite3_bind_int64(st, 1, before);
    sqlite3_bind_text(st, 2, log->experiment, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 3, log->date, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 4, log->host, -1, SQLITE_STATIC);
    int found = sqlite3_step(st) == SQLITE_ROW;
    sqlite3_finalize(st);
    return found;
}

static int is_store_file(mpb_store *s, const struct stat *out)
{
    const char *mine = mpb__store_filename(s);
    struct stat sb;
    return mine && *mine && stat(mine, &sb) == 0 &&
           sb.st_dev == out->st_dev && sb.st_ino == out->st_ino;
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
        return mpb__store_fail(s, MPB_EINVAL, "bad arguments");
    int exists = stat(path, &sb) == 0;
    if (exists && is_store_file(s, &sb))
        return mpb__store_fail(s, MPB_EINVAL, "%s is the database being "
                               "exported", path);
    if (exists && !(flags & MPB_EXPORT_APPEND))
        return mpb__store_fail(s, MPB_EEXISTS, "%s exists", path);
    if (!exists && errno != ENOENT)
        return mpb__store_fail(s, MPB_EIO, "%s: %s", path,
                               strerror(errno));
    if ((rc = mpb__store_experiment_ids(s, ids, num_ids, &exps, &num_exps)))
        return rc;
    if (sqlite3_open_v2(path, &o.db, SQLITE_OPEN_READWRITE |
                        (exists ? 0 : SQLITE_OPEN_CREATE), NULL) != SQLITE_OK) {
        rc = mpb__store_fail(s, MPB_EIO, "cannot open %s: %s", path,
                             o.db ? sqlite3_errmsg(o.db) : "out of memory");
        goto done;
    }
    created = !exists;
    sqlite3_busy_timeout(o.db, 5000);
    if (exists && (rc = is_planner_arena(&o)) != MPB_OK)
        goto done;
    if ((rc = mpb__pa_exec(&o, "PRAGMA foreign_keys = ON", "configure")) ||
        (rc = mpb__pa_begin(&o, 0)))
        goto done;
    /* Only what was there before can be exported already. */
    int64_t before = 0;
    if ((rc = last_experiment(&o, &before)))
        goto done;
    int mine = 0;       /* mpbench's enum and columns are there */
    for (int i = 0; i < num_exps && rc == MPB_OK; i++) {
        mpb_ompl_log *log;
        if ((rc = imported_log(&o, exps[i], &log)) != MPB_OK)
            break;
        if (log) {
            if (!log_exported(&o, log, before))
                rc = mpb__pa_write_log(&o, log);
            mpb_ompl_log_close(log);
            continue;
        }
        /* mpbench's status enum, and the experiment parameters after
         * the twelve known columns, once an experiment of its own goes
         * out. */
        if (!mine && (rc = mpb__pa_add_status_enum(&o)) != MPB_OK)
            break;
        for (int k = 0; !mine && k < MPB__PA_NUM_EXP_PARAMS && rc == MPB_OK;
             k++) {
            prop p = {.name = (char *)mpb__pa_exp_params[k][0],
                      .type = mpb__pa_exp_params[k][1]};
            prop_list one = {.v = &p, .n = 1, .cap = 1};
            rc = mpb__pa_ensure_columns(&o, "experiments", &one, 0);
        }
        mine = 1;
        if (rc == MPB_OK)
            rc = export_experiment(&o, exps[i], before);
    }
done:
    rc = mpb__pa_finish(&o, rc);
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

