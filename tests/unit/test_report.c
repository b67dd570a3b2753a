/* test_report.c - `mpb report`, run as a user runs it: the built tool on a
 * database written through the store, its printed numbers checked against
 * values worked out by hand, and its errors. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"

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
} run_spec;

static const run_spec runs[] = {
    /* cfg q  rep done ok  total raw   other raw_len len   smooth wp  clear */
    {A, K1, 0, 1, 1, 1.0,  0.9,  0.1, 10.0, 2.0,  0.1,  10, -1},
    {A, K2, 0, 1, 1, 4.0,  3.6,  0.4, 40.0, 5.0,  0.5,  40, -1},
    {B, K1, 0, 1, 1, 0.5,  0.3,  0.2, -1.0, 3.0,  1.5,  8,  -1},
    {A, K1, 1, 1, 1, 2.0,  1.8,  0.2, 20.0, 4.0,  0.2,  20, -1},
    {A, K2, 1, 1, 1, 6.0,  5.4,  0.6, 60.0, 5.0,  0.7,  50, -1},
    {B, K2, 0, 1, 0, 0.7,  0.5,  0.2, -1.0, 77.0, 7.7,  77, -1},
    {A, K1, 2, 1, 1, 3.0,  2.7,  0.3, 30.0, 6.0,  0.3,  30, -1},
    {A, K2, 2, 1, 0, 60.0, 59.5, 0.5, -1.0, 99.0, 9.9,  99, -1},
    {A, T1, 0, 1, 1, 7.0,  6.0,  1.0, -1.0, 8.0,  0.4,  12, 0.05},
    {B, K2, 1, 0, 0, 0.0,  0.0,  0.0, -1.0, 0.0,  0.0,  0,  -1},
};
#define NUM_RUNS ((int)(sizeof runs / sizeof runs[0]))

typedef struct fixture {
    char    dir[64];
    char    db[96];             /* the two experiments */
    char    empty[96];          /* a database with no experiment */
    char    text[96];           /* not a database */
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
        {.name = "raw", .valid = 1, .verdict = "valid", .verdict_segment = -1,
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
    };
    assert_int_equal(mpb_store_run_finish(s, &rec), MPB_OK);
}

static void write_paper(fixture *f, mpb_store *s)
{
    int64_t exp, scene[2];
    mpb_experiment_info e = {"paper", "paper.yaml", "h1", "text", 3, 60.0};
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
                            0.01};
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
    mpb_experiment_info e = {"newer", "newer.yaml", "h2", "text", 1, 10.0};
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
    mpb_query_info q = {"n1", 1, joints, zero, MPB_GOAL_JOINTS, one, 0.01};
    assert_int_equal(mpb_store_query_add(s, scene, &q, &query), MPB_OK);
    assert_int_equal(mpb_store_run_add(s, exp, cfg, query, 0, 1), MPB_OK);
    assert_int_equal(mpb_store_runs_unfinished(s, exp, first_id, &run), 1);
    run_spec r = {0, 0, 0, 1, 1, 0.25, 0.2496, 0.0004, -1.0, 1.0, 0.0, 2, -1};
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

    assert_int_equal(mpb_store_open(f->db, 0, &s), MPB_OK);
    write_paper(f, s);
    write_newer(s);
    mpb_store_close(s);

    assert_int_equal(mpb_store_open(f->empty, 0, &s), MPB_OK);
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

typedef struct output {
    char text[16384];
    int  status;                /* exit status */
} output;

/* Run `mpb ARGS` with the shell; keep stdout, stderr or both (which). */
static void run(output *o, const char *which, const char *fmt, ...)
{
    char args[1024], cmd[6144];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(args, sizeof args, fmt, ap);
    va_end(ap);
    snprintf(cmd, sizeof cmd, "'%s' %s %s", mpb_tool, args,
             strcmp(which, "stdout") == 0   ? "2>/dev/null"
             : strcmp(which, "stderr") == 0 ? "2>&1 >/dev/null"
                                            : "2>&1");
    FILE *p = popen(cmd, "r");
    assert_non_null(p);
    size_t n = fread(o->text, 1, sizeof o->text - 1, p);
    o->text[n] = '\0';
    int st = pclose(p);
    assert_true(WIFEXITED(st));
    o->status = WEXITSTATUS(st);
}

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
     * k2 failed with l_p 77, which must not show. One sample per query:
     * sigma 0. */
    assert_string_equal(cell(&o, KITCHEN, "tau_t (Mean, s)", B), "0.500");
    assert_string_equal(cell(&o, KITCHEN, "tau_t (sigma, s)", B), "0.000");
    assert_string_equal(cell(&o, KITCHEN, "tau_r (Mean, s)", B), "0.300");
    assert_string_equal(cell(&o, KITCHEN, "tau_o (Mean, s)", B), "0.200");
    assert_string_equal(cell(&o, KITCHEN, "l_p (Mean, rad)", B), "3.000");
    assert_string_equal(cell(&o, KITCHEN, "l_p (sigma, rad)", B), "0.000");
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
    assert_string_equal(cell(&o, TABLETOP, "tau_t (sigma, s)", A), "0.000");
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
    /* A's raw lengths 10, 20, 30 | 40, 60: mean 32, sigma (10 + 14.1421)/2;
     * times do not depend on the stage. B has no raw stage. */
    assert_string_equal(cell(&o, KITCHEN, "l_p (Mean, rad)", A), "32.000");
    assert_string_equal(cell(&o, KITCHEN, "l_p (sigma, rad)", A), "12.071");
    assert_string_equal(cell(&o, KITCHEN, "kappa' (Mean, rad^2)", A), "-");
    assert_string_equal(cell(&o, KITCHEN, "tau_t (Mean, s)", A), "3.200");
    assert_string_equal(cell(&o, KITCHEN, "l_p (Mean, rad)", B), "-");
    assert_string_equal(cell(&o, KITCHEN, "s_r (%)", B), "50.0");
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
    assert_non_null(strstr(o.text, "mpb report: cannot open "));
    assert_non_null(strstr(o.text, "not an mpbench database"));
    assert_int_equal(strchr(o.text, '\n') - o.text + 1, (int)strlen(o.text));

    run(&o, "stderr", "report '%s'", f->empty);
    assert_int_equal(o.status, 1);
    char want[256];
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
    run(&o, "stderr", "nosuchcommand");
    assert_int_equal(o.status, 2);
    assert_non_null(strstr(o.text, "unknown command 'nosuchcommand'"));
    run(&o, "stderr", "");
    assert_int_equal(o.status, 2);
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
                                   "[--stage NAME] DB"));
    assert_non_null(strstr(o.text, "--stage NAME"));

    output h;
    run(&h, "stdout", "help report");
    assert_int_equal(h.status, 0);
    assert_string_equal(h.text, o.text);
}

int main(void)
{
    const char *build = getenv("MPB_BUILD");
    if (build != NULL) {
        snprintf(mpb_tool, sizeof mpb_tool, "%s/tools/mpb", build);
    } else {
        /* This test is BUILD/tests/test_report; the tool BUILD/tools/mpb. */
        char self[2048];
        ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
        if (n <= 0) {
            fprintf(stderr, "test_report: cannot find myself; set MPB_BUILD\n");
            return 1;
        }
        self[n] = '\0';
        snprintf(mpb_tool, sizeof mpb_tool, "%s/../tools/mpb", dirname(self));
    }
    if (access(mpb_tool, X_OK) != 0) {
        fprintf(stderr, "test_report: no mpb at %s (build it first)\n",
                mpb_tool);
        return 1;
    }

    const struct CMUnitTest tests[] = {
        cmocka_unit_test(the_kitchen_table_matches_the_hand_computed_values),
        cmocka_unit_test(a_second_scene_has_its_own_table),
        cmocka_unit_test(a_chosen_stage_gives_its_own_metrics),
        cmocka_unit_test(the_newest_experiment_is_the_default),
        cmocka_unit_test(a_missing_file_is_one_line_and_exit_1),
        cmocka_unit_test(what_is_not_a_report_says_so),
        cmocka_unit_test(bad_command_lines_exit_2),
        cmocka_unit_test(help_is_clear),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
