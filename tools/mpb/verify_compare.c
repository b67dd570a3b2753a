/*
 * verify_compare.c - `mpb verify --compare`: every stored stage of an
 * experiment verified again both ways, certified and sampled
 * (docs/verification.md), and the two verdicts compared: where they
 * agree, the stages the certified check newly refuses with the
 * configuration that collides, the stages where the proof fell back to
 * sampling, and, loudly, any sampled collision the certified check
 * passes (which would be a bug).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "view.h"

#define CMD "verify"

typedef struct compare_totals {
    long runs, stages, agree, missed, refused, fell_back;
    double seconds[2];              /* CPU s: certified, sampled */
} compare_totals;

/* CPU time, not wall time: the machine may be busy with other work. */
static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* One stage in one mode: its verdict; 0, or -1 after one line. */
static int verify_as(view_run *v, const view_stage *st, const mpb_goal *goal,
                     double res, mpb_verification mode, int64_t run_id,
                     const char *db, compare_totals *t, mpb_verdict *out)
{
    mpb_world_set_verification(v->world, mode);
    double t0 = now_s();
    int rc = verify_stage(v, st, goal, res, db, run_id, out);
    t->seconds[mode] += now_s() - t0;
    return rc;
}

/* A stage the certified check refuses and the sampled one does not: the
 * colliding configuration, found again, and the bodies touching there. */
static void print_refused(view_run *v, const view_stage *st, double res,
                          int64_t run_id, const mpb_verdict *c,
                          const mpb_verdict *sm)
{
    char place[512];
    printf("newly refused: run %lld %s %s stage %s (stored %s): segment %d",
           (long long)run_id, view_place(v->scene, v->query, place,
                                         sizeof place),
           v->run.planner_config, st->name, st->verdict, c->segment);
    mpb_world_set_verification(v->world, MPB_VERIFY_CERTIFIED);
    double *q = view_calloc((size_t)v->num_joints, sizeof *q);
    mpb_collision_at at;
    if (mpb_find_collision(v->world, st->waypoints, st->num_waypoints,
                           v->num_joints, res, c->segment, q, &at) == 1) {
        printf(" at s=%.17g, q = [", at.s);
        for (int j = 0; j < v->num_joints; j++)
            printf("%s%.17g", j ? ", " : "", q[j]);
        printf("]%s%s", at.bodies[0] ? ", " : "", at.bodies);
    } else {
        printf(": %s", c->detail);
    }
    if (isfinite(c->depth_upper))
        printf("; depth %.3g-%.3g mm", 1e3 * c->depth_lower,
               1e3 * c->depth_upper);
    printf("; sampled: %s\n", mpb_verdict_name(sm->code));
    free(q);
}

static int compare_run(mpb_store *s, const char *db, int64_t run_id,
                       double step, compare_totals *t)
{
    view_run v = {0};
    double res;
    mpb_goal goal;
    int got = verify_read_run(s, db, run_id, step, &v, &res, &goal);
    if (got != 0) {
        view_free(&v);
        return got < 0 ? -1 : 0;    /* no stages: nothing to check */
    }
    char place[512];
    view_place(v.scene, v.query, place, sizeof place);
    t->runs++;
    for (int i = 0; i < v.num_stages; i++) {
        const view_stage *st = &v.stages[i];
        if (st->num_waypoints == 0)
            continue;               /* nothing stored whole to check */
        mpb_verdict c, sm;
        if (verify_as(&v, st, &goal, res, MPB_VERIFY_CERTIFIED, run_id, db, t,
                      &c) != 0 ||
            verify_as(&v, st, &goal, res, MPB_VERIFY_SAMPLED, run_id, db, t,
                      &sm) != 0) {
            view_free(&v);
            return -1;
        }
        t->stages++;
        int c_hit = c.code == MPB_VERDICT_COLLISION;
        int s_hit = sm.code == MPB_VERDICT_COLLISION;
        if (c.code == sm.code) {
            t->agree++;
        } else if (s_hit) {
            t->missed++;
            printf("DISAGREE (a bug in the certified check): run %lld %s "
                   "%s stage %s: sampled collision: %s; certified %s: %s\n",
                   (long long)run_id, place, v.run.planner_config,
                   st->name, sm.detail, mpb_verdict_name(c.code), c.detail);
        } else if (c_hit) {
            t->refused++;
            print_refused(&v, st, res, run_id, &c, &sm);
        }
        if ((c.code == MPB_VERDICT_VALID || c_hit) && !c.certified) {
            t->fell_back++;
            printf("fell back to sampled: run %lld %s %s stage %s: %s\n",
                   (long long)run_id, place, v.run.planner_config,
                   st->name, c.detail);
        }
    }
    view_free(&v);
    return 0;
}

int verify_compare(mpb_store *s, const char *db, int64_t experiment,
                   const selection *sel, double step)
{
    compare_totals t = {0};
    for (int i = 0; i < sel->num_runs; i++)
        if (compare_run(s, db, sel->runs[i], step, &t) != 0)
            return MPB_EXIT_ERROR;
    printf("experiment %lld: %ld runs with stages, %ld stages verified both "
           "ways; %ld agree; %ld sampled collisions the certified check "
           "passes; %ld newly refused by the certified check; %ld fell back "
           "to sampling (CPU: certified %.2f s, sampled %.2f s)\n",
           (long long)experiment, t.runs, t.stages, t.agree, t.missed,
           t.refused, t.fell_back, t.seconds[MPB_VERIFY_CERTIFIED],
           t.seconds[MPB_VERIFY_SAMPLED]);
    if (t.missed)
        fprintf(stderr, "mpb " CMD ": %s: %ld sampled collisions pass the "
                "certified check: a bug, please report it\n", db, t.missed);
    return t.missed ? MPB_EXIT_ERROR : MPB_EXIT_OK;
}
