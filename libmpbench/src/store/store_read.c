/*
 * store_read.c - reading an experiment back for reports: experiments, their
 * scenes, planner configurations and queries, and one pass over the
 * finished runs of a scene with the metrics of one stage of each.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/grow.h"
#include "store/store_columns.h"
#include "store/store_internal.h"

/* Finish a walk: finalize st and say how it ended. stop is what the
 * callback returned, step the last sqlite3_step() result. */
static int walk_end(mpb_store *s, sqlite3_stmt *st, int stop, int step,
                    const char *what)
{
    sqlite3_finalize(st);
    if (stop)
        return stop;
    return step == SQLITE_DONE ? MPB_OK : mpb__store_db_fail(s, what);
}

#define EXPERIMENT_COLUMNS                                                  \
    "SELECT id, name, config_file, config_hash, config_text, host, version," \
    " runs_per_query, time_limit, created, finished FROM experiments"

static mpb_experiment_row experiment_row(sqlite3_stmt *st)
{
    return (mpb_experiment_row){
        .id = sqlite3_column_int64(st, 0),
        .name = mpb__col_text(st, 1),
        .config_file = mpb__col_text(st, 2),
        .config_hash = mpb__col_text(st, 3),
        .config_text = mpb__col_text(st, 4),
        .host = mpb__col_text(st, 5),
        .version = mpb__col_text(st, 6),
        .runs_per_query = sqlite3_column_int(st, 7),
        .time_limit = mpb__col_real(st, 8),
        .created = mpb__col_real(st, 9),
        .finished = mpb__col_real(st, 10),
    };
}

int mpb_store_experiments(mpb_store *s,
                          int (*cb)(void *ud, const mpb_experiment_row *row),
                          void *ud)
{
    sqlite3_stmt *st = mpb__store_prepare(s, EXPERIMENT_COLUMNS " ORDER BY id");
    if (st == NULL)
        return MPB_EDB;
    int step, stop = 0;
    while (!stop && (step = sqlite3_step(st)) == SQLITE_ROW) {
        mpb_experiment_row row = experiment_row(st);
        stop = cb(ud, &row);
    }
    return walk_end(s, st, stop, step, "list experiments");
}

int mpb_store_experiment_get(mpb_store *s, int64_t id,
                             int (*cb)(void *ud, const mpb_experiment_row *row),
                             void *ud)
{
    sqlite3_stmt *st = mpb__store_prepare(s, EXPERIMENT_COLUMNS " WHERE id = ?");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, id);
    int step, stop = 0, seen = 0;
    while (!stop && (step = sqlite3_step(st)) == SQLITE_ROW) {
        mpb_experiment_row row = experiment_row(st);
        seen = 1;
        stop = cb(ud, &row);
    }
    int rc = walk_end(s, st, stop, step, "read experiment");
    if (rc == MPB_OK && !seen)
        rc = mpb__store_fail(s, MPB_ENOTFOUND, "no experiment %lld",
                             (long long)id);
    return rc;
}

int mpb_store_scenes(mpb_store *s, int64_t experiment_id,
                     int (*cb)(void *ud, const mpb_scene_row *row), void *ud)
{
    /* A database made before scenes.problem_set, opened read-only, has
     * none: the default rule, here; one made before seen scenes, none. */
    static const char *const sql[2][2] = {
        {"SELECT id, name, robot_format, robot_hash, robot, scene_format,"
         " scene_hash, scene, NULL, NULL, NULL, NULL, NULL FROM scenes"
         " WHERE experiment_id = ? ORDER BY id",
         "SELECT id, name, robot_format, robot_hash, robot, scene_format,"
         " scene_hash, scene, NULL, seen_format, seen_hash, seen, seen_how"
         " FROM scenes WHERE experiment_id = ? ORDER BY id"},
        {"SELECT id, name, robot_format, robot_hash, robot, scene_format,"
         " scene_hash, scene, problem_set, NULL, NULL, NULL, NULL FROM scenes"
         " WHERE experiment_id = ? ORDER BY id",
         "SELECT id, name, robot_format, robot_hash, robot, scene_format,"
         " scene_hash, scene, problem_set, seen_format, seen_hash, seen,"
         " seen_how FROM scenes WHERE experiment_id = ? ORDER BY id"},
    };
    int has_set = mpb__store_has_column(s, "scenes", "problem_set");
    int has_seen = mpb__store_has_column(s, "scenes", "seen");
    sqlite3_stmt *st = mpb__store_prepare(s, sql[has_set][has_seen]);
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, experiment_id);
    int step, stop = 0;
    char *set = NULL;
    while (!stop && (step = sqlite3_step(st)) == SQLITE_ROW) {
        const char *name = mpb__col_text(st, 1);
        const char *stored = mpb__col_text(st, 8);
        if (stored == NULL) {
            free(set);
            if ((set = strndup(name, mpb_store_problem_set_len(name))) == NULL) {
                sqlite3_finalize(st);
                return mpb__store_fail(s, MPB_ENOMEM, "out of memory");
            }
        }
        mpb_scene_row row = {
            .problem_set = stored != NULL ? stored : set,
            .id = sqlite3_column_int64(st, 0),
            .name = mpb__col_text(st, 1),
            .robot_format = mpb__col_text(st, 2),
            .robot_hash = mpb__col_text(st, 3),
            .robot = mpb__col_text(st, 4),
            .scene_format = mpb__col_text(st, 5),
            .scene_hash = mpb__col_text(st, 6),
            .scene = mpb__col_text(st, 7),
            .seen_format = mpb__col_text(st, 9),
            .seen_hash = mpb__col_text(st, 10),
            .seen = mpb__col_text(st, 11),
            .seen_how = mpb__col_text(st, 12),
        };
        if (row.seen_format == NULL || row.seen_hash == NULL || row.seen == NULL)
            row.seen_format = row.seen_hash = row.seen = row.seen_how = NULL;
        stop = cb(ud, &row);
    }
    free(set);
    return walk_end(s, st, stop, step, "list scenes");
}

int mpb_store_planner_configs(mpb_store *s, int64_t experiment_id,
                              int (*cb)(void *ud,
                                        const mpb_planner_config_row *row),
                              void *ud)
{
    /* A database made before planner_configs.approach, opened
     * read-only, has none: NULL. */
    sqlite3_stmt *st = mpb__store_prepare(s,
        mpb__store_has_column(s, "planner_configs", "approach")
        ? "SELECT id, name, planner, algorithm, params, approach"
          " FROM planner_configs WHERE experiment_id = ? ORDER BY id"
        : "SELECT id, name, planner, algorithm, params, NULL"
          " FROM planner_configs WHERE experiment_id = ? ORDER BY id");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, experiment_id);
    int step, stop = 0;
    while (!stop && (step = sqlite3_step(st)) == SQLITE_ROW) {
        mpb_planner_config_row row = {
            .id = sqlite3_column_int64(st, 0),
            .name = mpb__col_text(st, 1),
            .planner = mpb__col_text(st, 2),
            .algorithm = mpb__col_text(st, 3),
            .params = mpb__col_text(st, 4),
            .approach = mpb__col_text(st, 5),
        };
        stop = cb(ud, &row);
    }
    return walk_end(s, st, stop, step, "list planner configurations");
}

int mpb_store_queries(mpb_store *s, int64_t scene_id,
                      int (*cb)(void *ud, const mpb_query_row *row), void *ud)
{
    /* A database made before pose-region goals, opened read-only, has no
     * columns for them (a writer adds them): read NULLs instead. */
    int has_region = mpb__store_has_column(s, "queries", "goal_region");
    int has_held = mpb__store_has_column(s, "queries", "held");
    char sql[512];
    snprintf(sql, sizeof sql, "SELECT id, scene_id, name, joint_names, start,"
             " goal_kind = 'joints', goal_joints, goal_tolerance, %s, %s"
             " FROM queries WHERE scene_id = ? ORDER BY id",
             has_region ? "goal_link, goal_region" : "NULL, NULL",
             has_held ? "held" : "NULL");
    sqlite3_stmt *st = mpb__store_prepare(s, sql);
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, scene_id);
    int step, stop = 0;
    while (!stop && (step = sqlite3_step(st)) == SQLITE_ROW) {
        mpb_query_row row = {
            .id = sqlite3_column_int64(st, 0),
            .scene_id = sqlite3_column_int64(st, 1),
            .name = mpb__col_text(st, 2),
            .joint_names = mpb__col_text(st, 3),
            .start = mpb__col_text(st, 4),
            .goal_kind = sqlite3_column_int(st, 5) ? MPB_GOAL_JOINTS
                                                    : MPB_GOAL_POSE_REGION,
            .goal_joints = mpb__col_text(st, 6),
            .goal_tolerance = mpb__col_real(st, 7),
            .goal_link = mpb__col_text(st, 8),
            .goal_region = mpb__col_text(st, 9),
            .held = mpb__col_text(st, 10),
        };
        stop = cb(ud, &row);
    }
    return walk_end(s, st, stop, step, "list queries");
}

int mpb_store_unfinished_by_scene(mpb_store *s, int64_t experiment_id,
                                  int (*cb)(void *ud, int64_t scene_id,
                                            int unfinished),
                                  void *ud)
{
    /* +r.experiment_id: the runs in table order, not one seek per run
     * through runs_by_experiment (as mpb_store_refusal_depths()). */
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT q.scene_id, count(*) FROM runs r"
        " JOIN queries q ON q.id = r.query_id"
        " WHERE +r.experiment_id = ? AND r.state != 'done'"
        " GROUP BY q.scene_id ORDER BY q.scene_id");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, experiment_id);
    int step, stop = 0;
    while (!stop && (step = sqlite3_step(st)) == SQLITE_ROW)
        stop = cb(ud, sqlite3_column_int64(st, 0), sqlite3_column_int(st, 1));
    return walk_end(s, st, stop, step, "count unfinished runs");
}

int mpb_store_verification_counts(mpb_store *s, int64_t experiment_id,
                                  long *certified, long *sampled)
{
    *certified = *sampled = 0;
    if (!mpb__store_has_column(s, "stages", "verification"))
        return MPB_OK;          /* an older database, opened read-only */
    /* The stages in table order, each run found by its id: not every
     * run sought through runs_by_experiment and its stages after it
     * (a million runs: 0.48 s of CPU down to 0.26 s). */
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT sum(g.verification = 'certified'), sum(g.verification = 'sampled')"
        " FROM stages g JOIN runs r ON r.id = g.run_id WHERE +r.experiment_id = ?");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, experiment_id);
    int step = sqlite3_step(st);
    if (step == SQLITE_ROW) {
        *certified = (long)sqlite3_column_int64(st, 0);
        *sampled = (long)sqlite3_column_int64(st, 1);
        step = sqlite3_step(st);
    }
    return walk_end(s, st, 0, step, "count verifications");
}

int mpb_store_refusal_depths(mpb_store *s, int64_t experiment_id,
                             int (*cb)(void *ud, int64_t config_id,
                                       double lower_mm, double upper_mm),
                             void *ud)
{
    int depths = mpb__store_has_column(s, "stages", "depth_upper_mm");
    /* r.success = 0 first: a successful run's last stage is valid, and
     * its stage row (waypoints inline) is not read at all. A million
     * runs, 1 in 10 refused: 9 s down to 1 s on a loaded 2-core VM.
     * +r.experiment_id: the runs in table order, not one seek per run
     * through runs_by_experiment: 1.57 s of CPU down to 0.35 s there. */
    sqlite3_stmt *st = mpb__store_prepare(s, depths
        ? "SELECT r.planner_config_id, g.depth_lower_mm, g.depth_upper_mm"
          " FROM runs r JOIN stages g ON g.run_id = r.id"
          " WHERE +r.experiment_id = ? AND r.state = 'done'"
          " AND r.success = 0 AND g.verdict = 'collision'"
          " AND g.idx = (SELECT max(idx) FROM stages WHERE run_id = r.id)"
          " ORDER BY r.planner_config_id, r.id"
        : "SELECT r.planner_config_id, NULL, NULL"
          " FROM runs r JOIN stages g ON g.run_id = r.id"
          " WHERE +r.experiment_id = ? AND r.state = 'done'"
          " AND r.success = 0 AND g.verdict = 'collision'"
          " AND g.idx = (SELECT max(idx) FROM stages WHERE run_id = r.id)"
          " ORDER BY r.planner_config_id, r.id");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, experiment_id);
    int step, stop = 0;
    while (!stop && (step = sqlite3_step(st)) == SQLITE_ROW) {
        double lo = mpb__col_real(st, 1);
        double up = mpb__col_real(st, 2);
        stop = cb(ud, sqlite3_column_int64(st, 0), lo, up);
    }
    return walk_end(s, st, stop, step, "read refusal depths");
}

int mpb_store_seen_judgements(mpb_store *s, int64_t experiment_id,
                              int (*cb)(void *ud, const mpb_seen_judgement *j),
                              void *ud)
{
    if (!mpb__store_has_column(s, "runs", "seen_success"))
        return MPB_OK;
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT id, planner_config_id, query_id, coalesce(success, 0),"
        " seen_success, coalesce(claimed_success, 0), verdict, seen_verdict"
        " FROM runs WHERE +experiment_id = ? AND state = 'done'"
        " AND seen_success IS NOT NULL ORDER BY planner_config_id, id");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, experiment_id);
    int step, stop = 0;
    while (!stop && (step = sqlite3_step(st)) == SQLITE_ROW) {
        mpb_seen_judgement j = {
            .run_id = sqlite3_column_int64(st, 0),
            .planner_config_id = sqlite3_column_int64(st, 1),
            .query_id = sqlite3_column_int64(st, 2),
            .success = sqlite3_column_int(st, 3),
            .seen_success = sqlite3_column_int(st, 4),
            .claimed = sqlite3_column_int(st, 5),
            .verdict = mpb__col_text(st, 6),
            .seen_verdict = mpb__col_text(st, 7),
        };
        stop = cb(ud, &j);
    }
    return walk_end(s, st, stop, step, "read seen judgements");
}

/* ---- the results walk ---------------------------------------------------- */

/*
 * The statement yields one row per (run, metric of the chosen stage), or one
 * row with a NULL metric for a run whose stage has none; consecutive rows of
 * the same run are gathered into one mpb_result_row. Strings of the run
 * (status, stage, metric names) are copied into one text buffer that is
 * reused from run to run, so a walk allocates only while its buffers grow.
 */
#define MPB__HINTS 32          /* metrics a run, hinted */
#define MPB__HINT_NAME 48      /* bytes of a hinted name */

typedef struct result_walk {
    const char *const *names;
    int             num_names;
    mpb_result_row  row;
    double         *metrics;        /* num_names */
    char           *text;           /* status, stage, metric names */
    size_t          text_len, text_cap;
    size_t          status_off, stage_off;  /* (size_t)-1 for NULL */
    size_t         *name_off;       /* offsets of named[i].name in text */
    mpb_named      *named;
    int             named_cap;
    /* The k-th metric of the last run, for the next run's k-th: runs of
     * one stage name their metrics in one order, so one comparison finds
     * the wanted index that names[] would take num_names to find. */
    struct name_hint {
        char name[MPB__HINT_NAME];
        size_t len;             /* 0: no hint */
        int wanted;             /* its index in names, or -1 */
    } hint[MPB__HINTS];
} result_walk;

#define NO_TEXT ((size_t)-1)

/* Copy the n bytes of str into w->text, NUL-terminated; their offset. */
static int keep_textn(result_walk *w, const char *str, size_t len, size_t *off)
{
    size_t n = len + 1;
    if (w->text_len + n > w->text_cap) {
        size_t cap = w->text_cap ? w->text_cap : 256;
        while (cap < w->text_len + n)
            cap *= 2;
        char *t = realloc(w->text, cap);
        if (t == NULL)
            return MPB_ENOMEM;
        w->text = t;
        w->text_cap = cap;
    }
    memcpy(w->text + w->text_len, str, len);
    w->text[w->text_len + len] = '\0';
    *off = w->text_len;
    w->text_len += n;
    return MPB_OK;
}

/* Copy str (may be NULL) into w->text; its offset, or NO_TEXT. */
static int keep_text(result_walk *w, const char *str, size_t *off)
{
    if (str == NULL) {
        *off = NO_TEXT;
        return MPB_OK;
    }
    return keep_textn(w, str, strlen(str), off);
}

/* Start gathering the run in the statement's current row (columns 0-9 of
 * either results statement). */
static int begin_run(result_walk *w, sqlite3_stmt *st, int64_t scene_id)
{
    w->text_len = 0;
    w->row = (mpb_result_row){
        .run_id = sqlite3_column_int64(st, 0),
        .planner_config_id = sqlite3_column_int64(st, 1),
        .query_id = sqlite3_column_int64(st, 2),
        .scene_id = scene_id,
        .repetition = sqlite3_column_int(st, 3),
        .success = sqlite3_column_int(st, 4) != 0,
        .time_total = mpb__col_real(st, 6),
        .time_raw = mpb__col_real(st, 7),
        .time_other = mpb__col_real(st, 8),
        .metrics = w->metrics,
        .stage_valid = mpb__col_is_null(st, 13)
                           ? -1 : sqlite3_column_int(st, 13) != 0,
        .world_setup_time = mpb__col_real(st, 14),
        .verify_time = mpb__col_real(st, 15),
        .memory = mpb__col_real(st, 16),
        .outcome = mpb_run_outcome(sqlite3_column_int(st, 17),
                                   sqlite3_column_int(st, 18),
                                   sqlite3_column_int(st, 4) != 0),
    };
    for (int i = 0; i < w->num_names; i++)
        w->metrics[i] = NAN;
    if (keep_text(w, mpb__col_text(st, 5), &w->status_off) != MPB_OK ||
        keep_text(w, mpb__col_text(st, 9), &w->stage_off) != MPB_OK)
        return MPB_ENOMEM;
    return MPB_OK;
}

/* Add a metric (its name len bytes long) to the run. */
static int add_named(result_walk *w, const char *name, size_t len,
                     double value)
{
    int k = w->row.num_named;
    struct name_hint *h = k < MPB__HINTS ? &w->hint[k] : NULL;
    if (h != NULL && h->len == len && memcmp(h->name, name, len) == 0) {
        if (h->wanted >= 0)
            w->metrics[h->wanted] = value;
    } else {
        int wanted = -1;
        for (int i = 0; i < w->num_names; i++)
            if (strncmp(w->names[i], name, len) == 0 &&
                w->names[i][len] == '\0') {
                w->metrics[i] = value;
                wanted = wanted < 0 ? i : wanted;
            }
        /* names[] repeating a name would want both: not hinted then */
        for (int i = wanted + 1; wanted >= 0 && i < w->num_names; i++)
            if (strncmp(w->names[i], name, len) == 0 && w->names[i][len] == '\0')
                h = NULL;
        if (h != NULL && len > 0 && len < MPB__HINT_NAME) {
            memcpy(h->name, name, len);
            h->len = len;
            h->wanted = wanted;
        }
    }
    if (w->row.num_named == w->named_cap) {
        /* Two arrays of one capacity, each grown from the same one. */
        int need = w->row.num_named + 1, cap[2] = {w->named_cap, w->named_cap};
        if (mpb__grow((void **)&w->named, &cap[0], need, sizeof *w->named) !=
                MPB_OK ||
            mpb__grow((void **)&w->name_off, &cap[1], need,
                      sizeof *w->name_off) != MPB_OK)
            return MPB_ENOMEM;
        w->named_cap = cap[0];
    }
    if (keep_textn(w, name, len, &w->name_off[k]) != MPB_OK)
        return MPB_ENOMEM;
    w->named[k].value = value;
    w->row.num_named = k + 1;
    return MPB_OK;
}

/* Add the metric in columns 10 (name) and 11 (value) of st, if any. */
static int add_metric(result_walk *w, sqlite3_stmt *st)
{
    const char *name = mpb__col_text(st, 10);
    if (name == NULL)
        return MPB_OK;      /* the run's stage has no metrics */
    return add_named(w, name, strlen(name), mpb__col_real(st, 11));
}

/* Add the metrics packed in runs.final_metrics (store_internal.h). */
static int add_packed(result_walk *w, const unsigned char *p, int len)
{
    const unsigned char *end = p + len;
    while (end - p >= 1 && (size_t)(end - p - 1) >= (size_t)p[0] + 8) {
        size_t k = *p++;
        const char *name = (const char *)p;
        uint64_t bits = 0;
        double value;
        p += k;
        for (int b = 0; b < 8; b++)
            bits |= (uint64_t)p[b] << (8 * b);
        p += 8;
        memcpy(&value, &bits, sizeof value);
        if (add_named(w, name, k, value) != MPB_OK)
            return MPB_ENOMEM;
    }
    return MPB_OK;
}

/* Hand the gathered run to cb, its strings pointing into the text buffer
 * now that it has stopped moving. */
static int emit_run(result_walk *w,
                    int (*cb)(void *ud, const mpb_result_row *row), void *ud)
{
    w->row.status = w->status_off == NO_TEXT ? NULL : w->text + w->status_off;
    w->row.stage = w->stage_off == NO_TEXT ? NULL : w->text + w->stage_off;
    for (int i = 0; i < w->row.num_named; i++)
        w->named[i].name = w->text + w->name_off[i];
    w->row.named = w->row.num_named ? w->named : NULL;
    return cb(ud, &w->row);
}

/* Which scene each query of an experiment is in, for the results walk. */
typedef struct query_scenes {
    int64_t *query, *scene;
    int      n, last;
} query_scenes;

static int query_scenes_load(mpb_store *s, int64_t experiment_id,
                             query_scenes *qs)
{
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT q.id, q.scene_id FROM queries q JOIN scenes sc"
        " ON sc.id = q.scene_id WHERE sc.experiment_id = ?1");
    int step, cap = 0;
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, experiment_id);
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        if (qs->n == cap) {
            /* Two arrays of one capacity, each grown from the same one. */
            int c[2] = {cap, cap};
            if (mpb__grow((void **)&qs->query, &c[0], qs->n + 1,
                          sizeof *qs->query) != MPB_OK ||
                mpb__grow((void **)&qs->scene, &c[1], qs->n + 1,
                          sizeof *qs->scene) != MPB_OK) {
                sqlite3_finalize(st);
                return mpb__store_fail(s, MPB_ENOMEM,
                                       "read results: out of memory");
            }
            cap = c[0];
        }
        qs->query[qs->n] = sqlite3_column_int64(st, 0);
        qs->scene[qs->n++] = sqlite3_column_int64(st, 1);
    }
    return walk_end(s, st, 0, step, "read queries");
}

static int64_t query_scene(query_scenes *qs, int64_t query_id)
{
    if (qs->last < qs->n && qs->query[qs->last] == query_id)
        return qs->scene[qs->last];
    for (int i = 0; i < qs->n; i++)
        if (qs->query[i] == query_id) {
            qs->last = i;
            return qs->scene[i];
        }
    return 0;
}

/* Columns 17 and 18 of both results walks: the run's claim and its final
 * stage's stored validity, for its outcome (outcome.h). */
#define CLAIM "coalesce(r.claimed_success, 0), coalesce(r.valid, 0)"

/* The planner's world setup time of run r (MPB_WORLD_SETUP_TIME of
 * planner.h) for the statement that joins the metrics: one seek of
 * planner_values' key (run_id, name), NULL for the runs that built no
 * world. The packed walk reads runs.world_setup_time instead, where the
 * database has that column. */
#define WORLD_SETUP                                                         \
    "(SELECT v.value FROM planner_values v WHERE v.run_id = r.id"          \
    " AND v.name = 'world_setup_time')"

/*
 * The results walk over the final stages' packed metrics: one row per run,
 * no join. *absent is set if the database has no runs.final_metrics column
 * (opened read-only, made before it): then the caller joins the metrics
 * table.
 */
static int results_packed(mpb_store *s, int64_t experiment_id,
                          int64_t scene_id, result_walk *w,
                          int (*cb)(void *ud, const mpb_result_row *row),
                          void *ud, int *absent)
{
#define PACKED_SQL(setup, scene_where)                                      \
    "SELECT r.id, r.planner_config_id, r.query_id, r.repetition,"          \
    " r.success, r.status, r.time_total, r.time_raw, r.time_other,"        \
    " r.final_stage, r.final_metrics, NULL, NULL, r.valid, " setup         \
    ", " CLAIM " FROM runs r WHERE r.experiment_id = ?1 AND r.state = 'done'"         \
    scene_where " ORDER BY r.id"
#define IN_SCENE " AND r.query_id IN (SELECT id FROM queries WHERE scene_id = ?2)"
    /* Without runs.memory or runs.verify_time (a database made before
     * them, opened read-only), NULL; without runs.world_setup_time
     * either, that from planner_values, one seek per run. */
#define ALL "r.world_setup_time, r.verify_time, r.memory"
#define NO_MEMORY "r.world_setup_time, r.verify_time, NULL"
#define NO_VERIFY "r.world_setup_time, NULL, NULL"
#define NO_SETUP WORLD_SETUP ", NULL, NULL"
#define ONLY_MEMORY "r.world_setup_time, NULL, r.memory"
    static const char *const sql[5][2] = {
        {PACKED_SQL(ALL, ""), PACKED_SQL(ALL, IN_SCENE)},
        {PACKED_SQL(NO_MEMORY, ""), PACKED_SQL(NO_MEMORY, IN_SCENE)},
        {PACKED_SQL(ONLY_MEMORY, ""), PACKED_SQL(ONLY_MEMORY, IN_SCENE)},
        {PACKED_SQL(NO_VERIFY, ""), PACKED_SQL(NO_VERIFY, IN_SCENE)},
        {PACKED_SQL(NO_SETUP, ""), PACKED_SQL(NO_SETUP, IN_SCENE)},
    };
#undef ALL
#undef NO_MEMORY
#undef NO_VERIFY
#undef NO_SETUP
#undef ONLY_MEMORY
#undef IN_SCENE
#undef PACKED_SQL
    query_scenes qs = {0};
    sqlite3_stmt *st = NULL, *old = NULL;
    int rc, step = SQLITE_DONE, stop = 0;

    for (int k = 0; k < 5 && st == NULL; k++)
        if (sqlite3_prepare_v2(s->db, sql[k][scene_id > 0], -1, &st,
                               NULL) != SQLITE_OK) {
            sqlite3_finalize(st);
            st = NULL;
        }
    if (st == NULL) {
        *absent = 1;
        return MPB_OK;
    }
    if ((rc = query_scenes_load(s, experiment_id, &qs)) != MPB_OK)
        goto done;
    sqlite3_bind_int64(st, 1, experiment_id);
    if (scene_id > 0)
        sqlite3_bind_int64(st, 2, scene_id);
    while (!stop && (step = sqlite3_step(st)) == SQLITE_ROW) {
        int64_t query_id = sqlite3_column_int64(st, 2);
        if ((rc = begin_run(w, st, query_scene(&qs, query_id))) != MPB_OK)
            goto done;
        if (!mpb__col_is_null(st, 10)) {
            rc = add_packed(w, sqlite3_column_blob(st, 10),
                            sqlite3_column_bytes(st, 10));
        } else if (!mpb__col_is_null(st, 9)) {
            /* Finished before the column existed: the metrics table. */
            if (old == NULL && (old = mpb__store_prepare(s,
                    "SELECT NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL,"
                    " NULL, NULL, name, value FROM metrics"
                    " WHERE run_id = ?1 AND stage = ?2")) == NULL) {
                rc = MPB_EDB;
                goto done;
            }
            sqlite3_reset(old);
            sqlite3_bind_int64(old, 1, w->row.run_id);
            sqlite3_bind_text(old, 2, w->text + w->stage_off, -1,
                              SQLITE_STATIC);
            int ostep = SQLITE_DONE;
            while (rc == MPB_OK && (ostep = sqlite3_step(old)) == SQLITE_ROW)
                rc = add_metric(w, old);
            if (rc == MPB_OK && ostep != SQLITE_DONE) {
                rc = mpb__store_db_fail(s, "read results");
                goto done;
            }
        }
        if (rc != MPB_OK)
            goto done;
        stop = emit_run(w, cb, ud);
    }
    if (!stop && step != SQLITE_DONE)
        rc = mpb__store_db_fail(s, "read results");
done:
    sqlite3_finalize(st);
    sqlite3_finalize(old);
    free(qs.query);
    free(qs.scene);
    return stop ? stop : rc;
}

int mpb_store_results(mpb_store *s, int64_t experiment_id, int64_t scene_id,
                      const char *stage, const char *const *names,
                      int num_names,
                      int (*cb)(void *ud, const mpb_result_row *row),
                      void *ud)
{
    /* The metrics of each run's final stage are packed on its row (see
     * results_packed); those of another stage, or of a database made
     * before runs.final_metrics, come from this statement. Its history:
     * one statement for a scene, or for the whole experiment. Runs are
     * read in id order, the order of the runs_by_state index, so nothing
     * is sorted; the metrics are joined by their primary key (run_id,
     * stage, name), one index seek per run. Measured on a million runs
     * with nine metric rows each (2-core VM): 2.6 s for all scenes, where
     * ordering the rows by query for the caller took 5.7 s. */
#define RESULTS_SQL(scene_where, verify)                                    \
    "SELECT r.id, r.planner_config_id, r.query_id, r.repetition,"          \
    " r.success, r.status, r.time_total, r.time_raw, r.time_other,"        \
    " coalesce(?3, r.final_stage), m.name, m.value, q.scene_id, st.valid," \
    " " WORLD_SETUP ", " verify ", " CLAIM                                  \
    " FROM runs r JOIN queries q ON q.id = r.query_id"                     \
    " LEFT JOIN metrics m ON m.run_id = r.id"                              \
    "  AND m.stage = coalesce(?3, r.final_stage)"                          \
    " LEFT JOIN stages st ON st.run_id = r.id"                             \
    "  AND st.name = coalesce(?3, r.final_stage)"                          \
    " WHERE r.experiment_id = ?1 AND r.state = 'done'" scene_where         \
    " ORDER BY r.id"
    /* Without runs.verify_time or runs.memory (a database made before
     * it, opened read-only), NULL. */
#define IN_SCENE " AND q.scene_id = ?2"
#define BOTH(cols) {RESULTS_SQL("", cols), RESULTS_SQL(IN_SCENE, cols)}
    static const char *const sql[4][2] = {
        BOTH("r.verify_time, r.memory"), BOTH("r.verify_time, NULL"),
        BOTH("NULL, r.memory"), BOTH("NULL, NULL"),
    };
#undef BOTH
#undef IN_SCENE
#undef RESULTS_SQL
    result_walk w = {.names = names, .num_names = num_names};
    sqlite3_stmt *st = NULL;
    int rc = MPB_OK, stop = 0, step, have_run = 0;

    if (num_names < 0 || (num_names > 0 && names == NULL))
        return mpb__store_fail(s, MPB_EINVAL, "results: bad metric names");
    if (num_names > 0 &&
        (w.metrics = malloc(sizeof *w.metrics * (size_t)num_names)) == NULL) {
        rc = MPB_ENOMEM;
        goto done;
    }
    if (stage == NULL) {
        int absent = 0;
        rc = results_packed(s, experiment_id, scene_id, &w, cb, ud, &absent);
        if (!absent) {
            if (rc == MPB_ENOMEM)
                mpb__store_fail(s, rc, "read results: out of memory");
            goto done_packed;
        }
    }
    int cols = 2 * !mpb__store_has_column(s, "runs", "verify_time") +
               !mpb__store_has_column(s, "runs", "memory");
    if ((st = mpb__store_prepare(s, sql[cols][scene_id > 0])) == NULL) {
        rc = MPB_EDB;
        goto done;
    }
    sqlite3_bind_int64(st, 1, experiment_id);
    if (scene_id > 0)
        sqlite3_bind_int64(st, 2, scene_id);
    if (stage != NULL)
        sqlite3_bind_text(st, 3, stage, -1, SQLITE_STATIC);

    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        int64_t run_id = sqlite3_column_int64(st, 0);
        if (!have_run || run_id != w.row.run_id) {
            if (have_run && (stop = emit_run(&w, cb, ud)) != 0)
                goto done;
            if ((rc = begin_run(&w, st, sqlite3_column_int64(st, 12)))
                != MPB_OK)
                goto done;
            have_run = 1;
        }
        if ((rc = add_metric(&w, st)) != MPB_OK)
            goto done;
    }
    if (step != SQLITE_DONE) {
        rc = mpb__store_db_fail(s, "read results");
        goto done;
    }
    if (have_run)
        stop = emit_run(&w, cb, ud);
done:
    if (rc == MPB_ENOMEM)
        mpb__store_fail(s, rc, "read results: out of memory");
    sqlite3_finalize(st);
done_packed:
    free(w.metrics);
    free(w.text);
    free(w.name_off);
    free(w.named);
    return stop ? stop : rc;
}
