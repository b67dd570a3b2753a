/* stats.c - summaries of samples and the paper's per-query standard deviation. */
#include "mpbench/mpbench.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* A double's bits as a key whose unsigned order is the numbers' order:
 * the sign bit flipped for positives, every bit for negatives. */
static uint64_t key_of(double v)
{
    uint64_t b;
    memcpy(&b, &v, sizeof b);
    return b >> 63 ? ~b : b ^ UINT64_C(0x8000000000000000);
}

static double value_of(uint64_t k)
{
    uint64_t b = k >> 63 ? k ^ UINT64_C(0x8000000000000000) : ~k;
    double v;
    memcpy(&v, &b, sizeof v);
    return v;
}

int mpb_sort_doubles(double *x, size_t n)
{
    if (n > 0 && x == NULL)
        return MPB_EINVAL;
    if (n < 2)
        return MPB_OK;
    uint64_t *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
    if (a == NULL || b == NULL) {
        free(a);
        free(b);
        return MPB_ENOMEM;
    }
    for (size_t i = 0; i < n; i++)
        a[i] = key_of(x[i]);
    /* Least significant byte first, a byte a pass; a pass whose byte is
     * the same in every key (most of a double's exponent) is skipped. */
    for (int shift = 0; shift < 64; shift += 8) {
        size_t count[257] = {0};
        for (size_t i = 0; i < n; i++)
            count[((a[i] >> shift) & 0xff) + 1]++;
        if (count[((a[0] >> shift) & 0xff) + 1] == n)
            continue;
        for (int d = 0; d < 256; d++)
            count[d + 1] += count[d];
        for (size_t i = 0; i < n; i++)
            b[count[(a[i] >> shift) & 0xff]++] = a[i];
        uint64_t *t = a;
        a = b;
        b = t;
    }
    for (size_t i = 0; i < n; i++)
        x[i] = value_of(a[i]);
    free(a);
    free(b);
    return MPB_OK;
}

/* Quantile p of sorted x[0..n), type 7: x[h] interpolated, h = (n - 1) p. */
static double quantile7(const double *x, int n, double p)
{
    double h = (n - 1) * p;
    int lo = (int)floor(h);
    if (lo >= n - 1)
        return x[n - 1];
    return x[lo] + (h - lo) * (x[lo + 1] - x[lo]);
}

int mpb_summarize(const double *x, int n, mpb_summary *out)
{
    if (!out || n < 0 || (n > 0 && !x))
        return MPB_EINVAL;
    for (int i = 0; i < n; i++)
        if (isnan(x[i]))
            return MPB_EINVAL;
    out->n = n;
    if (n == 0) {
        out->mean = out->stddev = out->min = out->q1 = NAN;
        out->median = out->q3 = out->max = NAN;
        return MPB_OK;
    }
    double *s = malloc((size_t)n * sizeof *s);
    if (!s)
        return MPB_ENOMEM;
    memcpy(s, x, (size_t)n * sizeof *s);
    if (mpb_sort_doubles(s, (size_t)n) != MPB_OK) {
        free(s);
        return MPB_ENOMEM;
    }

    double sum = 0.0;
    for (int i = 0; i < n; i++)
        sum += s[i];
    double mean = sum / n;
    double m2 = 0.0;            /* second pass: no cancellation */
    for (int i = 0; i < n; i++)
        m2 += (s[i] - mean) * (s[i] - mean);

    out->mean = mean;
    out->stddev = n < 2 ? 0.0 : sqrt(m2 / (n - 1));
    out->min = s[0];
    out->q1 = quantile7(s, n, 0.25);
    out->median = quantile7(s, n, 0.5);
    out->q3 = quantile7(s, n, 0.75);
    out->max = s[n - 1];
    free(s);
    return MPB_OK;
}

void mpb_grouped_init(mpb_grouped *g)
{
    memset(g, 0, sizeof *g);
}

void mpb_grouped_add(mpb_grouped *g, double x)
{
    g->sum += x;
    g->n++;
    /* Welford: running mean and sum of squared deviations of the group. */
    g->g_n++;
    double d = x - g->g_mean;
    g->g_mean += d / (double)g->g_n;
    g->g_m2 += d * (x - g->g_mean);
}

/* Sample standard deviation of the open group; 0 below two samples. */
static double group_sd(const mpb_grouped *g)
{
    return g->g_n < 2 ? 0.0 : sqrt(g->g_m2 / (double)(g->g_n - 1));
}

void mpb_grouped_end_group(mpb_grouped *g)
{
    if (g->g_n > 0) {
        g->sd_sum += group_sd(g);
        g->groups++;
        g->measured += g->g_n >= 2;
    }
    g->g_n = 0;
    g->g_mean = 0.0;
    g->g_m2 = 0.0;
}

double mpb_grouped_mean(const mpb_grouped *g)
{
    return g->n > 0 ? g->sum / (double)g->n : NAN;
}

double mpb_grouped_stddev(const mpb_grouped *g)
{
    /* A group still open counts as if it had been ended. */
    double sd_sum = g->sd_sum;
    int groups = g->groups;
    if (g->g_n > 0) {
        sd_sum += group_sd(g);
        groups++;
    }
    return groups > 0 ? sd_sum / groups : NAN;
}

int mpb_grouped_measured(const mpb_grouped *g)
{
    return g->measured + (g->g_n >= 2);   /* the open group counts too */
}

void mpb_grouped_merge(mpb_grouped *into, const mpb_grouped *g)
{
    into->sum += g->sum;
    into->n += g->n;
    into->sd_sum += g->sd_sum;
    into->groups += g->groups;
    into->measured += g->measured;
    if (g->g_n > 0) {
        into->sd_sum += group_sd(g);
        into->groups++;
        into->measured += g->g_n >= 2;
    }
}
