/*
 * auth_internal.h - publishing bytes already encoded, for the planner
 * kit's last words (planner_memory.c); not part of the API.
 */
#ifndef MPB_AUTH_INTERNAL_H
#define MPB_AUTH_INTERNAL_H

#include <stdint.h>

#include <lcm/lcm.h>

#include "mpbench/auth.h"

/*
 * Publish len encoded bytes at buf on channel, sealed with a trailer when
 * a is not NULL (buf must then have MPB_AUTH_TRAILER_SIZE bytes of room
 * after len). Allocates nothing: buf stays the caller's. dying: called
 * from a signal handler, when no lock may be waited for (hub_internal.h).
 * MPB_OK or MPB_ELCM.
 */
int mpb__publish_encoded(lcm_t *lcm, mpb_auth *a, uint64_t echo,
                         const char *channel, unsigned char *buf, int len,
                         int dying);

#endif /* MPB_AUTH_INTERNAL_H */
