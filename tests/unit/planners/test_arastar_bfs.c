/*
 * test_arastar_bfs.c - the ARA* planner's heuristic grid: BFS distances
 * around a wall, and a scene's box voxelized into exactly the cells it
 * touches (with real FCL), then walked round by the BFS.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <cmocka.h>

#include "bfs_grid.h"
#include "mpbench/mpbench.h"
#include "voxelize.h"

static int imax(int a, int b) { return a > b ? a : b; }
static int iabs(int a) { return a < 0 ? -a : a; }

static void test_free_space_is_chebyshev(void **state)
{
    (void)state;
    ara_grid g;
    const double origin[3] = {0, 0, 0};
    assert_int_equal(ara_grid_init(&g, 9, 7, 5, origin, 0.1), 0);
    const int from[3] = {4, 3, 2};
    assert_int_equal(ara_grid_bfs(&g, from), 9 * 7 * 5);
    /* 26-connected steps in free space: the largest coordinate difference. */
    for (int z = 0; z < 5; z++)
        for (int y = 0; y < 7; y++)
            for (int x = 0; x < 9; x++)
                assert_int_equal(g.dist[ara_grid_index(&g, x, y, z)],
                                 imax(iabs(x - 4), imax(iabs(y - 3), iabs(z - 2))));
    const double p[3] = {0.05, 0.35, 0.25};    /* cell (0, 3, 2) */
    assert_int_equal(ara_grid_distance_at(&g, p), 4);
    const double outside[3] = {-0.01, 0.3, 0.2};
    assert_int_equal(ara_grid_distance_at(&g, outside), ARA_BFS_UNREACHED);
    ara_grid_free(&g);
}

static void test_wall_with_a_gap(void **state)
{
    (void)state;
    ara_grid g;
    const double origin[3] = {0, 0, 0};
    assert_int_equal(ara_grid_init(&g, 10, 10, 1, origin, 1.0), 0);
    /* A wall at x = 5, open only at y = 9. */
    for (int y = 0; y < 9; y++)
        g.blocked[ara_grid_index(&g, 5, y, 0)] = 1;
    const int from[3] = {0, 0, 0};
    assert_int_equal(ara_grid_bfs(&g, from), 100 - 9);
    /* Left of the wall, as in free space. */
    assert_int_equal(g.dist[ara_grid_index(&g, 4, 2, 0)], 4);
    /* Through the gap (5, 9), reached in 9 steps: 9 + Chebyshev from it. */
    assert_int_equal(g.dist[ara_grid_index(&g, 5, 9, 0)], 9);
    assert_int_equal(g.dist[ara_grid_index(&g, 9, 0, 0)], 9 + 9);
    assert_int_equal(g.dist[ara_grid_index(&g, 6, 8, 0)], 10);
    assert_int_equal(g.dist[ara_grid_index(&g, 5, 4, 0)], ARA_BFS_UNREACHED);
    /* The start counts as free even when blocked (a goal by an obstacle). */
    g.blocked[ara_grid_index(&g, 0, 0, 0)] = 1;
    assert_int_equal(ara_grid_bfs(&g, from), 100 - 9);
    const int outside[3] = {10, 0, 0};
    assert_int_equal(ara_grid_bfs(&g, outside), -1);
    ara_grid_free(&g);
}

/* A 0.1 m cube centred at (0.5, 0.5, 0.5), MoveIt's .scene format. */
static const char *BOX_SCENE =
    "cube\n* box\n0.5 0.5 0.5\n0 0 0 1\n1\nbox\n0.1 0.1 0.1\n0 0 0\n"
    "0 0 0 1\n0 0 0 0\n0\n.\n";

static void test_voxelized_box(void **state)
{
    (void)state;
    mpb_scene *scene = NULL;
    char err[200];
    assert_int_equal(mpb_scene_open_text(BOX_SCENE, &scene, err, sizeof err),
                     MPB_OK);
    ara_grid g;
    const double origin[3] = {0, 0, 0};
    assert_int_equal(ara_grid_init(&g, 32, 32, 32, origin, 0.02), 0);
    long tests = ara_voxelize(&g, scene, NULL, NULL, err, sizeof err);
    assert_true(tests > 0);
    /* The box spans 0.45 .. 0.55 on each axis: cells 22 .. 27. */
    long blocked = 0;
    for (int z = 0; z < 32; z++)
        for (int y = 0; y < 32; y++)
            for (int x = 0; x < 32; x++) {
                int in = x >= 22 && x <= 27 && y >= 22 && y <= 27 &&
                         z >= 22 && z <= 27;
                assert_int_equal(g.blocked[ara_grid_index(&g, x, y, z)], in);
                blocked += in;
            }
    assert_int_equal(blocked, 216);
    /* Octree: far fewer box tests than cells. */
    assert_true(tests < 32 * 32 * 32 / 4);
    /* From one face of the box to the opposite one, the BFS goes round. */
    const int from[3] = {21, 24, 24};
    assert_true(ara_grid_bfs(&g, from) > 0);
    int32_t round = g.dist[ara_grid_index(&g, 28, 24, 24)];
    assert_true(round > 7);                      /* 7 would go through it */
    /* Out to y = 21 and back: two steps each way that cannot also advance
       in x (the third is diagonal round the box's edge). */
    assert_int_equal(round, 7 + 2 + 2);
    assert_int_equal(ara_voxelize(&g, scene, NULL, NULL, err, sizeof err) > 0, 1);
    ara_grid_free(&g);

    /* Only cubes of 2^k cells are accepted. */
    assert_int_equal(ara_grid_init(&g, 30, 30, 30, origin, 0.02), 0);
    assert_int_equal(ara_voxelize(&g, scene, NULL, NULL, err, sizeof err),
                     MPB_EINVAL);
    ara_grid_free(&g);
    mpb_scene_close(scene);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_free_space_is_chebyshev),
        cmocka_unit_test(test_wall_with_a_gap),
        cmocka_unit_test(test_voxelized_box),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
