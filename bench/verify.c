/*
 * verify.c - mpb-bench-verify: how many waypoints per second mpbench
 * verifies and measures (mpb_verify_path plus every metric the daemon
 * computes: path length, smoothness, clearance, minimum clearance,
 * end-effector path length). In process, no network.
 *
 * The world is the planar demo arm among its three obstacles, or any world
 * the daemon reads (--robot-format urdf --scene-format moveit-scene with
 * --joints: the PR2 arm). The path goes back and forth along a free
 * straight line (planar: the query "small_move"; otherwise a segment
 * between two configurations drawn at random until the straight line
 * between them is free), its waypoints --spacing apart: at the verification
 * resolution (0.01 rad) each waypoint costs one collision check, as an
 * interpolated stage does; at 0.1 rad about ten, as a planner's raw path
 * does.
 */
#include <math.h>
#include <stdint.h>
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
"collision-free path, and prints waypoints per second.\n"
"\n"
"options:\n"
"  --robot-format F  planar (default) or urdf\n"
"  --scene-format F  planar (default) or moveit-scene\n"
"  --joints A,B,...  the planning group (needed for urdf)\n"
"  --srdf FILE       the robot's SRDF (urdf; its meshes are looked for in\n"
"                    the URDF's folder last, as mpbenchd does)\n"
"  --length RAD      joint-space length of the free segment drawn for a\n"
"                    world other than planar (default 1.0)\n"
"  --label TEXT      names the world in the output (default: the format)\n"
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
    int what;          /* 0 verify + metrics, 1 verify, 2 metrics,
                          3 verify + metrics with one clearance pass */
    double start_tolerance;
    mpb_verdict v;
    double sink;
} work;

static void once(work *k)
{
    const unsigned char *wraps = mpb_world_joint_wraps(k->w);
    if (k->what != 2) {
        mpb_goal goal = {.kind = MPB_GOAL_JOINTS, .joints = k->goal,
                         .joint_tolerance = 0.01};
        mpb_verify_path(k->w, k->start, k->start_tolerance, &goal, k->path,
                        k->n, k->nj, k->resolution, &k->v);
    }
    if (k->what == 0 || k->what == 2) { /* as mpbenchd does */
        mpb_stage_measure m = {.verdict = {.code = MPB_VERDICT_VALID}};
        mpb_measure_metrics(k->w, k->path, k->n, k->nj, 0, k->resolution,
                            &m);
        for (int i = 0; i < m.num_metrics; i++)
            k->sink += m.metrics[i].value;
    } else if (k->what == 3) {
        /* The same metrics with the mean and the minimum clearance in two
         * passes, as before mpb_path_clearances(): what one pass saves. */
        double sum = 0, least = INFINITY;
        k->sink += mpb_path_length(k->path, k->n, k->nj, wraps);
        k->sink += mpb_smoothness(k->path, k->n, k->nj, wraps);
        sum = mpb_path_clearance(k->w, k->path, k->n, k->nj) * k->n;
        least = mpb_path_min_clearance(k->w, k->path, k->n, k->nj);
        k->sink += sum / k->n + least;
        k->sink += mpb_ee_path_length(k->w, k->path, k->n, k->nj,
                                      k->resolution);
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

/* Uniform in [0, 1), from a 64-bit LCG: the same segment on every machine. */
static double rnd(uint64_t *x)
{
    *x = *x * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*x >> 11) / 9007199254740992.0;
}

/* A free straight segment a -> b of joint-space length len: a drawn
 * within the limits, b at len from it in a random direction, until both
 * are within the limits and mpb_verify_path() passes the segment. */
static int free_segment(mpb_world *w, int nj, double len, double resolution,
                        double *a, double *b)
{
    uint64_t x = 1;
    for (int tries = 0; tries < 100000; tries++) {
        double norm = 0;
        int ok = 1;
        for (int j = 0; j < nj; j++) {
            double lo, hi;
            mpb_world_joint_limits(w, j, &lo, &hi);
            a[j] = lo + rnd(&x) * (hi - lo);
            b[j] = rnd(&x) - 0.5;
            norm += b[j] * b[j];
        }
        norm = sqrt(norm);
        for (int j = 0; j < nj; j++) {
            double lo, hi;
            mpb_world_joint_limits(w, j, &lo, &hi);
            b[j] = a[j] + b[j] / norm * len;
            ok = ok && b[j] >= lo && b[j] <= hi;
        }
        if (!ok)
            continue;
        double seg[2 * 64];
        mpb_verdict v;
        mpb_goal goal = {.kind = MPB_GOAL_JOINTS, .joints = b,
                         .joint_tolerance = 0.01};
        memcpy(seg, a, (size_t)nj * sizeof *a);
        memcpy(seg + nj, b, (size_t)nj * sizeof *b);
        if (mpb_verify_path(w, a, 1e-9, &goal, seg, 2, nj, resolution, &v)
                == MPB_OK && v.code == MPB_VERDICT_VALID)
            return tries + 1;
    }
    return 0;
}

/* Split "a,b,c" in place; the number of names (at most max). */
static int split_names(char *s, const char **names, int max)
{
    int n = 0;
    for (char *t = strtok(s, ","); t != NULL && n < max; t = strtok(NULL, ","))
        names[n++] = t;
    return n;
}

int main(int argc, char **argv)
{
    const char *robot_file = NULL, *scene_file = NULL, *label = NULL;
    const char *srdf_file = NULL;
    const char *robot_format = "planar", *scene_format = "planar";
    char *joints_arg = NULL;
    double spacing = 0.01, resolution = 0.01, secs = 1.0, seg_len = 1.0;
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
        else if (strcmp(a, "--robot-format") == 0) robot_format = v;
        else if (strcmp(a, "--scene-format") == 0) scene_format = v;
        else if (strcmp(a, "--joints") == 0) {
            free(joints_arg);
            joints_arg = strdup(v);
        }
        else if (strcmp(a, "--length") == 0) seg_len = atof(v);
        else if (strcmp(a, "--label") == 0) label = v;
        else if (strcmp(a, "--srdf") == 0) srdf_file = v;
        else {
            usage(stderr);
            return 2;
        }
    }
    if (!robot_file || !scene_file || !(spacing > 0) || !(resolution > 0) ||
        n < 2 || !(secs > 0) || !(seg_len > 0)) {
        usage(stderr);
        return 2;
    }
    int planar = strcmp(robot_format, "planar") == 0;
    const char *names[64];
    int num_names = joints_arg ? split_names(joints_arg, names, 64) : 0;
    char *robot = mpb_read_file(robot_file, 0, NULL);
    char *scene = mpb_read_file(scene_file, 0, NULL);
    if (robot && srdf_file) {       /* the URDF, then the SRDF */
        char *srdf = mpb_read_file(srdf_file, 0, NULL);
        char *both = srdf ? malloc(strlen(robot) + strlen(srdf) + 2) : NULL;
        if (both)
            sprintf(both, "%s\n%s", robot, srdf);
        free(srdf);
        free(robot);
        robot = both;
    }
    /* The robot file's folder, where mpbenchd looks for meshes last. */
    char dir[4096] = "";
    const char *slash = strrchr(robot_file, '/');
    if (slash && (size_t)(slash - robot_file) + 1 < sizeof dir)
        memcpy(dir, robot_file, (size_t)(slash - robot_file) + 1);
    mpb_world *w = NULL;
    char err[512];
    if (!robot || !scene ||
        mpb_world_open_group_in(robot_format, robot, dir[0] ? dir : NULL,
                                scene_format, scene, num_names ? names : NULL,
                                num_names, &w, err, sizeof err) != MPB_OK) {
        fprintf(stderr, "mpb-bench-verify: cannot open the world: %s\n",
                robot && scene ? err : "cannot read the files");
        return 1;
    }
    int nj = mpb_world_num_joints(w);
    if (planar && nj != 3) {
        fprintf(stderr, "mpb-bench-verify: expected the 3-joint demo arm\n");
        return 1;
    }
    if (nj < 1 || nj > 64) {
        fprintf(stderr, "mpb-bench-verify: %d joints\n", nj);
        return 1;
    }
    /* A free straight line, walked back and forth: for the demo arm the
     * query small_move, else one drawn at random. */
    double a[64] = {0.0, 0.0, 0.0}, b[64] = {0.3, -0.2, 0.1};
    int draws = 0;
    if (!planar && (draws = free_segment(w, nj, seg_len, resolution, a, b))
                   == 0) {
        fprintf(stderr, "mpb-bench-verify: found no free segment\n");
        return 1;
    }
    double len = 0;
    for (int j = 0; j < nj; j++)
        len += (b[j] - a[j]) * (b[j] - a[j]);
    len = sqrt(len);
    double *path = malloc((size_t)n * (size_t)nj * sizeof *path);
    double s = 0;     /* arc length along the back-and-forth walk */
    for (long i = 0; i < n; i++, s += spacing) {
        double leg = floor(s / len), f = s / len - leg;
        if ((long)leg % 2)
            f = 1 - f;
        for (int j = 0; j < nj; j++)
            path[i * nj + j] = a[j] + f * (b[j] - a[j]);
    }
    /* Goal: where the path ends. */
    double goal[64];
    memcpy(goal, &path[(n - 1) * nj], (size_t)nj * sizeof *goal);

    work k = {.w = w, .path = path, .start = a, .goal = goal, .n = (int)n,
              .nj = nj, .resolution = resolution, .start_tolerance = 0.01};
    long reps[4];
    double t[4];
    for (int what = 0; what < 4; what++) {
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
        for (int j = 0; j < nj; j++) {
            double d = path[(i + 1) * nj + j] - path[i * nj + j];
            sq += d * d;
        }
        double c = ceil(sqrt(sq) / resolution);
        checks += c < 1 ? 1 : c;
    }
    if (label == NULL)
        label = planar ? "planar demo arm" : robot_format;
    printf("%s, %d joints, %ld waypoints %.3g rad apart, resolution %.3g "
           "(%.1f collision checks per waypoint", label, nj, n, spacing,
           resolution, checks / n);
    if (draws)
        printf("; free segment of %.2g rad found in %d draws", len, draws);
    printf("):\n");
    printf("  verify + metrics %10.0f waypoints/s (%.2f us per waypoint)\n",
           n / t[0], t[0] / n * 1e6);
    printf("  verify only      %10.0f waypoints/s, %.0f collision checks/s\n",
           n / t[1], checks / t[1]);
    printf("  metrics only     %10.0f waypoints/s\n", n / t[2]);
    printf("  verify + metrics %10.0f waypoints/s with two clearance passes "
           "(before mpb_path_clearances)\n", n / t[3]);
    mpbb_result("verify spacing=%g resolution=%g waypoints=%ld "
                "checks_per_waypoint=%.2f wps=%.0f verify_wps=%.0f "
                "metrics_wps=%.0f checks_per_s=%.0f reps=%ld "
                "two_pass_clearance_wps=%.0f", spacing, resolution, n,
                checks / n, n / t[0], n / t[1], n / t[2], checks / t[1],
                reps[0], n / t[3]);
    free(path);
    free(joints_arg);
    mpb_world_close(w);
    free(robot);
    free(scene);
    return 0;
}
