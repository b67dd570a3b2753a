/*
 * export.c - `mpb export`: an mpbench database as other tools read it: a
 * Planner Arena database (--planner-arena), OMPL benchmark logs
 * (--ompl-log), or the run_summary view as CSV (--runs-csv). The work is
 * the store's (store_export*.c); this is the command line.
 * docs/planner-arena.md and docs/analysis.md describe what is written.
 */
#include <errno.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "mpb.h"

#define CMD "export"

#define MAX_EXPERIMENTS 256

static void usage(FILE *out)
{
    fprintf(out,
        "usage: mpb export --planner-arena [--experiment ID]... [--append|--force]\n"
        "                  DB OUT.db\n"
        "       mpb export --ompl-log [--experiment ID]... [--force] DB DIR\n"
        "       mpb export --runs-csv [--experiment ID]... [--force] DB OUT.csv\n"
        "\n"
        "Write the finished runs of the database DB as another tool reads them.\n"
        "\n"
        "  --planner-arena  OUT.db is a database that Planner Arena\n"
        "                   (plannerarena.org) opens, as OMPL's\n"
        "                   ompl_benchmark_statistics.py would write it. Each\n"
        "                   query becomes a Planner Arena experiment named\n"
        "                   EXPERIMENT/SCENE (SCENE#N, N its place in the\n"
        "                   experiment, if two would be the same) with the\n"
        "                   query as a parameter; runs carry time, solved\n"
        "                   (mpbench's verified success), status, the path\n"
        "                   metrics of the first stage (\"solution ...\"), of\n"
        "                   the final one (\"simplified solution ...\") and of\n"
        "                   those between, and the planner's own numbers;\n"
        "                   progress samples go to the progress table. See\n"
        "                   docs/planner-arena.md.\n"
        "  --ompl-log       the same as OMPL benchmark logs in the directory DIR\n"
        "                   (made if missing), one per query, named\n"
        "                   EXPERIMENT.ID.SCENE.QUERY.log (other than\n"
        "                   [A-Za-z0-9.-] as '_'; names that would be alike\n"
        "                   get +QUERYID before .log); OMPL's\n"
        "                   ompl_benchmark_statistics.py reads them.\n"
        "  --runs-csv       the database's run_summary view as CSV, one row\n"
        "                   per finished run: experiment, problem set, scene,\n"
        "                   query, planner, algorithm, approach, seed, status,\n"
        "                   claimed, verified, outcome, verdict, times and the\n"
        "                   final stage's metrics (docs/schema.md); OUT.csv -\n"
        "                   writes to standard output. See docs/analysis.md.\n"
        "\n"
        "Options:\n"
        "  -e, --experiment ID  export experiment ID (repeat for more, each\n"
        "                       counts once; default: every experiment in DB)\n"
        "  -a, --append         add to OUT.db, an existing Planner Arena\n"
        "                       database (one of OMPL's, or an earlier export;\n"
        "                       any other file is refused, exit 1). A query\n"
        "                       exported there before (an experiment of the\n"
        "                       same name, query, date, run count and host,\n"
        "                       there before this export) is skipped with its\n"
        "                       runs, and said so\n"
        "  -f, --force          replace OUT.db (the logs, OUT.csv) if it exists\n"
        "  -h, --help           print this help\n"
        "\n"
        "Without --append or --force an existing OUT.db or log is left alone\n"
        "(exit 1; then no log is written). OUT.db or DIR that is DB itself,\n"
        "by any name, is refused (exit 2).\n"
        "DB is opened read-only. Exit status: 0 on success, 1 on an error, 2 on\n"
        "a bad command line.\n");
}

/* --runs-csv: the run_summary view into out ("-": standard output). A
 * file is written beside its name first and renamed when whole, so that
 * a failure leaves no half CSV (and an existing one as it was). */
static int runs_csv_export(const char *db, const char *out,
                           const int64_t *ids, int num_ids, int force)
{
    int to_stdout = strcmp(out, "-") == 0;
    char tmp[4200];
    if (!to_stdout && !force && access(out, F_OK) == 0) {
        fprintf(stderr, "mpb " CMD ": %s exists (--force replaces it)\n", out);
        return MPB_EXIT_ERROR;
    }
    mpb_store *s = tool_open_readonly(CMD, db);
    if (s == NULL)
        return MPB_EXIT_ERROR;
    FILE *f = stdout;
    if (!to_stdout) {
        snprintf(tmp, sizeof tmp, "%s.part", out);
        if ((f = fopen(tmp, "w")) == NULL) {
            fprintf(stderr, "mpb " CMD ": cannot write %s: %s\n", tmp,
                    strerror(errno));
            mpb_store_close(s);
            return MPB_EXIT_ERROR;
        }
    }
    long rows = 0;
    int rc = mpb_store_export_runs_csv(s, f, ids, num_ids, &rows);
    if (rc != MPB_OK)
        fprintf(stderr, "mpb " CMD ": %s: %s\n", db, mpb_store_errmsg(s));
    mpb_store_close(s);
    if (to_stdout)
        return rc == MPB_OK && fflush(stdout) == 0 ? MPB_EXIT_OK
                                                   : MPB_EXIT_ERROR;
    int bad = fclose(f) != 0;
    if (rc == MPB_OK && (bad || rename(tmp, out) != 0)) {
        fprintf(stderr, "mpb " CMD ": cannot write %s: %s\n", out,
                strerror(errno));
        rc = MPB_EIO;
    }
    if (rc != MPB_OK) {
        unlink(tmp);
        return MPB_EXIT_ERROR;
    }
    printf("%s: %ld run%s\n", out, rows, rows == 1 ? "" : "s");
    return MPB_EXIT_OK;
}

int cmd_export(int argc, char **argv)
{
    enum { OPT_PLANNER_ARENA = 256, OPT_OMPL_LOG, OPT_RUNS_CSV };
    static const struct option longopts[] = {
        {"planner-arena", no_argument, NULL, OPT_PLANNER_ARENA},
        {"ompl-log", no_argument, NULL, OPT_OMPL_LOG},
        {"runs-csv", no_argument, NULL, OPT_RUNS_CSV},
        {"experiment", required_argument, NULL, 'e'},
        {"append", no_argument, NULL, 'a'},
        {"force", no_argument, NULL, 'f'},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    int64_t ids[MAX_EXPERIMENTS];
    int num_ids = 0, planner_arena = 0, ompl_log = 0, runs_csv = 0;
    int append = 0, force = 0;
    int opt, rc;
    mpb_store *s = NULL;

    optind = 1;
    opterr = 0;
    while ((opt = getopt_long(argc, argv, ":e:afh", longopts, NULL)) != -1) {
        switch (opt) {
        case OPT_PLANNER_ARENA:
            planner_arena = 1;
            break;
        case OPT_OMPL_LOG:
            ompl_log = 1;
            break;
        case OPT_RUNS_CSV:
            runs_csv = 1;
            break;
        case 'e':
            if (num_ids == MAX_EXPERIMENTS) {
                fprintf(stderr, "mpb " CMD ": at most %d experiments at a "
                        "time\n", MAX_EXPERIMENTS);
                return MPB_EXIT_USAGE;
            }
            if (tool_parse_id(optarg, &ids[num_ids]) != 0) {
                fprintf(stderr, "mpb " CMD ": --experiment wants an "
                        "experiment id (a number), not '%s'\n", optarg);
                return MPB_EXIT_USAGE;
            }
            num_ids++;
            break;
        case 'a':
            append = 1;
            break;
        case 'f':
            force = 1;
            break;
        case 'h':
            usage(stdout);
            return MPB_EXIT_OK;
        default:    /* ':' a missing value, '?' an unknown option */
            return tool_option_error(CMD, opt, argv);
        }
    }
    if (planner_arena + ompl_log + runs_csv != 1) {
        fprintf(stderr, "mpb " CMD ": %s (try 'mpb " CMD " --help')\n",
                planner_arena + ompl_log + runs_csv
                ? "one of --planner-arena, --ompl-log and --runs-csv"
                : "which format? --planner-arena, --ompl-log or --runs-csv");
        return MPB_EXIT_USAGE;
    }
    if ((ompl_log || runs_csv) && append) {
        fprintf(stderr, "mpb " CMD ": --append is for --planner-arena\n");
        return MPB_EXIT_USAGE;
    }
    if (append && force) {
        fprintf(stderr, "mpb " CMD ": --append or --force, not both\n");
        return MPB_EXIT_USAGE;
    }
    if (argc - optind != 2) {
        fprintf(stderr, "mpb " CMD ": %s (try 'mpb " CMD " --help')\n",
                argc - optind < 2 ? (ompl_log ? "wants a database and a "
                                                "directory"
                                              : "wants a database and an "
                                                "output file")
                                  : "too many arguments");
        return MPB_EXIT_USAGE;
    }
    const char *path = argv[optind], *out = argv[optind + 1];
    struct stat in_sb, out_sb;
    if (stat(path, &in_sb) == 0 && stat(out, &out_sb) == 0 &&
        in_sb.st_dev == out_sb.st_dev && in_sb.st_ino == out_sb.st_ino) {
        fprintf(stderr, "mpb " CMD ": %s is the database %s itself; write "
                "to another file\n", out, path);
        return MPB_EXIT_USAGE;
    }

    if (runs_csv)
        return runs_csv_export(path, out, ids, num_ids, force);
    if ((s = tool_open_readonly(CMD, path)) == NULL)
        return MPB_EXIT_ERROR;
    mpb_export_counts counts;
    if (ompl_log) {
        rc = mpb_store_export_ompl_logs(s, out, ids, num_ids,
                                        force ? MPB_EXPORT_REPLACE : 0,
                                        &counts);
        if (rc == MPB_EEXISTS)
            fprintf(stderr, "mpb " CMD ": %s (--force replaces it)\n",
                    mpb_store_errmsg(s));
        else if (rc != MPB_OK)
            fprintf(stderr, "mpb " CMD ": %s\n", mpb_store_errmsg(s));
        else
            printf("%s: %d OMPL log%s, %ld run%s\n", out, counts.experiments,
                   counts.experiments == 1 ? "" : "s", counts.runs,
                   counts.runs == 1 ? "" : "s");
        mpb_store_close(s);
        return rc == MPB_OK ? MPB_EXIT_OK : MPB_EXIT_ERROR;
    }
    if (force && unlink(out) != 0 && errno != ENOENT) {
        fprintf(stderr, "mpb " CMD ": cannot replace %s: %s\n", out,
                strerror(errno));
        mpb_store_close(s);
        return MPB_EXIT_ERROR;
    }
    rc = mpb_store_export_planner_arena(s, out, ids, num_ids,
                                        append ? MPB_EXPORT_APPEND : 0,
                                        &counts);
    if (rc == MPB_EEXISTS) {
        fprintf(stderr, "mpb " CMD ": %s exists (--append adds to it, "
                "--force replaces it)\n", out);
    } else if (rc != MPB_OK) {
        fprintf(stderr, "mpb " CMD ": %s\n", mpb_store_errmsg(s));
    } else {
        printf("%s: %d Planner Arena experiment%s, %ld run%s, %d planner "
               "configuration%s added, %ld progress sample%s", out,
               counts.experiments, counts.experiments == 1 ? "" : "s",
               counts.runs, counts.runs == 1 ? "" : "s",
               counts.planner_configs,
               counts.planner_configs == 1 ? "" : "s", counts.progress,
               counts.progress == 1 ? "" : "s");
        if (counts.skipped > 0)
            printf("; %d there already, skipped", counts.skipped);
        putchar('\n');
    }
    mpb_store_close(s);
    return rc == MPB_OK ? MPB_EXIT_OK : MPB_EXIT_ERROR;
}
