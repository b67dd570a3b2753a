/*
 * report_rows.c - the rows of `mpb report`'s tables, in the paper's
 * order (the run's times, the list's metrics, success and claims), and
 * the metrics' names in the machine-readable formats. Every format
 * (report_cells.c and the writers) walks report_rows.
 */
#include <stdio.h>
#include <string.h>

#include "report.h"

const metric_info report_metrics[M_COUNT] = {
    [M_TT] = {"time_total", "s"},
    [M_TR] = {"time_raw", "s"},
    [M_TO] = {"time_other", "s"},
    [M_WS] = {"world_setup_time", "s"},
    [M_VT] = {"verify_time", "s"},
    [M_MEM] = {"memory", "MB"},
#define METRIC_KEY(id, name, unit, ...) \
    [FIRST_STORED + MPB_METRIC_##id] = {name, unit},
    MPB_METRIC_MAP(METRIC_KEY)
#undef METRIC_KEY
};

int report_metric_shown(int k)
{
    return k < FIRST_STORED ||
           (mpb_metric_info_of(k - FIRST_STORED)->flags & MPB_METRIC_F_TABLE);
}

/* The run's times, rows of their own; the metrics' rows follow. */
static const table_row time_rows[] = {
    {"tau_t (Mean, s)",       "$\\tau_t$ (Mean, s)",            M_TT,    SHOW_MEAN,  0, -1, 0},
    {"tau_t (sigma, s)",      "$\\tau_t$ ($\\sigma$, s)",       M_TT,    SHOW_SIGMA, 0, -1, 0},
    {"tau_r (Mean, s)",       "$\\tau_r$ (Mean, s)",            M_TR,    SHOW_MEAN,  0, -1, 0},
    {"tau_r (sigma, s)",      "$\\tau_r$ ($\\sigma$, s)",       M_TR,    SHOW_SIGMA, 0, -1, 0},
    {"tau_o (Mean, s)",       "$\\tau_o$ (Mean, s)",            M_TO,    SHOW_MEAN,  0, -1, 0},
    {"tau_o (sigma, s)",      "$\\tau_o$ ($\\sigma$, s)",       M_TO,    SHOW_SIGMA, 0, -1, 0},
    {"world setup (Mean, s)", "world setup (Mean, s)",         M_WS,    SHOW_MEAN,  1, -1, 0},
    {"verify (Mean, s)",      "verify (Mean, s)",              M_VT,    SHOW_MEAN,  1, -1, 0},
    {"memory (Mean, MB)",     "memory (Mean, MB)",             M_MEM,   SHOW_MEAN,  1, -1, 0},
};
#define NUM_TIME_ROWS ((int)(sizeof time_rows / sizeof time_rows[0]))

table_row report_rows[REPORT_MAX_ROWS];
int report_num_rows;

/* The labels of the metrics' rows, made once from the list. */
static char row_text[REPORT_MAX_ROWS][2][80];

/* A unit in LaTeX: "rad^2" as "rad$^2$". */
static void latex_unit(char *out, size_t size, const char *unit)
{
    const char *hat = strchr(unit, '^');
    if (hat == NULL)
        snprintf(out, size, "%s", unit);
    else
        snprintf(out, size, "%.*s$^%s$", (int)(hat - unit), unit, hat + 1);
}

static void add_metric_row(int id, show what)
{
    const mpb_metric_info *mi = mpb_metric_info_of(id);
    int i = report_num_rows++;
    const char *kind = what == SHOW_MEAN ? "Mean" : "sigma";
    const char *lkind = what == SHOW_MEAN ? "Mean" : "$\\sigma$";
    char unit[40];
    latex_unit(unit, sizeof unit, mi->unit);
    snprintf(row_text[i][0], sizeof row_text[i][0], "%s (%s%s%s)", mi->symbol,
             kind, mi->unit[0] ? ", " : "", mi->unit);
    snprintf(row_text[i][1], sizeof row_text[i][1], "%s (%s%s%s)", mi->latex,
             lkind, unit[0] ? ", " : "", unit);
    report_rows[i] = (table_row){
        row_text[i][0], row_text[i][1], FIRST_STORED + id, what,
        (mi->flags & MPB_METRIC_F_OPTIONAL) != 0,
        (mi->flags & MPB_METRIC_F_COUNT) ? 1 : -1, 0};
}

void report_rows_init(void)
{
    if (report_num_rows > 0)
        return;
    for (int i = 0; i < NUM_TIME_ROWS; i++) {
        report_rows[report_num_rows++] = time_rows[i];
        /* A problem set's: the median and the tail beside the mean. */
        if (time_rows[i].metric == M_TT && time_rows[i].what == SHOW_SIGMA) {
            report_rows[report_num_rows++] = (table_row){
                "tau_t (median, s)", "$\\tau_t$ (median, s)", M_TT,
                SHOW_MEDIAN, 1, -1, 1};
            report_rows[report_num_rows++] = (table_row){
                "tau_t median 95% CI", "$\\tau_t$ median 95\\% CI", M_TT,
                SHOW_MEDIAN_CI, 1, -1, 1};
            report_rows[report_num_rows++] = (table_row){
                "tau_t (p95, s)", "$\\tau_t$ (p95, s)", M_TT, SHOW_P95, 1,
                -1, 1};
        }
    }
    for (int id = 0; id < MPB_NUM_METRICS; id++) {
        unsigned flags = mpb_metric_info_of(id)->flags;
        if (flags & MPB_METRIC_F_TABLE)
            add_metric_row(id, SHOW_MEAN);
        if ((flags & MPB_METRIC_F_TABLE) && (flags & MPB_METRIC_F_SIGMA))
            add_metric_row(id, SHOW_SIGMA);
    }
    /* The planner's own claim of success beside mpbench's verdict. */
    report_rows[report_num_rows++] = (table_row){
        "claimed s_r (%)", "claimed $s_r$ (\\%)", 0, SHOW_CLAIMED, 0, 1, 0};
    report_rows[report_num_rows++] = (table_row){
        "s_r (%)", "$s_r$ (\\%)", 0, SHOW_RATE, 0, 1, 0};
    report_rows[report_num_rows++] = (table_row){
        "s_r 95% CI (%)", "$s_r$ 95\\% CI (\\%)", 0, SHOW_RATE_CI, 1, 1, 1};
    /* Claims in both directions, as counts of runs (outcome.h). */
    report_rows[report_num_rows++] = (table_row){
        "claimed", "claimed", COUNT_CLAIMED, SHOW_COUNT, 0, 0, 0};
    report_rows[report_num_rows++] = (table_row){
        "verified", "verified", MPB_OUTCOME_VERIFIED, SHOW_COUNT, 0, 0, 0};
    report_rows[report_num_rows++] = (table_row){
        "refused claims", "refused claims", MPB_OUTCOME_REFUSED, SHOW_COUNT,
        0, 0, 0};
    report_rows[report_num_rows++] = (table_row){
        "unclaimed valid", "unclaimed valid", MPB_OUTCOME_UNCLAIMED_VALID,
        SHOW_COUNT, 0, 0, 0};
}
