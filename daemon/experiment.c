/*
 * experiment.c - reading an experiment file: its settings, then its
 * robot and scenes (experiment_robot.c, experiment_scenes.c,
 * experiment_moveit.c) and planners (experiment_planners.c), through the
 * YAML kit (yamldoc.c); and what the daemon asks of an experiment once
 * read (seeds, goals, notes).
 */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "experiment_load.h"

/* Read as an integer, not through a double: 2^53 + 1 stays itself. */
static int parse_seed(mpbd_loader *L, yaml_node_t *n, uint64_t *out)
{
    const char *s = scalar(n);
    long long v;
    if (s != NULL && mpbd_yaml_is_decimal(s, 1)) {
        errno = 0;
        v = strtoll(s, NULL, 10);
        if (errno == 0) {
            *out = (uint64_t)v;
            return 0;
        }
    }
    return fail_at(L, n, "seed must be an integer in digits (no point or "
                   "exponent) from %lld to %lld%s%s%s",
                   LLONG_MIN, LLONG_MAX, s ? ", not '" : "", s ? s : "",
                   s ? "'" : "");
}

static int load_settings(mpbd_loader *L, mpbd_experiment *e, yaml_node_t *root)
{
    static const char *const keys[] = {"name", "runs", "time_limit", "seed",
                                       "retries", "runs_per_host",
                                       "queue_at_planner", "memory_limit",
                                       "verification", NULL};
    yaml_node_t *m = need(L, root, "experiment", YAML_MAPPING_NODE,
                          "a mapping of name, runs, time_limit, seed");
    yaml_node_t *n;
    if (m == NULL || only_keys(L, m, keys) != 0)
        return -1;
    if ((e->name = need_string(L, m, "name")) == NULL)
        return -1;
    e->runs = 1;
    if ((n = get(L, m, "runs")) && parse_positive_int(L, n, "runs", &e->runs))
        return -1;
    if ((n = need(L, m, "time_limit", YAML_SCALAR_NODE, "seconds")) == NULL ||
        parse_double(L, n, "time_limit", &e->time_limit) != 0)
        return -1;
    if (e->time_limit <= 0)
        return fail_at(L, n, "time_limit must be positive");
    if ((n = get(L, m, "seed")) != NULL && parse_seed(L, n, &e->seed) != 0)
        return -1;
    e->runs_per_host = 1;
    if ((n = get(L, m, "runs_per_host")) &&
        parse_positive_int(L, n, "runs_per_host", &e->runs_per_host))
        return -1;
    /* 0 is allowed for these, unlike the other counts. */
    if ((n = get(L, m, "retries")) &&
        parse_int_in(L, n, "retries", 0, 1000000000, &e->retries))
        return -1;
    if ((n = get(L, m, "queue_at_planner")) &&
        parse_int_in(L, n, "queue_at_planner", 0, MPBD_QUEUE_AT_PLANNER_MAX,
                     &e->queue_at_planner))
        return -1;
    /* MB over what the planner process held when the run began
     * (docs/experiment-format.md); the planner enforces it. */
    if ((n = get(L, m, "memory_limit")) != NULL) {
        if (parse_double(L, n, "memory_limit", &e->memory_limit) != 0)
            return -1;
        if (!(e->memory_limit > 0 && e->memory_limit <= 1048576))
            return fail_at(L, n, "memory_limit must be MB above 0 and at "
                           "most 1048576 (1 TB), not '%s'", scalar(n));
    }
    /* How segments are checked (mpb_verification, docs/verification.md). */
    if ((n = get(L, m, "verification")) != NULL) {
        const char *v = scalar(n);
        if (v && strcmp(v, "sampled") == 0)
            e->verification = MPB_VERIFY_SAMPLED;
        else if (!v || strcmp(v, "certified") != 0)
            return fail_at(L, n, "verification must be certified or sampled, "
                           "not '%s'", v ? v : "");
    }
    return 0;
}

static char *dir_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    size_t n = slash ? (size_t)(slash - path + 1) : 0;
    char *d = malloc(n + 1);
    if (d) {
        memcpy(d, path, n);
        d[n] = '\0';
    }
    return d;
}

mpbd_experiment *mpbd_experiment_load(const char *path, char *err,
                                      size_t errlen)
{
    static const char *const top_keys[] = {"experiment", "robot", "scenes",
                                           "planners", NULL};
    mpbd_loader L = {.y = {.path = path, .err = err, .errlen = errlen}};
    mpbd_experiment *e = calloc(1, sizeof *e);
    size_t len = 0;
    int have_doc = 0;

    if (e == NULL) {
        snprintf(err, errlen, "%s: out of memory", path);
        return NULL;
    }
    if ((e->text = mpb_read_file(path, 0, &len)) == NULL) {
        snprintf(err, errlen, "%s: cannot read: %s", path, strerror(errno));
        goto fail;
    }
    e->file = strdup(path);
    L.dir = dir_of(path);
    if (e->file == NULL || L.dir == NULL) {
        snprintf(err, errlen, "%s: out of memory", path);
        goto fail;
    }
    mpb_hash_hex(e->text, len, e->hash);

    if (mpbd_yaml_load(&L.y, e->text, len, "an experiment file holds one")
        != 0)
        goto fail;
    have_doc = 1;

    yaml_node_t *root = yaml_document_get_root_node(&L.y.doc);
    if (root == NULL || root->type != YAML_MAPPING_NODE) {
        fail_at(&L, root, "expected a mapping with experiment, robot, scenes "
                "and planners");
        goto fail;
    }
    if (mpbd_yaml_no_repeated_keys(&L.y) != 0 ||
        only_keys(&L, root, top_keys) != 0 || load_settings(&L, e, root) != 0 ||
        mpbd_load_scenes(&L, e, root) != 0 ||
        mpbd_load_planners(&L, e, root) != 0)
        goto fail;

    yaml_document_delete(&L.y.doc);
    mpb_srdf_close(L.srdf);
    free(L.dir);
    return e;
fail:
    if (have_doc)
        yaml_document_delete(&L.y.doc);
    mpb_srdf_close(L.srdf);
    free(L.dir);
    mpbd_experiment_free(e);
    return NULL;
}

void mpbd_experiment_free(mpbd_experiment *e)
{
    if (e == NULL)
        return;
    for (int i = 0; i < e->num_scenes; i++) {
        mpbd_scene *s = &e->scenes[i];
        free(s->name);
        free(s->robot_format);
        free(s->robot);
        free(s->scene_format);
        free(s->scene);
        free(s->scene_file);
        free(s->problem_set);
        mpb_world_close(s->world);
        free(s->seen_format);
        free(s->seen);
        free(s->seen_how);
        mpb_world_close(s->seen_world);
    }
    for (int i = 0; i < e->num_queries; i++) {
        free(e->queries[i].name);
        free(e->queries[i].start);
        free(e->queries[i].goal);
        free(e->queries[i].goal_link);
        free(e->queries[i].held);
        free(e->queries[i].moveit_group);
    }
    for (int i = 0; i < e->num_configs; i++) {
        mpbd_config *c = &e->configs[i];
        free(c->name);
        free(c->planner);
        free(c->algorithm);
        for (int p = 0; p < c->num_params; p++) {
            free(c->params[p].key);
            free(c->params[p].value);
        }
        free(c->params);
        free(c->params_text);
        free(c->approach);
    }
    for (int j = 0; j < e->num_joints && e->joint_names; j++)
        free(e->joint_names[j]);
    free(e->joint_names);
    for (int j = 0; j < e->num_held; j++)
        free(e->held_names[j]);
    free(e->held_names);
    free(e->held_default);
    for (int j = 0; j < e->num_group; j++)
        free(e->group[j]);
    free(e->group);
    free(e->wraps);
    free(e->robot_file);
    free(e->srdf_file);
    free(e->srdf_warning);
    free(e->acm_skipped_at);
    free(e->orientation_identity_at);
    free(e->group_name);
    free(e->scenes);
    free(e->queries);
    free(e->configs);
    free(e->name);
    free(e->file);
    free(e->text);
    free(e);
}

/* splitmix64: a well-mixed 64-bit function of the run's place. */
static uint64_t mix(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

int64_t mpbd_run_seed(const mpbd_experiment *e, int config, int query,
                      int repetition)
{
    uint64_t h = mix(e->seed);
    h = mix(h ^ (uint64_t)config);
    h = mix(h ^ (uint64_t)query);
    h = mix(h ^ (uint64_t)repetition);
    /* Keep it positive and within 31 bits: every planner's RNG takes it. */
    return (int64_t)(h & 0x7fffffff);
}

int mpbd_experiment_acm_note(const mpbd_experiment *e, char *buf, size_t len)
{
    if (e->num_scenes < 1 || e->srdf_file != NULL ||
        strcmp(e->scenes[0].robot_format, "urdf") != 0)
        return 0;
    mpb_world *w = e->scenes[0].world;
    int n = mpb_world_num_allowed_pairs(w), adjacent = 0, dflt = 0, always = 0;
    int never = 0;
    for (int i = 0; i < n; i++) {
        mpb_world_acm_pair p;
        if (mpb_world_allowed_pair(w, i, &p) != MPB_OK)
            continue;
        adjacent += strcmp(p.reason, "Adjacent") == 0;
        dflt += strcmp(p.reason, "Default") == 0;
        always += strcmp(p.reason, "Always") == 0;
        never += strcmp(p.reason, "Never") == 0;
    }
    char joints[1024] = "";
    size_t used = 0;
    for (int j = 0; j < e->num_joints && used < sizeof joints; j++)
        used += (size_t)snprintf(joints + used, sizeof joints - used, "%s%s",
                                 j ? "," : "", e->joint_names[j]);
    snprintf(buf, len, "robot has no srdf: self-collision matrix generated "
             "as MoveIt's setup assistant does, %d pairs allowed (%d adjacent, "
             "%d in collision at the default state, %d nearly always, %d "
             "never in %d random states); review it with 'mpb srdf %s -j %s "
             "-o robot.srdf' and give the file as the robot's srdf", n,
             adjacent, dflt, always, never, MPB_WORLD_ACM_SAMPLES,
             e->robot_file ? e->robot_file : "ROBOT.urdf", joints);
    return 1;
}

int mpbd_experiment_scene_acm_note(const mpbd_experiment *e, char *buf,
                                   size_t len)
{
    if (e->acm_skipped == 0)
        return 0;
    snprintf(buf, len, "%d allowed_collision_matrix pairs in %d MoveIt "
             "scene%s name links the robot lacks (%s) and are skipped, as "
             "MoveIt does; the first at %s", e->acm_skipped,
             e->acm_skipped_scenes, e->acm_skipped_scenes == 1 ? "" : "s",
             e->acm_skipped_names, e->acm_skipped_at ? e->acm_skipped_at : "?");
    return 1;
}

int mpbd_experiment_orientation_note(const mpbd_experiment *e, char *buf,
                                     size_t len)
{
    if (e->orientation_identity == 0)
        return 0;
    snprintf(buf, len, "%d MoveIt orientation constraint%s not a unit "
             "quaternion (norm off 1 by more than 1e-3): identity assumed "
             "instead, as MoveIt does; the first at %s",
             e->orientation_identity,
             e->orientation_identity == 1 ? " is" : "s are",
             e->orientation_identity_at ? e->orientation_identity_at : "?");
    return 1;
}

int mpbd_experiment_moveit_note(const mpbd_experiment *e, char *buf,
                                size_t len)
{
    int moveit = 0, other_time = 0;
    double most = 0;
    for (int i = 0; i < e->num_queries; i++) {
        const mpbd_query *q = &e->queries[i];
        if (q->moveit_group == NULL && q->planning_time == 0)
            continue;
        moveit++;
        if (q->planning_time > 0 && q->planning_time != e->time_limit) {
            other_time++;
            most = q->planning_time > most ? q->planning_time : most;
        }
    }
    if (moveit == 0 || (e->held_clamped == 0 && e->held_ignored == 0 &&
                        e->held_unknown == 0 && e->goal_clamped == 0 &&
                        e->start_clamped == 0 &&
                        other_time == 0))
        return 0;
    char unknown[400] = "", goals[160] = "";
    if (e->goal_clamped > 0 || e->start_clamped > 0)
        snprintf(goals, sizeof goals, ", %d start values within %g of a "
                 "limit and %d goal values within their tolerance of one "
                 "moved onto it", e->start_clamped, MPBD_START_BOUNDS_ERROR,
                 e->goal_clamped);
    if (e->held_unknown > 0)
        snprintf(unknown, sizeof unknown, ", %d of joints the robot lacks "
                 "ignored (%s)", e->held_unknown, e->held_unknown_names);
    snprintf(buf, len, "%d MoveIt queries: %d joint values moved into their "
             "limits and %d of fixed joints ignored%s%s (clamp_joint_values); "
             "%d ask for an allowed_planning_time other than the time_limit "
             "(up to %g s), which rules (%g s)", moveit, e->held_clamped,
             e->held_ignored, unknown, goals, other_time, most,
             e->time_limit);
    return 1;
}

