/*
 * verify.c - mpb-bench-verify: how many waypoints per second mpbench
 * verifies and measures (mpb_verify_path plus every metric the daemon
 * computes: path length, smoothness, clearance). In process, no network.
 *
 * The world is the planar demo arm among its three obstacles (the PR2 arm
 * in the kitchen comes with the URDF world). The path goes back and forth
 * along the free straight line of the query "small_move", its waypoints
 * --spacing apart: at the verification resolution (0.01 rad) each waypoint
 * costs one collision check, as an interpolated stage does; at 0.1 rad about
 * ten, as a planner's raw path does.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"

#include "bench_util.h"

static void usage(FILE *out)
{
    fprintf(out,
"usage: mpb-bench-verify --robot FILE --scene FILE [options]\n"
"\n"
"Times verification (mpb_verify_path) and the daemon's metrics on a long\n"
"collision-free path of the planar demo world, and prints waypoints per\n"
"second.\n"
"\n"
"options:\n"
"  --spacing RAD     joint-space distance between waypoints (default 0.01)\n"
"  --resolution RAD  verification step, as mpbenchd -r (default 0.01)\n"
"  --waypoints N     waypoints of the path (default 10000)\n"
"  --seconds S       repeat for at least S seconds (default 1)\n");
}

/* Time fn over the path until at least secs have passed; seconds per call. */
typedef struct work {
    mpb_world *w;
    const double *path, *start, *goal;
    int n, nj;
    double resolution;
    int what;          /* 0 verify + metrics, 1 verify, 2 metrics */
    mpb_verdict v;
    double sink;
} work;

static void once(work *k)
{
    const unsigned char *wraps = mpb_world_joint_wraps(k->w);
    if (k->what != 2) {
        mpb_goal goal = {.kind = MPB_GOAL_JOINTS, .joints = k->goal,
                         .joint_tolerance = 0.01};
        mpb_verify_path(k->w, k->start, 0.01, &goal, k->path, k->n, k->nj,
                        k->resolution, &k->v);
    }
    if (k->what != 1) {
        k->sink += mpb_path_length(k->path, k->n, k->nj, wraps);
        k->sink += mpb_smoothness(k->path, k->n, k->nj, wraps);
        k->sink += mpb_path_clearance(k->w, k->path, k->n, k->nj);
    }
}

static double timed(work *k, double secs, long *reps)
{
    double t0 = mpbb_now(), t;
    long r = 0;
    once(k);                 /* warm */
    do {
        once(k);
        r++;
        t = mpbb_now();
    } while (t - t0 < secs);
    *reps = r;
    return (t - t0) / (double)r;
}

int main(int argc, char **argv)
{
    const char *robot_file = NULL, *scene_file = NULL;
    double spacing = 0.01, resolution = 0.01, secs = 1.0;
    long n = 10000;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--help") == 0) {
            usage(stdout);
            return 0;
        }
        if (v == NULL) {
            usage(stderr);
            return 2;
        }
        i++;
        if (strcmp(a, "--robot") == 0) robot_file = v;
        else if (strcmp(a, "--scene") == 0) scene_file = v;
        else if (strcmp(a, "--spacing") == 0) spacing = atof(v);
        else if (strcmp(a, "--resolution") == 0) resolution = atof(v);
        else if (strcmp(a, "--waypoints") == 0) n = atol(v);
        else if (strcmp(a, "--seconds") == 0) secs = atof(v);
        else {
            usage(stderr);
            return 2;
        }
    }
    if (!robot_file || !scene_file || !(spacing > 0) || !(resolution > 0) ||
        n < 2 || !(secs > 0)) {
        usage(stderr);
        return 2;
    }
    char *robot = mpbb_slurp(robot_file), *scene = mpbb_slurp(scene_file);
    mpb_world *w = NULL;
    char err[256];
    if (!robot || !scene ||
        mpb_world_open("planar", robot, "planar", scene, &w, err,
                       sizeof err) != MPB_OK) {
        fprintf(stderr, "mpb-bench-verify: cannot open the world: %s\n",
                robot && scene ? err : "cannot read the files");
        return 1;
    }
    int nj = mpb_world_num_joints(w);
    if (nj != 3) {
        fprintf(stderr, "mpb-bench-verify: expected the 3-joint demo arm\n");
        return 1;
    }
    /* small_move: a free straight line, walked back and forth. */
    const double a[3] = {0.0, 0.0, 0.0}, b[3] = {0.3, -0.2, 0.1};
    double len = 0;
    for (int j = 0; j < 3; j++)
        len += (b[j] - a[j]) * (b[j] - a[j]);
    len = sqrt(len);
    double *path = malloc((size_t)n * 3 * sizeof *path);
    double s = 0;     /* arc length along the back-and-forth walk */
    for (long i = 0; i < n; i++, s += spacing) {
        double leg = floor(s / len), f = s / len - leg;
        if ((long)leg % 2)
            f = 1 - f;
        for (int j = 0; j < 3; j++)
            path[i * 3 + j] = a[j] + f * (b[j] - a[j]);
    }
    /* Goal: where the path ends. */
    double goal[3];
    memcpy(goal, &path[(n - 1) * 3], sizeof goal);

    work k = {.w = w, .path = path, .start = a, .goal = goal, .n = (int)n,
              .nj = 3, .resolution = resolution};
    long reps[3];
    double t[3];
    for (int what = 0; what < 3; what++) {
        k.what = what;
        t[what] = timed(&k, secs, &reps[what]);
        if (what == 0 && k.v.code != MPB_VERDICT_VALID) {
            fprintf(stderr, "mpb-bench-verify: the path is not valid: %s\n",
                    k.v.detail);
            return 1;
        }
    }
    /* Collision checks one verification makes: one at waypoint 0, then
     * ceil(segment / resolution) per segment. */
    double checks = 1;
    for (long i = 0; i + 1 < n; i++) {
        double sq = 0;
        for (int j = 0; j < 3; j++) {
            double d = path[(i + 1) * 3 + j] - path[i * 3 + j];
            sq += d * d;
        }
        double c = ceil(sqrt(sq) / resolution);
        checks += c < 1 ? 1 : c;
    }
    printf("planar demo arm, %ld waypoints %.3g rad apart, resolution %.3g "
           "(%.1f collision checks per waypoint):\n", n, spacing, resolution,
           checks / n);
    printf("  verify + metrics %10.0f waypoints/s (%.2f us per waypoint)\n",
           n / t[0], t[0] / n * 1e6);
    printf("  verify only      %10.0f waypoints/s, %.0f collision checks/s\n",
           n / t[1], checks / t[1]);
    printf("  metrics only     %10.0f waypoints/s\n", n / t[2]);
    mpbb_result("verify spacing=%g resolution=%g waypoints=%ld "
                "checks_per_waypoint=%.2f wps=%.0f verify_wps=%.0f "
                "metrics_wps=%.0f checks_per_s=%.0f reps=%ld", spacing,
                resolution, n, checks / n, n / t[0], n / t[1], n / t[2],
                checks / t[1], reps[0]);
    free(path);
    mpb_world_close(w);
    free(robot);
    free(scene);
    return 0;
}
