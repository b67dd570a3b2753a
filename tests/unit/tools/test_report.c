/* test_report.c - `mpb report`, run as a user runs it: the built tool on a
 * database written through the store, its printed numbers checked against
 * values worked out by hand, and its errors. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"
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
    char    dir[64];
    char    db[96];             /* the two experiments */
    char    empty[96];          /* a database with no experiment */
    char    text[96];           /* not a database */
    char    odd[96];            /* names that need escaping in every format */
    char    out[96];            /* a report written to a file */
    int64_t run_id[NUM_RUNS];
    int64_t cfg[2], query[3];
} fixture;

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

/* The world setup time the next finish() reports, then NaN (none). */
static double next_world_setup = NAN;
/* The daemon's verify time the next finish() records, then NaN (none). */
static double next_verify = NAN;
/* The planner's peak memory the next finish() records, then NaN. */
static double next_memory = NAN;

static void finish(mpb_store *s, int64_t run_id, const run_spec *r)
{
    char uid[32];
    snprintf(uid, sizeof uid, "uid-%lld", (long long)run_id);
    assert_int_equal(mpb_store_run_sent(s, run_id, uid, "planner-1"), MPB_OK);
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
        .run_id = run_id, .run_uid = uid, .planner_id = "planner-1",
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

static void write_paper(fixture *f, mpb_store *s)
{
    int64_t exp, scene[2];
    mpb_experiment_info e = {"paper", "paper.yaml", "h1", "text", 3, 60.0, NULL, 0};
    assert_int_equal(mpb_store_experiment_create(s, &e, &exp), MPB_OK);
    assert_int_equal(exp, 1);
    assert_int_equal(mpb_store_planner_config_add(s, exp, "ompl/RRTConnect",
                                                  "ompl", "RRTConnect", "",
                                                  &f->cfg[A]), MPB_OK);
    assert_int_equal(mpb_store_planner_config_add(s, exp, "ara/ARAstar", "ara",
                                                  "ARAstar", "eps=100",
                                                  &f->cfg[B]), MPB_OK);
    mpb_scene_info kitchen = {"KITCHEN", "planar", "r", "r", "planar", "k", "k"};
    mpb_scene_info tabletop = {"TABLETOP", "planar", "r", "r", "planar", "t",
                               "t"};
    assert_int_equal(mpb_store_scene_add(s, exp, &kitchen, &scene[0]), MPB_OK);
    assert_int_equal(mpb_store_scene_add(s, exp, &tabletop, &scene[1]), MPB_OK);
    static const char *const joints[] = {"j"};
    static const double zero[] = {0.0}, one[] = {1.0};
    const char *qname[] = {"k1", "k2", "t1"};
    for (int i = 0; i < 3; i++) {
        mpb_query_info q = {qname[i], 1, joints, zero, MPB_GOAL_JOINTS, one,
                            0.01, NULL, NULL};
        assert_int_equal(mpb_store_query_add(s, scene[i == T1], &q,
                                             &f->query[i]), MPB_OK);
    }
    for (int i = 0; i < NUM_RUNS; i++)
        assert_int_equal(mpb_store_run_add(s, exp, f->cfg[runs[i].cfg],
                                           f->query[runs[i].query],
                                           runs[i].rep, i), MPB_OK);
    assert_int_equal(mpb_store_runs_unfinished(s, exp, find_ids, f), MPB_OK);
    for (int i = 0; i < NUM_RUNS; i++)
        if (runs[i].done)
            finish(s, f->run_id[i], &runs[i]);
}

static int first_id(void *ud, const mpb_run_row *row)
{
    *(int64_t *)ud = row->id;
    return 1;
}

static void write_newer(mpb_store *s)
{
    int64_t exp, cfg, scene, query, run = 0;
    mpb_experiment_info e = {"newer", "newer.yaml", "h2", "text", 1, 10.0, NULL, 0};
    assert_int_equal(mpb_store_experiment_create(s, &e, &exp), MPB_OK);
    assert_int_equal(exp, 2);
    assert_int_equal(mpb_store_planner_config_add(s, exp, "null/straight_line",
                                                  "null", "straight_line", "",
                                                  &cfg), MPB_OK);
    mpb_scene_info sc = {"NARROW_PASSAGE", "planar", "r", "r", "planar", "n",
                         "n"};
    assert_int_equal(mpb_store_scene_add(s, exp, &sc, &scene), MPB_OK);
    static const char *const joints[] = {"j"};
    static const double zero[] = {0.0}, one[] = {1.0};
    mpb_query_info q = {"n1", 1, joints, zero, MPB_GOAL_JOINTS, one, 0.01,
                        NULL, NULL};
    assert_int_equal(mpb_store_query_add(s, scene, &q, &query), MPB_OK);
    assert_int_equal(mpb_store_run_add(s, exp, cfg, query, 0, 1), MPB_OK);
    assert_int_equal(mpb_store_runs_unfinished(s, exp, first_id, &run), 1);
    run_spec r = {0, 0, 0, 1, 1, 0.25, 0.2496, 0.0004, -1.0, 1.0, 0.0, 2, -1, 0};
    finish(s, run, &r);
}

/* One experiment whose names hold what CSV, LaTeX, Markdown and JSON must
 * escape; one successful run of 2 s. */
static void write_odd(mpb_store *s)
{
    int64_t exp, cfg, scene, query, run = 0;
    mpb_experiment_info e = {"odd \"one\"", "odd.yaml", "h3", "text", 1, 10.0, NULL, 0};
    assert_int_equal(mpb_store_experiment_create(s, &e, &exp), MPB_OK);
    assert_int_equal(mpb_store_planner_config_add(s, exp, "x/a,b|c*d",
                                                  "x", "a,b|c*d", "k=v",
                                                  &cfg), MPB_OK);
    mpb_scene_info sc = {"S_1 & 50% {#}", "planar", "r", "r", "planar", "n",
                         "n"};
    assert_int_equal(mpb_store_scene_add(s, exp, &sc, &scene), MPB_OK);
    static const char *const joints[] = {"j"};
    static const double zero[] = {0.0}, one[] = {1.0};
    mpb_query_info q = {"q", 1, joints, zero, MPB_GOAL_JOINTS, one, 0.01,
                        NULL, NULL};
    assert_int_equal(mpb_store_query_add(s, scene, &q, &query), MPB_OK);
    assert_int_equal(mpb_store_run_add(s, exp, cfg, query, 0, 1), MPB_OK);
    assert_int_equal(mpb_store_runs_unfinished(s, exp, first_id, &run), 1);
    run_spec r = {0, 0, 0, 1, 1, 2.0, 1.5, 0.5, -1.0, 1.0, 0.0, 2, -1, 0};
    finish(s, run, &r);
}

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    mpb_store *s;
    strcpy(f->dir, "/tmp/mpb_test_report_XXXXXX");
    assert_non_null(mkdtemp(f->dir));
    snprintf(f->db, sizeof f->db, "%s/results.db", f->dir);
    snprintf(f->empty, sizeof f->empty, "%s/empty.db", f->dir);
    snprintf(f->text, sizeof f->text, "%s/notes.txt", f->dir);
    snprintf(f->odd, sizeof f->odd, "%s/odd.db", f->dir);
    snprintf(f->out, sizeof f->out, "%s/report.out", f->dir);

    assert_int_equal(mpb_store_open(f->db, 0, &s), MPB_OK);
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

static int teardown(void **state)
{
    fixture *f = *state;
    char cmd[256];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", f->dir);
    assert_int_equal(system(cmd), 0);
    free(f);
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
static const char *cell(const output *o, const char *title, const char *label,
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

/* ---- the numbers ------------------------------------------------------------ */

static void the_kitchen_table_matches_the_hand_computed_values(void **state)
{
    fixture *f = *state;
    output o;
    run(&o, "stdout", "report --experiment 1 '%s'", f->db);
    assert_int_equal(o.status, 0);

    /* 6 runs of A and 2 of B are finished; B's k2 repetition 1 is not. */
    assert_non_null(strstr(o.text, KITCHEN "8 runs\n"));
    assert_non_null(strstr(o.text, "1 more run not finished yet"));
    /* One column per configuration, named. */
    assert_non_null(strstr(o.text, "ompl/RRTConnect  ara/ARAstar\n"));

    /*
     * A (ompl/RRTConnect), successful runs only: k1 times 1, 2, 3 and k2
     * times 4, 6; the 60 s failure on k2 is out.
     *   tau_t mean 16/5 = 3.2; sd(k1) = 1, sd(k2) = sqrt(2): (1 + 1.41421)/2
     *   tau_r 0.9, 1.8, 2.7 | 3.6, 5.4: mean 2.88, (0.9 + 1.27279)/2 = 1.08640
     *   tau_o 0.1, 0.2, 0.3 | 0.4, 0.6: mean 0.32, (0.1 + 0.14142)/2 = 0.12071
     *   l_p   2, 4, 6 | 5, 5: mean 4.4, (2 + 0)/2 = 1
     *   kappa' 0.1, 0.2, 0.3 | 0.5, 0.7: mean 0.36, sigma 0.12071
     *   waypoints 10, 20, 30, 40, 50: 30
     *   s_r 5 of 6 finished: 83.3 %
     */
    assert_string_equal(cell(&o, KITCHEN, "tau_t (Mean, s)", A), "3.200");
    assert_string_equal(cell(&o, KITCHEN, "tau_t (sigma, s)", A), "1.207");
    assert_string_equal(cell(&o, KITCHEN, "tau_r (Mean, s)", A), "2.880");
    assert_string_equal(cell(&o, KITCHEN, "tau_r (sigma, s)", A), "1.086");
    assert_string_equal(cell(&o, KITCHEN, "tau_o (Mean, s)", A), "0.320");
    assert_string_equal(cell(&o, KITCHEN, "tau_o (sigma, s)", A), "0.121");
    assert_string_equal(cell(&o, KITCHEN, "l_p (Mean, rad)", A), "4.400");
    assert_string_equal(cell(&o, KITCHEN, "l_p (sigma, rad)", A), "1.000");
    assert_string_equal(cell(&o, KITCHEN, "kappa' (Mean, rad^2)", A), "0.360");
    assert_string_equal(cell(&o, KITCHEN, "kappa' (sigma, rad^2)", A), "0.121");
    assert_string_equal(cell(&o, KITCHEN, "waypoints (Mean)", A), "30.0");
    assert_string_equal(cell(&o, KITCHEN, "s_r (%)", A), "83.3");

    /* B (ara/ARAstar), one run per query: k1 succeeded (0.5 s, l_p 3),
     * k2 failed with l_p 77, which must not show. One successful run:
     * no sigma to compute, '-'. */
    assert_string_equal(cell(&o, KITCHEN, "tau_t (Mean, s)", B), "0.500");
    assert_string_equal(cell(&o, KITCHEN, "tau_t (sigma, s)", B), "-");
    assert_string_equal(cell(&o, KITCHEN, "tau_r (Mean, s)", B), "0.300");
    assert_string_equal(cell(&o, KITCHEN, "tau_o (Mean, s)", B), "0.200");
    assert_string_equal(cell(&o, KITCHEN, "l_p (Mean, rad)", B), "3.000");
    assert_string_equal(cell(&o, KITCHEN, "l_p (sigma, rad)", B), "-");
    assert_string_equal(cell(&o, KITCHEN, "kappa' (Mean, rad^2)", B), "1.500");
    assert_string_equal(cell(&o, KITCHEN, "waypoints (Mean)", B), "8.0");
    assert_string_equal(cell(&o, KITCHEN, "s_r (%)", B), "50.0");

    /* No run in KITCHEN measured clearance: no d_n rows there. */
    assert_string_equal(cell(&o, KITCHEN, "d_n (Mean, m)", A), "");
}

static void a_second_scene_has_its_own_table(void **state)
{
    fixture *f = *state;
    output o;
    run(&o, "stdout", "report -e 1 '%s'", f->db);
    assert_int_equal(o.status, 0);
    assert_non_null(strstr(o.text, TABLETOP "1 run\n"));
    /* KITCHEN's numbers are not in it, nor its unfinished run. */
    assert_string_equal(cell(&o, TABLETOP, "tau_t (Mean, s)", A), "7.000");
    assert_string_equal(cell(&o, TABLETOP, "tau_t (sigma, s)", A), "-");
    assert_string_equal(cell(&o, TABLETOP, "l_p (Mean, rad)", A), "8.000");
    /* 0.05: 3 significant digits, as every row's smallest value keeps. */
    assert_string_equal(cell(&o, TABLETOP, "d_n (Mean, m)", A), "0.0500");
    assert_string_equal(cell(&o, TABLETOP, "s_r (%)", A), "100.0");
    /* B never ran there: nothing to show. */
    assert_string_equal(cell(&o, TABLETOP, "tau_t (Mean, s)", B), "-");
    assert_string_equal(cell(&o, TABLETOP, "d_n (Mean, m)", B), "-");
    assert_string_equal(cell(&o, TABLETOP, "s_r (%)", B), "-");
    const char *t = strstr(o.text, TABLETOP);
    assert_null(strstr(t, "not finished"));
}

static void a_chosen_stage_gives_its_own_metrics(void **state)
{
    fixture *f = *state;
    output o;
    run(&o, "stdout", "report --stage raw --experiment=1 '%s'", f->db);
    assert_int_equal(o.status, 0);
    assert_non_null(strstr(o.text, "stage 'raw'"));
    /* A's raw lengths 10, 20, 30 | 40, and 60 whose raw stage failed
     * verification: mean 25, sigma (10 + 0)/2; times do not depend on the
     * stage. B has no raw stage. */
    assert_string_equal(cell(&o, KITCHEN, "l_p (Mean, rad)", A), "25.000");
    /* k2's one raw path is no spread measured: the sigma is marked. */
    assert_string_equal(cell(&o, KITCHEN, "l_p (sigma, rad)", A), "5.000*");
    assert_non_null(strstr(o.text, "\n* sigma counts a query with one "
                           "successful run as 0 spread\n"));
    /* TABLETOP has no sigma, so no mark. */
    assert_null(strstr(strstr(o.text, "TABLETOP"), "*"));
    assert_non_null(strstr(o.text, "\nompl/RRTConnect: 1 successful run "
                           "whose stage 'raw' failed verification, its path "
                           "metrics not counted above\n"));
    assert_string_equal(cell(&o, KITCHEN, "kappa' (Mean, rad^2)", A), "-");
    assert_string_equal(cell(&o, KITCHEN, "tau_t (Mean, s)", A), "3.200");
    assert_string_equal(cell(&o, KITCHEN, "l_p (Mean, rad)", B), "-");
    assert_string_equal(cell(&o, KITCHEN, "s_r (%)", B), "50.0");
    run(&o, "stdout", "report -f markdown --stage raw -e 1 '%s'", f->db);
    assert_non_null(strstr(o.text, "| l_p (sigma, rad) | 5.000\\* |"));
    assert_non_null(strstr(o.text, "\n\\* sigma counts a query with one "
                           "successful run as 0 spread.\n"));
}

static void the_newest_experiment_is_the_default(void **state)
{
    fixture *f = *state;
    output o;
    run(&o, "stdout", "report '%s'", f->db);
    assert_int_equal(o.status, 0);
    assert_non_null(strstr(o.text,
                           "Scene NARROW_PASSAGE - experiment newer (2), 1 run\n"));
    assert_null(strstr(o.text, "KITCHEN"));
    assert_string_equal(cell(&o, "Scene NARROW_PASSAGE", "tau_t (Mean, s)", 0),
                        "0.250");
    /* Small values keep 3 significant digits rather than print as 0.000. */
    assert_string_equal(cell(&o, "Scene NARROW_PASSAGE", "tau_o (Mean, s)", 0),
                        "0.000400");
}

/*
 * A row whose values span four decades: 0.004895 s and 5.21e-7 s. At the
 * row's 6 decimals the second would keep one digit (0.000001); it keeps
 * three in exponent form. The configuration named with a UTF-8 letter
 * lines up with the rule below it, counted in the columns a terminal
 * gives it (the CJK ones take two), not in bytes.
 */
static void tiny_values_and_wide_names(void **state)
{
    fixture *f = *state;
    char path[128];
    mpb_store *s;
    int64_t exp, cfg[2], scene, query, ids[2];
    snprintf(path, sizeof path, "%s/tiny.db", f->dir);
    assert_int_equal(mpb_store_open(path, 0, &s), MPB_OK);
    mpb_experiment_info e = {"tiny", "t.yaml", "h4", "text", 1, 10.0, NULL, 0};
    assert_int_equal(mpb_store_experiment_create(s, &e, &exp), MPB_OK);
    assert_int_equal(mpb_store_planner_config_add(s, exp, "x/\u8abf\u6574_\u00fc", "x",
                     "tuned", "", &cfg[0]), MPB_OK);
    assert_int_equal(mpb_store_planner_config_add(s, exp, "x/plain", "x",
                     "plain", "", &cfg[1]), MPB_OK);
    mpb_scene_info sc = {"S\u00e4ule", "planar", "r", "r", "planar", "n", "n"};
    assert_int_equal(mpb_store_scene_add(s, exp, &sc, &scene), MPB_OK);
    static const char *const joints[] = {"j"};
    static const double zero[] = {0.0}, one[] = {1.0};
    mpb_query_info q = {"q", 1, joints, zero, MPB_GOAL_JOINTS, one, 0.01,
                        NULL, NULL};
    assert_int_equal(mpb_store_query_add(s, scene, &q, &query), MPB_OK);
    for (int c = 0; c < 2; c++) {
        assert_int_equal(mpb_store_run_add(s, exp, cfg[c], query, 0, c), MPB_OK);
        assert_int_equal(mpb_store_runs_unfinished(s, exp, first_id, &ids[c]), 1);
        /* kappa' 2.17e-30: the rounding a straight path once gave. */
        run_spec r = {0, 0, 0, 1, 1, c ? 5.21e-7 : 0.004895, 0, 0, -1.0, 1.0,
                      c ? 2.17e-30 : 0.0, 2, -1, 0};
        /* The first run of x/plain built the world: 0.508 s, outside its
         * tau_t. */
        if (c == 1)
            next_world_setup = 0.508;
        /* The daemon verified the first configuration's run in 0.25 s. */
        if (c == 0)
            next_verify = 0.25;
        /* ... and its planner peaked at 48.5 MB; the other's said none. */
        if (c == 0)
            next_memory = 48.5;
        finish(s, ids[c], &r);
    }
    mpb_store_close(s);

    output o;
    run(&o, "stdout", "report '%s'", path);
    assert_int_equal(o.status, 0);
    const char *title = "Scene S\u00e4ule - experiment tiny";
    assert_string_equal(cell(&o, title, "tau_t (Mean, s)", 0), "0.004895");
    assert_string_equal(cell(&o, title, "tau_t (Mean, s)", 1), "5.21e-07");
    assert_string_equal(cell(&o, title, "world setup (Mean, s)", 0), "-");
    assert_string_equal(cell(&o, title, "world setup (Mean, s)", 1), "0.508");
    assert_string_equal(cell(&o, title, "verify (Mean, s)", 0), "0.250");
    assert_string_equal(cell(&o, title, "verify (Mean, s)", 1), "-");
    assert_string_equal(cell(&o, title, "memory (Mean, MB)", 0), "48.500");
    assert_string_equal(cell(&o, title, "memory (Mean, MB)", 1), "-");
    /* Rounding noise is no data: 0 beside 0, not 2.17e-30 beside
     * 0.000000. */
    assert_string_equal(cell(&o, title, "kappa' (Mean, rad^2)", 0), "0.000");
    assert_string_equal(cell(&o, title, "kappa' (Mean, rad^2)", 1), "0.000");
    /* The header, the rule and a row: the same number of characters. */
    const char *head = strstr(o.text, "\nMetric");
    assert_non_null(head);
    int widths[3] = {0};
    const char *p = head + 1;
    for (int line = 0; line < 3; line++) {
        for (; *p != '\n'; p++)
            /* A lead byte is a column; U+4000-U+9FFF (E4-E9) two. */
            widths[line] += (((unsigned char)*p & 0xC0) != 0x80) +
                            ((unsigned char)*p >= 0xE4 &&
                             (unsigned char)*p <= 0xE9);
        p++;
    }
    assert_int_equal(widths[0], widths[1]);
    assert_int_equal(widths[2], widths[1]);
}

/* ---- the other formats -------------------------------------------------------- */

/* The part of o's text from the first occurrence of from up to (not
 * including) the first occurrence of to after it, or to the end. */
static const char *section(const output *o, const char *from, const char *to)
{
    static char buf[16384];
    const char *a = strstr(o->text, from);
    assert_non_null(a);
    const char *b = to ? strstr(a + 1, to) : NULL;
    size_t n = b ? (size_t)(b - a) : strlen(a);
    memcpy(buf, a, n);
    buf[n] = '\0';
    return buf;
}

static int count(const char *text, const char *what)
{
    int n = 0;
    for (const char *p = strstr(text, what); p; p = strstr(p + 1, what))
        n++;
    return n;
}

/*
 * Write the report `mpb report ARGS` to f->out, then run python3 on script
 * (read from a file) with f->out as its argument; its stdout in o.
 */
static void python_on_report(fixture *f, output *o, const char *script,
                             const char *args_fmt, ...)
    __attribute__((format(printf, 4, 5)));
static void python_on_report(fixture *f, output *o, const char *script,
                             const char *args_fmt, ...)
{
    char args[512], path[128], cmd[512];
    va_list ap;
    va_start(ap, args_fmt);
    vsnprintf(args, sizeof args, args_fmt, ap);
    va_end(ap);
    output w;
    run(&w, "stdout", "%s >'%s'", args, f->out);
    assert_int_equal(w.status, 0);

    snprintf(path, sizeof path, "%s/check.py", f->dir);
    FILE *py = fopen(path, "w");
    assert_non_null(py);
    fputs(script, py);
    fclose(py);
    snprintf(cmd, sizeof cmd, "python3 '%s' '%s' 2>&1", path, f->out);
    FILE *p = popen(cmd, "r");
    assert_non_null(p);
    size_t n = fread(o->text, 1, sizeof o->text - 1, p);
    o->text[n] = '\0';
    int st = pclose(p);
    assert_true(WIFEXITED(st));
    o->status = WEXITSTATUS(st);
}

static void markdown_has_the_same_tables(void **state)
{
    fixture *f = *state;
    output o;
    run(&o, "stdout", "report --format markdown -e 1 '%s'", f->db);
    assert_int_equal(o.status, 0);
    assert_non_null(strstr(o.text, "# Experiment paper (1)\n\n"));
    assert_non_null(strstr(o.text, "Path metrics of each run's final stage."));

    /* The hand-worked values of the text table, in a pipe table. */
    const char *k = section(&o, "## Scene KITCHEN", "## Scene TABLETOP");
    assert_non_null(strstr(k,
        "## Scene KITCHEN: 8 runs\n\n"
        "| Metric | ompl/RRTConnect | ara/ARAstar |\n"
        "|:---|---:|---:|\n"
        "| tau_t (Mean, s) | 3.200 | 0.500 |\n"
        "| tau_t (sigma, s) | 1.207 | - |\n"
        "| tau_r (Mean, s) | 2.880 | 0.300 |\n"));
    assert_non_null(strstr(k, "| l_p (Mean, rad) | 4.400 | 3.000 |\n"
                              "| l_p (sigma, rad) | 1.000 | - |\n"));
    assert_non_null(strstr(k, "| kappa' (Mean, rad^2) | 0.360 | 1.500 |\n"));
    assert_non_null(strstr(k, "| waypoints (Mean) | 30.0 | 8.0 |\n"
                              "| claimed s_r (%) | "));
    assert_non_null(strstr(k, "|\n| s_r (%) | 83.3 | 50.0 |\n"));
    assert_null(strstr(k, "d_n"));      /* nothing measured it there */
    assert_non_null(strstr(k, "\n1 more run not finished yet, not counted "
                              "above.\n"));
    const char *t = section(&o, "## Scene TABLETOP", "\n### How deep");
    assert_non_null(strstr(t, "## Scene TABLETOP: 1 run\n"));
    assert_non_null(strstr(t, "| d_n (Mean, m) | 0.0500 | - |\n"
                              "| d_n (sigma, m) | - | - |\n"));
    assert_non_null(strstr(t, "| s_r (%) | 100.0 | - |\n"));
    assert_null(strstr(t, "not finished"));
    /* The header, the rule and 15 rows (no l_e: nothing measured it). */
    assert_int_equal(count(t, "\n|"), 21);

    /* Names cannot break the table or turn into emphasis. */
    run(&o, "stdout", "report -f markdown '%s'", f->odd);
    assert_int_equal(o.status, 0);
    assert_non_null(strstr(o.text, "# Experiment odd \"one\" (1)\n"));
    assert_non_null(strstr(o.text, "## Scene S_1 & 50% {#}: 1 run\n"));
    assert_non_null(strstr(o.text, "| Metric | x/a,b\\|c\\*d |\n"));
    assert_non_null(strstr(o.text, "| tau_t (Mean, s) | 2.000 |\n"));
}

static void csv_has_a_row_per_scene_planner_and_metric(void **state)
{
    fixture *f = *state;
    output o;
    run(&o, "stdout", "report --format=csv -e 1 '%s'", f->db);
    assert_int_equal(o.status, 0);
    const char *header =
        "experiment_id,experiment,scene,planner,metric,unit,mean,sigma,n,"
        "unfinished,sigma_single\n";
    assert_int_equal(strncmp(o.text, header, strlen(header)), 0);
    /* 2 scenes x 2 configurations x (15 metrics + the success rate and
     * the claimed one + 5 outcomes), and the header: always the same
     * rows, empty where nothing was measured. */
    assert_int_equal(count(o.text, "\n"), 1 + 2 * 2 * 22);
    /* tau_t of A on KITCHEN: mean 16/5, sigma (1 + sqrt 2)/2 over 5 runs */
    assert_non_null(strstr(o.text, "\n1,paper,KITCHEN,ompl/RRTConnect,"
                                   "time_total,s,3.2,1.20710678118655,5,1,0\n"));
    assert_non_null(strstr(o.text, "\n1,paper,KITCHEN,ompl/RRTConnect,"
                                   "path_length,rad,4.4,1,5,1,0\n"));
    assert_non_null(strstr(o.text, "\n1,paper,KITCHEN,ompl/RRTConnect,"
                                   "waypoints,,30,"));
    /* 5 of 6 finished runs; B: 1 of 2. */
    assert_non_null(strstr(o.text, "\n1,paper,KITCHEN,ompl/RRTConnect,"
                                   "success_rate,,0.833333333333333,,6,1,\n"));
    assert_non_null(strstr(o.text, "\n1,paper,KITCHEN,ara/ARAstar,"
                                   "success_rate,,0.5,,2,1,\n"));
    assert_non_null(strstr(o.text, "\n1,paper,KITCHEN,ara/ARAstar,"
                                   "time_total,s,0.5,,1,1,\n"));
    /* Claims: B's K2 run claimed, its final stage refused. */
    assert_non_null(strstr(o.text, "\n1,paper,KITCHEN,ara/ARAstar,"
                                   "refused_runs,,1,,2,1,\n"));
    assert_non_null(strstr(o.text, "\n1,paper,KITCHEN,ara/ARAstar,"
                                   "verified_runs,,1,,2,1,\n"));
    /* Not measured, never run: empty values, n = 0. */
    assert_non_null(strstr(o.text, "\n1,paper,KITCHEN,ompl/RRTConnect,"
                                   "clearance,m,,,0,1,\n"));
    assert_non_null(strstr(o.text, "\n1,paper,TABLETOP,ompl/RRTConnect,"
                                   "clearance,m,0.05,,1,0,\n"));
    assert_non_null(strstr(o.text, "\n1,paper,TABLETOP,ara/ARAstar,"
                                   "time_total,s,,,0,0,\n"));
    assert_non_null(strstr(o.text, "\n1,paper,TABLETOP,ara/ARAstar,"
                                   "success_rate,,,,0,0,\n"));
    /* --stage changes the path metrics only. */
    run(&o, "stdout", "report -f csv -e 1 --stage raw '%s'", f->db);
    assert_non_null(strstr(o.text, "\n1,paper,KITCHEN,ompl/RRTConnect,"
                                   "path_length,rad,25,5,4,1,1\n"));
    /* ... where K2 keeps one valid raw stage: its 0 spread is marked. */
    assert_non_null(strstr(o.text, "\n1,paper,KITCHEN,ompl/RRTConnect,"
                                   "time_total,s,3.2,1.20710678118655,5,1,0\n"));

    /* A CSV reader gets the names back whole. */
    python_on_report(f, &o,
        "import csv, sys\n"
        "rows = list(csv.DictReader(open(sys.argv[1], newline='')))\n"
        "print(len(rows))\n"
        "r = rows[0]\n"
        "print('|'.join([r['experiment'], r['scene'], r['planner'],\n"
        "                r['metric'], r['mean'], r['n']]))\n",
        "report -f csv '%s'", f->odd);
    assert_int_equal(o.status, 0);
    assert_string_equal(o.text, "22\nodd \"one\"|S_1 & 50% {#}|x/a,b|c*d|"
                                "time_total|2|1\n");
}

static void latex_has_a_tabular_per_scene(void **state)
{
    fixture *f = *state;
    output o;
    run(&o, "stdout", "report -f latex -e 1 '%s'", f->db);
    assert_int_equal(o.status, 0);
    assert_int_equal(count(o.text, "\\begin{table}[htbp]"), 2);
    assert_int_equal(count(o.text, "\\end{table}"), 2);
    assert_int_equal(count(o.text, "\\begin{tabular}{l|rr}"), 2);
    const char *k = section(&o, "\\caption{KITCHEN", "\\end{table}");
    assert_non_null(strstr(k, "\\caption{KITCHEN: experiment paper, 8 runs "
                              "(1 more not finished yet, not counted). "));
    assert_non_null(strstr(k, "\\label{tab:mpb-paper-KITCHEN}\n"));
    assert_non_null(strstr(k,
        "    Metric & ompl/RRTConnect & ara/ARAstar \\\\\n"
        "    \\hline\n"
        "    $\\tau_t$ (Mean, s) & 3.200 & 0.500 \\\\\n"
        "    $\\tau_t$ ($\\sigma$, s) & 1.207 & -- \\\\\n"));
    assert_non_null(strstr(k, "    $\\kappa'$ (Mean, rad$^2$) & 0.360 & "
                              "1.500 \\\\\n"));
    assert_non_null(strstr(k, "    $s_r$ (\\%) & 83.3 & 50.0 \\\\\n"
                              "    claimed & 6 & 2 \\\\\n"
                              "    verified & 5 & 1 \\\\\n"
                              "    refused claims & 1 & 1 \\\\\n"
                              "    unclaimed valid & 0 & 0 \\\\\n"
                              "    \\hline\n  \\end{tabular}\n"));
    assert_null(strstr(k, "$d_n$"));
    const char *t = section(&o, "\\caption{TABLETOP", "\\end{table}");
    assert_non_null(strstr(t, "\\caption{TABLETOP: experiment paper, 1 run. "));
    assert_non_null(strstr(t, "    $d_n$ (Mean, m) & 0.0500 & -- \\\\\n"));
    assert_non_null(strstr(t, "    $s_r$ (\\%) & 100.0 & -- \\\\\n"));

    /* TeX's specials in names are escaped; the label keeps to [A-Za-z0-9-]. */
    run(&o, "stdout", "report -f latex '%s'", f->odd);
    assert_int_equal(o.status, 0);
    assert_non_null(strstr(o.text, "\\caption{S\\_1 \\& 50\\% \\{\\#\\}: "
                                   "experiment odd \"one\", 1 run. "));
    assert_non_null(strstr(o.text, "\\label{tab:mpb-odd--one--S-1---50-----}"));
    assert_non_null(strstr(o.text, "    Metric & x/a,b\\textbar{}c*d \\\\\n"));
}

static void json_holds_every_number_by_name(void **state)
{
    fixture *f = *state;
    output o;
    python_on_report(f, &o,
        "import json, sys\n"
        "d = json.load(open(sys.argv[1]))\n"
        "e = d['experiment']\n"
        "print(d['mpbench_report'], e['id'], e['name'], e['runs_per_query'],\n"
        "      float(e['time_limit']), d['stage'], d['units']['smoothness'])\n"
        "for s in d['scenes']:\n"
        "    print(s['name'], s['runs'], s['unfinished'])\n"
        "    for p in s['planners']:\n"
        "        print(' ', p['name'], p['planner'], p['algorithm'],\n"
        "              p['params'], p['runs'], p['successes'],\n"
        "              None if p['success_rate'] is None\n"
        "              else round(float(p['success_rate']), 6))\n"
        "        for k, m in p['metrics'].items():\n"
        "            f = lambda x: None if x is None else round(float(x), 6)\n"
        "            print('   ', k, f(m['mean']), f(m['sigma']), m['n'],\n"
        "                  m['sigma_single'])\n",
        "report --format json --experiment 1 '%s'", f->db);
    assert_int_equal(o.status, 0);
    /* The values of the text tables above, unrounded; never-run and
     * unmeasured metrics are null with n = 0. */
    assert_string_equal(o.text,
        "1 1 paper 3 60.0 None rad^2\n"
        "KITCHEN 8 1\n"
        "  ompl/RRTConnect ompl RRTConnect  6 5 0.833333\n"
        "    time_total 3.2 1.207107 5 0\n"
        "    time_raw 2.88 1.086396 5 0\n"
        "    time_other 0.32 0.120711 5 0\n"
        "    world_setup_time None None 0 None\n"
        "    verify_time None None 0 None\n"
        "    memory None None 0 None\n"
        "    clearance None None 0 None\n"
        "    path_length 4.4 1.0 5 0\n"
        "    ee_path_length None None 0 None\n"
        "    smoothness 0.36 0.120711 5 0\n"
        "    smoothness_resampled None None 0 None\n"
        "    waypoints 30.0 8.535534 5 0\n"
        "    duration None None 0 None\n"
        "    max_velocity None None 0 None\n"
        "    max_acceleration None None 0 None\n"
        "  ara/ARAstar ara ARAstar eps=100 2 1 0.5\n"
        "    time_total 0.5 None 1 None\n"
        "    time_raw 0.3 None 1 None\n"
        "    time_other 0.2 None 1 None\n"
        "    world_setup_time None None 0 None\n"
        "    verify_time None None 0 None\n"
        "    memory None None 0 None\n"
        "    clearance None None 0 None\n"
        "    path_length 3.0 None 1 None\n"
        "    ee_path_length None None 0 None\n"
        "    smoothness 1.5 None 1 None\n"
        "    smoothness_resampled None None 0 None\n"
        "    waypoints 8.0 None 1 None\n"
        "    duration None None 0 None\n"
        "    max_velocity None None 0 None\n"
        "    max_acceleration None None 0 None\n"
        "TABLETOP 1 0\n"
        "  ompl/RRTConnect ompl RRTConnect  1 1 1.0\n"
        "    time_total 7.0 None 1 None\n"
        "    time_raw 6.0 None 1 None\n"
        "    time_other 1.0 None 1 None\n"
        "    world_setup_time None None 0 None\n"
        "    verify_time None None 0 None\n"
        "    memory None None 0 None\n"
        "    clearance 0.05 None 1 None\n"
        "    path_length 8.0 None 1 None\n"
        "    ee_path_length None None 0 None\n"
        "    smoothness 0.4 None 1 None\n"
        "    smoothness_resampled None None 0 None\n"
        "    waypoints 12.0 None 1 None\n"
        "    duration None None 0 None\n"
        "    max_velocity None None 0 None\n"
        "    max_acceleration None None 0 None\n"
        "  ara/ARAstar ara ARAstar eps=100 0 0 None\n"
        "    time_total None None 0 None\n"
        "    time_raw None None 0 None\n"
        "    time_other None None 0 None\n"
        "    world_setup_time None None 0 None\n"
        "    verify_time None None 0 None\n"
        "    memory None None 0 None\n"
        "    clearance None None 0 None\n"
        "    path_length None None 0 None\n"
        "    ee_path_length None None 0 None\n"
        "    smoothness None None 0 None\n"
        "    smoothness_resampled None None 0 None\n"
        "    waypoints None None 0 None\n"
        "    duration None None 0 None\n"
        "    max_velocity None None 0 None\n"
        "    max_acceleration None None 0 None\n");

    /* In the raw stage K2 keeps one valid run: path_length's sigma counts
     * that query as 0 spread, and says so. */
    python_on_report(f, &o,
        "import json, sys\n"
        "d = json.load(open(sys.argv[1]))\n"
        "m = d['scenes'][0]['planners'][0]['metrics']['path_length']\n"
        "print(m['n'], m['sigma'], m['sigma_single'])\n",
        "report -f json -e 1 --stage raw '%s'", f->db);
    assert_int_equal(o.status, 0);
    assert_string_equal(o.text, "4 5 1\n");

    /* A stage asked for is named; strings are escaped. */
    python_on_report(f, &o,
        "import json, sys\n"
        "d = json.load(open(sys.argv[1]))\n"
        "p = d['scenes'][0]['planners'][0]\n"
        "print(d['stage'], d['experiment']['name'], d['scenes'][0]['name'],\n"
        "      p['name'], float(p['metrics']['time_total']['mean']))\n",
        "report -f json --stage 'raw\"\\' '%s'", f->odd);
    assert_int_equal(o.status, 0);
    assert_string_equal(o.text, "raw\"\\ odd \"one\" S_1 & 50% {#} "
                                "x/a,b|c*d 2.0\n");
}

/* ---- errors and help --------------------------------------------------------- */

static void a_missing_file_is_one_line_and_exit_1(void **state)
{
    (void)state;
    output o;
    run(&o, "stderr", "report /nonexistent/nosuch.db");
    assert_int_equal(o.status, 1);
    assert_string_equal(o.text, "mpb report: cannot open "
                                "/nonexistent/nosuch.db: No such file or "
                                "directory\n");
    run(&o, "stdout", "report /nonexistent/nosuch.db");
    assert_string_equal(o.text, "");
}

static void what_is_not_a_report_says_so(void **state)
{
    fixture *f = *state;
    output o;

    run(&o, "stderr", "report '%s'", f->text);
    assert_int_equal(o.status, 1);
    char want[256];
    snprintf(want, sizeof want, "mpb report: %s is not an mpbench database: "
             "not an SQLite file\n", f->text);
    assert_string_equal(o.text, want);
    assert_int_equal(strchr(o.text, '\n') - o.text + 1, (int)strlen(o.text));

    run(&o, "stderr", "report '%s'", f->empty);
    assert_int_equal(o.status, 1);
    snprintf(want, sizeof want, "mpb report: %s holds no experiment yet\n",
             f->empty);
    assert_string_equal(o.text, want);

    run(&o, "stderr", "report --experiment 99 '%s'", f->db);
    assert_int_equal(o.status, 1);
    snprintf(want, sizeof want, "mpb report: %s has no experiment 99\n", f->db);
    assert_string_equal(o.text, want);
}

static void bad_command_lines_exit_2(void **state)
{
    fixture *f = *state;
    output o;
    run(&o, "stderr", "report");
    assert_int_equal(o.status, 2);
    assert_non_null(strstr(o.text, "mpb report: "));
    run(&o, "stderr", "report --bogus '%s'", f->db);
    assert_int_equal(o.status, 2);
    assert_non_null(strstr(o.text, "--bogus"));
    run(&o, "stderr", "report --experiment");
    assert_int_equal(o.status, 2);
    run(&o, "stderr", "report --experiment one '%s'", f->db);
    assert_int_equal(o.status, 2);
    run(&o, "stderr", "report '%s' '%s'", f->db, f->db);
    assert_int_equal(o.status, 2);
    run(&o, "stderr", "report --format xml '%s'", f->db);
    assert_int_equal(o.status, 2);
    assert_string_equal(o.text, "mpb report: unknown format 'xml' (text, "
                                "markdown, csv, latex, json or html)\n");
    run(&o, "stderr", "report --format");
    assert_int_equal(o.status, 2);
    run(&o, "stderr", "nosuchcommand");
    assert_int_equal(o.status, 2);
    assert_non_null(strstr(o.text, "unknown command 'nosuchcommand'"));
    run(&o, "stderr", "%s", "");
    assert_int_equal(o.status, 2);
}

/* One run of a configuration of the approach experiment: the planner's
 * status, its final stage's verdict and mpbench's success. */
static void finish_claim(mpb_store *s, int64_t run_id, const char *status,
                         int valid, int success)
{
    char uid[32];
    snprintf(uid, sizeof uid, "uid-%lld", (long long)run_id);
    assert_int_equal(mpb_store_run_sent(s, run_id, uid, "planner-1"), MPB_OK);
    mpb_named m[] = {{"path_length", 1.0}, {"time", 0.01}};
    mpb_stage_record st = {.name = "raw", .valid = valid,
                           .verdict = valid ? "valid" : "collision",
                           .verdict_segment = -1, .num_metrics = 2,
                           .metrics = m};
    mpb_run_record rec = {
        .run_id = run_id, .run_uid = uid, .planner_id = "planner-1",
        .status = status, .claimed_success = strcmp(status, "solved") == 0,
        .success = success, .time_total = 0.5, .time_raw = 0.5,
        .time_other = 0, .num_stages = 1, .stages = &st,
        .verify_time = NAN, .memory = NAN,
    };
    assert_int_equal(mpb_store_run_finish(s, &rec), MPB_OK);
}

static int each_run(void *ud, const mpb_run_row *row)
{
    int64_t (*ids)[2] = ud;
    ids[row->planner_config_id - 1][row->repetition] = row->id;
    return 0;
}

/*
 * Columns grouped and labelled by approach (sampling, search,
 * optimisation, hybrid, then none), whatever the order of the
 * configurations' ids; the claims counted both ways; the findings name
 * the best configuration of each approach from the data.
 */
static void columns_are_grouped_by_approach_and_claims_counted(void **state)
{
    fixture *f = *state;
    char db[128];
    mpb_store *s;
    int64_t exp, scene, query, cfg[4], ids[4][2] = {{0}};
    snprintf(db, sizeof db, "%s/approach.db", f->dir);
    assert_int_equal(mpb_store_open(db, 0, &s), MPB_OK);
    mpb_experiment_info e = {"kinds", "k.yaml", "h4", "text", 2, 10.0, NULL, 0};
    assert_int_equal(mpb_store_experiment_create(s, &e, &exp), MPB_OK);
    static const char *const names[4][3] = {
        {"null/straight_line", "null", NULL},
        {"srmp/wAstar", "srmp", "search"},
        {"klampt/sbl", "klampt", "sampling"},
        {"drake/KTO", "drake", "optimisation"},
    };
    for (int c = 0; c < 4; c++) {
        assert_int_equal(mpb_store_planner_config_add(s, exp, names[c][0],
                             names[c][1], strchr(names[c][0], '/') + 1, "",
                             &cfg[c]), MPB_OK);
        assert_int_equal(cfg[c], c + 1);
        if (names[c][2] != NULL)
            assert_int_equal(mpb_store_planner_config_set_approach(s, cfg[c],
                                 names[c][2], c == 1), MPB_OK);
    }
    /* A planner's word does not replace the file's: kept. */
    assert_int_equal(mpb_store_planner_config_set_approach(s, cfg[1],
                                                           "hybrid", 1),
                     MPB_OK);
    mpb_scene_info sc = {"wall", "planar", "r", "r", "planar", "w", "w"};
    assert_int_equal(mpb_store_scene_add(s, exp, &sc, &scene), MPB_OK);
    static const char *const joints[] = {"j"};
    static const double zero[] = {0.0}, one[] = {1.0};
    mpb_query_info q = {"w1", 1, joints, zero, MPB_GOAL_JOINTS, one, 0.01,
                        NULL, NULL};
    assert_int_equal(mpb_store_query_add(s, scene, &q, &query), MPB_OK);
    for (int c = 0; c < 4; c++)
        for (int rep = 0; rep < 2; rep++)
            assert_int_equal(mpb_store_run_add(s, exp, cfg[c], query, rep,
                                               rep), MPB_OK);
    assert_int_equal(mpb_store_runs_unfinished(s, exp, each_run, ids), MPB_OK);
    /* null: failed by its word, valid by mpbench's, twice. */
    finish_claim(s, ids[0][0], "failed", 1, 0);
    finish_claim(s, ids[0][1], "approximate", 1, 0);
    /* srmp: verified, then a claim refused. */
    finish_claim(s, ids[1][0], "solved", 1, 1);
    finish_claim(s, ids[1][1], "solved", 0, 0);
    /* klampt: verified twice. */
    finish_claim(s, ids[2][0], "solved", 1, 1);
    finish_claim(s, ids[2][1], "solved", 1, 1);
    /* drake: "infeasible" with a valid path, and a plain failure. */
    finish_claim(s, ids[3][0], "failed", 1, 0);
    finish_claim(s, ids[3][1], "failed", 0, 0);
    mpb_store_close(s);

    output o;
    run(&o, "stdout", "report --findings '%s'", db);
    assert_int_equal(o.status, 0);
    const char *approach = strstr(o.text, "\nApproach ");
    const char *metric = strstr(o.text, "\nMetric ");
    assert_non_null(approach);
    assert_non_null(metric);
    assert_true(approach < metric);
    /* sampling, search, optimisation, then the one that declares none,
     * each label over its column. */
    const char *a1 = strstr(approach, "sampling"), *a2 = strstr(approach, "search"),
               *a3 = strstr(approach, "optimisation"), *a4 = strstr(approach + 1, " -\n");
    assert_true(a1 && a2 && a3 && a4 && a1 < a2 && a2 < a3 && a3 < a4 &&
                a4 < metric);
    const char *m1 = strstr(metric, "klampt/sbl"), *m2 = strstr(metric, "srmp/wAstar"),
               *m3 = strstr(metric, "drake/KTO"), *m4 = strstr(metric, "null/straight_line");
    assert_true(m1 && m2 && m3 && m4 && m1 < m2 && m2 < m3 && m3 < m4);
    /* The counts, in that column order (the text's runs of spaces as
     * one). */
    static char sq[sizeof o.text];
    size_t n = 0;
    for (const char *p = o.text; *p; p++)
        if (!(*p == ' ' && n > 0 && sq[n - 1] == ' '))
            sq[n++] = *p;
    sq[n] = '\0';
    assert_non_null(strstr(sq, "\nclaimed 2 2 0 0\n"));
    assert_non_null(strstr(sq, "\nverified 2 1 0 0\n"));
    assert_non_null(strstr(sq, "\nrefused claims 0 1 0 0\n"));
    assert_non_null(strstr(sq, "\nunclaimed valid 0 0 1 2\n"));
    /* s_r stays the claims confirmed: the unclaimed valid paths are no
     * successes. */
    assert_non_null(strstr(sq, "\ns_r (%) 100.0 50.0 0.0 0.0\n"));
    assert_non_null(strstr(o.text, "best by approach: sampling klampt/sbl "
                                   "(success 100%, tau_t 0.5 s, 2 verified "
                                   "of 2 claimed, 0 unclaimed valid); search "
                                   "srmp/wAstar (success 50%, tau_t 0.5 s, 1 "
                                   "verified of 2 claimed, 0 unclaimed "
                                   "valid); optimisation none solved a run.\n"));
    /* The search-based planner of the paper's findings is the one of
     * approach search, whatever its family. */
    assert_non_null(strstr(o.text, "wall: sigma(l_p) - (no query run twice); "
                                   "l_p 1 rad, next klampt/sbl (1 rad)"));
    run(&o, "stdout", "report -f json '%s'", db);
    assert_int_equal(o.status, 0);
    assert_non_null(strstr(o.text, "\"approach\": \"sampling\""));
    assert_non_null(strstr(o.text, "\"approach\": null"));
    assert_non_null(strstr(o.text, "\"outcomes\": {\"unclaimed\": 1, "
                                   "\"verified\": 0, \"refused\": 0, "
                                   "\"late\": 0, \"unclaimed_valid\": 1}"));
    run(&o, "stdout", "report -f csv '%s'", db);
    assert_non_null(strstr(o.text, "\n1,kinds,wall,null/straight_line,"
                                   "unclaimed_valid_runs,,2,,2,0,\n"));
    run(&o, "stdout", "report -f markdown '%s'", db);
    assert_non_null(strstr(o.text, "| approach | sampling | search | "
                                   "optimisation | - |\n"));
}

static void help_is_clear(void **state)
{
    (void)state;
    output o;
    run(&o, "stdout", "--help");
    assert_int_equal(o.status, 0);
    assert_non_null(strstr(o.text, "usage: mpb COMMAND"));
    assert_non_null(strstr(o.text, "  report "));

    run(&o, "stdout", "report --help");
    assert_int_equal(o.status, 0);
    assert_non_null(strstr(o.text, "usage: mpb report [--experiment ID] "
                                   "[--stage NAME] [--format FORMAT]\n"
                                   "                  [--by set|scene|all] "
                                   "[--findings] [-o FILE] DB\n"));
    assert_non_null(strstr(o.text, "  -o, --output FILE    write the report to "
                                   "FILE"));
    assert_non_null(strstr(o.text, "views/run-ID.html"));
    /* Every format is listed, html with what it writes. */
    assert_non_null(strstr(o.text, "scene), json, or html: one self-contained "
                                   "page\n"));
    assert_non_null(strstr(o.text, "mpb plot as SVG"));
    assert_non_null(strstr(o.text, "its mpb view page"));
    assert_non_null(strstr(o.text, "--format FORMAT"));
    assert_non_null(strstr(o.text, "--stage NAME"));

    output h;
    run(&h, "stdout", "help report");
    assert_int_equal(h.status, 0);
    assert_string_equal(h.text, o.text);
}

int main(void)
{
    if (test_built_program("tools/mpb", mpb_tool, sizeof mpb_tool) != 0)
        return 1;

    const struct CMUnitTest tests[] = {
        cmocka_unit_test(the_kitchen_table_matches_the_hand_computed_values),
        cmocka_unit_test(a_second_scene_has_its_own_table),
        cmocka_unit_test(a_chosen_stage_gives_its_own_metrics),
        cmocka_unit_test(the_newest_experiment_is_the_default),
        cmocka_unit_test(tiny_values_and_wide_names),
        cmocka_unit_test(markdown_has_the_same_tables),
        cmocka_unit_test(csv_has_a_row_per_scene_planner_and_metric),
        cmocka_unit_test(latex_has_a_tabular_per_scene),
        cmocka_unit_test(json_holds_every_number_by_name),
        cmocka_unit_test(a_missing_file_is_one_line_and_exit_1),
        cmocka_unit_test(what_is_not_a_report_says_so),
        cmocka_unit_test(bad_command_lines_exit_2),
        cmocka_unit_test(columns_are_grouped_by_approach_and_claims_counted),
        cmocka_unit_test(help_is_clear),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
