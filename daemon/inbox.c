/* inbox.c - every message from the network is authenticated (when the
 * daemon has a secret, auth.h: a right tag, from a sender believed, not had
 * before) and checked (wire.h) before it is decoded; a message that fails
 * is counted as rejected and logged. */
#include <stdio.h>

#include "daemon.h"

void mpbd_reject(mpbd *d, const char *channel, const char *why)
{
    d->count.rejected++;
    if (d->count.rejected <= 10 || d->count.rejected % 1000 == 0)
        mpbd_log("rejected a message on %.64s: %s (%ld rejected so far)",
                 channel, why, d->count.rejected);
}

size_t mpbd_message_ok(mpbd *d, mpb_wire_type type, const lcm_recv_buf_t *rbuf,
                       const char *channel)
{
    char why[160] = "";
    size_t len = 0;
    mpb_auth_info info;
    mpb_auth_verdict v = mpb_auth_open(d->auth, channel, rbuf->data,
                                       rbuf->data_size, &len, &info);
    d->msg_from = info.instance;
    /* A log given to --replay is what was heard then: its messages are
     * all from others, and their tags are all that can be checked. */
    if (d->replaying && v != MPB_AUTH_BAD_TAG)
        v = MPB_AUTH_FRESH;
    if (v == MPB_AUTH_FRESH &&
        mpb_wire_check(type, rbuf->data, len, why, sizeof why))
        return len;
    mpbd_reject(d, channel, v == MPB_AUTH_FRESH ? why : mpb_auth_verdict_text(v));
    return 0;
}
