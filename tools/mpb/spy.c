/*
 * spy.c - `mpb spy`: starts LCM's lcm-spy with mpbench's message types on
 * its class path, so that every mpbench channel shows decoded. Debian's
 * lcm-spy wrapper passes -Xincgc, which Java 17 refuses, so this runs
 * `java -cp lcm.jar:jchart2d.jar:mpb_types.jar lcm.spy.Spy` itself, as its
 * child: once Java's LCM has made its UDP socket, this process takes it
 * (pidfd_getfd(), which a parent may do to its child) and attaches the
 * filter of lcm_filter.h that keeps every channel and drops malformed
 * datagrams, then waits for lcm-spy and exits with its status. Through a
 * hub (tcpq://) there is no datagram to filter: lcm-spy's Java client
 * reads what the hub relays.
 */
#include <dirent.h>
#include <errno.h>
#include <getopt.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "mpb.h"

#define CMD "spy"

/* Where Debian's liblcm-java and libjchart2d-java put their jars; the
 * build may say otherwise (tools/CMakeLists.txt). */
#ifndef MPB_LCM_JAR
#define MPB_LCM_JAR "/usr/share/java/lcm.jar"
#endif
#ifndef MPB_JCHART2D_JAR
#define MPB_JCHART2D_JAR "/usr/share/java/jchart2d.jar"
#endif
/* From the directory of the installed `mpb` to share/mpbench. */
#ifndef MPB_BIN_TO_DATA
#define MPB_BIN_TO_DATA "../share/mpbench"
#endif
/* The same jar in the build tree: build/tools/mpb, build/lcmtypes/. */
#define MPB_BUILD_TO_JAR "../lcmtypes"
#define MPB_TYPES_JAR "mpb_types.jar"

static void usage(FILE *out)
{
    fprintf(out,
        "usage: mpb spy [--lcm-url URL] [--classpath PATH] [--print-command]\n"
        "\n"
        "Start lcm-spy, LCM's traffic viewer, with mpbench's message types on\n"
        "its class path: every mpbench channel (MPB_ANNOUNCE, MPB_REQUEST_*,\n"
        "MPB_ACK, MPB_ACK_*, MPB_RESULT, MPB_STATUS) shows decoded, and\n"
        "MPB_STATUS reads as the experiment's progress. Double-click a\n"
        "channel to see its last message field by field.\n"
        "\n"
        "It runs java -cp LCM.jar:JCHART2D.jar:mpb_types.jar lcm.spy.Spy,\n"
        "with lcm.jar and jchart2d.jar from /usr/share/java (Debian packages\n"
        "liblcm-java and libjchart2d-java) and mpb_types.jar from the build\n"
        "tree or the install prefix (share/mpbench). Java is $JAVA_HOME/bin/java\n"
        "when JAVA_HOME is set, else java on the PATH. It needs a display:\n"
        "without DISPLAY (or WAYLAND_DISPLAY) it exits 1 at once. Its LCM\n"
        "socket drops malformed datagrams, as every mpbench process's does;\n"
        "a warning says when that filter could not be attached.\n"
        "\n"
        "Options:\n"
        "  -u, --lcm-url URL     LCM URL (default: " MPB_DEFAULT_LCM_URL ");\n"
        "                        the daemon's\n"
        "  -c, --classpath PATH  more jars or directories for the class path,\n"
        "                        ':'-separated: your planners' own LCM types,\n"
        "                        lcm-spy plugins\n"
        "  -n, --print-command   print the command instead of running it\n"
        "  -h, --help            print this help\n"
        "\n"
        "Exit status: lcm-spy's; 1 when java or a jar is missing, 2 on a bad\n"
        "command line.\n");
}

/* How long Java may take to make its LCM socket. */
#define SPY_SOCKET_WAIT_S 60

static volatile sig_atomic_t spy_child;

static void forward_signal(int sig)
{
    if (spy_child > 0)
        kill((pid_t)spy_child, sig);
}

/* Attach the keep-every-channel filter to the UDP socket on url's port
 * of the child pidfd names, pid: each of its sockets is taken in turn
 * (a duplicate, closed again) and the ones mpb_lcm_sockets() then finds
 * in this process are its. 1 if attached. */
static int filter_child(int pidfd, pid_t pid, const char *url)
{
    char dir[64];
    snprintf(dir, sizeof dir, "/proc/%d/fd", (int)pid);
    DIR *d = opendir(dir);
    struct dirent *e;
    int attached = 0;
    if (d == NULL)
        return 0;
    while (!attached && (e = readdir(d)) != NULL) {
        char path[sizeof dir + sizeof e->d_name], target[64];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        ssize_t n = readlink(path, target, sizeof target - 1);
        if (n <= 0)
            continue;
        target[n] = '\0';
        if (strncmp(target, "socket:", 7) != 0)
            continue;
        int fd = (int)syscall(SYS_pidfd_getfd, pidfd, atoi(e->d_name), 0);
        if (fd < 0)
            continue;
        int mine[4];
        int k = mpb_lcm_sockets(url, mine, 4);
        for (int i = 0; i < k; i++)
            if (mine[i] == fd)
                attached = mpb_lcm_filter_socket(fd, NULL, 0) == MPB_OK;
        close(fd);
    }
    closedir(d);
    return attached;
}

/* Run lcm-spy as a child, filter its LCM socket, and wait for it: its
 * exit status. */
static int run_spy(const char *java, char *const args[], const char *url)
{
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) {
        fprintf(stderr, "mpb " CMD ": cannot start %s: %s\n", java, strerror(errno));
        return MPB_EXIT_ERROR;
    }
    if (pid == 0) {
        execv(java, args);
        fprintf(stderr, "mpb " CMD ": cannot run %s: %s\n", java, strerror(errno));
        _exit(MPB_EXIT_ERROR);
    }
    spy_child = pid;
    struct sigaction sa = {.sa_handler = forward_signal};
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);

    /* Through a hub lcm-spy reads a TCP stream, which no socket filter
     * can check; lcm-java's client takes a frame only as large as the hub
     * could hold (tools/run_benchmark.sh --hub bounds its heap). */
    int hub = mpb_lcm_url_is_hub(url);
    int pidfd = hub ? -1 : (int)syscall(SYS_pidfd_open, pid, 0);
    int attached = 0, status = 0;
    struct timespec tick = {0, 20 * 1000000L};
    for (int i = 0; pidfd >= 0 && !attached && i < SPY_SOCKET_WAIT_S * 50; i++) {
        pid_t w = waitpid(pid, &status, WNOHANG);
        if (w == pid) {
            close(pidfd);
            return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        }
        attached = filter_child(pidfd, pid, url);
        if (!attached)
            nanosleep(&tick, NULL);
    }
    if (pidfd >= 0)
        close(pidfd);
    if (hub)
        fprintf(stderr, "mpb " CMD ": through the hub at %s: lcm-spy takes "
                "each frame the hub relays, whose size the hub's own memory "
                "bounds (docs/reliability.md)\n", url);
    else if (!attached)
        fprintf(stderr, "mpb " CMD ": " MPB_LCM_UNFILTERED "\n");
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return MPB_EXIT_ERROR;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/* path is a readable regular file or directory. */
static int readable(const char *path)
{
    return access(path, R_OK) == 0;
}

/* The directory of the running `mpb`, from /proc/self/exe; 0 on success. */
static int exe_dir(char *buf, size_t n)
{
    ssize_t len = readlink("/proc/self/exe", buf, n - 1);
    if (len <= 0 || (size_t)len >= n - 1)
        return -1;
    buf[len] = '\0';
    char *slash = strrchr(buf, '/');
    if (slash == NULL)
        return -1;
    *slash = '\0';
    return 0;
}

/*
 * mpb_types.jar: next to an installed `mpb` (PREFIX/bin -> PREFIX/share/
 * mpbench) or a built one (build/tools -> build/lcmtypes). Relative to the
 * program, not a fixed path, so that a staged or moved install still finds
 * its own jar and never another build's.
 */
static int find_types_jar(char *out, size_t n)
{
    static const char *const rel[] = {MPB_BIN_TO_DATA, MPB_BUILD_TO_JAR};
    char dir[PATH_MAX];
    if (exe_dir(dir, sizeof dir) != 0)
        return -1;
    for (size_t i = 0; i < sizeof rel / sizeof rel[0]; i++) {
        char path[PATH_MAX];
        int len = snprintf(path, sizeof path, "%s/%s/%s", dir, rel[i],
                           MPB_TYPES_JAR);
        if (len > 0 && (size_t)len < sizeof path && readable(path) &&
            n >= PATH_MAX && realpath(path, out) != NULL)
            return 0;
    }
    return -1;
}

/* java: $JAVA_HOME/bin/java, else the first executable java on the PATH. */
static int find_java(char *out, size_t n)
{
    const char *home = getenv("JAVA_HOME");
    if (home != NULL && home[0] != '\0') {
        int len = snprintf(out, n, "%s/bin/java", home);
        return len > 0 && (size_t)len < n && access(out, X_OK) == 0 ? 0 : -1;
    }
    const char *path = getenv("PATH");
    if (path == NULL)
        path = "/usr/bin:/bin";
    while (*path != '\0') {
        size_t dirlen = strcspn(path, ":");
        int len = snprintf(out, n, "%.*s/java", (int)dirlen,
                           dirlen > 0 ? path : ".");
        if (len > 0 && (size_t)len < n && access(out, X_OK) == 0)
            return 0;
        path += dirlen + (path[dirlen] == ':');
    }
    return -1;
}

/* Print one word of a command, quoted for a POSIX shell when it needs to be. */
static void print_word(const char *w)
{
    if (w[0] != '\0' && strspn(w, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOP"
                                  "QRSTUVWXYZ0123456789/._-=:,+@%") == strlen(w)) {
        fputs(w, stdout);
        return;
    }
    putchar('\'');
    for (const char *p = w; *p != '\0'; p++) {
        if (*p == '\'')
            fputs("'\\''", stdout);
        else
            putchar(*p);
    }
    putchar('\'');
}

int cmd_spy(int argc, char **argv)
{
    static const struct option longopts[] = {
        {"lcm-url", required_argument, NULL, 'u'},
        {"classpath", required_argument, NULL, 'c'},
        {"print-command", no_argument, NULL, 'n'},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    const char *url = MPB_DEFAULT_LCM_URL, *extra = NULL;
    int print_only = 0, opt;

    optind = 1;
    opterr = 0;
    while ((opt = getopt_long(argc, argv, ":u:c:nh", longopts, NULL)) != -1) {
        switch (opt) {
        case 'u':
            url = optarg;
            break;
        case 'c':
            extra = optarg;
            break;
        case 'n':
            print_only = 1;
            break;
        case 'h':
            usage(stdout);
            return MPB_EXIT_OK;
        default:    /* ':' a missing value, '?' an unknown option */
            return tool_option_error(CMD, opt, argv);
        }
    }
    if (optind < argc)
        return tool_extra_argument(CMD, argv[optind]);

    char java[PATH_MAX], types[PATH_MAX];
    if (find_java(java, sizeof java) != 0) {
        if (getenv("JAVA_HOME") != NULL && getenv("JAVA_HOME")[0] != '\0')
            fprintf(stderr, "mpb " CMD ": no java in $JAVA_HOME/bin (JAVA_HOME"
                    "=%s)\n", getenv("JAVA_HOME"));
        else
            fprintf(stderr, "mpb " CMD ": java not found on the PATH (install "
                    "a Java runtime, e.g. Debian's default-jre, or set "
                    "JAVA_HOME)\n");
        return MPB_EXIT_ERROR;
    }
    if (!readable(MPB_LCM_JAR)) {
        fprintf(stderr, "mpb " CMD ": %s not found (Debian package "
                "liblcm-java)\n", MPB_LCM_JAR);
        return MPB_EXIT_ERROR;
    }
    if (!readable(MPB_JCHART2D_JAR)) {
        fprintf(stderr, "mpb " CMD ": %s not found (Debian package "
                "libjchart2d-java)\n", MPB_JCHART2D_JAR);
        return MPB_EXIT_ERROR;
    }
    if (find_types_jar(types, sizeof types) != 0) {
        fprintf(stderr, "mpb " CMD ": " MPB_TYPES_JAR " not found in "
                "PREFIX/share/mpbench nor in the build tree (it is built when "
                "javac and lcm.jar are there: Debian's default-jdk-headless, "
                "liblcm-java)\n");
        return MPB_EXIT_ERROR;
    }

    size_t cplen = strlen(MPB_LCM_JAR) + strlen(MPB_JCHART2D_JAR) +
                   strlen(types) + (extra ? strlen(extra) : 0) + 4;
    char *classpath = malloc(cplen);
    char *urlarg = malloc(strlen("--lcm-url=") + strlen(url) + 1);
    if (classpath == NULL || urlarg == NULL) {
        fprintf(stderr, "mpb " CMD ": out of memory\n");
        free(classpath);
        free(urlarg);
        return MPB_EXIT_ERROR;
    }
    snprintf(classpath, cplen, "%s:%s:%s%s%s", MPB_LCM_JAR, MPB_JCHART2D_JAR,
             types, extra ? ":" : "", extra ? extra : "");
    /* One word, so that a URL beginning with '-' cannot be taken for an
     * option by lcm-spy. */
    sprintf(urlarg, "--lcm-url=%s", url);

    /* IPv4 for LCM's UDP multicast, as LCM's own launcher asks. */
    char *args[] = {java, "-Djava.net.preferIPv4Stack=true", "-cp", classpath,
                    "lcm.spy.Spy", urlarg, NULL};
    if (print_only) {
        for (int i = 0; args[i] != NULL; i++) {
            if (i > 0)
                putchar(' ');
            print_word(args[i]);
        }
        putchar('\n');
        free(classpath);
        free(urlarg);
        return MPB_EXIT_OK;
    }
    const char *x = getenv("DISPLAY"), *wl = getenv("WAYLAND_DISPLAY");
    if ((x == NULL || *x == '\0') && (wl == NULL || *wl == '\0')) {
        /* Java would only throw a HeadlessException at length. */
        fprintf(stderr, "mpb " CMD ": no display (DISPLAY is not set): "
                "lcm-spy is a window; run it on a desktop, over ssh -X, or "
                "under xvfb-run\n");
        free(classpath);
        free(urlarg);
        return MPB_EXIT_ERROR;
    }
    int rc = run_spy(java, args, url);
    free(classpath);
    free(urlarg);
    return rc;
}
