/* test_store_read.c - the store's read API: what a report reads back is
 * exactly what was written, scene by scene and experiment by experiment. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"

/*
 * The fixture. Experiment "exp" has configurations A and B, scene S1 with
 * queries q1 and q2, scene S2 with q3. Experiment "other" has one run of
 * its own that must never show up in exp's results. Every run of exp, in
 * the order added (so in run id order):
 */
enum { PENDING, SENT, DONE };
enum { NO_STAGES, SMOOTHED, RAW_AND_SMOOTHED };

typedef struct run_spec {
    int    cfg, query, rep, state, success;
    double total, raw, other;
    int    stages;
    double raw_len, len, smooth;
    int    waypoints;
} run_spec;

static const run_spec runs[] = {
    /* cfg q  rep state  ok total  raw   other stages            raw_len len  smooth wp */
    {0, 0, 0, DONE,    1, 1.0,  0.9,  0.1, RAW_AND_SMOOTHED, 10.0, 3.0,   0.5,  10},
    {0, 0, 1, DONE,    1, 2.0,  1.8,  0.2, RAW_AND_SMOOTHED, 20.0, 5.0,   0.25, 20},
    {0, 0, 2, DONE,    1, 4.0,  3.6,  0.4, SMOOTHED,          0.0, 7.0,   0.75, 30},
    {0, 1, 0, DONE,    1, 3.0,  2.0,  1.0, RAW_AND_SMOOTHED, 40.0, 9.0,   1.0,  40},
    {0, 1, 1, DONE,    0, 60.0, 59.0, 1.0, SMOOTHED,          0.0, 100.0, 2.0,  50},
    {1, 0, 0, DONE,    1, 0.5,  0.4,  0.1, SMOOTHED,          0.0, 6.0,   0.1,  5},
    {1, 0, 1, DONE,    0, 0.3,  0.3,  0.0, NO_STAGES,         0.0, 0.0,   0.0,  0},
    {1, 1, 0, PENDING, 0, 0.0,  0.0,  0.0, NO_STAGES,         0.0, 0.0,   0.0,  0},
    {1, 1, 1, SENT,    0, 0.0,  0.0,  0.0, NO_STAGES,         0.0, 0.0,   0.0,  0},
    {0, 2, 0, DONE,    1, 5.0,  4.5,  0.5, SMOOTHED,          0.0, 11.0,  0.2,  7},
};
#define NUM_RUNS ((int)(sizeof runs / sizeof runs[0]))

typedef struct fixture {
    char       path[64];
    mpb_store *w;              /* the writer, as the daemon */
    mpb_store *s;              /* a read-only reader, as mpb report */
    int64_t    exp, other, cfg[2], scene[2], query[3], other_scene;
    int64_t    run_id[NUM_RUNS];
} fixture;

static const char *const joint_names[] = {"a", "b"};
static const double start[] = {0.0, 0.5};
static const double goal[] = {1.0, -0.25};

/* The run ids the store gave, matched to the specs by (cfg, query, rep). */
static int find_ids(void *ud, const mpb_run_row *row)
{
    fixture *f = ud;
    for (int i = 0; i < NUM_RUNS; i++)
        if (f->cfg[runs[i].cfg] == row->planner_config_id &&
            f->query[runs[i].query] == row->query_id &&
            runs[i].rep == row->repetition)
            f->run_id[i] = row->id;
    return 0;
}

static int first_id(void *ud, const mpb_run_row *row)
{
    *(int64_t *)ud = row->id;
    return 1;
}

static void finish(fixture *f, int i)
{
    const run_spec *r = &runs[i];
    char uid[32];
    snprintf(uid, sizeof uid, "uid-%d", i);
    assert_int_equal(mpb_store_run_sent(f->w, f->run_id[i], uid, "planner-1"),
                     MPB_OK);
    if (r->state != DONE)
        return;

    mpb_named raw_m[] = {{"path_length", r->raw_len}, {"time", 0.01}};
    mpb_named final_m[] = {{"path_length", r->len}, {"smoothness", r->smooth},
                           {"waypoints", r->waypoints}, {"time", 0.02}};
    mpb_stage_record st[2] = {
        {.name = "raw", .valid = 1, .verdict = "valid", .verdict_segment = -1,
         .num_metrics = 2, .metrics = raw_m},
        {.name = "smoothed", .valid = r->success,
         .verdict = r->success ? "valid" : "collision", .verdict_segment = -1,
         .num_metrics = 4, .metrics = final_m},
    };
    mpb_run_record rec = {
        .run_id = f->run_id[i], .attempt_id = uid, .planner_id = "planner-1",
        .status = r->stages == NO_STAGES ? "crash" : "solved",
        .claimed_success = r->stages != NO_STAGES, .success = r->success,
        .time_total = r->total, .time_raw = r->raw, .time_other = r->other,
        .wall_time = r->total + 0.001,
        .num_stages = r->stages == RAW_AND_SMOOTHED ? 2
                      : r->stages == SMOOTHED ? 1 : 0,
        .stages = r->stages == RAW_AND_SMOOTHED ? st : st + 1,
    };
    assert_int_equal(mpb_store_run_finish(f->w, &rec), MPB_OK);
}

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    strcpy(f->path, "/tmp/mpb_test_store_read_XXXXXX");
    int fd = mkstemp(f->path);
    close(fd);
    unlink(f->path);
    assert_int_equal(mpb_store_open(f->path, 0, &f->w), MPB_OK);

    mpb_experiment_info e = {"exp", "exp.yaml", "h1", "text", 3, 1.5, NULL, 0};
    assert_int_equal(mpb_store_experiment_create(f->w, &e, &f->exp), MPB_OK);
    assert_int_equal(mpb_store_planner_config_add(f->w, f->exp, "p/A", "p",
                                                  "A", "k=1", &f->cfg[0]),
                     MPB_OK);
    assert_int_equal(mpb_store_planner_config_add(f->w, f->exp, "p/B", "p",
                                                  "B", "", &f->cfg[1]),
                     MPB_OK);
    mpb_scene_info s1 = {"S1", "planar", "rh", "robot", "planar", "sh1", "s1"};
    mpb_scene_info s2 = {"S2", "planar", "rh", "robot", "moveit", "sh2", "s2"};
    assert_int_equal(mpb_store_scene_add(f->w, f->exp, &s1, &f->scene[0]),
                     MPB_OK);
    assert_int_equal(mpb_store_scene_add(f->w, f->exp, &s2, &f->scene[1]),
                     MPB_OK);
    const char *qname[] = {"q1", "q2", "q3"};
    for (int i = 0; i < 3; i++) {
        mpb_query_info q = {qname[i], 2, joint_names, start, MPB_GOAL_JOINTS,
                            goal, 0.01 * (i + 1), NULL, NULL};
        assert_int_equal(mpb_store_query_add(f->w, f->scene[i < 2 ? 0 : 1], &q,
                                             &f->query[i]), MPB_OK);
    }
    /* q1 holds two joints outside its group (a torso, a finger). */
    static const char *const held_names[] = {"torso", "finger"};
    static const double held_values[] = {0.1 + 0.2, -1e-300};
    assert_int_equal(mpb_store_query_set_held(f->w, f->query[0], 2, held_names,
                                              held_values), MPB_OK);
    for (int i = 0; i < NUM_RUNS; i++)
        assert_int_equal(mpb_store_run_add(f->w, f->exp, f->cfg[runs[i].cfg],
                                           f->query[runs[i].query],
                                           runs[i].rep, 100 + i), MPB_OK);

    /* The other experiment: same names, one successful run. */
    int64_t ocfg, oquery;
    mpb_experiment_info o = {"other", "other.yaml", "h2", "text2", 1, 9.0, NULL, 0};
    assert_int_equal(mpb_store_experiment_create(f->w, &o, &f->other), MPB_OK);
    assert_int_equal(mpb_store_planner_config_add(f->w, f->other, "p/A", "p",
                                                  "A", "", &ocfg), MPB_OK);
    assert_int_equal(mpb_store_scene_add(f->w, f->other, &s1, &f->other_scene),
                     MPB_OK);
    mpb_query_info oq = {"q1", 2, joint_names, start, MPB_GOAL_JOINTS, goal,
                         0.01, NULL, NULL};
    assert_int_equal(mpb_store_query_add(f->w, f->other_scene, &oq, &oquery),
                     MPB_OK);
    assert_int_equal(mpb_store_run_add(f->w, f->other, ocfg, oquery, 0, 7),
                     MPB_OK);

    assert_int_equal(mpb_store_runs_unfinished(f->w, f->exp, find_ids, f),
                     MPB_OK);
    for (int i = 0; i < NUM_RUNS; i++) {
        assert_true(f->run_id[i] > 0);
        if (i > 0)
            assert_true(f->run_id[i] > f->run_id[i - 1]);
    }
    for (int i = 0; i < NUM_RUNS; i++)
        if (runs[i].state != PENDING)
            finish(f, i);

    /* The other experiment's run: a time and a length that would show in
     * any result of exp it leaked into. */
    int64_t orun = 0;
    /* The callback's 1 stops the walk and comes back. */
    assert_int_equal(mpb_store_runs_unfinished(f->w, f->other, first_id, &orun),
                     1);
    mpb_named om[] = {{"path_length", 1000.0}};
    mpb_stage_record ost = {.name = "smoothed", .valid = 1, .verdict = "valid",
                            .verdict_segment = -1, .num_metrics = 1,
                            .metrics = om};
    mpb_run_record orec = {.run_id = orun, .attempt_id = "uid-other",
                           .planner_id = "planner-1", .status = "solved",
                           .claimed_success = 1, .success = 1,
                           .time_total = 500.0, .time_raw = 500.0,
                           .num_stages = 1, .stages = &ost};
    assert_int_equal(mpb_store_run_sent(f->w, orun, "uid-other", "planner-1"),
                     MPB_OK);
    assert_int_equal(mpb_store_run_finish(f->w, &orec), MPB_OK);
    assert_int_equal(mpb_store_experiment_finish(f->w, f->other), MPB_OK);

    assert_int_equal(mpb_store_open(f->path, 1, &f->s), MPB_OK);
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    char name[80];
    mpb_store_close(f->s);
    mpb_store_close(f->w);
    unlink(f->path);
    snprintf(name, sizeof name, "%s-wal", f->path);
    unlink(name);
    snprintf(name, sizeof name, "%s-shm", f->path);
    unlink(name);
    free(f);
    return 0;
}

/* ---- collecting what the walks give -------------------------------------- */

#define MAX_ROWS 16
#define TEXT 64

typedef struct got_row {
    int64_t id, a, b;
    int     i;
    double  x, y;
    char    s1[TEXT], s2[TEXT], s3[TEXT], s4[TEXT];
    int     null_s3;
} got_row;

typedef struct got {
    int     n;
    got_row r[MAX_ROWS];
} got;

static void copy(char *dst, const char *src)
{
    snprintf(dst, TEXT, "%s", src ? src : "(null)");
}

static int on_experiment(void *ud, const mpb_experiment_row *e)
{
    got *g = ud;
    got_row *r = &g->r[g->n++];
    r->id = e->id;
    r->i = e->runs_per_query;
    r->x = e->time_limit;
    r->y = e->finished;
    copy(r->s1, e->name);
    copy(r->s2, e->config_file);
    snprintf(r->s3, TEXT, "%s|%s|%s", e->config_hash, e->config_text,
             e->version);
    r->a = e->created > 1.6e9 && e->host != NULL;
    return 0;
}

static void experiments_are_listed_in_id_order(void **state)
{
    fixture *f = *state;
    got g = {0};
    assert_int_equal(mpb_store_experiments(f->s, on_experiment, &g), MPB_OK);
    assert_int_equal(g.n, 2);
    assert_int_equal(g.r[0].id, f->exp);
    assert_string_equal(g.r[0].s1, "exp");
    assert_string_equal(g.r[0].s2, "exp.yaml");
    assert_string_equal(g.r[0].s3, "h1|text|mpbench " MPB_VERSION_STRING);
    assert_int_equal(g.r[0].i, 3);
    assert_true(g.r[0].x == 1.5);
    assert_true(isnan(g.r[0].y));              /* not finished */
    assert_int_equal(g.r[0].a, 1);             /* a creation date, a host */
    assert_int_equal(g.r[1].id, f->other);
    assert_string_equal(g.r[1].s1, "other");
    assert_true(g.r[1].y > 1.6e9);             /* finished */
}

static void an_experiment_is_found_by_id(void **state)
{
    fixture *f = *state;
    got g = {0};
    assert_int_equal(mpb_store_experiment_get(f->s, f->other, on_experiment,
                                              &g), MPB_OK);
    assert_int_equal(g.n, 1);
    assert_string_equal(g.r[0].s1, "other");
    assert_true(g.r[0].x == 9.0);

    g.n = 0;
    assert_int_equal(mpb_store_experiment_get(f->s, 999, on_experiment, &g),
                     MPB_ENOTFOUND);
    assert_int_equal(g.n, 0);
    assert_string_equal(mpb_store_errmsg(f->s), "no experiment 999");
}

static int on_scene(void *ud, const mpb_scene_row *sc)
{
    got *g = ud;
    got_row *r = &g->r[g->n++];
    r->id = sc->id;
    copy(r->s1, sc->name);
    snprintf(r->s2, TEXT, "%s|%s|%s", sc->robot_format, sc->robot_hash,
             sc->robot);
    snprintf(r->s3, TEXT, "%s|%s|%s", sc->scene_format, sc->scene_hash,
             sc->scene);
    return 0;
}

static void scenes_belong_to_their_experiment(void **state)
{
    fixture *f = *state;
    got g = {0};
    assert_int_equal(mpb_store_scenes(f->s, f->exp, on_scene, &g), MPB_OK);
    assert_int_equal(g.n, 2);
    assert_int_equal(g.r[0].id, f->scene[0]);
    assert_string_equal(g.r[0].s1, "S1");
    assert_string_equal(g.r[0].s2, "planar|rh|robot");
    assert_string_equal(g.r[0].s3, "planar|sh1|s1");
    assert_int_equal(g.r[1].id, f->scene[1]);
    assert_string_equal(g.r[1].s1, "S2");
    assert_string_equal(g.r[1].s3, "moveit|sh2|s2");

    g.n = 0;
    assert_int_equal(mpb_store_scenes(f->s, f->other, on_scene, &g), MPB_OK);
    assert_int_equal(g.n, 1);
    assert_int_equal(g.r[0].id, f->other_scene);
}

static int on_config(void *ud, const mpb_planner_config_row *c)
{
    got *g = ud;
    got_row *r = &g->r[g->n++];
    r->id = c->id;
    copy(r->s1, c->name);
    snprintf(r->s2, TEXT, "%s|%s|%s", c->planner, c->algorithm, c->params);
    return 0;
}

static void planner_configs_are_listed(void **state)
{
    fixture *f = *state;
    got g = {0};
    assert_int_equal(mpb_store_planner_configs(f->s, f->exp, on_config, &g),
                     MPB_OK);
    assert_int_equal(g.n, 2);
    assert_int_equal(g.r[0].id, f->cfg[0]);
    assert_string_equal(g.r[0].s1, "p/A");
    assert_string_equal(g.r[0].s2, "p|A|k=1");
    assert_int_equal(g.r[1].id, f->cfg[1]);
    assert_string_equal(g.r[1].s1, "p/B");
    assert_string_equal(g.r[1].s2, "p|B|");
}

static int on_query(void *ud, const mpb_query_row *q)
{
    got *g = ud;
    got_row *r = &g->r[g->n++];
    r->id = q->id;
    r->a = q->scene_id;
    r->i = q->goal_kind;
    r->x = q->goal_tolerance;
    copy(r->s1, q->name);
    snprintf(r->s2, TEXT, "%s|%s", q->joint_names, q->start);
    copy(r->s3, q->goal_joints);
    copy(r->s4, q->held);
    return 0;
}

static void queries_of_a_scene_read_back_as_written(void **state)
{
    fixture *f = *state;
    got g = {0};
    assert_int_equal(mpb_store_queries(f->s, f->scene[0], on_query, &g),
                     MPB_OK);
    assert_int_equal(g.n, 2);
    for (int i = 0; i < 2; i++) {
        assert_int_equal(g.r[i].id, f->query[i]);
        assert_int_equal(g.r[i].a, f->scene[0]);
        assert_int_equal(g.r[i].i, MPB_GOAL_JOINTS);
        assert_true(fabs(g.r[i].x - 0.01 * (i + 1)) < 1e-15);
        assert_string_equal(g.r[i].s2, "a b|0 0.5");
        assert_string_equal(g.r[i].s3, "1 -0.25");
    }
    assert_string_equal(g.r[0].s1, "q1");
    assert_string_equal(g.r[1].s1, "q2");
    /* Held values come back exact, NULL where none is held. */
    assert_string_equal(g.r[0].s4, "torso=0.30000000000000004 finger=-1e-300");
    assert_string_equal(g.r[1].s4, "(null)");

    g.n = 0;
    assert_int_equal(mpb_store_queries(f->s, f->scene[1], on_query, &g),
                     MPB_OK);
    assert_int_equal(g.n, 1);
    assert_string_equal(g.r[0].s1, "q3");
}

static int on_unfinished(void *ud, int64_t scene_id, int n)
{
    got *g = ud;
    g->r[g->n].id = scene_id;
    g->r[g->n++].i = n;
    return 0;
}

static void unfinished_runs_are_counted_per_scene(void **state)
{
    fixture *f = *state;
    got g = {0};
    /* One pending and one sent run, both in S1; S2 is complete. */
    assert_int_equal(mpb_store_unfinished_by_scene(f->s, f->exp, on_unfinished,
                                                   &g), MPB_OK);
    assert_int_equal(g.n, 1);
    assert_int_equal(g.r[0].id, f->scene[0]);
    assert_int_equal(g.r[0].i, 2);

    g.n = 0;
    assert_int_equal(mpb_store_unfinished_by_scene(f->s, f->other,
                                                   on_unfinished, &g), MPB_OK);
    assert_int_equal(g.n, 0);
}

/* ---- the results walk ----------------------------------------------------- */

typedef struct result {
    int64_t run_id, cfg, query, scene;
    int     rep, success;
    double  total, raw, other;
    char    status[TEXT], stage[TEXT];
    double  m[4];
    int     num_named;
    char    named[4 * TEXT];        /* "name=value;..." */
} result;

typedef struct results {
    int    n, stop_after;
    result r[MAX_ROWS];
} results;

static int on_result(void *ud, const mpb_result_row *row)
{
    results *g = ud;
    result *r = &g->r[g->n++];
    r->run_id = row->run_id;
    r->cfg = row->planner_config_id;
    r->query = row->query_id;
    r->scene = row->scene_id;
    r->rep = row->repetition;
    r->success = row->success;
    r->total = row->time_total;
    r->raw = row->time_raw;
    r->other = row->time_other;
    copy(r->status, row->status);
    copy(r->stage, row->stage);
    for (int k = 0; k < 4; k++)
        r->m[k] = row->metrics[k];
    r->num_named = row->num_named;
    r->named[0] = '\0';
    for (int k = 0; k < row->num_named; k++) {
        size_t len = strlen(r->named);
        snprintf(r->named + len, sizeof r->named - len, "%s=%g;",
                 row->named[k].name, row->named[k].value);
    }
    return g->stop_after && g->n == g->stop_after ? 42 : 0;
}

static int on_result_no_names(void *ud, const mpb_result_row *row)
{
    results *g = ud;
    g->r[g->n++].num_named = row->num_named;
    return 0;
}

static const char *const wanted[] = {"path_length", "smoothness", "waypoints",
                                     "clearance"};

/* The run of spec i, as the walk should give it from stage (NULL: final). */
static void check_result(const fixture *f, const result *r, int i,
                         const char *stage)
{
    const run_spec *sp = &runs[i];
    assert_int_equal(r->run_id, f->run_id[i]);
    assert_int_equal(r->cfg, f->cfg[sp->cfg]);
    assert_int_equal(r->query, f->query[sp->query]);
    assert_int_equal(r->scene, f->scene[sp->query < 2 ? 0 : 1]);
    assert_int_equal(r->rep, sp->rep);
    assert_int_equal(r->success, sp->success);
    assert_true(r->total == sp->total);
    assert_true(r->raw == sp->raw);
    assert_true(r->other == sp->other);
    assert_string_equal(r->status, sp->stages == NO_STAGES ? "crash"
                                                           : "solved");
    assert_true(isnan(r->m[3]));            /* no run has a clearance */
    if (stage == NULL) {
        if (sp->stages == NO_STAGES) {
            assert_string_equal(r->stage, "(null)");
            assert_int_equal(r->num_named, 0);
            for (int k = 0; k < 3; k++)
                assert_true(isnan(r->m[k]));
            return;
        }
        assert_string_equal(r->stage, "smoothed");
        assert_true(r->m[0] == sp->len);
        assert_true(r->m[1] == sp->smooth);
        assert_true(r->m[2] == sp->waypoints);
        char named[4 * TEXT];
        snprintf(named, sizeof named,
                 "path_length=%g;smoothness=%g;time=0.02;waypoints=%d;",
                 sp->len, sp->smooth, sp->waypoints);
        assert_int_equal(r->num_named, 4);
        assert_string_equal(r->named, named);
    } else {
        assert_string_equal(r->stage, "raw");
        if (sp->stages == RAW_AND_SMOOTHED) {
            assert_true(r->m[0] == sp->raw_len);
            assert_int_equal(r->num_named, 2);
        } else {
            assert_true(isnan(r->m[0]));
            assert_int_equal(r->num_named, 0);
        }
        assert_true(isnan(r->m[1]));        /* raw has no smoothness here */
        assert_true(isnan(r->m[2]));
    }
}

static void results_give_each_finished_run_of_a_scene(void **state)
{
    fixture *f = *state;
    results g = {0};
    assert_int_equal(mpb_store_results(f->s, f->exp, f->scene[0], NULL, wanted,
                                       4, on_result, &g), MPB_OK);
    /* Specs 0-6: S1's finished runs, failed ones too, in run id order; not
     * the pending and the sent one, not S2's, not the other experiment's. */
    assert_int_equal(g.n, 7);
    for (int i = 0; i < 7; i++)
        check_result(f, &g.r[i], i, NULL);
}

static void results_of_a_chosen_stage(void **state)
{
    fixture *f = *state;
    results g = {0};
    assert_int_equal(mpb_store_results(f->s, f->exp, f->scene[0], "raw", wanted,
                                       4, on_result, &g), MPB_OK);
    assert_int_equal(g.n, 7);
    for (int i = 0; i < 7; i++)
        check_result(f, &g.r[i], i, "raw");

    g.n = 0;
    assert_int_equal(mpb_store_results(f->s, f->exp, f->scene[0], "nosuch",
                                       wanted, 4, on_result, &g), MPB_OK);
    assert_int_equal(g.n, 7);       /* every run, with no metrics */
    for (int i = 0; i < 7; i++) {
        assert_int_equal(g.r[i].num_named, 0);
        assert_true(isnan(g.r[i].m[0]));
    }
}

static void a_second_scene_is_kept_separate(void **state)
{
    fixture *f = *state;
    results g = {0};
    assert_int_equal(mpb_store_results(f->s, f->exp, f->scene[1], NULL, wanted,
                                       4, on_result, &g), MPB_OK);
    assert_int_equal(g.n, 1);
    check_result(f, &g.r[0], 9, NULL);

    /* Scene 0: every scene of the experiment, still in run id order. */
    g.n = 0;
    assert_int_equal(mpb_store_results(f->s, f->exp, 0, NULL, wanted, 4,
                                       on_result, &g), MPB_OK);
    assert_int_equal(g.n, 8);
    for (int i = 0; i < 7; i++)
        check_result(f, &g.r[i], i, NULL);
    check_result(f, &g.r[7], 9, NULL);

    /* The other experiment's scene of the same name holds only its run. */
    g.n = 0;
    assert_int_equal(mpb_store_results(f->s, f->other, 0, NULL, wanted, 4,
                                       on_result, &g), MPB_OK);
    assert_int_equal(g.n, 1);
    assert_true(g.r[0].total == 500.0);
    assert_true(g.r[0].m[0] == 1000.0);
}

static void a_walk_stops_when_told(void **state)
{
    fixture *f = *state;
    results g = {.stop_after = 3};
    assert_int_equal(mpb_store_results(f->s, f->exp, f->scene[0], NULL, wanted,
                                       4, on_result, &g), 42);
    assert_int_equal(g.n, 3);

    /* No names asked for: the runs still come, with every named metric. */
    g = (results){0};
    assert_int_equal(mpb_store_results(f->s, f->exp, f->scene[1], NULL, NULL,
                                       0, on_result_no_names, &g), MPB_OK);
    assert_int_equal(g.n, 1);
    assert_int_equal(g.r[0].num_named, 4);

    assert_int_equal(mpb_store_results(f->s, f->exp, f->scene[1], NULL, NULL,
                                       -1, on_result, &g), MPB_EINVAL);
}

/* What a report does with the walk: means over successful runs, standard
 * deviation per query averaged over the queries (the paper's convention).
 * A's runs of S1 come query by query in this fixture, so groups can be ended
 * on a change of query. */
typedef struct scene_stats {
    int64_t     cfg, query;
    long        finished, succeeded;
    mpb_grouped time, length;
} scene_stats;

static int on_stats(void *ud, const mpb_result_row *row)
{
    scene_stats *st = ud;
    if (row->planner_config_id != st->cfg)
        return 0;
    if (row->query_id != st->query) {
        mpb_grouped_end_group(&st->time);
        mpb_grouped_end_group(&st->length);
        st->query = row->query_id;
    }
    st->finished++;
    if (row->success) {
        st->succeeded++;
        mpb_grouped_add(&st->time, row->time_total);
        mpb_grouped_add(&st->length, row->metrics[0]);
    }
    return 0;
}

static void failed_runs_stay_out_of_the_means(void **state)
{
    fixture *f = *state;
    scene_stats a = {.cfg = f->cfg[0]}, b = {.cfg = f->cfg[1]};
    mpb_grouped_init(&a.time);
    mpb_grouped_init(&a.length);
    mpb_grouped_init(&b.time);
    mpb_grouped_init(&b.length);
    assert_int_equal(mpb_store_results(f->s, f->exp, f->scene[0], NULL, wanted,
                                       1, on_stats, &a), MPB_OK);
    assert_int_equal(mpb_store_results(f->s, f->exp, f->scene[0], NULL, wanted,
                                       1, on_stats, &b), MPB_OK);

    /* A: q1 times 1, 2, 4 and q2 time 3 succeeded; q2's 60 s failure does
     * not count. Mean (1 + 2 + 4 + 3) / 4 = 2.5. Standard deviation of q1:
     * mean 7/3, squares 16/9 + 1/9 + 25/9 = 42/9, / (3 - 1) = 7/3, so
     * sqrt(7/3); q2 has one sample: 0. Averaged: sqrt(7/3) / 2. */
    assert_int_equal(a.finished, 5);
    assert_int_equal(a.succeeded, 4);
    assert_true(fabs(mpb_grouped_mean(&a.time) - 2.5) < 1e-12);
    assert_true(fabs(mpb_grouped_stddev(&a.time) - sqrt(7.0 / 3.0) / 2.0)
                < 1e-12);
    /* Lengths 3, 5, 7 (sd 2) and 9 (sd 0), not the failure's 100. */
    assert_true(fabs(mpb_grouped_mean(&a.length) - 6.0) < 1e-12);
    assert_true(fabs(mpb_grouped_stddev(&a.length) - 1.0) < 1e-12);

    /* B: one success (0.5 s, length 6) and one crash in q1. */
    assert_int_equal(b.finished, 2);
    assert_int_equal(b.succeeded, 1);
    assert_true(mpb_grouped_mean(&b.time) == 0.5);
    assert_true(mpb_grouped_stddev(&b.time) == 0.0);
    assert_true(mpb_grouped_mean(&b.length) == 6.0);
}

static void reading_a_missing_database_fails_cleanly(void **state)
{
    (void)state;
    mpb_store *s = NULL;
    assert_int_not_equal(mpb_store_open("/nonexistent/mpb.db", 1, &s), MPB_OK);
    assert_non_null(s);
    assert_non_null(strstr(mpb_store_errmsg(s), "/nonexistent/mpb.db"));
    mpb_store_close(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(experiments_are_listed_in_id_order,
                                        setup, teardown),
        cmocka_unit_test_setup_teardown(an_experiment_is_found_by_id, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(scenes_belong_to_their_experiment,
                                        setup, teardown),
        cmocka_unit_test_setup_teardown(planner_configs_are_listed, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(queries_of_a_scene_read_back_as_written,
                                        setup, teardown),
        cmocka_unit_test_setup_teardown(unfinished_runs_are_counted_per_scene,
                                        setup, teardown),
        cmocka_unit_test_setup_teardown(results_give_each_finished_run_of_a_scene,
                                        setup, teardown),
        cmocka_unit_test_setup_teardown(results_of_a_chosen_stage, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(a_second_scene_is_kept_separate, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(a_walk_stops_when_told, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(failed_runs_stay_out_of_the_means,
                                        setup, teardown),
        cmocka_unit_test(reading_a_missing_database_fails_cleanly),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
