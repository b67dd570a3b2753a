/* store_internal.h - what the store's files share; not part of the API. */
#ifndef MPB_STORE_INTERNAL_H
#define MPB_STORE_INTERNAL_H

#include <sqlite3.h>
#include <sys/types.h>

#include "mpbench/mpbench.h"

#define MPB__SCHEMA_VERSION 1

extern const char mpb__schema_v1[];
extern const char mpb__schema_results_view[];
extern const char mpb__schema_experiment_params[];
extern const char mpb__schema_log_properties[];
extern const char mpb__schema_fill_problem_sets[];
extern const char mpb__schema_run_summary_view[];
/* run_summary's SELECT (no ';'), and the same for a database made before
 * scenes.problem_set (opened read-only, not migrated): the sets by the
 * default rule. */
extern const char mpb__run_summary_select[];
extern const char mpb__run_summary_select_old[];

/* Whether the table (or view) has the column: a database made by an earlier
 * mpbench and opened read-only may lack one that a writer would add. */
int mpb__store_has_column(mpb_store *s, const char *table, const char *column);

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
    MPB__ST_SAVEPOINT,
    MPB__ST_RELEASE,
    MPB__ST_ROLLBACK_TO,
    MPB__ST_COUNT
} mpb__stmt_id;

/* mpb_store.in_tx: mpb_store_begin() only marks the transaction wanted; it
 * is opened (BEGIN IMMEDIATE) just before the first statement that needs
 * it, so that the daemon's loop, which begins and commits at every wake-up,
 * touches no lock when a wake-up writes nothing. */
enum { MPB__TX_NONE, MPB__TX_WANTED, MPB__TX_OPEN };

/* Most metric rows one INSERT writes (a stage has about seven). */
#define MPB__METRIC_ROWS_MAX 8

/* The WAL checkpointer of a writable handle (store.c). */
typedef struct mpb__checkpointer mpb__checkpointer;

struct mpb_store {
    sqlite3      *db;
    int           readonly;
    int           in_tx;        /* MPB__TX_... */
    int           tx_failed;    /* opening the wanted transaction failed */
    sqlite3_stmt *stmt[MPB__ST_COUNT];
    mpb__checkpointer *ckpt;    /* NULL: SQLite checkpoints in commits */
    /* INSERT of k metric rows in one statement, [k - 1], made on first
     * use (store_runs.c). */
    sqlite3_stmt *metric_rows[MPB__METRIC_ROWS_MAX];
    unsigned char *pack;        /* mpb__metrics_pack's buffer */
    size_t        pack_cap;
    char          errmsg[256];
    /* A writable handle's own descriptor of the file it opened, for
     * mpb_store_check_file() and mpb_store_claim(); -1 if none. Closed
     * after SQLite's connections: closing any descriptor of a file drops
     * the process's fcntl() locks on it, SQLite's among them. */
    int           fd;
    dev_t         dev;
    ino_t         ino;
    /* The -wal and -shm files seen beside it while it was still ours. */
    dev_t         side_dev[2];
    ino_t         side_ino[2];
    int           side_seen[2];
    char         *path;
};

/* Record an error on s (printf-style) and return code. */
int mpb__store_fail(mpb_store *s, int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Record SQLite's error for what was being done and return MPB_EDB. */
int mpb__store_db_fail(mpb_store *s, const char *what);

/* The statement id, prepared on first use; NULL on failure (error set).
 * Opens the wanted transaction first. */
sqlite3_stmt *mpb__store_stmt(mpb_store *s, mpb__stmt_id id);

/* Prepare a one-off statement; NULL on failure (error set). Opens the
 * wanted transaction first. */
sqlite3_stmt *mpb__store_prepare(mpb_store *s, const char *sql);

/*
 * runs.final_metrics: every metric of the run's final stage, packed, so
 * that a report reads one row per run instead of joining the metrics table
 * (docs/schema.md). Each metric is its name's length in one byte, the name
 * (no NUL), then the value as an 8-byte IEEE double in little-endian order.
 * The metrics table stays the reference; NULL means "look there" (a run
 * finished before the column existed, or a name longer than 255 bytes).
 */
#define MPB__PACK_NAME_MAX 255

/* Pack m[0..n) into s->pack; *out NULL (and MPB_OK) if it cannot be
 * packed, so the column stays NULL. */
int mpb__metrics_pack(mpb_store *s, const mpb_named *m, int n,
                      const unsigned char **out, int *len);

/* Unix time in seconds, for the sent and finished columns of runs: bound
 * from C. julianday('now') inside the statements cost about 1,200
 * instructions each, twice per run (callgrind). */
static inline double mpb__store_now(void)
{
    return (double)mpb_utime_now() * 1e-6;
}

/* Open the transaction mpb_store_begin() asked for, if not yet open (the
 * statement functions above do it themselves). */
int mpb__store_tx_open(mpb_store *s);

/* Step statement id, which returns no row, and reset it; MPB_OK or the
 * error (what says what was being done). */
int mpb__store_step(mpb_store *s, mpb__stmt_id id, const char *what);

#endif
