/*
 * wrist_hints.c - the wrist tables of a "urdf" world (wrist_table.h):
 * which self pairs get one, and, for each check, the pairs the tables
 * prove apart at q, handed to the collision world as hints.
 */
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "core/grow.h"
#include "geometry/collision_internal.h"
#include "model/world_urdf.h"

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
    if (mpb__grow((void **)&u->wrist, &u->cap_wrist, u->num_wrist + 1,
                  sizeof *u->wrist) != MPB_OK) {
        rc = MPB_ENOMEM;
        goto done;
    }
    struct urdf_wrist *w = &u->wrist[u->num_wrist];
    *w = (struct urdf_wrist){near, far, {joint[0], joint[1]}, NULL};
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
int mpb__urdf_find_wrists(urdf_world *u)
{
    int n = u->num_links, rc = MPB_OK;
    u->num_wrist = 0;
    mpb_pose *poses = calloc((size_t)n + 1, sizeof *poses);
    double *q0 = calloc((size_t)mpb_robot_num_joints(u->robot) + 1, sizeof *q0);
    if (!poses || !q0) {
        rc = MPB_ENOMEM;
        goto done;
    }
    mpb__urdf_default_state(u->robot, q0);
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

void mpb__urdf_hint_wrists(urdf_world *u, const double *q)
{
    for (int i = 0; i < u->num_wrist; i++) {
        const struct urdf_wrist *w = &u->wrist[i];
        if (mpb__wrist_table_apart(w->table, q[w->joint[0]],
                                   w->joint[1] >= 0 ? q[w->joint[1]] : 0.0))
            mpb__collision_hint_apart(u->coll, w->near, w->far);
    }
}
