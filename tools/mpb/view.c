/*
 * view.c - `mpb view`: runs drawn in 3-D in self-contained HTML pages. The
 * command line, and where three.js comes from; view_run.c reads a run and
 * makes it ready, view_page.c writes its page, view_select.c chooses runs
 * by name and writes several.
 */
#include <errno.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "view.h"

#define CMD "view"

#define THREE_JS_NAME "three.module.min.js"

static void usage(FILE *out)
{
    fprintf(out,
        "usage: mpb view [-o FILE] DB RUN\n"
        "       mpb view [-o PATH] [-e ID] [-s SCENE] [-q QUERY] [-p PLANNER]\n"
        "                [--failed] DB\n"
        "\n"
        "Draw run RUN (its id in the database DB, as the results view gives\n"
        "it) in 3-D: one self-contained HTML file that opens in a browser\n"
        "offline, without mpbench. It shows the scene and the robot with the\n"
        "geometry the verifier checks (primitives and meshes), the start, the\n"
        "goal (the robot at a joint goal, or a goal region's box and\n"
        "orientation cone), and every stage the planner returned, each\n"
        "selectable, animated with a slider and a play button. A stage that\n"
        "failed verification shows the verdict; for a collision, the\n"
        "configuration where the verifier found it, with the two bodies that\n"
        "touch there in red.\n"
        "\n"
        "Without RUN, the finished runs of an experiment that the options\n"
        "name: one run is drawn as RUN would be; several are drawn one page\n"
        "each (run-ID.html) with an index.html listing them all, into the\n"
        "folder PATH (made if missing).\n"
        "\n"
        "Options:\n"
        "  -o, --output PATH    write the page to PATH (replaced if it exists);\n"
        "                       default: a new file (or folder) in $TMPDIR or\n"
        "                       /tmp, whose path is printed\n"
        "  -e, --experiment ID  runs of experiment ID (default: the newest)\n"
        "  -s, --scene NAME     runs in that scene\n"
        "  -q, --query NAME     runs of that query\n"
        "  -p, --planner NAME   runs of that planner configuration\n"
        "                       (\"ompl/RRTConnect\", as mpb report names it)\n"
        "  -f, --failed         runs that are no success\n"
        "  -h, --help           this text\n"
        "\n"
        "three.js is read from $MPB_THREE_JS if set, else from mpbench's data\n"
        "folder (share/mpbench/" THREE_JS_NAME "), else from the source\n"
        "tree's .cache/web (tools/web_env.sh). Meshes of a URDF robot are\n"
        "found as mpbenchd finds them ($MPB_MESH_PATH). docs/reports.md\n"
        "describes the page.\n"
        "\n"
        "Exit status: 0 on success, 1 on an error (an unknown run, a run with\n"
        "no stages, no run that the options name, a database that is not\n"
        "mpbench's), 2 on a bad command line.\n");
}

/* three.js, from the first place that has it (see usage()). */
char *view_load_three(char *where, size_t len)
{
    char exe[4096];
    const char *env = getenv("MPB_THREE_JS");
    if (env && *env) {
        snprintf(where, len, "%s", env);
        return mpb_read_file(where, 0, NULL);
    }
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = '\0';
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = '\0';
            int w = snprintf(where, len, "%s/%s/%s", exe, MPB_BIN_TO_DATA,
                             THREE_JS_NAME);
            char *t = w > 0 && (size_t)w < len
                    ? mpb_read_file(where, 0, NULL) : NULL;
            if (t)
                return t;
        }
    }
    snprintf(where, len, "%s", MPB_SOURCE_THREE_JS);
    return mpb_read_file(where, 0, NULL);
}

static const char *tmp_dir(void)
{
    const char *dir = getenv("TMPDIR");
    return dir && *dir ? dir : "/tmp";
}

/* Tell where the page (or the index of pages) is and how to open it. */
static void say_where(const char *path)
{
    const char *display = getenv("DISPLAY"), *wayland =
        getenv("WAYLAND_DISPLAY");
    printf("wrote %s\n", path);
    if ((display && *display) || (wayland && *wayland))
        printf("open it in a browser: xdg-open %s\n", path);
    else
        printf("no display here: copy it to a machine with a browser "
               "and open it there (it needs no network)\n");
}

int cmd_view(int argc, char **argv)
{
    static const struct option longopts[] = {
        {"output", required_argument, NULL, 'o'},
        {"experiment", required_argument, NULL, 'e'},
        {"scene", required_argument, NULL, 's'},
        {"query", required_argument, NULL, 'q'},
        {"planner", required_argument, NULL, 'p'},
        {"failed", no_argument, NULL, 'f'},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    const char *output = NULL;
    selection sel = {0};
    int64_t experiment = 0;
    int opt, selecting = 0;
    optind = 1;
    opterr = 0;
    while ((opt = getopt_long(argc, argv, ":o:e:s:q:p:fh", longopts,
                              NULL)) != -1) {
        switch (opt) {
        case 'o':
            output = optarg;
            break;
        case 'e':
            if (tool_parse_id(optarg, &experiment) != 0) {
                fprintf(stderr, "mpb " CMD ": --experiment wants an "
                        "experiment id (a number), not '%s'\n", optarg);
                return MPB_EXIT_USAGE;
            }
            selecting = 1;
            break;
        case 's':
            sel.scene = optarg;
            selecting = 1;
            break;
        case 'q':
            sel.query = optarg;
            selecting = 1;
            break;
        case 'p':
            sel.planner = optarg;
            selecting = 1;
            break;
        case 'f':
            sel.failed = 1;
            selecting = 1;
            break;
        case 'h':
            usage(stdout);
            return MPB_EXIT_OK;
        default:
            return tool_option_error(CMD, opt, argv);
        }
    }
    int want = selecting ? 1 : 2;
    if (argc - optind < want) {
        fprintf(stderr, "mpb " CMD ": wants a database and %s (try 'mpb "
                CMD " --help')\n", selecting ? "nothing more" : "a run id");
        return MPB_EXIT_USAGE;
    }
    if (argc - optind > 2 || (selecting && argc - optind > 1)) {
        if (selecting && argc - optind == 2)
            fprintf(stderr, "mpb " CMD ": a run id, or --experiment, "
                    "--scene, --query, --planner, --failed: not both\n");
        else
            return tool_extra_argument(CMD, argv[optind + 2]);
        return MPB_EXIT_USAGE;
    }
    const char *db = argv[optind];
    int64_t run_id = 0;
    if (!selecting && tool_parse_id(argv[optind + 1], &run_id) != 0) {
        fprintf(stderr, "mpb " CMD ": RUN is a run id (a number), not '%s'\n",
                argv[optind + 1]);
        return MPB_EXIT_USAGE;
    }

    char where[4096], path[4200];
    char *three = view_load_three(where, sizeof where);
    if (!three) {
        fprintf(stderr, "mpb " CMD ": cannot read three.js at %s: %s (run "
                "tools/web_env.sh, or set MPB_THREE_JS)\n", where,
                strerror(errno));
        return MPB_EXIT_ERROR;
    }
    mpb_store *s = tool_open_readonly(CMD, db);
    if (!s) {
        free(three);
        return MPB_EXIT_ERROR;
    }
    int status = MPB_EXIT_ERROR;
    if (selecting) {
        if (tool_experiment(CMD, s, db, &experiment) != 0)
            goto out;
        if (view_select_runs(s, db, experiment, &sel) != 0)
            goto out;
        if (sel.num_runs == 0) {
            fprintf(stderr, "mpb " CMD ": %s: no finished%s run of "
                    "experiment %lld%s%s%s%s%s%s%s%s%s\n", db,
                    sel.failed ? " failed" : "", (long long)experiment,
                    sel.scene ? " in scene '" : "", sel.scene ? sel.scene : "",
                    sel.scene ? "'" : "", sel.query ? " for query '" : "",
                    sel.query ? sel.query : "", sel.query ? "'" : "",
                    sel.planner ? " by '" : "", sel.planner ? sel.planner : "",
                    sel.planner ? "'" : "");
            goto out;
        }
        if (sel.num_runs > 1) {
            /* A folder of pages and their index. */
            if (output) {
                if (mkdir(output, 0777) != 0 && errno != EEXIST) {
                    fprintf(stderr, "mpb " CMD ": cannot make %s: %s\n",
                            output, strerror(errno));
                    goto out;
                }
                snprintf(path, sizeof path, "%s", output);
            } else {
                snprintf(path, sizeof path, "%s/mpb-view-experiment%lld-XXXXXX",
                         tmp_dir(), (long long)experiment);
                if (!mkdtemp(path)) {
                    fprintf(stderr, "mpb " CMD ": cannot make a folder in "
                            "%s: %s\n", tmp_dir(), strerror(errno));
                    goto out;
                }
            }
            if (view_write_many(s, db, experiment, &sel, three, path) != 0)
                goto out;
            size_t n = strlen(path);
            snprintf(path + n, sizeof path - n, "/index.html");
            say_where(path);
            status = MPB_EXIT_OK;
            goto out;
        }
        run_id = sel.runs[0];
    }

    view_run v = {0};
    char why[512] = "";
    int got = view_load(s, db, run_id, &v, why, sizeof why);
    if (got == 1)
        fprintf(stderr, "mpb " CMD ": %s: %s\n", db, why);
    if (got == 0) {
        if (output) {
            if (view_write_file(&v, three, output) == 0) {
                printf("wrote %s\n", output);
                status = MPB_EXIT_OK;
            }
        } else {
            snprintf(path, sizeof path, "%s/mpb-view-run%lld-XXXXXX.html",
                     tmp_dir(), (long long)run_id);
            int fd = mkstemps(path, 5);
            if (fd < 0) {
                fprintf(stderr, "mpb " CMD ": cannot make a file in %s: %s\n",
                        tmp_dir(), strerror(errno));
            } else {
                close(fd);
                if (view_write_file(&v, three, path) == 0) {
                    say_where(path);
                    status = MPB_EXIT_OK;
                } else {
                    remove(path);
                }
            }
        }
    }
    view_free(&v);
out:
    view_selection_free(&sel);
    mpb_store_close(s);
    free(three);
    return status;
}

