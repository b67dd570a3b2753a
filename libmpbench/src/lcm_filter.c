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

/* Offsets as the filter sees a UDP datagram: the UDP header (8 bytes),
 * then LCM's: magic (4), sequence number (4), the channel, NUL-ended. */
#define UDP_HEADER 8
#define LCM_MAGIC_SHORT 0x4c433032u     /* "LC02" */
#define CHANNEL_AT (UDP_HEADER + 8)

#define PROGRAM_MAX                                                        \
    (4 + MPB_LCM_FILTER_CHANNELS * (3 + 2 * (MPB_LCM_FILTER_NAME_MAX + 1)) + 1)

typedef struct program {
    struct sock_filter op[PROGRAM_MAX];
    int n;
} program;

static void emit(program *p, uint16_t code, uint8_t jt, uint8_t jf, uint32_t k)
{
    p->op[p->n++] = (struct sock_filter){code, jt, jf, k};
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

/* One channel's test: if the datagram is long enough and names exactly
 * this channel, accept it; otherwise fall through to what follows. */
static void emit_channel(program *p, const char *name)
{
    uint32_t size = (uint32_t)strlen(name) + 1;     /* with its NUL */
    uint32_t words = size / 4, tail = size % 4;
    /* Jumps skip to the end of this test: every test below is two ops
     * (load, compare) and then one (accept). */
    int left = 2 * (int)(words + tail) + 1;

    emit(p, BPF_MISC | BPF_TXA, 0, 0, 0);            /* A = length */
    emit(p, BPF_JMP | BPF_JGE | BPF_K, 0, (uint8_t)(left + 0), CHANNEL_AT + size);
    for (uint32_t w = 0; w < words; w++, left -= 2) {
        const unsigned char *b = (const unsigned char *)name + 4 * w;
        uint32_t k = (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 |
                     (uint32_t)b[2] << 8 | b[3];
        emit(p, BPF_LD | BPF_W | BPF_ABS, 0, 0, CHANNEL_AT + 4 * w);
        emit(p, BPF_JMP | BPF_JEQ | BPF_K, 0, (uint8_t)(left - 2), k);
    }
    for (uint32_t t = 0; t < tail; t++, left -= 2) {
        unsigned char b = (unsigned char)name[4 * words + t];
        emit(p, BPF_LD | BPF_B | BPF_ABS, 0, 0, CHANNEL_AT + 4 * words + t);
        emit(p, BPF_JMP | BPF_JEQ | BPF_K, 0, (uint8_t)(left - 2), b);
    }
    emit(p, BPF_RET | BPF_K, 0, 0, 0xffffffffu);      /* accept */
}

/* Attach to fd a filter passing only these channels; 0 on success. */
static int attach(int fd, const char *const *channels, int n)
{
    program *p = calloc(1, sizeof *p);
    if (p == NULL)
        return -1;
    emit(p, BPF_LD | BPF_W | BPF_LEN, 0, 0, 0);      /* X = length */
    emit(p, BPF_MISC | BPF_TAX, 0, 0, 0);
    /* Not a short LCM message (a fragment, too short, another format):
     * pass it. A load past the end ends the filter, so check the length
     * first: magic and sequence number need 8 bytes after UDP's. */
    emit(p, BPF_JMP | BPF_JGE | BPF_K, 1, 0, UDP_HEADER + 8);
    emit(p, BPF_RET | BPF_K, 0, 0, 0xffffffffu);
    emit(p, BPF_LD | BPF_W | BPF_ABS, 0, 0, UDP_HEADER);
    emit(p, BPF_JMP | BPF_JEQ | BPF_K, 1, 0, LCM_MAGIC_SHORT);
    emit(p, BPF_RET | BPF_K, 0, 0, 0xffffffffu);
    for (int i = 0; i < n; i++)
        emit_channel(p, channels[i]);
    emit(p, BPF_RET | BPF_K, 0, 0, 0);               /* drop */

    struct sock_fprog prog = {.len = (unsigned short)p->n, .filter = p->op};
    int rc = setsockopt(fd, SOL_SOCKET, SO_ATTACH_FILTER, &prog, sizeof prog);
    free(p);
    return rc;
}

#define SOCKETS_MAX 64

lcm_t *mpb_lcm_create_keeping(const char *url, const char *const *channels,
                              int n, int *filtered)
{
    int port = url_port(url ? url : MPB_DEFAULT_LCM_URL), ok = port != 0;
    int after_fd[SOCKETS_MAX], nb = 0, na = 0;
    ino_t before[SOCKETS_MAX], after[SOCKETS_MAX];

    ok = ok && channels != NULL && n >= 1 && n <= MPB_LCM_FILTER_CHANNELS;
    for (int i = 0; ok && i < n; i++)
        ok = channels[i] != NULL && strlen(channels[i]) <= MPB_LCM_FILTER_NAME_MAX;
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
        ok = fresh == 1 && attach(found, channels, n) == 0;
    }
    if (filtered)
        *filtered = ok;
    return lcm;
}
