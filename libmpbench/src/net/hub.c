/* hub.c - LCM through lcm-java's TCP hub, every length checked (hub.h). */
#include <errno.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/uio.h>
#include <time.h>
#include <unistd.h>

#include "mpbench/mpbench.h"
#include "mpbench/link.h"
#include "net/hub_internal.h"

/* The hub's protocol (lcm-java's TCPProvider and TCPService; liblcm's
 * lcm_tcpq.c): each side first sends a magic number and a version, then
 * frames of big-endian 32-bit words: a type, then for a message the
 * channel's length and bytes and the message's length and bytes, for a
 * subscription the length and bytes of a Java regular expression. */
#define HUB_MAGIC_SERVER 0x287617fau
#define HUB_MAGIC_CLIENT 0x287617fbu
#define HUB_VERSION 0x0100u
#define HUB_PUBLISH 1u
#define HUB_SUBSCRIBE 2u
/* Seconds to connect and hear the hub's greeting; to send one frame. */
#define HUB_CONNECT_S 2.0
#define HUB_SEND_S 5.0
/* Milliseconds sent data may stay unacknowledged before the kernel gives
 * the connection up (TCP_USER_TIMEOUT). */
#define HUB_USER_TIMEOUT_MS 10000u

typedef struct mpb__hub {
    lcm_t *local;               /* memq: the process's subscriptions */
    lcm_subscription_t *meter;  /* counts what leaves the queue */
    char host[256];
    char port[8];
    char **subs;                /* regular expressions sent to the hub */
    int nsubs;
    int wake[2];                /* a pipe: written to stop the thread */
    pthread_t thread;
    pthread_mutex_t send_mu;    /* one frame at a time; guards fd */
    int fd;                     /* -1 while not connected */
    atomic_size_t queued;       /* bytes handed to local, not handled */
    atomic_int connected;
    atomic_long connects, oversized, overflowed, malformed;
    struct mpb__hub *next;
} mpb__hub;

/* Every hub link of the process, by its lcm_t: lcm_t is liblcm's handle,
 * so the link cannot ride on it. */
static pthread_mutex_t g_hubs_mu = PTHREAD_MUTEX_INITIALIZER;
static mpb__hub *g_hubs;

static mpb__hub *hub_of(lcm_t *lcm, int dying)
{
    mpb__hub *h = NULL;
    if (lcm == NULL)
        return NULL;
    if (dying ? pthread_mutex_trylock(&g_hubs_mu) != 0
              : pthread_mutex_lock(&g_hubs_mu) != 0)
        return NULL;
    for (h = g_hubs; h != NULL && h->local != lcm; h = h->next)
        ;
    pthread_mutex_unlock(&g_hubs_mu);
    return h;
}

int mpb_lcm_url_is_hub(const char *url)
{
    return url != NULL && strncmp(url, "tcpq://", 7) == 0;
}

/* host and port of a tcpq:// URL (liblcm's defaults: 127.0.0.1:7700);
 * 0 if malformed. */
static int parse_url(const char *url, mpb__hub *h)
{
    const char *p = url + 7, *end = p + strcspn(p, "?/");
    const char *colon = memchr(p, ':', (size_t)(end - p));
    size_t hl = (size_t)((colon ? colon : end) - p);
    if (hl >= sizeof h->host)
        return 0;
    memcpy(h->host, p, hl);
    h->host[hl] = '\0';
    if (hl == 0)
        snprintf(h->host, sizeof h->host, "127.0.0.1");
    if (colon == NULL) {
        snprintf(h->port, sizeof h->port, "7700");
        return 1;
    }
    size_t pl = (size_t)(end - colon - 1);
    if (pl < 1 || pl > 5 || strspn(colon + 1, "0123456789") < pl)
        return 0;
    memcpy(h->port, colon + 1, pl);
    h->port[pl] = '\0';
    long port = strtol(h->port, NULL, 10);
    return port > 0 && port < 65536;
}

/* A channel as a Java regular expression matching it alone: a backslash
 * before every character that is not a letter, digit or '_' (each of
 * those is then a literal). */
static char *channel_regex(const char *channel)
{
    size_t n = strlen(channel);
    char *re = malloc(2 * n + 1), *q = re;
    if (re == NULL)
        return NULL;
    for (const char *c = channel; *c; c++) {
        if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') ||
              (*c >= '0' && *c <= '9') || *c == '_'))
            *q++ = '\\';
        *q++ = *c;
    }
    *q = '\0';
    return re;
}

static void put32(unsigned char *b, uint32_t v)
{
    b[0] = (unsigned char)(v >> 24);
    b[1] = (unsigned char)(v >> 16);
    b[2] = (unsigned char)(v >> 8);
    b[3] = (unsigned char)v;
}

static uint32_t get32(const unsigned char *b)
{
    return (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | b[3];
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* Wait until fd is ready for events, the stop pipe is written, or
 * deadline (monotonic s; 0: none) passes. 1 ready, 0 not (stop, time,
 * error). */
static int wait_fd(mpb__hub *h, int fd, short events, double deadline)
{
    for (;;) {
        struct pollfd p[2] = {{.fd = fd, .events = events},
                              {.fd = h->wake[0], .events = POLLIN}};
        int ms = -1;
        if (deadline > 0) {
            double left = deadline - now_s();
            if (left <= 0)
                return 0;
            ms = (int)(left * 1000) + 1;
        }
        int n = poll(p, 2, ms);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0 || p[1].revents)
            return 0;
        if (p[0].revents)
            return 1;
    }
}

/* Read exactly len bytes (into buf, or thrown away if buf is NULL). */
static int read_full(mpb__hub *h, int fd, void *buf, size_t len,
                     double deadline)
{
    unsigned char scratch[65536];
    while (len > 0) {
        if (!wait_fd(h, fd, POLLIN, deadline))
            return -1;
        size_t want = buf != NULL || len < sizeof scratch ? len : sizeof scratch;
        ssize_t n = recv(fd, buf != NULL ? buf : scratch, want, 0);
        if (n < 0 && (errno == EINTR || errno == EAGAIN))
            continue;
        if (n <= 0)
            return -1;
        /* Acknowledge at once: the hub (lcm-java) writes a frame's words
         * one by one with Nagle's algorithm on, so a delayed ACK here
         * holds each frame's last part back by up to 40 ms. */
        int one = 1;
        setsockopt(fd, IPPROTO_TCP, TCP_QUICKACK, &one, sizeof one);
        len -= (size_t)n;
        if (buf != NULL)
            buf = (unsigned char *)buf + n;
    }
    return 0;
}

/* Send an iovec whole within HUB_SEND_S; 0 or -1. */
static int send_all(int fd, struct iovec *iov, int n)
{
    double deadline = now_s() + HUB_SEND_S;
    while (n > 0) {
        struct msghdr m = {.msg_iov = iov, .msg_iovlen = (size_t)n};
        ssize_t sent = sendmsg(fd, &m, MSG_NOSIGNAL | MSG_DONTWAIT);
        if (sent < 0 && (errno == EAGAIN || errno == EINTR)) {
            struct pollfd p = {.fd = fd, .events = POLLOUT};
            double left = deadline - now_s();
            if (left <= 0 || poll(&p, 1, (int)(left * 1000) + 1) <= 0)
                return -1;
            continue;
        }
        if (sent <= 0)
            return -1;
        while (n > 0 && (size_t)sent >= iov->iov_len) {
            sent -= (ssize_t)iov->iov_len;
            iov++;
            n--;
        }
        if (n > 0) {
            iov->iov_base = (char *)iov->iov_base + sent;
            iov->iov_len -= (size_t)sent;
        }
    }
    return 0;
}

/* One frame: type, a name (channel or regex), and for a message its data. */
static int send_frame(int fd, uint32_t type, const char *name,
                      const void *data, uint32_t len, int with_data)
{
    unsigned char head[8], mid[4];
    size_t nl = strlen(name);
    put32(head, type);
    put32(head + 4, (uint32_t)nl);
    put32(mid, len);
    struct iovec iov[4] = {{head, 8}, {(void *)name, nl}, {mid, 4},
                           {(void *)data, len}};
    return send_all(fd, iov, with_data ? 4 : 2);
}

/* Connect, greet, subscribe; the socket, or -1. */
static int hub_connect(mpb__hub *h)
{
    struct addrinfo hints = {.ai_family = AF_UNSPEC, .ai_socktype = SOCK_STREAM};
    struct addrinfo *res = NULL;
    if (getaddrinfo(h->host, h->port, &hints, &res) != 0)
        return -1;
    int fd = -1;
    double deadline = now_s() + HUB_CONNECT_S;
    for (struct addrinfo *a = res; a != NULL && fd < 0; a = a->ai_next) {
        fd = socket(a->ai_family, a->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC,
                    a->ai_protocol);
        if (fd < 0)
            continue;
        int err = 0;
        socklen_t el = sizeof err;
        if ((connect(fd, a->ai_addr, a->ai_addrlen) != 0 &&
             (errno != EINPROGRESS || !wait_fd(h, fd, POLLOUT, deadline) ||
              getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &el) != 0 || err != 0))) {
            close(fd);
            fd = -1;
        }
    }
    freeaddrinfo(res);
    if (fd < 0)
        return -1;
    int one = 1;
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    /* A hub that stops acknowledging what is sent (its host cut off) ends
     * the connection after this long, rather than TCP's quarter of an
     * hour of retries: the link then connects again. */
    unsigned int user_timeout_ms = HUB_USER_TIMEOUT_MS;
    setsockopt(fd, IPPROTO_TCP, TCP_USER_TIMEOUT, &user_timeout_ms,
               sizeof user_timeout_ms);
    unsigned char hello[8], answer[8];
    put32(hello, HUB_MAGIC_CLIENT);
    put32(hello + 4, HUB_VERSION);
    struct iovec iov = {hello, 8};
    if (send_all(fd, &iov, 1) != 0 ||
        read_full(h, fd, answer, 8, deadline) != 0 ||
        get32(answer) != HUB_MAGIC_SERVER) {
        close(fd);
        return -1;
    }
    for (int i = 0; i < h->nsubs; i++)
        if (send_frame(fd, HUB_SUBSCRIBE, h->subs[i], NULL, 0, 0) != 0) {
            close(fd);
            return -1;
        }
    return fd;
}

/* Read frames until the connection fails or the thread is stopped. */
static void hub_read(mpb__hub *h, int fd)
{
    unsigned char *buf = NULL;
    size_t cap = 0;
    for (;;) {
        unsigned char w[8];
        char channel[MPB_LCM_CHANNEL_MAX + 1];
        if (read_full(h, fd, w, 8, 0) != 0)
            break;
        uint32_t type = get32(w), cl = get32(w + 4);
        if (type != HUB_PUBLISH) {
            atomic_fetch_add(&h->malformed, 1);
            break;
        }
        int fits = cl >= 1 && cl <= MPB_LCM_CHANNEL_MAX;
        if (read_full(h, fd, fits ? channel : NULL, cl, 0) != 0 ||
            read_full(h, fd, w, 4, 0) != 0)
            break;
        uint32_t dl = get32(w);
        if (!fits || dl > MPB_LCM_MESSAGE_MAX) {
            atomic_fetch_add(&h->oversized, 1);
            if (read_full(h, fd, NULL, dl, 0) != 0)
                break;
            continue;
        }
        channel[cl] = '\0';
        if (dl > cap) {
            unsigned char *nb = realloc(buf, dl);
            if (nb == NULL)
                break;
            buf = nb;
            cap = dl;
        }
        if (read_full(h, fd, buf, dl, 0) != 0)
            break;
        if (strlen(channel) != cl) {           /* a NUL inside */
            atomic_fetch_add(&h->oversized, 1);
            continue;
        }
        if (atomic_load(&h->queued) + dl > MPB_HUB_QUEUE_MAX) {
            atomic_fetch_add(&h->overflowed, 1);
            continue;
        }
        atomic_fetch_add(&h->queued, dl);
        if (lcm_publish(h->local, channel, dl > 0 ? buf : w, dl) != 0)
            atomic_fetch_sub(&h->queued, dl);
    }
    free(buf);
}

static void *hub_main(void *arg)
{
    mpb__hub *h = arg;
    for (;;) {
        int fd = hub_connect(h);
        if (fd >= 0) {
            pthread_mutex_lock(&h->send_mu);
            h->fd = fd;
            pthread_mutex_unlock(&h->send_mu);
            atomic_fetch_add(&h->connects, 1);
            atomic_store(&h->connected, 1);
            hub_read(h, fd);
            atomic_store(&h->connected, 0);
            pthread_mutex_lock(&h->send_mu);
            h->fd = -1;
            pthread_mutex_unlock(&h->send_mu);
            close(fd);
        }
        /* Stopped, or wait before trying again. */
        struct pollfd p = {.fd = h->wake[0], .events = POLLIN};
        if (poll(&p, 1, (int)(MPB_HUB_RETRY_S * 1000)) > 0)
            return NULL;
    }
}

/* What leaves the queue: every message, whatever else handles it. */
static void on_any(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    mpb__hub *h = user;
    /* Never below 0: a dying process's last words may reach the queue
     * without passing the link (mpb__hub_publish). */
    size_t n = (size_t)rbuf->data_size, q = atomic_load(&h->queued);
    while (!atomic_compare_exchange_weak(&h->queued, &q, q > n ? q - n : 0))
        ;
}

static void hub_free(mpb__hub *h)
{
    for (int i = 0; i < h->nsubs; i++)
        free(h->subs[i]);
    free(h->subs);
    if (h->wake[0] >= 0)
        close(h->wake[0]);
    if (h->wake[1] >= 0)
        close(h->wake[1]);
    pthread_mutex_destroy(&h->send_mu);
    free(h);
}

lcm_t *mpb__hub_create(const char *url, const char *const *channels, int n)
{
    mpb__hub *h = calloc(1, sizeof *h);
    if (h == NULL)
        return NULL;
    h->fd = -1;
    h->wake[0] = h->wake[1] = -1;
    pthread_mutex_init(&h->send_mu, NULL);
    int ok = parse_url(url, h) && pipe(h->wake) == 0;
    int want = channels != NULL && n > 0 ? n : 1;
    if (ok && (h->subs = calloc((size_t)want, sizeof *h->subs)) == NULL)
        ok = 0;
    for (int i = 0; ok && i < want; i++) {
        h->subs[i] = channels != NULL && n > 0 ? channel_regex(channels[i])
                                               : strdup(".*");
        ok = h->subs[i] != NULL;
        h->nsubs += ok;
    }
    if (ok && (h->local = lcm_create("memq://")) == NULL)
        ok = 0;
    if (ok && (h->meter = lcm_subscribe(h->local, ".*", on_any, h)) == NULL)
        ok = 0;
    if (ok)
        lcm_subscription_set_queue_capacity(h->meter, 0);
    if (ok) {
        /* The thread takes no signals: they are the caller's. */
        sigset_t all, old;
        sigfillset(&all);
        pthread_sigmask(SIG_SETMASK, &all, &old);
        ok = pthread_create(&h->thread, NULL, hub_main, h) == 0;
        pthread_sigmask(SIG_SETMASK, &old, NULL);
    }
    if (!ok) {
        if (h->local != NULL)
            lcm_destroy(h->local);
        hub_free(h);
        return NULL;
    }
    pthread_mutex_lock(&g_hubs_mu);
    h->next = g_hubs;
    g_hubs = h;
    pthread_mutex_unlock(&g_hubs_mu);
    return h->local;
}

int mpb__hub_publish(lcm_t *lcm, const char *channel, const void *data,
                     unsigned int datalen, int dying)
{
    /* Not a hub link (or, dying, the list busy: then a hub link's local
     * queue takes it, which harms nothing): liblcm's own publishing. */
    mpb__hub *h = hub_of(lcm, dying);
    if (h == NULL)
        return lcm_publish(lcm, channel, data, datalen);
    if (channel == NULL || strlen(channel) > MPB_LCM_CHANNEL_MAX ||
        datalen > MPB_LCM_MESSAGE_MAX ||
        (dying ? pthread_mutex_trylock(&h->send_mu) != 0
               : pthread_mutex_lock(&h->send_mu) != 0))
        return -1;
    int rc = -1;
    if (h->fd >= 0) {
        rc = send_frame(h->fd, HUB_PUBLISH, channel, data, datalen, 1);
        /* A frame half sent leaves the stream unreadable: end it; the
         * thread sees the connection close and makes a new one. */
        if (rc != 0)
            shutdown(h->fd, SHUT_RDWR);
    }
    pthread_mutex_unlock(&h->send_mu);
    return rc;
}

int mpb_lcm_publish(lcm_t *lcm, const char *channel, const void *data,
                    unsigned int datalen)
{
    return mpb__hub_publish(lcm, channel, data, datalen, 0) == 0 ? MPB_OK
                                                                 : MPB_ELCM;
}

void mpb_lcm_hub_stats(lcm_t *lcm, mpb_hub_stats *out)
{
    memset(out, 0, sizeof *out);
    mpb__hub *h = hub_of(lcm, 0);
    if (h == NULL)
        return;
    out->is_hub = 1;
    out->connected = atomic_load(&h->connected);
    out->connects = atomic_load(&h->connects);
    out->oversized = atomic_load(&h->oversized);
    out->overflowed = atomic_load(&h->overflowed);
    out->malformed = atomic_load(&h->malformed);
    out->retry_s = MPB_HUB_RETRY_S;
}

int mpb_lcm_hub_wait(lcm_t *lcm, double timeout_s)
{
    mpb__hub *h = hub_of(lcm, 0);
    double end = now_s() + timeout_s;
    while (h != NULL && !atomic_load(&h->connected)) {
        if (now_s() >= end)
            return 0;
        struct timespec ts = {0, 10 * 1000 * 1000};
        nanosleep(&ts, NULL);
    }
    return 1;
}

void mpb_lcm_destroy(lcm_t *lcm)
{
    if (lcm == NULL)
        return;
    mpb__hub *h = NULL;
    pthread_mutex_lock(&g_hubs_mu);
    for (mpb__hub **p = &g_hubs; *p != NULL; p = &(*p)->next)
        if ((*p)->local == lcm) {
            h = *p;
            *p = h->next;
            break;
        }
    pthread_mutex_unlock(&g_hubs_mu);
    if (h != NULL) {
        ssize_t w = write(h->wake[1], "x", 1);
        (void)w;
        pthread_join(h->thread, NULL);
        lcm_unsubscribe(lcm, h->meter);
        hub_free(h);
    }
    lcm_destroy(lcm);
}
