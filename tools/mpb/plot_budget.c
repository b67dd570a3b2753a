/*
 * plot_budget.c - success against the time budget, for `mpb plot`: per
 * problem set and over every problem, the fraction of each
 * configuration's runs that were verified successes within t seconds, for
 * every t up to the time limit, beside the fraction its planner claimed
 * (plot.h). MotionBenchMaker's and VAMP's papers draw their problem sets
 * so; here both curves come from the stored times, without planning again.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpb.h"
#include "plot.h"

/* The times of one configuration's runs in one set (or all). */
typedef struct curve {
    int     runs;              /* finished runs */
    double *verified, *claimed; /* time_total of each such run */
    int     nv, nc, capv, capc;
} curve;

struct plot_budget {
    double   limit;
    int      nconfigs, nsets;
    int64_t *config_ids;
    char   **configs;
    char   **sets;             /* set names; index nsets is "all" */
    int64_t *scene_ids;
    int     *scene_set;
    int      nscenes;
    curve   *curves;           /* [(set) * nconfigs + config], set nsets: all */
    int      nomem;
};

static curve *curve_of(const plot_budget *b, int set, int config)
{
    return &b->curves[(size_t)set * (size_t)b->nconfigs + (size_t)config];
}

static int push(double **v, int *n, int *cap, double x)
{
    if (*n == *cap) {
        int c = *cap ? 2 * *cap : 8;
        double *nv = realloc(*v, (size_t)c * sizeof *nv);
        if (nv == NULL)
            return -1;
        *v = nv;
        *cap = c;
    }
    (*v)[(*n)++] = x;
    return 0;
}

static int on_experiment(void *ud, const mpb_experiment_row *e)
{
    ((plot_budget *)ud)->limit = e->time_limit;
    return 0;
}

static int on_config(void *ud, const mpb_planner_config_row *c)
{
    plot_budget *b = ud;
    if (tool_config_add(&b->config_ids, &b->configs, &b->nconfigs, c) == 0)
        return 0;
    b->nomem = 1;
    return 1;
}

static int on_scene(void *ud, const mpb_scene_row *row)
{
    plot_budget *b = ud;
    if (tool_scene_add(&b->scene_ids, &b->scene_set, &b->nscenes, &b->sets,
                       &b->nsets, row) == 0)
        return 0;
    b->nomem = 1;
    return 1;
}

static int add_run(plot_budget *b, curve *c, const mpb_result_row *row)
{
    c->runs++;
    int claimed = row->status != NULL && strcmp(row->status, "solved") == 0;
    int rc = 0;
    if (claimed && isfinite(row->time_total))
        rc |= push(&c->claimed, &c->nc, &c->capc, row->time_total);
    if (row->success && isfinite(row->time_total))
        rc |= push(&c->verified, &c->nv, &c->capv, row->time_total);
    if (rc)
        b->nomem = 1;
    return rc;
}

static int on_run(void *ud, const mpb_result_row *row)
{
    plot_budget *b = ud;
    int config = 0, set = -1;
    while (config < b->nconfigs && b->config_ids[config] != row->planner_config_id)
        config++;
    for (int i = 0; i < b->nscenes; i++)
        if (b->scene_ids[i] == row->scene_id)
            set = b->scene_set[i];
    if (config == b->nconfigs || set < 0)
        return 0;
    if (add_run(b, curve_of(b, set, config), row) ||
        add_run(b, curve_of(b, b->nsets, config), row))
        return 1;
    return 0;
}

static int by_value(const void *x, const void *y)
{
    double a = *(const double *)x, c = *(const double *)y;
    return (a > c) - (a < c);
}

int plot_budget_read(mpb_store *s, int64_t experiment_id, int64_t scene_id,
                     plot_budget **out)
{
    plot_budget *b = calloc(1, sizeof *b);
    int rc;
    *out = NULL;
    if (b == NULL)
        return MPB_ENOMEM;
    if ((rc = mpb_store_experiment_get(s, experiment_id, on_experiment, b)) ||
        (rc = mpb_store_planner_configs(s, experiment_id, on_config, b)) ||
        (rc = mpb_store_scenes(s, experiment_id, on_scene, b)))
        goto fail;
    b->curves = calloc((size_t)(b->nsets + 1) * (size_t)(b->nconfigs + 1),
                       sizeof *b->curves);
    if (b->curves == NULL) {
        rc = MPB_ENOMEM;
        goto fail;
    }
    if ((rc = mpb_store_results(s, experiment_id, scene_id, NULL, NULL, 0,
                                on_run, b)))
        goto fail;
    for (int i = 0; i <= b->nsets; i++)
        for (int c = 0; c < b->nconfigs; c++) {
            curve *k = curve_of(b, i, c);
            /* qsort() of no array (NULL) is undefined even for 0 items. */
            if (k->nv > 0)
                qsort(k->verified, (size_t)k->nv, sizeof *k->verified, by_value);
            if (k->nc > 0)
                qsort(k->claimed, (size_t)k->nc, sizeof *k->claimed, by_value);
        }
    *out = b;
    return MPB_OK;
fail:
    if (b->nomem)
        rc = MPB_ENOMEM;
    plot_budget_free(b);
    return rc;
}

void plot_budget_free(plot_budget *b)
{
    if (b == NULL)
        return;
    for (int i = 0; b->curves && i <= b->nsets; i++)
        for (int c = 0; c < b->nconfigs; c++) {
            free(curve_of(b, i, c)->verified);
            free(curve_of(b, i, c)->claimed);
        }
    for (int c = 0; c < b->nconfigs; c++)
        free(b->configs[c]);
    for (int i = 0; i < b->nsets; i++)
        free(b->sets[i]);
    free(b->configs);
    free(b->config_ids);
    free(b->sets);
    free(b->scene_ids);
    free(b->scene_set);
    free(b->curves);
    free(b);
}

static const char *set_name(const plot_budget *b, int set)
{
    return set == b->nsets ? "all problems" : b->sets[set];
}

/* The sets drawn: every one, and all of them together when there is more
 * than one. */
static int drawn(const plot_budget *b, int set)
{
    return set < b->nsets || b->nsets > 1;
}

int plot_budget_csv(const plot_budget *b, const char *dir,
                    void (*wrote)(void *ud, const char *path), void *ud)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/budget.csv", dir);
    FILE *f = fopen(path, "w");
    if (f == NULL)
        return MPB_EIO;
    /* A row per step of a curve: the fraction of the runs done by time. */
    fprintf(f, "set,planner,curve,time,fraction,runs\n");
    for (int i = 0; i <= b->nsets; i++) {
        if (!drawn(b, i))
            continue;
        for (int c = 0; c < b->nconfigs; c++) {
            const curve *k = curve_of(b, i, c);
            for (int which = 0; which < 2; which++) {
                const double *t = which ? k->claimed : k->verified;
                int n = which ? k->nc : k->nv;
                for (int j = 0; j < n; j++) {
                    if (j + 1 < n && t[j + 1] == t[j])
                        continue;          /* one step per time */
                    tool_csv_text(f, set_name(b, i));
                    fputc(',', f);
                    tool_csv_text(f, b->configs[c]);
                    fprintf(f, ",%s,%.9g,%.9g,%d\n",
                            which ? "claimed" : "verified", t[j],
                            (double)(j + 1) / k->runs, k->runs);
                }
            }
        }
    }
    int bad = ferror(f);
    if (fclose(f) != 0 || bad)
        return MPB_EIO;
    wrote(ud, path);
    return MPB_OK;
}

/* A curve as a datablock: from (lo, 0) a step at each run's time up to
 * (limit, its final fraction). */
static void datablock(FILE *gp, const char *name, const double *t, int n,
                      int runs, double lo, double limit)
{
    fprintf(gp, "$%s << EOD\n%.9g 0\n", name, lo);
    for (int j = 0; j < n; j++)
        fprintf(gp, "%.9g %.9g\n", fmax(t[j], lo), (double)(j + 1) / runs);
    fprintf(gp, "%.9g %.9g\nEOD\n", limit,
            runs > 0 ? (double)n / runs : 0.0);
}

/* Set i's part of its file name: the set's name as plot_file_part() makes
 * it ("all" for all problems), and "-N" (N = i + 1) added when an earlier
 * set's part is the same ("a b" and "a_b"). */
static void file_part(const plot_budget *b, int i, char *out, size_t size)
{
    char mine[PLOT_PART_MAX + 1], other[PLOT_PART_MAX + 1];
    plot_file_part(mine, sizeof mine, i == b->nsets ? "all" : b->sets[i]);
    int clash = 0;
    for (int j = 0; j < i && !clash; j++) {
        plot_file_part(other, sizeof other, b->sets[j]);
        clash = strcmp(mine, other) == 0;
    }
    if (clash)
        snprintf(out, size, "%s-%d", mine, i + 1);
    else
        snprintf(out, size, "%s", mine);
}

int plot_gnuplot_budget(FILE *gp, const plot_budget *b, const char *dir,
                        const char *ext, plot_glyphs *gl,
                        void (*wrote)(void *ud, const char *path), void *ud)
{
    int plots = 0;
    for (int i = 0; i <= b->nsets; i++) {
        if (!drawn(b, i))
            continue;
        double lo = INFINITY;
        int any = 0;
        for (int c = 0; c < b->nconfigs; c++) {
            const curve *k = curve_of(b, i, c);
            any |= k->runs > 0;
            if (k->nc > 0)
                lo = fmin(lo, k->claimed[0]);
            if (k->nv > 0)
                lo = fmin(lo, k->verified[0]);
        }
        if (!any)
            continue;
        double limit = b->limit > 0 ? b->limit : 1.0;
        /* A decade below the first success, at least 1 us. */
        lo = isfinite(lo) ? fmax(lo / 2, 1e-6) : limit / 1000;
        if (!(lo < limit))
            lo = limit / 1000;
        char part[PLOT_PART_MAX + 16], path[4096];
        file_part(b, i, part, sizeof part);
        snprintf(path, sizeof path, "%s/plot-budget-%s.%s", dir, part, ext);
        plot_begin(gp, path, ext, 900);
        char title[512];
        snprintf(title, sizeof title, "%s: runs solved within the time "
                 "budget", set_name(b, i));
        fprintf(gp, "set title ");
        plot_put_text(gp, title, gl);
        fprintf(gp, ".\"\\n\".");      /* a second line */
        plot_put_text(gp, "solid: verified by mpbench; dotted: claimed by "
                      "the planner", gl);
        fprintf(gp, "\nset logscale x\nset xrange [%.9g:%.9g]\n"
                    "set yrange [0:1.02]\nset xtics mirror scale 1\n"
                    "set grid xtics ytics lc rgb '#dddddd'\n"
                    "set xlabel \"time budget t (s, log scale)\"\n"
                    "set ylabel \"fraction of runs solved by t\"\n"
                    "set key outside right top\n", lo, limit);
        for (int c = 0; c < b->nconfigs; c++) {
            const curve *k = curve_of(b, i, c);
            char name[32];
            snprintf(name, sizeof name, "v%d", c);
            datablock(gp, name, k->verified, k->nv, k->runs, lo, limit);
            snprintf(name, sizeof name, "c%d", c);
            datablock(gp, name, k->claimed, k->nc, k->runs, lo, limit);
        }
        fprintf(gp, "plot ");
        int first = 1;
        for (int c = 0; c < b->nconfigs; c++) {
            if (curve_of(b, i, c)->runs == 0)
                continue;
            const char *color = plot_config_color(c);
            fprintf(gp, "%s$v%d using 1:2 with steps lw 2 lc rgb '%s' title ",
                    first ? "" : ", ", c, color);
            plot_put_text(gp, b->configs[c], gl);
            fprintf(gp, ", $c%d using 1:2 with steps lw 1 dt 3 lc rgb '%s' "
                        "notitle", c, color);
            first = 0;
        }
        fprintf(gp, "\nunset output\n");
        wrote(ud, path);
        plots++;
    }
    return plots;
}

/* ---- what other writers read (plot.h) ------------------------------------- */

int plot_budget_num_sets(const plot_budget *b)
{
    return b->nsets;
}

const char *plot_budget_set(const plot_budget *b, int set)
{
    return set_name(b, set);
}

int plot_budget_drawn(const plot_budget *b, int set)
{
    return drawn(b, set);
}

int plot_budget_num_configs(const plot_budget *b)
{
    return b->nconfigs;
}

const char *plot_budget_config(const plot_budget *b, int config)
{
    return b->configs[config];
}

double plot_budget_limit(const plot_budget *b)
{
    return b->limit;
}

void plot_budget_curve(const plot_budget *b, int set, int config,
                       plot_budget_steps *out)
{
    const curve *k = curve_of(b, set, config);
    *out = (plot_budget_steps){k->runs, k->verified, k->nv, k->claimed, k->nc};
}
