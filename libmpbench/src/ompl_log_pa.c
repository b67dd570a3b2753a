/*
 * ompl_log_pa.c - OMPL benchmark logs straight into a Planner Arena
 * database, with the same rows OMPL's ompl_benchmark_statistics.py writes
 * (mpb_ompl_logs_to_planner_arena(); the database's tables are
 * store_pa_db.c's). A new database is written beside its name and takes
 * it only once complete.
 */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "mpbench/ompl_log.h"
#include "store_pa.h"

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
    /* The settings as OMPL's script writes them, each line with its end
     * and then ';' ("a = 1\n;b = 2\n;"), so that a log it added and one
     * added here are one configuration. */
    if (sqlite3_prepare_v2(o->db, "INSERT INTO plannerConfigs (name, settings)"
                           " VALUES (?1, CASE ?2 WHEN '' THEN '' ELSE"
                           " replace(?2, ';', char(10) || ';') || char(10)"
                           " || ';' END)", -1, &st, NULL) != SQLITE_OK) {
        rc = mpb__pa_fail(o, "prepare plannerConfigs");
        goto done;
    }
    sqlite3_bind_text(st, 1, p->name, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 2, p->settings, -1, SQLITE_STATIC);
    if (sqlite3_step(st) != SQLITE_DONE) {
        rc = mpb__pa_fail(o, "add a planner configuration");
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
    if ((rc = mpb__pa_ensure_columns(o, "runs", &props, 0)) != MPB_OK ||
        (rc = mpb__pa_prepare_rows(o, "INSERT", "runs", "experimentid,plannerid", ids,
                           &props, 1, &st)) != MPB_OK ||
        (rows > 1 && p->num_runs >= rows &&
         (rc = mpb__pa_prepare_rows(o, "INSERT", "runs", "experimentid,plannerid", ids,
                            &props, rows, &many)) != MPB_OK))
        goto done;
    for (int k = 0; k < np; k++)
        real[k] = strcmp(props.v[k].type, "REAL") == 0;
    for (long r = 0; r < p->num_runs && rc == MPB_OK;) {
        int k = p->num_runs - r >= rows ? rows : 1;
        sqlite3_stmt *ins = k > 1 ? many : st;
        const double *v = p->values + (size_t)r * (size_t)np;
        for (int i = 0; i < k * np; i++)
            mpb__pa_bind_number(ins, i + 1, real[i % np], v[i]);
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
                mpb__pa_bind_number(ins, b * n + 2 + j, real[j], sample[j]);
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

/* The log's experiment, then its planner blocks. */
static int write_log(pa_out *o, const mpb_ompl_log *log)
{
    sqlite3_stmt *st;
    if (sqlite3_prepare_v2(o->db, "INSERT INTO experiments (name, totaltime,"
                           " timelimit, memorylimit, runcount, version,"
                           " hostname, cpuinfo, date, seed, setup) VALUES"
                           " (?1, ?2, ?3, ?4, ?5,"
                           /* "OMPL version " (no number) is "OMPL version"
                            * to OMPL's script, which takes the line's last
                            * word for the number. */
                           " CASE instr(?6, ' ') WHEN 0 THEN ?6 || ' version'"
                           " ELSE ?6 END, ?7, ?8, ?9, ?10, ?11)", -1, &st,
                           NULL) != SQLITE_OK)
        return mpb__pa_fail(o, "prepare experiments");
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
    int rc = MPB_OK;
    if (sqlite3_step(st) != SQLITE_DONE)
        rc = mpb__pa_fail(o, "add the experiment");
    sqlite3_finalize(st);
    int64_t experiment = sqlite3_last_insert_rowid(o->db);
    if (rc == MPB_OK)
        o->counts.experiments++;
    for (int i = 0; i < log->num_planners && rc == MPB_OK; i++)
        rc = write_log_planner(o, experiment, &log->planners[i]);
    return rc;
}

int mpb_ompl_logs_to_planner_arena(const char *path, int flags,
                                   mpb_ompl_log_next_fn next, void *ud,
                                   mpb_export_counts *counts, char *err,
                                   size_t errlen)
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
    if (next == NULL || path == NULL) {
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
    if ((tmp && (rc = mpb__pa_exec(&o, "PRAGMA journal_mode = OFF;"
                                   "PRAGMA synchronous = OFF;"
                                   "PRAGMA locking_mode = EXCLUSIVE", "configure"))) ||
        (rc = mpb__pa_begin(&o)))
        goto close;
    for (;;) {
        const mpb_ompl_log *log = NULL;
        if ((rc = next(ud, &log)) != MPB_OK) {
            rc = mpb__store_fail(&errs, rc, "a log to write could not be "
                                 "read: nothing written");
            break;
        }
        if (log == NULL || (rc = write_log(&o, log)) != MPB_OK)
            break;
    }
close:
    rc = mpb__pa_finish(&o, rc);
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
