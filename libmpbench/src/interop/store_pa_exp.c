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
typedef struct scene_gather {
    const exp_info *e;
    scene_problem  *v;
    int             n, cap;
} scene_gather;

static int gather_scene(void *ud, int64_t id, const char *name)
{
    scene_gather *g = ud;
    size_t len = strlen(g->e->name) + strlen(name) + 2;
    if (mpb__grow((void **)&g->v, &g->cap, g->n + 1, sizeof *g->v))
        return MPB_ENOMEM;
    g->v[g->n] = (scene_problem){.id = id, .problem = malloc(len)};
    if (g->v[g->n++].problem == NULL)
        return MPB_ENOMEM;
    snprintf(g->v[g->n - 1].problem, len, "%s/%s", g->e->name, name);
    mpb__pa_one_word(g->v[g->n - 1].problem);
    return MPB_OK;
}

static int scene_problems(mpb_store *s, const exp_info *e,
                          scene_problem **out, int *num)
{
    scene_gather g = {.e = e};
    *out = NULL;
    *num = 0;
    int rc = mpb__store_each_scene(s, e->id, gather_scene, &g);
    scene_problem *v = g.v;
    int n = g.n;
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
    char *setup = NULL, *name = NULL;
    int rc = mpb__store_scene_robot(s, scene_id, &setup);
    if (rc != MPB_OK || setup == NULL)
        return rc;
    if ((name = strdup(e->name)) == NULL) {
        free(setup);
        return MPB_ENOMEM;
    }
    mpb__pa_one_word(name);
    free(q->setup);
    free(q->problem);
    q->setup = setup;
    q->problem = name;
    return MPB_OK;
}

typedef struct query_gather {
    mpb_store           *s;
    const exp_info      *e;
    const scene_problem *scenes;
    int                  num_scenes, si;
    pa_query_list       *out;
} query_gather;

static int gather_query(void *ud, const mpb__done_query *dq)
{
    query_gather *g = ud;
    const exp_info *e = g->e;
    if (mpb__grow((void **)&g->out->v, &g->out->cap, g->out->n + 1,
                  sizeof *g->out->v))
        return MPB_ENOMEM;
    pa_query *q = &g->out->v[g->out->n++];
    *q = (pa_query){.query_id = dq->id, .runs = dq->runs,
                    .total_time = dq->total_time};
    /* By scene, as the scenes are. */
    while (g->si < g->num_scenes && g->scenes[g->si].id != dq->scene_id)
        g->si++;
    if (g->si == g->num_scenes)
        return mpb__store_fail(g->s, MPB_EDB, "query %lld has no scene",
                               (long long)q->query_id);
    char *goal = goal_text(dq->goal_kind, dq->goal_joints, dq->goal_tolerance,
                           dq->goal_link, dq->goal_region);
    size_t ns = strlen(e->config_text) + 256 + strlen(dq->joint_names) +
                strlen(dq->start) + (goal ? strlen(goal) : 0) +
                strlen(dq->name);
    q->problem = strdup(g->scenes[g->si].problem);
    q->query = strdup(dq->name);
    q->setup = malloc(ns);
    if (!q->problem || !q->query || !q->setup || !goal) {
        free(goal);
        return MPB_ENOMEM;
    }
    snprintf(q->setup, ns,
             "%s%s\nmpbench experiment %lld, query %s\n"
             "joints: %s\nstart: %s\n%s",
             e->config_text,
             e->config_text[0] &&
                     e->config_text[strlen(e->config_text) - 1] != '\n'
                 ? "\n" : "",
             (long long)e->id, q->query, dq->joint_names, dq->start, goal);
    free(goal);
    /* An imported log's experiment (one scene, one query) keeps its name
     * and its setup block (the scene's robot text). */
    return e->started ? log_problem(g->s, e, dq->scene_id, q) : MPB_OK;
}

int mpb__pa_read_queries(mpb_store *s, const exp_info *e, pa_query_list *out)
{
    scene_problem *scenes = NULL;
    int num_scenes = 0;
    int rc = scene_problems(s, e, &scenes, &num_scenes);
    if (rc == MPB_OK) {
        query_gather g = {.s = s, .e = e, .scenes = scenes,
                          .num_scenes = num_scenes, .out = out};
        rc = mpb__store_each_done_query(s, e->id, gather_query, &g);
    }
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
