/* inbox.c - every message from the network passes the library's receive
 * gate (receive.h: with a secret, a right tag from a sender believed, not
 * had before; its bytes checked; then decoded); a message that fails is
 * counted as rejected and logged. */
#include <stdio.h>

#include "daemon.h"

void mpbd_reject(mpbd *d, const char *channel, const char *why)
{
    d->count.rejected++;
    if (d->count.rejected <= 10 || d->count.rejected % 1000 == 0)
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
    if (!ok) {
        mpbd_reject(d, channel, r.why);
        if (r.verdict == MPB_AUTH_UNPROVEN)
            d->count.unproven++;
    }
    return ok;
}
