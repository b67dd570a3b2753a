/*
 * make_seeds.c - writes the encoded-message seeds of the committed fuzz
 * corpus (tests/fuzz/corpus/messages/), so that they can be made again:
 *   make_seeds DIR
 */
#include <stdio.h>
#include <stdlib.h>

#include "mpbench/mpbench.h"
#include "mpb_plan_request_t.h"
#include "mpb_plan_result_t.h"
#include "mpb_plan_request_v1_t.h"
#include "mpb_plan_result_v1_t.h"
#include "mpb_plan_result_v2_t.h"
#include "mpb_planner_announce_t.h"
#include "mpb_planner_announce_v1_t.h"
#include "mpb_planner_announce_v2_t.h"
#include "mpb_run_ack_t.h"
#include "mpb_run_ack_v1_t.h"

static void put(const char *dir, const char *name, unsigned char kind,
                const unsigned char *buf, int len)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (f == NULL || fputc(kind, f) == EOF ||
        fwrite(buf, 1, (size_t)len, f) != (size_t)len) {
        perror(path);
        exit(1);
    }
    fclose(f);
}

#define ENCODE(type, msg, dir, name, kind)                                   \
    do {                                                                     \
        int n_ = type##_encoded_size(&(msg));                                \
        unsigned char *b_ = malloc((size_t)n_);                              \
        type##_encode(b_, 0, n_, &(msg));                                    \
        put(dir, name, kind, b_, n_);                                        \
        free(b_);                                                            \
    } while (0)

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: make_seeds DIR\n");
        return 2;
    }
    const char *dir = argv[1];
    char *names[] = {"a", "b", "c"};
    double start[] = {0, 0, 0}, goal[] = {0.3, -0.2, 0.1};
    double wp[] = {0, 0, 0, 0.1, 0.0, 0.05, 0.3, -0.2, 0.1};
    double bad[] = {0, 0, 0, 0.0 / 0.0, 1, 2};
    mpb_named_value_t val = {"graph states", 12};
    mpb_named_value_t pv = {"best cost", 1.5};
    mpb_progress_t prog = {0.01, 1, &pv};
    double times[] = {0, 0.25, 1.0}, bad_times[] = {0.5, 0.25};
    mpb_stage_t stages[] = {
        {"raw", 0.001, 3, 3, 9, wp, 3, times},
        {"shortcut", 0.0005, 2, 3, 6, bad, 2, bad_times},
    };
    mpb_plan_result_t res = {1, "0123456789abcdef0123456789abcdef", "null@h:1",
                             0, "", 0.002, 0.0001, 3.5, 2, stages, 1, &val, 1,
                             &prog};
    ENCODE(mpb_plan_result_t, res, dir, "result", 0);
    /* As a planner built before waypoint times sends it. */
    mpb_stage_v1_t stages_v1[] = {
        {"raw", 0.001, 3, 3, 9, wp},
        {"shortcut", 0.0005, 2, 3, 6, bad},
    };
    mpb_plan_result_v1_t res_v1 = {1, "0123456789abcdef0123456789abcdef",
                                   "null@h:1", 0, "", 0.002, 0.0001, 3.5, 2,
                                   stages_v1, 1, &val, 1, &prog};
    ENCODE(mpb_plan_result_v1_t, res_v1, dir, "result-v1", 0);
    /* As a planner built before attempt ids sends it (run_id). */
    mpb_plan_result_v2_t res_v2 = {1, "0123456789abcdef0123456789abcdef",
                                   "null@h:1", 0, "", 0.002, 0.0001, 3.5, 2,
                                   stages, 1, &val, 1, &prog};
    ENCODE(mpb_plan_result_v2_t, res_v2, dir, "result-v2", 0);

    char *algos[] = {"RRTConnect", "RRT"};
    char *active[] = {"0123456789abcdef0123456789abcdef"};
    char *approaches[] = {"sampling", "sampling"};
    mpb_planner_announce_t ann = {1, "ompl@h:2", "ompl", "h", 2, "c++", "1",
                                  500, 2, algos, 1, 1, active, 2, approaches};
    ENCODE(mpb_planner_announce_t, ann, dir, "announce", 1);
    /* Before approaches, and before attempt ids (active_runs). */
    mpb_planner_announce_v1_t ann_v1 = {1, "ompl@h:2", "ompl", "h", 2, "c++",
                                        "1", 500, 2, algos, 1, 1, active};
    ENCODE(mpb_planner_announce_v1_t, ann_v1, dir, "announce-v1", 1);
    mpb_planner_announce_v2_t ann_v2 = {1, "ompl@h:2", "ompl", "h", 2, "c++",
                                        "1", 500, 2, algos, 1, 1, active, 2,
                                        approaches};
    ENCODE(mpb_planner_announce_v2_t, ann_v2, dir, "announce-v2", 1);

    mpb_run_ack_t ack = {1, "0123456789abcdef0123456789abcdef", "null@h:1", 0};
    ENCODE(mpb_run_ack_t, ack, dir, "ack", 2);
    mpb_run_ack_v1_t ack_v1 = {1, "0123456789abcdef0123456789abcdef",
                               "null@h:1", 0};
    ENCODE(mpb_run_ack_v1_t, ack_v1, dir, "ack-v1", 2);

    mpb_param_t par = {"range", "0.3"};
    mpb_plan_request_t req = {
        .utime = 1, .attempt_id = "0123456789abcdef0123456789abcdef",
        .planner_id = "null@h:1", .algorithm = "straight_line",
        .num_params = 1, .params = &par, .time_limit = 1, .seed = 7,
        .robot_format = "planar", .robot_hash = "", .robot = "link_radius 0.03\n",
        .scene_format = "planar", .scene_hash = "", .scene = "",
        .num_joints = 3, .joint_names = names, .start = start,
        .goal = {.kind = 0, .num_joints = 3, .joints = goal,
                 .joint_tolerance = 0.01, .link = ""},
    };
    ENCODE(mpb_plan_request_t, req, dir, "request", 3);
    /* As the daemon sends a planner built before attempt ids (run_id). */
    mpb_plan_request_v1_t req_v1 = {
        .utime = req.utime, .run_id = req.attempt_id,
        .planner_id = req.planner_id, .algorithm = req.algorithm,
        .num_params = req.num_params, .params = req.params,
        .time_limit = req.time_limit, .seed = req.seed,
        .robot_format = req.robot_format, .robot_hash = req.robot_hash,
        .robot = req.robot, .scene_format = req.scene_format,
        .scene_hash = req.scene_hash, .scene = req.scene,
        .num_joints = req.num_joints, .joint_names = req.joint_names,
        .start = req.start, .goal = req.goal,
    };
    ENCODE(mpb_plan_request_v1_t, req_v1, dir, "request-v1", 3);
    return 0;
}
