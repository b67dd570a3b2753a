/*
 * hostile_datagrams.c - mpb-test-hostile: sends the malformed LCM datagrams
 * of issue 28 to an LCM group, to show that no mpbench process dies of
 * them (tests/integration/test_hostile_datagrams.sh; run it only inside a
 * private network namespace).
 *
 *   mpb-test-hostile [-g GROUP] [-p PORT] [-n RANDOM] [-r PER_S] [-s SEED]
 *                    CHANNEL...
 *   mpb-test-hostile --seeds DIR
 *
 * For each CHANNEL (one a receiver subscribes to, so that liblcm takes the
 * bait) it sends, in this order:
 *   wrap       a fragment 0 whose offset is near 2^32 (offset + size wraps
 *              liblcm's 32-bit bounds check: the copy lands 4 GB away);
 *   wrap_n     a good fragment 0, then fragment 1 with such an offset;
 *   past_total a good fragment 0, then fragment 5 of 2;
 *   oversize   a fragment 0 of a message of 255 MiB (over
 *              MPB_LCM_MESSAGE_MAX, under liblcm's own limit);
 *   unterminated  a filler that is not LCM and holds "CHANNEL\0" where a
 *              short message's channel goes, then a short message that
 *              holds CHANNEL without its last character and no NUL: liblcm
 *              reads the name on into the filler's bytes left in its
 *              buffer, and hands over a message of negative size.
 * Then RANDOM datagrams (default 0) at PER_S a second (default 300), from
 * SEED (default 1): LCM headers with random fields, random lengths, parts
 * of the channels' names, and plain random bytes.
 * --seeds writes each crafted datagram (for channel MPB_RESULT), and two
 * well-formed ones, to DIR as files, for the fuzz corpus
 * (tests/fuzz/corpus/lcm_filter).
 */
#include <arpa/inet.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#define MAGIC_SHORT 0x4c433032u
#define MAGIC_LONG 0x4c433033u

typedef struct out {
    int fd;
    struct sockaddr_in to;
    const char *seeds;          /* a directory, or NULL: send */
    long sent;
} out;

static void put32(unsigned char *b, uint32_t v)
{
    b[0] = (unsigned char)(v >> 24);
    b[1] = (unsigned char)(v >> 16);
    b[2] = (unsigned char)(v >> 8);
    b[3] = (unsigned char)v;
}

static void put16(unsigned char *b, uint32_t v)
{
    b[0] = (unsigned char)(v >> 8);
    b[1] = (unsigned char)v;
}

static void send_one(out *o, const char *name, const unsigned char *b, size_t len)
{
    if (o->seeds != NULL) {
        char path[512];
        snprintf(path, sizeof path, "%s/%s", o->seeds, name);
        FILE *f = fopen(path, "wb");
        if (f == NULL || fwrite(b, 1, len, f) != len || fclose(f) != 0) {
            fprintf(stderr, "mpb-test-hostile: %s: %s\n", path, strerror(errno));
            exit(1);
        }
        return;
    }
    if (sendto(o->fd, b, len, 0, (struct sockaddr *)&o->to, sizeof o->to) < 0)
        fprintf(stderr, "mpb-test-hostile: sendto: %s\n", strerror(errno));
    else
        o->sent++;
}

/* An LCM fragment header, then the channel (if not NULL) and its NUL, then
 * payload bytes of 'p'; its length. */
static size_t fragment(unsigned char *b, uint32_t seq, uint32_t size,
                       uint32_t offset, uint32_t number, uint32_t count,
                       const char *channel, size_t payload)
{
    size_t n = 20;
    put32(b, MAGIC_LONG);
    put32(b + 4, seq);
    put32(b + 8, size);
    put32(b + 12, offset);
    put16(b + 16, number);
    put16(b + 18, count);
    if (channel != NULL) {
        memcpy(b + n, channel, strlen(channel) + 1);
        n += strlen(channel) + 1;
    }
    memset(b + n, 'p', payload);
    return n + payload;
}

static void crafted(out *o, const char *ch, uint32_t *seq)
{
    static unsigned char b[65536];
    size_t n;

    /* wrap: 0xfffffff0 + 40 bytes = 24 (mod 2^32) <= 100. */
    n = fragment(b, ++*seq, 100, 0xfffffff0u, 0, 2, ch, 40);
    send_one(o, "wrap", b, n);

    n = fragment(b, ++*seq, 3000, 0, 0, 2, ch, 1500);
    send_one(o, "wrap_n_first", b, n);
    n = fragment(b, *seq, 3000, 0xffffff00u, 1, 2, NULL, 1500);
    send_one(o, "wrap_n", b, n);

    n = fragment(b, ++*seq, 3000, 0, 0, 2, ch, 1500);
    send_one(o, "past_total_first", b, n);
    n = fragment(b, *seq, 3000, 1500, 5, 2, NULL, 1500);
    send_one(o, "past_total", b, n);

    n = fragment(b, ++*seq, 255u << 20, 0, 0, 4000, ch, 1000);
    send_one(o, "oversize", b, n);

    /* unterminated: a filler in liblcm's buffer, then the short message. */
    size_t len = strlen(ch);
    memset(b, 'f', 200);
    put32(b, 0x4d504221u);              /* "MPB!": not LCM, dropped */
    memcpy(b + 8, ch, len + 1);
    send_one(o, "unterminated_filler", b, 200);
    put32(b, MAGIC_SHORT);
    put32(b + 4, ++*seq);
    send_one(o, "unterminated", b, 8 + len - 1);
}

/* Random numbers of our own, the same for a seed everywhere. */
static uint64_t rnd_state;
static uint32_t rnd(void)
{
    rnd_state = rnd_state * 6364136223846793005u + 1442695040888963407u;
    return (uint32_t)(rnd_state >> 33);
}

static void random_one(out *o, char **channels, int nch, uint32_t *seq)
{
    static unsigned char b[65536];
    size_t len = rnd() % 4 == 0 ? rnd() % 9000 : rnd() % 200;
    for (size_t i = 0; i < len; i++)
        b[i] = (unsigned char)(rnd() % 3 == 0 ? 0 : rnd());
    int kind = (int)(rnd() % 4);
    const char *ch = channels[rnd() % (uint32_t)nch];
    size_t cl = strlen(ch);
    if (kind == 0 && len >= 8) {                /* short, a channel's part */
        put32(b, MAGIC_SHORT);
        size_t take = rnd() % (cl + 2);
        if (8 + take <= len)
            memcpy(b + 8, ch, take < cl ? take : cl + 1);
    } else if (kind >= 1 && len >= 20) {        /* a fragment */
        uint32_t size = rnd() % 2 ? rnd() % 5000 : rnd();
        put32(b, MAGIC_LONG);
        put32(b + 4, rnd() % 2 ? *seq : rnd());
        put32(b + 8, size);
        put32(b + 12, rnd() % 3 == 0 ? 0 : rnd() % 2 ? rnd() % 5000
                                                      : 0u - rnd() % 70000);
        put16(b + 16, rnd() % 2 ? 0 : rnd() % 4);
        put16(b + 18, rnd() % 4);
        if (rnd() % 2 && 20 + cl < len)
            memcpy(b + 20, ch, cl + (rnd() % 2));
    }
    send_one(o, "random", b, len);
}

int main(int argc, char **argv)
{
    out o = {.fd = -1};
    const char *group = "239.255.76.67";
    int port = 7667, i = 1;
    long nrandom = 0, rate = 300;
    unsigned long seed = 1;

    for (; i < argc && argv[i][0] == '-'; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (v == NULL)
            break;
        if (strcmp(a, "-g") == 0)
            group = v;
        else if (strcmp(a, "-p") == 0)
            port = atoi(v);
        else if (strcmp(a, "-n") == 0)
            nrandom = atol(v);
        else if (strcmp(a, "-r") == 0)
            rate = atol(v);
        else if (strcmp(a, "-s") == 0)
            seed = strtoul(v, NULL, 10);
        else if (strcmp(a, "--seeds") == 0)
            o.seeds = v;
        else
            break;
        i++;
    }
    if (o.seeds != NULL) {
        uint32_t seq = 0;
        static unsigned char b[2000];
        crafted(&o, "MPB_RESULT", &seq);
        /* And well-formed ones: a short message, a fragment that ends one. */
        put32(b, MAGIC_SHORT);
        put32(b + 4, 1);
        memcpy(b + 8, "MPB_STATUS\0hello", 17);
        send_one(&o, "good_short", b, 25);
        send_one(&o, "good_last", b, fragment(b, 2, 3000, 1500, 1, 2, NULL, 1500));
        return 0;
    }
    if (i >= argc || rate < 1 || port < 1 || port > 65535) {
        fprintf(stderr, "usage: mpb-test-hostile [-g GROUP] [-p PORT] "
                "[-n RANDOM] [-r PER_S] [-s SEED] CHANNEL...\n"
                "       mpb-test-hostile --seeds DIR\n");
        return 2;
    }
    o.fd = socket(AF_INET, SOCK_DGRAM, 0);
    unsigned char ttl = 0, loop = 1;
    o.to.sin_family = AF_INET;
    o.to.sin_port = htons((uint16_t)port);
    if (o.fd < 0 || inet_pton(AF_INET, group, &o.to.sin_addr) != 1 ||
        setsockopt(o.fd, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl) != 0 ||
        setsockopt(o.fd, IPPROTO_IP, IP_MULTICAST_LOOP, &loop, sizeof loop) != 0) {
        fprintf(stderr, "mpb-test-hostile: cannot send to %s:%d\n", group, port);
        return 1;
    }

    uint32_t seq = 0x70000000u;
    struct timespec gap = {0, 1000000000L / rate};
    for (int c = i; c < argc; c++) {
        crafted(&o, argv[c], &seq);
        nanosleep(&gap, NULL);
    }
    rnd_state = seed;
    for (long k = 0; k < nrandom; k++) {
        random_one(&o, argv + i, argc - i, &seq);
        nanosleep(&gap, NULL);
    }
    printf("mpb-test-hostile: %ld datagrams sent\n", o.sent);
    close(o.fd);
    return 0;
}
