/* test_store_run_read.c - one run read back whole (mpb_store_run_get,
 * mpb_store_run_stages): where it belongs, its outcome, and each stage's
 * waypoints and verdict exactly as written. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"

typedef struct fixture {
    char       path[64];
    mpb_store *w, *s;
    int64_t    exp, cfg, scene, query, run, empty_run;
} fixture;

static const char *const joint_names[] = {"a", "b"};
static const double start[] = {0.0, 0.5};
static const double goal[] = {1.0, -0.25};
static const double raw_wp[] = {0.0, 0.5, 0.5, 0.125, 1.0, -0.25};

static int run_ids(void *ud, const mpb_run_row *row)
{
    fixture *f = ud;
    if (row->repetition == 0)
        f->run = row->id;
    else
        f->empty_run = row->id;
    return 0;
}

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    strcpy(f->path, "/tmp/mpb_test_store_run_read_XXXXXX");
    int fd = mkstemp(f->path);
    close(fd);
    unlink(f->path);
    assert_int_equal(mpb_store_open(f->path, 0, &f->w), MPB_OK);
    mpb_experiment_info e = {"exp", "exp.yaml", "h1", "text", 2, 1.5, NULL, 0};
    assert_int_equal(mpb_store_experiment_create(f->w, &e, &f->exp), MPB_OK);
    assert_int_equal(mpb_store_planner_config_add(f->w, f->exp, "ompl/RRT",
                                                  "ompl", "RRT", "", &f->cfg),
                     MPB_OK);
    mpb_scene_info sc = {"S", "planar", "rh", "robot", "planar", "sh", "scene"};
    assert_int_equal(mpb_store_scene_add(f->w, f->exp, &sc, &f->scene), MPB_OK);
    mpb_query_info q = {.name = "q", .num_joints = 2, .joint_names = joint_names,
                        .start = start, .goal_kind = MPB_GOAL_JOINTS,
                        .goal_joints = goal, .goal_tolerance = 0.01};
    assert_int_equal(mpb_store_query_add(f->w, f->scene, &q, &f->query), MPB_OK);
    for (int rep = 0; rep < 2; rep++)
        assert_int_equal(mpb_store_run_add(f->w, f->exp, f->cfg, f->query, rep,
                                           7 + rep), MPB_OK);
    assert_int_equal(mpb_store_runs_unfinished(f->w, f->exp, run_ids, f),
                     MPB_OK);

    assert_int_equal(mpb_store_run_sent(f->w, f->run, "uid-1", "ompl@h:1"),
                     MPB_OK);
    mpb_stage_record st[2] = {
        {.name = "raw", .time = 0.25, .num_waypoints = 3, .num_joints = 2,
         .waypoints = raw_wp, .valid = 0, .verdict = "collision",
         .verdict_detail = "segment 1 collides at s=0.5 (waypoints 1-2)",
         .verdict_segment = 1, .verification = "certified"},
        {.name = "smoothed", .time = 0.5, .num_waypoints = 2, .num_joints = 2,
         .waypoints = raw_wp + 2, .valid = 0, .verdict = "start",
         .verdict_detail = "waypoint 0 ...", .verdict_segment = 0},
    };
    mpb_run_record rec = {
        .run_id = f->run, .attempt_id = "uid-1", .planner_id = "ompl@h:1",
        .status = "solved", .message = "final stage is collision",
        .claimed_success = 1, .success = 0, .time_total = 0.75,
        .num_stages = 2, .stages = st,
    };
    assert_int_equal(mpb_store_run_finish(f->w, &rec), MPB_OK);
    assert_int_equal(mpb_store_run_sent(f->w, f->empty_run, "uid-2", "ompl@h:1"),
                     MPB_OK);
    mpb_run_record none = {
        .run_id = f->empty_run, .attempt_id = "uid-2", .planner_id = "ompl@h:1",
        .status = "failed", .message = "no way", .time_total = 1.5,
    };
    assert_int_equal(mpb_store_run_finish(f->w, &none), MPB_OK);
    assert_int_equal(mpb_store_open(f->path, 1, &f->s), MPB_OK);
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    mpb_store_close(f->s);
    mpb_store_close(f->w);
    unlink(f->path);
    char side[80];
    snprintf(side, sizeof side, "%s-wal", f->path);
    unlink(side);
    snprintf(side, sizeof side, "%s-shm", f->path);
    unlink(side);
    free(f);
    return 0;
}

typedef struct got {
    int              calls;
    mpb_run_detail   d;
    char             text[6][80];
    char             names[4][16], details[4][80], verdicts[4][16];
    char             verification[4][16];
    int              n[4], nj[4], segment[4], valid[4];
    double           wp[4][6], time[4];
} got;

static int on_run(void *ud, const mpb_run_detail *d)
{
    got *g = ud;
    g->calls++;
    g->d = *d;
    const char *s[6] = {d->state, d->planner_config, d->planner_id, d->status,
                        d->message, d->verdict};
    for (int i = 0; i < 6; i++)
        snprintf(g->text[i], sizeof g->text[i], "%s", s[i]);
    return 0;
}

static int on_stage(void *ud, const mpb_stage_record *st)
{
    got *g = ud;
    int i = g->calls++;
    snprintf(g->names[i], sizeof g->names[i], "%s", st->name);
    snprintf(g->details[i], sizeof g->details[i], "%s", st->verdict_detail);
    snprintf(g->verdicts[i], sizeof g->verdicts[i], "%s", st->verdict);
    snprintf(g->verification[i], sizeof g->verification[i], "%s",
             st->verification ? st->verification : "(null)");
    g->n[i] = st->num_waypoints;
    g->nj[i] = st->num_joints;
    g->segment[i] = st->verdict_segment;
    g->valid[i] = st->valid;
    g->time[i] = st->time;
    memcpy(g->wp[i], st->waypoints,
           sizeof(double) * (size_t)st->num_waypoints * (size_t)st->num_joints);
    return 0;
}

static void a_run_reads_back_with_where_it_belongs(void **state)
{
    fixture *f = *state;
    got g = {0};
    assert_int_equal(mpb_store_run_get(f->s, f->run, on_run, &g), MPB_OK);
    assert_int_equal(g.calls, 1);
    assert_true(g.d.run_id == f->run && g.d.experiment_id == f->exp &&
                g.d.planner_config_id == f->cfg && g.d.query_id == f->query &&
                g.d.scene_id == f->scene);
    assert_int_equal(g.d.repetition, 0);
    assert_string_equal(g.text[0], "done");
    assert_string_equal(g.text[1], "ompl/RRT");
    assert_string_equal(g.text[2], "ompl@h:1");
    assert_string_equal(g.text[3], "solved");
    assert_string_equal(g.text[4], "final stage is collision");
    assert_int_equal(g.d.success, 0);
    assert_float_equal(g.d.time_total, 0.75, 0);
}

static void stages_read_back_as_written(void **state)
{
    fixture *f = *state;
    got g = {0};
    assert_int_equal(mpb_store_run_stages(f->s, f->run, on_stage, &g), MPB_OK);
    assert_int_equal(g.calls, 2);
    assert_string_equal(g.names[0], "raw");
    assert_string_equal(g.names[1], "smoothed");
    assert_string_equal(g.verdicts[0], "collision");
    assert_string_equal(g.details[0], "segment 1 collides at s=0.5 (waypoints 1-2)");
    assert_int_equal(g.segment[0], 1);
    assert_int_equal(g.segment[1], 0);
    /* how the collision was found, for mpb view to find it again so;
       none where the check did not run */
    assert_string_equal(g.verification[0], "certified");
    assert_string_equal(g.verification[1], "(null)");
    assert_int_equal(g.valid[0], 0);
    assert_int_equal(g.n[0], 3);
    assert_int_equal(g.nj[0], 2);
    assert_memory_equal(g.wp[0], raw_wp, sizeof raw_wp);
    assert_int_equal(g.n[1], 2);
    assert_memory_equal(g.wp[1], raw_wp + 2, 4 * sizeof(double));
    assert_float_equal(g.time[1], 0.5, 0);
}

static void a_run_without_stages_and_an_unknown_run(void **state)
{
    fixture *f = *state;
    got g = {0};
    assert_int_equal(mpb_store_run_stages(f->s, f->empty_run, on_stage, &g),
                     MPB_OK);
    assert_int_equal(g.calls, 0);
    assert_int_equal(mpb_store_run_get(f->s, f->empty_run, on_run, &g), MPB_OK);
    assert_string_equal(g.text[3], "failed");
    assert_string_equal(g.text[4], "no way");
    g.calls = 0;
    assert_int_equal(mpb_store_run_get(f->s, 999, on_run, &g), MPB_ENOTFOUND);
    assert_int_equal(g.calls, 0);
    assert_string_equal(mpb_store_errmsg(f->s), "no run 999");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_run_reads_back_with_where_it_belongs),
        cmocka_unit_test(stages_read_back_as_written),
        cmocka_unit_test(a_run_without_stages_and_an_unknown_run),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
