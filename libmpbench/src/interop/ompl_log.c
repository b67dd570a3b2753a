/*
 * ompl_log.c - the reader of OMPL's (and MoveIt's) benchmark logs
 * (ompl_log.h). A cursor walks the text line by line; every line the
 * grammar expects is read by one function that says, on failure, which
 * line and what it wanted.
 */
#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"

/* Counts above these are taken for damage, not data. */
#define MAX_COUNT 100000000L
#define MAX_PROPERTIES 10000

typedef struct reader {
    const char *p, *end;
    long line;                  /* of the line last read */
    char *buf;                  /* that line, NUL-terminated, trimmed */
    size_t cap;
    const char *raw;            /* that line as written, without its end */
    size_t raw_len;
    char *err;
    size_t errlen;
    int failed;
    struct log_enum {           /* the log's enum types */
        char *name;
        long count;             /* of its values */
    } *enums;
    long num_enums;
} reader;

/* What a run's value may be, by its property's type. */
enum value_kind { V_REAL, V_INTEGER, V_BOOLEAN, V_ENUM, V_TIME };
static const char *const kind_names[] = {"REAL", "INTEGER", "BOOLEAN", "ENUM",
                                         "time"};

static int fail(reader *r, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static int fail(reader *r, const char *fmt, ...)
{
    if (!r->failed && r->err && r->errlen) {
        int n = snprintf(r->err, r->errlen, "line %ld: ", r->line);
        va_list ap;
        va_start(ap, fmt);
        if (n >= 0 && (size_t)n < r->errlen)
            vsnprintf(r->err + n, r->errlen - (size_t)n, fmt, ap);
        va_end(ap);
    }
    r->failed = 1;
    return MPB_EPARSE;
}

/* The next line, without its end and surrounding blanks; NULL at the end
 * of the text. */
static char *next_line(reader *r)
{
    if (r->p >= r->end)
        return NULL;
    const char *nl = memchr(r->p, '\n', (size_t)(r->end - r->p));
    const char *stop = nl ? nl : r->end;
    size_t n = (size_t)(stop - r->p);
    if (memchr(r->p, '\0', n) != NULL) {
        r->line++;
        fail(r, "a NUL byte: not a benchmark log");
        return NULL;
    }
    if (n + 1 > r->cap) {
        size_t cap = n + 1 > 2 * r->cap ? n + 1 : 2 * r->cap;
        char *b = realloc(r->buf, cap);
        if (b == NULL)
            return NULL;
        r->buf = b;
        r->cap = cap;
    }
    memcpy(r->buf, r->p, n);
    r->buf[n] = '\0';
    r->raw = r->p;
    r->raw_len = n > 0 && r->p[n - 1] == '\r' ? n - 1 : n;
    r->p = nl ? nl + 1 : r->end;
    r->line++;
    char *s = r->buf;
    while (*s && isspace((unsigned char)*s))
        s++;
    char *e = s + strlen(s);
    while (e > s && isspace((unsigned char)e[-1]))
        *--e = '\0';
    return s;
}

static char *need_line(reader *r, const char *what)
{
    char *s = next_line(r);
    if (s == NULL && !r->failed) {
        r->line++;
        fail(r, "the log ends where %s was expected", what);
    }
    return s;
}

static char *dup(reader *r, const char *s)
{
    char *d = strdup(s);
    if (d == NULL)
        fail(r, "out of memory");
    return d;
}

/* "N words...": the count, with the rest of the line checked to be words. */
static int count_line(reader *r, const char *words, long *out)
{
    char *s = need_line(r, words);
    if (s == NULL)
        return -1;
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    while (*end == ' ')
        end++;
    if (end == s || errno || v < 0 || strcmp(end, words) != 0)
        return fail(r, "expected 'N %s', found '%.60s'", words, s);
    if (v > MAX_COUNT)
        return fail(r, "%ld %s is more than a log holds", v, words);
    *out = v;
    return 0;
}

/* "X words": the number in front. */
static int number_line(reader *r, const char *words, double *out)
{
    char *s = need_line(r, words);
    if (s == NULL)
        return -1;
    char *end;
    double v = strtod(s, &end);
    while (*end == ' ')
        end++;
    if (end == s || strcmp(end, words) != 0)
        return fail(r, "expected 'X %s', found '%.60s'", words, s);
    if (!(v >= 0 && v <= DBL_MAX))
        return fail(r, "'%.60s': X must be a number no less than 0", s);
    *out = v;
    return 0;
}

/* "<<<|" text "|>>>", each line as it is in the log (blanks and all,
 * only "\r\n" read as "\n"), as OMPL's script keeps it. */
static int block(reader *r, char **out)
{
    char *s = need_line(r, "'<<<|'");
    if (s == NULL)
        return -1;
    if (strcmp(s, "<<<|") != 0)
        return fail(r, "expected '<<<|', found '%.60s'", s);
    size_t len = 0, cap = 64;
    char *text = malloc(cap);
    if (text == NULL)
        return fail(r, "out of memory");
    text[0] = '\0';
    for (;;) {
        const char *raw = r->p;
        s = need_line(r, "'|>>>'");
        if (s == NULL) {
            free(text);
            return -1;
        }
        size_t n = (size_t)(r->p - raw);
        if (n > 0 && raw[n - 1] == '\n')
            n--;
        if (n > 0 && raw[n - 1] == '\r')
            n--;
        /* The end is a line that starts with it, as OMPL's own script
         * reads it: an indented one is text (mpb export --ompl-log writes
         * one so, from a setup that holds a log's). */
        if (s == r->buf && strcmp(s, "|>>>") == 0)
            break;
        if (len + n + 2 > cap) {
            cap = 2 * (len + n + 2);
            char *t = realloc(text, cap);
            if (t == NULL) {
                free(text);
                return fail(r, "out of memory");
            }
            text = t;
        }
        memcpy(text + len, raw, n);
        len += n;
        text[len++] = '\n';
        text[len] = '\0';
    }
    *out = text;
    return 0;
}

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

static double value_of(char *s)
{
    return value_in(s, s + strlen(s));
}

/* 1 when [s, e) is a value of that kind as OMPL writes it: empty (not
 * measured) for any; 0, 1, true or false for a BOOLEAN; an integer of at
 * most 64 bits for an INTEGER; an index into its enum's values (below
 * limit, when the log declares the enum) for an ENUM; a number, nan or
 * inf for a REAL, and a time no less than 0. *e is restored. */
static int value_ok(const char *s, char *e, int kind, long limit)
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
 * split(s, ';', fields, n + 1) and value_of each field, without copying
 * the fields. The count of fields found; *extra_empty says whether an
 * (n+1)-th was found, and empty.
 */
static int keep_exact(reader *r, mpb_ompl_planner *pl, size_t cell,
                      const char *s, const char *e);

static int run_values(reader *r, mpb_ompl_planner *pl, long run, char *s,
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
            if (*bad < 0 && !value_ok(b, e, kinds[k], limits[k])) {
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

/* The integer [s, e) (checked by value_ok()) kept exactly in pl's exact
 * list when a double would round it. */
static int keep_exact(reader *r, mpb_ompl_planner *pl, size_t cell,
                      const char *s, const char *e)
{
    char text[32];
    size_t n = (size_t)(e - s);
    if (n >= sizeof text)
        return 0;       /* past 64 bits: value_ok() refuses it */
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
            return fail(r, "out of memory");
        pl->exact = x;
    }
    pl->exact[pl->num_exact++] = (mpb_ompl_exact){cell, v};
    return 0;
}

/* Each of the n properties' kind of value and, for an ENUM the log
 * declares, its count of values (else -1). */
static void kinds_of(const reader *r, const mpb_ompl_property *p, long n,
                     unsigned char *kinds, long *limits)
{
    for (long k = 0; k < n; k++) {
        kinds[k] = V_REAL;
        for (int t = 0; t < V_TIME; t++)
            if (strcmp(p[k].type, kind_names[t]) == 0)
                kinds[k] = (unsigned char)t;
        if (kinds[k] == V_REAL && strcmp(p[k].name, "time") == 0)
            kinds[k] = V_TIME;
        limits[k] = -1;
        for (long e = 0; e < r->num_enums; e++)
            if (strcmp(r->enums[e].name, p[k].name) == 0)
                limits[k] = r->enums[e].count;
    }
}

/* The error for text in where, which value_ok() refused for property p. */
static int not_a_value(reader *r, const char *where, const char *text,
                       const mpb_ompl_property *p, int kind, long limit)
{
    if (kind == V_TIME)
        return fail(r, "%s: '%.60s' is not a time (a number of seconds, not "
                    "negative)", where, text);
    if (kind == V_ENUM && limit >= 0)
        return fail(r, "%s: '%.60s' is not a value of the ENUM '%.60s' (0 to "
                    "%ld)", where, text, p->name, limit - 1);
    return fail(r, "%s: '%.60s' is not %s %s", where, text,
                kind == V_INTEGER ? "an" : "a", kind_names[kind]);
}

/* Split s at sep into at most n trimmed fields; the count found. */
static int split(char *s, char sep, char **fields, int n)
{
    int k = 0;
    while (*s && k < n) {
        char *next = strchr(s, sep);
        if (next)
            *next = '\0';
        while (*s == ' ')
            s++;
        char *e = s + strlen(s);
        while (e > s && e[-1] == ' ')
            *--e = '\0';
        fields[k++] = s;
        if (!next)
            break;
        s = next + 1;
    }
    return k;
}

/* "name TYPE" lines (the type is the last word) into *out; *count says
 * how many are filled, for freeing after a failure. */
static int property_lines(reader *r, long n, mpb_ompl_property **out,
                          int *count)
{
    if (n > MAX_PROPERTIES)
        return fail(r, "%ld properties is more than a log holds", n);
    mpb_ompl_property *p = calloc(n ? (size_t)n : 1, sizeof *p);
    if (p == NULL)
        return fail(r, "out of memory");
    *out = p;
    *count = (int)n;    /* unfilled entries are NULL: freeing them is fine */
    for (long i = 0; i < n; i++) {
        char *s = need_line(r, "a property 'name TYPE'");
        if (s == NULL)
            return -1;
        char *sp = strrchr(s, ' ');
        if (sp == NULL || sp == s)
            return fail(r, "expected a property 'name TYPE', found '%.60s'", s);
        *sp = '\0';
        if ((p[i].name = dup(r, s)) == NULL || (p[i].type = dup(r, sp + 1)) == NULL)
            return -1;
        for (long k = 0; k < i; k++)
            if (strcmp(p[k].name, p[i].name) == 0)
                return fail(r, "the property '%.60s' a second time", p[i].name);
        int known = 0;
        for (int k = 0; k < V_TIME; k++)
            known |= strcmp(p[i].type, kind_names[k]) == 0;
        if (!known)
            return fail(r, "unknown property type '%.60s' (not REAL, INTEGER, "
                        "BOOLEAN or ENUM)", p[i].type);
    }
    return 0;
}

/*
 * The progress of pl's runs: "N runs", then a line per run of samples
 * "a,b,;a,b,;", q values each, typed like a run's values. Value at of a
 * sample is stored first (its time), as planner_block() moved its name.
 */
static int progress_samples(reader *r, mpb_ompl_planner *pl, long q, long at)
{
    long nr;
    size_t used = 0, cap = 0;
    char **vals = NULL, *s;
    unsigned char *kinds = NULL;
    long *limits = NULL;
    int rc = -1;

    if (count_line(r, "runs", &nr) != 0)
        return -1;
    if (nr != pl->num_runs)
        return fail(r, "%ld runs of progress for %ld runs", nr, pl->num_runs);
    pl->progress_start = calloc((size_t)nr + 1, sizeof *pl->progress_start);
    vals = calloc((size_t)q + 1, sizeof *vals);
    kinds = malloc((size_t)q);
    limits = malloc((size_t)q * sizeof *limits);
    if (pl->progress_start == NULL || vals == NULL || kinds == NULL ||
        limits == NULL) {
        fail(r, "out of memory");
        goto done;
    }
    kinds_of(r, pl->progress_properties, q, kinds, limits);
    for (long i = 0; i < nr; i++) {
        if ((s = need_line(r, "a run's progress")) == NULL)
            goto done;
        pl->progress_start[i] = (long)(used / (size_t)q);
        char *sample = s;
        while (*sample) {
            char *semi = strchr(sample, ';');
            if (semi)
                *semi = '\0';
            if (*sample) {
                int k = split(sample, ',', vals, (int)q + 1);
                if (k == (int)q + 1 && vals[q][0] == '\0')
                    k--;
                if (k != (int)q) {
                    fail(r, "a progress sample of %s has %d values, not %ld",
                         pl->name, k, q);
                    goto done;
                }
                if (used + (size_t)q > cap) {
                    cap = cap ? 2 * cap : 64 * (size_t)q;
                    double *t = realloc(pl->progress, cap * sizeof *t);
                    if (t == NULL) {
                        fail(r, "out of memory");
                        goto done;
                    }
                    pl->progress = t;
                }
                for (long j = 0; j < q; j++) {
                    long to = j == at ? 0 : j < at ? j + 1 : j;
                    /* A sample without a time cannot be placed (the
                     * databases' column is NOT NULL). */
                    double v = value_of(vals[j]);
                    if (!value_ok(vals[j], vals[j] + strlen(vals[j]), kinds[to],
                                  limits[to]) ||
                        (to == 0 && !isfinite(v))) {
                        char where[128];
                        snprintf(where, sizeof where, "the progress of run %ld "
                                 "of %.60s", i + 1, pl->name);
                        not_a_value(r, where, vals[j],
                                    &pl->progress_properties[to], kinds[to],
                                    limits[to]);
                        goto done;
                    }
                    pl->progress[used + (size_t)to] = v;
                }
                used += (size_t)q;
            }
            if (!semi)
                break;
            sample = semi + 1;
        }
    }
    pl->progress_start[nr] = (long)(used / (size_t)q);
    rc = 0;
done:
    free(vals);
    free(kinds);
    free(limits);
    return rc;
}

/* The planner block of log->planners[index]. */
static int planner_block(reader *r, mpb_ompl_log *log, int index)
{
    mpb_ompl_planner *pl = &log->planners[index];
    long n;
    char *s = need_line(r, "a planner's name");
    if (s == NULL || (pl->name = dup(r, s)) == NULL)
        return -1;
    if (*s == '\0')
        return fail(r, "expected a planner's name, found an empty line");
    for (int k = 0; k < index; k++)
        if (strcmp(log->planners[k].name, pl->name) == 0)
            return fail(r, "the planner '%.60s' a second time", pl->name);
    if (count_line(r, "common properties", &n) != 0)
        return -1;
    size_t len = 0, tlen = 0;
    pl->settings = calloc(1, 1);
    pl->settings_text = calloc(1, 1);
    if (pl->settings == NULL || pl->settings_text == NULL)
        return fail(r, "out of memory");
    for (long i = 0; i < n; i++) {
        if ((s = need_line(r, "a common property")) == NULL)
            return -1;
        /* The script's form: the line as written, its end, then ';'. */
        char *st = realloc(pl->settings_text, tlen + r->raw_len + 3);
        if (st == NULL)
            return fail(r, "out of memory");
        pl->settings_text = st;
        memcpy(st + tlen, r->raw, r->raw_len);
        tlen += r->raw_len;
        memcpy(st + tlen, "\n;", 3);
        tlen += 2;
        size_t k = strlen(s);
        char *t = realloc(pl->settings, len + k + 2);
        if (t == NULL)
            return fail(r, "out of memory");
        pl->settings = t;
        if (len)
            t[len++] = ';';
        memcpy(t + len, s, k + 1);
        len += k;
    }
    long np;
    if (count_line(r, "properties for each run", &np) != 0 ||
        property_lines(r, np, &pl->properties, &pl->num_properties) != 0)
        return -1;
    if (count_line(r, "runs", &pl->num_runs) != 0)
        return -1;
    size_t cells = (size_t)pl->num_runs * (size_t)(np ? np : 1);
    pl->values = malloc(cells * sizeof *pl->values);
    unsigned char *kinds = malloc((size_t)np + 1);
    long *limits = malloc(((size_t)np + 1) * sizeof *limits);
    if (pl->values == NULL || kinds == NULL || limits == NULL) {
        free(kinds);
        free(limits);
        return fail(r, "out of memory");
    }
    kinds_of(r, pl->properties, np, kinds, limits);
    for (long i = 0; i < pl->num_runs; i++) {
        if ((s = need_line(r, "a run's values")) == NULL)
            break;
        int extra_empty, bad;
        char *bad_text = NULL;
        int k = run_values(r, pl, i, s, pl->values + (size_t)i * (size_t)np,
                           (int)np, &extra_empty, kinds, limits, &bad,
                           &bad_text);
        if (r->failed)
            break;
        /* The trailing "; " leaves one empty field more. */
        if (k == (int)np + 1 && extra_empty)
            k--;
        if (k != (int)np) {
            fail(r, "run %ld of %s has %d values, not %ld", i + 1,
                 pl->name, k, np);
            break;
        }
        if (bad >= 0) {
            char where[128];
            snprintf(where, sizeof where, "run %ld of %.60s", i + 1, pl->name);
            not_a_value(r, where, bad_text, &pl->properties[bad], kinds[bad],
                        limits[bad]);
            break;
        }
    }
    free(kinds);
    free(limits);
    if (r->failed)
        return -1;

    if ((s = need_line(r, "'.' or progress properties")) == NULL)
        return -1;
    if (strcmp(s, ".") == 0)
        return 0;
    /* Progress: "Q progress properties for each run", Q lines, "N runs",
     * N lines of samples "a,b,;a,b,;". */
    char *end;
    long q = strtol(s, &end, 10);
    while (*end == ' ')
        end++;
    if (end == s || q < 1 || q > MAX_PROPERTIES ||
        strcmp(end, "progress properties for each run") != 0)
        return fail(r, "expected '.' or 'N progress properties for each run', "
                    "found '%.60s'", s);
    if (property_lines(r, q, &pl->progress_properties,
                       &pl->num_progress_properties) != 0)
        return -1;
    /* The sample's time first: OMPL's Benchmark sorts the names, so "time"
     * comes after "best cost", "iterations", ... Each sample's values are
     * moved likewise (position at to 0, those before it one on). */
    long at = 0;
    while (at < q && strcmp(pl->progress_properties[at].name, "time") != 0)
        at++;
    if (at == q)
        at = 0;      /* no "time": the first property stands for it */
    if (at > 0) {
        mpb_ompl_property time = pl->progress_properties[at];
        memmove(pl->progress_properties + 1, pl->progress_properties,
                (size_t)at * sizeof *pl->progress_properties);
        pl->progress_properties[0] = time;
    }
    if (progress_samples(r, pl, q, at) != 0)
        return -1;
    if ((s = need_line(r, "'.'")) == NULL)
        return -1;
    if (strcmp(s, ".") != 0)
        return fail(r, "expected '.' after %s's runs, found '%.60s'", pl->name, s);
    return 0;
}

/* "WORD rest": rest, when the line starts with WORD and a space. */
static const char *after(const char *s, const char *word)
{
    size_t n = strlen(word);
    return strncmp(s, word, n) == 0 && s[n] == ' ' ? s + n + 1 : NULL;
}

/* An experiment property "name TYPE = value" into log->params. */
static int param_line(reader *r, mpb_ompl_log *log)
{
    char *s = need_line(r, "an experiment property 'name TYPE = value'");
    if (s == NULL)
        return -1;
    char *eq = strstr(s, " = "), *sp = NULL;
    const char *value = eq ? eq + 3 : "";
    size_t n = strlen(s);
    /* An empty value: the line's trailing blank was trimmed. */
    if (eq == NULL && n > 2 && strcmp(s + n - 2, " =") == 0)
        eq = s + n - 2;
    if (eq != NULL) {
        *eq = '\0';
        sp = strrchr(s, ' ');
    }
    if (sp == NULL || sp == s) {
        if (eq)
            *eq = ' ';
        return fail(r, "expected an experiment property 'name TYPE = value', "
                    "found '%.60s'", s);
    }
    *sp = '\0';
    /* The type becomes a column's declared type: a word, maybe with a
     * size, "VARCHAR(512)". */
    if (strspn(sp + 1, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
               "0123456789_(),") != strlen(sp + 1))
        return fail(r, "'%.60s' is not a type (the experiment property "
                    "'%.60s')", sp + 1, s);
    for (int i = 0; i < log->num_params; i++)
        if (strcmp(log->params[i].name, s) == 0)
            return fail(r, "the experiment property '%.60s' a second time", s);
    mpb_ompl_param *p = &log->params[log->num_params++];
    if ((p->name = dup(r, s)) == NULL || (p->type = dup(r, sp + 1)) == NULL ||
        (p->value = dup(r, value)) == NULL)
        return -1;
    return 0;
}

/* An enum line as written, split at '|', into log->enums. */
static int enum_line(reader *r, mpb_ompl_log *log)
{
    mpb_ompl_enum *en = &log->enums[log->num_enums++];
    int n = 1;
    for (size_t i = 0; i < r->raw_len; i++)
        n += r->raw[i] == '|';
    if ((en->values = calloc((size_t)n, sizeof *en->values)) == NULL)
        return fail(r, "out of memory");
    const char *f = r->raw, *end = r->raw + r->raw_len;
    for (int i = 0; i < n; i++) {
        const char *bar = memchr(f, '|', (size_t)(end - f));
        const char *stop = bar ? bar : end;
        char *v = strndup(f, (size_t)(stop - f));
        if (v == NULL)
            return fail(r, "out of memory");
        if (i == 0)
            en->name = v;
        else
            en->values[en->num_values++] = v;
        f = stop + 1;
    }
    return 0;
}

static int header(reader *r, mpb_ompl_log *log)
{
    char *s = need_line(r, "'OMPL version ...'");
    if (s == NULL)
        return -1;
    /* "OMPL version 1.5.2", "MoveIt version 1.1.9", "MoveIt! version ...";
     * Debian's OMPL 1.5 writes "OMPL version " with no number. */
    char *v = strstr(s, " version");
    if (v == NULL || v == s || (v[8] != ' ' && v[8] != '\0'))
        return fail(r, "expected 'OMPL version X' (or MoveIt's), found '%.60s'", s);
    *v = '\0';
    const char *number = v[8] ? v + 9 : "";
    char version[256];
    snprintf(version, sizeof version, "%s%s%s", s, *number ? " " : "", number);
    if ((log->version = dup(r, version)) == NULL)
        return -1;
    if ((s = need_line(r, "'Experiment NAME'")) == NULL)
        return -1;
    const char *name = after(s, "Experiment");
    if (name == NULL)
        return fail(r, "expected 'Experiment NAME', found '%.60s'", s);
    if ((log->experiment = dup(r, name)) == NULL)
        return -1;
    /* Experiment properties (OMPL 1.5), then the host. */
    if ((s = need_line(r, "'Running on HOST'")) == NULL)
        return -1;
    char *end;
    long k = strtol(s, &end, 10);
    if (end != s && strcmp(end, " experiment properties") == 0) {
        if (k < 0)
            return fail(r, "'%.60s': not a count", s);
        if (k > MAX_PROPERTIES)
            return fail(r, "%ld experiment properties is more than a log holds", k);
        if ((log->params = calloc(k ? (size_t)k : 1, sizeof *log->params)) == NULL)
            return fail(r, "out of memory");
        for (long i = 0; i < k; i++)
            if (param_line(r, log) != 0)
                return -1;
        if ((s = need_line(r, "'Running on HOST'")) == NULL)
            return -1;
    }
    const char *host = after(s, "Running on");
    if (host == NULL)
        return fail(r, "expected 'Running on HOST', found '%.60s'", s);
    if ((log->host = dup(r, host)) == NULL)
        return -1;
    if ((s = need_line(r, "'Starting at DATE'")) == NULL)
        return -1;
    const char *date = after(s, "Starting at");
    if (date == NULL)
        return fail(r, "expected 'Starting at DATE', found '%.60s'", s);
    /* Boost's to_simple_string(): "2026-Nov-22 11:22:29", or ISO's
     * "2026-11-22 11:22:29". */
    if (strlen(date) < 8 || strspn(date, "0123456789") != 4 || date[4] != '-')
        return fail(r, "'%.60s' is not a date (YYYY-MM-DD ...)", date);
    if ((log->date = dup(r, date)) == NULL || block(r, &log->setup) != 0)
        return -1;
    /* cpuinfo is optional: another block, or the seed line. */
    const char *mark = r->p;
    long line = r->line;
    if ((s = need_line(r, "'SEED is the random seed'")) == NULL)
        return -1;
    if (strcmp(s, "<<<|") == 0) {
        r->p = mark;
        r->line = line;
        if (block(r, &log->cpuinfo) != 0 ||
            (s = need_line(r, "'SEED is the random seed'")) == NULL)
            return -1;
    }
    char *seed_end = strstr(s, " is the random seed");
    if (seed_end == NULL || seed_end[19] != '\0')
        return fail(r, "expected 'SEED is the random seed', found '%.60s'", s);
    *seed_end = '\0';
    if (*s == '\0' || strspn(s, "0123456789") != strlen(s))
        return fail(r, "'%.60s' is not a random seed (a number)", s);
    if ((log->seed = dup(r, s)) == NULL)
        return -1;
    if (number_line(r, "seconds per run", &log->time_limit) != 0 ||
        number_line(r, "MB per run", &log->memory_limit) != 0)
        return -1;
    /* Optional "N runs per planner"; then the time spent. */
    log->runs_per_planner = -1;
    if ((s = need_line(r, "'S seconds spent to collect the data'")) == NULL)
        return -1;
    double t = strtod(s, &end);
    if (end != s && strcmp(end, " runs per planner") == 0) {
        if (!(t >= 0 && t <= MAX_COUNT))
            return fail(r, "%.60s: not a run count", s);
        log->runs_per_planner = (long)t;
        if ((s = need_line(r, "'S seconds spent to collect the data'")) == NULL)
            return -1;
        t = strtod(s, &end);
    }
    if (end == s || strcmp(end, " seconds spent to collect the data") != 0)
        return fail(r, "expected 'S seconds spent to collect the data', "
                    "found '%.60s'", s);
    log->total_time = t;
    /* Optional enums, then the planner count. */
    if ((s = need_line(r, "'P planners'")) == NULL)
        return -1;
    long n = strtol(s, &end, 10);
    if (end != s && (strcmp(end, " enum types") == 0 ||
                     strcmp(end, " enum type") == 0)) {
        if (n < 0)
            return fail(r, "'%.60s': not a count", s);
        if (n > MAX_PROPERTIES)
            return fail(r, "%ld enum types is more than a log holds", n);
        r->enums = calloc(n ? (size_t)n : 1, sizeof *r->enums);
        log->enums = calloc(n ? (size_t)n : 1, sizeof *log->enums);
        if (r->enums == NULL || log->enums == NULL)
            return fail(r, "out of memory");
        for (long i = 0; i < n; i++) {
            if ((s = need_line(r, "an enum 'name|value|...'")) == NULL)
                return -1;
            char *bar = strchr(s, '|');
            if (bar == NULL || bar == s)
                return fail(r, "expected an enum 'name|value|...', found '%.60s'", s);
            if (enum_line(r, log) != 0)
                return -1;
            *bar = '\0';
            long count = 1;
            for (const char *c = bar + 1; *c; c++)
                count += *c == '|';
            if ((r->enums[i].name = dup(r, s)) == NULL)
                return -1;
            r->enums[i].count = count;
            r->num_enums = i + 1;
        }
        if ((s = need_line(r, "'P planners'")) == NULL)
            return -1;
        n = strtol(s, &end, 10);
    }
    if (end == s || n < 0 || strcmp(end, " planners") != 0)
        return fail(r, "expected 'P planners', found '%.60s'", s);
    if (n > MAX_PROPERTIES)
        return fail(r, "%ld planners is more than a log holds", n);
    log->num_planners = (int)n;
    return 0;
}

static void free_enums(reader *r)
{
    for (long i = 0; i < r->num_enums; i++)
        free(r->enums[i].name);
    free(r->enums);
    r->enums = NULL;
    r->num_enums = 0;
}

int mpb_ompl_log_parse(const char *text, size_t len, mpb_ompl_log **out,
                       char *err, size_t errlen)
{
    if (out)
        *out = NULL;
    if (text == NULL || out == NULL)
        return MPB_EINVAL;
    if (err && errlen)
        err[0] = '\0';
    reader r = {.p = text, .end = text + len, .err = err, .errlen = errlen};
    mpb_ompl_log *log = calloc(1, sizeof *log);
    int rc = MPB_ENOMEM;
    if (log == NULL)
        goto done;
    if (header(&r, log) != 0)
        goto fail;
    log->planners = calloc(log->num_planners ? (size_t)log->num_planners : 1,
                           sizeof *log->planners);
    if (log->planners == NULL) {
        fail(&r, "out of memory");
        goto fail;
    }
    for (int i = 0; i < log->num_planners; i++)
        if (planner_block(&r, log, i) != 0)
            goto fail;
    /* A planner count too small leaves planners unread: nothing may
     * follow the last one but blank lines. */
    for (const char *s; (s = next_line(&r)) != NULL;)
        if (*s) {
            fail(&r, "text after the last planner");
            goto fail;
        }
    if (r.failed)
        goto fail;
    free(r.buf);
    free_enums(&r);
    *out = log;
    return MPB_OK;
fail:
    rc = r.err && strstr(r.err, "out of memory") ? MPB_ENOMEM : MPB_EPARSE;
    mpb_ompl_log_free(log);
done:
    free(r.buf);
    free_enums(&r);
    return rc;
}

static void free_properties(mpb_ompl_property *p, int n)
{
    for (int i = 0; p && i < n; i++) {
        free(p[i].name);
        free(p[i].type);
    }
    free(p);
}

void mpb_ompl_log_free(mpb_ompl_log *log)
{
    if (log == NULL)
        return;
    for (int i = 0; log->planners && i < log->num_planners; i++) {
        mpb_ompl_planner *p = &log->planners[i];
        free(p->name);
        free(p->settings);
        free(p->settings_text);
        free(p->exact);
        free_properties(p->properties, p->num_properties);
        free(p->values);
        free_properties(p->progress_properties, p->num_progress_properties);
        free(p->progress_start);
        free(p->progress);
    }
    free(log->planners);
    for (int i = 0; log->params && i < log->num_params; i++) {
        free(log->params[i].name);
        free(log->params[i].type);
        free(log->params[i].value);
    }
    free(log->params);
    for (int i = 0; log->enums && i < log->num_enums; i++) {
        for (int k = 0; k < log->enums[i].num_values; k++)
            free(log->enums[i].values[k]);
        free(log->enums[i].values);
        free(log->enums[i].name);
    }
    free(log->enums);
    free(log->version);
    free(log->experiment);
    free(log->host);
    free(log->date);
    free(log->setup);
    free(log->cpuinfo);
    free(log->seed);
    free(log);
}

int mpb_ompl_planner_property(const mpb_ompl_planner *p, const char *name)
{
    for (int i = 0; p && i < p->num_properties; i++)
        if (strcmp(p->properties[i].name, name) == 0)
            return i;
    return -1;
}

const char *mpb_ompl_status_name(double v)
{
    static const char *const name[] = {
        "failed", "invalid_request", "invalid_request", "invalid_request",
        "timeout", "approximate", "solved", "crash", "failed", "failed",
        "invalid_request", "memory",    /* mpbench's own (mpb export) */
    };
    if (!(v >= 0 && v <= 11) || v != (double)(int)v)
        return NULL;
    return name[(int)v];
}
