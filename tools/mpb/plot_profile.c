/*
 * plot_profile.c - performance profiles (Dolan and Moré, 2002), for `mpb
 * plot`: per problem set and over every problem, for planning time and
 * for path length, the fraction of the problems on which each
 * configuration is within a factor tau of the best configuration on that
 * problem (plot.h). A problem is a query; a configuration's value on it
 * is the median over its runs there, a run that is no verified success
 * counting as infinite, so that a configuration that fails half its runs
 * or more on a problem has not solved it (its ratio is infinite, never
 * within any tau).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpb.h"
#include "plot.h"

static const char *const metric_name[PLOT_PROFILE_METRICS] = {"time",
                                                              "path_length"};
static const char *const metric_label[PLOT_PROFILE_METRICS] = {
    "planning time", "path length"};

/* One finished run, as the profile needs it. */
typedef struct prun {
    int64_t query;
    int     config, set;
    double  value[PLOT_PROFILE_METRICS];   /* INFINITY unless a success */
} prun;

/* A configuration's ratios to the best over the problems of a set. */
typedef struct ratios {
    double *r;                 /* finite ones, sorted */
    int     n, cap;
} ratios;

struct plot_profile {
    int      nconfigs, nsets;
    int64_t *config_ids;
    char   **configs;
    char   **sets;             /* index nsets: all problems */
    int64_t *scene_ids;
    int     *scene_set;
    int      nscenes;
    prun    *runs;
    int      nruns, capruns;
    int     *problems;         /* per set (and all): problems */
    ratios  *ratio;            /* [(set * METRICS + metric) * nconfigs + c] */
    int      nomem;
};

static ratios *ratio_of(const plot_profile *p, int set, int metric, int config)
{
    return &p->ratio[((size_t)set * PLOT_PROFILE_METRICS + (size_t)metric) *
                     (size_t)p->nconfigs + (size_t)config];
}

static int on_config(void *ud, const mpb_planner_config_row *c)
{
    plot_profile *p = ud;
    if (tool_config_add(&p->config_ids, &p->configs, &p->nconfigs, c) == 0)
        return 0;
    p->nomem = 1;
    return 1;
}

static int on_scene(void *ud, const mpb_scene_row *row)
{
    plot_profile *p = ud;
    if (tool_scene_add(&p->scene_ids, &p->scene_set, &p->nscenes, &p->sets,
                       &p->nsets, row) == 0)
        return 0;
    p->nomem = 1;
    return 1;
}

static int on_run(void *ud, const mpb_result_row *row)
{
    plot_profile *p = ud;
    int config = 0, set = -1;
    while (config < p->nconfigs && p->config_ids[config] != row->planner_config_id)
        config++;
    for (int i = 0; i < p->nscenes && set < 0; i++)
        if (p->scene_ids[i] == row->scene_id)
            set = p->scene_set[i];
    if (config == p->nconfigs || set < 0)
        return 0;
    if (p->nruns == p->capruns) {
        int cap = p->capruns ? 2 * p->capruns : 256;
        prun *nr = realloc(p->runs, (size_t)cap * sizeof *nr);
        if (nr == NULL) {
            p->nomem = 1;
            return 1;
        }
        p->runs = nr;
        p->capruns = cap;
    }
    prun *r = &p->runs[p->nruns++];
    r->query = row->query_id;
    r->config = config;
    r->set = set;
    double v[PLOT_PROFILE_METRICS] = {row->time_total, row->metrics[0]};
    for (int m = 0; m < PLOT_PROFILE_METRICS; m++)
        r->value[m] = row->success && isfinite(v[m]) && v[m] >= 0 ? v[m]
                                                                  : INFINITY;
    return 0;
}

static int by_query_config(const void *x, const void *y)
{
    const prun *a = x, *b = y;
    if (a->query != b->query)
        return (a->query > b->query) - (a->query < b->query);
    return (a->config > b->config) - (a->config < b->config);
}

static int by_value(const void *x, const void *y)
{
    double a = *(const double *)x, c = *(const double *)y;
    return (a > c) - (a < c);
}

/* The median of v[0..n) (sorted here), INFINITY for none; of an even
 * count the mean of the middle two, infinite when either is. */
static double median(double *v, int n)
{
    if (n == 0)
        return INFINITY;
    qsort(v, (size_t)n, sizeof *v, by_value);
    return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

static int push_ratio(ratios *k, double r)
{
    if (k->n == k->cap) {
        int cap = k->cap ? 2 * k->cap : 16;
        double *nr = realloc(k->r, (size_t)cap * sizeof *nr);
        if (nr == NULL)
            return -1;
        k->r = nr;
        k->cap = cap;
    }
    k->r[k->n++] = r;
    return 0;
}

/* One problem: runs[0..n) of one query, by configuration. */
static int add_problem(plot_profile *p, const prun *runs, int n, double *buf,
                       double *value)
{
    int set = runs[0].set;
    for (int m = 0; m < PLOT_PROFILE_METRICS; m++) {
        double best = INFINITY;
        for (int c = 0; c < p->nconfigs; c++) {
            int k = 0;
            for (int i = 0; i < n; i++)
                if (runs[i].config == c)
                    buf[k++] = runs[i].value[m];
            value[c] = median(buf, k);
            best = fmin(best, value[c]);
        }
        for (int c = 0; c < p->nconfigs; c++) {
            if (!isfinite(value[c]))
                continue;           /* not solved: within no factor */
            double r = best > 0 ? value[c] / best : value[c] == 0 ? 1 : INFINITY;
            if (isfinite(r) && (push_ratio(ratio_of(p, set, m, c), r) ||
                                push_ratio(ratio_of(p, p->nsets, m, c), r)))
                return -1;
        }
    }
    p->problems[set]++;
    p->problems[p->nsets]++;
    return 0;
}

int plot_profile_read(mpb_store *s, int64_t experiment_id, plot_profile **out)
{
    static const char *const names[] = {"path_length"};
    plot_profile *p = calloc(1, sizeof *p);
    double *buf = NULL, *value = NULL;
    int rc;
    *out = NULL;
    if (p == NULL)
        return MPB_ENOMEM;
    if ((rc = mpb_store_planner_configs(s, experiment_id, on_config, p)) ||
        (rc = mpb_store_scenes(s, experiment_id, on_scene, p)) ||
        (rc = mpb_store_results(s, experiment_id, 0, NULL, names, 1, on_run, p)))
        goto fail;
    p->problems = calloc((size_t)p->nsets + 1, sizeof *p->problems);
    p->ratio = calloc((size_t)(p->nsets + 1) * PLOT_PROFILE_METRICS *
                      (size_t)(p->nconfigs + 1), sizeof *p->ratio);
    buf = malloc(((size_t)p->nruns + 1) * sizeof *buf);
    value = malloc(((size_t)p->nconfigs + 1) * sizeof *value);
    rc = MPB_ENOMEM;
    if (p->problems == NULL || p->ratio == NULL || buf == NULL || value == NULL)
        goto fail;
    if (p->nruns > 0)
        qsort(p->runs, (size_t)p->nruns, sizeof *p->runs, by_query_config);
    for (int i = 0, j; i < p->nruns; i = j) {
        for (j = i; j < p->nruns && p->runs[j].query == p->runs[i].query; j++)
            ;
        if (add_problem(p, p->runs + i, j - i, buf, value) != 0)
            goto fail;
    }
    for (int i = 0; i <= p->nsets; i++)
        for (int m = 0; m < PLOT_PROFILE_METRICS; m++)
            for (int c = 0; c < p->nconfigs; c++) {
                ratios *k = ratio_of(p, i, m, c);
                if (k->n > 0)
                    qsort(k->r, (size_t)k->n, sizeof *k->r, by_value);
            }
    free(buf);
    free(value);
    *out = p;
    return MPB_OK;
fail:
    if (p->nomem)
        rc = MPB_ENOMEM;
    free(buf);
    free(value);
    plot_profile_free(p);
    return rc;
}

void plot_profile_free(plot_profile *p)
{
    if (p == NULL)
        return;
    for (int i = 0; p->ratio && i <= p->nsets; i++)
        for (int m = 0; m < PLOT_PROFILE_METRICS; m++)
            for (int c = 0; c < p->nconfigs; c++)
                free(ratio_of(p, i, m, c)->r);
    for (int c = 0; c < p->nconfigs; c++)
        free(p->configs[c]);
    for (int i = 0; i < p->nsets; i++)
        free(p->sets[i]);
    free(p->configs);
    free(p->config_ids);
    free(p->sets);
    free(p->scene_ids);
    free(p->scene_set);
    free(p->runs);
    free(p->problems);
    free(p->ratio);
    free(p);
}

static const char *set_name(const plot_profile *p, int set)
{
    return set == p->nsets ? "all problems" : p->sets[set];
}

/* Every set with problems, and all of them together when there are
 * several sets. */
static int drawn(const plot_profile *p, int set)
{
    return p->problems[set] > 0 && (set < p->nsets || p->nsets > 1);
}

int plot_profile_csv(const plot_profile *p, const char *dir,
                     void (*wrote)(void *ud, const char *path), void *ud)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/profile.csv", dir);
    FILE *f = fopen(path, "w");
    if (f == NULL)
        return MPB_EIO;
    /* A row per step: the fraction of the set's problems within tau. */
    fprintf(f, "set,metric,planner,tau,fraction,problems\n");
    for (int i = 0; i <= p->nsets; i++) {
        if (!drawn(p, i))
            continue;
        for (int m = 0; m < PLOT_PROFILE_METRICS; m++)
            for (int c = 0; c < p->nconfigs; c++) {
                const ratios *k = ratio_of(p, i, m, c);
                for (int j = 0; j < k->n; j++) {
                    if (j + 1 < k->n && k->r[j + 1] == k->r[j])
                        continue;          /* one step per tau */
                    tool_csv_text(f, set_name(p, i));
                    fprintf(f, ",%s,", metric_name[m]);
                    tool_csv_text(f, p->configs[c]);
                    fprintf(f, ",%.9g,%.9g,%d\n", k->r[j],
                            (double)(j + 1) / p->problems[i], p->problems[i]);
                }
            }
    }
    int bad = ferror(f);
    if (fclose(f) != 0 || bad)
        return MPB_EIO;
    wrote(ud, path);
    return MPB_OK;
}

/* Set i's part of its file name, as plot_budget.c makes it. */
static void file_part(const plot_profile *p, int i, char *out, size_t size)
{
    char mine[PLOT_PART_MAX + 1], other[PLOT_PART_MAX + 1];
    plot_file_part(mine, sizeof mine, i == p->nsets ? "all" : p->sets[i]);
    int clash = 0;
    for (int j = 0; j < i && !clash; j++) {
        plot_file_part(other, sizeof other, p->sets[j]);
        clash = strcmp(mine, other) == 0;
    }
    if (clash)
        snprintf(out, size, "%s-%d", mine, i + 1);
    else
        snprintf(out, size, "%s", mine);
}

/* One panel: metric m of set i, tau from 1 to hi. */
static void panel(FILE *gp, const plot_profile *p, int i, int m, double hi,
                  plot_glyphs *gl)
{
    fprintf(gp, "set title ");
    plot_put_text(gp, metric_label[m], gl);
    fprintf(gp, "\nset logscale x 2\nset xrange [1:%.9g]\nset yrange [0:1.02]\n"
                "set xtics nomirror scale 1\nset ytics 0.2\n"
                "set grid xtics ytics lc rgb '#dddddd'\n"
                "set xlabel \"tau: within this factor of the best (log scale)\"\n"
                "set ylabel \"fraction of the %d problems\"\n"
                "%s\n", hi, p->problems[i],
                /* One key for both, right of the second: inside either it
                 * hid the curves that end low. */
                m == 0 ? "unset key" : "set key at screen 0.99,0.86 right top");
    /* Over a short range gnuplot's log tics are 1 and 2 alone. */
    if (hi <= 4) {
        static const double tics[] = {1, 1.1, 1.25, 1.5, 2, 3, 4};
        fprintf(gp, "set xtics (");
        for (size_t t = 0; t < sizeof tics / sizeof *tics && tics[t] <= hi; t++)
            fprintf(gp, "%s\"%g\" %g", t ? ", " : "", tics[t], tics[t]);
        fprintf(gp, ")\n");
    }
    for (int c = 0; c < p->nconfigs; c++) {
        const ratios *k = ratio_of(p, i, m, c);
        fprintf(gp, "$p%d_%d << EOD\n1 0\n", m, c);
        for (int j = 0; j < k->n; j++)
            fprintf(gp, "%.9g %.9g\n", k->r[j],
                    (double)(j + 1) / p->problems[i]);
        fprintf(gp, "%.9g %.9g\nEOD\n", hi, (double)k->n / p->problems[i]);
    }
    fprintf(gp, "plot ");
    for (int c = 0; c < p->nconfigs; c++) {
        fprintf(gp, "%s$p%d_%d using 1:2 with steps lw 2 lc rgb '%s' title ",
                c ? ", " : "", m, c, plot_config_color(c));
        plot_put_text(gp, p->configs[c], gl);
    }
    fprintf(gp, "\n");
}

int plot_gnuplot_profile(FILE *gp, const plot_profile *p, const char *dir,
                         const char *ext, plot_glyphs *gl,
                         void (*wrote)(void *ud, const char *path), void *ud)
{
    int plots = 0;
    for (int i = 0; i <= p->nsets; i++) {
        if (!drawn(p, i) || p->nconfigs == 0)
            continue;
        char part[PLOT_PART_MAX + 16], path[4096], title[512];
        file_part(p, i, part, sizeof part);
        snprintf(path, sizeof path, "%s/plot-profile-%s.%s", dir, part, ext);
        plot_begin(gp, path, ext, 1400);
        snprintf(title, sizeof title, "%s: performance profiles, %d problem%s",
                 set_name(p, i), p->problems[i], p->problems[i] == 1 ? "" : "s");
        fprintf(gp, "set multiplot layout 1,2 margins 0.06,0.80,0.12,0.86 "
                    "spacing 0.07,0 title ");
        plot_put_text(gp, title, gl);
        fprintf(gp, ".\"\\n\".");
        plot_put_text(gp, "on each problem, the fraction where a planner's "
                      "median run is within tau of the best planner's", gl);
        fprintf(gp, "\n");
        for (int m = 0; m < PLOT_PROFILE_METRICS; m++) {
            double hi = 2;
            for (int c = 0; c < p->nconfigs; c++) {
                const ratios *k = ratio_of(p, i, m, c);
                if (k->n > 0)
                    hi = fmax(hi, k->r[k->n - 1] * 1.25);
            }
            panel(gp, p, i, m, hi, gl);
        }
        fprintf(gp, "unset multiplot\nunset output\n");
        wrote(ud, path);
        plots++;
    }
    return plots;
}
