/*
 * voxelize.h - mark the cells of a grid that obstacles touch: the scene's
 * objects and the robot's own links that do not move with the arm (base,
 * torso), so the end-effector's BFS goes round them too.
 */
#ifndef ARASTAR_VOXELIZE_H
#define ARASTAR_VOXELIZE_H

#include "bfs_grid.h"
#include "mpbench/robot.h"
#include "mpbench/scene.h"

/*
 * Fill g->blocked from scene (may be NULL) and the static links of robot
 * (may be NULL; q is any configuration of its group). g must be a cube of
 * n x n x n cells, n a power of two: blocks of cells are tested against
 * the obstacles with FCL, and only blocks that touch something are split
 * into eight, so free space costs little. Returns the number of box tests
 * made (>= 0), or a negative MPB_E code with one line in err.
 */
long ara_voxelize(ara_grid *g, const mpb_scene *scene, const mpb_robot *robot,
                  const double *q, char *err, size_t errlen);

#endif
