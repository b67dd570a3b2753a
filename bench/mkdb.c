/*
 * mkdb.c - mpb-bench-mkdb: a database of many finished runs, written
 * through the store API exactly as mpbenchd writes them (run added, sent,
 * finished with its stages, metrics and planner values), for timing
 * `mpb report` at scale. Prints how fast the store took the runs: with
 * --batch 1 that is the daemon's pattern of one transaction per result,
 * without the network.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mpbench/mpbench.h"

#include "bench_util.h"

/* A metric's stored name, from the list (mpbench/metrics.h). */
#define NAME(id) (mpb_metric_info_of(MPB_METRIC_##id)->name)

typedef struct options {
    const char *db, *robot, *scene;
    long runs, batch;
    int configs, queries, stages, waypoints;
    int scenes, sets;       /* scenes, in problem sets named set_K */
} options;

static void usage(FILE *out)
{
    fprintf(out,
"usage: mpb-bench-mkdb --db NEW.db --robot FILE --scene FILE --runs N [options]\n"
"\n"
"Writes an experiment of N finished runs through the store API, as\n"
"mpbenchd would: C planner configurations x Q queries, each run with S\n"
"stages of W waypoints, the daemon's five metrics per stage and two\n"
"planner values. About 9 in 10 runs succeed. Prints the write rate.\n"
"\n"
"options:\n"
"  --configs C    planner configurations (default 3)\n"
"  --queries Q    queries per scene (default 5)\n"
"  --scenes N     scenes (default 1, named pillars); with more, named\n"
"                 set_K/NNNN, K from 1 to --sets (default 7), as\n"
"                 MotionBenchMaker's problem sets\n"
"  --sets K       problem sets the scenes are dealt into (default 7)\n"
"  --stages S     stages per run, 1..3: raw, shortcut, smoothed (default 3)\n"
"  --waypoints W  waypoints per stage (default 4)\n"
"  --batch B      runs per transaction (default 10000; 1 = the daemon)\n");
}

static int parse(int argc, char **argv, options *o)
{
    *o = (options){.configs = 3, .queries = 5, .stages = 3, .waypoints = 4,
                   .batch = 10000, .scenes = 1, .sets = 7};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--help") == 0) {
            usage(stdout);
            exit(0);
        }
        if (v == NULL)
            goto bad;
        i++;
        if (strcmp(a, "--db") == 0) o->db = v;
        else if (strcmp(a, "--robot") == 0) o->robot = v;
        else if (strcmp(a, "--scene") == 0) o->scene = v;
        else if (strcmp(a, "--runs") == 0) o->runs = atol(v);
        else if (strcmp(a, "--batch") == 0) o->batch = atol(v);
        else if (strcmp(a, "--configs") == 0) o->configs = atoi(v);
        else if (strcmp(a, "--queries") == 0) o->queries = atoi(v);
        else if (strcmp(a, "--stages") == 0) o->stages = atoi(v);
        else if (strcmp(a, "--waypoints") == 0) o->waypoints = atoi(v);
        else if (strcmp(a, "--scenes") == 0) o->scenes = atoi(v);
        else if (strcmp(a, "--sets") == 0) o->sets = atoi(v);
        else goto bad;
    }
    if (o->db && o->robot && o->scene && o->runs > 0 && o->batch > 0 &&
        o->configs > 0 && o->queries > 0 && o->stages >= 1 && o->stages <= 3 &&
        o->waypoints >= 2 && o->scenes >= 1 && o->sets >= 1)
        return 0;
bad:
    usage(stderr);
    return -1;
}

/* A small deterministic generator (xorshift64*), uniform in [0, 1). */
static double rnd(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ull) >> 11) * 0x1.0p-53;
}

typedef struct run_ref {
    int64_t id;
    int64_t config;      /* planner_config_id */
} run_ref;

typedef struct collect {
    run_ref *runs;
    long     n, cap;
} collect;

static int collect_row(void *ud, const mpb_run_row *row)
{
    collect *c = ud;
    if (c->n == c->cap)
        return MPB_ENOMEM;
    c->runs[c->n++] = (run_ref){row->id, row->planner_config_id};
    return 0;
}

#define CHECK(call)                                                        \
    do {                                                                   \
        int rc_ = (call);                                                  \
        if (rc_ != MPB_OK) {                                               \
            fprintf(stderr, "mpb-bench-mkdb: %s: %s\n", #call,             \
                    mpb_store_errmsg(s));                                  \
            return 1;                                                      \
        }                                                                  \
    } while (0)

int main(int argc, char **argv)
{
    static const char *const algos[] = {"RRTConnect", "RRT", "KPIECE1", "SBL",
                                        "LBKPIECE1", "RRTstar", "PRM", "EST"};
    static const char *const stage_names[] = {"raw", "shortcut", "smoothed"};
    options o;
    mpb_store *s = NULL;
    char attempt[MPB_ATTEMPT_ID_SIZE], name[96], rh[MPB_HASH_SIZE], sh[MPB_HASH_SIZE];
    uint64_t seed = 88172645463325252ull;

    if (parse(argc, argv, &o) != 0)
        return 2;
    char *robot = mpb_read_file(o.robot, 0, NULL);
    char *scene = mpb_read_file(o.scene, 0, NULL);
    if (!robot || !scene) {
        fprintf(stderr, "mpb-bench-mkdb: cannot read %s or %s\n", o.robot,
                o.scene);
        return 1;
    }
    mpb_world *world = NULL;
    char err[256];
    if (mpb_world_open("planar", robot, "planar", scene, &world, err,
                       sizeof err) != MPB_OK) {
        fprintf(stderr, "mpb-bench-mkdb: %s\n", err);
        return 1;
    }
    int nj = mpb_world_num_joints(world);
    const char **jn = calloc((size_t)nj, sizeof *jn);
    for (int j = 0; j < nj; j++)
        jn[j] = mpb_world_joint_name(world, j);
    mpb_hash_hex(robot, strlen(robot), rh);
    mpb_hash_hex(scene, strlen(scene), sh);

    unlink(o.db);
    if (mpb_store_open(o.db, 0, &s) != MPB_OK) {
        fprintf(stderr, "mpb-bench-mkdb: %s\n", mpb_store_errmsg(s));
        return 1;
    }
    int nq = o.scenes * o.queries;
    long per = o.runs / ((long)o.configs * nq);
    if (per < 1)
        per = 1;
    long total = per * o.configs * nq;
    int64_t exp_id, scene_id, *cfg = calloc((size_t)o.configs, sizeof *cfg),
            *qid = calloc((size_t)nq, sizeof *qid);
    double t0 = mpbb_now();

    CHECK(mpb_store_begin(s));
    mpb_experiment_info ei = {.name = "bench-report", .config_file = "mkdb",
                              .config_hash = "0", .config_text = "",
                              .runs_per_query = (int)per, .time_limit = 1.0};
    CHECK(mpb_store_experiment_create(s, &ei, &exp_id));
    for (int c = 0; c < o.configs; c++) {
        char algo[64];
        snprintf(algo, sizeof algo, "%s", algos[c % 8]);
        if (c >= 8)
            snprintf(algo, sizeof algo, "%s%d", algos[c % 8], c / 8);
        snprintf(name, sizeof name, "ompl/%s", algo);
        CHECK(mpb_store_planner_config_add(s, exp_id, name, "ompl", algo, "",
                                           &cfg[c]));
    }
    double *start = calloc((size_t)nj, sizeof *start),
           *goal = calloc((size_t)nj, sizeof *goal);
    for (int k = 0; k < o.scenes; k++) {
        char scene_name[64] = "pillars";
        if (o.scenes > 1)
            snprintf(scene_name, sizeof scene_name, "set_%d/%04d",
                     k % o.sets + 1, k / o.sets + 1);
        mpb_scene_info si = {.name = scene_name, .robot_format = "planar",
                             .robot_hash = rh, .robot = robot,
                             .scene_format = "planar", .scene_hash = sh,
                             .scene = scene};
        CHECK(mpb_store_scene_add(s, exp_id, &si, &scene_id));
        for (int q = 0; q < o.queries; q++) {
            snprintf(name, sizeof name, "query_%d", q);
            for (int j = 0; j < nj; j++)
                goal[j] = 0.1 * (q + 1) * (j % 2 ? -1 : 1);
            mpb_query_info qi = {.name = name, .num_joints = nj,
                                 .joint_names = jn, .start = start,
                                 .goal_kind = MPB_GOAL_JOINTS,
                                 .goal_joints = goal, .goal_tolerance = 0.01};
            CHECK(mpb_store_query_add(s, scene_id, &qi,
                                      &qid[k * o.queries + q]));
        }
    }
    long added = 0;
    for (long r = 0; r < per; r++)
        for (int q = 0; q < nq; q++)
            for (int c = 0; c < o.configs; c++) {
                CHECK(mpb_store_run_add(s, exp_id, cfg[c], qid[q], (int)r,
                                        (int64_t)(r * 1000003 + q * 101 + c)));
                if (++added % o.batch == 0) {
                    CHECK(mpb_store_commit(s));
                    CHECK(mpb_store_begin(s));
                }
            }
    CHECK(mpb_store_commit(s));
    double t1 = mpbb_now();

    collect col = {.runs = calloc((size_t)total, sizeof(run_ref)),
                   .cap = total};
    CHECK(mpb_store_runs_unfinished(s, exp_id, collect_row, &col));

    int nwp = o.waypoints;
    double *wp = calloc((size_t)o.stages * nwp * nj, sizeof *wp);
    mpb_stage_record st[3];
    mpb_named metrics[3][5];
    char *planner_id = "ompl@mpbench-bench-host:4242";
    double t2 = mpbb_now();
    CHECK(mpb_store_begin(s));
    for (long i = 0; i < col.n; i++) {
        int ok = rnd(&seed) < 0.9;
        double t_raw = 0.01 + 0.05 * rnd(&seed), total_t = t_raw;
        snprintf(attempt, sizeof attempt, "%016llx%016llx",
                 (unsigned long long)col.runs[i].id,
                 (unsigned long long)(seed & 0xffffffffffffull));
        CHECK(mpb_store_run_sent(s, col.runs[i].id, attempt, planner_id));
        for (int k = 0; k < o.stages; k++) {
            double *w = wp + (size_t)k * nwp * nj;
            for (int p = 0; p < nwp * nj; p++)
                w[p] = (rnd(&seed) - 0.5) * 2.0;
            double t = k == 0 ? t_raw : 0.002 * rnd(&seed);
            total_t += k ? t : 0;
            metrics[k][0] = (mpb_named){NAME(TIME), t};
            metrics[k][1] = (mpb_named){NAME(WAYPOINTS), nwp};
            metrics[k][2] = (mpb_named){NAME(PATH_LENGTH), 1 + rnd(&seed)};
            metrics[k][3] = (mpb_named){NAME(SMOOTHNESS), rnd(&seed)};
            metrics[k][4] = (mpb_named){NAME(CLEARANCE), 0.1 * rnd(&seed)};
            st[k] = (mpb_stage_record){
                .name = stage_names[k], .time = t, .num_waypoints = nwp,
                .num_joints = nj, .waypoints = w, .valid = ok,
                .verdict = ok ? "valid" : "collision",
                .verdict_detail = ok ? "valid" : "segment 1 collides at s=0.5",
                .verdict_segment = ok ? -1 : 1, .num_metrics = 5,
                .metrics = metrics[k]};
        }
        mpb_named values[2] = {{"graph_states", (double)(int)(100 * rnd(&seed))},
                               {"collision_checks", (double)(int)(1e4 * rnd(&seed))}};
        mpb_run_record rec = {
            .run_id = col.runs[i].id, .attempt_id = attempt, .planner_id = planner_id,
            .status = "solved", .message = "", .claimed_success = 1,
            .success = ok, .time_total = total_t, .time_raw = total_t,
            .time_other = 0, .wall_time = total_t + 0.0002,
            .num_stages = o.stages, .stages = st, .num_values = 2,
            .values = values};
        CHECK(mpb_store_run_finish(s, &rec));
        if ((i + 1) % o.batch == 0) {
            CHECK(mpb_store_commit(s));
            CHECK(mpb_store_begin(s));
        }
    }
    CHECK(mpb_store_commit(s));
    CHECK(mpb_store_experiment_finish(s, exp_id));
    double t3 = mpbb_now();
    mpb_store_close(s);

    printf("%s: %ld runs (%d configurations x %d queries x %ld), %d stage%s of "
           "%d waypoints, %d metric rows per run\n", o.db, col.n, o.configs,
           nq, per, o.stages, o.stages == 1 ? "" : "s", nwp,
           5 * o.stages);
    printf("  added in %.2f s (%.0f runs/s); sent+finished in %.2f s "
           "(%.0f runs/s, %.1f us/run) with %ld runs per transaction\n",
           t1 - t0, total / (t1 - t0), t3 - t2, col.n / (t3 - t2),
           (t3 - t2) / col.n * 1e6, o.batch);
    mpbb_result("mkdb runs=%ld batch=%ld add_s=%.3f finish_s=%.3f "
                "finish_runs_per_s=%.0f finish_us_per_run=%.2f", col.n,
                o.batch, t1 - t0, t3 - t2, col.n / (t3 - t2),
                (t3 - t2) / col.n * 1e6);
    free(col.runs);
    free(wp);
    free(start);
    free(goal);
    free(cfg);
    free(qid);
    free(jn);
    mpb_world_close(world);
    free(robot);
    free(scene);
    return 0;
}
