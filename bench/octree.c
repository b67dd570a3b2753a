/*
 * octree.c - mpb-bench-octree: what octrees cost (issue 48). Two
 * measures in one run:
 *   - loading a cloud of 10^6 points (a binary PLY written here: three
 *     unit squares, a corner of a room) into a 1 cm octree: wall time
 *     and the process's peak memory growth;
 *   - a state check of the PR2's right arm (with its SRDF) in the
 *     paper's tabletop against its primitives and against the 1 cm
 *     octree of their surfaces (points every 2.5 mm on each box face),
 *     over the states free among the primitives, in interleaved rounds;
 *     the median of the rounds' ratios.
 * Usage: mpb-bench-octree SOURCE_DIR [ROUNDS]
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "mpbench/mpbench.h"

#include "bench_util.h"

static long peak_kib(void)
{
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss;
}

static uint64_t lcg(uint64_t *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return *s >> 11;
}

static double unit(uint64_t *s)
{
    return (double)lcg(s) / 9007199254740992.0;
}

static int cloud_load(void)
{
    const char *path = "/tmp/mpb-bench-octree.ply";
    const long n = 1000000;
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    fprintf(f, "ply\nformat binary_little_endian 1.0\nelement vertex %ld\nproperty float x\n"
            "property float y\nproperty float z\nend_header\n", n);
    uint64_t s = 1;
    for (long i = 0; i < n; i++) {
        float p[3] = {(float)unit(&s), (float)unit(&s), (float)unit(&s)};
        p[i % 3] = 0.0f;
        fwrite(p, sizeof p, 1, f);
    }
    if (fclose(f) != 0)
        return -1;
    long before = peak_kib();
    double t0 = mpbb_now();
    mpb_octree *o;
    char err[300];
    if (mpb_cloud_load_octree(path, 0.01, &o, err, sizeof err) != MPB_OK) {
        fprintf(stderr, "%s\n", err);
        return -1;
    }
    double t = mpbb_now() - t0;
    printf("10^6 points (binary PLY, 12 MB) into a 1 cm octree: %.3f s, %d cells, peak "
           "memory +%ld KiB\n", t, mpb_octree_num_cells(o), peak_kib() - before);
    mpbb_result("cloud_load_s=%.4f cloud_cells=%d cloud_peak_kib=%ld", t,
                mpb_octree_num_cells(o), peak_kib() - before);
    mpb_octree_destroy(o);
    remove(path);
    return 0;
}

/* The 1 cm octree of the surfaces of the boxes of scene s. */
static mpb_octree *surfaces(const mpb_scene *s)
{
    mpb_octree *o;
    if (mpb_octree_create(0.01, &o) != MPB_OK)
        return NULL;
    const double st = 0.0025;
    for (int i = 0; i < mpb_scene_num_objects(s); i++) {
        const mpb_scene_object *ob = mpb_scene_object_at(s, i);
        for (int k = 0; k < ob->num_shapes; k++) {
            const mpb_scene_shape *sh = &ob->shapes[k];
            if (sh->geometry.type != MPB_SHAPE_BOX)
                continue;
            mpb_pose p;
            mpb_pose_mul(&ob->pose, &sh->pose, &p);
            const double *d = sh->geometry.dims;
            for (int ax = 0; ax < 3; ax++)
                for (int side = 0; side < 2; side++) {
                    int u = (ax + 1) % 3, v = (ax + 2) % 3;
                    int nu = (int)(d[u] / st) + 1, nv = (int)(d[v] / st) + 1;
                    for (int a = 0; a <= nu; a++)
                        for (int b = 0; b <= nv; b++) {
                            double l[3], w[3];
                            l[ax] = (side ? 0.5 : -0.5) * d[ax];
                            l[u] = -d[u] / 2 + d[u] * a / nu;
                            l[v] = -d[v] / 2 + d[v] * b / nv;
                            mpb_pose_apply(&p, l, w);
                            mpb_octree_add_point(o, w);
                        }
                }
        }
    }
    return o;
}

static double time_checks(mpb_world *w, const double *q, int n)
{
    double t0 = mpbb_now();
    for (int i = 0; i < n; i++)
        mpb_world_in_collision(w, q + 7 * i);
    return (mpbb_now() - t0) / n;
}

static int check_ratio(const char *src, int rounds)
{
    char path[4096], err[400];
    size_t len;
    snprintf(path, sizeof path, "%s/scenes/paper/tabletop.scene", src);
    char *prim = mpb_read_file(path, 0, &len);
    snprintf(path, sizeof path, "%s/tests/support/data/pr2_right_arm.urdf", src);
    char *urdf = mpb_read_file(path, 0, &len);
    snprintf(path, sizeof path, "%s/tests/support/data/pr2_right_arm.srdf", src);
    char *srdf = mpb_read_file(path, 0, &len);
    mpb_scene *s = NULL;
    if (!prim || !urdf || !srdf || mpb_scene_open_text(prim, &s, err, sizeof err) != MPB_OK) {
        fprintf(stderr, "mpb-bench-octree: cannot read %s's scenes and robots\n", src);
        return -1;
    }
    mpb_octree *o = surfaces(s);
    char *oct = NULL;
    if (!o || mpb_scene_octree_text(o, "cells", NULL, &oct) != MPB_OK)
        return -1;
    char *otext = malloc(strlen(oct) + 16), *robot = malloc(strlen(urdf) + strlen(srdf) + 2);
    sprintf(otext, "cells\n.\n%s", oct);
    sprintf(robot, "%s\n%s", urdf, srdf);
    static const char *const J[] = {"r_shoulder_pan_joint", "r_shoulder_lift_joint",
                                    "r_upper_arm_roll_joint", "r_elbow_flex_joint",
                                    "r_forearm_roll_joint", "r_wrist_flex_joint",
                                    "r_wrist_roll_joint"};
    mpb_world *wp, *wo;
    if (mpb_world_open_group("urdf", robot, "moveit-scene", prim, J, 7, &wp, err,
                             sizeof err) != MPB_OK ||
        mpb_world_open_group("urdf", robot, "moveit-scene", otext, J, 7, &wo, err,
                             sizeof err) != MPB_OK) {
        fprintf(stderr, "mpb-bench-octree: %s\n", err);
        return -1;
    }
    int n = 40000, m = 0, differ = 0;
    double *q = malloc(sizeof *q * 7 * (size_t)n);
    uint64_t seed = 3;
    for (int i = 0; i < n; i++) {
        double *x = q + 7 * m;
        for (int j = 0; j < 7; j++) {
            double lo, hi;
            mpb_world_joint_limits(wp, j, &lo, &hi);
            if (!(hi - lo < 10))
                lo = -3.14159, hi = 3.14159;
            x[j] = lo + (hi - lo) * unit(&seed);
        }
        if (mpb_world_in_collision(wp, x) == 0) {
            differ += mpb_world_in_collision(wo, x) != 0;
            m++;
        }
    }
    double *ratio = malloc(sizeof *ratio * (size_t)rounds), tp = 0, to = 0;
    for (int r = 0; r < rounds; r++) {
        double a, b;
        if (r % 2) {
            b = time_checks(wo, q, m);
            a = time_checks(wp, q, m);
        } else {
            a = time_checks(wp, q, m);
            b = time_checks(wo, q, m);
        }
        ratio[r] = b / a;
        tp += a / rounds;
        to += b / rounds;
    }
    mpbb_sort(ratio, (size_t)rounds);
    double med = mpbb_quantile(ratio, (size_t)rounds, 0.5);
    printf("PR2 right arm, tabletop, %d free states: primitives %.2f us a check, 1 cm "
           "octree of their surfaces (%d cells) %.2f us: %.2fx (median of %d rounds); "
           "%d states touch a cell\n", m, tp * 1e6, mpb_octree_num_cells(o), to * 1e6, med,
           rounds, differ);
    mpbb_result("check_primitives_us=%.3f check_octree_us=%.3f octree_ratio=%.3f "
                "octree_cells=%d", tp * 1e6, to * 1e6, med, mpb_octree_num_cells(o));
    mpb_world_close(wp);
    mpb_world_close(wo);
    mpb_octree_destroy(o);
    mpb_scene_close(s);
    free(q);
    free(ratio);
    free(oct);
    free(otext);
    free(robot);
    free(prim);
    free(urdf);
    free(srdf);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 2 || argc > 3) {
        fprintf(stderr, "usage: mpb-bench-octree SOURCE_DIR [ROUNDS]\n");
        return 2;
    }
    int rounds = argc == 3 ? atoi(argv[2]) : 7;
    if (rounds < 1)
        rounds = 1;
    if (cloud_load() != 0 || check_ratio(argv[1], rounds) != 0)
        return 1;
    return 0;
}
