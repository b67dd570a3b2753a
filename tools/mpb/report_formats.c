/*
 * report_formats.c - `mpb report --format`: the numbers of the text tables
 * as Markdown, CSV, LaTeX and JSON. The layouts are documented in
 * docs/reports.md; the JSON and CSV ones are meant to stay stable.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "report.h"

/* A scene's columns and cell texts, as the tables show them. */
typedef struct scene_table {
    column *cols;
    char  (*text)[CELL_TEXT];
    int    *visible;
    long    finished;
} scene_table;

static void scene_table_free(scene_table *t)
{
    free(t->cols);
    free(t->text);
    free(t->visible);
}

static int scene_table_make(const report *r, int si, scene_table *t)
{
    size_t nc = (size_t)(r->num_configs > 0 ? r->num_configs : 1);
    t->cols = calloc(nc, sizeof *t->cols);
    t->text = calloc((size_t)report_num_rows * nc, sizeof *t->text);
    t->visible = calloc((size_t)report_num_rows, sizeof *t->visible);
    if (t->cols == NULL || t->text == NULL || t->visible == NULL) {
        scene_table_free(t);
        return MPB_ENOMEM;
    }
    t->finished = report_scene_columns(r, si, t->cols);
    report_cells(r, t->cols, t->text, t->visible);
    return MPB_OK;
}

static const char *plural(long n)
{
    return n == 1 ? "" : "s";
}

/* ---- Markdown ---------------------------------------------------------------- */

static int is_alnum(char ch)
{
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
           (ch >= '0' && ch <= '9');
}

/*
 * Text with Markdown's inline specials (and the table's |) escaped. An '_'
 * between two letters or digits cannot start or end emphasis (CommonMark),
 * so "tau_t" and "straight_line" stay as they are.
 */
static void md_text(const char *s, FILE *out)
{
    for (const char *p = s; *p; p++) {
        int escape = strchr("\\`*[]<>|", *p) != NULL ||
                     (*p == '_' && !(p > s && is_alnum(p[-1]) &&
                                     is_alnum(p[1])));
        if (escape)
            fputc('\\', out);
        fputc(*p, out);
    }
}

int report_write_markdown(const report *r, FILE *out)
{
    int nc = r->num_configs;
    fputs("# Experiment ", out);
    md_text(r->experiment_name, out);
    fprintf(out, " (%lld)\n\n", (long long)r->experiment_id);
    if (nc == 0 || r->num_scenes == 0) {
        fprintf(out, "No %s.\n",
                nc == 0 ? "planner configurations" : "scenes");
        return MPB_OK;
    }
    fputs("Means over successful runs; sigma: standard deviation per query, "
          "averaged over the scene's queries. Path metrics of ", out);
    if (r->stage) {
        fputs("stage '", out);
        md_text(r->stage, out);
        fputs("'.\n", out);
    } else {
        fputs("each run's final stage.\n", out);
    }
    if (r->stage != NULL && r->staged == 0)
        fputs("No successful run has metrics for this stage.\n", out);

    for (int si = 0; si < r->num_scenes; si++) {
        scene_table t = {0};
        if (scene_table_make(r, si, &t) != MPB_OK)
            return MPB_ENOMEM;
        fputs("\n## Scene ", out);
        md_text(r->scenes[si].name, out);
        fprintf(out, ": %ld run%s\n\n| Metric |", t.finished,
                plural(t.finished));
        for (int c = 0; c < nc; c++) {
            fputc(' ', out);
            md_text(r->configs[c].name, out);
            fputs(" |", out);
        }
        fputs("\n|:---|", out);
        for (int c = 0; c < nc; c++)
            fputs("---:|", out);
        fputc('\n', out);
        /* The columns come grouped by approach: each labelled. */
        if (report_any_approach(r)) {
            fputs("| approach |", out);
            for (int c = 0; c < nc; c++)
                fprintf(out, " %s |", report_approach_label(&r->configs[c]));
            fputc('\n', out);
        }
        for (int i = 0; i < report_num_rows; i++) {
            if (!t.visible[i])
                continue;
            fputs("| ", out);
            md_text(report_rows[i].label, out);
            fputs(" |", out);
            for (int c = 0; c < nc; c++) {
                fputc(' ', out);
                md_text(t.text[i * nc + c], out);
                fputs(" |", out);
            }
            fputc('\n', out);
        }
        if (report_any_single(t.text, t.visible, nc)) {
            fputc('\n', out);
            md_text(SIGMA_SINGLE_NOTE ".", out);
            fputc('\n', out);
        }
        if (r->scenes[si].unfinished > 0)
            fprintf(out, "\n%d more run%s not finished yet, not counted "
                    "above.\n", r->scenes[si].unfinished,
                    plural(r->scenes[si].unfinished));
        scene_table_free(&t);
    }
    return MPB_OK;
}

/* ---- CSV ------------------------------------------------------------------- */

/* A field, quoted (RFC 4180) if it holds a comma, a quote or a line break. */
static void csv_text(const char *s, FILE *out)
{
    if (strpbrk(s, ",\"\r\n") == NULL) {
        fputs(s, out);
        return;
    }
    fputc('"', out);
    for (; *s; s++) {
        if (*s == '"')
            fputc('"', out);
        fputc(*s, out);
    }
    fputc('"', out);
}

/* A number with 15 significant digits; nothing for NaN. */
static void csv_number(double v, FILE *out)
{
    if (!isnan(v))
        fprintf(out, "%.15g", v);
}

static void csv_row_start(const report *r, int si, int c, const char *metric,
                          const char *unit, FILE *out)
{
    fprintf(out, "%lld,", (long long)r->experiment_id);
    csv_text(r->experiment_name, out);
    fputc(',', out);
    csv_text(r->scenes[si].name, out);
    fputc(',', out);
    csv_text(r->configs[c].name, out);
    fprintf(out, ",%s,%s,", metric, unit);
}

int report_write_csv(const report *r, FILE *out)
{
    /* unfinished: the scene's runs not finished yet, on each of its rows,
     * so that a partial experiment cannot pass for a whole one. */
    /* sigma_single: of the queries sigma averages over, how many had one
     * successful run and count as 0 spread (the text tables' '*'). Last,
     * so that readers of the older columns by position still read them. */
    fputs("experiment_id,experiment,scene,planner,metric,unit,mean,sigma,n,"
          "unfinished,sigma_single\n", out);
    for (int si = 0; si < r->num_scenes; si++) {
        scene_table t = {0};
        if (scene_table_make(r, si, &t) != MPB_OK)
            return MPB_ENOMEM;
        for (int c = 0; c < r->num_configs; c++) {
            const column *col = &t.cols[c];
            for (int k = 0; k < M_COUNT; k++) {
                if (!report_metric_shown(k))
                    continue;
                csv_row_start(r, si, c, report_metrics[k].key,
                              report_metrics[k].unit, out);
                csv_number(mpb_grouped_mean(&col->m[k]), out);
                fputc(',', out);
                double sigma = report_sigma(&col->m[k]);
                csv_number(sigma, out);
                fprintf(out, ",%ld,%d,", col->m[k].n,
                        r->scenes[si].unfinished);
                if (!isnan(sigma))
                    fprintf(out, "%d", report_sigma_single(&col->m[k]));
                fputc('\n', out);
            }
            /* The success rate: a fraction of the n finished runs. */
            csv_row_start(r, si, c, "success_rate", "", out);
            csv_number(col->finished > 0 ? (double)col->succeeded /
                                               (double)col->finished
                                         : NAN, out);
            fprintf(out, ",,%ld,%d,\n", col->finished,
                    r->scenes[si].unfinished);
            /* The planner's own claim, beside it. */
            csv_row_start(r, si, c, "claimed_success_rate", "", out);
            csv_number(col->finished > 0 ? (double)col->claimed /
                                               (double)col->finished
                                         : NAN, out);
            fprintf(out, ",,%ld,%d,\n", col->finished,
                    r->scenes[si].unfinished);
            /* Claims in both directions: counts of runs by outcome. */
            for (int o = 0; o < MPB_OUTCOME_COUNT; o++) {
                char key[40];
                snprintf(key, sizeof key, "%s_runs",
                         mpb_outcome_name((mpb_outcome)o));
                csv_row_start(r, si, c, key, "", out);
                fprintf(out, "%ld,,%ld,%d,\n", col->outcomes[o],
                        col->finished, r->scenes[si].unfinished);
            }
        }
        scene_table_free(&t);
    }
    return MPB_OK;
}

/* ---- LaTeX ------------------------------------------------------------------ */

static void tex_text(const char *s, FILE *out)
{
    for (; *s; s++) {
        switch (*s) {
        case '\\': fputs("\\textbackslash{}", out); break;
        case '~':  fputs("\\textasciitilde{}", out); break;
        case '^':  fputs("\\textasciicircum{}", out); break;
        case '|':  fputs("\\textbar{}", out); break;
        case '<':  fputs("\\textless{}", out); break;
        case '>':  fputs("\\textgreater{}", out); break;
        case '&': case '%': case '$': case '#': case '_': case '{': case '}':
            fputc('\\', out);
            fputc(*s, out);
            break;
        default:
            fputc(*s, out);
        }
    }
}

/* A \label key: letters, digits and '-' only. */
static void tex_key(const char *s, FILE *out)
{
    for (; *s; s++)
        fputc(is_alnum(*s) ? *s : '-', out);
}

int report_write_latex(const report *r, FILE *out)
{
    int nc = r->num_configs;
    fprintf(out, "%% mpbench report: experiment %s (%lld)\n",
            r->experiment_name, (long long)r->experiment_id);
    if (nc == 0 || r->num_scenes == 0) {
        fprintf(out, "%% no %s\n",
                nc == 0 ? "planner configurations" : "scenes");
        return MPB_OK;
    }
    fputs("% Means over successful runs; sigma: standard deviation per "
          "query, averaged over\n% the scene's queries. Path metrics of ",
          out);
    if (r->stage)
        fprintf(out, "stage '%s'.\n", r->stage);
    else
        fputs("each run's final stage.\n", out);

    for (int si = 0; si < r->num_scenes; si++) {
        scene_table t = {0};
        if (scene_table_make(r, si, &t) != MPB_OK)
            return MPB_ENOMEM;
        fputs("\n\\begin{table}[htbp]\n  \\centering\n  \\caption{", out);
        tex_text(r->scenes[si].name, out);
        fputs(": experiment ", out);
        tex_text(r->experiment_name, out);
        fprintf(out, ", %ld run%s", t.finished, plural(t.finished));
        if (r->scenes[si].unfinished > 0)
            fprintf(out, " (%d more not finished yet, not counted)",
                    r->scenes[si].unfinished);
        fputs(". Means over successful runs; $\\sigma$: standard deviation "
              "per query, averaged over the scene's queries", out);
        if (r->stage) {
            fputs("; path metrics of stage ", out);
            tex_text(r->stage, out);
        }
        if (report_any_single(t.text, t.visible, nc)) {
            fputs("; ", out);
            tex_text(SIGMA_SINGLE_NOTE, out);
        }
        fputs(".}\n  \\label{tab:mpb-", out);
        tex_key(r->experiment_name, out);
        fputc('-', out);
        tex_key(r->scenes[si].name, out);
        fputs("}\n  \\begin{tabular}{l|", out);
        for (int c = 0; c < nc; c++)
            fputc('r', out);
        fputs("}\n    \\hline\n    Metric", out);
        for (int c = 0; c < nc; c++) {
            fputs(" & ", out);
            tex_text(r->configs[c].name, out);
        }
        fputs(" \\\\\n    \\hline\n", out);
        for (int i = 0; i < report_num_rows; i++) {
            if (!t.visible[i])
                continue;
            fprintf(out, "    %s", report_rows[i].latex);
            for (int c = 0; c < nc; c++) {
                const char *cell = t.text[i * nc + c];
                fprintf(out, " & %s", strcmp(cell, "-") == 0 ? "--" : cell);
            }
            fputs(" \\\\\n", out);
        }
        fputs("    \\hline\n  \\end{tabular}\n\\end{table}\n", out);
        scene_table_free(&t);
    }
    return MPB_OK;
}

/* ---- JSON ------------------------------------------------------------------- */

static void json_string(const char *s, FILE *out)
{
    fputc('"', out);
    for (; *s; s++) {
        unsigned char ch = (unsigned char)*s;
        switch (ch) {
        case '"':  fputs("\\\"", out); break;
        case '\\': fputs("\\\\", out); break;
        case '\n': fputs("\\n", out); break;
        case '\r': fputs("\\r", out); break;
        case '\t': fputs("\\t", out); break;
        default:
            if (ch < 0x20)
                fprintf(out, "\\u%04x", ch);
            else
                fputc(ch, out);
        }
    }
    fputc('"', out);
}

/* A number with 15 significant digits; null for NaN or infinity. */
static void json_number(double v, FILE *out)
{
    if (isnan(v) || isinf(v))
        fputs("null", out);
    else
        fprintf(out, "%.15g", v);
}

int report_write_json(const report *r, FILE *out)
{
    fputs("{\n  \"mpbench_report\": 1,\n  \"experiment\": {\n    \"id\": ",
          out);
    fprintf(out, "%lld,\n    \"name\": ", (long long)r->experiment_id);
    json_string(r->experiment_name, out);
    fputs(",\n    \"host\": ", out);
    json_string(r->host, out);
    fputs(",\n    \"version\": ", out);
    json_string(r->version, out);
    fprintf(out, ",\n    \"runs_per_query\": %d,\n    \"time_limit\": ",
            r->runs_per_query);
    json_number(r->time_limit, out);
    fputs(",\n    \"created\": ", out);
    json_number(r->created, out);
    fputs(",\n    \"finished\": ", out);
    json_number(r->finished, out);
    fputs("\n  },\n  \"stage\": ", out);
    if (r->stage)
        json_string(r->stage, out);
    else
        fputs("null", out);
    fputs(",\n  \"units\": {", out);
    for (int k = 0; k < M_COUNT; k++) {
        if (!report_metric_shown(k))
            continue;
        fprintf(out, "%s\n    \"%s\": ", k ? "," : "", report_metrics[k].key);
        json_string(report_metrics[k].unit, out);
    }
    fputs("\n  },\n  \"scenes\": [", out);
    for (int si = 0; si < r->num_scenes; si++) {
        scene_table t = {0};
        if (scene_table_make(r, si, &t) != MPB_OK)
            return MPB_ENOMEM;
        fprintf(out, "%s\n    {\n      \"id\": %lld,\n      \"name\": ",
                si ? "," : "", (long long)r->scenes[si].id);
        json_string(r->scenes[si].name, out);
        fprintf(out, ",\n      \"runs\": %ld,\n      \"unfinished\": %d,\n"
                "      \"planners\": [", t.finished, r->scenes[si].unfinished);
        for (int c = 0; c < r->num_configs; c++) {
            const config_ref *cf = &r->configs[c];
            const column *col = &t.cols[c];
            fprintf(out, "%s\n        {\n          \"id\": %lld,\n"
                    "          \"name\": ", c ? "," : "", (long long)cf->id);
            json_string(cf->name, out);
            fputs(",\n          \"planner\": ", out);
            json_string(cf->planner, out);
            fputs(",\n          \"algorithm\": ", out);
            json_string(cf->algorithm, out);
            fputs(",\n          \"params\": ", out);
            json_string(cf->params, out);
            fputs(",\n          \"approach\": ", out);
            if (cf->approach != NULL)
                json_string(cf->approach, out);
            else
                fputs("null", out);
            fprintf(out, ",\n          \"runs\": %ld,\n"
                    "          \"successes\": %ld,\n"
                    "          \"success_rate\": ", col->finished,
                    col->succeeded);
            json_number(col->finished > 0 ? (double)col->succeeded /
                                                (double)col->finished
                                          : NAN, out);
            fprintf(out, ",\n          \"claimed_successes\": %ld,\n"
                    "          \"claimed_success_rate\": ", col->claimed);
            json_number(col->finished > 0 ? (double)col->claimed /
                                                (double)col->finished
                                          : NAN, out);
            /* Claims in both directions (outcome.h). */
            fputs(",\n          \"outcomes\": {", out);
            for (int o = 0; o < MPB_OUTCOME_COUNT; o++)
                fprintf(out, "%s\"%s\": %ld", o ? ", " : "",
                        mpb_outcome_name((mpb_outcome)o), col->outcomes[o]);
            fputs("}", out);
            fputs(",\n          \"metrics\": {", out);
            for (int k = 0; k < M_COUNT; k++) {
                if (!report_metric_shown(k))
                    continue;
                fprintf(out, "%s\n            \"%s\": {\"mean\": ",
                        k ? "," : "", report_metrics[k].key);
                json_number(mpb_grouped_mean(&col->m[k]), out);
                double sigma = report_sigma(&col->m[k]);
                fputs(", \"sigma\": ", out);
                json_number(sigma, out);
                /* As the CSV's sigma_single: null where sigma is. */
                fputs(", \"sigma_single\": ", out);
                if (isnan(sigma))
                    fputs("null", out);
                else
                    fprintf(out, "%d", report_sigma_single(&col->m[k]));
                fprintf(out, ", \"n\": %ld}", col->m[k].n);
            }
            fputs("\n          }\n        }", out);
        }
        fputs(r->num_configs ? "\n      ]\n    }" : "]\n    }", out);
        scene_table_free(&t);
    }
    fputs(r->num_scenes ? "\n  ]\n}\n" : "]\n}\n", out);
    return MPB_OK;
}
