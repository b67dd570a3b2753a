/*
 * compare.c - `mpb compare`: planner configurations compared problem by
 * problem, with intervals and paired tests, over each problem set and
 * over every problem. The question it answers: is A faster (or shorter)
 * than B on the same problems, and how sure is that?
 *
 * How each problem's numbers are made and compared: pairs.h. Every pair
 * of an experiment gets its p values adjusted together by Holm's method.
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
#include "pairs.h"

#define CMD "compare"
#define ALPHA PAIRS_ALPHA

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
    pairs_data pairs;            /* the runs, per configuration and query */
    int      nomem;
} data;

static int on_experiment(void *ud, const mpb_experiment_row *e)
{
    ((data *)ud)->limit = e->time_limit;
    return 0;
}

static int on_config(void *ud, const mpb_planner_config_row *c)
{
    data *d = ud;
    if (tool_config_add(&d->config_ids, &d->config_names, &d->nc, c) == 0)
        return 0;
    d->nomem = 1;
    return 1;
}

static int on_scene(void *ud, const mpb_scene_row *row)
{
    data *d = ud;
    if (tool_scene_add(&d->scene_ids, &d->scene_set, &d->num_scenes, &d->set_names,
                       &d->ns, row) == 0)
        return 0;
    d->nomem = 1;
    return 1;
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
    if (pairs_add(&d->pairs, c, q, row->success, row->time_total,
                  row->metrics[0]) != MPB_OK) {
        d->nomem = 1;
        return 1;
    }
    return 0;
}

static const char *verdict(const pairs_ratio *r, double p, const char *a,
                           const char *b, const char *less, char *buf,
                           size_t size)
{
    if (r->n == 0 || !(p < ALPHA) || r->median == 1)
        snprintf(buf, size, "no significant difference");
    else
        snprintf(buf, size, "%s %s", r->median < 1 ? a : b, less);
    return buf;
}

static void print_pair(const data *d, const pairs_pair *p, const char *set)
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

static void print_csv(const data *d, const pairs_pair *p, const char *set)
{
    tool_csv_text(stdout, set);
    putchar(',');
    tool_csv_text(stdout, d->config_names[p->a]);
    putchar(',');
    tool_csv_text(stdout, d->config_names[p->b]);
    printf(",%d,%d,%d,%d,%d,%d,%.9g,%.9g,%.9g,%.9g,%.9g,%d,%.9g,%.9g,%.9g,"
           "%.9g\n", p->problems, p->both, p->only_a, p->only_b, p->neither,
           p->time.n, p->time.median, p->time.lo, p->time.hi, p->time.p,
           p->time.p_holm, p->length.n, p->length.median, p->length.lo,
           p->length.hi, p->length.p);
}

/* Every pair of configurations on one set (-1: all problems). */
static int all_pairs(data *d, int set, int csv)
{
    const char *name = set < 0 ? "all problems" : d->set_names[set];
    int n = d->nc * (d->nc - 1) / 2, k;
    pairs_pair *pairs = NULL;
    int rc = pairs_all(&d->pairs, set, &pairs);
    if (rc != MPB_OK)
        goto done;
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
            const pairs_pair *q = &pairs[pairs_index(d->nc, a, b)];
            double r = a < b ? q->time.median : 1.0 / q->time.median;
            char cellbuf[16];
            if (q->time.n == 0)
                snprintf(cellbuf, sizeof cellbuf, "n/a");
            else
                snprintf(cellbuf, sizeof cellbuf, "%.3g%s", r,
                         q->time.p_holm < ALPHA ? "*" : "");
            printf(" %8s", cellbuf);
        }
        printf("\n");
    }
    int any = 0;
    for (k = 0; k < n; k++) {
        const pairs_pair *q = &pairs[k];
        if (!(q->time.p_holm < ALPHA) || q->time.median == 1)
            continue;
        int faster = q->time.median < 1 ? q->a : q->b;
        int slower = faster == q->a ? q->b : q->a;
        double r = q->time.median < 1 ? q->time.median : 1 / q->time.median;
        printf("  %s faster than %s: time ratio %.3g, adjusted p = %.2g "
               "(%d problems)\n", d->config_names[faster],
               d->config_names[slower], r, q->time.p_holm, q->time.n);
        any = 1;
    }
    if (!any)
        printf("  no significant difference in time between any two\n");
    printf("\n");
done:
    free(pairs);
    return rc;
}

static void data_free(data *d)
{
    for (int i = 0; i < d->nc; i++)
        free(d->config_names[i]);
    for (int i = 0; i < d->ns; i++)
        free(d->set_names[i]);
    pairs_free(&d->pairs);
    free(d->config_ids);
    free(d->config_names);
    free(d->set_names);
    free(d->scene_ids);
    free(d->scene_set);
    free(d->query_ids);
    free(d->query_set);
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
    if (pairs_init(&d->pairs, d->nc, d->nq, d->limit) != MPB_OK)
        return MPB_ENOMEM;
    memcpy(d->pairs.query_set, d->query_set,
           (size_t)d->nq * sizeof *d->query_set);
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
            pairs_pair p;
            if ((rc = pairs_compare(&d.pairs, a, b, k, &p)) != MPB_OK) {
                fprintf(stderr, "mpb " CMD ": out of memory\n");
                goto done;
            }
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
