/*
 * store_schema.c - the database schema, one statement list per version.
 * docs/schema.md explains every table; keep the two in step.
 */
#include "store/store_internal.h"

/* Version 1. Every statement is idempotent (IF NOT EXISTS). */
const char mpb__schema_v1[] =
    "CREATE TABLE IF NOT EXISTS meta(\n"
    "  key   TEXT PRIMARY KEY,\n"
    "  value TEXT NOT NULL);\n"

    "CREATE TABLE IF NOT EXISTS experiments(\n"
    "  id             INTEGER PRIMARY KEY,\n"
    "  name           TEXT NOT NULL,\n"
    "  config_file    TEXT NOT NULL,\n"
    "  config_hash    TEXT NOT NULL,\n"
    "  config_text    TEXT NOT NULL,\n"
    "  runs_per_query INTEGER NOT NULL,\n"
    "  time_limit     REAL NOT NULL,\n"
    "  resolution     REAL,\n"
    "  host           TEXT NOT NULL,\n"
    "  version        TEXT NOT NULL,\n"
    "  created        REAL NOT NULL,\n"
    "  finished       REAL);\n"

    "CREATE TABLE IF NOT EXISTS planner_configs(\n"
    "  id            INTEGER PRIMARY KEY,\n"
    "  experiment_id INTEGER NOT NULL REFERENCES experiments(id),\n"
    "  name          TEXT NOT NULL,\n"
    "  planner       TEXT NOT NULL,\n"
    "  algorithm     TEXT NOT NULL,\n"
    "  params        TEXT NOT NULL,\n"
    "  approach      TEXT,\n"
    "  UNIQUE(experiment_id, name));\n"

    "CREATE TABLE IF NOT EXISTS scenes(\n"
    "  id            INTEGER PRIMARY KEY,\n"
    "  experiment_id INTEGER NOT NULL REFERENCES experiments(id),\n"
    "  name          TEXT NOT NULL,\n"
    "  robot_format  TEXT NOT NULL,\n"
    "  robot_hash    TEXT NOT NULL,\n"
    "  robot         TEXT NOT NULL,\n"
    "  scene_format  TEXT NOT NULL,\n"
    "  scene_hash    TEXT NOT NULL,\n"
    "  scene         TEXT NOT NULL,\n"
    "  problem_set   TEXT,\n"
    "  seen_format   TEXT,\n"
    "  seen_hash     TEXT,\n"
    "  seen          TEXT,\n"
    "  seen_how      TEXT,\n"
    "  UNIQUE(experiment_id, name));\n"

    "CREATE TABLE IF NOT EXISTS queries(\n"
    "  id             INTEGER PRIMARY KEY,\n"
    "  scene_id       INTEGER NOT NULL REFERENCES scenes(id),\n"
    "  name           TEXT NOT NULL,\n"
    "  joint_names    TEXT NOT NULL,\n"
    "  start          TEXT NOT NULL,\n"
    "  goal_kind      TEXT NOT NULL,\n"
    "  goal_joints    TEXT,\n"
    "  goal_tolerance REAL,\n"
    "  goal_link      TEXT,\n"
    "  goal_region    TEXT,\n"
    "  held           TEXT,\n"
    "  UNIQUE(scene_id, name));\n"

    "CREATE TABLE IF NOT EXISTS runs(\n"
    "  id                INTEGER PRIMARY KEY,\n"
    "  experiment_id     INTEGER NOT NULL REFERENCES experiments(id),\n"
    "  planner_config_id INTEGER NOT NULL REFERENCES planner_configs(id),\n"
    "  query_id          INTEGER NOT NULL REFERENCES queries(id),\n"
    "  repetition        INTEGER NOT NULL,\n"
    "  seed              INTEGER NOT NULL,\n"
    "  state             TEXT NOT NULL DEFAULT 'pending'\n"
    /* Not "state IN (...)": SQLite builds a temporary index of the list
     * for every row it checks, twice per run (bench/results/history.md, change 4). */
    "                    CHECK(state = 'pending' OR state = 'sent'\n"
    "                          OR state = 'done'),\n"
    /* Not UNIQUE: runs are found by id, and an index of a random key costs
     * a page of its own in every commit (bench/results/history.md,
     * change 10). */
    "  attempt_id        TEXT,\n"
    "  attempts          INTEGER NOT NULL DEFAULT 0,\n"
    "  crashes           INTEGER NOT NULL DEFAULT 0,\n"
    "  planner_id        TEXT,\n"
    "  sent              REAL,\n"
    "  finished          REAL,\n"
    "  status            TEXT,\n"
    "  message           TEXT,\n"
    "  claimed_success   INTEGER,\n"
    "  valid             INTEGER,\n"
    "  verdict           TEXT,\n"
    "  success           INTEGER,\n"
    "  time_total        REAL,\n"
    "  time_raw          REAL,\n"
    "  time_other        REAL,\n"
    "  wall_time         REAL,\n"
    "  final_stage       TEXT,\n"
    "  final_metrics     BLOB,\n"
    "  world_setup_time  REAL,\n"
    "  verify_time       REAL,\n"
    "  memory            REAL,\n"
    "  outcome           TEXT,\n"
    "  in_time           INTEGER,\n"
    "  seen_verdict      TEXT,\n"
    "  seen_detail       TEXT,\n"
    "  seen_success      INTEGER,\n"
    "  UNIQUE(experiment_id, planner_config_id, query_id, repetition));\n"
    /* By experiment, in run order: what reports and a resume read. Not by
     * state: each change of state would move an entry between three
     * regions of such an index, three pages per commit; this one is
     * written only when a run is added. */
    "CREATE INDEX IF NOT EXISTS runs_by_experiment ON runs(experiment_id);\n"

    "CREATE TABLE IF NOT EXISTS stages(\n"
    "  run_id          INTEGER NOT NULL REFERENCES runs(id),\n"
    "  idx             INTEGER NOT NULL,\n"
    "  name            TEXT NOT NULL,\n"
    "  time            REAL,\n"
    "  num_waypoints   INTEGER NOT NULL,\n"
    "  num_joints      INTEGER NOT NULL,\n"
    "  waypoints       BLOB,\n"
    "  valid           INTEGER NOT NULL,\n"
    "  verdict         TEXT NOT NULL,\n"
    "  verdict_detail  TEXT,\n"
    "  verdict_segment INTEGER,\n"
    "  verification    TEXT,\n"
    "  times           BLOB,\n"
    "  depth_lower_mm  REAL,\n"
    "  depth_upper_mm  REAL,\n"
    "  PRIMARY KEY(run_id, idx)) WITHOUT ROWID;\n"

    "CREATE TABLE IF NOT EXISTS metrics(\n"
    "  run_id INTEGER NOT NULL REFERENCES runs(id),\n"
    "  stage  TEXT NOT NULL,\n"
    "  name   TEXT NOT NULL,\n"
    "  value  REAL,\n"
    "  PRIMARY KEY(run_id, stage, name)) WITHOUT ROWID;\n"

    /* value as a REAL, exact the same when it is an integer: a REAL
     * column turns an integer into the nearest double (store.c,
     * add_exact_values()). */
    "CREATE TABLE IF NOT EXISTS planner_values(\n"
    "  run_id INTEGER NOT NULL REFERENCES runs(id),\n"
    "  name   TEXT NOT NULL,\n"
    "  value  REAL,\n"
    "  exact  INTEGER,\n"
    "  PRIMARY KEY(run_id, name)) WITHOUT ROWID;\n"

    "CREATE TABLE IF NOT EXISTS progress(\n"
    "  run_id INTEGER NOT NULL REFERENCES runs(id),\n"
    "  seq    INTEGER NOT NULL,\n"
    "  time   REAL NOT NULL,\n"
    "  name   TEXT NOT NULL,\n"
    "  value  REAL,\n"
    "  PRIMARY KEY(run_id, seq, name)) WITHOUT ROWID;\n";

/* An imported log's experiment properties ("wall_width REAL = 0.6"), in
 * its order, each part as written; the experiments' columns started,
 * total_time, seed, memory_limit and cpuinfo come with it (store.c,
 * add_log_header()). */
const char mpb__schema_experiment_params[] =
    "CREATE TABLE IF NOT EXISTS experiment_params(\n"
    "  experiment_id INTEGER NOT NULL REFERENCES experiments(id),\n"
    "  idx           INTEGER NOT NULL,\n"
    "  name          TEXT NOT NULL,\n"
    "  type          TEXT NOT NULL,\n"
    "  value         TEXT NOT NULL,\n"
    "  PRIMARY KEY(experiment_id, idx)) WITHOUT ROWID;\n";

/* The run and progress properties an imported log declares for each
 * planner, in its order, measured or not (store.c, add_exact_values()). */
const char mpb__schema_log_properties[] =
    "CREATE TABLE IF NOT EXISTS log_properties(\n"
    "  planner_config_id INTEGER NOT NULL REFERENCES planner_configs(id),\n"
    "  progress          INTEGER NOT NULL,\n"
    "  idx               INTEGER NOT NULL,\n"
    "  name              TEXT NOT NULL,\n"
    "  type              TEXT NOT NULL,\n"
    "  PRIMARY KEY(planner_config_id, progress, idx)) WITHOUT ROWID;\n";

/* For people at the sqlite3 prompt: one row per finished run, with the
 * metrics of its final stage. An experiment run again after it finished
 * gets a new id under the same name, so the id is there to tell them
 * apart. */
const char mpb__schema_results_view[] =
    "CREATE VIEW IF NOT EXISTS results AS\n"
    "SELECT r.id AS run, r.experiment_id, e.name AS experiment,\n"
    "       s.name AS scene,\n"
    "       q.name AS query, c.name AS planner, c.approach,\n"
    "       r.repetition, r.status,\n"
    "       r.claimed_success,\n"
    "       r.success, r.outcome, r.verdict, r.message,\n"
    "       r.time_total, r.time_raw, r.time_other,\n"
    "       r.final_stage,\n"
    "       (SELECT value FROM metrics m WHERE m.run_id = r.id\n"
    "          AND m.stage = r.final_stage AND m.name = 'path_length')\n"
    "         AS path_length,\n"
    "       (SELECT value FROM metrics m WHERE m.run_id = r.id\n"
    "          AND m.stage = r.final_stage AND m.name = 'smoothness')\n"
    "         AS smoothness,\n"
    "       (SELECT value FROM metrics m WHERE m.run_id = r.id\n"
    "          AND m.stage = r.final_stage AND m.name = 'waypoints')\n"
    "         AS waypoints\n"
    "FROM runs r JOIN experiments e ON e.id = r.experiment_id\n"
    "  JOIN queries q ON q.id = r.query_id\n"
    "  JOIN scenes s ON s.id = q.scene_id\n"
    "  JOIN planner_configs c ON c.id = r.planner_config_id\n"
    "WHERE r.state = 'done';\n";

/* The default rule of scenes.problem_set (mpb_store_problem_set_len()) in
 * SQL, of the scene name N: the part before its last '/', else all of it.
 * rtrim(N, the characters of N but '/') leaves N up to its last '/'. */
#define DEFAULT_SET(n)                                                       \
    "CASE WHEN instr(" n ", '/') > 0 THEN substr(rtrim(" n ", replace(" n    \
    ", '/', '')), 1, length(rtrim(" n ", replace(" n ", '/', ''))) - 1)"     \
    " ELSE " n " END"

/* A database made before scenes.problem_set: each scene's set by the
 * default rule. */
const char mpb__schema_fill_problem_sets[] =
    "UPDATE scenes SET problem_set = " DEFAULT_SET("name")
    " WHERE problem_set IS NULL";

/* run_summary's columns, for the view and for a reader of a database
 * made before it (PS: the scene's problem set there). */
#define RUN_SUMMARY(ps)                                                      \
    "SELECT r.id AS run, r.experiment_id, e.name AS experiment,\n"          \
    "       " ps " AS problem_set, s.name AS scene, q.name AS query,\n"     \
    "       c.name AS planner, c.planner AS family, c.algorithm,\n"          \
    "       c.approach, r.repetition, r.seed, r.status,\n"                   \
    "       r.claimed_success AS claimed, r.success AS verified,\n"          \
    "       r.outcome, r.verdict,\n"                                         \
    "       r.time_total, r.time_raw, r.time_other, r.wall_time,\n"          \
    "       r.final_stage,\n"                                                \
    METRIC("path_length") METRIC("smoothness") METRIC("clearance")           \
    METRIC("ee_path_length") METRIC("waypoints")                             \
    "       r.planner_id\n"                                                  \
    "FROM runs r JOIN experiments e ON e.id = r.experiment_id\n"             \
    "  JOIN queries q ON q.id = r.query_id\n"                                \
    "  JOIN scenes s ON s.id = q.scene_id\n"                                 \
    "  JOIN planner_configs c ON c.id = r.planner_config_id\n"               \
    "WHERE r.state = 'done'"
#define METRIC(m)                                                            \
    "       (SELECT value FROM metrics m WHERE m.run_id = r.id\n"            \
    "          AND m.stage = r.final_stage AND m.name = '" m "') AS " m ",\n"

/* For users who analyse the runs themselves (docs/analysis.md): one row
 * per finished run, every name spelled out, the final stage's metrics. */
const char mpb__schema_run_summary_view[] =
    "CREATE VIEW IF NOT EXISTS run_summary AS\n" RUN_SUMMARY("s.problem_set")
    ";\n";

const char mpb__run_summary_select[] = RUN_SUMMARY("s.problem_set");
const char mpb__run_summary_select_old[] = RUN_SUMMARY(DEFAULT_SET("s.name"));
