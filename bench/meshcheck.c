/*
 * meshcheck.c - mpb-bench-meshcheck: what one state check costs for a
 * robot with mesh links (the Panda with its SRDF in a MotionBenchMaker
 * scene) against the primitive PR2 right arm in the paper's kitchen, both
 * measured in the same run, in interleaved rounds, so that the ratio holds
 * on a shared machine. In process, no network.
 *
 * Each world gets a fixed list of states drawn uniformly within its
 * joint limits (a 64-bit LCG, the same on every machine); a round times
 * mpb_world_in_collision(), mpb_world_contact() and mpb_world_clearance()
 * over the whole list, for one world and then the other (the order swapped
 * every round). Per query it prints the median over the rounds of the
 * mean time per check, and the median of the rounds' ratios; and the
 * median over the rounds of the measured robot's clearance time over its
 * collision check time (issue 37: at most 5). Times are
 * the thread's CPU time, not the wall clock: on a machine shared with
 * other work, waiting for a core would count otherwise.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "mpbench/mpbench.h"

#include "bench_util.h"

static void usage(FILE *out)
{
    fprintf(out,
"usage: mpb-bench-meshcheck --robot URDF [--srdf SRDF] --scene SCENE\n"
"           --joints A,B,... --ref-robot URDF --ref-scene SCENE\n"
"           --ref-joints A,B,... [options]\n"
"\n"
"Times a state check (collision, contact, clearance) of a robot against a\n"
"reference robot, in interleaved rounds, and prints the ratio.\n"
"\n"
"  --robot, --srdf, --scene, --joints  the measured world (urdf +\n"
"                    moveit-scene; meshes looked for as mpbenchd does,\n"
"                    the URDF's folder last)\n"
"  --ref-robot, --ref-srdf, --ref-scene, --ref-joints  the reference\n"
"  --label, --ref-label TEXT  their names in the output\n"
"  --states N        random states per world (default 2000)\n"
"  --rounds N        interleaved rounds (default 10)\n"
"  --seed N          of the states (default 1)\n"
"  --query Q         in_collision, contact or clearance only (default all;\n"
"                    one alone is for a profiler)\n");
}

typedef struct side {
    const char *robot, *srdf, *scene, *label;
    char       *joints;
    mpb_world  *w;
    int         nj;
    double     *q;                /* states x nj */
    int         in_collision;     /* how many of the states */
    double     *t[3];             /* per round: seconds per check */
} side;

enum { Q_COLLISION, Q_CONTACT, Q_CLEARANCE };
static const char *const qname[3] = {"in_collision", "contact", "clearance"};

/* Uniform in [0, 1), from a 64-bit LCG. */
static double rnd(uint64_t *x)
{
    *x = *x * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*x >> 11) / 9007199254740992.0;
}

/* The folder of path, with its slash ("" for none); the caller frees. */
static char *dir_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    size_t n = slash ? (size_t)(slash - path) + 1 : 0;
    char *d = malloc(n + 1);
    if (d) {
        memcpy(d, path, n);
        d[n] = '\0';
    }
    return d;
}

static int open_side(side *s, int states, uint64_t seed, int rounds)
{
    char *urdf = mpb_read_file(s->robot, 0, NULL);
    char *scene = mpb_read_file(s->scene, 0, NULL);
    char *srdf = s->srdf ? mpb_read_file(s->srdf, 0, NULL) : NULL, *text = NULL;
    char *dir = dir_of(s->robot), err[512];
    const char *names[64];
    int n = 0, rc = -1;
    if (!urdf || !scene || (s->srdf && !srdf) || !dir) {
        fprintf(stderr, "mpb-bench-meshcheck: %s: cannot read its files\n",
                s->label);
        goto done;
    }
    /* The robot text is the URDF followed by the SRDF (world_urdf.c). */
    size_t lu = strlen(urdf), ls = srdf ? strlen(srdf) : 0;
    if (!(text = malloc(lu + ls + 2)))
        goto done;
    memcpy(text, urdf, lu);
    text[lu] = '\n';
    memcpy(text + lu + 1, srdf ? srdf : "", ls + 1);
    for (char *t = strtok(s->joints, ","); t && n < 64; t = strtok(NULL, ","))
        names[n++] = t;
    if (mpb_world_open_group_in("urdf", text, dir, "moveit-scene", scene,
                                names, n, &s->w, err, sizeof err) != MPB_OK) {
        fprintf(stderr, "mpb-bench-meshcheck: %s: %s\n", s->label, err);
        goto done;
    }
    s->nj = mpb_world_num_joints(s->w);
    s->q = malloc((size_t)states * (size_t)s->nj * sizeof *s->q);
    for (int k = 0; k < 3; k++)
        s->t[k] = calloc((size_t)rounds, sizeof *s->t[k]);
    if (!s->q || !s->t[0] || !s->t[1] || !s->t[2])
        goto done;
    uint64_t x = seed;
    for (int i = 0; i < states; i++)
        for (int j = 0; j < s->nj; j++) {
            double lo, hi;
            mpb_world_joint_limits(s->w, j, &lo, &hi);
            s->q[i * s->nj + j] = lo + rnd(&x) * (hi - lo);
        }
    for (int i = 0; i < states; i++)
        s->in_collision += mpb_world_in_collision(s->w, &s->q[i * s->nj]) != 0;
    rc = 0;
done:
    free(urdf);
    free(scene);
    free(srdf);
    free(text);
    free(dir);
    return rc;
}

/* This thread's CPU time (s): on a shared machine, time spent waiting for
 * a core is no part of a check. */
static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* One pass of query k over the states: CPU seconds per check. */
static double pass(side *s, int k, int states, double *sink)
{
    char what[256];
    double t0 = cpu_now();
    for (int i = 0; i < states; i++) {
        const double *q = &s->q[i * s->nj];
        if (k == Q_COLLISION)
            *sink += mpb_world_in_collision(s->w, q);
        else if (k == Q_CONTACT)
            *sink += mpb_world_contact(s->w, q, what, sizeof what);
        else
            *sink += mpb_world_clearance(s->w, q);
    }
    return (cpu_now() - t0) / states;
}

static double median(const double *v, int n)
{
    double *c = malloc((size_t)n * sizeof *c);
    if (!c)
        return NAN;
    memcpy(c, v, (size_t)n * sizeof *c);
    mpbb_sort(c, (size_t)n);
    double m = mpbb_quantile(c, (size_t)n, 0.5);
    free(c);
    return m;
}

int main(int argc, char **argv)
{
    side s[2] = {{.label = "robot"}, {.label = "reference"}};
    int states = 2000, rounds = 10;
    uint64_t seed = 1;
    int only = -1;
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
        int r = strncmp(a, "--ref-", 6) == 0;
        const char *key = r ? a + 6 : a + 2;
        if (strncmp(a, "--", 2) != 0) { usage(stderr); return 2; }
        if (strcmp(key, "robot") == 0) s[r].robot = v;
        else if (strcmp(key, "srdf") == 0) s[r].srdf = v;
        else if (strcmp(key, "scene") == 0) s[r].scene = v;
        else if (strcmp(key, "label") == 0) s[r].label = v;
        else if (strcmp(key, "joints") == 0) {
            free(s[r].joints);
            s[r].joints = strdup(v);
        }
        else if (!r && strcmp(key, "states") == 0) states = atoi(v);
        else if (!r && strcmp(key, "rounds") == 0) rounds = atoi(v);
        else if (!r && strcmp(key, "seed") == 0) seed = strtoull(v, NULL, 10);
        else if (!r && strcmp(key, "query") == 0) {
            for (int k = 0; k < 3; k++)
                if (strcmp(v, qname[k]) == 0)
                    only = k;
            if (only < 0) {
                usage(stderr);
                return 2;
            }
        }
        else {
            usage(stderr);
            return 2;
        }
    }
    for (int k = 0; k < 2; k++)
        if (!s[k].robot || !s[k].scene || !s[k].joints) {
            usage(stderr);
            return 2;
        }
    if (states < 1 || rounds < 1) {
        usage(stderr);
        return 2;
    }
    double t0 = mpbb_now();
    if (open_side(&s[0], states, seed, rounds) != 0)
        return 1;
    double t_open = mpbb_now() - t0;
    t0 = mpbb_now();
    if (open_side(&s[1], states, seed, rounds) != 0)
        return 1;
    double t_open_ref = mpbb_now() - t0;
    double sink = 0, *ratio[3];
    for (int k = 0; k < 3; k++)
        if (!(ratio[k] = calloc((size_t)rounds, sizeof *ratio[k])))
            return 1;
    for (int k = 0; k < 3; k++) {     /* warm both */
        if (only >= 0 && k != only)
            continue;
        pass(&s[0], k, states, &sink);
        pass(&s[1], k, states, &sink);
    }
    for (int r = 0; r < rounds; r++)
        for (int k = 0; k < 3; k++) {
            int first = r % 2;
            if (only >= 0 && k != only)
                continue;
            s[first].t[k][r] = pass(&s[first], k, states, &sink);
            s[!first].t[k][r] = pass(&s[!first], k, states, &sink);
            ratio[k][r] = s[0].t[k][r] / s[1].t[k][r];
        }
    for (int k = 0; k < 2; k++)
        printf("%s: %d joints, %d of %d random states in collision, "
               "opened in %.3f s\n", s[k].label, s[k].nj, s[k].in_collision,
               states, k ? t_open_ref : t_open);
    printf("%d rounds of %d states each, interleaved; medians of the rounds:\n",
           rounds, states);
    for (int k = 0; k < 3; k++) {
        if (only >= 0 && k != only)
            continue;
        double a = median(s[0].t[k], rounds), b = median(s[1].t[k], rounds);
        double rr = median(ratio[k], rounds);
        double lo = ratio[k][0], hi = ratio[k][0];
        for (int r = 1; r < rounds; r++) {
            lo = fmin(lo, ratio[k][r]);
            hi = fmax(hi, ratio[k][r]);
        }
        printf("  %-12s %9.2f us / %9.2f us per check: ratio %.2f "
               "(rounds %.2f-%.2f)\n", qname[k], a * 1e6, b * 1e6, rr, lo, hi);
        mpbb_result("meshcheck_%s us=%.3f ref_us=%.3f ratio=%.3f ratio_min=%.3f "
                    "ratio_max=%.3f", qname[k], a * 1e6, b * 1e6, rr, lo, hi);
    }
    if (only < 0) {
        /* issue 37: a clearance query against a collision check of the
           same robot, round by round (both passes in the same round, so
           that the machine's load moves both alike) */
        double *cc = ratio[Q_CONTACT];  /* reused: its ratios are printed */
        for (int r = 0; r < rounds; r++)
            cc[r] = s[0].t[Q_CLEARANCE][r] / s[0].t[Q_COLLISION][r];
        double rr = median(cc, rounds), lo = cc[0], hi = cc[0];
        for (int r = 1; r < rounds; r++) {
            lo = fmin(lo, cc[r]);
            hi = fmax(hi, cc[r]);
        }
        printf("  %s: clearance / in_collision %.2f (rounds %.2f-%.2f)\n",
               s[0].label, rr, lo, hi);
        mpbb_result("meshcheck_clearance_vs_collision ratio=%.3f ratio_min=%.3f "
                    "ratio_max=%.3f", rr, lo, hi);
    }
    mpbb_result("meshcheck_setup states=%d rounds=%d colliding=%d "
                "ref_colliding=%d open_s=%.3f ref_open_s=%.3f", states, rounds,
                s[0].in_collision, s[1].in_collision, t_open, t_open_ref);
    if (sink == 12345.678)      /* keep the calls */
        printf("\n");
    for (int k = 0; k < 2; k++) {
        mpb_world_close(s[k].w);
        free(s[k].q);
        free(s[k].joints);
        for (int j = 0; j < 3; j++)
            free(s[k].t[j]);
    }
    for (int k = 0; k < 3; k++)
        free(ratio[k]);
    return 0;
}
