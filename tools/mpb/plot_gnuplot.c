/*
 * plot_gnuplot.c - `mpb plot`'s drawing: gnuplot commands, data inline as
 * datablocks, for one scene's box plots and success-rate bars.
 *
 * Names from the database reach gnuplot only through safe_text(): gnuplot
 * runs `commands` found in double-quoted strings, so every character but
 * a harmless few becomes '?'. Paths go in single quotes, which gnuplot
 * takes literally.
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plot.h"

const plot_metric_info plot_metrics[PM_COUNT] = {
    [PM_PATH_LENGTH] = {"path_length", "Joint-space path length",
                        "joint-space path length (rad)", "shorter is better"},
    [PM_SMOOTHNESS] = {"smoothness",
                       "Smoothness: mean squared turning angle between segments",
                       "smoothness (rad^2)", "lower is smoother"},
    [PM_CLEARANCE] = {"clearance", "Mean clearance from obstacles",
                      "mean distance to the nearest obstacle (m)",
                      "higher keeps further away"},
    [PM_EE_PATH_LENGTH] = {"ee_path_length", "End-effector path length",
                           "distance travelled by the end-effector (m)",
                           "shorter is better"},
};

/* Stage colours (a colour-blind-safe set), then a fallback. */
static const char *const colors[] = {
    "#d95f02", "#7570b3", "#1b9e77", "#e7298a", "#66a61e", "#e6ab02",
};
#define NUM_COLORS ((int)(sizeof colors / sizeof colors[0]))
#define ONE_COLOR "#4c72b0"

static const char *safe_text(char *out, size_t size, const char *in)
{
    size_t n = 0;
    for (; in && *in && n + 1 < size; in++) {
        unsigned char c = (unsigned char)*in;
        out[n++] = (char)(isalnum(c) || strchr(" _./#:+()=,-", c) ? c : '?');
    }
    out[n] = '\0';
    return out;
}

void plot_file_part(char *out, size_t size, const char *scene)
{
    size_t n = 0, max = size < PLOT_PART_MAX + 1 ? size : PLOT_PART_MAX + 1;
    unsigned char prev = 0;
    for (; scene && *scene && n + 1 < max; scene++) {
        unsigned char c = (unsigned char)*scene;
        /* A UTF-8 continuation byte after a non-ASCII byte: the same
         * character, already one '_'. */
        if ((c & 0xc0) == 0x80 && prev >= 0x80) {
            prev = c;
            continue;
        }
        prev = c;
        out[n++] = (char)(c < 0x80 && (isalnum(c) || strchr("_.-", c))
                          ? c : '_');
    }
    out[n] = '\0';
}

static void file_name(char *out, size_t size, const char *dir,
                      const char *part, const char *what, const char *ext)
{
    snprintf(out, size, "%s/plot-%s-%s.%s", dir, part, what, ext);
}

/* A path as a gnuplot single-quoted string: ' doubled. */
static void put_path(FILE *gp, const char *path)
{
    fputc('\'', gp);
    for (; *path; path++) {
        if (*path == '\'')
            fputc('\'', gp);
        fputc(*path, gp);
    }
    fputc('\'', gp);
}

static void begin_plot(FILE *gp, const char *path, const char *ext, int width)
{
    fprintf(gp, "reset\n");
    if (strcmp(ext, "svg") == 0)
        fprintf(gp, "set terminal svg size %d,560 font 'Sans,12' noenhanced "
                    "background rgb 'white'\n", width);
    else
        fprintf(gp, "set terminal pngcairo size %d,560 font 'Sans,10' "
                    "noenhanced\n", width);
    fprintf(gp, "set output ");
    put_path(gp, path);
    fprintf(gp, "\n"
                "set border 3\n"
                "set xtics nomirror scale 0\n"
                "set ytics nomirror\n"
                "set grid ytics lc rgb '#dddddd'\n"
                "set style fill solid 0.4 border -1\n"
                "set style boxplot nooutliers candlesticks\n"
                /* Room for the two-line labels under the axis. */
                "set bmargin 4\n");
}

/* Wide enough for the boxes, up to a width a page or screen still takes. */
static int plot_width(const plot_scene *sc, int per_config)
{
    int w = 160 + per_config * sc->num_configs;
    return w < 800 ? 800 : w > 1600 ? 1600 : w;
}

/* xtics: one label per configuration, with its count of values; slanted
 * when they would not fit side by side. */
static void config_tics(FILE *gp, const plot_scene *sc, const int *counts,
                        const char *what, int width)
{
    char name[160];
    int slant = (width - 160) / (sc->num_configs > 0 ? sc->num_configs : 1)
                < 150;
    if (slant)
        fprintf(gp, "set xtics rotate by -25 left\nset bmargin 9\n"
                    "set rmargin 26\n");
    fprintf(gp, "set xtics (");
    for (int c = 0; c < sc->num_configs; c++)
        fprintf(gp, slant ? "%s\"%s (%d %s)\" %d" : "%s\"%s\\n%d %s\" %d",
                c ? ", " : "", safe_text(name, sizeof name, sc->configs[c]),
                counts[c], what, c + 1);
    fprintf(gp, ")\nset xrange [0.4:%d.6]\n", sc->num_configs);
}

static void datablock(FILE *gp, const char *name, const plot_series *s)
{
    fprintf(gp, "$%s << EOD\n", name);
    for (int i = 0; i < s->n; i++)
        fprintf(gp, "%.17g\n", s->v[i]);
    fprintf(gp, "EOD\n");
}

/* Box plots of boxes[c * num_stages + k]; stage names in the key when
 * there are several. Returns 0 if there is nothing to draw. */
static int boxes(FILE *gp, const plot_scene *sc, plot_series *const *series,
                 int num_stages, char *const *stage_names, int logscale)
{
    double width = 0.7 / num_stages;
    int plotted = 0, keyed[64] = {0};
    char name[160];

    for (int c = 0; c < sc->num_configs; c++) {
        int any = 0;
        for (int k = 0; k < num_stages; k++) {
            const plot_series *s = series[c * num_stages + k];
            if (s->n == 0)
                continue;
            char block[32];
            snprintf(block, sizeof block, "b%d_%d", c, k);
            datablock(gp, block, s);
            any = 1;
        }
        if (!any)
            fprintf(gp, "set label \"no successful run\" at %d, graph 0.5 "
                        "center rotate by 90 tc rgb '#888888'\n", c + 1);
    }
    if (logscale)
        fprintf(gp, "set logscale y\nset format y '%%g'\n");
    fprintf(gp, "set boxwidth %g\n", width * 0.9);
    if (num_stages > 1)
        fprintf(gp, "set key outside right top vertical title 'stage' "
                    "samplen 2\n");
    else
        fprintf(gp, "unset key\n");
    fprintf(gp, "plot");
    for (int c = 0; c < sc->num_configs; c++)
        for (int k = 0; k < num_stages; k++) {
            const plot_series *s = series[c * num_stages + k];
            if (s->n == 0)
                continue;
            double x = c + 1 + (k - (num_stages - 1) / 2.0) * width;
            const char *color = num_stages > 1 ? colors[k % NUM_COLORS]
                                               : ONE_COLOR;
            /* Every run as a dot, spread sideways (gnuplot's rand() is
             * seeded the same each time: the same picture each time); a
             * box of two values says little alone. */
            fprintf(gp, "%s $b%d_%d using (%g + %g * (rand(0) - 0.5)):1 with "
                        "points pt 7 ps 0.5 lc rgb '#60%s' notitle",
                    plotted ? ", \\\n    " : " ", c, k, x, width * 0.5,
                    color + 1);
            fprintf(gp, ", \\\n    $b%d_%d using (%g):1 with boxplot "
                        "lc rgb '%s' fs transparent solid 0.4 border -1",
                    c, k, x, color);
            if (num_stages > 1 && k < 64 && !keyed[k]) {
                keyed[k] = 1;
                fprintf(gp, " title \"%s\"",
                        safe_text(name, sizeof name, stage_names[k]));
            } else {
                fprintf(gp, " notitle");
            }
            plotted++;
        }
    fprintf(gp, "\n");
    return plotted;
}

static void heading(char *out, size_t size, const plot_scene *sc,
                    const char *what)
{
    char scene[160], exp[160];
    snprintf(out, size, "%s - scene %s, %d quer%s pooled (experiment %s)",
             what, safe_text(scene, sizeof scene, sc->scene), sc->num_queries,
             sc->num_queries == 1 ? "y" : "ies",
             safe_text(exp, sizeof exp, sc->experiment));
}

static int time_plot(FILE *gp, const plot_scene *sc, const char *path,
                     const char *ext)
{
    plot_series **series = calloc((size_t)sc->num_configs + 1, sizeof *series);
    int *counts = calloc((size_t)sc->num_configs + 1, sizeof *counts);
    double lo = INFINITY, hi = 0;
    char title[512];
    int n = 0;

    if (series == NULL || counts == NULL)
        goto done;
    for (int c = 0; c < sc->num_configs; c++) {
        series[c] = &sc->time[c];
        counts[c] = sc->time[c].n;
        for (int i = 0; i < series[c]->n; i++) {
            lo = fmin(lo, series[c]->v[i]);
            hi = fmax(hi, series[c]->v[i]);
        }
    }
    if (!(hi > 0))
        goto done;
    /* Times of different planners differ by orders of magnitude. */
    int logscale = lo > 0 && hi / lo > 100;
    int width = plot_width(sc, 150);
    begin_plot(gp, path, ext, width);
    heading(title, sizeof title, sc, "Planning time per run");
    fprintf(gp, "set title \"%s\\nevery finished run, solved or not; "
                "box: quartiles and median, whiskers: 1.5 IQR\"\n", title);
    fprintf(gp, "set ylabel \"total planning time tau_t (s%s)\"\n",
            logscale ? ", log scale" : "");
    config_tics(gp, sc, counts, "runs", width);
    if (sc->time_limit > 0 && (logscale || hi > sc->time_limit / 10)) {
        fprintf(gp, "set yrange [*:%g]\n", sc->time_limit * (logscale ? 3 : 1.1));
        fprintf(gp, "set arrow from graph 0, first %g to graph 1, first %g "
                    "nohead dt 2 lc rgb '#aa0000'\n",
                sc->time_limit, sc->time_limit);
        fprintf(gp, "set label \"time limit %g s\" at graph 0.01, first %g "
                    "offset 0,0.7 tc rgb '#aa0000'\n",
                sc->time_limit, sc->time_limit);
    }
    n = boxes(gp, sc, series, 1, NULL, logscale);
done:
    free(series);
    free(counts);
    return n;
}

static int metric_plot(FILE *gp, const plot_scene *sc, int m,
                       const char *path, const char *ext)
{
    int nk = sc->num_stages, nc = sc->num_configs, total = 0, n = 0;
    plot_series **series = calloc((size_t)(nc * nk) + 1, sizeof *series);
    int *counts = calloc((size_t)nc + 1, sizeof *counts);
    char title[512];

    if (series == NULL || counts == NULL)
        goto done;
    for (int c = 0; c < nc; c++) {
        counts[c] = sc->succeeded[c];
        for (int k = 0; k < nk; k++) {
            series[c * nk + k] = plot_metric_series(sc, m, k, c);
            total += series[c * nk + k]->n;
        }
    }
    if (total == 0)
        goto done;
    int width = plot_width(sc, 60 + 50 * nk);
    begin_plot(gp, path, ext, width);
    heading(title, sizeof title, sc, plot_metrics[m].title);
    fprintf(gp, "set title \"%s\\nsuccessful runs only, per stage of the "
                "planner's answer; %s\"\n", title, plot_metrics[m].note);
    fprintf(gp, "set ylabel \"%s\"\n", plot_metrics[m].axis);
    config_tics(gp, sc, counts, "successful runs", width);
    fprintf(gp, "set yrange [0:*]\n"); /* every path metric is >= 0 */
    n = boxes(gp, sc, series, nk, sc->stages, 0);
done:
    free(series);
    free(counts);
    return n;
}

static int success_plot(FILE *gp, const plot_scene *sc, const char *path,
                        const char *ext)
{
    char title[512];
    int finished = 0;

    for (int c = 0; c < sc->num_configs; c++)
        finished += sc->finished[c];
    if (finished == 0)
        return 0;
    int width = plot_width(sc, 120);
    begin_plot(gp, path, ext, width);
    heading(title, sizeof title, sc, "Success rate per planner");
    fprintf(gp, "set title \"%s\\nsolved, verified valid by mpbench and "
                "within the %g s time limit\"\n", title, sc->time_limit);
    fprintf(gp, "set ylabel \"successful runs (%% of finished runs)\"\n"
                "set yrange [0:115]\nset ytics 0, 20, 100\n"
                "set boxwidth 0.6\nset style fill solid 0.6 border -1\n"
                "unset key\n");
    config_tics(gp, sc, sc->finished, "runs", width);
    fprintf(gp, "$s << EOD\n");
    for (int c = 0; c < sc->num_configs; c++)
        if (sc->finished[c] > 0)
            fprintf(gp, "%d %.6g \"%d of %d\"\n", c + 1,
                    100.0 * sc->succeeded[c] / sc->finished[c],
                    sc->succeeded[c], sc->finished[c]);
    fprintf(gp, "EOD\n"
                "plot $s using 1:2 with boxes lc rgb '" ONE_COLOR "', \\\n"
                "    $s using 1:2:3 with labels offset 0,0.8\n");
    return 1;
}

int plot_gnuplot_scene(FILE *gp, const plot_scene *sc, const char *dir,
                       const char *ext,
                       void (*wrote)(void *ud, const char *path), void *ud)
{
    char path[4096];
    int n = 0;

    file_name(path, sizeof path, dir, sc->file, "time", ext);
    if (time_plot(gp, sc, path, ext)) {
        wrote(ud, path);
        n++;
    }
    file_name(path, sizeof path, dir, sc->file, "success", ext);
    if (success_plot(gp, sc, path, ext)) {
        wrote(ud, path);
        n++;
    }
    for (int m = 0; m < PM_COUNT; m++) {
        file_name(path, sizeof path, dir, sc->file, plot_metrics[m].name,
                       ext);
        if (metric_plot(gp, sc, m, path, ext)) {
            wrote(ud, path);
            n++;
        }
    }
    fprintf(gp, "unset output\n");
    return n;
}
