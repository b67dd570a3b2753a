/* store.c - opening the database, its schema version, transactions, errors,
 * and the WAL checkpoints, kept out of the writer's commits. */
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>

#include "mpbench/outcome.h"
#include <unistd.h>

#include "store/store_internal.h"

static const char *const stmt_sql[MPB__ST_COUNT] = {
    [MPB__ST_BEGIN] = "BEGIN IMMEDIATE",
    [MPB__ST_COMMIT] = "COMMIT",
    [MPB__ST_ROLLBACK] = "ROLLBACK",
    [MPB__ST_RUN_SENT] =
        "UPDATE runs SET state = 'sent', attempt_id = ?2, planner_id = ?3,"
        " attempts = attempts + (attempt_id IS NOT ?2), sent = ?4"
        " WHERE id = ?1 AND state != 'done'",
    [MPB__ST_RUN_FINISH] =
        "UPDATE runs SET state = 'done', finished = ?16,"
        " planner_id = ?3, status = ?4, message = ?5, claimed_success = ?6,"
        " valid = ?7, verdict = ?8, success = ?9, time_total = ?10,"
        " time_raw = ?11, time_other = ?12, wall_time = ?13, final_stage = ?14,"
        " final_metrics = ?15, world_setup_time = ?17, verify_time = ?18,"
        " memory = ?19, outcome = ?20, in_time = ?21, seen_verdict = ?22,"
        " seen_detail = ?23, seen_success = ?24"
        " WHERE id = ?1 AND attempt_id = ?2 AND state != 'done'",
    [MPB__ST_STAGE_INSERT] =
        "INSERT OR REPLACE INTO stages(run_id, idx, name, time, num_waypoints,"
        " num_joints, waypoints, valid, verdict, verdict_detail,"
        " verdict_segment, verification, times, depth_lower_mm, depth_upper_mm)"
        " VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14, ?15)",
    [MPB__ST_METRIC_INSERT] =
        "INSERT OR REPLACE INTO metrics(run_id, stage, name, value)"
        " VALUES (?1, ?2, ?3, ?4)",
    [MPB__ST_VALUE_INSERT] =
        "INSERT OR REPLACE INTO planner_values(run_id, name, value, exact)"
        " VALUES (?1, ?2, ?3, ?4)",
    [MPB__ST_PROGRESS_INSERT] =
        "INSERT OR REPLACE INTO progress(run_id, seq, time, name, value)"
        " VALUES (?1, ?2, ?3, ?4, ?5)",
    [MPB__ST_RUN_ADD] =
        "INSERT OR IGNORE INTO runs(experiment_id, planner_config_id,"
        " query_id, repetition, seed) VALUES (?1, ?2, ?3, ?4, ?5)",
    [MPB__ST_SAVEPOINT] = "SAVEPOINT mpb_run",
    [MPB__ST_RELEASE] = "RELEASE mpb_run",
    [MPB__ST_ROLLBACK_TO] = "ROLLBACK TO mpb_run",
};

int mpb__store_fail(mpb_store *s, int code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(s->errmsg, sizeof s->errmsg, fmt, ap);
    va_end(ap);
    return code;
}

int mpb__store_db_fail(mpb_store *s, const char *what)
{
    return mpb__store_fail(s, MPB_EDB, "%s: %s", what, sqlite3_errmsg(s->db));
}

static int tx_open(mpb_store *s);

static sqlite3_stmt *prepare(mpb_store *s, const char *sql)
{
    sqlite3_stmt *st = NULL;
    if (sqlite3_prepare_v2(s->db, sql, -1, &st, NULL) != SQLITE_OK) {
        mpb__store_db_fail(s, "prepare");
        return NULL;
    }
    return st;
}

sqlite3_stmt *mpb__store_prepare(mpb_store *s, const char *sql)
{
    return tx_open(s) == MPB_OK ? prepare(s, sql) : NULL;
}

sqlite3_stmt *mpb__store_stmt(mpb_store *s, mpb__stmt_id id)
{
    if (id != MPB__ST_BEGIN && id != MPB__ST_COMMIT &&
        id != MPB__ST_ROLLBACK && tx_open(s) != MPB_OK)
        return NULL;
    if (s->stmt[id] == NULL)
        s->stmt[id] = prepare(s, stmt_sql[id]);
    else
        sqlite3_reset(s->stmt[id]);
    if (s->stmt[id] != NULL)
        sqlite3_clear_bindings(s->stmt[id]);
    return s->stmt[id];
}

static int exec(mpb_store *s, const char *sql, const char *what)
{
    char *msg = NULL;
    if (sqlite3_exec(s->db, sql, NULL, NULL, &msg) != SQLITE_OK) {
        mpb__store_fail(s, MPB_EDB, "%s: %s", what, msg ? msg : "?");
        sqlite3_free(msg);
        return MPB_EDB;
    }
    return MPB_OK;
}

static int schema_version(mpb_store *s, int *version)
{
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT value FROM meta WHERE key = 'schema_version'");
    *version = 0;
    if (st == NULL)
        return MPB_EDB;
    if (sqlite3_step(st) == SQLITE_ROW)
        *version = sqlite3_column_int(st, 0);
    sqlite3_finalize(st);
    return MPB_OK;
}

int mpb__store_has_column(mpb_store *s, const char *table, const char *column)
{
    char sql[160];
    sqlite3_stmt *probe = NULL;
    snprintf(sql, sizeof sql, "SELECT %s FROM %s LIMIT 0", column, table);
    int present = sqlite3_prepare_v2(s->db, sql, -1, &probe, NULL) == SQLITE_OK;
    sqlite3_finalize(probe);
    return present;
}

/* Add a column that a database made by an earlier mpbench lacks; *added
 * (may be NULL) says whether it did. */
static int add_column(mpb_store *s, const char *table, const char *column,
                      const char *type, int *added)
{
    char sql[160], what[96];
    if (added != NULL)
        *added = 0;
    if (mpb__store_has_column(s, table, column))
        return MPB_OK;
    if (added != NULL)
        *added = 1;
    snprintf(sql, sizeof sql, "ALTER TABLE %s ADD COLUMN %s %s", table,
             column, type);
    snprintf(what, sizeof what, "add %s.%s", table, column);
    return exec(s, sql, what);
}

static int add_missing_column(mpb_store *s, const char *table,
                              const char *column, const char *type)
{
    return add_column(s, table, column, type, NULL);
}

/* The migration step of claims in both directions (docs/schema.md): a
 * database made before runs.outcome gets it for its finished runs, from
 * the success rule's own function (outcome.h) over what it kept, and
 * runs.in_time 0 where a claimed run with a valid final stage was no
 * success (the only such reason then was time), else 1. */
static int add_outcomes(mpb_store *s)
{
    int added, rc;
    if ((rc = add_column(s, "runs", "outcome", "TEXT", &added)) != MPB_OK ||
        (rc = add_missing_column(s, "runs", "in_time", "INTEGER")) != MPB_OK ||
        !added)
        return rc;
    sqlite3_stmt *rd = mpb__store_prepare(s,
        "SELECT id, coalesce(claimed_success, 0), coalesce(valid, 0),"
        " coalesce(success, 0) FROM runs WHERE state = 'done'");
    sqlite3_stmt *wr = mpb__store_prepare(s,
        "UPDATE runs SET outcome = ?2, in_time = ?3 WHERE id = ?1");
    rc = rd != NULL && wr != NULL ? MPB_OK : MPB_EDB;
    while (rc == MPB_OK && sqlite3_step(rd) == SQLITE_ROW) {
        int claimed = sqlite3_column_int(rd, 1);
        int valid = sqlite3_column_int(rd, 2);
        int success = sqlite3_column_int(rd, 3);
        mpb_outcome o = mpb_run_outcome(claimed, valid, success);
        sqlite3_bind_int64(wr, 1, sqlite3_column_int64(rd, 0));
        sqlite3_bind_text(wr, 2, mpb_outcome_name(o), -1, SQLITE_STATIC);
        sqlite3_bind_int(wr, 3, o != MPB_OUTCOME_LATE);
        if (sqlite3_step(wr) != SQLITE_DONE)
            rc = mpb__store_db_fail(s, "add runs.outcome");
        sqlite3_reset(wr);
    }
    sqlite3_finalize(rd);
    sqlite3_finalize(wr);
    return rc;
}

static int refresh_results_view(mpb_store *s)
{
    if (mpb__store_has_column(s, "results", "experiment_id") &&
        mpb__store_has_column(s, "results", "message") &&
        mpb__store_has_column(s, "results", "outcome") &&
        mpb__store_has_column(s, "results", "approach"))
        return MPB_OK;
    int rc = exec(s, "DROP VIEW IF EXISTS results", "drop results view");
    return rc != MPB_OK ? rc
                        : exec(s, mpb__schema_results_view, "create results view");
}

/* The migration step of imported logs' headers: what an OMPL log says of
 * its experiment beyond mpbench's own columns (docs/schema.md). A
 * database made before it gets the columns, NULL (not a log's, or not
 * kept), and the empty table. */
static int add_log_header(mpb_store *s)
{
    static const char *const columns[][2] = {
        {"started", "TEXT"}, {"total_time", "REAL"}, {"seed", "TEXT"},
        {"memory_limit", "REAL"}, {"cpuinfo", "TEXT"},
    };
    int rc = MPB_OK;
    for (size_t i = 0; i < sizeof columns / sizeof *columns && rc == MPB_OK; i++)
        rc = add_missing_column(s, "experiments", columns[i][0], columns[i][1]);
    return rc != MPB_OK ? rc : exec(s, mpb__schema_experiment_params,
                                    "create experiment_params");
}

/* The migration step of imported logs' integers and declared
 * properties: planner_values.exact (NULL for the values there were: the
 * REAL is all that was kept) and the empty log_properties (an older
 * import's unmeasured properties are lost, its others typed REAL). */
static int add_exact_values(mpb_store *s)
{
    int rc = add_missing_column(s, "planner_values", "exact", "INTEGER");
    return rc != MPB_OK ? rc : exec(s, mpb__schema_log_properties,
                                    "create log_properties");
}

/* The migration step of seen scenes (docs/schema.md): a database made
 * before them gets the columns, NULL: every planner had the scene. */
static int add_seen(mpb_store *s)
{
    static const char *const columns[][3] = {
        {"scenes", "seen_format", "TEXT"}, {"scenes", "seen_hash", "TEXT"},
        {"scenes", "seen", "TEXT"},        {"scenes", "seen_how", "TEXT"},
        {"runs", "seen_verdict", "TEXT"},  {"runs", "seen_detail", "TEXT"},
        {"runs", "seen_success", "INTEGER"},
    };
    int rc = MPB_OK;
    for (size_t i = 0; i < sizeof columns / sizeof *columns && rc == MPB_OK; i++)
        rc = add_missing_column(s, columns[i][0], columns[i][1], columns[i][2]);
    return rc;
}

/* The migration step of problem sets (docs/schema.md): a database made
 * before scenes.problem_set gets it, each scene's by the default rule
 * (mpb_store_problem_set_len()), and the run_summary view over it. */
static int add_problem_sets(mpb_store *s)
{
    int rc = add_missing_column(s, "scenes", "problem_set", "TEXT");
    if (rc == MPB_OK)
        rc = exec(s, mpb__schema_fill_problem_sets, "fill scenes.problem_set");
    return rc != MPB_OK ? rc : exec(s, mpb__schema_run_summary_view,
                                    "create run_summary view");
}

/* The migration step of attempt ids (docs/schema.md): a database made
 * before the wire's run_id was named attempt_id keeps the attempt's id
 * in runs.run_uid; the column is renamed, its values kept, so that a
 * daemon resumes such a database's runs in flight under their ids. */
static int rename_attempt_id(mpb_store *s)
{
    if (!mpb__store_has_column(s, "runs", "run_uid") ||
        mpb__store_has_column(s, "runs", "attempt_id"))
        return MPB_OK;
    return exec(s, "ALTER TABLE runs RENAME COLUMN run_uid TO attempt_id",
                "rename runs.run_uid to attempt_id");
}

static int create_schema(mpb_store *s)
{
    int version, rc;
    if ((rc = exec(s, "BEGIN IMMEDIATE", "begin")) != MPB_OK)
        return rc;
    if ((rc = exec(s, mpb__schema_v1, "create schema")) != MPB_OK ||
        (rc = rename_attempt_id(s)) != MPB_OK)
        goto fail;
    /* A database made before runs.final_metrics gets the column, NULL for
     * its runs: reports read their metrics from the metrics table. One made
     * before pose-region goals gets their columns, NULL for its queries;
     * one made before experiments.resolution, NULL: not known; one made
     * before runs.world_setup_time, NULL: its runs' planner_values hold
     * the value, if a planner reported it; one made before runs.verify_time,
     * NULL: the daemon's verification was not timed; one made before
     * runs.memory, NULL: no planner reported its memory; one made before
     * queries.held, NULL: its joints outside the group held defaults; one
     * made before stages.verification, NULL: its stages were sampled;
     * one made before stages.times, NULL: no stage had waypoint times;
     * one made before stages.depth_lower_mm and depth_upper_mm, NULL:
     * the depth of its collisions was not measured. */
    if ((rc = add_missing_column(s, "runs", "final_metrics", "BLOB")) != MPB_OK ||
        (rc = add_missing_column(s, "runs", "world_setup_time", "REAL")) != MPB_OK ||
        (rc = add_missing_column(s, "runs", "verify_time", "REAL")) != MPB_OK ||
        (rc = add_missing_column(s, "runs", "memory", "REAL")) != MPB_OK ||
        (rc = add_missing_column(s, "queries", "goal_link", "TEXT")) != MPB_OK ||
        (rc = add_missing_column(s, "queries", "goal_region", "TEXT")) != MPB_OK ||
        (rc = add_missing_column(s, "queries", "held", "TEXT")) != MPB_OK ||
        (rc = add_missing_column(s, "stages", "verification", "TEXT")) != MPB_OK ||
        (rc = add_missing_column(s, "stages", "times", "BLOB")) != MPB_OK ||
        (rc = add_missing_column(s, "stages", "depth_lower_mm", "REAL")) != MPB_OK ||
        (rc = add_missing_column(s, "stages", "depth_upper_mm", "REAL")) != MPB_OK ||
        (rc = add_missing_column(s, "experiments", "resolution", "REAL")) != MPB_OK ||
        (rc = add_log_header(s)) != MPB_OK ||
        (rc = add_exact_values(s)) != MPB_OK ||
        (rc = add_outcomes(s)) != MPB_OK ||
        (rc = add_missing_column(s, "planner_configs", "approach", "TEXT")) != MPB_OK ||
        (rc = add_problem_sets(s)) != MPB_OK ||
        (rc = add_seen(s)) != MPB_OK)
        goto fail;
    /* The results view is made again when it lacks a column this version
     * gives it (a database made before results.experiment_id). */
    if ((rc = refresh_results_view(s)) != MPB_OK)
        goto fail;
    /* A database made before the state index was dropped loses it: it
     * cost three pages in every commit and serves nothing frequent. */
    if ((rc = exec(s, "DROP INDEX IF EXISTS runs_by_state", "drop index")) != MPB_OK)
        goto fail;
    if ((rc = schema_version(s, &version)) != MPB_OK)
        goto fail;
    if (version > MPB__SCHEMA_VERSION) {
        rc = mpb__store_fail(s, MPB_EUNSUPPORTED,
                             "database schema version %d is newer than this "
                             "mpbench (%d)", version, MPB__SCHEMA_VERSION);
        goto fail;
    }
    if (version == 0 &&
        (rc = exec(s, "INSERT INTO meta(key, value) VALUES "
                      "('schema_version', '1')", "schema version")) != MPB_OK)
        goto fail;
    return exec(s, "COMMIT", "commit");
fail:
    sqlite3_exec(s->db, "ROLLBACK", NULL, NULL, NULL);
    return rc;
}

/* ---- locks and checkpoints -------------------------------------------------
 *
 * SQLite's automatic checkpoint runs inside the commit that takes the WAL
 * past 1000 pages: that commit copies the WAL into the database and syncs
 * both, and a run's latency goes from a few hundred microseconds to several
 * milliseconds once every hundred runs (bench/results/history.md,
 * change 1). Instead, a
 * writable handle turns the automatic checkpoint off, and a thread of its
 * own, on a connection of its own, checkpoints:
 *
 * - every CKPT_PERIOD_MS after a commit, PASSIVE: it copies what the WAL
 *   holds into the database without ever waiting for or blocking the
 *   writer;
 * - once the WAL has grown past CKPT_FRAMES, RESTART as well. A writer that
 *   never pauses never lets a PASSIVE checkpoint reach the end of the WAL,
 *   and the WAL only starts again from its beginning once one has: without
 *   this it grows by every page of every commit. RESTART holds the writer
 *   off for as long as it takes to copy what came after the PASSIVE pass
 *   and sync: about a millisecond, once per CKPT_FRAMES pages, instead of
 *   the copy of the whole WAL once per 1000.
 *
 * Durability is unchanged: with synchronous=NORMAL a commit in WAL mode is
 * not synced; the checkpoints sync, as before.
 */
#define CKPT_PERIOD_MS 200
#define CKPT_FRAMES 4096            /* 16 MiB of 4 KiB pages */
#define BUSY_WAIT_US 5000000L       /* how long a handle waits for a lock */
#define CKPT_BUSY_WAIT_US 2000L     /* ... the checkpointer, for RESTART */

/* The busy handler: wait for a lock in short steps first (the daemon's
 * transactions and a RESTART checkpoint last about a millisecond), longer
 * ones later, at most *(long *)ud microseconds in all. */
static int store_busy(void *ud, int n)
{
    long limit = *(const long *)ud;
    long waited = n < 20 ? n * 100L
                : n < 38 ? 2000L + (n - 20) * 1000L
                         : 20000L + (n - 38) * 10000L;
    long step = n < 20 ? 100L : n < 38 ? 1000L : 10000L;
    struct timespec ts = {0, step * 1000L};
    if (waited >= limit)
        return 0;
    nanosleep(&ts, NULL);
    return 1;
}

static const long busy_wait_us = BUSY_WAIT_US;
static const long ckpt_busy_wait_us = CKPT_BUSY_WAIT_US;

struct mpb__checkpointer {
    sqlite3        *db;         /* used by the thread only */
    pthread_t       thread;
    pthread_mutex_t mu;
    pthread_cond_t  cond;
    int             dirty;      /* a commit since the last checkpoint */
    int             frames;     /* WAL frames after the last commit */
    int             kicked;     /* woken for a long WAL, not yet served */
    int             quit;
};

/* sqlite3_wal_hook: after every commit of the writer, in its thread. */
static int ckpt_on_commit(void *ud, sqlite3 *db, const char *name, int frames)
{
    mpb__checkpointer *c = ud;
    (void)db;
    (void)name;
    pthread_mutex_lock(&c->mu);
    c->dirty = 1;
    c->frames = frames;
    if (frames >= CKPT_FRAMES && !c->kicked) {
        c->kicked = 1;
        pthread_cond_signal(&c->cond);
    }
    pthread_mutex_unlock(&c->mu);
    return SQLITE_OK;
}

static void *ckpt_main(void *arg)
{
    mpb__checkpointer *c = arg;
    struct timespec due;
    int held_off = 0;           /* the last RESTART could not finish */

    pthread_mutex_lock(&c->mu);
    while (!c->quit) {
        clock_gettime(CLOCK_MONOTONIC, &due);
        due.tv_nsec += CKPT_PERIOD_MS * 1000000L;
        if (due.tv_nsec >= 1000000000L) {
            due.tv_sec++;
            due.tv_nsec -= 1000000000L;
        }
        /* A long WAL cuts the wait short, unless a reader kept the last
         * RESTART from finishing: then try again only a period later, not
         * after every commit. */
        while (!c->quit && (held_off || c->frames < CKPT_FRAMES) &&
               pthread_cond_timedwait(&c->cond, &c->mu, &due) != ETIMEDOUT)
            ;
        if (c->quit || !c->dirty)
            continue;
        c->dirty = 0;
        c->frames = 0;
        c->kicked = 0;
        pthread_mutex_unlock(&c->mu);
        /* Best effort: what cannot be done now (a reader holds an older
         * snapshot, the writer holds its lock) is done next time. */
        int wal_frames = 0;
        held_off = 0;
        int restarted = 0;
        if (sqlite3_wal_checkpoint_v2(c->db, NULL, SQLITE_CHECKPOINT_PASSIVE,
                                      &wal_frames, NULL) == SQLITE_OK &&
            wal_frames >= CKPT_FRAMES) {
            restarted = sqlite3_wal_checkpoint_v2(c->db, NULL,
                                                  SQLITE_CHECKPOINT_RESTART,
                                                  NULL, NULL) == SQLITE_OK;
            held_off = !restarted;
        }
        pthread_mutex_lock(&c->mu);
        if (held_off)
            c->dirty = 1;
        /* Commits before the RESTART reported the long WAL; the next one
         * starts it again. */
        if (restarted)
            c->frames = 0;
    }
    pthread_mutex_unlock(&c->mu);
    return NULL;
}

static void ckpt_stop(mpb_store *s)
{
    mpb__checkpointer *c = s->ckpt;
    if (c == NULL)
        return;
    sqlite3_wal_hook(s->db, NULL, NULL);
    pthread_mutex_lock(&c->mu);
    c->quit = 1;
    pthread_cond_signal(&c->cond);
    pthread_mutex_unlock(&c->mu);
    pthread_join(c->thread, NULL);
    sqlite3_close(c->db);
    pthread_cond_destroy(&c->cond);
    pthread_mutex_destroy(&c->mu);
    free(c);
    s->ckpt = NULL;
}

/* Start the checkpointer of s; if it cannot start, SQLite's automatic
 * checkpoint stays on, which is slower but just as correct. */
static void ckpt_start(mpb_store *s, const char *path)
{
    mpb__checkpointer *c = calloc(1, sizeof *c);
    pthread_condattr_t ca;
    if (c == NULL)
        return;
    /* The connection finds the WAL when it first reads the database. */
    if (sqlite3_open_v2(path, &c->db, SQLITE_OPEN_READWRITE |
                        SQLITE_OPEN_NOMUTEX, NULL) != SQLITE_OK ||
        sqlite3_exec(c->db, "SELECT count(*) FROM sqlite_master", NULL, NULL,
                     NULL) != SQLITE_OK) {
        sqlite3_close(c->db);
        free(c);
        return;
    }
    sqlite3_busy_handler(c->db, store_busy, (void *)&ckpt_busy_wait_us);
    pthread_condattr_init(&ca);
    pthread_condattr_setclock(&ca, CLOCK_MONOTONIC);
    pthread_mutex_init(&c->mu, NULL);
    pthread_cond_init(&c->cond, &ca);
    pthread_condattr_destroy(&ca);
    if (pthread_create(&c->thread, NULL, ckpt_main, c) != 0) {
        sqlite3_close(c->db);
        pthread_cond_destroy(&c->cond);
        pthread_mutex_destroy(&c->mu);
        free(c);
        return;
    }
    s->ckpt = c;
    /* The hook replaces SQLite's automatic checkpoint (itself a WAL hook). */
    sqlite3_wal_hook(s->db, ckpt_on_commit, c);
}

/* ---- opening ---------------------------------------------------------------
 *
 * Every error of mpb_store_open() names the file and says what is wrong
 * with it in words a user can act on. A file is inspected before anything
 * is written to it, so that a wrong path given as the database (a Planner
 * Arena database, some other program's) is refused, not converted.
 */

/* What inspect() found the file to be. */
enum { FILE_EMPTY, FILE_MPBENCH, FILE_OTHER };

/* The last SQLite error on s, said of the file at path. */
static int file_fail(mpb_store *s, const char *path)
{
    const char *why = sqlite3_errmsg(s->db);
    switch (sqlite3_errcode(s->db) & 0xff) {
    case SQLITE_NOTADB:
        return mpb__store_fail(s, MPB_EDB, "%s is not an mpbench database: "
                               "not an SQLite file", path);
    case SQLITE_CORRUPT:
        return mpb__store_fail(s, MPB_EDB, "%s is damaged: %s", path, why);
    case SQLITE_READONLY:
        return mpb__store_fail(s, MPB_EIO, "%s cannot be written: %s", path, why);
    default:
        return mpb__store_fail(s, MPB_EIO, "cannot open %s: %s", path, why);
    }
}

/* Read what the file holds: nothing yet, an mpbench database (*version its
 * schema's), or the tables of something else. */
static int inspect(mpb_store *s, const char *path, int *kind, int *version)
{
    sqlite3_stmt *st = NULL;
    int tables = 0, meta = 0;
    *version = 0;
    if (sqlite3_prepare_v2(s->db, "SELECT count(*), count(*) FILTER (WHERE"
                           " name = 'meta') FROM sqlite_master WHERE type ="
                           " 'table'", -1, &st, NULL) != SQLITE_OK ||
        sqlite3_step(st) != SQLITE_ROW) {
        sqlite3_finalize(st);
        return file_fail(s, path);
    }
    tables = sqlite3_column_int(st, 0);
    meta = sqlite3_column_int(st, 1);
    sqlite3_finalize(st);
    if (meta && schema_version(s, version) != MPB_OK)
        return file_fail(s, path);
    *kind = tables == 0 ? FILE_EMPTY
          : *version > 0 ? FILE_MPBENCH : FILE_OTHER;
    return MPB_OK;
}

static int exists(const char *path, const char *suffix)
{
    char p[4096];
    struct stat st;
    return snprintf(p, sizeof p, "%s%s", path, suffix) < (int)sizeof p &&
           stat(p, &st) == 0;
}

/* A read-only URI for path: "file:" and the path with the characters a URI
 * gives a meaning to escaped. */
static int immutable_uri(const char *path, char *uri, size_t cap)
{
    size_t n = (size_t)snprintf(uri, cap, "file:");
    for (const char *c = path; *c != '\0'; c++) {
        int special = *c == '%' || *c == '?' || *c == '#';
        if (n + 4 >= cap)
            return -1;
        n += (size_t)(special ? snprintf(uri + n, cap - n, "%%%02X",
                                         (unsigned char)*c)
                              : snprintf(uri + n, cap - n, "%c", *c));
    }
    return snprintf(uri + n, cap - n, "?immutable=1") < (int)(cap - n) ? 0 : -1;
}

/*
 * Open path for reading only. Where the file and its folder can be
 * written, a read-write connection that runs nothing but queries
 * (query_only): closing it as the last one folds the WAL back into the
 * database and removes -wal and -shm, which a read-only connection cannot
 * and leaves behind. Where they cannot be written (an archive, another
 * user's results) and no writer is at work (no -wal), the file is opened
 * immutable, which needs no -shm: a read-only connection would have to
 * create one, and fails in a read-only folder or leaves a file of ours
 * that keeps the owner from writing.
 */
static int open_for_reading(mpb_store *s, const char *path)
{
    char dir[4096], uri[8300];
    const char *slash = strrchr(path, '/');
    if (slash == NULL)
        snprintf(dir, sizeof dir, ".");
    else
        snprintf(dir, sizeof dir, "%.*s", slash == path ? 1 : (int)(slash - path),
                 path);
    int writable = access(path, W_OK) == 0 && access(dir, W_OK) == 0;
    int flags = SQLITE_OPEN_NOMUTEX;

    if (writable) {
        flags |= SQLITE_OPEN_READWRITE;
    } else if (!exists(path, "-wal") && immutable_uri(path, uri, sizeof uri) == 0) {
        flags |= SQLITE_OPEN_READONLY | SQLITE_OPEN_URI;
        path = uri;
    } else {
        flags |= SQLITE_OPEN_READONLY;
    }
    if (sqlite3_open_v2(path, &s->db, flags, NULL) != SQLITE_OK)
        return MPB_EIO;
    return writable ? exec(s, "PRAGMA query_only=ON", "configure") : MPB_OK;
}

/* A descriptor of our own on the file SQLite opened at path, and who the
 * file is (device, inode), for mpb_store_check_file(). */
static int remember_file(mpb_store *s, const char *path)
{
    struct stat st;
    if ((s->path = strdup(path)) == NULL)
        return mpb__store_fail(s, MPB_ENOMEM, "out of memory");
    s->fd = open(path, O_RDONLY | O_CLOEXEC);
    if (s->fd < 0 || fstat(s->fd, &st) != 0)
        return mpb__store_fail(s, MPB_EIO, "cannot open %s: %s", path,
                               strerror(errno));
    s->dev = st.st_dev;
    s->ino = st.st_ino;
    return MPB_OK;
}

int mpb_store_open(const char *path, int readonly, mpb_store **out)
{
    mpb_store *s = calloc(1, sizeof *s);
    int rc, kind, version;

    *out = s;
    if (s == NULL)
        return MPB_ENOMEM;
    s->fd = -1;
    s->readonly = readonly;
    rc = readonly ? open_for_reading(s, path)
                  : sqlite3_open_v2(path, &s->db, SQLITE_OPEN_NOMUTEX |
                                    SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE,
                                    NULL) == SQLITE_OK ? MPB_OK : MPB_EIO;
    if (s->db == NULL)
        return mpb__store_fail(s, MPB_ENOMEM, "out of memory");
    if (rc != MPB_OK)
        return file_fail(s, path);
    /* Several processes (the daemon, `mpb report`, sqlite3) share the file;
     * wait for a lock rather than fail. */
    sqlite3_busy_handler(s->db, store_busy, (void *)&busy_wait_us);
    if ((rc = inspect(s, path, &kind, &version)) != MPB_OK)
        return rc;
    if (kind == FILE_OTHER || (readonly && kind == FILE_EMPTY))
        return mpb__store_fail(s, MPB_EDB, "%s is not an mpbench database%s",
                               path, kind == FILE_OTHER && !readonly
                               ? " (it holds other tables; give a new file)" : "");
    if (readonly && version != MPB__SCHEMA_VERSION)
        return mpb__store_fail(s, MPB_EUNSUPPORTED,
                               "%s has schema version %d, expected %d",
                               path, version, MPB__SCHEMA_VERSION);
    /* A reader's pages mapped, not copied by a read() each: a report over
     * a million runs reads the whole file (bench/report_sets.sh). */
    if (readonly)
        return exec(s, "PRAGMA mmap_size=4294967296; PRAGMA cache_size=-16384;",
                     "configure");
    /* WAL: readers never block the daemon's writer. synchronous=NORMAL keeps
     * every committed transaction across a process crash (only a power loss
     * can take the last ones), at a fraction of FULL's fsyncs. Savepoint
     * journals in memory and a 16 MiB page cache: each run's savepoint
     * otherwise spills to a temporary file (bench/mkdb.c: 367 -> 190 us per
     * run at one transaction per run). */
    if ((rc = exec(s, "PRAGMA journal_mode=WAL; PRAGMA synchronous=NORMAL;"
                      " PRAGMA foreign_keys=ON; PRAGMA temp_store=MEMORY;"
                      " PRAGMA cache_size=-16384;", "configure")) != MPB_OK ||
        (rc = create_schema(s)) != MPB_OK) {
        if ((sqlite3_errcode(s->db) & 0xff) == SQLITE_READONLY)
            return file_fail(s, path);
        char why[sizeof s->errmsg];
        snprintf(why, sizeof why, "%s", s->errmsg);
        return mpb__store_fail(s, rc, "%s: %s", path, why);
    }
    if ((rc = remember_file(s, path)) != MPB_OK)
        return rc;
    ckpt_start(s, path);
    return MPB_OK;
}

void mpb_store_close(mpb_store *s)
{
    if (s == NULL)
        return;
    ckpt_stop(s);
    for (int i = 0; i < MPB__ST_COUNT; i++)
        sqlite3_finalize(s->stmt[i]);
    for (int i = 0; i < MPB__METRIC_ROWS_MAX; i++)
        sqlite3_finalize(s->metric_rows[i]);
    sqlite3_close(s->db);
    /* Last: SQLite's locks on the file are gone with its connections. */
    if (s->fd >= 0)
        close(s->fd);
    free(s->path);
    free(s->pack);
    free(s);
}

static const char *const side_suffix[2] = {"-wal", "-shm"};

/* While the file at path is ours, so are the -wal and -shm beside it:
 * remember who they are. */
static void note_side_files(mpb_store *s)
{
    char side[4096];
    struct stat st;
    for (int i = 0; i < 2; i++) {
        snprintf(side, sizeof side, "%s%s", s->path, side_suffix[i]);
        if (stat(side, &st) == 0) {
            s->side_dev[i] = st.st_dev;
            s->side_ino[i] = st.st_ino;
            s->side_seen[i] = 1;
        }
    }
}

/* Our file has no name left, so what our -wal holds is lost with it; left
 * beside whatever the path names now (a file moved over ours, or one made
 * there later), SQLite would replay our pages into that file. Remove our
 * own -wal and -shm, and nothing that is not ours. */
static void drop_side_files(mpb_store *s)
{
    char side[4096];
    struct stat st;
    for (int i = 0; i < 2; i++) {
        snprintf(side, sizeof side, "%s%s", s->path, side_suffix[i]);
        if (s->side_seen[i] && stat(side, &st) == 0 &&
            st.st_dev == s->side_dev[i] && st.st_ino == s->side_ino[i])
            unlink(side);
    }
}

int mpb_store_check_file(mpb_store *s)
{
    struct stat now, own;
    if (s->fd < 0)
        return MPB_OK;
    if (fstat(s->fd, &own) != 0)
        return mpb__store_fail(s, MPB_EIO, "%s: %s", s->path, strerror(errno));
    /* Links left to the file we write: 0, and what it holds dies with us. */
    const char *fate = own.st_nlink == 0 ? "what was written to it is lost"
                     : "it lives on under another name";
    if (stat(s->path, &now) != 0) {
        if (errno != ENOENT)
            return mpb__store_fail(s, MPB_EIO, "%s: %s", s->path,
                                   strerror(errno));
        if (own.st_nlink == 0)
            drop_side_files(s);
        return mpb__store_fail(s, MPB_ENOTFOUND, "%s was %s while in use: %s",
                               s->path, own.st_nlink == 0 ? "removed" : "moved",
                               fate);
    }
    if (now.st_dev != s->dev || now.st_ino != s->ino) {
        if (own.st_nlink == 0)
            drop_side_files(s);
        return mpb__store_fail(s, MPB_EEXISTS, "%s was replaced by another "
                               "file while in use: the file written to %s",
                               s->path, own.st_nlink == 0 ? "is gone, and "
                               "what was written to it lost" : "lives on "
                               "under another name");
    }
    note_side_files(s);
    return MPB_OK;
}

/* SQLite's PENDING byte (os.h, PENDING_BYTE): a connection asks for it,
 * as a write lock, on its way to an EXCLUSIVE lock, and no connection can
 * take a SHARED lock, as every reader must to begin, while another holds
 * it. In WAL mode a connection closing asks for EXCLUSIVE (to checkpoint
 * and remove the WAL if it is the last), fails while the daemon holds
 * SHARED, but holds PENDING meanwhile: a reader opening the database at
 * that moment, with no busy timeout, is refused ("database is locked").
 * Readers closing while others open (two sqlite3 shells, a script beside
 * one) refused each other so, a few times in a thousand while the daemon
 * ran (issue 47). A read lock on the byte, held by the daemon, makes that
 * request fail at once, before PENDING is held: readers, which take the
 * byte only as a read lock for a moment, are never refused. Held on the
 * store's own descriptor, closed only after SQLite's connections
 * (fcntl() locks are the process's: closing any descriptor of the file
 * would drop them all). */
#define SQLITE_PENDING_BYTE 0x40000000L

static void admit_readers(mpb_store *s)
{
    struct flock fl = {.l_type = F_RDLCK, .l_whence = SEEK_SET,
                       .l_start = SQLITE_PENDING_BYTE, .l_len = 1};
    /* Best effort: without it, readers are as SQLite leaves them. */
    (void)fcntl(s->fd, F_SETLK, &fl);
}

int mpb_store_claim(mpb_store *s)
{
    if (s->fd < 0)
        return mpb__store_fail(s, MPB_EINVAL, "claim: the database is open "
                               "for reading only");
    if (flock(s->fd, LOCK_EX | LOCK_NB) == 0) {
        note_side_files(s);     /* ours now, as the file is */
        admit_readers(s);
        return MPB_OK;
    }
    if (errno == EWOULDBLOCK)
        return mpb__store_fail(s, MPB_EBUSY, "%s is claimed by another "
                               "process", s->path);
    return mpb__store_fail(s, MPB_EIO, "claim %s: %s", s->path, strerror(errno));
}

const char *mpb_store_errmsg(const mpb_store *s)
{
    if (s == NULL)
        return "out of memory";
    return s->errmsg[0] ? s->errmsg : "no error";
}

int mpb__store_step(mpb_store *s, mpb__stmt_id id, const char *what)
{
    sqlite3_stmt *st = mpb__store_stmt(s, id);
    if (st == NULL)
        return MPB_EDB;
    int rc = sqlite3_step(st);
    sqlite3_reset(st);
    return rc == SQLITE_DONE ? MPB_OK : mpb__store_db_fail(s, what);
}

/* Open the wanted transaction, if there is one. A failure sticks until the
 * commit, which reports it: nothing of that transaction runs outside it. */
static int tx_open(mpb_store *s)
{
    if (s->in_tx != MPB__TX_WANTED)
        return MPB_OK;
    if (s->tx_failed)
        return MPB_EDB;
    int rc = mpb__store_step(s, MPB__ST_BEGIN, "begin");
    if (rc == MPB_OK)
        s->in_tx = MPB__TX_OPEN;
    else
        s->tx_failed = 1;
    return rc;
}

int mpb__store_tx_open(mpb_store *s)
{
    return tx_open(s);
}

int mpb_store_begin(mpb_store *s)
{
    if (s->in_tx != MPB__TX_NONE)
        return mpb__store_fail(s, MPB_EDB, "begin: a transaction is already "
                               "open");
    s->in_tx = MPB__TX_WANTED;
    s->tx_failed = 0;
    return MPB_OK;
}

int mpb_store_commit(mpb_store *s)
{
    if (s->in_tx == MPB__TX_WANTED) {
        /* Nothing ran: nothing to commit (or the failure to open it). */
        s->in_tx = MPB__TX_NONE;
        return s->tx_failed ? MPB_EDB : MPB_OK;
    }
    int rc = mpb__store_step(s, MPB__ST_COMMIT, "commit");
    if (rc == MPB_OK)
        s->in_tx = MPB__TX_NONE;
    return rc;
}

int mpb_store_rollback(mpb_store *s)
{
    int was = s->in_tx;
    s->in_tx = MPB__TX_NONE;
    return was == MPB__TX_WANTED ? MPB_OK
                                 : mpb__store_step(s, MPB__ST_ROLLBACK, "rollback");
}
