/*
 * daemons.c - the other daemons on the same LCM URL, heard from their
 * status messages.
 *
 * Two daemons on one URL share its planners without knowing of each
 * other: each sends requests to planners busy with the other's runs, and
 * answers the other's results as strays, which stops the planner from
 * re-sending them. So one of the two stops: the one that started later,
 * before it sends anything. A daemon publishes its status as its loop
 * starts and sends no request in its first MPBD_LISTEN_S (longer if it
 * hears a planner echo another daemon meanwhile: main.c); one that hears
 * a younger daemon's status answers at once with its own, and the younger
 * one stops on hearing it. Daemons with different secrets (auth.h) do not
 * hear each other, and need not: their planners do not answer each other;
 * each counts the other's status as a rejected message, as it counts a
 * forged one, which it cannot tell from it.
 * A status the daemon cannot trust does not stop it once it has sent a
 * request (believe_elder()).
 */
#include <stdio.h>
#include <string.h>

#include "daemon.h"
#include "mpb_daemon_status_t.h"

/* 1 if this daemon may believe that the daemon whose status it holds
 * started first and runs: then it stops. With a secret, the status must
 * be fresh (auth.h): the elder's answer to this one's status echoes it,
 * while a recorded status replayed echoes another. Without one, anybody
 * on the network may send any status: it is believed only before this
 * daemon's first request, when stopping loses nothing (a daemon that has
 * sent requests goes on; docs/reliability.md). */
static int believe_elder(mpbd *d, const mpb_daemon_status_t *m,
                         mpb_auth_verdict v, const char *channel)
{
    if (d->auth != NULL) {
        if (v == MPB_AUTH_FRESH)
            return 1;
        mpbd_reject(d, channel, mpb_auth_verdict_text(v));
        return 0;
    }
    if (!d->requested)
        return 1;
    if (strcmp(d->ignored_elder, m->daemon_id) != 0) {
        snprintf(d->ignored_elder, sizeof d->ignored_elder, "%s",
                 m->daemon_id);
        char id[4 * MPB_PLANNER_ID_MAX + 1];
        mpb_escape(m->daemon_id, id, sizeof id);
        mpbd_log("a status from %s says it started on this LCM URL before "
                 "this one: ignored, since this one has sent requests "
                 "already and without --secret-file a status may be forged",
                 id);
    }
    d->count.rejected++;
    return 0;
}

static void on_status(mpbd *d, const mpb_daemon_status_t *m,
                      mpb_auth_verdict v, const mpb_auth_info *info,
                      const char *channel, double now)
{
    if (strcmp(m->daemon_id, d->daemon_id) == 0 ||
        (d->auth != NULL && info->instance == mpb_auth_instance(d->auth))) {
        mpbd_hub_echo(d, now);   /* itself: through a hub, the link works */
        return;
    }
    int ending = strcmp(m->state, "waiting") != 0 &&
                 strcmp(m->state, "running") != 0;
    int64_t theirs = mpb_daemon_started_utime(m);
    if (mpb_daemon_started_before(theirs, m->daemon_id, d->started_utime,
                                  d->daemon_id)) {
        /* One that is ending is no concern; with a secret, one that
         * cannot be believed is counted all the same (a replay). */
        if ((ending && d->auth == NULL) || !believe_elder(d, m, v, channel) ||
            ending)
            return;
        if (d->elder[0] == '\0') {
            char id[4 * MPB_PLANNER_ID_MAX + 1], exp[160];
            mpb_escape(m->daemon_id, id, sizeof id);
            mpb_escape(m->experiment, exp, sizeof exp);
            snprintf(d->elder, sizeof d->elder, "%s (experiment '%s', "
                     "started %.1f s before this one)", id, exp,
                     (double)(d->started_utime - theirs) * 1e-6);
        }
        return;
    }
    if (v == MPB_AUTH_REPLAYED) {
        mpbd_reject(d, channel, mpb_auth_verdict_text(v));
        return;
    }
    if (ending)
        return;
    /* A younger one: it stops once it hears this one. Answering needs no
     * trust: a replayed status costs one status more. */
    if (strcmp(d->younger_logged, m->daemon_id) != 0) {
        char id[4 * MPB_PLANNER_ID_MAX + 1], exp[160];
        mpb_escape(m->daemon_id, id, sizeof id);
        mpb_escape(m->experiment, exp, sizeof exp);
        mpbd_log("another mpbenchd, %s (experiment '%s'), started on this "
                 "LCM URL after this one: it stops", id, exp);
        snprintf(d->younger_logged, sizeof d->younger_logged, "%s",
                 m->daemon_id);
    }
    /* At once, whenever this one published last: the younger one waits
     * MPBD_LISTEN_S for it, and publishes once a second itself. With a
     * secret, the answer echoes it, so that it can believe it. */
    d->status_echo = info->instance;
    mpbd_status_publish(d, d->num_planners ? "running" : "waiting", now);
}

static void on_status_raw(const lcm_recv_buf_t *rbuf, const char *channel,
                          void *user)
{
    mpbd *d = user;
    mpb_daemon_status_t m;
    mpb_received r;
    /* Without the right tag a status may be a daemon's with another
     * secret (or none), which is no concern of this one, or a forgery:
     * the two cannot be told apart, and a forgery is what the count and
     * the log are for, so both are counted and logged as every dropped
     * message is (mpbd_reject() limits the lines). Another secret's
     * daemon costs a count a second; docs/protocol.md says so. */
    if (mpb_receive(d->auth, MPB_RECEIVE_AUTHENTIC, MPB_WIRE_DAEMON_STATUS,
                    channel, rbuf->data, (size_t)rbuf->data_size, &m, &r)
            != MPB_OK) {
        mpbd_reject(d, channel, r.verdict == MPB_AUTH_BAD_TAG
                    ? "a daemon status without the right tag (another "
                      "secret's daemon, or forged)"
                    : r.why);
        return;
    }
    on_status(d, &m, r.verdict, &r.info, channel, mpb_monotonic_s());
    mpb_receive_done(MPB_WIRE_DAEMON_STATUS, &m);
}

void mpbd_daemons_subscribe(mpbd *d)
{
    d->sub_status = lcm_subscribe(d->lcm, MPB_CHANNEL_STATUS, on_status_raw, d);
}
