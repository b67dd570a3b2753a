/*
 * worldopen.c - mpb-bench-worldopen: what the first world of a process
 * costs, the Panda with its SRDF and collision meshes in an empty scene:
 * one mpb_world_open_group_in() in a fresh process, wall and CPU time.
 * Which wrist tables it builds or reads depends on the cache the
 * environment names (MPB_CACHE_DIR); bench/worldopen.sh runs it cold,
 * warm and without a cache.
 *
 *   mpb-bench-worldopen PANDA_DIR [SCENE...]
 *
 * PANDA_DIR holds panda.urdf, panda.srdf and the meshes they name. With
 * SCENE files (MoveIt .scene texts), the later worlds of the process too:
 * one world per scene, the last four kept open as mpb-planner-ompl keeps
 * them, the first world open throughout; their median and mean wall time.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "mpbench/mpbench.h"

#include "bench_util.h"

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The worlds of n scene files after the first; 0, or 1 with a message. */
static int later_worlds(const char *robot, const char *dir,
                        const char *const *joints, int n, char **files)
{
    enum { KEEP = 4 };
    mpb_world *open[KEEP] = {NULL};
    double *t = calloc((size_t)n, sizeof *t), sum = 0.0;
    int rc = 0;
    for (int i = 0; i < n && t && rc == 0; i++) {
        char *scene = mpb_read_file(files[i], 0, NULL), err[512];
        mpb_world_close(open[i % KEEP]);
        open[i % KEEP] = NULL;
        double w0 = mpbb_now();
        if (!scene || mpb_world_open_group_in("urdf", robot, dir, "moveit-scene",
                                              scene, joints, 7, &open[i % KEEP],
                                              err, sizeof err) != MPB_OK) {
            fprintf(stderr, "mpb-bench-worldopen: %s: %s\n", files[i],
                    scene ? err : "cannot read");
            rc = 1;
        }
        t[i] = mpbb_now() - w0;
        sum += t[i];
        free(scene);
    }
    for (int k = 0; k < KEEP; k++)
        mpb_world_close(open[k]);
    if (!t)
        return 1;
    if (rc == 0) {
        mpbb_sort(t, (size_t)n);
        mpbb_result("later_worlds n=%d median_ms=%.3f mean_ms=%.3f", n,
                    1e3 * mpbb_quantile(t, (size_t)n, 0.5), 1e3 * sum / n);
    }
    free(t);
    return rc;
}

int main(int argc, char **argv)
{
    static const char *const joints[7] = {
        "panda_joint1", "panda_joint2", "panda_joint3", "panda_joint4",
        "panda_joint5", "panda_joint6", "panda_joint7"};
    if (argc < 2) {
        fprintf(stderr, "usage: mpb-bench-worldopen PANDA_DIR [SCENE...]\n");
        return 2;
    }
    char path[4096], dir[4096];
    snprintf(dir, sizeof dir, "%s/", argv[1]);
    snprintf(path, sizeof path, "%s/panda.urdf", argv[1]);
    char *urdf = mpb_read_file(path, 0, NULL);
    snprintf(path, sizeof path, "%s/panda.srdf", argv[1]);
    char *srdf = mpb_read_file(path, 0, NULL);
    if (!urdf || !srdf) {
        fprintf(stderr, "mpb-bench-worldopen: cannot read %s\n", path);
        return 1;
    }
    char *robot = malloc(strlen(urdf) + strlen(srdf) + 1);
    if (!robot)
        return 1;
    strcpy(robot, urdf);
    strcat(robot, srdf);
    mpb_world *w = NULL;
    char err[512];
    double w0 = mpbb_now(), c0 = cpu_now();
    int rc = mpb_world_open_group_in("urdf", robot, dir, "moveit-scene",
                                     "empty\n.\n", joints, 7, &w, err, sizeof err);
    double w1 = mpbb_now(), c1 = cpu_now();
    if (rc != MPB_OK) {
        fprintf(stderr, "mpb-bench-worldopen: %s\n", err);
        return 1;
    }
    mpbb_result("world_open wall_ms=%.1f cpu_ms=%.1f", 1e3 * (w1 - w0),
                1e3 * (c1 - c0));
    if (argc > 2 && later_worlds(robot, dir, joints, argc - 2, argv + 2) != 0)
        rc = MPB_EINVAL;
    mpb_world_close(w);
    free(robot);
    free(urdf);
    free(srdf);
    return rc == MPB_OK ? 0 : 1;
}
