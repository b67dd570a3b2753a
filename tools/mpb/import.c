/*
 * import.c - `mpb import`: OMPL and MoveIt benchmark logs into an mpbench
 * database, so that `mpb report`, `mpb plot` and `mpb export` treat their
 * results as they treat mpbench's own.
 *
 * One log is one experiment, with one scene and one query (both named
 * after the log's experiment) and a planner configuration per planner
 * block ("ompl/RRTConnect"). Each run keeps OMPL's time as tau_t, its
 * `solved` as the claim, and as mpbench's success `solved` and not
 * approximate and (where the log says) a correct solution: nothing can be
 * verified again, since OMPL logs hold no paths. The path properties
 * become stages without waypoints: `raw` from "solution ...", `simplified`
 * from "simplified solution ..."; every other number is kept as the
 * planner's own value (an integer one exactly), progress samples as
 * progress, and the properties each planner block declares, with their
 * types, whether measured or not. docs/planner-arena.md.
 */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpb.h"

#define CMD "import"

static void usage(FILE *out)
{
    fprintf(out,
        "usage: mpb import -d DB LOG...\n"
        "       mpb import -p OUT.db [-a] LOG...\n"
        "\n"
        "Read benchmark logs written by OMPL's ompl::tools::Benchmark (or\n"
        "MoveIt's benchmark executor, in the same format) into the mpbench\n"
        "database DB (created if missing): each log becomes an experiment\n"
        "that mpb report, mpb plot and mpb export read like mpbench's own.\n"
        "Every log is read and checked before the database is opened: if\n"
        "one cannot be read or has an error, nothing is imported. Each log\n"
        "is then read again and imported in one transaction, so that one\n"
        "log at a time is held in memory.\n"
        "\n"
        "With -p, write the logs straight into a new Planner Arena database\n"
        "instead, as OMPL's ompl_benchmark_statistics.py does, without an\n"
        "mpbench database in between: each log is read once and written as\n"
        "it is read, and OUT.db appears only once every log is in it (if\n"
        "one cannot be read or has an error, it does not appear). With -a,\n"
        "add to OUT.db, an existing Planner Arena database (the script's -a),\n"
        "in one transaction: a planner configuration or enum it holds is\n"
        "not added again.\n"
        "\n"
        "Options:\n"
        "  -d, --db DB               the mpbench database to add to\n"
        "  -p, --planner-arena OUT   the Planner Arena database to write (it\n"
        "                            must not exist, unless -a)\n"
        "  -a, --append              with -p: add to OUT, which exists\n"
        "  -h, --help                print this help\n"
        "\n"
        "Exit status: 0 when every log was imported, 1 on an error, 2 on a\n"
        "bad command line.\n");
}

/* ---- one planner's runs --------------------------------------------------- */

/* Where a planner's properties are, looked up once per planner. */
typedef struct columns {
    int time, solved, approximate, correct, status, memory;
    int length, smoothness, clearance, segments;
    int s_time, s_length, s_smoothness, s_clearance, s_segments, s_correct;
} columns;

static columns find_columns(const mpb_ompl_planner *p)
{
    return (columns){
        .time = mpb_ompl_planner_property(p, "time"),
        .solved = mpb_ompl_planner_property(p, "solved"),
        .approximate = mpb_ompl_planner_property(p, "approximate solution"),
        .correct = mpb_ompl_planner_property(p, "correct solution"),
        .status = mpb_ompl_planner_property(p, "status"),
        .memory = mpb_ompl_planner_property(p, "memory"),
        .length = mpb_ompl_planner_property(p, "solution length"),
        .smoothness = mpb_ompl_planner_property(p, "solution smoothness"),
        .clearance = mpb_ompl_planner_property(p, "solution clearance"),
        .segments = mpb_ompl_planner_property(p, "solution segments"),
        .s_time = mpb_ompl_planner_property(p, "simplification time"),
        .s_length = mpb_ompl_planner_property(p, "simplified solution length"),
        .s_smoothness = mpb_ompl_planner_property(p, "simplified solution smoothness"),
        .s_clearance = mpb_ompl_planner_property(p, "simplified solution clearance"),
        .s_segments = mpb_ompl_planner_property(p, "simplified solution segments"),
        .s_correct = mpb_ompl_planner_property(p, "simplified correct solution"),
    };
}

/* Properties that become run fields or stage metrics, not planner values.
 * The claim, whether approximate and whether correct make mpbench's
 * success and its stages' validity, and are kept as planner values too:
 * mpb export gives back the log's own cells (empty ones too). */
static int is_mapped(const char *name)
{
    static const char *const mapped[] = {
        "time", "solution length", "solution smoothness", "solution clearance",
        "solution segments", "simplification time",
        "simplified solution length", "simplified solution smoothness",
        "simplified solution clearance", "simplified solution segments",
        "memory", NULL};
    for (int i = 0; mapped[i]; i++)
        if (strcmp(name, mapped[i]) == 0)
            return 1;
    return 0;
}

static double cell(const mpb_ompl_planner *p, long run, int col)
{
    return col < 0 ? NAN : p->values[(size_t)run * (size_t)p->num_properties + (size_t)col];
}

/* 1 for the types whose values a log writes as integers. */
static int integer_type(const char *type)
{
    return strcmp(type, "INTEGER") == 0 || strcmp(type, "BOOLEAN") == 0 ||
           strcmp(type, "ENUM") == 0;
}

static int by_cell(const void *key, const void *elem)
{
    size_t k = *(const size_t *)key, c = ((const mpb_ompl_exact *)elem)->cell;
    return k < c ? -1 : k > c;
}

/* The integer of a run's property col, which cell() gives as the nearest
 * double: as written when a double would round it (the parser's exact
 * list, in cell order), else that double. */
static int64_t integer_cell(const mpb_ompl_planner *p, long run, int col)
{
    size_t key = (size_t)run * (size_t)p->num_properties + (size_t)col;
    const mpb_ompl_exact *x = p->num_exact > 0
        ? bsearch(&key, p->exact, (size_t)p->num_exact, sizeof *p->exact, by_cell)
        : NULL;
    return x ? (int64_t)x->value : (int64_t)cell(p, run, col);
}

/* OMPL's status enum as mpbench's status names; the log's own number is
 * kept as the planner value "status". */
static const char *status_of(double v, int solved)
{
    const char *name = mpb_ompl_status_name(v);
    return name ? name : solved ? "solved" : "timeout";
}

/* Append a metric if the log has it. */
static void metric(mpb_named *m, int *n, const char *name, double v)
{
    if (!isnan(v))
        m[(*n)++] = (mpb_named){name, v};
}

typedef struct run_ids {
    int64_t  config;
    int64_t *ids;               /* by repetition */
    long     n;
} run_ids;

static int collect_id(void *ud, const mpb_run_row *row)
{
    run_ids *r = ud;
    if (row->planner_config_id == r->config && row->repetition >= 0 &&
        row->repetition < r->n)
        r->ids[row->repetition] = row->id;
    return 0;
}

/* A metric's stored name, from the list (mpbench/metrics.h). */
#define NAME(id) (mpb_metric_info_of(MPB_METRIC_##id)->name)

static int import_run(mpb_store *s, const mpb_ompl_planner *p, const columns *c,
                      long run, int64_t run_id, mpb_named *values,
                      mpb_exact_value *exact, mpb_progress_record *progress)
{
    char attempt[64];
    snprintf(attempt, sizeof attempt, "imported-%lld", (long long)run_id);
    int rc = mpb_store_run_sent(s, run_id, attempt, "imported");
    if (rc != MPB_OK)
        return rc;
    int solved = cell(p, run, c->solved) == 1.0;
    int approximate = cell(p, run, c->approximate) == 1.0;
    double correct = cell(p, run, c->correct);
    int success = solved && !approximate && (isnan(correct) || correct == 1.0);

    mpb_named raw[5], simplified[5];
    int nraw = 0, nsimp = 0;
    metric(raw, &nraw, NAME(PATH_LENGTH), cell(p, run, c->length));
    metric(raw, &nraw, NAME(SMOOTHNESS), cell(p, run, c->smoothness));
    metric(raw, &nraw, NAME(CLEARANCE), cell(p, run, c->clearance));
    metric(raw, &nraw, NAME(WAYPOINTS), cell(p, run, c->segments) + 1.0);
    metric(simplified, &nsimp, NAME(PATH_LENGTH), cell(p, run, c->s_length));
    metric(simplified, &nsimp, NAME(SMOOTHNESS), cell(p, run, c->s_smoothness));
    metric(simplified, &nsimp, NAME(CLEARANCE), cell(p, run, c->s_clearance));
    metric(simplified, &nsimp, NAME(WAYPOINTS),
           cell(p, run, c->s_segments) + 1.0);
    /* A stage is valid as the log's "correct solution" says (OMPL checked
     * the path), or without one if the run succeeded. A run has stages
     * when it solved or has a path (an approximate one, which OMPL
     * measures without calling it solved). */
    double s_correct = cell(p, run, c->s_correct);
    int raw_valid = isnan(correct) ? success : correct == 1.0;
    int simp_valid = isnan(s_correct) ? raw_valid : s_correct == 1.0;
    mpb_stage_record st[2] = {
        {.name = "raw", .time = cell(p, run, c->time), .valid = raw_valid,
         .verdict = raw_valid ? "valid" : "imported", .verdict_segment = -1,
         .num_metrics = nraw, .metrics = raw},
        {.name = "simplified", .time = cell(p, run, c->s_time),
         .valid = simp_valid,
         .verdict = simp_valid ? "valid" : "imported", .verdict_segment = -1,
         .num_metrics = nsimp, .metrics = simplified},
    };
    int nstages = solved || nraw > 0 || nsimp > 0 ? (nsimp > 0 ? 2 : 1) : 0;

    /* The planner's own numbers; its integers exactly too. */
    int nv = 0, nx = 0;
    for (int k = 0; k < p->num_properties; k++) {
        if (is_mapped(p->properties[k].name) || isnan(cell(p, run, k)))
            continue;
        if (integer_type(p->properties[k].type))
            exact[nx++] = (mpb_exact_value){nv, integer_cell(p, run, k)};
        values[nv++] = (mpb_named){p->properties[k].name, cell(p, run, k)};
    }
    int np = 0;
    if (p->progress_start != NULL) {
        int q = p->num_progress_properties;
        for (long i = p->progress_start[run]; i < p->progress_start[run + 1]; i++) {
            const double *sample = p->progress + (size_t)i * (size_t)q;
            for (int k = 1; k < q; k++)
                if (!isnan(sample[k]))
                    progress[np++] = (mpb_progress_record){
                        sample[0], p->progress_properties[k].name, sample[k]};
        }
    }
    /* tau_t is the planning and the simplification, as the time OMPL's
     * script ranks by (time + simplification_time); tau_r the planning. */
    double t = cell(p, run, c->time), ts = cell(p, run, c->s_time);
    double total = isnan(ts) ? t : t + ts;
    mpb_run_record rec = {
        .run_id = run_id, .attempt_id = attempt, .planner_id = "imported",
        .status = status_of(cell(p, run, c->status), solved), .message = "",
        .claimed_success = solved, .success = success,
        .time_total = total, .time_raw = t, .time_other = isnan(ts) ? 0.0 : ts,
        .wall_time = NAN,
        .verify_time = NAN,
        .memory = cell(p, run, c->memory),
        .num_stages = nstages, .stages = st,
        .num_values = nv, .values = values,
        .num_progress = np, .progress = progress,
        .num_exact = nx, .exact = exact,
    };
    return mpb_store_run_finish(s, &rec);
}

/* ---- one log ---------------------------------------------------------------- */

/* The run and progress properties the planner's block declares, measured
 * or not, for mpb export to give each its column and type. */
static int declare_properties(mpb_store *s, int64_t config,
                              const mpb_ompl_planner *p)
{
    int n = p->num_properties > p->num_progress_properties
                ? p->num_properties : p->num_progress_properties;
    mpb_log_property *l = calloc((size_t)n + 1, sizeof *l);
    if (l == NULL)
        return MPB_ENOMEM;
    for (int k = 0; k < p->num_properties; k++)
        l[k] = (mpb_log_property){p->properties[k].name, p->properties[k].type};
    int rc = mpb_store_log_properties(s, config, 0, p->num_properties, l);
    for (int k = 0; k < p->num_progress_properties; k++)
        l[k] = (mpb_log_property){p->progress_properties[k].name,
                                  p->progress_properties[k].type};
    if (rc == MPB_OK)
        rc = mpb_store_log_properties(s, config, 1,
                                      p->num_progress_properties, l);
    free(l);
    return rc;
}

static int import_log(mpb_store *s, const char *path, const char *text,
                      const mpb_ompl_log *log, long *runs_out)
{
    char hash[MPB_HASH_SIZE], family[32];
    mpb_hash_hex(text, strlen(text), hash);
    /* "OMPL 1.5.2" -> "ompl", "MoveIt 1.1" -> "moveit". */
    size_t k = 0;
    for (const char *c = log->version; *c && *c != ' ' && k + 1 < sizeof family; c++)
        if ((*c >= 'A' && *c <= 'Z') || (*c >= 'a' && *c <= 'z'))
            family[k++] = (char)(*c | 0x20);
    family[k] = '\0';
    if (k == 0)
        strcpy(family, "ompl");

    long most = 0;
    for (int i = 0; i < log->num_planners; i++)
        if (log->planners[i].num_runs > most)
            most = log->planners[i].num_runs;
    int64_t exp, scene, query;
    /* The log's header and experiment properties, for mpb export. */
    mpb_experiment_param *params = calloc((size_t)log->num_params + 1,
                                          sizeof *params);
    if (params == NULL)
        return MPB_ENOMEM;
    for (int i = 0; i < log->num_params; i++)
        params[i] = (mpb_experiment_param){log->params[i].name,
                                           log->params[i].type,
                                           log->params[i].value};
    mpb_log_header header = {
        .host = log->host, .version = log->version, .started = log->date,
        .seed = log->seed, .cpuinfo = log->cpuinfo,
        .total_time = log->total_time, .memory_limit = log->memory_limit,
        .num_params = log->num_params, .params = params,
    };
    mpb_experiment_info e = {log->experiment, path, hash, text,
                             (int)(log->runs_per_planner > 0 ? log->runs_per_planner
                                                             : most),
                             log->time_limit, &header, 0};
    mpb_scene_info sc = {log->experiment, "ompl-log", hash,
                         log->setup ? log->setup : "", "ompl-log", hash, ""};
    static const double none[1] = {0.0};
    mpb_query_info q = {.name = log->experiment, .num_joints = 0,
                        .joint_names = NULL, .start = none,
                        .goal_kind = MPB_GOAL_JOINTS, .goal_joints = NULL,
                        .goal_tolerance = 0.0};
    int rc = mpb_store_experiment_create(s, &e, &exp);
    free(params);
    if (rc != MPB_OK ||
        (rc = mpb_store_scene_add(s, exp, &sc, &scene)) != MPB_OK ||
        (rc = mpb_store_query_add(s, scene, &q, &query)) != MPB_OK)
        return rc;

    long runs = 0;
    for (int i = 0; i < log->num_planners; i++) {
        const mpb_ompl_planner *p = &log->planners[i];
        /* Planner Arena strips these prefixes too. */
        const char *algo = p->name;
        if (strncmp(algo, "geometric_", 10) == 0)
            algo += 10;
        else if (strncmp(algo, "control_", 8) == 0)
            algo += 8;
        char name[600];
        snprintf(name, sizeof name, "%s/%s", family, algo);
        int64_t config;
        if ((rc = mpb_store_planner_config_add(s, exp, name, family, algo,
                                               p->settings, &config)) != MPB_OK)
            return rc;
        if ((rc = declare_properties(s, config, p)) != MPB_OK)
            return rc;
        for (long r = 0; r < p->num_runs; r++)
            if ((rc = mpb_store_run_add(s, exp, config, query, (int)r, 0)) != MPB_OK)
                return rc;
        run_ids ids = {config, calloc((size_t)p->num_runs + 1, sizeof(int64_t)),
                       p->num_runs};
        long samples = p->progress_start ? p->progress_start[p->num_runs] : 0;
        long most_progress = 0;
        for (long r = 0; p->progress_start && r < p->num_runs; r++)
            if (p->progress_start[r + 1] - p->progress_start[r] > most_progress)
                most_progress = p->progress_start[r + 1] - p->progress_start[r];
        (void)samples;
        mpb_named *values = calloc((size_t)p->num_properties + 1, sizeof *values);
        mpb_exact_value *exact = calloc((size_t)p->num_properties + 1,
                                        sizeof *exact);
        mpb_progress_record *progress =
            calloc((size_t)most_progress * (size_t)(p->num_progress_properties + 1) + 1,
                   sizeof *progress);
        if (ids.ids == NULL || values == NULL || exact == NULL ||
            progress == NULL)
            rc = MPB_ENOMEM;
        else
            rc = mpb_store_runs_unfinished(s, exp, collect_id, &ids);
        columns c = find_columns(p);
        for (long r = 0; rc == MPB_OK && r < p->num_runs; r++)
            rc = import_run(s, p, &c, r, ids.ids[r], values, exact, progress);
        free(ids.ids);
        free(values);
        free(exact);
        free(progress);
        if (rc != MPB_OK)
            return rc;
        runs += p->num_runs;
    }
    *runs_out = runs;
    return mpb_store_experiment_finish(s, exp);
}

/* A log read and parsed. */
typedef struct loaded {
    char *text;
    mpb_ompl_log *log;
} loaded;

static void unload(loaded *l)
{
    mpb_ompl_log_close(l->log);
    free(l->text);
    *l = (loaded){0};
}

static long total_runs(const mpb_ompl_log *log)
{
    long n = 0;
    for (int i = 0; i < log->num_planners; i++)
        n += log->planners[i].num_runs;
    return n;
}

/* The log at path read and parsed into *l; 0 and its error said in one
 * line when it cannot be. */
static int load(const char *path, loaded *l)
{
    size_t len = 0;
    char err[256];
    int rc;
    *l = (loaded){0};
    errno = 0;
    if ((l->text = mpb_read_file(path, 0, &len)) == NULL) {
        fprintf(stderr, "mpb " CMD ": cannot read %s: %s\n", path,
                errno ? strerror(errno) : "out of memory");
        return 0;
    }
    if ((rc = mpb_ompl_log_open(l->text, len, &l->log, err, sizeof err)) !=
        MPB_OK) {
        /* "line N: what" -> "PATH:N: what", as compilers say it. */
        fprintf(stderr, "mpb " CMD ": %s:%s\n", path,
                rc == MPB_ENOMEM ? " out of memory"
                : strncmp(err, "line ", 5) == 0 ? err + 5 : err);
        unload(l);
        return 0;
    }
    if (total_runs(l->log) == 0) {
        /* OMPL writes such a log when no planner was added; importing it
         * would make an experiment that reports nothing. */
        int np = l->log->num_planners;
        fprintf(stderr, "mpb " CMD ": %s: no runs in the log (%d planner%s): "
                "nothing to import\n", path, np, np == 1 ? "" : "s");
        unload(l);
        return 0;
    }
    return 1;
}

/* Every log read and checked, one at a time, each error said: 1 when all
 * can be imported. */
static int check_all(int num_logs, char **logs)
{
    int ok = 1;
    for (int i = 0; i < num_logs; i++) {
        loaded l;
        if (load(logs[i], &l))
            unload(&l);
        else
            ok = 0;
    }
    return ok;
}

/* What is said of a log once it is imported. */
typedef struct imported {
    const char *path;
    char       *experiment;
    int         planners;
    long        runs;
} imported;

/* -p: the logs handed to the Planner Arena writer one at a time, each
 * read as the one before is written, so that one log at a time is held. */
typedef struct arena_feed {
    char     **logs;
    int        num_logs, next, bad;
    loaded     current;
    imported  *done;
} arena_feed;

static int feed_next(void *ud, const mpb_ompl_log **log)
{
    arena_feed *f = ud;
    unload(&f->current);
    *log = NULL;
    if (f->next == f->num_logs)
        return MPB_OK;
    const char *path = f->logs[f->next];
    if (!load(path, &f->current)) {
        f->bad = 1;
        f->next++;              /* said: the rest are checked after */
        return MPB_EPARSE;
    }
    const mpb_ompl_log *l = f->current.log;
    f->done[f->next++] = (imported){path, strdup(l->experiment ? l->experiment : ""),
                                    l->num_planners, total_runs(l)};
    *log = l;
    return MPB_OK;
}

/* -p: the logs straight into one new Planner Arena database, whole or
 * not at all. */
static int to_planner_arena(const char *out, int append, int num_logs,
                            char **logs)
{
    arena_feed f = {.logs = logs, .num_logs = num_logs};
    char err[256];
    int status = MPB_EXIT_OK;
    if ((f.done = calloc((size_t)num_logs, sizeof *f.done)) == NULL) {
        fprintf(stderr, "mpb " CMD ": out of memory\n");
        return MPB_EXIT_ERROR;
    }
    if (mpb_ompl_logs_to_planner_arena(out, append ? MPB_EXPORT_APPEND : 0,
                                       feed_next, &f, NULL, err,
                                       sizeof err) != MPB_OK) {
        if (f.bad)      /* the rest checked too, for every error at once */
            check_all(num_logs - f.next, logs + f.next);
        else
            fprintf(stderr, "mpb " CMD ": %s\n", err);
        status = MPB_EXIT_ERROR;
    }
    unload(&f.current);
    for (int i = 0; i < num_logs; i++) {
        if (status == MPB_EXIT_OK)
            printf("%s: experiment '%s', %d planners, %ld runs\n",
                   f.done[i].path, f.done[i].experiment ? f.done[i].experiment
                                   : "?", f.done[i].planners,
                   f.done[i].runs);
        free(f.done[i].experiment);
    }
    free(f.done);
    return status;
}

int cmd_import(int argc, char **argv)
{
    static const struct option longopts[] = {
        {"db", required_argument, NULL, 'd'},
        {"planner-arena", required_argument, NULL, 'p'},
        {"append", no_argument, NULL, 'a'},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    const char *db = NULL, *arena = NULL;
    int opt, append = 0;
    optind = 1;
    opterr = 0;
    while ((opt = getopt_long(argc, argv, ":d:p:ah", longopts, NULL)) != -1) {
        switch (opt) {
        case 'd':
            db = optarg;
            break;
        case 'p':
            arena = optarg;
            break;
        case 'a':
            append = 1;
            break;
        case 'h':
            usage(stdout);
            return MPB_EXIT_OK;
        default:    /* ':' a missing value, '?' an unknown option */
            return tool_option_error(CMD, opt, argv);
        }
    }
    if ((db == NULL) == (arena == NULL) || optind == argc) {
        fprintf(stderr, "mpb " CMD ": %s (try 'mpb " CMD " --help')\n",
                optind == argc ? "which logs?"
                : db ? "-d or -p, not both" : "into which database? (-d DB or -p OUT.db)");
        return MPB_EXIT_USAGE;
    }
    if (append && arena == NULL) {
        fprintf(stderr, "mpb " CMD ": -a is for -p (try 'mpb " CMD " --help')\n");
        return MPB_EXIT_USAGE;
    }
    if (arena != NULL)
        return to_planner_arena(arena, append, argc - optind, argv + optind);
    /* Every log checked before the database is created or opened, then
     * read again as it is imported: one log in memory at a time. */
    int num_logs = argc - optind;
    char **logs = argv + optind;
    if (!check_all(num_logs, logs))
        return MPB_EXIT_ERROR;
    mpb_store *s = NULL;
    if (mpb_store_open(db, 0, &s) != MPB_OK) {
        fprintf(stderr, "mpb " CMD ": %s\n", mpb_store_errmsg(s));
        mpb_store_close(s);
        return MPB_EXIT_ERROR;
    }
    int status = MPB_EXIT_OK;
    for (int i = 0; i < num_logs; i++) {
        loaded l;
        long runs = 0;
        int rc;
        if (!load(logs[i], &l)) {   /* changed since it was checked */
            status = MPB_EXIT_ERROR;
            continue;
        }
        if ((rc = mpb_store_begin(s)) != MPB_OK ||
                   (rc = import_log(s, logs[i], l.text, l.log, &runs)) != MPB_OK ||
                   (rc = mpb_store_commit(s)) != MPB_OK) {
            fprintf(stderr, "mpb " CMD ": %s: %s\n", logs[i], mpb_store_errmsg(s));
            mpb_store_rollback(s);
            status = MPB_EXIT_ERROR;
        } else {
            printf("%s: experiment '%s', %d planners, %ld runs\n", logs[i],
                   l.log->experiment, l.log->num_planners, runs);
        }
        unload(&l);
    }
    mpb_store_close(s);
    return status;
}
