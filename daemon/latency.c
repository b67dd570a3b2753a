/*
 * latency.c - the daemon's own count of each run's latency: from the first
 * send of its request to the commit that stored its result, by the
 * daemon's monotonic clock. With a planner that answers at once, this is
 * what mpbench adds to a run; measured inside, it needs no listener of its
 * own on the network (a listener is one more process woken by every
 * message, and on a small machine it slows what it watches).
 *
 * One counter per microsecond up to 65.536 ms, then one per millisecond
 * up to 65.536 s, then one per second up to 18 hours, then one for all
 * longer: exact quantiles to the microsecond where a benchmark of the
 * benchmark needs them, to 0.1 % or better above, in a fixed 768 KiB
 * however many runs. (One tier of microseconds alone saturated at 65 ms,
 * and a run that plans for a second is longer than that.)
 */
#include <stdlib.h>

#include "daemon.h"

/* Each tier's unit, us. */
static const long tier_unit[MPBD_LATENCY_TIERS] = {1L, 1000L, 1000000L};

#define NUM_COUNTS ((size_t)MPBD_LATENCY_TIERS * MPBD_LATENCY_TIER + 1)

int mpbd_latency_init(mpbd_latency *l)
{
    l->count = calloc(NUM_COUNTS, sizeof *l->count);
    l->n = 0;
    return l->count ? MPB_OK : MPB_ENOMEM;
}

void mpbd_latency_add(mpbd_latency *l, double seconds)
{
    if (l->count == NULL || !(seconds >= 0))
        return;
    double us = seconds * 1e6;
    size_t i = NUM_COUNTS - 1;
    for (int t = 0; t < MPBD_LATENCY_TIERS; t++)
        if (us / (double)tier_unit[t] < MPBD_LATENCY_TIER) {
            i = (size_t)t * MPBD_LATENCY_TIER +
                (size_t)(us / (double)tier_unit[t]);
            break;
        }
    l->count[i]++;
    l->n++;
}

/* The smallest latency (us) that at least a fraction p of the runs meet,
 * to its tier's unit; MPBD_LATENCY_MAX_US stands for "longer", -1 for no
 * runs. */
long mpbd_latency_quantile_us(const mpbd_latency *l, double p)
{
    if (l->count == NULL || l->n == 0)
        return -1;
    uint64_t need = (uint64_t)(p * (double)l->n + 0.5), seen = 0;
    if (need < 1)
        need = 1;
    for (size_t i = 0; i + 1 < NUM_COUNTS; i++)
        if ((seen += l->count[i]) >= need) {
            long us = (long)(i % MPBD_LATENCY_TIER) *
                      tier_unit[i / MPBD_LATENCY_TIER];
            /* A tier's first counters overlap the tier below: its own
             * values start where that one ends. */
            long floor = i < MPBD_LATENCY_TIER ? 0 :
                (long)MPBD_LATENCY_TIER * tier_unit[i / MPBD_LATENCY_TIER - 1];
            return us > floor ? us : floor;
        }
    return MPBD_LATENCY_MAX_US;
}

void mpbd_latency_free(mpbd_latency *l)
{
    free(l->count);
    l->count = NULL;
    l->n = 0;
}
