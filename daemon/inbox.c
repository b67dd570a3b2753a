/* inbox.c - every message from the network is checked (wire.h) before it
 * is decoded; a malformed one is counted as rejected and logged. */
#include "daemon.h"

int mpbd_message_ok(mpbd *d, mpb_wire_type type, const lcm_recv_buf_t *rbuf,
                    const char *channel)
{
    char why[160];
    if (mpb_wire_check(type, rbuf->data, rbuf->data_size, why, sizeof why))
        return 1;
    d->count.rejected++;
    if (d->count.rejected <= 10 || d->count.rejected % 1000 == 0)
        mpbd_log("rejected a malformed message on %.64s: %s (%ld rejected "
                 "so far)", channel, why, d->count.rejected);
    return 0;
}
