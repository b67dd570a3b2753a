/* hub.c - the daemon's side of a TCP hub (tcpq://, link.h): the link's
 * comings and goings logged; while it is away, planners' silence and runs'
 * deadlines wait for it (the caller pauses them: mpbd_hub_news); away too
 * long, the daemon stops to be resumed. */
#include "daemon.h"

int mpbd_hub_watch(mpbd *d, double now, double secs, mpbd_hub_news *news)
{
    mpbd_hub *h = &d->hub;
    *news = (mpbd_hub_news){0};
    mpb_hub_stats st;
    mpb_lcm_hub_stats(d->lcm, &st);
    if (!st.is_hub)
        return 0;
    long bad = st.oversized + st.malformed + st.overflowed;
    if (bad != h->bad) {
        h->bad = bad;
        mpbd_log("hub link: dropped %ld frames over the length bounds, %ld "
                 "messages with its queue full; closed %ld connections on "
                 "a frame that was none (so far)", st.oversized,
                 st.overflowed, st.malformed);
    }
    /* Connected, but nothing of its own comes back: the hub is stalled. */
    int echoless = st.connected && h->echo_at > 0 &&
                   now - h->echo_at > MPBD_HUB_ECHO_MAX_S;
    if (st.connected && !echoless) {
        if (h->state == MPBD_HUB_AWAY || h->state == MPBD_HUB_STALLED) {
            mpbd_log("the hub %s after %.1f s (connection %ld)",
                     h->state == MPBD_HUB_AWAY ? "is back"
                                                   : "relays again",
                     now - h->lost_at, st.connects);
            news->relinked = 1;
        } else if (h->state == MPBD_HUB_UNKNOWN) {
            mpbd_log("connected to the hub");
        } else if (st.connects != h->connects) {
            /* Lost and made again within one round of the loop. */
            mpbd_log("reconnected to the hub (connection %ld)", st.connects);
            news->relinked = 1;
        }
        if (h->state != MPBD_HUB_UP || st.connects != h->connects)
            h->echo_at = now;     /* a new link: its echo is to come */
        h->connects = st.connects;
        h->state = MPBD_HUB_UP;
        return 0;
    }
    if (echoless && h->state != MPBD_HUB_STALLED &&
        h->state != MPBD_HUB_AWAY) {
        /* Stalled since its last echo: that time is the hub's too. */
        h->lost_at = h->echo_at;
        if (now - h->echo_at > secs)
            news->away_s += now - h->echo_at - secs;
        mpbd_log("the hub is stalled: connected, but none of this daemon's "
                 "statuses has come back for %.1f s (a client that never "
                 "reads blocks it, docs/topology.md); for at most %.0f s "
                 "planners' silence and runs' deadlines wait",
                 now - h->echo_at, MPBD_HUB_AWAY_MAX_S);
        h->state = MPBD_HUB_STALLED;
    } else if (!st.connected && h->state != MPBD_HUB_AWAY) {
        if (h->state != MPBD_HUB_STALLED)
            h->lost_at = now;
        mpbd_log("%s; trying every %.1f s, for at most %.0f s: meanwhile "
                 "planners' silence and runs' deadlines wait",
                 h->state == MPBD_HUB_UP ? "lost the hub"
                 : h->state == MPBD_HUB_STALLED ? "the stalled hub's "
                                                      "link is closed"
                                             : "cannot reach the hub yet",
                 MPB_HUB_RETRY_S, MPBD_HUB_AWAY_MAX_S);
        h->state = MPBD_HUB_AWAY;
    }
    news->away_s += secs;
    news->stop = now - h->lost_at > MPBD_HUB_AWAY_MAX_S;
    return news->stop;
}

int mpbd_hub_unproven(const mpbd *d, double now)
{
    const mpbd_hub *h = &d->hub;
    return h->state != MPBD_HUB_UNKNOWN && h->echo_at > 0 &&
           now - h->echo_at > MPBD_HUB_ECHO_DUE_S;
}

int mpbd_hub_down(const mpbd *d)
{
    return d->hub.state == MPBD_HUB_AWAY || d->hub.state == MPBD_HUB_STALLED;
}

int mpbd_hub_heard_since(const mpbd *d, double since)
{
    return d->hub.state == MPBD_HUB_UNKNOWN || d->hub.echo_at > since;
}

void mpbd_hub_echo(mpbd *d, double now)
{
    d->hub.echo_at = now;
}
