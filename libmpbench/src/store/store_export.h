/*
 * store_export.h - private to libmpbench: what the exporters of interop/
 * (Planner Arena databases, OMPL benchmark logs) read of an experiment,
 * so that every SQL statement on mpbench's own tables is in store/.
 * Implemented in store_export_read.c.
 *
 * Strings a reader hands to a callback live during the call; strings it
 * returns in a struct are the caller's (freed by the struct's free
 * function). Every reader returns MPB_OK or a negative code with the
 * store's error set (mpb_store_errmsg()); a callback's nonzero return
 * stops the walk and is returned.
 */
#ifndef MPB_STORE_EXPORT_H
#define MPB_STORE_EXPORT_H

#include <stddef.h>
#include <stdint.h>

#include "mpbench/mpbench.h"

/* Record an error on s (printf-style) and return code (store.c). */
int mpb__store_fail(mpb_store *s, int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* A handle that opens no database, only to carry an error message
 * (mpb__store_fail(), mpb_store_errmsg()) through the exporters' code;
 * NULL when out of memory. Release it with mpb_store_close(). */
mpb_store *mpb__store_errors_create(void);

/* The path of the file s has open ("" for an in-memory one). */
const char *mpb__store_filename(mpb_store *s);

/* ---- experiments ------------------------------------------------------ */

/* An imported log's experiment property, as its log wrote it. */
typedef struct exp_param {
    char *name, *type, *value;
} exp_param;

typedef struct exp_info {
    int64_t id;
    char   *name, *config_text, *host, *version;
    int     runs_per_query;
    double  time_limit, created;
    /* An imported log's header (NULL, NaN when the experiment is
     * mpbench's own): its date as written, seed, CPU block, total time,
     * memory limit, and its experiment properties. */
    char   *started, *seed, *cpuinfo;
    double  total_time, memory_limit;
    int     num_params;
    exp_param *params;
} exp_info;

/* Experiment id into *e (zeroed first by the caller); MPB_ENOTFOUND if
 * there is none. Free with mpb__store_exp_info_free(), either way. */
int mpb__store_exp_info_read(mpb_store *s, int64_t id, exp_info *e);
void mpb__store_exp_info_free(exp_info *e);

/* Ids of every experiment, or the ids given (each checked: MPB_ENOTFOUND
 * "no experiment N"), each once, into *out (the caller frees) and *n. No
 * experiment at all is MPB_ENOTFOUND. */
int mpb__store_experiment_ids(mpb_store *s, const int64_t *ids, int num_ids,
                              int64_t **out, int *n);

/* Experiment id's file as stored (*text, the caller frees; NULL if none)
 * and how many runs it has, how many done. */
int mpb__store_experiment_completion(mpb_store *s, int64_t id, char **text,
                                     size_t *len, int64_t *runs,
                                     int64_t *done);

/* *yes = 1 if experiment id holds a scene imported from an OMPL log. */
int mpb__store_experiment_imported(mpb_store *s, int64_t id, int *yes);

/* ---- scenes, queries, configurations ---------------------------------- */

/* Each scene of the experiment, by id. */
int mpb__store_each_scene(mpb_store *s, int64_t experiment_id,
                          int (*fn)(void *ud, int64_t id, const char *name),
                          void *ud);

/* A scene's robot text (*robot, the caller frees; NULL if none). */
int mpb__store_scene_robot(mpb_store *s, int64_t scene_id, char **robot);

/* A query of the experiment with finished runs, by scene and query. The
 * texts are as stored ("" for NULL). */
typedef struct mpb__done_query {
    int64_t     id, scene_id;
    const char *name;
    long        runs;          /* finished runs */
    double      total_time;    /* the sum of their wall times */
    const char *joint_names, *start, *goal_kind, *goal_joints,
               *goal_tolerance, *goal_link, *goal_region;
} mpb__done_query;

int mpb__store_each_done_query(mpb_store *s, int64_t experiment_id,
                               int (*fn)(void *ud, const mpb__done_query *q),
                               void *ud);

/* Finished runs of one query, counted by planner configuration, by id. */
int mpb__store_each_config_count(mpb_store *s, int64_t experiment_id,
                                 int64_t query_id,
                                 int (*fn)(void *ud, int64_t config_id,
                                           long runs),
                                 void *ud);

/* A planner configuration's name, planner, algorithm and parameters
 * (each the caller's to free); MPB_ENOTFOUND if there is none. */
int mpb__store_config_read(mpb_store *s, int64_t config_id, char **name,
                           char **planner, char **algorithm, char **params);

/* What the finished runs of an experiment name: their metrics, the
 * stages between the first and the final one (by first place), the
 * planners' own values and progress properties; each name once. */
typedef enum mpb__run_names {
    MPB__NAMES_METRICS,
    MPB__NAMES_MID_STAGES,
    MPB__NAMES_VALUES,
    MPB__NAMES_PROGRESS
} mpb__run_names;

int mpb__store_each_run_name(mpb_store *s, int64_t experiment_id,
                             mpb__run_names which,
                             int (*fn)(void *ud, const char *name), void *ud);

/* The run (progress 0) or progress (1) properties the imported logs of an
 * experiment declared, with their types, in their planners' and the logs'
 * order (repeats included); none for a database made before they were
 * kept. */
int mpb__store_each_log_property(mpb_store *s, int64_t experiment_id,
                                 int progress,
                                 int (*fn)(void *ud, const char *name,
                                           const char *type),
                                 void *ud);

/* ---- finished runs, whole ---------------------------------------------- */

typedef struct mpb__done_stage {
    char  *name;
    double time;               /* NaN for NULL */
    int    num_waypoints;
    int    valid;
} mpb__done_stage;

typedef struct mpb__done_metric {
    char  *stage, *name;
    double value;              /* NaN for NULL or not finite */
} mpb__done_metric;

typedef struct mpb__done_value {
    char   *name;
    double  value;
    int     is_int;            /* the integer exact is the value */
    int64_t exact;
} mpb__done_value;

typedef struct mpb__done_sample {
    double time;
    char  *name;               /* NULL for NULL */
    double value;
} mpb__done_sample;

/* One finished run as the store holds it. Numbers are NaN for NULL (and
 * for what is not finite), texts NULL for NULL; success and
 * claimed_success as stored (0 or 1 for mpbench's own). */
typedef struct mpb__done_run {
    int64_t id, config_id, query_id;
    char   *status;
    double  success, claimed_success;
    double  time_total, time_raw, time_other, wall_time, verify_time,
            memory;
    char   *final_stage;
    mpb__done_stage  *stages;  /* in order */
    int               num_stages;
    mpb__done_metric *metrics;
    int               num_metrics;
    mpb__done_value  *values;
    int               num_values;
    mpb__done_sample *samples; /* in the order received */
    int               num_samples;
} mpb__done_run;

typedef struct mpb__run_cursor mpb__run_cursor;

/* The finished runs of an experiment (of one query when query_id > 0), by
 * scene, query, planner configuration and repetition. *out is NULL on
 * failure; mpb__run_cursor_close() takes either. */
int mpb__run_cursor_open(mpb_store *s, int64_t experiment_id,
                         int64_t query_id, mpb__run_cursor **out);

/* The next run, into *out (the cursor's, valid until the next call): 1,
 * or 0 at the end, or a negative code. */
int mpb__run_cursor_next(mpb__run_cursor *c, const mpb__done_run **out);

void mpb__run_cursor_close(mpb__run_cursor *c);

#endif /* MPB_STORE_EXPORT_H */
