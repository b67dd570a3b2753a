/*
 * report_cells.c - what a table's cell shows, for every format: a row's
 * value or interval of a column, sigma and its single-run mark, and the
 * text of each cell as the text table prints it (decimals per row).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "report.h"

double report_sigma(const mpb_grouped *g)
{
    return g->n < 2 ? NAN : mpb_grouped_stddev(g);
}

int report_sigma_single(const mpb_grouped *g)
{
    int groups = g->groups + (g->g_n > 0);
    return groups - mpb_grouped_measured(g);
}

double report_row_value(const table_row *tr, const column *c)
{
    switch (tr->what) {
    case SHOW_MEAN:
        return mpb_grouped_mean(&c->m[tr->metric]);
    case SHOW_SIGMA:
        return report_sigma(&c->m[tr->metric]);
    case SHOW_RATE:
        return c->finished > 0 ? 100.0 * (double)c->succeeded /
                                     (double)c->finished
                               : NAN;
    case SHOW_CLAIMED:
        return c->finished > 0 ? 100.0 * (double)c->claimed /
                                     (double)c->finished
                               : NAN;
    case SHOW_COUNT:
        if (c->finished == 0)
            return NAN;
        return tr->metric == COUNT_CLAIMED ? (double)c->claimed
             : (double)c->outcomes[tr->metric];
    case SHOW_MEDIAN:
        return c->ntimes > 0 ? mpb_quantile(c->times, (int)c->ntimes, 0.5)
                             : NAN;
    case SHOW_P95:
        return c->ntimes > 0 ? mpb_quantile(c->times, (int)c->ntimes, 0.95)
                             : NAN;
    case SHOW_RATE_CI:
    case SHOW_MEDIAN_CI: {
        double lo, hi;
        report_row_interval(tr, c, &lo, &hi);
        return lo;
    }
    }
    return NAN;
}

int report_row_interval(const table_row *tr, const column *c, double *lo,
                        double *hi)
{
    double coverage = 0;
    *lo = *hi = NAN;
    if (tr->what == SHOW_RATE_CI && c->finished > 0 &&
        mpb_wilson_interval((int)c->succeeded, (int)c->finished, lo, hi) ==
            MPB_OK) {
        *lo *= 100.0;
        *hi *= 100.0;
    } else if (tr->what == SHOW_MEDIAN_CI && c->ntimes > 0 &&
               (mpb_median_interval(c->times, (int)c->ntimes, lo, hi,
                                    &coverage) != MPB_OK ||
                coverage < 0.95)) {
        *lo = *hi = NAN;    /* too few runs for a 95 % interval */
    }
    return !isnan(*lo);
}

/* A mean or sigma smaller than this in magnitude is the rounding of
 * floating-point arithmetic (a straight path's kappa' of 2e-30 in a
 * database written before it was 0), not a measurement: it prints as 0. */
#define NOISE 1e-12

static double denoise(double v)
{
    return fabs(v) < NOISE ? 0.0 : v;
}

/*
 * Decimals for a row of the general format: 3, as the paper's 2 would
 * hide today's millisecond plans, or more, up to 6, so that the row's
 * smallest nonzero value keeps 3 significant digits. One count per row
 * keeps a row's numbers aligned on the point.
 */
static int row_decimals(const column *cols, int n, const table_row *tr)
{
    int decimals = 3;
    for (int i = 0; i < n; i++) {
        double v = denoise(report_row_value(tr, &cols[i]));
        if (isnan(v) || v == 0.0 || isinf(v))
            continue;
        int d = 2 - (int)floor(log10(fabs(v)));
        if (d > decimals)
            decimals = d;
    }
    return decimals < 6 ? decimals : 6;
}

static void format_value(char *buf, int decimals, double v)
{
    if (isnan(v))
        snprintf(buf, CELL_TEXT, "-");
    else if (v != 0.0 && fabs(v) < 1e-4 && decimals == 6)
        snprintf(buf, CELL_TEXT, "%.2e", v);    /* 3 digits, not 0.00000x */
    else
        snprintf(buf, CELL_TEXT, "%.*f", decimals, v);
}

void report_cells(const report *r, const column *cols, char (*text)[CELL_TEXT],
                  int *visible)
{
    int nc = r->num_configs;
    for (int i = 0; i < report_num_rows; i++) {
        const table_row *tr = &report_rows[i];
        int decimals = tr->decimals >= 0 ? tr->decimals
                                         : row_decimals(cols, nc, tr);
        int any = 0;
        for (int c = 0; c < nc; c++) {
            double v = report_row_value(tr, &cols[c]), lo, hi;
            if (tr->sets_only) {
                any |= cols[c].in_set;
                if (report_row_interval(tr, &cols[c], &lo, &hi)) {
                    char a[CELL_TEXT], b[CELL_TEXT];
                    format_value(a, decimals, denoise(lo));
                    format_value(b, decimals, denoise(hi));
                    snprintf(text[i * nc + c], CELL_TEXT, "%.14s-%.14s", a, b);
                } else {
                    format_value(text[i * nc + c], decimals, denoise(v));
                }
                continue;
            }
            format_value(text[i * nc + c], decimals, denoise(v));
            if (tr->what == SHOW_SIGMA && !isnan(v) &&
                report_sigma_single(&cols[c].m[tr->metric]) > 0)
                strcat(text[i * nc + c], SIGMA_SINGLE_MARK);
            /* Measured: a value, or runs of a metric row (a count row's
             * metric is an outcome, or COUNT_CLAIMED, no index of m). */
            any |= !isnan(v) ||
                   ((tr->what == SHOW_MEAN || tr->what == SHOW_SIGMA) &&
                    cols[c].m[tr->metric].n > 0);
        }
        visible[i] = tr->sets_only ? any : !tr->optional || any;
    }
}

int report_any_single(char (*text)[CELL_TEXT], const int *visible, int nc)
{
    for (int i = 0; i < report_num_rows; i++)
        if (visible[i] && report_rows[i].what == SHOW_SIGMA)
            for (int c = 0; c < nc; c++)
                if (strstr(text[i * nc + c], SIGMA_SINGLE_MARK) != NULL)
                    return 1;
    return 0;
}
