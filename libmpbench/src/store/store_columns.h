/* store_columns.h - reading one column of a result row, the one way the
 * store's files and interop/ (whose Planner Arena database is SQLite
 * too) read it. Not part of the API.
 *
 * SQLite stores a NaN as NULL, so a REAL column that may be NULL reads
 * back as NaN; an INTEGER column that may be NULL takes the caller's
 * value for "none". Text pointers live until the next step or reset of
 * the statement, as sqlite3_column_text()'s do. */
#ifndef MPB_STORE_COLUMNS_H
#define MPB_STORE_COLUMNS_H

#include <math.h>
#include <sqlite3.h>
#include <stdlib.h>
#include <string.h>

static inline int mpb__col_is_null(sqlite3_stmt *st, int i)
{
    return sqlite3_column_type(st, i) == SQLITE_NULL;
}

/* A REAL column, NaN when NULL. */
static inline double mpb__col_real(sqlite3_stmt *st, int i)
{
    return mpb__col_is_null(st, i) ? NAN : sqlite3_column_double(st, i);
}

/* A REAL column, NaN when NULL and when not finite: what an export
 * writes as "no value". */
static inline double mpb__col_finite(sqlite3_stmt *st, int i)
{
    double v = mpb__col_real(st, i);
    return isfinite(v) ? v : NAN;
}

/* An INTEGER column, none when NULL. */
static inline int mpb__col_int_or(sqlite3_stmt *st, int i, int none)
{
    return mpb__col_is_null(st, i) ? none : sqlite3_column_int(st, i);
}

/* A TEXT column, NULL when NULL. */
static inline const char *mpb__col_text(sqlite3_stmt *st, int i)
{
    return (const char *)sqlite3_column_text(st, i);
}

/* A TEXT column, "" when NULL. */
static inline const char *mpb__col_text_or_empty(sqlite3_stmt *st, int i)
{
    const char *t = mpb__col_text(st, i);
    return t ? t : "";
}

/* A TEXT column copied with malloc ("" for NULL); NULL when out of
 * memory. The caller frees it. */
static inline char *mpb__col_dup(sqlite3_stmt *st, int i)
{
    return strdup(mpb__col_text_or_empty(st, i));
}

#endif
