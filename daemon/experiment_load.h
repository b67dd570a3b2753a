/*
 * experiment_load.h - what the files that read an experiment share, and
 * nothing outside them uses: the loader (the YAML document, and what the
 * reading has found so far), short names for the YAML kit (yamldoc.h),
 * and the steps each file gives the others:
 *   experiment.c          the file as a whole, its settings
 *   experiment_robot.c    the robot, its SRDF and group, each scene's world
 *   experiment_scenes.c   the scenes: list, plain scenes and their queries
 *   experiment_entry.c    what either kind of entry shares: set, states
 *                         checked, held joints, a query's goal
 *   experiment_moveit.c   MoveIt problem sets and scene files
 *   experiment_seen.c     an entry's `seen:`, what its planners are given
 *   experiment_planners.c planner configurations and parameters
 */
#ifndef MPBD_EXPERIMENT_LOAD_H
#define MPBD_EXPERIMENT_LOAD_H

#include <stdarg.h>

#include "experiment.h"
#include "moveit.h"
#include "mpbench/robot.h"
#include "yamldoc.h"

/* Everything the loader carries, so helpers can report errors in one way. */
typedef struct mpbd_loader {
    mpbd_yaml   y;           /* the experiment file, and its fault */
    char       *dir;         /* directory of the file, for relative names */
    yaml_node_t *robot;      /* the robot: mapping, for errors about it */
    mpb_srdf   *srdf;        /* with robot.group: the SRDF, for its group
                                states; else NULL */
    int         group;       /* with robot.group: its index in srdf */
    mpb_robot  *model;       /* the urdf robot, for link names; or NULL */
} mpbd_loader;

/* ---- the YAML kit, on the loader's document ----------------------- */

static inline int fail_at(mpbd_loader *L, const yaml_node_t *n,
                          const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
static inline int fail_at(mpbd_loader *L, const yaml_node_t *n,
                          const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = mpbd_yaml_vfail(&L->y, n, fmt, ap);
    va_end(ap);
    return rc;
}

static inline yaml_node_t *node(mpbd_loader *L, int id)
{
    return mpbd_yaml_node(&L->y, id);
}

static inline const char *scalar(const yaml_node_t *n)
{
    return mpbd_yaml_scalar(n);
}

static inline yaml_node_t *get(mpbd_loader *L, yaml_node_t *m,
                               const char *key)
{
    return mpbd_yaml_get(&L->y, m, key);
}

static inline int count_items(const yaml_node_t *n)
{
    return mpbd_yaml_count(n);
}

static inline int only_keys(mpbd_loader *L, yaml_node_t *m,
                            const char *const *known)
{
    return mpbd_yaml_only_keys(&L->y, m, known);
}

static inline yaml_node_t *need(mpbd_loader *L, yaml_node_t *m,
                                const char *key, yaml_node_type_t type,
                                const char *what)
{
    return mpbd_yaml_need(&L->y, m, key, type, what);
}

static inline char *dup_str(mpbd_loader *L, const yaml_node_t *n,
                            const char *s)
{
    return mpbd_yaml_dup(&L->y, n, s);
}

static inline char *need_string(mpbd_loader *L, yaml_node_t *m,
                                const char *key)
{
    return mpbd_yaml_need_string(&L->y, m, key);
}

static inline int parse_double(mpbd_loader *L, yaml_node_t *n,
                               const char *what, double *out)
{
    return mpbd_yaml_double(&L->y, n, what, out);
}

static inline int parse_int_in(mpbd_loader *L, yaml_node_t *n,
                               const char *what, long lo, long hi, int *out)
{
    return mpbd_yaml_int_in(&L->y, n, what, lo, hi, out);
}

static inline int parse_positive_int(mpbd_loader *L, yaml_node_t *n,
                                     const char *what, int *out)
{
    return mpbd_yaml_int_in(&L->y, n, what, 1, 1000000000, out);
}

/* ---- experiment_entry.c ------------------------------------------- */

/* Longest problem set name `set:` may give, in bytes. */
#define MPBD_SET_MAX 255


/* ---- experiment_robot.c ------------------------------------------- */

/* A robot or scene (what: "robot" or "scene"): inline `text:` or a
 * `file:` relative to the experiment file, plus its `format:`. */
int mpbd_load_model(mpbd_loader *L, yaml_node_t *m, const char *what,
                    char **format, char **text, char **file_path);
/* The robot's `srdf:`, read against the URDF and appended to *robot. */
int mpbd_load_srdf(mpbd_loader *L, mpbd_experiment *e, char **robot);
/* The planning group: `joints:` (node n) or `group:` of the SRDF. */
int mpbd_load_group(mpbd_loader *L, mpbd_experiment *e, yaml_node_t *n);
/* Scene sc's world, with the robot; faults at `where`. */
int mpbd_open_world(mpbd_loader *L, mpbd_experiment *e, mpbd_scene *sc,
                    yaml_node_t *where);

/* ---- experiment_scenes.c ------------------------------------------ */

/* The `scenes:` of the document's root, with the robot. */
int mpbd_load_scenes(mpbd_loader *L, mpbd_experiment *e, yaml_node_t *root);

/* ---- experiment_entry.c ------------------------------------------- */

/* Whether q (a start or goal) is within the limits and collision-free. */
int mpbd_check_state(mpbd_loader *L, const mpbd_experiment *e, int scene,
                     const double *q, const char *what, yaml_node_t *where);
/* Give query q a value for every held joint known so far. */
int mpbd_held_fill(mpbd_experiment *e, mpbd_query *q);
/* Hold joint `name` at v in world w (experiment_entry.c says how). */
int mpbd_hold_one(mpbd_loader *L, mpbd_experiment *e, mpb_world *w,
                  const char *name, double v, yaml_node_t *key,
                  yaml_node_t *val, int clamp, int *clamped, int *index);
/* After the first scene's world opens: the robot's held joint values. */
int mpbd_first_world(mpbd_loader *L, mpbd_experiment *e, mpbd_scene *sc);
/* `joint_values: {name: value, ...}` (m, may be NULL): the robot's held
 * joints (q NULL), or query q's own. */
int mpbd_load_joint_values(mpbd_loader *L, mpbd_experiment *e, mpb_world *w,
                           yaml_node_t *m, mpbd_query *q);
/*
 * A scene entry's `set:` (m a scenes entry), into *out (NULL when the key
 * is absent: the store's default): a non-empty name of at most
 * MPBD_SET_MAX bytes without control characters. 0, or -1 with one line
 * at the key's value.
 */
int mpbd_load_set(mpbd_loader *L, yaml_node_t *m, char **out);


/* ---- experiment_moveit.c ------------------------------------------ */

/* Whether scene entry m is a MoveIt entry (problems: or moveit_scene:). */
int mpbd_is_moveit_entry(mpbd_loader *L, yaml_node_t *m);
/* How many scenes and queries MoveIt entry m makes. 0, or -1. */
int mpbd_moveit_entry_size(mpbd_loader *L, yaml_node_t *m, int *scenes,
                           int *queries);
/* MoveIt entry m's scenes and queries, into e. */
int mpbd_load_moveit_entry(mpbd_loader *L, mpbd_experiment *e,
                           yaml_node_t *m, const char *robot_format,
                           const char *robot);

/* ---- experiment_seen.c -------------------------------------------- */

/* Scene sc's `seen:` (entry's key; absent: none), after its world opened:
 * the text its planners are given, its hash, its world. A problem set's
 * entry (one_scene 0) may only sense. 0, or -1 with one line. */
int mpbd_load_seen(mpbd_loader *L, mpbd_experiment *e, mpbd_scene *sc,
                   yaml_node_t *entry, int one_scene);

/* ---- experiment_planners.c ---------------------------------------- */

/* The `planners:` of the document's root. */
int mpbd_load_planners(mpbd_loader *L, mpbd_experiment *e,
                       yaml_node_t *root);

#endif
