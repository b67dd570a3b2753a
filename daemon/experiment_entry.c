/*
 * experiment_entry.c - what a scene entry of either kind (experiment_scenes.c,
 * experiment_moveit.c) shares: its `set:`, its start and goal states
 * checked against the robot, the joints its queries hold outside the
 * planning group, and a query's goal as planners and the verifier read it.
 */
#include <stdlib.h>
#include <string.h>

#include "experiment_load.h"

/* A start or goal must be a state the robot can be in: within its joint
 * limits and free of collision. Otherwise no planner can succeed. */
int mpbd_check_state(mpbd_loader *L, const mpbd_experiment *e, int scene,
                     const double *q, const char *what, yaml_node_t *where)
{
    mpb_world *w = e->scenes[scene].world;
    for (int j = 0; j < e->num_joints; j++) {
        double lo, hi;
        mpb_world_joint_limits(w, j, &lo, &hi);
        if (!mpb_world_joint_is_continuous(w, j) && (q[j] < lo || q[j] > hi))
            return fail_at(L, where, "%s: joint %s = %.10g is outside its "
                           "limits [%.10g, %.10g]", what, e->joint_names[j],
                           q[j], lo, hi);
    }
    char contact[200];
    if (mpb_world_contact(w, q, contact, sizeof contact) != 0)
        return fail_at(L, where, "%s is in collision in scene '%s'%s%s", what,
                       e->scenes[scene].name, contact[0] ? ": " : "", contact);
    return 0;
}

/* ---- joints held outside the group ---------------------------------- */

/* Give q a value for every held joint known so far: the robot's, or the
 * world's default for a joint only other queries name. */
int mpbd_held_fill(mpbd_experiment *e, mpbd_query *q)
{
    if (q->num_held_set == e->num_held)
        return 0;
    double *v = realloc(q->held, ((size_t)e->num_held + 1) * sizeof *v);
    if (v == NULL)
        return -1;
    for (int i = q->num_held_set; i < e->num_held; i++)
        v[i] = e->held_default[i];
    q->held = v;
    q->num_held_set = e->num_held;
    return 0;
}

/*
 * The index of the held joint `name` in e->held_names, added (held at the
 * world's default, 0 moved into its limits) if new; -1 with one line at
 * `at` for a joint that cannot be held.
 */
static int held_index(mpbd_loader *L, mpbd_experiment *e, mpb_world *w,
                      const char *name, yaml_node_t *at)
{
    for (int i = 0; i < e->num_held; i++)
        if (strcmp(e->held_names[i], name) == 0)
            return i;
    double lo, hi;
    int rc = mpb_world_held(w, name, NULL, &lo, &hi);
    if (rc == MPB_EUNSUPPORTED)
        return fail_at(L, at, "joint '%s': a %s robot holds no joints "
                       "outside its group", name, e->scenes[0].robot_format);
    if (rc == MPB_ENOTFOUND)
        return fail_at(L, at, "joint '%s' is not a joint of the robot", name);
    for (int j = 0; rc != MPB_OK && j < e->num_joints; j++)
        if (strcmp(e->joint_names[j], name) == 0)
            return fail_at(L, at, "joint '%s' is in the planning group: its "
                           "value belongs in the start, not held", name);
    if (rc != MPB_OK)
        return fail_at(L, at, "joint '%s' cannot hold a value (a fixed, "
                       "floating or planar joint)", name);
    char **names = realloc(e->held_names,
                           ((size_t)e->num_held + 1) * sizeof *names);
    if (names != NULL)
        e->held_names = names;
    double *dflt = realloc(e->held_default,
                           ((size_t)e->num_held + 1) * sizeof *dflt);
    if (dflt != NULL)
        e->held_default = dflt;
    if (names == NULL || dflt == NULL ||
        (names[e->num_held] = strdup(name)) == NULL)
        return fail_at(L, at, "out of memory");
    dflt[e->num_held] = 0.0 < lo ? lo : 0.0 > hi ? hi : 0.0;
    return e->num_held++;
}

/*
 * Hold joint `name` at v in the world w, into *out (the query's or the
 * robot's value). With clamp, a value outside the joint's limits is moved
 * to the nearer one and counted in *clamped; without, it is refused at
 * `val`. `key` is where the name is written, for an unknown joint.
 */
int mpbd_hold_one(mpbd_loader *L, mpbd_experiment *e, mpb_world *w,
                  const char *name, double v, yaml_node_t *key,
                  yaml_node_t *val, int clamp, int *clamped, int *index)
{
    char why[256];
    double lo, hi;
    int i = held_index(L, e, w, name, key);
    if (i < 0)
        return -1;
    if (clamp && mpb_world_held(w, name, NULL, &lo, &hi) == MPB_OK &&
        (v < lo || v > hi)) {
        v = v < lo ? lo : hi;
        (*clamped)++;
    }
    const char *names[1] = {name};
    if (mpb_world_hold(w, names, &v, 1, why, sizeof why) != MPB_OK)
        return fail_at(L, val, "%s", why);
    *index = i;
    return 0;
}

/* `joint_values: {name: value, ...}`: the robot's held joints, or a
 * query's own (into q). */
int mpbd_load_joint_values(mpbd_loader *L, mpbd_experiment *e, mpb_world *w,
                           yaml_node_t *m, mpbd_query *q)
{
    if (m == NULL)
        return 0;
    if (m->type != YAML_MAPPING_NODE)
        return fail_at(L, m, "joint_values must be a mapping of joint: value");
    for (yaml_node_pair_t *p = m->data.mapping.pairs.start;
         p < m->data.mapping.pairs.top; p++) {
        yaml_node_t *k = node(L, p->key), *vn = node(L, p->value);
        double v;
        int i;
        if (scalar(k) == NULL || scalar(k)[0] == '\0')
            return fail_at(L, k, "a joint must be a name");
        if (parse_double(L, vn, "a joint value", &v) != 0 ||
            mpbd_hold_one(L, e, w, scalar(k), v, k, vn, 0, NULL, &i) != 0)
            return -1;
        if (q == NULL) {
            e->held_default[i] = v;
        } else {
            if (mpbd_held_fill(e, q) != 0)
                return fail_at(L, m, "out of memory");
            q->held[i] = v;
        }
    }
    return 0;
}

int mpbd_query_hold(const mpbd_experiment *e, const mpbd_query *q)
{
    return mpbd_query_hold_in(e, q, e->scenes[q->scene].world);
}

int mpbd_query_hold_in(const mpbd_experiment *e, const mpbd_query *q,
                       mpb_world *w)
{
    return mpb_world_hold(w,
                          (const char *const *)e->held_names, q->held,
                          q->num_held_set < e->num_held ? q->num_held_set
                                                        : e->num_held,
                          NULL, 0);
}

int mpbd_load_set(mpbd_loader *L, yaml_node_t *m, char **out)
{
    yaml_node_t *n = get(L, m, "set");
    *out = NULL;
    if (n == NULL)
        return 0;
    const char *v = scalar(n);
    size_t len = v != NULL ? strlen(v) : 0;
    int control = 0;
    for (size_t i = 0; i < len; i++)
        control |= (unsigned char)v[i] < 0x20 || v[i] == 0x7f;
    if (v == NULL || len == 0 || len > MPBD_SET_MAX || control)
        return fail_at(L, n, "set must be a problem set's name: a "
                       "non-empty string of at most %d bytes, no control "
                       "characters", MPBD_SET_MAX);
    return (*out = dup_str(L, n, v)) != NULL ? 0 : -1;
}

/* After the first scene's world opens: the robot's held joint values,
 * which need a world to check them against. */
int mpbd_first_world(mpbd_loader *L, mpbd_experiment *e, mpbd_scene *sc)
{
    if (e->num_scenes != 1)
        return 0;
    return mpbd_load_joint_values(L, e, sc->world, get(L, L->robot, "joint_values"),
                             NULL);
}

void mpbd_query_region(const mpbd_query *q, double region[12])
{
    for (int k = 0; k < 3; k++) {
        region[k] = q->position[k];
        region[3 + k] = q->position_tolerance[k];
        region[6 + k] = q->rpy[k];
        region[9 + k] = q->rpy_tolerance[k];
    }
}

mpb_goal mpbd_query_goal(const mpbd_query *q)
{
    double region[12];
    mpbd_query_region(q, region);
    return mpb_query_goal(q->goal_kind, q->goal, q->tolerance, q->goal_link,
                          region);
}

