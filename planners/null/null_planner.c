/* null_planner.c - mpb-planner-null: the unchecked straight line, for tests and overhead. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "mpbench/mpbench.h"
#include "mpbench/planner.h"

static void usage(FILE *out)
{
    fprintf(out,
"usage: mpb-planner-null [--lcm-url URL] [--name NAME] [--max-runs N]\n"
"                        [--secret-file FILE]\n"
"\n"
"A planner process for mpbench that does no planning. It answers every\n"
"plan request for the algorithm \"straight_line\" with status SOLVED and one\n"
"stage, \"raw\", of two waypoints: the start state and the goal joints. It\n"
"checks nothing, so the path may well collide: that is the point. Use it to\n"
"test the daemon and to measure mpbench's own overhead per run.\n"
"Only joint-space goals are supported; a pose-region goal is answered with\n"
"INVALID_REQUEST. A request parameter \"delay\" (seconds) makes it sleep that\n"
"long before answering, as if it were planning: fault tests use it to catch\n"
"planners in the middle of a run. A parameter \"setup\" (seconds) makes it\n"
"sleep that long first, as if building its model of the robot and scene,\n"
"having told the daemon so (SETTING_UP, then PLANNING: docs/protocol.md),\n"
"and report it as world_setup_time: tests use it for a slow model\n"
"build. A parameter \"waypoints\" (2 to\n"
"10000000, default 2) makes the stage that many waypoints, evenly from\n"
"start to goal: tests use it for results too large to send. A parameter\n"
"\"allocate\" (MB, 0 to 65536) makes it allocate and touch that much memory,\n"
"in 1 MB blocks, and free it before answering: tests use it for the run's\n"
"peak memory and the experiment's memory_limit. An allocation that fails\n"
"is answered as MEMORY, or with \"out_of_memory\" = \"abort\" kills the\n"
"process with abort(), as an uncaught std::bad_alloc would. A parameter\n"
"\"status\" (solved, failed, timeout or approximate; default solved) is\n"
"the status it answers with, the same straight line as its stage: tests\n"
"use it for claims in both directions, a path its planner calls failed\n"
"that mpbench finds valid (an unclaimed valid path) and one it calls\n"
"solved that collides (a refused claim). It declares no approach\n"
"(docs/protocol.md): it is no kind of planner.\n"
"A parameter \"duration\" (s, -3600 to 3600) makes the stage a timed\n"
"trajectory: waypoint "
"i at time i * duration / (waypoints - 1), from 0 to the duration, as a\n"
"time-parameterising library would send it; tests use it for the daemon's\n"
"velocity limits (a short duration moves the joints too fast) and, with\n"
"a negative duration (times decreasing), for times it refuses.\n"
"\n"
"It announces itself on LCM as NAME@host:pid and serves until SIGINT or\n"
"SIGTERM (or N runs). It prints one line when it starts, nothing per run.\n"
"\n"
"options:\n"
"  --lcm-url URL   LCM URL to join (default %s;\n"
"                  the daemon must use the same one)\n"
"  --name NAME     planner name used in experiment files (default \"null\")\n"
"  --max-runs N    exit after answering N runs (default 0: no limit)\n"
"  --secret-file F authenticate every message with the shared secret in F\n"
"                  (the daemon must use the same file)\n"
"  --help          show this text\n",
            MPB_DEFAULT_LCM_URL);
}

/* Allocate and touch mb MB in 1 MB blocks, then free them: what a
 * planner's search would hold at its peak. A failed allocation is
 * MPB_ENOMEM (the kit reports MEMORY), or abort() when asked. */
static int allocate_mb(const mpb_plan_request_t *req, mpb_plan_result_t *res,
                       const char *text)
{
    char *end;
    errno = 0;
    long mb = strtol(text, &end, 10);
    if (end == text || *end != '\0' || errno != 0 || mb < 0 || mb > 65536) {
        mpb_result_set_message(res, "allocate must be MB from 0 to 65536, "
                                    "not '%.40s'", text);
        return MPB_EINVAL;
    }
    const char *oom = mpb_request_param(req, "out_of_memory");
    int die = oom != NULL && strcmp(oom, "abort") == 0;
    char **blocks = calloc((size_t)mb + 1, sizeof *blocks);
    int rc = blocks != NULL ? MPB_OK : MPB_ENOMEM;
    for (long i = 0; rc == MPB_OK && i < mb; i++) {
        if ((blocks[i] = malloc(1 << 20)) == NULL)
            rc = MPB_ENOMEM;
        else
            memset(blocks[i], (int)(i & 0x7f) + 1, 1 << 20);
    }
    if (rc != MPB_OK && die)
        abort();
    for (long i = 0; blocks != NULL && i < mb; i++)
        free(blocks[i]);
    free(blocks);
    if (rc != MPB_OK)
        mpb_result_set_message(res, "could not allocate %ld MB", mb);
    return rc;
}

/* The status the request's "status" parameter asks for (SOLVED when it
 * has none); -1 for a word that is none of them. */
static int asked_status(const mpb_plan_request_t *req)
{
    static const struct { const char *word; int status; } words[] = {
        {"solved", MPB_PLAN_RESULT_T_SOLVED},
        {"failed", MPB_PLAN_RESULT_T_FAILED},
        {"timeout", MPB_PLAN_RESULT_T_TIMEOUT},
        {"approximate", MPB_PLAN_RESULT_T_APPROXIMATE},
    };
    const char *word = mpb_request_param(req, "status");
    if (word == NULL)
        return MPB_PLAN_RESULT_T_SOLVED;
    for (size_t i = 0; i < sizeof words / sizeof *words; i++)
        if (strcmp(word, words[i].word) == 0)
            return words[i].status;
    return -1;
}

/* Sleep the seconds text says, parameter name's (0 to 3600), until done
 * or the process is asked to stop. */
static int sleep_param(const mpb_solve_limits *lim, mpb_plan_result_t *res,
                       const char *name, const char *text)
{
    char *end;
    double s = strtod(text, &end);
    if (end == text || *end != '\0' || !(s >= 0 && s <= 3600)) {
        mpb_result_set_message(res, "%s must be seconds in [0, 3600], "
                                    "not '%.40s'", name, text);
        return MPB_EINVAL;
    }
    struct timespec ts = {(time_t)s, (long)((s - (double)(time_t)s) * 1e9)};
    while (nanosleep(&ts, &ts) != 0 && errno == EINTR &&
           !(lim->stop != NULL && *lim->stop))
        ;
    return MPB_OK;
}

static int solve_straight_line(void *user, const mpb_plan_request_t *req,
                               const mpb_solve_limits *lim,
                               mpb_plan_result_t *res)
{
    double t0 = mpb_monotonic_s();
    const char *delay = mpb_request_param(req, "delay");
    int status = asked_status(req);
    (void)user;
    if (status < 0) {
        mpb_result_set_message(res, "status must be solved, failed, timeout "
                                    "or approximate, not '%.40s'",
                               mpb_request_param(req, "status"));
        return MPB_EINVAL;
    }
    const char *setup = mpb_request_param(req, "setup");
    if (setup != NULL) {
        /* As a planner that builds its model first: said, left out of
         * the run's time, reported as the world's. */
        mpb_solve_setting_up(lim);
        int rc = sleep_param(lim, res, "setup", setup);
        if (rc != MPB_OK)
            return rc;
        mpb_solve_planning(lim);
        double built = mpb_monotonic_s() - t0;
        t0 += built;
        if ((rc = mpb_result_add_value(res, MPB_WORLD_SETUP_TIME, built)) !=
            MPB_OK)
            return rc;
    }
    if (delay != NULL) {
        int rc = sleep_param(lim, res, "delay", delay);
        if (rc != MPB_OK)
            return rc;
    }
    const char *allocate = mpb_request_param(req, "allocate");
    if (allocate != NULL) {
        int rc = allocate_mb(req, res, allocate);
        res->time_total = mpb_monotonic_s() - t0;
        if (rc != MPB_OK)
            return rc;
    }
    if (req->goal.kind != MPB_GOAL_T_JOINTS) {
        mpb_result_set_message(res, "straight_line needs a joint-space goal");
        return MPB_EUNSUPPORTED;
    }
    long m = 2;
    const char *count = mpb_request_param(req, "waypoints");
    if (count != NULL) {
        char *end;
        errno = 0;
        m = strtol(count, &end, 10);
        if (end == count || *end != '\0' || errno != 0 || m < 2 ||
            m > 10000000) {
            mpb_result_set_message(res, "waypoints must be a whole number "
                                        "from 2 to 10000000, not '%.40s'",
                                   count);
            return MPB_EINVAL;
        }
    }
    int n = req->num_joints;
    double *wp = malloc((size_t)m * (size_t)n * sizeof *wp);
    if (wp == NULL)
        return MPB_ENOMEM;
    /* The ends exactly the start and the goal, as with two waypoints. */
    for (long i = 0; i < m - 1; i++) {
        double t = (double)i / (double)(m - 1);
        for (int j = 0; j < n; j++)
            wp[i * n + j] = req->start[j] +
                            t * (req->goal.joints[j] - req->start[j]);
    }
    memcpy(wp + (m - 1) * n, req->goal.joints, (size_t)n * sizeof *wp);
    int rc = mpb_result_add_stage(res, "raw", 0.0, wp, (int)m, n);
    free(wp);
    const char *duration = mpb_request_param(req, "duration");
    if (rc == MPB_OK && duration != NULL) {
        char *end;
        double d = strtod(duration, &end);
        if (end == duration || *end != '\0' || !(d >= -3600 && d <= 3600)) {
            mpb_result_set_message(res, "duration must be seconds in "
                                        "[-3600, 3600], not '%.40s'", duration);
            return MPB_EINVAL;
        }
        double *times = malloc((size_t)m * sizeof *times);
        if (times == NULL)
            return MPB_ENOMEM;
        for (long i = 0; i < m; i++)
            times[i] = i == 0 ? 0.0 : d * (double)i / (double)(m - 1);
        rc = mpb_result_set_times(res, 0, times, (int)m);
        free(times);
    }
    if (rc != MPB_OK) {
        res->status = MPB_PLAN_RESULT_T_FAILED;
        mpb_result_set_message(res, "%s", mpb_strerror(rc));
        return MPB_OK;
    }
    res->status = (int8_t)status;
    if (status != MPB_PLAN_RESULT_T_SOLVED)
        mpb_result_set_message(res, "answered %s as asked (parameter status)",
                               mpb_status_name(status));
    res->time_total = mpb_monotonic_s() - t0;
    res->stages[0].time = res->time_total;
    return MPB_OK;
}

int main(int argc, char **argv)
{
    mpb_planner_options opt = {.name = "null"};
    char err[256];

    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int took = mpb_planner_option(argc, argv, &i, &opt, err, sizeof err);
        if (took < 0) {
            fprintf(stderr, "mpb-planner-null: %s (see --help)\n", err);
            return 2;
        }
        if (took)
            continue;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            return 0;
        }
        fprintf(stderr, "mpb-planner-null: unknown argument '%s' (see --help)\n",
                a);
        return 2;
    }

    static const char *const algorithms[] = { "straight_line" };
    mpb_planner_def def = {
        .language = "c",
        .version = MPB_VERSION_STRING,
        .algorithms = algorithms,
        .num_algorithms = 1,
        .solve = solve_straight_line,
        .user = NULL,
        .heartbeat_ms = 0,
    };
    return mpb_planner_main(&def, &opt, "mpb-planner-null");
}
