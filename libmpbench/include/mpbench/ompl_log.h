/*
 * ompl_log.h - reading the benchmark logs that OMPL's ompl::tools::Benchmark
 * (and MoveIt's benchmark executor, in the same format) write, so that
 * their results can be imported into an mpbench database (`mpb import`)
 * and reported, plotted and exported beside mpbench's own.
 *
 * The format (one experiment per file, as OMPL 1.5's
 * Benchmark::saveResultsToStream() writes it):
 *
 *   OMPL version 1.5.2
 *   Experiment NAME
 *   K experiment properties          K lines "name TYPE = value"
 *   Running on HOST
 *   Starting at DATE
 *   <<<| setup |>>>   [<<<| cpuinfo |>>>]
 *   SEED is the random seed
 *   T seconds per run
 *   M MB per run
 *   [N runs per planner]
 *   S seconds spent to collect the data
 *   [E enum type(s)                  E lines "name|value0|value1|..."]
 *   P planners
 *   then per planner: its name; C common properties ("name = value"); R
 *   properties for each run ("name TYPE"); N runs, one line each of R
 *   values "v1; v2; ...; "; optionally Q progress properties and N lines
 *   of samples "a,b,;a,b,;"; and a line ".".
 *
 * Values that are empty, "nan" or "inf" read as NaN (an INTEGER's past
 * 2^53 is also kept exactly, in the planner's exact list); BOOLEAN values are
 * 0 or 1 (also written "true"/"false"). A property's type is REAL,
 * INTEGER, BOOLEAN or ENUM, and each value must be one of its type, as
 * OMPL writes it: an INTEGER one of at most 64 bits, an ENUM an index
 * into its enum's values, a REAL a number, nan or inf, the "time" no less
 * than 0 (an empty value, for what a run did not measure, is any type's).
 * SEED is a number, DATE starts "YYYY-". Nothing may follow the last
 * planner but blank lines.
 */
#ifndef MPBENCH_OMPL_LOG_H
#define MPBENCH_OMPL_LOG_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mpb_ompl_property {
    char *name;                 /* "time", "solution length", ... */
    char *type;                 /* "REAL", "BOOLEAN", "INTEGER", "ENUM", ... */
} mpb_ompl_property;

/* An integer of a run that a double does not hold exactly (past 2^53),
 * as written. */
typedef struct mpb_ompl_exact {
    size_t    cell;             /* index into the planner's values */
    long long value;
} mpb_ompl_exact;

typedef struct mpb_ompl_planner {
    char  *name;                /* "geometric_RRTConnect" */
    char  *settings;            /* common properties, "k = v" joined by ';' */
    char  *settings_text;       /* the same as OMPL's script stores them:
                                   each line as written, then "\n;" */
    int    num_properties;
    mpb_ompl_property *properties;
    long   num_runs;
    double *values;             /* num_runs x num_properties, row-major;
                                   NaN where empty, nan or inf; a REAL
                                   the double SQLite makes of its text,
                                   as OMPL's script stores it */
    int    num_progress_properties;   /* the first is the sample's time
                                         (the log's "time", wherever the
                                         log lists it) */
    mpb_ompl_property *progress_properties;
    long  *progress_start;      /* num_runs + 1 offsets into progress, in
                                   samples */
    double *progress;           /* samples x num_progress_properties */
    long   num_exact;           /* INTEGER values past 2^53, by cell */
    mpb_ompl_exact *exact;
} mpb_ompl_planner;

/* An experiment property line "name TYPE = value" (OMPL's experiment
 * parameters, mpbench's query): each part as written. */
typedef struct mpb_ompl_param {
    char *name;                 /* "wall width" */
    char *type;                 /* "REAL", "INTEGER", ... */
    char *value;                /* "0.6" */
} mpb_ompl_param;

/* An enum line "name|value0|value1|...": value i is values[i]. */
typedef struct mpb_ompl_enum {
    char  *name;
    int    num_values;
    char **values;
} mpb_ompl_enum;

typedef struct mpb_ompl_log {
    char  *version;             /* "OMPL 1.5.2", "MoveIt 1.1.9", ... */
    char  *experiment;          /* the experiment's name */
    char  *host, *date, *setup, *cpuinfo;
    char  *seed;                /* as written */
    double time_limit;          /* s per run */
    double memory_limit;        /* MB per run */
    double total_time;          /* s spent collecting the data */
    long   runs_per_planner;    /* -1 when not written */
    int    num_params;          /* experiment properties, in the log's order */
    mpb_ompl_param *params;
    int    num_enums;
    mpb_ompl_enum *enums;
    int    num_planners;
    mpb_ompl_planner *planners;
} mpb_ompl_log;

/*
 * Parse a log held in text[0..len) (it need not end in NUL). On success
 * *out is a new log, freed with mpb_ompl_log_close(). On failure returns
 * MPB_EPARSE (or MPB_ENOMEM, MPB_EINVAL for NULL arguments) with one line
 * in err: "line N: what was expected" (lines count from 1).
 */
int mpb_ompl_log_open(const char *text, size_t len, mpb_ompl_log **out,
                      char *err, size_t errlen);

void mpb_ompl_log_close(mpb_ompl_log *log);

struct mpb_export_counts;

/*
 * Write the log, as read, straight into a Planner Arena database at path,
 * as OMPL's ompl_benchmark_statistics.py does (its tables, the status
 * enum, one runs row per run with the log's properties as columns, the
 * progress, its two views), in one transaction: what `mpb import
 * --planner-arena` does without an mpbench database. path must not exist
 * (MPB_EEXISTS) unless flags has MPB_EXPORT_APPEND (store.h). A new
 * database is written into a file beside path ("PATH.tmp-PID-N") and
 * takes the name path only once complete and on disk, never replacing a
 * file that appeared meanwhile; an existing one (MPB_EXPORT_APPEND) is
 * added to in one transaction. counts (may be NULL) says what was
 * written; on failure err says why, path is as it was and no temporary
 * file is left.
 */
int mpb_ompl_log_to_planner_arena(const mpb_ompl_log *log, const char *path,
                                  int flags, struct mpb_export_counts *counts,
                                  char *err, size_t errlen);

/*
 * Gives the next log to write: *log, or NULL after the last, and MPB_OK.
 * The log stays the caller's and need live only until the next call. Any
 * other return abandons the writing (the caller tells why).
 */
typedef int (*mpb_ompl_log_next_fn)(void *ud, const mpb_ompl_log **log);

/*
 * mpb_ompl_log_to_planner_arena() for every log next(ud, ...) gives, one
 * at a time, all into the one database at path and in the one transaction:
 * each log need be held only while it is written. If next() fails,
 * nothing is written (path is as it was, no temporary file is left) and
 * its return is returned.
 */
int mpb_ompl_logs_to_planner_arena(const char *path, int flags,
                                   mpb_ompl_log_next_fn next, void *ud,
                                   struct mpb_export_counts *counts,
                                   char *err, size_t errlen);

/* The index of the run property of that name, or -1. */
int mpb_ompl_planner_property(const mpb_ompl_planner *p, const char *name);

/*
 * The mpbench status (mpb_status_name()'s names) nearest to a value of
 * OMPL's base::PlannerStatus: 0 (unknown), 8 (abort) and 9 (infeasible)
 * "failed", 1-3 "invalid_request", 4 "timeout", 5 "approximate", 6
 * "solved", 7 "crash"; and of the two mpb export adds, 10
 * "invalid_request" and 11 "memory"; NULL for any other value (NaN,
 * non-integers).
 */
const char *mpb_ompl_status_name(double ompl_status);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_OMPL_LOG_H */
