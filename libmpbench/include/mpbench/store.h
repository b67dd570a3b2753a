/*
 * store.h - the SQLite database that holds experiments, their runs, every
 * stage's trajectory and every metric. All writes and reads go through here;
 * the schema is in docs/schema.md.
 *
 * Writes are idempotent: adding what exists returns the existing row's id,
 * and finishing a run twice writes nothing the second time. The database is
 * in WAL mode; group many writes in one mpb_store_begin()/mpb_store_commit()
 * for speed.
 */
#ifndef MPBENCH_STORE_H
#define MPBENCH_STORE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mpb_store mpb_store;

/*
 * Open (creating if needed) the database at path and bring its schema up to
 * date. A file that holds tables of something else (another program's, a
 * Planner Arena database) is refused before anything is written to it.
 * *out is set even on failure (except MPB_ENOMEM) so that mpb_store_errmsg()
 * can say why, naming the file; close it either way.
 *
 * readonly != 0 opens without creating or changing anything (for reports),
 * and leaves no -wal or -shm file behind; a database in a folder that
 * cannot be written is read as it is.
 */
int mpb_store_open(const char *path, int readonly, mpb_store **out);
void mpb_store_close(mpb_store *s);

/* The last error on s, one line; valid until the next call on s. */
const char *mpb_store_errmsg(const mpb_store *s);

/*
 * Whether the path s was opened at still names the file s writes to. SQLite
 * goes on writing into a file that has been removed or replaced, and what
 * it writes is lost with it: a long-running writer calls this now and then
 * (it costs one stat()). MPB_OK if it does, or if s is read-only;
 * MPB_ENOTFOUND if nothing is at the path any more (removed or moved away),
 * MPB_EEXISTS if another file is (moved or copied over it), MPB_EIO if it
 * cannot be told. mpb_store_errmsg() names the path and says which, and
 * whether what was written is lost (the file has no name left).
 */
int mpb_store_check_file(mpb_store *s);

/*
 * Claim the database for s, so that no other handle can claim it until s
 * is closed (or its process ends, however it ends): mpbenchd claims its
 * database, and a second one on the same file is refused. An advisory
 * flock() on the file, apart from SQLite's own locks: handles that do not
 * claim (readers, `mpb import`, the sqlite3 shell) are not affected.
 * While claimed, no other connection to the file can hold SQLite's
 * PENDING lock, so that a reader with no busy timeout (the sqlite3 shell)
 * is never refused for another reader closing (docs/schema.md).
 * MPB_EBUSY if another handle holds the claim, MPB_EINVAL if s is
 * read-only. (On NFS, Linux emulates flock() with fcntl() locks, which
 * would hold readers off: keep the database on a local disk, as SQLite's
 * WAL mode needs anyway.)
 */
int mpb_store_claim(mpb_store *s);

int mpb_store_begin(mpb_store *s);
int mpb_store_commit(mpb_store *s);
int mpb_store_rollback(mpb_store *s);

/* ---- experiments and what they are made of ----------------------------- */

/* An experiment property of an imported log: "name TYPE = value". */
typedef struct mpb_experiment_param {
    const char *name, *type, *value;
} mpb_experiment_param;

/* What an imported log's header says of its experiment (OMPL's Benchmark
 * writes it), kept so that `mpb export` writes it back. */
typedef struct mpb_log_header {
    const char *host;           /* "Running on HOST" */
    const char *version;        /* "OMPL 1.5.2" */
    const char *started;        /* "Starting at DATE", as written */
    const char *seed;           /* as written */
    const char *cpuinfo;        /* the block's text, or NULL */
    double      total_time;     /* s spent to collect the data */
    double      memory_limit;   /* MB per run */
    int         num_params;
    const mpb_experiment_param *params;
} mpb_log_header;

typedef struct mpb_experiment_info {
    const char *name;
    const char *config_file;   /* path as given */
    const char *config_hash;   /* hex digest of the file's bytes */
    const char *config_text;   /* the file itself */
    int         runs_per_query;
    double      time_limit;    /* s */
    const mpb_log_header *log; /* an imported log's; NULL for mpbench's own
                                  (this host and version) */
    double      memory_limit;  /* mpbench's own: MB a run may add, as OMPL's
                                  memory limit; 0 for none (log: its own) */
} mpb_experiment_info;

int mpb_store_experiment_create(mpb_store *s, const mpb_experiment_info *e,
                                int64_t *id);
/* The newest unfinished experiment with this name and config hash (any
 * hash when config_hash is NULL); MPB_ENOTFOUND if there is none. */
int mpb_store_experiment_find_unfinished(mpb_store *s, const char *name,
                                         const char *config_hash, int64_t *id);
/* The verifier's step (rad) the experiment's runs are checked at: set once,
 * when it is created; 0 if not known (an import, or a database made before
 * it was kept). */
int mpb_store_experiment_set_resolution(mpb_store *s, int64_t id,
                                        double resolution);
int mpb_store_experiment_resolution(mpb_store *s, int64_t id, double *out);
/* The newest experiment of any state; MPB_ENOTFOUND in an empty database. */
int mpb_store_experiment_latest(mpb_store *s, int64_t *id);
int mpb_store_experiment_finish(mpb_store *s, int64_t id);

int mpb_store_planner_config_add(mpb_store *s, int64_t experiment_id,
                                 const char *name, const char *planner,
                                 const char *algorithm, const char *params,
                                 int64_t *id);

/*
 * Record configuration config_id's approach (planner_configs.approach,
 * proto.h's words: "sampling", "search", "optimisation", "hybrid"), as
 * the experiment file gives it (keep 0: written over what is there) or
 * as a planner announces it (keep 1: written only where none is yet, so
 * that the file's word stands). MPB_OK (also when keep left it), MPB_EDB.
 */
int mpb_store_planner_config_set_approach(mpb_store *s, int64_t config_id,
                                          const char *approach, int keep);

/* A property an imported log declares for each run ("graph states
 * INTEGER") or for each progress sample. */
typedef struct mpb_log_property {
    const char *name, *type;
} mpb_log_property;

/*
 * Record the run properties (progress 0) or progress properties
 * (progress 1) an imported log declares for the planner of configuration
 * config_id, in the log's order, whether or not any run measured them:
 * `mpb export` gives each a column of its type, as OMPL's script does.
 * Replaces what was recorded for that configuration and kind before.
 */
int mpb_store_log_properties(mpb_store *s, int64_t config_id, int progress,
                             int n, const mpb_log_property *props);

typedef struct mpb_scene_info {
    const char *name;
    const char *robot_format, *robot_hash, *robot;
    const char *scene_format, *scene_hash, *scene;
} mpb_scene_info;

/*
 * The default problem set of a scene named scene: the length of its
 * name's part before the last '/' (a MotionBenchMaker problem
 * "box_panda/0001" is in "box_panda"), or of the whole name when it has
 * none ("KITCHEN" is its own). The store fills scenes.problem_set so
 * where a scene is added without one, and in a database made before the
 * column.
 */
size_t mpb_store_problem_set_len(const char *scene);

/* Add a scene, in its default problem set (mpb_store_problem_set_len());
 * an existing scene of that name is left as it is, its id in *id. */
int mpb_store_scene_add(mpb_store *s, int64_t experiment_id,
                        const mpb_scene_info *scene, int64_t *id);

/*
 * Put scene scene_id in the problem set named set (scenes.problem_set),
 * as an experiment file's `set:` says, over the default. MPB_OK,
 * MPB_ENOTFOUND if there is no such scene, MPB_EDB.
 */
int mpb_store_scene_set_problem_set(mpb_store *s, int64_t scene_id,
                                    const char *set);

/*
 * What the planners of a scene were given instead of the scene itself
 * (an experiment's `seen:`, docs/experiment-format.md): what sensors saw
 * of it, or any other stand-in. The daemon judges every path on the
 * scene (the truth) and also on what was seen (mpb_run_record.seen_*).
 */
typedef struct mpb_seen_scene {
    const char *format, *hash, *text;  /* as mpb_scene_info's scene */
    const char *how;                   /* one line: where it came from ("a
                                          file", the cameras that sensed
                                          it); may be NULL */
} mpb_seen_scene;

/* Record what scene scene_id's planners were given (scenes.seen_format,
 * seen_hash, seen, seen_how). MPB_OK, MPB_EINVAL for a NULL part,
 * MPB_ENOTFOUND if there is no such scene, MPB_EDB. */
int mpb_store_scene_set_seen(mpb_store *s, int64_t scene_id,
                             const mpb_seen_scene *seen);

typedef struct mpb_query_info {
    const char   *name;
    int           num_joints;
    const char *const *joint_names;
    const double *start;
    int           goal_kind;          /* mpb_goal_kind */
    const double *goal_joints;        /* num_joints values, or NULL */
    double        goal_tolerance;
    /* MPB_GOAL_POSE_REGION: the link, and 12 numbers: box centre (m), half
     * extents (m), reference roll pitch yaw (rad), their tolerances (rad).
     * NULL for joint goals. */
    const char   *goal_link;
    const double *goal_region;
} mpb_query_info;

int mpb_store_query_add(mpb_store *s, int64_t scene_id,
                        const mpb_query_info *q, int64_t *id);

/*
 * Record the joints outside the planning group that query query_id holds
 * and their values (world.h mpb_world_hold()) in queries.held, as "name=value
 * name=value" (exact); n = 0 leaves it NULL. MPB_OK, MPB_EDB, MPB_ENOMEM.
 */
int mpb_store_query_set_held(mpb_store *s, int64_t query_id, int n,
                             const char *const *names, const double *values);

/* Add one pending run; nothing happens if it already exists. */
int mpb_store_run_add(mpb_store *s, int64_t experiment_id,
                      int64_t planner_config_id, int64_t query_id,
                      int repetition, int64_t seed);

/* ---- scheduling ---------------------------------------------------------- */

typedef struct mpb_run_row {
    int64_t id;
    int64_t planner_config_id;
    int64_t query_id;
    int     repetition;
    int64_t seed;
    int     attempts;
    int     sent;                     /* 1 if a request went out before */
    const char *attempt_id;           /* current attempt's id, or NULL */
} mpb_run_row;

/*
 * Call cb once for each run of the experiment not yet done, in id order.
 * The row's strings are valid only during the call. A nonzero return from
 * cb stops the walk and is returned.
 */
int mpb_store_runs_unfinished(mpb_store *s, int64_t experiment_id,
                              int (*cb)(void *ud, const mpb_run_row *row),
                              void *ud);

/* Counts of an experiment's runs. */
typedef struct mpb_run_counts {
    int total, done, succeeded, crashed;
} mpb_run_counts;
int mpb_store_run_counts(mpb_store *s, int64_t experiment_id,
                         mpb_run_counts *out);

/* Record that a request with attempt_id (the wire's: plan_request_t's,
 * kept in runs.attempt_id; run_id is the run's row, runs.id) went to
 * planner_id: attempts + 1, unless attempt_id is already the run's
 * attempt (sent again after a restart: the same attempt). */
int mpb_store_run_sent(mpb_store *s, int64_t run_id, const char *attempt_id,
                       const char *planner_id);

/*
 * Put a sent run back to pending after its attempt attempt_id ended
 * without a result (its planner crashed or fell silent), to be sent again with a new
 * id; why is kept in runs.message and runs.crashes counts such attempts.
 * MPB_ENOTFOUND if attempt_id is not the run's current attempt.
 */
int mpb_store_run_retry(mpb_store *s, int64_t run_id, const char *attempt_id,
                        const char *why);

/*
 * Take back a request that its planner never started (it declined it, or
 * went away while the request still waited in its queue): the run is
 * pending again as if attempt attempt_id had not been sent (attempts - 1,
 * no crash counted). MPB_ENOTFOUND if attempt_id is not the run's current
 * attempt.
 */
int mpb_store_run_unsent(mpb_store *s, int64_t run_id, const char *attempt_id);

/* ---- results ------------------------------------------------------------- */

typedef struct mpb_named {
    const char *name;
    double      value;
} mpb_named;

typedef struct mpb_stage_record {
    const char   *name;           /* "raw", "shortcut", "smoothed", ... */
    double        time;           /* s, as the planner reported it */
    int           num_waypoints;
    int           num_joints;
    const double *waypoints;      /* row-major, num_waypoints * num_joints */
    int           valid;          /* mpbench's verdict on this stage */
    const char   *verdict;        /* verdict name, "valid" when valid */
    const char   *verdict_detail;
    int           verdict_segment;/* first failing segment, -1 if none */
    int           num_metrics;
    const mpb_named *metrics;     /* path_length, smoothness, ... */
    const char   *verification;   /* how its segments were checked for
                                     collision: "certified" (proved, or a
                                     colliding configuration found),
                                     "sampled" (mpb_verdict.certified 0),
                                     NULL when the check did not run */
    /* A collision verdict: how deep the refused segment goes, mm, at its
     * worst configuration examined (mpb_verdict.depth_*): the deepest
     * robot point found inside what it hits, and the penetration of the
     * colliding shapes' convex hulls (stages.depth_lower_mm,
     * depth_upper_mm), when has_depth is 1: stored only with a collision
     * verdict; read back has_depth 0 (NULL) where not measured, and for a
     * database made before them. */
    int           has_depth;
    double        depth_lower_mm, depth_upper_mm;
    /* Last, so that the fields above keep their places. */
    const double *times;          /* s, the time of each waypoint
                                     (num_waypoints values), as the planner
                                     sent them (stages.times); NULL for an
                                     untimed stage */
} mpb_stage_record;

/* A planner value that is an integer, kept exactly: the record's
 * values[index] is it as the nearest double, which past 2^53 may differ
 * (an imported log's INTEGER, BOOLEAN or ENUM property). */
typedef struct mpb_exact_value {
    int     index;
    int64_t value;
} mpb_exact_value;

typedef struct mpb_progress_record {
    double      time;
    const char *name;
    double      value;
} mpb_progress_record;

typedef struct mpb_run_record {
    int64_t     run_id;           /* runs.id */
    const char *attempt_id;       /* the attempt's id on the wire */
    const char *planner_id;
    const char *status;           /* mpb_status_name() of the planner's status */
    const char *message;          /* planner's message, may be "" */
    int         claimed_success;  /* planner said solved */
    int         success;          /* solved in time and verified valid
                                     (mpb_run_success(), outcome.h) */
    double      time_total, time_raw, time_other; /* tau_t, tau_r, tau_o, s */
    double      wall_time;        /* request sent (or started) to result
                                     verified and measured, s */
    int         num_stages;
    const mpb_stage_record *stages;
    int         num_values;
    const mpb_named *values;      /* the planner's own numbers */
    int         num_progress;
    const mpb_progress_record *progress;
    double      verify_time;      /* s the daemon spent verifying and
                                     measuring the run's stages; NaN (stored
                                     NULL) where it did none */
    double      memory;           /* MB, the planner's peak resident
                                     memory during the planning; NaN
                                     (stored NULL): not reported */
    int         num_exact;
    const mpb_exact_value *exact; /* values that are integers, as such
                                     (planner_values.exact); may be NULL */
    int         late;             /* 1 where the run was not in time
                                     (mpb_run_in_time() said 0): stored
                                     as runs.in_time = 0, so that `mpb
                                     verify` can apply the success rule
                                     again; 0 (in time) by default */
    /* Judged on what was seen, where the planners were given a seen
     * scene (mpb_seen_scene): the final stage's verdict in its world
     * (mpb_verdict_name()) with its detail, and the success rule applied
     * to that verdict. seen_verdict NULL: nothing seen instead (all three
     * stored NULL). */
    const char *seen_verdict;
    const char *seen_detail;
    int         seen_success;
} mpb_run_record;

/*
 * Store a finished run: its outcome, stages, metrics, planner values and
 * progress. runs.outcome is mpb_run_outcome(claimed_success, the final
 * stage's validity, success) (outcome.h), runs.in_time !late. Returns MPB_OK, or MPB_EEXISTS (writing nothing) if the run was
 * already done, or MPB_ENOTFOUND if attempt_id is not the run's current
 * attempt.
 */
int mpb_store_run_finish(mpb_store *s, const mpb_run_record *r);

/* ---- reading, for reports ----------------------------------------------
 *
 * Every reader walks rows through a callback, as mpb_store_runs_unfinished()
 * does: the row and its strings are valid only during the call, and a
 * nonzero return from cb stops the walk and is returned. Rows come in id
 * order unless stated. Dates are Unix times in seconds; a number the
 * database does not have (NULL, or NaN when it was written) reads as NaN.
 */

typedef struct mpb_experiment_row {
    int64_t     id;
    const char *name;
    const char *config_file;
    const char *config_hash;
    const char *config_text;
    const char *host;
    const char *version;       /* mpbench version that created it */
    int         runs_per_query;
    double      time_limit;    /* s */
    double      created;
    double      finished;      /* NaN while unfinished */
} mpb_experiment_row;

/* Every experiment in the database. */
int mpb_store_experiments(mpb_store *s,
                          int (*cb)(void *ud, const mpb_experiment_row *row),
                          void *ud);
/* One experiment; MPB_ENOTFOUND (cb not called) if there is no such id. */
int mpb_store_experiment_get(mpb_store *s, int64_t id,
                             int (*cb)(void *ud, const mpb_experiment_row *row),
                             void *ud);

typedef struct mpb_scene_row {
    int64_t     id;
    const char *name;
    const char *robot_format, *robot_hash, *robot;
    const char *scene_format, *scene_hash, *scene;
    const char *problem_set;   /* scenes.problem_set, never NULL (the
                                  default rule for a database made before
                                  the column, opened read-only) */
    const char *seen_format, *seen_hash, *seen, *seen_how;
                               /* what its planners were given instead
                                  (mpb_seen_scene); NULL: the scene */
} mpb_scene_row;

/* The scenes of an experiment. */
int mpb_store_scenes(mpb_store *s, int64_t experiment_id,
                     int (*cb)(void *ud, const mpb_scene_row *row), void *ud);

typedef struct mpb_planner_config_row {
    int64_t     id;
    const char *name;          /* e.g. "ompl/RRTConnect" */
    const char *planner, *algorithm, *params;
    const char *approach;      /* "sampling", "search", ...; NULL where
                                  none was declared (or the database was
                                  made before planner_configs.approach) */
} mpb_planner_config_row;

/* The planner configurations of an experiment. */
int mpb_store_planner_configs(mpb_store *s, int64_t experiment_id,
                              int (*cb)(void *ud,
                                        const mpb_planner_config_row *row),
                              void *ud);

typedef struct mpb_query_row {
    int64_t     id;
    int64_t     scene_id;
    const char *name;
    const char *joint_names;   /* space-separated, as written */
    const char *start;         /* space-separated numbers */
    int         goal_kind;     /* mpb_goal_kind */
    const char *goal_joints;   /* space-separated numbers, or NULL */
    double      goal_tolerance;
    const char *goal_link;     /* pose-region goals: the link, else NULL */
    const char *goal_region;   /* and its 12 numbers, as in mpb_query_info */
    const char *held;          /* the joints outside the group it holds,
                                  "name=value name=value" (exact), as
                                  mpb_store_query_set_held() wrote them;
                                  NULL when it holds none */
} mpb_query_row;

/*
 * Read n numbers of a query row's space-separated text (start,
 * goal_joints, goal_region) into out[0..n). Returns MPB_OK, or MPB_EINVAL
 * if text (NULL reads as "") holds fewer than n numbers; text after the
 * n-th is not read.
 */
int mpb_store_numbers(const char *text, double *out, int n);

/* The queries of a scene. */
int mpb_store_queries(mpb_store *s, int64_t scene_id,
                      int (*cb)(void *ud, const mpb_query_row *row), void *ud);

/*
 * Call cb for each scene of the experiment that has runs not yet done, with
 * their number, in scene id order. Reads only the unfinished runs, so it
 * costs nothing on a finished experiment.
 */
int mpb_store_unfinished_by_scene(mpb_store *s, int64_t experiment_id,
                                  int (*cb)(void *ud, int64_t scene_id,
                                            int unfinished),
                                  void *ud);

/*
 * How deep the experiment's refused paths go (stages.depth_lower_mm,
 * depth_upper_mm, docs/verification.md): cb(ud, planner_config_id,
 * lower_mm, upper_mm) for each finished run whose last stage was refused
 * for a collision, by configuration id; NaN where the depth was not
 * measured (a database made before it, a world that cannot say). A
 * nonzero return from cb stops the walk and is returned. MPB_OK or
 * MPB_EDB.
 */
int mpb_store_refusal_depths(mpb_store *s, int64_t experiment_id,
                             int (*cb)(void *ud, int64_t config_id,
                                       double lower_mm, double upper_mm),
                             void *ud);

/* A finished run judged on the truth and on what its planner was given
 * (mpb_run_record.seen_*). */
typedef struct mpb_seen_judgement {
    int64_t     run_id, planner_config_id, query_id;
    int         success;        /* on the truth: runs.success */
    int         seen_success;   /* on what was seen */
    int         claimed;        /* the planner said solved */
    const char *verdict;        /* the final stage's on the truth, or NULL */
    const char *seen_verdict;   /* its on what was seen */
} mpb_seen_judgement;

/*
 * Walk the experiment's finished runs that were judged on a seen scene,
 * by configuration id then run id; none in an experiment without (or a
 * database made before them). A nonzero return from cb stops the walk
 * and is returned. MPB_OK or MPB_EDB.
 */
int mpb_store_seen_judgements(mpb_store *s, int64_t experiment_id,
                              int (*cb)(void *ud, const mpb_seen_judgement *j),
                              void *ud);

/*
 * How the experiment's stages were checked for collision
 * (stages.verification, docs/verification.md): the number stored
 * "certified" and "sampled" into *certified and *sampled (stages whose
 * verdict came before the check, or stored before the column, count in
 * neither). MPB_OK or MPB_EDB.
 */
int mpb_store_verification_counts(mpb_store *s, int64_t experiment_id,
                                  long *certified, long *sampled);

/* One finished run, as mpb_store_results() gives it. */
typedef struct mpb_result_row {
    int64_t     run_id;
    int64_t     planner_config_id;
    int64_t     query_id;
    int64_t     scene_id;      /* the query's scene */
    int         repetition;
    int         success;       /* solved in time and verified valid */
    const char *status;        /* the planner's status name */
    double      time_total, time_raw, time_other; /* tau_t, tau_r, tau_o, s */
    double      world_setup_time; /* the planner's MPB_WORLD_SETUP_TIME
                                     value (s, outside tau_t), NaN if none */
    const char *stage;         /* the stage the metrics are read from: the
                                  one asked for, else the run's final stage
                                  (NULL if the run has none) */
    const double *metrics;     /* one value per name asked for, in that
                                  order; NaN where the stage lacks it */
    int         stage_valid;   /* 1 if that stage passed verification, 0
                                  if it failed (a run's earlier stage may
                                  fail while its final one passes), -1 if
                                  the run has no such stage */
    int         num_named;     /* 0 if that stage has no metrics */
    const mpb_named *named;    /* every metric of that stage, by name */
    double      verify_time;   /* runs.verify_time (s), NaN if none */
    double      memory;        /* runs.memory (MB), NaN if none */
    int         outcome;       /* mpb_outcome (outcome.h): verified,
                                  refused, late, unclaimed_valid or
                                  unclaimed, by mpb_run_outcome() from the
                                  run's claim, final stage and success
                                  (databases made before runs.outcome too) */
} mpb_result_row;

/*
 * Walk the finished runs (failed ones included; see success) of an
 * experiment's queries in one scene, or in every scene when scene_id is 0:
 * one statement, one pass, in run id order. Runs of different queries and
 * configurations come interleaved as they were run, so accumulate per
 * (configuration, query), as mpb report does, for the paper's per-query
 * standard deviations.
 *
 * Metrics are read from the stage named stage, or from each run's final
 * stage when stage is NULL. names[0..num_names) are the metrics wanted in
 * row->metrics (e.g. "path_length", "smoothness"); num_names may be 0.
 * Returns MPB_ENOMEM if a row cannot be assembled.
 */
int mpb_store_results(mpb_store *s, int64_t experiment_id, int64_t scene_id,
                      const char *stage, const char *const *names,
                      int num_names,
                      int (*cb)(void *ud, const mpb_result_row *row),
                      void *ud);

/* ---- one run, whole (store_run_read.c), for `mpb view` -------------- */

typedef struct mpb_run_detail {
    int64_t     run_id, experiment_id, planner_config_id, query_id;
    int64_t     scene_id;       /* the query's scene */
    int         repetition;
    const char *state;          /* "pending", "sent" or "done" */
    const char *planner_config; /* the configuration's name */
    const char *planner_id;     /* "" where the database has none */
    const char *status, *message, *verdict;   /* the same */
    int         success;        /* 1, 0, or -1 while the run is not done */
    double      time_total;     /* s; NaN if none */
    int         claimed;        /* runs.claimed_success (0 if none) */
    int         final_valid;    /* runs.valid: the final stage's stored
                                   verdict was valid (0 if none) */
    int         in_time;        /* runs.in_time (1 if none): the facts
                                   the success rule takes (outcome.h) */
    const char *seen_verdict;   /* judged on what its planner was given
                                   (mpb_seen_scene): the final stage's
                                   verdict there and its detail; NULL: */
    const char *seen_detail;    /* the run was not so judged */
    int         seen_success;   /* 1, 0; -1 where not so judged */
} mpb_run_detail;

/*
 * Call cb once with the run of that id. MPB_ENOTFOUND (cb not called, the
 * message "no run N") if there is none; else cb's return or MPB_OK.
 */
int mpb_store_run_get(mpb_store *s, int64_t run_id,
                      int (*cb)(void *ud, const mpb_run_detail *row),
                      void *ud);

/*
 * Call cb for each stage of the run, in the planner's order, with its
 * waypoints (num_waypoints 0 and waypoints NULL where the stored blob does
 * not hold num_waypoints * num_joints values) and verdict; metrics are not
 * read (num_metrics 0). A run without stages calls cb never and returns
 * MPB_OK.
 */
int mpb_store_run_stages(mpb_store *s, int64_t run_id,
                         int (*cb)(void *ud, const mpb_stage_record *stage),
                         void *ud);

/* ---- exporting: Planner Arena and OMPL (store_export*.c, store_pa*) -----
 *
 * An experiment's finished runs as OMPL's benchmark tools and Planner Arena
 * read them; docs/planner-arena.md gives the mapping. Each query of an
 * experiment becomes one Planner Arena experiment named
 * "<experiment>/<scene>" with the query's name as its "query" parameter, so
 * Planner Arena shows a scene's queries one by one, side by side or pooled.
 */

/* What an export wrote. */
typedef struct mpb_export_counts {
    int  experiments;       /* Planner Arena experiments (= OMPL logs) */
    int  planner_configs;   /* plannerConfigs rows added */
    long runs;
    long progress;          /* progress rows (samples) */
    int  skipped;           /* Planner Arena experiments there already */
} mpb_export_counts;

/* Flags of the exports. */
#define MPB_EXPORT_APPEND  1 /* add to an existing Planner Arena database */
#define MPB_EXPORT_REPLACE 2 /* overwrite log files that exist */

/*
 * Write the finished runs of the experiments ids[0..num_ids) (every
 * experiment in s when num_ids is 0) into a Planner Arena database at path,
 * in one transaction: the tables and the bestPlannerConfigs views of OMPL's
 * ompl_benchmark_statistics.py. path must not exist (MPB_EEXISTS) unless
 * flags has MPB_EXPORT_APPEND, which adds to a database that script (or
 * this function) wrote (MPB_EINVAL, nothing written, for a file without its
 * tables experiments, plannerConfigs and runs, or for s's own file). Each
 * query is an experiment named EXPERIMENT/SCENE, whitespace as '_', with
 * "#N" (N the scene's place in its experiment) for scenes that would
 * share a name. A query there already (an experiment of the same name,
 * query, date, runcount and hostname, in the file before this call:
 * exported before) is skipped with its runs (counts->skipped); an id given
 * twice counts once. On failure nothing changes: a new file is removed.
 * counts (may be NULL) says what was written. MPB_ENOTFOUND if an id is no
 * experiment or s holds none.
 */
int mpb_store_export_planner_arena(mpb_store *s, const char *path,
                                   const int64_t *ids, int num_ids, int flags,
                                   mpb_export_counts *counts);

/*
 * Write the same as OMPL benchmark logs, one per query (OMPL's one
 * experiment per file), into the directory dir (created if missing), named
 * EXPERIMENT.ID.SCENE.QUERY.log (anything but [A-Za-z0-9.-] as '_'; names
 * that would be one file, case ignored, each with "+QUERYID" before
 * ".log", so that each query has a file of its own).
 * ompl_benchmark_statistics.py turns them into the database
 * mpb_store_export_planner_arena() writes (no seed, memory limit 0). A
 * file that exists is an error (MPB_EEXISTS, found before any is written)
 * unless flags has MPB_EXPORT_REPLACE. counts (may be NULL): experiments =
 * files written.
 */
int mpb_store_export_ompl_logs(mpb_store *s, const char *dir,
                               const int64_t *ids, int num_ids, int flags,
                               mpb_export_counts *counts);

/*
 * Write the run_summary view (docs/schema.md: one row per finished run,
 * its experiment, problem set, scene, query, planner, seed, outcome,
 * times and final-stage metrics) of the experiments ids[0..num_ids)
 * (every experiment when num_ids is 0) to out as CSV: a header of the
 * view's column names, then a row per run in run id order; NULL as an
 * empty field, numbers in the fewest digits that read back exactly,
 * text quoted as RFC 4180 says where it must be. A database made before
 * the view is read the same. *rows (may be NULL) counts the rows.
 * MPB_OK, MPB_ENOTFOUND (nothing written) if an id is no experiment,
 * MPB_EIO if out reports an error, MPB_EDB, MPB_ENOMEM.
 */
int mpb_store_export_runs_csv(mpb_store *s, FILE *out, const int64_t *ids,
                              int num_ids, long *rows);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_STORE_H */
