/*
 * store_experiment.c - writing what an experiment is made of: the
 * experiment, its planner configurations, scenes, queries and pending runs.
 * Each add is idempotent: adding what exists returns the existing id.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "store/store_internal.h"

/* Run a one-off statement that returns nothing; the caller binds. */
static int step_once(mpb_store *s, sqlite3_stmt *st, const char *what)
{
    int rc = sqlite3_step(st);
    if (rc != SQLITE_DONE && rc != SQLITE_ROW)
        return mpb__store_db_fail(s, what);
    return MPB_OK;
}

/* The id of the first row a query returns; MPB_ENOTFOUND if none. */
static int select_id(mpb_store *s, sqlite3_stmt *st, int64_t *id)
{
    int rc = sqlite3_step(st);
    if (rc == SQLITE_ROW) {
        *id = sqlite3_column_int64(st, 0);
        return MPB_OK;
    }
    if (rc == SQLITE_DONE)
        return MPB_ENOTFOUND;
    return mpb__store_db_fail(s, "select");
}

/* An imported log's experiment properties, in its order. */
static int add_params(mpb_store *s, int64_t id, const mpb_log_header *h)
{
    if (h->num_params == 0)
        return MPB_OK;
    sqlite3_stmt *st = mpb__store_prepare(s,
        "INSERT INTO experiment_params(experiment_id, idx, name, type, value)"
        " VALUES (?, ?, ?, ?, ?)");
    if (st == NULL)
        return MPB_EDB;
    int rc = MPB_OK;
    for (int i = 0; i < h->num_params && rc == MPB_OK; i++) {
        sqlite3_reset(st);
        sqlite3_bind_int64(st, 1, id);
        sqlite3_bind_int(st, 2, i);
        sqlite3_bind_text(st, 3, h->params[i].name, -1, SQLITE_STATIC);
        sqlite3_bind_text(st, 4, h->params[i].type, -1, SQLITE_STATIC);
        sqlite3_bind_text(st, 5, h->params[i].value, -1, SQLITE_STATIC);
        rc = step_once(s, st, "add an experiment parameter");
    }
    sqlite3_finalize(st);
    return rc;
}

int mpb_store_experiment_create(mpb_store *s, const mpb_experiment_info *e,
                                int64_t *id)
{
    char host[256] = "";
    const mpb_log_header *h = e->log;
    sqlite3_stmt *st = mpb__store_prepare(s,
        "INSERT INTO experiments(name, config_file, config_hash, config_text,"
        " runs_per_query, time_limit, host, version, created, started,"
        " total_time, seed, memory_limit, cpuinfo)"
        " VALUES (?, ?, ?, ?, ?, ?, ?, ?,"
        " (julianday('now') - 2440587.5) * 86400.0, ?, ?, ?, ?, ?)");
    if (st == NULL)
        return MPB_EDB;
    gethostname(host, sizeof host - 1);
    sqlite3_bind_text(st, 1, e->name, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 2, e->config_file, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 3, e->config_hash, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 4, e->config_text, -1, SQLITE_STATIC);
    sqlite3_bind_int(st, 5, e->runs_per_query);
    sqlite3_bind_double(st, 6, e->time_limit);
    sqlite3_bind_text(st, 7, h && h->host ? h->host : host, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 8, h && h->version ? h->version
                             : "mpbench " MPB_VERSION_STRING, -1, SQLITE_STATIC);
    /* An imported log's header; NULL (unbound) for mpbench's own. */
    if (h) {
        sqlite3_bind_text(st, 9, h->started, -1, SQLITE_STATIC);
        sqlite3_bind_double(st, 10, h->total_time);
        sqlite3_bind_text(st, 11, h->seed, -1, SQLITE_STATIC);
        sqlite3_bind_double(st, 12, h->memory_limit);
        sqlite3_bind_text(st, 13, h->cpuinfo, -1, SQLITE_STATIC);
    } else if (e->memory_limit > 0) {
        sqlite3_bind_double(st, 12, e->memory_limit);
    }
    int rc = step_once(s, st, "create experiment");
    sqlite3_finalize(st);
    if (rc == MPB_OK)
        *id = sqlite3_last_insert_rowid(s->db);
    if (rc == MPB_OK && h)
        rc = add_params(s, *id, h);
    return rc;
}

int mpb_store_experiment_find_unfinished(mpb_store *s, const char *name,
                                         const char *config_hash, int64_t *id)
{
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT id FROM experiments WHERE name = ?1"
        " AND (?2 IS NULL OR config_hash = ?2)"
        " AND finished IS NULL ORDER BY id DESC LIMIT 1");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_text(st, 1, name, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 2, config_hash, -1, SQLITE_STATIC);
    int rc = select_id(s, st, id);
    sqlite3_finalize(st);
    return rc;
}

int mpb_store_experiment_set_resolution(mpb_store *s, int64_t id,
                                        double resolution)
{
    sqlite3_stmt *st = mpb__store_prepare(s,
        "UPDATE experiments SET resolution = ? WHERE id = ?");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_double(st, 1, resolution);
    sqlite3_bind_int64(st, 2, id);
    int rc = step_once(s, st, "set resolution");
    sqlite3_finalize(st);
    return rc;
}

int mpb_store_experiment_resolution(mpb_store *s, int64_t id, double *out)
{
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT coalesce(resolution, 0) FROM experiments WHERE id = ?");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, id);
    int rc = sqlite3_step(st);
    *out = rc == SQLITE_ROW ? sqlite3_column_double(st, 0) : 0.0;
    sqlite3_finalize(st);
    if (rc == SQLITE_ROW)
        return MPB_OK;
    if (rc == SQLITE_DONE)
        return mpb__store_fail(s, MPB_ENOTFOUND, "no experiment %lld",
                               (long long)id);
    return mpb__store_db_fail(s, "experiment resolution");
}

int mpb_store_experiment_latest(mpb_store *s, int64_t *id)
{
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT id FROM experiments ORDER BY id DESC LIMIT 1");
    if (st == NULL)
        return MPB_EDB;
    int rc = select_id(s, st, id);
    sqlite3_finalize(st);
    if (rc == MPB_ENOTFOUND)
        mpb__store_fail(s, rc, "the database holds no experiment");
    return rc;
}

int mpb_store_experiment_finish(mpb_store *s, int64_t id)
{
    sqlite3_stmt *st = mpb__store_prepare(s,
        "UPDATE experiments SET finished = (julianday('now') - 2440587.5)"
        " * 86400.0 WHERE id = ? AND finished IS NULL");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, id);
    int rc = step_once(s, st, "finish experiment");
    sqlite3_finalize(st);
    return rc;
}

/*
 * Insert with OR IGNORE, then read the row's id back through its unique
 * key: the same code path whether the row is new or was there already.
 */
static int insert_or_get(mpb_store *s, sqlite3_stmt *ins, sqlite3_stmt *sel,
                         const char *what, int64_t *id)
{
    int rc = step_once(s, ins, what);
    if (rc == MPB_OK && (rc = select_id(s, sel, id)) == MPB_ENOTFOUND)
        rc = mpb__store_fail(s, MPB_EDB, "%s: row vanished", what);
    sqlite3_finalize(ins);
    sqlite3_finalize(sel);
    return rc;
}

int mpb_store_planner_config_add(mpb_store *s, int64_t experiment_id,
                                 const char *name, const char *planner,
                                 const char *algorithm, const char *params,
                                 int64_t *id)
{
    sqlite3_stmt *ins = mpb__store_prepare(s,
        "INSERT OR IGNORE INTO planner_configs(experiment_id, name, planner,"
        " algorithm, params) VALUES (?, ?, ?, ?, ?)");
    sqlite3_stmt *sel = mpb__store_prepare(s,
        "SELECT id FROM planner_configs WHERE experiment_id = ? AND name = ?");
    if (ins == NULL || sel == NULL) {
        sqlite3_finalize(ins);
        sqlite3_finalize(sel);
        return MPB_EDB;
    }
    sqlite3_bind_int64(ins, 1, experiment_id);
    sqlite3_bind_text(ins, 2, name, -1, SQLITE_STATIC);
    sqlite3_bind_text(ins, 3, planner, -1, SQLITE_STATIC);
    sqlite3_bind_text(ins, 4, algorithm, -1, SQLITE_STATIC);
    sqlite3_bind_text(ins, 5, params ? params : "", -1, SQLITE_STATIC);
    sqlite3_bind_int64(sel, 1, experiment_id);
    sqlite3_bind_text(sel, 2, name, -1, SQLITE_STATIC);
    return insert_or_get(s, ins, sel, "add planner config", id);
}

int mpb_store_planner_config_set_approach(mpb_store *s, int64_t config_id,
                                          const char *approach, int keep)
{
    sqlite3_stmt *st = mpb__store_prepare(s, keep
        ? "UPDATE planner_configs SET approach = ?2 WHERE id = ?1"
          " AND approach IS NULL"
        : "UPDATE planner_configs SET approach = ?2 WHERE id = ?1");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, config_id);
    sqlite3_bind_text(st, 2, approach, -1, SQLITE_STATIC);
    int rc = sqlite3_step(st) == SQLITE_DONE
                 ? MPB_OK : mpb__store_db_fail(s, "set approach");
    sqlite3_finalize(st);
    return rc;
}

int mpb_store_log_properties(mpb_store *s, int64_t config_id, int progress,
                             int n, const mpb_log_property *props)
{
    if (n < 0 || (n > 0 && props == NULL))
        return mpb__store_fail(s, MPB_EINVAL, "bad arguments");
    sqlite3_stmt *del = mpb__store_prepare(s,
        "DELETE FROM log_properties WHERE planner_config_id = ?"
        " AND progress = ?");
    sqlite3_stmt *ins = mpb__store_prepare(s,
        "INSERT INTO log_properties(planner_config_id, progress, idx, name,"
        " type) VALUES (?, ?, ?, ?, ?)");
    int rc = del && ins ? MPB_OK : MPB_EDB;
    if (rc == MPB_OK) {
        sqlite3_bind_int64(del, 1, config_id);
        sqlite3_bind_int(del, 2, progress != 0);
        rc = step_once(s, del, "forget a log's properties");
    }
    for (int i = 0; i < n && rc == MPB_OK; i++) {
        sqlite3_reset(ins);
        sqlite3_bind_int64(ins, 1, config_id);
        sqlite3_bind_int(ins, 2, progress != 0);
        sqlite3_bind_int(ins, 3, i);
        sqlite3_bind_text(ins, 4, props[i].name, -1, SQLITE_STATIC);
        sqlite3_bind_text(ins, 5, props[i].type, -1, SQLITE_STATIC);
        rc = step_once(s, ins, "add a log's property");
    }
    sqlite3_finalize(del);
    sqlite3_finalize(ins);
    return rc;
}

size_t mpb_store_problem_set_len(const char *scene)
{
    const char *slash = strrchr(scene, '/');
    return slash ? (size_t)(slash - scene) : strlen(scene);
}

int mpb_store_scene_add(mpb_store *s, int64_t experiment_id,
                        const mpb_scene_info *sc, int64_t *id)
{
    sqlite3_stmt *ins = mpb__store_prepare(s,
        "INSERT OR IGNORE INTO scenes(experiment_id, name, robot_format,"
        " robot_hash, robot, scene_format, scene_hash, scene, problem_set)"
        " VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)");
    sqlite3_stmt *sel = mpb__store_prepare(s,
        "SELECT id FROM scenes WHERE experiment_id = ? AND name = ?");
    if (ins == NULL || sel == NULL) {
        sqlite3_finalize(ins);
        sqlite3_finalize(sel);
        return MPB_EDB;
    }
    sqlite3_bind_int64(ins, 1, experiment_id);
    sqlite3_bind_text(ins, 2, sc->name, -1, SQLITE_STATIC);
    sqlite3_bind_text(ins, 3, sc->robot_format, -1, SQLITE_STATIC);
    sqlite3_bind_text(ins, 4, sc->robot_hash, -1, SQLITE_STATIC);
    sqlite3_bind_text(ins, 5, sc->robot, -1, SQLITE_STATIC);
    sqlite3_bind_text(ins, 6, sc->scene_format, -1, SQLITE_STATIC);
    sqlite3_bind_text(ins, 7, sc->scene_hash, -1, SQLITE_STATIC);
    sqlite3_bind_text(ins, 8, sc->scene, -1, SQLITE_STATIC);
    sqlite3_bind_text(ins, 9, sc->name,
                      (int)mpb_store_problem_set_len(sc->name), SQLITE_STATIC);
    sqlite3_bind_int64(sel, 1, experiment_id);
    sqlite3_bind_text(sel, 2, sc->name, -1, SQLITE_STATIC);
    return insert_or_get(s, ins, sel, "add scene", id);
}

int mpb_store_scene_set_seen(mpb_store *s, int64_t scene_id,
                             const mpb_seen_scene *v)
{
    if (v == NULL || v->format == NULL || v->hash == NULL || v->text == NULL)
        return mpb__store_fail(s, MPB_EINVAL, "set a scene's seen scene: a part is NULL");
    sqlite3_stmt *st = mpb__store_prepare(s,
        "UPDATE scenes SET seen_format = ?2, seen_hash = ?3, seen = ?4,"
        " seen_how = ?5 WHERE id = ?1");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, scene_id);
    sqlite3_bind_text(st, 2, v->format, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 3, v->hash, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 4, v->text, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 5, v->how, -1, SQLITE_STATIC);
    int rc = sqlite3_step(st) == SQLITE_DONE
             ? MPB_OK : mpb__store_db_fail(s, "set a scene's seen scene");
    sqlite3_finalize(st);
    if (rc == MPB_OK && sqlite3_changes(s->db) == 0)
        rc = mpb__store_fail(s, MPB_ENOTFOUND, "no scene %lld",
                             (long long)scene_id);
    return rc;
}

int mpb_store_scene_set_problem_set(mpb_store *s, int64_t scene_id,
                                    const char *set)
{
    sqlite3_stmt *st = mpb__store_prepare(s,
        "UPDATE scenes SET problem_set = ?2 WHERE id = ?1");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, scene_id);
    sqlite3_bind_text(st, 2, set, -1, SQLITE_STATIC);
    int rc = sqlite3_step(st) == SQLITE_DONE
             ? MPB_OK : mpb__store_db_fail(s, "set a scene's problem set");
    sqlite3_finalize(st);
    if (rc == MPB_OK && sqlite3_changes(s->db) == 0)
        rc = mpb__store_fail(s, MPB_ENOTFOUND, "no scene %lld",
                             (long long)scene_id);
    return rc;
}

/* v in the fewest digits that read back as v: 0.08, not the
 * 0.080000000000000002 that %.17g gives; 17 always suffice. */
static int exact_number(char *buf, size_t cap, double v)
{
    int len = 0;
    for (int digits = 15; digits <= 17; digits++) {
        len = snprintf(buf, cap, "%.*g", digits, v);
        if (strtod(buf, NULL) == v)
            break;
    }
    return len;
}

/* Numbers as text, space-separated, exact: readable at the sqlite3 prompt
 * and read back without loss. Free the result. */
static char *numbers_text(const double *v, int n)
{
    size_t cap = (size_t)n * 26 + 1;
    char *buf = malloc(cap), *p = buf;
    if (buf == NULL)
        return NULL;
    *p = '\0';
    for (int i = 0; i < n; i++) {
        if (i)
            *p++ = ' ';
        p += exact_number(p, cap - (size_t)(p - buf), v[i]);
    }
    return buf;
}

static char *names_text(const char *const *names, int n)
{
    size_t cap = 1;
    for (int i = 0; i < n; i++)
        cap += strlen(names[i]) + 1;
    char *buf = malloc(cap), *p = buf;
    if (buf == NULL)
        return NULL;
    *p = '\0';
    for (int i = 0; i < n; i++)
        p += snprintf(p, cap - (size_t)(p - buf), i ? " %s" : "%s", names[i]);
    return buf;
}

int mpb_store_query_add(mpb_store *s, int64_t scene_id,
                        const mpb_query_info *q, int64_t *id)
{
    char *names = names_text(q->joint_names, q->num_joints);
    char *start = numbers_text(q->start, q->num_joints);
    char *goal = q->goal_joints ? numbers_text(q->goal_joints, q->num_joints)
                                : NULL;
    char *region = q->goal_region ? numbers_text(q->goal_region, 12) : NULL;
    sqlite3_stmt *ins = NULL, *sel = NULL;
    int rc = MPB_ENOMEM;

    if (names == NULL || start == NULL || (q->goal_joints && goal == NULL) ||
        (q->goal_region && region == NULL))
        goto done;
    rc = MPB_EDB;
    ins = mpb__store_prepare(s,
        "INSERT OR IGNORE INTO queries(scene_id, name, joint_names, start,"
        " goal_kind, goal_joints, goal_tolerance, goal_link, goal_region)"
        " VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)");
    sel = mpb__store_prepare(s,
        "SELECT id FROM queries WHERE scene_id = ? AND name = ?");
    if (ins == NULL || sel == NULL) {
        sqlite3_finalize(ins);
        sqlite3_finalize(sel);
        goto done;
    }
    sqlite3_bind_int64(ins, 1, scene_id);
    sqlite3_bind_text(ins, 2, q->name, -1, SQLITE_STATIC);
    sqlite3_bind_text(ins, 3, names, -1, SQLITE_STATIC);
    sqlite3_bind_text(ins, 4, start, -1, SQLITE_STATIC);
    sqlite3_bind_text(ins, 5, q->goal_kind == MPB_GOAL_JOINTS ? "joints"
                                                              : "pose_region",
                      -1, SQLITE_STATIC);
    if (goal)
        sqlite3_bind_text(ins, 6, goal, -1, SQLITE_STATIC);
    sqlite3_bind_double(ins, 7, q->goal_tolerance);
    if (q->goal_link)
        sqlite3_bind_text(ins, 8, q->goal_link, -1, SQLITE_STATIC);
    if (region)
        sqlite3_bind_text(ins, 9, region, -1, SQLITE_STATIC);
    sqlite3_bind_int64(sel, 1, scene_id);
    sqlite3_bind_text(sel, 2, q->name, -1, SQLITE_STATIC);
    rc = insert_or_get(s, ins, sel, "add query", id);
done:
    if (rc == MPB_ENOMEM)
        mpb__store_fail(s, rc, "add query: out of memory");
    free(names);
    free(start);
    free(goal);
    free(region);
    return rc;
}

int mpb_store_query_set_held(mpb_store *s, int64_t query_id, int n,
                             const char *const *names, const double *values)
{
    if (n <= 0)
        return MPB_OK;
    size_t cap = 1;
    for (int i = 0; i < n; i++)
        cap += strlen(names[i]) + 2 + 32;
    char *text = malloc(cap), *p = text;
    if (text == NULL)
        return mpb__store_fail(s, MPB_ENOMEM, "held joints: out of memory");
    *p = '\0';
    for (int i = 0; i < n; i++)
        p += snprintf(p, cap - (size_t)(p - text), "%s%s=%.17g", i ? " " : "",
                      names[i], values[i]);
    sqlite3_stmt *up = mpb__store_prepare(s,
        "UPDATE queries SET held = ? WHERE id = ?");
    int rc = MPB_EDB;
    if (up != NULL) {
        sqlite3_bind_text(up, 1, text, -1, SQLITE_STATIC);
        sqlite3_bind_int64(up, 2, query_id);
        rc = sqlite3_step(up) == SQLITE_DONE
                 ? MPB_OK : mpb__store_db_fail(s, "record held joints");
        sqlite3_finalize(up);
    }
    free(text);
    return rc;
}

int mpb_store_run_add(mpb_store *s, int64_t experiment_id,
                      int64_t planner_config_id, int64_t query_id,
                      int repetition, int64_t seed)
{
    sqlite3_stmt *st = mpb__store_stmt(s, MPB__ST_RUN_ADD);
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, experiment_id);
    sqlite3_bind_int64(st, 2, planner_config_id);
    sqlite3_bind_int64(st, 3, query_id);
    sqlite3_bind_int(st, 4, repetition);
    sqlite3_bind_int64(st, 5, seed);
    int rc = sqlite3_step(st);
    sqlite3_reset(st);
    return rc == SQLITE_DONE ? MPB_OK : mpb__store_db_fail(s, "add run");
}
