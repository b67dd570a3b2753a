/*
 * test_store.h - a unit test's results database, built through the store
 * API as the daemon builds it: experiments, configurations, planar scenes,
 * one-joint queries and runs, each call failing the test when the store
 * refuses it. Include it after <cmocka.h> and "mpbench/mpbench.h".
 */
#ifndef MPB_TEST_STORE_H
#define MPB_TEST_STORE_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_tool.h"

/* A new results database, results.db in a new temporary folder
 * /tmp/mpb_test_NAME_XXXXXX (test_tool.h): the folder into dir, the
 * database's path into db, and the store open on it. */
static inline mpb_store *test_store_new(char *dir, size_t dir_size, char *db,
                                        size_t db_size, const char *name)
{
    mpb_store *s;
    test_make_dir(dir, dir_size, name);
    snprintf(db, db_size, "%s/results.db", dir);
    assert_int_equal(mpb_store_open(db, 0, &s), MPB_OK);
    return s;
}

/* A group teardown for a fixture that calloc() made and whose first
 * member is the char array of its test_store_new() folder: the folder
 * removed with all it holds, the fixture freed. */
static inline int test_store_teardown(void **state)
{
    char *dir = *state;
    test_remove_dir(dir);
    free(*state);
    return 0;
}

/* A new experiment: its name, file, hash, repetitions and time limit (s). */
static inline int64_t test_store_experiment(mpb_store *s, const char *name,
                                            const char *file, const char *hash,
                                            int repetitions, double limit)
{
    int64_t id;
    mpb_experiment_info e = {name, file, hash, "text", repetitions, limit,
                             NULL, 0};
    assert_int_equal(mpb_store_experiment_create(s, &e, &id), MPB_OK);
    return id;
}

/* A configuration "planner/algorithm" of experiment exp, with params. */
static inline int64_t test_store_config(mpb_store *s, int64_t exp,
                                        const char *planner,
                                        const char *algorithm,
                                        const char *params)
{
    char name[256];
    int64_t id;
    snprintf(name, sizeof name, "%s/%s", planner, algorithm);
    assert_int_equal(mpb_store_planner_config_add(s, exp, name, planner,
                                                  algorithm, params, &id),
                     MPB_OK);
    return id;
}

/* A scene of experiment exp: a planar robot "r", the scene's hash and
 * text as given. */
static inline int64_t test_store_scene(mpb_store *s, int64_t exp,
                                       const char *name, const char *hash,
                                       const char *text)
{
    int64_t id;
    mpb_scene_info sc = {name, "planar", "r", "r", "planar", hash, text};
    assert_int_equal(mpb_store_scene_add(s, exp, &sc, &id), MPB_OK);
    return id;
}

/* A query of scene: joint "j" from 0 to 1 (tolerance 0.01). */
static inline int64_t test_store_query(mpb_store *s, int64_t scene,
                                       const char *name)
{
    static const char *const joints[] = {"j"};
    static const double zero[] = {0.0}, one[] = {1.0};
    int64_t id;
    mpb_query_info q = {name, 1, joints, zero, MPB_GOAL_JOINTS, one, 0.01,
                        NULL, NULL};
    assert_int_equal(mpb_store_query_add(s, scene, &q, &id), MPB_OK);
    return id;
}

typedef struct test_store_key {
    int64_t cfg, query, id;
    int     rep;
} test_store_key;

static int test_store_match(void *ud, const mpb_run_row *row)
{
    test_store_key *k = ud;
    if (row->planner_config_id == k->cfg && row->query_id == k->query &&
        row->repetition == k->rep) {
        k->id = row->id;
        return 1;
    }
    return 0;
}

/* The id of experiment exp's unfinished run of configuration cfg on
 * query, repetition rep. */
static inline int64_t test_store_run_id(mpb_store *s, int64_t exp,
                                        int64_t cfg, int64_t query, int rep)
{
    test_store_key k = {cfg, query, 0, rep};
    assert_int_equal(mpb_store_runs_unfinished(s, exp, test_store_match, &k),
                     1);
    return k.id;
}

/* Run id sent to planner "p-1" and finished: one stage "raw" valid when
 * success, a path_length metric of length (NaN for none), time s in all
 * and in the raw stage, no verify time or memory measured. */
static inline void test_store_finish(mpb_store *s, int64_t run_id, int success,
                                     double time, double length)
{
    char attempt[32];
    snprintf(attempt, sizeof attempt, "attempt-%lld", (long long)run_id);
    assert_int_equal(mpb_store_run_sent(s, run_id, attempt, "p-1"), MPB_OK);
    mpb_named m[] = {{"path_length", length}};
    mpb_stage_record st = {.name = "raw", .valid = success,
                           .verdict = success ? "valid" : "collision",
                           .verdict_segment = -1, .num_metrics = 1,
                           .metrics = m};
    mpb_run_record rec = {
        .run_id = run_id, .attempt_id = attempt, .planner_id = "p-1",
        .status = success ? "solved" : "timeout",
        .claimed_success = success, .success = success, .time_total = time,
        .time_raw = time, .num_stages = 1, .stages = &st,
        .verify_time = NAN, .memory = NAN,
    };
    assert_int_equal(mpb_store_run_finish(s, &rec), MPB_OK);
}

/* A new run of configuration cfg on query, repetition rep, with seed:
 * its id. */
static inline int64_t test_store_run(mpb_store *s, int64_t exp, int64_t cfg,
                                     int64_t query, int rep, int64_t seed)
{
    assert_int_equal(mpb_store_run_add(s, exp, cfg, query, rep, seed), MPB_OK);
    return test_store_run_id(s, exp, cfg, query, rep);
}

#endif
