/* status.c - the daemon's state on MPB_STATUS, for lcm-spy and `mpb status`. */
#include <math.h>
#include <stdlib.h>

#include "daemon.h"
#include "mpb_daemon_status_t.h"

void mpbd_status_publish(mpbd *d, const char *state, double now)
{
    mpb_planner_seen_t *seen = calloc((size_t)d->num_planners + 1, sizeof *seen);
    /* utime is the start's wall time plus elapsed_s by the monotonic
     * clock, so that utime less elapsed_s (mpb_daemon_started_utime())
     * is exactly this daemon's started_utime, in every status: two
     * daemons that start together then judge which is older alike
     * (daemons.c). Read from two clocks at two moments, the start wobbled
     * by as long as the reads were apart, and under load both once
     * judged the other older, and both stopped. */
    double elapsed = mpb_monotonic_s() - d->started;
    mpb_daemon_status_t st = {
        .utime = d->started_utime + (int64_t)llround(elapsed * 1e6),
        .daemon_id = d->daemon_id,
        .experiment = d->exp->name,
        .state = (char *)state,
        .runs_total = d->runs_total,
        .runs_done = (int32_t)(d->runs_total - d->runs.total_pending - d->runs.num_flights),
        .runs_succeeded = (int32_t)d->count.succeeded,
        .runs_failed = (int32_t)d->count.failed,
        .runs_crashed = (int32_t)d->count.crashed,
        .runs_in_flight = d->runs.num_flights,
        .rejected_messages = (int32_t)d->count.rejected,
        .elapsed_s = elapsed,
        .runs_per_s = elapsed > 0 ? d->count.done / elapsed : 0,
        .num_planners = 0,
        .planners = seen,
    };
    for (int i = 0; seen && i < d->num_planners; i++) {
        const mpbd_planner *p = &d->planners[i];
        if (p->gone)
            continue;
        seen[st.num_planners++] = (mpb_planner_seen_t){
            .planner_id = (char *)p->id,
            .name = p->name ? p->name : "",
            .num_active = (int16_t)p->active,
            .runs_done = p->runs_done,
            .last_seen_s = now - p->last_seen,
        };
    }
    mpb_publish_status(d->lcm, d->auth, d->status_echo, MPB_CHANNEL_STATUS, &st);
    d->status_echo = 0;
    free(seen);
    d->last_status = now;
}
