/*
 * ompl_log.c - the reader of OMPL's (and MoveIt's) benchmark logs
 * (ompl_log.h): the header, each planner's block and its progress, read
 * with the cursor of ompl_log_reader.c and the values of
 * ompl_log_values.c.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "interop/ompl_log_reader.h"

/* "name TYPE" lines (the type is the last word) into *out; *count says
 * how many are filled, for freeing after a failure. */
static int property_lines(reader *r, long n, mpb_ompl_property **out,
                          int *count)
{
    if (n > MAX_PROPERTIES)
        return mpb__log_fail(r, "%ld properties is more than a log holds", n);
    mpb_ompl_property *p = calloc(n ? (size_t)n : 1, sizeof *p);
    if (p == NULL)
        return mpb__log_fail(r, "out of memory");
    *out = p;
    *count = (int)n;    /* unfilled entries are NULL: freeing them is fine */
    for (long i = 0; i < n; i++) {
        char *s = mpb__log_need_line(r, "a property 'name TYPE'");
        if (s == NULL)
            return -1;
        char *sp = strrchr(s, ' ');
        if (sp == NULL || sp == s)
            return mpb__log_fail(r, "expected a property 'name TYPE', found '%.60s'", s);
        *sp = '\0';
        if ((p[i].name = mpb__log_dup(r, s)) == NULL ||
            (p[i].type = mpb__log_dup(r, sp + 1)) == NULL)
            return -1;
        for (long k = 0; k < i; k++)
            if (strcmp(p[k].name, p[i].name) == 0)
                return mpb__log_fail(r, "the property '%.60s' a second time", p[i].name);
        int known = 0;
        for (int k = 0; k < V_TIME; k++)
            known |= strcmp(p[i].type, mpb__log_kind_names[k]) == 0;
        if (!known)
            return mpb__log_fail(r, "unknown property type '%.60s' (not REAL, INTEGER, "
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

    if (mpb__log_count_line(r, "runs", &nr) != 0)
        return -1;
    if (nr != pl->num_runs)
        return mpb__log_fail(r, "%ld runs of progress for %ld runs", nr, pl->num_runs);
    pl->progress_start = calloc((size_t)nr + 1, sizeof *pl->progress_start);
    vals = calloc((size_t)q + 1, sizeof *vals);
    kinds = malloc((size_t)q);
    limits = malloc((size_t)q * sizeof *limits);
    if (pl->progress_start == NULL || vals == NULL || kinds == NULL ||
        limits == NULL) {
        mpb__log_fail(r, "out of memory");
        goto done;
    }
    mpb__log_kinds_of(r, pl->progress_properties, q, kinds, limits);
    for (long i = 0; i < nr; i++) {
        if ((s = mpb__log_need_line(r, "a run's progress")) == NULL)
            goto done;
        pl->progress_start[i] = (long)(used / (size_t)q);
        char *sample = s;
        while (*sample) {
            char *semi = strchr(sample, ';');
            if (semi)
                *semi = '\0';
            if (*sample) {
                int k = mpb__log_split(sample, ',', vals, (int)q + 1);
                if (k == (int)q + 1 && vals[q][0] == '\0')
                    k--;
                if (k != (int)q) {
                    mpb__log_fail(r, "a progress sample of %s has %d values, not %ld",
                         pl->name, k, q);
                    goto done;
                }
                if (used + (size_t)q > cap) {
                    /* The values waiting for SQLite's reading move. */
                    if (mpb__log_reals_flush(r) != 0)
                        goto done;
                    cap = cap ? 2 * cap : 64 * (size_t)q;
                    double *t = realloc(pl->progress, cap * sizeof *t);
                    if (t == NULL) {
                        mpb__log_fail(r, "out of memory");
                        goto done;
                    }
                    pl->progress = t;
                }
                for (long j = 0; j < q; j++) {
                    long to = j == at ? 0 : j < at ? j + 1 : j;
                    /* A sample without a time cannot be placed (the
                     * databases' column is NOT NULL). */
                    double v = mpb__log_value_of(vals[j]);
                    if (!mpb__log_value_ok(vals[j], vals[j] + strlen(vals[j]), kinds[to],
                                  limits[to]) ||
                        (to == 0 && !isfinite(v))) {
                        char where[128];
                        snprintf(where, sizeof where, "the progress of run %ld "
                                 "of %.60s", i + 1, pl->name);
                        mpb__log_not_a_value(r, where, vals[j],
                                    &pl->progress_properties[to], kinds[to],
                                    limits[to]);
                        goto done;
                    }
                    pl->progress[used + (size_t)to] = v;
                    if ((kinds[to] == V_REAL || kinds[to] == V_TIME) &&
                        mpb__log_real_text(r, &pl->progress[used + (size_t)to],
                                           r->raw + (vals[j] - r->buf),
                                           strlen(vals[j])) != 0)
                        goto done;
                }
                used += (size_t)q;
            }
            if (!semi)
                break;
            sample = semi + 1;
        }
    }
    pl->progress_start[nr] = (long)(used / (size_t)q);
    if (mpb__log_reals_flush(r) != 0)
        goto done;
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
    char *s = mpb__log_need_line(r, "a planner's name");
    if (s == NULL || (pl->name = mpb__log_dup(r, s)) == NULL)
        return -1;
    if (*s == '\0')
        return mpb__log_fail(r, "expected a planner's name, found an empty line");
    for (int k = 0; k < index; k++)
        if (strcmp(log->planners[k].name, pl->name) == 0)
            return mpb__log_fail(r, "the planner '%.60s' a second time", pl->name);
    if (mpb__log_count_line(r, "common properties", &n) != 0)
        return -1;
    size_t len = 0, tlen = 0;
    pl->settings = calloc(1, 1);
    pl->settings_text = calloc(1, 1);
    if (pl->settings == NULL || pl->settings_text == NULL)
        return mpb__log_fail(r, "out of memory");
    for (long i = 0; i < n; i++) {
        if ((s = mpb__log_need_line(r, "a common property")) == NULL)
            return -1;
        /* The script's form: the line as written, its end, then ';'. */
        char *st = realloc(pl->settings_text, tlen + r->raw_len + 3);
        if (st == NULL)
            return mpb__log_fail(r, "out of memory");
        pl->settings_text = st;
        memcpy(st + tlen, r->raw, r->raw_len);
        tlen += r->raw_len;
        memcpy(st + tlen, "\n;", 3);
        tlen += 2;
        size_t k = strlen(s);
        char *t = realloc(pl->settings, len + k + 2);
        if (t == NULL)
            return mpb__log_fail(r, "out of memory");
        pl->settings = t;
        if (len)
            t[len++] = ';';
        memcpy(t + len, s, k + 1);
        len += k;
    }
    long np;
    if (mpb__log_count_line(r, "properties for each run", &np) != 0 ||
        property_lines(r, np, &pl->properties, &pl->num_properties) != 0)
        return -1;
    if (mpb__log_count_line(r, "runs", &pl->num_runs) != 0)
        return -1;
    size_t cells = (size_t)pl->num_runs * (size_t)(np ? np : 1);
    pl->values = malloc(cells * sizeof *pl->values);
    unsigned char *kinds = malloc((size_t)np + 1);
    long *limits = malloc(((size_t)np + 1) * sizeof *limits);
    if (pl->values == NULL || kinds == NULL || limits == NULL) {
        free(kinds);
        free(limits);
        return mpb__log_fail(r, "out of memory");
    }
    mpb__log_kinds_of(r, pl->properties, np, kinds, limits);
    for (long i = 0; i < pl->num_runs; i++) {
        if ((s = mpb__log_need_line(r, "a run's values")) == NULL)
            break;
        int extra_empty, bad;
        char *bad_text = NULL;
        int k = mpb__log_run_values(r, pl, i, s, pl->values + (size_t)i * (size_t)np,
                           (int)np, &extra_empty, kinds, limits, &bad,
                           &bad_text);
        if (r->failed)
            break;
        /* The trailing "; " leaves one empty field more. */
        if (k == (int)np + 1 && extra_empty)
            k--;
        if (k != (int)np) {
            mpb__log_fail(r, "run %ld of %s has %d values, not %ld", i + 1,
                 pl->name, k, np);
            break;
        }
        if (bad >= 0) {
            char where[128];
            snprintf(where, sizeof where, "run %ld of %.60s", i + 1, pl->name);
            mpb__log_not_a_value(r, where, bad_text, &pl->properties[bad], kinds[bad],
                        limits[bad]);
            break;
        }
    }
    free(kinds);
    free(limits);
    if (r->failed || mpb__log_reals_flush(r) != 0)
        return -1;

    if ((s = mpb__log_need_line(r, "'.' or progress properties")) == NULL)
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
        return mpb__log_fail(r, "expected '.' or 'N progress properties for each run', "
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
    if ((s = mpb__log_need_line(r, "'.'")) == NULL)
        return -1;
    if (strcmp(s, ".") != 0)
        return mpb__log_fail(r, "expected '.' after %s's runs, found '%.60s'", pl->name, s);
    return 0;
}

/* An experiment property "name TYPE = value" into log->params. */
static int param_line(reader *r, mpb_ompl_log *log)
{
    char *s = mpb__log_need_line(r, "an experiment property 'name TYPE = value'");
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
        return mpb__log_fail(r, "expected an experiment property 'name TYPE = value', "
                    "found '%.60s'", s);
    }
    *sp = '\0';
    /* The type becomes a column's declared type: a word, maybe with a
     * size, "VARCHAR(512)". */
    if (strspn(sp + 1, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
               "0123456789_(),") != strlen(sp + 1))
        return mpb__log_fail(r, "'%.60s' is not a type (the experiment property "
                    "'%.60s')", sp + 1, s);
    for (int i = 0; i < log->num_params; i++)
        if (strcmp(log->params[i].name, s) == 0)
            return mpb__log_fail(r, "the experiment property '%.60s' a second time", s);
    mpb_ompl_param *p = &log->params[log->num_params++];
    if ((p->name = mpb__log_dup(r, s)) == NULL || (p->type = mpb__log_dup(r, sp + 1)) == NULL ||
        (p->value = mpb__log_dup(r, value)) == NULL)
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
        return mpb__log_fail(r, "out of memory");
    const char *f = r->raw, *end = r->raw + r->raw_len;
    for (int i = 0; i < n; i++) {
        const char *bar = memchr(f, '|', (size_t)(end - f));
        const char *stop = bar ? bar : end;
        char *v = strndup(f, (size_t)(stop - f));
        if (v == NULL)
            return mpb__log_fail(r, "out of memory");
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
    char *s = mpb__log_need_line(r, "'OMPL version ...'");
    if (s == NULL)
        return -1;
    /* "OMPL version 1.5.2", "MoveIt version 1.1.9", "MoveIt! version ...";
     * Debian's OMPL 1.5 writes "OMPL version " with no number. */
    char *v = strstr(s, " version");
    if (v == NULL || v == s || (v[8] != ' ' && v[8] != '\0'))
        return mpb__log_fail(r, "expected 'OMPL version X' (or MoveIt's), found '%.60s'", s);
    *v = '\0';
    const char *number = v[8] ? v + 9 : "";
    char version[256];
    snprintf(version, sizeof version, "%s%s%s", s, *number ? " " : "", number);
    if ((log->version = mpb__log_dup(r, version)) == NULL)
        return -1;
    if ((s = mpb__log_need_line(r, "'Experiment NAME'")) == NULL)
        return -1;
    const char *name = mpb__log_after(s, "Experiment");
    if (name == NULL)
        return mpb__log_fail(r, "expected 'Experiment NAME', found '%.60s'", s);
    if ((log->experiment = mpb__log_dup(r, name)) == NULL)
        return -1;
    /* Experiment properties (OMPL 1.5), then the host. */
    if ((s = mpb__log_need_line(r, "'Running on HOST'")) == NULL)
        return -1;
    char *end;
    long k = strtol(s, &end, 10);
    if (end != s && strcmp(end, " experiment properties") == 0) {
        if (k < 0)
            return mpb__log_fail(r, "'%.60s': not a count", s);
        if (k > MAX_PROPERTIES)
            return mpb__log_fail(r, "%ld experiment properties is more than a log holds", k);
        if ((log->params = calloc(k ? (size_t)k : 1, sizeof *log->params)) == NULL)
            return mpb__log_fail(r, "out of memory");
        for (long i = 0; i < k; i++)
            if (param_line(r, log) != 0)
                return -1;
        if ((s = mpb__log_need_line(r, "'Running on HOST'")) == NULL)
            return -1;
    }
    const char *host = mpb__log_after(s, "Running on");
    if (host == NULL)
        return mpb__log_fail(r, "expected 'Running on HOST', found '%.60s'", s);
    if ((log->host = mpb__log_dup(r, host)) == NULL)
        return -1;
    if ((s = mpb__log_need_line(r, "'Starting at DATE'")) == NULL)
        return -1;
    const char *date = mpb__log_after(s, "Starting at");
    if (date == NULL)
        return mpb__log_fail(r, "expected 'Starting at DATE', found '%.60s'", s);
    /* Boost's to_simple_string(): "2026-Nov-22 11:22:29", or ISO's
     * "2026-11-22 11:22:29". */
    if (strlen(date) < 8 || strspn(date, "0123456789") != 4 || date[4] != '-')
        return mpb__log_fail(r, "'%.60s' is not a date (YYYY-MM-DD ...)", date);
    if ((log->date = mpb__log_dup(r, date)) == NULL || mpb__log_block(r, &log->setup) != 0)
        return -1;
    /* cpuinfo is optional: another block, or the seed line. */
    const char *mark = r->p;
    long line = r->line;
    if ((s = mpb__log_need_line(r, "'SEED is the random seed'")) == NULL)
        return -1;
    if (strcmp(s, "<<<|") == 0) {
        r->p = mark;
        r->line = line;
        if (mpb__log_block(r, &log->cpuinfo) != 0 ||
            (s = mpb__log_need_line(r, "'SEED is the random seed'")) == NULL)
            return -1;
    }
    char *seed_end = strstr(s, " is the random seed");
    if (seed_end == NULL || seed_end[19] != '\0')
        return mpb__log_fail(r, "expected 'SEED is the random seed', found '%.60s'", s);
    *seed_end = '\0';
    if (*s == '\0' || strspn(s, "0123456789") != strlen(s))
        return mpb__log_fail(r, "'%.60s' is not a random seed (a number)", s);
    if ((log->seed = mpb__log_dup(r, s)) == NULL)
        return -1;
    if (mpb__log_number_line(r, "seconds per run", &log->time_limit) != 0 ||
        mpb__log_number_line(r, "MB per run", &log->memory_limit) != 0)
        return -1;
    /* Optional "N runs per planner"; then the time spent. */
    log->runs_per_planner = -1;
    if ((s = mpb__log_need_line(r, "'S seconds spent to collect the data'")) == NULL)
        return -1;
    double t = strtod(s, &end);
    if (end != s && strcmp(end, " runs per planner") == 0) {
        if (!(t >= 0 && t <= MAX_COUNT))
            return mpb__log_fail(r, "%.60s: not a run count", s);
        log->runs_per_planner = (long)t;
        if ((s = mpb__log_need_line(r, "'S seconds spent to collect the data'")) == NULL)
            return -1;
        t = strtod(s, &end);
    }
    if (end == s || strcmp(end, " seconds spent to collect the data") != 0)
        return mpb__log_fail(r, "expected 'S seconds spent to collect the data', "
                    "found '%.60s'", s);
    log->total_time = t;
    /* Optional enums, then the planner count. */
    if ((s = mpb__log_need_line(r, "'P planners'")) == NULL)
        return -1;
    long n = strtol(s, &end, 10);
    if (end != s && (strcmp(end, " enum types") == 0 ||
                     strcmp(end, " enum type") == 0)) {
        if (n < 0)
            return mpb__log_fail(r, "'%.60s': not a count", s);
        if (n > MAX_PROPERTIES)
            return mpb__log_fail(r, "%ld enum types is more than a log holds", n);
        r->enums = calloc(n ? (size_t)n : 1, sizeof *r->enums);
        log->enums = calloc(n ? (size_t)n : 1, sizeof *log->enums);
        if (r->enums == NULL || log->enums == NULL)
            return mpb__log_fail(r, "out of memory");
        for (long i = 0; i < n; i++) {
            if ((s = mpb__log_need_line(r, "an enum 'name|value|...'")) == NULL)
                return -1;
            char *bar = strchr(s, '|');
            if (bar == NULL || bar == s)
                return mpb__log_fail(r, "expected an enum 'name|value|...', found '%.60s'", s);
            if (enum_line(r, log) != 0)
                return -1;
            *bar = '\0';
            long count = 1;
            for (const char *c = bar + 1; *c; c++)
                count += *c == '|';
            if ((r->enums[i].name = mpb__log_dup(r, s)) == NULL)
                return -1;
            r->enums[i].count = count;
            r->num_enums = i + 1;
        }
        if ((s = mpb__log_need_line(r, "'P planners'")) == NULL)
            return -1;
        n = strtol(s, &end, 10);
    }
    if (end == s || n < 0 || strcmp(end, " planners") != 0)
        return mpb__log_fail(r, "expected 'P planners', found '%.60s'", s);
    if (n > MAX_PROPERTIES)
        return mpb__log_fail(r, "%ld planners is more than a log holds", n);
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

int mpb_ompl_log_open(const char *text, size_t len, mpb_ompl_log **out,
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
        mpb__log_fail(&r, "out of memory");
        goto fail;
    }
    for (int i = 0; i < log->num_planners; i++)
        if (planner_block(&r, log, i) != 0)
            goto fail;
    /* A planner count too small leaves planners unread: nothing may
     * follow the last one but blank lines. */
    for (const char *s; (s = mpb__log_next_line(&r)) != NULL;)
        if (*s) {
            mpb__log_fail(&r, "text after the last planner");
            goto fail;
        }
    if (r.failed)
        goto fail;
    free(r.buf);
    free_enums(&r);
    mpb__log_reals_free(&r);
    *out = log;
    return MPB_OK;
fail:
    rc = r.err && strstr(r.err, "out of memory") ? MPB_ENOMEM : MPB_EPARSE;
    mpb_ompl_log_close(log);
done:
    free(r.buf);
    free_enums(&r);
    mpb__log_reals_free(&r);
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

void mpb_ompl_log_close(mpb_ompl_log *log)
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
