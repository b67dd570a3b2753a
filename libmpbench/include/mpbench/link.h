/*
 * link.h - the LCM link every mpbench process talks through: made by
 * mpb_lcm_create() and released by mpb_lcm_destroy(); messages sent with
 * mpb_publish_...() (mpb_lcm_publish() for bytes already encoded) and
 * received through one gate, mpb_receive(). The daemon, the C planner kit
 * and the Python kit (through ctypes) all use these.
 *
 * The link. mpb_lcm_create() takes an LCM URL, udpm:// (multicast, with
 * the socket filter of lcm_filter.h on the receive socket) or tcpq:// (a
 * TCP hub, below), and gives a plain lcm_t: lcm_subscribe(),
 * lcm_get_fileno() (readable whenever a message waits) and lcm_handle()
 * work on it as usual. Publishing must go through mpb_lcm_publish() (the
 * mpb_publish_...() functions do), which is safe from any thread.
 *
 * The gate. A received message passes three checks in this order, and is
 * decoded only if it passes all of them: its trailer (auth.h: a right tag,
 * from a sender believed, not had before; the caller says which verdicts
 * it takes), its bytes (wire.h: every length within the message, every
 * string ended), and the generated decoder. Nothing is allocated for a
 * message that fails.
 *
 * Hubs (tcpq://HOST:PORT), for hosts that multicast does not reach. The
 * hub is lcm-java's lcm.lcm.TCPService: every client sends it the
 * channels it wants, and it relays each message published by any client
 * to every client that wants that channel. A tcpq:// link speaks to it
 * with this library's own client instead of liblcm's, for three reasons
 * found in liblcm 1.3.1's: it allocates whatever length a frame claims
 * (4 GiB for 0xffffffff); its descriptor is the TCP socket itself, which
 * changes when it reconnects and makes lcm_handle() block until a whole
 * frame is in; and its publishing takes no lock, so two threads
 * publishing at once (a planner's heartbeat and its result) interleave
 * their bytes and the hub stops relaying that client. The lcm_t is then
 * liblcm's memq:// provider, fed by a thread of the library that connects
 * (and reconnects, every MPB_HUB_RETRY_S, when the hub goes away),
 * subscribes to the channels given at creation, reads frames, and hands
 * each to the instance's queue. Every length is checked before anything
 * is allocated: a channel name over MPB_LCM_CHANNEL_MAX or a message over
 * MPB_LCM_MESSAGE_MAX is read past and dropped, a frame that is not a
 * message closes the connection (then reconnects), and at most
 * MPB_HUB_QUEUE_MAX bytes wait in the queue (more are dropped, as a full
 * UDP receive buffer drops datagrams). A message published while the hub
 * is away is lost, as a datagram may be, and the protocol's re-sends
 * cover it.
 */
#ifndef MPBENCH_LINK_H
#define MPBENCH_LINK_H

#include <stddef.h>
#include <stdint.h>

#include <lcm/lcm.h>

#include "mpbench/auth.h"
#include "mpbench/lcm_filter.h"
#include "mpbench/messages.h"
#include "mpbench/wire.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Making and releasing a link ---------------------------------- */

/*
 * lcm_create(url), with the filter for these channels (as
 * mpb_lcm_filter_program; n == 0 keeps every channel) on the new
 * instance's receive socket: the one UDP socket on url's port that
 * appears while the instance is made (its receive side is set up at once,
 * as lcm_get_fileno() does). *filtered (if not NULL) says whether the
 * filter is on: 0 for a URL that is not udpm://, a socket not found or not
 * alone, or a kernel that refused the filter; the instance then receives
 * every datagram, malformed ones included, as a plain one does, and the
 * caller should say so once (MPB_LCM_UNFILTERED). NULL if lcm_create()
 * fails.
 */
lcm_t *mpb_lcm_create(const char *url, const char *const *channels, int n,
                      int *filtered);

/* The warning every process prints, once, when its socket has no filter. */
#define MPB_LCM_UNFILTERED                                                 \
    "warning: LCM's receive socket has no filter (not a udpm:// URL, or "  \
    "the kernel refused it): a malformed datagram can crash this process"

/* Release a link made by mpb_lcm_create() (any URL): a hub link's thread
 * is stopped first. No other thread may be publishing on it meanwhile.
 * NULL is a no-op. */
void mpb_lcm_destroy(lcm_t *lcm);

/* 1 if url names a hub (tcpq://...). */
int mpb_lcm_url_is_hub(const char *url);

/* ---- Publishing --------------------------------------------------- */

/*
 * Publish datalen bytes on channel: through the hub for a hub link, else
 * lcm_publish(). MPB_OK, or MPB_ELCM if not sent. Safe from any thread.
 */
int mpb_lcm_publish(lcm_t *lcm, const char *channel, const void *data,
                    unsigned int datalen);

/*
 * Publish a message, followed by its trailer when a is not NULL; echo is
 * the instance of the process it answers (0 for none). Return MPB_OK, or
 * MPB_ENOMEM / MPB_ELCM. One function per message of messages.h:
 *   int mpb_publish_announce(lcm_t *lcm, mpb_auth *a, uint64_t echo,
 *                            const char *channel,
 *                            const mpb_planner_announce_t *m);
 * and mpb_publish_request, _result, _ack, _status the same way.
 *
 * mpb_publish_<name>_in(..., m, layout) publishes m in layout of its
 * type (wire.h: today's bytes under an older layout's fingerprint, for a
 * planner built before that takes no other, as the daemon sends
 * requests and acks in MPB_WIRE_BEFORE_ATTEMPT_ID); MPB_EINVAL for a
 * layout that is not today's bytes. Layout 0 is mpb_publish_<name>().
 */
#define MPB__PUBLISH_DECL(ID, name, type, channel)                          \
    int mpb_publish_##name(lcm_t *lcm, mpb_auth *a, uint64_t echo,          \
                           const char *ch, const mpb_##type *m);            \
    int mpb_publish_##name##_in(lcm_t *lcm, mpb_auth *a, uint64_t echo,     \
                                const char *ch, const mpb_##type *m,        \
                                int layout);
MPB_MESSAGES(MPB__PUBLISH_DECL)
#undef MPB__PUBLISH_DECL

/* ---- Receiving ---------------------------------------------------- */

/* Verdicts a caller takes, as bits of its accept argument. */
#define MPB_RECEIVE_FRESH (1u << MPB_AUTH_FRESH)
#define MPB_RECEIVE_UNPROVEN (1u << MPB_AUTH_UNPROVEN)
#define MPB_RECEIVE_REPLAYED (1u << MPB_AUTH_REPLAYED)
/* Every authentic message: a log played back, or a daemon's status from
 * another daemon, where freshness cannot be asked for. */
#define MPB_RECEIVE_AUTHENTIC \
    (MPB_RECEIVE_FRESH | MPB_RECEIVE_UNPROVEN | MPB_RECEIVE_REPLAYED)

/* What the gate made of a message. */
typedef struct mpb_received {
    mpb_auth_verdict verdict;   /* mpb_auth_check()'s */
    mpb_auth_info info;         /* the trailer's fields (zero without one) */
    int layout;                 /* the layout it came in (wire.h): 0
                                   today's, 1.. an older one; -1 refused
                                   before its fingerprint was read */
    char why[160];              /* why it was refused, one line; "" if not */
} mpb_received;

/*
 * Pass the size bytes at data, received on channel, through the gate: with
 * auth (NULL: no authentication, every message fresh), taking the verdicts
 * in accept (MPB_RECEIVE_...), as a message of the given type. On success
 * return MPB_OK with the message decoded into *msg, which must point to
 * the generated struct of that type (mpb_plan_request_t for
 * MPB_WIRE_PLAN_REQUEST, ...); free its contents with mpb_receive_done().
 * Otherwise return MPB_EREJECTED with nothing allocated and r->why saying
 * why. r (not NULL) gets the verdict and the trailer's fields either way.
 */
int mpb_receive(mpb_auth *auth, unsigned accept, mpb_wire_type type,
                const char *channel, const void *data, size_t size,
                void *msg, mpb_received *r);

/*
 * Decode a result that mpb_wire_check(MPB_WIRE_PLAN_RESULT) passed, in
 * any layout it takes: plan_result_t; plan_result_v2_t (from a planner
 * built before attempt_id: the same bytes); or plan_result_v1_t (built
 * before waypoint times), read as a plan_result_t whose stages have no
 * times (num_times 0). Returns the bytes decoded, or < 0
 * as the generated decoder does; free with
 * mpb_plan_result_t_decode_cleanup(). mpb_receive() decodes results so.
 */
struct _mpb_plan_result_t;
int mpb_receive_decode_result(const void *data, int len,
                              struct _mpb_plan_result_t *out);

/* Free what mpb_receive() decoded into *msg, a message of type. */
void mpb_receive_done(mpb_wire_type type, void *msg);

/* ---- Hub links --------------------------------------------------- */

/* Seconds between attempts to reach a hub that is away. */
#define MPB_HUB_RETRY_S 0.5
/* Bytes of received messages that may wait for lcm_handle(). */
#define MPB_HUB_QUEUE_MAX (64u << 20)

/* What a hub link has seen (all zero for an instance that is not one). */
typedef struct mpb_hub_stats {
    int  is_hub;        /* 1 for an instance made for a tcpq:// URL */
    int  connected;     /* the connection is up now */
    long connects;      /* connections made, the first included */
    long oversized;     /* frames dropped: a length over the bounds, or
                           a channel name with a NUL in it */
    long overflowed;    /* messages dropped with the queue full */
    long malformed;     /* connections closed for a frame that was not one */
    double retry_s;     /* a lost connection is tried again this often
                           (MPB_HUB_RETRY_S; for kits that cannot read
                           the macro) */
} mpb_hub_stats;

/* Fill *out for lcm (any instance; NULL-safe). */
void mpb_lcm_hub_stats(lcm_t *lcm, mpb_hub_stats *out);

/*
 * Wait up to timeout_s seconds for a hub link to be connected; 1 if it is
 * (or lcm is not a hub link), else 0.
 */
int mpb_lcm_hub_wait(lcm_t *lcm, double timeout_s);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_LINK_H */
