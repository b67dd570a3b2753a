/* store_internal.h - what the store's files share; not part of the API. */
#ifndef MPB_STORE_INTERNAL_H
#define MPB_STORE_INTERNAL_H

#include <sqlite3.h>

#include "mpbench/mpbench.h"

#define MPB__SCHEMA_VERSION 1

extern const char mpb__schema_v1[];

/* Prepared statements, made once per handle and kept (SQLite's own advice
 * for statements run thousands of times). */
typedef enum mpb__stmt_id {
    MPB__ST_BEGIN,
    MPB__ST_COMMIT,
    MPB__ST_ROLLBACK,
    MPB__ST_RUN_SENT,
    MPB__ST_RUN_FINISH,
    MPB__ST_STAGE_INSERT,
    MPB__ST_METRIC_INSERT,
    MPB__ST_VALUE_INSERT,
    MPB__ST_PROGRESS_INSERT,
    MPB__ST_RUN_ADD,
    MPB__ST_COUNT
} mpb__stmt_id;

struct mpb_store {
    sqlite3      *db;
    int           readonly;
    int           in_tx;
    sqlite3_stmt *stmt[MPB__ST_COUNT];
    char          errmsg[256];
};

/* Record an error on s (printf-style) and return code. */
int mpb__store_fail(mpb_store *s, int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Record SQLite's error for what was being done and return MPB_EDB. */
int mpb__store_db_fail(mpb_store *s, const char *what);

/* The statement id, prepared on first use; NULL on failure (error set). */
sqlite3_stmt *mpb__store_stmt(mpb_store *s, mpb__stmt_id id);

/* Prepare a one-off statement; NULL on failure (error set). */
sqlite3_stmt *mpb__store_prepare(mpb_store *s, const char *sql);

#endif
