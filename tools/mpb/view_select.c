/*
 * view_select.c - `mpb view` without a run id: the finished runs of an
 * experiment that --scene, --query, --planner and --failed name, and, for
 * more than one, a page each with an index.html that lists them.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/grow.h"
#include "view.h"

#define CMD "view"

static int on_experiment_name(void *ud, const mpb_experiment_row *e)
{
    ((view_run *)ud)->experiment = view_strdup(e->name);
    return 0;
}

static void add_name(selection *sel, int64_t id, const char *name)
{
    if (sel->num_names == sel->cap_names) {
        /* Two arrays of one capacity, each grown from the same one. */
        int need = sel->num_names + 1, cap[2] = {sel->cap_names, sel->cap_names};
        if (mpb__grow((void **)&sel->ids, &cap[0], need, sizeof *sel->ids) !=
                MPB_OK ||
            mpb__grow((void **)&sel->names, &cap[1], need,
                      sizeof *sel->names) != MPB_OK) {
            fprintf(stderr, "mpb " CMD ": out of memory\n");
            exit(MPB_EXIT_ERROR);
        }
        sel->cap_names = cap[0];
    }
    sel->ids[sel->num_names] = id;
    sel->names[sel->num_names++] = view_strdup(name);
}

/* Ids of the three kinds are kept apart by sign and offset: configurations
 * as they are, scenes negated, queries past 2^52. */
#define SCENE_KEY(id) (-(id))
#define QUERY_KEY(id) ((id) + ((int64_t)1 << 52))

static const char *name_of(const selection *sel, int64_t key)
{
    for (int i = 0; i < sel->num_names; i++)
        if (sel->ids[i] == key)
            return sel->names[i];
    return "";
}

static int on_config_name(void *ud, const mpb_planner_config_row *row)
{
    add_name(ud, row->id, row->name);
    return 0;
}

static int on_query_name(void *ud, const mpb_query_row *row)
{
    add_name(ud, QUERY_KEY(row->id), row->name);
    return 0;
}

static int on_scene_name(void *ud, const mpb_scene_row *row)
{
    selection *sel = ud;
    add_name(sel, SCENE_KEY(row->id), row->name);
    return mpb_store_queries(sel->store, row->id, on_query_name, sel);
}

static int on_result(void *ud, const mpb_result_row *row)
{
    selection *sel = ud;
    if ((sel->failed && row->success) ||
        (sel->scene && strcmp(sel->scene,
                              name_of(sel, SCENE_KEY(row->scene_id))) != 0) ||
        (sel->query && strcmp(sel->query,
                              name_of(sel, QUERY_KEY(row->query_id))) != 0) ||
        (sel->planner && strcmp(sel->planner,
                                name_of(sel, row->planner_config_id)) != 0))
        return 0;
    if (mpb__grow((void **)&sel->runs, &sel->cap_runs, sel->num_runs + 1,
                  sizeof *sel->runs) != MPB_OK) {
        fprintf(stderr, "mpb " CMD ": out of memory\n");
        exit(MPB_EXIT_ERROR);
    }
    sel->runs[sel->num_runs++] = row->run_id;
    return 0;
}

/* The finished runs of the experiment that the selection names, in run
 * order, into sel->runs. 0, or -1 after one line. */
int view_select_runs(mpb_store *s, const char *db, int64_t experiment,
                       selection *sel)
{
    sel->store = s;
    int rc = mpb_store_planner_configs(s, experiment, on_config_name, sel);
    if (rc == MPB_OK)
        rc = mpb_store_scenes(s, experiment, on_scene_name, sel);
    if (rc == MPB_OK)
        rc = mpb_store_results(s, experiment, 0, NULL, NULL, 0, on_result,
                               sel);
    if (rc != MPB_OK) {
        fprintf(stderr, "mpb " CMD ": %s: %s\n", db, mpb_store_errmsg(s));
        return -1;
    }
    return 0;
}

void view_selection_free(selection *sel)
{
    for (int i = 0; i < sel->num_names; i++)
        free(sel->names[i]);
    free(sel->names);
    free(sel->ids);
    free(sel->runs);
}

/* An index page (index.html) of one page per run, written into dir. */
int view_write_many(mpb_store *s, const char *db, int64_t experiment,
                      const selection *sel, const char *three,
                      const char *dir)
{
    char path[4200];
    int n = snprintf(path, sizeof path, "%s/index.html", dir);
    FILE *index = n > 0 && (size_t)n < sizeof path ? fopen(path, "w") : NULL;
    if (!index) {
        fprintf(stderr, "mpb " CMD ": cannot write %s: %s\n", path,
                strerror(errno));
        return -1;
    }
    view_run e = {0};   /* for the experiment's name */
    mpb_store_experiment_get(s, experiment, on_experiment_name, &e);
    fputs("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
          "<title>mpb view: ", index);
    view_html_text(index, e.experiment ? e.experiment : "");
    fprintf(index, " (experiment %lld)</title>\n"
            "<style>body{font:14px/1.4 system-ui,sans-serif;margin:20px;"
            "color:#1d2433}table{border-collapse:collapse}td,th{padding:"
            "3px 10px;border-bottom:1px solid #d5dae3;text-align:left}"
            "</style></head><body>\n<h1>", (long long)experiment);
    view_html_text(index, e.experiment ? e.experiment : "");
    fprintf(index, " (experiment %lld): %d run%s</h1>\n"
            "<p>%s, drawn by mpb view: each linked page is one run in 3-D."
            "</p>\n"
            "<table><tr><th>run</th><th>planner</th><th>scene / query"
            "</th><th>rep.</th><th>outcome</th><th>message</th>"
            "</tr>\n", (long long)experiment,
            sel->num_runs, sel->num_runs == 1 ? "" : "s",
            sel->failed ? "The runs that are no success" : "The runs chosen");
    free(e.experiment);
    int written = 0, rc = 0;
    for (int i = 0; i < sel->num_runs && rc == 0; i++) {
        view_run v = {0};
        char why[512] = "";
        int got = view_load(s, db, sel->runs[i], &v, why, sizeof why);
        if (got < 0) {
            rc = -1;
            break;
        }
        char page[64];
        snprintf(page, sizeof page, "run-%lld.html", (long long)sel->runs[i]);
        n = snprintf(path, sizeof path, "%s/%s", dir, page);
        if (got == 0 && (n < 0 || (size_t)n >= sizeof path ||
                         view_write_file(&v, three, path) != 0))
            rc = -1;
        written += got == 0;
        fputs("<tr><td>", index);
        if (got == 0)
            fprintf(index, "<a href=\"%s\">%lld</a>", page,
                    (long long)sel->runs[i]);
        else
            fprintf(index, "%lld", (long long)sel->runs[i]);
        fputs("</td><td>", index);
        view_html_text(index, v.run.planner_config ? v.run.planner_config : "");
        fputs("</td><td>", index);
        char place[512];
        view_html_text(index, view_place(v.scene, v.query, place,
                                         sizeof place));
        fprintf(index, "</td><td>%d</td><td>", v.run.repetition);
        view_html_text(index, v.run.success == 1 ? "success"
                         : v.run.verdict && *v.run.verdict ? v.run.verdict
                         : v.run.status ? v.run.status : "");
        fputs("</td><td>", index);
        view_html_text(index, got == 0 ? (v.run.message ? v.run.message : "") : why);
        fputs("</td></tr>\n", index);
        view_free(&v);
    }
    fputs("</table>\n</body></html>\n", index);
    if (fclose(index) != 0 && rc == 0) {
        fprintf(stderr, "mpb " CMD ": cannot write %s/index.html: %s\n", dir,
                strerror(errno));
        rc = -1;
    }
    if (rc == 0)
        printf("%d page%s, one per run with stages\n", written,
               written == 1 ? "" : "s");
    return rc;
}
