/*
 * latency.c - the daemon's own count of each run's latency: from the first
 * send of its request to the commit that stored its result, by the
 * daemon's monotonic clock. With a planner that answers at once, this is
 * what mpbench adds to a run; measured inside, it needs no listener of its
 * own on the network (a listener is one more process woken by every
 * message, and on a small machine it slows what it watches).
 *
 * One counter per microsecond up to MPBD_LATENCY_MAX_US, then one for all
 * longer: exact quantiles to the microsecond where a benchmark of the
 * benchmark needs them, in a fixed 256 KiB however many runs.
 */
#include <stdlib.h>

#include "daemon.h"

int mpbd_latency_init(mpbd_latency *l)
{
    l->count = calloc(MPBD_LATENCY_MAX_US + 1, sizeof *l->count);
    l->n = 0;
    return l->count ? MPB_OK : MPB_ENOMEM;
}

void mpbd_latency_add(mpbd_latency *l, double seconds)
{
    if (l->count == NULL || !(seconds >= 0))
        return;
    double us = seconds * 1e6;
    l->count[us < MPBD_LATENCY_MAX_US ? (int)us : MPBD_LATENCY_MAX_US]++;
    l->n++;
}

/* The smallest latency (us) that at least a fraction p of the runs meet;
 * MPBD_LATENCY_MAX_US stands for "longer", -1 for no runs. */
long mpbd_latency_quantile_us(const mpbd_latency *l, double p)
{
    if (l->count == NULL || l->n == 0)
        return -1;
    uint64_t need = (uint64_t)(p * (double)l->n + 0.5), seen = 0;
    if (need < 1)
        need = 1;
    for (long us = 0; us < MPBD_LATENCY_MAX_US; us++)
        if ((seen += l->count[us]) >= need)
            return us;
    return MPBD_LATENCY_MAX_US;
}

void mpbd_latency_free(mpbd_latency *l)
{
    free(l->count);
    l->count = NULL;
    l->n = 0;
}
