/*
 * measure.c - one result verified and measured: each stage's verdict
 * (mpbench's own, whatever the planner claims) and metrics, against the
 * query's scene. It touches the experiment's worlds and nothing else of
 * the daemon, so that the verifier's thread may call it while the loop
 * runs (verifier.c).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "daemon.h"

/* Check and measure one stage (mpb_measure_stage()). */
static void measure_stage(const mpbd *d, mpb_world *world, const mpbd_query *q,
                          const mpb_stage_t *st, mpbd_stage_work *w)
{
    const mpbd_experiment *e = d->exp;
    mpb_goal goal = mpbd_query_goal(q);
    char why[200];

    w->rec.name = st->name;
    w->rec.time = st->time;
    if (!mpb_stage_sizes_ok(st, e->num_joints, w->m.verdict.detail,
                            sizeof w->m.verdict.detail)) {
        w->m.verdict.code = MPB_VERDICT_WRONG_SIZE;
        w->m.verdict.segment = -1;
        /* Stored as sent when its sizes agree with its values (another
         * number of joints): the blob is the message's own array. */
        if (st->num_waypoints > 0 && st->num_joints > 0 &&
            (int64_t)st->num_waypoints * st->num_joints == st->num_values) {
            w->rec.num_waypoints = st->num_waypoints;
            w->rec.num_joints = st->num_joints;
            w->rec.waypoints = st->waypoints;
        }
        mpb_measure_metrics(world, w->rec.waypoints, w->rec.num_waypoints,
                            w->rec.num_joints, st->time, d->resolution,
                            &w->m);
    } else if (st->num_times != 0 &&
               !mpb_times_ok(st->times, st->num_times, st->num_waypoints,
                             why, sizeof why)) {
        /* Times that are no timing of the waypoints: refused, the path's
         * own metrics measured (of a path whose values are all finite),
         * the times kept when there is one per waypoint. */
        int finite = 1;
        for (int32_t k = 0; k < st->num_values && finite; k++)
            finite = isfinite(st->waypoints[k]);
        w->m.verdict.code = MPB_VERDICT_BAD_TIMES;
        w->m.verdict.segment = -1;
        snprintf(w->m.verdict.detail, sizeof w->m.verdict.detail,
                 "stage '%.40s' waypoint times: %s", st->name, why);
        w->rec.num_waypoints = st->num_waypoints;
        w->rec.num_joints = st->num_joints;
        w->rec.waypoints = st->waypoints;
        if (st->num_times == st->num_waypoints)
            w->rec.times = st->times;
        mpb_measure_metrics(world, finite ? st->waypoints : NULL,
                            st->num_waypoints, st->num_joints, st->time,
                            d->resolution, &w->m);
    } else {
        w->rec.num_waypoints = st->num_waypoints;
        w->rec.num_joints = st->num_joints;
        w->rec.waypoints = st->waypoints;
        w->rec.times = st->num_times > 0 ? st->times : NULL;
        mpb_measure_stage_timed(world, q->start, q->tolerance, &goal,
                                st->waypoints, w->rec.times,
                                st->num_waypoints, st->num_joints, st->time,
                                d->resolution, 0, &w->m);
    }
    /* Proved over the whole segment, or sampled where the proof could
     * not close (docs/verification.md); a verdict of no path, none. */
    w->rec.verification = mpb_verdict_verification(&w->m.verdict);
    w->rec.valid = w->m.verdict.code == MPB_VERDICT_VALID;
    w->rec.verdict = mpb_verdict_name(w->m.verdict.code);
    w->rec.verdict_detail = w->m.verdict.detail;
    w->rec.verdict_segment = w->m.verdict.segment;
    w->rec.has_depth = w->m.verdict.code == MPB_VERDICT_COLLISION &&
                       isfinite(w->m.verdict.depth_upper);
    w->rec.depth_lower_mm = w->m.verdict.code == MPB_VERDICT_COLLISION
                                ? 1e3 * w->m.verdict.depth_lower : NAN;
    w->rec.depth_upper_mm = w->m.verdict.code == MPB_VERDICT_COLLISION
                                ? 1e3 * w->m.verdict.depth_upper : NAN;
    for (int i = 0; i < w->m.num_metrics; i++)
        w->metrics[i] = (mpb_named){w->m.metrics[i].name,
                                    w->m.metrics[i].value};
    w->rec.metrics = w->metrics;
    w->rec.num_metrics = w->m.num_metrics;
}

/* For tests and bench/backlog.sh only: MPBD_TEST_SLOW_VERIFY=F (1 to
 * 1000) makes every verification take F times as long, by sleeping the
 * difference, as a slower verifier or a heavier scene would. */
static void test_slow_down(mpbd_measured *out)
{
    const char *e = getenv("MPBD_TEST_SLOW_VERIFY");
    double f = e != NULL ? strtod(e, NULL) : 0;
    if (!(f > 1 && f <= 1000))
        return;
    double extra = (f - 1) * (out->verified - out->verify_start);
    struct timespec ts = {(time_t)extra,
                          (long)((extra - (double)(time_t)extra) * 1e9)};
    nanosleep(&ts, NULL);
    out->verified = mpb_monotonic_s();
}

/* The final stage st judged on what was seen, in world seen: as on the
 * truth (a fault of the path's own, its sizes or times, is the same
 * there), without metrics. */
static void judge_seen(const mpbd *d, mpb_world *seen, const mpbd_query *q,
                       const mpb_stage_t *st, const mpbd_stage_work *truth,
                       mpb_stage_measure *out)
{
    mpb_goal goal = mpbd_query_goal(q);
    if (truth->m.verdict.code == MPB_VERDICT_WRONG_SIZE ||
        truth->m.verdict.code == MPB_VERDICT_BAD_TIMES) {
        out->verdict = truth->m.verdict;
        out->num_metrics = 0;
        return;
    }
    mpbd_query_hold_in(d->exp, q, seen);
    mpb_measure_stage_timed(seen, q->start, q->tolerance, &goal,
                            st->waypoints, truth->rec.times,
                            st->num_waypoints, st->num_joints, st->time,
                            d->resolution, MPB_MEASURE_NO_METRICS, out);
}

int mpbd_result_measure(const mpbd *d, const mpbd_worlds *worlds,
                        const mpbd_flight *f, const mpb_plan_result_t *m,
                        mpbd_measured *out)
{
    const mpbd_query *q = &d->exp->queries[f->run.query];
    const mpbd_scene *sc = &d->exp->scenes[q->scene];
    mpb_world *world = worlds != NULL ? worlds->truth[q->scene] : sc->world;
    mpb_world *seen = worlds != NULL ? worlds->seen[q->scene] : sc->seen_world;
    out->works = calloc((size_t)m->num_stages + 1, sizeof *out->works);
    if (out->works == NULL)
        return MPB_ENOMEM;
    /* runs.verify_time: the daemon's verification and metrics of every
     * stage, a cost of the scene (its meshes), not of the planner. */
    out->verify_start = mpb_monotonic_s();
    /* The scene's world holds the joints outside the group as this
     * query does (its start state may set a Panda's fingers). */
    mpbd_query_hold_in(d->exp, q, world);
    for (int i = 0; i < m->num_stages; i++)
        measure_stage(d, world, q, &m->stages[i], &out->works[i]);
    out->judged_seen = seen != NULL && m->num_stages > 0;
    if (out->judged_seen)
        judge_seen(d, seen, q, &m->stages[m->num_stages - 1],
                   &out->works[m->num_stages - 1], &out->seen);
    out->verified = mpb_monotonic_s();
    test_slow_down(out);
    return MPB_OK;
}

void mpbd_measured_free(mpbd_measured *ms)
{
    free(ms->works);
    ms->works = NULL;
}

