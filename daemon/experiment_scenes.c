/*
 * experiment_scenes.c - an experiment's `scenes:`: each entry a scene of
 * its own with its queries (starts, goals as joint values or regions for
 * a link), or a MoveIt one (experiment_moveit.c). What both kinds share
 * is experiment_entry.c's.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "experiment_load.h"
#include "core/mathconst.h"


/* A list of exactly n numbers. */
static double *parse_vector(mpbd_loader *L, yaml_node_t *n, const char *what,
                            int len)
{
    double *v;
    int count;
    if (n == NULL || n->type != YAML_SEQUENCE_NODE)
        return fail_at(L, n, "%s must be a list of %d numbers", what, len), NULL;
    count = (int)(n->data.sequence.items.top - n->data.sequence.items.start);
    if (count != len)
        return fail_at(L, n, "%s has %d values, the robot has %d joints", what,
                       count, len), NULL;
    v = calloc((size_t)len, sizeof *v);
    if (v == NULL)
        return fail_at(L, n, "out of memory"), NULL;
    for (int i = 0; i < len; i++)
        if (parse_double(L, node(L, n->data.sequence.items.start[i]), what,
                         &v[i]) != 0) {
            free(v);
            return NULL;
        }
    return v;
}

/*
 * A start or a joint goal: a list of one number per joint, or, when the
 * group is a group of the SRDF, the name of one of its group states
 * ("start: ready"), whose values it takes. n is the node, or NULL when
 * absent (the fault then at parent).
 */
static double *parse_state(mpbd_loader *L, const mpbd_experiment *e,
                           yaml_node_t *n, yaml_node_t *parent,
                           const char *what)
{
    if (n == NULL || n->type != YAML_SCALAR_NODE || L->srdf == NULL)
        return parse_vector(L, n ? n : parent, what, e->num_joints);
    char why[512];
    double *v = calloc((size_t)e->num_joints + 1, sizeof *v);
    if (v == NULL)
        return fail_at(L, n, "out of memory"), NULL;
    if (mpb_srdf_state_values(L->srdf, L->group, scalar(n), v, why,
                              sizeof why) != MPB_OK) {
        free(v);
        return fail_at(L, n, "%s: %s", what, why), NULL;
    }
    return v;
}

/*
 * Three numbers: a list of 3, or, where one_for_all, a single number for
 * all three ("position_tolerance: 0.01").
 */
static int parse_triple(mpbd_loader *L, yaml_node_t *m, const char *key,
                        int one_for_all, double out[3])
{
    yaml_node_t *n = get(L, m, key);
    if (n == NULL)
        return fail_at(L, m, "goal: missing '%s'", key);
    if (one_for_all && n->type == YAML_SCALAR_NODE) {
        if (parse_double(L, n, key, &out[0]) != 0)
            return -1;
        out[1] = out[2] = out[0];
        return 0;
    }
    if (n->type != YAML_SEQUENCE_NODE || count_items(n) != 3)
        return fail_at(L, n, "%s must be a list of 3 numbers%s", key,
                       one_for_all ? " (or one number for all three)" : "");
    for (int i = 0; i < 3; i++)
        if (parse_double(L, node(L, n->data.sequence.items.start[i]), key,
                         &out[i]) != 0)
            return -1;
    return 0;
}

static int parse_tolerance(mpbd_loader *L, yaml_node_t *m, const char *key,
                           double out[3])
{
    if (parse_triple(L, m, key, 1, out) != 0)
        return -1;
    for (int i = 0; i < 3; i++)
        if (out[i] < 0)
            return fail_at(L, get(L, m, key), "%s must not be negative (%g)",
                           key, out[i]);
    return 0;
}

/*
 * A pose-region goal: `goal: {link, position, position_tolerance, rpy,
 * rpy_tolerance}`. Without rpy the orientation is free. The link must be
 * one of the robot's, which the world checks.
 */
static int load_region_goal(mpbd_loader *L, const mpbd_experiment *e, int scene,
                            mpbd_query *q, yaml_node_t *m)
{
    static const char *const keys[] = {"link", "position",
                                       "position_tolerance", "rpy",
                                       "rpy_tolerance", NULL};
    if (only_keys(L, m, keys) != 0 ||
        (q->goal_link = need_string(L, m, "link")) == NULL ||
        parse_triple(L, m, "position", 0, q->position) != 0 ||
        parse_tolerance(L, m, "position_tolerance", q->position_tolerance) != 0)
        return -1;
    q->goal_kind = MPB_GOAL_POSE_REGION;
    if (get(L, m, "rpy") == NULL) {
        if (get(L, m, "rpy_tolerance") != NULL)
            return fail_at(L, get(L, m, "rpy_tolerance"),
                           "rpy_tolerance without rpy");
        for (int i = 0; i < 3; i++)
            q->rpy_tolerance[i] = M_PI;
    } else if (parse_triple(L, m, "rpy", 0, q->rpy) != 0 ||
               parse_tolerance(L, m, "rpy_tolerance", q->rpy_tolerance) != 0) {
        return -1;
    }
    /* Asking the world whether the start is inside checks the link and the
     * numbers, and whether this world can check regions at all. */
    char why[256];
    mpb_goal g = mpbd_query_goal(q);
    int in = mpb_world_goal_contains(e->scenes[scene].world, &g, q->start, why,
                                     sizeof why);
    if (in == MPB_EUNSUPPORTED)
        return fail_at(L, m, "%s (a region goal needs a urdf robot)", why);
    if (in < 0)
        return fail_at(L, get(L, m, "link"), "%s", why);
    return 0;
}

/* `goal:` is a configuration (a list) or a region for a link (a mapping). */
static int load_goal(mpbd_loader *L, mpbd_experiment *e, int scene,
                     mpbd_query *q,
                     yaml_node_t *query)
{
    yaml_node_t *n = get(L, query, "goal");
    if (n != NULL && n->type == YAML_MAPPING_NODE)
        return load_region_goal(L, e, scene, q, n);
    q->goal_kind = MPB_GOAL_JOINTS;
    if ((q->goal = parse_state(L, e, n, query, "goal")) == NULL)
        return -1;
    return mpbd_check_state(L, e, scene, q->goal, "goal", n);
}

static int load_queries(mpbd_loader *L, mpbd_experiment *e, int scene,
                        yaml_node_t *scene_map)
{
    static const char *const keys[] = {"name", "start", "goal", "tolerance",
                                       "joint_values", NULL};
    yaml_node_t *list = get(L, scene_map, "queries");
    if (list == NULL || list->type != YAML_SEQUENCE_NODE ||
        list->data.sequence.items.top == list->data.sequence.items.start)
        return fail_at(L, list ? list : scene_map,
                       "scene '%s' needs a non-empty list 'queries'",
                       e->scenes[scene].name);
    for (yaml_node_item_t *it = list->data.sequence.items.start;
         it < list->data.sequence.items.top; it++) {
        yaml_node_t *m = node(L, *it), *n;
        mpbd_query *q = &e->queries[e->num_queries];
        if (m->type != YAML_MAPPING_NODE)
            return fail_at(L, m,
                           "a query must be a mapping of name, start, goal");
        if (only_keys(L, m, keys) != 0)
            return -1;
        e->num_queries++;
        q->scene = scene;
        q->tolerance = 1e-3;
        if ((q->name = need_string(L, m, "name")) == NULL)
            return -1;
        for (mpbd_query *o = e->queries; o < q; o++)
            if (o->scene == scene && strcmp(o->name, q->name) == 0)
                return fail_at(L, m, "query '%s' appears twice in scene '%s'",
                               q->name, e->scenes[scene].name);
        if (mpbd_held_fill(e, q) != 0)
            return fail_at(L, m, "out of memory");
        if (mpbd_load_joint_values(L, e, e->scenes[scene].world,
                              get(L, m, "joint_values"), q) != 0 ||
            mpbd_held_fill(e, q) != 0)
            return -1;
        if (mpbd_query_hold(e, q) != MPB_OK)
            return fail_at(L, m, "query '%s': its held joint values do not "
                           "fit the robot", q->name);
        if ((q->start = parse_state(L, e, get(L, m, "start"), m,
                                    "start")) == NULL)
            return -1;
        if (mpbd_check_state(L, e, scene, q->start, "start",
                             get(L, m, "start")) != 0 ||
            load_goal(L, e, scene, q, m) != 0)
            return -1;
        if ((n = get(L, m, "tolerance")) != NULL &&
            (parse_double(L, n, "tolerance", &q->tolerance) != 0 ||
             (q->tolerance <= 0 && fail_at(L, n,
                                           "tolerance must be positive"))))
            return -1;
    }
    return 0;
}

int mpbd_load_scenes(mpbd_loader *L, mpbd_experiment *e, yaml_node_t *root)
{
    char *robot_format = NULL, *robot = NULL;
    yaml_node_t *list = need(L, root, "scenes", YAML_SEQUENCE_NODE,
                             "a list of scenes");
    int rc = -1;
    size_t total_queries = 0;

    if (list == NULL)
        return -1;
    if ((L->robot = need(L, root, "robot", YAML_MAPPING_NODE,
                         "a mapping of format and file or text")) == NULL ||
        mpbd_load_model(L, L->robot, "robot", &robot_format, &robot,
                        &e->robot_file) != 0 ||
        mpbd_load_srdf(L, e, &robot) != 0 ||
        mpbd_load_group(L, e, get(L, L->robot, "joints")) != 0)
        goto done;
    e->num_scenes = 0;
    size_t total_scenes = 0;
    for (yaml_node_item_t *it = list->data.sequence.items.start;
         it < list->data.sequence.items.top; it++) {
        yaml_node_t *m = node(L, *it);
        int ns = 1, nq = (int)count_items(get(L, m, "queries"));
        if (mpbd_is_moveit_entry(L, m) &&
            mpbd_moveit_entry_size(L, m, &ns, &nq) != 0)
            goto done;
        total_scenes += (size_t)ns;
        total_queries += (size_t)nq;
    }
    e->scenes = calloc(total_scenes + 1, sizeof *e->scenes);
    e->queries = calloc(total_queries + 1, sizeof *e->queries);
    if (e->scenes == NULL || e->queries == NULL) {
        fail_at(L, list, "out of memory");
        goto done;
    }
    if (count_items(list) == 0) {
        fail_at(L, list, "'scenes' must not be empty");
        goto done;
    }
    for (yaml_node_item_t *it = list->data.sequence.items.start;
         it < list->data.sequence.items.top; it++) {
        yaml_node_t *m = node(L, *it);
        mpbd_scene *sc = &e->scenes[e->num_scenes];
        if (m->type != YAML_MAPPING_NODE) {
            fail_at(L, m, "a scene must be a mapping of name, format, file "
                    "or text, queries");
            goto done;
        }
        if (mpbd_is_moveit_entry(L, m)) {
            if (mpbd_load_moveit_entry(L, e, m, robot_format, robot) != 0)
                goto done;
            continue;
        }
        e->num_scenes++;
        if (get(L, m, "joints") != NULL) {
            fail_at(L, get(L, m, "joints"), "joints belong to the robot, not "
                    "to a scene");
            goto done;
        }
        if ((sc->name = need_string(L, m, "name")) == NULL ||
            mpbd_load_model(L, m, "scene", &sc->scene_format, &sc->scene,
                            &sc->scene_file) != 0 ||
            mpbd_load_set(L, m, &sc->problem_set) != 0)
            goto done;
        for (mpbd_scene *o = e->scenes; o < sc; o++)
            if (strcmp(o->name, sc->name) == 0) {
                fail_at(L, m, "scene '%s' appears twice", sc->name);
                goto done;
            }
        if ((sc->robot_format = strdup(robot_format)) == NULL ||
            (sc->robot = strdup(robot)) == NULL) {
            fail_at(L, m, "out of memory");
            goto done;
        }
        mpb_hash_hex(sc->robot, strlen(sc->robot), sc->robot_hash);
        mpb_hash_hex(sc->scene, strlen(sc->scene), sc->scene_hash);
        if (mpbd_open_world(L, e, sc, m) != 0 ||
            mpbd_first_world(L, e, sc) != 0 ||
            mpbd_load_seen(L, e, sc, m, 1) != 0 ||
            load_queries(L, e, e->num_scenes - 1, m) != 0)
            goto done;
    }
    /* Every query holds every joint some query names. */
    for (int i = 0; i < e->num_queries; i++)
        if (mpbd_held_fill(e, &e->queries[i]) != 0) {
            fail_at(L, list, "out of memory");
            goto done;
        }
    rc = 0;
done:
    mpb_robot_close(L->model);
    L->model = NULL;
    free(robot_format);
    free(robot);
    return rc;
}
