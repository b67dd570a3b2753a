/*
 * inference.c - the intervals and tests a comparison of planners over a
 * problem set rests on (stats.h): Wilson's interval for a rate, an
 * order-statistic interval for a median, quantiles, the Wilcoxon
 * signed-rank test on paired samples, and Holm's adjustment of p values
 * across pairs.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpbench/stats.h"

int mpb_wilson_interval(int k, int n, double *lo, double *hi)
{
    if (lo == NULL || hi == NULL || n < 0 || k < 0 || k > n)
        return MPB_EINVAL;
    if (n == 0) {
        *lo = *hi = NAN;
        return MPB_OK;
    }
    const double z = 1.959963984540054;      /* the normal's 97.5 % point */
    double p = (double)k / n, z2n = z * z / n;
    double centre = (p + z2n / 2) / (1 + z2n);
    double half = z * sqrt(p * (1 - p) / n + z2n / (4.0 * n)) / (1 + z2n);
    *lo = k == 0 ? 0.0 : fmax(0.0, centre - half);
    *hi = k == n ? 1.0 : fmin(1.0, centre + half);
    return MPB_OK;
}

double mpb_quantile(const double *sorted, int n, double q)
{
    if (sorted == NULL || n <= 0 || !(q >= 0 && q <= 1))
        return NAN;
    double h = (n - 1) * q;
    int i = (int)floor(h);
    if (i >= n - 1)
        return sorted[n - 1];
    return sorted[i] + (h - i) * (sorted[i + 1] - sorted[i]);
}

int mpb_median_interval(const double *sorted, int n, double *lo, double *hi,
                        double *coverage)
{
    if (sorted == NULL || lo == NULL || hi == NULL || n <= 0)
        return MPB_EINVAL;
    /* The ranks l and n + 1 - l, l the largest with P(X <= l - 1) <= 2.5 %
     * for X ~ B(n, 1/2), so that the interval holds the median with
     * probability 1 - 2 P(X <= l - 1) >= 95 %. Fewer than 6 samples
     * cannot reach 95 %: then the range, with the coverage it has. */
    double pj = pow(0.5, n);         /* P(X = 0) */
    double below = pj;               /* P(X <= l - 1), l = 1 */
    int l = 1;
    for (int j = 1; j <= n / 2; j++) {
        pj = pj * (n - j + 1) / j;   /* P(X = j) */
        if (below + pj > 0.025)
            break;
        below += pj;
        l = j + 1;
    }
    *lo = sorted[l - 1];
    *hi = sorted[n - l];
    if (coverage != NULL)
        *coverage = 1.0 - 2.0 * below;
    return MPB_OK;
}

typedef struct ranked {
    double a;      /* |d| */
    int    pos;    /* d > 0 */
} ranked;

static int by_abs(const void *x, const void *y)
{
    double a = ((const ranked *)x)->a, b = ((const ranked *)y)->a;
    return (a > b) - (a < b);
}

int mpb_signed_rank_test(const double *d, int n, int *used, double *p)
{
    if (p == NULL || n < 0 || (d == NULL && n > 0))
        return MPB_EINVAL;
    ranked *r = malloc((size_t)(n > 0 ? n : 1) * sizeof *r);
    if (r == NULL)
        return MPB_ENOMEM;
    int m = 0;
    for (int i = 0; i < n; i++) {
        if (isnan(d[i])) {
            free(r);
            return MPB_EINVAL;
        }
        if (d[i] != 0)      /* Wilcoxon's way: zero differences left out */
            r[m++] = (ranked){fabs(d[i]), d[i] > 0};
    }
    if (used != NULL)
        *used = m;
    if (m == 0) {
        free(r);
        *p = 1.0;
        return MPB_OK;
    }
    qsort(r, (size_t)m, sizeof *r, by_abs);
    /* W+: the sum of the positive differences' ranks, ties at their mean
     * rank; the ties' correction of the variance as they go. */
    double w = 0, ties = 0;
    int tied = 0;
    for (int i = 0; i < m;) {
        int j = i;
        while (j + 1 < m && r[j + 1].a == r[i].a)
            j++;
        double rank = (i + j + 2) / 2.0;
        for (int k = i; k <= j; k++)
            if (r[k].pos)
                w += rank;
        double t = j - i + 1;
        if (t > 1) {
            tied = 1;
            ties += t * t * t - t;
        }
        i = j + 1;
    }
    free(r);
    double total = m * (m + 1) / 2.0;
    if (!tied && m <= 50) {
        /* Exact: the number of subsets of {1..m} with each rank sum. */
        int top = m * (m + 1) / 2;
        double *c = calloc((size_t)top + 1, sizeof *c);
        if (c == NULL)
            return MPB_ENOMEM;
        c[0] = 1;
        for (int k = 1; k <= m; k++)
            for (int s = top; s >= k; s--)
                c[s] += c[s - k];
        double all = ldexp(1.0, m), low = 0, high = 0;
        int wi = (int)lround(w);
        for (int s = 0; s <= top; s++) {
            if (s <= wi)
                low += c[s];
            if (s >= wi)
                high += c[s];
        }
        free(c);
        *p = fmin(1.0, 2.0 * fmin(low, high) / all);
        return MPB_OK;
    }
    /* Normal, with the ties' correction and a continuity correction. */
    double mean = total / 2;
    double var = m * (m + 1.0) * (2.0 * m + 1) / 24.0 - ties / 48.0;
    if (!(var > 0)) {
        *p = 1.0;
        return MPB_OK;
    }
    double dev = fabs(w - mean) - 0.5;
    if (dev < 0)
        dev = 0;
    *p = fmin(1.0, erfc(dev / sqrt(var) / sqrt(2.0)));
    return MPB_OK;
}

typedef struct indexed {
    double p;
    int    i;
} indexed;

static int by_p(const void *x, const void *y)
{
    double a = ((const indexed *)x)->p, b = ((const indexed *)y)->p;
    return (a > b) - (a < b);
}

int mpb_holm(const double *p, int m, double *adjusted)
{
    if (m < 0 || (m > 0 && (p == NULL || adjusted == NULL)))
        return MPB_EINVAL;
    indexed *s = malloc((size_t)(m > 0 ? m : 1) * sizeof *s);
    if (s == NULL)
        return MPB_ENOMEM;
    for (int i = 0; i < m; i++) {
        if (!(p[i] >= 0 && p[i] <= 1)) {
            free(s);
            return MPB_EINVAL;
        }
        s[i] = (indexed){p[i], i};
    }
    qsort(s, (size_t)m, sizeof *s, by_p);
    double running = 0;
    for (int k = 0; k < m; k++) {
        double a = fmin(1.0, (m - k) * s[k].p);
        if (a > running)
            running = a;
        adjusted[s[k].i] = running;
    }
    free(s);
    return MPB_OK;
}
