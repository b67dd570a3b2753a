/* hub.c - the daemon's side of a TCP hub (tcpq://, hub.h): the link's
 * comings and goings logged; while it is away, planners' silence and runs'
 * deadlines wait for it; away too long, the daemon stops to be resumed. */
#include "daemon.h"

int mpbd_hub_watch(mpbd *d, double now, double secs)
{
    mpb_hub_stats st;
    mpb_lcm_hub_stats(d->lcm, &st);
    if (!st.is_hub)
        return 0;
    long bad = st.oversized + st.malformed + st.overflowed;
    if (bad != d->hub_bad) {
        d->hub_bad = bad;
        mpbd_log("hub link: dropped %ld frames over the length bounds, %ld "
                 "messages with its queue full; closed %ld connections on "
                 "a frame that was none (so far)", st.oversized,
                 st.overflowed, st.malformed);
    }
    /* Connected, but nothing of its own comes back: the hub is stalled. */
    int echoless = st.connected && d->hub_echo_at > 0 &&
                   now - d->hub_echo_at > MPBD_HUB_ECHO_MAX_S;
    if (st.connected && !echoless) {
        if (d->hub_state == MPBD_HUB_AWAY || d->hub_state == MPBD_HUB_STALLED) {
            mpbd_log("the hub %s after %.1f s (connection %ld)",
                     d->hub_state == MPBD_HUB_AWAY ? "is back"
                                                   : "relays again",
                     now - d->hub_lost_at, st.connects);
            mpbd_scheduler_relink(d, now);
        } else if (d->hub_state == MPBD_HUB_UNKNOWN) {
            mpbd_log("connected to the hub");
        } else if (st.connects != d->hub_connects) {
            /* Lost and made again within one round of the loop. */
            mpbd_log("reconnected to the hub (connection %ld)", st.connects);
            mpbd_scheduler_relink(d, now);
        }
        if (d->hub_state != MPBD_HUB_UP || st.connects != d->hub_connects)
            d->hub_echo_at = now;     /* a new link: its echo is to come */
        d->hub_connects = st.connects;
        d->hub_state = MPBD_HUB_UP;
        return 0;
    }
    if (echoless && d->hub_state != MPBD_HUB_STALLED &&
        d->hub_state != MPBD_HUB_AWAY) {
        /* Stalled since its last echo: that time is the hub's too. */
        d->hub_lost_at = d->hub_echo_at;
        if (now - d->hub_echo_at > secs)
            mpbd_scheduler_pause(d, now - d->hub_echo_at - secs);
        mpbd_log("the hub is stalled: connected, but none of this daemon's "
                 "statuses has come back for %.1f s (a client that never "
                 "reads blocks it, docs/topology.md); for at most %.0f s "
                 "planners' silence and runs' deadlines wait",
                 now - d->hub_echo_at, MPBD_HUB_AWAY_MAX_S);
        d->hub_state = MPBD_HUB_STALLED;
    } else if (!st.connected && d->hub_state != MPBD_HUB_AWAY) {
        if (d->hub_state != MPBD_HUB_STALLED)
            d->hub_lost_at = now;
        mpbd_log("%s; trying every %.1f s, for at most %.0f s: meanwhile "
                 "planners' silence and runs' deadlines wait",
                 d->hub_state == MPBD_HUB_UP ? "lost the hub"
                 : d->hub_state == MPBD_HUB_STALLED ? "the stalled hub's "
                                                      "link is closed"
                                             : "cannot reach the hub yet",
                 MPB_HUB_RETRY_S, MPBD_HUB_AWAY_MAX_S);
        d->hub_state = MPBD_HUB_AWAY;
    }
    mpbd_scheduler_pause(d, secs);
    return now - d->hub_lost_at > MPBD_HUB_AWAY_MAX_S;
}

int mpbd_hub_unproven(const mpbd *d, double now)
{
    return d->hub_state != MPBD_HUB_UNKNOWN && d->hub_echo_at > 0 &&
           now - d->hub_echo_at > MPBD_HUB_ECHO_DUE_S;
}
