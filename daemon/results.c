/*
 * results.c - a planner's answer as it arrives: is it for a run we sent,
 * to that planner? Then it is measured (measure.c) beside the loop
 * (verifier.c) or, when quick, at once, and recorded (record.c).
 */
#include <string.h>

#include "daemon.h"
#include "mpb_plan_result_t.h"
#include "mpb_run_ack_t.h"

/* recv: when the result arrived, by the monotonic clock. */
static void on_result(mpbd *d, const mpb_plan_result_t *m, double recv)
{
    mpbd_flight *f;

    if (!mpb_attempt_id_is_valid(m->attempt_id)) {
        /* No run has such an id: answered so that a planner stops
         * re-sending it (if it names a valid planner to answer). */
        mpbd_result_reject(d, "malformed attempt id", m);
        mpbd_ack(d, m->planner_id, m->attempt_id, MPB_RUN_ACK_T_RESULT_REJECTED);
        return;
    }
    if ((f = mpbd_flight_find(d, m->attempt_id)) == NULL) {
        /* Being verified: acknowledged once stored. */
        if (mpbd_verifier_has(d, m->attempt_id))
            return;
        if (mpbd_recently_done(d, m->attempt_id)) {
            /* Stored, perhaps in the transaction still open: acknowledged
             * again once that commits. */
            mpbd_ack_after_commit(d, m->planner_id, m->attempt_id, -1.0);
            return;
        }
        mpbd_result_reject(d, "no such run in flight", m);
        mpbd_ack(d, m->planner_id, m->attempt_id, MPB_RUN_ACK_T_RESULT_REJECTED);
        return;
    }
    if (strcmp(d->planners[f->planner].id, m->planner_id) != 0) {
        /* Not acknowledged: the planner the run went to may still answer. */
        mpbd_result_reject(d, "sent by a planner the run did not go to", m);
        return;
    }
    mpbd_planner_heard(d, f->planner, mpb_monotonic_s());
    /* Verified beside the loop (verifier.c): the run's flight ends now,
     * so that its planner's next request need not wait; unless it is
     * known to be quick. */
    if (!mpbd_verifier_quick(d, f, m) &&
        mpbd_verifier_submit(d, f, m, recv) == MPB_OK) {
        mpbd_flight_remove(d, f);
        return;
    }
    mpbd_measured ms = {0};
    int rc = MPBD_RETRY;        /* out of memory: the planner re-sends */
    if (mpbd_result_measure(d, NULL, f, m, &ms) == MPB_OK) {
        mpbd_verifier_learn(d, f, m, &ms);
        rc = mpbd_result_store(d, f, m, recv, &ms);
    }
    mpbd_measured_free(&ms);
    if (rc != MPBD_RETRY)
        mpbd_flight_remove(d, f);
}

static void on_result_raw(const lcm_recv_buf_t *rbuf, const char *channel,
                          void *user)
{
    mpb_plan_result_t m;
    if (!mpbd_receive(user, MPB_WIRE_PLAN_RESULT, rbuf, channel, &m))
        return;
    /* When it arrived, from LCM's receive time (the kernel's, where it
     * keeps one): not when a busy daemon got round to it. */
    double now = mpb_monotonic_s();
    double waited = (double)(mpb_utime_now() - rbuf->recv_utime) * 1e-6;
    on_result(user, &m, waited > 0 && waited < 3600 ? now - waited : now);
    mpb_receive_done(MPB_WIRE_PLAN_RESULT, &m);
}

void mpbd_results_subscribe(mpbd *d)
{
    d->sub_result = lcm_subscribe(d->lcm, MPB_CHANNEL_RESULT, on_result_raw, d);
}

