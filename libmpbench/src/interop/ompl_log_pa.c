/*
 * ompl_log_pa.c - OMPL benchmark logs straight into a Planner Arena
 * database, with the same rows OMPL's ompl_benchmark_statistics.py writes
 * (mpb_ompl_logs_to_planner_arena(); the database's tables are
 * store_pa_db.c's). A new database is written beside its name and takes
 * it only once complete.
 */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "mpbench/ompl_log.h"
#include "interop/store_pa.h"

/*
 * Rows per INSERT statement of the runs and progress: one statement's own
 * cost (its start and end, the AUTOINCREMENT counter written back) shared
 * by that many rows instead of paid by each.
 */
#define PA_BATCH 64

/* How many rows of n values one statement may take (at least 1). */
static int batch_rows(pa_out *o, int n)
{
    int vars = sqlite3_limit(o->db, SQLITE_LIMIT_VARIABLE_NUMBER, -1);
    int rows = n > 0 ? vars / n : PA_BATCH;
    return rows < 1 ? 1 : rows > PA_BATCH ? PA_BATCH : rows;
}

/* 1 for the types whose values a log writes as integers. */
static int integer_type(const char *type)
{
    return strcmp(type, "INTEGER") == 0 || strcmp(type, "BOOLEAN") == 0 ||
           strcmp(type, "ENUM") == 0;
}

/*
 * A value as OMPL's script stores it: it binds the log's text, which
 * SQLite turns into a number by the column's affinity (aff, as
 * mpb__pa_affinity()): a REAL column holds reals; another holds an
 * integer's text as an integer, and a real's as a real unless it is a
 * whole number within 2^51 (SQLite 3.40's sqlite3RealSameAsInt()). exact
 * is the integer as written when a double would round it (or NULL).
 */
static void bind_cell(sqlite3_stmt *st, int i, char aff, int integer,
                      double v, const long long *exact)
{
    if (isnan(v))
        sqlite3_bind_null(st, i);
    else if (aff == 'R')
        sqlite3_bind_double(st, i, v);
    else if (exact)
        sqlite3_bind_int64(st, i, *exact);
    else if (v == floor(v) && (integer ? fabs(v) < 0x1p63
                                       : fabs(v) < 0x1p51))
        sqlite3_bind_int64(st, i, (sqlite3_int64)v);
    else
        sqlite3_bind_double(st, i, v);
}

/* The plannerConfigs row of p: the one of its name and settings, as the
 * script finds it (either tool may have added it), or a new one. */
static int config_id(pa_out *o, const mpb_ompl_planner *p, int64_t *out)
{
    sqlite3_stmt *st;
    if (sqlite3_prepare_v2(o->db, "SELECT id FROM plannerConfigs WHERE"
                           " name = ?1 AND settings = ?2", -1, &st,
                           NULL) != SQLITE_OK)
        return mpb__pa_fail(o, "prepare plannerConfigs");
    sqlite3_bind_text(st, 1, p->name, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 2, p->settings_text, -1, SQLITE_STATIC);
    int step = sqlite3_step(st), rc = MPB_OK;
    if (step == SQLITE_ROW) {
        *out = sqlite3_column_int64(st, 0);
    } else if (step != SQLITE_DONE) {
        rc = mpb__pa_fail(o, "find a planner configuration");
    } else {
        sqlite3_finalize(st);
        st = NULL;
        if (sqlite3_prepare_v2(o->db, "INSERT INTO plannerConfigs (name,"
                               " settings) VALUES (?1, ?2)", -1, &st,
                               NULL) != SQLITE_OK)
            return mpb__pa_fail(o, "prepare plannerConfigs");
        sqlite3_bind_text(st, 1, p->name, -1, SQLITE_STATIC);
        sqlite3_bind_text(st, 2, p->settings_text, -1, SQLITE_STATIC);
        if (sqlite3_step(st) != SQLITE_DONE) {
            rc = mpb__pa_fail(o, "add a planner configuration");
        } else {
            *out = sqlite3_last_insert_rowid(o->db);
            o->counts.planner_configs++;
        }
    }
    sqlite3_finalize(st);
    return rc;
}

/* One planner block's runs (and progress) as OMPL's script writes them:
 * the runs in the log's order, then their progress samples. */
static int write_log_planner(pa_out *o, int64_t experiment_id,
                             const mpb_ompl_planner *p)
{
    sqlite3_stmt *st = NULL, *many = NULL;
    prop_list props = {0}, tprog = {0}, prog;
    int64_t planner = 0, *run_ids = NULL;
    char *aff = NULL, *integer = NULL;
    int rc = MPB_ENOMEM;
    int np = p->num_properties, q = p->num_progress_properties;
    int has_progress = q > 1 && p->progress_start != NULL &&
                       p->progress_start[p->num_runs] > 0;
    props.v = calloc((size_t)np + 1, sizeof *props.v);
    tprog.v = calloc((size_t)q + 1, sizeof *tprog.v);
    aff = calloc((size_t)(np > q ? np : q) + 1, 1);
    integer = calloc((size_t)(np > q ? np : q) + 1, 1);
    if (props.v == NULL || tprog.v == NULL || aff == NULL || integer == NULL)
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
    if ((rc = config_id(o, p, &planner)) != MPB_OK)
        goto done;

    /* The runs, PA_BATCH a statement, the last few one by one. */
    char ids[64];
    snprintf(ids, sizeof ids, "%lld,%lld", (long long)experiment_id,
             (long long)planner);
    int rows = batch_rows(o, np);
    if ((rc = mpb__pa_ensure_columns(o, "runs", &props, 0)) != MPB_OK ||
        (rc = mpb__pa_affinities(o, "runs", &props, aff)) != MPB_OK ||
        (rc = mpb__pa_prepare_rows(o, "INSERT", "runs", "experimentid,plannerid", ids,
                           &props, 1, &st)) != MPB_OK ||
        (rows > 1 && p->num_runs >= rows &&
         (rc = mpb__pa_prepare_rows(o, "INSERT", "runs", "experimentid,plannerid", ids,
                            &props, rows, &many)) != MPB_OK))
        goto done;
    for (int k = 0; k < np; k++)
        integer[k] = (char)integer_type(props.v[k].type);
    long x = 0;         /* the next of p->exact */
    for (long r = 0; r < p->num_runs && rc == MPB_OK;) {
        int k = p->num_runs - r >= rows ? rows : 1;
        sqlite3_stmt *ins = k > 1 ? many : st;
        size_t first = (size_t)r * (size_t)np;
        const double *v = p->values + first;
        for (int i = 0; i < k * np; i++) {
            const long long *exact = NULL;
            if (x < p->num_exact && p->exact[x].cell == first + (size_t)i)
                exact = &p->exact[x++].value;
            bind_cell(ins, i + 1, aff[i % np], integer[i % np], v[i], exact);
        }
        if (sqlite3_step(ins) != SQLITE_DONE) {
            rc = mpb__pa_fail(o, "add a run");
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
        rc = mpb__pa_ensure_columns(o, "progress", &prog, 0);
    if (rc == MPB_OK)
        rc = mpb__pa_affinities(o, "progress", &tprog, aff);
    if (rc != MPB_OK || !has_progress)
        goto done;

    /* The progress samples, in the log's order (a repeated time keeps the
     * first, as the script does), PA_BATCH a statement. */
    int n = 1 + q;
    rows = batch_rows(o, n);
    long total = p->progress_start[p->num_runs];
    if ((rc = mpb__pa_prepare_rows(o, "INSERT OR IGNORE", "progress", "runid", "?",
                           &tprog, 1, &st)) != MPB_OK ||
        (rows > 1 && total >= rows &&
         (rc = mpb__pa_prepare_rows(o, "INSERT OR IGNORE", "progress", "runid", "?",
                            &tprog, rows, &many)) != MPB_OK))
        goto done;
    for (int k = 0; k < q; k++)
        integer[k] = (char)integer_type(tprog.v[k].type);
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
                bind_cell(ins, b * n + 2 + j, aff[j], integer[j], sample[j],
                          NULL);
        }
        if (sqlite3_step(ins) != SQLITE_DONE) {
            rc = mpb__pa_fail(o, "add a progress sample");
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
    free(aff);
    free(integer);
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

static int by_name(const void *a, const void *b)
{
    return strcmp(((const prop *)a)->name, ((const prop *)b)->name);
}

/* The log's enums, each unless one of its name is there already (added
 * by an earlier log), as the script adds them. */
static int write_enums(pa_out *o, const mpb_ompl_log *log)
{
    sqlite3_stmt *find = NULL, *add = NULL;
    if (sqlite3_prepare_v2(o->db, "SELECT 1 FROM enums WHERE name = ?", -1,
                           &find, NULL) != SQLITE_OK ||
        sqlite3_prepare_v2(o->db, "INSERT INTO enums (name, value, description)"
                           " VALUES (?, ?, ?)", -1, &add, NULL) != SQLITE_OK) {
        sqlite3_finalize(find);
        return mpb__pa_fail(o, "prepare enums");
    }
    int rc = MPB_OK;
    for (int i = 0; i < log->num_enums && rc == MPB_OK; i++) {
        const mpb_ompl_enum *en = &log->enums[i];
        sqlite3_reset(find);
        sqlite3_bind_text(find, 1, en->name, -1, SQLITE_STATIC);
        int step = sqlite3_step(find);
        if (step == SQLITE_ROW)
            continue;
        if (step != SQLITE_DONE) {
            rc = mpb__pa_fail(o, "read enums");
            break;
        }
        for (int k = 0; k < en->num_values && rc == MPB_OK; k++) {
            sqlite3_reset(add);
            sqlite3_bind_text(add, 1, en->name, -1, SQLITE_STATIC);
            sqlite3_bind_int(add, 2, k);
            sqlite3_bind_text(add, 3, en->values[k], -1, SQLITE_STATIC);
            if (sqlite3_step(add) != SQLITE_DONE)
                rc = mpb__pa_fail(o, "add an enum");
        }
    }
    sqlite3_finalize(find);
    sqlite3_finalize(add);
    return rc;
}

/* The log's experiment, with its parameters as columns (added in the
 * order of their names, as the script adds them), then its planner
 * blocks. */
int mpb__pa_write_log(pa_out *o, const mpb_ompl_log *log)
{
    sqlite3_stmt *st = NULL;
    int np = log->num_params, rc = MPB_ENOMEM;
    prop_list params = {.v = calloc((size_t)np + 1, sizeof(prop)), .n = np};
    char *sql = NULL;
    size_t cap = 512;
    if (params.v == NULL)
        goto done;
    for (int i = 0; i < np; i++) {
        if ((params.v[i].name = mpb__pa_param_column(log->params[i].name)) == NULL)
            goto done;
        params.v[i].type = log->params[i].type;
        cap += strlen(params.v[i].name) + 16;
    }
    if ((sql = malloc(cap)) == NULL)
        goto done;
    /* The columns in the log's order for the row. */
    size_t len = (size_t)snprintf(sql, cap, "INSERT INTO experiments (name,"
                                  " totaltime, timelimit, memorylimit, runcount,"
                                  " version, hostname, cpuinfo, date, seed,"
                                  " setup");
    for (int i = 0; i < np; i++)
        len += (size_t)snprintf(sql + len, cap - len, ",\"%s\"", params.v[i].name);
    len += (size_t)snprintf(sql + len, cap - len, ") VALUES (?1, ?2, ?3, ?4,"
                            " ?5, "
                            /* "OMPL version " (no number) is "OMPL version"
                             * to OMPL's script, which takes the line's
                             * last word for the number. */
                            "CASE instr(?6, ' ') WHEN 0 THEN ?6 || ' version'"
                            " ELSE ?6 END, ?7, ?8, ?9, ?10, ?11");
    for (int i = 0; i < np; i++)
        len += (size_t)snprintf(sql + len, cap - len, ",?");
    snprintf(sql + len, cap - len, ")");
    if (np > 1)
        qsort(params.v, (size_t)np, sizeof *params.v, by_name);
    if ((rc = mpb__pa_ensure_columns(o, "experiments", &params, 0)) != MPB_OK ||
        (rc = write_enums(o, log)) != MPB_OK)
        goto done;
    if (sqlite3_prepare_v2(o->db, sql, -1, &st, NULL) != SQLITE_OK) {
        rc = mpb__pa_fail(o, "prepare experiments");
        goto done;
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
    /* The values as the script binds them, text: the column's affinity
     * makes them numbers where it does for the script. */
    for (int i = 0; i < np; i++)
        sqlite3_bind_text(st, 12 + i, log->params[i].value, -1, SQLITE_STATIC);
    rc = MPB_OK;
    if (sqlite3_step(st) != SQLITE_DONE)
        rc = mpb__pa_fail(o, "add the experiment");
    int64_t experiment = sqlite3_last_insert_rowid(o->db);
    if (rc == MPB_OK)
        o->counts.experiments++;
    for (int i = 0; i < log->num_planners && rc == MPB_OK; i++)
        rc = write_log_planner(o, experiment, &log->planners[i]);
done:
    if (rc == MPB_ENOMEM)
        mpb__store_fail(o->s, rc, "out of memory");
    sqlite3_finalize(st);
    for (int i = 0; params.v && i < np; i++)
        free(params.v[i].name);
    free(params.v);
    free(sql);
    return rc;
}

int mpb_ompl_logs_to_planner_arena(const char *path, int flags,
                                   mpb_ompl_log_next_fn next, void *ud,
                                   mpb_export_counts *counts, char *err,
                                   size_t errlen)
{
    /* The Planner Arena writer reports through a store's message; this
     * one has nothing else. */
    mpb_store *errs = mpb__store_errors_create();
    pa_out o = {.s = errs, .path = path};
    struct stat sb;
    char *tmp = NULL;
    int rc;
    if (counts)
        *counts = (mpb_export_counts){0};
    if (errs == NULL) {
        if (err && errlen)
            snprintf(err, errlen, "out of memory");
        return MPB_ENOMEM;
    }
    if (next == NULL || path == NULL) {
        rc = mpb__store_fail(errs, MPB_EINVAL, "bad arguments");
        goto out;
    }
    int exists = stat(path, &sb) == 0;
    if (exists && !(flags & MPB_EXPORT_APPEND)) {
        rc = mpb__store_fail(errs, MPB_EEXISTS, "%s exists", path);
        goto out;
    }
    /* A new database is written whole into a file beside path and takes
     * its name only once complete: until then nobody reads it, so it
     * needs no journal, no locks and no syncs but the last (publish()).
     * An existing one is added to in place, with SQLite's defaults. */
    if (!exists && (rc = create_beside(path, &tmp)) != MPB_OK) {
        rc = mpb__store_fail(errs, rc, "cannot create a file beside %s: %s",
                             path, rc == MPB_ENOMEM ? "out of memory"
                                                    : strerror(errno));
        goto out;
    }
    /* One thread uses the connection: no mutexes. */
    if (sqlite3_open_v2(tmp ? tmp : path, &o.db, SQLITE_OPEN_READWRITE |
                        SQLITE_OPEN_NOMUTEX, NULL) != SQLITE_OK) {
        rc = mpb__store_fail(errs, MPB_EIO, "cannot open %s: %s", path,
                             o.db ? sqlite3_errmsg(o.db) : "out of memory");
        goto close;
    }
    sqlite3_busy_timeout(o.db, 5000);
    /* No foreign key checks: every id written is one this function has
     * just inserted (the script does not check them either). */
    if ((tmp && (rc = mpb__pa_exec(&o, "PRAGMA journal_mode = OFF;"
                                   "PRAGMA synchronous = OFF;"
                                   "PRAGMA locking_mode = EXCLUSIVE", "configure"))) ||
        (rc = mpb__pa_begin(&o, 0)))
        goto close;
    for (;;) {
        const mpb_ompl_log *log = NULL;
        if ((rc = next(ud, &log)) != MPB_OK) {
            rc = mpb__store_fail(errs, rc, "a log to write could not be "
                                 "read: nothing written");
            break;
        }
        if (log == NULL || (rc = mpb__pa_write_log(&o, log)) != MPB_OK)
            break;
    }
close:
    rc = mpb__pa_finish(&o, rc);
    if (tmp) {
        /* Leave nothing half-written behind. */
        if (rc == MPB_OK)
            rc = publish(errs, tmp, path);
        else
            unlink(tmp);
    }
out:
    if (rc == MPB_OK && counts)
        *counts = o.counts;
    if (rc != MPB_OK && err && errlen)
        snprintf(err, errlen, "%s", mpb_store_errmsg(errs));
    mpb_store_close(errs);
    free(tmp);
    return rc;
}

/* next() for one log, which ud points to: it, then the end. */
static int one_log(void *ud, const mpb_ompl_log **log)
{
    const mpb_ompl_log **only = ud;
    *log = *only;
    *only = NULL;
    return MPB_OK;
}

int mpb_ompl_log_to_planner_arena(const mpb_ompl_log *log, const char *path,
                                  int flags, mpb_export_counts *counts,
                                  char *err, size_t errlen)
{
    if (log == NULL) {
        if (counts)
            *counts = (mpb_export_counts){0};
        if (err && errlen)
            snprintf(err, errlen, "bad arguments");
        return MPB_EINVAL;
    }
    return mpb_ompl_logs_to_planner_arena(path, flags, one_log, &log, counts,
                                          err, errlen);
}
