/*
 * forge_result.c - test tool: publish one plan_result_t as an attacker or a
 * confused planner would, and report the daemon's acknowledgement.
 *
 *   mpb-test-forge-result [OPTIONS] RUN_ID PLANNER_ID [LCM_URL]
 *   mpb-test-forge-result [OPTIONS] --serve PLANNER_ID [LCM_URL]
 *
 * With --serve it is a planner for one run: it announces PLANNER_ID (the
 * family before '@', algorithm "forged", a 30 s heartbeat), acknowledges
 * the first request sent to it and answers that run, its stage the
 * straight line from the request's start to its joint goal. The options
 * shape the result:
 *
 *   --status N         plan_result_t.status (default SOLVED)
 *   --message TEXT     (default "forged")
 *   --time-total S     --time-other S     --stage-time S   (s; "nan" too)
 *   --stages A,B,...   stage names (default one, "forged"); "" for none
 *   --values A=1,B=2   the planner's own numbers
 *   --wrong-size       the first stage has one joint too many
 *   --delay S          wait this long before answering
 *
 * Prints "acked stored", "acked rejected" or "no ack" and exits 0.
 */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/select.h>
#include <unistd.h>

#include "mpbench/mpbench.h"
#include "mpb_plan_request_t.h"
#include "mpb_plan_result_t.h"
#include "mpb_planner_announce_t.h"
#include "mpb_run_ack_t.h"

#define MAX_NAMED 16

static char run_id[256];
static int ack_kind = -1;
/* --serve: what the forger keeps of the run to answer. Not a copy of the
 * request: LCM's generated copy hands memcpy a NULL for an empty array
 * (no held joints), which UBSan stops. */
static struct {
    int    received, num_joints;
    double start[3], goal[3];
} request;

static void on_ack(const lcm_recv_buf_t *rbuf, const char *channel,
                   const mpb_run_ack_t *m, void *user)
{
    (void)rbuf;
    (void)channel;
    (void)user;
    if (strcmp(m->attempt_id, run_id) == 0 &&
        m->kind != MPB_RUN_ACK_T_REQUEST_RECEIVED)
        ack_kind = m->kind;
}

static void on_request(const lcm_recv_buf_t *rbuf, const char *channel,
                       const mpb_plan_request_t *m, void *user)
{
    (void)rbuf;
    (void)channel;
    (void)user;
    /* A stored result of ours riding on the request is an ack too. */
    for (int i = 0; i < m->num_stored; i++)
        if (strcmp(m->stored[i], run_id) == 0)
            ack_kind = MPB_RUN_ACK_T_RESULT_STORED;
    if (!request.received) {
        request.received = 1;
        request.num_joints = m->num_joints;
        for (int j = 0; j < m->num_joints && j < 3; j++) {
            request.start[j] = m->start[j];
            request.goal[j] = m->goal.num_joints > j ? m->goal.joints[j] : 0;
        }
        snprintf(run_id, sizeof run_id, "%s", m->attempt_id);
    }
}

/* Handle LCM messages for up to seconds, or until an acknowledgement
 * came if until_ack. */
static void handle_for(lcm_t *lcm, double seconds, int until_ack)
{
    double until = mpb_monotonic_s() + seconds;
    int fd = lcm_get_fileno(lcm);
    while (!(until_ack && ack_kind >= 0) && mpb_monotonic_s() < until) {
        fd_set fds;
        struct timeval tv = {0, 50000};
        FD_ZERO(&fds);
        FD_SET(fd, &fds);
        if (select(fd + 1, &fds, NULL, NULL, &tv) > 0)
            lcm_handle(lcm);
    }
}

/* Split a comma-separated list in place into at most MAX_NAMED parts. */
static int split(char *list, char **parts)
{
    int n = 0;
    if (list == NULL || list[0] == '\0')
        return 0;
    for (char *p = strtok(list, ","); p && n < MAX_NAMED; p = strtok(NULL, ","))
        parts[n++] = p;
    return n;
}

static void announce(lcm_t *lcm, const char *id)
{
    char name[MPB_PLANNER_ID_MAX + 1], *algorithms[] = {"forged"};
    snprintf(name, sizeof name, "%s", id);
    name[strcspn(name, "@")] = '\0';
    mpb_planner_announce_t a = {
        .utime = mpb_utime_now(), .planner_id = (char *)id, .name = name,
        .host = "forged", .pid = (int32_t)getpid(), .language = "c",
        .version = "0", .heartbeat_ms = 30000, .num_algorithms = 1,
        .algorithms = algorithms, .capacity = 1,
    };
    mpb_planner_announce_t_publish(lcm, MPB_CHANNEL_ANNOUNCE, &a);
}

int main(int argc, char **argv)
{
    static const struct option longs[] = {
        {"status", required_argument, NULL, 's'},
        {"message", required_argument, NULL, 'm'},
        {"time-total", required_argument, NULL, 'T'},
        {"time-other", required_argument, NULL, 'O'},
        {"stage-time", required_argument, NULL, 'S'},
        {"stages", required_argument, NULL, 'n'},
        {"values", required_argument, NULL, 'v'},
        {"wrong-size", no_argument, NULL, 'w'},
        {"delay", required_argument, NULL, 'd'},
        {"serve", no_argument, NULL, 'r'},
        {NULL, 0, NULL, 0},
    };
    int status = MPB_PLAN_RESULT_T_SOLVED, serve = 0, wrong_size = 0, c;
    double time_total = 0.001, time_other = 0.0, stage_time = 0.001, delay = 0;
    char *message = "forged", stage_list[1024] = "forged", value_list[1024] = "";
    while ((c = getopt_long(argc, argv, "", longs, NULL)) != -1) {
        switch (c) {
        case 's': status = atoi(optarg); break;
        case 'm': message = optarg; break;
        case 'T': time_total = strtod(optarg, NULL); break;
        case 'O': time_other = strtod(optarg, NULL); break;
        case 'S': stage_time = strtod(optarg, NULL); break;
        case 'n': snprintf(stage_list, sizeof stage_list, "%s", optarg); break;
        case 'v': snprintf(value_list, sizeof value_list, "%s", optarg); break;
        case 'w': wrong_size = 1; break;
        case 'd': delay = strtod(optarg, NULL); break;
        case 'r': serve = 1; break;
        default: return 2;
        }
    }
    argc -= optind;
    argv += optind;
    if (argc < 2 - serve) {
        fprintf(stderr, "usage: mpb-test-forge-result [OPTIONS] RUN_ID "
                "PLANNER_ID [LCM_URL]\n       mpb-test-forge-result "
                "[OPTIONS] --serve PLANNER_ID [LCM_URL]\n");
        return 2;
    }
    const char *planner_id = argv[1 - serve];
    const char *url = argc > 2 - serve ? argv[2 - serve] : MPB_DEFAULT_LCM_URL;
    if (!serve)
        snprintf(run_id, sizeof run_id, "%s", argv[0]);
    lcm_t *lcm = lcm_create(url);
    if (lcm == NULL)
        return 1;
    /* The daemon answers the planner the result names, on its channel. */
    mpb_run_ack_t_subscription_t *sub =
        mpb_run_ack_t_subscribe(lcm, MPB_CHANNEL_ACK_PREFIX ".*", on_ack, NULL);

    /* A plausible answer, marked so that the test can look for it. */
    double wp[8] = {0, 0, 0, 0.3, -0.2, 0.1, 0, 0};
    int nj = 3;
    if (serve) {
        char channel[sizeof MPB_CHANNEL_REQUEST_PREFIX + MPB_PLANNER_ID_MAX];
        if (mpb_request_channel(planner_id, channel, sizeof channel) != MPB_OK)
            return 2;
        mpb_plan_request_t_subscribe(lcm, channel, on_request, NULL);
        for (int i = 0; i < 100 && !request.received; i++) {
            announce(lcm, planner_id);
            handle_for(lcm, 0.2, 0);
        }
        if (!request.received || request.num_joints > 3) {
            puts("no request");
            return 1;
        }
        mpb_run_ack_t received = {
            .utime = mpb_utime_now(), .attempt_id = run_id,
            .sender_id = (char *)planner_id,
            .kind = MPB_RUN_ACK_T_REQUEST_RECEIVED,
        };
        mpb_run_ack_t_publish(lcm, MPB_CHANNEL_ACK, &received);
        nj = request.num_joints;
        for (int j = 0; j < nj; j++) {
            wp[j] = request.start[j];
            wp[nj + j] = request.goal[j];
        }
        handle_for(lcm, delay, 0);
    }

    char *stage_names[MAX_NAMED], *value_specs[MAX_NAMED];
    mpb_stage_t stages[MAX_NAMED];
    mpb_named_value_t values[MAX_NAMED];
    int num_stages = split(stage_list, stage_names);
    int num_values = split(value_list, value_specs);
    for (int i = 0; i < num_stages; i++)
        stages[i] = (mpb_stage_t){.name = stage_names[i], .time = stage_time,
                                  .num_waypoints = 2, .num_joints = (int16_t)nj,
                                  .num_values = 2 * nj, .waypoints = wp};
    if (wrong_size && num_stages > 0) {
        stages[0].num_joints = (int16_t)(nj + 1);
        stages[0].num_values = 2 * (nj + 1);
    }
    for (int i = 0; i < num_values; i++) {
        char *eq = strchr(value_specs[i], '=');
        if (eq != NULL)
            *eq++ = '\0';
        values[i] = (mpb_named_value_t){.name = value_specs[i],
                                        .value = eq ? strtod(eq, NULL) : 0};
    }
    mpb_plan_result_t res = {
        .utime = mpb_utime_now(), .attempt_id = run_id,
        .planner_id = (char *)planner_id, .status = (int8_t)status,
        .message = message, .time_total = time_total, .time_other = time_other,
        .num_stages = (int16_t)num_stages, .stages = stages,
        .num_values = (int16_t)num_values, .values = values,
    };
    mpb_plan_result_t_publish(lcm, MPB_CHANNEL_RESULT, &res);

    /* Wait up to a second for the daemon's answer (with --serve, it may
     * ride on the next request instead: still subscribed). */
    handle_for(lcm, 1.0, 1);
    puts(ack_kind == MPB_RUN_ACK_T_RESULT_STORED     ? "acked stored"
         : ack_kind == MPB_RUN_ACK_T_RESULT_REJECTED ? "acked rejected"
                                                      : "no ack");
    mpb_run_ack_t_unsubscribe(lcm, sub);
    lcm_destroy(lcm);
    return 0;
}
