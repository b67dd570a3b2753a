/*
 * report_depth.c - `mpb report`'s section on how deep refused paths go:
 * for each planner configuration, the runs whose last stage was refused
 * for a collision, and the distribution of their depth (the bounds stored
 * with each collision verdict, docs/verification.md): median and deepest,
 * lower and upper bound, and how many are under 0.1 mm (upper bound), so
 * that a reader tells a graze from a plunge. Text and markdown only; an
 * experiment without such runs prints nothing.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "report.h"

/* Under this (mm, the upper bound) a refusal is a graze. */
#define GRAZE_MM 0.1

typedef struct depths {
    int64_t config;            /* the configuration being filled */
    int     index;             /* its index in the report's configs */
    long    refused;           /* its refused runs */
    double *lo, *up;           /* their measured depths, mm */
    long    n, cap;
    int     nomem;
} depths;

typedef struct row {
    long        refused, measured, grazes;
    mpb_summary lo, up;
} row;

static int on_depth(void *ud, int64_t config, double lo, double up)
{
    depths *d = ud;
    (void)config;
    d->refused++;
    if (!isfinite(lo) || !isfinite(up))
        return 0;
    if (d->n == d->cap) {
        long cap = d->cap ? 2 * d->cap : 64;
        double *a = realloc(d->lo, (size_t)cap * sizeof *a);
        if (a)
            d->lo = a;
        double *b = a ? realloc(d->up, (size_t)cap * sizeof *b) : NULL;
        if (!b)
            return d->nomem = 1, 1;
        d->up = b;
        d->cap = cap;
    }
    d->lo[d->n] = lo;
    d->up[d->n++] = up;
    return 0;
}

/* One walk over the refusals, in configuration order: each
 * configuration's depths summarised when the next one starts. */
typedef struct all_depths {
    const report *r;
    row          *rows;
    depths        cur;
} all_depths;

static void close_config(all_depths *a)
{
    depths *d = &a->cur;
    if (d->index < 0)
        return;
    row *w = &a->rows[d->index];
    w->refused = d->refused;
    w->measured = d->n;
    for (long i = 0; i < d->n; i++)
        w->grazes += d->up[i] < GRAZE_MM;
    if (d->n > 0) {
        mpb_summarize(d->lo, (int)d->n, &w->lo);
        mpb_summarize(d->up, (int)d->n, &w->up);
    }
    d->refused = d->n = 0;
}

static int on_any(void *ud, int64_t config, double lo, double up)
{
    all_depths *a = ud;
    if (config != a->cur.config) {
        close_config(a);
        a->cur.config = config;
        a->cur.index = -1;
        for (int i = 0; i < a->r->num_configs; i++)
            if (a->r->configs[i].id == config)
                a->cur.index = i;
    }
    return on_depth(&a->cur, config, lo, up);
}

static void cell(char *buf, size_t len, const row *w, double lo, double up)
{
    if (w->measured == 0)
        snprintf(buf, len, "-");
    else
        snprintf(buf, len, "%.3g-%.3g", lo, up);
}

int report_write_depth(mpb_store *s, const report *r, int markdown, FILE *out)
{
    all_depths a = {.r = r, .cur = {.config = -1, .index = -1}};
    if (r->num_configs == 0)
        return MPB_OK;
    if (!(a.rows = calloc((size_t)r->num_configs, sizeof *a.rows)))
        return MPB_ENOMEM;
    int rc = mpb_store_refusal_depths(s, r->experiment_id, on_any, &a);
    close_config(&a);
    if (a.cur.nomem)
        rc = MPB_ENOMEM;
    long any = 0;
    for (int i = 0; i < r->num_configs; i++)
        any += a.rows[i].refused;
    if (rc == MPB_OK && any > 0) {
        if (markdown)
            fprintf(out, "\n### How deep refused paths go\n\nRuns whose "
                    "last stage was refused for a collision; depth in mm at "
                    "the worst configuration examined, lower-upper bound "
                    "(docs/verification.md).\n\n| planner | refused | "
                    "measured | median | deepest | under %g mm |\n"
                    "|---|---:|---:|---:|---:|---:|\n", GRAZE_MM);
        else
            fprintf(out, "\nHow deep refused paths go (runs whose last stage "
                    "was refused for a collision;\ndepth in mm at the worst "
                    "configuration examined, lower-upper bound;\n"
                    "docs/verification.md):\n  %-28s %8s %8s %15s %15s %8s\n",
                    "planner", "refused", "measured", "median", "deepest",
                    "<0.1 mm");
        for (int i = 0; i < r->num_configs; i++) {
            const row *w = &a.rows[i];
            if (w->refused == 0)
                continue;
            char med[40], max[40];
            cell(med, sizeof med, w, w->lo.median, w->up.median);
            cell(max, sizeof max, w, w->lo.max, w->up.max);
            if (markdown)
                fprintf(out, "| %s | %ld | %ld | %s | %s | %ld |\n",
                        r->configs[i].name, w->refused, w->measured, med, max,
                        w->grazes);
            else
                fprintf(out, "  %-28s %8ld %8ld %15s %15s %8ld\n",
                        r->configs[i].name, w->refused, w->measured, med, max,
                        w->grazes);
        }
    }
    free(a.cur.lo);
    free(a.cur.up);
    free(a.rows);
    return rc;
}
