/* planner_memory.c - a planner's peak memory and memory limit around one solve, and its last words. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include "mpbench/mpbench.h"
#include "mpbench/proto.h"
#include "mpb_plan_result_t.h"
#include "net/auth_internal.h"
#include "planner/planner_memory.h"

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MPB__ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define MPB__ASAN 1
#endif
#ifdef MPB__ASAN
void __sanitizer_set_death_callback(void (*callback)(void));

/*
 * In a sanitized build, an allocation past the memory limit must fail
 * as malloc does (NULL, std::bad_alloc), as the kit expects: ASan's
 * default is a report of it, which itself needs memory the limit
 * refuses, fails a CHECK and leaves the process hung mid-run. ASan reads
 * this from a program linking the kit before ASAN_OPTIONS, which can
 * still set it otherwise.
 */
const char *__asan_default_options(void);
const char *__asan_default_options(void)
{
    return "allocator_may_return_null=1";
}
#endif

/*
 * The kB of a "Key:" line of /proc/self/status, or -1. With open() and
 * read() into the stack only: it is also called from a signal handler,
 * and under the memory limit, where stdio's buffer may not be had.
 */
static long status_kb(const char *key)
{
    char buf[8192];
    int fd = open("/proc/self/status", O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return -1;
    size_t n = 0;
    for (;;) {
        ssize_t r = read(fd, buf + n, sizeof buf - 1 - n);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            break;
        n += (size_t)r;
        if (n == sizeof buf - 1)
            break;
    }
    close(fd);
    buf[n] = '\0';
    size_t klen = strlen(key);
    for (char *line = buf; line != NULL && *line != '\0';) {
        if (strncmp(line, key, klen) == 0 && line[klen] == ':') {
            long kb = 0;
            int digits = 0;
            for (const char *p = line + klen + 1; *p != '\n' && *p != '\0'; p++)
                if (*p >= '0' && *p <= '9') {
                    kb = kb * 10 + (*p - '0');
                    digits = 1;
                }
            return digits ? kb : -1;
        }
        line = strchr(line, '\n');
        if (line != NULL)
            line++;
    }
    return -1;
}

/* Reset VmHWM to the resident size now (Linux 4.0 and later). */
static int reset_peak(void)
{
    int fd = open("/proc/self/clear_refs", O_WRONLY | O_CLOEXEC);
    if (fd < 0)
        return 0;
    ssize_t w = write(fd, "5", 1);
    close(fd);
    return w == 1;
}

/*
 * Why RLIMIT_DATA and not RLIMIT_AS: since Linux 4.7 the data limit
 * counts the private writable memory a process maps (the brk heap,
 * malloc's mmap'd chunks and arenas as they are made writable, C++'s new,
 * which is malloc), not address space merely reserved: glibc reserves
 * 64 MB per malloc arena (one per thread that allocates) and 8 MB per
 * thread stack, and AddressSanitizer reserves terabytes of shadow, all of
 * which RLIMIT_AS would charge to the planning. The limit is the data
 * size now plus the allowance, so what the process held before the solve
 * (its world, LCM's buffers) is not counted, as OMPL's Benchmark counts
 * maxMem over the memory at the start of the run.
 */
int mpb__mem_begin(mpb__memwatch *w, double limit_mb, char *err,
                   size_t errlen)
{
    memset(w, 0, sizeof *w);
    w->limit_mb = limit_mb > 0 && isfinite(limit_mb) ? limit_mb : 0;
    long data_kb = status_kb("VmData");
    w->data_start_mb = data_kb >= 0 ? (double)data_kb / 1024.0 : NAN;
    w->reset = reset_peak();
    if (w->limit_mb <= 0)
        return 0;
    if (data_kb < 0 || getrlimit(RLIMIT_DATA, &w->old) != 0) {
        snprintf(err, errlen, "memory_limit %g MB not enforced: cannot read "
                 "the process's data size (/proc/self/status VmData)",
                 limit_mb);
        return -1;
    }
    double want = ((double)data_kb / 1024.0 + w->limit_mb) * 1048576.0;
    struct rlimit lim = w->old;
    if (want < (double)RLIM_INFINITY &&
        (w->old.rlim_max == RLIM_INFINITY || want < (double)w->old.rlim_max))
        lim.rlim_cur = (rlim_t)want;
    else
        lim.rlim_cur = w->old.rlim_max;
    if (setrlimit(RLIMIT_DATA, &lim) != 0) {
        snprintf(err, errlen, "memory_limit %g MB not enforced: "
                 "setrlimit(RLIMIT_DATA): %s", limit_mb, strerror(errno));
        return -1;
    }
    w->limited = 1;
    return 0;
}

double mpb__mem_end(mpb__memwatch *w)
{
    if (w->limited) {
        setrlimit(RLIMIT_DATA, &w->old);
        w->limited = 0;
    }
    long hwm = status_kb("VmHWM");
    return hwm > 0 ? (double)hwm / 1024.0 : NAN;
}

/* ---- last words ---------------------------------------------------------- */

/* What a handler needs, set by arm() before the handlers are installed.
 * Globals, unlike the rest of the library: a signal handler has no
 * other way to its state. */
static struct {
    volatile sig_atomic_t armed;
    lcm_t *lcm;
    mpb_auth *auth;
    uint64_t echo;
    const char *attempt_id;
    const char *planner_id;
    double limit_mb, data_start_mb, start_s;
    unsigned char *announce;
    int announce_len;
    struct sigaction old[3];
} g_lw;

static const int lw_signals[3] = {SIGABRT, SIGSEGV, SIGBUS};

/* Append s to buf (cap bytes, NUL-terminated), async-signal-safely. */
static void lw_append(char *buf, size_t cap, const char *s)
{
    size_t n = strlen(buf);
    while (*s != '\0' && n + 1 < cap)
        buf[n++] = *s++;
    buf[n] = '\0';
}

static void lw_append_long(char *buf, size_t cap, long v)
{
    char d[24];
    int i = (int)sizeof d - 1;
    d[i] = '\0';
    if (v < 0)
        v = 0;
    do {
        d[--i] = (char)('0' + v % 10);
        v /= 10;
    } while (v > 0 && i > 0);
    lw_append(buf, cap, d + i);
}

/* Publish the run's MEMORY result if the solve had used at least half
 * its allowance; sig 0 for a sanitizer's death. */
static void lw_speak(int sig)
{
    if (!g_lw.armed)
        return;
    g_lw.armed = 0;
    long data_kb = status_kb("VmData");
    double used = data_kb >= 0 ? (double)data_kb / 1024.0 - g_lw.data_start_mb
                               : NAN;
    if (!(used >= g_lw.limit_mb / 2))
        return;                 /* some other death: the daemon's crash */

    char msg[256] = "";
    lw_append(msg, sizeof msg, "the planner process died (");
    if (sig == SIGABRT)
        lw_append(msg, sizeof msg, "SIGABRT, as of an uncaught allocation "
                                   "failure");
    else if (sig == SIGSEGV)
        lw_append(msg, sizeof msg, "SIGSEGV");
    else if (sig == SIGBUS)
        lw_append(msg, sizeof msg, "SIGBUS");
    else
        lw_append(msg, sizeof msg, "the sanitizer's death");
    lw_append(msg, sizeof msg, ") after its data grew ");
    lw_append_long(msg, sizeof msg, (long)used);
    lw_append(msg, sizeof msg, " MB of its memory_limit of ");
    lw_append_long(msg, sizeof msg, (long)g_lw.limit_mb);
    lw_append(msg, sizeof msg, " MB");

    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    double took = (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9 - g_lw.start_s;
    long hwm = status_kb("VmHWM");
    mpb_plan_result_t res;
    memset(&res, 0, sizeof res);
    clock_gettime(CLOCK_REALTIME, &ts);
    res.utime = (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
    res.attempt_id = (char *)g_lw.attempt_id;
    res.planner_id = (char *)g_lw.planner_id;
    res.status = MPB_PLAN_RESULT_T_MEMORY;
    res.message = msg;
    res.time_total = took;          /* solve() began to its death */
    res.time_other = 0;
    res.memory = hwm > 0 ? (double)hwm / 1024.0 : NAN;

    static unsigned char buf[2048];
    int n = mpb_plan_result_t_encoded_size(&res);
    if (n <= 0 || (size_t)n + MPB_AUTH_TRAILER_SIZE > sizeof buf ||
        mpb_plan_result_t_encode(buf, 0, n, &res) != n)
        return;
    /* Closing first, so that the daemon, storing the result, sends the
     * next run elsewhere; then three copies of the result: the process
     * will not be there to re-send. */
    if (g_lw.announce != NULL)
        for (int i = 0; i < 2; i++)
            mpb__publish_encoded(g_lw.lcm, g_lw.auth, g_lw.echo,
                                 MPB_CHANNEL_ANNOUNCE, g_lw.announce,
                                 g_lw.announce_len, 1);
    for (int i = 0; i < 3; i++)
        mpb__publish_encoded(g_lw.lcm, g_lw.auth, g_lw.echo,
                             MPB_CHANNEL_RESULT, buf, n, 1);
}

static void lw_on_signal(int sig)
{
    lw_speak(sig);
    /* Die of it as before: the handler was reset (SA_RESETHAND). */
    raise(sig);
}

#ifdef MPB__ASAN
static void lw_on_sanitizer_death(void)
{
    lw_speak(0);
}
#endif

void mpb__last_words_arm(const mpb__memwatch *w, lcm_t *lcm, mpb_auth *a,
                         uint64_t echo, const char *attempt_id,
                         const char *planner_id, unsigned char *announce,
                         int announce_len)
{
    if (w->limit_mb <= 0 || !isfinite(w->data_start_mb))
        return;
    g_lw.announce = announce;
    g_lw.announce_len = announce_len;
    g_lw.start_s = mpb_monotonic_s();
    g_lw.lcm = lcm;
    g_lw.auth = a;
    g_lw.echo = echo;
    g_lw.attempt_id = attempt_id;
    g_lw.planner_id = planner_id;
    g_lw.limit_mb = w->limit_mb;
    g_lw.data_start_mb = w->data_start_mb;
    /* The generated code computes its type hash on first use: not in a
     * handler. */
    mpb_plan_result_t probe;
    memset(&probe, 0, sizeof probe);
    probe.attempt_id = probe.planner_id = probe.message = (char *)"";
    (void)mpb_plan_result_t_encoded_size(&probe);
    unsigned char tmp[256];
    (void)mpb_plan_result_t_encode(tmp, 0, (int)sizeof tmp, &probe);

    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = lw_on_signal;
    sa.sa_flags = SA_RESETHAND | SA_NODEFER;
    sigemptyset(&sa.sa_mask);
    g_lw.armed = 1;
    for (int i = 0; i < 3; i++)
        sigaction(lw_signals[i], &sa, &g_lw.old[i]);
#ifdef MPB__ASAN
    __sanitizer_set_death_callback(lw_on_sanitizer_death);
#endif
}

void mpb__last_words_disarm(void)
{
    if (!g_lw.armed)
        return;
    g_lw.armed = 0;
    for (int i = 0; i < 3; i++)
        sigaction(lw_signals[i], &g_lw.old[i], NULL);
#ifdef MPB__ASAN
    __sanitizer_set_death_callback(NULL);
#endif
}
