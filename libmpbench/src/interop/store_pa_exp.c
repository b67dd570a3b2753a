/*
 * store_pa_exp.c - what every writer of OMPL's formats says of an
 * experiment (store_pa.h): its header (name, host, version, date, seed,
 * an imported log's experiment properties), its queries as Planner Arena
 * experiments, a configuration's settings text and the ids to export.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/grow.h"
#include "interop/store_pa.h"

void mpb__pa_exp_info_free(exp_info *e)
{
    free(e->name);
    free(e->config_text);
    free(e->host);
    free(e->version);
    free(e->started);
    free(e->seed);
    free(e->cpuinfo);
    for (int i = 0; e->params && i < e->num_params; i++) {
        free(e->params[i].name);
        free(e->params[i].type);
        free(e->params[i].value);
    }
    free(e->params);
    *e = (exp_info){0};
}

char *mpb__pa_param_column(const char *name)
{
    char *c = malloc(strlen(name) + 1), *d = c;
    for (; c && *name; name++)
        if (*name != ' ')
            *d++ = *name == '-' ? '_' : *name;
    if (c)
        *d = '\0';
    return c;
}

const char *mpb__pa_exp_param(const exp_info *e, const char *column)
{
    for (int i = 0; i < e->num_params; i++) {
        char *c = mpb__pa_param_column(e->params[i].name);
        int same = c && mpb__pa_same_column(c, column);
        free(c);
        if (same)
            return e->params[i].value;
    }
    return NULL;
}

/* A text column copied, NULL for NULL; *oom set when out of memory. */
static char *col_dup_or_null(sqlite3_stmt *st, int i, int *oom)
{
    if (sqlite3_column_type(st, i) == SQLITE_NULL)
        return NULL;
    char *c = mpb__pa_col_dup(st, i);
    *oom |= c == NULL;
    return c;
}

/* An imported log's header and experiment properties into e; nothing
 * for a database made before they were kept. */
static int read_log_header(mpb_store *s, exp_info *e)
{
    e->total_time = e->memory_limit = NAN;
    if (!mpb__store_has_column(s, "experiments", "started"))
        return MPB_OK;
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT started, seed, cpuinfo, total_time, memory_limit"
        " FROM experiments WHERE id = ?");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, e->id);
    int oom = 0, rc = MPB_OK;
    if (sqlite3_step(st) == SQLITE_ROW) {
        e->started = col_dup_or_null(st, 0, &oom);
        e->seed = col_dup_or_null(st, 1, &oom);
        e->cpuinfo = col_dup_or_null(st, 2, &oom);
        e->total_time = mpb__pa_col_num(st, 3);
        e->memory_limit = mpb__pa_col_num(st, 4);
    }
    sqlite3_finalize(st);
    if (!oom && mpb__store_has_column(s, "experiment_params", "name")) {
        st = mpb__store_prepare(s, "SELECT name, type, value FROM"
                                " experiment_params WHERE experiment_id = ?"
                                " ORDER BY idx");
        if (st == NULL)
            return MPB_EDB;
        sqlite3_bind_int64(st, 1, e->id);
        int cap = 0, step;
        while (!oom && (step = sqlite3_step(st)) == SQLITE_ROW) {
            if (mpb__grow((void **)&e->params, &cap, e->num_params + 1,
                          sizeof *e->params)) {
                oom = 1;
                break;
            }
            exp_param *p = &e->params[e->num_params++];
            *p = (exp_param){mpb__pa_col_dup(st, 0), mpb__pa_col_dup(st, 1),
                             mpb__pa_col_dup(st, 2)};
            oom |= !p->name || !p->type || !p->value;
        }
        if (!oom && step != SQLITE_DONE)
            rc = mpb__store_db_fail(s, "read experiment parameters");
        sqlite3_finalize(st);
    }
    return oom ? mpb__store_fail(s, MPB_ENOMEM, "out of memory") : rc;
}

int mpb__pa_exp_info_read(mpb_store *s, int64_t id, exp_info *e)
{
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT name, config_text, host, version, runs_per_query, time_limit,"
        " created FROM experiments WHERE id = ?");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, id);
    int step = sqlite3_step(st), rc = MPB_OK;
    if (step == SQLITE_ROW) {
        e->id = id;
        e->name = mpb__pa_col_dup(st, 0);
        e->config_text = mpb__pa_col_dup(st, 1);
        e->host = mpb__pa_col_dup(st, 2);
        e->version = mpb__pa_col_dup(st, 3);
        e->runs_per_query = sqlite3_column_int(st, 4);
        e->time_limit = mpb__pa_col_num(st, 5);
        e->created = mpb__pa_col_num(st, 6);
        if (!e->name || !e->config_text || !e->host || !e->version)
            rc = mpb__store_fail(s, MPB_ENOMEM, "out of memory");
        else
            rc = read_log_header(s, e);
    } else if (step == SQLITE_DONE) {
        rc = mpb__store_fail(s, MPB_ENOTFOUND, "no experiment %lld",
                             (long long)id);
    } else {
        rc = mpb__store_db_fail(s, "read experiment");
    }
    sqlite3_finalize(st);
    return rc;
}

void mpb__pa_one_word(char *s)
{
    for (; *s; s++)
        if (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r')
            *s = '_';
}

const char *mpb__pa_version_of(const exp_info *e)
{
    return e->version[0] ? e->version : "mpbench " MPB_VERSION_STRING;
}

void mpb__pa_queries_free(pa_query_list *l)
{
    for (int i = 0; i < l->n; i++) {
        free(l->v[i].problem);
        free(l->v[i].query);
        free(l->v[i].setup);
    }
    free(l->v);
    *l = (pa_query_list){0};
}

/* A scene's Planner Arena experiment name. */
typedef struct scene_problem {
    int64_t id;
    char   *problem;
    int     clash;
} scene_problem;

static void scene_problems_free(scene_problem *v, int n)
{
    for (int i = 0; i < n; i++)
        free(v[i].problem);
    free(v);
}

/*
 * The Planner Arena experiment name of each scene of experiment e, by
 * scene id: "<experiment>/<scene>", one word. Scenes whose names become
 * the same word ("a b", "a_b") are told apart by "#N", N the scene's place
 * in the experiment (1, 2, ...), so that reruns of an experiment file get
 * the same names; again while names are the same (a scene may be called
 * "a_b#1"). That ends: two names that end in "#N" differ in N, so each
 * round gives a suffix to at least one scene that had none.
 */
static int scene_problems(mpb_store *s, const exp_info *e,
                          scene_problem **out, int *num)
{
    scene_problem *v = NULL;
    int n = 0, cap = 0, step, rc = MPB_OK;
    *out = NULL;
    *num = 0;
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT id, name FROM scenes WHERE experiment_id = ?1 ORDER BY id");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, e->id);
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        const char *name = (const char *)sqlite3_column_text(st, 1);
        size_t len = strlen(e->name) + strlen(name ? name : "") + 2;
        if (mpb__grow((void **)&v, &cap, n + 1, sizeof *v)) {
            rc = MPB_ENOMEM;
            break;
        }
        v[n] = (scene_problem){.id = sqlite3_column_int64(st, 0),
                               .problem = malloc(len)};
        if (v[n++].problem == NULL) {
            rc = MPB_ENOMEM;
            break;
        }
        snprintf(v[n - 1].problem, len, "%s/%s", e->name, name ? name : "");
        mpb__pa_one_word(v[n - 1].problem);
    }
    if (rc == MPB_OK && step != SQLITE_DONE)
        rc = mpb__store_db_fail(s, "read scenes");
    sqlite3_finalize(st);
    for (int clashes = 1; rc == MPB_OK && clashes;) {
        clashes = 0;
        for (int i = 0; i < n; i++) {
            v[i].clash = 0;
            for (int j = 0; j < n && !v[i].clash; j++)
                v[i].clash = j != i && strcmp(v[i].problem, v[j].problem) == 0;
            clashes |= v[i].clash;
        }
        for (int i = 0; i < n && rc == MPB_OK; i++) {
            if (!v[i].clash)
                continue;
            size_t len = strlen(v[i].problem) + 16;
            char *p = malloc(len);
            if (p == NULL) {
                rc = MPB_ENOMEM;
                break;
            }
            snprintf(p, len, "%s#%d", v[i].problem, i + 1);
            free(v[i].problem);
            v[i].problem = p;
        }
    }
    if (rc != MPB_OK) {
        scene_problems_free(v, n);
        return rc;
    }
    *out = v;
    *num = n;
    return MPB_OK;
}

/*
 * The goal lines of a query's setup. A joint goal: its joints and the
 * tolerance (the start's and the goal's). A pose region: its link, the
 * 12 stored numbers under their experiment file keys (box centre and half
 * sizes, reference rpy and tolerances), and the tolerance, the start's
 * only. Caller frees; NULL when out of memory.
 */
static char *goal_text(const char *kind, const char *joints,
                       const char *tolerance, const char *link,
                       const char *region)
{
    static const char *const keys[] = {"position", "position_tolerance",
                                       "rpy", "rpy_tolerance"};
    char *text = NULL;
    size_t len = 0;
    FILE *out = open_memstream(&text, &len);
    if (out == NULL)
        return NULL;
    if (strcmp(kind, "pose_region") != 0) {
        fprintf(out, "goal (%s): %s\ntolerance: %s\n", kind, joints,
                tolerance);
    } else {
        const char *num[12];
        size_t num_len[12];
        int n = 0;
        for (const char *p = region; n < 13;) {
            p += strspn(p, " ");
            if (*p == '\0')
                break;
            size_t k = strcspn(p, " ");
            if (n < 12) {
                num[n] = p;
                num_len[n] = k;
            }
            n++;
            p += k;
        }
        fprintf(out, "goal (%s): link %s\n", kind, link);
        if (n == 12)
            for (int i = 0; i < 4; i++)
                fprintf(out, "  %s: %.*s %.*s %.*s\n", keys[i],
                        (int)num_len[3 * i], num[3 * i],
                        (int)num_len[3 * i + 1], num[3 * i + 1],
                        (int)num_len[3 * i + 2], num[3 * i + 2]);
        else
            fprintf(out, "  region: %s\n", region);  /* not 12 numbers */
        fprintf(out, "start tolerance: %s\n", tolerance);
    }
    if (fclose(out) != 0) {
        free(text);
        return NULL;
    }
    return text;
}

/* q as the imported log e had it: its experiment's name and setup. */
static int log_problem(mpb_store *s, const exp_info *e, int64_t scene_id,
                       pa_query *q)
{
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT robot FROM scenes WHERE id = ?");
    if (st == NULL)
        return MPB_EDB;
    sqlite3_bind_int64(st, 1, scene_id);
    int rc = MPB_OK;
    if (sqlite3_step(st) == SQLITE_ROW) {
        char *setup = mpb__pa_col_dup(st, 0), *name = strdup(e->name);
        if (setup == NULL || name == NULL) {
            free(setup);
            free(name);
            rc = MPB_ENOMEM;
        } else {
            mpb__pa_one_word(name);
            free(q->setup);
            free(q->problem);
            q->setup = setup;
            q->problem = name;
        }
    }
    sqlite3_finalize(st);
    return rc;
}

int mpb__pa_read_queries(mpb_store *s, const exp_info *e, pa_query_list *out)
{
    scene_problem *scenes = NULL;
    int step, rc, num_scenes = 0, si = 0;
    if ((rc = scene_problems(s, e, &scenes, &num_scenes)) != MPB_OK)
        goto done;
    /* A database made before pose-region goals, opened read-only, has no
     * columns for them (a writer adds them): NULLs instead. */
    int has_region = mpb__store_has_column(s, "queries", "goal_region");
    sqlite3_stmt *st = mpb__store_prepare(s, has_region
        ? "SELECT q.id, q.name, q.scene_id, count(r.id), total(r.wall_time),"
          " q.joint_names, q.start, q.goal_kind, q.goal_joints,"
          " q.goal_tolerance, q.goal_link, q.goal_region"
          " FROM queries q JOIN scenes sc ON sc.id = q.scene_id"
          " JOIN runs r ON r.query_id = q.id AND r.state = 'done'"
          " WHERE sc.experiment_id = ?1 GROUP BY q.id ORDER BY sc.id, q.id"
        : "SELECT q.id, q.name, q.scene_id, count(r.id), total(r.wall_time),"
          " q.joint_names, q.start, q.goal_kind, q.goal_joints,"
          " q.goal_tolerance, NULL, NULL"
          " FROM queries q JOIN scenes sc ON sc.id = q.scene_id"
          " JOIN runs r ON r.query_id = q.id AND r.state = 'done'"
          " WHERE sc.experiment_id = ?1 GROUP BY q.id ORDER BY sc.id, q.id");
    if (st == NULL) {
        rc = MPB_EDB;
        goto done;
    }
    sqlite3_bind_int64(st, 1, e->id);
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        if ((rc = mpb__grow((void **)&out->v, &out->cap, out->n + 1,
                            sizeof *out->v)))
            break;
        pa_query *q = &out->v[out->n++];
        *q = (pa_query){.query_id = sqlite3_column_int64(st, 0),
                        .runs = sqlite3_column_int(st, 3),
                        .total_time = sqlite3_column_double(st, 4)};
        /* By scene, as the scenes are. */
        int64_t scene_id = sqlite3_column_int64(st, 2);
        while (si < num_scenes && scenes[si].id != scene_id)
            si++;
        if (si == num_scenes) {
            rc = mpb__store_fail(s, MPB_EDB, "query %lld has no scene",
                                 (long long)q->query_id);
            break;
        }
        const char *text[7];
        for (int i = 0; i < 7; i++) {
            text[i] = (const char *)sqlite3_column_text(st, 5 + i);
            if (text[i] == NULL)
                text[i] = "";
        }
        char *goal = goal_text(text[2], text[3], text[4], text[5], text[6]);
        size_t ns = strlen(e->config_text) + 256 + strlen(text[0]) +
                    strlen(text[1]) + (goal ? strlen(goal) : 0) +
                    strlen((const char *)sqlite3_column_text(st, 1));
        q->problem = strdup(scenes[si].problem);
        q->query = mpb__pa_col_dup(st, 1);
        q->setup = malloc(ns);
        if (!q->problem || !q->query || !q->setup || !goal) {
            free(goal);
            rc = MPB_ENOMEM;
            break;
        }
        snprintf(q->setup, ns,
                 "%s%s\nmpbench experiment %lld, query %s\n"
                 "joints: %s\nstart: %s\n%s",
                 e->config_text,
                 e->config_text[0] &&
                         e->config_text[strlen(e->config_text) - 1] != '\n'
                     ? "\n" : "",
                 (long long)e->id, q->query, text[0], text[1], goal);
        free(goal);
        /* An imported log's experiment (one scene, one query) keeps its
         * name and its setup block (the scene's robot text). */
        if (e->started && (rc = log_problem(s, e, scene_id, q)) != MPB_OK)
            break;
    }
    if (rc == MPB_OK && step != SQLITE_DONE)
        rc = mpb__store_db_fail(s, "read queries");
    sqlite3_finalize(st);
done:
    if (rc == MPB_ENOMEM)
        mpb__store_fail(s, rc, "out of memory");
    scene_problems_free(scenes, num_scenes);
    return rc;
}

char *mpb__pa_config_settings(const char *planner, const char *algorithm,
                              const char *params)
{
    size_t cap = strlen(planner) + strlen(algorithm) + 3 * strlen(params) +
                 64;
    char *lines[256];
    int n = 0;
    char *buf = malloc(cap), *text = strdup(params ? params : "");
    if (buf == NULL || text == NULL) {
        free(buf);
        free(text);
        return NULL;
    }
    char alg[256], pl[256];
    snprintf(alg, sizeof alg, "algorithm = %s", algorithm);
    snprintf(pl, sizeof pl, "planner = %s", planner);
    lines[n++] = alg;
    lines[n++] = pl;
    /* params: "key=value;key=value" */
    char *save = NULL;
    char *kv_store = malloc(strlen(text) * 3 + 64);
    char *kv = kv_store;
    if (kv_store == NULL) {
        free(buf);
        free(text);
        return NULL;
    }
    for (char *tok = strtok_r(text, ";", &save); tok && n < 256;
         tok = strtok_r(NULL, ";", &save)) {
        char *eq = strchr(tok, '=');
        if (eq == NULL || eq == tok)
            continue;
        /* An imported log's "k = v" as OMPL writes it, not "k  =  v". */
        char *end = eq, *value = eq + 1;
        while (end > tok && end[-1] == ' ')
            end--;
        while (*value == ' ')
            value++;
        *end = '\0';
        int len = sprintf(kv, "%s = %s", tok, value);
        lines[n++] = kv;
        kv += len + 1;
    }
    /* sort (insertion: a handful of lines) */
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && strcmp(lines[j - 1], lines[j]) > 0; j--) {
            char *t = lines[j];
            lines[j] = lines[j - 1];
            lines[j - 1] = t;
        }
    buf[0] = '\0';
    size_t len = 0;
    for (int i = 0; i < n; i++)
        len += (size_t)snprintf(buf + len, cap - len, "%s\n;", lines[i]);
    free(text);
    free(kv_store);
    return buf;
}

void mpb__pa_format_date(double t, char *buf, size_t n)
{
    buf[0] = '\0';
    if (isnan(t))
        return;
    time_t tt = (time_t)t;
    struct tm tm;
    if (gmtime_r(&tt, &tm) != NULL)
        strftime(buf, n, "%Y-%m-%d %H:%M:%S", &tm);
}

int mpb__pa_experiment_ids(mpb_store *s, const int64_t *ids, int num_ids,
                           int64_t **out, int *n)
{
    *out = NULL;
    *n = 0;
    if (num_ids > 0) {
        sqlite3_stmt *st = mpb__store_prepare(s,
            "SELECT 1 FROM experiments WHERE id = ?");
        if (st == NULL)
            return MPB_EDB;
        for (int i = 0; i < num_ids; i++) {
            sqlite3_reset(st);
            sqlite3_bind_int64(st, 1, ids[i]);
            if (sqlite3_step(st) != SQLITE_ROW) {
                sqlite3_finalize(st);
                return mpb__store_fail(s, MPB_ENOTFOUND, "no experiment %lld",
                                       (long long)ids[i]);
            }
        }
        sqlite3_finalize(st);
        if ((*out = malloc(sizeof **out * (size_t)num_ids)) == NULL)
            return mpb__store_fail(s, MPB_ENOMEM, "out of memory");
        for (int i = 0; i < num_ids; i++) {   /* each id once */
            int seen = 0;
            for (int j = 0; j < *n && !seen; j++)
                seen = (*out)[j] == ids[i];
            if (!seen)
                (*out)[(*n)++] = ids[i];
        }
        return MPB_OK;
    }
    sqlite3_stmt *st = mpb__store_prepare(s,
        "SELECT id FROM experiments ORDER BY id");
    int step, cap = 0;
    if (st == NULL)
        return MPB_EDB;
    while ((step = sqlite3_step(st)) == SQLITE_ROW) {
        if (mpb__grow((void **)out, &cap, *n + 1, sizeof **out)) {
            sqlite3_finalize(st);
            return mpb__store_fail(s, MPB_ENOMEM, "out of memory");
        }
        (*out)[(*n)++] = sqlite3_column_int64(st, 0);
    }
    sqlite3_finalize(st);
    if (step != SQLITE_DONE)
        return mpb__store_db_fail(s, "list experiments");
    if (*n == 0)
        return mpb__store_fail(s, MPB_ENOTFOUND, "no experiment to export");
    return MPB_OK;
}

