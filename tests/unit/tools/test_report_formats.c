/* test_report_formats.c - `mpb report`'s other formats (Markdown, CSV,
 * LaTeX, JSON), run as a user runs it on the databases of
 * test_report_paper.h: the same numbers as the text tables, and names
 * escaped as each format needs. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "test_report_paper.h"

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

int main(void)
{
    if (test_built_program("tools/mpb", mpb_tool, sizeof mpb_tool) != 0)
        return 1;

    const struct CMUnitTest tests[] = {
        cmocka_unit_test(markdown_has_the_same_tables),
        cmocka_unit_test(csv_has_a_row_per_scene_planner_and_metric),
        cmocka_unit_test(latex_has_a_tabular_per_scene),
        cmocka_unit_test(json_holds_every_number_by_name),
    };
    return cmocka_run_group_tests(tests, setup, test_store_teardown);
}
