/*
 * report_columns.c - the cells of `mpb report` folded into one column
 * per configuration: over one scene's queries (the per-scene tables) or
 * over one problem set's, or every problem's (--by set, --by all), with
 * the set's times for its own rows.
 */
#include <string.h>

#include "report.h"

/* Fold one query's cell into a column: its counts and its metrics. */
static void column_add(column *to, const column *cell)
{
    to->finished += cell->finished;
    to->succeeded += cell->succeeded;
    to->claimed += cell->claimed;
    for (int o = 0; o < MPB_OUTCOME_COUNT; o++)
        to->outcomes[o] += cell->outcomes[o];
    to->stage_invalid += cell->stage_invalid;
    for (int k = 0; k < M_COUNT; k++)
        mpb_grouped_merge(&to->m[k], &cell->m[k]);
}

long report_scene_columns(const report *r, int si, column *cols)
{
    long finished = 0;
    for (int c = 0; c < r->num_configs; c++) {
        cols[c].finished = cols[c].succeeded = cols[c].stage_invalid = 0;
        cols[c].claimed = 0;
        cols[c].in_set = 0;
        cols[c].times = NULL;
        cols[c].ntimes = 0;
        memset(cols[c].outcomes, 0, sizeof cols[c].outcomes);
        for (int k = 0; k < M_COUNT; k++)
            mpb_grouped_init(&cols[c].m[k]);
        for (int q = 0; q < r->num_queries; q++) {
            if (r->queries[q].scene != si)
                continue;
            const column *cl = &r->cells[(size_t)c * (size_t)r->num_queries +
                                         (size_t)q];
            column_add(&cols[c], cl);
        }
        finished += cols[c].finished;
    }
    return finished;
}

long report_set_columns(const report *r, int set, column *cols,
                        int *unfinished)
{
    long finished = 0;
    int waiting = 0;
    for (int c = 0; c < r->num_configs; c++) {
        cols[c] = (column){.in_set = 1};
        for (int k = 0; k < M_COUNT; k++)
            mpb_grouped_init(&cols[c].m[k]);
        if (r->times != NULL) {
            const report_samples *x =
                &r->times[(size_t)(set < 0 ? r->num_sets : set) *
                          (size_t)r->num_configs + (size_t)c];
            cols[c].times = x->v;
            cols[c].ntimes = x->n;
        }
    }
    for (int q = 0; q < r->num_queries; q++) {
        if (set >= 0 && r->scenes[r->queries[q].scene].set != set)
            continue;
        for (int c = 0; c < r->num_configs; c++) {
            const column *cl = &r->cells[(size_t)c * (size_t)r->num_queries +
                                         (size_t)q];
            column_add(&cols[c], cl);
            finished += cl->finished;
        }
    }
    for (int i = 0; i < r->num_scenes; i++)
        if (set < 0 || r->scenes[i].set == set)
            waiting += r->scenes[i].unfinished;
    if (unfinished != NULL)
        *unfinished = waiting;
    return finished;
}

const char *report_set_name(const report *r, int set)
{
    return set < 0 ? "all problems" : r->sets[set];
}

int report_set_scenes(const report *r, int set)
{
    int n = 0;
    for (int i = 0; i < r->num_scenes; i++)
        n += set < 0 || r->scenes[i].set == set;
    return n;
}
