/* bfs_grid.c - voxel grid and 3-D breadth-first search for the heuristic. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bfs_grid.h"

int ara_grid_init(ara_grid *g, int nx, int ny, int nz,
                  const double origin[3], double cell)
{
    memset(g, 0, sizeof *g);
    if (nx <= 0 || ny <= 0 || nz <= 0 || !(cell > 0) ||
        (double)nx * ny * nz > 1e8)
        return -1;
    size_t n = (size_t)nx * (size_t)ny * (size_t)nz;
    g->blocked = calloc(n, 1);
    g->dist = malloc(n * sizeof *g->dist);
    if (!g->blocked || !g->dist) {
        ara_grid_free(g);
        return -1;
    }
    g->nx = nx;
    g->ny = ny;
    g->nz = nz;
    memcpy(g->origin, origin, sizeof g->origin);
    g->cell = cell;
    for (size_t i = 0; i < n; i++)
        g->dist[i] = ARA_BFS_UNREACHED;
    return 0;
}

void ara_grid_free(ara_grid *g)
{
    free(g->blocked);
    free(g->dist);
    memset(g, 0, sizeof *g);
}

int ara_grid_cell_of(const ara_grid *g, const double p[3], int c[3])
{
    const int n[3] = {g->nx, g->ny, g->nz};
    for (int i = 0; i < 3; i++) {
        double f = floor((p[i] - g->origin[i]) / g->cell);
        if (!(f >= 0 && f < n[i]))
            return -1;
        c[i] = (int)f;
    }
    return 0;
}

long ara_grid_bfs(ara_grid *g, const int from[3])
{
    size_t n = (size_t)g->nx * (size_t)g->ny * (size_t)g->nz;
    if (from[0] < 0 || from[0] >= g->nx || from[1] < 0 || from[1] >= g->ny ||
        from[2] < 0 || from[2] >= g->nz)
        return -1;
    int32_t *queue = malloc(n * sizeof *queue);   /* each cell enters once */
    if (!queue)
        return -1;
    for (size_t i = 0; i < n; i++)
        g->dist[i] = ARA_BFS_UNREACHED;
    long head = 0, tail = 0;
    long start = ara_grid_index(g, from[0], from[1], from[2]);
    g->dist[start] = 0;
    queue[tail++] = (int32_t)start;
    while (head < tail) {
        long i = queue[head++];
        int x = (int)(i % g->nx), y = (int)((i / g->nx) % g->ny),
            z = (int)(i / ((long)g->nx * g->ny));
        int32_t d = g->dist[i] + 1;
        for (int dz = -1; dz <= 1; dz++)
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int a = x + dx, b = y + dy, c = z + dz;
                    if (a < 0 || a >= g->nx || b < 0 || b >= g->ny ||
                        c < 0 || c >= g->nz)
                        continue;
                    long k = ara_grid_index(g, a, b, c);
                    if (g->blocked[k] || g->dist[k] != ARA_BFS_UNREACHED)
                        continue;
                    g->dist[k] = d;
                    queue[tail++] = (int32_t)k;
                }
    }
    free(queue);
    return tail;
}

int32_t ara_grid_distance_at(const ara_grid *g, const double p[3])
{
    int c[3];
    if (ara_grid_cell_of(g, p, c) != 0)
        return ARA_BFS_UNREACHED;
    return g->dist[ara_grid_index(g, c[0], c[1], c[2])];
}
