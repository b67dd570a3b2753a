/*
 * report_seen.c - `mpb report`'s section on scenes planned on what was
 * seen (an experiment's `seen:`, docs/experiment-format.md): for each
 * planner configuration, over all problems and per problem set, success
 * judged on the truth (the scene, s_r) beside success judged on what its
 * planner was given, and where the two part: paths that succeed on what
 * was seen and fail on the truth (the view missed what they hit), and the
 * reverse (the view held something that is not there, or hid nothing the
 * path needed). Text and markdown only; an experiment whose planners all
 * had the scene itself prints nothing.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "report.h"

typedef struct tally {
    long runs, truth, seen, seen_only, truth_only;
} tally;

typedef struct walk {
    const report *r;
    tally        *t;       /* [(set) * num_configs + config], set num_sets:
                              all problems */
    int           nconfig;
    int64_t       config;  /* the configuration of the runs coming */
    int           index;   /* its index in r->configs, or -1 */
} walk;

static int query_set(const report *r, int64_t query_id)
{
    int lo = 0, hi = r->num_queries - 1;
    while (lo <= hi) {
        int mid = lo + (hi - lo) / 2;
        if (r->queries[mid].id == query_id)
            return r->scenes[r->queries[mid].scene].set;
        if (r->queries[mid].id < query_id)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    return -1;
}

static void count(tally *t, const mpb_seen_judgement *j)
{
    t->runs++;
    t->truth += j->success != 0;
    t->seen += j->seen_success != 0;
    t->seen_only += j->seen_success && !j->success;
    t->truth_only += j->success && !j->seen_success;
}

static int on_run(void *ud, const mpb_seen_judgement *j)
{
    walk *w = ud;
    const report *r = w->r;
    if (j->planner_config_id != w->config) {
        w->config = j->planner_config_id;
        w->index = -1;
        for (int i = 0; i < r->num_configs; i++)
            if (r->configs[i].id == j->planner_config_id)
                w->index = i;
    }
    if (w->index < 0)
        return 0;
    count(&w->t[r->num_sets * w->nconfig + w->index], j);
    int set = query_set(r, j->query_id);
    if (set >= 0 && set < r->num_sets)
        count(&w->t[set * w->nconfig + w->index], j);
    return 0;
}

static void percent(char *buf, size_t len, long k, long n)
{
    snprintf(buf, len, "%ld (%.0f%%)", k, n > 0 ? 100.0 * (double)k / (double)n : 0.0);
}

static void write_rows(const walk *w, int set, int markdown, FILE *out)
{
    const report *r = w->r;
    for (int i = 0; i < r->num_configs; i++) {
        const tally *t = &w->t[set * w->nconfig + i];
        if (t->runs == 0)
            continue;
        char truth[40], seen[40];
        percent(truth, sizeof truth, t->truth, t->runs);
        percent(seen, sizeof seen, t->seen, t->runs);
        if (markdown)
            fprintf(out, "| %s | %ld | %s | %s | %ld | %ld |\n",
                    r->configs[i].name, t->runs, truth, seen, t->seen_only,
                    t->truth_only);
        else
            fprintf(out, "  %-28s %6ld %12s %12s %9ld %10ld\n",
                    r->configs[i].name, t->runs, truth, seen, t->seen_only,
                    t->truth_only);
    }
}

static void write_table(const walk *w, int set, int markdown, FILE *out)
{
    const report *r = w->r;
    const char *name = set == r->num_sets ? "all problems" : r->sets[set];
    if (markdown)
        fprintf(out, "\n#### %s\n\n| planner | runs | success on the truth "
                "| success on what was seen | seen only | truth only |\n"
                "|---|---:|---:|---:|---:|---:|\n", name);
    else
        fprintf(out, "\n %s:\n  %-28s %6s %12s %12s %9s %10s\n", name,
                "planner", "runs", "truth", "seen", "seen only",
                "truth only");
    write_rows(w, set, markdown, out);
}

int report_write_seen(mpb_store *s, const report *r, int markdown, FILE *out)
{
    if (r->num_configs == 0 || !r->any_seen)
        return MPB_OK;      /* and no walk over every run for nothing */
    walk w = {.r = r, .nconfig = r->num_configs, .config = -1, .index = -1};
    size_t n = (size_t)(r->num_sets + 1) * (size_t)r->num_configs;
    if ((w.t = calloc(n, sizeof *w.t)) == NULL)
        return MPB_ENOMEM;
    int rc = mpb_store_seen_judgements(s, r->experiment_id, on_run, &w);
    long any = 0;
    for (int i = 0; i < r->num_configs; i++)
        any += w.t[r->num_sets * w.nconfig + i].runs;
    if (rc == MPB_OK && any > 0) {
        if (markdown)
            fprintf(out, "\n### Planned on what was seen, judged on what is "
                    "there\n\nPlanners were given what was seen of these "
                    "scenes (`seen:`); each path is judged on the scene "
                    "itself (the truth: s_r above) and on what its planner "
                    "saw. *Seen only*: a success on what was seen that the "
                    "truth refuses; *truth only*, the reverse.\n");
        else
            fprintf(out, "\nPlanned on what was seen, judged on what is there "
                    "(planners were given what\nwas seen of these scenes; "
                    "success on the truth is s_r above; seen only:\na "
                    "success on what was seen that the truth refuses; truth "
                    "only: the reverse):\n");
        write_table(&w, r->num_sets, markdown, out);
        for (int set = 0; r->num_sets > 1 && set < r->num_sets; set++)
            write_table(&w, set, markdown, out);
    }
    free(w.t);
    return rc;
}
