/*
 * stats.h - summaries of samples for reports: mean, standard deviation,
 * median, quartiles, and the paper's convention for a scene's standard
 * deviation (computed per query, then averaged over the scene's queries).
 */
#ifndef MPBENCH_STATS_H
#define MPBENCH_STATS_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mpb_summary {
    int    n;          /* samples */
    double mean;
    double stddev;     /* sample standard deviation (n - 1); 0 when n < 2 */
    double min;
    double q1;         /* quartiles by linear interpolation (type 7, as R and numpy) */
    double median;
    double q3;
    double max;
} mpb_summary;

/*
 * Sort n doubles ascending, in place, in time linear in n (a radix sort of
 * their bits: a million in some 20 ms, where qsort() takes ten times as
 * long), -0 before +0. NaNs are no samples: leave them out first (they
 * would sort to the ends by their sign). MPB_OK, MPB_ENOMEM (x untouched),
 * MPB_EINVAL for x NULL with n > 0.
 */
int mpb_sort_doubles(double *x, size_t n);

/*
 * Summarise n samples. x is not modified (a sorted copy is made). With n == 0
 * every field but n is NaN. Returns MPB_OK, MPB_ENOMEM, or MPB_EINVAL (out
 * NULL, n < 0, x NULL with n > 0, or a sample is NaN: leave failed runs out
 * rather than pass NaN).
 */
int mpb_summarize(const double *x, int n, mpb_summary *out);

/*
 * Accumulates samples group by group (a group is a query) and gives the
 * scene-level mean over all samples and the mean of the per-group standard
 * deviations, as the paper reports them. A group's standard deviation is
 * the sample one (n - 1). Groups with one sample contribute a standard
 * deviation of 0, as one deterministic run does; groups with none (ended
 * with no sample added, e.g. a query with no successful run) do not count.
 * Use: init; then per group, add each sample and end_group. A group still
 * open when mean/stddev are read counts as if it had been ended. A NaN
 * sample makes both results NaN.
 */
typedef struct mpb_grouped {
    double sum;        /* over all samples */
    long   n;          /* all samples */
    double sd_sum;     /* sum of per-group standard deviations */
    int    groups;     /* groups with at least one sample */
    int    measured;   /* groups with two or more: a spread was measured */
    /* the group being filled (Welford's running mean and M2) */
    long   g_n;
    double g_mean;
    double g_m2;
} mpb_grouped;

void   mpb_grouped_init(mpb_grouped *g);
void   mpb_grouped_add(mpb_grouped *g, double x);
void   mpb_grouped_end_group(mpb_grouped *g);   /* call after each group */
double mpb_grouped_mean(const mpb_grouped *g);  /* NaN when empty */
double mpb_grouped_stddev(const mpb_grouped *g);/* NaN when no group */
/* Groups with two samples or more. With none, the standard deviation is 0
 * by the convention above, not by measurement: nothing was repeated. */
int    mpb_grouped_measured(const mpb_grouped *g);
/* Add g's groups to into's, as if their samples had been added there group
 * by group (g's open group counts as ended; into's stays open): for groups
 * that arrive interleaved and are kept apart until they end. */
void   mpb_grouped_merge(mpb_grouped *into, const mpb_grouped *g);

/* ---- intervals and tests for comparing planners (inference.c) -------- */

/*
 * Wilson's 95 % interval for a rate of k successes in n trials, into *lo
 * and *hi (both NaN when n is 0). MPB_OK, or MPB_EINVAL (NULL out, n < 0,
 * k outside 0..n).
 */
int mpb_wilson_interval(int k, int n, double *lo, double *hi);

/* The q-quantile (0 <= q <= 1) of n sorted samples by linear
 * interpolation (type 7, as mpb_summarize()); NaN when n <= 0. */
double mpb_quantile(const double *sorted, int n, double q);

/*
 * An interval for the median of n sorted samples from their order
 * statistics (distribution-free): the ranks l and n + 1 - l with the
 * largest l that keeps the coverage at 95 % or more. With fewer than 6
 * samples no ranks reach 95 %: the interval is the range, and *coverage
 * (if not NULL) says what it reaches (50 % for two samples). MPB_OK or
 * MPB_EINVAL.
 */
int mpb_median_interval(const double *sorted, int n, double *lo, double *hi,
                        double *coverage);

/*
 * The Wilcoxon signed-rank test of n paired differences d (a - b):
 * two-sided p value that their distribution is symmetric about 0, into
 * *p. Zero differences are left out (Wilcoxon's way; *used, if not NULL,
 * is how many were kept; none left gives p = 1). Exact when there are no
 * ties among |d| and at most 50 remain, else the normal approximation
 * with the ties' correction and a continuity correction. MPB_OK,
 * MPB_EINVAL (a NaN difference), MPB_ENOMEM.
 */
int mpb_signed_rank_test(const double *d, int n, int *used, double *p);

/*
 * Holm's step-down adjustment of m p values for testing them together:
 * adjusted[i] for p[i] (the arrays may be the same). MPB_OK, MPB_EINVAL
 * (a p outside [0, 1]), MPB_ENOMEM.
 */
int mpb_holm(const double *p, int m, double *adjusted);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_STATS_H */
