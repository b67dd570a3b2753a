/*
 * world_urdf.c - the "urdf" + "moveit-scene" world: a robot from URDF
 * (robot.h), a MoveIt .scene (scene.h), collision and distance through FCL
 * (collision.h). The planning group is named by its joints.
 *
 * Bodies in the collision world:
 *   movable id = link index        each link with shapes; the links that
 *                                  do not move are placed once and are
 *                                  self-only (no part of the clearance)
 *   movable id = num_links + k     scene object k when attached to a link
 *   static id  = k                 scene object k
 * Self-collision is MoveIt's: every pair of links is checked, the moving
 * against the fixed ones too, unless the allowed-collision matrix (ACM)
 * allows it. The ACM is the SRDF's <disable_collisions> pairs plus the
 * adjacent links when the robot text carries an SRDF, else generated as
 * MoveIt's setup assistant does (acm.c). Pairs of fixed links never
 * change and are never checked; wrist tables prove some pairs apart
 * before FCL looks (wrist_hints.c).
 *
 * Mesh collision shapes (package://NAME/path, relative paths) are looked
 * for in the folders of MPB_MESH_PATH, then of ROS_PACKAGE_PATH (each
 * colon-separated; a folder holds NAME/ or is NAME itself), all of them,
 * then in the URDF's folder when the caller names it (mesh_search.c).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpbench/collision.h"
#include "mpbench/robot.h"
#include "mpbench/scene.h"
#include "mpbench/srdf.h"
#include "core/errbuf.h"
#include "geometry/collision_internal.h"
#include "core/grow.h"
#include "geometry/mesh_cache.h"
#include "model/srdf_xml.h"
#include "model/world_provider.h"
#include "model/world_urdf.h"

static void urdf_close(void *impl)
{
    urdf_world *u = impl;
    if (!u)
        return;
    mpb_srdf_close(u->srdf);     /* it borrows the robot's names */
    mpb__sweep_free(u->sweep);
    mpb_collision_destroy(u->coll);
    mpb_scene_close(u->scene);
    mpb_robot_close(u->robot);
    for (int i = 0; i < u->num_meshes; i++)
        mpb__mesh_release(u->meshes[i]);
    free(u->meshes);
    free(u->poses);
    free(u->moving);
    free(u->attached);
    free(u->attached_link);
    free(u->allowed);
    free(u->pairs);
    free(u->robot_dir_copy);
    free(u->wrist);
    free(u);
}

/* The geometry of a robot collision shape; loads a mesh if needed. */
static int shape_geometry(urdf_world *u, const mpb__mesh_search *ms,
                          const mpb_robot_collision *c, mpb_geometry *g,
                          char *err, size_t errlen)
{
    memset(g, 0, sizeof *g);
    g->type = c->type;
    memcpy(g->dims, c->dims, sizeof g->dims);
    if (c->type != MPB_SHAPE_MESH)
        return MPB_OK;
    const mpb_mesh *m = NULL;
    if (mpb__grow((void **)&u->meshes, &u->cap_meshes, u->num_meshes + 1,
                  sizeof *u->meshes) != MPB_OK)
        return MPB_ENOMEM;
    int rc = mpb__mesh_load_shared(c->mesh_uri, ms->dirs, ms->num_dirs,
                                   c->mesh_scale, &m, err, errlen);
    if (rc == MPB_ENOTFOUND)
        mpb__mesh_not_found(ms, err, errlen);
    if (rc != MPB_OK)
        return rc;
    u->meshes[u->num_meshes++] = m;
    g->mesh = m;
    return MPB_OK;
}

/* Every link's collision shapes into the collision world: each link with
 * shapes is a movable body; those that do not move stand where the static
 * poses put them and take part in self checks only. */
static int add_robot(urdf_world *u, char *err, size_t errlen)
{
    const mpb_robot *r = u->robot;
    mpb__mesh_search ms;
    u->moving = calloc((size_t)u->num_links + 1, sizeof *u->moving);
    if (!u->moving)
        return MPB_ENOMEM;
    if (mpb__mesh_search_init(&ms, u->robot_dir) != MPB_OK) {
        mpb__mesh_search_free(&ms);
        return MPB_ENOMEM;
    }
    int rc = MPB_OK;
    for (int l = 0; l < u->num_links && rc == MPB_OK; l++) {
        const mpb_robot_link *link = mpb_robot_get_link(r, l);
        for (int k = 0; k < link->num_collisions && rc == MPB_OK; k++) {
            const mpb_robot_collision *c =
                mpb_robot_get_collision(r, link->first_collision + k);
            mpb_geometry g;
            rc = shape_geometry(u, &ms, c, &g, err, errlen);
            if (rc != MPB_OK)
                break;
            rc = mpb_collision_add_movable(u->coll, l, &g, &c->origin);
            if (rc != MPB_OK)
                mpb__set_err(err, errlen, "robot link '%s': %s", link->name,
                             mpb_collision_errmsg(u->coll));
        }
        if (rc == MPB_OK && link->num_collisions > 0 && !link->moves) {
            rc = mpb_collision_set_pose(u->coll, l, &u->poses[l]);
            if (rc == MPB_OK)
                rc = mpb__collision_set_self_only(u->coll, l, 1);
            if (rc != MPB_OK)
                mpb__set_err(err, errlen, "robot link '%s': %s", link->name,
                             mpb_collision_errmsg(u->coll));
        }
        if (rc == MPB_OK && link->moves && link->num_collisions > 0)
            u->moving[u->num_moving++] = l;
    }
    mpb__mesh_search_free(&ms);
    return rc;
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
        if (has_body(u, l))
            mpb__collision_allow_pair(u->coll, id, l);
        for (int t = 0; t < o->num_touch_links; t++) {
            int tl = mpb_robot_link_index(u->robot, o->touch_links[t]);
            if (has_body(u, tl))
                mpb__collision_allow_pair(u->coll, id, tl);
        }
        u->attached[u->num_attached] = k;
        u->attached_link[u->num_attached++] = l;
    }
    return MPB_OK;
}

int mpb__urdf_place(urdf_world *u, const double *q)
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

void mpb__urdf_default_state(const mpb_robot *r, double *q)
{
    for (int j = 0; j < mpb_robot_num_joints(r); j++) {
        const mpb_robot_joint *jt = mpb_robot_get_joint(r, j);
        int zero_ok = jt->type == MPB_JOINT_CONTINUOUS ||
                      (jt->lo <= 0.0 && 0.0 <= jt->hi);
        q[j] = zero_ok ? 0.0 : 0.5 * (jt->lo + jt->hi);
    }
}

/*
 * A generated matrix depends on the values the joints outside the group
 * hold (the default state and every sampled state keep them): built
 * lazily, before the first check after opening or after mpb_world_hold()
 * changed a value. The collision world cannot forget allowed pairs, so
 * when it holds those of an earlier matrix it is made again (the robot's
 * meshes taken again from the mesh cache, mesh_cache.h).
 */
static int ensure_acm(urdf_world *u)
{
    if (!u->acm_stale)
        return MPB_OK;
    int rc;
    if (u->acm_in_coll) {
        /* The old collision world and meshes are let go only after the
         * new ones are made, so that the caches hand the same meshes and
         * BVH models back instead of reading and building them again. */
        mpb_collision *old_coll = u->coll;
        const mpb_mesh **old_meshes = u->meshes;
        int old_num_meshes = u->num_meshes;
        u->coll = NULL;
        u->meshes = NULL;
        u->num_meshes = u->cap_meshes = 0;
        free(u->moving);
        u->moving = NULL;
        u->num_moving = 0;
        free(u->attached);
        free(u->attached_link);
        u->attached = u->attached_link = NULL;
        u->num_attached = 0;
        u->acm_in_coll = 0;
        char err[512];
        u->robot_dir = u->robot_dir_copy;
        rc = mpb_collision_create(&u->coll);
        if (rc == MPB_OK)
            rc = add_robot(u, err, sizeof err);
        if (rc == MPB_OK)
            rc = add_scene(u, err, sizeof err);
        u->robot_dir = NULL;
        mpb_collision_destroy(old_coll);
        for (int i = 0; i < old_num_meshes; i++)
            mpb__mesh_release(old_meshes[i]);
        free(old_meshes);
        if (rc != MPB_OK)
            return rc;
    }
    free(u->allowed);
    free(u->pairs);
    u->allowed = NULL;
    u->pairs = NULL;
    u->num_pairs = 0;
    double *q0 = calloc((size_t)mpb_robot_num_joints(u->robot) + 1, sizeof *q0);
    if (!q0)
        return MPB_ENOMEM;
    mpb__urdf_default_state(u->robot, q0);
    char err[512];
    rc = mpb__urdf_build_acm(u, q0, err, sizeof err);
    free(q0);
    if (rc == MPB_OK)
        u->acm_stale = 0;
    return rc;
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
    u->robot_dir = w->robot_dir;
    if (joints == NULL || num_joints < 1) {
        mpb__set_err(err, errlen, "robot: a urdf world needs the joints of "
                     "its planning group");
        return MPB_EINVAL;
    }
    size_t urdf_len, srdf_at;
    const char *srdf = NULL;
    if ((rc = mpb_robot_text_split(robot_text, &urdf_len, &srdf_at)) != MPB_OK)
        return rc;
    if (robot_text[srdf_at] != '\0')
        srdf = robot_text + srdf_at;
    if (srdf) {
        char why[512];
        mpb__srdf raw;
        if ((rc = mpb__srdf_parse_cached(srdf, &raw, why, sizeof why)) != MPB_OK) {
            mpb__set_err(err, errlen, "srdf %s", why);
            return rc;
        }
        u->from_srdf = 1;
        char *urdf = strndup(robot_text, urdf_len);
        if (!urdf) {
            mpb__srdf_clear(&raw);
            return MPB_ENOMEM;
        }
        rc = mpb_robot_open_urdf_joints(urdf, joints, num_joints, &u->robot,
                                        err, errlen);
        free(urdf);
        if (rc != MPB_OK) {
            mpb__srdf_clear(&raw);
            return rc;
        }
        /* Its names checked against the robot, as mpb_srdf_open() does. */
        if ((rc = mpb__srdf_bind_robot(&raw, u->robot, &u->srdf, why,
                                       sizeof why)) != MPB_OK) {
            mpb__set_err(err, errlen, "srdf %s", why);
            return rc;
        }
        for (int j = 0; j < num_joints; j++) {
            int line = mpb_srdf_is_passive(u->srdf, joints[j]);
            if (line) {
                mpb__set_err(err, errlen, "srdf line %d: joint '%.80s' is "
                             "passive; a passive joint cannot be in the group",
                             line, joints[j]);
                return MPB_EPARSE;
            }
        }
    } else {
        rc = mpb_robot_open_urdf_joints(robot_text, joints, num_joints,
                                        &u->robot, err, errlen);
    }
    if (rc != MPB_OK)
        return rc;
    if ((rc = mpb_scene_open_text(scene_text, &u->scene, err, errlen)) != MPB_OK)
        return rc;
    if ((rc = mpb_collision_create(&u->coll)) != MPB_OK)
        return rc;
    u->num_links = mpb_robot_num_links(u->robot);
    u->ee_link = find_ee_link(u->robot);
    u->poses = calloc((size_t)u->num_links + 1, sizeof *u->poses);
    double *q0 = calloc((size_t)num_joints, sizeof *q0);
    if (!u->poses || !q0) {
        free(q0);
        return MPB_ENOMEM;
    }
    mpb__urdf_default_state(u->robot, q0);
    for (int j = 0; j < num_joints; j++) {
        const mpb_robot_joint *jt = mpb_robot_get_joint(u->robot, j);
        rc = mpb__world_add_joint(w, jt->name, strlen(jt->name), jt->lo, jt->hi,
                                  jt->type == MPB_JOINT_CONTINUOUS,
                                  jt->max_velocity);
        if (rc != MPB_OK) {
            free(q0);
            return rc;
        }
    }
    /* Static links' poses, once. */
    rc = mpb_robot_fk(u->robot, q0, u->poses);
    if (rc == MPB_OK)
        rc = add_robot(u, err, errlen);
    /* A generated matrix waits for the held values (ensure_acm()). */
    if (rc == MPB_OK && u->from_srdf)
        rc = mpb__urdf_build_acm(u, q0, err, errlen);
    u->acm_stale = !u->from_srdf;
    if (rc == MPB_OK)
        rc = add_scene(u, err, errlen);
    free(q0);
    if (rc == MPB_OK && u->robot_dir && !u->from_srdf &&
        !(u->robot_dir_copy = strdup(u->robot_dir)))
        rc = MPB_ENOMEM;
    u->robot_dir = NULL;
    return rc;
}

static int urdf_in_collision(void *impl, const double *q)
{
    urdf_world *u = impl;
    if (ensure_acm(u) != MPB_OK)
        return 1;       /* not known to be free */
    if (mpb__urdf_place(u, q) != MPB_OK)
        return 1;
    mpb__urdf_hint_wrists(u, q);
    if (mpb_collision_check(u->coll, NULL, NULL) != 0)
        return 1;   /* a collision, or an error: not known to be free */
    return mpb__collision_check_self(u->coll, NULL, NULL) != 0;
}

/* A body of the collision world by name: a link, or an attached object. */
static const char *body_name(const urdf_world *u, int movable, const char **kind)
{
    *kind = "";
    if (movable >= 0 && movable < u->num_links)
        return mpb_robot_get_link(u->robot, movable)->name;
    *kind = "attached object ";
    const mpb_scene_object *o = mpb_scene_object_at(u->scene, movable - u->num_links);
    return o ? o->id : "?";
}

static int urdf_contact(void *impl, const double *q, char *what, size_t len)
{
    urdf_world *u = impl;
    int m, st, a, b, hit;
    const char *ka, *kb;
    if ((hit = ensure_acm(u)) != MPB_OK) {
        mpb__set_err(what, len, "self-collision matrix: %s",
                     u->coll ? mpb_collision_errmsg(u->coll) : "out of memory");
        return hit;
    }
    if (mpb__urdf_place(u, q) != MPB_OK)
        return MPB_EINVAL;
    mpb__urdf_hint_wrists(u, q);
    if ((hit = mpb_collision_check(u->coll, &m, &st)) != 0) {
        if (hit < 0)
            return hit;
        const mpb_scene_object *o = mpb_scene_object_at(u->scene, st);
        const char *name = body_name(u, m, &ka);
        mpb__set_err(what, len, "%s%s touches scene object %s", ka, name,
                     o ? o->id : "?");
        return MPB_CONTACT_SCENE;
    }
    if ((hit = mpb__collision_check_self(u->coll, &a, &b)) != 0) {
        if (hit < 0)
            return hit;
        const char *na = body_name(u, a, &ka), *nb = body_name(u, b, &kb);
        mpb__set_err(what, len, "self-collision between %s%s and %s%s", ka, na,
                     kb, nb);
        return MPB_CONTACT_SELF;
    }
    return 0;
}

static int urdf_held(void *impl, const char *joint, double *value, double *lo,
                     double *hi)
{
    urdf_world *u = impl;
    return mpb_robot_get_passive(u->robot, joint, value, lo, hi);
}

/* Hold the joints, then put the links that do not move where they now
 * are (a PR2's torso lifts the arm's base with it). */
static int urdf_hold(void *impl, const char *const *joints,
                     const double *values, int n, char *err, size_t errlen)
{
    urdf_world *u = impl;
    int rc = MPB_OK;
    for (int i = 0; i < n && rc == MPB_OK; i++) {
        double lo, hi, was;
        const char *j = joints[i] ? joints[i] : "";
        rc = mpb_robot_get_passive(u->robot, j, &was, &lo, &hi);
        if (rc == MPB_ENOTFOUND)
            mpb__set_err(err, errlen, "joint '%s' is not a joint of the robot",
                         j);
        else if (rc != MPB_OK && mpb_robot_joint_index(u->robot, j) >= 0)
            mpb__set_err(err, errlen, "joint '%s' is in the planning group: "
                         "its value is the start's, not a held one", j);
        else if (rc != MPB_OK)
            mpb__set_err(err, errlen, "joint '%s' cannot hold a value (a "
                         "fixed, floating or planar joint)", j);
        else if ((rc = mpb_robot_set_passive(u->robot, j, values[i])) != MPB_OK)
            mpb__set_err(err, errlen, "joint '%s' = %g is outside its limits "
                         "[%g, %g]", j, values[i], lo, hi);
        else if (values[i] != was && !u->from_srdf)
            u->acm_stale = 1;   /* the generated matrix, again */
    }
    double *q0 = calloc((size_t)mpb_robot_num_joints(u->robot) + 1, sizeof *q0);
    if (!q0)
        return MPB_ENOMEM;
    mpb__urdf_default_state(u->robot, q0);
    if (mpb_robot_fk(u->robot, q0, u->poses) == MPB_OK)
        for (int l = 0; l < u->num_links; l++)
            if (has_body(u, l) && !mpb_robot_get_link(u->robot, l)->moves)
                mpb_collision_set_pose(u->coll, l, &u->poses[l]);
    free(q0);
    return rc;
}

static int urdf_num_allowed(void *impl)
{
    urdf_world *u = impl;
    if (ensure_acm(u) != MPB_OK)
        return 0;
    return u->num_pairs;
}

static int urdf_allowed_pair(void *impl, int i, mpb_world_acm_pair *out)
{
    urdf_world *u = impl;
    int rc = ensure_acm(u);
    if (rc != MPB_OK)
        return rc;
    if (i < 0 || i >= u->num_pairs)
        return MPB_EINVAL;
    int a = u->pairs[2 * i], b = u->pairs[2 * i + 1];
    out->link1 = mpb_robot_get_link(u->robot, a)->name;
    out->link2 = mpb_robot_get_link(u->robot, b)->name;
    out->reason = *acm_at(u, a, b);
    out->from_srdf = u->from_srdf;
    return MPB_OK;
}

static double urdf_clearance(void *impl, const double *q)
{
    urdf_world *u = impl;
    mpb_collision_distance_result d;
    if (mpb__urdf_place(u, q) != MPB_OK ||
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

/* The end effector along a segment (mpb__robot_link_sweep()). */
static int urdf_ee_sweep(void *impl, const double *a, const double *d,
                         int steps, int first, int count, double *xyz)
{
    urdf_world *u = impl;
    return mpb__robot_link_sweep(u->robot, u->ee_link, a, d, steps, first,
                                 count, xyz);
}

/* Certified verification's step from q along d (world_sweep.c). */
static int urdf_safe_step(void *impl, const double *q, const double *d,
                          double margin, double want, double moved,
                          double *step)
{
    urdf_world *u = impl;
    if (!u->sweep && !(u->sweep = mpb__sweep_new()))
        return MPB_ENOMEM;
    if (ensure_acm(u) != MPB_OK || mpb__urdf_place(u, q) != MPB_OK)
        return MPB_EINVAL;
    return mpb__urdf_safe_step(u->robot, u->coll, u->poses, u->attached,
                               u->attached_link, u->num_attached, u->sweep,
                               moved, d, margin, want, step);
}

/* How deep the robot at q collides (mpb__collision_depth()). */
static int urdf_depth(void *impl, const double *q, double floor,
                      double *lower, double *upper)
{
    urdf_world *u = impl;
    mpb__collision_depth_result r;
    int rc = ensure_acm(u);
    if (rc == MPB_OK)
        rc = mpb__urdf_place(u, q);
    if (rc == MPB_OK)
        rc = mpb__collision_depth(u->coll, floor, &r);
    if (rc != MPB_OK)
        return rc;
    *lower = r.lower;
    *upper = r.upper;
    return MPB_OK;
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
    .ee_sweep     = urdf_ee_sweep,
    .contact      = urdf_contact,
    .num_allowed  = urdf_num_allowed,
    .allowed_pair = urdf_allowed_pair,
    .hold         = urdf_hold,
    .held         = urdf_held,
    .safe_step    = urdf_safe_step,
    .depth        = urdf_depth,
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
    /* The matrix for the values held now: a rebuild later would remake
     * the collision world and its meshes under the caller. */
    int rc = ensure_acm(u);
    if (rc != MPB_OK)
        return rc;
    *out = (mpb__urdf_model){u->robot, u->scene, u->coll, u->meshes,
                             u->num_meshes};
    return MPB_OK;
}

int mpb__urdf_num_wrists(mpb_world *w)
{
    if (!w || w->provider != &mpb__world_urdf || !w->impl)
        return 0;
    urdf_world *u = w->impl;
    return ensure_acm(u) == MPB_OK ? u->num_wrist : 0;
}

int mpb__urdf_wrist(mpb_world *w, int i, int *near, int *far, int joint[2],
                    const mpb__wrist_table **table)
{
    if (i < 0 || i >= mpb__urdf_num_wrists(w))
        return MPB_EINVAL;
    const struct urdf_wrist *p = &((urdf_world *)w->impl)->wrist[i];
    *near = p->near;
    *far = p->far;
    joint[0] = p->joint[0];
    joint[1] = p->joint[1];
    *table = p->table;
    return MPB_OK;
}
