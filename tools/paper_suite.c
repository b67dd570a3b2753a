/*
 * paper_suite.c - `mpb-paper-suite`: turns the suite description
 * (scenes/paper/suite.txt: the start state, the environments and their
 * end-effector goals) into the experiment files of the paper's benchmark,
 * scenes/experiments/paper.yaml and paper-quick.yaml.
 *
 * The paper plans "between successive goals, the first from the start
 * state". A run must be repeatable, so each query needs a fixed start: the
 * first query of an environment starts at the start state, query k at a
 * collision-free configuration inside goal k-1's region, found here once
 * by inverse kinematics with a fixed random seed and written into the file.
 * Of several collision-free solutions the one nearest the previous
 * configuration is kept, as a robot moving on from there would reach it.
 *
 * Usage: mpb-paper-suite [--quick] [--check FILE] [-v] SUITE
 *   writes the YAML to stdout; --check compares it with FILE instead and
 *   exits 1 if they differ (the test suite keeps the committed files
 *   honest this way).
 */
#include <getopt.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "mpbench/mpbench.h"

#define NUM_JOINTS 7
#define MAX_GOALS 16
#define MAX_ENVS 8
#define SOLUTIONS_PER_GOAL 12   /* collision-free IK answers compared */
#define DRAWS_PER_GOAL 400      /* IK draws before a goal is declared unreachable */

static const char *const arm_joints[NUM_JOINTS] = {
    "r_shoulder_pan_joint", "r_shoulder_lift_joint", "r_upper_arm_roll_joint",
    "r_elbow_flex_joint", "r_forearm_roll_joint", "r_wrist_flex_joint",
    "r_wrist_roll_joint",
};
#define EE_LINK "r_gripper_tool_frame"
#define POSITION_HALF 0.01      /* the paper's 2 cm cube */
#define RPY_TOLERANCE 0.05      /* rad, each of roll, pitch, yaw */

typedef struct goal {
    char   name[64];
    double xyz[3], rpy[3];
    int    line;
} goal;

typedef struct env {
    char name[64];
    char scene[256];            /* file name, beside the suite file */
    goal goals[MAX_GOALS];
    int  num_goals;
} env;

typedef struct suite {
    char   dir[512];            /* the suite file's directory */
    char   robot[256];          /* relative to dir */
    double start[NUM_JOINTS];
    env    envs[MAX_ENVS];
    int    num_envs;
} suite;

static int verbose;

static void die(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("mpb-paper-suite: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    exit(1);
}

static char *read_file(const char *path)
{
    char *text = mpb_read_file(path, 0, NULL);
    if (text == NULL)
        die("cannot read %s", path);
    return text;
}

/* ---- the suite file ------------------------------------------------------ */

static void parse_suite(const char *path, suite *s)
{
    FILE *f = fopen(path, "r");
    if (f == NULL)
        die("cannot read %s", path);
    const char *slash = strrchr(path, '/');
    snprintf(s->dir, sizeof s->dir, "%.*s",
             slash ? (int)(slash - path) : 1, slash ? path : ".");
    char line[512];
    int lineno = 0;
    env *e = NULL;
    while (fgets(line, sizeof line, f) != NULL) {
        lineno++;
        char *hash = strchr(line, '#');
        if (hash)
            *hash = '\0';
        char word[64];
        int used = 0;
        if (sscanf(line, " %63s %n", word, &used) != 1)
            continue;
        const char *rest = line + used;
        if (strcmp(word, "robot") == 0) {
            if (sscanf(rest, "%255s", s->robot) != 1)
                die("%s:%d: robot needs a file name", path, lineno);
        } else if (strcmp(word, "start") == 0) {
            double *q = s->start;
            if (sscanf(rest, "%lf %lf %lf %lf %lf %lf %lf", &q[0], &q[1], &q[2],
                       &q[3], &q[4], &q[5], &q[6]) != NUM_JOINTS)
                die("%s:%d: start needs %d joint values", path, lineno,
                    NUM_JOINTS);
        } else if (strcmp(word, "environment") == 0) {
            if (s->num_envs == MAX_ENVS)
                die("%s:%d: more than %d environments", path, lineno, MAX_ENVS);
            e = &s->envs[s->num_envs++];
            if (sscanf(rest, "%63s %255s", e->name, e->scene) != 2)
                die("%s:%d: environment needs a name and a scene file", path,
                    lineno);
        } else if (strcmp(word, "goal") == 0) {
            if (e == NULL)
                die("%s:%d: a goal before any environment", path, lineno);
            if (e->num_goals == MAX_GOALS)
                die("%s:%d: more than %d goals", path, lineno, MAX_GOALS);
            goal *g = &e->goals[e->num_goals++];
            g->line = lineno;
            if (sscanf(rest, "%63s %lf %lf %lf %lf %lf %lf", g->name, &g->xyz[0],
                       &g->xyz[1], &g->xyz[2], &g->rpy[0], &g->rpy[1],
                       &g->rpy[2]) != 7)
                die("%s:%d: goal needs a name, x y z (m) and roll pitch yaw "
                    "(rad)", path, lineno);
        } else {
            die("%s:%d: unknown word '%s' (robot, start, environment, goal)",
                path, lineno, word);
        }
    }
    fclose(f);
    if (s->robot[0] == '\0' || s->num_envs == 0)
        die("%s: needs a robot and at least one environment", path);
}

/* ---- goals and their inverse kinematics --------------------------------- */

static double joint_distance(const double *a, const double *b)
{
    double d = 0.0;
    for (int j = 0; j < NUM_JOINTS; j++)
        d += (a[j] - b[j]) * (a[j] - b[j]);
    return sqrt(d);
}

/* Continuous joints: the representative nearest the previous value, so
 * that a query's start and the path to it do not turn a full circle. */
static void unwrap_near(const mpb_robot *r, const double *prev, double *q)
{
    const unsigned char *wraps = mpb_robot_joint_wraps(r);
    for (int j = 0; j < NUM_JOINTS; j++)
        if (wraps[j])
            q[j] = prev[j] + remainder(q[j] - prev[j], 2.0 * M_PI);
}

static void region_of(const mpb_robot *r, const goal *g, mpb_goal_region *out)
{
    *out = (mpb_goal_region){.link = mpb_robot_link_index(r, EE_LINK)};
    for (int i = 0; i < 3; i++) {
        out->center[i] = g->xyz[i];
        out->half_extents[i] = POSITION_HALF;
        out->ref_rpy[i] = g->rpy[i];
        out->rpy_tolerance[i] = RPY_TOLERANCE;
    }
}

/*
 * A collision-free configuration inside g's region near prev, into q.
 * Returns the number of collision-free solutions seen (0: none found).
 */
static int solve_goal(const mpb_robot *r, mpb_world *w, const goal *g,
                      uint64_t seed, const double *prev, double *q)
{
    mpb_goal_region region;
    region_of(r, g, &region);
    uint64_t rng = seed;
    double cand[NUM_JOINTS], best = INFINITY;
    int found = 0, solved = 0;
    for (int draw = 0; draw < DRAWS_PER_GOAL && found < SOLUTIONS_PER_GOAL;
         draw++) {
        /* Seed IK from the previous configuration first, then at random. */
        if (mpb_goal_region_sample(r, &region, draw == 0 ? prev : NULL, NULL,
                                   0, &rng, cand) != MPB_OK)
            continue;
        solved++;
        unwrap_near(r, prev, cand);
        if (!mpb_robot_within_limits(r, cand) ||
            mpb_goal_region_contains(r, &region, cand) != 1 ||
            mpb_world_in_collision(w, cand) != 0)
            continue;
        found++;
        double d = joint_distance(cand, prev);
        if (d < best) {
            best = d;
            memcpy(q, cand, sizeof cand);
        }
    }
    if (verbose && found == 0)
        fprintf(stderr, "  %s: %d of %d IK draws reached the region, all "
                "in collision, e.g. %g %g %g %g %g %g %g\n", g->name, solved,
                DRAWS_PER_GOAL, cand[0], cand[1], cand[2], cand[3], cand[4],
                cand[5], cand[6]);
    return found;
}

/* ---- writing the experiment file ----------------------------------------- */

static void put_vector(FILE *out, const double *v, int n)
{
    fputc('[', out);
    for (int i = 0; i < n; i++)
        fprintf(out, "%s%.6f", i ? ", " : "", v[i] == 0.0 ? 0.0 : v[i]);
    fputc(']', out);
}

/* The experiment files made from one suite: the paper's protocol, a
 * quick variant, and the slice `make demo` runs. */
typedef struct variant {
    const char *name;           /* --variant NAME, the experiment's name */
    const char *about;          /* the header's description */
    int         runs;           /* per sampling planner and query */
    double      time_limit;     /* s */
    int         goals;          /* goals per environment, 0: all */
    const char *ompl;           /* OMPL algorithms */
} variant;

static const variant variants[] = {
    {"paper",
     "The paper's protocol: 30 runs per sampling planner and\n"
     "# query, 1 for deterministic ones, 60 s limit.",
     30, 60.0, 0,
     "KPIECE1, LBKPIECE1, SBL, RRT, RRTConnect, RRTstar, BKPIECE1, PRM, EST, "
     "BITstar"},
    {"paper-quick",
     "Quick variant: 3 runs per sampling planner and query,\n"
     "# 10 s limit, no planners beyond the paper's (meant to take\n"
     "# under 30 minutes on 2 cores).",
     3, 10.0, 0, "KPIECE1, LBKPIECE1, SBL, RRT, RRTConnect, RRTstar"},
    {"paper-demo",
     "The slice `make demo` runs: the first two goals of each\n"
     "# environment, 3 runs per sampling planner and query, 5 s limit,\n"
     "# two OMPL planners (a few minutes at most on 2 cores).",
     3, 5.0, 2, "RRTConnect, RRT"},
};
#define NUM_VARIANTS ((int)(sizeof variants / sizeof variants[0]))

static void write_header(FILE *out, const suite *s, const variant *v)
{
    fprintf(out,
        "# The benchmark of Cohen, Sucan and Chitta, section IV: the PR2's right\n"
        "# arm between successive end-effector goals (2 cm cube, 0.05 rad) in\n"
        "# four environments. %s\n"
        "#\n"
        "# GENERATED by mpb-paper-suite from scenes/paper/suite.txt; edit that\n"
        "# file and run tools/paper_suite.sh instead of editing this one.\n"
        "experiment:\n"
        "  name: %s\n"
        "  runs: %d\n"
        "  time_limit: %.1f\n"
        "  seed: 2012\n"
        "  retries: 1\n"
        "\n"
        "robot:\n"
        "  format: urdf\n"
        "  file: ../%s\n"
        "  joints: [",
        v->about, v->name, v->runs, v->time_limit,
        s->robot + (strncmp(s->robot, "../", 3) == 0 ? 3 : 0));
    for (int j = 0; j < NUM_JOINTS; j++)
        fprintf(out, "%s%s", j ? ", " : "", arm_joints[j]);
    fputs("]\n\nscenes:\n", out);
}

static void write_planners(FILE *out, const variant *v)
{
    fprintf(out,
        "\n"
        "planners:\n"
        "  - planner: ompl\n"
        "    algorithms: [%s]\n"
        "  - planner: arastar\n"
        "    algorithms: [ARAstar]\n"
        "    runs: 1             # deterministic\n"
        "  - planner: python\n"
        "    algorithms: [RRTConnect]\n",
        v->ompl);
}

static void write_goal(FILE *out, const goal *g)
{
    fprintf(out, "        goal:\n          link: " EE_LINK "\n          position: ");
    put_vector(out, g->xyz, 3);
    fprintf(out, "\n          position_tolerance: [%.2f, %.2f, %.2f]\n"
            "          rpy: ", POSITION_HALF, POSITION_HALF, POSITION_HALF);
    put_vector(out, g->rpy, 3);
    fprintf(out, "\n          rpy_tolerance: [%.2f, %.2f, %.2f]\n",
            RPY_TOLERANCE, RPY_TOLERANCE, RPY_TOLERANCE);
}

static int write_suite(FILE *out, const suite *s, const variant *v)
{
    char path[1024], err[512];
    snprintf(path, sizeof path, "%s/%s", s->dir, s->robot);
    char *urdf = read_file(path);
    mpb_robot *robot;
    if (mpb_robot_open_urdf_joints(urdf, arm_joints, NUM_JOINTS, &robot, err,
                                   sizeof err) != MPB_OK)
        die("%s: %s", path, err);
    if (mpb_robot_link_index(robot, EE_LINK) < 0)
        die("%s: no link " EE_LINK, path);
    int unreachable = 0;
    write_header(out, s, v);
    for (int e = 0; e < s->num_envs; e++) {
        const env *en = &s->envs[e];
        snprintf(path, sizeof path, "%s/%s", s->dir, en->scene);
        char *scene = read_file(path);
        mpb_world *w;
        if (mpb_world_open_group("urdf", urdf, "moveit-scene", scene,
                                 arm_joints, NUM_JOINTS, &w, err,
                                 sizeof err) != MPB_OK)
            die("%s: %s", path, err);
        if (mpb_world_in_collision(w, s->start) != 0)
            die("%s: the start state collides in this scene", path);
        fprintf(out, "  - name: %s\n    format: moveit-scene\n"
                "    file: ../paper/%s\n    queries:\n", en->name, en->scene);
        double prev[NUM_JOINTS];
        memcpy(prev, s->start, sizeof prev);
        int goals = v->goals > 0 && v->goals < en->num_goals ? v->goals
                                                           : en->num_goals;
        for (int k = 0; k < goals; k++) {
            const goal *g = &en->goals[k];
            double q[NUM_JOINTS];
            clock_t t0 = clock();
            int found = solve_goal(robot, w, g,
                                   0x9e3779b97f4a7c15ULL * (uint64_t)(e * 64 + k + 1),
                                   prev, q);
            if (verbose)
                fprintf(stderr, "%s/%s: %d collision-free IK solutions in "
                        "%.0f ms\n", en->name, g->name, found,
                        1e3 * (double)(clock() - t0) / CLOCKS_PER_SEC);
            if (found == 0) {
                fprintf(stderr, "mpb-paper-suite: suite.txt:%d: goal %s of %s "
                        "has no collision-free IK solution in its region\n",
                        g->line, g->name, en->name);
                unreachable++;
                continue;
            }
            fprintf(out, "      - name: %s\n        start: ", g->name);
            put_vector(out, prev, NUM_JOINTS);
            fputc('\n', out);
            write_goal(out, g);
            memcpy(prev, q, sizeof prev);
        }
        mpb_world_close(w);
        free(scene);
    }
    write_planners(out, v);
    mpb_robot_close(robot);
    free(urdf);
    return unreachable;
}

static void usage(FILE *out)
{
    fprintf(out,
        "usage: mpb-paper-suite [--variant NAME | --quick] [--check FILE] [-v] SUITE\n"
        "\n"
        "Write the experiment file of the paper's benchmark from SUITE\n"
        "(scenes/paper/suite.txt): each environment's queries between\n"
        "successive goals, every query's start a fixed collision-free IK\n"
        "solution inside the previous goal's region (the first query starts\n"
        "at the start state).\n"
        "\n"
        "  -V, --variant NAME  paper (the default: 30 runs, 60 s, ten OMPL\n"
        "                      planners), paper-quick (3 runs, 10 s, the\n"
        "                      paper's six) or paper-demo (two goals per\n"
        "                      environment, 3 runs, 5 s, two OMPL planners)\n"
        "  -q, --quick         the same as --variant paper-quick\n"
        "  -c, --check FILE    compare with FILE instead of writing; exit 1 if\n"
        "                      they differ\n"
        "  -v, --verbose       print each goal's IK search to stderr\n"
        "  -h, --help          print this help\n");
}

int main(int argc, char **argv)
{
    static const struct option longopts[] = {
        {"variant", required_argument, NULL, 'V'},
        {"quick", no_argument, NULL, 'q'},
        {"check", required_argument, NULL, 'c'},
        {"verbose", no_argument, NULL, 'v'},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    const variant *v = &variants[0];
    int opt;
    const char *check = NULL;
    while ((opt = getopt_long(argc, argv, "V:qc:vh", longopts, NULL)) != -1) {
        switch (opt) {
        case 'V':
            for (v = variants; v < variants + NUM_VARIANTS; v++)
                if (strcmp(v->name, optarg) == 0)
                    break;
            if (v == variants + NUM_VARIANTS) {
                fprintf(stderr, "mpb-paper-suite: unknown variant '%s' "
                        "(paper, paper-quick, paper-demo)\n", optarg);
                return 2;
            }
            break;
        case 'q': v = &variants[1]; break;
        case 'c': check = optarg; break;
        case 'v': verbose = 1; break;
        case 'h': usage(stdout); return 0;
        default: usage(stderr); return 2;
        }
    }
    if (argc - optind != 1) {
        usage(stderr);
        return 2;
    }
    static suite s;
    parse_suite(argv[optind], &s);

    char *text = NULL;
    size_t len = 0;
    FILE *out = check ? open_memstream(&text, &len) : stdout;
    if (out == NULL)
        die("out of memory");
    int unreachable = write_suite(out, &s, v);
    if (check == NULL)
        return unreachable ? 1 : 0;
    fclose(out);
    char *committed = read_file(check);
    int same = strcmp(committed, text) == 0;
    if (!same)
        fprintf(stderr, "mpb-paper-suite: %s differs from what %s generates; "
                "regenerate it with tools/paper_suite.sh\n", check,
                argv[optind]);
    free(committed);
    free(text);
    return same && unreachable == 0 ? 0 : 1;
}
