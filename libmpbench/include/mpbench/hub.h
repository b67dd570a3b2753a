/*
 * hub.h - LCM through a TCP hub (tcpq://HOST:PORT), for hosts that
 * multicast does not reach.
 *
 * The hub is lcm-java's lcm.lcm.TCPService: every client sends it the
 * channels it wants, and it relays each message published by any client
 * to every client that wants that channel. mpb_lcm_create_keeping()
 * (lcm_filter.h) given a tcpq:// URL speaks to it with this library's own
 * client instead of liblcm's, for three reasons found in liblcm 1.3.1's:
 * it allocates whatever length a frame claims (4 GiB for 0xffffffff);
 * its descriptor is the TCP socket itself, which changes when it
 * reconnects and makes lcm_handle() block until a whole frame is in; and
 * its publishing takes no lock, so two threads publishing at once (a
 * planner's heartbeat and its result) interleave their bytes and the hub
 * stops relaying that client.
 *
 * The instance returned is a plain lcm_t (liblcm's memq:// provider):
 * lcm_subscribe(), lcm_get_fileno() (readable whenever a message waits)
 * and lcm_handle() work on it as usual. A thread of the library keeps the
 * connection: it connects (and reconnects, every MPB_HUB_RETRY_S, when the
 * hub goes away), subscribes to the channels given at creation, reads
 * frames, and hands each to the instance's queue. Every length is checked
 * before anything is allocated: a channel name over MPB_LCM_CHANNEL_MAX
 * or a message over MPB_LCM_MESSAGE_MAX is read past and dropped, a frame
 * that is not a message closes the connection (then reconnects), and at
 * most MPB_HUB_QUEUE_MAX bytes wait in the queue (more are dropped, as a
 * full UDP receive buffer drops datagrams). Publishing must go through
 * mpb_lcm_publish() (the mpb_publish_... functions of auth.h do), one frame
 * at a time under a lock; a message published while the hub is away is
 * lost, as a datagram may be, and the protocol's re-sends cover it.
 */
#ifndef MPBENCH_HUB_H
#define MPBENCH_HUB_H

#include <lcm/lcm.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Seconds between attempts to reach a hub that is away. */
#define MPB_HUB_RETRY_S 0.5
/* Bytes of received messages that may wait for lcm_handle(). */
#define MPB_HUB_QUEUE_MAX (64u << 20)

/* 1 if url names a hub (tcpq://...). */
int mpb_lcm_url_is_hub(const char *url);

/* What a hub link has seen (all zero for an instance that is not one). */
typedef struct mpb_hub_stats {
    int  is_hub;        /* 1 for an instance made for a tcpq:// URL */
    int  connected;     /* the connection is up now */
    long connects;      /* connections made, the first included */
    long oversized;     /* frames dropped: a length over the bounds, or
                           a channel name with a NUL in it */
    long overflowed;    /* messages dropped with the queue full */
    long malformed;     /* connections closed for a frame that was not one */
} mpb_hub_stats;

/* Fill *out for lcm (any instance; NULL-safe). */
void mpb_lcm_hub_stats(lcm_t *lcm, mpb_hub_stats *out);

/*
 * Wait up to timeout_s seconds for a hub link to be connected; 1 if it is
 * (or lcm is not a hub link), else 0.
 */
int mpb_lcm_hub_wait(lcm_t *lcm, double timeout_s);

/*
 * Publish datalen bytes on channel: through the hub for a hub link, else
 * lcm_publish(). MPB_OK, or MPB_ELCM if not sent. Safe from any thread.
 */
int mpb_lcm_publish(lcm_t *lcm, const char *channel, const void *data,
                    unsigned int datalen);

/* Destroy an instance made by mpb_lcm_create_keeping() (any URL): its hub
 * link's thread is stopped first. No other thread may be publishing on it
 * meanwhile. NULL is a no-op. */
void mpb_lcm_destroy(lcm_t *lcm);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_HUB_H */
