/*
 * daemons.c - the other daemons on the same LCM URL, heard from their
 * status messages.
 *
 * Two daemons on one URL share its planners without knowing of each
 * other: each sends requests to planners busy with the other's runs, and
 * answers the other's results as strays, which stops the planner from
 * re-sending them. So one of the two stops: the one that started later,
 * before it sends anything. A daemon publishes its status as its loop
 * starts and sends no request in its first MPBD_LISTEN_S; one that hears
 * a younger daemon's status answers at once with its own, and the younger
 * one stops on hearing it. Daemons with different secrets (auth.h) do not
 * hear each other, and need not: their planners do not answer each other.
 */
#include <stdio.h>
#include <string.h>

#include "daemon.h"
#include "mpb_daemon_status_t.h"

static void on_status(mpbd *d, const mpb_daemon_status_t *m, double now)
{
    if (strcmp(m->daemon_id, d->daemon_id) == 0 ||
        (strcmp(m->state, "waiting") != 0 && strcmp(m->state, "running") != 0))
        return;                 /* itself, or one that is ending */
    int64_t theirs = mpb_daemon_started_utime(m);
    if (mpb_daemon_started_before(theirs, m->daemon_id, d->started_utime,
                                  d->daemon_id)) {
        if (d->elder[0] == '\0')
            snprintf(d->elder, sizeof d->elder, "%s (experiment '%s', "
                     "started %.1f s before this one)", m->daemon_id,
                     m->experiment, (double)(d->started_utime - theirs) * 1e-6);
        return;
    }
    /* A younger one: it stops once it hears this one. */
    if (strcmp(d->younger_logged, m->daemon_id) != 0) {
        mpbd_log("another mpbenchd, %s (experiment '%s'), started on this "
                 "LCM URL after this one: it stops", m->daemon_id,
                 m->experiment);
        snprintf(d->younger_logged, sizeof d->younger_logged, "%s",
                 m->daemon_id);
    }
    /* At once, whenever this one published last: the younger one waits
     * MPBD_LISTEN_S for it, and publishes once a second itself. */
    mpbd_status_publish(d, d->num_planners ? "running" : "waiting", now);
}

static void on_status_raw(const lcm_recv_buf_t *rbuf, const char *channel,
                          void *user)
{
    mpbd *d = user;
    mpb_daemon_status_t m;
    size_t len;
    /* Checked quietly: a daemon with another secret, or none, is no
     * concern of this one, and its status is not a rejected message. */
    if (!mpb_auth_check(d->auth, channel, rbuf->data, rbuf->data_size, &len) ||
        !mpb_wire_check(MPB_WIRE_DAEMON_STATUS, rbuf->data, len, NULL, 0) ||
        mpb_daemon_status_t_decode(rbuf->data, 0, (int)len, &m) < 0)
        return;
    on_status(d, &m, mpb_monotonic_s());
    mpb_daemon_status_t_decode_cleanup(&m);
}

void mpbd_daemons_subscribe(mpbd *d)
{
    d->sub_status = lcm_subscribe(d->lcm, MPB_CHANNEL_STATUS, on_status_raw, d);
}
