/*
 * experiment_moveit.c - an experiment's MoveIt entries: a problem set (a
 * folder of sceneNNNN.yaml and requestNNNN.yaml, as MotionBenchMaker
 * writes them) or one scene file with its requests, made into scenes and
 * queries (docs/moveit-problems.md).
 */
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <dirent.h>
#include <sys/stat.h>

#include "experiment_load.h"

/* Errors with no node here go to this place of a MoveIt file. */
static void at_place(mpbd_loader *L, const char *path, mpbd_mark m)
{
    L->y.place_path = path;
    L->y.place = m;
}

/* The robot as robot.h reads it, for link names; NULL for planar. */
static mpb_robot *robot_model(mpbd_loader *L, const mpbd_experiment *e,
                              const char *robot_format, const char *robot)
{
    if (L->model == NULL && strcmp(robot_format, "urdf") == 0 &&
        e->num_group > 0)
        mpb_robot_open_urdf_joints(robot, (const char *const *)e->group,
                                   e->num_group, &L->model, NULL, 0);
    return L->model;
}

/* Add name to the list "a, b, c" in names (cap bytes), once, as many as
 * fit, then "...". */
static void note_name(char *names, size_t cap, const char *name)
{
    char esc[128];
    size_t used = strlen(names);
    mpb_escape(name, esc, sizeof esc);
    for (const char *p = names; *p;) {
        size_t k = strcspn(p, ",");
        if (k == strlen(esc) && strncmp(p, esc, k) == 0)
            return;
        p += k + (p[k] == ',' ? 2 : 0);
    }
    if (used >= 3 && strcmp(names + used - 3, "...") == 0)
        return;
    if (used + strlen(esc) + 8 < cap)
        snprintf(names + used, cap - used, "%s%s", used ? ", " : "", esc);
    else
        snprintf(names + used, cap - used, ", ...");
}

/* Is name the id of an object of the moveit-scene text (its "* id"
 * lines)? */
static int scene_has_object(const char *text, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = text; p; p = strchr(p, '\n'), p = p ? p + 1 : NULL)
        if (p[0] == '*' && p[1] == ' ' && strncmp(p + 2, name, n) == 0 &&
            (p[2 + n] == '\n' || p[2 + n] == '\0'))
            return 1;
    return 0;
}

/* A scene's allowed pair naming a link the robot lacks: skipped, counted
 * for the warning mpbd_experiment_scene_acm_note() words. */
static int skip_scene_pair(mpbd_loader *L, mpbd_experiment *e,
                           const char *scene_path, const mpbd_moveit_scene *ms,
                           int i, int *counted)
{
    const char *name = ms->pairs[i];
    e->acm_skipped++;
    if (!*counted) {
        e->acm_skipped_scenes++;
        *counted = 1;
    }
    if (e->acm_skipped_at == NULL) {
        char at[4200];
        snprintf(at, sizeof at, "%s:%d:%d", scene_path, ms->pair_at[i].line,
                 ms->pair_at[i].column);
        if ((e->acm_skipped_at = strdup(at)) == NULL)
            return fail_at(L, NULL, "out of memory");
    }
    note_name(e->acm_skipped_names, sizeof e->acm_skipped_names, name);
    return 0;
}

/*
 * The robot text with a scene's allowed pairs added as SRDF
 * <disable_collisions reason="Scene"/> elements: inside the robot's SRDF
 * (before its closing tag), or as an SRDF of their own when it has none.
 * A pair naming a link the robot lacks is skipped, as MoveIt does (its
 * matrix takes any names; MotionBenchMaker's Fetch and UR5 scenes name
 * links of their own robot models), and counted; a name that is an
 * object of the scene is refused (MoveIt would allow that contact, which
 * mpbench does not read).
 */
static char *robot_with_pairs(mpbd_loader *L, mpbd_experiment *e,
                              const char *robot_format, const char *robot,
                              const char *scene_path, const char *scene_text,
                              const mpbd_moveit_scene *ms)
{
    if (ms->num_pairs == 0)
        return strdup(robot);
    mpb_robot *model = robot_model(L, e, robot_format, robot);
    unsigned char *keep = calloc((size_t)ms->num_pairs + 1, 1);
    if (keep == NULL)
        return NULL;
    int counted = 0;
    for (int k = 0; k < ms->num_pairs; k++) {
        keep[k] = 1;
        for (int i = 2 * k; i < 2 * k + 2 && keep[k]; i++) {
            if (model != NULL && mpb_robot_link_index(model, ms->pairs[i]) >= 0)
                continue;
            char esc[256];
            at_place(L, scene_path, ms->pair_at[i]);
            if (model == NULL || scene_has_object(scene_text, ms->pairs[i])) {
                fail_at(L, NULL, "allowed_collision_matrix: '%s' is %s",
                        mpb_escape(ms->pairs[i], esc, sizeof esc),
                        model == NULL ? "not a link of the robot"
                                      : "an object of the scene; allowed "
                                        "contacts with objects are not read");
                free(keep);
                return NULL;
            }
            if (skip_scene_pair(L, e, scene_path, ms, i, &counted) != 0) {
                free(keep);
                return NULL;
            }
            keep[k] = 0;
        }
    }
    L->y.place_path = NULL;
    size_t extra = 64;
    for (int i = 0; i < 2 * ms->num_pairs; i++)
        extra += strlen(ms->pairs[i]) + 40;
    size_t len = strlen(robot);
    char *out = malloc(len + extra + 64);
    if (out == NULL) {
        free(keep);
        return NULL;
    }
    /* The SRDF's closing tag is the text's last "</robot" when the
     * experiment has an SRDF. */
    const char *close = NULL;
    if (e->srdf_file != NULL)
        for (const char *p = strstr(robot, "</robot"); p;
             p = strstr(p + 1, "</robot"))
            close = p;
    size_t head = close ? (size_t)(close - robot) : len;
    memcpy(out, robot, head);
    char *w = out + head;
    if (close == NULL) {
        if (head > 0 && out[head - 1] != '\n')
            *w++ = '\n';
        w += sprintf(w, "<robot name=\"scene\">\n");
    }
    for (int i = 0; i < ms->num_pairs; i++)
        if (keep[i])
            w += sprintf(w, "<disable_collisions link1=\"%s\" link2=\"%s\" "
                         "reason=\"Scene\"/>\n", ms->pairs[2 * i],
                         ms->pairs[2 * i + 1]);
    free(keep);
    if (close == NULL)
        w += sprintf(w, "</robot>\n");
    strcpy(w, robot + head);
    return out;
}

/*
 * Joint values of a MoveIt robot state: group joints into q (where set),
 * the others held by the query (clamped into their limits with clamp).
 */
static int moveit_state(mpbd_loader *L, mpbd_experiment *e, mpbd_query *q,
                        const char *path, const mpbd_moveit_joints *j,
                        double *group_q, unsigned char *set, int clamp)
{
    mpb_world *w = e->scenes[q->scene].world;
    for (int i = 0; i < j->n; i++) {
        int g = -1, index;
        for (int k = 0; k < e->num_joints && g < 0; k++)
            if (strcmp(e->joint_names[k], j->names[i]) == 0)
                g = k;
        at_place(L, path, j->at[i]);
        if (g >= 0) {
            group_q[g] = j->values[i];
            set[g] = 1;
            continue;
        }
        /* A joint the URDF fixes (this Panda's fingers) has no value to
         * hold: leniently skipped, as a model without that variable
         * would. */
        int known = mpb_world_held(w, j->names[i], NULL, NULL, NULL);
        if (clamp && known == MPB_EINVAL) {
            e->held_ignored++;
            continue;
        }
        /* A joint the URDF lacks (MotionBenchMaker's Fetch states give
         * its wheels and bellows, which VAMP's Fetch leaves out): skipped
         * with clamp too, counted and named. MoveIt refuses such a state
         * for a model without the joint; without clamp, so does mpbench. */
        if (clamp && known == MPB_ENOTFOUND) {
            note_name(e->held_unknown_names, sizeof e->held_unknown_names,
                      j->names[i]);
            e->held_unknown++;
            continue;
        }
        if (mpbd_hold_one(L, e, w, j->names[i], j->values[i], NULL, NULL, clamp,
                          &e->held_clamped, &index) != 0 || mpbd_held_fill(e,
                                                                           q) != 0)
            return -1;
        double v;
        mpb_world_held(w, j->names[i], &v, NULL, NULL);
        q->held[index] = v;
    }
    return 0;
}

/* One request of a MoveIt scene: a query. */
static int moveit_query(mpbd_loader *L, mpbd_experiment *e, int scene,
                        const mpbd_moveit_scene *ms, const char *scene_path,
                        const char *req_path,
                        const char *name, int clamp, double tolerance)
{
    mpbd_moveit_request r;
    mpbd_query *q = &e->queries[e->num_queries];
    if (mpbd_moveit_request_read(req_path, &r, L->y.err,
                                 L->y.errlen) != MPB_OK) {
        L->y.failed = 1;
        return -1;
    }
    int rc = -1, nj = e->num_joints;
    unsigned char *set = calloc((size_t)nj + 1, 1);
    e->num_queries++;
    q->scene = scene;
    q->tolerance = tolerance;
    q->planning_time = r.allowed_planning_time;
    q->name = strdup(name);
    q->start = calloc((size_t)nj + 1, sizeof *q->start);
    if (set == NULL || q->name == NULL || q->start == NULL ||
        mpbd_held_fill(e, q) != 0 ||
        (r.group_name && (q->moveit_group = strdup(r.group_name)) == NULL)) {
        fail_at(L, NULL, "out of memory");
        goto done;
    }
    /* A request for another group than the one planned would be solved
     * for the wrong joints; with joints: listed there is no name to
     * compare, and the joint names are checked below. */
    if (e->group_name && r.group_name &&
        strcmp(e->group_name, r.group_name) != 0) {
        at_place(L, req_path, r.group_at);
        fail_at(L, NULL, "group_name '%s' is not the experiment's group '%s'",
                r.group_name, e->group_name);
        goto done;
    }
    /* The scene's robot state, then the request's start on top of it, as
     * MoveIt reads a start state: a difference from the scene's. */
    if (moveit_state(L, e, q, scene_path, &ms->state, q->start, set,
                     clamp) != 0 ||
        moveit_state(L, e, q, req_path, &r.start, q->start, set, clamp) != 0)
        goto done;
    for (int j = 0; j < nj; j++)
        if (!set[j]) {
            at_place(L, req_path, r.start_at);
            fail_at(L, NULL, "start_state: no value for joint '%s' of the "
                    "group (nor in the scene's robot_state)",
                    e->joint_names[j]);
            goto done;
        }
    if (mpbd_query_hold(e, q) != MPB_OK) {
        fail_at(L, NULL, "query '%s': its held joint values do not fit the "
                "robot", name);
        goto done;
    }
    /* A start just outside a limit: with clamp moved onto it, as MoveIt's
     * FixStartStateBounds adapter does within its default 0.05. */
    for (int j = 0; clamp && j < nj; j++) {
        mpb_world *sw = e->scenes[scene].world;
        double lo, hi, v = q->start[j];
        mpb_world_joint_limits(sw, j, &lo, &hi);
        if (mpb_world_joint_is_continuous(sw, j) || (v >= lo && v <= hi) ||
            v < lo - MPBD_START_BOUNDS_ERROR || v > hi + MPBD_START_BOUNDS_ERROR)
            continue;
        q->start[j] = v < lo ? lo : hi;
        e->start_clamped++;
    }
    at_place(L, req_path, r.start_at);
    if (mpbd_check_state(L, e, scene, q->start, "start", NULL) != 0)
        goto done;
    q->goal_kind = r.goal_kind;
    if (r.orientation_identity && e->orientation_identity++ == 0) {
        char where[4200];
        snprintf(where, sizeof where, "%s:%d:%d", req_path,
                 r.orientation_at.line, r.orientation_at.column);
        if ((e->orientation_identity_at = strdup(where)) == NULL) {
            fail_at(L, NULL, "out of memory");
            goto done;
        }
    }
    if (r.goal_kind == MPB_GOAL_JOINTS) {
        double tol = INFINITY;
        q->goal = calloc((size_t)nj + 1, sizeof *q->goal);
        if (q->goal == NULL) {
            fail_at(L, NULL, "out of memory");
            goto done;
        }
        memset(set, 0, (size_t)nj);
        for (int i = 0; i < r.goal.n; i++) {
            int g = -1;
            for (int k = 0; k < nj && g < 0; k++)
                if (strcmp(e->joint_names[k], r.goal.names[i]) == 0)
                    g = k;
            at_place(L, req_path, r.goal.at[i]);
            if (g < 0) {
                double v;
                char esc[256];
                mpb_escape(r.goal.names[i], esc, sizeof esc);
                if (mpb_world_held(e->scenes[scene].world, r.goal.names[i],
                                   &v, NULL, NULL) == MPB_ENOTFOUND)
                    fail_at(L, NULL, "joint '%s' is not a joint of the robot",
                            esc);
                else
                    fail_at(L, NULL, "joint '%s' is outside the planning "
                            "group: a goal constrains the group's joints",
                            esc);
                goto done;
            }
            q->goal[g] = r.goal.values[i];
            set[g] = 1;
            double a = r.tolerance_above[i], b = r.tolerance_below[i];
            if (!isnan(a) && a < tol)
                tol = a;
            if (!isnan(b) && b < tol)
                tol = b;
        }
        for (int j = 0; j < nj; j++)
            if (!set[j]) {
                at_place(L, req_path, r.goal_at);
                fail_at(L, NULL, "goal_constraints: no joint constraint on "
                        "joint '%s' of the group", e->joint_names[j]);
                goto done;
            }
        /* One tolerance per query: the tightest the file gives, so that
         * every goal mpbench accepts is one MoveIt accepts too. */
        if (isfinite(tol))
            q->tolerance = tol > 0 ? tol : 1e-9;
        /* A goal just outside a joint's limits whose tolerance reaches
         * inside them (VAMP's Fetch makes wrist_roll_joint revolute at
         * +-3.14159; its problems ask for -3.1415926): MoveIt samples the
         * constraint within the limits, so with clamp the value moves
         * onto the limit and the tolerance shrinks by as much, keeping
         * the region within the file's. */
        mpb_world *gw = e->scenes[scene].world;
        double moved = 0;
        for (int j = 0; clamp && j < nj; j++) {
            double lo, hi, v = q->goal[j];
            mpb_world_joint_limits(gw, j, &lo, &hi);
            if (mpb_world_joint_is_continuous(gw, j) || (v >= lo && v <= hi))
                continue;
            double d = v < lo ? lo - v : v - hi;
            if (d >= q->tolerance)
                continue;       /* no part of the region is inside */
            q->goal[j] = v < lo ? lo : hi;
            moved = d > moved ? d : moved;
            e->goal_clamped++;
        }
        q->tolerance -= moved;
        at_place(L, req_path, r.goal_at);
        if (mpbd_check_state(L, e, scene, q->goal, "goal", NULL) != 0)
            goto done;
    } else {
        char why[256];
        q->goal_link = r.link;
        r.link = NULL;
        memcpy(q->position, r.position, sizeof q->position);
        memcpy(q->position_tolerance, r.position_tolerance,
               sizeof q->position_tolerance);
        memcpy(q->rpy, r.rpy, sizeof q->rpy);
        memcpy(q->rpy_tolerance, r.rpy_tolerance, sizeof q->rpy_tolerance);
        mpb_goal g = mpbd_query_goal(q);
        int in = mpb_world_goal_contains(e->scenes[scene].world, &g, q->start,
                                         why, sizeof why);
        at_place(L, req_path, r.link_at);
        if (in < 0) {
            fail_at(L, NULL, "%s", why);
            goto done;
        }
    }
    rc = 0;
done:
    L->y.place_path = NULL;
    free(set);
    mpbd_moveit_request_clear(&r);
    return rc;
}

/*
 * One MoveIt scene file with its requests: a scene of the experiment and
 * one query per request. The scene's robot text carries its allowed
 * pairs, so every world of its runs has the same matrix.
 */
static int moveit_scene(mpbd_loader *L, mpbd_experiment *e, yaml_node_t *entry,
                        const char *robot_format, const char *robot,
                        const char *name, const char *scene_path,
                        char *const *req_paths, char *const *qnames, int nreq,
                        int clamp, double tolerance)
{
    mpbd_moveit_scene ms;
    mpbd_scene *sc = &e->scenes[e->num_scenes];
    if (mpbd_moveit_scene_read(scene_path, name, &ms, L->y.err, L->y.errlen)
        != MPB_OK) {
        L->y.failed = 1;
        return -1;
    }
    e->num_scenes++;
    int rc = -1;
    for (mpbd_scene *o = e->scenes; o < sc; o++)
        if (strcmp(o->name, name) == 0) {
            fail_at(L, entry, "scene '%s' appears twice", name);
            goto done;
        }
    if (mpbd_load_set(L, entry, &sc->problem_set) != 0)
        goto done;
    sc->name = strdup(name);
    sc->scene_format = strdup("moveit-scene");
    sc->scene_file = strdup(scene_path);
    sc->robot_format = strdup(robot_format);
    sc->scene = ms.text;
    ms.text = NULL;
    if (!sc->name || !sc->scene_format || !sc->scene_file ||
        !sc->robot_format) {
        fail_at(L, entry, "out of memory");
        goto done;
    }
    if ((sc->robot = robot_with_pairs(L, e, robot_format, robot, scene_path,
                                      sc->scene, &ms)) == NULL) {
        if (!L->y.failed)
            fail_at(L, entry, "out of memory");
        goto done;
    }
    mpb_hash_hex(sc->robot, strlen(sc->robot), sc->robot_hash);
    mpb_hash_hex(sc->scene, strlen(sc->scene), sc->scene_hash);
    if (mpbd_open_world(L, e, sc, entry) != 0 ||
        mpbd_first_world(L, e, sc) != 0 ||
        mpbd_load_seen(L, e, sc, entry,
                       get(L, entry, "moveit_scene") != NULL) != 0)
        goto done;
    for (int i = 0; i < nreq; i++) {
        if (moveit_query(L, e, e->num_scenes - 1, &ms, scene_path,
                         req_paths[i], qnames[i], clamp, tolerance) != 0)
            goto done;
    }
    rc = 0;
done:
    L->y.place_path = NULL;
    mpbd_moveit_scene_clear(&ms);
    return rc;
}

/* A problem set: the NNNN of every sceneNNNN.yaml with a requestNNNN.yaml
 * beside it, sorted (as numbers: same-width digits sort as text). */
typedef struct problem_set {
    char  **ids;
    int     n;
} problem_set;

static int id_cmp(const void *a, const void *b)
{
    const char *x = *(char *const *)a, *y = *(char *const *)b;
    size_t lx = strlen(x), ly = strlen(y);
    return lx != ly ? (lx < ly ? -1 : 1) : strcmp(x, y);
}

static void problem_set_free(problem_set *ps)
{
    for (int i = 0; i < ps->n; i++)
        free(ps->ids[i]);
    free(ps->ids);
    memset(ps, 0, sizeof *ps);
}

/* The length of NNNN in nm = "<prefix>NNNN.yaml" (1 to 9 digits), or 0
 * when nm is no such name. */
static size_t numbered(const char *nm, const char *prefix)
{
    size_t len = strlen(nm), p = strlen(prefix), digits = 0;
    if (len < p + 6 || strncmp(nm, prefix, p) != 0 ||
        strcmp(nm + len - 5, ".yaml") != 0)
        return 0;
    for (size_t k = p; k < len - 5; k++)
        digits += isdigit((unsigned char)nm[k]) != 0;
    return digits == len - 5 - p && digits <= 9 ? digits : 0;
}

/*
 * The problems of folder dir: every sceneNNNN.yaml with its
 * requestNNNN.yaml. A scene without its request, or a request without
 * its scene, is refused, naming the file: skipped, a set would shrink
 * without a word.
 */
static int problem_set_read(mpbd_loader *L, yaml_node_t *at, const char *dir,
                            problem_set *ps)
{
    DIR *d = opendir(dir);
    struct dirent *ent;
    int cap = 0;
    char lone[300] = "", other[4096];
    memset(ps, 0, sizeof *ps);
    if (d == NULL)
        return fail_at(L, at, "cannot read problem set %s: %s", dir,
                       strerror(errno));
    while ((ent = readdir(d)) != NULL) {
        const char *nm = ent->d_name;
        size_t digits = numbered(nm, "scene"), rd = numbered(nm, "request");
        struct stat st;
        if (rd > 0) {
            snprintf(other, sizeof other, "%s/scene%.*s.yaml", dir, (int)rd,
                     nm + 7);
            if (stat(other, &st) != 0) {
                snprintf(lone, sizeof lone, "%s", nm);
                break;
            }
            continue;
        }
        if (digits == 0)
            continue;
        snprintf(other, sizeof other, "%s/request%.*s.yaml", dir,
                 (int)digits, nm + 5);
        if (stat(other, &st) != 0) {
            snprintf(lone, sizeof lone, "%s", nm);
            break;
        }
        if (ps->n == cap) {
            char **ids = realloc(ps->ids, (size_t)(cap = cap * 2 + 64) *
                                              sizeof *ids);
            if (ids == NULL)
                break;
            ps->ids = ids;
        }
        if ((ps->ids[ps->n] = strndup(nm + 5, digits)) == NULL)
            break;
        ps->n++;
    }
    int broke = ent != NULL;
    closedir(d);
    if (lone[0] != '\0') {
        const char *missing = strrchr(other, '/') + 1;
        char esc[300];
        fail_at(L, at, "problem set %s: %s has no %s beside it (a problem "
                "is a scene and a request)", dir,
                mpb_escape(lone, esc, sizeof esc), missing);
        problem_set_free(ps);
        return -1;
    }
    if (broke) {
        problem_set_free(ps);
        return fail_at(L, at, "out of memory");
    }
    if (ps->n == 0)
        return fail_at(L, at, "problem set %s holds no sceneNNNN.yaml with "
                       "a requestNNNN.yaml beside it", dir);
    qsort(ps->ids, (size_t)ps->n, sizeof *ps->ids, id_cmp);
    return 0;
}

/* A path from the experiment file's folder. */
static void path_from(const mpbd_loader *L, const char *f, char *out, size_t n)
{
    snprintf(out, n, "%s%s", f[0] == '/' ? "" : L->dir, f);
}

/* The keys of a MoveIt entry: `problems: DIR` (with first, count) or
 * `moveit_scene: FILE` with `requests`. */
static const char *const moveit_keys[] = {"problems", "first", "count",
                                          "moveit_scene", "requests", "name",
                                          "tolerance", "clamp_joint_values",
                                          "set", "seen", NULL};

int mpbd_is_moveit_entry(mpbd_loader *L, yaml_node_t *m)
{
    return get(L, m, "problems") != NULL || get(L, m, "moveit_scene") != NULL;
}

/* How many scenes and queries a MoveIt entry makes (0 on error). */
int mpbd_moveit_entry_size(mpbd_loader *L, yaml_node_t *m, int *scenes,
                           int *queries)
{
    if (get(L, m, "moveit_scene") != NULL) {
        *scenes = 1;
        *queries = (int)count_items(get(L, m, "requests"));
        return 0;
    }
    char dir[4096];
    problem_set ps;
    const char *p = scalar(get(L, m, "problems"));
    if (p == NULL || p[0] == '\0')
        return fail_at(L, get(L, m, "problems"), "problems must be the path "
                       "of a folder");
    path_from(L, p, dir, sizeof dir);
    if (problem_set_read(L, get(L, m, "problems"), dir, &ps) != 0)
        return -1;
    *scenes = *queries = ps.n;
    problem_set_free(&ps);
    return 0;
}

int mpbd_load_moveit_entry(mpbd_loader *L, mpbd_experiment *e, yaml_node_t *m,
                           const char *robot_format, const char *robot)
{
    yaml_node_t *n;
    int first = 1, num = INT_MAX, clamp = 0, rc = -1;
    double tolerance = 1e-3;
    if (only_keys(L, m, moveit_keys) != 0)
        return -1;
    if ((get(L, m, "problems") != NULL) == (get(L, m, "moveit_scene") != NULL))
        return fail_at(L, m, "a MoveIt entry names 'problems' (a folder) or "
                       "'moveit_scene' (a file), not both");
    if ((n = get(L, m, "tolerance")) != NULL &&
        (parse_double(L, n, "tolerance", &tolerance) != 0 ||
         (tolerance <= 0 && fail_at(L, n, "tolerance must be positive"))))
        return -1;
    if ((n = get(L, m, "clamp_joint_values")) != NULL) {
        const char *b = scalar(n);
        if (b == NULL || (strcmp(b, "true") != 0 && strcmp(b, "false") != 0))
            return fail_at(L, n, "clamp_joint_values must be true or false");
        clamp = strcmp(b, "true") == 0;
    }
    if (get(L, m, "moveit_scene") != NULL) {
        yaml_node_t *reqs = get(L, m, "requests"), *sn = get(L, m,
                                                             "moveit_scene");
        char *name = need_string(L, m, "name");
        if (name == NULL)
            return -1;
        if (get(L, m, "first") || get(L, m, "count")) {
            free(name);
            return fail_at(L, get(L, m, "first") ? get(L, m, "first")
                                                 : get(L, m, "count"),
                           "first and count slice a problem set");
        }
        int k = (int)count_items(reqs);
        char **paths = calloc((size_t)k + 1, sizeof *paths);
        char **qnames = calloc((size_t)k + 1, sizeof *qnames);
        char spath[4096];
        if (scalar(sn) == NULL || scalar(sn)[0] == '\0' || k == 0) {
            fail_at(L, k == 0 ? (reqs ? reqs : m) : sn, k == 0 ?
                    "requests must be a non-empty list of MoveIt request "
                    "files" : "moveit_scene must be the path of a file");
            goto one_done;
        }
        path_from(L, scalar(sn), spath, sizeof spath);
        for (int i = 0; paths && qnames && i < k; i++) {
            yaml_node_t *it = node(L, reqs->data.sequence.items.start[i]);
            const char *f = scalar(it);
            char p[4096];
            if (f == NULL || f[0] == '\0') {
                fail_at(L, it, "a request must be the path of a file");
                goto one_done;
            }
            path_from(L, f, p, sizeof p);
            const char *base = strrchr(f, '/') ? strrchr(f, '/') + 1 : f;
            size_t bl = strlen(base);
            if (bl > 5 && strcmp(base + bl - 5, ".yaml") == 0)
                bl -= 5;
            paths[i] = strdup(p);
            qnames[i] = strndup(base, bl);
            for (int o = 0; o < i && qnames[i]; o++)
                if (strcmp(qnames[o], qnames[i]) == 0) {
                    fail_at(L, it, "query '%s' appears twice in scene '%s'",
                            qnames[i], name);
                    goto one_done;
                }
        }
        rc = moveit_scene(L, e, m, robot_format, robot, name, spath, paths,
                          qnames, k, clamp, tolerance);
one_done:
        for (int i = 0; i < k; i++) {
            free(paths ? paths[i] : NULL);
            free(qnames ? qnames[i] : NULL);
        }
        free(paths);
        free(qnames);
        free(name);
        return rc;
    }

    char dir[4096];
    problem_set ps;
    if (get(L, m, "name") != NULL)
        return fail_at(L, get(L, m, "name"), "a problem set's scenes are "
                       "named after its folder and files");
    if ((n = get(L, m, "first")) &&
        parse_int_in(L, n, "first", 1, INT_MAX, &first) != 0)
        return -1;
    if ((n = get(L, m, "count")) && parse_positive_int(L, n, "count", &num))
        return -1;
    path_from(L, scalar(get(L, m, "problems")), dir, sizeof dir);
    if (problem_set_read(L, get(L, m, "problems"), dir, &ps) != 0)
        return -1;
    if (first > ps.n) {
        fail_at(L, get(L, m, "first"), "first: %d is past the %d problems "
                "of %s", first, ps.n, dir);
        problem_set_free(&ps);
        return -1;
    }
    /* As first: past the end, a count would load fewer without a word. */
    if (get(L, m, "count") != NULL && num > ps.n - (first - 1)) {
        fail_at(L, get(L, m, "count"), "count: %d from problem %d is past "
                "the end of %s, which holds %d problem%s", num, first, dir,
                ps.n, ps.n == 1 ? "" : "s");
        problem_set_free(&ps);
        return -1;
    }
    /* The set's name: its folder's ("box_panda"). */
    char set[256];
    size_t dl = strlen(dir);
    while (dl > 1 && dir[dl - 1] == '/')
        dl--;
    const char *b = dir + dl;
    while (b > dir && b[-1] != '/')
        b--;
    snprintf(set, sizeof set, "%.*s", (int)(dir + dl - b), b);
    rc = 0;
    for (int i = first - 1; rc == 0 && i < ps.n && i - (first - 1) < num;
         i++) {
        char name[512], spath[4200], rpath[4200];
        char *rp = rpath, *qn = name;
        snprintf(name, sizeof name, "%s/%s", set, ps.ids[i]);
        snprintf(spath, sizeof spath, "%s/scene%s.yaml", dir, ps.ids[i]);
        snprintf(rpath, sizeof rpath, "%s/request%s.yaml", dir, ps.ids[i]);
        rc = moveit_scene(L, e, m, robot_format, robot, name, spath, &rp, &qn,
                          1, clamp, tolerance);
    }
    problem_set_free(&ps);
    return rc;
}
