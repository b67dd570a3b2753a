/*
 * announce.c - a planner's announcement (MPB_ANNOUNCE) as it arrives: the
 * planner table learns it (planners.c); then what it says it is working
 * on starts its queued runs, frees the slots of runs given up on, and,
 * when it is closing, takes back what it never started (runs.c).
 */
#include "daemon.h"
#include "mpb_planner_announce_t.h"

/* Runs the planner says it plans that this daemon does not know: not in
 * flight, given up on, being verified, just stored, or to be sent again
 * after a restart. Such a run was given up on by this daemon before a
 * restart; each holds a slot of the planner's capacity. */
static int unknown_runs(const mpbd *d, int planner, char *const *active_runs,
                        int num_active)
{
    int unknown = 0;
    for (int k = 0; k < num_active; k++)
        if (mpb_attempt_id_is_valid(active_runs[k]) &&
            !mpbd_runs_knows(d, planner, active_runs[k]) &&
            !mpbd_verifier_has(d, active_runs[k]))
            unknown++;
    return unknown;
}

static void on_announce(mpbd *d, const mpb_planner_announce_t *m)
{
    double now = mpb_monotonic_s();
    mpbd_planner *p = mpbd_planner_learn(d, m, now);
    if (p == NULL)
        return;
    int index = (int)(p - d->planners);
    mpbd_planner_heard(d, index, now);
    int num_active = m->num_active > 0 ? m->num_active : 0;
    int unknown = unknown_runs(d, index, m->active_attempts, num_active);
    if (unknown > 0 && p->unknown == 0)
        mpbd_log("planner %s is planning %d run%s this daemon did not send "
                 "it (given up on before a restart?): it gets no run in "
                 "%s place until it stops", p->id, unknown,
                 unknown == 1 ? "" : "s", unknown == 1 ? "its" : "their");
    else if (unknown == 0 && p->unknown > 0)
        mpbd_log("planner %s has stopped planning the run%s this daemon did "
                 "not send it: it takes runs again", p->id,
                 p->unknown == 1 ? "" : "s");
    mpbd_planner_working_on(d, index, m->active_attempts, num_active, unknown);
    if (p->closing)
        mpbd_planner_closing(d, index, m->active_attempts, num_active);
}

static void on_announce_raw(const lcm_recv_buf_t *rbuf, const char *channel,
                            void *user)
{
    mpb_planner_announce_t m;
    if (!mpbd_receive(user, MPB_WIRE_PLANNER_ANNOUNCE, rbuf, channel, &m))
        return;
    on_announce(user, &m);
    mpb_receive_done(MPB_WIRE_PLANNER_ANNOUNCE, &m);
}

void mpbd_announce_subscribe(mpbd *d)
{
    d->sub_announce = lcm_subscribe(d->lcm, MPB_CHANNEL_ANNOUNCE, on_announce_raw, d);
}

