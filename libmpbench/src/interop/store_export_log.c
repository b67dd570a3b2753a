/*
 * store_export_log.c - an experiment's finished runs as OMPL benchmark
 * logs, one per query, in the format OMPL's Benchmark class writes and
 * ompl_benchmark_statistics.py reads (mpb_store_export_ompl_logs();
 * the run properties are store_pa_props.c's).
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/grow.h"
#include "interop/store_pa.h"

/* A file name part: [A-Za-z0-9._-] kept, anything else '_'. */
static void file_word(char *s)
{
    for (; *s; s++) {
        char ch = *s;
        int ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                 (ch >= '0' && ch <= '9') || ch == '.' || ch == '-';
        if (!ok)
            *s = '_';
    }
}

/* A value of a log's run line: integers for all but REAL, 17 digits for
 * REAL (exact), nothing for NULL. */
static void log_value(FILE *out, const prop *p, double v)
{
    if (isnan(v))
        return;
    if (strcmp(p->type, "REAL") != 0 && v == floor(v) && fabs(v) < 9e15)
        fprintf(out, "%lld", (long long)v);
    else
        fprintf(out, "%.17g", v);
}

/* A line of the log without its line breaks (a name, a setting). */
static void log_line(FILE *out, const char *text)
{
    for (; *text; text++)
        fputc(*text == '\n' || *text == '\r' ? ' ' : *text, out);
    fputc('\n', out);
}

typedef struct config_count {
    int64_t id;
    long    runs;
} config_count;

/*
 * The setup block, "<<<|" to "|>>>". Readers end it at the first line that
 * starts with "|>>>" (OMPL's script) or is one (mpb import), and the setup
 * may hold such a line: an imported log keeps its own setup block in its
 * text. Such a line is written with a space before it.
 */
static void write_setup(FILE *out, const char *text)
{
    fputs("<<<|\n", out);
    for (const char *line = text; *line != '\0';) {
        const char *end = strchr(line, '\n');
        size_t n = end ? (size_t)(end - line) : strlen(line);
        if (strncmp(line, "|>>>", 4) == 0)
            fputc(' ', out);
        fwrite(line, 1, n, out);
        fputc('\n', out);
        line += end ? n + 1 : n;
    }
    fputs("|>>>\n", out);
}

/* 1 for the experiment properties mpbench writes itself. */
static int is_reserved_param(const char *name)
{
    char *c = mpb__pa_param_column(name);
    int r = c && (mpb__pa_same_column(c, "query") ||
                  mpb__pa_same_column(c, "mpbench_experiment"));
    free(c);
    return r;
}

typedef struct config_counts {
    config_count *v;
    int           n, cap;
} config_counts;

static int add_count(void *ud, int64_t config_id, long runs)
{
    config_counts *c = ud;
    if (mpb__grow((void **)&c->v, &c->cap, c->n + 1, sizeof *c->v))
        return MPB_ENOMEM;
    c->v[c->n].id = config_id;
    c->v[c->n++].runs = runs;
    return MPB_OK;
}

/* One log: one query of experiment e. */
static int write_log(mpb_store *s, FILE *out, const exp_info *e,
                     const pa_query *q, const prop_list *props,
                     const prop_list *progress)
{
    config_count *cfg = NULL;
    int num_cfg = 0, rc = MPB_OK;
    pa_walker *w = NULL;
    char *prog_text = NULL;
    size_t prog_len = 0;
    FILE *prog = NULL;

    config_counts cc = {0};
    rc = mpb__store_each_config_count(s, e->id, q->query_id, add_count, &cc);
    cfg = cc.v;
    num_cfg = cc.n;
    if (rc == MPB_ENOMEM)
        mpb__store_fail(s, rc, "out of memory");
    if (rc)
        goto done;

    /* The experiment: OMPL's header, our version as "NAME version X"; an
     * imported log's as it had it ("OMPL version " without a number). */
    const char *version = mpb__pa_version_of(e);
    const char *space = strchr(version, ' ');
    if (space)
        fprintf(out, "%.*s version %s\n", (int)(space - version), version,
                space + 1);
    else if (e->started)
        fprintf(out, "%s version \n", version);
    else
        fprintf(out, "mpbench version %s\n", version);
    fprintf(out, "Experiment %s\n", q->problem);
    /* mpbench's two, unless the log had them (an exported log imported
     * again): its own values then; then the log's others, in its order. */
    const char *query = mpb__pa_exp_param(e, "query");
    const char *mpbexp = mpb__pa_exp_param(e, "mpbench_experiment");
    int others = 0;
    for (int i = 0; i < e->num_params; i++)
        others += !is_reserved_param(e->params[i].name);
    fprintf(out, "%d experiment properties\n", MPB__PA_NUM_EXP_PARAMS + others);
    fprintf(out, "query VARCHAR(512) = ");
    log_line(out, query ? query : q->query);
    if (mpbexp)
        fprintf(out, "mpbench_experiment INTEGER = %s\n", mpbexp);
    else
        fprintf(out, "mpbench_experiment INTEGER = %lld\n", (long long)e->id);
    for (int i = 0; i < e->num_params; i++)
        if (!is_reserved_param(e->params[i].name)) {
            fprintf(out, "%s %s = ", e->params[i].name, e->params[i].type);
            log_line(out, e->params[i].value);
        }
    fprintf(out, "Running on ");
    char host[256];
    snprintf(host, sizeof host, "%s", e->host[0] ? e->host : "UNKNOWN");
    mpb__pa_one_word(host);
    log_line(out, host);
    char date[32];
    mpb__pa_format_date(e->created, date, sizeof date);
    fprintf(out, "Starting at ");
    log_line(out, e->started ? e->started : date);
    write_setup(out, q->setup);
    if (e->cpuinfo)
        write_setup(out, e->cpuinfo);
    fprintf(out, "%s is the random seed\n", e->seed ? e->seed : "0");
    fprintf(out, "%.17g seconds per run\n", isnan(e->time_limit) ? 0.0
                                                                 : e->time_limit);
    fprintf(out, "%.17g MB per run\n", isnan(e->memory_limit) ? 0.0
                                                              : e->memory_limit);
    fprintf(out, "%d runs per planner\n", e->runs_per_query);
    fprintf(out, "%.17g seconds spent to collect the data\n",
            isnan(e->total_time) ? q->total_time : e->total_time);
    fprintf(out, "1 enum type\nstatus");
    for (int i = 0; i < MPB__PA_NUM_STATUS; i++)
        fprintf(out, "|%s", mpb__pa_status_enum[i]);
    fprintf(out, "\n%d planners\n", num_cfg);

    if ((rc = mpb__pa_walker_open(&w, s, e->id, q->query_id, props,
                                  progress)))
        goto done;
    run_view rv = {0};
    for (int c = 0; c < num_cfg; c++) {
        /* The planner: its name and settings. */
        char *name, *planner, *algorithm, *params, *settings = NULL;
        if ((rc = mpb__store_config_read(s, cfg[c].id, &name, &planner,
                                         &algorithm, &params)))
            goto done;
        log_line(out, name);
        settings = mpb__pa_config_settings(planner, algorithm, params);
        free(name);
        free(planner);
        free(algorithm);
        free(params);
        if (settings == NULL) {
            rc = mpb__store_fail(s, MPB_ENOMEM, "out of memory");
            goto done;
        }
        int lines = 0;
        for (const char *p = settings; *p; p++)
            lines += *p == ';';
        fprintf(out, "%d common properties\n", lines);
        for (char *p = settings; *p; p++)
            if (*p != ';')
                fputc(*p, out);     /* "name = value\n" lines */
        free(settings);

        fprintf(out, "%d properties for each run\n", props->n);
        for (int k = 0; k < props->n; k++)
            fprintf(out, "%s %s\n", props->v[k].name, props->v[k].type);
        fprintf(out, "%ld runs\n", cfg[c].runs);
        free(prog_text);
        prog_text = NULL;
        if ((prog = open_memstream(&prog_text, &prog_len)) == NULL) {
            rc = mpb__store_fail(s, MPB_ENOMEM, "out of memory");
            goto done;
        }
        long any_samples = 0;
        for (long i = 0; i < cfg[c].runs; i++) {
            int got = mpb__pa_walker_next(w, &rv);
            if (got < 0) {
                rc = got;
                goto done;
            }
            if (got == 0 || rv.config_id != cfg[c].id) {
                rc = mpb__store_fail(s, MPB_EDB, "runs changed while "
                                     "being read");
                goto done;
            }
            for (int k = 0; k < props->n; k++) {
                if (rv.is_int[k])
                    fprintf(out, "%lld", (long long)rv.ints[k]);
                else
                    log_value(out, &props->v[k], rv.values[k]);
                fputs("; ", out);
            }
            fputc('\n', out);
            for (int j = 0; j < rv.num_samples; j++) {
                const double *smp = rv.samples + (size_t)j * (size_t)progress->n;
                for (int k = 0; k < progress->n; k++) {
                    log_value(prog, &progress->v[k], smp[k]);
                    fputc(',', prog);
                }
                fputc(';', prog);
                any_samples++;
            }
            fputc('\n', prog);
        }
        fclose(prog);
        prog = NULL;
        if (progress->n > 1 || any_samples > 0) {
            fprintf(out, "%d progress properties for each run\n", progress->n);
            for (int k = 0; k < progress->n; k++)
                fprintf(out, "%s %s\n", progress->v[k].name,
                        progress->v[k].type);
            fprintf(out, "%ld runs\n", cfg[c].runs);
            fwrite(prog_text, 1, prog_len, out);
        }
        fprintf(out, ".\n");
    }
done:
    if (prog)
        fclose(prog);
    free(prog_text);
    mpb__pa_walker_close(w);
    free(cfg);
    return rc;
}

/* A log's file name, without its directory and ".log". */
typedef struct log_name {
    int64_t query_id;
    char   *base;
    int     clash;
} log_name;

typedef struct log_names {
    log_name *v;
    int       n, cap;
} log_names;

static void log_names_free(log_names *l)
{
    for (int i = 0; i < l->n; i++)
        free(l->v[i].base);
    free(l->v);
    *l = (log_names){0};
}

static int cmp_base(const void *a, const void *b)
{
    const log_name *x = *(const log_name *const *)a,
                   *y = *(const log_name *const *)b;
    return strcasecmp(x->base, y->base);
}

/*
 * The file names of the logs of experiments exps, in the order they are
 * written: EXPERIMENT.ID.SCENE.QUERY of file_word()'s characters (the
 * scene is the problem name's part after the experiment's). Names that
 * would be one file, compared ignoring case as some file systems do, all
 * get "+QUERYID": file_word() makes no '+' and query ids are unique, so
 * then every name differs.
 */
static int plan_names(mpb_store *s, const int64_t *exps, int num_exps,
                      log_names *out)
{
    int rc = MPB_OK;
    for (int i = 0; i < num_exps && rc == MPB_OK; i++) {
        exp_info e = {0};
        pa_query_list queries = {0};
        if ((rc = mpb__store_exp_info_read(s, exps[i], &e)) == MPB_OK &&
            (rc = mpb__pa_read_queries(s, &e, &queries)) == MPB_OK) {
            for (int k = 0; k < queries.n && rc == MPB_OK; k++) {
                const pa_query *q = &queries.v[k];
                const char *scene = q->problem + strlen(e.name);
                scene += *scene == '/';
                size_t n = strlen(e.name) + strlen(scene) + strlen(q->query) +
                           64;
                char *base = malloc(n);
                if (base == NULL ||
                    mpb__grow((void **)&out->v, &out->cap, out->n + 1,
                              sizeof *out->v)) {
                    free(base);
                    rc = mpb__store_fail(s, MPB_ENOMEM, "out of memory");
                    break;
                }
                snprintf(base, n, "%s.%lld.%s.%s", e.name, (long long)e.id,
                         scene, q->query);
                file_word(base);
                out->v[out->n++] = (log_name){.query_id = q->query_id,
                                              .base = base};
            }
        }
        mpb__pa_queries_free(&queries);
        mpb__store_exp_info_free(&e);
    }
    if (rc != MPB_OK || out->n == 0)
        return rc;

    log_name **order = malloc(sizeof *order * (size_t)out->n);
    if (order == NULL)
        return mpb__store_fail(s, MPB_ENOMEM, "out of memory");
    for (int i = 0; i < out->n; i++)
        order[i] = &out->v[i];
    qsort(order, (size_t)out->n, sizeof *order, cmp_base);
    for (int i = 1; i < out->n; i++)
        if (strcasecmp(order[i - 1]->base, order[i]->base) == 0)
            order[i - 1]->clash = order[i]->clash = 1;
    free(order);
    for (int i = 0; i < out->n; i++) {
        log_name *l = &out->v[i];
        if (!l->clash)
            continue;
        size_t n = strlen(l->base) + 32;
        char *base = malloc(n);
        if (base == NULL)
            return mpb__store_fail(s, MPB_ENOMEM, "out of memory");
        snprintf(base, n, "%s+%lld", l->base, (long long)l->query_id);
        free(l->base);
        l->base = base;
    }
    return MPB_OK;
}

/* DIR/BASE.log; caller frees; NULL when out of memory. */
static char *log_path(const char *dir, const char *base)
{
    size_t n = strlen(dir) + strlen(base) + 8;
    char *path = malloc(n);
    if (path)
        snprintf(path, n, "%s/%s.log", dir, base);
    return path;
}

int mpb_store_export_ompl_logs(mpb_store *s, const char *dir,
                               const int64_t *ids, int num_ids, int flags,
                               mpb_export_counts *counts)
{
    int64_t *exps = NULL;
    int num_exps = 0, rc, next = 0;
    mpb_export_counts c = {0};
    log_names names = {0};

    if (counts)
        *counts = c;
    if (dir == NULL || num_ids < 0 || (num_ids > 0 && ids == NULL))
        return mpb__store_fail(s, MPB_EINVAL, "bad arguments");
    struct stat sb;
    if (stat(dir, &sb) != 0 && errno == ENOENT && mkdir(dir, 0777) != 0)
        return mpb__store_fail(s, MPB_EIO, "cannot create %s: %s",
                               dir, strerror(errno));
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode))
        return mpb__store_fail(s, MPB_EIO, "%s is not a directory",
                               dir);
    if ((rc = mpb__store_experiment_ids(s, ids, num_ids, &exps, &num_exps)) ||
        (rc = plan_names(s, exps, num_exps, &names)))
        goto done;
    /* Without MPB_EXPORT_REPLACE, a log there already stops the export
     * before it writes any. */
    for (int i = 0; i < names.n && !(flags & MPB_EXPORT_REPLACE); i++) {
        char *path = log_path(dir, names.v[i].base);
        if (path == NULL) {
            rc = mpb__store_fail(s, MPB_ENOMEM, "out of memory");
            goto done;
        }
        if (lstat(path, &sb) == 0)
            rc = mpb__store_fail(s, MPB_EEXISTS, "%s: exists", path);
        free(path);
        if (rc)
            goto done;
    }
    for (int i = 0; i < num_exps && rc == MPB_OK; i++) {
        exp_info e = {0};
        prop_list props = {0}, progress = {0};
        pa_query_list queries = {0};
        if ((rc = mpb__store_exp_info_read(s, exps[i], &e)) ||
            (rc = mpb__pa_experiment_props(s, exps[i], &props, &progress)) ||
            (rc = mpb__pa_read_queries(s, &e, &queries)))
            goto next;
        for (int k = 0; k < queries.n && rc == MPB_OK; k++) {
            const pa_query *q = &queries.v[k];
            /* Its name: the next planned, unless runs were finished
             * since (a query with its first). */
            if (next == names.n || names.v[next].query_id != q->query_id) {
                rc = mpb__store_fail(s, MPB_EDB, "runs changed while "
                                     "being read");
                break;
            }
            char *path = log_path(dir, names.v[next++].base);
            if (path == NULL) {
                rc = mpb__store_fail(s, MPB_ENOMEM, "out of memory");
                break;
            }
            FILE *out = fopen(path, (flags & MPB_EXPORT_REPLACE) ? "w" : "wx");
            if (out == NULL) {
                rc = mpb__store_fail(s, errno == EEXIST ? MPB_EEXISTS : MPB_EIO,
                                     "%s: %s", path,
                                     errno == EEXIST ? "exists"
                                                     : strerror(errno));
                free(path);
                break;
            }
            rc = write_log(s, out, &e, q, &props, &progress);
            if (fclose(out) != 0 && rc == MPB_OK)
                rc = mpb__store_fail(s, MPB_EIO, "cannot write %s",
                                     path);
            if (rc != MPB_OK)
                unlink(path);
            else {
                c.experiments++;
                c.runs += q->runs;
            }
            free(path);
        }
    next:
        mpb__store_exp_info_free(&e);
        mpb__pa_props_free(&props);
        mpb__pa_props_free(&progress);
        mpb__pa_queries_free(&queries);
    }
done:
    log_names_free(&names);
    free(exps);
    if (counts)
        *counts = c;
    return rc;
}
