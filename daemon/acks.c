/*
 * acks.c - acknowledging stored results. A planner keeps each result, and
 * re-sends it, until the daemon says it is stored; the daemon says so only
 * once the transaction that holds it has committed (an acknowledgement is
 * a promise that the result is on disk).
 *
 * After the commit, an acknowledgement is owed to its planner. It rides on
 * the next request that goes to that planner (plan_request_t.stored),
 * which the daemon sends right after that commit if the planner has more
 * to do: one message per run fewer, for the daemon and for every process
 * in the multicast group. One that finds no request within
 * MPBD_ACK_HOLD_S goes out alone, on MPB_ACK_<planner_id>; so does the
 * answer to a result the planner sent again.
 */
#include <stdlib.h>
#include <string.h>

#include "core/grow.h"
#include "daemon.h"
#include "mpb_run_ack_t.h"

void mpbd_ack(mpbd *d, const char *planner_id, const char *attempt_id, int kind)
{
    char channel[sizeof MPB_CHANNEL_ACK_PREFIX + MPB_PLANNER_ID_MAX];
    mpb_run_ack_t ack = {
        .utime = mpb_utime_now(),
        .attempt_id = (char *)attempt_id,
        .sender_id = d->daemon_id,
        .kind = (int8_t)kind,
    };
    /* A result that names no valid planner cannot be answered. A planner
     * built before attempt_id takes its acks in their older layout. */
    if (mpb_ack_channel(planner_id, channel, sizeof channel) == MPB_OK)
        mpb_publish_ack_in(d->lcm, d->auth, d->auth != NULL
                               ? mpbd_planner_instance(d, planner_id) : 0,
                           channel, &ack, mpbd_planner_layout(d, planner_id));
}

static mpbd_ack_due *push(mpbd_ack_due **arr, int *num, int *cap)
{
    if (mpb__grow((void **)arr, cap, *num + 1, sizeof **arr) != MPB_OK)
        return NULL;
    return &(*arr)[(*num)++];
}

int mpbd_ack_after_commit(mpbd *d, const char *planner_id, const char *attempt_id,
                          double sent_at)
{
    mpbd_acks *k = &d->acks;
    if (!mpb_planner_id_is_valid(planner_id) || !mpb_attempt_id_is_valid(attempt_id))
        return MPB_EINVAL;
    mpbd_ack_due *a = push(&k->due, &k->num_due, &k->cap_due);
    if (a == NULL)
        return MPB_ENOMEM;
    memcpy(a->attempt_id, attempt_id, sizeof a->attempt_id);
    memcpy(a->planner_id, planner_id, strlen(planner_id) + 1);
    a->sent_at = sent_at;
    return MPB_OK;
}

void mpbd_acks_flush(mpbd *d)
{
    mpbd_acks *k = &d->acks;
    double now = k->num_due ? mpb_monotonic_s() : 0.0;
    for (int i = 0; i < k->num_due; i++) {
        mpbd_ack_due *a = &k->due[i], *o;
        if (a->sent_at >= 0)
            mpbd_latency_add(&k->latency, now - a->sent_at);
        /* A result sent again: its planner is waiting, answer at once. */
        if (a->sent_at < 0 ||
            (o = push(&k->owed, &k->num_owed, &k->cap_owed)) == NULL) {
            mpbd_ack(d, a->planner_id, a->attempt_id, MPB_RUN_ACK_T_RESULT_STORED);
            continue;
        }
        *o = *a;
        o->due = now + MPBD_ACK_HOLD_S;
    }
    k->num_due = 0;
}

void mpbd_acks_drop(mpbd *d)
{
    d->acks.num_due = 0;
}

int mpbd_acks_due(const mpbd *d)
{
    return d->acks.num_due;
}

int mpbd_owed_take(mpbd *d, const char *planner_id,
                   char (*ids)[MPB_ATTEMPT_ID_SIZE], int max)
{
    mpbd_acks *k = &d->acks;
    int n = 0;
    for (int i = 0; i < k->num_owed && n < max;) {
        if (strcmp(k->owed[i].planner_id, planner_id) != 0) {
            i++;
            continue;
        }
        memcpy(ids[n++], k->owed[i].attempt_id, MPB_ATTEMPT_ID_SIZE);
        k->owed[i] = k->owed[--k->num_owed];
    }
    return n;
}

void mpbd_owed_send(mpbd *d, double now, int all)
{
    mpbd_acks *k = &d->acks;
    for (int i = 0; i < k->num_owed;) {
        if (!all && k->owed[i].due > now) {
            i++;
            continue;
        }
        mpbd_ack(d, k->owed[i].planner_id, k->owed[i].attempt_id,
                 MPB_RUN_ACK_T_RESULT_STORED);
        k->owed[i] = k->owed[--k->num_owed];
    }
}

int mpbd_acks_init(mpbd *d)
{
    return mpbd_latency_init(&d->acks.latency);
}

void mpbd_acks_free(mpbd *d)
{
    mpbd_acks *k = &d->acks;
    free(k->due);
    free(k->owed);
    mpbd_latency_free(&k->latency);
    memset(k, 0, sizeof *k);
}
