/*
 * report_html.c - `mpb report --format html`: an experiment as one
 * self-contained HTML page. At the top the table over all problems, the
 * success-against-budget curves (drawn here as SVG) and the comparison
 * matrix of `mpb compare`; then a table per problem set (--by set); then
 * per scene, folded away when there are sets: the paper's tables (the
 * numbers of the text report), the plots of `mpb plot` inlined as SVG,
 * and the runs that are no success, each linked to its `mpb view` page
 * (views/run-ID.html beside the report); last what they say (--findings'
 * text).
 * Written to a file (-o), the report writes those pages too, with the
 * view code; written to stdout, it says how to make them.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "plot.h"
#include "report.h"
#include "view.h"

/* Failed runs listed per scene; the rest are counted. */
#define MAX_FAILED_LISTED 200

static const char STYLE[] =
    "body{font:14px/1.45 system-ui,sans-serif;color:#1d2433;margin:0;"
    "background:#eef1f5}main{max-width:1100px;margin:0 auto;padding:16px 24px;"
    "background:#fff}h1{font-size:22px}h2{font-size:18px;margin-top:32px;"
    "border-bottom:2px solid #1d2433}h3{font-size:15px}table{border-collapse:"
    "collapse;margin:8px 0;display:block;max-width:100%;overflow-x:auto}"
    /* A table wider than the page (nine configurations) scrolls on its
     * own, its cells unwrapped, instead of spilling past the page. */
    "th,td{padding:3px 10px;white-space:nowrap;border-bottom:1px solid "
    "#d5dae3;text-align:right}th:first-child,td:first-child{text-align:left}"
    "td.l,th.l{text-align:left}pre{background:#f4f6f9;padding:10px;white-space:pre-wrap;"
    "overflow:auto}.note{color:#5b6579}.budget{display:flex;flex-wrap:wrap;"
    "gap:8px}.budget figure{margin:0;flex:1 1 45%;min-width:320px}"
    ".budget svg{width:100%;height:auto}.budget figcaption{text-align:center;font-weight:600}td.win{background:#d9f2e3}td.lose{"
    "background:#f9dede}details>summary{cursor:pointer;font-weight:600;"
    "margin:10px 0}.plots{display:grid;grid-template-columns:"
    "1fr 1fr;gap:8px}.plots svg{max-width:100%;height:auto;"
    "display:block;margin:8px 0}\n";

#define H(text) view_html_text(out, (text) ? (text) : "")

/* ---- the tables ---------------------------------------------------------- */

/* The table of scene si, or (scene 0) of problem set si (-1: all). */
static int write_table(const report *r, int scene, int si, FILE *out)
{
    int nc = r->num_configs;
    column *cols = calloc((size_t)nc + 1, sizeof *cols);
    char (*text)[CELL_TEXT] = calloc((size_t)report_num_rows * (size_t)nc + 1,
                                     sizeof *text);
    int *visible = calloc((size_t)report_num_rows + 1, sizeof *visible);
    if (!cols || !text || !visible) {
        free(cols);
        free(text);
        free(visible);
        return MPB_ENOMEM;
    }
    int unfinished;
    long finished = scene ? report_scene_columns(r, si, cols)
                          : report_set_columns(r, si, cols, &unfinished);
    if (scene)
        unfinished = r->scenes[si].unfinished;
    report_cells(r, cols, text, visible);
    fprintf(out, "<p>%ld finished run%s", finished, finished == 1 ? "" : "s");
    if (!scene)
        fprintf(out, " on %d scene%s", report_set_scenes(r, si),
                report_set_scenes(r, si) == 1 ? "" : "s");
    if (unfinished > 0)
        fprintf(out, "; <b>%d more not finished yet, not counted here</b>",
                unfinished);
    fputs(".</p>\n<table><tr><th>Metric</th>", out);
    for (int c = 0; c < nc; c++) {
        fputs("<th>", out);
        H(r->configs[c].name);
        fputs("</th>", out);
    }
    fputs("</tr>\n", out);
    for (int i = 0; i < report_num_rows; i++) {
        if (!visible[i])
            continue;
        fputs("<tr><td>", out);
        H(report_rows[i].label);
        fputs("</td>", out);
        for (int c = 0; c < nc; c++) {
            fputs("<td>", out);
            H(text[(size_t)i * nc + c]);
            fputs("</td>", out);
        }
        fputs("</tr>\n", out);
    }
    fputs("</table>\n", out);
    free(cols);
    free(text);
    free(visible);
    return MPB_OK;
}

/* ---- the findings: the text --findings writes ------------------------------ */

static int write_findings(const report *r, FILE *out)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&buf, &len);
    if (!mem)
        return MPB_ENOMEM;
    int rc = report_write_findings(r, mem);
    fclose(mem);
    if (rc == MPB_OK) {
        fputs("<h2>What the tables say</h2>\n<pre>", out);
        H(buf);
        fputs("</pre>\n", out);
    }
    free(buf);
    return rc;
}

/* ---- the plots: `mpb plot --format svg` into a temporary folder ----------- */

typedef struct plots {
    char   dir[256];
    char **paths;       /* as mpb plot printed them, scene by scene */
    int    n;
    char   why[256];    /* why there are none, if so */
} plots;

static void plots_make(const report *r, plots *p)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(p->dir, sizeof p->dir, "%s/mpb-report-XXXXXX",
             tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(p->dir)) {
        snprintf(p->why, sizeof p->why, "no temporary folder: %s",
                 strerror(errno));
        p->dir[0] = '\0';
        return;
    }
    int fds[2];
    if (pipe(fds) != 0) {
        snprintf(p->why, sizeof p->why, "%s", strerror(errno));
        return;
    }
    char id[32];
    snprintf(id, sizeof id, "%lld", (long long)r->experiment_id);
    pid_t pid = fork();
    if (pid == 0) {
        dup2(fds[1], 1);
        close(fds[0]);
        close(fds[1]);
        /* Its messages stay on stderr: a missing gnuplot is said there. */
        execl("/proc/self/exe", "mpb", "plot", "--experiment", id,
              "--format", "svg", "-o", p->dir, r->db_path, (char *)NULL);
        _exit(127);
    }
    close(fds[1]);
    FILE *in = pid > 0 ? fdopen(fds[0], "r") : NULL;
    char line[4096];
    while (in && fgets(line, sizeof line, in)) {
        line[strcspn(line, "\n")] = '\0';
        char **grown = realloc(p->paths, (size_t)(p->n + 1) * sizeof *grown);
        if (!grown || !(grown[p->n] = strdup(line))) {
            free(grown);
            break;
        }
        p->paths = grown;
        p->n++;
    }
    if (in)
        fclose(in);
    else
        close(fds[0]);
    int status = 0;
    if (pid > 0)
        waitpid(pid, &status, 0);
    if (pid < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        snprintf(p->why, sizeof p->why, "mpb plot did not draw them (its "
                 "message is above; it needs gnuplot)");
}

static void plots_free(plots *p)
{
    for (int i = 0; i < p->n; i++) {
        remove(p->paths[i]);
        free(p->paths[i]);
    }
    free(p->paths);
    if (p->dir[0])
        rmdir(p->dir);
}

/* The SVG file inline: from its <svg element on. */
static void inline_svg(FILE *out, const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return;
    char buf[65536];
    size_t n;
    int started = 0;
    while ((n = fread(buf, 1, sizeof buf - 1, f)) > 0) {
        buf[n] = '\0';
        const char *at = buf;
        if (!started) {
            const char *svg = strstr(buf, "<svg");
            if (!svg)
                continue;
            at = svg;
            started = 1;
        }
        fwrite(at, 1, n - (size_t)(at - buf), out);
    }
    fclose(f);
}

/* The plots of scene si: the files named plot-PART-... */
static void write_plots(const report *r, int si, const plots *p, FILE *out)
{
    char part[PLOT_PART_MAX + 8], prefix[PLOT_PART_MAX + 16];
    plot_file_part(part, sizeof part, r->scenes[si].name);
    snprintf(prefix, sizeof prefix, "/plot-%s-", part);
    int any = 0;
    for (int i = 0; i < p->n; i++) {
        if (!strstr(p->paths[i], prefix))
            continue;
        if (!any)
            fputs("<h3>Plots</h3>\n<div class=\"plots\">\n", out);
        any = 1;
        inline_svg(out, p->paths[i]);
        fputc('\n', out);
    }
    if (any)
        fputs("</div>\n", out);
}

/* ---- the runs that are no success ---------------------------------------- */

typedef struct failed {
    const report *r;
    mpb_store    *store;
    int           listed, more;
    FILE         *out;
    char        **query_names;  /* by index into r->queries */
    int64_t      *ids;          /* the scene's runs listed */
    int           linked;       /* the run at hand has a view */
    const char   *no_view;      /* if not, why not, or NULL */
    int           told;         /* how to make the views, said */
    int           views_made;   /* r->views_dir exists */
} failed;

static const char *query_name(const failed *f, int64_t id)
{
    for (int i = 0; i < f->r->num_queries; i++)
        if (f->r->queries[i].id == id)
            return f->query_names[i] ? f->query_names[i] : "";
    return "";
}

static int on_query_name(void *ud, const mpb_query_row *q)
{
    failed *f = ud;
    for (int i = 0; i < f->r->num_queries; i++)
        if (f->r->queries[i].id == q->id && !f->query_names[i])
            f->query_names[i] = strdup(q->name);
    return 0;
}

static int on_failed_run(void *ud, const mpb_run_detail *d)
{
    failed *f = ud;
    FILE *out = f->out;
    if (f->linked)
        fprintf(out, "<tr><td><a href=\"views/run-%lld.html\">%lld</a></td>"
                "<td class=\"l\">", (long long)d->run_id,
                (long long)d->run_id);
    else
        fprintf(out, "<tr><td>%lld</td><td class=\"l\">",
                (long long)d->run_id);
    H(d->planner_config);
    fputs("</td><td class=\"l\">", out);
    H(query_name(f, d->query_id));
    fprintf(out, "</td><td>%d</td><td class=\"l\">", d->repetition);
    H(*d->verdict && strcmp(d->verdict, "valid") != 0 ? d->verdict : d->status);
    fputs("</td><td class=\"l\">", out);
    H(d->message);
    if (f->no_view) {
        fputs(" <span class=\"note\">(no view: ", out);
        H(f->no_view);
        fputs(")</span>", out);
    }
    fputs("</td></tr>\n", out);
    return 0;
}

/* Collect the ids of the scene's runs that are no success. */
static int on_result(void *ud, const mpb_result_row *row)
{
    failed *f = ud;
    if (row->success)
        return 0;
    if (f->listed == MAX_FAILED_LISTED) {
        f->more++;
        return 0;
    }
    f->ids[f->listed++] = row->run_id;
    return 0;
}

/* With r->views_dir: the view of run id into it, and whether there is one
 * to link (a run without stages has none: why says so). MPB_OK, or
 * REPORT_SAID after one line on stderr. */
static int write_view(failed *f, int64_t id, char *why, size_t whylen)
{
    const report *r = f->r;
    f->linked = 1;
    f->no_view = NULL;
    if (!r->views_dir)
        return MPB_OK;
    if (!f->views_made) {
        if (mkdir(r->views_dir, 0777) != 0 && errno != EEXIST) {
            fprintf(stderr, "mpb report: cannot make %s: %s\n", r->views_dir,
                    strerror(errno));
            return REPORT_SAID;
        }
        f->views_made = 1;
    }
    view_run v = {0};
    int got = view_load(f->store, r->db_path, id, &v, why, whylen);
    int rc = got < 0 ? REPORT_SAID : MPB_OK;
    if (got == 0) {
        size_t len = strlen(r->views_dir) + 48;
        char *path = malloc(len);
        if (!path)
            rc = MPB_ENOMEM;
        else {
            snprintf(path, len, "%s/run-%lld.html", r->views_dir,
                     (long long)id);
            if (view_write_file(&v, r->three_js, path) != 0)
                rc = REPORT_SAID;
        }
        free(path);
    } else if (got == 1) {
        /* "run N has no stages to draw (...)": the table names the run. */
        const char *has = strstr(why, " has ");
        f->linked = 0;
        f->no_view = has ? has + 5 : why;
    }
    view_free(&v);
    return rc;
}

static int write_failed(failed *f, int si)
{
    const report *r = f->r;
    f->listed = f->more = 0;
    int rc = mpb_store_results(f->store, r->experiment_id, r->scenes[si].id,
                               NULL, NULL, 0, on_result, f);
    if (rc != MPB_OK || f->listed == 0)
        return rc;
    FILE *out = f->out;
    fputs("<h3>Runs that are no success</h3>\n<table><tr><th>run</th>"
          "<th class=\"l\">planner</th><th class=\"l\">query</th>"
          "<th>rep.</th><th class=\"l\">outcome</th><th class=\"l\">"
          "message</th></tr>\n", out);
    char why[512];
    for (int i = 0; i < f->listed && rc == MPB_OK; i++) {
        why[0] = '\0';
        rc = write_view(f, f->ids[i], why, sizeof why);
        if (rc == MPB_OK)
            rc = mpb_store_run_get(f->store, f->ids[i], on_failed_run, f);
    }
    fputs("</table>\n", out);
    if (f->more)
        fprintf(out, "<p class=\"note\">... and %d more.</p>\n", f->more);
    if (r->views_dir) {
        fputs("<p class=\"note\">A run's number opens its view "
              "(views/run-ID.html beside this page): the run in 3-D, where "
              "it failed and why.</p>\n", out);
    } else if (!f->told) {
        /* Written to stdout: the views are not there yet. */
        fputs("<p class=\"note\" id=\"make-views\">The run links open "
              "views/run-ID.html beside this page, which was written "
              "without them. Write the page to a file and they are written "
              "too: <code>mpb report --format html -o report.html ", out);
        H(r->db_path);
        fprintf(out, "</code>; or, beside this page, <code>mpb view --failed "
                "--experiment %lld -o views ", (long long)r->experiment_id);
        H(r->db_path);
        fputs("</code>.</p>\n", out);
        f->told = 1;
    }
    return rc;
}

/* ---- the top: all problems, the budget curves, the comparison matrix ------ */

/* The time ratios row/column of every pair on all problems, marked where
 * the Holm-adjusted signed-rank test says so at 5 % (mpb compare). */
static int write_matrix(const report *r_, FILE *out)
{
    report *r = (report *)r_;   /* pairs_all() sorts samples in place */
    int nc = r->num_configs;
    pairs_pair *pairs = NULL;
    if (nc < 2 || r->pairs.cells == NULL)
        return MPB_OK;
    int rc = pairs_all(&r->pairs, -1, &pairs);
    if (rc != MPB_OK)
        return rc;
    fputs("<h2>Comparison matrix</h2>\n<p class=\"note\">Median over the "
          "problems either solved of the per-problem time ratio row/column "
          "(a run that is no success counts at the time limit); * and the "
          "colour where the Wilcoxon signed-rank test, Holm-adjusted over "
          "every pair, says so at 5 %. <code>mpb compare</code> gives the "
          "intervals and path lengths.</p>\n<table class=\"matrix\"><tr><th>"
          "</th>", out);
    for (int b = 0; b < nc; b++) {
        fputs("<th>", out);
        H(r->configs[b].name);
        fputs("</th>", out);
    }
    fputs("</tr>\n", out);
    for (int a = 0; a < nc; a++) {
        fputs("<tr><td>", out);
        H(r->configs[a].name);
        fputs("</td>", out);
        for (int b = 0; b < nc; b++) {
            if (a == b) {
                fputs("<td>-</td>", out);
                continue;
            }
            const pairs_pair *q = &pairs[pairs_index(nc, a, b)];
            if (q->time.n == 0) {
                fputs("<td>n/a</td>", out);
                continue;
            }
            double ratio = a < b ? q->time.median : 1.0 / q->time.median;
            int v = pairs_verdict(&q->time) * (a < b ? 1 : -1);
            fprintf(out, "<td%s title=\"%d problems, adjusted p = %.2g\">"
                    "%.3g%s</td>", v < 0 ? " class=\"win\"" : v > 0 ?
                    " class=\"lose\"" : "", q->time.n, q->time.p_holm, ratio,
                    v ? "*" : "");
        }
        fputs("</tr>\n", out);
    }
    fputs("</table>\n", out);
    free(pairs);
    return MPB_OK;
}

/* The success-against-budget curves: over all problems, then per set. */
static int write_budget(const report *r, mpb_store *s, FILE *out)
{
    plot_budget *b = NULL;
    int rc = plot_budget_read(s, r->experiment_id, 0, &b);
    if (rc != MPB_OK)
        return rc;
    fputs("<h2>Success against the time budget</h2>\n<p class=\"note\">Per "
          "configuration, the fraction of its runs verified successful "
          "within t seconds (solid) and claimed by the planner within t "
          "(dotted), from the stored times.</p>\n<div class=\"budget\">\n",
          out);
    int n = plot_budget_num_sets(b);
    for (int k = 0; k <= n; k++) {  /* all problems first */
        int i = k == 0 ? n : k - 1;
        if (plot_budget_drawn(b, i))
            plot_budget_svg(out, b, i);
    }
    fputs("</div>\n", out);
    plot_budget_free(b);
    return MPB_OK;
}

static int write_overview(const report *r, mpb_store *s, FILE *out)
{
    int rc;
    fputs("<h2>All problems</h2>\n", out);
    if ((rc = write_table(r, 0, -1, out)) != MPB_OK ||
        (rc = write_budget(r, s, out)) != MPB_OK)
        return rc;
    return write_matrix(r, out);
}

/* ---- the page -------------------------------------------------------------- */

int report_write_html(const report *r, FILE *out)
{
    int rc = MPB_OK;
    char date[64] = "";
    time_t created = (time_t)r->created;
    struct tm tm;
    if (gmtime_r(&created, &tm))
        strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", &tm);
    fputs("<!DOCTYPE html>\n<!-- Written by mpb report --format html "
          "(mpbench). -->\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
          "<title>", out);
    H(r->experiment_name);
    fprintf(out, " (%lld): mpbench report</title>\n<style>%s</style></head>"
            "<body><main>\n<h1>Experiment ", (long long)r->experiment_id,
            STYLE);
    H(r->experiment_name);
    fprintf(out, " (%lld)</h1>\n<p class=\"note\">", (long long)r->experiment_id);
    fprintf(out, "%d run%s per query, time limit %g s; started %s on ",
            r->runs_per_query, r->runs_per_query == 1 ? "" : "s",
            r->time_limit, date);
    H(r->host);
    fputs(", mpbench ", out);
    H(r->version);
    fputs(". Means over successful runs; sigma: the standard deviation per "
          "query, averaged over the scene's queries; path metrics of ", out);
    if (r->stage) {
        fputs("stage '", out);
        H(r->stage);
        fputs("'", out);
    } else {
        fputs("each run's final stage", out);
    }
    fputs(" (docs/reports.md).</p>\n", out);

    plots p = {0};
    plots_make(r, &p);
    failed f = {.r = r, .out = out};
    f.ids = calloc(MAX_FAILED_LISTED, sizeof *f.ids);
    f.query_names = calloc((size_t)r->num_queries + 1, sizeof *f.query_names);
    if (!f.ids || !f.query_names) {
        rc = MPB_ENOMEM;
        goto done;
    }
    if (mpb_store_open(r->db_path, 1, &f.store) != MPB_OK) {
        rc = MPB_EIO;
        goto done;
    }
    for (int si = 0; si < r->num_scenes && rc == MPB_OK; si++)
        rc = mpb_store_queries(f.store, r->scenes[si].id, on_query_name, &f);
    if (rc == MPB_OK)
        rc = write_overview(r, f.store, out);
    for (int set = 0; r->by == BY_SET && set < r->num_sets && rc == MPB_OK;
         set++) {
        fputs("<h2>Problem set ", out);
        H(r->sets[set]);
        fputs("</h2>\n", out);
        rc = write_table(r, 0, set, out);
    }
    /* The scenes' detail: folded away under the sets. */
    for (int si = 0; si < r->num_scenes && rc == MPB_OK; si++) {
        fprintf(out, "<details%s><summary>scene ",
                r->by == BY_SCENE ? " open" : "");
        H(r->scenes[si].name);
        fputs("</summary>\n<h2>Scene ", out);
        H(r->scenes[si].name);
        fputs("</h2>\n", out);
        if ((rc = write_table(r, 1, si, out)) == MPB_OK)
            write_plots(r, si, &p, out);
        if (rc == MPB_OK)
            rc = write_failed(&f, si);
        fputs("</details>\n", out);
    }
    if (rc == MPB_OK && p.why[0]) {
        fputs("<p class=\"note\">No plots: ", out);
        H(p.why);
        fputs(".</p>\n", out);
    }
    if (rc == MPB_OK)
        rc = write_findings(r, out);
    if (rc == MPB_OK)
        fputs("</main></body></html>\n", out);
done:
    mpb_store_close(f.store);
    if (f.query_names)
        for (int i = 0; i < r->num_queries; i++)
            free(f.query_names[i]);
    free(f.query_names);
    free(f.ids);
    plots_free(&p);
    return rc;
}
