/* lcm_filter.c - a socket filter on LCM's receive socket (lcm_filter.h). */
#include <dirent.h>
#include <linux/filter.h>
#include <netinet/in.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include "mpbench/mpbench.h"
#include "mpbench/lcm_filter.h"
#include "mpbench/link.h"
#include "net/hub_internal.h"

/* LCM's UDP format (liblcm's lcm_udpm.c): every datagram starts with a
 * magic number and a sequence number, 32 bits each, big-endian. */
#define LCM_MAGIC_SHORT 0x4c433032u     /* "LC02": a whole message */
#define LCM_MAGIC_LONG 0x4c433033u      /* "LC03": one fragment of one */
#define SHORT_HEADER 8                  /* magic, sequence number */
#define LONG_HEADER 20                  /* and size, offset, number, count */

/* Big-endian fields of a datagram. */
static uint32_t be32(const unsigned char *b)
{
    return (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | b[3];
}

static uint32_t be16(const unsigned char *b)
{
    return (uint32_t)b[0] << 8 | b[1];
}

/* The length of the channel name at b, NUL-terminated within the n bytes
 * there and at most MPB_LCM_CHANNEL_MAX long; -1 if it is not. */
static long channel_length(const unsigned char *b, size_t n)
{
    for (size_t i = 0; i < n && i <= MPB_LCM_CHANNEL_MAX; i++)
        if (b[i] == '\0')
            return (long)i;
    return -1;
}

int mpb_lcm_datagram_is_valid(const void *buf, size_t len)
{
    const unsigned char *b = buf;
    if (b == NULL || len < SHORT_HEADER)
        return 0;
    uint32_t magic = be32(b);
    if (magic == LCM_MAGIC_SHORT)
        return channel_length(b + SHORT_HEADER, len - SHORT_HEADER) >= 0;
    if (magic != LCM_MAGIC_LONG || len < LONG_HEADER + 1)
        return 0;

    uint64_t size = be32(b + 8), offset = be32(b + 12);
    uint32_t number = be16(b + 16), count = be16(b + 18);
    uint64_t payload = len - LONG_HEADER;
    if (size < 1 || size > MPB_LCM_MESSAGE_MAX || count < 1 || count > size ||
        (uint64_t)count * MPB_LCM_FRAGMENT_PAYLOAD_MAX < size || number >= count)
        return 0;
    if (number == 0) {
        long channel = channel_length(b + LONG_HEADER, len - LONG_HEADER);
        if (offset != 0 || channel < 0)
            return 0;
        payload -= (uint64_t)channel + 1;
    }
    if (payload < 1 || offset + payload > size)
        return 0;
    /* Only the last fragment ends the message. */
    return (offset + payload == size) == (number == count - 1);
}

/* ---- the socket filter: the same checks in classic BPF ---- */

/* Offsets as the filter sees a datagram: the UDP header (8 bytes) first. */
#define UDP_HEADER 8
#define AT_MAGIC UDP_HEADER
#define AT_SHORT_CHANNEL (UDP_HEADER + SHORT_HEADER)
#define AT_SIZE (UDP_HEADER + 8)
#define AT_OFFSET (UDP_HEADER + 12)
#define AT_NUMBER (UDP_HEADER + 16)
#define AT_COUNT (UDP_HEADER + 18)
#define AT_PAYLOAD (UDP_HEADER + LONG_HEADER)

/* The filter's scratch memory: the fragment header's fields. */
enum { M_SIZE, M_COUNT, M_NUMBER, M_OFFSET };

#define ACCEPT 0xffffffffu      /* pass the whole datagram */

typedef struct program {
    struct sock_filter *op;
    int n, max, bad;
} program;

/* Append one instruction; its index. */
static int emit(program *p, uint16_t code, uint8_t jt, uint8_t jf, uint32_t k)
{
    if (p->n >= p->max) {
        p->bad = 1;
        return p->n;
    }
    p->op[p->n] = (struct sock_filter){code, jt, jf, k};
    return p->n++;
}

/* Make the jump at index j (its true branch, or a BPF_JA) land on the
 * next instruction emitted. */
static void land(program *p, int j)
{
    int d = p->n - j - 1;
    if (j >= p->max)
        return;
    if (BPF_OP(p->op[j].code) == BPF_JA)
        p->op[j].k = (uint32_t)d;
    else if (d > 255)
        p->bad = 1;
    else
        p->op[j].jt = (uint8_t)d;
}

/* Go on if A compares true with k (code: BPF_JMP | op | BPF_K or BPF_X),
 * else drop the datagram; drop_if: the other way round. */
static void drop_unless(program *p, uint16_t code, uint32_t k)
{
    emit(p, code, 1, 0, k);
    emit(p, BPF_RET | BPF_K, 0, 0, 0);
}

static void drop_if(program *p, uint16_t code, uint32_t k)
{
    emit(p, code, 0, 1, k);
    emit(p, BPF_RET | BPF_K, 0, 0, 0);
}

/* Find the NUL ending the channel name at offset at, within
 * MPB_LCM_CHANNEL_MAX characters: go on with X = the name's length. A
 * datagram that ends first is dropped by the load past its end; one with
 * no NUL soon enough by the return after the search. */
static void emit_channel_end(program *p, uint32_t at)
{
    int found[MPB_LCM_CHANNEL_MAX + 1];
    for (uint32_t i = 0; i <= MPB_LCM_CHANNEL_MAX; i++) {
        emit(p, BPF_LDX | BPF_W | BPF_IMM, 0, 0, i);
        emit(p, BPF_LD | BPF_B | BPF_ABS, 0, 0, at + i);
        found[i] = emit(p, BPF_JMP | BPF_JEQ | BPF_K, 0, 0, 0);
    }
    emit(p, BPF_RET | BPF_K, 0, 0, 0);
    for (int i = 0; i <= MPB_LCM_CHANNEL_MAX; i++)
        land(p, found[i]);
}

/* With X = the length of a short message's channel: accept it if the
 * channel is name, else go on. */
static void emit_channel(program *p, const char *name)
{
    uint32_t size = (uint32_t)strlen(name);
    uint32_t words = size / 4, tail = size % 4;
    /* Each jump skips the rest of this test: two instructions (load,
     * compare) a word or byte left, then the accept. */
    int left = 2 * (int)(words + tail) + 1;

    emit(p, BPF_MISC | BPF_TXA, 0, 0, 0);
    emit(p, BPF_JMP | BPF_JEQ | BPF_K, 0, (uint8_t)left, size);
    for (uint32_t w = 0; w < words; w++, left -= 2) {
        emit(p, BPF_LD | BPF_W | BPF_ABS, 0, 0, AT_SHORT_CHANNEL + 4 * w);
        emit(p, BPF_JMP | BPF_JEQ | BPF_K, 0, (uint8_t)(left - 2),
             be32((const unsigned char *)name + 4 * w));
    }
    for (uint32_t t = 0; t < tail; t++, left -= 2) {
        emit(p, BPF_LD | BPF_B | BPF_ABS, 0, 0, AT_SHORT_CHANNEL + 4 * words + t);
        emit(p, BPF_JMP | BPF_JEQ | BPF_K, 0, (uint8_t)(left - 2),
             (unsigned char)name[4 * words + t]);
    }
    emit(p, BPF_RET | BPF_K, 0, 0, ACCEPT);
}

/* A fragment ("LC03"), A = the datagram's length: mpb_lcm_datagram_is_valid's
 * checks in its order. */
static void emit_fragment(program *p)
{
    drop_unless(p, BPF_JMP | BPF_JGE | BPF_K, AT_PAYLOAD + 1);
    emit(p, BPF_LD | BPF_W | BPF_ABS, 0, 0, AT_SIZE);
    drop_unless(p, BPF_JMP | BPF_JGE | BPF_K, 1);
    drop_if(p, BPF_JMP | BPF_JGT | BPF_K, MPB_LCM_MESSAGE_MAX);
    emit(p, BPF_ST, 0, 0, M_SIZE);
    emit(p, BPF_LD | BPF_H | BPF_ABS, 0, 0, AT_COUNT);
    drop_unless(p, BPF_JMP | BPF_JGE | BPF_K, 1);
    emit(p, BPF_ST, 0, 0, M_COUNT);
    emit(p, BPF_MISC | BPF_TAX, 0, 0, 0);
    emit(p, BPF_LD | BPF_MEM, 0, 0, M_SIZE);            /* size >= count */
    drop_unless(p, BPF_JMP | BPF_JGE | BPF_X, 0);
    emit(p, BPF_LD | BPF_MEM, 0, 0, M_COUNT);           /* no 32-bit wrap: */
    emit(p, BPF_ALU | BPF_MUL | BPF_K, 0, 0, MPB_LCM_FRAGMENT_PAYLOAD_MAX);
    emit(p, BPF_LDX | BPF_W | BPF_MEM, 0, 0, M_SIZE);   /* 65535 * 65487 */
    drop_unless(p, BPF_JMP | BPF_JGE | BPF_X, 0);
    emit(p, BPF_LD | BPF_H | BPF_ABS, 0, 0, AT_NUMBER);
    emit(p, BPF_ST, 0, 0, M_NUMBER);
    emit(p, BPF_LDX | BPF_W | BPF_MEM, 0, 0, M_COUNT);  /* number < count */
    drop_if(p, BPF_JMP | BPF_JGE | BPF_X, 0);
    emit(p, BPF_LD | BPF_W | BPF_ABS, 0, 0, AT_OFFSET);
    emit(p, BPF_ST, 0, 0, M_OFFSET);
    emit(p, BPF_LDX | BPF_W | BPF_MEM, 0, 0, M_SIZE);   /* offset <= size, */
    drop_if(p, BPF_JMP | BPF_JGT | BPF_X, 0);           /* so no wrap below */

    emit(p, BPF_LD | BPF_MEM, 0, 0, M_NUMBER);
    int first = emit(p, BPF_JMP | BPF_JEQ | BPF_K, 0, 0, 0);
    emit(p, BPF_LD | BPF_W | BPF_LEN, 0, 0, 0);         /* A = payload */
    emit(p, BPF_ALU | BPF_SUB | BPF_K, 0, 0, AT_PAYLOAD);
    int to_end = emit(p, BPF_JMP | BPF_JA, 0, 0, 0);

    land(p, first);                                     /* fragment 0 */
    emit(p, BPF_LD | BPF_MEM, 0, 0, M_OFFSET);
    drop_unless(p, BPF_JMP | BPF_JEQ | BPF_K, 0);
    emit_channel_end(p, AT_PAYLOAD);
    emit(p, BPF_LD | BPF_W | BPF_LEN, 0, 0, 0);         /* A = payload, */
    emit(p, BPF_ALU | BPF_SUB | BPF_X, 0, 0, 0);        /* after the name */
    emit(p, BPF_ALU | BPF_SUB | BPF_K, 0, 0, AT_PAYLOAD + 1);
    drop_if(p, BPF_JMP | BPF_JEQ | BPF_K, 0);

    land(p, to_end);                                    /* A = payload */
    emit(p, BPF_LDX | BPF_W | BPF_MEM, 0, 0, M_OFFSET);
    emit(p, BPF_ALU | BPF_ADD | BPF_X, 0, 0, 0);        /* A = its end */
    emit(p, BPF_LDX | BPF_W | BPF_MEM, 0, 0, M_SIZE);
    drop_if(p, BPF_JMP | BPF_JGT | BPF_X, 0);
    int ends = emit(p, BPF_JMP | BPF_JEQ | BPF_X, 0, 0, 0);
    emit(p, BPF_LD | BPF_MEM, 0, 0, M_COUNT);           /* not at the end: */
    emit(p, BPF_ALU | BPF_SUB | BPF_K, 0, 0, 1);        /* not the last */
    emit(p, BPF_LDX | BPF_W | BPF_MEM, 0, 0, M_NUMBER);
    drop_if(p, BPF_JMP | BPF_JEQ | BPF_X, 0);
    emit(p, BPF_RET | BPF_K, 0, 0, ACCEPT);
    land(p, ends);                                      /* at the end: */
    emit(p, BPF_LD | BPF_MEM, 0, 0, M_COUNT);           /* the last */
    emit(p, BPF_ALU | BPF_SUB | BPF_K, 0, 0, 1);
    emit(p, BPF_LDX | BPF_W | BPF_MEM, 0, 0, M_NUMBER);
    drop_unless(p, BPF_JMP | BPF_JEQ | BPF_X, 0);
    emit(p, BPF_RET | BPF_K, 0, 0, ACCEPT);
}

/* Whether the filter keeps only these channels (else every one). */
static int keeps_some(const char *const *channels, int n)
{
    if (channels == NULL || n < 1 || n > MPB_LCM_FILTER_CHANNELS)
        return 0;
    for (int i = 0; i < n; i++)
        if (channels[i] == NULL || strlen(channels[i]) > MPB_LCM_FILTER_NAME_MAX)
            return 0;
    return 1;
}

int mpb_lcm_filter_program(const char *const *channels, int n,
                           struct sock_filter *ops, int max)
{
    program p = {.op = ops, .max = ops != NULL && max > 0 ? max : 0};

    emit(&p, BPF_LD | BPF_W | BPF_LEN, 0, 0, 0);
    drop_unless(&p, BPF_JMP | BPF_JGE | BPF_K, AT_MAGIC + SHORT_HEADER);
    emit(&p, BPF_LD | BPF_W | BPF_ABS, 0, 0, AT_MAGIC);
    emit(&p, BPF_JMP | BPF_JEQ | BPF_K, 0, 1, LCM_MAGIC_SHORT);
    int to_short = emit(&p, BPF_JMP | BPF_JA, 0, 0, 0);
    drop_unless(&p, BPF_JMP | BPF_JEQ | BPF_K, LCM_MAGIC_LONG);
    emit(&p, BPF_LD | BPF_W | BPF_LEN, 0, 0, 0);
    emit_fragment(&p);

    land(&p, to_short);                                 /* "LC02" */
    emit_channel_end(&p, AT_SHORT_CHANNEL);
    if (keeps_some(channels, n)) {
        for (int i = 0; i < n; i++)
            emit_channel(&p, channels[i]);
        emit(&p, BPF_RET | BPF_K, 0, 0, 0);
    } else {
        emit(&p, BPF_RET | BPF_K, 0, 0, ACCEPT);
    }
    return p.bad ? -1 : p.n;
}

int mpb_lcm_filter_socket(int fd, const char *const *channels, int n)
{
    struct sock_filter *ops = calloc(MPB_LCM_FILTER_PROGRAM_MAX, sizeof *ops);
    if (ops == NULL)
        return MPB_ENOMEM;
    int len = mpb_lcm_filter_program(channels, n, ops, MPB_LCM_FILTER_PROGRAM_MAX);
    struct sock_fprog prog = {.len = (unsigned short)len, .filter = ops};
    int rc = len > 0 && setsockopt(fd, SOL_SOCKET, SO_ATTACH_FILTER, &prog,
                                   sizeof prog) == 0 ? MPB_OK : MPB_ELCM;
    free(ops);
    return rc;
}

/* The port of a udpm:// URL, or 0. */
static int url_port(const char *url)
{
    if (url == NULL || strncmp(url, "udpm://", 7) != 0)
        return 0;
    const char *colon = strchr(url + 7, ':');
    if (colon == NULL)
        return 7667;            /* LCM's default port */
    char *end;
    long port = strtol(colon + 1, &end, 10);
    return port > 0 && port < 65536 && (*end == '\0' || *end == '?' || *end == '/')
               ? (int)port : 0;
}

/* This process's UDP sockets bound to port: their inodes and, if fds is
 * not NULL, descriptors, at most max; returns how many. */
static int sockets_on(int port, int *fds, ino_t *inos, int max)
{
    DIR *dir = opendir("/proc/self/fd");
    struct dirent *e;
    int n = 0;
    if (dir == NULL)
        return 0;
    while ((e = readdir(dir)) != NULL && n < max) {
        char *end;
        long fd = strtol(e->d_name, &end, 10);
        struct stat st;
        struct sockaddr_in addr;
        socklen_t len = sizeof addr;
        int type = 0;
        socklen_t tlen = sizeof type;
        if (*end != '\0' || fd < 0 || fd == dirfd(dir) ||
            fstat((int)fd, &st) != 0 || !S_ISSOCK(st.st_mode) ||
            getsockopt((int)fd, SOL_SOCKET, SO_TYPE, &type, &tlen) != 0 ||
            type != SOCK_DGRAM ||
            getsockname((int)fd, (struct sockaddr *)&addr, &len) != 0 ||
            addr.sin_family != AF_INET || ntohs(addr.sin_port) != port)
            continue;
        if (fds != NULL)
            fds[n] = (int)fd;
        inos[n++] = st.st_ino;
    }
    closedir(dir);
    return n;
}

#define SOCKETS_MAX 64

int mpb_lcm_sockets(const char *url, int *fds, int max)
{
    ino_t inos[SOCKETS_MAX];
    int port = url_port(url ? url : MPB_DEFAULT_LCM_URL);
    if (port == 0 || fds == NULL || max < 1)
        return 0;
    return sockets_on(port, fds, inos, max < SOCKETS_MAX ? max : SOCKETS_MAX);
}

lcm_t *mpb_lcm_create(const char *url, const char *const *channels,
                              int n, int *filtered)
{
    if (mpb_lcm_url_is_hub(url)) {
        /* Not a socket to filter: a link that checks every length. */
        lcm_t *hub = mpb__hub_create(url, channels, n);
        if (filtered)
            *filtered = hub != NULL;
        return hub;
    }
    int port = url_port(url ? url : MPB_DEFAULT_LCM_URL), ok = port != 0;
    int after_fd[SOCKETS_MAX], nb = 0, na = 0;
    ino_t before[SOCKETS_MAX], after[SOCKETS_MAX];

    if (ok)
        nb = sockets_on(port, NULL, before, SOCKETS_MAX);
    lcm_t *lcm = lcm_create(url);
    if (lcm == NULL) {
        if (filtered)
            *filtered = 0;
        return NULL;
    }
    if (ok) {
        /* The receive socket, set up now; the one new socket on the port. */
        lcm_get_fileno(lcm);
        na = sockets_on(port, after_fd, after, SOCKETS_MAX);
        int found = -1, fresh = 0;
        for (int i = 0; i < na; i++) {
            int old = 0;
            for (int j = 0; j < nb && !old; j++)
                old = after[i] == before[j];
            if (!old) {
                found = after_fd[i];
                fresh++;
            }
        }
        ok = fresh == 1 && mpb_lcm_filter_socket(found, channels, n) == MPB_OK;
    }
    if (filtered)
        *filtered = ok;
    return lcm;
}
