/*
 * hub_internal.h - the hub link's entry points for the rest of net/
 * (hub.h is the public side); not part of the API.
 */
#ifndef MPB_HUB_INTERNAL_H
#define MPB_HUB_INTERNAL_H

#include <lcm/lcm.h>

/* A memq:// instance fed by a new hub link for url (tcpq://), subscribed
 * to these channels at the hub (n == 0: every channel); NULL if the URL
 * is malformed or out of memory. Destroy with mpb_lcm_destroy(). */
lcm_t *mpb__hub_create(const char *url, const char *const *channels, int n);

/* mpb_lcm_publish(); dying: called from a signal handler, when no lock
 * may be waited for (the message is then dropped instead). */
int mpb__hub_publish(lcm_t *lcm, const char *channel, const void *data,
                     unsigned int datalen, int dying);

#endif /* MPB_HUB_INTERNAL_H */
