/*
 * mpb.h - what the files of the `mpb` command line share: the list of
 * subcommands (one file each) and small helpers. Not part of libmpbench.
 */
#ifndef MPB_TOOL_H
#define MPB_TOOL_H

#include <stdint.h>
#include <stdio.h>

#include "mpbench/mpbench.h"

/*
 * The subcommands: name, one-line summary. `mpb NAME ARGS...` calls
 * cmd_NAME(argc, argv) with argv[0] = "NAME". To add one, add a line here
 * and a file NAME.c defining cmd_NAME; main.c needs no change.
 */
#define MPB_TOOL_COMMANDS(X)                                                  \
    X(report, "print an experiment's results as the paper's tables, per scene or set") \
    X(plot,   "box plots per scene; success-in-budget curves and profiles per set") \
    X(status, "follow a running experiment: progress, rate, time left, planners") \
    X(spy,    "start lcm-spy with mpbench's message types, to watch the traffic") \
    X(export, "write results for Planner Arena, OMPL's tools, or as CSV")    \
    X(import, "read OMPL and MoveIt benchmark logs into a database")       \
    X(srdf,   "write a robot's self-collision matrix as an SRDF, for review") \
    X(view,   "draw a run in 3-D: a self-contained HTML page (three.js)") \
    X(verify, "check stored runs again with this mpbench's world model") \
    X(compare, "compare configurations problem by problem: intervals, paired tests") \
    X(sense,  "what depth cameras see of a scene, as a scene of one octree")

#define MPB__TOOL_DECLARE(name, summary) int cmd_##name(int argc, char **argv);
MPB_TOOL_COMMANDS(MPB__TOOL_DECLARE)
#undef MPB__TOOL_DECLARE

/* Exit statuses of every subcommand. */
enum {
    MPB_EXIT_OK = 0,
    MPB_EXIT_ERROR = 1,     /* the command could not do its work */
    MPB_EXIT_USAGE = 2      /* bad command line */
};

/*
 * Open the database at path read-only. On failure print one line,
 * "mpb CMD: cannot open PATH: why", and return NULL. Close the store with
 * mpb_store_close().
 */
mpb_store *tool_open_readonly(const char *cmd, const char *path);

/*
 * The experiment a command works on: *experiment if nonzero (it must
 * exist), else the newest in the database. 0, or -1 after one line ("mpb
 * CMD: DB holds no experiment", "mpb CMD: DB: no experiment 7").
 */
int tool_experiment(const char *cmd, mpb_store *s, const char *db,
                    int64_t *experiment);

/* Parse a whole decimal integer > 0 (an id); 0 on success, -1 if not one. */
int tool_parse_id(const char *text, int64_t *out);

/*
 * For getopt_long run with opterr = 0 and an option string that starts
 * with ':': say in one line what was wrong with the option just read (opt
 * ':' a missing value, anything else an unknown option) or with an
 * argument left over, and return MPB_EXIT_USAGE.
 */
int tool_option_error(const char *cmd, int opt, char **argv);
int tool_extra_argument(const char *cmd, const char *arg);

/* The problem set a scene belongs to, as the database keeps it
 * (scenes.problem_set: the experiment file's `set:`, else
 * MotionBenchMaker's "box_panda/0001" is in "box_panda" and a scene
 * without a '/' is its own; mpb_store_problem_set_len()). Every tool
 * groups by it, so all agree. Valid as long as the row. */
const char *tool_problem_set(const mpb_scene_row *scene);

/* The index of scene's problem set (tool_problem_set()) among the *n
 * names of *sets, the set added at the end (a copy of its name) when it
 * is not there yet; -1 when out of memory. free() each name and the
 * array. */
int tool_set_index(char ***sets, int *n, const mpb_scene_row *scene);

/* s as one CSV field, always quoted, '"' doubled (RFC 4180). */
void tool_csv_text(FILE *f, const char *s);

/* The lists a tool reads an experiment into, from the store's callbacks:
 * a configuration's id and a copy of its name appended to *ids and
 * *names (*n of each); a scene's id and its problem set's index
 * (tool_set_index(), into *sets of *nsets) appended to *ids and *set_of.
 * 0, or -1 when out of memory (the lists stay valid, to free). */
int tool_config_add(int64_t **ids, char ***names, int *n,
                    const mpb_planner_config_row *config);
int tool_scene_add(int64_t **ids, int **set_of, int *n, char ***sets,
                   int *nsets, const mpb_scene_row *scene);

/* The length of the valid UTF-8 sequence at s, its code point in *cp; 0
 * when s does not start one. */
int tool_utf8_char(const char *s, unsigned *cp);
/* Columns character c takes on a terminal or in a plot: 2 for the wide
 * (East Asian) ones, else 1. */
int tool_char_cols(unsigned c);
/* Columns of the text from s up to end (or its '\0'); a byte that starts
 * no valid character takes one. */
int tool_text_cols(const char *s, const char *end);

#endif
