/*
 * report_findings.c - `mpb report --findings`: after the tables, what they
 * say, in sentences. Per scene the fastest planner, the shortest paths and
 * the least spread; over the experiment the hardest scene; then the
 * qualitative findings of the paper (section V), each marked as holding or
 * not here, with the numbers that decide it.
 *
 * The kinds of planner come from the data: each configuration's approach
 * (planner_configs.approach: sampling, search, optimisation, hybrid), and
 * per scene the best configuration of each approach is named. The search-
 * based planners of the paper's findings are the configurations of
 * approach "search", the sampling-based ones those of "sampling"; only in
 * a database that records no approach at all (made before it was kept)
 * are the `arastar` and `ompl` families taken as search and sampling, as
 * the paper's own planners. RRTConnect is the algorithm of that name, and
 * the narrow passage the scene whose name contains "narrow". A finding
 * whose planners or scene are absent is reported as not checked.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "report.h"

#define SEARCH          "search"
#define SAMPLING        "sampling"
#define FASTEST_ALGO    "RRTConnect"
#define HARD_SCENE_PART "narrow"

/* Zero spread, allowing for the rounding of a sum of squares. */
#define ZERO_SPREAD 1e-9

static double mean_of(const column *c, int metric)
{
    return mpb_grouped_mean(&c->m[metric]);
}

static double sigma_of(const column *c, int metric)
{
    return report_sigma(&c->m[metric]);
}

/* A spread that was measured: NaN unless some query has two successful
 * runs or more. With one run per query sigma is 0 by the paper's
 * convention, which says nothing about the planner. */
static double measured_sigma_of(const column *c, int metric)
{
    return mpb_grouped_measured(&c->m[metric]) > 0 ? sigma_of(c, metric) : NAN;
}

/* Set by report_write_findings(): whether the database records any
 * approach; if not, the paper's families stand in for them. */
static int g_recorded;

/* A configuration's approach for the findings (see the top). */
static const char *approach_of(const config_ref *cf)
{
    if (g_recorded || cf->approach != NULL)
        return cf->approach;
    if (strcmp(cf->planner, "arastar") == 0)
        return SEARCH;
    if (strcmp(cf->planner, "ompl") == 0)
        return SAMPLING;
    return NULL;
}

static int is_approach(const config_ref *cf, const char *approach)
{
    const char *a = approach_of(cf);
    return a != NULL && strcmp(a, approach) == 0;
}

/* The configuration with the smallest value of f among those where select
 * holds and f is a number; -1 if none. */
static int argmin(const report *r, const column *cols,
                  double (*f)(const column *, int), int metric,
                  int (*select)(const config_ref *, const char *),
                  const char *arg)
{
    int best = -1;
    for (int c = 0; c < r->num_configs; c++) {
        if (select != NULL && !select(&r->configs[c], arg))
            continue;
        double v = f(&cols[c], metric);
        if (isnan(v))
            continue;
        if (best < 0 || v < f(&cols[best], metric))
            best = c;
    }
    return best;
}

static int not_approach(const config_ref *cf, const char *approach)
{
    return !is_approach(cf, approach);
}

static int is_hard_scene(const report *r, int s)
{
    return strstr(r->scenes[s].name, HARD_SCENE_PART) != NULL;
}

/* What the experiment's scenes look like, folded once. */
typedef struct scene_summary {
    column *cols;               /* num_configs */
    double  success;            /* over every configuration's runs */
    double  time;               /* mean tau_t over successful runs */
} scene_summary;

static void summarise(const report *r, int s, scene_summary *out)
{
    long finished = 0, succeeded = 0;
    double tsum = 0.0;
    long tn = 0;
    report_scene_columns(r, s, out->cols);
    for (int c = 0; c < r->num_configs; c++) {
        finished += out->cols[c].finished;
        succeeded += out->cols[c].succeeded;
        tsum += out->cols[c].m[M_TT].sum;
        tn += out->cols[c].m[M_TT].n;
    }
    out->success = finished > 0 ? (double)succeeded / (double)finished : NAN;
    out->time = tn > 0 ? tsum / (double)tn : NAN;
}

static double rate_of(const column *c)
{
    return c->finished > 0 ? (double)c->succeeded / (double)c->finished : NAN;
}

/*
 * The fastest configuration among those with the scene's best success
 * rate: a planner that failed runs its rivals solved is not the fastest
 * for having timed only its easy ones. -1 if none solved a run.
 */
static int fastest_of_most_successful(const report *r, const column *cols,
                                      const char *approach)
{
    double best = -1.0;
    for (int c = 0; c < r->num_configs; c++)
        if ((approach == NULL || is_approach(&r->configs[c], approach)) &&
            cols[c].m[M_TT].n > 0 && rate_of(&cols[c]) > best)
            best = rate_of(&cols[c]);
    int fast = -1;
    for (int c = 0; c < r->num_configs; c++)
        if ((approach == NULL || is_approach(&r->configs[c], approach)) &&
            cols[c].m[M_TT].n > 0 && rate_of(&cols[c]) == best &&
            (fast < 0 || mean_of(&cols[c], M_TT) < mean_of(&cols[fast], M_TT)))
            fast = c;
    return fast;
}

/* Per scene, the best configuration of each approach the experiment
 * has: its best success rate, the fastest among those (as "fastest"
 * above), with its verified and unclaimed valid counts. */
static void print_best_by_approach(const report *r, const column *cols,
                                   FILE *out)
{
    static const char *const words[MPB_NUM_APPROACHES] = {MPB_APPROACHES};
    int any = 0;
    for (int a = 0; a < MPB_NUM_APPROACHES; a++) {
        int present = 0;
        for (int c = 0; c < r->num_configs; c++)
            present |= is_approach(&r->configs[c], words[a]);
        if (!present)
            continue;
        fputs(any++ ? "; " : "      best by approach: ", out);
        int best = fastest_of_most_successful(r, cols, words[a]);
        if (best < 0) {
            fprintf(out, "%s none solved a run", words[a]);
            continue;
        }
        const column *c = &cols[best];
        fprintf(out, "%s %s (success %.0f%%, tau_t %.3g s, %ld verified of "
                "%ld claimed, %ld unclaimed valid)", words[a],
                r->configs[best].name, 100.0 * rate_of(c), mean_of(c, M_TT),
                c->outcomes[MPB_OUTCOME_VERIFIED], c->claimed,
                c->outcomes[MPB_OUTCOME_UNCLAIMED_VALID]);
    }
    if (any)
        fputs(".\n", out);
}

static void print_scene_findings(const report *r, int s,
                                 const scene_summary *sum, FILE *out)
{
    const column *cols = sum->cols;
    int fast = fastest_of_most_successful(r, cols, NULL);
    int any_fast = argmin(r, cols, mean_of, M_TT, NULL, NULL);
    int shortest = argmin(r, cols, mean_of, M_LP, NULL, NULL);
    int steady = argmin(r, cols, measured_sigma_of, M_LP, NULL, NULL);
    if (isnan(sum->success)) {
        fprintf(out, "  %s: no runs finished yet.\n", r->scenes[s].name);
        return;
    }
    fprintf(out, "  %s: success %.0f%%", r->scenes[s].name,
            100.0 * sum->success);
    if (fast >= 0) {
        fprintf(out, "; fastest %s (tau_t %.3g s, success %.0f%%",
                r->configs[fast].name, mean_of(&cols[fast], M_TT),
                100.0 * rate_of(&cols[fast]));
        if (any_fast != fast && mean_of(&cols[any_fast], M_TT) <
                                    mean_of(&cols[fast], M_TT))
            fprintf(out, "; %s faster, %.3g s, at %.0f%% success",
                    r->configs[any_fast].name, mean_of(&cols[any_fast], M_TT),
                    100.0 * rate_of(&cols[any_fast]));
        fputc(')', out);
    }
    if (shortest >= 0)
        fprintf(out, "; shortest paths %s (l_p %.3g rad, success %.0f%%)",
                r->configs[shortest].name, mean_of(&cols[shortest], M_LP),
                100.0 * rate_of(&cols[shortest]));
    if (steady >= 0)
        fprintf(out, "; least spread in l_p %s (sigma %.3g rad, success "
                "%.0f%%)", r->configs[steady].name,
                sigma_of(&cols[steady], M_LP), 100.0 * rate_of(&cols[steady]));
    fputs(".\n", out);
    print_best_by_approach(r, cols, out);
}

static const char *verdict(int held, int checked)
{
    if (checked == 0)
        return "not checked";
    if (held == checked)
        return "holds";
    return held == 0 ? "does not hold" : "holds in part";
}

/* "ARA* has zero spread in path length" and "ARA* has the shortest
 * paths", per scene where the search-based planner succeeded. */
static void check_search_planner(const report *r, const scene_summary *sums,
                                 FILE *out)
{
    int spread_held = 0, short_held = 0, short_checked = 0;
    int spread_checked = 0;
    char detail[2048] = "";
    size_t used = 0;
    for (int s = 0; s < r->num_scenes; s++) {
        const column *cols = sums[s].cols;
        int ara = argmin(r, cols, mean_of, M_LP, is_approach, SEARCH);
        if (ara < 0)
            continue;
        double sd = measured_sigma_of(&cols[ara], M_LP);  /* NaN: no repeat */
        spread_checked += !isnan(sd);
        spread_held += !isnan(sd) && sd <= ZERO_SPREAD;
        char sd_text[48] = "- (no query run twice)";
        if (!isnan(sd))
            snprintf(sd_text, sizeof sd_text, "%.3g rad", sd);
        /* Shortest of one is no finding: with no other planner's path
         * the scene is not checked. */
        int other = argmin(r, cols, mean_of, M_LP, not_approach, SEARCH);
        char other_text[160] = ", no other planner's path to compare";
        if (other >= 0) {
            int shortest = mean_of(&cols[ara], M_LP) <=
                           mean_of(&cols[other], M_LP);
            short_checked++;
            short_held += shortest;
            snprintf(other_text, sizeof other_text, ", %s %s (%.3g rad)",
                     shortest ? "next" : "beaten by", r->configs[other].name,
                     mean_of(&cols[other], M_LP));
        }
        if (used < sizeof detail)
            used += (size_t)snprintf(detail + used, sizeof detail - used,
                "      %s: sigma(l_p) %s; l_p %.3g rad%s\n",
                r->scenes[s].name, sd_text, mean_of(&cols[ara], M_LP),
                other_text);
    }
    fprintf(out, "  [%s] ARA* has zero spread in path length (%d of %d scenes)\n",
            verdict(spread_held, spread_checked), spread_held,
            spread_checked);
    fprintf(out, "  [%s] ARA* has the shortest paths (%d of %d scenes)\n",
            verdict(short_held, short_checked), short_held, short_checked);
    fputs(detail, out);
}

static int is_sampling(const config_ref *cf, const char *unused)
{
    (void)unused;
    return is_approach(cf, SAMPLING);
}

static int is_fastest_algo(const config_ref *cf, const char *unused)
{
    return is_sampling(cf, unused) && strcmp(cf->algorithm, FASTEST_ALGO) == 0;
}

static int is_other_sampling(const config_ref *cf, const char *unused)
{
    return is_sampling(cf, unused) && strcmp(cf->algorithm, FASTEST_ALGO) != 0;
}

/* "RRTConnect is the fastest sampling-based planner" outside the narrow
 * passage: its fastest configuration against the fastest other
 * sampling-based one, in each scene where both solved a run. */
static void check_fastest(const report *r, const scene_summary *sums,
                          FILE *out)
{
    int held = 0, checked = 0;
    char detail[2048] = "";
    size_t used = 0;
    for (int s = 0; s < r->num_scenes; s++) {
        if (is_hard_scene(r, s))
            continue;
        const column *cols = sums[s].cols;
        int rrtc = argmin(r, cols, mean_of, M_TT, is_fastest_algo, NULL);
        int other = argmin(r, cols, mean_of, M_TT, is_other_sampling, NULL);
        if (rrtc < 0 || other < 0)
            continue;
        checked++;
        int fastest = mean_of(&cols[rrtc], M_TT) <= mean_of(&cols[other], M_TT);
        held += fastest;
        if (used < sizeof detail)
            used += (size_t)snprintf(detail + used, sizeof detail - used,
                "      %s: %s %.3g s (success %.0f%%), %s %s (%.3g s, "
                "success %.0f%%)\n", r->scenes[s].name,
                r->configs[rrtc].name, mean_of(&cols[rrtc], M_TT),
                100.0 * rate_of(&cols[rrtc]),
                fastest ? "next" : "beaten by", r->configs[other].name,
                mean_of(&cols[other], M_TT), 100.0 * rate_of(&cols[other]));
    }
    fprintf(out, "  [%s] RRTConnect is the fastest sampling-based planner "
            "outside the narrow passage (%d of %d scenes)\n",
            verdict(held, checked), held, checked);
    fputs(detail, out);
}

/* "The narrow passage is the hardest environment": the lowest success
 * rate over all planners, and the longest mean total time tau_t. */
static void check_hardest(const report *r, const scene_summary *sums,
                          FILE *out)
{
    int hard = -1, least_success = -1, slowest = -1;
    for (int s = 0; s < r->num_scenes; s++) {
        if (is_hard_scene(r, s) && hard < 0)
            hard = s;
        if (!isnan(sums[s].success) &&
            (least_success < 0 || sums[s].success < sums[least_success].success))
            least_success = s;
        if (!isnan(sums[s].time) &&
            (slowest < 0 || sums[s].time > sums[slowest].time))
            slowest = s;
    }
    if (hard < 0 || r->num_scenes < 2) {
        fprintf(out, "  [not checked] the narrow passage is the hardest "
                "environment (no second scene or no '%s' scene)\n",
                HARD_SCENE_PART);
        return;
    }
    /* A measure on which every scene is alike decides nothing. */
    int by_success = sums[least_success].success < sums[hard].success ||
                     least_success == hard;
    int success_differs = 0;
    for (int s = 0; s < r->num_scenes; s++)
        success_differs |= sums[s].success != sums[hard].success;
    int checked = success_differs + (slowest >= 0);
    int held = (success_differs && by_success && sums[hard].success ==
                sums[least_success].success) + (slowest == hard);
    fprintf(out, "  [%s] the narrow passage is the hardest environment "
            "(%d of %d measures)\n", verdict(held, checked), held, checked);
    /* Each measure beside the next scene's, to show by how much. */
    int next_success = -1, next_time = -1;
    for (int s = 0; s < r->num_scenes; s++)
        if (s != least_success && !isnan(sums[s].success) &&
            (next_success < 0 || sums[s].success < sums[next_success].success))
            next_success = s;
    for (int s = 0; s < r->num_scenes; s++)
        if (s != slowest && !isnan(sums[s].time) &&
            (next_time < 0 || sums[s].time > sums[next_time].time))
            next_time = s;
    int other = least_success == hard ? next_success : hard;
    fprintf(out, "      lowest success rate: %s (%.0f%%; %s %s %.0f%%)\n",
            r->scenes[least_success].name, 100.0 * sums[least_success].success,
            least_success == hard ? "next" : "the narrow passage",
            other >= 0 ? r->scenes[other].name : "-",
            other >= 0 ? 100.0 * sums[other].success : NAN);
    if (slowest >= 0) {
        other = slowest == hard ? next_time : hard;
        fprintf(out, "      longest mean total time tau_t: %s (%.3g s; %s %s %.3g s)\n",
                r->scenes[slowest].name, sums[slowest].time,
                slowest == hard ? "next" : "the narrow passage",
                other >= 0 ? r->scenes[other].name : "-",
                other >= 0 ? sums[other].time : NAN);
    }
}

int report_write_findings(const report *r, FILE *out)
{
    if (r->num_configs == 0 || r->num_scenes == 0)
        return MPB_OK;
    /* By problem set, the tests' findings; the means' sentences per
     * scene and the paper's findings (checked scene by scene) with --by
     * scene. */
    if (r->by != BY_SCENE) {
        int rc = report_write_paired(r, out);
        if (rc == MPB_OK)
            fputs("\nPer scene, and the paper's findings: mpb report "
                  "--by scene --findings.\n", out);
        return rc;
    }
    scene_summary *sums = calloc((size_t)r->num_scenes, sizeof *sums);
    column *cols = calloc((size_t)r->num_scenes * (size_t)r->num_configs,
                          sizeof *cols);
    if (sums == NULL || cols == NULL) {
        free(sums);
        free(cols);
        return MPB_ENOMEM;
    }
    g_recorded = report_any_approach(r);
    for (int s = 0; s < r->num_scenes; s++) {
        sums[s].cols = cols + (size_t)s * (size_t)r->num_configs;
        summarise(r, s, &sums[s]);
    }
    fputs("\nFindings (means over successful runs of each run's final stage):\n",
          out);
    for (int s = 0; s < r->num_scenes; s++)
        print_scene_findings(r, s, &sums[s], out);
    fputs("\nThe paper's findings, checked here:\n", out);
    check_search_planner(r, sums, out);
    check_fastest(r, sums, out);
    check_hardest(r, sums, out);
    free(cols);
    free(sums);
    return report_write_paired(r, out);
}
