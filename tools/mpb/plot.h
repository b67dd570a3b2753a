/*
 * plot.h - what `mpb plot` gathers for one scene (plot.c) and hands to the
 * gnuplot writer (plot_gnuplot.c).
 */
#ifndef MPB_PLOT_H
#define MPB_PLOT_H

#include <stdio.h>

#include "mpbench/metrics.h"
#include "mpbench/store.h"

/* The path metrics plotted per stage: those of the metric list
 * (MPB_METRIC_MAP, mpbench/metrics.h) that have a rank, in rank order;
 * plot_metric(m), m < plot_num_metrics(), gives the list's line. */
int plot_num_metrics(void);
const mpb_metric_info *plot_metric(int m);

/* A box needs this many values; fewer are drawn only as dots. */
#define PLOT_BOX_MIN 3

/* Values of one box, grown as rows come. */
typedef struct plot_series {
    double *v;
    int     n, cap;
} plot_series;

typedef struct plot_scene {
    const char *experiment;  /* name */
    const char *scene;       /* name */
    const char *file;        /* the scene in file names, unique in the
                              * experiment: see plot_file_part() */
    int         num_queries; /* the scene's queries, pooled in every plot */
    double      time_limit;  /* s */
    int         unfinished;  /* runs of the scene not done yet */
    int         num_configs;
    char      **configs;     /* names, "ompl/RRTConnect" */
    int         num_stages;
    char      **stages;      /* "raw", "shortcut", "smoothed", ... */
    int        *finished;    /* per config: finished runs */
    int        *succeeded;   /* per config */
    plot_series *time;       /* per config: time_total of finished runs */
    plot_series *metric;     /* [metric][stage][config], successful runs */
} plot_scene;

static inline plot_series *plot_metric_series(const plot_scene *sc, int m,
                                              int stage, int config)
{
    return &sc->metric[((size_t)m * (size_t)sc->num_stages + (size_t)stage)
                       * (size_t)sc->num_configs + (size_t)config];
}

/*
 * Which characters a PNG can show. For a character no installed font has,
 * pango draws a box many times the text's size across the image, so such
 * characters are drawn as '?'. Latin, Greek and Cyrillic are taken as
 * there; any other character is looked up once with fontconfig's fc-list
 * (none without fc-list). An SVG is drawn by its viewer's fonts: all.
 */
typedef struct plot_glyphs {
    int       all;        /* every character (SVG) */
    unsigned *cp;         /* characters looked up */
    char     *ok;         /* per cp: a font has it */
    int       n, cap;
} plot_glyphs;

void plot_glyphs_free(plot_glyphs *gl);

/*
 * Write to gp the gnuplot commands that draw one scene's plots into dir,
 * as plot-FILE-WHAT.EXT (FILE sc->file, EXT "png" or "svg"): planning
 * time, success rate, and each path metric that has values; names drawn
 * as gl lets them. wrote(ud, path) is called for each file the commands
 * make. Returns the number of plots.
 */
int plot_gnuplot_scene(FILE *gp, const plot_scene *sc, const char *dir,
                       const char *ext, plot_glyphs *gl,
                       void (*wrote)(void *ud, const char *path), void *ud);

/*
 * A scene's name as it goes into file names: [A-Za-z0-9_.-] kept, any other
 * character (a UTF-8 sequence counts as one) as '_', at most
 * PLOT_PART_MAX bytes. Two names can give the same part ("a b", "a_b");
 * plot.c then adds each such scene's id (see name_files()).
 */
#define PLOT_PART_MAX 120
void plot_file_part(char *out, size_t size, const char *scene);

/* What every plot's writer shares (plot_gnuplot.c): text as a gnuplot
 * string drawn as gl lets it, a path as one, and the terminal, output and
 * axes' style of a new plot width pixels wide. */
void plot_put_text(FILE *gp, const char *text, plot_glyphs *gl);
void plot_put_path(FILE *gp, const char *path);
void plot_begin(FILE *gp, const char *path, const char *ext, int width);
/* The colour, "#rrggbb", configuration number config (in id order) is
 * drawn in, in every plot of curves per configuration (the budget
 * curves, gnuplot's and the report's SVG, and the performance
 * profiles), so that a configuration looks the same in all; distinct
 * for the first PLOT_COLORS. */
#define PLOT_COLORS 12
const char *plot_config_color(int config);

/*
 * Success against the time budget (plot_budget.c): for each problem set
 * (scenes.problem_set, tool_problem_set()) and over all
 * problems, each configuration's fraction of runs verified successful by
 * time t, and the fraction claimed (status solved) by t, for every t up
 * to the time limit: from the stored times, no run again. Read from the
 * experiment (scene_id 0 for all scenes, else one), written as
 * DIR/budget.csv and drawn into gp as plot-budget-SET.EXT; wrote() as
 * for plot_gnuplot_scene(). MPB_OK, MPB_ENOMEM, or a store error.
 */
typedef struct plot_budget plot_budget;
int  plot_budget_read(mpb_store *s, int64_t experiment_id, int64_t scene_id,
                      plot_budget **out);
int  plot_budget_csv(const plot_budget *b, const char *dir,
                     void (*wrote)(void *ud, const char *path), void *ud);
int  plot_gnuplot_budget(FILE *gp, const plot_budget *b, const char *dir,
                         const char *ext, plot_glyphs *gl,
                         void (*wrote)(void *ud, const char *path), void *ud);
void plot_budget_free(plot_budget *b);

/* What b holds, for writers of their own (the HTML report's SVG): its
 * sets (index plot_budget_num_sets() is all problems, drawn only when
 * there are several: plot_budget_drawn()), configurations (in id order),
 * the time limit, and per set and configuration its finished runs and
 * the sorted times of the verified and of the claimed ones, owned by b. */
typedef struct plot_budget_steps {
    int           runs;
    const double *verified;
    int           nv;
    const double *claimed;
    int           nc;
} plot_budget_steps;
int         plot_budget_num_sets(const plot_budget *b);
const char *plot_budget_set(const plot_budget *b, int set);
int         plot_budget_drawn(const plot_budget *b, int set);
int         plot_budget_num_configs(const plot_budget *b);
const char *plot_budget_config(const plot_budget *b, int config);
double      plot_budget_limit(const plot_budget *b);
void        plot_budget_curve(const plot_budget *b, int set, int config,
                              plot_budget_steps *out);

/*
 * Set set's curves as one inline SVG element (plot_budget_svg.c), with
 * no gnuplot: a log time axis, per configuration a solid step path
 * (class "curve verified") and a dotted one ("curve claimed"), a legend.
 * Returns the number of paths drawn (0: no run, nothing written).
 */
int plot_budget_svg(FILE *out, const plot_budget *b, int set);

/*
 * Performance profiles (plot_profile.c; Dolan and Moré): for each problem
 * set (tool_problem_set()) and over all problems when there are several,
 * for planning time and for path length (the final stage's), each
 * configuration's fraction of the set's problems (queries) on which its
 * value is within a factor tau of the best configuration's, for every
 * tau >= 1. A configuration's value on a problem is the median over its
 * runs there, a run that is no verified success counting as infinite;
 * an infinite value is within no factor. Read from the experiment,
 * written as DIR/profile.csv (set, metric time or path_length, planner,
 * tau, fraction, problems: one row per step) and drawn into gp as
 * plot-profile-SET.EXT, both metrics side by side; wrote() as for
 * plot_gnuplot_scene(). MPB_OK, MPB_ENOMEM, or a store error.
 */
#define PLOT_PROFILE_METRICS 2
typedef struct plot_profile plot_profile;
int  plot_profile_read(mpb_store *s, int64_t experiment_id, plot_profile **out);
int  plot_profile_csv(const plot_profile *p, const char *dir,
                      void (*wrote)(void *ud, const char *path), void *ud);
int  plot_gnuplot_profile(FILE *gp, const plot_profile *p, const char *dir,
                          const char *ext, plot_glyphs *gl,
                          void (*wrote)(void *ud, const char *path), void *ud);
void plot_profile_free(plot_profile *p);

#endif
