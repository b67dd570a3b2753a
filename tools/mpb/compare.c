/*
 * compare.c - `mpb compare`: planner configurations compared problem by
 * problem, with intervals and paired tests, over each problem set and
 * over every problem. The question it answers: is A faster (or shorter)
 * than B on the same problems, and how sure is that?
 *
 * Per configuration and problem (query), its runs give: solved (more than
 * half of the runs verified successes), a time (the median over the runs
 * of time_total, a run that is no success counted at the time limit: the
 * budget it used up) and a path length (the median over its successful
 * runs). A pair is compared on the problems both ran: how many each
 * solved alone; the per-problem time ratio A/B on the problems at least
 * one solved, its median with a distribution-free 95 % interval and the
 * Wilcoxon signed-rank test of the log ratios; the path-length ratio
 * likewise on the problems both solved. Every pair of an experiment gets
 * its p values adjusted together by Holm's method (stats.h).
 */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpbench/stats.h"
#include "mpbench/store.h"
#include "mpb.h"

#define CMD "compare"
#define ALPHA 0.05

static void usage(FILE *out)
{
    fprintf(out,
        "usage: mpb compare [-e ID] [-s SET] [-f text|csv] DB [A B]\n"
        "\n"
        "Compare planner configurations (as `mpb report` names them, e.g.\n"
        "ompl/RRTConnect) on the problems both ran, one problem set at a time\n"
        "and over every problem. A problem set is the scene's `set:` in the\n"
        "experiment file, else the part of its name before its last '/'\n"
        "(MotionBenchMaker's box_panda/0001 is in box_panda), else the scene.\n"
        "\n"
        "With A and B: how many problems each solved alone, the median of the\n"
        "per-problem time ratio A/B with its 95 %% interval and the Wilcoxon\n"
        "signed-rank test's p value (on the problems at least one solved; a\n"
        "run that is no verified success counts at the time limit), and the\n"
        "path-length ratio likewise (on the problems both solved). Without\n"
        "them: every pair, as a matrix of time ratios with Holm-adjusted p\n"
        "values, and the differences significant at 5 %%.\n"
        "\n"
        "Options:\n"
        "  -e, --experiment ID  the experiment (default: the newest)\n"
        "  -s, --set SET        only this problem set\n"
        "  -f, --format F       text (default) or csv (one row per set and\n"
        "                       pair, every number)\n"
        "  -h, --help           this text\n"
        "\n"
        "Exit status: 0, 1 on an error (no such experiment or configuration),\n"
        "2 on a bad command line. docs/reports.md.\n");
}

/* What one configuration did on one problem. */
typedef struct cell {
    int     runs, successes;
    double *times;      /* per run: time_total, or the limit if no success */
    double *lengths;    /* per successful run: path_length */
    int     cap_t, cap_l;
} cell;

typedef struct data {
    double   limit;
    int      nc, nq, ns;         /* configurations, queries, sets */
    int64_t *config_ids;
    char   **config_names;
    int64_t *scene_ids;
    int     *scene_set;          /* per scene: its set's index */
    int      num_scenes;
    char   **set_names;
    int64_t *query_ids;
    int     *query_set;
    cell    *cells;              /* [config * nq + query] */
    int      nomem;
} data;

static int grow(double **v, int *cap, int n)
{
    if (n < *cap)
        return 0;
    int c = *cap ? 2 * *cap : 4;
    double *nv = realloc(*v, (size_t)c * sizeof *nv);
    if (nv == NULL)
        return -1;
    *v = nv;
    *cap = c;
    return 0;
}

static int on_experiment(void *ud, const mpb_experiment_row *e)
{
    ((data *)ud)->limit = e->time_limit;
    return 0;
}

static int on_config(void *ud, const mpb_planner_config_row *c)
{
    data *d = ud;
    int64_t *ids = realloc(d->config_ids, (size_t)(d->nc + 1) * sizeof *ids);
    if (ids != NULL)
        d->config_ids = ids;
    char **names = ids ? realloc(d->config_names,
                                 (size_t)(d->nc + 1) * sizeof *names) : NULL;
    if (names != NULL)
        d->config_names = names;
    if (ids == NULL || names == NULL ||
        (names[d->nc] = strdup(c->name)) == NULL) {
        d->nomem = 1;
        return 1;
    }
    ids[d->nc++] = c->id;
    return 0;
}

/* The index of the problem set a scene belongs to (tool_problem_set()),
 * added if new; -1 without memory. */
static int set_index(data *d, const mpb_scene_row *scene)
{
    const char *set = tool_problem_set(scene);
    for (int i = 0; i < d->ns; i++)
        if (strcmp(d->set_names[i], set) == 0)
            return i;
    char **names = realloc(d->set_names, (size_t)(d->ns + 1) * sizeof *names);
    if (names == NULL)
        return -1;
    d->set_names = names;
    if ((names[d->ns] = strdup(set)) == NULL)
        return -1;
    return d->ns++;
}

static int on_scene(void *ud, const mpb_scene_row *s)
{
    data *d = ud;
    int set = set_index(d, s);
    int64_t *ids = set < 0 ? NULL : realloc(d->scene_ids,
                              (size_t)(d->num_scenes + 1) * sizeof *ids);
    if (ids != NULL)
        d->scene_ids = ids;
    int *sets = ids ? realloc(d->scene_set,
                              (size_t)(d->num_scenes + 1) * sizeof *sets) : NULL;
    if (sets == NULL) {
        d->nomem = 1;
        return 1;
    }
    d->scene_set = sets;
    ids[d->num_scenes] = s->id;
    sets[d->num_scenes++] = set;
    return 0;
}

static int on_query(void *ud, const mpb_query_row *q)
{
    data *d = ud;
    int set = -1;
    for (int i = 0; i < d->num_scenes; i++)
        if (d->scene_ids[i] == q->scene_id)
            set = d->scene_set[i];
    int64_t *ids = realloc(d->query_ids, (size_t)(d->nq + 1) * sizeof *ids);
    if (ids != NULL)
        d->query_ids = ids;
    int *sets = ids ? realloc(d->query_set, (size_t)(d->nq + 1) * sizeof *sets)
                    : NULL;
    if (sets == NULL) {
        d->nomem = 1;
        return 1;
    }
    d->query_set = sets;
    ids[d->nq] = q->id;
    sets[d->nq++] = set;
    return 0;
}

static int find(const int64_t *ids, int n, int64_t id)
{
    for (int i = 0; i < n; i++)
        if (ids[i] == id)
            return i;
    return -1;
}

static int on_run(void *ud, const mpb_result_row *row)
{
    data *d = ud;
    int c = find(d->config_ids, d->nc, row->planner_config_id);
    int q = find(d->query_ids, d->nq, row->query_id);
    if (c < 0 || q < 0)
        return 0;
    cell *x = &d->cells[(size_t)c * (size_t)d->nq + (size_t)q];
    double t = row->success && isfinite(row->time_total) ? row->time_total
                                                         : d->limit;
    if (grow(&x->times, &x->cap_t, x->runs) != 0) {
        d->nomem = 1;
        return 1;
    }
    x->times[x->runs++] = t;
    if (row->success) {
        if (grow(&x->lengths, &x->cap_l, x->successes) != 0) {
            d->nomem = 1;
            return 1;
        }
        x->lengths[x->successes++] = row->metrics[0];   /* NaN: none */
    }
    return 0;
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median_of(double *v, int n)
{
    int m = 0;
    for (int i = 0; i < n; i++)
        if (isfinite(v[i]))
            v[m++] = v[i];
    if (m == 0)
        return NAN;
    qsort(v, (size_t)m, sizeof *v, by_value);
    return mpb_quantile(v, m, 0.5);
}

/* One side of a comparison: a ratio's median, interval and p value. */
typedef struct ratio {
    int    n;              /* problems compared */
    double median, lo, hi, p;
} ratio;

typedef struct pair {
    int   a, b;
    int   problems, both, only_a, only_b, neither;
    ratio time, length;
    double time_p_holm;
} pair;

/* ratio of x[i] / y[i] over n problems: median, interval, signed-rank p of
 * the log ratios. x and y are overwritten. */
static int ratio_of(double *x, double *y, int n, ratio *r)
{
    *r = (ratio){.n = n, .median = NAN, .lo = NAN, .hi = NAN, .p = NAN};
    if (n == 0)
        return MPB_OK;
    for (int i = 0; i < n; i++) {
        double a = fmax(x[i], 1e-9), b = fmax(y[i], 1e-9);
        x[i] = a / b;
        y[i] = log(x[i]);   /* of the ratio: equal ratios tie exactly */
    }
    int rc = mpb_signed_rank_test(y, n, NULL, &r->p);
    if (rc != MPB_OK)
        return rc;
    qsort(x, (size_t)n, sizeof *x, by_value);
    r->median = mpb_quantile(x, n, 0.5);
    return mpb_median_interval(x, n, &r->lo, &r->hi, NULL);
}

/* Compare configurations a and b on the problems of set (-1: all). */
static int compare(data *d, int a, int b, int set, pair *out)
{
    *out = (pair){.a = a, .b = b};
    size_t nq = (size_t)d->nq;
    double *ta = malloc((nq + 1) * sizeof *ta), *tb = malloc((nq + 1) * sizeof *tb);
    double *la = malloc((nq + 1) * sizeof *la), *lb = malloc((nq + 1) * sizeof *lb);
    int rc = MPB_ENOMEM, nt = 0, nl = 0;
    if (!ta || !tb || !la || !lb)
        goto done;
    for (int q = 0; q < d->nq; q++) {
        if (set >= 0 && d->query_set[q] != set)
            continue;
        cell *x = &d->cells[(size_t)a * nq + (size_t)q];
        cell *y = &d->cells[(size_t)b * nq + (size_t)q];
        if (x->runs == 0 || y->runs == 0)
            continue;
        out->problems++;
        int sa = 2 * x->successes > x->runs, sb = 2 * y->successes > y->runs;
        out->both += sa && sb;
        out->only_a += sa && !sb;
        out->only_b += !sa && sb;
        out->neither += !sa && !sb;
        if (sa || sb) {
            ta[nt] = median_of(x->times, x->runs);
            tb[nt++] = median_of(y->times, y->runs);
        }
        if (sa && sb) {
            la[nl] = median_of(x->lengths, x->successes);
            lb[nl] = median_of(y->lengths, y->successes);
            if (isfinite(la[nl]) && isfinite(lb[nl]))
                nl++;
        }
    }
    if ((rc = ratio_of(ta, tb, nt, &out->time)) == MPB_OK)
        rc = ratio_of(la, lb, nl, &out->length);
done:
    free(ta);
    free(tb);
    free(la);
    free(lb);
    return rc;
}

static const char *verdict(const ratio *r, double p, const char *a,
                           const char *b, const char *less, char *buf,
                           size_t size)
{
    if (r->n == 0 || !(p < ALPHA) || r->median == 1)
        snprintf(buf, size, "no significant difference");
    else
        snprintf(buf, size, "%s %s", r->median < 1 ? a : b, less);
    return buf;
}

static void print_pair(const data *d, const pair *p, const char *set)
{
    const char *a = d->config_names[p->a], *b = d->config_names[p->b];
    char v[512];
    printf("%s vs %s, %s: %d problems both ran\n", a, b, set, p->problems);
    printf("  solved: both %d, only %s %d, only %s %d, neither %d\n", p->both,
           a, p->only_a, b, p->only_b, p->neither);
    if (p->time.n > 0)
        printf("  time A/B (%d problem%s at least one solved): median %.3g, "
               "95 %% interval %.3g-%.3g, signed-rank p = %.2g: %s\n",
               p->time.n, p->time.n == 1 ? "" : "s", p->time.median, p->time.lo, p->time.hi, p->time.p,
               verdict(&p->time, p->time.p, a, b, "faster", v, sizeof v));
    else
        printf("  time: no problem solved by either\n");
    if (p->length.n > 0)
        printf("  path length A/B (%d problem%s both solved): median %.3g, "
               "95 %% interval %.3g-%.3g, signed-rank p = %.2g: %s\n",
               p->length.n, p->length.n == 1 ? "" : "s", p->length.median, p->length.lo, p->length.hi,
               p->length.p, verdict(&p->length, p->length.p, a, b, "shorter",
                                    v, sizeof v));
    else
        printf("  path length: no problem solved by both\n");
}

static void csv_text(const char *s)
{
    putchar('"');
    for (; *s; s++) {
        if (*s == '"')
            putchar('"');
        putchar(*s);
    }
    putchar('"');
}

static void print_csv(const data *d, const pair *p, const char *set)
{
    csv_text(set);
    putchar(',');
    csv_text(d->config_names[p->a]);
    putchar(',');
    csv_text(d->config_names[p->b]);
    printf(",%d,%d,%d,%d,%d,%d,%.9g,%.9g,%.9g,%.9g,%.9g,%d,%.9g,%.9g,%.9g,"
           "%.9g\n", p->problems, p->both, p->only_a, p->only_b, p->neither,
           p->time.n, p->time.median, p->time.lo, p->time.hi, p->time.p,
           p->time_p_holm, p->length.n, p->length.median, p->length.lo,
           p->length.hi, p->length.p);
}

/* Every pair of configurations on one set (-1: all problems). */
static int all_pairs(data *d, int set, int csv)
{
    const char *name = set < 0 ? "all problems" : d->set_names[set];
    int n = d->nc * (d->nc - 1) / 2, k = 0, rc = MPB_OK;
    pair *pairs = calloc((size_t)(n > 0 ? n : 1), sizeof *pairs);
    double *p = calloc((size_t)(n > 0 ? n : 1), sizeof *p);
    if (pairs == NULL || p == NULL) {
        rc = MPB_ENOMEM;
        goto done;
    }
    for (int a = 0; a < d->nc; a++)
        for (int b = a + 1; b < d->nc; b++, k++) {
            if ((rc = compare(d, a, b, set, &pairs[k])) != MPB_OK)
                goto done;
            p[k] = isnan(pairs[k].time.p) ? 1.0 : pairs[k].time.p;
        }
    if ((rc = mpb_holm(p, n, p)) != MPB_OK)
        goto done;
    for (k = 0; k < n; k++)
        pairs[k].time_p_holm = p[k];
    if (csv) {
        for (k = 0; k < n; k++)
            print_csv(d, &pairs[k], name);
        goto done;
    }
    printf("%s: time ratio row/column (median over the problems either "
           "solved), * where Holm-adjusted p < 0.05\n", name);
    printf("%-28s", "");
    for (int b = 0; b < d->nc; b++)
        printf(" %8d", b + 1);
    printf("\n");
    for (int a = 0; a < d->nc; a++) {
        printf("%2d %-25.25s", a + 1, d->config_names[a]);
        for (int b = 0; b < d->nc; b++) {
            if (a == b) {
                printf(" %8s", "-");
                continue;
            }
            int lo = a < b ? a : b, hi = a < b ? b : a;
            int idx = lo * d->nc - lo * (lo + 1) / 2 + (hi - lo - 1);
            const pair *q = &pairs[idx];
            double r = a < b ? q->time.median : 1.0 / q->time.median;
            char cellbuf[16];
            if (q->time.n == 0)
                snprintf(cellbuf, sizeof cellbuf, "n/a");
            else
                snprintf(cellbuf, sizeof cellbuf, "%.3g%s", r,
                         q->time_p_holm < ALPHA ? "*" : "");
            printf(" %8s", cellbuf);
        }
        printf("\n");
    }
    int any = 0;
    for (k = 0; k < n; k++) {
        const pair *q = &pairs[k];
        if (!(q->time_p_holm < ALPHA) || q->time.median == 1)
            continue;
        int faster = q->time.median < 1 ? q->a : q->b;
        int slower = faster == q->a ? q->b : q->a;
        double r = q->time.median < 1 ? q->time.median : 1 / q->time.median;
        printf("  %s faster than %s: time ratio %.3g, adjusted p = %.2g "
               "(%d problems)\n", d->config_names[faster],
               d->config_names[slower], r, q->time_p_holm, q->time.n);
        any = 1;
    }
    if (!any)
        printf("  no significant difference in time between any two\n");
    printf("\n");
done:
    free(pairs);
    free(p);
    return rc;
}

static void data_free(data *d)
{
    for (int i = 0; i < d->nc; i++)
        free(d->config_names[i]);
    for (int i = 0; i < d->ns; i++)
        free(d->set_names[i]);
    if (d->cells != NULL)
        for (size_t i = 0; i < (size_t)d->nc * (size_t)d->nq; i++) {
            free(d->cells[i].times);
            free(d->cells[i].lengths);
        }
    free(d->config_ids);
    free(d->config_names);
    free(d->set_names);
    free(d->scene_ids);
    free(d->scene_set);
    free(d->query_ids);
    free(d->query_set);
    free(d->cells);
}

static int read_data(mpb_store *s, int64_t experiment, data *d)
{
    int rc;
    if ((rc = mpb_store_experiment_get(s, experiment, on_experiment, d)) ||
        (rc = mpb_store_planner_configs(s, experiment, on_config, d)) ||
        (rc = mpb_store_scenes(s, experiment, on_scene, d)))
        return d->nomem ? MPB_ENOMEM : rc;
    for (int i = 0; i < d->num_scenes; i++)
        if ((rc = mpb_store_queries(s, d->scene_ids[i], on_query, d)))
            return d->nomem ? MPB_ENOMEM : rc;
    d->cells = calloc((size_t)(d->nc > 0 ? d->nc : 1) *
                      (size_t)(d->nq > 0 ? d->nq : 1), sizeof *d->cells);
    if (d->cells == NULL)
        return MPB_ENOMEM;
    const char *const names[] = {"path_length"};
    rc = mpb_store_results(s, experiment, 0, NULL, names, 1, on_run, d);
    return d->nomem ? MPB_ENOMEM : rc;
}

static int config_named(const data *d, const char *name)
{
    for (int i = 0; i < d->nc; i++)
        if (strcmp(d->config_names[i], name) == 0)
            return i;
    return -1;
}

int cmd_compare(int argc, char **argv)
{
    static const struct option longopts[] = {
        {"experiment", required_argument, NULL, 'e'},
        {"set", required_argument, NULL, 's'},
        {"format", required_argument, NULL, 'f'},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    const char *experiment = NULL, *only = NULL;
    int opt, csv = 0, status = MPB_EXIT_ERROR;
    int64_t experiment_id = 0;
    optind = 1;
    opterr = 0;
    while ((opt = getopt_long(argc, argv, ":e:s:f:h", longopts, NULL)) != -1) {
        switch (opt) {
        case 'e':
            experiment = optarg;
            break;
        case 's':
            only = optarg;
            break;
        case 'f':
            if (strcmp(optarg, "csv") == 0)
                csv = 1;
            else if (strcmp(optarg, "text") != 0) {
                fprintf(stderr, "mpb " CMD ": unknown format '%s' (text or "
                        "csv)\n", optarg);
                return MPB_EXIT_USAGE;
            }
            break;
        case 'h':
            usage(stdout);
            return MPB_EXIT_OK;
        default:
            return tool_option_error(CMD, opt, argv);
        }
    }
    int args = argc - optind;
    if (args != 1 && args != 3) {
        fprintf(stderr, "mpb " CMD ": %s (try 'mpb " CMD " --help')\n",
                args < 1 ? "which database?"
                         : "a database, then two configurations or none");
        return MPB_EXIT_USAGE;
    }
    if (experiment != NULL && tool_parse_id(experiment, &experiment_id) != 0) {
        fprintf(stderr, "mpb " CMD ": --experiment wants an experiment id "
                "(a number), not '%s'\n", experiment);
        return MPB_EXIT_USAGE;
    }
    const char *path = argv[optind];
    mpb_store *s = tool_open_readonly(CMD, path);
    if (s == NULL)
        return MPB_EXIT_ERROR;
    data d = {0};
    int rc;
    if (tool_experiment(CMD, s, path, &experiment_id) != 0)
        goto done;
    if ((rc = read_data(s, experiment_id, &d)) != MPB_OK) {
        fprintf(stderr, "mpb " CMD ": %s: %s\n", path,
                rc == MPB_ENOMEM ? "out of memory" : mpb_store_errmsg(s));
        goto done;
    }
    int set = -1;
    if (only != NULL) {
        for (set = 0; set < d.ns; set++)
            if (strcmp(d.set_names[set], only) == 0)
                break;
        if (set == d.ns) {
            fprintf(stderr, "mpb " CMD ": %s: no problem set '%s' (", path,
                    only);
            for (int i = 0; i < d.ns; i++)
                fprintf(stderr, "%s%s", i ? ", " : "", d.set_names[i]);
            fprintf(stderr, ")\n");
            goto done;
        }
    }
    /* The blocks: the one set asked for, else every problem and then each
     * set (when there is more than one). */
    int first = only ? set : -1, last = only ? set : (d.ns > 1 ? d.ns - 1 : -1);
    if (csv)
        printf("set,a,b,problems,both,only_a,only_b,neither,time_problems,"
               "time_ratio,time_lo,time_hi,time_p,time_p_holm,"
               "length_problems,length_ratio,length_lo,length_hi,length_p\n");
    if (args == 3) {
        int a = config_named(&d, argv[optind + 1]);
        int b = config_named(&d, argv[optind + 2]);
        if (a < 0 || b < 0 || a == b) {
            const char *bad = a < 0 ? argv[optind + 1] : argv[optind + 2];
            if (a >= 0 && b >= 0)
                fprintf(stderr, "mpb " CMD ": compare two different "
                        "configurations\n");
            else {
                fprintf(stderr, "mpb " CMD ": %s: no configuration '%s' (",
                        path, bad);
                for (int i = 0; i < d.nc; i++)
                    fprintf(stderr, "%s%s", i ? ", " : "", d.config_names[i]);
                fprintf(stderr, ")\n");
            }
            goto done;
        }
        for (int k = first; k <= last; k++) {
            pair p;
            if ((rc = compare(&d, a, b, k, &p)) != MPB_OK) {
                fprintf(stderr, "mpb " CMD ": out of memory\n");
                goto done;
            }
            p.time_p_holm = p.time.p;
            const char *name = k < 0 ? "all problems" : d.set_names[k];
            if (csv)
                print_csv(&d, &p, name);
            else
                print_pair(&d, &p, name);
        }
    } else {
        for (int k = first; k <= last; k++)
            if (all_pairs(&d, k, csv) != MPB_OK) {
                fprintf(stderr, "mpb " CMD ": out of memory\n");
                goto done;
            }
    }
    status = MPB_EXIT_OK;
done:
    data_free(&d);
    mpb_store_close(s);
    return status;
}
