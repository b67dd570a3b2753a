/* store.c - opening the database, its schema version, transactions, errors. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "store_internal.h"

/* Unix time in seconds with milliseconds (unixepoch('subsec') needs
 * SQLite 3.42; Debian 12 has 3.40). */
#define NOW_SQL "((julianday('now') - 2440587.5) * 86400.0)"

static const char *const stmt_sql[MPB__ST_COUNT] = {
    [MPB__ST_BEGIN] = "BEGIN IMMEDIATE",
    [MPB__ST_COMMIT] = "COMMIT",
    [MPB__ST_ROLLBACK] = "ROLLBACK",
    [MPB__ST_RUN_SENT] =
        "UPDATE runs SET state = 'sent', run_uid = ?2, planner_id = ?3,"
        " attempts = attempts + 1, sent = " NOW_SQL
        " WHERE id = ?1 AND state != 'done'",
    [MPB__ST_RUN_FINISH] =
        "UPDATE runs SET state = 'done', finished = " NOW_SQL ","
        " planner_id = ?3, status = ?4, message = ?5, claimed_success = ?6,"
        " valid = ?7, verdict = ?8, success = ?9, time_total = ?10,"
        " time_raw = ?11, time_other = ?12, wall_time = ?13, final_stage = ?14"
        " WHERE id = ?1 AND run_uid = ?2 AND state != 'done'",
    [MPB__ST_STAGE_INSERT] =
        "INSERT OR REPLACE INTO stages(run_id, idx, name, time, num_waypoints,"
        " num_joints, waypoints, valid, verdict, verdict_detail,"
        " verdict_segment) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11)",
    [MPB__ST_METRIC_INSERT] =
        "INSERT OR REPLACE INTO metrics(run_id, stage, name, value)"
        " VALUES (?1, ?2, ?3, ?4)",
    [MPB__ST_VALUE_INSERT] =
        "INSERT OR REPLACE INTO planner_values(run_id, name, value)"
        " VALUES (?1, ?2, ?3)",
    [MPB__ST_PROGRESS_INSERT] =
        "INSERT OR REPLACE INTO progress(run_id, seq, time, name, value)"
        " VALUES (?1, ?2, ?3, ?4, ?5)",
    [MPB__ST_RUN_ADD] =
        "INSERT OR IGNORE INTO runs(experiment_id, planner_config_id,"
        " query_id, repetition, seed) VALUES (?1, ?2, ?3, ?4, ?5)",
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

sqlite3_stmt *mpb__store_prepare(mpb_store *s, const char *sql)
{
    sqlite3_stmt *st = NULL;
    if (sqlite3_prepare_v2(s->db, sql, -1, &st, NULL) != SQLITE_OK) {
        mpb__store_db_fail(s, "prepare");
        return NULL;
    }
    return st;
}

sqlite3_stmt *mpb__store_stmt(mpb_store *s, mpb__stmt_id id)
{
    if (s->stmt[id] == NULL)
        s->stmt[id] = mpb__store_prepare(s, stmt_sql[id]);
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

static int create_schema(mpb_store *s)
{
    int version, rc;
    if ((rc = exec(s, "BEGIN IMMEDIATE", "begin")) != MPB_OK)
        return rc;
    if ((rc = exec(s, mpb__schema_v1, "create schema")) != MPB_OK)
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

int mpb_store_open(const char *path, int readonly, mpb_store **out)
{
    mpb_store *s = calloc(1, sizeof *s);
    int flags = readonly ? SQLITE_OPEN_READONLY
                         : SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE;
    int rc;

    *out = s;
    if (s == NULL)
        return MPB_ENOMEM;
    s->readonly = readonly;
    if (sqlite3_open_v2(path, &s->db, flags, NULL) != SQLITE_OK) {
        return mpb__store_fail(s, MPB_EIO, "cannot open database %s: %s", path,
                               s->db ? sqlite3_errmsg(s->db) : "out of memory");
    }
    /* Several processes (the daemon, `mpb report`, sqlite3) share the file;
     * wait for a lock rather than fail. */
    sqlite3_busy_timeout(s->db, 5000);
    if (readonly) {
        int version;
        if ((rc = schema_version(s, &version)) != MPB_OK)
            return mpb__store_fail(s, MPB_EDB, "%s is not an mpbench database",
                                   path);
        if (version != MPB__SCHEMA_VERSION)
            return mpb__store_fail(s, MPB_EUNSUPPORTED,
                                   "%s has schema version %d, expected %d",
                                   path, version, MPB__SCHEMA_VERSION);
        return MPB_OK;
    }
    /* WAL: readers never block the daemon's writer. synchronous=NORMAL keeps
     * every committed transaction across a process crash (only a power loss
     * can take the last ones), at a fraction of FULL's fsyncs. Savepoint
     * journals in memory and a 16 MiB page cache: each run's savepoint
     * otherwise spills to a temporary file (bench/mkdb.c: 367 -> 190 us per
     * run at one transaction per run). */
    if ((rc = exec(s, "PRAGMA journal_mode=WAL; PRAGMA synchronous=NORMAL;"
                      " PRAGMA foreign_keys=ON; PRAGMA temp_store=MEMORY;"
                      " PRAGMA cache_size=-16384;", "configure")) != MPB_OK)
        return rc;
    return create_schema(s);
}

void mpb_store_close(mpb_store *s)
{
    if (s == NULL)
        return;
    for (int i = 0; i < MPB__ST_COUNT; i++)
        sqlite3_finalize(s->stmt[i]);
    sqlite3_close(s->db);
    free(s);
}

const char *mpb_store_errmsg(const mpb_store *s)
{
    if (s == NULL)
        return "out of memory";
    return s->errmsg[0] ? s->errmsg : "no error";
}

static int step_done(mpb_store *s, mpb__stmt_id id, const char *what)
{
    sqlite3_stmt *st = mpb__store_stmt(s, id);
    if (st == NULL)
        return MPB_EDB;
    int rc = sqlite3_step(st);
    sqlite3_reset(st);
    return rc == SQLITE_DONE ? MPB_OK : mpb__store_db_fail(s, what);
}

int mpb_store_begin(mpb_store *s)
{
    int rc = step_done(s, MPB__ST_BEGIN, "begin");
    if (rc == MPB_OK)
        s->in_tx = 1;
    return rc;
}

int mpb_store_commit(mpb_store *s)
{
    int rc = step_done(s, MPB__ST_COMMIT, "commit");
    if (rc == MPB_OK)
        s->in_tx = 0;
    return rc;
}

int mpb_store_rollback(mpb_store *s)
{
    s->in_tx = 0;
    return step_done(s, MPB__ST_ROLLBACK, "rollback");
}
