/*
 * store_pa.h - what the writers of OMPL's formats share; not part of the
 * API. docs/planner-arena.md is the mapping, and the database OMPL 1.5.2's
 * ompl_benchmark_statistics.py builds the target (bench/ompl_peer.sh).
 *
 *   store_pa_props.c   an mpbench experiment as run properties: their
 *                      names and types
 *   store_pa_walk.c    a walk that turns each finished run into a row
 *                      of them
 *   store_pa_exp.c     what every writer says of an experiment: its
 *                      header, queries, settings
 *   store_pa_db.c      the Planner Arena database: its tables, columns,
 *                      values and views, as OMPL's script makes them
 *   store_export.c     mpbench experiments into that database
 *   store_export_log.c mpbench experiments as OMPL benchmark logs
 *   ompl_log_pa.c      an OMPL benchmark log into that database
 *
 * Everything they read of mpbench's own database comes through
 * store/store_export.h.
 */
#ifndef MPB_STORE_PA_H
#define MPB_STORE_PA_H

#include <stdint.h>

#include <sqlite3.h>

#include "mpbench/ompl_log.h"
#include "store/store_columns.h"
#include "store/store_export.h"

/* ---- run properties (store_pa_props.c) ------------------------------------ */

/* What fills a property. */
typedef enum {
    K_TIME, K_TIME_RAW, K_TIME_OTHER, K_WALL, K_VERIFY, K_MEMORY, K_SOLVED, K_CLAIMED, K_APPROX,
    K_STATUS, K_STAGE_TIME, K_STAGE_METRIC, K_STAGE_SEGMENTS, K_STAGE_VALID,
    K_VALUE
} prop_kind;

/* Which stage a stage property reads: ROLE_SIMPLIFIED is the final
 * stage of an imported log's run, none when it is the first (the log had
 * no simplified solution). */
typedef enum { ROLE_FIRST, ROLE_MID, ROLE_FINAL, ROLE_SIMPLIFIED } stage_role;

typedef struct prop {
    char       *name;       /* as in a log: words joined by single spaces */
    const char *type;       /* REAL, INTEGER, BOOLEAN or ENUM */
    prop_kind   kind;
    stage_role  role;
    char       *stage;      /* ROLE_MID: the stage's name */
    char       *source;     /* metric or planner value name */
} prop;

typedef struct prop_list {
    prop *v;
    int   n, cap;
} prop_list;

typedef struct name_list {
    char **v;
    int    n, cap;
} name_list;

/*
 * The status enum: OMPL's PlannerStatus values and names (0-9, as OMPL
 * 1.5+ and its Benchmark class write them), and two of mpbench's own:
 * 10 "Invalid request", 11 "Out of memory" (a run stopped by the
 * experiment's memory_limit).
 */
#define MPB__PA_NUM_STATUS 12
extern const char *const mpb__pa_status_enum[MPB__PA_NUM_STATUS];

/* Experiment parameters added after the twelve columns Planner Arena
 * knows: name (a log's words) and SQL type. */
#define MPB__PA_NUM_EXP_PARAMS 2
extern const char *const mpb__pa_exp_params[MPB__PA_NUM_EXP_PARAMS][2];

void mpb__pa_props_free(prop_list *l);
void mpb__pa_names_free(name_list *l);

/* 1 if a and b name the same SQL column (case-insensitive, ' ' == '_'). */
int mpb__pa_same_column(const char *a, const char *b);

/*
 * The run properties of an experiment, in column order, and the names of
 * its progress properties (after "time"). Property names are unique.
 */
int mpb__pa_experiment_props(mpb_store *s, int64_t experiment_id,
                             prop_list *props, prop_list *progress);

/* ---- the walk over the runs (store_pa_walk.c) ------------------------------ */

/* One finished run, as the writers take it. */
typedef struct run_view {
    int64_t       run_id, config_id, query_id;
    const double *values;       /* one per run property; NaN for NULL */
    const int64_t *ints;        /* where is_int[k], the property is the
                                   integer ints[k] (values[k] the double
                                   nearest it: past 2^53 not the same) */
    const unsigned char *is_int;
    const double *samples;      /* num_samples rows of one value per
                                   progress property, time first */
    int           num_samples;
} run_view;

typedef struct pa_walker pa_walker;

/*
 * Walk the finished runs of an experiment (of one query when query_id > 0),
 * by scene, query, planner configuration and repetition. *out is NULL on
 * failure; mpb__pa_walker_close() takes either.
 */
int mpb__pa_walker_open(pa_walker **out, mpb_store *s, int64_t experiment_id,
                        int64_t query_id, const prop_list *props,
                        const prop_list *progress);

/* The next run into *out, valid until the next call: 1, or 0 at the
 * end, or an error. */
int mpb__pa_walker_next(pa_walker *w, run_view *out);

void mpb__pa_walker_close(pa_walker *w);

/* ---- what every writer says of an experiment (store_pa_exp.c) -------------- */

/* The experiment itself: exp_info, mpb__store_exp_info_read()
 * (store/store_export.h). */


/* Whitespace to '_': a log's "Experiment NAME" line keeps one word. */
void mpb__pa_one_word(char *s);

/* The column OMPL's script gives the experiment property of that name:
 * its words joined with nothing, '-' as '_' ("wall height" is
 * "wallheight"). Caller frees; NULL when out of memory. */
char *mpb__pa_param_column(const char *name);

/* The value e's log had for the experiment property whose column is
 * column (mpb__pa_param_column()), or NULL. */
const char *mpb__pa_exp_param(const exp_info *e, const char *column);

/* "mpbench 0.1.0" as the experiment recorded it, never empty (Planner
 * Arena sorts and selects by it). */
const char *mpb__pa_version_of(const exp_info *e);

/* "2024-05-01 12:34:56" (UTC) of a Unix time; "" if there is none. */
void mpb__pa_format_date(double t, char *buf, size_t n);

/* A Planner Arena experiment: one query of an mpbench experiment. */
typedef struct pa_query {
    int64_t query_id;
    char   *problem;    /* "<experiment>/<scene>", one word, "#N" after
                           a scene whose word another scene has */
    char   *query;      /* the query's name */
    char   *setup;      /* the experiment file and the query */
    long    runs;
    double  total_time; /* sum of the runs' wall times */
} pa_query;

typedef struct pa_query_list {
    pa_query *v;
    int       n, cap;
} pa_query_list;

/* The queries of experiment e with finished runs, by scene and query. */
int mpb__pa_read_queries(mpb_store *s, const exp_info *e, pa_query_list *out);
void mpb__pa_queries_free(pa_query_list *l);

/*
 * A planner configuration's common properties, as OMPL's script stores
 * them from a log's "name = value" lines: sorted, each line followed by
 * "\n;". Caller frees; NULL when out of memory.
 */
char *mpb__pa_config_settings(const char *planner, const char *algorithm,
                              const char *params);

/* ---- the Planner Arena database (store_pa_db.c) ---------------------------- */

typedef struct pa_out {
    mpb_store *s;                   /* errors go here */
    sqlite3   *db;
    const char *path;
    mpb_export_counts counts;
    int64_t   *config_map;          /* pairs: mpbench config id, plannerid */
    int        num_configs, configs_cap;
} pa_out;

/* Record SQLite's error for what was being done, after o->path; MPB_EDB. */
int mpb__pa_fail(pa_out *o, const char *what);

/* Run sql (several statements may follow each other). */
int mpb__pa_exec(pa_out *o, const char *sql, const char *what);

/* Open a transaction and create the tables that are missing, as OMPL's
 * script does before it reads a log; with status_enum, add mpbench's
 * status enum too (a log brings its own). */
int mpb__pa_begin(pa_out *o, int status_enum);

/* mpbench's status enum (mpb__pa_status_enum), the values missing. */
int mpb__pa_add_status_enum(pa_out *o);

/* An OMPL log as OMPL's script writes it (ompl_log_pa.c): the experiment,
 * its enums, planners, runs and progress. */
int mpb__pa_write_log(pa_out *o, const mpb_ompl_log *log);

/* End what mpb__pa_begin() began and close o->db (if open): with rc
 * MPB_OK the views made anew and the transaction committed, otherwise
 * rolled back. rc, or the first error of these. */
int mpb__pa_finish(pa_out *o, int rc);

/* Add the columns of props missing from table (from props->v[first] on),
 * as OMPL's script does with ALTER TABLE. */
int mpb__pa_ensure_columns(pa_out *o, const char *table,
                           const prop_list *props, int first);

/*
 * Prepare "VERB INTO table (fixed, props...) VALUES (values, ?, ...), ..."
 * with rows rows: values is the fixed columns' text, the same in every
 * row ("?" parameters, or numbers written out), then a parameter for each
 * property. Many rows a statement share its own cost among them.
 */
int mpb__pa_prepare_rows(pa_out *o, const char *verb, const char *table,
                         const char *fixed, const char *values,
                         const prop_list *props, int rows,
                         sqlite3_stmt **out);

/* The affinity SQLite gives a column declared type: 'I' INTEGER, 'T'
 * TEXT, 'B' BLOB, 'R' REAL, 'N' NUMERIC. */
char mpb__pa_affinity(const char *type);

/* The affinity of the column of each of props in table, as the database
 * declares it (which an earlier log may have), into out[0..props->n). */
int mpb__pa_affinities(pa_out *o, const char *table, const prop_list *props,
                       char *out);

/* A number as the script's text becomes in a column of that affinity:
 * NULL for NaN, an integer (unless the column is REAL) or a real. */
void mpb__pa_bind_number(sqlite3_stmt *st, int i, int real, double v);

#endif /* MPB_STORE_PA_H */
