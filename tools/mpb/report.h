/*
 * report.h - what `mpb report`'s files share: an experiment's results
 * gathered per (planner configuration, query) (report_gather.c) and
 * folded per scene or problem set (report_columns.c), the paper's table
 * rows (report_rows.c) and their cells (report_cells.c), and one writer
 * per output format (report_text.c: text; report_formats.c: Markdown,
 * CSV, LaTeX, JSON; report_html.c). Not part of libmpbench.
 */
#ifndef MPB_TOOL_REPORT_H
#define MPB_TOOL_REPORT_H

#include <stdio.h>

#include "mpb.h"
#include "pairs.h"

/* What is averaged: the run's times, then the stage metrics of the list
 * (MPB_METRIC_MAP, mpbench/metrics.h), metric id k at FIRST_STORED + k;
 * the tables show those flagged MPB_METRIC_F_TABLE. */
enum { M_TT, M_TR, M_TO, M_WS, M_VT, M_MEM, FIRST_STORED,
       M_COUNT = FIRST_STORED + MPB_NUM_METRICS };
#define M_LP (FIRST_STORED + MPB_METRIC_PATH_LENGTH)

/* Whether the report shows metric k (M_...): the run's times always, a
 * stage metric when the list flags it MPB_METRIC_F_TABLE. */
int report_metric_shown(int k);

/* A metric's name in the machine-readable formats (its name in the
 * database for the stored ones) and its unit ("" for counts). */
typedef struct metric_info {
    const char *key;
    const char *unit;
} metric_info;
extern const metric_info report_metrics[M_COUNT];

/* SHOW_COUNT: a count of runs, metric the mpb_outcome counted
 * (outcome.h), or COUNT_CLAIMED for every claimed one. */
/* The problem-set tables' own rows (sets_only): SHOW_RATE_CI the success
 * rate's 95 % Wilson interval, SHOW_MEDIAN and SHOW_P95 the median and
 * 95th percentile of tau_t over successful runs, SHOW_MEDIAN_CI the
 * median's 95 % order-statistic interval. */
typedef enum { SHOW_MEAN, SHOW_SIGMA, SHOW_RATE, SHOW_CLAIMED, SHOW_COUNT,
               SHOW_RATE_CI, SHOW_MEDIAN, SHOW_MEDIAN_CI, SHOW_P95 } show;
#define COUNT_CLAIMED (-1)

typedef struct table_row {
    const char *label;      /* text and Markdown */
    const char *latex;      /* LaTeX (math mode where the paper has it) */
    int         metric;     /* M_..., unused for SHOW_RATE */
    show        what;
    int         optional;   /* printed only if some column has a value */
    int         decimals;   /* fixed decimals, or -1: the general format */
    int         sets_only;  /* only in a problem set's table (--by set) */
} table_row;

/* The paper's rows, in its order, then the list's other metrics;
 * report_rows_init() fills them (once; later calls do nothing). */
#define REPORT_MAX_ROWS (2 * M_COUNT + 10)
extern table_row report_rows[REPORT_MAX_ROWS];
extern int report_num_rows;
void report_rows_init(void);

/* One planner configuration on one query, or (folded) on one scene. */
typedef struct column {
    long        finished, succeeded;
    long        claimed;        /* finished runs the planner said it
                                   solved (verified or not) */
    long        outcomes[MPB_OUTCOME_COUNT]; /* finished runs by their
                                   outcome (outcome.h): verified,
                                   refused, late, unclaimed valid ... */
    long        stage_invalid;  /* successful runs whose --stage failed
                                   verification: its metrics left out */
    mpb_grouped m[M_COUNT];     /* successful runs; M_WS: every finished
                                   run that built a world; M_VT: every
                                   finished run the daemon verified;
                                   M_MEM: every finished run whose
                                   planner reported its memory */
    int         in_set;         /* a problem set's column (or all of
                                   them): times below, the sets_only rows */
    const double *times;        /* then: tau_t of the successful runs,
                                   sorted */
    long        ntimes;
} column;

typedef struct config_ref {
    int64_t id;
    char   *name, *planner, *algorithm, *params;
    char   *approach;   /* planner_configs.approach, or NULL: none declared */
} config_ref;

typedef struct scene_ref {
    int64_t id;
    char   *name;
    int     unfinished;         /* runs not done yet */
    int     set;                /* index into sets (tool_problem_set()) */
} scene_ref;

/* What the tables are one per (--by). */
typedef enum { BY_SCENE, BY_SET, BY_ALL } report_by;

/* Samples grown as runs come. */
typedef struct report_samples {
    double *v;
    long    n, cap;
} report_samples;

typedef struct query_ref {
    int64_t id;
    int     scene;              /* index into scenes */
} query_ref;

typedef struct report {
    const char *stage;          /* --stage, or NULL: each run's final one */
    int64_t     experiment_id;
    char       *experiment_name, *host, *version;
    int         runs_per_query;
    long        certified, sampled; /* stages by stages.verification */
    double      time_limit, created, finished;
    config_ref *configs;        /* grouped by approach, in the order of
                                   MPB_APPROACHES, none last; in id order
                                   within a group */
    int         num_configs, configs_cap;
    scene_ref  *scenes;         /* in id order */
    int         num_scenes, scenes_cap;
    query_ref  *queries;        /* sorted by id */
    int         num_queries, queries_cap;
    int         scene_index;    /* scene whose queries are being listed */
    column     *cells;          /* num_configs x num_queries */
    long        staged;         /* successful runs with stage metrics */
    const char *db_path;        /* the database: report_html.c reads runs */
    const char *views_dir;      /* html written to a file: the folder its
                                   failed runs' views go into (made if
                                   missing), views/ beside it; NULL when
                                   the page goes to stdout */
    const char *three_js;       /* three.js's source, for those views */
    report_by   by;
    int         by_default;     /* no --by: chosen once the scenes are
                                   read */
    int         any_seen;       /* some scene's planners were given what
                                   was seen of it (report_seen.c) */
    char      **sets;           /* problem sets' names, in order of
                                   their first scene */
    int         num_sets;
    report_samples *times;      /* by set or all: [(set) * num_configs +
                                   config], set num_sets: all problems;
                                   tau_t of successful runs, sorted */
    int         want_pairs;     /* fill pairs (--findings, html) */
    pairs_data  pairs;          /* the runs per configuration and query,
                                   query_set the query's set */
    int         nomem;
} report;

/* mpb_store_experiment_get()'s callback: the experiment's row into the
 * report r (ud); nonzero, and r->nomem set, when out of memory. */
int report_on_experiment(void *ud, const mpb_experiment_row *e);

/* Everything the tables need, after report_on_experiment(): the
 * experiment's configurations, scenes and queries, then one walk over
 * its runs (report_gather.c). MPB_OK, a store's error code, or nonzero
 * with r->nomem set. */
int report_gather(report *r, mpb_store *s);

/* Everything r holds freed (r itself is the caller's). */
void report_free(report *r);

/* The group of a configuration's approach: its place among
 * MPB_APPROACHES (proto.h), MPB_NUM_APPROACHES for none. */
int report_approach_group(const config_ref *c);

/* The word a report shows for c's approach: "-" for none. */
const char *report_approach_label(const config_ref *c);

/* Whether any configuration of r declares an approach. */
int report_any_approach(const report *r);

/* The sigma the report shows of g: NaN ('-') from fewer than two values,
 * where there is no spread to compute. */
double report_sigma(const mpb_grouped *g);

/* How many of g's groups (queries) have one sample: the paper's sigma
 * counts each as 0 spread, which is convention, not measurement. */
int report_sigma_single(const mpb_grouped *g);

/* A sigma cell with such queries ends with this mark; the note says why. */
#define SIGMA_SINGLE_MARK "*"
#define SIGMA_SINGLE_NOTE "* sigma counts a query with one successful run " \
                          "as 0 spread"

/* The value a row shows for a column; NaN when there is nothing. */
double report_row_value(const table_row *tr, const column *c);

/* The interval a SHOW_RATE_CI or SHOW_MEDIAN_CI row shows for a column,
 * into *lo and *hi; 1, or 0 (both NaN) when there is none: no run, or
 * too few for a median's 95 % interval (mpb_median_interval()). */
int report_row_interval(const table_row *tr, const column *c, double *lo,
                        double *hi);

/*
 * Fold the cells of scene si into one column per configuration:
 * cols[num_configs], filled in. Returns the scene's finished runs.
 */
long report_scene_columns(const report *r, int si, column *cols);

/*
 * The same of problem set set (-1: every problem), with its times and
 * sets_only rows. Returns the set's finished runs; *unfinished (if not
 * NULL) gets its runs not done yet.
 */
long report_set_columns(const report *r, int set, column *cols,
                        int *unfinished);

/* The name of set (-1: "all problems"). */
const char *report_set_name(const report *r, int set);

/* How many scenes of r are in set. */
int report_set_scenes(const report *r, int set);

#define CELL_TEXT 32

/*
 * Every row's text for the columns cols (num_configs of them), as the text
 * table prints it: text[row * num_configs + c]; "-" where there is nothing.
 * visible[row] says whether the row is printed (optional rows with no
 * value are not).
 */
void report_cells(const report *r, const column *cols, char (*text)[CELL_TEXT],
                  int *visible);

/* Whether some visible sigma cell of report_cells() is marked. */
int report_any_single(char (*text)[CELL_TEXT], const int *visible, int nc);

/* A writer's failure already told on stderr, in one line. */
#define REPORT_SAID (-1000)

/* The writers. Each returns MPB_OK or MPB_ENOMEM (the HTML one also
 * REPORT_SAID when a view cannot be written); output errors are found
 * by the caller with ferror(). */
int report_write_text(const report *r, FILE *out);
int report_write_markdown(const report *r, FILE *out);
int report_write_csv(const report *r, FILE *out);
int report_write_latex(const report *r, FILE *out);
int report_write_json(const report *r, FILE *out);
int report_write_html(const report *r, FILE *out);   /* report_html.c */

/* `--findings`: what the tables say, and whether the paper's qualitative
 * findings hold (report_findings.c). */
int report_write_findings(const report *r, FILE *out);

/* Its paired tests (report_paired.c): per problem set and approach, the
 * fastest and the best-path configuration where the signed-rank test
 * says so at 5 %, Holm-adjusted, else "no significant difference".
 * Needs r->want_pairs. MPB_OK or MPB_ENOMEM. */
int report_write_paired(const report *r, FILE *out);

/* The depth of refused paths per configuration, text or markdown
 * (report_depth.c); nothing when no run was refused for a collision. */
int report_write_depth(mpb_store *s, const report *r, int markdown, FILE *out);

/* Success on the truth beside success on what was seen, per configuration
 * and problem set, text or markdown (report_seen.c); nothing when every
 * planner had the scene itself. */
int report_write_seen(mpb_store *s, const report *r, int markdown, FILE *out);

#endif
