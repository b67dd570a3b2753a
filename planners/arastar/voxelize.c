/* voxelize.c - obstacle cells of the BFS grid by octree subdivision with FCL. */
#include <stdio.h>
#include <stdlib.h>

#include "mpbench/mpbench.h"
#include "mpbench/collision.h"
#include "voxelize.h"

/* Robot static links go in as statics above the scene's object ids. */
#define ROBOT_STATIC_BASE 500000

static int add_robot_statics(mpb_collision *c, const mpb_robot *r,
                             const double *q)
{
    int nl = mpb_robot_num_links(r);
    mpb_pose *poses = malloc((size_t)nl * sizeof *poses);
    if (!poses)
        return MPB_ENOMEM;
    int rc = mpb_robot_fk(r, q, poses);
    for (int i = 0; rc == MPB_OK && i < mpb_robot_num_collisions(r); i++) {
        const mpb_robot_collision *rc_ = mpb_robot_get_collision(r, i);
        const mpb_robot_link *l = mpb_robot_get_link(r, rc_->link);
        if (l->moves || rc_->type == MPB_SHAPE_MESH)
            continue;           /* meshes would need loading; rare on bases */
        mpb_geometry geo = {rc_->type, {rc_->dims[0], rc_->dims[1],
                            rc_->dims[2], rc_->dims[3]}, NULL};
        mpb_pose p;
        mpb_pose_mul(&poses[rc_->link], &rc_->origin, &p);
        rc = mpb_collision_add_static(c, ROBOT_STATIC_BASE + rc_->link,
                                      &geo, &p);
    }
    free(poses);
    return rc;
}

typedef struct octree {
    ara_grid      *g;
    mpb_collision *c;
    long           tests;
    int            error;
} octree;

/* Block of `size` cells (level id = log2 size) with corner cell x,y,z. */
static void test_block(octree *o, int x, int y, int z, int size, int level)
{
    if (o->error)
        return;
    const ara_grid *g = o->g;
    mpb_pose p;
    mpb_pose_identity(&p);
    p.t[0] = g->origin[0] + (x + size / 2.0) * g->cell;
    p.t[1] = g->origin[1] + (y + size / 2.0) * g->cell;
    p.t[2] = g->origin[2] + (z + size / 2.0) * g->cell;
    mpb_collision_set_pose(o->c, level, &p);
    mpb_collision_set_enabled(o->c, level, 1);
    int hit = mpb_collision_check(o->c, NULL, NULL);
    mpb_collision_set_enabled(o->c, level, 0);
    o->tests++;
    if (hit < 0) {
        o->error = hit;
        return;
    }
    if (!hit)
        return;
    if (size == 1) {
        o->g->blocked[ara_grid_index(g, x, y, z)] = 1;
        return;
    }
    int h = size / 2;
    for (int i = 0; i < 8; i++)
        test_block(o, x + (i & 1) * h, y + ((i >> 1) & 1) * h,
                   z + ((i >> 2) & 1) * h, h, level - 1);
}

long ara_voxelize(ara_grid *g, const mpb_scene *scene, const mpb_robot *robot,
                  const double *q, char *err, size_t errlen)
{
    int n = g->nx, levels = 0;
    if (n != g->ny || n != g->nz || n <= 0 || (n & (n - 1)) != 0) {
        snprintf(err, errlen, "voxel grid must be a cube of 2^k cells");
        return MPB_EINVAL;
    }
    while ((1 << levels) < n)
        levels++;
    mpb_collision *c = NULL;
    int rc = mpb_collision_create(&c);
    if (rc == MPB_OK && scene)
        rc = mpb_scene_add_statics(scene, c);
    if (rc == MPB_OK && robot)
        rc = add_robot_statics(c, robot, q);
    /* One box body per block size; only the one being tested is enabled. */
    for (int l = 0; rc == MPB_OK && l <= levels; l++) {
        double side = (double)(1 << l) * g->cell;
        mpb_geometry box = {MPB_SHAPE_BOX, {side, side, side, 0}, NULL};
        rc = mpb_collision_add_movable(c, l, &box, NULL);
        if (rc == MPB_OK)
            rc = mpb_collision_set_enabled(c, l, 0);
    }
    if (rc != MPB_OK) {
        snprintf(err, errlen, "voxel grid: %s", mpb_collision_errmsg(c));
        mpb_collision_destroy(c);
        return rc;
    }
    octree o = {g, c, 0, 0};
    test_block(&o, 0, 0, 0, n, levels);
    mpb_collision_destroy(c);
    if (o.error) {
        snprintf(err, errlen, "voxel grid: collision check failed (%s)",
                 mpb_strerror(o.error));
        return o.error;
    }
    return o.tests;
}
