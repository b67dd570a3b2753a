/*
 * lcm_filter.h - let the kernel drop the multicast messages a process does
 * not subscribe to, before they wake anything in it.
 *
 * LCM's UDP multicast delivers every message to every process of the
 * group, its sender included: each one wakes the process's LCM receive
 * thread, which reads it, looks up the channel and drops it. In a
 * benchmark of quick planners most messages are for someone else (the
 * requests to the other planners, their results, one's own messages), and
 * those wake-ups cost more CPU than the work
 * (docs/performance-history.md, change 15).
 *
 * mpb_lcm_create_keeping() attaches a socket filter (classic BPF) to a new
 * LCM instance's receive socket that passes a message only if its channel
 * is one of the given names, exactly. It reads LCM's UDP format: a short
 * message (magic "LC02") names its channel after an 8-byte header; the
 * fragments of a long one ("LC03") are all passed, as is anything else,
 * so a format it does not know loses nothing. lcm-spy and other
 * listeners have sockets of their own and still see every message.
 */
#ifndef MPBENCH_LCM_FILTER_H
#define MPBENCH_LCM_FILTER_H

#include <lcm/lcm.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The most channels, and the longest channel name, a filter can hold. */
#define MPB_LCM_FILTER_CHANNELS 8
#define MPB_LCM_FILTER_NAME_MAX 127

/*
 * lcm_create(url), with a filter on the new instance's receive socket that
 * passes only the n channels named (exact names, no patterns). The socket
 * is the one UDP socket on url's port that appears while the instance is
 * made (its receive side is set up at once, as lcm_get_fileno() does).
 * *filtered (if not NULL) says whether the filter is on: 0 for a URL that
 * is not udpm://, too many (MPB_LCM_FILTER_CHANNELS) or too long names,
 * a socket not found or not alone, or a kernel that refused the filter;
 * the instance then receives every message, as a plain one does.
 * NULL if lcm_create() fails.
 */
lcm_t *mpb_lcm_create_keeping(const char *url, const char *const *channels,
                              int n, int *filtered);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_LCM_FILTER_H */
