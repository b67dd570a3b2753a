/*
 * status.c - `mpb status`: follows a running experiment from the daemon's
 * status messages (daemon_status_t on MPB_STATUS, once a second): runs
 * done of the total, successes, failures, crashes, rate, time left and the
 * planners the daemon sees. On a terminal one line is redrawn in place;
 * otherwise a plain line is printed whenever the numbers change. Exits when
 * the daemon says the experiment is done.
 */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <lcm/lcm.h>

#include "mpb.h"
#include "mpb_daemon_status_t.h"

#define CMD "status"

#define LINE_MAX_LEN 1024

static volatile sig_atomic_t stop_signal;

static void on_signal(int sig)
{
    stop_signal = sig;
}

typedef struct follower {
    const char *experiment;     /* --experiment, or NULL: any */
    int         tty;            /* stdout is a terminal: redraw in place */
    int         once;
    int         seen;           /* messages taken */
    int         line_open;      /* a redrawn line is on the screen */
    int         ended;          /* "done" (1) or "stopped" (2) seen */
    int         waiting;        /* the "waiting for" line is on the screen */
    char        following[256]; /* the experiment the header names */
    char        daemon[128];    /* the daemon followed: the first to start */
    int64_t     daemon_started; /* when it started, wall clock us */
    char        last_key[LINE_MAX_LEN]; /* the numbers printed last */
    char        detail[8192];   /* --once: a line per planner */
} follower;

static void usage(FILE *out)
{
    fprintf(out,
        "usage: mpb status [--lcm-url URL] [--experiment NAME] [--once]\n"
        "                  [--timeout S]\n"
        "\n"
        "Follow a running experiment from mpbenchd's status messages (LCM\n"
        "channel MPB_STATUS, once a second): runs done of the total, how many\n"
        "succeeded, failed (finished without a valid solution) and crashed,\n"
        "runs in flight, the rate, the time left, and the planners the daemon\n"
        "sees (name, and how many processes when more than one). On a\n"
        "terminal a progress bar is redrawn in place; otherwise a plain line\n"
        "is printed each time the numbers change. It follows the daemon on the\n"
        "URL (of two, the one that started first and stays), and exits when\n"
        "that daemon reports the experiment done.\n"
        "\n"
        "Options:\n"
        "  -u, --lcm-url URL      LCM URL (default: " MPB_DEFAULT_LCM_URL ");\n"
        "                         the daemon's\n"
        "  -e, --experiment NAME  follow only a daemon running the experiment\n"
        "                         NAME\n"
        "  -1, --once             print the current status, one line per\n"
        "                         planner, and exit\n"
        "  -t, --timeout S        give up after S seconds (decimal, e.g. 2.5)\n"
        "                         without a status message (default: wait for\n"
        "                         ever; with --once, 5)\n"
        "  -h, --help             print this help\n"
        "\n"
        "Exit status: 0 when the experiment is done (or, with --once, a status\n"
        "was printed), 1 on a timeout, an LCM error or a daemon stopped before\n"
        "the end, 2 on a bad command line, 128+N on signal N.\n");
}

/* ---- one line of status ----------------------------------------------------- */

/* Append to buf (size n, holding a string) like printf. */
static void append(char *buf, size_t n, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static void append(char *buf, size_t n, const char *fmt, ...)
{
    size_t len = strlen(buf);
    if (len + 1 >= n)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf + len, n - len, fmt, ap);
    va_end(ap);
}

/* "7 s", "4:05" or "1:04:05"; with decimals, "7.3 s" below a minute. */
static void format_duration(char *buf, size_t n, double s, int decimals)
{
    if (!(s >= 0) || s > 99 * 3600.0) {
        snprintf(buf, n, "?");
        return;
    }
    if (s < 59.5) {
        snprintf(buf, n, "%.*f s", decimals, s);
        return;
    }
    long t = (long)(s + 0.5);
    if (t >= 3600)
        snprintf(buf, n, "%ld:%02ld:%02ld", t / 3600, t / 60 % 60, t % 60);
    else
        snprintf(buf, n, "%ld:%02ld", t / 60, t % 60);
}

/* The planners, by family name: "planners: null, ompl x2" ("null, ompl x2"
 * without label). */
static void describe_planners(const mpb_daemon_status_t *st, char *buf,
                              size_t n, int label)
{
    int np = st->num_planners > 0 ? st->num_planners : 0;
    if (np == 0) {
        append(buf, n, "no planners");
        return;
    }
    if (label)
        append(buf, n, "planners: ");
    int listed = 0;
    for (int i = 0; i < np; i++) {
        const char *name = st->planners[i].name;
        if (name == NULL || name[0] == '\0')
            name = st->planners[i].planner_id;
        int first = 1, count = 0;
        for (int j = 0; j < np; j++) {
            const char *other = st->planners[j].name;
            if (other == NULL || other[0] == '\0')
                other = st->planners[j].planner_id;
            if (strcmp(other, name) != 0)
                continue;
            if (j < i)
                first = 0;
            count++;
        }
        if (!first)
            continue;
        append(buf, n, "%s%s", listed++ ? ", " : "", name);
        if (count > 1)
            append(buf, n, " x%d", count);
    }
}

/*
 * The status in one line:
 *   demo: running, 21/42 runs (50%), 18 succeeded, 3 failed, 0 crashed,
 *   2 in flight, 4.20 runs/s, 0:05 left, planners: null, ompl x2
 * (one line; wrapped here). Done, the time taken replaces the time left.
 */
static void describe(const mpb_daemon_status_t *st, char *buf, size_t n)
{
    char t[32];
    int total = st->runs_total, done = st->runs_done;
    int percent = total > 0 ? (int)floor(100.0 * done / total) : 0;
    int finished = strcmp(st->state, "done") == 0;

    buf[0] = '\0';
    append(buf, n, "%s: %s, %d/%d runs (%d%%), %d succeeded, %d failed, "
           "%d crashed, %d in flight, %.2f runs/s, ", st->experiment,
           st->state, done, total, percent, st->runs_succeeded,
           st->runs_failed, st->runs_crashed, st->runs_in_flight,
           st->runs_per_s);
    if (finished) {
        format_duration(t, sizeof t, st->elapsed_s, 1);
        append(buf, n, "took %s, ", t);
    } else {
        double left = st->runs_per_s > 0
                          ? (double)(total - done) / st->runs_per_s : -1.0;
        format_duration(t, sizeof t, left, 0);
        append(buf, n, "%s left, ", t);
    }
    if (st->rejected_messages > 0)
        append(buf, n, "%d rejected messages, ", st->rejected_messages);
    describe_planners(st, buf, n, 1);
}

/* The planners as describe_planners() lists them, in at most room
 * columns (names are ASCII): whole names while they fit, then "+N more";
 * "N planners" when not even the first fits; nothing when that does not
 * either. Never a name cut short. */
static void describe_planners_fit(const mpb_daemon_status_t *st, char *buf,
                                  size_t n, int room)
{
    char all[LINE_MAX_LEN] = "";
    describe_planners(st, all, sizeof all, 0);
    if ((int)strlen(all) <= room) {
        append(buf, n, "%s", all);
        return;
    }
    /* Items are separated by ", "; a name holds no comma. */
    int items = 1;
    for (const char *p = all; (p = strstr(p, ", ")) != NULL; p += 2)
        items++;
    char fit[LINE_MAX_LEN] = "";
    int shown = 0;
    const char *item = all;
    while (shown < items) {
        const char *end = strstr(item, ", ");
        int len = end ? (int)(end - item) : (int)strlen(item);
        char more[32];
        snprintf(more, sizeof more, ", +%d more", items - shown - 1);
        int need = (int)strlen(fit) + (shown ? 2 : 0) + len +
                   (shown + 1 < items ? (int)strlen(more) : 0);
        if (need > room)
            break;
        append(fit, sizeof fit, "%s%.*s", shown ? ", " : "", len, item);
        shown++;
        item = end ? end + 2 : item + len;
    }
    if (shown > 0) {
        append(buf, n, "%s, +%d more", fit, items - shown);
        return;
    }
    char count[32];
    snprintf(count, sizeof count, "%d planners", items);
    if ((int)strlen(count) <= room) {
        append(buf, n, "%s", count);
        return;
    }
    /* Not even that: the numbers without the planners, and no spaces
     * left hanging. */
    size_t len = strlen(buf);
    while (len > 0 && buf[len - 1] == ' ')
        buf[--len] = '\0';
}

static int terminal_width(void)
{
    struct winsize ws;
    if (ioctl(STDOUT_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0)
        return ws.ws_col;
    const char *cols = getenv("COLUMNS");
    int c = cols ? atoi(cols) : 0;
    return c > 0 ? c : 80;
}

/*
 * The terminal's line: a bar (10 wide in 80 columns, up to 30 in wider
 * ones), then the numbers, short enough for 80 columns:
 *   [####------] 24/60 40%  12 ok  12 failed  0 crashed  8.0/s  5 s left
 *   null x2
 * (one line; wrapped here). The experiment's name is on the line above.
 */
static void describe_tty(const mpb_daemon_status_t *st, int width, char *buf,
                         size_t n)
{
    char rest[LINE_MAX_LEN], t[32];
    int total = st->runs_total, done = st->runs_done;
    rest[0] = '\0';
    append(rest, sizeof rest, "%d/%d %d%%  %d ok  %d failed  %d crashed  "
           "%.1f/s  ", done, total,
           total > 0 ? (int)floor(100.0 * done / total) : 0,
           st->runs_succeeded, st->runs_failed, st->runs_crashed,
           st->runs_per_s);
    if (strcmp(st->state, "done") == 0) {
        format_duration(t, sizeof t, st->elapsed_s, 1);
        append(rest, sizeof rest, "in %s  ", t);
    } else if (strcmp(st->state, "running") == 0) {
        format_duration(t, sizeof t, st->runs_per_s > 0
                        ? (double)(total - done) / st->runs_per_s : -1.0, 0);
        append(rest, sizeof rest, "%s left  ", t);
    } else {
        append(rest, sizeof rest, "%s  ", st->state);
    }

    int bar = width - 70;   /* the same width all along, 10 in 80 columns */
    bar = bar < 10 ? 10 : bar > 30 ? 30 : bar;
    int fill = total > 0 ? (int)((double)bar * done / total) : 0;
    fill = fill < 0 ? 0 : fill > bar ? bar : fill;
    char b[32];
    memset(b, '#', (size_t)fill);
    memset(b + fill, '-', (size_t)(bar - fill));
    b[bar] = '\0';
    snprintf(buf, n, "[%s] %s", b, rest);
    /* The planners in what is left of the line redraw() shows. */
    describe_planners_fit(st, buf, n, width - 1 - (int)strlen(buf));
}

/* Redraw the line on the terminal, cut to its width. */
static void redraw(follower *f, const char *text)
{
    int width = terminal_width() - 1;
    if (width < 10)
        width = 10;
    printf("\r%.*s\033[K", width, text);
    fflush(stdout);
    f->line_open = 1;
}

/* End a redrawn line so that what follows starts on a line of its own. */
static void close_line(follower *f)
{
    if (f->waiting) {
        printf("\r\033[K");
        f->waiting = 0;
    }
    if (f->line_open) {
        putchar('\n');
        fflush(stdout);
        f->line_open = 0;
    }
}

static void follow(follower *f, const mpb_daemon_status_t *st);

/* Escape s (mpb_escape) into the buffer at *at, which has room. */
static char *escaped(const char *s, char **at)
{
    char *out = *at;
    size_t n = 4 * strlen(s) + 1;
    mpb_escape(s, out, n);
    *at += strlen(out) + 1;
    return out;
}

/*
 * A status is any process's to send: followed with every string as a
 * terminal may show it, control characters and invalid UTF-8 as \xNN,
 * so that none can move the cursor, clear the screen or add a line.
 */
static void on_status(const mpb_daemon_status_t *st, void *ud)
{
    follower *f = ud;

    if (f->ended || st->experiment == NULL || st->state == NULL ||
        st->daemon_id == NULL)
        return;
    if (f->experiment != NULL && strcmp(st->experiment, f->experiment) != 0)
        return;
    int np = st->num_planners > 0 ? st->num_planners : 0;
    size_t room = 4 * (strlen(st->experiment) + strlen(st->state) +
                       strlen(st->daemon_id)) + 3;
    for (int i = 0; i < np; i++)
        room += 4 * (strlen(st->planners[i].planner_id) +
                     strlen(st->planners[i].name)) + 2;
    char *buf = malloc(room), *at = buf;
    mpb_planner_seen_t *seen = calloc((size_t)np + 1, sizeof *seen);
    if (buf == NULL || seen == NULL) {
        free(buf);
        free(seen);
        return;
    }
    mpb_daemon_status_t safe = *st;
    safe.experiment = escaped(st->experiment, &at);
    safe.state = escaped(st->state, &at);
    safe.daemon_id = escaped(st->daemon_id, &at);
    for (int i = 0; i < np; i++) {
        seen[i] = st->planners[i];
        seen[i].planner_id = escaped(st->planners[i].planner_id, &at);
        seen[i].name = escaped(st->planners[i].name, &at);
    }
    safe.planners = seen;
    follow(f, &safe);
    free(seen);
    free(buf);
}

/* Every status through the library's receive gate (link.h): its bytes
 * checked before it is decoded. Tags are not checked: mpb status holds
 * no secret (docs/reliability.md); a status with a trailer is read
 * without it. */
static void on_status_raw(const lcm_recv_buf_t *rbuf, const char *channel,
                          void *ud)
{
    mpb_daemon_status_t st;
    mpb_received r;
    size_t n = (size_t)rbuf->data_size;
    if (mpb_receive(NULL, MPB_RECEIVE_FRESH, MPB_WIRE_DAEMON_STATUS, channel,
                    rbuf->data, n, &st, &r) != MPB_OK &&
        (n <= MPB_AUTH_TRAILER_SIZE ||
         mpb_receive(NULL, MPB_RECEIVE_FRESH, MPB_WIRE_DAEMON_STATUS, channel,
                     rbuf->data, n - MPB_AUTH_TRAILER_SIZE, &st, &r) != MPB_OK))
        return;
    on_status(&st, ud);
    mpb_receive_done(MPB_WIRE_DAEMON_STATUS, &st);
}

static void follow(follower *f, const mpb_daemon_status_t *st)
{
    char line[LINE_MAX_LEN];
    /* One daemon: another started beside it on the URL stops at once, and
     * its "stopped" is not the end of this one's experiment. The one that
     * stays is the first to start, which answers a younger one at once:
     * followed from then on, even if the younger one was heard first. */
    if (st->daemon_id != NULL && strcmp(st->daemon_id, f->daemon) != 0) {
        int64_t started = mpb_daemon_started_utime(st);
        if (f->daemon[0] != '\0' &&
            !mpb_daemon_started_before(started, st->daemon_id,
                                       f->daemon_started, f->daemon))
            return;
        if (f->daemon[0] != '\0') {
            f->following[0] = '\0';     /* a header, a line, for this one */
            f->last_key[0] = '\0';
        }
        snprintf(f->daemon, sizeof f->daemon, "%s", st->daemon_id);
        f->daemon_started = started;
    }
    f->seen++;
    describe(st, line, sizeof line);

    if (f->once) {
        printf("%s\n", line);
        f->detail[0] = '\0';
        for (int i = 0; i < st->num_planners; i++) {
            const mpb_planner_seen_t *p = &st->planners[i];
            append(f->detail, sizeof f->detail, "  %s (%s): %d runs done, "
                   "%d active, last heard %.1f s ago\n", p->planner_id,
                   p->name, p->runs_done, p->num_active, p->last_seen_s);
        }
        fputs(f->detail, stdout);
        fflush(stdout);
        f->ended = strcmp(st->state, "done") == 0 ? 1 : 3;
        return;
    }
    if (f->tty) {
        char full[LINE_MAX_LEN + 40];
        if (strcmp(st->experiment, f->following) != 0) {
            /* A header line per experiment; the numbers redrawn below. */
            close_line(f);
            if (f->waiting) {
                printf("\r\033[K");
                f->waiting = 0;
            }
            printf("experiment %s (%s)\n", st->experiment,
                   st->daemon_id ? st->daemon_id : "?");
            snprintf(f->following, sizeof f->following, "%s", st->experiment);
        }
        describe_tty(st, terminal_width(), full, sizeof full);
        redraw(f, full);
    } else {
        /* A plain line when something other than the clock moved. */
        char key[LINE_MAX_LEN];
        snprintf(key, sizeof key, "%s|%s|%d|%d|%d|%d|%d|%d|%d|", st->experiment,
                 st->state, st->runs_total, st->runs_done, st->runs_succeeded,
                 st->runs_failed, st->runs_crashed, st->runs_in_flight,
                 st->rejected_messages);
        describe_planners(st, key, sizeof key, 1);
        if (strcmp(key, f->last_key) != 0) {
            printf("%s\n", line);
            fflush(stdout);
            snprintf(f->last_key, sizeof f->last_key, "%s", key);
        }
    }
    if (strcmp(st->state, "done") == 0)
        f->ended = 1;
    else if (strcmp(st->state, "stopped") == 0)
        f->ended = 2;
}

/* ---- the command --------------------------------------------------------- */

int cmd_status(int argc, char **argv)
{
    static const struct option longopts[] = {
        {"lcm-url", required_argument, NULL, 'u'},
        {"experiment", required_argument, NULL, 'e'},
        {"once", no_argument, NULL, '1'},
        {"timeout", required_argument, NULL, 't'},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    follower f = {0};
    const char *url = MPB_DEFAULT_LCM_URL;
    double timeout = -1.0;
    int opt, status = MPB_EXIT_ERROR;

    optind = 1;
    opterr = 0;
    while ((opt = getopt_long(argc, argv, ":u:e:1t:h", longopts, NULL)) != -1) {
        switch (opt) {
        case 'u':
            url = optarg;
            break;
        case 'e':
            f.experiment = optarg;
            break;
        case '1':
            f.once = 1;
            break;
        case 't': {
            char *end;
            errno = 0;
            timeout = strtod(optarg, &end);
            /* Decimal only: strtod would take 0x10, 1e3, inf too. */
            if (optarg[strspn(optarg, "0123456789.")] != '\0' ||
                errno != 0 || end == optarg || *end != '\0' ||
                !(timeout > 0) || isinf(timeout)) {
                fprintf(stderr, "mpb " CMD ": --timeout wants a number of "
                        "seconds > 0, not '%s'\n", optarg);
                return MPB_EXIT_USAGE;
            }
            break;
        }
        case 'h':
            usage(stdout);
            return MPB_EXIT_OK;
        default:    /* ':' a missing value, '?' an unknown option */
            return tool_option_error(CMD, opt, argv);
        }
    }
    if (optind < argc)
        return tool_extra_argument(CMD, argv[optind]);
    if (timeout < 0 && f.once)
        timeout = 5.0;
    f.tty = isatty(STDOUT_FILENO);

    /* Its one channel, and no malformed datagram (lcm_filter.h). */
    static const char *const mine[] = {MPB_CHANNEL_STATUS};
    int filtered = 0;
    lcm_t *lcm = mpb_lcm_create(url, mine, 1, &filtered);
    if (lcm != NULL && !filtered)
        fprintf(stderr, "mpb " CMD ": " MPB_LCM_UNFILTERED "\n");
    if (lcm == NULL) {
        /* Only a UDP multicast URL fails for want of a route. */
        if (strncmp(url, "udpm://", 7) == 0)
            fprintf(stderr, "mpb " CMD ": cannot start LCM on %s (no "
                    "multicast route? see README)\n", url);
        else
            fprintf(stderr, "mpb " CMD ": cannot start LCM on %s (see "
                    "LCM's URLs: udpm://, tcpq://HOST:PORT, file://, "
                    "memq://)\n", url);
        return MPB_EXIT_ERROR;
    }
    lcm_subscription_t *sub =
        lcm_subscribe(lcm, MPB_CHANNEL_STATUS, on_status_raw, &f);
    if (sub == NULL) {
        fprintf(stderr, "mpb " CMD ": cannot subscribe to " MPB_CHANNEL_STATUS
                " on %s\n", url);
        mpb_lcm_destroy(lcm);
        return MPB_EXIT_ERROR;
    }

    struct sigaction sa = {.sa_handler = on_signal};
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);

    if (f.tty && !f.once) {
        char wait[LINE_MAX_LEN];
        snprintf(wait, sizeof wait, "waiting for mpbenchd's status on %s%s%s "
                 "...", url, f.experiment ? " for experiment " : "",
                 f.experiment ? f.experiment : "");
        redraw(&f, wait);
        f.line_open = 0;
        f.waiting = 1;
    }

    int fd = lcm_get_fileno(lcm);
    double last_heard = mpb_monotonic_s();
    while (!f.ended && !stop_signal) {
        struct pollfd pfd = {.fd = fd, .events = POLLIN};
        int n = poll(&pfd, 1, 200);
        if (n < 0 && errno != EINTR) {
            close_line(&f);
            fprintf(stderr, "mpb " CMD ": %s\n", strerror(errno));
            goto done;
        }
        if (n > 0 && (pfd.revents & POLLIN)) {
            int before = f.seen;
            if (lcm_handle(lcm) != 0) {
                close_line(&f);
                fprintf(stderr, "mpb " CMD ": LCM stopped receiving on %s\n",
                        url);
                goto done;
            }
            if (f.seen != before)
                last_heard = mpb_monotonic_s();
        }
        if (timeout > 0 && !f.ended &&
            mpb_monotonic_s() - last_heard >= timeout) {
            close_line(&f);
            fprintf(stderr, "mpb " CMD ": no status from mpbenchd%s%s on %s "
                    "for %g s (is it running, on the same LCM URL?)\n",
                    f.experiment ? " for experiment " : "",
                    f.experiment ? f.experiment : "", url, timeout);
            goto done;
        }
    }
    close_line(&f);
    if (stop_signal) {
        status = 128 + (int)stop_signal;
    } else if (f.ended == 2) {
        fprintf(stderr, "mpb " CMD ": mpbenchd stopped before the experiment "
                "was done (run it again to resume)\n");
    } else {
        status = MPB_EXIT_OK;
    }
done:
    lcm_unsubscribe(lcm, sub);
    mpb_lcm_destroy(lcm);
    return status;
}
