/*
 * plot.c - `mpb plot`: an experiment's results as pictures, per scene: box
 * plots of planning time and of each path metric per planner configuration
 * (per stage: raw, shortcut, smoothed, ...), and a bar chart of success
 * rates. This file reads the database through the store's read API;
 * plot_gnuplot.c draws, through one gnuplot process per image format.
 */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "mpb.h"
#include "plot.h"

#define CMD "plot"

/* Stages looked for in every run, in the order they are drawn; each run's
 * final stage is added when it has another name. */
static const char *const known_stages[] = {
    "raw", "shortcut", "simplified", "smoothed", "interpolated",
};
#define NUM_KNOWN ((int)(sizeof known_stages / sizeof known_stages[0]))

static void usage(FILE *out)
{
    fprintf(out,
        "usage: mpb plot [--experiment ID] [--scene NAME] [-o DIR]\n"
        "                [--format png|svg|both] DB\n"
        "\n"
        "Draw the results of an experiment in the database DB, one set of\n"
        "images per scene, named DIR/plot-SCENE-WHAT.png (or .svg):\n"
        "  time            box plot of the total planning time of every\n"
        "                  finished run, per planner configuration (log scale\n"
        "                  when times differ by more than 100x)\n"
        "  success         bar chart of the success rate per configuration\n"
        "  path_length, smoothness, clearance, ee_path_length\n"
        "                  box plots over successful runs, one box per\n"
        "                  configuration and stage (raw, shortcut, smoothed,\n"
        "                  ...), for the metrics the database holds\n"
        "and, per problem set (a scene's set:, else its name before its last\n"
        "'/') and over all problems when there are several sets,\n"
        "DIR/plot-budget-SET.png:\n"
        "  budget          the fraction of each configuration's runs solved\n"
        "                  within every time budget t up to the time limit,\n"
        "                  verified by mpbench (solid) and claimed by the\n"
        "                  planner (dotted), log time axis; its numbers in\n"
        "                  DIR/budget.csv (set, planner, curve, time,\n"
        "                  fraction, runs: one row per step)\n"
        "and DIR/plot-profile-SET.png:\n"
        "  profile         performance profiles (Dolan and More) of planning\n"
        "                  time and path length: the fraction of the set's\n"
        "                  problems on which each configuration's median run\n"
        "                  (a failed run counting as infinite) is within a\n"
        "                  factor tau of the best configuration's, log tau\n"
        "                  axis; its numbers in DIR/profile.csv (set, metric,\n"
        "                  planner, tau, fraction, problems: one row per step)\n"
        "SCENE is the scene's name with characters other than [A-Za-z0-9_.-]\n"
        "as '_', and -ID, the scene's id, added when two scenes would share it.\n"
        "Draws through gnuplot (Debian: gnuplot-nox), which must be on PATH.\n"
        "Prints the path of each image written.\n"
        "\n"
        "Options:\n"
        "  -e, --experiment ID  plot experiment ID (default: the newest)\n"
        "  -s, --scene NAME     only this scene\n"
        "  -o, --output DIR     where to write (default: .; created if missing)\n"
        "  -f, --format FMT     png (the default), svg, or both\n"
        "  -h, --help           print this help\n"
        "\n"
        "Exit status: 0 on success, 1 on an error (no such database or\n"
        "experiment, no finished runs, gnuplot missing or failing), 2 on a\n"
        "bad command line.\n");
}

/* ---- gathering ----------------------------------------------------------- */

typedef struct gather {
    int64_t     experiment_id;
    char       *experiment;
    double      time_limit;
    int64_t    *config_ids;
    char      **configs;
    int         num_configs;
    int64_t    *scene_ids;
    char      **scenes;
    char      **files;         /* per scene: its part of the file names */
    int         num_scenes;
    /* The scene being read. */
    plot_scene *sc;
    char      **finals;        /* final stage names seen */
    int         num_finals;
    int         stage;         /* stage index of the pass under way */
    int         nomem;
} gather;

static int push(plot_series *s, double v)
{
    if (s->n == s->cap) {
        int cap = s->cap ? 2 * s->cap : 16;
        double *nv = realloc(s->v, (size_t)cap * sizeof *nv);
        if (nv == NULL)
            return -1;
        s->v = nv;
        s->cap = cap;
    }
    s->v[s->n++] = v;
    return 0;
}

/* Append a copy of text to a growing array of strings. */
static int add_name(gather *g, char ***list, int *n, const char *text)
{
    char **nl = realloc(*list, (size_t)(*n + 1) * sizeof *nl);
    if (nl == NULL)
        return g->nomem = 1;
    *list = nl;
    if ((nl[*n] = strdup(text ? text : "?")) == NULL)
        return g->nomem = 1;
    (*n)++;
    return 0;
}

static int add_id(gather *g, int64_t **ids, int n, int64_t id)
{
    int64_t *ni = realloc(*ids, (size_t)(n + 1) * sizeof *ni);
    if (ni == NULL)
        return g->nomem = 1;
    ni[n] = id;
    *ids = ni;
    return 0;
}

static int on_experiment(void *ud, const mpb_experiment_row *e)
{
    gather *g = ud;
    g->time_limit = e->time_limit;
    if ((g->experiment = strdup(e->name ? e->name : "?")) == NULL)
        return g->nomem = 1;
    return 0;
}

static int on_config(void *ud, const mpb_planner_config_row *c)
{
    gather *g = ud;
    if (add_id(g, &g->config_ids, g->num_configs, c->id))
        return 1;
    return add_name(g, &g->configs, &g->num_configs, c->name);
}

static int on_scene(void *ud, const mpb_scene_row *s)
{
    gather *g = ud;
    if (add_id(g, &g->scene_ids, g->num_scenes, s->id))
        return 1;
    return add_name(g, &g->scenes, &g->num_scenes, s->name);
}

static int config_index(const gather *g, int64_t id)
{
    for (int c = 0; c < g->num_configs; c++)
        if (g->config_ids[c] == id)
            return c;
    return -1;
}

static int on_query(void *ud, const mpb_query_row *q)
{
    (void)q;
    ((gather *)ud)->sc->num_queries++;
    return 0;
}

/* Pass 1, each run's final stage: counts, times, and the final stages. */
static int on_run(void *ud, const mpb_result_row *row)
{
    gather *g = ud;
    plot_scene *sc = g->sc;
    int c = config_index(g, row->planner_config_id);
    if (c < 0)
        return 0;
    sc->finished[c]++;
    sc->succeeded[c] += row->success != 0;
    if (isfinite(row->time_total) && push(&sc->time[c], row->time_total))
        return g->nomem = 1;
    if (row->stage == NULL)
        return 0;
    for (int i = 0; i < NUM_KNOWN; i++)
        if (strcmp(known_stages[i], row->stage) == 0)
            return 0;
    for (int i = 0; i < g->num_finals; i++)
        if (strcmp(g->finals[i], row->stage) == 0)
            return 0;
    return add_name(g, &g->finals, &g->num_finals, row->stage);
}

/* Pass 2, once per stage: the path metrics of successful runs. */
static int on_stage_metrics(void *ud, const mpb_result_row *row)
{
    gather *g = ud;
    int c = config_index(g, row->planner_config_id);
    if (c < 0 || !row->success || row->num_named == 0)
        return 0;
    for (int m = 0; m < plot_num_metrics(); m++)
        if (isfinite(row->metrics[m]) &&
            push(plot_metric_series(g->sc, m, g->stage, c), row->metrics[m]))
            return g->nomem = 1;
    return 0;
}

static void scene_free(plot_scene *sc)
{
    if (sc == NULL)
        return;
    for (int c = 0; sc->time && c < sc->num_configs; c++)
        free(sc->time[c].v);
    for (size_t i = 0; sc->metric &&
         i < (size_t)plot_num_metrics() * (size_t)sc->num_stages * (size_t)sc->num_configs;
         i++)
        free(sc->metric[i].v);
    for (int k = 0; sc->stages && k < sc->num_stages; k++)
        free(sc->stages[k]);
    free(sc->stages);
    free(sc->finished);
    free(sc->succeeded);
    free(sc->time);
    free(sc->metric);
}

/* Drop the stages no successful run has metrics for. */
static void drop_empty_stages(plot_scene *sc)
{
    int nc = sc->num_configs, kept = 0;
    for (int k = 0; k < sc->num_stages; k++) {
        int values = 0;
        for (int m = 0; m < plot_num_metrics(); m++)
            for (int c = 0; c < nc; c++)
                values += plot_metric_series(sc, m, k, c)->n;
        if (values == 0) {
            free(sc->stages[k]);
            continue;
        }
        /* Move stage k to kept; the layout is [metric][stage][config], so
         * kept <= k never overwrites what is still to be read. */
        sc->stages[kept] = sc->stages[k];
        for (int m = 0; m < plot_num_metrics(); m++)
            for (int c = 0; c < nc; c++) {
                plot_series *from = plot_metric_series(sc, m, k, c);
                plot_series *to = &sc->metric[((size_t)m * (size_t)sc->num_stages
                                               + (size_t)kept) * (size_t)nc
                                              + (size_t)c];
                plot_series t = *from;
                *from = (plot_series){0};
                *to = t;
            }
        kept++;
    }
    /* Re-pack from a stride of num_stages to one of kept stages. */
    for (int m = 0; m < plot_num_metrics(); m++)
        for (int k = 0; k < kept; k++)
            for (int c = 0; c < nc; c++) {
                size_t from = ((size_t)m * (size_t)sc->num_stages + (size_t)k)
                              * (size_t)nc + (size_t)c;
                size_t to = ((size_t)m * (size_t)kept + (size_t)k)
                            * (size_t)nc + (size_t)c;
                plot_series t = sc->metric[from];
                sc->metric[from] = (plot_series){0};
                sc->metric[to] = t;
            }
    sc->num_stages = kept;
}

/* Read one scene; MPB_OK, or an error already printed. */
static int read_scene(mpb_store *s, gather *g, int i, plot_scene *sc)
{
    const char *names[MPB_NUM_METRICS];
    for (int m = 0; m < plot_num_metrics(); m++)
        names[m] = plot_metric(m)->name;
    size_t nc = (size_t)g->num_configs;
    int rc;

    *sc = (plot_scene){.experiment = g->experiment, .scene = g->scenes[i],
                       .file = g->files[i],
                       .time_limit = g->time_limit,
                       .num_configs = g->num_configs, .configs = g->configs};
    g->sc = sc;
    sc->finished = calloc(nc + 1, sizeof *sc->finished);
    sc->succeeded = calloc(nc + 1, sizeof *sc->succeeded);
    sc->time = calloc(nc + 1, sizeof *sc->time);
    if (!sc->finished || !sc->succeeded || !sc->time)
        goto nomem;
    rc = mpb_store_queries(s, g->scene_ids[i], on_query, g);
    if (rc == MPB_OK)
        rc = mpb_store_results(s, g->experiment_id, g->scene_ids[i], NULL,
                               NULL, 0, on_run, g);
    if (g->nomem)
        goto nomem;
    if (rc != MPB_OK)
        goto db;

    int candidates = NUM_KNOWN + g->num_finals;
    sc->stages = calloc((size_t)candidates, sizeof *sc->stages);
    sc->metric = calloc((size_t)plot_num_metrics() * (size_t)candidates * nc + 1,
                        sizeof *sc->metric);
    if (!sc->stages || !sc->metric)
        goto nomem;
    for (int k = 0; k < candidates; k++) {
        const char *name = k < NUM_KNOWN ? known_stages[k]
                                         : g->finals[k - NUM_KNOWN];
        if ((sc->stages[k] = strdup(name)) == NULL)
            goto nomem;
        sc->num_stages = k + 1;
    }
    for (int k = 0; k < candidates; k++) {
        g->stage = k;
        rc = mpb_store_results(s, g->experiment_id, g->scene_ids[i],
                               sc->stages[k], names, plot_num_metrics(),
                               on_stage_metrics, g);
        if (g->nomem)
            goto nomem;
        if (rc != MPB_OK)
            goto db;
    }
    drop_empty_stages(sc);
    return MPB_OK;
nomem:
    fprintf(stderr, "mpb " CMD ": out of memory\n");
    return MPB_ENOMEM;
db:
    fprintf(stderr, "mpb " CMD ": cannot read the results of scene '%s': "
            "%s\n", g->scenes[i], mpb_store_errmsg(s));
    return rc;
}

/*
 * Each scene's part of the file names, over all the experiment's scenes
 * (so that --scene does not change them): plot_file_part() of its name,
 * and for every scene whose part another scene has too, the part, '-' and
 * the scene's id. Parts with an id differ from each other (their last '-'
 * is followed by the id); one can still meet another scene's plain part,
 * which then takes its id in the next round. 0, or -1 out of memory.
 */
static int name_files(gather *g)
{
    char part[PLOT_PART_MAX + 32];
    int n = g->num_scenes, rc = -1, again = 1;
    int *with_id = calloc((size_t)n + 1, sizeof *with_id);
    int *clash = calloc((size_t)n + 1, sizeof *clash);

    if ((g->files = calloc((size_t)n + 1, sizeof *g->files)) == NULL ||
        with_id == NULL || clash == NULL)
        goto done;
    for (int i = 0; i < n; i++) {
        plot_file_part(part, sizeof part, g->scenes[i]);
        if ((g->files[i] = strdup(part)) == NULL)
            goto done;
    }
    while (again) {
        again = 0;
        for (int i = 0; i < n; i++) {
            clash[i] = 0;
            for (int j = 0; !with_id[i] && j < n && !clash[i]; j++)
                clash[i] = j != i && strcmp(g->files[i], g->files[j]) == 0;
        }
        for (int i = 0; i < n; i++) {
            if (!clash[i])
                continue;
            plot_file_part(part, sizeof part, g->scenes[i]);
            size_t len = strlen(part);
            snprintf(part + len, sizeof part - len, "-%lld",
                     (long long)g->scene_ids[i]);
            char *file = strdup(part);
            if (file == NULL)
                goto done;
            free(g->files[i]);
            g->files[i] = file;
            with_id[i] = again = 1;
        }
    }
    rc = 0;
done:
    free(with_id);
    free(clash);
    return rc;
}

typedef struct unfinished {
    const gather *g;
    plot_scene   *scenes;
} unfinished;

static int on_unfinished(void *ud, int64_t scene_id, int n)
{
    unfinished *u = ud;
    for (int i = 0; i < u->g->num_scenes; i++)
        if (u->g->scene_ids[i] == scene_id)
            u->scenes[i].unfinished = n;
    return 0;
}

static void gather_free(gather *g)
{
    for (int i = 0; i < g->num_configs; i++)
        free(g->configs[i]);
    for (int i = 0; i < g->num_scenes; i++) {
        free(g->scenes[i]);
        free(g->files ? g->files[i] : NULL);
    }
    for (int i = 0; i < g->num_finals; i++)
        free(g->finals[i]);
    free(g->configs);
    free(g->config_ids);
    free(g->scenes);
    free(g->files);
    free(g->scene_ids);
    free(g->finals);
    free(g->experiment);
}

/* ---- drawing ------------------------------------------------------------- */

typedef struct written {
    char **paths;
    int    n, nomem;
} written;

static void on_wrote(void *ud, const char *path)
{
    written *w = ud;
    char **np = realloc(w->paths, (size_t)(w->n + 1) * sizeof *np);
    if (np == NULL || (np[w->n] = strdup(path)) == NULL) {
        if (np)
            w->paths = np;
        w->nomem = 1;
        return;
    }
    w->paths = np;
    w->n++;
}

/* Run gnuplot over the plots of every scene in one format. */
static int draw(plot_scene *scenes, int num_scenes,
                const plot_budget *budget, const plot_profile *profile,
                const char *dir, const char *ext)
{
    written w = {0};
    plot_glyphs gl = {.all = strcmp(ext, "svg") == 0};
    int rc = MPB_EXIT_ERROR;
    /* gnuplot's own messages go to our stderr; a missing gnuplot is
     * told apart by status 127, without the shell's own "not found". */
    FILE *gp = popen("command -v gnuplot >/dev/null 2>&1 || exit 127; "
                     "exec gnuplot", "w");
    if (gp == NULL) {
        fprintf(stderr, "mpb " CMD ": cannot start gnuplot: %s\n",
                strerror(errno));
        return MPB_EXIT_ERROR;
    }
    for (int i = 0; i < num_scenes; i++)
        if (scenes[i].num_configs > 0)
            plot_gnuplot_scene(gp, &scenes[i], dir, ext, &gl, on_wrote, &w);
    if (budget != NULL)
        plot_gnuplot_budget(gp, budget, dir, ext, &gl, on_wrote, &w);
    if (profile != NULL)
        plot_gnuplot_profile(gp, profile, dir, ext, &gl, on_wrote, &w);
    int status = pclose(gp);
    if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) == 127) {
        fprintf(stderr, "mpb " CMD ": gnuplot not found on PATH (Debian: "
                "apt-get install gnuplot-nox, or sh tools/deps.sh)\n");
        goto done;
    }
    if (WEXITSTATUS(status) != 0) {
        fprintf(stderr, "mpb " CMD ": gnuplot failed (exit status %d) while "
                "writing %s images into %s\n", WEXITSTATUS(status), ext, dir);
        goto done;
    }
    if (w.nomem) {
        fprintf(stderr, "mpb " CMD ": out of memory\n");
        goto done;
    }
    rc = MPB_EXIT_OK;
    for (int i = 0; i < w.n; i++) {
        struct stat st;
        if (stat(w.paths[i], &st) != 0 || st.st_size == 0) {
            fprintf(stderr, "mpb " CMD ": gnuplot did not write %s\n",
                    w.paths[i]);
            rc = MPB_EXIT_ERROR;
        } else {
            printf("%s\n", w.paths[i]);
        }
    }
done:
    for (int i = 0; i < w.n; i++)
        free(w.paths[i]);
    free(w.paths);
    plot_glyphs_free(&gl);
    return rc;
}

/* ---- the command --------------------------------------------------------- */

typedef struct options {
    int64_t     experiment_id;   /* 0: the newest */
    const char *scene, *dir, *db;
    int         png, svg;
} options;

static int parse(int argc, char **argv, options *o)
{
    static const struct option longopts[] = {
        {"experiment", required_argument, NULL, 'e'},
        {"scene", required_argument, NULL, 's'},
        {"output", required_argument, NULL, 'o'},
        {"format", required_argument, NULL, 'f'},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    int c;
    *o = (options){.dir = ".", .png = 1};
    optind = 1;
    opterr = 0;
    while ((c = getopt_long(argc, argv, ":e:s:o:f:h", longopts, NULL)) != -1) {
        switch (c) {
        case 'e':
            if (tool_parse_id(optarg, &o->experiment_id) != 0) {
                fprintf(stderr, "mpb " CMD ": --experiment wants an id (a "
                        "whole number > 0), not '%s'\n", optarg);
                return MPB_EXIT_USAGE;
            }
            break;
        case 's': o->scene = optarg; break;
        case 'o': o->dir = optarg; break;
        case 'f':
            o->png = strcmp(optarg, "png") == 0 || strcmp(optarg, "both") == 0;
            o->svg = strcmp(optarg, "svg") == 0 || strcmp(optarg, "both") == 0;
            if (!o->png && !o->svg) {
                fprintf(stderr, "mpb " CMD ": --format is png, svg or both, "
                        "not '%s'\n", optarg);
                return MPB_EXIT_USAGE;
            }
            break;
        case 'h': usage(stdout); return -1;
        default:    /* ':' a missing value, '?' an unknown option */
            return tool_option_error(CMD, c, argv);
        }
    }
    if (optind != argc - 1) {
        fprintf(stderr, "mpb " CMD ": expected one database (try 'mpb "
                CMD " --help')\n");
        return MPB_EXIT_USAGE;
    }
    o->db = argv[optind];
    return MPB_EXIT_OK;
}

static int make_dir(const char *dir)
{
    struct stat st;
    if (mkdir(dir, 0777) == 0 || (errno == EEXIST && stat(dir, &st) == 0 &&
                                  S_ISDIR(st.st_mode)))
        return 0;
    fprintf(stderr, "mpb " CMD ": cannot create directory %s: %s\n", dir,
            strerror(errno == EEXIST ? ENOTDIR : errno));
    return -1;
}

int cmd_plot(int argc, char **argv)
{
    options o;
    gather g = {0};
    plot_scene *scenes = NULL;
    plot_budget *budget = NULL;
    plot_profile *profile = NULL;
    int rc = parse(argc, argv, &o), exit_code = MPB_EXIT_ERROR, wanted = -1;
    long finished = 0;

    if (rc != MPB_EXIT_OK)
        return rc < 0 ? MPB_EXIT_OK : rc;
    mpb_store *s = tool_open_readonly(CMD, o.db);
    if (s == NULL)
        return MPB_EXIT_ERROR;
    g.experiment_id = o.experiment_id;
    if (g.experiment_id == 0 &&
        (rc = mpb_store_experiment_latest(s, &g.experiment_id)) != MPB_OK) {
        fprintf(stderr, "mpb " CMD ": %s holds no experiment%s\n", o.db,
                rc == MPB_ENOTFOUND ? "" : ": cannot read it");
        goto out;
    }
    rc = mpb_store_experiment_get(s, g.experiment_id, on_experiment, &g);
    if (rc == MPB_OK)
        rc = mpb_store_planner_configs(s, g.experiment_id, on_config, &g);
    if (rc == MPB_OK)
        rc = mpb_store_scenes(s, g.experiment_id, on_scene, &g);
    if (rc == MPB_OK && !g.nomem && name_files(&g) != 0)
        g.nomem = 1;
    if (g.nomem || rc != MPB_OK) {
        fprintf(stderr, "mpb " CMD ": %s: %s\n", o.db,
                rc == MPB_ENOTFOUND ? "no such experiment" :
                g.nomem ? "out of memory" : mpb_store_errmsg(s));
        goto out;
    }
    for (int i = 0; o.scene && i < g.num_scenes; i++)
        if (strcmp(g.scenes[i], o.scene) == 0)
            wanted = i;
    if (o.scene && wanted < 0) {
        fprintf(stderr, "mpb " CMD ": experiment '%s' in %s has no scene '%s' "
                "(its scenes:", g.experiment, o.db, o.scene);
        for (int i = 0; i < g.num_scenes; i++)
            fprintf(stderr, " %s", g.scenes[i]);
        fprintf(stderr, ")\n");
        goto out;
    }
    if ((scenes = calloc((size_t)g.num_scenes + 1, sizeof *scenes)) == NULL)
        goto out;
    for (int i = 0; i < g.num_scenes; i++) {
        if (wanted >= 0 && i != wanted)
            continue;
        if (read_scene(s, &g, i, &scenes[i]) != MPB_OK)
            goto out;
        for (int c = 0; c < scenes[i].num_configs; c++)
            finished += scenes[i].finished[c];
    }
    unfinished u = {&g, scenes};
    if ((rc = mpb_store_unfinished_by_scene(s, g.experiment_id, on_unfinished,
                                            &u)) != MPB_OK) {
        fprintf(stderr, "mpb " CMD ": %s: cannot count the runs not finished "
                "yet: %s\n", o.db, mpb_store_errmsg(s));
        goto out;
    }
    if (finished == 0) {
        fprintf(stderr, "mpb " CMD ": experiment '%s' (id %lld) in %s has no "
                "finished runs to plot%s%s\n", g.experiment,
                (long long)g.experiment_id, o.db, o.scene ? " in scene " : "",
                o.scene ? o.scene : "");
        goto out;
    }
    if (make_dir(o.dir) != 0)
        goto out;
    /* A gnuplot that dies early must not take us with it. */
    signal(SIGPIPE, SIG_IGN);
    /* Success against the time budget, per problem set: the whole
     * experiment's, unless one scene was asked for. */
    if (o.scene == NULL) {
        if ((rc = plot_budget_read(s, g.experiment_id, 0, &budget)) != MPB_OK) {
            fprintf(stderr, "mpb " CMD ": %s: %s\n", o.db, rc == MPB_ENOMEM ?
                    "out of memory" : mpb_store_errmsg(s));
            goto out;
        }
        if ((rc = plot_profile_read(s, g.experiment_id, &profile)) != MPB_OK) {
            fprintf(stderr, "mpb " CMD ": %s: %s\n", o.db, rc == MPB_ENOMEM ?
                    "out of memory" : mpb_store_errmsg(s));
            goto out;
        }
        written csv = {0};
        if (plot_budget_csv(budget, o.dir, on_wrote, &csv) != MPB_OK) {
            fprintf(stderr, "mpb " CMD ": cannot write %s/budget.csv: %s\n",
                    o.dir, strerror(errno));
            goto out;
        }
        if (plot_profile_csv(profile, o.dir, on_wrote, &csv) != MPB_OK) {
            fprintf(stderr, "mpb " CMD ": cannot write %s/profile.csv: %s\n",
                    o.dir, strerror(errno));
            goto out;
        }
        for (int i = 0; i < csv.n; i++) {
            printf("%s\n", csv.paths[i]);
            free(csv.paths[i]);
        }
        free(csv.paths);
    }
    exit_code = MPB_EXIT_OK;
    if (o.png && draw(scenes, g.num_scenes, budget, profile, o.dir, "png") !=
            MPB_EXIT_OK)
        exit_code = MPB_EXIT_ERROR;
    if (exit_code == MPB_EXIT_OK && o.svg &&
        draw(scenes, g.num_scenes, budget, profile, o.dir, "svg") != MPB_EXIT_OK)
        exit_code = MPB_EXIT_ERROR;
out:
    plot_budget_free(budget);
    plot_profile_free(profile);
    for (int i = 0; scenes && i < g.num_scenes; i++)
        scene_free(&scenes[i]);
    free(scenes);
    gather_free(&g);
    mpb_store_close(s);
    return exit_code;
}
