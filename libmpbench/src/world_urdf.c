/*
 * world_urdf.c - the "urdf" + "moveit-scene" world: a robot from URDF
 * (robot.h), a MoveIt .scene (scene.h), collision and distance through FCL
 * (collision.h). The planning group is named by its joints.
 *
 * Bodies in the collision world:
 *   movable id = link index        each link that moves with the group
 *   movable id = num_links + k     scene object k when attached to a link
 *   static id  = k                 scene object k
 *   static id  = ROBOT_STATIC + l  each robot link that does not move
 * Self-collision skips adjacent links and every pair already touching at
 * the reference configuration (all joints at the middle of their limits,
 * continuous ones at 0), the "default" pairs MoveIt's setup assistant
 * disables; robot links never collide with the robot's own static links
 * they are attached to.
 *
 * Mesh collision shapes are looked for in the directories of the
 * environment variable MPB_MESH_PATH (colon-separated).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpbench/collision.h"
#include "mpbench/robot.h"
#include "mpbench/scene.h"
#include "errbuf.h"
#include "world_provider.h"

#define ROBOT_STATIC 500000

typedef struct urdf_world {
    mpb_robot     *robot;
    mpb_scene     *scene;
    mpb_collision *coll;
    mpb_pose      *poses;        /* every link, robot frame */
    int            num_links;
    int           *moving;       /* links with shapes that move */
    int            num_moving;
    int           *attached;     /* scene objects attached to links */
    int           *attached_link;
    int            num_attached;
    mpb_mesh     **meshes;       /* loaded for the robot's mesh shapes */
    int            num_meshes;
    int            ee_link;      /* see mpb_world_ee_position() */
} urdf_world;

static void urdf_close(void *impl)
{
    urdf_world *u = impl;
    if (!u)
        return;
    mpb_collision_destroy(u->coll);
    mpb_scene_free(u->scene);
    mpb_robot_free(u->robot);
    for (int i = 0; i < u->num_meshes; i++)
        mpb_mesh_free(u->meshes[i]);
    free(u->meshes);
    free(u->poses);
    free(u->moving);
    free(u->attached);
    free(u->attached_link);
    free(u);
}

/* The directories of MPB_MESH_PATH, split in place in buf. */
static int mesh_dirs(char *buf, size_t len, const char **dirs, int max)
{
    const char *env = getenv("MPB_MESH_PATH");
    int n = 0;
    if (!env || !*env)
        return 0;
    snprintf(buf, len, "%s", env);
    for (char *s = strtok(buf, ":"); s && n < max; s = strtok(NULL, ":"))
        dirs[n++] = s;
    return n;
}

/* The geometry of a robot collision shape; loads a mesh if needed. */
static int shape_geometry(urdf_world *u, const mpb_robot_collision *c,
                          mpb_geometry *g, char *err, size_t errlen)
{
    memset(g, 0, sizeof *g);
    g->type = c->type;
    memcpy(g->dims, c->dims, sizeof g->dims);
    if (c->type != MPB_SHAPE_MESH)
        return MPB_OK;
    char buf[4096];
    const char *dirs[32];
    int nd = mesh_dirs(buf, sizeof buf, dirs, 32);
    mpb_mesh *m = NULL;
    mpb_mesh **grown = realloc(u->meshes, (size_t)(u->num_meshes + 1) * sizeof *grown);
    if (!grown)
        return MPB_ENOMEM;
    u->meshes = grown;
    int rc = mpb_mesh_load(c->mesh_uri, dirs, nd, c->mesh_scale, &m, err, errlen);
    if (rc != MPB_OK)
        return rc;
    u->meshes[u->num_meshes++] = m;
    g->mesh = m;
    return MPB_OK;
}

/* Every link's collision shapes into the collision world. */
static int add_robot(urdf_world *u, char *err, size_t errlen)
{
    const mpb_robot *r = u->robot;
    u->moving = calloc((size_t)u->num_links + 1, sizeof *u->moving);
    if (!u->moving)
        return MPB_ENOMEM;
    for (int l = 0; l < u->num_links; l++) {
        const mpb_robot_link *link = mpb_robot_get_link(r, l);
        for (int k = 0; k < link->num_collisions; k++) {
            const mpb_robot_collision *c =
                mpb_robot_get_collision(r, link->first_collision + k);
            mpb_geometry g;
            int rc = shape_geometry(u, c, &g, err, errlen);
            if (rc != MPB_OK)
                return rc;
            if (link->moves) {
                rc = mpb_collision_add_movable(u->coll, l, &g, &c->origin);
            } else {
                mpb_pose at;
                mpb_pose_mul(&u->poses[l], &c->origin, &at);
                rc = mpb_collision_add_static(u->coll, ROBOT_STATIC + l, &g, &at);
            }
            if (rc != MPB_OK) {
                mpb__set_err(err, errlen, "robot link '%s': %s", link->name,
                             mpb_collision_errmsg(u->coll));
                return rc;
            }
        }
        if (link->moves && link->num_collisions > 0)
            u->moving[u->num_moving++] = l;
    }
    /* A moving link may rest on the static link it hangs from, and on the
     * robot's other static links (the base it is mounted on). */
    for (int i = 0; i < u->num_moving; i++)
        for (int l = 0; l < u->num_links; l++)
            if (!mpb_robot_get_link(r, l)->moves &&
                mpb_robot_get_link(r, l)->num_collisions > 0)
                mpb_collision_allow_static(u->coll, u->moving[i], ROBOT_STATIC + l);
    return MPB_OK;
}

/* The moving link whose body carries link l's shapes: l itself if it has
 * shapes, else -1. */
static int is_moving_body(const urdf_world *u, int l)
{
    for (int i = 0; i < u->num_moving; i++)
        if (u->moving[i] == l)
            return 1;
    return 0;
}

static int add_scene(urdf_world *u, char *err, size_t errlen)
{
    int rc = mpb_scene_add_statics(u->scene, u->coll);
    if (rc != MPB_OK) {
        mpb__set_err(err, errlen, "scene: %s", mpb_collision_errmsg(u->coll));
        return rc;
    }
    int n = mpb_scene_num_objects(u->scene);
    u->attached = calloc((size_t)n + 1, sizeof *u->attached);
    u->attached_link = calloc((size_t)n + 1, sizeof *u->attached_link);
    if (!u->attached || !u->attached_link)
        return MPB_ENOMEM;
    for (int k = 0; k < n; k++) {
        const mpb_scene_object *o = mpb_scene_object_at(u->scene, k);
        if (!o->attached_link)
            continue;
        /* A fault in the attachment is on its attach line, if it has one. */
        int line = o->attach_line ? o->attach_line : o->line;
        int l = mpb_robot_link_index(u->robot, o->attached_link);
        if (l < 0) {
            mpb__set_err(err, errlen, "scene line %d: object '%s' is attached "
                         "to '%s', which is not a link of the robot", line,
                         o->id, o->attached_link);
            return MPB_EPARSE;
        }
        /* A misspelt touch link would leave a contact forbidden, unseen. */
        for (int t = 0; t < o->num_touch_links; t++)
            if (mpb_robot_link_index(u->robot, o->touch_links[t]) < 0) {
                mpb__set_err(err, errlen, "scene line %d: object '%s' may "
                             "touch '%s', which is not a link of the robot",
                             line, o->id, o->touch_links[t]);
                return MPB_EPARSE;
            }
        int id = u->num_links + k;
        for (int s = 0; s < o->num_shapes; s++) {
            mpb_pose at;
            mpb_pose_mul(&o->pose, &o->shapes[s].pose, &at);
            if ((rc = mpb_collision_add_movable(u->coll, id, &o->shapes[s].geometry,
                                                &at)) != MPB_OK) {
                mpb__set_err(err, errlen, "scene line %d: %s", o->line,
                             mpb_collision_errmsg(u->coll));
                return rc;
            }
        }
        if (o->num_shapes == 0)
            continue;
        if (is_moving_body(u, l))
            mpb_collision_allow_pair(u->coll, id, l);
        for (int t = 0; t < o->num_touch_links; t++) {
            int tl = mpb_robot_link_index(u->robot, o->touch_links[t]);
            if (is_moving_body(u, tl))
                mpb_collision_allow_pair(u->coll, id, tl);
        }
        u->attached[u->num_attached] = k;
        u->attached_link[u->num_attached++] = l;
    }
    return MPB_OK;
}

/* Place every moving body for configuration q. */
static int place(urdf_world *u, const double *q)
{
    if (mpb_robot_fk_moving(u->robot, q, u->poses) != MPB_OK)
        return MPB_EINVAL;
    for (int i = 0; i < u->num_moving; i++)
        mpb_collision_set_pose(u->coll, u->moving[i], &u->poses[u->moving[i]]);
    for (int i = 0; i < u->num_attached; i++)
        mpb_collision_set_pose(u->coll, u->num_links + u->attached[i],
                               &u->poses[u->attached_link[i]]);
    return MPB_OK;
}

/* Allow adjacent links, and every pair touching at the reference pose. */
static int allow_default_pairs(urdf_world *u, const double *ref)
{
    const mpb_robot *r = u->robot;
    for (int i = 0; i < u->num_moving; i++) {
        int l = u->moving[i];
        /* The nearest ancestor with shapes is its neighbour. */
        for (int p = mpb_robot_get_link(r, l)->parent; p >= 0;
             p = mpb_robot_get_link(r, p)->parent)
            if (mpb_robot_get_link(r, p)->num_collisions > 0) {
                if (is_moving_body(u, p))
                    mpb_collision_allow_pair(u->coll, l, p);
                break;
            }
    }
    if (place(u, ref) != MPB_OK)
        return MPB_EINVAL;
    int a, b, guard = 0, rc;
    while ((rc = mpb_collision_check_self(u->coll, &a, &b)) == 1 && guard++ < 10000)
        mpb_collision_allow_pair(u->coll, a, b);
    return rc < 0 ? rc : MPB_OK;
}

/* The chain's tip, followed down fixed joints while there is one child. */
static int find_ee_link(const mpb_robot *r)
{
    int l = mpb_robot_tip_link(r), n = mpb_robot_num_links(r);
    for (;;) {
        int child = -1, count = 0;
        for (int k = 0; k < n; k++) {
            const mpb_robot_link *c = mpb_robot_get_link(r, k);
            if (c->parent == l) {
                count++;
                child = c->joint_type == MPB_JOINT_FIXED ? k : -1;
            }
        }
        if (count != 1 || child < 0)
            return l;
        l = child;
    }
}

static int urdf_open(mpb_world *w, const char *robot_text,
                     const char *scene_text, const char *const *joints,
                     int num_joints, char *err, size_t errlen)
{
    urdf_world *u = calloc(1, sizeof *u);
    int rc;
    if (!u)
        return MPB_ENOMEM;
    w->impl = u;
    if (joints == NULL || num_joints < 1) {
        mpb__set_err(err, errlen, "robot: a urdf world needs the joints of "
                     "its planning group");
        return MPB_EINVAL;
    }
    if ((rc = mpb_robot_load_urdf_joints(robot_text, joints, num_joints,
                                         &u->robot, err, errlen)) != MPB_OK)
        return rc;
    if ((rc = mpb_scene_parse(scene_text, &u->scene, err, errlen)) != MPB_OK)
        return rc;
    if ((rc = mpb_collision_create(&u->coll)) != MPB_OK)
        return rc;
    u->num_links = mpb_robot_num_links(u->robot);
    u->ee_link = find_ee_link(u->robot);
    u->poses = calloc((size_t)u->num_links + 1, sizeof *u->poses);
    double *ref = calloc((size_t)num_joints, sizeof *ref);
    if (!u->poses || !ref) {
        free(ref);
        return MPB_ENOMEM;
    }
    for (int j = 0; j < num_joints; j++) {
        const mpb_robot_joint *jt = mpb_robot_get_joint(u->robot, j);
        ref[j] = jt->type == MPB_JOINT_CONTINUOUS ? 0.0 : 0.5 * (jt->lo + jt->hi);
        rc = mpb__world_add_joint(w, jt->name, strlen(jt->name), jt->lo, jt->hi,
                                  jt->type == MPB_JOINT_CONTINUOUS);
        if (rc != MPB_OK) {
            free(ref);
            return rc;
        }
    }
    /* Static links' poses, once. */
    rc = mpb_robot_fk(u->robot, ref, u->poses);
    if (rc == MPB_OK)
        rc = add_robot(u, err, errlen);
    if (rc == MPB_OK)
        rc = add_scene(u, err, errlen);
    if (rc == MPB_OK)
        rc = allow_default_pairs(u, ref);
    free(ref);
    return rc;
}

static int urdf_in_collision(void *impl, const double *q)
{
    urdf_world *u = impl;
    if (place(u, q) != MPB_OK)
        return 1;
    if (mpb_collision_check(u->coll, NULL, NULL) != 0)
        return 1;   /* a collision, or an error: not known to be free */
    return mpb_collision_check_self(u->coll, NULL, NULL) != 0;
}

static double urdf_clearance(void *impl, const double *q)
{
    urdf_world *u = impl;
    mpb_collision_distance_result d;
    if (place(u, q) != MPB_OK ||
        mpb_collision_distance(u->coll, 0, &d) != MPB_OK)
        return NAN;
    return d.distance;
}

static int urdf_goal_region(void *impl, const mpb_goal *g, const double *q,
                            char *detail, size_t len)
{
    urdf_world *u = impl;
    mpb_goal_region region = {0};
    mpb_goal_distance dist;
    char why[160];
    region.link = g->link ? mpb_robot_link_index(u->robot, g->link) : -1;
    if (region.link < 0) {
        mpb__set_err(detail, len, "goal link '%.60s' is not a link of the "
                     "robot", g->link ? g->link : "");
        return MPB_EINVAL;
    }
    for (int i = 0; i < 3; i++) {
        region.center[i] = g->position[i];
        region.half_extents[i] = g->position_tolerance[i];
        region.ref_rpy[i] = g->orientation_rpy[i];
        region.rpy_tolerance[i] = g->orientation_tolerance[i];
    }
    if (mpb_goal_region_check(u->robot, &region, why, sizeof why) != MPB_OK) {
        mpb__set_err(detail, len, "goal region: %s", why);
        return MPB_EINVAL;
    }
    if (mpb_goal_region_distance(u->robot, &region, q, &dist) != MPB_OK)
        return MPB_EINVAL;
    if (dist.position == 0 && dist.orientation == 0)
        return 1;
    mpb__set_err(detail, len, "link '%.40s' is %.4g m outside the goal box "
                 "and %.4g rad outside the orientation tolerance", g->link,
                 dist.position, dist.orientation);
    return 0;
}

static void urdf_ee_position(void *impl, const double *q, double xyz[3])
{
    urdf_world *u = impl;
    mpb_pose p;
    mpb_robot_link_pose(u->robot, q, u->ee_link, &p);
    memcpy(xyz, p.t, sizeof p.t);
}

const mpb__world_provider mpb__world_urdf = {
    .robot_format = "urdf",
    .scene_format = "moveit-scene",
    .open         = urdf_open,
    .close        = urdf_close,
    .in_collision = urdf_in_collision,
    .clearance    = urdf_clearance,
    .goal_region  = urdf_goal_region,
    .ee_position  = urdf_ee_position,
};

struct mpb_collision *mpb__urdf_collision(mpb_world *w)
{
    if (!w || w->provider != &mpb__world_urdf || !w->impl)
        return NULL;
    return ((urdf_world *)w->impl)->coll;
}

int mpb__urdf_get_model(mpb_world *w, mpb__urdf_model *out)
{
    if (!w || !out || w->provider != &mpb__world_urdf || !w->impl)
        return MPB_EINVAL;
    urdf_world *u = w->impl;
    *out = (mpb__urdf_model){u->robot, u->scene, u->coll, u->meshes,
                             u->num_meshes, ROBOT_STATIC};
    return MPB_OK;
}
