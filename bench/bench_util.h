/*
 * bench_util.h - what the bench programs share: clocks, percentiles of a
 * sample, one machine-readable result line (a file is read whole with
 * mpb_read_file()).
 * Header-only (static functions): each bench program is one .c file.
 */
#ifndef MPBB_UTIL_H
#define MPBB_UTIL_H

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Monotonic time in seconds. */
static inline double mpbb_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static int mpbb__cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Sort v[0..n) ascending, in place. */
static inline void mpbb_sort(double *v, size_t n)
{
    qsort(v, n, sizeof *v, mpbb__cmp_double);
}

/* The p-quantile (0 < p <= 1) of a sorted sample, nearest rank; NaN if
 * n == 0. p = 0.5 is the median, 0.99 the 99th percentile. */
static inline double mpbb_quantile(const double *sorted, size_t n, double p)
{
    if (n == 0)
        return NAN;
    size_t k = (size_t)ceil(p * (double)n);
    if (k < 1)
        k = 1;
    if (k > n)
        k = n;
    return sorted[k - 1];
}

static inline double mpbb_mean(const double *v, size_t n)
{
    double s = 0.0;
    for (size_t i = 0; i < n; i++)
        s += v[i];
    return n ? s / (double)n : NAN;
}

/*
 * Print one result line for bench/run.sh to collect: "RESULT key=value ...".
 * Keys are words; values numbers or words without spaces.
 */
static inline void mpbb_result(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

static inline void mpbb_result(const char *fmt, ...)
{
    va_list ap;
    fputs("RESULT ", stdout);
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    fputc('\n', stdout);
    fflush(stdout);
}

#endif
