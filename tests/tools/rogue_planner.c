/*
 * rogue_planner.c - test tool: a planner that breaks the protocol the way a
 * planner's first version does, for the daemon to cope with.
 *
 *   mpb-test-rogue-planner MODE PLANNER_ID NAME ALGORITHM SECONDS
 *
 * Announces PLANNER_ID (taken as given, valid or not) with family NAME,
 * one ALGORITHM and capacity 1, every 0.5 s, for SECONDS; then prints how
 * many requests for it it saw ("N requests") and exits 0. MODE:
 *   deaf     never subscribes to its request channel, so never answers
 *   decline  answers every request with REQUEST_DECLINED
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/select.h>
#include <unistd.h>

#include "mpbench/mpbench.h"
#include "mpb_plan_request_t.h"
#include "mpb_planner_announce_t.h"
#include "mpb_run_ack_t.h"

static const char *planner_id;
static long requests;

static void on_request(const lcm_recv_buf_t *rbuf, const char *channel,
                       const mpb_plan_request_t *m, void *user)
{
    lcm_t *lcm = user;
    (void)rbuf;
    (void)channel;
    requests++;
    mpb_run_ack_t ack = {.utime = mpb_utime_now(), .attempt_id = m->attempt_id,
                         .sender_id = (char *)planner_id,
                         .kind = MPB_RUN_ACK_T_REQUEST_DECLINED};
    mpb_run_ack_t_publish(lcm, MPB_CHANNEL_ACK, &ack);
}

int main(int argc, char **argv)
{
    if (argc != 6 || (strcmp(argv[1], "deaf") != 0 &&
                      strcmp(argv[1], "decline") != 0)) {
        fprintf(stderr, "usage: %s deaf|decline PLANNER_ID NAME ALGORITHM "
                "SECONDS\n", argv[0]);
        return 2;
    }
    int decline = strcmp(argv[1], "decline") == 0;
    planner_id = argv[2];
    char *algorithms[1] = {argv[4]};
    double seconds = atof(argv[5]);
    lcm_t *lcm = lcm_create(MPB_DEFAULT_LCM_URL);
    if (lcm == NULL)
        return 1;
    mpb_plan_request_t_subscription_t *sub = NULL;
    if (decline) {
        char channel[512];
        snprintf(channel, sizeof channel, "%s%s", MPB_CHANNEL_REQUEST_PREFIX,
                 planner_id);
        sub = mpb_plan_request_t_subscribe(lcm, channel, on_request, lcm);
    }
    mpb_planner_announce_t a = {
        .planner_id = (char *)planner_id, .name = argv[3], .host = "rogue",
        .pid = (int32_t)getpid(), .language = "c", .version = "0",
        .heartbeat_ms = 500, .num_algorithms = 1, .algorithms = algorithms,
        .capacity = 1, .num_active = 0, .active_attempts = NULL,
    };
    double end = mpb_monotonic_s() + seconds, next_announce = 0;
    int fd = lcm_get_fileno(lcm);
    while (mpb_monotonic_s() < end) {
        if (mpb_monotonic_s() >= next_announce) {
            a.utime = mpb_utime_now();
            mpb_planner_announce_t_publish(lcm, MPB_CHANNEL_ANNOUNCE, &a);
            next_announce = mpb_monotonic_s() + 0.5;
        }
        fd_set fds;
        struct timeval tv = {0, 50000};
        FD_ZERO(&fds);
        FD_SET(fd, &fds);
        if (select(fd + 1, &fds, NULL, NULL, &tv) > 0)
            lcm_handle(lcm);
    }
    printf("%ld requests\n", requests);
    if (sub != NULL)
        mpb_plan_request_t_unsubscribe(lcm, sub);
    lcm_destroy(lcm);
    return 0;
}
