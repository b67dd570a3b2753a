/*
 * bfs_grid.h - a 3-D voxel grid of the workspace: which cells obstacles
 * block, and the breadth-first distance (26-connected, in cells) of every
 * free cell from a goal cell. The search's heuristic reads the distance of
 * the end-effector's cell.
 */
#ifndef ARASTAR_BFS_GRID_H
#define ARASTAR_BFS_GRID_H

#include <stdint.h>

#define ARA_BFS_UNREACHED INT32_MAX

typedef struct ara_grid {
    int      nx, ny, nz;
    double   origin[3];     /* corner of cell (0,0,0), robot frame (m) */
    double   cell;          /* side length (m) */
    uint8_t *blocked;       /* nx*ny*nz, 1 where an obstacle is */
    int32_t *dist;          /* BFS distance in cells, ARA_BFS_UNREACHED */
} ara_grid;

/* A grid of free cells; 0, or -1 for bad sizes / out of memory. */
int  ara_grid_init(ara_grid *g, int nx, int ny, int nz,
                   const double origin[3], double cell);
void ara_grid_free(ara_grid *g);

static inline long ara_grid_index(const ara_grid *g, int x, int y, int z)
{
    return ((long)z * g->ny + y) * g->nx + x;
}

/* The cell holding point p; 0, or -1 when p is outside the grid. */
int ara_grid_cell_of(const ara_grid *g, const double p[3], int c[3]);

/*
 * Breadth-first search from cell `from` (which counts as free even if
 * blocked: a goal touching an obstacle must still be reachable) through
 * free cells, 26-connected. Fills dist; returns the number of cells
 * reached, or -1 out of memory / `from` outside.
 */
long ara_grid_bfs(ara_grid *g, const int from[3]);

/* The distance of the cell holding p, in cells (ARA_BFS_UNREACHED if none). */
int32_t ara_grid_distance_at(const ara_grid *g, const double p[3]);

#endif
