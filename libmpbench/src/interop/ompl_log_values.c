/*
 * ompl_log_values.c - the values of a benchmark log's runs and progress
 * samples (ompl_log_reader.h): each checked against its property's type
 * and read into the double OMPL's script stores: an integer as written,
 * a REAL as SQLite reads its text.
 */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sqlite3.h>

#include "interop/ompl_log_reader.h"

/*
 * A decimal "[+-]digits[.digits][(e|E)[+-]digits]" taking all of [s, e)
 * as its parts: the sign, the digits as an integer *m (valid for at most
 * 19 of them), their count and the power of ten *k, so that the value is
 * m * 10^k. 0 when the text is not that simple.
 */
static int decimal_parts(const char *s, const char *e, int *neg,
                         uint64_t *m, long *k, long *digits)
{
    const char *p = s, *d;
    *neg = 0;
    *k = 0;
    *m = 0;     /* wraps beyond 19 digits: then unused */
    if (p < e && (*p == '-' || *p == '+'))
        *neg = *p++ == '-';
    for (d = p; p < e && (unsigned)(*p - '0') < 10; p++)
        *m = 10 * *m + (uint64_t)(*p - '0');
    *digits = p - d;
    if (p < e && *p == '.') {
        for (d = ++p; p < e && (unsigned)(*p - '0') < 10; p++)
            *m = 10 * *m + (uint64_t)(*p - '0');
        *k = -(p - d);
        *digits += p - d;
    }
    if (*digits == 0)
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
        *k += eneg ? -x : x;
    }
    return p == e;
}

/*
 * The decimal [s, e) (decimal_parts()) of at most 19 digits into *out; 0
 * when it is not that simple. Clinger's fast path: when the digits as an
 * integer m are at most 2^53 and the exponent k is within +-22, m and
 * 10^|k| are exact doubles and m * 10^k (or m / 10^-k) is one correctly
 * rounded operation, the very double strtod returns. Anything else is
 * left to strtod.
 */
static int fast_decimal(const char *s, const char *e, double *out)
{
#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD == 0
    static const double p10[] = {
        1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11,
        1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    int neg;
    uint64_t m;
    long k, digits;
    if (!decimal_parts(s, e, &neg, &m, &k, &digits) || digits > 19 ||
        m > (UINT64_C(1) << 53))
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
            if ((kinds[k] == V_REAL || kinds[k] == V_TIME) && *bad < 0 &&
                mpb__log_real_text(r, &out[k], r->raw + (b - r->buf),
                                   (size_t)(e - b)) != 0)
                return -1;
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

/*
 * OMPL's script binds a value's text and SQLite's REAL affinity makes
 * the number, with SQLite's own conversion: not always strtod's double
 * (SQLite 3.40 reads "0.814637" as 0.8146370000000001, the script's
 * cell; Python's float() and strtod give 0.814637). So the texts of REAL
 * values are read by SQLite itself, MPB__REALS_BATCH to one statement of
 * CASTs (the same conversion), in a database of its own in memory.
 */
#define MPB__REALS_BATCH 64

struct mpb__log_reals {
    sqlite3      *db;
    sqlite3_stmt *st;
    int           n;
    double       *dst[MPB__REALS_BATCH];
    int           same;   /* 1: SQLite reads a short decimal as shortly() */
};

/*
 * A decimal of at most 18 digits with a power of ten within +-22, read as
 * SQLite 3.40 does: the digits as an integer and the power of ten, both
 * exact in long double, divided (or multiplied) in long double, the
 * quotient rounded to double; a double rounding, hence its last digit.
 * 1 and *out when [s, e) is such a decimal, else 0. Whether the SQLite at
 * hand does so is asked it once (reals_open()); when not, it reads
 * every text itself.
 */
static int shortly(const char *s, const char *e, double *out)
{
    static const long double p10[] = {
        1e0L, 1e1L, 1e2L, 1e3L, 1e4L, 1e5L, 1e6L, 1e7L, 1e8L, 1e9L, 1e10L,
        1e11L, 1e12L, 1e13L, 1e14L, 1e15L, 1e16L, 1e17L, 1e18L, 1e19L,
        1e20L, 1e21L, 1e22L};
    int neg;
    uint64_t m;
    long k, digits;
    if (!decimal_parts(s, e, &neg, &m, &k, &digits) || digits > 18 ||
        k < -22 || k > 22)
        return 0;
    long double v = (long double)m;
    v = k < 0 ? v / p10[-k] : v * p10[k];
    *out = neg ? -(double)v : (double)v;
    return 1;
}

int mpb__log_reals_flush(reader *r)
{
    struct mpb__log_reals *q = r->reals;
    if (q == NULL || q->n == 0)
        return 0;
    for (int i = q->n; i < MPB__REALS_BATCH; i++)
        sqlite3_bind_null(q->st, i + 1);
    if (sqlite3_step(q->st) != SQLITE_ROW) {
        q->n = 0;
        sqlite3_reset(q->st);
        return mpb__log_fail(r, "SQLite could not read the values: %s",
                             sqlite3_errmsg(q->db));
    }
    for (int i = 0; i < q->n; i++)
        if (sqlite3_column_type(q->st, i) == SQLITE_FLOAT ||
            sqlite3_column_type(q->st, i) == SQLITE_INTEGER)
            *q->dst[i] = sqlite3_column_double(q->st, i);
    sqlite3_reset(q->st);
    q->n = 0;
    return 0;
}

/* 1 when SQLite's reading of [s, e) may differ from strtod's: anything
 * but an integer of at most 15 digits (exact either way). */
static int sqlite_may_differ(const char *s, const char *e)
{
    if (s < e && (*s == '-' || *s == '+'))
        s++;
    if (e - s > 15 || s == e)
        return 1;
    for (; s < e; s++)
        if ((unsigned)(*s - '0') >= 10)
            return 1;
    return 0;
}

static int reals_open(reader *r)
{
    struct mpb__log_reals *q = calloc(1, sizeof *q);
    if (q == NULL)
        return mpb__log_fail(r, "out of memory");
    r->reals = q;
    char sql[MPB__REALS_BATCH * 24 + 16] = "SELECT ";
    size_t len = strlen(sql);
    for (int i = 0; i < MPB__REALS_BATCH; i++)
        len += (size_t)snprintf(sql + len, sizeof sql - len,
                                "%sCAST(?%d AS REAL)", i ? "," : "", i + 1);
    if (sqlite3_open_v2(":memory:", &q->db, SQLITE_OPEN_READWRITE |
                        SQLITE_OPEN_NOMUTEX, NULL) != SQLITE_OK ||
        sqlite3_prepare_v2(q->db, sql, -1, &q->st, NULL) != SQLITE_OK)
        return mpb__log_fail(r, "SQLite could not read the values: %s",
                             q->db ? sqlite3_errmsg(q->db) : "out of memory");
    /* Does this SQLite read short decimals as shortly() does? Asked of
     * texts it reads otherwise than strtod (3.40 does), and plain ones. */
    static const char *const probe[] = {
        "0.814637", "0.549012", "0.906472", "0.265514", "0.656028",
        "0.797097", "12.2571", "3.14159", "1e-7", "123456.789", "2.5e3",
        "-0.1", "0.3", "7e22", "9.87654321e-22",
    };
    enum { NUM_PROBES = sizeof probe / sizeof *probe };
    double want[NUM_PROBES];
    for (int i = 0; i < NUM_PROBES; i++) {
        want[i] = NAN;
        sqlite3_bind_text(q->st, i + 1, probe[i], -1, SQLITE_STATIC);
        q->dst[q->n++] = &want[i];
    }
    if (mpb__log_reals_flush(r) != 0)
        return -1;
    q->same = 1;
    for (int i = 0; q->same && i < NUM_PROBES; i++) {
        double got;
        q->same = shortly(probe[i], probe[i] + strlen(probe[i]), &got) &&
                  memcmp(&got, &want[i], sizeof got) == 0;
    }
    return 0;
}

int mpb__log_real_text(reader *r, double *dst, const char *s, size_t n)
{
    if (!isfinite(*dst) || !sqlite_may_differ(s, s + n))
        return 0;
    if (r->reals == NULL && reals_open(r) != 0)
        return -1;
    struct mpb__log_reals *q = r->reals;
    if (q->st == NULL)
        return -1;
    if (q->same && shortly(s, s + n, dst))
        return 0;
    sqlite3_bind_text(q->st, q->n + 1, s, (int)n, SQLITE_STATIC);
    q->dst[q->n++] = dst;
    return q->n == MPB__REALS_BATCH ? mpb__log_reals_flush(r) : 0;
}

void mpb__log_reals_free(reader *r)
{
    if (r->reals == NULL)
        return;
    sqlite3_finalize(r->reals->st);
    sqlite3_close(r->reals->db);
    free(r->reals);
    r->reals = NULL;
}
