/*
 * plot_gnuplot.c - `mpb plot`'s drawing: gnuplot commands, data inline as
 * datablocks, for one scene's box plots and success-rate bars.
 *
 * Text reaches gnuplot only through put_text() and paths through
 * put_path(), as single-quoted strings, which gnuplot takes literally
 * (it runs `commands` found in double-quoted ones): names keep their
 * UTF-8, which the pngcairo and svg terminals draw. Titles are wrapped to
 * the image's width.
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpb.h"
#include "plot.h"

static int plot_ids[MPB_NUM_METRICS], num_plotted = -1;

int plot_num_metrics(void)
{
    if (num_plotted < 0) {
        num_plotted = 0;
        for (int rank = 1; rank <= MPB_NUM_METRICS; rank++)
            for (int id = 0; id < MPB_NUM_METRICS; id++)
                if (mpb_metric_info_of(id)->rank == rank)
                    plot_ids[num_plotted++] = id;
    }
    return num_plotted;
}

const mpb_metric_info *plot_metric(int m)
{
    return m >= 0 && m < plot_num_metrics() ? mpb_metric_info_of(plot_ids[m])
                                            : NULL;
}

/* Stage colours (a colour-blind-safe set), then a fallback. */
static const char *const colors[] = {
    "#d95f02", "#7570b3", "#1b9e77", "#e7298a", "#66a61e", "#e6ab02",
};
#define NUM_COLORS ((int)(sizeof colors / sizeof colors[0]))
#define ONE_COLOR "#4c72b0"

void plot_glyphs_free(plot_glyphs *gl)
{
    free(gl->cp);
    free(gl->ok);
    *gl = (plot_glyphs){.all = gl->all};
}

/* Whether a font has character c (a printable one). */
static int drawable(plot_glyphs *gl, unsigned c)
{
    if (gl == NULL || gl->all || c < 0x590 || (c >= 0x1e00 && c < 0x2300))
        return 1;
    for (int i = 0; i < gl->n; i++)
        if (gl->cp[i] == c)
            return gl->ok[i];
    char cmd[80];
    snprintf(cmd, sizeof cmd, "fc-list ':charset=%x' family 2>/dev/null", c);
    FILE *f = popen(cmd, "r");
    int ok = f != NULL && fgetc(f) != EOF;
    if (f != NULL) {
        while (fgetc(f) != EOF)
            ;
        pclose(f);
    }
    if (gl->n == gl->cap) {
        int cap = gl->cap ? 2 * gl->cap : 16;
        unsigned *ncp = realloc(gl->cp, (size_t)cap * sizeof *ncp);
        if (ncp != NULL)
            gl->cp = ncp;
        char *nok = ncp ? realloc(gl->ok, (size_t)cap) : NULL;
        if (nok == NULL)
            return ok;      /* not kept: looked up again next time */
        gl->ok = nok;
        gl->cap = cap;
    }
    gl->cp[gl->n] = c;
    gl->ok[gl->n++] = (char)ok;
    return ok;
}

/* Up to size - 1 bytes of in, as text to draw: valid UTF-8 kept whole; a
 * control character, a byte of no valid sequence or a character gl says no
 * font has as '?'; "..." ends it when it does not fit. */
static const char *clean_text(char *out, size_t size, const char *in,
                              plot_glyphs *gl)
{
    size_t n = 0;
    unsigned cp;
    while (in && *in) {
        int len = tool_utf8_char(in, &cp);
        if (len == 0)
            len = -1;
        else if (cp < 0x20 || (cp >= 0x7f && cp < 0xa0) || !drawable(gl, cp))
            len = -len;
        size_t need = len < 0 ? (size_t)-len : (size_t)len;
        size_t room = len < 0 ? 1 : need;
        if (n + room + 1 > size) {
            while (n > 0 && n + 4 > size) {    /* room for "...": drop */
                n--;                           /* whole characters */
                while (n > 0 && ((unsigned char)out[n] & 0xc0) == 0x80)
                    n--;
            }
            if (n + 4 <= size)
                memcpy(out + n, "...", 3), n += 3;
            break;
        }
        if (len < 0)
            out[n++] = '?';
        else
            memcpy(out + n, in, need), n += need;
        in += need;     /* a character not drawn: one '?' for all of it */
    }
    if (size > 0)
        out[n] = '\0';
    return out;
}

/* Append clean text in to out (size bytes in all), on a line of its own
 * when out has one, broken at spaces into lines of at most cols columns; a
 * word longer than that is broken where it reaches them. */
static void add_lines(char *out, size_t size, const char *in, int cols)
{
    size_t n = strlen(out);
    int col = 0;
    unsigned cp;

    if (n > 0 && n + 1 < size)
        out[n++] = '\n';
    while (*in && n + 1 < size) {
        const char *word = in;
        while (*in && *in != ' ')
            in++;
        int w = tool_text_cols(word, in);
        if (col > 0 && col + 1 + w > cols) {
            out[n++] = '\n';
            col = 0;
        } else if (col > 0) {
            out[n++] = ' ';
            col++;
        }
        for (const char *p = word; p < in && n + 1 < size;) {
            int len = tool_utf8_char(p, &cp), cw;
            if (len == 0)
                len = 1, cp = '?';
            cw = tool_char_cols(cp);
            if (col > 0 && col + cw > cols && n + 2 < size) {
                out[n++] = '\n';
                col = 0;
            }
            if (n + (size_t)len + 1 > size)
                break;
            memcpy(out + n, p, (size_t)len);
            n += (size_t)len;
            p += len;
            col += cw;
        }
        while (*in == ' ')
            in++;
    }
    out[n < size ? n : size - 1] = '\0';
}

/* Text as a gnuplot string: single-quoted, ' doubled, each '\n' a line
 * break ('...'."\n".'...'). */
static void put_text(FILE *gp, const char *text)
{
    fputc('\'', gp);
    for (; *text; text++) {
        if (*text == '\n')
            fputs("'.\"\\n\".'", gp);
        else if (*text == '\'')
            fputs("''", gp);
        else
            fputc(*text, gp);
    }
    fputc('\'', gp);
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
    fprintf(gp, "set encoding utf8\nset output ");
    put_path(gp, path);
    fprintf(gp, "\n"
                "set border 3\n"
                "set xtics nomirror scale 0\n"
                "set ytics nomirror\n"
                "set grid ytics lc rgb '#dddddd'\n"
                "set style fill solid 0.4 border -1\n"
                /* Room for the two-line labels under the axis. */
                "set bmargin 4\n");
}

/* Wide enough for the boxes, up to a width a page or screen still takes. */
static int plot_width(const plot_scene *sc, int per_config)
{
    int w = 160 + per_config * sc->num_configs;
    return w < 800 ? 800 : w > 1600 ? 1600 : w;
}

/* Cut clean text s to at most cols columns, "..." at the end if cut. */
static void cut_cols(char *s, int cols)
{
    int col = 0;
    unsigned cp;
    char *end = NULL;   /* where "..." would go: cols - 3 columns in */
    for (char *p = s; *p;) {
        int len = tool_utf8_char(p, &cp);
        int cw = len ? tool_char_cols(cp) : 1;
        if (col + cw > cols - 3 && end == NULL)
            end = p;
        if (col + cw > cols) {
            strcpy(end, "...");
            return;
        }
        col += cw;
        p += len ? len : 1;
    }
}

/* xtics: one label per configuration, with its count of values; slanted
 * (and cut to 40 columns) when they would not fit side by side, else
 * broken into lines as wide as a box's room. */
static void config_tics(FILE *gp, const plot_scene *sc, plot_glyphs *gl,
                        const int *counts, const char *what, int width)
{
    char name[512], label[1200];
    int room = (width - 160) / (sc->num_configs > 0 ? sc->num_configs : 1);
    int slant = room < 150;
    if (slant)
        fprintf(gp, "set xtics rotate by -25 left\nset bmargin 9\n"
                    "set rmargin 26\n");
    fprintf(gp, "set xtics (");
    for (int c = 0; c < sc->num_configs; c++) {
        clean_text(name, sizeof name, sc->configs[c], gl);
        if (slant) {
            cut_cols(name, 40);
            snprintf(label, sizeof label, "%s (%d %s)", name, counts[c], what);
        } else {
            label[0] = '\0';
            add_lines(label, sizeof label, name, room / 8);
            size_t n = strlen(label);
            snprintf(label + n, sizeof label - n, "\n%d %s", counts[c], what);
        }
        fprintf(gp, "%s", c ? ", " : "");
        put_text(gp, label);
        fprintf(gp, " %d", c + 1);
    }
    fprintf(gp, ")\nset xrange [0.4:%d.6]\n", sc->num_configs);
}

static void datablock(FILE *gp, const char *name, const plot_series *s)
{
    fprintf(gp, "$%s << EOD\n", name);
    for (int i = 0; i < s->n; i++)
        fprintf(gp, "%.17g\n", s->v[i]);
    fprintf(gp, "EOD\n");
}

/* A configuration's place in a plot when it has nothing to draw. */
static void no_values(FILE *gp, const char *why, int c)
{
    fprintf(gp, "set label '%s' at %d, graph 0.5 center rotate by 90 "
                "tc rgb '#888888'\n", why, c + 1);
}

/*
 * One box, from mpb_summarize()'s quartiles (type 7, as R and numpy; see
 * docs/metrics.md): x q1 low high q3 median, where the whiskers reach the
 * furthest value within 1.5 interquartile ranges of the box. 0, or -1 when
 * there is no box (too few values, or no memory).
 */
static int box_row(FILE *gp, const char *name, const plot_series *s, double x)
{
    mpb_summary q;
    if (s->n < PLOT_BOX_MIN || mpb_summarize(s->v, s->n, &q) != MPB_OK)
        return -1;
    double iqr = q.q3 - q.q1, low = q.q1, high = q.q3;
    for (int i = 0; i < s->n; i++) {
        if (s->v[i] >= q.q1 - 1.5 * iqr && s->v[i] < low)
            low = s->v[i];
        if (s->v[i] <= q.q3 + 1.5 * iqr && s->v[i] > high)
            high = s->v[i];
    }
    fprintf(gp, "$%s << EOD\n%.17g %.17g %.17g %.17g %.17g %.17g\nEOD\n",
            name, x, q.q1, low, high, q.q3, q.median);
    return 0;
}

/* Box plots of series[c * num_stages + k], each run also a dot; stage
 * names in the key when there are several; none written where a
 * configuration has no values. Returns 0 if there is nothing to draw. */
static int boxes(FILE *gp, const plot_scene *sc, plot_glyphs *gl,
                 plot_series *const *series, int num_stages,
                 char *const *stage_names, const char *none, int logscale)
{
    double width = 0.7 / num_stages;
    int plotted = 0, n = sc->num_configs * num_stages;
    int *boxed = calloc((size_t)n + 1, sizeof *boxed);
    int *keyed = calloc((size_t)num_stages + 1, sizeof *keyed);
    int *stage_boxed = calloc((size_t)num_stages + 1, sizeof *stage_boxed);
    char name[160], block[32];

    if (boxed == NULL || keyed == NULL || stage_boxed == NULL)
        goto done;
    for (int c = 0; c < sc->num_configs; c++) {
        int any = 0;
        for (int k = 0; k < num_stages; k++) {
            const plot_series *s = series[c * num_stages + k];
            if (s->n == 0)
                continue;
            double x = c + 1 + (k - (num_stages - 1) / 2.0) * width;
            snprintf(block, sizeof block, "b%d_%d", c, k);
            datablock(gp, block, s);
            snprintf(block, sizeof block, "q%d_%d", c, k);
            boxed[c * num_stages + k] = box_row(gp, block, s, x) == 0;
            stage_boxed[k] |= boxed[c * num_stages + k];
            any = 1;
        }
        if (!any)
            no_values(gp, none, c);
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
            int box = boxed[c * num_stages + k];
            /* The stage's key: its first box, or its first dots when it
             * has no box. */
            int key = num_stages > 1 && !keyed[k] && (box || !stage_boxed[k]);
            /* Every run as a dot, spread sideways (gnuplot's rand() is
             * seeded the same each time: the same picture each time). */
            fprintf(gp, "%s $b%d_%d using (%g + %g * (rand(0) - 0.5)):1 with "
                        "points pt 7 ps 0.5 lc rgb '#60%s'",
                    plotted ? ", \\\n    " : " ", c, k, x, width * 0.5,
                    color + 1);
            if (key && !box) {
                keyed[k] = 1;
                fprintf(gp, " title ");
                put_text(gp, clean_text(name, sizeof name, stage_names[k], gl));
            } else {
                fprintf(gp, " notitle");
            }
            /* The box, its whiskers with bars at their ends, and the
             * median as a box of no height. */
            if (box) {
                fprintf(gp, ", \\\n    $q%d_%d using 1:2:3:4:5 with "
                            "candlesticks whiskerbars 0.5 lc rgb '%s' "
                            "fs transparent solid 0.4 border rgb '#000000'",
                        c, k, color);
                if (key) {
                    keyed[k] = 1;
                    fprintf(gp, " title ");
                    put_text(gp, clean_text(name, sizeof name, stage_names[k],
                                            gl));
                } else {
                    fprintf(gp, " notitle");
                }
                fprintf(gp, ", \\\n    $q%d_%d using 1:6:6:6:6 with "
                            "candlesticks lc rgb '#000000' lw 1.5 notitle",
                        c, k);
            }
            plotted++;
        }
    fprintf(gp, "\n");
done:
    free(boxed);
    free(keyed);
    free(stage_boxed);
    return plotted;
}

/* Columns of title text that fit across an image width px wide. */
static int title_cols(int width)
{
    return (width - 40) / 8;
}

/*
 * set title: what, the scene and the experiment (on one line when they fit
 * on one), then sub; each line broken to fit the image's width.
 */
static void set_title(FILE *gp, const plot_scene *sc, plot_glyphs *gl,
                      const char *what, const char *sub, int width)
{
    char scene[512], exp[512], where[1200], text[4096] = "";
    int cols = title_cols(width);

    snprintf(where, sizeof where, "scene %s, %d quer%s pooled (experiment %s)",
             clean_text(scene, sizeof scene, sc->scene, gl), sc->num_queries,
             sc->num_queries == 1 ? "y" : "ies",
             clean_text(exp, sizeof exp, sc->experiment, gl));
    if (tool_text_cols(what, NULL) + 3 + tool_text_cols(where, NULL) <= cols) {
        char line[1400];
        snprintf(line, sizeof line, "%s - %s", what, where);
        add_lines(text, sizeof text, line, cols);
    } else {
        add_lines(text, sizeof text, what, cols);
        add_lines(text, sizeof text, where, cols);
    }
    add_lines(text, sizeof text, sub, cols);
    if (sc->unfinished > 0) {
        char more[128];
        snprintf(more, sizeof more, "UNFINISHED: %d more run%s not finished "
                 "yet, not counted here", sc->unfinished,
                 sc->unfinished == 1 ? "" : "s");
        add_lines(text, sizeof text, more, cols);
    }
    fprintf(gp, "set title ");
    put_text(gp, text);
    fprintf(gp, "\n");
}

static int time_plot(FILE *gp, const plot_scene *sc, plot_glyphs *gl,
                     const char *path, const char *ext)
{
    plot_series **series = calloc((size_t)sc->num_configs + 1, sizeof *series);
    int *counts = calloc((size_t)sc->num_configs + 1, sizeof *counts);
    double lo = INFINITY, hi = 0;
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
    set_title(gp, sc, gl, "Planning time per run", "every finished run, solved "
              "or not; box: quartiles and median, whiskers: 1.5 IQR", width);
    fprintf(gp, "set ylabel \"total planning time tau_t (s%s)\"\n",
            logscale ? ", log scale" : "");
    config_tics(gp, sc, gl, counts, "runs", width);
    if (sc->time_limit > 0 && (logscale || hi > sc->time_limit / 10)) {
        fprintf(gp, "set yrange [*:%g]\n", sc->time_limit * (logscale ? 3 : 1.1));
        fprintf(gp, "set arrow from graph 0, first %g to graph 1, first %g "
                    "nohead dt 2 lc rgb '#aa0000'\n",
                sc->time_limit, sc->time_limit);
        fprintf(gp, "set label \"time limit %g s\" at graph 0.01, first %g "
                    "offset 0,0.7 tc rgb '#aa0000'\n",
                sc->time_limit, sc->time_limit);
    } else if (!(hi > lo)) {
        /* One value: gnuplot would warn of an empty range. */
        fprintf(gp, "set yrange [0:%g]\n", 2 * hi);
    }
    n = boxes(gp, sc, gl, series, 1, NULL, "no finished run", logscale);
done:
    free(series);
    free(counts);
    return n;
}

static int metric_plot(FILE *gp, const plot_scene *sc, plot_glyphs *gl,
                       int m, const char *path, const char *ext)
{
    int nk = sc->num_stages, nc = sc->num_configs, total = 0, n = 0;
    double hi = 0;
    plot_series **series = calloc((size_t)(nc * nk) + 1, sizeof *series);
    int *counts = calloc((size_t)nc + 1, sizeof *counts);
    char sub[256];

    if (series == NULL || counts == NULL)
        goto done;
    for (int c = 0; c < nc; c++) {
        counts[c] = sc->succeeded[c];
        for (int k = 0; k < nk; k++) {
            series[c * nk + k] = plot_metric_series(sc, m, k, c);
            total += series[c * nk + k]->n;
            for (int i = 0; i < series[c * nk + k]->n; i++)
                hi = fmax(hi, series[c * nk + k]->v[i]);
        }
    }
    if (total == 0)
        goto done;
    int width = plot_width(sc, 60 + 50 * nk);
    begin_plot(gp, path, ext, width);
    snprintf(sub, sizeof sub, "successful runs only, per stage of the "
             "planner's answer; %s", plot_metric(m)->better);
    set_title(gp, sc, gl, plot_metric(m)->title, sub, width);
    fprintf(gp, "set ylabel \"%s\"\n", plot_metric(m)->axis);
    config_tics(gp, sc, gl, counts, "successful runs", width);
    /* Every path metric is >= 0; all 0 (a straight path's smoothness)
     * would be an empty range to gnuplot. */
    fprintf(gp, hi > 0 ? "set yrange [0:*]\n" : "set yrange [0:1]\n");
    n = boxes(gp, sc, gl, series, nk, sc->stages, "no successful run", 0);
done:
    free(series);
    free(counts);
    return n;
}

static int success_plot(FILE *gp, const plot_scene *sc, plot_glyphs *gl,
                        const char *path, const char *ext)
{
    char sub[256];
    int finished = 0;

    for (int c = 0; c < sc->num_configs; c++)
        finished += sc->finished[c];
    if (finished == 0)
        return 0;
    int width = plot_width(sc, 120);
    begin_plot(gp, path, ext, width);
    snprintf(sub, sizeof sub, "solved, verified valid by mpbench and within "
             "the %g s time limit", sc->time_limit);
    set_title(gp, sc, gl, "Success rate per planner", sub, width);
    fprintf(gp, "set ylabel \"successful runs (%% of finished runs)\"\n"
                "set yrange [0:115]\nset ytics 0, 20, 100\n"
                "set boxwidth 0.6\nset style fill solid 0.6 border -1\n"
                "unset key\n");
    config_tics(gp, sc, gl, sc->finished, "runs", width);
    for (int c = 0; c < sc->num_configs; c++)
        if (sc->finished[c] == 0)
            no_values(gp, "no finished run", c);
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
                       const char *ext, plot_glyphs *gl,
                       void (*wrote)(void *ud, const char *path), void *ud)
{
    char path[4096];
    int n = 0;

    file_name(path, sizeof path, dir, sc->file, "time", ext);
    if (time_plot(gp, sc, gl, path, ext)) {
        wrote(ud, path);
        n++;
    }
    file_name(path, sizeof path, dir, sc->file, "success", ext);
    if (success_plot(gp, sc, gl, path, ext)) {
        wrote(ud, path);
        n++;
    }
    for (int m = 0; m < plot_num_metrics(); m++) {
        file_name(path, sizeof path, dir, sc->file, plot_metric(m)->name,
                       ext);
        if (metric_plot(gp, sc, gl, m, path, ext)) {
            wrote(ud, path);
            n++;
        }
    }
    fprintf(gp, "unset output\n");
    return n;
}

/* ---- for the other plots' writers (plot.h) -------------------------- */

void plot_put_text(FILE *gp, const char *text, plot_glyphs *gl)
{
    char clean[1024];
    put_text(gp, clean_text(clean, sizeof clean, text, gl));
}

void plot_put_path(FILE *gp, const char *path)
{
    put_path(gp, path);
}

void plot_begin(FILE *gp, const char *path, const char *ext, int width)
{
    begin_plot(gp, path, ext, width);
}

const char *plot_config_color(int config)
{
    /* ColorBrewer's Dark2, then four more far from all of them. */
    static const char *const config_colors[PLOT_COLORS] = {
        "#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02",
        "#a6761d", "#666666", "#1f78b4", "#e31a1c", "#000000", "#17becf",
    };
    return config_colors[config % PLOT_COLORS];
}
