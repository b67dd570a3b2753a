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
 * MoveIt's setup assistant does (acm_generate()). Pairs of fixed links
 * never change and are never checked.
 *
 * Mesh collision shapes (package://NAME/path, relative paths) are looked
 * for in the folders of MPB_MESH_PATH, then of ROS_PACKAGE_PATH (each
 * colon-separated; a folder holds NAME/ or is NAME itself), all of them,
 * then in the URDF's folder when the caller names it.
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
#include "geometry/collision_internal.h"
#include "core/errbuf.h"
#include "geometry/mesh_cache.h"
#include "model/srdf_xml.h"
#include "model/world_provider.h"
#include "geometry/wrist_table.h"

/* The reasons a pair is allowed, as MoveIt's setup assistant writes them. */
static const char REASON_ADJACENT[] = "Adjacent";
static const char REASON_DEFAULT[] = "Default";
static const char REASON_ALWAYS[] = "Always";
static const char REASON_NEVER[] = "Never";

/* The setup assistant's batch for "Always" pairs (its SMALL_TRIAL_COUNT). */
#define ACM_BATCH 200

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
    const mpb_mesh **meshes;     /* the robot's mesh shapes, shared by
                                    every world (mesh_cache.h) */
    int            num_meshes;
    int            ee_link;      /* see mpb_world_ee_position() */
    const char   **allowed;      /* num_links^2: why link a may touch b,
                                    NULL where it may not */
    int           *pairs;        /* the allowed pairs a < b, 2 a pair, in
                                    order of a then b */
    int            num_pairs;
    mpb_srdf      *srdf;         /* the SRDF, or NULL; owns its reasons */
    int            from_srdf;    /* 1 if the ACM came from an SRDF */
    const char    *robot_dir;    /* the URDF's folder, or NULL */
    char          *robot_dir_copy; /* owned: for a rebuild after open */
    int            acm_stale;    /* generated ACM: not built for the values
                                    held now; built before the next check */
    int            acm_in_coll;  /* coll holds a built ACM's pairs */
    struct wrist_pair {          /* self pairs a wrist table may prove
                                    apart (wrist_table.h) */
        int near, far, joint[2];
        const mpb__wrist_table *table;  /* the cache's */
    }             *wrist;
    int            num_wrist;
} urdf_world;

static void urdf_close(void *impl)
{
    urdf_world *u = impl;
    if (!u)
        return;
    mpb_srdf_free(u->srdf);     /* it borrows the robot's names */
    mpb_collision_destroy(u->coll);
    mpb_scene_free(u->scene);
    mpb_robot_free(u->robot);
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

/* Where meshes are looked for: the folders of MPB_MESH_PATH, then those
 * of ROS_PACKAGE_PATH, as many as they hold, then the URDF's folder when
 * the caller gave it. */
typedef struct mesh_search {
    char        *buf[2];      /* copies of the two variables, split */
    const char **dirs;
    int          num_dirs;
    int          from_env[2]; /* how many came from each */
    const char  *robot_dir;   /* the URDF's folder, last; or NULL */
} mesh_search;

static const char *const mesh_vars[2] = {"MPB_MESH_PATH", "ROS_PACKAGE_PATH"};

static void mesh_search_free(mesh_search *m)
{
    free(m->buf[0]);
    free(m->buf[1]);
    free(m->dirs);
}

static int mesh_search_init(mesh_search *m, const char *robot_dir)
{
    memset(m, 0, sizeof *m);
    size_t cap = 2;
    for (int v = 0; v < 2; v++) {
        const char *env = getenv(mesh_vars[v]);
        if (!env)
            continue;
        if (!(m->buf[v] = strdup(env)))
            return MPB_ENOMEM;
        for (const char *c = env; *c; c++)
            cap += *c == ':';
        cap++;
    }
    if (!(m->dirs = calloc(cap, sizeof *m->dirs)))
        return MPB_ENOMEM;
    for (int v = 0; v < 2; v++) {
        char *save = NULL;
        for (char *d = m->buf[v] ? strtok_r(m->buf[v], ":", &save) : NULL; d;
             d = strtok_r(NULL, ":", &save)) {
            m->dirs[m->num_dirs++] = d;
            m->from_env[v]++;
        }
    }
    if (robot_dir && *robot_dir)
        m->dirs[m->num_dirs++] = m->robot_dir = robot_dir;
    return MPB_OK;
}

/* After a mesh was not found: the variables and the folders tried, the
 * first few of each, into err after what mpb_mesh_load() said. */
static void mesh_not_found(const mesh_search *m, char *err, size_t errlen)
{
    char what[1024];
    size_t n = 0;
    int first = 0;
    n += (size_t)snprintf(what + n, sizeof what - n, "; looked in");
    for (int v = 0; v < 2; v++) {
        int k = m->from_env[v];
        n += (size_t)snprintf(what + n, n < sizeof what ? sizeof what - n : 0,
                              "%s %s (", v ? " and" : "", mesh_vars[v]);
        if (k == 0)
            n += (size_t)snprintf(what + n, n < sizeof what ? sizeof what - n : 0,
                                  "%s", getenv(mesh_vars[v]) ? "empty" : "not set");
        for (int i = 0; i < k && i < 3; i++)
            n += (size_t)snprintf(what + n, n < sizeof what ? sizeof what - n : 0,
                                  "%s%s", i ? ", " : "", m->dirs[first + i]);
        if (k > 3)
            n += (size_t)snprintf(what + n, n < sizeof what ? sizeof what - n : 0,
                                  " and %d more: %d folders", k - 3, k);
        n += (size_t)snprintf(what + n, n < sizeof what ? sizeof what - n : 0, ")");
        first += k;
    }
    if (m->robot_dir)
        n += (size_t)snprintf(what + n, n < sizeof what ? sizeof what - n : 0,
                              " and the URDF's folder (%s)", m->robot_dir);
    size_t len = strlen(err);
    if (len < errlen)
        mpb__set_err(err + len, errlen - len, "%s", what);
}

/* The geometry of a robot collision shape; loads a mesh if needed. */
static int shape_geometry(urdf_world *u, const mesh_search *ms,
                          const mpb_robot_collision *c, mpb_geometry *g,
                          char *err, size_t errlen)
{
    memset(g, 0, sizeof *g);
    g->type = c->type;
    memcpy(g->dims, c->dims, sizeof g->dims);
    if (c->type != MPB_SHAPE_MESH)
        return MPB_OK;
    const mpb_mesh *m = NULL;
    const mpb_mesh **grown = realloc(u->meshes, (size_t)(u->num_meshes + 1) *
                                                sizeof *grown);
    if (!grown)
        return MPB_ENOMEM;
    u->meshes = grown;
    int rc = mpb__mesh_load_shared(c->mesh_uri, ms->dirs, ms->num_dirs,
                                   c->mesh_scale, &m, err, errlen);
    if (rc == MPB_ENOTFOUND)
        mesh_not_found(ms, err, errlen);
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
    mesh_search ms;
    u->moving = calloc((size_t)u->num_links + 1, sizeof *u->moving);
    if (!u->moving)
        return MPB_ENOMEM;
    if (mesh_search_init(&ms, u->robot_dir) != MPB_OK) {
        mesh_search_free(&ms);
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
                rc = mpb_collision_set_self_only(u->coll, l, 1);
            if (rc != MPB_OK)
                mpb__set_err(err, errlen, "robot link '%s': %s", link->name,
                             mpb_collision_errmsg(u->coll));
        }
        if (rc == MPB_OK && link->moves && link->num_collisions > 0)
            u->moving[u->num_moving++] = l;
    }
    mesh_search_free(&ms);
    return rc;
}

/* Is link l a body of the collision world (has it shapes)? */
static int has_body(const urdf_world *u, int l)
{
    return l >= 0 && mpb_robot_get_link(u->robot, l)->num_collisions > 0;
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
            mpb_collision_allow_pair(u->coll, id, l);
        for (int t = 0; t < o->num_touch_links; t++) {
            int tl = mpb_robot_link_index(u->robot, o->touch_links[t]);
            if (has_body(u, tl))
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

/* After place(): the wrist pairs their tables prove apart at q, as hints
 * for the next self check (they lapse with the next placing). */
static void hint_wrists(urdf_world *u, const double *q)
{
    for (int i = 0; i < u->num_wrist; i++) {
        const struct wrist_pair *w = &u->wrist[i];
        if (mpb__wrist_table_apart(w->table, q[w->joint[0]],
                                   w->joint[1] >= 0 ? q[w->joint[1]] : 0.0))
            mpb__collision_hint_apart(u->coll, w->near, w->far);
    }
}

/* ---- the allowed-collision matrix ------------------------------------ */

static const char **acm_at(urdf_world *u, int a, int b)
{
    return &u->allowed[(size_t)a * (size_t)u->num_links + (size_t)b];
}

/* Allow the pair (a, b) for `reason`, unless it is allowed already. */
static void acm_allow(urdf_world *u, int a, int b, const char *reason)
{
    if (a == b || *acm_at(u, a, b))
        return;
    *acm_at(u, a, b) = *acm_at(u, b, a) = reason;
}

/*
 * Adjacent links, as MoveIt's setup assistant finds them: parent and child
 * are connected, whatever the joint (fixed ones too); then, again and
 * again until nothing changes, every two links connected to a link without
 * shapes are connected to each other. Adjacent are the connected pairs of
 * links that both have shapes.
 */
static int acm_adjacent(urdf_world *u)
{
    int n = u->num_links;
    unsigned char *g = calloc((size_t)n * (size_t)n + 1, 1);
    if (!g)
        return MPB_ENOMEM;
    for (int l = 0; l < n; l++) {
        int p = mpb_robot_get_link(u->robot, l)->parent;
        if (p >= 0)
            g[(size_t)l * n + p] = g[(size_t)p * n + l] = 1;
    }
    for (int changed = 1; changed;) {
        changed = 0;
        for (int l = 0; l < n; l++) {
            if (has_body(u, l))
                continue;
            for (int i = 0; i < n; i++)
                for (int j = i + 1; g[(size_t)l * n + i] && j < n; j++)
                    if (g[(size_t)l * n + j] && i != j && !g[(size_t)i * n + j]) {
                        g[(size_t)i * n + j] = g[(size_t)j * n + i] = 1;
                        changed = 1;
                    }
        }
    }
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++)
            if (g[(size_t)i * n + j] && has_body(u, i) && has_body(u, j))
                acm_allow(u, i, j, REASON_ADJACENT);
    free(g);
    return MPB_OK;
}

/*
 * MoveIt's default state: each joint at 0 when 0 is within its limits,
 * else at the middle of them (RobotState::setToDefaultValues()).
 */
static void default_state(const mpb_robot *r, double *q)
{
    for (int j = 0; j < mpb_robot_num_joints(r); j++) {
        const mpb_robot_joint *jt = mpb_robot_get_joint(r, j);
        int zero_ok = jt->type == MPB_JOINT_CONTINUOUS ||
                      (jt->lo <= 0.0 && 0.0 <= jt->hi);
        q[j] = zero_ok ? 0.0 : 0.5 * (jt->lo + jt->hi);
    }
}

/*
 * The rest of MoveIt's setup assistant's matrix, after the adjacent pairs:
 * the pairs in collision at the default state ("Default"), the pairs in
 * collision nearly always ("Always"), then the pairs never in collision in
 * MPB_WORLD_ACM_SAMPLES random states ("Never"), all drawn from a fixed
 * seed. Pairs of fixed links are decided by the default state alone: they
 * never move.
 */
static int acm_generate(urdf_world *u, const double *q0)
{
    const mpb_robot *r = u->robot;
    int n = u->num_links, nj = mpb_robot_num_joints(r), rc = MPB_OK;
    int *cand = malloc(((size_t)n * (size_t)n + 1) * 2 * sizeof *cand);
    int *count = NULL;
    unsigned char *seen = NULL;
    double *q = malloc(((size_t)nj + 1) * sizeof *q);
    if (!cand || !q) {
        free(cand);
        free(q);
        return MPB_ENOMEM;
    }
    if (place(u, q0) != MPB_OK) {
        rc = MPB_EINVAL;
        goto done;
    }
    int nc = 0;
    for (int a = 0; a < n; a++)
        for (int b = a + 1; has_body(u, a) && b < n; b++) {
            if (!has_body(u, b) || *acm_at(u, a, b))
                continue;
            int hit = mpb_collision_check_pair(u->coll, a, b);
            if (hit < 0) {
                rc = hit;
                goto done;
            }
            const mpb_robot_link *la = mpb_robot_get_link(r, a);
            const mpb_robot_link *lb = mpb_robot_get_link(r, b);
            if (hit)
                acm_allow(u, a, b, REASON_DEFAULT);
            else if (!la->moves && !lb->moves)
                acm_allow(u, a, b, REASON_NEVER);
            else {
                cand[2 * nc] = a;
                cand[2 * nc + 1] = b;
                nc++;
            }
        }
    uint64_t rng = MPB_WORLD_ACM_SEED;
    /* "Always": batches of ACM_BATCH random states; a pair in collision in
     * more than 95 % of a batch is allowed, until a batch allows none.
     * A pair seen in collision here is no "Never" pair. */
    count = calloc((size_t)nc + 1, sizeof *count);
    seen = calloc((size_t)nc + 1, 1);
    if (!count || !seen) {
        rc = MPB_ENOMEM;
        goto done;
    }
    for (int found = 1; found && nc > 0;) {
        memset(count, 0, (size_t)nc * sizeof *count);
        for (int s = 0; s < ACM_BATCH; s++) {
            mpb_robot_random_config(r, &rng, q);
            if (place(u, q) != MPB_OK) {
                rc = MPB_EINVAL;
                goto done;
            }
            for (int i = 0; i < nc; i++) {
                int hit = mpb_collision_check_pair(u->coll, cand[2 * i],
                                                   cand[2 * i + 1]);
                if (hit < 0) {
                    rc = hit;
                    goto done;
                }
                count[i] += hit;
                seen[i] |= (unsigned char)hit;
            }
        }
        found = 0;
        for (int i = 0; i < nc;) {
            if (count[i] * 100 <= ACM_BATCH * 95) {
                i++;
                continue;
            }
            acm_allow(u, cand[2 * i], cand[2 * i + 1], REASON_ALWAYS);
            found = 1;
            nc--;
            cand[2 * i] = cand[2 * nc];
            cand[2 * i + 1] = cand[2 * nc + 1];
            count[i] = count[nc];
            seen[i] = seen[nc];
        }
    }
    for (int i = 0; i < nc;) {
        if (!seen[i]) {
            i++;
            continue;
        }
        nc--;
        cand[2 * i] = cand[2 * nc];
        cand[2 * i + 1] = cand[2 * nc + 1];
        seen[i] = seen[nc];
    }
    /* "Never": each pair seen in collision leaves the candidates. */
    for (int s = 0; s < MPB_WORLD_ACM_SAMPLES && nc > 0; s++) {
        mpb_robot_random_config(r, &rng, q);
        if (place(u, q) != MPB_OK) {
            rc = MPB_EINVAL;
            goto done;
        }
        for (int i = 0; i < nc;) {
            int hit = mpb_collision_check_pair(u->coll, cand[2 * i], cand[2 * i + 1]);
            if (hit < 0) {
                rc = hit;
                goto done;
            }
            if (hit) {
                nc--;
                cand[2 * i] = cand[2 * nc];
                cand[2 * i + 1] = cand[2 * nc + 1];
            } else {
                i++;
            }
        }
    }
    for (int i = 0; i < nc; i++)
        acm_allow(u, cand[2 * i], cand[2 * i + 1], REASON_NEVER);
done:
    free(cand);
    free(count);
    free(seen);
    free(q);
    return rc;
}

/* The SRDF's pairs; those naming a link the robot lacks are skipped, as
 * MoveIt does (mpb_srdf_skipped_pairs() says which, for a warning). */
static void acm_from_srdf(urdf_world *u)
{
    const mpb__srdf *raw = mpb__srdf_raw(u->srdf);
    for (int i = 0; i < raw->num_pairs; i++) {
        const mpb__srdf_pair *p = &raw->pairs[i];
        int a = mpb_robot_link_index(u->robot, p->link1);
        int b = mpb_robot_link_index(u->robot, p->link2);
        if (a >= 0 && b >= 0)
            acm_allow(u, a, b, p->reason);
    }
}

/* Link l's shapes as the collision world holds them: geoms and offsets
 * (room for its num_collisions), meshes from u->meshes, which add_robot()
 * filled in the order of the robot's shapes. */
static void link_shapes(const urdf_world *u, int l, mpb_geometry *geoms,
                        mpb_pose *offsets)
{
    const mpb_robot_link *link = mpb_robot_get_link(u->robot, l);
    int mesh = 0;
    for (int i = 0; i < link->first_collision; i++)
        mesh += mpb_robot_get_collision(u->robot, i)->type == MPB_SHAPE_MESH;
    for (int k = 0; k < link->num_collisions; k++) {
        const mpb_robot_collision *c =
            mpb_robot_get_collision(u->robot, link->first_collision + k);
        memset(&geoms[k], 0, sizeof geoms[k]);
        geoms[k].type = c->type;
        memcpy(geoms[k].dims, c->dims, sizeof geoms[k].dims);
        if (c->type == MPB_SHAPE_MESH)
            geoms[k].mesh = u->meshes[mesh++];
        offsets[k] = c->origin;
    }
}

/* The pair (near, far), which qualifies for a table with spec's
 * kinematics: its table into u->wrist. */
static int add_wrist(urdf_world *u, int near, int far, const int joint[2],
                     mpb__wrist_spec *spec)
{
    int ends[2] = {near, far}, n[2], rc = MPB_OK;
    mpb_geometry *geoms[2] = {NULL, NULL};
    mpb_pose *offsets[2] = {NULL, NULL};
    for (int s = 0; s < 2; s++) {
        n[s] = mpb_robot_get_link(u->robot, ends[s])->num_collisions;
        geoms[s] = calloc((size_t)n[s], sizeof *geoms[s]);
        offsets[s] = calloc((size_t)n[s], sizeof *offsets[s]);
        if (!geoms[s] || !offsets[s]) {
            rc = MPB_ENOMEM;
            goto done;
        }
        link_shapes(u, ends[s], geoms[s], offsets[s]);
        spec->side[s] = (mpb__wrist_side){n[s], geoms[s], offsets[s]};
    }
    if (!mpb__wrist_affordable(spec))
        goto done;      /* FCL decides the pair, as without tables */
    struct wrist_pair *grown = realloc(u->wrist, (size_t)(u->num_wrist + 1) *
                                                 sizeof *grown);
    if (!grown) {
        rc = MPB_ENOMEM;
        goto done;
    }
    u->wrist = grown;
    struct wrist_pair *w = &u->wrist[u->num_wrist];
    *w = (struct wrist_pair){near, far, {joint[0], joint[1]}, NULL};
    if ((rc = mpb__wrist_table_get(spec, &w->table)) == MPB_OK)
        u->num_wrist++;
done:
    for (int s = 0; s < 2; s++) {
        free(geoms[s]);
        free(offsets[s]);
    }
    return rc;
}

/* Has link l a mesh among its shapes? */
static int has_mesh(const urdf_world *u, int l)
{
    const mpb_robot_link *link = mpb_robot_get_link(u->robot, l);
    for (int k = 0; k < link->num_collisions; k++)
        if (mpb_robot_get_collision(u->robot, link->first_collision + k)->type ==
            MPB_SHAPE_MESH)
            return 1;
    return 0;
}

/*
 * The self pairs a wrist table may prove apart (wrist_table.h): not
 * allowed, both links with shapes, one of them a mesh, one the other's
 * ancestor across one or two revolute joints (mpb__wrist_path() says
 * which qualify). Primitives are left out: their narrow phase costs about
 * what a look-up does (the PR2's arm has three such pairs: 12.1k
 * instructions a check with tables, 11.5k without). After the matrix,
 * which decides the pairs; the tables come from the process-wide cache,
 * built once.
 */
static int find_wrists(urdf_world *u)
{
    int n = u->num_links, rc = MPB_OK;
    u->num_wrist = 0;
    mpb_pose *poses = calloc((size_t)n + 1, sizeof *poses);
    double *q0 = calloc((size_t)mpb_robot_num_joints(u->robot) + 1, sizeof *q0);
    if (!poses || !q0) {
        rc = MPB_ENOMEM;
        goto done;
    }
    default_state(u->robot, q0);
    if (mpb_robot_fk(u->robot, q0, poses) != MPB_OK) {
        rc = MPB_EINVAL;
        goto done;
    }
    for (int a = 0; a < n && rc == MPB_OK; a++)
        for (int b = a + 1; has_body(u, a) && b < n && rc == MPB_OK; b++) {
            int joint[2];
            mpb__wrist_spec spec;
            /* an ancestor has the smaller index (robot.h) */
            if (has_body(u, b) && !*acm_at(u, a, b) &&
                (has_mesh(u, a) || has_mesh(u, b)) &&
                mpb__wrist_path(u->robot, poses, a, b, joint, &spec))
                rc = add_wrist(u, a, b, joint, &spec);
        }
done:
    free(poses);
    free(q0);
    return rc;
}

/*
 * Build the matrix (from the SRDF, or generated), list its pairs, and let
 * the collision world skip them, and every pair of fixed links; then the
 * wrist tables of the pairs left.
 */
static int build_acm(urdf_world *u, const double *q0, char *err, size_t errlen)
{
    int n = u->num_links, rc;
    u->allowed = calloc((size_t)n * (size_t)n + 1, sizeof *u->allowed);
    if (!u->allowed)
        return MPB_ENOMEM;
    if (u->from_srdf)
        acm_from_srdf(u);
    if ((rc = acm_adjacent(u)) != MPB_OK)
        return rc;
    if (!u->from_srdf && (rc = acm_generate(u, q0)) != MPB_OK) {
        mpb__set_err(err, errlen, "robot: self-collision matrix: %s",
                     mpb_collision_errmsg(u->coll));
        return rc;
    }
    u->pairs = malloc(((size_t)n * (size_t)n + 1) * sizeof *u->pairs);
    if (!u->pairs)
        return MPB_ENOMEM;
    u->acm_in_coll = 1;
    for (int a = 0; a < n; a++)
        for (int b = a + 1; b < n; b++) {
            int fixed = !mpb_robot_get_link(u->robot, a)->moves &&
                        !mpb_robot_get_link(u->robot, b)->moves;
            if (*acm_at(u, a, b)) {
                u->pairs[2 * u->num_pairs] = a;
                u->pairs[2 * u->num_pairs + 1] = b;
                u->num_pairs++;
            }
            if ((*acm_at(u, a, b) || fixed) && has_body(u, a) && has_body(u, b) &&
                (rc = mpb_collision_allow_pair(u->coll, a, b)) != MPB_OK)
                return rc;
        }
    if ((rc = find_wrists(u)) != MPB_OK)
        mpb__set_err(err, errlen, "robot: wrist tables: %s",
                     rc == MPB_ENOMEM ? "out of memory" : "FCL failed");
    return rc;
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
        u->num_meshes = 0;
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
    default_state(u->robot, q0);
    char err[512];
    rc = build_acm(u, q0, err, sizeof err);
    free(q0);
    if (rc == MPB_OK)
        u->acm_stale = 0;
    return rc;
}

/*
 * The robot text is a URDF, perhaps followed by an SRDF: the SRDF begins
 * on the line after the one where the URDF's root element ends (its first
 * "</robot>" outside comments), or right after it if more follows on that
 * line. *urdf_len is the URDF's length, *srdf the SRDF's text or NULL when
 * only blanks and comments follow.
 */
static void split_srdf(const char *text, size_t *urdf_len, const char **srdf)
{
    const char *p = text;
    *urdf_len = strlen(text);
    *srdf = NULL;
    while (*p) {
        if (strncmp(p, "<!--", 4) == 0) {
            const char *e = strstr(p + 4, "-->");
            if (!e)
                return;
            p = e + 3;
        } else if (strncmp(p, "</robot", 7) == 0 && (p[7] == '>' ||
                   p[7] == ' ' || p[7] == '\t' || p[7] == '\r' || p[7] == '\n')) {
            const char *e = strchr(p, '>');
            if (!e)
                return;
            /* The next line, or right after the tag if more follows on
             * its line. */
            const char *start = e + 1;
            while (*start == ' ' || *start == '\t' || *start == '\r')
                start++;
            start = *start == '\n' ? start + 1 : e + 1;
            *urdf_len = (size_t)(start - text);
            /* An SRDF only if an element follows, not just comments. */
            for (const char *t = start; *t; t++) {
                if (strncmp(t, "<!--", 4) == 0) {
                    const char *ce = strstr(t + 4, "-->");
                    if (!ce)
                        break;
                    t = ce + 2;
                } else if (*t == '<') {
                    *srdf = start;
                    return;
                }
            }
            return;
        } else {
            p++;
        }
    }
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
    size_t urdf_len;
    const char *srdf;
    split_srdf(robot_text, &urdf_len, &srdf);
    if (srdf) {
        char why[512];
        mpb__srdf raw;
        if ((rc = mpb__srdf_parse(srdf, &raw, why, sizeof why)) != MPB_OK) {
            mpb__set_err(err, errlen, "srdf %s", why);
            return rc;
        }
        u->from_srdf = 1;
        char *urdf = strndup(robot_text, urdf_len);
        if (!urdf) {
            mpb__srdf_clear(&raw);
            return MPB_ENOMEM;
        }
        rc = mpb_robot_load_urdf_joints(urdf, joints, num_joints, &u->robot,
                                        err, errlen);
        free(urdf);
        if (rc != MPB_OK) {
            mpb__srdf_clear(&raw);
            return rc;
        }
        /* Its names checked against the robot, as mpb_srdf_load() does. */
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
        rc = mpb_robot_load_urdf_joints(robot_text, joints, num_joints,
                                        &u->robot, err, errlen);
    }
    if (rc != MPB_OK)
        return rc;
    if ((rc = mpb_scene_parse(scene_text, &u->scene, err, errlen)) != MPB_OK)
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
    default_state(u->robot, q0);
    for (int j = 0; j < num_joints; j++) {
        const mpb_robot_joint *jt = mpb_robot_get_joint(u->robot, j);
        rc = mpb__world_add_joint(w, jt->name, strlen(jt->name), jt->lo, jt->hi,
                                  jt->type == MPB_JOINT_CONTINUOUS);
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
        rc = build_acm(u, q0, err, errlen);
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
    if (place(u, q) != MPB_OK)
        return 1;
    hint_wrists(u, q);
    if (mpb_collision_check(u->coll, NULL, NULL) != 0)
        return 1;   /* a collision, or an error: not known to be free */
    return mpb_collision_check_self(u->coll, NULL, NULL) != 0;
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
    if (place(u, q) != MPB_OK)
        return MPB_EINVAL;
    hint_wrists(u, q);
    if ((hit = mpb_collision_check(u->coll, &m, &st)) != 0) {
        if (hit < 0)
            return hit;
        const mpb_scene_object *o = mpb_scene_object_at(u->scene, st);
        const char *name = body_name(u, m, &ka);
        mpb__set_err(what, len, "%s%s touches scene object %s", ka, name,
                     o ? o->id : "?");
        return 1;
    }
    if ((hit = mpb_collision_check_self(u->coll, &a, &b)) != 0) {
        if (hit < 0)
            return hit;
        const char *na = body_name(u, a, &ka), *nb = body_name(u, b, &kb);
        mpb__set_err(what, len, "self-collision between %s%s and %s%s", ka, na,
                     kb, nb);
        return 1;
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
    default_state(u->robot, q0);
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

/* Certified verification's step from q along d (world_sweep.c). */
static int urdf_safe_step(void *impl, const double *q, const double *d,
                          double margin, double want, double *step)
{
    urdf_world *u = impl;
    if (ensure_acm(u) != MPB_OK || place(u, q) != MPB_OK)
        return MPB_EINVAL;
    return mpb__urdf_safe_step(u->robot, u->coll, u->poses, u->attached,
                               u->attached_link, u->num_attached, d, margin,
                               want, step);
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
    .contact      = urdf_contact,
    .num_allowed  = urdf_num_allowed,
    .allowed_pair = urdf_allowed_pair,
    .hold         = urdf_hold,
    .held         = urdf_held,
    .safe_step    = urdf_safe_step,
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
    const struct wrist_pair *p = &((urdf_world *)w->impl)->wrist[i];
    *near = p->near;
    *far = p->far;
    joint[0] = p->joint[0];
    joint[1] = p->joint[1];
    *table = p->table;
    return MPB_OK;
}
