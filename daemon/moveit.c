/*
 * moveit.c - MoveIt PlanningScene and MotionPlanRequest YAML files, read
 * through libyaml's document API (every node keeps its line and column)
 * into a moveit-scene text, allowed pairs, joint values and a goal.
 */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <yaml.h>

#include "moveit.h"
#include "mpbench/pose.h"
#include "mpbench/proto.h"
#include "core/base64.h"
#include "core/mathconst.h"
#include "mpbench/octree.h"


/* One file being read (yamldoc.h). */
typedef mpbd_yaml reader;

/* A growing text, for the scene. */
typedef struct text {
    char  *s;
    size_t len, cap;
    int    oom;
} text;

static void add(text *t, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

static void add(text *t, const char *fmt, ...)
{
    va_list ap;
    for (;;) {
        size_t room = t->cap - t->len;
        va_start(ap, fmt);
        int n = t->s ? vsnprintf(t->s + t->len, room, fmt, ap) : -1;
        va_end(ap);
        if (n >= 0 && (size_t)n < room) {
            t->len += (size_t)n;
            return;
        }
        size_t cap = t->cap * 2 + (n > 0 ? (size_t)n : 0) + 4096;
        char *s = realloc(t->s, cap);
        if (s == NULL) {
            t->oom = 1;
            return;
        }
        t->s = s;
        t->cap = cap;
    }
}

/* ---- the YAML kit (yamldoc.h), by the short names read below ------- */

static int fail_at(reader *R, const yaml_node_t *n, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static int fail_at(reader *R, const yaml_node_t *n, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = mpbd_yaml_vfail(R, n, fmt, ap);
    va_end(ap);
    return rc;
}

static const char *scalar(const yaml_node_t *n)
{
    return mpbd_yaml_scalar(n);
}

static yaml_node_t *get(reader *R, yaml_node_t *m, const char *key)
{
    return mpbd_yaml_get(R, m, key);
}

static int count(const yaml_node_t *n)
{
    return mpbd_yaml_count(n);
}

static yaml_node_t *item(reader *R, yaml_node_t *seq, int i)
{
    return mpbd_yaml_item(R, seq, i);
}

static mpbd_mark mark_of(const yaml_node_t *n)
{
    return mpbd_yaml_mark(n);
}

/* A list, or an absent key (an empty list); else an error at n. */
static int list_or_none(reader *R, yaml_node_t *n, const char *what)
{
    if (n != NULL && n->type != YAML_SEQUENCE_NODE &&
        !(n->type == YAML_SCALAR_NODE && scalar(n)[0] == '\0'))
        return fail_at(R, n, "%s must be a list", what);
    return 0;
}

static int number(reader *R, yaml_node_t *n, const char *what, double *out)
{
    const char *s = scalar(n);
    if (n == NULL)
        return fail_at(R, NULL, "missing %s", what);
    if (s == NULL)
        return fail_at(R, n, "%s must be a number", what);
    if (!mpbd_parse_decimal(s, out))
        return fail_at(R, n, "%s must be a finite number, not '%.40s'", what, s);
    return 0;
}

/*
 * k numbers: a list [a, b, ...] or a mapping of the names in keys (a
 * geometry_msgs Point {x, y, z} or Quaternion {x, y, z, w}), as MoveIt's
 * YAML writers produce either.
 */
static int numbers(reader *R, yaml_node_t *parent, yaml_node_t *n,
                   const char *what, const char *const *keys, int k,
                   double *out)
{
    if (n == NULL)
        return fail_at(R, parent, "missing '%s'", what);
    if (n->type == YAML_MAPPING_NODE) {
        for (int i = 0; i < k; i++) {
            yaml_node_t *v = get(R, n, keys[i]);
            if (v == NULL)
                return fail_at(R, n, "%s needs '%s'", what, keys[i]);
            if (number(R, v, what, &out[i]) != 0)
                return -1;
        }
        return 0;
    }
    if (count(n) != k)
        return fail_at(R, n, "%s must be a list of %d numbers", what, k);
    for (int i = 0; i < k; i++)
        if (number(R, item(R, n, i), what, &out[i]) != 0)
            return -1;
    return 0;
}

static const char *const XYZ[] = {"x", "y", "z", "w"};

/* A geometry_msgs/Pose: position and orientation (x y z w, normalised);
 * a zero or non-finite quaternion is refused at its node. */
static int pose(reader *R, yaml_node_t *n, double p[3], double q[4])
{
    if (n == NULL || n->type != YAML_MAPPING_NODE)
        return fail_at(R, n, "a pose must be a mapping of position and "
                       "orientation");
    if (numbers(R, n, get(R, n, "position"), "position", XYZ, 3, p) != 0 ||
        numbers(R, n, get(R, n, "orientation"), "orientation", XYZ, 4, q) != 0)
        return -1;
    double norm = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(norm > 1e-9))
        return fail_at(R, get(R, n, "orientation"), "orientation is a zero "
                       "quaternion");
    for (int i = 0; i < 4; i++)
        q[i] /= norm;
    return 0;
}

/* ---- loading a file ---------------------------------------------------- */

/* The file at path as one checked YAML document (yamldoc.h) whose root
 * is a mapping: MPB_OK with R->doc to free, else an error in err. */
static int open_file(reader *R, const char *path, char *err, size_t errlen)
{
    *R = (reader){.path = path, .err = err, .errlen = errlen};
    size_t len;
    char *body = mpb_read_file(path, 0, &len);
    if (body == NULL) {
        /* A folder says "Is a directory" (mpb_read_file()), not libyaml's
         * "input error". */
        snprintf(err, errlen, "%s: cannot read: %s", path, strerror(errno));
        return MPB_EIO;
    }
    int ok = mpbd_yaml_load(R, body, len, "a MoveIt file holds one message")
             == 0;
    free(body);
    if (!ok)
        return MPB_EPARSE;
    yaml_node_t *root = yaml_document_get_root_node(&R->doc);
    if (root == NULL || root->type != YAML_MAPPING_NODE) {
        fail_at(R, root, "expected a mapping (a MoveIt message as YAML)");
        yaml_document_delete(&R->doc);
        return MPB_EPARSE;
    }
    return MPB_OK;
}

/* ---- robot states ------------------------------------------------------ */

static void joints_clear(mpbd_moveit_joints *j)
{
    for (int i = 0; i < j->n; i++)
        free(j->names[i]);
    free(j->names);
    free(j->values);
    free(j->at);
    memset(j, 0, sizeof *j);
}

static int joints_alloc(reader *R, yaml_node_t *at, mpbd_moveit_joints *j,
                        int n)
{
    j->names = calloc((size_t)n + 1, sizeof *j->names);
    j->values = calloc((size_t)n + 1, sizeof *j->values);
    j->at = calloc((size_t)n + 1, sizeof *j->at);
    if (!j->names || !j->values || !j->at)
        return fail_at(R, at, "out of memory");
    return 0;
}

/*
 * A moveit_msgs/RobotState: joint_state.name and .position, of the same
 * length. Attached objects are refused (not read yet); the
 * multi_dof_joint_state (the virtual joint) is ignored: the robot's base
 * frame is the scene's.
 */
static int robot_state(reader *R, yaml_node_t *m, mpbd_moveit_joints *j)
{
    if (m == NULL)
        return 0;
    if (m->type != YAML_MAPPING_NODE)
        return fail_at(R, m, "a robot state must be a mapping");
    yaml_node_t *att = get(R, m, "attached_collision_objects");
    if (count(att) > 0)
        return fail_at(R, att, "attached collision objects are not read "
                       "(yet): attach the object in a .scene file instead "
                       "(docs/scenes.md)");
    yaml_node_t *js = get(R, m, "joint_state");
    if (js == NULL)
        return 0;
    yaml_node_t *names = get(R, js, "name"), *pos = get(R, js, "position");
    if (list_or_none(R, names, "joint_state.name") != 0 ||
        list_or_none(R, pos, "joint_state.position") != 0)
        return -1;
    if (count(names) != count(pos))
        return fail_at(R, pos ? pos : js, "joint_state has %d names and %d "
                       "positions", count(names), count(pos));
    int n = count(names);
    if (joints_alloc(R, js, j, n) != 0)
        return -1;
    for (int i = 0; i < n; i++) {
        yaml_node_t *nn = item(R, names, i);
        const char *s = scalar(nn);
        if (s == NULL || s[0] == '\0')
            return fail_at(R, nn, "a joint name must be a string");
        if ((j->names[i] = strdup(s)) == NULL)
            return fail_at(R, nn, "out of memory");
        j->at[i] = mark_of(nn);
        j->n = i + 1;
        if (number(R, item(R, pos, i), "a joint position", &j->values[i]) != 0)
            return -1;
        for (int k = 0; k < i; k++)
            if (strcmp(j->names[k], s) == 0)
                return fail_at(R, nn, "joint '%s' appears twice", s);
    }
    return 0;
}

/* ---- scenes ---------------------------------------------------------- */

/* One primitive, written as the moveit-scene format wants it: cylinder
 * and cone as radius then length, where shape_msgs has height first. */
static int primitive(reader *R, yaml_node_t *n, text *t)
{
    const char *type = scalar(get(R, n, "type"));
    yaml_node_t *dims = get(R, n, "dimensions");
    double d[3];
    int want;
    if (type == NULL)
        return fail_at(R, n, "a primitive needs a 'type' (box, sphere, "
                       "cylinder, cone)");
    want = strcmp(type, "box") == 0 ? 3 : strcmp(type, "sphere") == 0 ? 1
         : strcmp(type, "cylinder") == 0 || strcmp(type, "cone") == 0 ? 2 : 0;
    if (want == 0) {
        char esc[64];
        return fail_at(R, get(R, n, "type"), "unknown primitive type '%s' "
                       "(box, sphere, cylinder, cone)",
                       mpb_escape(type, esc, sizeof esc));
    }
    if (count(dims) != want)
        return fail_at(R, dims ? dims : n, "a %s needs %d dimensions", type,
                       want);
    for (int i = 0; i < want; i++) {
        if (number(R, item(R, dims, i), "a dimension", &d[i]) != 0)
            return -1;
        if (!(d[i] > 0))
            return fail_at(R, item(R, dims, i), "a dimension must be "
                           "positive, not %g", d[i]);
    }
    if (want == 3)
        add(t, "box\n%.17g %.17g %.17g\n", d[0], d[1], d[2]);
    else if (want == 1)
        add(t, "sphere\n%.17g\n", d[0]);
    else
        add(t, "%s\n%.17g %.17g\n", type, d[1], d[0]);
    return 0;
}

/* One shape_msgs/Mesh: vertices (points) and triangles (vertex_indices). */
static int mesh(reader *R, yaml_node_t *n, text *t)
{
    yaml_node_t *v = get(R, n, "vertices"), *tr = get(R, n, "triangles");
    int nv = count(v), nt = count(tr);
    if (nv < 3 || nt < 1)
        return fail_at(R, n, "a mesh needs at least 3 vertices and 1 "
                       "triangle");
    add(t, "mesh\n%d %d\n", nv, nt);
    for (int i = 0; i < nv; i++) {
        double p[3];
        if (numbers(R, v, item(R, v, i), "a vertex", XYZ, 3, p) != 0)
            return -1;
        add(t, "%.17g %.17g %.17g\n", p[0], p[1], p[2]);
    }
    for (int i = 0; i < nt; i++) {
        yaml_node_t *tn = item(R, tr, i), *idx = get(R, tn, "vertex_indices");
        double k[3];
        if (idx == NULL)
            idx = tn;
        if (count(idx) != 3)
            return fail_at(R, tn, "a triangle needs 3 vertex_indices");
        for (int c = 0; c < 3; c++) {
            if (number(R, item(R, idx, c), "a vertex index", &k[c]) != 0)
                return -1;
            if (k[c] != floor(k[c]) || k[c] < 0 || k[c] >= nv)
                return fail_at(R, item(R, idx, c), "vertex index %g is not "
                               "one of the mesh's %d vertices", k[c], nv);
        }
        add(t, "%d %d %d\n", (int)k[0], (int)k[1], (int)k[2]);
    }
    return 0;
}

/* The shapes of one kind (primitives, meshes or planes) with their poses. */
static int shapes(reader *R, yaml_node_t *obj, const char *key,
                  const char *poses_key, text *t, int *written)
{
    yaml_node_t *list = get(R, obj, key), *poses = get(R, obj, poses_key);
    if (list_or_none(R, list, key) != 0 || list_or_none(R, poses, poses_key))
        return -1;
    if (count(list) != count(poses))
        return fail_at(R, poses ? poses : obj, "%d %s but %d %s", count(list),
                       key, count(poses), poses_key);
    for (int i = 0; i < count(list); i++) {
        yaml_node_t *s = item(R, list, i);
        double p[3], q[4];
        if (s->type != YAML_MAPPING_NODE && strcmp(key, "planes") != 0)
            return fail_at(R, s, "a shape must be a mapping");
        if (strcmp(key, "primitives") == 0) {
            if (primitive(R, s, t) != 0)
                return -1;
        } else if (strcmp(key, "meshes") == 0) {
            if (mesh(R, s, t) != 0)
                return -1;
        } else {
            double c[4];
            yaml_node_t *coef = s->type == YAML_MAPPING_NODE
                                    ? get(R, s, "coef") : s;
            if (numbers(R, s, coef, "plane coef", XYZ, 4, c) != 0)
                return -1;
            add(t, "plane\n%.17g %.17g %.17g %.17g\n", c[0], c[1], c[2], c[3]);
        }
        if (pose(R, item(R, poses, i), p, q) != 0)
            return -1;
        add(t, "%.17g %.17g %.17g\n%.17g %.17g %.17g %.17g\n0 0 0 0\n", p[0],
            p[1], p[2], q[0], q[1], q[2], q[3]);
        (*written)++;
    }
    return 0;
}

/* A newline or a leading '*' or '.' in an id would break the text. */
static int id_ok(const char *id)
{
    if (id[0] == '\0' || strchr(id, '\n') || strchr(id, '\r'))
        return 0;
    return 1;
}

static int collision_object(reader *R, yaml_node_t *o, text *t,
                            char **ids, int k)
{
    yaml_node_t *idn = get(R, o, "id");
    const char *id = scalar(idn);
    double p[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1};
    if (o->type != YAML_MAPPING_NODE)
        return fail_at(R, o, "a collision object must be a mapping");
    if (id == NULL || !id_ok(id))
        return fail_at(R, idn ? idn : o, "a collision object needs an 'id' "
                       "on one line");
    for (int i = 0; i < k; i++)
        if (strcmp(ids[i], id) == 0)
            return fail_at(R, idn, "object '%s' appears twice", id);
    if ((ids[k] = strdup(id)) == NULL)
        return fail_at(R, idn, "out of memory");
    const char *op = scalar(get(R, o, "operation"));
    if (op != NULL && strcmp(op, "0") != 0 && strcmp(op, "ADD") != 0)
        return fail_at(R, get(R, o, "operation"), "only ADD (0) objects are "
                       "read, not operation '%s'", op);
    /* The object's own pose (newer messages); its shapes' are relative. */
    if (get(R, o, "pose") != NULL && pose(R, get(R, o, "pose"), p, q) != 0)
        return -1;
    add(t, "* %s\n%.17g %.17g %.17g\n%.17g %.17g %.17g %.17g\n", id, p[0],
        p[1], p[2], q[0], q[1], q[2], q[3]);
    int n = count(get(R, o, "primitives")) + count(get(R, o, "meshes")) +
            count(get(R, o, "planes")), written = 0;
    /* MoveIt refuses to add an object without shapes; read as one, a
     * wall cut short would vanish from the benchmark without a word. */
    if (n == 0)
        return fail_at(R, idn, "object '%s' has no shapes (primitives, "
                       "meshes or planes): MoveIt refuses such an object", id);
    add(t, "%d\n", n);
    if (shapes(R, o, "primitives", "primitive_poses", t, &written) != 0 ||
        shapes(R, o, "meshes", "mesh_poses", t, &written) != 0 ||
        shapes(R, o, "planes", "plane_poses", t, &written) != 0)
        return -1;
    add(t, "0\n");
    return 0;
}

/* allowed_collision_matrix: the pairs a < b whose entry is true in both
 * rows (MoveIt's matrix is symmetric; a lopsided one is refused). */
static int acm(reader *R, yaml_node_t *m, mpbd_moveit_scene *s)
{
    if (m == NULL)
        return 0;
    yaml_node_t *names = get(R, m, "entry_names"), *rows = get(R, m,
                                                              "entry_values");
    if (list_or_none(R, names, "entry_names") != 0 ||
        list_or_none(R, rows, "entry_values") != 0)
        return -1;
    int n = count(names);
    if (count(rows) != n)
        return fail_at(R, rows ? rows : m, "%d entry_names but %d rows of "
                       "entry_values", n, count(rows));
    for (int i = 0; i < n; i++) {
        const char *a = scalar(item(R, names, i));
        if (a == NULL || a[0] == '\0')
            return fail_at(R, item(R, names, i), "an entry name must be a "
                           "link's name");
        yaml_node_t *row = item(R, rows, i);
        yaml_node_t *vals = get(R, row, "enabled") ? get(R, row, "enabled")
                                                   : row;
        if (count(vals) != n)
            return fail_at(R, row, "row %d of entry_values has %d values, "
                           "not %d", i + 1, count(vals), n);
    }
    s->pairs = calloc((size_t)n * (size_t)n + 2, sizeof *s->pairs);
    s->pair_at = calloc((size_t)n * (size_t)n + 2, sizeof *s->pair_at);
    if (!s->pairs || !s->pair_at)
        return fail_at(R, m, "out of memory");
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            yaml_node_t *ri = item(R, rows, i), *rj = item(R, rows, j);
            ri = get(R, ri, "enabled") ? get(R, ri, "enabled") : ri;
            rj = get(R, rj, "enabled") ? get(R, rj, "enabled") : rj;
            yaml_node_t *v = item(R, ri, j);
            const char *b = scalar(v);
            int yes = b && (strcmp(b, "true") == 0 || strcmp(b, "True") == 0);
            if (!b || (!yes && strcmp(b, "false") != 0 &&
                       strcmp(b, "False") != 0))
                return fail_at(R, v, "an entry value must be true or false");
            const char *bt = scalar(item(R, rj, i));
            int back = bt && (strcmp(bt, "true") == 0 || strcmp(bt, "True") == 0);
            if (yes != back)
                return fail_at(R, v, "entry_values is not symmetric: "
                               "row %d, column %d", i + 1, j + 1);
            if (!yes || j <= i)
                continue;
            int k = 2 * s->num_pairs;
            s->pairs[k] = strdup(scalar(item(R, names, i)));
            s->pairs[k + 1] = strdup(scalar(item(R, names, j)));
            s->pair_at[k] = mark_of(item(R, names, i));
            s->pair_at[k + 1] = mark_of(item(R, names, j));
            s->num_pairs++;
            if (!s->pairs[k] || !s->pairs[k + 1])
                return fail_at(R, v, "out of memory");
        }
    return 0;
}

/*
 * world.octomap (moveit_msgs/OctomapWithPose): its origin and its
 * octomap_msgs/Octomap (binary or full data of an "OcTree", resolution,
 * data as int8 values) as the scene's octree line (scene.h), after the
 * '.'; absent or without data: nothing. The data is read here too, so
 * that a fault is named at its place in the YAML file.
 */
static int octomap(reader *R, yaml_node_t *world, text *t)
{
    yaml_node_t *ow = get(R, world, "octomap");
    if (ow == NULL)
        return 0;
    if (ow->type != YAML_MAPPING_NODE)
        return fail_at(R, ow, "octomap must be a mapping of origin and octomap");
    yaml_node_t *om = get(R, ow, "octomap");
    if (om == NULL || om->type != YAML_MAPPING_NODE)
        return fail_at(R, om ? om : ow, "octomap needs an 'octomap' mapping (binary, "
                       "id, resolution, data)");
    yaml_node_t *data = get(R, om, "data");
    if (data == NULL || count(data) == 0)
        return 0;
    if (data->type != YAML_SEQUENCE_NODE)
        return fail_at(R, data, "octomap data must be a list of int8 values");
    double p[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, res;
    yaml_node_t *origin = get(R, ow, "origin");
    if (origin != NULL && pose(R, origin, p, q) != 0)
        return -1;
    yaml_node_t *id = get(R, om, "id"), *bin = get(R, om, "binary");
    if (id != NULL && (scalar(id) == NULL || strcmp(scalar(id), "OcTree") != 0))
        return fail_at(R, id, "octomap id '%.40s' is not supported (only OcTree)",
                       scalar(id) ? scalar(id) : "");
    int binary = 1;
    if (bin != NULL) {
        const char *b = scalar(bin);
        if (b == NULL || (strcmp(b, "true") != 0 && strcmp(b, "false") != 0))
            return fail_at(R, bin, "octomap binary must be true or false");
        binary = strcmp(b, "true") == 0;
    }
    yaml_node_t *rn = get(R, om, "resolution");
    if (number(R, rn, "octomap resolution", &res) != 0)
        return -1;
    if (!(res >= MPB_OCTREE_MIN_RESOLUTION && res <= MPB_OCTREE_MAX_RESOLUTION))
        return fail_at(R, rn, "octomap resolution %g is outside %g .. %g m", res,
                       MPB_OCTREE_MIN_RESOLUTION, MPB_OCTREE_MAX_RESOLUTION);
    int n = count(data);
    unsigned char *bytes = malloc((size_t)n);
    if (bytes == NULL)
        return fail_at(R, data, "out of memory");
    for (int i = 0; i < n; i++) {
        yaml_node_t *v = item(R, data, i);
        double x;
        if (number(R, v, "octomap data value", &x) != 0 || x != floor(x) ||
            x < -128 || x > 255) {
            free(bytes);
            return R->failed ? -1 : fail_at(R, v, "octomap data value %d is not an "
                                            "int8", i);
        }
        bytes[i] = (unsigned char)(int)x;
    }
    char why[300];
    mpb_octree *o = NULL;
    if (mpb_octree_create_from_stream(bytes, (size_t)n, res, binary, "octomap data", &o, why,
                                      sizeof why) != MPB_OK) {
        free(bytes);
        return fail_at(R, data, "%s", why);
    }
    mpb_octree_destroy(o);
    char *b64 = NULL;
    if (mpb__base64_encode(bytes, (size_t)n, &b64, NULL) != MPB_OK) {
        free(bytes);
        return fail_at(R, data, "out of memory");
    }
    free(bytes);
    add(t, "octree octomap %s %.17g %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n",
        binary ? "binary" : "full", res, n, p[0], p[1], p[2], q[0], q[1], q[2], q[3]);
    add(t, "%s", b64);
    free(b64);
    return 0;
}

int mpbd_moveit_scene_read(const char *path, const char *name,
                           mpbd_moveit_scene *s, char *err, size_t errlen)
{
    reader R;
    text t = {0};
    char **ids = NULL;
    int nobj = 0, rc;
    memset(s, 0, sizeof *s);
    if ((rc = open_file(&R, path, err, errlen)) != MPB_OK)
        return rc;
    yaml_node_t *root = yaml_document_get_root_node(&R.doc);
    yaml_node_t *world = get(&R, root, "world");
    yaml_node_t *objs = get(&R, world, "collision_objects");
    if (world != NULL && world->type != YAML_MAPPING_NODE)
        fail_at(&R, world, "world must be a mapping");
    else if (list_or_none(&R, objs, "collision_objects") == 0 &&
             robot_state(&R, get(&R, root, "robot_state"), &s->state) == 0 &&
             acm(&R, get(&R, root, "allowed_collision_matrix"), s) == 0) {
        nobj = count(objs);
        ids = calloc((size_t)nobj + 1, sizeof *ids);
        if (ids == NULL)
            fail_at(&R, objs, "out of memory");
        add(&t, "%s\n", name);
        for (int i = 0; ids && i < nobj && !R.failed; i++)
            collision_object(&R, item(&R, objs, i), &t, ids, i);
        add(&t, ".\n");
        if (!R.failed)
            octomap(&R, world, &t);
        if (t.oom)
            fail_at(&R, NULL, "out of memory");
    }
    for (int i = 0; ids && i < nobj; i++)
        free(ids[i]);
    free(ids);
    yaml_document_delete(&R.doc);
    if (R.failed) {
        free(t.s);
        mpbd_moveit_scene_clear(s);
        return MPB_EPARSE;
    }
    s->text = t.s;
    s->num_objects = nobj;
    return MPB_OK;
}

void mpbd_moveit_scene_clear(mpbd_moveit_scene *s)
{
    if (s == NULL)
        return;
    free(s->text);
    for (int i = 0; i < 2 * s->num_pairs; i++)
        free(s->pairs[i]);
    free(s->pairs);
    free(s->pair_at);
    joints_clear(&s->state);
    memset(s, 0, sizeof *s);
}

/* ---- requests ---------------------------------------------------------- */

static int joint_goal(reader *R, yaml_node_t *list, mpbd_moveit_request *r)
{
    int n = count(list);
    mpbd_moveit_joints *g = &r->goal;
    r->goal_kind = MPB_GOAL_JOINTS;
    if (joints_alloc(R, list, g, n) != 0)
        return -1;
    r->tolerance_above = calloc((size_t)n + 1, sizeof *r->tolerance_above);
    r->tolerance_below = calloc((size_t)n + 1, sizeof *r->tolerance_below);
    if (!r->tolerance_above || !r->tolerance_below)
        return fail_at(R, list, "out of memory");
    for (int i = 0; i < n; i++) {
        yaml_node_t *c = item(R, list, i), *nn = get(R, c, "joint_name");
        const char *name = scalar(nn);
        if (name == NULL || name[0] == '\0')
            return fail_at(R, nn ? nn : c, "a joint constraint needs a "
                           "joint_name");
        if ((g->names[i] = strdup(name)) == NULL)
            return fail_at(R, nn, "out of memory");
        g->at[i] = mark_of(nn);
        g->n = i + 1;
        for (int k = 0; k < i; k++)
            if (strcmp(g->names[k], name) == 0)
                return fail_at(R, nn, "joint '%s' is constrained twice", name);
        if (get(R, c, "position") == NULL)
            return fail_at(R, c, "joint constraint on '%s' needs a 'position'",
                           name);
        if (number(R, get(R, c, "position"), "a joint constraint's position",
                   &g->values[i]) != 0)
            return -1;
        r->tolerance_above[i] = r->tolerance_below[i] = NAN;
        yaml_node_t *ta = get(R, c, "tolerance_above");
        yaml_node_t *tb = get(R, c, "tolerance_below");
        if ((ta && number(R, ta, "tolerance_above",
                          &r->tolerance_above[i]) != 0) ||
            (tb && number(R, tb, "tolerance_below",
                          &r->tolerance_below[i]) != 0))
            return -1;
        if ((ta && r->tolerance_above[i] < 0) ||
            (tb && r->tolerance_below[i] < 0))
            return fail_at(R, ta && r->tolerance_above[i] < 0 ? ta : tb,
                           "a tolerance must not be negative");
    }
    return 0;
}

/*
 * A position constraint (a box region around a point of the link) and an
 * orientation constraint (absolute axis tolerances) of the same link, as
 * mpbench's pose region: what cannot be said that way is refused.
 */
static int pose_goal(reader *R, yaml_node_t *c, mpbd_moveit_request *r)
{
    yaml_node_t *pcs = get(R, c, "position_constraints");
    yaml_node_t *ocs = get(R, c, "orientation_constraints");
    if (count(pcs) != 1)
        return fail_at(R, pcs ? pcs : c, "a pose goal needs exactly one "
                       "position constraint (mpbench's region is one box)");
    if (count(ocs) > 1)
        return fail_at(R, ocs, "a pose goal takes at most one orientation "
                       "constraint");
    yaml_node_t *pc = item(R, pcs, 0), *ln = get(R, pc, "link_name");
    if (scalar(ln) == NULL || scalar(ln)[0] == '\0')
        return fail_at(R, ln ? ln : pc, "a position constraint needs a "
                       "link_name");
    if ((r->link = strdup(scalar(ln))) == NULL)
        return fail_at(R, ln, "out of memory");
    r->link_at = mark_of(ln);
    yaml_node_t *off = get(R, pc, "target_point_offset");
    if (off != NULL) {
        double o[3];
        if (numbers(R, pc, off, "target_point_offset", XYZ, 3, o) != 0)
            return -1;
        if (o[0] != 0 || o[1] != 0 || o[2] != 0)
            return fail_at(R, off, "a target_point_offset other than 0 "
                           "cannot be mapped: the region holds the link's "
                           "origin");
    }
    yaml_node_t *reg = get(R, pc, "constraint_region");
    yaml_node_t *prims = get(R, reg, "primitives");
    yaml_node_t *poses = get(R, reg, "primitive_poses");
    if (count(prims) != 1 || count(poses) != 1 ||
        count(get(R, reg, "meshes")) != 0)
        return fail_at(R, reg ? reg : pc, "the constraint region must be "
                       "one box primitive with its pose");
    yaml_node_t *prim = item(R, prims, 0), *dims = get(R, prim, "dimensions");
    const char *type = scalar(get(R, prim, "type"));
    double d[3], q[4];
    if (type == NULL || (strcmp(type, "box") != 0 && strcmp(type, "1") != 0))
        return fail_at(R, prim, "the constraint region must be a box (a "
                       "sphere or cylinder cannot be mapped to mpbench's "
                       "box region)");
    if (numbers(R, prim, dims, "box dimensions", XYZ, 3, d) != 0 ||
        pose(R, item(R, poses, 0), r->position, q) != 0)
        return -1;
    if (fabs(fabs(q[3]) - 1.0) > 1e-9)
        return fail_at(R, item(R, poses, 0), "the constraint box must be "
                       "aligned with the frame's axes (orientation 0 0 0 1): "
                       "mpbench's region box is");
    for (int i = 0; i < 3; i++) {
        /* A box without volume holds no pose a planner can sample: every
         * run would fail in goal sampling. */
        if (!(d[i] > 0))
            return fail_at(R, dims, "box dimensions must be above 0 (a "
                           "region without volume holds no reachable "
                           "pose), not %g", d[i]);
        r->position_tolerance[i] = d[i] / 2;
        r->rpy_tolerance[i] = M_PI;
    }
    if (count(ocs) == 1) {
        yaml_node_t *oc = item(R, ocs, 0), *oln = get(R, oc, "link_name");
        if (scalar(oln) == NULL || strcmp(scalar(oln), r->link) != 0)
            return fail_at(R, oln ? oln : oc, "the orientation constraint "
                           "must be on the position constraint's link '%s'",
                           r->link);
        double oq[4];
        if (numbers(R, oc, get(R, oc, "orientation"), "orientation", XYZ, 4,
                    oq) != 0)
            return -1;
        double norm = sqrt(oq[0] * oq[0] + oq[1] * oq[1] + oq[2] * oq[2] +
                           oq[3] * oq[3]);
        /* As MoveIt's OrientationConstraint does: a quaternion whose norm
         * is off 1 by more than 1e-3 is "probably incorrect", and identity
         * is assumed instead, with a warning (the caller's). */
        if (fabs(norm - 1.0) > 1e-3) {
            r->orientation_identity = 1;
            r->orientation_at = mark_of(get(R, oc, "orientation"));
            oq[0] = oq[1] = oq[2] = 0;
            oq[3] = 1;
        }
        mpb_pose ref;
        mpb_pose_set_quat(&ref, oq[0], oq[1], oq[2], oq[3]);
        mpb_pose_get_rpy(&ref, r->rpy);
        static const char *const tol[] = {"absolute_x_axis_tolerance",
                                          "absolute_y_axis_tolerance",
                                          "absolute_z_axis_tolerance"};
        for (int i = 0; i < 3; i++) {
            yaml_node_t *tn = get(R, oc, tol[i]);
            if (tn == NULL)
                return fail_at(R, oc, "missing '%s'", tol[i]);
            if (number(R, tn, tol[i], &r->rpy_tolerance[i]) != 0)
                return -1;
            if (r->rpy_tolerance[i] < 0)
                return fail_at(R, tn, "%s must not be negative", tol[i]);
        }
    }
    r->goal_kind = MPB_GOAL_POSE_REGION;
    return 0;
}

int mpbd_moveit_request_read(const char *path, mpbd_moveit_request *r,
                             char *err, size_t errlen)
{
    reader R;
    int rc;
    memset(r, 0, sizeof *r);
    if ((rc = open_file(&R, path, err, errlen)) != MPB_OK)
        return rc;
    yaml_node_t *root = yaml_document_get_root_node(&R.doc);
    yaml_node_t *g = get(&R, root, "group_name");
    yaml_node_t *t = get(&R, root, "allowed_planning_time");
    yaml_node_t *goals = get(&R, root, "goal_constraints");
    if (g != NULL && scalar(g) == NULL)
        fail_at(&R, g, "group_name must be a name");
    else if (g != NULL && scalar(g)[0] != '\0' &&
             (r->group_name = strdup(scalar(g))) == NULL)
        fail_at(&R, g, "out of memory");
    if (g != NULL)
        r->group_at = mark_of(g);
    if (!R.failed && t != NULL &&
        number(&R, t, "allowed_planning_time", &r->allowed_planning_time) == 0
        && r->allowed_planning_time < 0)
        fail_at(&R, t, "allowed_planning_time must not be negative");
    r->start_at = (mpbd_mark){1, 1};
    if (get(&R, root, "start_state") != NULL)
        r->start_at = mark_of(get(&R, root, "start_state"));
    if (!R.failed)
        robot_state(&R, get(&R, root, "start_state"), &r->start);
    if (!R.failed && count(goals) != 1)
        fail_at(&R, goals ? goals : root, "goal_constraints must hold one "
                "goal (found %d): mpbench's query has one", count(goals));
    if (!R.failed) {
        yaml_node_t *c = item(&R, goals, 0);
        yaml_node_t *jc = get(&R, c, "joint_constraints");
        int pose = count(get(&R, c, "position_constraints")) +
                   count(get(&R, c, "orientation_constraints"));
        r->goal_at = mark_of(c);
        if (count(get(&R, c, "visibility_constraints")) > 0)
            fail_at(&R, get(&R, c, "visibility_constraints"), "visibility "
                    "constraints cannot be mapped to a goal");
        else if (count(jc) > 0 && pose > 0)
            fail_at(&R, c, "a goal of joint and pose constraints at once "
                    "cannot be mapped: give one kind");
        else if (count(jc) > 0)
            joint_goal(&R, jc, r);
        else if (pose > 0)
            pose_goal(&R, c, r);
        else
            fail_at(&R, c, "the goal has no joint or position constraints");
    }
    yaml_document_delete(&R.doc);
    if (R.failed) {
        mpbd_moveit_request_clear(r);
        return MPB_EPARSE;
    }
    return MPB_OK;
}

void mpbd_moveit_request_clear(mpbd_moveit_request *r)
{
    if (r == NULL)
        return;
    free(r->group_name);
    free(r->link);
    free(r->tolerance_above);
    free(r->tolerance_below);
    joints_clear(&r->start);
    joints_clear(&r->goal);
    memset(r, 0, sizeof *r);
}
