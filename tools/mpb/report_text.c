/*
 * report_text.c - `mpb report`'s text format: the preamble, then one
 * table per scene (--by scene) or per problem set and one over all
 * problems (--by set, --by all), the columns aligned, each column's
 * approach above its name.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "report.h"

/* s right-aligned in width columns. */
static void print_right(FILE *out, const char *s, int width)
{
    for (int pad = width - tool_text_cols(s, NULL); pad > 0; pad--)
        fputc(' ', out);
    fputs(s, out);
}

/* A table: kind "Scene" with index a scene's, "Problem set" a set's,
 * index -1 for all problems. */
static int print_table(const report *r, const char *kind, int index,
                       FILE *out)
{
    int nc = r->num_configs;
    size_t ncols = (size_t)(nc > 0 ? nc : 1);
    column *cols = calloc(ncols, sizeof *cols);
    char (*text)[CELL_TEXT] = calloc((size_t)report_num_rows * ncols,
                                     sizeof *text);
    int *width = calloc(ncols, sizeof *width);
    int *visible = calloc((size_t)report_num_rows, sizeof *visible);
    int rc = MPB_OK;

    if (cols == NULL || text == NULL || width == NULL || visible == NULL) {
        rc = MPB_ENOMEM;
        goto done;
    }
    int scene = strcmp(kind, "Scene") == 0, unfinished;
    long finished = scene ? report_scene_columns(r, index, cols)
                          : report_set_columns(r, index, cols, &unfinished);
    if (scene)
        unfinished = r->scenes[index].unfinished;
    report_cells(r, cols, text, visible);

    int label_width = (int)strlen("Metric");
    for (int i = 0; i < report_num_rows; i++) {
        int len = (int)strlen(report_rows[i].label);
        if (len > label_width)
            label_width = len;
    }
    int approaches = report_any_approach(r);
    for (int c = 0; c < nc; c++) {
        width[c] = tool_text_cols(r->configs[c].name, NULL);
        if (width[c] < 8)
            width[c] = 8;
        if (approaches &&
            (int)strlen(report_approach_label(&r->configs[c])) > width[c])
            width[c] = (int)strlen(report_approach_label(&r->configs[c]));
        for (int i = 0; i < report_num_rows; i++)
            if (tool_text_cols(text[i * nc + c], NULL) > width[c])
                width[c] = tool_text_cols(text[i * nc + c], NULL);
    }

    if (scene) {
        fprintf(out, "Scene %s", r->scenes[index].name);
    } else {
        int n = report_set_scenes(r, index);
        if (index < 0)
            fputs("All problems", out);
        else
            fprintf(out, "%s %s", kind, r->sets[index]);
        fprintf(out, " (%d scene%s)", n, n == 1 ? "" : "s");
    }
    fprintf(out, " - experiment %s (%lld), %ld run%s\n", r->experiment_name,
            (long long)r->experiment_id, finished, finished == 1 ? "" : "s");
    int rule = label_width;
    /* Each column's approach above its name, the columns grouped by it. */
    if (approaches) {
        fprintf(out, "%-*s", label_width, "Approach");
        for (int c = 0; c < nc; c++) {
            fputs("  ", out);
            print_right(out, report_approach_label(&r->configs[c]), width[c]);
        }
        fputc('\n', out);
    }
    fprintf(out, "%-*s", label_width, "Metric");
    for (int c = 0; c < nc; c++) {
        fputs("  ", out);
        print_right(out, r->configs[c].name, width[c]);
        rule += 2 + width[c];
    }
    fputc('\n', out);
    for (int i = 0; i < rule; i++)
        fputc('-', out);
    fputc('\n', out);
    for (int i = 0; i < report_num_rows; i++) {
        if (!visible[i])
            continue;
        fprintf(out, "%-*s", label_width, report_rows[i].label);
        for (int c = 0; c < nc; c++) {
            fputs("  ", out);
            print_right(out, text[i * nc + c], width[c]);
        }
        fputc('\n', out);
    }
    for (int c = 0; c < nc; c++)
        if (cols[c].stage_invalid > 0)
            fprintf(out, "%s: %ld successful run%s whose stage '%s' failed "
                    "verification, its path metrics not counted above\n",
                    r->configs[c].name, cols[c].stage_invalid,
                    cols[c].stage_invalid == 1 ? "" : "s",
                    r->stage ? r->stage : "?");
    if (report_any_single(text, visible, nc))
        fputs(SIGMA_SINGLE_NOTE "\n", out);
    if (unfinished > 0)
        fprintf(out, "%d more run%s not finished yet, not counted above\n",
                unfinished, unfinished == 1 ? "" : "s");
done:
    free(cols);
    free(text);
    free(width);
    free(visible);
    return rc;
}

int report_write_text(const report *r, FILE *out)
{
    int rc;
    if (r->num_configs == 0 || r->num_scenes == 0) {
        fprintf(out, "Experiment %s (%lld) has no %s.\n", r->experiment_name,
                (long long)r->experiment_id,
                r->num_configs == 0 ? "planner configurations" : "scenes");
        return MPB_OK;
    }
    fprintf(out, "Means over successful runs; sigma: standard deviation per "
            "query, averaged\nover the scene's queries. Path metrics of "
            "%s%s%s.\n", r->stage ? "stage '" : "each run's final stage",
            r->stage ? r->stage : "", r->stage ? "'" : "");
    if (r->stage != NULL && r->staged == 0)
        fprintf(out, "No successful run has metrics for a stage '%s'.\n",
                r->stage);
    if (r->certified + r->sampled > 0)
        fprintf(out, "Collision checks: %ld stage%s certified, %ld sampled "
                "(docs/verification.md).\n", r->certified,
                r->certified == 1 ? "" : "s", r->sampled);
    if (r->by == BY_SCENE) {
        for (int i = 0; i < r->num_scenes; i++) {
            fputc('\n', out);
            if ((rc = print_table(r, "Scene", i, out)) != MPB_OK)
                return rc;
        }
        return MPB_OK;
    }
    fputs("Problem sets: s_r's 95% CI is Wilson's; tau_t's median and p95 "
          "are over\nsuccessful runs, the median's 95% CI from order "
          "statistics ('-' with fewer\nthan 6 successful runs).\n", out);
    for (int i = r->by == BY_SET ? 0 : r->num_sets; i <= r->num_sets; i++) {
        if (i == r->num_sets && r->by == BY_SET && r->num_sets < 2)
            break;      /* all problems are the one set */
        fputc('\n', out);
        if ((rc = print_table(r, "Problem set", i < r->num_sets ? i : -1,
                              out)) != MPB_OK)
            return rc;
    }
    return MPB_OK;
}
