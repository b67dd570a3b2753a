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
    if (st.connected) {
        if (d->hub_state == MPBD_HUB_AWAY) {
            mpbd_log("the hub is back after %.1f s (connection %ld)",
                     now - d->hub_lost_at, st.connects);
            mpbd_scheduler_relink(d, now);
        } else if (d->hub_state == MPBD_HUB_UNKNOWN) {
            mpbd_log("connected to the hub");
        } else if (st.connects != d->hub_connects) {
            /* Lost and made again within one round of the loop. */
            mpbd_log("reconnected to the hub (connection %ld)", st.connects);
            mpbd_scheduler_relink(d, now);
        }
        d->hub_connects = st.connects;
        d->hub_state = MPBD_HUB_UP;
        return 0;
    }
    if (d->hub_state != MPBD_HUB_AWAY) {
        d->hub_lost_at = now;
        mpbd_log("%s; trying every %.1f s, for at most %.0f s: meanwhile "
                 "planners' silence and runs' deadlines wait",
                 d->hub_state == MPBD_HUB_UP ? "lost the hub"
                                             : "cannot reach the hub yet",
                 MPB_HUB_RETRY_S, MPBD_HUB_AWAY_MAX_S);
        d->hub_state = MPBD_HUB_AWAY;
    }
    mpbd_scheduler_pause(d, secs);
    return now - d->hub_lost_at > MPBD_HUB_AWAY_MAX_S;
}
