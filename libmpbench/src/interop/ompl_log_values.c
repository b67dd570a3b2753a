/*
 * ompl_log_values.c - the values of a benchmark log's runs and progress
 * samples (ompl_log_reader.h): each checked against its property's type
 * and read into the very double Python's float() makes of the text.
 */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "interop/ompl_log_reader.h"

/*
 * A decimal "[+-]digits[.digits][(e|E)[+-]digits]" taking all of [s, e),
 * with at most 19 digits, into *out; 0 when the text is not that simple.
 * Clinger's fast path: when the digits as an integer m are at most 2^53
 * and the exponent k is within +-22, m and 10^|k| are exact doubles and
 * m * 10^k (or m / 10^-k) is one correctly rounded operation, the very
 * double strtod returns. Anything else is left to strtod.
 */
static int fast_decimal(const char *s, const char *e, double *out)
{
#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD == 0
    static const double p10[] = {
        1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11,
        1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    const char *p = s, *d;
    int neg = 0;
    long k = 0, digits;
    uint64_t m = 0;     /* wraps beyond 19 digits: then unused */
    if (p < e && (*p == '-' || *p == '+'))
        neg = *p++ == '-';
    for (d = p; p < e && (unsigned)(*p - '0') < 10; p++)
        m = 10 * m + (uint64_t)(*p - '0');
    digits = p - d;
    if (p < e && *p == '.') {
        for (d = ++p; p < e && (unsigned)(*p - '0') < 10; p++)
            m = 10 * m + (uint64_t)(*p - '0');
        k = -(p - d);
        digits += p - d;
    }
    if (digits == 0 || digits > 19)
        return 0;
    if (p < e && (*p == 'e' || *p == 'E')) {
        int eneg = 0;
        long x = 0;
        if (++p < e && (*p == '-' || *p == '+'))
            eneg = *p++ == '-';
        if (p == e || (unsigned)(*p - '0') >= 10)
            return 0;
        for (; p < e && (unsigned)(*p - '0') < 10; p++)
            if (x < 100000)
                x = 10 * x + (*p - '0');
        k += eneg ? -x : x;
    }
    if (p != e || m > (UINT64_C(1) << 53))
        return 0;
    double v = (double)m;
    if (m != 0) {
        if (k < -22 || k > 22)
            return 0;
        v = k < 0 ? v / p10[-k] : v * p10[k];
    }
    *out = neg ? -v : v;
    return 1;
#else
    (void)s;
    (void)e;
    (void)out;
    return 0;   /* double rounding: only strtod is exact */
#endif
}

/* A value of a run line, the text [s, e) (*e may be overwritten); NaN for
 * "", nan, inf. */
static double value_in(char *s, char *e)
{
    double v;
    if (s == e)
        return NAN;
    if (fast_decimal(s, e, &v))
        return v;
    *e = '\0';
    if (strcmp(s, "true") == 0)
        return 1.0;
    if (strcmp(s, "false") == 0)
        return 0.0;
    char *end;
    v = strtod(s, &end);
    if (end == s || !isfinite(v))
        return NAN;
    return v;
}

double mpb__log_value_of(char *s)
{
    return value_in(s, s + strlen(s));
}

/* 1 when [s, e) is a value of that kind as OMPL writes it: empty (not
 * measured) for any; 0, 1, true or false for a BOOLEAN; an integer of at
 * most 64 bits for an INTEGER; an index into its enum's values (below
 * limit, when the log declares the enum) for an ENUM; a number, nan or
 * inf for a REAL, and a time no less than 0. *e is restored. */
int mpb__log_value_ok(const char *s, char *e, int kind, long limit)
{
    size_t n = (size_t)(e - s);
    if (n == 0)
        return 1;
    if (kind == V_BOOLEAN)
        return (n == 1 && (*s == '0' || *s == '1')) ||
               (n == 4 && memcmp(s, "true", 4) == 0) ||
               (n == 5 && memcmp(s, "false", 5) == 0);
    char keep = *e;
    *e = '\0';
    char *end;
    int ok;
    errno = 0;
    if (kind == V_INTEGER || kind == V_ENUM) {
        const char *d = s + (kind == V_INTEGER && (*s == '-' || *s == '+'));
        ok = d < e;
        for (const char *c = d; ok && c < e; c++)
            ok = (unsigned)(*c - '0') < 10;
        long long v = ok ? strtoll(s, &end, 10) : 0;
        ok = ok && errno == 0 && (kind == V_INTEGER || limit < 0 || v < limit);
    } else {
        double v;
        if (!fast_decimal(s, e, &v)) {
            v = strtod(s, &end);
            ok = end == e;
        } else {
            ok = 1;
        }
        ok = ok && !(kind == V_TIME && v < 0);
    }
    *e = keep;
    return ok;
}

/*
 * A run line's values, "v1; v2; ...; " (trimmed), into out[0..n): as
 * mpb__log_split(s, ';', fields, n + 1) and value_of each field, without copying
 * the fields. The count of fields found; *extra_empty says whether an
 * (n+1)-th was found, and empty.
 */
static int keep_exact(reader *r, mpb_ompl_planner *pl, size_t cell,
                      const char *s, const char *e);

int mpb__log_run_values(reader *r, mpb_ompl_planner *pl, long run, char *s,
                      double *out, int n, int *extra_empty,
                      const unsigned char *kinds, const long *limits,
                      int *bad, char **bad_text)
{
    int k = 0;
    *extra_empty = 0;
    *bad = -1;
    while (*s && k <= n) {
        char *next = s;
        while (*next && *next != ';')
            next++;
        int last = *next == '\0';
        char *b = s, *e = next;
        while (*b == ' ')
            b++;
        while (e > b && e[-1] == ' ')
            e--;
        if (k < n) {
            if (*bad < 0 && !mpb__log_value_ok(b, e, kinds[k], limits[k])) {
                *bad = k;
                *e = '\0';
                *bad_text = b;
            }
            /* An integer of more than 15 digits may be past 2^53. */
            if (e - b > 15 && (kinds[k] == V_INTEGER || kinds[k] == V_ENUM) &&
                *bad < 0 && keep_exact(r, pl, (size_t)run * (size_t)n + (size_t)k,
                                       b, e) != 0)
                return -1;
            out[k] = value_in(b, e);    /* may write a NUL at e */
        } else
            *extra_empty = b == e;
        k++;
        if (last)
            break;
        s = next + 1;
    }
    return k;
}

/* The integer [s, e) (checked by mpb__log_value_ok()) kept exactly in pl's exact
 * list when a double would round it. */
static int keep_exact(reader *r, mpb_ompl_planner *pl, size_t cell,
                      const char *s, const char *e)
{
    char text[32];
    size_t n = (size_t)(e - s);
    if (n >= sizeof text)
        return 0;       /* past 64 bits: mpb__log_value_ok() refuses it */
    memcpy(text, s, n);
    text[n] = '\0';
    errno = 0;
    long long v = strtoll(text, NULL, 10);
    if (errno != 0 || (v <= (1LL << 53) && v >= -(1LL << 53)))
        return 0;
    /* The list's room doubles when its length reaches a power of 2. */
    size_t have = (size_t)pl->num_exact;
    if ((have & (have - 1)) == 0) {
        mpb_ompl_exact *x = realloc(pl->exact, (have ? 2 * have : 1) *
                                                   sizeof *x);
        if (x == NULL)
            return mpb__log_fail(r, "out of memory");
        pl->exact = x;
    }
    pl->exact[pl->num_exact++] = (mpb_ompl_exact){cell, v};
    return 0;
}

/* Each of the n properties' kind of value and, for an ENUM the log
 * declares, its count of values (else -1). */
void mpb__log_kinds_of(const reader *r, const mpb_ompl_property *p, long n,
                     unsigned char *kinds, long *limits)
{
    for (long k = 0; k < n; k++) {
        kinds[k] = V_REAL;
        for (int t = 0; t < V_TIME; t++)
            if (strcmp(p[k].type, mpb__log_kind_names[t]) == 0)
                kinds[k] = (unsigned char)t;
        if (kinds[k] == V_REAL && strcmp(p[k].name, "time") == 0)
            kinds[k] = V_TIME;
        limits[k] = -1;
        for (long e = 0; e < r->num_enums; e++)
            if (strcmp(r->enums[e].name, p[k].name) == 0)
                limits[k] = r->enums[e].count;
    }
}

/* The error for text in where, which mpb__log_value_ok() refused for property p. */
int mpb__log_not_a_value(reader *r, const char *where, const char *text,
                       const mpb_ompl_property *p, int kind, long limit)
{
    if (kind == V_TIME)
        return mpb__log_fail(r, "%s: '%.60s' is not a time (a number of seconds, not "
                    "negative)", where, text);
    if (kind == V_ENUM && limit >= 0)
        return mpb__log_fail(r, "%s: '%.60s' is not a value of the ENUM '%.60s' (0 to "
                    "%ld)", where, text, p->name, limit - 1);
    return mpb__log_fail(r, "%s: '%.60s' is not %s %s", where, text,
                kind == V_INTEGER ? "an" : "a", mpb__log_kind_names[kind]);
}
