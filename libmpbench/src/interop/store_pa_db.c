/*
 * store_pa_db.c - the Planner Arena database (store_pa.h): its tables,
 * columns, values and views, as OMPL 1.5's ompl_benchmark_statistics.py
 * makes them, for the writers that fill it (store_export.c from an
 * mpbench store, ompl_log_pa.c from an OMPL log).
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/grow.h"
#include "interop/store_pa.h"

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

int mpb__pa_fail(pa_out *o, const char *what)
{
    return mpb__store_fail(o->s, MPB_EDB, "%s: %s: %s", o->path, what,
                           sqlite3_errmsg(o->db));
}

int mpb__pa_exec(pa_out *o, const char *sql, const char *what)
{
    char *msg = NULL;
    if (sqlite3_exec(o->db, sql, NULL, NULL, &msg) != SQLITE_OK) {
        mpb__store_fail(o->s, MPB_EDB, "%s: %s: %s", o->path, what,
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

int mpb__pa_ensure_columns(pa_out *o, const char *table,
                           const prop_list *props, int first)
{
    char sql[1024];
    sqlite3_stmt *st;
    snprintf(sql, sizeof sql, "PRAGMA table_info(%s)", table);
    if (sqlite3_prepare_v2(o->db, sql, -1, &st, NULL) != SQLITE_OK)
        return mpb__pa_fail(o, "read columns");
    name_list have = {0};
    int step, rc = MPB_OK;
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        if (mpb__grow((void **)&have.v, &have.cap, have.n + 1,
                      sizeof *have.v) ||
            (have.v[have.n] = mpb__col_dup(st, 1)) == NULL) {
            rc = MPB_ENOMEM;
            break;
        }
        have.n++;
    }
    sqlite3_finalize(st);
    for (int k = first; rc == MPB_OK && k < props->n; k++) {
        int found = 0;
        for (int i = 0; i < have.n && !found; i++)
            found = mpb__pa_same_column(have.v[i], props->v[k].name);
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
        rc = mpb__pa_exec(o, sql, "add a column");
    }
    mpb__pa_names_free(&have);
    if (rc == MPB_ENOMEM)
        mpb__store_fail(o->s, rc, "out of memory");
    return rc;
}

char mpb__pa_affinity(const char *type)
{
    /* SQLite's rules (datatype3.html, 3.1), in their order. */
    char up[64];
    size_t n = 0;
    for (; type && type[n] && n + 1 < sizeof up; n++)
        up[n] = (char)toupper((unsigned char)type[n]);
    up[n] = '\0';
    if (strstr(up, "INT"))
        return 'I';
    if (strstr(up, "CHAR") || strstr(up, "CLOB") || strstr(up, "TEXT"))
        return 'T';
    if (n == 0 || strstr(up, "BLOB"))
        return 'B';
    if (strstr(up, "REAL") || strstr(up, "FLOA") || strstr(up, "DOUB"))
        return 'R';
    return 'N';
}

int mpb__pa_affinities(pa_out *o, const char *table, const prop_list *props,
                       char *out)
{
    char sql[128];
    sqlite3_stmt *st;
    snprintf(sql, sizeof sql, "SELECT name, type FROM pragma_table_info('%s')",
             table);
    if (sqlite3_prepare_v2(o->db, sql, -1, &st, NULL) != SQLITE_OK)
        return mpb__pa_fail(o, "read columns");
    for (int k = 0; k < props->n; k++)
        out[k] = 'N';
    int step;
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        const char *name = (const char *)sqlite3_column_text(st, 0);
        const char *type = (const char *)sqlite3_column_text(st, 1);
        for (int k = 0; name && k < props->n; k++)
            if (mpb__pa_same_column(name, props->v[k].name))
                out[k] = mpb__pa_affinity(type);
    }
    sqlite3_finalize(st);
    return step == SQLITE_DONE ? MPB_OK : mpb__pa_fail(o, "read columns");
}

void mpb__pa_bind_number(sqlite3_stmt *st, int i, int real, double v)
{
    if (isnan(v))
        sqlite3_bind_null(st, i);
    else if (!real && v == floor(v) && fabs(v) < 9e15)
        sqlite3_bind_int64(st, i, (sqlite3_int64)v);
    else
        sqlite3_bind_double(st, i, v);
}

int mpb__pa_prepare_rows(pa_out *o, const char *verb, const char *table,
                         const char *fixed, const char *values,
                         const prop_list *props, int rows,
                         sqlite3_stmt **out)
{
    *out = NULL;
    size_t cap = 256 + strlen(fixed) +
                 (size_t)rows * (strlen(values) + 2 * (size_t)props->n + 4);
    for (int k = 0; k < props->n; k++)
        cap += strlen(props->v[k].name) + 8;
    char *sql = malloc(cap);
    if (sql == NULL)
        return mpb__store_fail(o->s, MPB_ENOMEM, "out of memory");
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
                 ? MPB_OK : mpb__pa_fail(o, "prepare an insert");
    free(sql);
    return rc;
}

/* The views of OMPL 1.5's script (not MoveIt's format): the best
 * configurations by average solved, then by time. */
static int create_views(pa_out *o)
{
    sqlite3_stmt *st;
    int simplification = 0;
    if (sqlite3_prepare_v2(o->db, "PRAGMA table_info(runs)", -1, &st, NULL) !=
        SQLITE_OK)
        return mpb__pa_fail(o, "read columns");
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
    int rc = mpb__pa_exec(o, "DROP VIEW IF EXISTS bestPlannerConfigsPerExperiment;"
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
    if ((rc = mpb__pa_exec(o, sql, "create a view")))
        return rc;
    snprintf(sql, sizeof sql,
             "CREATE VIEW IF NOT EXISTS bestPlannerConfigs AS"
             " SELECT plannerid, MIN(avg_solved) AS avg_solved, avg_total_time"
             " FROM (SELECT plannerid, plannerName, AVG(solved) AS avg_solved,"
             " AVG(total_time) AS avg_total_time FROM (%s) GROUP BY"
             " plannerid) GROUP BY plannerName ORDER BY avg_solved DESC,"
             " avg_total_time ASC", s0);
    return mpb__pa_exec(o, sql, "create a view");
}

int mpb__pa_begin(pa_out *o, int status_enum)
{
    int rc;
    if ((rc = mpb__pa_exec(o, "BEGIN IMMEDIATE", "begin")) ||
        (rc = mpb__pa_exec(o, pa_schema, "create the tables")) || !status_enum)
        return rc;
    return mpb__pa_add_status_enum(o);
}

int mpb__pa_add_status_enum(pa_out *o)
{
    int rc = MPB_OK;
    sqlite3_stmt *st;
    if (sqlite3_prepare_v2(o->db, "INSERT OR IGNORE INTO enums (name, value,"
                           " description) VALUES ('status', ?, ?)", -1, &st,
                           NULL) != SQLITE_OK)
        return mpb__pa_fail(o, "prepare enums");
    for (int i = 0; i < MPB__PA_NUM_STATUS && rc == MPB_OK; i++) {
        sqlite3_reset(st);
        sqlite3_bind_int(st, 1, i);
        sqlite3_bind_text(st, 2, mpb__pa_status_enum[i], -1, SQLITE_STATIC);
        if (sqlite3_step(st) != SQLITE_DONE)
            rc = mpb__pa_fail(o, "add the status enum");
    }
    sqlite3_finalize(st);
    return rc;
}

int mpb__pa_finish(pa_out *o, int rc)
{
    if (o->db == NULL)
        return rc;
    if (rc == MPB_OK && (rc = create_views(o)) == MPB_OK)
        rc = mpb__pa_exec(o, "COMMIT", "commit");
    if (rc != MPB_OK)
        sqlite3_exec(o->db, "ROLLBACK", NULL, NULL, NULL);
    if (sqlite3_close(o->db) != SQLITE_OK && rc == MPB_OK)
        rc = mpb__store_fail(o->s, MPB_EIO, "cannot close %s", o->path);
    o->db = NULL;
    return rc;
}
