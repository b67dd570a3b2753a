/*
 * floor.c - mpb-bench-floor: the LCM round trip no design of mpbench can
 * beat. Two processes (this one and a forked echo) over the same LCM URL as
 * the daemon and its planners; a real plan request of the planar demo scene
 * goes out, a small result like the null planner's comes back, each checked
 * (wire.h) and decoded as the daemon and the planner kit do. Each side's
 * LCM drops in the kernel what it does not subscribe to, its own messages
 * included, as mpbenchd's and the kit's do (lcm_filter.h). Prints the
 * round-trip median and p99 over --count exchanges.
 *
 * Run it only inside a private network namespace (bench/run.sh does).
 */
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <lcm/lcm.h>

#include "mpbench/mpbench.h"
#include "mpb_plan_request_t.h"
#include "mpb_plan_result_t.h"

#include "bench_util.h"

#define REQ_CHANNEL "MPBB_FLOOR_REQUEST"
#define RES_CHANNEL "MPBB_FLOOR_RESULT"

typedef struct options {
    const char *url, *robot, *scene, *samples;
    long count, warmup;
    double timeout;
} options;

static void usage(FILE *out)
{
    fprintf(out,
"usage: mpb-bench-floor --robot FILE --scene FILE [options]\n"
"\n"
"LCM ping-pong between this process and a forked echo process: a plan\n"
"request of the planar robot and scene (as mpbenchd sends it) out, a small\n"
"result of two waypoints (as the null planner answers) back. Prints the\n"
"round-trip time's median and p99. Run it inside a private network\n"
"namespace (bench/run.sh does).\n"
"\n"
"options:\n"
"  --count N      timed round trips (default 20000)\n"
"  --warmup N     untimed round trips first (default 1000)\n"
"  --timeout S    give up after S seconds in all (default 120)\n"
"  --url URL      LCM URL (default " MPB_DEFAULT_LCM_URL ")\n"
"  --samples FILE write every round trip (us), one a line\n");
}

static int parse(int argc, char **argv, options *o)
{
    *o = (options){.url = MPB_DEFAULT_LCM_URL, .count = 20000, .warmup = 1000,
                   .timeout = 120};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--help") == 0) {
            usage(stdout);
            exit(0);
        }
        if (v == NULL)
            goto bad;
        i++;
        if (strcmp(a, "--robot") == 0) o->robot = v;
        else if (strcmp(a, "--scene") == 0) o->scene = v;
        else if (strcmp(a, "--url") == 0) o->url = v;
        else if (strcmp(a, "--samples") == 0) o->samples = v;
        else if (strcmp(a, "--count") == 0) o->count = atol(v);
        else if (strcmp(a, "--warmup") == 0) o->warmup = atol(v);
        else if (strcmp(a, "--timeout") == 0) o->timeout = atof(v);
        else goto bad;
    }
    if (o->robot && o->scene && o->count > 0 && o->warmup >= 0 &&
        o->timeout > 0)
        return 0;
bad:
    usage(stderr);
    return -1;
}

/* ---- the echo: answers each request as the null planner would ---------- */

typedef struct echo {
    lcm_t *lcm;
    int stop;
} echo;

static void on_request(const lcm_recv_buf_t *rbuf, const char *channel,
                       void *user)
{
    echo *e = user;
    mpb_plan_request_t rq;
    (void)channel;
    if (!mpb_wire_check(MPB_WIRE_PLAN_REQUEST, rbuf->data, rbuf->data_size,
                        NULL, 0) ||
        mpb_plan_request_t_decode(rbuf->data, 0, (int)rbuf->data_size, &rq) < 0)
        return;
    if (rq.seed < 0) {
        e->stop = 1;
    } else {
        int n = rq.num_joints;
        double wp[2 * 16];
        if (n > 16)
            n = 16;
        memcpy(wp, rq.start, (size_t)n * sizeof *wp);
        memcpy(wp + n, rq.goal.joints, (size_t)n * sizeof *wp);
        mpb_stage_t stage = {.name = "raw", .num_waypoints = 2,
                             .num_joints = (int16_t)n, .num_values = 2 * n,
                             .waypoints = wp};
        mpb_plan_result_t res = {
            .utime = mpb_utime_now(), .attempt_id = rq.attempt_id,
            .planner_id = rq.planner_id, .status = MPB_PLAN_RESULT_T_SOLVED,
            .message = "", .num_stages = 1, .stages = &stage,
        };
        mpb_plan_result_t_publish(e->lcm, RES_CHANNEL, &res);
    }
    mpb_plan_request_t_decode_cleanup(&rq);
}

static int run_echo(const options *o, pid_t parent)
{
    echo e = {0};
    double deadline = mpbb_now() + o->timeout + 10;
    static const char *const mine[] = {REQ_CHANNEL};
    if ((e.lcm = mpb_lcm_create(o->url, mine, 1, NULL)) == NULL) {
        fprintf(stderr, "mpb-bench-floor: echo: cannot start LCM on %s\n",
                o->url);
        return 1;
    }
    lcm_subscription_t *sub = lcm_subscribe(e.lcm, REQ_CHANNEL, on_request, &e);
    while (!e.stop && getppid() == parent && mpbb_now() < deadline)
        lcm_handle_timeout(e.lcm, 100);
    lcm_unsubscribe(e.lcm, sub);
    lcm_destroy(e.lcm);
    return 0;
}

/* ---- the pinger ---------------------------------------------------------- */

typedef struct pinger {
    int64_t got;        /* seed of the last result received */
    int     res_bytes;  /* its encoded size */
} pinger;

static void on_result(const lcm_recv_buf_t *rbuf, const char *channel,
                      void *user)
{
    pinger *p = user;
    mpb_plan_result_t res;
    (void)channel;
    if (!mpb_wire_check(MPB_WIRE_PLAN_RESULT, rbuf->data, rbuf->data_size,
                        NULL, 0) ||
        mpb_plan_result_t_decode(rbuf->data, 0, (int)rbuf->data_size, &res) < 0)
        return;
    /* The run id carries the sequence number, as hex. */
    p->got = (int64_t)strtoll(res.attempt_id, NULL, 16);
    p->res_bytes = (int)rbuf->data_size;
    mpb_plan_result_t_decode_cleanup(&res);
}

/* The joint names of the robot, from the world itself. */
static char **joint_names(mpb_world *w)
{
    int n = mpb_world_num_joints(w);
    char **names = calloc((size_t)n, sizeof *names);
    for (int j = 0; names && j < n; j++)
        names[j] = (char *)mpb_world_joint_name(w, j);
    return names;
}

int main(int argc, char **argv)
{
    options o;
    char err[256], run_id[MPB_ATTEMPT_ID_SIZE], robot_hash[MPB_HASH_SIZE],
         scene_hash[MPB_HASH_SIZE];
    mpb_world *world = NULL;

    if (parse(argc, argv, &o) != 0)
        return 2;
    char *robot = mpb_read_file(o.robot, 0, NULL);
    char *scene = mpb_read_file(o.scene, 0, NULL);
    if (robot == NULL || scene == NULL) {
        fprintf(stderr, "mpb-bench-floor: cannot read %s or %s\n", o.robot,
                o.scene);
        return 1;
    }
    if (mpb_world_open("planar", robot, "planar", scene, &world, err,
                       sizeof err) != MPB_OK) {
        fprintf(stderr, "mpb-bench-floor: %s\n", err);
        return 1;
    }
    mpb_hash_hex(robot, strlen(robot), robot_hash);
    mpb_hash_hex(scene, strlen(scene), scene_hash);

    pid_t parent = getpid();
    fflush(stdout);
    pid_t child = fork();
    if (child < 0) {
        perror("mpb-bench-floor: fork");
        return 1;
    }
    if (child == 0)
        _exit(run_echo(&o, parent));

    /* The query "small_move" of the demo scene; a planner id like a real
     * one, so the request has its real size. */
    int nj = mpb_world_num_joints(world);
    double start[16] = {0}, goal[16] = {0.3, -0.2, 0.1};
    mpb_param_t param = {.key = "delay", .value = "0"};
    mpb_plan_request_t rq = {
        .attempt_id = run_id,
        .planner_id = "null@mpbench-bench-host:123456",
        .algorithm = "straight_line",
        .num_params = 0, .params = &param,
        .time_limit = 1.0,
        .robot_format = "planar", .robot_hash = robot_hash, .robot = robot,
        .scene_format = "planar", .scene_hash = scene_hash, .scene = scene,
        .num_joints = (int16_t)nj,
        .joint_names = joint_names(world),
        .start = start,
        .goal = {.kind = MPB_GOAL_T_JOINTS, .num_joints = (int16_t)nj,
                 .joints = goal, .joint_tolerance = 0.01, .link = ""},
    };

    static const char *const mine[] = {RES_CHANNEL};
    lcm_t *lcm = mpb_lcm_create(o.url, mine, 1, NULL);
    if (lcm == NULL) {
        fprintf(stderr, "mpb-bench-floor: cannot start LCM on %s (no multicast"
                        " route?)\n", o.url);
        kill(child, SIGTERM);
        return 1;
    }
    pinger p = {.got = -1};
    lcm_subscription_t *sub = lcm_subscribe(lcm, RES_CHANNEL, on_result, &p);

    long total = o.warmup + o.count, lost = 0, done = 0;
    double *rtt = calloc((size_t)o.count, sizeof *rtt);
    double deadline = mpbb_now() + o.timeout;
    int rc = 0;
    for (long i = 0; i < total && mpbb_now() < deadline; i++) {
        /* The first exchange waits for the echo to subscribe. */
        double patience = i == 0 ? 5.0 : 0.5, t0 = 0, t1 = 0;
        snprintf(run_id, sizeof run_id, "%032lx", (unsigned long)i);
        rq.seed = i;
        for (int tries = 0; p.got != i && tries < (i == 0 ? 50 : 1); tries++) {
            rq.utime = mpb_utime_now();
            t0 = mpbb_now();
            mpb_plan_request_t_publish(lcm, REQ_CHANNEL, &rq);
            double until = t0 + (i == 0 ? 0.1 : patience);
            while (p.got != i) {
                int ms = (int)((until - mpbb_now()) * 1000) + 1;
                if (ms <= 0 || lcm_handle_timeout(lcm, ms) <= 0)
                    break;
            }
            t1 = mpbb_now();
        }
        if (p.got != i) {
            if (i == 0) {
                fprintf(stderr, "mpb-bench-floor: the echo never answered\n");
                rc = 1;
                break;
            }
            lost++;
            continue;
        }
        if (i >= o.warmup)
            rtt[done++] = (t1 - t0) * 1e6;
    }
    /* Stop the echo. */
    rq.seed = -1;
    snprintf(run_id, sizeof run_id, "%032x", 0);
    for (int k = 0; k < 3; k++)
        mpb_plan_request_t_publish(lcm, REQ_CHANNEL, &rq);
    int status;
    double wait_until = mpbb_now() + 2;
    while (waitpid(child, &status, WNOHANG) == 0) {
        if (mpbb_now() > wait_until) {
            kill(child, SIGKILL);
            waitpid(child, &status, 0);
            break;
        }
        usleep(10000);
    }

    if (rc == 0 && o.samples) {
        FILE *f = fopen(o.samples, "w");
        for (long i = 0; f && i < done; i++)
            fprintf(f, "%.3f\n", rtt[i]);
        if (f)
            fclose(f);
    }
    if (rc == 0 && done > 0) {
        mpbb_sort(rtt, (size_t)done);
        printf("LCM round trip, %ld exchanges (after %ld warm-up), request %d "
               "bytes, result %d bytes:\n", done, o.warmup,
               mpb_plan_request_t_encoded_size(&rq), p.res_bytes);
        printf("  median %.1f us, p90 %.1f us, p99 %.1f us, max %.1f us, "
               "mean %.1f us, lost %ld\n",
               mpbb_quantile(rtt, done, 0.5), mpbb_quantile(rtt, done, 0.9),
               mpbb_quantile(rtt, done, 0.99), rtt[done - 1],
               mpbb_mean(rtt, done), lost);
        mpbb_result("floor n=%ld median_us=%.2f p90_us=%.2f p99_us=%.2f "
                    "max_us=%.2f mean_us=%.2f lost=%ld request_bytes=%d result_bytes=%d",
                    done, mpbb_quantile(rtt, done, 0.5),
                    mpbb_quantile(rtt, done, 0.9),
                    mpbb_quantile(rtt, done, 0.99), rtt[done - 1],
                    mpbb_mean(rtt, done), lost,
                    mpb_plan_request_t_encoded_size(&rq), p.res_bytes);
    } else if (rc == 0) {
        fprintf(stderr, "mpb-bench-floor: no exchange completed\n");
        rc = 1;
    }
    lcm_unsubscribe(lcm, sub);
    lcm_destroy(lcm);
    free(rtt);
    free(rq.joint_names);
    mpb_world_close(world);
    free(robot);
    free(scene);
    return rc;
}
