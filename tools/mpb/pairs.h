/*
 * pairs.h - configurations compared problem by problem (pairs.c): what
 * `mpb compare` prints, and what `mpb report` uses for --findings and
 * the HTML page's comparison matrix. Not part of libmpbench.
 *
 * Per configuration and problem (query), its runs give: solved (more than
 * half of the runs verified successes), a time (the median over the runs
 * of time_total, a run that is no success counted at the time limit: the
 * budget it used up) and a path length (the median over its successful
 * runs). A pair is compared on the problems both ran: how many each
 * solved alone; the per-problem time ratio A/B on the problems at least
 * one solved, its median with a distribution-free 95 % interval and the
 * Wilcoxon signed-rank test of the log ratios; the path-length ratio
 * likewise on the problems both solved (stats.h).
 */
#ifndef MPB_TOOL_PAIRS_H
#define MPB_TOOL_PAIRS_H

/* Significance of every finding and mark: 5 %. */
#define PAIRS_ALPHA 0.05

/* What one configuration did on one problem. */
typedef struct pairs_cell {
    int     runs, successes;
    double *times;      /* per run: time_total, or the limit if no success */
    double *lengths;    /* per successful run: path_length (NaN: none) */
    int     cap_t, cap_l;
} pairs_cell;

/* The runs of nc configurations on nq problems, each problem in a set
 * (query_set[q], filled in by the caller; -1 in none). */
typedef struct pairs_data {
    double      limit;
    int         nc, nq;
    int        *query_set;  /* nq */
    pairs_cell *cells;      /* [config * nq + query] */
} pairs_data;

/* Room for nc x nq cells and nq sets, all empty. MPB_OK or MPB_ENOMEM
 * (then pairs_free() is still to be called). */
int pairs_init(pairs_data *d, int nc, int nq, double limit);

/* One finished run of configuration config on problem query: whether it
 * was a verified success, its time_total and final path length. MPB_OK
 * or MPB_ENOMEM. */
int pairs_add(pairs_data *d, int config, int query, int success,
              double time, double length);

/* Everything d holds freed; pairs_free() of a zeroed d does nothing. */
void pairs_free(pairs_data *d);

/* One side of a comparison: a ratio's median, interval and p value. */
typedef struct pairs_ratio {
    int    n;              /* problems compared */
    double median, lo, hi, p;
    double p_holm;         /* p adjusted with the others (pairs_holm()) */
} pairs_ratio;

typedef struct pairs_pair {
    int         a, b;
    int         problems, both, only_a, only_b, neither;
    pairs_ratio time, length;
} pairs_pair;

/* Compare configurations a and b on the problems of set (-1: all).
 * Sorts the cells' samples in place. MPB_OK or MPB_ENOMEM. */
int pairs_compare(pairs_data *d, int a, int b, int set, pairs_pair *out);

/* Holm's adjustment of the n pairs' time p values together, and of their
 * path-length ones together, into p_holm (a ratio with no problem counts
 * as p = 1). MPB_OK or MPB_ENOMEM. */
int pairs_holm(pairs_pair *p, int n);

/* The index of the pair (a, b), a != b, in the list of every pair in the
 * order a < b by a then b (pairs_all()), of n configurations. */
int pairs_index(int n, int a, int b);

/* Every pair (a < b) of d's configurations on set (-1: all), Holm-
 * adjusted together, into *out (n(n-1)/2 of them; free() it; NULL when
 * there are fewer than two). MPB_OK or MPB_ENOMEM. */
int pairs_all(pairs_data *d, int set, pairs_pair **out);

/* Whether the ratio says the first of its pair is smaller (-1), larger
 * (1), or neither (0), at PAIRS_ALPHA by its Holm-adjusted p. */
int pairs_verdict(const pairs_ratio *r);

#endif
