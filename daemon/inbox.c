/* inbox.c - every message from the network is authenticated (when the
 * daemon has a secret, auth.h) and checked (wire.h) before it is decoded; a
 * message that fails is counted as rejected and logged. */
#include <stdio.h>

#include "daemon.h"

size_t mpbd_message_ok(mpbd *d, mpb_wire_type type, const lcm_recv_buf_t *rbuf,
                       const char *channel)
{
    char why[160] = "";
    size_t len = 0;
    if (!mpb_auth_check(d->auth, channel, rbuf->data, rbuf->data_size, &len))
        snprintf(why, sizeof why, "missing or wrong authentication tag");
    else if (mpb_wire_check(type, rbuf->data, len, why, sizeof why))
        return len;
    d->count.rejected++;
    if (d->count.rejected <= 10 || d->count.rejected % 1000 == 0)
        mpbd_log("rejected a message on %.64s: %s (%ld rejected so far)",
                 channel, why, d->count.rejected);
    return 0;
}
