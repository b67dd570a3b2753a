/*
 * experiment_robot.c - an experiment's robot: its model (a file or inline
 * text), its SRDF, its planning group, and the world each scene opens
 * with it.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "experiment_load.h"
#include "mpbench/scene.h"

/*
 * A robot or scene: inline `text:` or a `file:` relative to the experiment
 * file, plus its `format:`.
 */
int mpbd_load_model(mpbd_loader *L, yaml_node_t *m, const char *what,
                    char **format, char **text, char **file_path)
{
    /* Each its own: a robot has no name or queries, a scene no joints. */
    static const char *const robot_keys[] = {"format", "file", "text",
                                             "joints", "group", "srdf",
                                             "joint_values", NULL};
    static const char *const scene_keys[] = {"format", "file", "text", "name",
                                             "queries", "joints", "set",
                                             "seen", NULL};
    static const char *const seen_keys[] = {"format", "file", "text", NULL};
    const char *const *keys = strcmp(what, "robot") == 0  ? robot_keys
                              : strcmp(what, "seen") == 0 ? seen_keys
                                                          : scene_keys;
    yaml_node_t *file, *inline_text;
    if (m == NULL || m->type != YAML_MAPPING_NODE)
        return fail_at(L, m,
                       "%s must be a mapping with format and file or text",
                       what);
    if (only_keys(L, m, keys) != 0)
        return -1;
    if ((*format = need_string(L, m, "format")) == NULL)
        return -1;
    file = get(L, m, "file");
    inline_text = get(L, m, "text");
    if ((file == NULL) == (inline_text == NULL))
        return fail_at(L, m, "%s needs exactly one of 'file' and 'text'", what);
    if (inline_text) {
        if (scalar(inline_text) == NULL)
            return fail_at(L, inline_text, "%s text must be a string", what);
        *text = dup_str(L, inline_text, scalar(inline_text));
        if (*text == NULL)
            return -1;
        /* its octree and cloud files beside the experiment file */
        if (strcmp(what, "robot") != 0 && strcmp(*format, "moveit-scene") == 0) {
            char why[512], *whole;
            if (mpb_scene_resolve(*text, L->dir, &whole, why, sizeof why) != MPB_OK)
                return fail_at(L, inline_text, "%s", why);
            free(*text);
            *text = whole;
        }
        return 0;
    }
    if (scalar(file) == NULL || scalar(file)[0] == '\0')
        return fail_at(L, file, "%s file must be a path", what);
    char path[4096];
    const char *f = scalar(file);
    snprintf(path, sizeof path, "%s%s", f[0] == '/' ? "" : L->dir, f);
    if ((*file_path = strdup(path)) == NULL)
        return fail_at(L, file, "out of memory");
    size_t len;
    if ((*text = mpb_read_file(path, 0, &len)) == NULL)
        return fail_at(L, file, "cannot read %s file %s: %s", what, path,
                       strerror(errno));
    /* The parsers stop at a NUL: the rest would vanish without a word. */
    if (strlen(*text) != len)
        return fail_at(L, file, "%s: not a text file (a NUL byte at offset "
                       "%zu)", path, strlen(*text));
    /* A scene's octree and cloud files, read against its folder: the
       text that travels holds their data (scene.h). */
    if (strcmp(what, "robot") != 0 && strcmp(*format, "moveit-scene") == 0) {
        char dir[4096], why[512], *whole;
        const char *slash = strrchr(path, '/');
        snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - path + 1) : 0, path);
        if (mpb_scene_resolve(*text, dir, &whole, why, sizeof why) != MPB_OK)
            return fail_at(L, file, "%s: %s", path, why);
        free(*text);
        *text = whole;
    }
    return 0;
}

/*
 * A fault of the robot's, its URDF's ("urdf: ...") or its SRDF's ("srdf
 * line 3: ..."), as the library words it: at the robot's key that names
 * the file it is in, and naming that file.
 */
static int robot_fault(mpbd_loader *L, const mpbd_experiment *e,
                       const char *why)
{
    int in_srdf = strncmp(why, "srdf", 4) == 0;
    const char *file = in_srdf ? e->srdf_file : e->robot_file;
    /* "srdf line 3: ..." in the SRDF file is its "line 3: ...". */
    const char *what = in_srdf && file != NULL ? why + 5 : why;
    yaml_node_t *at = get(L, L->robot, in_srdf ? "srdf" : "file");
    if (at == NULL)
        at = get(L, L->robot, "text");
    if (file != NULL)
        return fail_at(L, at ? at : L->robot, "robot: %s: %s", file, what);
    return fail_at(L, at ? at : L->robot, "robot: %s", why);
}

/*
 * The robot's SRDF, `srdf:` a file relative to the experiment file: its
 * text goes into the robot text, on the line after the URDF (world.h),
 * for the world of every scene and every planner. It is read here too,
 * against the URDF: with `group:` for the group and its states, and for
 * the warning about pairs it names that the URDF lacks.
 */
int mpbd_load_srdf(mpbd_loader *L, mpbd_experiment *e, char **robot)
{
    yaml_node_t *n = get(L, L->robot, "srdf");
    if (n == NULL)
        return 0;
    const char *f = scalar(n);
    if (f == NULL || f[0] == '\0')
        return fail_at(L, n, "srdf must be the path of a file");
    const char *format = scalar(get(L, L->robot, "format"));
    if (format == NULL || strcmp(format, "urdf") != 0)
        return fail_at(L, n, "srdf goes with a urdf robot only");
    char path[4096];
    snprintf(path, sizeof path, "%s%s", f[0] == '/' ? "" : L->dir, f);
    if ((e->srdf_file = strdup(path)) == NULL)
        return fail_at(L, n, "out of memory");
    size_t len;
    char *srdf = mpb_read_file(path, 0, &len);
    if (srdf == NULL)
        return fail_at(L, n, "cannot read srdf file %s: %s", path,
                       strerror(errno));
    if (strlen(srdf) != len) {
        fail_at(L, n, "%s: not a text file (a NUL byte at offset %zu)", path,
                strlen(srdf));
        free(srdf);
        return -1;
    }
    /* Read against the URDF here, for the group and for the warning about
     * pairs naming links the URDF lacks (skipped, as MoveIt does). */
    char why[512];
    mpb_srdf *sem = NULL;
    if (mpb_srdf_open(*robot, srdf, &sem, why, sizeof why) != MPB_OK) {
        free(srdf);
        return robot_fault(L, e, why);
    }
    if (mpb_srdf_skipped_pairs(sem) != NULL) {
        char line[6144];
        snprintf(line, sizeof line, "robot: %s: %s", path,
                 mpb_srdf_skipped_pairs(sem));
        if ((e->srdf_warning = strdup(line)) == NULL) {
            mpb_srdf_close(sem);
            free(srdf);
            return fail_at(L, n, "out of memory");
        }
    }
    if (get(L, L->robot, "group") != NULL)
        L->srdf = sem;
    else
        mpb_srdf_close(sem);
    size_t rl = strlen(*robot);
    int nl = rl > 0 && (*robot)[rl - 1] != '\n';
    char *both = malloc(rl + (size_t)nl + len + 1);
    if (both == NULL) {
        free(srdf);
        return fail_at(L, n, "out of memory");
    }
    memcpy(both, *robot, rl);
    if (nl)
        both[rl] = '\n';
    memcpy(both + rl + nl, srdf, len + 1);
    free(srdf);
    free(*robot);
    *robot = both;
    return 0;
}

/*
 * `group:` names a group of the SRDF: its active joints, base first, are
 * the planning group. mpbench plans a serial chain; a group that is not
 * one is refused, saying why.
 */
static int load_srdf_group(mpbd_loader *L, mpbd_experiment *e, yaml_node_t *n)
{
    const char *name = scalar(n);
    char why[512];
    if (get(L, L->robot, "joints") != NULL)
        return fail_at(L, n, "give the planning group as joints or as group, "
                       "not both");
    if (name == NULL || *name == '\0')
        return fail_at(L, n, "group must be the name of a group of the "
                       "robot's srdf");
    if (L->srdf == NULL)
        return fail_at(L, n, "group '%s' names a group of the robot's SRDF: "
                       "give it as srdf", name);
    int g = mpb_srdf_group_index(L->srdf, name);
    if (g < 0) {
        size_t used = 0;
        why[0] = '\0';
        for (int i = 0; i < mpb_srdf_num_groups(L->srdf) && used < sizeof why;
             i++)
            used += (size_t)snprintf(why + used, sizeof why - used, "%s%s",
                                     i ? ", " : "",
                                     mpb_srdf_get_group(L->srdf, i)->name);
        return fail_at(L, n, "%s has no group '%s' (%s%s)", e->srdf_file, name,
                       used ? "its groups: " : "it has none", why);
    }
    if (mpb_srdf_group_check(L->srdf, g, why, sizeof why) != MPB_OK)
        return fail_at(L, n, "%s", why);
    const mpb_srdf_group *G = mpb_srdf_get_group(L->srdf, g);
    if ((e->group_name = strdup(name)) == NULL ||
        (e->group = calloc((size_t)G->num_active + 1,
                           sizeof *e->group)) == NULL)
        return fail_at(L, n, "out of memory");
    for (int j = 0; j < G->num_active; j++)
        if ((e->group[e->num_group++] = strdup(G->active[j])) == NULL)
            return fail_at(L, n, "out of memory");
    L->group = g;
    return 0;
}

/* The robot's planning group, as a list of joint names (optional for
 * planar robots, whose joints are all in the group), or as a group of its
 * SRDF. */
int mpbd_load_group(mpbd_loader *L, mpbd_experiment *e, yaml_node_t *n)
{
    if (get(L, L->robot, "group") != NULL)
        return load_srdf_group(L, e, get(L, L->robot, "group"));
    if (n == NULL)
        return 0;
    if (n->type != YAML_SEQUENCE_NODE || count_items(n) == 0)
        return fail_at(L, n, "joints must be a list of joint names");
    e->group = calloc(count_items(n) + 1, sizeof *e->group);
    if (e->group == NULL)
        return fail_at(L, n, "out of memory");
    for (yaml_node_item_t *it = n->data.sequence.items.start;
         it < n->data.sequence.items.top; it++) {
        const char *s = scalar(node(L, *it));
        if (s == NULL || *s == '\0')
            return fail_at(L, node(L, *it), "a joint must be a name");
        if ((e->group[e->num_group++] = strdup(s)) == NULL)
            return fail_at(L, n, "out of memory");
    }
    return 0;
}

/* Scene sc's world as the experiment opens it, into *out: the robot, the
 * scene, the group, the verification; meshes looked for last in the robot
 * file's folder. MPB_OK, or the world's code and why. */
static int open_scene_world(const mpbd_experiment *e, const mpbd_scene *sc,
                            int seen, mpb_world **out, char *why, size_t len)
{
    char dir[4096] = "";
    if (e->robot_file) {
        snprintf(dir, sizeof dir, "%s", e->robot_file);
        char *slash = strrchr(dir, '/');
        if (slash)
            slash[1] = '\0';
        else
            snprintf(dir, sizeof dir, ".");
    }
    int rc = mpb_world_open_group_in(sc->robot_format, sc->robot,
                                     dir[0] ? dir : NULL,
                                     seen ? sc->seen_format : sc->scene_format,
                                     seen ? sc->seen : sc->scene,
                                     (const char *const *)e->group,
                                     e->num_group, out, why, len);
    if (rc == MPB_OK)
        mpb_world_set_verification(*out, (mpb_verification)e->verification);
    return rc;
}

int mpbd_scene_world_copy(const mpbd_experiment *e, int scene, int seen,
                          mpb_world **out, char *why, size_t len)
{
    return open_scene_world(e, &e->scenes[scene], seen, out, why, len);
}

/* The robot: formats its joints, and gives each scene its world. */
int mpbd_open_world(mpbd_loader *L, mpbd_experiment *e, mpbd_scene *sc,
                    yaml_node_t *where)
{
    char why[512];
    int rc = open_scene_world(e, sc, 0, &sc->world, why, sizeof why);
    const char *goes_with = mpb_world_scene_format(sc->robot_format);
    if (rc == MPB_EUNSUPPORTED &&
        (goes_with == NULL || strcmp(goes_with, sc->scene_format) != 0)) {
        /* A format: point at the robot's, or at this scene's if the
         * robot's is known but the scene's does not go with it. (Other
         * faults are unsupported too, a mesh URI's scheme: not these.) */
        yaml_node_t *at = goes_with == NULL ? get(L, L->robot, "format")
                                            : get(L, where, "format");
        const char *what = strncmp(why, "world: ", 7) == 0 ? why + 7 : why;
        return fail_at(L, at ? at : where, "%s", what);
    }
    if (rc != MPB_OK) {
        /* Name the file the fault is in, when it came from one, and point
         * at the key that names it: a fault of the robot's (its URDF or
         * SRDF) is at the robot's key, whichever scene it was loaded with. */
        if (strncmp(why, "scene", 5) != 0)
            return robot_fault(L, e, why);
        if (sc->scene_file != NULL)
            return fail_at(L, where, "scene '%s': %s: %s", sc->name,
                           sc->scene_file, why);
        return fail_at(L, where, "scene '%s': %s", sc->name, why);
    }
    int nj = mpb_world_num_joints(sc->world);
    if (e->joint_names == NULL) {
        e->num_joints = nj;
        e->joint_names = calloc((size_t)nj, sizeof *e->joint_names);
        e->wraps = calloc((size_t)nj + 1, 1);
        if (e->joint_names == NULL || e->wraps == NULL)
            return fail_at(L, where, "out of memory");
        for (int j = 0; j < nj; j++) {
            if ((e->joint_names[j] = strdup(mpb_world_joint_name(sc->world, j)))
                == NULL)
                return fail_at(L, where, "out of memory");
            e->wraps[j] = (unsigned char)mpb_world_joint_is_continuous(sc->world, j);
        }
    } else if (nj != e->num_joints) {
        return fail_at(L, where, "scene '%s': robot has %d joints, earlier "
                       "scenes have %d", sc->name, nj, e->num_joints);
    }
    return 0;
}
