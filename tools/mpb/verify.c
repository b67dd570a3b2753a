/*
 * verify.c - `mpb verify`: an experiment's stored runs checked again by this
 * mpbench's verifier and world model, every stage of every finished run,
 * and each verdict that changes listed. The database is only read. It is
 * what tells, after mpbench's world model changed (the whole-body
 * self-collision, an SRDF's matrix), which stored successes still hold.
 */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view.h"

#define CMD "verify"

static void usage(FILE *out)
{
    fprintf(out,
        "usage: mpb verify [-e ID] [-r STEP] [--compare] DB\n"
        "\n"
        "Check the finished runs of an experiment in the database DB again,\n"
        "with this mpbench's verifier and world model: every stage of every\n"
        "run, against its query's start and goal, the joint limits and\n"
        "collisions (the scene and the robot's own body), each segment proved\n"
        "free (a segment the proof cannot finish is sampled every STEP rad).\n"
        "Each stage whose verdict now differs from the stored one is listed,\n"
        "one line each:\n"
        "\n"
        "  run 41 kitchen/counter_cup ompl/RRT stage simplified: stored valid,\n"
        "  now collision: segment 3 ... self-collision between A and B\n"
        "\n"
        "then how deep the collision verdicts go: the median and deepest of\n"
        "their lower and upper bounds (mm) and how many are under 0.1 mm; and\n"
        "one line of totals: the runs that were successes and no longer\n"
        "are, and how many of them go through the robot's own body. Each run\n"
        "is then decided again by mpbenchd's own success rule (docs/metrics.md,\n"
        "\"Claims\"): its stored claim and time, its final stage's verdict now;\n"
        "a run whose outcome (verified, refused, late, unclaimed_valid,\n"
        "unclaimed) differs from the stored one is listed, and a last line\n"
        "counts the outcomes and the runs decided otherwise. The\n"
        "database is not changed. Use it after upgrading mpbench or editing a\n"
        "robot's SRDF, to see what the stored results still say.\n"
        "\n"
        "Options:\n"
        "  -e, --experiment ID  the experiment (default: the newest)\n"
        "  -r, --resolution STEP  the sampling step in rad where a proof\n"
        "                       cannot finish, and of --compare's sampled\n"
        "                       check (default: the one the experiment was\n"
        "                       verified at, else 0.01)\n"
        "  -c, --compare        verify every stage both ways, certified and\n"
        "                       sampled (docs/verification.md), whatever\n"
        "                       was stored, and list where they differ:\n"
        "                       each stage the certified check newly\n"
        "                       refuses with the colliding configuration\n"
        "                       and the bodies touching there, each\n"
        "                       stage whose proof fell back to sampling,\n"
        "                       and, as a bug, any sampled collision the\n"
        "                       certified check passes; then the counts.\n"
        "                       Exit 1 only for such a bug or an error\n"
        "  -h, --help           this text\n"
        "\n"
        "Meshes of a URDF robot are found as mpbenchd finds them\n"
        "($MPB_MESH_PATH, $ROS_PACKAGE_PATH).\n"
        "\n"
        "Exit status: 0 when every verdict is the stored one, 1 when some\n"
        "differ or on an error (a database that is not mpbench's, no such\n"
        "experiment, a world that no longer opens), 2 on a bad command line.\n");
}

typedef struct totals {
    long runs, stages, changed_stages, changed_runs;
    long successes, lost, lost_self, gained;
    long outcomes[MPB_OUTCOME_COUNT];   /* decided again, runs with stages */
    long decided_otherwise;             /* outcome now not the stored one */
    long seen_checked, seen_changed;    /* final stages judged again on what
                                           their planner saw (seen:) */
    /* the depths of the collision verdicts now, mm (upper, lower) */
    double *depth_up, *depth_lo;
    long    collisions, depths, depth_cap;
} totals;

/* A collision verdict's depth kept for the totals; 0, -1 out of memory. */
static int keep_depth(totals *t, const mpb_verdict *v)
{
    if (v->code != MPB_VERDICT_COLLISION)
        return 0;
    t->collisions++;
    if (!isfinite(v->depth_upper))
        return 0;
    if (t->depths == t->depth_cap) {
        long cap = t->depth_cap ? 2 * t->depth_cap : 64;
        double *u = realloc(t->depth_up, (size_t)cap * sizeof *u);
        if (u)
            t->depth_up = u;
        double *l = u ? realloc(t->depth_lo, (size_t)cap * sizeof *l) : NULL;
        if (!l)
            return -1;
        t->depth_lo = l;
        t->depth_cap = cap;
    }
    t->depth_up[t->depths] = 1e3 * v->depth_upper;
    t->depth_lo[t->depths++] = 1e3 * v->depth_lower;
    return 0;
}

/* " (depth L-U mm)" of a collision verdict that has one, else "". */
static const char *depth_text(const mpb_verdict *v, char *buf, size_t len)
{
    buf[0] = '\0';
    if (v->code == MPB_VERDICT_COLLISION && isfinite(v->depth_upper))
        snprintf(buf, len, " (depth %.3g-%.3g mm)", 1e3 * v->depth_lower,
                 1e3 * v->depth_upper);
    return buf;
}

int verify_read_run(mpb_store *s, const char *db, int64_t run_id,
                    double step, view_run *v, double *res, mpb_goal *goal)
{
    char why[512] = "";
    int got = view_read(CMD, s, db, run_id, v, why, sizeof why);
    if (got != 0)
        return got;
    *res = step > 0 ? step : v->resolution;
    *goal = mpb_query_goal(v->goal_kind, v->goal_joints, v->tolerance,
                           v->goal_link, v->goal_region);
    return 0;
}

int verify_stage(const view_run *v, const view_stage *st,
                 const mpb_goal *goal, double res, const char *db,
                 int64_t run_id, mpb_verdict *out)
{
    mpb_stage_measure m;
    /* A stage's times as stored: checked again as the daemon checked them
     * (a stage it refused for them is not checked again, below). */
    const double *times = st->times != NULL &&
        mpb_times_ok(st->times, st->num_waypoints, st->num_waypoints, NULL, 0)
        ? st->times : NULL;
    int rc = mpb_measure_stage_timed(v->world, v->start, v->tolerance, goal,
                                     st->waypoints, times, st->num_waypoints,
                                     v->num_joints, 0, res,
                                     MPB_MEASURE_NO_METRICS, &m);
    *out = m.verdict;
    if (rc != MPB_OK && rc != MPB_EINVAL) {
        fprintf(stderr, "mpb " CMD ": %s: run %lld stage %s: %s\n", db,
                (long long)run_id, st->name, mpb_strerror(rc));
        return -1;
    }
    return 0;
}

/* Whether the collision of verdict now on stage st is with the robot's
 * own body: the colliding configuration found again where the verdict
 * points (mpb_find_collision()) and asked what it touches. */
static int self_collision(const view_run *v, const view_stage *st,
                          const mpb_verdict *now, double res)
{
    if (now->code != MPB_VERDICT_COLLISION)
        return 0;
    double *q = view_calloc((size_t)v->num_joints, sizeof *q);
    mpb_collision_at at;
    int self = mpb_find_collision(v->world, st->waypoints, st->num_waypoints,
                                  v->num_joints, res, now->segment, q,
                                  &at) == 1 &&
               mpb_world_contact(v->world, q, NULL, 0) == MPB_CONTACT_SELF;
    free(q);
    return self;
}

/* One run: each stage verified again; 0, or -1 after one line. */
static int verify_run(mpb_store *s, const char *db, int64_t run_id,
                      double step, totals *t)
{
    view_run v = {0};
    double res;
    mpb_goal goal;
    int got = verify_read_run(s, db, run_id, step, &v, &res, &goal);
    if (got != 0) {
        view_free(&v);
        return got < 0 ? -1 : 0;    /* no stages: nothing to check */
    }
    /* The final stage's verdict as stored, unless it is checked again. */
    int final_valid = v.run.final_valid, final_self = 0, changed = 0;
    t->runs++;
    for (int i = 0; i < v.num_stages; i++) {
        const view_stage *st = &v.stages[i];
        /* Waypoints not stored whole (the wrong size, none), or times that
         * are no timing of them: nothing to check again, and the stored
         * verdict stands. */
        if (st->num_waypoints == 0 ||
            (st->verdict != NULL && strcmp(st->verdict, "bad_times") == 0))
            continue;
        mpb_verdict now;
        if (verify_stage(&v, st, &goal, res, db, run_id, &now) != 0) {
            view_free(&v);
            return -1;
        }
        const char *name = mpb_verdict_name(now.code);
        int valid = now.code == MPB_VERDICT_VALID;
        t->stages++;
        if (keep_depth(t, &now) != 0) {
            fprintf(stderr, "mpb " CMD ": out of memory\n");
            view_free(&v);
            return -1;
        }
        if (i == v.num_stages - 1) {
            final_valid = valid;
            final_self = self_collision(&v, st, &now, res);
        }
        if (strcmp(name, st->verdict) == 0)
            continue;
        changed = 1;
        t->changed_stages++;
        char deep[64];
        printf("run %lld %s/%s %s stage %s: stored %s, now %s%s%s%s\n",
               (long long)run_id, v.scene, v.query, v.run.planner_config,
               st->name, st->verdict, name, now.detail[0] ? ": " : "",
               now.detail, depth_text(&now, deep, sizeof deep));
    }
    t->changed_runs += changed;
    /* Its final stage judged again on what its planner saw, as the daemon
     * judged it (measure.c): its verdict there as stored, or another. */
    const view_stage *last = v.num_stages > 0 ? &v.stages[v.num_stages - 1]
                                              : NULL;
    if (v.seen_world != NULL && v.seen_verdict != NULL && last != NULL &&
        last->num_waypoints > 0 && strcmp(last->verdict, "bad_times") != 0) {
        view_run seen = v;
        seen.world = v.seen_world;
        mpb_verdict now;
        if (verify_stage(&seen, last, &goal, res, db, run_id, &now) != 0) {
            view_free(&v);
            return -1;
        }
        t->seen_checked++;
        const char *name = mpb_verdict_name(now.code);
        if (strcmp(name, v.seen_verdict) != 0) {
            t->seen_changed++;
            printf("run %lld %s/%s %s stage %s on what was seen: stored %s, "
                   "now %s%s%s\n", (long long)run_id, v.scene, v.query,
                   v.run.planner_config, last->name, v.seen_verdict, name,
                   now.detail[0] ? ": " : "", now.detail);
        }
    }
    /* The success rule again (outcome.h), as mpbenchd applied it: the
     * planner's claim and the time it took as stored, the final verdict
     * as found now. */
    int stored_success = v.run.success == 1;
    int success = mpb_run_success(v.run.claimed, final_valid, v.run.in_time);
    mpb_outcome now = mpb_run_outcome(v.run.claimed, final_valid, success);
    mpb_outcome was = mpb_run_outcome(v.run.claimed, v.run.final_valid,
                                      stored_success);
    t->outcomes[now]++;
    if (now != was) {
        t->decided_otherwise++;
        printf("run %lld %s/%s %s: stored %s, now %s\n", (long long)run_id,
               v.scene, v.query, v.run.planner_config, mpb_outcome_name(was),
               mpb_outcome_name(now));
    }
    if (stored_success) {
        t->successes++;
        if (!success) {
            t->lost++;
            t->lost_self += final_self;
        }
    } else if (success) {
        t->gained++;
    }
    view_free(&v);
    return 0;
}

int cmd_verify(int argc, char **argv)
{
    static const struct option longopts[] = {
        {"experiment", required_argument, NULL, 'e'},
        {"resolution", required_argument, NULL, 'r'},
        {"compare", no_argument, NULL, 'c'},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    int64_t experiment = 0;
    double step = 0;
    int opt, compare = 0;
    optind = 1;
    opterr = 0;
    while ((opt = getopt_long(argc, argv, ":e:r:ch", longopts, NULL)) != -1) {
        switch (opt) {
        case 'e':
            if (tool_parse_id(optarg, &experiment) != 0) {
                fprintf(stderr, "mpb " CMD ": --experiment wants an "
                        "experiment id (a number), not '%s'\n", optarg);
                return MPB_EXIT_USAGE;
            }
            break;
        case 'r': {
            char *end;
            step = strtod(optarg, &end);
            if (end == optarg || *end || !(step > 0) || step > 1) {
                fprintf(stderr, "mpb " CMD ": --resolution wants a step in "
                        "rad, more than 0 and at most 1, not '%s'\n", optarg);
                return MPB_EXIT_USAGE;
            }
            break;
        }
        case 'c':
            compare = 1;
            break;
        case 'h':
            usage(stdout);
            return MPB_EXIT_OK;
        default:
            return tool_option_error(CMD, opt, argv);
        }
    }
    if (argc - optind < 1) {
        fprintf(stderr, "mpb " CMD ": wants a database (try 'mpb " CMD
                " --help')\n");
        return MPB_EXIT_USAGE;
    }
    if (argc - optind > 1)
        return tool_extra_argument(CMD, argv[optind + 1]);
    const char *db = argv[optind];
    mpb_store *s = tool_open_readonly(CMD, db);
    if (!s)
        return MPB_EXIT_ERROR;
    int status = MPB_EXIT_ERROR;
    selection sel = {0};
    if (tool_experiment(CMD, s, db, &experiment) != 0)
        goto out;
    if (view_select_runs(s, db, experiment, &sel) != 0)
        goto out;
    if (compare) {
        status = verify_compare(s, db, experiment, &sel, step);
        goto out;
    }
    totals t = {0};
    for (int i = 0; i < sel.num_runs; i++)
        if (verify_run(s, db, sel.runs[i], step, &t) != 0)
            goto out;
    /* How deep the refused stages go (docs/verification.md). */
    mpb_summary lo, up;
    if (t.depths > 0 &&
        mpb_summarize(t.depth_lo, (int)t.depths, &lo) == MPB_OK &&
        mpb_summarize(t.depth_up, (int)t.depths, &up) == MPB_OK) {
        long graze = 0;
        for (long i = 0; i < t.depths; i++)
            graze += t.depth_up[i] < 0.1;
        printf("%ld collision verdicts, %ld with a depth: median %.3g-%.3g "
               "mm, deepest %.3g-%.3g mm, %ld under 0.1 mm\n", t.collisions,
               t.depths, lo.median, up.median, lo.max, up.max, graze);
    }
    printf("experiment %lld: %ld runs with stages, %ld stages verified "
           "again; %ld "
           "stages of %ld runs changed verdict; %ld of %ld successes no "
           "longer hold (%ld through the robot's own body)",
           (long long)experiment, t.runs, t.stages, t.changed_stages,
           t.changed_runs, t.lost, t.successes, t.lost_self);
    if (t.gained)
        printf("; %ld failed runs now verify", t.gained);
    printf("\n");
    if (t.seen_checked > 0)
        printf("%ld final stages judged again on what their planner saw: "
               "%ld changed verdict\n", t.seen_checked, t.seen_changed);
    free(t.depth_up);
    free(t.depth_lo);
    printf("outcomes by the success rule:");
    for (int o = 0; o < MPB_OUTCOME_COUNT; o++)
        printf(" %s %ld%s", mpb_outcome_name((mpb_outcome)o), t.outcomes[o],
               o + 1 < MPB_OUTCOME_COUNT ? "," : "");
    printf("; %ld runs decided otherwise than stored\n", t.decided_otherwise);
    status = t.changed_stages || t.decided_otherwise || t.seen_changed
                 ? MPB_EXIT_ERROR : MPB_EXIT_OK;
out:
    view_selection_free(&sel);
    mpb_store_close(s);
    return status;
}
