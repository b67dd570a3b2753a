/*
 * store_export_csv.c - the run_summary view (one row per finished run,
 * docs/schema.md) as CSV, for people who analyse the runs with their own
 * tools (mpb_store_export_runs_csv(); docs/analysis.md).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "store/store_export.h"
#include "store/store_internal.h"

/* A number in the fewest digits that read back as it: 0.08, not the
 * 0.080000000000000002 of %.17g. */
static void put_real(FILE *out, double v)
{
    char buf[40];
    for (int digits = 15; digits <= 17; digits++) {
        snprintf(buf, sizeof buf, "%.*g", digits, v);
        if (strtod(buf, NULL) == v)
            break;
    }
    fputs(buf, out);
}

/* Text as RFC 4180 has it: quoted when it holds a comma, a quote, a line
 * break or space at either end (which readers strip), quotes doubled. */
static void put_text(FILE *out, const char *t)
{
    size_t n = strlen(t);
    int quote = n > 0 && (t[0] == ' ' || t[n - 1] == ' ');
    for (const char *c = t; *c && !quote; c++)
        quote = *c == ',' || *c == '"' || *c == '\n' || *c == '\r';
    if (!quote) {
        fputs(t, out);
        return;
    }
    fputc('"', out);
    for (const char *c = t; *c; c++) {
        if (*c == '"')
            fputc('"', out);
        fputc(*c, out);
    }
    fputc('"', out);
}

int mpb_store_export_runs_csv(mpb_store *s, FILE *out, const int64_t *ids,
                              int num_ids, long *rows)
{
    /* run_summary's own SELECT, so that a database made before the view
     * (opened read-only, not migrated) is read the same. */
    const char *select = mpb__store_has_column(s, "scenes", "problem_set")
                         ? mpb__run_summary_select
                         : mpb__run_summary_select_old;
    size_t cap = strlen(select) + 96 + (size_t)num_ids * 2;
    char *sql = malloc(cap);
    if (rows != NULL)
        *rows = 0;
    if (sql == NULL)
        return mpb__store_fail(s, MPB_ENOMEM, "out of memory");
    size_t n = (size_t)snprintf(sql, cap, "SELECT * FROM (%s)", select);
    for (int i = 0; i < num_ids; i++)
        n += (size_t)snprintf(sql + n, cap - n, "%s?", i ? "," : " WHERE "
                              "experiment_id IN (");
    snprintf(sql + n, cap - n, "%s ORDER BY run", num_ids ? ")" : "");
    if (num_ids > 0) {                  /* each id given must exist */
        int64_t *known = NULL;
        int num_known = 0;
        int rc = mpb__store_experiment_ids(s, ids, num_ids, &known,
                                           &num_known);
        free(known);
        if (rc != MPB_OK) {
            free(sql);
            return rc;
        }
    }
    sqlite3_stmt *st = mpb__store_prepare(s, sql);
    free(sql);
    if (st == NULL)
        return MPB_EDB;
    for (int i = 0; i < num_ids; i++)
        sqlite3_bind_int64(st, i + 1, ids[i]);
    int cols = sqlite3_column_count(st), step;
    for (int c = 0; c < cols; c++) {
        fputs(c ? "," : "", out);
        put_text(out, sqlite3_column_name(st, c));
    }
    fputc('\n', out);
    long count = 0;
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        for (int c = 0; c < cols; c++) {
            if (c)
                fputc(',', out);
            switch (sqlite3_column_type(st, c)) {
            case SQLITE_INTEGER:
                fprintf(out, "%lld", (long long)sqlite3_column_int64(st, c));
                break;
            case SQLITE_FLOAT:
                put_real(out, sqlite3_column_double(st, c));
                break;
            case SQLITE_NULL:
                break;
            default:
                put_text(out, (const char *)sqlite3_column_text(st, c));
                break;
            }
        }
        fputc('\n', out);
        count++;
    }
    int rc = step == SQLITE_DONE ? MPB_OK
                                 : mpb__store_db_fail(s, "read run_summary");
    sqlite3_finalize(st);
    if (rc == MPB_OK && ferror(out))
        rc = mpb__store_fail(s, MPB_EIO, "cannot write the CSV");
    if (rows != NULL)
        *rows = count;
    return rc;
}
