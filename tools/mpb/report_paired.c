/*
 * report_paired.c - the part of `mpb report --findings` that names a
 * fastest and a best configuration only where a test says so: per
 * problem set (and over all problems when there are several), within
 * each approach, every pair of its configurations compared on the
 * problems both ran (pairs.h: the per-problem time and path-length
 * ratios, the Wilcoxon signed-rank test), the p values Holm-adjusted over
 * the approach's pairs. A configuration is named the fastest (the best,
 * by path length) when it is smaller than each other configuration of its
 * approach at 5 %; else the line says "no significant difference".
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "report.h"

/* The configurations of one approach, as indices into r->configs. */
typedef struct group {
    const char *label;
    int        *members;
    int         n;
} group;

/* Which side of the pair (a, b) is which ratio's sign for config x. */
static int smaller(const pairs_pair *p, const pairs_ratio *ratio, int x)
{
    int v = pairs_verdict(ratio);
    return (v < 0 && p->a == x) || (v > 0 && p->b == x);
}

/* One line: the winner on time (length = 0) or path length, or none. */
static void say_winner(const report *r, const group *g, pairs_pair *pairs,
                       int np, int length, FILE *out)
{
    const char *what = length ? "best paths" : "fastest";
    fprintf(out, "    %s, ", g->label);
    int winner = -1;
    for (int i = 0; i < g->n && winner < 0; i++) {
        int x = g->members[i], all = 1;
        for (int k = 0; k < np && all; k++) {
            const pairs_pair *p = &pairs[k];
            if (p->a != x && p->b != x)
                continue;
            all = smaller(p, length ? &p->length : &p->time, x);
        }
        if (all)
            winner = x;
    }
    if (winner < 0) {
        int any = 0;
        fprintf(out, "%s: no significant difference", what);
        for (int k = 0; k < np; k++) {
            const pairs_pair *q = &pairs[k];
            const pairs_ratio *x = length ? &q->length : &q->time;
            int v = pairs_verdict(x);
            if (v == 0)
                continue;
            fprintf(out, "%s      %s %s than %s (ratio %.3g)",
                    any++ ? "\n" : " of one to all others; only:\n",
                    r->configs[v < 0 ? q->a : q->b].name,
                    length ? "shorter" : "faster",
                    r->configs[v < 0 ? q->b : q->a].name,
                    v < 0 ? x->median : 1.0 / x->median);
        }
        fputc('\n', out);
        return;
    }
    /* The narrowest of its wins: the largest ratio and p. */
    double ratio = 0, p = 0;
    int problems = 0;
    const char *next = "";
    for (int k = 0; k < np; k++) {
        const pairs_pair *q = &pairs[k];
        if (q->a != winner && q->b != winner)
            continue;
        const pairs_ratio *x = length ? &q->length : &q->time;
        double mine = q->a == winner ? x->median : 1.0 / x->median;
        if (mine > ratio) {
            ratio = mine;
            next = r->configs[q->a == winner ? q->b : q->a].name;
            problems = x->n;
        }
        if (x->p_holm > p)
            p = x->p_holm;
    }
    fprintf(out, "%s: %s (%s ratio %.3g to %s on %d problems, adjusted p "
            "%s %.2g)\n", what, r->configs[winner].name,
            length ? "path-length" : "time", ratio, next, problems,
            g->n > 2 ? "<=" : "=", p);
}

static int write_group(report *r, const group *g, int set, FILE *out)
{
    if (g->n < 2) {
        fprintf(out, "    %s: %s alone, nothing to compare\n", g->label,
                g->n ? r->configs[g->members[0]].name : "none");
        return MPB_OK;
    }
    int np = g->n * (g->n - 1) / 2, k = 0, rc = MPB_OK;
    pairs_pair *pairs = calloc((size_t)np, sizeof *pairs);
    if (pairs == NULL)
        return MPB_ENOMEM;
    for (int i = 0; i < g->n && rc == MPB_OK; i++)
        for (int j = i + 1; j < g->n && rc == MPB_OK; j++)
            rc = pairs_compare(&r->pairs, g->members[i], g->members[j], set,
                               &pairs[k++]);
    if (rc == MPB_OK)
        rc = pairs_holm(pairs, np);
    if (rc == MPB_OK) {
        say_winner(r, g, pairs, np, 0, out);
        say_winner(r, g, pairs, np, 1, out);
    }
    free(pairs);
    return rc;
}

int report_write_paired(const report *r_, FILE *out)
{
    /* pairs_compare() sorts the cells' samples in place: nothing the
     * numbers depend on. */
    report *r = (report *)r_;
    static const char *const words[MPB_NUM_APPROACHES] = {MPB_APPROACHES};
    group groups[MPB_NUM_APPROACHES + 1] = {{0}};
    int rc = MPB_OK, any = report_any_approach(r);
    if (r->num_configs == 0 || r->pairs.cells == NULL)
        return MPB_OK;
    for (int a = 0; a <= MPB_NUM_APPROACHES; a++) {
        groups[a].label = a < MPB_NUM_APPROACHES ? words[a]
                        : any ? "no approach declared" : "all configurations";
        if ((groups[a].members = calloc((size_t)r->num_configs,
                                        sizeof (int))) == NULL)
            rc = MPB_ENOMEM;
    }
    for (int c = 0; c < r->num_configs && rc == MPB_OK; c++) {
        group *g = &groups[report_approach_group(&r->configs[c])];
        g->members[g->n++] = c;
    }
    if (rc == MPB_OK)
        fputs("\nPer problem set, by approach: the fastest and the best "
              "paths only where the\nsigned-rank test on the problems both "
              "ran says so at 5 % (Holm-adjusted over\nthe approach's pairs; "
              "mpb compare for the numbers):\n", out);
    int first = r->num_sets > 1 ? -1 : 0;
    for (int set = first; set < r->num_sets && rc == MPB_OK; set++) {
        fprintf(out, "  %s:\n", report_set_name(r, set));
        for (int a = 0; a <= MPB_NUM_APPROACHES && rc == MPB_OK; a++)
            if (groups[a].n > 0)
                rc = write_group(r, &groups[a], set, out);
    }
    for (int a = 0; a <= MPB_NUM_APPROACHES; a++)
        free(groups[a].members);
    return rc;
}
