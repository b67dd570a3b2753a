/* inbox.c - every message from the network passes the library's receive
 * gate (link.h: with a secret, a right tag from a sender believed, not
 * had before; its bytes checked; then decoded); a message that fails is
 * counted as rejected and logged. */
#include <stdio.h>
#include <string.h>

#include "daemon.h"

/* Which channel of the message list channel is (a prefix, for one sent
 * to one process), or MPB_WIRE_COUNT for none. */
static int channel_kind(const char *channel)
{
    int best = MPB_WIRE_COUNT;
    size_t best_len = 0;
    for (int t = 0; t < MPB_WIRE_COUNT; t++) {
        const char *c = mpb_wire_channel((mpb_wire_type)t);
        size_t n = strlen(c);
        if (n > best_len && strncmp(channel, c, n) == 0)
            best = t, best_len = n;
    }
    return best;
}

void mpbd_reject(mpbd *d, const char *channel, const char *why)
{
    d->count.rejected++;
    long *on = &d->count.rejected_on[channel_kind(channel)];
    (*on)++;
    if (*on <= 10 || d->count.rejected % 1000 == 0)
        mpbd_log("rejected a message on %.64s: %s (%ld rejected so far)",
                 channel, why, d->count.rejected);
}

int mpbd_receive(mpbd *d, mpb_wire_type type, const lcm_recv_buf_t *rbuf,
                 const char *channel, void *msg)
{
    mpb_received r;
    /* A log given to --replay is what was heard then: its messages are
     * all from others, and their tags are all that can be checked. */
    unsigned accept = d->replaying ? MPB_RECEIVE_AUTHENTIC : MPB_RECEIVE_FRESH;
    int ok = mpb_receive(d->auth, accept, type, channel, rbuf->data,
                         (size_t)rbuf->data_size, msg, &r) == MPB_OK;
    d->msg_from = r.info.instance;
    d->msg_layout = r.layout;
    if (!ok) {
        mpbd_reject(d, channel, r.why);
        if (r.verdict == MPB_AUTH_UNPROVEN)
            d->count.unproven++;
    }
    return ok;
}
