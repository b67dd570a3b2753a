/*
 * report.c - `mpb report`: an experiment's results as the paper's Tables
 * II-V. Per scene, one column per planner configuration: the mean and the
 * standard deviation of each metric over successful runs, and the success
 * rate. As in the paper, a scene's standard deviation is computed per query
 * and averaged over the scene's queries.
 *
 * This file is the command: its options, its help, and the choice of
 * writer. report_gather.c reads the runs into a cell per (configuration,
 * query); report_columns.c folds them per scene or problem set;
 * report_cells.c makes each cell's text; report_text.c prints the text
 * tables and report_formats.c writes the same numbers as Markdown, CSV,
 * LaTeX and JSON (docs/reports.md).
 */
#include <errno.h>
#include <getopt.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "report.h"
#include "view.h"

#define CMD "report"

typedef enum {
    FORMAT_TEXT, FORMAT_MARKDOWN, FORMAT_CSV, FORMAT_LATEX, FORMAT_JSON
} format;

static const struct {
    const char *name;
    int (*write)(const report *r, FILE *out);
} formats[] = {
    [FORMAT_TEXT] = {"text", report_write_text},
    [FORMAT_MARKDOWN] = {"markdown", report_write_markdown},
    [FORMAT_CSV] = {"csv", report_write_csv},
    [FORMAT_LATEX] = {"latex", report_write_latex},
    [FORMAT_JSON] = {"json", report_write_json},
    {"html", report_write_html},    /* report_html.c */
};
#define NUM_FORMATS ((int)(sizeof formats / sizeof formats[0]))

static void usage(FILE *out)
{
    fprintf(out,
        "usage: mpb report [--experiment ID] [--stage NAME] [--format FORMAT]\n"
        "                  [--by set|scene|all] [--findings] [-o FILE] DB\n"
        "\n"
        "Print the results of an experiment in the database DB as the tables\n"
        "of Cohen, Sucan and Chitta, \"A Generic Infrastructure for\n"
        "Benchmarking Motion Planners\": one table per scene or problem set\n"
        "(--by), one column per planner configuration, grouped by approach\n"
        "(sampling, search, optimisation, hybrid, then those that declare\n"
        "none), each column's approach above its name. Rows:\n"
        "  tau_t, tau_r, tau_o  total, planning and other time (s)\n"
        "  world setup          the planner's loading of the robot and scene,\n"
        "                       outside tau_t, over the runs that loaded one\n"
        "                       (s), when reported\n"
        "  verify               the daemon's verification and metrics of a\n"
        "                       run's stages, outside every planner time,\n"
        "                       over the finished runs (s), when recorded\n"
        "  memory               the planner process's peak resident memory\n"
        "                       during the planning, over the finished runs\n"
        "                       (MB), when reported\n"
        "  d_n                  clearance (m), when measured\n"
        "  l_p                  joint-space path length (rad)\n"
        "  l_e                  end-effector path length (m), when measured\n"
        "  kappa'               smoothness: mean squared turning angle\n"
        "  kappa'_r             the same of the path cut into 100 equal\n"
        "                       pieces, whatever its waypoints, when measured\n"
        "  waypoints            number of waypoints\n"
        "  claimed s_r          runs the planner said it solved / finished\n"
        "                       runs (%%): its own claim, beside s_r\n"
        "  s_r                  successful runs / finished runs (%%)\n"
        "  claimed              runs the planner said it solved\n"
        "  verified             claimed, valid and in time: the successes\n"
        "  refused claims       claimed, and the final stage not valid\n"
        "  unclaimed valid      not claimed (failed, approximate, timeout\n"
        "                       by the planner's word), yet the final stage\n"
        "                       valid by mpbench's verification\n"
        "                       (docs/metrics.md, \"Claims\")\n"
        "Means are over successful runs; sigma is the standard deviation of\n"
        "each query's successful runs, averaged over the scene's queries;\n"
        "a sigma marked * counts a query with one successful run as 0.\n"
        "'-' marks a value there is nothing to compute from (a sigma from\n"
        "fewer than two successful runs, too).\n"
        "\n"
        "Options:\n"
        "  -e, --experiment ID  report on experiment ID (default: the newest)\n"
        "  -s, --stage NAME     path metrics of stage NAME (raw, shortcut,\n"
        "                       smoothed, ...) instead of each run's final\n"
        "                       stage; only where that stage passed\n"
        "                       verification (the others are counted below\n"
        "                       the table)\n"
        "  -f, --format FORMAT  text (the default), markdown, csv (one row per\n"
        "                       scene, planner and metric), latex (a table per\n"
        "                       scene), json, or html: one self-contained page\n"
        "                       with the tables, the findings, the plots of\n"
        "                       mpb plot as SVG (when gnuplot is there) and\n"
        "                       the runs that are no success, each linked to\n"
        "                       its mpb view page (see -o); docs/reports.md\n"
        "                       describes each format\n"
        "  -b, --by BY          set: a table per problem set (the experiment\n"
        "                       file's set:, else a scene's name before its\n"
        "                       last '/') and one over all problems, adding\n"
        "                       s_r's 95%% Wilson interval and tau_t's\n"
        "                       median, its 95%% interval and p95;\n"
        "                       all: that one only; scene: a table per scene.\n"
        "                       Default: set where scenes outnumber sets, else\n"
        "                       scene. Text and html only\n"
        "  -F, --findings       after the tables, what they say: per scene the\n"
        "                       fastest planner (of those with the best success\n"
        "                       rate), the shortest and the steadiest paths,\n"
        "                       each with its success rate, the hardest scene,\n"
        "                       and whether the paper's findings hold (ARA*\n"
        "                       paths, RRTConnect's speed, the narrow passage)\n"
        "                       (--by scene); per set and approach the fastest\n"
        "                       and best only where a paired signed-rank test,\n"
        "                       Holm-adjusted, says so at 5%%; with the text\n"
        "                       format only (another --format is refused)\n"
        "  -o, --output FILE    write the report to FILE (replaced if it\n"
        "                       exists) instead of stdout; with html, also\n"
        "                       each linked run's 3-D view into views/ beside\n"
        "                       FILE (views/run-ID.html), as mpb view draws it\n"
        "  -h, --help           print this help\n"
        "\n"
        "The database is opened read-only; a running mpbenchd may go on\n"
        "writing. Exit status: 0 on success, 1 on an error, 2 on a bad\n"
        "command line.\n");
}

int cmd_report(int argc, char **argv)
{
    static const struct option longopts[] = {
        {"experiment", required_argument, NULL, 'e'},
        {"stage", required_argument, NULL, 's'},
        {"format", required_argument, NULL, 'f'},
        {"findings", no_argument, NULL, 'F'},
        {"by", required_argument, NULL, 'b'},
        {"output", required_argument, NULL, 'o'},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    report r = {0};
    const char *experiment = NULL, *path, *output = NULL, *by = NULL;
    char *three = NULL, *views = NULL, *tmp = NULL;
    FILE *out = stdout;
    int64_t experiment_id = 0;
    int opt, rc, status = MPB_EXIT_ERROR, fmt = FORMAT_TEXT, findings = 0;
    mpb_store *s = NULL;

    report_rows_init();
    optind = 1;
    opterr = 0;
    while ((opt = getopt_long(argc, argv, ":e:s:f:Fb:o:h", longopts, NULL)) != -1) {
        switch (opt) {
        case 'e':
            experiment = optarg;
            break;
        case 's':
            r.stage = optarg;
            break;
        case 'f':
            for (fmt = 0; fmt < NUM_FORMATS; fmt++)
                if (strcmp(optarg, formats[fmt].name) == 0)
                    break;
            if (fmt == NUM_FORMATS) {
                fprintf(stderr, "mpb " CMD ": unknown format '%s' (", optarg);
                for (int k = 0; k < NUM_FORMATS; k++)
                    fprintf(stderr, "%s%s", k == 0 ? "" : k + 1 < NUM_FORMATS
                            ? ", " : " or ", formats[k].name);
                fprintf(stderr, ")\n");
                return MPB_EXIT_USAGE;
            }
            break;
        case 'F':
            findings = 1;
            break;
        case 'b':
            by = optarg;
            if (strcmp(by, "scene") == 0)
                r.by = BY_SCENE;
            else if (strcmp(by, "set") == 0)
                r.by = BY_SET;
            else if (strcmp(by, "all") == 0)
                r.by = BY_ALL;
            else {
                fprintf(stderr, "mpb " CMD ": --by wants set, scene or all, "
                        "not '%s'\n", by);
                return MPB_EXIT_USAGE;
            }
            break;
        case 'o':
            output = optarg;
            break;
        case 'h':
            usage(stdout);
            return MPB_EXIT_OK;
        default:    /* ':' a missing value, '?' an unknown option */
            return tool_option_error(CMD, opt, argv);
        }
    }
    if (findings && fmt != FORMAT_TEXT) {
        fprintf(stderr, "mpb " CMD ": --findings is plain text, not for "
                "--format %s (try 'mpb " CMD " --help')\n", formats[fmt].name);
        return MPB_EXIT_USAGE;
    }
    /* The machine-readable layouts stay per scene (docs/reports.md). */
    int grouped = fmt == FORMAT_TEXT || strcmp(formats[fmt].name, "html") == 0;
    if (by != NULL && r.by != BY_SCENE && !grouped) {
        fprintf(stderr, "mpb " CMD ": --format %s is per scene; --by %s is "
                "for text and html\n", formats[fmt].name, by);
        return MPB_EXIT_USAGE;
    }
    r.by_default = by == NULL && grouped;
    r.want_pairs = findings || strcmp(formats[fmt].name, "html") == 0;
    if (argc - optind != 1) {
        fprintf(stderr, "mpb " CMD ": %s (try 'mpb " CMD " --help')\n",
                argc - optind < 1 ? "which database?"
                                  : "one database at a time");
        return MPB_EXIT_USAGE;
    }
    path = argv[optind];
    r.db_path = path;
    if (experiment != NULL && tool_parse_id(experiment, &experiment_id) != 0) {
        fprintf(stderr, "mpb " CMD ": --experiment wants an experiment id "
                "(a number), not '%s'\n", experiment);
        return MPB_EXIT_USAGE;
    }

    if ((s = tool_open_readonly(CMD, path)) == NULL)
        return MPB_EXIT_ERROR;
    if (experiment_id == 0) {
        rc = mpb_store_experiment_latest(s, &experiment_id);
        if (rc == MPB_ENOTFOUND) {
            fprintf(stderr, "mpb " CMD ": %s holds no experiment yet\n", path);
            goto done;
        }
        if (rc != MPB_OK)
            goto fail;
    }
    rc = mpb_store_experiment_get(s, experiment_id, report_on_experiment, &r);
    if (rc == MPB_ENOTFOUND) {
        fprintf(stderr, "mpb " CMD ": %s has no experiment %lld\n", path,
                (long long)experiment_id);
        goto done;
    }
    if (rc != MPB_OK && !r.nomem)
        goto fail;
    if (!r.nomem && (rc = report_gather(&r, s)) != MPB_OK && !r.nomem)
        goto fail;
    if (r.nomem) {
        fprintf(stderr, "mpb " CMD ": out of memory\n");
        goto done;
    }

    if (output) {
        /* Into output.tmp, renamed when whole; an HTML page's failed runs'
         * views into views/ beside it. */
        size_t len = strlen(output) + 8;
        char *copy = strdup(output);
        if ((tmp = malloc(len)) == NULL || copy == NULL ||
            (views = malloc(len + strlen("/views"))) == NULL) {
            free(copy);
            fprintf(stderr, "mpb " CMD ": out of memory\n");
            goto done;
        }
        snprintf(views, len + strlen("/views"), "%s/views", dirname(copy));
        free(copy);
        snprintf(tmp, len, "%s.tmp", output);
        if (strcmp(formats[fmt].name, "html") == 0) {
            char where[4096];
            if ((three = view_load_three(where, sizeof where)) == NULL) {
                fprintf(stderr, "mpb " CMD ": cannot read three.js at %s for "
                        "the failed runs' views: %s (run tools/web_env.sh, or "
                        "set MPB_THREE_JS)\n", where, strerror(errno));
                goto done;
            }
            r.views_dir = views;
            r.three_js = three;
        }
        if ((out = fopen(tmp, "w")) == NULL) {
            fprintf(stderr, "mpb " CMD ": cannot write %s: %s\n", output,
                    strerror(errno));
            out = stdout;
            goto done;
        }
    }
    if ((rc = formats[fmt].write(&r, out)) != MPB_OK ||
        (findings && (rc = report_write_findings(&r, out)) != MPB_OK) ||
        ((fmt == FORMAT_TEXT || fmt == FORMAT_MARKDOWN) &&
         ((rc = report_write_depth(s, &r, fmt == FORMAT_MARKDOWN, out)) != MPB_OK ||
          (rc = report_write_seen(s, &r, fmt == FORMAT_MARKDOWN, out)) != MPB_OK))) {
        if (rc == REPORT_SAID)
            goto done;
        goto fail;
    }
    if (fflush(out) != 0 || ferror(out)) {
        fprintf(stderr, "mpb " CMD ": cannot write %s: %s\n",
                output ? output : "the report", strerror(errno));
        goto done;
    }
    if (output) {
        int bad = fclose(out) != 0;
        out = stdout;
        if (bad || rename(tmp, output) != 0) {
            fprintf(stderr, "mpb " CMD ": cannot write %s: %s\n", output,
                    strerror(errno));
            goto done;
        }
    }
    status = MPB_EXIT_OK;
    goto done;
fail:
    fprintf(stderr, "mpb " CMD ": %s: %s\n", path,
            rc == MPB_ENOMEM ? "out of memory" : mpb_store_errmsg(s));
done:
    if (out != stdout)
        fclose(out);
    if (tmp && status != MPB_EXIT_OK)
        remove(tmp);
    free(tmp);
    free(views);
    free(three);
    mpb_store_close(s);
    report_free(&r);
    return status;
}

