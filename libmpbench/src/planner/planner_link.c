/* planner_link.c - a planner's watch of its hub link: the heartbeat's
 * echo that tells a stalled hub, and the lines a stall and an outage
 * are told in (mpbench/planner.h says what the kit does meanwhile). */
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpbench/planner.h"
#include "mpbench/link.h"
#include "mpb_run_ack_t.h"
#include "planner/planner_internal.h"

/* The heartbeat's echo, to this planner itself on its acknowledgement
 * channel (no run, sender_id its own id, and with a secret echoing its
 * own instance, so that its gate believes it): the hub relays it back
 * only while it relays at all. */
void mpb__echo(mpb__server *s)
{
    mpb_run_ack_t a;
    memset(&a, 0, sizeof a);
    a.utime = mpb_utime_now();
    a.attempt_id = "";
    a.sender_id = s->id;
    a.kind = MPB_RUN_ACK_T_REQUEST_RECEIVED;
    mpb_publish_ack(s->lcm, s->auth, mpb_auth_instance(s->auth),
                    s->ack_channel, &a);
}

void mpb__warn(mpb__server *s, const char *fmt, ...)
{
    if (s->def->on_warning == NULL)
        return;
    char line[320];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    s->def->on_warning(s->def->user, line);
}

static void mpb__set_stalled(mpb__server *s, int stalled)
{
    pthread_mutex_lock(&s->mu);
    s->stalled = stalled;
    if (!stalled) {                 /* the daemon hears of it at once */
        s->announce_now = 1;
        pthread_cond_signal(&s->cond);
    }
    pthread_mutex_unlock(&s->mu);
}

/* An echo came back: the hub relays; if it was stalled, say so once and
 * have every result not yet stored sent at once. */
void mpb__echo_back(mpb__server *s)
{
    double now = mpb_monotonic_s();
    s->echo_back_s = now;
    if (!s->stalled)
        return;
    mpb__set_stalled(s, 0);
    s->relays_again = 1;
    mpb__warn(s, "the hub relays again after %.1f s: the results it has "
              "not stored go again now", now - s->stalled_since);
}

/* A hub away (killed, restarted, out of reach) is an outage: say so in
 * one line when the link goes and one when it is back, as the daemon
 * does; the results not stored go again then (mpb__resend_due). */
static void mpb__tell_outage(mpb__server *s, const mpb_hub_stats *st,
                             double now)
{
    if (st->connected && s->link_said == 2)
        mpb__warn(s, "the hub is back after %.1f s (connection %ld): the "
                  "results it has not stored go again now",
                  now - s->link_lost_s, st->connects);
    else if (!st->connected && s->link_said != 2) {
        s->link_lost_s = now;
        mpb__warn(s, "%s; trying again every %.1f s, its results wait "
                  "meanwhile", s->link_said == 1 ? "lost the hub"
                  : "cannot reach the hub yet", MPB_HUB_RETRY_S);
    }
    s->link_said = st->connected ? 1 : 2;
}

/* With nothing waiting to be handled (so that an echo received is one
 * handled, however long a solve kept this thread): connected, and none of
 * the heartbeats' echoes back for stall_s, the hub is stalled. The link
 * away is an outage instead (it reconnects, and the results go again), and
 * a new connection's echo is yet to come. Once stalled, only an echo ends
 * it, whatever the link does meanwhile. */
void mpb__watch_link(mpb__server *s)
{
    if (!s->is_hub || s->stalled)
        return;
    double now = mpb_monotonic_s();
    mpb_hub_stats st;
    mpb_lcm_hub_stats(s->lcm, &st);
    mpb__tell_outage(s, &st, now);
    if (!st.connected || st.connects != s->echo_connects) {
        s->echo_connects = st.connects;
        s->echo_back_s = now;
        return;
    }
    if (now - s->echo_back_s <= s->stall_s)
        return;
    s->stalled_since = s->echo_back_s;
    mpb__set_stalled(s, 1);
    mpb__warn(s, "the hub is stalled: connected, but none of this "
              "planner's heartbeats has come back for %.1f s (a client "
              "that never reads blocks it, docs/topology.md); its results "
              "wait until it relays again", now - s->echo_back_s);
}
