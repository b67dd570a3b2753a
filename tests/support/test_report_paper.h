/*
 * test_report_paper.h - the databases the `mpb report` tests read, written
 * through the store (test_store.h), and the helpers that run the built mpb
 * on them: one fixture for every tests/unit/tools/test_report_*.c that
 * shares it. Include it after <cmocka.h>.
 */
#ifndef MPB_TEST_REPORT_PAPER_H
#define MPB_TEST_REPORT_PAPER_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "test_store.h"
#include "test_tool.h"

static char mpb_tool[4096];     /* the built mpb */

/*
 * Experiment 1, "paper": configurations A = ompl/RRTConnect (3 runs per
 * query) and B = ara/ARAstar (1 run), scenes KITCHEN (queries k1, k2) and
 * TABLETOP (t1). Experiment 2, "newer", comes after it. Runs are added
 * interleaved, as a scheduler would run them.
 */
enum { A, B };
enum { K1, K2, T1 };

typedef struct run_spec {
    int    cfg, query, rep, done, success;
    double total, raw, other;
    double raw_len;             /* < 0: no raw stage */
    double len, smooth;
    int    waypoints;
    double clearance;           /* < 0: not measured */
    int    raw_bad;             /* the raw stage failed verification */
} run_spec;

static const run_spec runs[] = {
    /* cfg q  rep done ok  total raw   other raw_len len   smooth wp  clear raw_bad */
    {A, K1, 0, 1, 1, 1.0,  0.9,  0.1, 10.0, 2.0,  0.1,  10, -1, 0},
    {A, K2, 0, 1, 1, 4.0,  3.6,  0.4, 40.0, 5.0,  0.5,  40, -1, 0},
    {B, K1, 0, 1, 1, 0.5,  0.3,  0.2, -1.0, 3.0,  1.5,  8,  -1, 0},
    {A, K1, 1, 1, 1, 2.0,  1.8,  0.2, 20.0, 4.0,  0.2,  20, -1, 0},
    {A, K2, 1, 1, 1, 6.0,  5.4,  0.6, 60.0, 5.0,  0.7,  50, -1, 1},
    {B, K2, 0, 1, 0, 0.7,  0.5,  0.2, -1.0, 77.0, 7.7,  77, -1, 0},
    {A, K1, 2, 1, 1, 3.0,  2.7,  0.3, 30.0, 6.0,  0.3,  30, -1, 0},
    {A, K2, 2, 1, 0, 60.0, 59.5, 0.5, -1.0, 99.0, 9.9,  99, -1, 0},
    {A, T1, 0, 1, 1, 7.0,  6.0,  1.0, -1.0, 8.0,  0.4,  12, 0.05, 0},
    {B, K2, 1, 0, 0, 0.0,  0.0,  0.0, -1.0, 0.0,  0.0,  0,  -1, 0},
};
#define NUM_RUNS ((int)(sizeof runs / sizeof runs[0]))

typedef struct fixture {
    char    dir[64];            /* first: test_store_teardown() */
    char    db[96];             /* the two experiments */
    char    empty[96];          /* a database with no experiment */
    char    text[96];           /* not a database */
    char    odd[96];            /* names that need escaping in every format */
    char    out[96];            /* a report written to a file */
    int64_t run_id[NUM_RUNS];
    int64_t cfg[2], query[3];
} fixture;

/* The world setup time the next finish() reports, then NaN (none). */
static double next_world_setup = NAN;
/* The daemon's verify time the next finish() records, then NaN (none). */
static double next_verify = NAN;
/* The planner's peak memory the next finish() records, then NaN. */
static double next_memory = NAN;

static inline void finish(mpb_store *s, int64_t run_id, const run_spec *r)
{
    char attempt[32];
    snprintf(attempt, sizeof attempt, "attempt-%lld", (long long)run_id);
    assert_int_equal(mpb_store_run_sent(s, run_id, attempt, "planner-1"), MPB_OK);
    mpb_named raw_m[] = {{"path_length", r->raw_len}, {"time", 0.01}};
    mpb_named fin_m[] = {{"path_length", r->len}, {"smoothness", r->smooth},
                         {"waypoints", r->waypoints}, {"time", 0.02},
                         {"clearance", r->clearance}};
    mpb_stage_record st[2] = {
        {.name = "raw", .valid = !r->raw_bad,
         .verdict = r->raw_bad ? "collision" : "valid", .verdict_segment = -1,
         .num_metrics = 2, .metrics = raw_m},
        {.name = "smoothed", .valid = r->success,
         .verdict = r->success ? "valid" : "collision", .verdict_segment = -1,
         .num_metrics = r->clearance >= 0 ? 5 : 4, .metrics = fin_m},
    };
    int has_raw = r->raw_len >= 0;
    mpb_run_record rec = {
        .run_id = run_id, .attempt_id = attempt, .planner_id = "planner-1",
        .status = "solved", .claimed_success = 1, .success = r->success,
        .time_total = r->total, .time_raw = r->raw, .time_other = r->other,
        .num_stages = has_raw ? 2 : 1, .stages = has_raw ? st : st + 1,
        .verify_time = next_verify,
        .memory = next_memory,
    };
    next_verify = NAN;
    next_memory = NAN;
    mpb_named values[] = {{"collision checks", 12.0},
                          {"world_setup_time", next_world_setup}};
    if (!isnan(next_world_setup)) {
        rec.num_values = 2;
        rec.values = values;
    }
    next_world_setup = NAN;
    assert_int_equal(mpb_store_run_finish(s, &rec), MPB_OK);
}

static inline void write_paper(fixture *f, mpb_store *s)
{
    int64_t exp = test_store_experiment(s, "paper", "paper.yaml", "h1", 3,
                                        60.0);
    assert_int_equal(exp, 1);
    f->cfg[A] = test_store_config(s, exp, "ompl", "RRTConnect", "");
    f->cfg[B] = test_store_config(s, exp, "ara", "ARAstar", "eps=100");
    int64_t scene[2] = {test_store_scene(s, exp, "KITCHEN", "k", "k"),
                        test_store_scene(s, exp, "TABLETOP", "t", "t")};
    const char *qname[] = {"k1", "k2", "t1"};
    for (int i = 0; i < 3; i++)
        f->query[i] = test_store_query(s, scene[i == T1], qname[i]);
    for (int i = 0; i < NUM_RUNS; i++)
        f->run_id[i] = test_store_run(s, exp, f->cfg[runs[i].cfg],
                                      f->query[runs[i].query], runs[i].rep, i);
    for (int i = 0; i < NUM_RUNS; i++)
        if (runs[i].done)
            finish(s, f->run_id[i], &runs[i]);
}

/* An experiment of one configuration, scene and query, and one run of it
 * finished as r says. */
static inline void write_one_run(mpb_store *s, int64_t exp, const char *planner,
                                 const char *algorithm, const char *params,
                                 const char *scene, const char *hash,
                                 const char *query, const run_spec *r)
{
    int64_t cfg = test_store_config(s, exp, planner, algorithm, params);
    int64_t q = test_store_query(s, test_store_scene(s, exp, scene, hash, hash),
                                 query);
    finish(s, test_store_run(s, exp, cfg, q, 0, 1), r);
}

static inline void write_newer(mpb_store *s)
{
    int64_t exp = test_store_experiment(s, "newer", "newer.yaml", "h2", 1,
                                        10.0);
    assert_int_equal(exp, 2);
    run_spec r = {0, 0, 0, 1, 1, 0.25, 0.2496, 0.0004, -1.0, 1.0, 0.0, 2, -1, 0};
    write_one_run(s, exp, "null", "straight_line", "", "NARROW_PASSAGE", "n",
                  "n1", &r);
}

/* One experiment whose names hold what CSV, LaTeX, Markdown and JSON must
 * escape; one successful run of 2 s. */
static inline void write_odd(mpb_store *s)
{
    int64_t exp = test_store_experiment(s, "odd \"one\"", "odd.yaml", "h3", 1,
                                        10.0);
    run_spec r = {0, 0, 0, 1, 1, 2.0, 1.5, 0.5, -1.0, 1.0, 0.0, 2, -1, 0};
    write_one_run(s, exp, "x", "a,b|c*d", "k=v", "S_1 & 50% {#}", "n", "q", &r);
}

static inline int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    mpb_store *s = test_store_new(f->dir, sizeof f->dir, f->db, sizeof f->db,
                                  "report");
    snprintf(f->empty, sizeof f->empty, "%s/empty.db", f->dir);
    snprintf(f->text, sizeof f->text, "%s/notes.txt", f->dir);
    snprintf(f->odd, sizeof f->odd, "%s/odd.db", f->dir);
    snprintf(f->out, sizeof f->out, "%s/report.out", f->dir);

    write_paper(f, s);
    write_newer(s);
    mpb_store_close(s);

    assert_int_equal(mpb_store_open(f->empty, 0, &s), MPB_OK);
    mpb_store_close(s);

    assert_int_equal(mpb_store_open(f->odd, 0, &s), MPB_OK);
    write_odd(s);
    mpb_store_close(s);

    FILE *t = fopen(f->text, "w");
    assert_non_null(t);
    fputs("These are not the results you are looking for.\n", t);
    fclose(t);
    *state = f;
    return 0;
}

/* ---- running the tool ------------------------------------------------------ */

/* `mpb ARGS` run as a user runs it (test_tool.h), its output kept: which
 * is "stdout", "stderr" or "both". */
typedef test_output output;
#define run(o, which, ...) test_run((o), mpb_tool, (which), __VA_ARGS__)

/*
 * The text of column col (0 = the first configuration) in the row labelled
 * label of the table whose title starts with title; "" if there is no such
 * row or column (the row is left out).
 */
static inline const char *cell(const output *o, const char *title, const char *label,
                        int col)
{
    static char buf[64];
    char key[128];
    const char *t = strstr(o->text, title);
    buf[0] = '\0';
    assert_non_null(t);
    const char *end = strstr(t + 1, "\nScene ");
    if (end == NULL)
        end = t + strlen(t);
    snprintf(key, sizeof key, "\n%s ", label);
    const char *row = strstr(t, key);
    if (row == NULL || row > end)
        return buf;
    row += strlen(key);
    const char *eol = strchr(row, '\n');
    for (int c = 0; c <= col; c++) {
        while (*row == ' ')
            row++;
        if (row >= eol)
            return "";
        size_t len = strcspn(row, " \n");
        if (c == col) {
            snprintf(buf, sizeof buf, "%.*s", (int)len, row);
            return buf;
        }
        row += len;
    }
    return buf;
}

#define KITCHEN "Scene KITCHEN - experiment paper (1), "
#define TABLETOP "Scene TABLETOP - experiment paper (1), "

#endif
