/*
 * lcm_filter.h - a kernel socket filter on LCM's receive socket: it drops
 * the malformed datagrams that would crash LCM's receive thread, and the
 * messages on channels the process does not subscribe to, before they
 * reach the process at all.
 *
 * Malformed datagrams. LCM's UDP receive code (liblcm 1.3.1, and the
 * PyPI binding 1.5.x) trusts the headers it reads: a fragment whose offset
 * is near 2^32 wraps its bounds check and is copied far past its buffer;
 * a channel name without a NUL in the datagram is read past it, and a
 * short message's size goes negative (4294967295 bytes). One datagram
 * from anyone on the LAN would kill every mpbench process. The filter
 * passes only what mpb_lcm_datagram_is_valid() accepts, so LCM never sees
 * the rest (docs/reliability.md).
 *
 * Channels. UDP multicast delivers every message to every process of the
 * group, its sender included, and each one wakes the process's LCM
 * receive thread, which reads it, looks up the channel and drops it. In a
 * benchmark of quick planners most messages are for someone else, and
 * those wake-ups cost more CPU than the work (bench/results/history.md,
 * change 15). A filter given channel names passes a short message ("LC02")
 * only if its channel is one of them, exactly. The fragments of a long
 * message ("LC03") all pass if they are valid: only the first names its
 * channel.
 *
 * lcm-spy and other listeners have sockets of their own and see every
 * message, malformed ones included, unless their socket is filtered too
 * (mpb spy filters lcm-spy's).
 */
#ifndef MPBENCH_LCM_FILTER_H
#define MPBENCH_LCM_FILTER_H

#include <stddef.h>

#include <linux/filter.h>
#include <lcm/lcm.h>

#ifdef __cplusplus
extern "C" {
#endif

/*
 * The largest LCM message (encoded, without LCM's headers) an mpbench
 * process accepts: 16 MiB. The largest are results, whose stages
 * carry trajectories (a 7-joint path of 299,000 waypoints is 16 MiB), and
 * requests, which carry the robot and scene text. liblcm keeps at most
 * 16 MiB of partly received messages in all, so a larger one would push
 * every other out while it arrives. A fragment claiming a larger message
 * is dropped. The daemon refuses an experiment whose requests would be
 * larger, and the planner kits send a failure instead of such a result.
 */
#define MPB_LCM_MESSAGE_MAX (16u << 20)

/* LCM's longest channel name (LCM_MAX_CHANNEL_NAME_LENGTH); LCM refuses
 * to publish a longer one. */
#define MPB_LCM_CHANNEL_MAX 63

/* The most payload one fragment can carry: a UDP datagram over IPv4 holds
 * at most 65,507 bytes, less LCM's 20-byte fragment header. */
#define MPB_LCM_FRAGMENT_PAYLOAD_MAX 65487u

/* The most channels, and the longest channel name, a filter can hold. A
 * longer list, or a longer name (one LCM could not carry), makes a filter
 * that keeps every channel and still drops what is malformed. */
#define MPB_LCM_FILTER_CHANNELS 8
#define MPB_LCM_FILTER_NAME_MAX MPB_LCM_CHANNEL_MAX

/* The most instructions a filter program has (mpb_lcm_filter_program). */
#define MPB_LCM_FILTER_PROGRAM_MAX 1024

/*
 * 1 if the len bytes at buf (one UDP datagram's payload) are a
 * well-formed LCM datagram, else 0. This is the readable specification of
 * the socket filter, which must agree with it (tests/fuzz/fuzz_lcm_filter.c):
 *
 * - At least 8 bytes: magic and sequence number, big-endian.
 * - Magic "LC02", a short message: the channel follows the 8-byte header
 *   and ends with a NUL within the datagram, after at most
 *   MPB_LCM_CHANNEL_MAX characters; the message is the rest.
 * - Magic "LC03", a fragment of a long message: a 20-byte header of magic,
 *   sequence number, message size (32 bits), fragment offset (32 bits),
 *   fragment number and fragment count (16 bits each), then the payload;
 *   fragment 0 starts it with the channel as above. Then:
 *     1 <= message size <= MPB_LCM_MESSAGE_MAX;
 *     1 <= fragment count <= message size, and fragment count times
 *       MPB_LCM_FRAGMENT_PAYLOAD_MAX >= message size;
 *     fragment number < fragment count;
 *     fragment 0 is at offset 0;
 *     the payload (after fragment 0's channel) is at least one byte, and
 *       offset + payload <= message size (no 32-bit wrap: the sizes are
 *       bounded first);
 *     the fragment that ends at the message size is the last (number
 *       count - 1), and the last ends there.
 * - Any other magic: not LCM, 0.
 */
int mpb_lcm_datagram_is_valid(const void *buf, size_t len);

/*
 * The filter program (classic BPF, as SO_ATTACH_FILTER takes it) for the
 * n channels named: into ops (room for max instructions), returning how
 * many it wrote, or -1 if they do not fit. n == 0 (channels may be NULL),
 * more than MPB_LCM_FILTER_CHANNELS, or a name longer than
 * MPB_LCM_FILTER_NAME_MAX: a program that keeps every channel. The program
 * sees a datagram with its 8-byte UDP header first; it returns 0 to drop
 * it, nonzero to pass it. A load past the datagram's end drops it, as the
 * kernel does. MPB_LCM_FILTER_PROGRAM_MAX is always room enough.
 */
int mpb_lcm_filter_program(const char *const *channels, int n,
                           struct sock_filter *ops, int max);

/*
 * Attach the program for these channels (as mpb_lcm_filter_program) to
 * the socket fd. MPB_OK, or MPB_ELCM if the kernel refuses it (errno says
 * why).
 */
int mpb_lcm_filter_socket(int fd, const char *const *channels, int n);

/*
 * This process's UDP sockets bound to the port of url (a udpm:// URL;
 * NULL for MPB_DEFAULT_LCM_URL):
 * their descriptors in fds, at most max; returns how many (0 for a URL
 * that is not udpm://). With a list taken before an LCM instance is made
 * and one after, the new descriptor is that instance's receive socket:
 * how a binding that makes its own socket (Python's) is filtered.
 */
int mpb_lcm_sockets(const char *url, int *fds, int max);


#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_LCM_FILTER_H */
