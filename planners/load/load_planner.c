/*
 * load_planner.c - mpb-planner-load: answers every request at once with a
 * path some planner found before for the same problem, read from a results
 * database, so that the daemon's verification can be loaded with real
 * paths at any rate, without the planners' time.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpbench/planner.h"

#define PROG "mpb-planner-load"

static void usage(FILE *out)
{
    fprintf(out,
"usage: " PROG " --from DB [--config NAME] [--experiment ID]\n"
"                        [--lcm-url URL] [--name NAME] [--max-runs N]\n"
"                        [--secret-file FILE]\n"
"\n"
"A planner process for mpbench that does no planning: it answers every\n"
"plan request for the algorithm \"replay\" at once, with status SOLVED\n"
"and the stages (names, waypoints) of a finished run of the same problem\n"
"in the results database DB: the same start state and joint goal, to\n"
"1e-9. A problem DB has no path for is answered with the straight line\n"
"from start to goal, one stage \"raw\" of two waypoints, unchecked. So the\n"
"daemon verifies and measures the paths planners really returned, as\n"
"fast as it can take them: bench/verifyload.sh measures how many a\n"
"second. It prints one line when it starts (the problems read), nothing\n"
"per run.\n"
"\n"
"options:\n"
"  --from DB       the results database the paths are read from\n"
"  --config NAME   only runs of this planner configuration (e.g.\n"
"                  ompl/RRTConnect; default: any, the first finished run\n"
"                  with a valid final stage, else the first with stages)\n"
"  --experiment ID the experiment of DB (default: the newest)\n"
"  --lcm-url URL   LCM URL to join (default %s)\n"
"  --name NAME     planner name in experiment files (default \"load\")\n"
"  --max-runs N    exit after answering N runs (default 0: no limit)\n"
"  --secret-file F authenticate every message with the secret in F\n"
"  --help          show this text\n", MPB_DEFAULT_LCM_URL);
}

/* ---- the paths of the database ----------------------------------------- */

typedef struct path_stage {
    char   *name;
    int     n;
    double *wp;
} path_stage;

/* One problem: its start and joint goal, and the stages of one run. */
typedef struct problem {
    int64_t     query;
    int         nj;
    double     *start, *goal;
    int         rank;        /* of the run taken: 2 valid final stage,
                                1 stages, 0 none */
    int64_t     run;
    int         num_stages;
    path_stage *stages;
} problem;

typedef struct library {
    mpb_store *s;
    int64_t    config;       /* 0: any */
    problem   *p;
    int        num, cap;
    char       err[300];
} library;

static void stages_free(problem *p)
{
    for (int i = 0; i < p->num_stages; i++) {
        free(p->stages[i].name);
        free(p->stages[i].wp);
    }
    free(p->stages);
    p->stages = NULL;
    p->num_stages = 0;
}

static int on_query(void *ud, const mpb_query_row *r)
{
    library *lib = ud;
    if (r->goal_kind != MPB_GOAL_JOINTS)
        return 0;               /* a pose region: answered by the line */
    int nj = 1;
    for (const char *c = r->joint_names; *c; c++)
        nj += *c == ' ';
    if (lib->num == lib->cap) {
        int cap = lib->cap ? 2 * lib->cap : 64;
        problem *p = realloc(lib->p, (size_t)cap * sizeof *p);
        if (p == NULL)
            return 1;
        lib->p = p;
        lib->cap = cap;
    }
    problem *p = &lib->p[lib->num];
    memset(p, 0, sizeof *p);
    p->query = r->id;
    p->nj = nj;
    p->start = calloc((size_t)nj, sizeof *p->start);
    p->goal = calloc((size_t)nj, sizeof *p->goal);
    if (!p->start || !p->goal ||
        mpb_store_numbers(r->start, p->start, nj) != MPB_OK ||
        mpb_store_numbers(r->goal_joints, p->goal, nj) != MPB_OK) {
        free(p->start);
        free(p->goal);
        return 0;               /* numbers it cannot read: left out */
    }
    lib->num++;
    return 0;
}

static int on_scene(void *ud, const mpb_scene_row *r)
{
    library *lib = ud;
    return mpb_store_queries(lib->s, r->id, on_query, lib) != MPB_OK;
}

static problem *problem_of(library *lib, int64_t query)
{
    for (int i = 0; i < lib->num; i++)
        if (lib->p[i].query == query)
            return &lib->p[i];
    return NULL;
}

/* The stages of the run being read, into the problem being filled. */
typedef struct reading {
    problem *p;
    int      ok;
} reading;

static int on_stage(void *ud, const mpb_stage_record *st)
{
    reading *rd = ud;
    problem *p = rd->p;
    if (st->num_waypoints < 1 || st->num_joints != p->nj) {
        rd->ok = 0;
        return 1;
    }
    path_stage *grown = realloc(p->stages, (size_t)(p->num_stages + 1) *
                                               sizeof *grown);
    if (grown == NULL) {
        rd->ok = 0;
        return 1;
    }
    p->stages = grown;
    path_stage *s = &p->stages[p->num_stages];
    size_t nv = (size_t)st->num_waypoints * (size_t)st->num_joints;
    s->name = strdup(st->name);
    s->wp = malloc(nv * sizeof *s->wp);
    if (s->name == NULL || s->wp == NULL) {
        free(s->name);
        free(s->wp);
        rd->ok = 0;
        return 1;
    }
    memcpy(s->wp, st->waypoints, nv * sizeof *s->wp);
    s->n = st->num_waypoints;
    p->num_stages++;
    return 0;
}

/* The run to take for each problem: the first with a valid final stage,
 * else the first with stages (their stages read after the walk). */
static int on_result(void *ud, const mpb_result_row *r)
{
    library *lib = ud;
    if (lib->config != 0 && r->planner_config_id != lib->config)
        return 0;
    problem *p = problem_of(lib, r->query_id);
    if (p == NULL || r->stage == NULL)
        return 0;
    int rank = r->stage_valid == 1 ? 2 : 1;
    if (rank > p->rank) {
        p->rank = rank;
        p->run = r->run_id;
    }
    return 0;
}

/* The stages of each problem's run; a run whose stages do not read
 * whole leaves its problem to the straight line. */
static void read_paths(library *lib)
{
    for (int i = 0; i < lib->num; i++) {
        problem *p = &lib->p[i];
        if (p->rank == 0)
            continue;
        reading rd = {p, 1};
        if (mpb_store_run_stages(lib->s, p->run, on_stage, &rd) != MPB_OK ||
            !rd.ok)
            stages_free(p);
    }
}

typedef struct config_find {
    const char *name;
    int64_t     id;
} config_find;

static int on_config(void *ud, const mpb_planner_config_row *r)
{
    config_find *f = ud;
    if (strcmp(r->name, f->name) == 0)
        f->id = r->id;
    return 0;
}

/* Read the problems and paths of DB's experiment; one line in err and
 * nonzero on failure. */
static int library_load(library *lib, const char *path, int64_t experiment,
                        const char *config)
{
    if (mpb_store_open(path, 1, &lib->s) != MPB_OK) {
        snprintf(lib->err, sizeof lib->err, "%s: %s", path,
                 lib->s ? mpb_store_errmsg(lib->s) : "out of memory");
        return 1;
    }
    if (experiment == 0 &&
        mpb_store_experiment_latest(lib->s, &experiment) != MPB_OK) {
        snprintf(lib->err, sizeof lib->err, "%s: no experiment", path);
        return 1;
    }
    if (config != NULL) {
        config_find f = {config, 0};
        if (mpb_store_planner_configs(lib->s, experiment, on_config, &f) !=
                MPB_OK || f.id == 0) {
            snprintf(lib->err, sizeof lib->err, "%s: experiment %lld has no "
                     "planner configuration '%.80s'", path,
                     (long long)experiment, config);
            return 1;
        }
        lib->config = f.id;
    }
    if (mpb_store_scenes(lib->s, experiment, on_scene, lib) != MPB_OK ||
        mpb_store_results(lib->s, experiment, 0, NULL, NULL, 0, on_result,
                          lib) != MPB_OK) {
        snprintf(lib->err, sizeof lib->err, "%s: %s", path,
                 mpb_store_errmsg(lib->s));
        return 1;
    }
    read_paths(lib);
    return 0;
}

static void library_free(library *lib)
{
    for (int i = 0; i < lib->num; i++) {
        stages_free(&lib->p[i]);
        free(lib->p[i].start);
        free(lib->p[i].goal);
    }
    free(lib->p);
    mpb_store_close(lib->s);
}

/* The problem of DB with this start and joint goal (to 1e-9), or NULL. */
static const problem *find(const library *lib, const mpb_plan_request_t *req)
{
    if (req->goal.kind != MPB_GOAL_T_JOINTS ||
        req->goal.num_joints != req->num_joints)
        return NULL;
    for (int i = 0; i < lib->num; i++) {
        const problem *p = &lib->p[i];
        if (p->nj != req->num_joints || p->num_stages == 0)
            continue;
        int same = 1;
        for (int j = 0; j < p->nj && same; j++)
            same = fabs(p->start[j] - req->start[j]) <= 1e-9 &&
                   fabs(p->goal[j] - req->goal.joints[j]) <= 1e-9;
        if (same)
            return p;
    }
    return NULL;
}

static int solve_replay(void *user, const mpb_plan_request_t *req,
                        const mpb_solve_limits *lim, mpb_plan_result_t *res)
{
    const library *lib = user;
    double t0 = mpb_monotonic_s();
    (void)lim;
    const problem *p = find(lib, req);
    int rc = MPB_OK;
    if (p != NULL) {
        for (int i = 0; i < p->num_stages && rc == MPB_OK; i++)
            rc = mpb_result_add_stage(res, p->stages[i].name, 0.0,
                                      p->stages[i].wp, p->stages[i].n, p->nj);
    } else if (req->goal.kind == MPB_GOAL_T_JOINTS &&
               req->goal.num_joints == req->num_joints) {
        int n = req->num_joints;
        double *wp = malloc(2 * (size_t)n * sizeof *wp);
        if (wp == NULL)
            return MPB_ENOMEM;
        memcpy(wp, req->start, (size_t)n * sizeof *wp);
        memcpy(wp + n, req->goal.joints, (size_t)n * sizeof *wp);
        rc = mpb_result_add_stage(res, "raw", 0.0, wp, 2, n);
        free(wp);
    } else {
        mpb_result_set_message(res, "replay needs a joint-space goal");
        return MPB_EUNSUPPORTED;
    }
    if (rc != MPB_OK)
        return rc;
    res->status = MPB_PLAN_RESULT_T_SOLVED;
    res->time_total = mpb_monotonic_s() - t0;
    for (int i = 0; i < res->num_stages; i++)
        res->stages[i].time = res->time_total;
    return MPB_OK;
}

static void on_ready(void *user, const char *planner_id)
{
    const library *lib = user;
    int paths = 0;
    for (int i = 0; i < lib->num; i++)
        paths += lib->p[i].num_stages > 0;
    printf(PROG ": serving as %s, %d problems, %d with a path\n", planner_id,
           lib->num, paths);
    fflush(stdout);
}

int main(int argc, char **argv)
{
    mpb_planner_options opt = {.name = "load"};
    const char *from = NULL, *config = NULL;
    int64_t experiment = 0;
    char err[256];

    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int took = mpb_planner_option(argc, argv, &i, &opt, err, sizeof err);
        if (took < 0) {
            fprintf(stderr, PROG ": %s (see --help)\n", err);
            return 2;
        }
        if (took)
            continue;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            return 0;
        }
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (v != NULL && strcmp(a, "--from") == 0) {
            from = v;
        } else if (v != NULL && strcmp(a, "--config") == 0) {
            config = v;
        } else if (v != NULL && strcmp(a, "--experiment") == 0) {
            char *end;
            errno = 0;
            long long id = strtoll(v, &end, 10);
            if (end == v || *end != '\0' || errno != 0 || id < 1) {
                fprintf(stderr, PROG ": --experiment wants an id, not "
                        "'%s'\n", v);
                return 2;
            }
            experiment = id;
        } else {
            fprintf(stderr, PROG ": unknown argument '%s' (see --help)\n", a);
            return 2;
        }
        i++;
    }
    if (from == NULL) {
        fprintf(stderr, PROG ": wants --from DB (see --help)\n");
        return 2;
    }
    library lib;
    memset(&lib, 0, sizeof lib);
    if (library_load(&lib, from, experiment, config) != 0) {
        fprintf(stderr, PROG ": %s\n", lib.err);
        library_free(&lib);
        return 1;
    }

    static const char *const algorithms[] = { "replay" };
    mpb_planner_def def = {
        .language = "c",
        .version = MPB_VERSION_STRING,
        .algorithms = algorithms,
        .num_algorithms = 1,
        .solve = solve_replay,
        .user = &lib,
        .heartbeat_ms = 0,
        .on_ready = on_ready,
    };
    int status = mpb_planner_main(&def, &opt, PROG);
    library_free(&lib);
    return status;
}
