/*
 * forge_result.c - test tool: publish one plan_result_t as an attacker or a
 * confused planner would, and report the daemon's acknowledgement.
 *
 *   mpb-test-forge-result RUN_ID PLANNER_ID [LCM_URL]
 *
 * Prints "acked stored", "acked rejected" or "no ack" and exits 0.
 */
#include <stdio.h>
#include <string.h>
#include <sys/select.h>

#include "mpbench/mpbench.h"
#include "mpb_plan_result_t.h"
#include "mpb_run_ack_t.h"

static const char *run_id;
static int ack_kind = -1;

static void on_ack(const lcm_recv_buf_t *rbuf, const char *channel,
                   const mpb_run_ack_t *m, void *user)
{
    (void)rbuf;
    (void)channel;
    (void)user;
    if (strcmp(m->run_id, run_id) == 0 &&
        m->kind != MPB_RUN_ACK_T_REQUEST_RECEIVED)
        ack_kind = m->kind;
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: %s RUN_ID PLANNER_ID [LCM_URL]\n", argv[0]);
        return 2;
    }
    run_id = argv[1];
    lcm_t *lcm = lcm_create(argc > 3 ? argv[3] : MPB_DEFAULT_LCM_URL);
    if (lcm == NULL)
        return 1;
    /* The daemon answers the planner the result names, on its channel. */
    mpb_run_ack_t_subscription_t *sub =
        mpb_run_ack_t_subscribe(lcm, MPB_CHANNEL_ACK_PREFIX ".*", on_ack, NULL);

    /* A plausible answer, marked so that the test can look for it. */
    double wp[6] = {0, 0, 0, 0.3, -0.2, 0.1};
    mpb_stage_t stage = {.name = "forged", .time = 0.001, .num_waypoints = 2,
                         .num_joints = 3, .num_values = 6, .waypoints = wp};
    mpb_plan_result_t res = {
        .utime = mpb_utime_now(), .run_id = (char *)run_id,
        .planner_id = argv[2], .status = MPB_PLAN_RESULT_T_SOLVED,
        .message = "forged", .time_total = 0.001, .num_stages = 1,
        .stages = &stage,
    };
    mpb_plan_result_t_publish(lcm, MPB_CHANNEL_RESULT, &res);

    /* Wait up to a second for the daemon's answer. */
    double until = mpb_monotonic_s() + 1.0;
    int fd = lcm_get_fileno(lcm);
    while (ack_kind < 0 && mpb_monotonic_s() < until) {
        fd_set fds;
        struct timeval tv = {0, 50000};
        FD_ZERO(&fds);
        FD_SET(fd, &fds);
        if (select(fd + 1, &fds, NULL, NULL, &tv) > 0)
            lcm_handle(lcm);
    }
    puts(ack_kind == MPB_RUN_ACK_T_RESULT_STORED     ? "acked stored"
         : ack_kind == MPB_RUN_ACK_T_RESULT_REJECTED ? "acked rejected"
                                                      : "no ack");
    mpb_run_ack_t_unsubscribe(lcm, sub);
    lcm_destroy(lcm);
    return 0;
}
