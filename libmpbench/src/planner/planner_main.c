/* planner_main.c - what every planner process's main() does once its
 * options are read: stop on a signal, serve, say why it stopped. */
#include "mpbench/mpbench.h"
#include "mpbench/planner.h"

#include <signal.h>
#include <stdio.h>
#include <string.h>

/* One serving loop a process: the signal handler and the default
 * callbacks have no other way to reach their state. */
static volatile sig_atomic_t mpb__stop;
static const char *mpb__prog;

static void mpb__on_signal(int sig)
{
    (void)sig;
    mpb__stop = 1;
}

static void mpb__print_warning(void *user, const char *line)
{
    (void)user;
    fprintf(stderr, "%s: %s\n", mpb__prog, line);
}

static void mpb__print_ready(void *user, const char *planner_id)
{
    (void)user;
    printf("%s: serving as %s\n", mpb__prog, planner_id);
    fflush(stdout);
}

int mpb_planner_main(const mpb_planner_def *def, const mpb_planner_options *o,
                     const char *prog)
{
    mpb_planner_def d = *def;
    mpb__prog = prog;
    if (d.name == NULL)
        d.name = o->name;
    if (d.secret_file == NULL)
        d.secret_file = o->secret_file;
    if (d.on_ready == NULL)
        d.on_ready = mpb__print_ready;
    if (d.on_warning == NULL)
        d.on_warning = mpb__print_warning;

    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = mpb__on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);

    char err[256] = "";
    int rc = mpb_planner_serve(&d, o->lcm_url, &mpb__stop, o->max_runs, err,
                               sizeof err);
    if (rc != MPB_OK) {
        fprintf(stderr, "%s: %s\n", prog, err[0] ? err : mpb_strerror(rc));
        return 1;
    }
    return 0;
}
