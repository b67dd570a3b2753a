/*
 * verifydb.c - mpb-bench-verifydb: how many waypoints per second mpbench
 * verifies and measures on the trajectories planners really returned. It
 * reads the finished runs of an experiment in a results database through
 * the store API (as `mpb verify` does): each run's world (the stored robot
 * text, its SRDF inside, and scene; the joints its query held), start,
 * goal and stages. Then, in process, it times what mpbenchd does per
 * result (mpb_measure_stage(): mpb_verify_path at the experiment's
 * resolution and every metric the daemon stores), over all of
 * them, repeated for at least S seconds. Opening the worlds is timed apart.
 * With --verification both, certified and sampled verification are timed
 * in the same run, interleaved, as ratios on a shared machine want.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "mpbench/mpbench.h"

#include "bench_util.h"

#define PROG "mpb-bench-verifydb"

/* The verifier's step when the database does not say (mpbenchd -r). */
#define DEFAULT_RESOLUTION 0.01

static void usage(FILE *out)
{
    fprintf(out,
"usage: " PROG " --db FILE [options]\n"
"\n"
"Times verification (mpb_verify_path) and the daemon's metrics on every\n"
"stage of every finished run of an experiment in the results database\n"
"FILE, as mpbenchd computes them per result, and prints waypoints per\n"
"second. The database is only read.\n"
"\n"
"options:\n"
"  --experiment ID   the experiment (default: the newest)\n"
"  --resolution RAD  verification step (default: the experiment's, else\n"
"                    0.01)\n"
"  --robot-dir DIR   where a URDF robot's meshes are looked for last,\n"
"                    after MPB_MESH_PATH and ROS_PACKAGE_PATH (mpbenchd\n"
"                    uses the URDF's folder)\n"
"  --seconds S       repeat each measurement for at least S seconds\n"
"                    (default 1)\n"
"  --verification M  certified (the default), sampled, or both: each\n"
"                    measurement of one mode, then of the other, --reps\n"
"                    times, a RESULT line per mode (key_certified,\n"
"                    key_sampled)\n"
"  --reps N          repetitions, interleaved (default 1)\n"
"  --key NAME        the RESULT line's key (default verify_db)\n"
"  --label TEXT      names the trajectories in the output\n"
"  --compare-stored FILE  instead: measure every stage once as mpbenchd\n"
"                    does, compare its verdict (name, detail, how\n"
"                    checked) with the stored one, one line per\n"
"                    difference, exit 1 if any; every metric into FILE\n"
"                    as run|stage|name|value (- for none)\n"
"  --per-run N       instead: each run's CPU time of verification and\n"
"                    metrics (every stage, the mean of N passes), their\n"
"                    median, percentiles, mean and largest\n");
}

/* CPU time of this thread, s: waiting for a core on a shared machine is
 * no part of it. */
static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void *xcalloc(size_t n, size_t size)
{
    void *p = calloc(n ? n : 1, size);
    if (p == NULL) {
        fprintf(stderr, PROG ": out of memory\n");
        exit(1);
    }
    return p;
}

static char *xstrdup(const char *s)
{
    char *d = strdup(s ? s : "");
    if (d == NULL) {
        fprintf(stderr, PROG ": out of memory\n");
        exit(1);
    }
    return d;
}

/* Space-separated numbers into a new array of exactly n; NULL if not n. */
static double *parse_numbers(const char *text, int n)
{
    double *v = xcalloc((size_t)n, sizeof *v);
    if (mpb_store_numbers(text, v, n) != MPB_OK) {
        free(v);
        return NULL;
    }
    return v;
}

/* ---- what the database holds ------------------------------------------ */

typedef struct scene {
    int64_t id;
    char   *name, *robot_format, *robot, *scene_format, *scene;
} scene;

typedef struct query {
    int64_t  id, scene_id;
    char    *name, *joint_names, *held;  /* held: NULL if none */
    int      num_joints;
    double  *start, *goal_joints;        /* goal_joints: joint goals */
    double   tolerance;
    int      goal_kind;
    char    *goal_link;
    double   goal_region[12];
    struct world *world;
} query;

/* A world per scene and set of held joints, as the daemon's. */
typedef struct world {
    int64_t    scene_id;
    const char *held;
    mpb_world *w;
} world;

/* A finished run and its query. */
typedef struct run_ref {
    int64_t run, query;
} run_ref;

/* One stage to time, with what its run's verification needs. */
typedef struct stage {
    int64_t      run_id;
    const query *q;
    char        *name, *stored;   /* stored: the verdict in the database */
    char        *stored_detail, *stored_verification;   /* "" if none */
    int          n;
    double      *wp, *times;      /* times NULL: untimed */
    double       time;            /* the stage's time, as stored */
    int          num_metrics;     /* stored */
    char       **metric_names;
    double      *metric_values;
} stage;

typedef struct db {
    const char *path;
    mpb_store  *s;
    scene      *scenes;
    int         num_scenes;
    query      *queries;
    int         num_queries, cap_queries;
    world      *worlds;
    int         num_worlds;
    run_ref    *runs;             /* finished runs, in run order */
    int         num_runs, cap_runs;
    stage      *stages;
    int         num_stages, cap_stages;
    int64_t     cur_run;          /* while its stages are read */
    const query *cur_query;
    int         runs_with_stages, skipped;
    long        waypoints;
    char        err[512];         /* a fault found in a callback */
} db;

static void grow(void **p, int *cap, int need, size_t size)
{
    if (need <= *cap)
        return;
    int c = *cap ? 2 * *cap : 64;
    void *q = realloc(*p, (size_t)c * size);
    if (q == NULL) {
        fprintf(stderr, PROG ": out of memory\n");
        exit(1);
    }
    *p = q;
    *cap = c;
}

static int on_scene(void *ud, const mpb_scene_row *r)
{
    db *d = ud;
    scene *grown = realloc(d->scenes, (size_t)(d->num_scenes + 1) *
                                      sizeof *grown);
    if (grown == NULL) {
        fprintf(stderr, PROG ": out of memory\n");
        exit(1);
    }
    d->scenes = grown;
    scene *sc = &d->scenes[d->num_scenes++];
    sc->id = r->id;
    sc->name = xstrdup(r->name);
    sc->robot_format = xstrdup(r->robot_format);
    sc->robot = xstrdup(r->robot);
    sc->scene_format = xstrdup(r->scene_format);
    sc->scene = xstrdup(r->scene);
    return 0;
}

static int on_query(void *ud, const mpb_query_row *r)
{
    db *d = ud;
    grow((void **)&d->queries, &d->cap_queries, d->num_queries + 1,
         sizeof *d->queries);
    query *q = &d->queries[d->num_queries++];
    memset(q, 0, sizeof *q);
    q->id = r->id;
    q->scene_id = r->scene_id;
    q->name = xstrdup(r->name);
    q->joint_names = xstrdup(r->joint_names);
    q->held = r->held ? xstrdup(r->held) : NULL;
    for (const char *c = q->joint_names; *c; c++)
        if (*c != ' ' && (c == q->joint_names || c[-1] == ' '))
            q->num_joints++;
    q->start = parse_numbers(r->start, q->num_joints);
    q->tolerance = r->goal_tolerance;
    q->goal_kind = r->goal_kind;
    if (r->goal_kind == MPB_GOAL_JOINTS) {
        q->goal_joints = parse_numbers(r->goal_joints, q->num_joints);
    } else {
        q->goal_link = xstrdup(r->goal_link);
        double *g = parse_numbers(r->goal_region, 12);
        if (g)
            memcpy(q->goal_region, g, sizeof q->goal_region);
        free(g);
    }
    return 0;
}

static int on_result(void *ud, const mpb_result_row *r)
{
    db *d = ud;
    grow((void **)&d->runs, &d->cap_runs, d->num_runs + 1, sizeof *d->runs);
    d->runs[d->num_runs++] = (run_ref){r->run_id, r->query_id};
    return 0;
}

static int on_stage(void *ud, const mpb_stage_record *st)
{
    db *d = ud;
    int nj = d->cur_query->num_joints;
    /* What the daemon would not verify (the wrong size), and blobs that do
     * not hold their waypoints whole: nothing to time. */
    if (st->num_waypoints < 1 || st->num_joints != nj) {
        d->skipped++;
        return 0;
    }
    size_t nv = (size_t)st->num_waypoints * (size_t)nj;
    for (size_t i = 0; i < nv; i++)
        if (!isfinite(st->waypoints[i])) {
            snprintf(d->err, sizeof d->err, "run %lld stage %s: waypoint "
                     "%zu holds a value that is not finite (a corrupt "
                     "trajectory); nothing timed", (long long)d->cur_run,
                     st->name, i / (size_t)nj);
            return 1;
        }
    grow((void **)&d->stages, &d->cap_stages, d->num_stages + 1,
         sizeof *d->stages);
    stage *s = &d->stages[d->num_stages++];
    s->run_id = d->cur_run;
    s->q = d->cur_query;
    s->name = xstrdup(st->name);
    s->stored = xstrdup(st->verdict);
    s->stored_detail = xstrdup(st->verdict_detail);
    s->stored_verification = xstrdup(st->verification);
    s->n = st->num_waypoints;
    s->wp = xcalloc(nv, sizeof *s->wp);
    memcpy(s->wp, st->waypoints, nv * sizeof *s->wp);
    s->times = NULL;
    if (st->times != NULL) {
        s->times = xcalloc((size_t)s->n, sizeof *s->times);
        memcpy(s->times, st->times, (size_t)s->n * sizeof *s->times);
    }
    s->time = st->time;
    s->num_metrics = st->num_metrics;
    s->metric_names = xcalloc((size_t)st->num_metrics, sizeof (char *));
    s->metric_values = xcalloc((size_t)st->num_metrics, sizeof (double));
    for (int k = 0; k < st->num_metrics; k++) {
        s->metric_names[k] = xstrdup(st->metrics[k].name);
        s->metric_values[k] = st->metrics[k].value;
    }
    d->waypoints += st->num_waypoints;
    return 0;
}

static const scene *scene_of(const db *d, int64_t id)
{
    for (int i = 0; i < d->num_scenes; i++)
        if (d->scenes[i].id == id)
            return &d->scenes[i];
    return NULL;
}

static query *query_of(const db *d, int64_t id)
{
    for (int i = 0; i < d->num_queries; i++)
        if (d->queries[i].id == id)
            return &d->queries[i];
    return NULL;
}

/* The held joints "name=value name=value" into names and values (n). */
static int parse_held(char *text, const char **names, double *values,
                      int max)
{
    int n = 0;
    char *save = NULL;
    for (char *t = strtok_r(text, " ", &save); t && n < max;
         t = strtok_r(NULL, " ", &save)) {
        char *eq = strrchr(t, '=');
        if (eq == NULL)
            continue;
        *eq = '\0';
        names[n] = t;
        values[n++] = strtod(eq + 1, NULL);
    }
    return n;
}

/* The world of query q, opened once per scene and held joints; 0, or -1
 * with d->err set. *secs grows by the time opening took. */
static int world_for(db *d, query *q, const char *robot_dir, double *secs)
{
    for (int i = 0; i < d->num_worlds; i++)
        if (d->worlds[i].scene_id == q->scene_id &&
            strcmp(d->worlds[i].held ? d->worlds[i].held : "",
                   q->held ? q->held : "") == 0) {
            q->world = &d->worlds[i];
            return 0;
        }
    const scene *sc = scene_of(d, q->scene_id);
    if (sc == NULL) {
        snprintf(d->err, sizeof d->err, "query %s: its scene is not in the "
                 "database", q->name);
        return -1;
    }
    /* The group, in the query's order. */
    char *names_text = xstrdup(q->joint_names);
    const char **names = xcalloc((size_t)q->num_joints, sizeof *names);
    int n = 0;
    char *save = NULL;
    for (char *t = strtok_r(names_text, " ", &save); t && n < q->num_joints;
         t = strtok_r(NULL, " ", &save))
        names[n++] = t;
    char err[512] = "";
    mpb_world *w = NULL;
    double t0 = mpbb_now();
    int rc = mpb_world_open_group_in(sc->robot_format, sc->robot, robot_dir,
                                     sc->scene_format, sc->scene, names, n,
                                     &w, err, sizeof err);
    if (rc == MPB_OK && q->held) {
        char *held = xstrdup(q->held);
        size_t max = strlen(held) / 2 + 1;
        const char **hn = xcalloc(max, sizeof *hn);
        double *hv = xcalloc(max, sizeof *hv);
        int nh = parse_held(held, hn, hv, (int)max);
        rc = mpb_world_hold(w, hn, hv, nh, err, sizeof err);
        free(hn);
        free(hv);
        free(held);
    }
    *secs += mpbb_now() - t0;
    free(names);
    free(names_text);
    if (rc != MPB_OK) {
        mpb_world_close(w);
        snprintf(d->err, sizeof d->err, "scene '%.100s': %.400s", sc->name, err);
        return -1;
    }
    /* Worlds are never moved: queries point at them. */
    world *wd = &d->worlds[d->num_worlds++];
    wd->scene_id = q->scene_id;
    wd->held = q->held;
    wd->w = w;
    q->world = wd;
    return 0;
}

/* Read the experiment's finished runs and open their worlds; 0, or -1
 * after one line on stderr. */
static int load(db *d, int64_t experiment, const char *robot_dir,
                double *open_secs)
{
    int rc = mpb_store_scenes(d->s, experiment, on_scene, d);
    for (int i = 0; rc == MPB_OK && i < d->num_scenes; i++)
        rc = mpb_store_queries(d->s, d->scenes[i].id, on_query, d);
    if (rc == MPB_OK)
        rc = mpb_store_results(d->s, experiment, 0, NULL, NULL, 0, on_result,
                               d);
    if (rc != MPB_OK) {
        fprintf(stderr, PROG ": %s: %s\n", d->path, mpb_store_errmsg(d->s));
        return -1;
    }
    if (d->num_runs == 0) {
        fprintf(stderr, PROG ": %s: experiment %lld has no finished runs\n",
                d->path, (long long)experiment);
        return -1;
    }
    d->worlds = xcalloc((size_t)d->num_queries, sizeof *d->worlds);
    for (int i = 0; i < d->num_runs; i++) {
        query *q = query_of(d, d->runs[i].query);
        if (q == NULL || q->start == NULL ||
            (q->goal_kind == MPB_GOAL_JOINTS && q->goal_joints == NULL)) {
            fprintf(stderr, PROG ": %s: run %lld: its query is not in the "
                    "database, or its start or goal is not %d numbers\n",
                    d->path, (long long)d->runs[i].run,
                    q ? q->num_joints : 0);
            return -1;
        }
        int before = d->num_stages;
        d->cur_run = d->runs[i].run;
        d->cur_query = q;
        rc = mpb_store_run_stages(d->s, d->runs[i].run, on_stage, d);
        if (rc == 1) {
            fprintf(stderr, PROG ": %s: %s\n", d->path, d->err);
            return -1;
        }
        if (rc != MPB_OK) {
            fprintf(stderr, PROG ": %s: run %lld: %s\n", d->path,
                    (long long)d->runs[i].run, mpb_store_errmsg(d->s));
            return -1;
        }
        if (d->num_stages == before)
            continue;
        d->runs_with_stages++;
        if (q->world == NULL &&
            world_for(d, q, robot_dir, open_secs) != 0) {
            fprintf(stderr, PROG ": %s: run %lld: %s\n", d->path,
                    (long long)d->runs[i].run, d->err);
            return -1;
        }
    }
    if (d->num_stages == 0) {
        fprintf(stderr, PROG ": %s: experiment %lld: none of its %d "
                "finished runs has a stage with waypoints to time\n",
                d->path, (long long)experiment, d->num_runs);
        return -1;
    }
    return 0;
}

/* ---- timing ----------------------------------------------------------- */

enum { BOTH, VERIFY, METRICS, NUM_WHAT };

/* Where the metrics go, so that no pass is thought idle. */
static volatile double sink;

/* One pass over every stage: what mpbenchd does with each stage
 * (mpb_measure_stage()), or its verification or its metrics alone. */
static void pass(const db *d, double resolution, int what,
                 mpb_verdict *verdicts)
{
    mpb_stage_measure m;
    for (int i = 0; i < d->num_stages; i++) {
        const stage *s = &d->stages[i];
        const query *q = s->q;
        mpb_world *w = q->world->w;
        int nj = q->num_joints;
        mpb_goal goal = mpb_query_goal(q->goal_kind, q->goal_joints,
                                       q->tolerance, q->goal_link,
                                       q->goal_region);
        if (what == VERIFY || what == BOTH) {
            mpb_measure_stage(w, q->start, q->tolerance, &goal, s->wp, s->n,
                              nj, 0, resolution,
                              what == VERIFY ? MPB_MEASURE_NO_METRICS : 0,
                              &m);
            verdicts[i] = m.verdict;
        } else {
            m.verdict.code = MPB_VERDICT_VALID;
            mpb_measure_metrics(w, s->wp, s->n, nj, 0, resolution, &m);
        }
        for (int k = 0; k < m.num_metrics; k++)
            sink += m.metrics[k].value;
    }
}

typedef struct timing {
    double wall, cpu;   /* s per pass */
    long   passes;
} timing;

static timing timed(const db *d, double resolution, int what, double secs,
                    mpb_verdict *verdicts)
{
    pass(d, resolution, what, verdicts);   /* warm */
    double t0 = mpbb_now(), c0 = cpu_now(), t;
    long r = 0;
    do {
        pass(d, resolution, what, verdicts);
        r++;
        t = mpbb_now();
    } while (t - t0 < secs);
    timing out = {(t - t0) / (double)r, (cpu_now() - c0) / (double)r, r};
    return out;
}

/* Stage i as mpbenchd measures it: its time, its waypoint times. */
static void measure_as_stored(const db *d, int i, double resolution,
                              mpb_stage_measure *m)
{
    const stage *s = &d->stages[i];
    const query *q = s->q;
    mpb_goal goal = mpb_query_goal(q->goal_kind, q->goal_joints,
                                   q->tolerance, q->goal_link,
                                   q->goal_region);
    mpb_measure_stage_timed(q->world->w, q->start, q->tolerance, &goal,
                            s->wp, s->times, s->n, q->num_joints, s->time,
                            resolution, 0, m);
}

/*
 * --compare-stored: every stage measured once as mpbenchd does, its
 * verdict (name, detail, how it was checked) against what the database
 * holds, one line per difference; every metric into dump (when not
 * NULL) as run|stage|name|value. Returns how many verdicts differ.
 */
static int compare_stored(const db *d, double resolution, FILE *dump,
                          const char *label)
{
    int differ = 0, metrics = 0;
    mpb_stage_measure m;
    for (int i = 0; i < d->num_stages; i++) {
        const stage *s = &d->stages[i];
        measure_as_stored(d, i, resolution, &m);
        const char *name = mpb_verdict_name(m.verdict.code);
        const char *how = mpb_verdict_verification(&m.verdict);
        int bad = 0;
        if (strcmp(name, s->stored) != 0 ||
            strcmp(m.verdict.detail, s->stored_detail) != 0 ||
            strcmp(how ? how : "", s->stored_verification) != 0) {
            printf("  run %lld stage %s: stored %s (%s, %s), now %s (%s, "
                   "%s)\n", (long long)s->run_id, s->name, s->stored,
                   s->stored_detail, s->stored_verification, name,
                   m.verdict.detail, how ? how : "");
            bad = 1;
        }
        for (int k = 0; dump != NULL && k < m.num_metrics; k++)
            fprintf(dump, "%lld|%s|%s|%.17g\n", (long long)s->run_id,
                    s->name, m.metrics[k].name, m.metrics[k].value);
        metrics += m.num_metrics;
        differ += bad;
    }
    printf("%s: %d of %d stages have another verdict than the stored one "
           "(%d metrics measured)\n", label, differ, d->num_stages, metrics);
    mpbb_result("verify_compare_stored stages=%d differ=%d metrics=%d",
                d->num_stages, differ, metrics);
    return differ;
}

static int by_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/*
 * --per-run: the CPU time of each run's verification and metrics, all
 * its stages as mpbenchd measures them (the mean of reps passes over the
 * run after one to warm), and their median, 10th and 90th percentile,
 * mean and largest, ms.
 */
static void per_run(const db *d, double resolution, long reps,
                    const char *key)
{
    double *ms = xcalloc((size_t)d->num_stages + 1, sizeof *ms);
    int runs = 0;
    long waypoints = 0;
    mpb_stage_measure m;
    for (int i = 0; i < d->num_stages;) {
        int j = i;
        while (j < d->num_stages && d->stages[j].run_id == d->stages[i].run_id)
            j++;
        for (int k = i; k < j; k++)
            measure_as_stored(d, k, resolution, &m);
        double c0 = cpu_now();
        for (long r = 0; r < reps; r++)
            for (int k = i; k < j; k++) {
                measure_as_stored(d, k, resolution, &m);
                sink += m.num_metrics > 0 ? m.metrics[0].value : 0;
            }
        ms[runs++] = (cpu_now() - c0) / (double)reps * 1e3;
        for (int k = i; k < j; k++)
            waypoints += d->stages[k].n;
        i = j;
    }
    double sum = 0;
    for (int r = 0; r < runs; r++)
        sum += ms[r];
    qsort(ms, (size_t)runs, sizeof *ms, by_double);
    if (runs > 0) {
        double med = runs % 2 ? ms[runs / 2]
                              : (ms[runs / 2 - 1] + ms[runs / 2]) / 2;
        double p10 = ms[(runs - 1) / 10], p90 = ms[(runs - 1) * 9 / 10];
        printf("  per run, CPU time of verification + metrics (ms): median "
               "%.3f, 10th percentile %.3f, 90th %.3f, mean %.3f, max %.3f "
               "(%d runs, %.1f waypoints a run, %ld passes each)\n", med, p10,
               p90, sum / runs, ms[runs - 1], runs,
               (double)waypoints / runs, reps);
        mpbb_result("%s_per_run runs=%d waypoints_per_run=%.1f "
                    "cpu_ms_median=%.4f cpu_ms_p10=%.4f cpu_ms_p90=%.4f "
                    "cpu_ms_mean=%.4f cpu_ms_max=%.4f reps=%ld", key, runs,
                    (double)waypoints / runs, med, p10, p90, sum / runs,
                    ms[runs - 1], reps);
    }
    free(ms);
}

/* Collision checks one verification makes, as bench/verify.c counts
 * them: one at the first waypoint, then ceil(segment / resolution) per
 * segment (continuous joints the short way). */
static double count_checks(const db *d, double resolution)
{
    double checks = 0;
    for (int i = 0; i < d->num_stages; i++) {
        const stage *s = &d->stages[i];
        int nj = s->q->num_joints;
        const unsigned char *wraps = mpb_world_joint_wraps(s->q->world->w);
        checks += 1;
        for (int k = 0; k + 1 < s->n; k++) {
            double sq = 0;
            for (int j = 0; j < nj; j++) {
                double dj = mpb_joint_delta(s->wp[k * nj + j],
                                            s->wp[(k + 1) * nj + j],
                                            wraps ? wraps[j] : 0);
                sq += dj * dj;
            }
            double c = ceil(sqrt(sq) / resolution);
            checks += c < 1 ? 1 : c;
        }
    }
    return checks;
}

/* Every world verifies in the given mode. */
static void set_mode(db *d, int mode)
{
    for (int i = 0; i < d->num_worlds; i++)
        mpb_world_set_verification(d->worlds[i].w, (mpb_verification)mode);
}

static void db_free(db *d)
{
    for (int i = 0; i < d->num_stages; i++) {
        free(d->stages[i].name);
        free(d->stages[i].stored);
        free(d->stages[i].stored_detail);
        free(d->stages[i].stored_verification);
        free(d->stages[i].wp);
        free(d->stages[i].times);
        for (int k = 0; k < d->stages[i].num_metrics; k++)
            free(d->stages[i].metric_names[k]);
        free(d->stages[i].metric_names);
        free(d->stages[i].metric_values);
    }
    free(d->stages);
    for (int i = 0; i < d->num_worlds; i++)
        mpb_world_close(d->worlds[i].w);
    free(d->worlds);
    for (int i = 0; i < d->num_queries; i++) {
        query *q = &d->queries[i];
        free(q->name);
        free(q->joint_names);
        free(q->held);
        free(q->start);
        free(q->goal_joints);
        free(q->goal_link);
    }
    free(d->queries);
    for (int i = 0; i < d->num_scenes; i++) {
        scene *sc = &d->scenes[i];
        free(sc->name);
        free(sc->robot_format);
        free(sc->robot);
        free(sc->scene_format);
        free(sc->scene);
    }
    free(d->scenes);
    free(d->runs);
    mpb_store_close(d->s);
}

static int parse_double(const char *v, double *out)
{
    char *end;
    *out = strtod(v, &end);
    return end != v && *end == '\0' && *out > 0 && isfinite(*out);
}

int main(int argc, char **argv)
{
    const char *path = NULL, *robot_dir = NULL, *key = "verify_db";
    const char *label = NULL;
    double resolution = 0, secs = 1;
    int64_t experiment = 0;
    long reps = 1, run_reps = 0;
    const char *compare = NULL;
    int modes[2] = {MPB_VERIFY_CERTIFIED, MPB_VERIFY_SAMPLED}, num_modes = 1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            return 0;
        }
        if (v == NULL) {
            fprintf(stderr, PROG ": '%s' wants a value (see --help)\n", a);
            return 2;
        }
        i++;
        int ok = 1, known = 1;
        if (strcmp(a, "--db") == 0) path = v;
        else if (strcmp(a, "--robot-dir") == 0) robot_dir = v;
        else if (strcmp(a, "--key") == 0) key = v;
        else if (strcmp(a, "--label") == 0) label = v;
        else if (strcmp(a, "--seconds") == 0) ok = parse_double(v, &secs);
        else if (strcmp(a, "--compare-stored") == 0) compare = v;
        else if (strcmp(a, "--per-run") == 0) {
            char *end;
            run_reps = strtol(v, &end, 10);
            ok = end != v && *end == '\0' && run_reps > 0;
        } else if (strcmp(a, "--reps") == 0) {
            char *end;
            reps = strtol(v, &end, 10);
            ok = end != v && *end == '\0' && reps > 0;
        } else if (strcmp(a, "--verification") == 0) {
            num_modes = strcmp(v, "both") == 0 ? 2 : 1;
            if (strcmp(v, "sampled") == 0)
                modes[0] = MPB_VERIFY_SAMPLED;
            else if (strcmp(v, "certified") != 0 && num_modes == 1) {
                fprintf(stderr, PROG ": --verification wants certified, "
                        "sampled or both, not '%s'\n", v);
                return 2;
            }
        }
        else if (strcmp(a, "--resolution") == 0)
            ok = parse_double(v, &resolution);
        else if (strcmp(a, "--experiment") == 0) {
            char *end;
            long long id = strtoll(v, &end, 10);
            ok = end != v && *end == '\0' && id > 0;
            experiment = id;
        } else
            known = 0;
        if (!known) {
            fprintf(stderr, PROG ": unknown argument '%s' (see --help)\n", a);
            return 2;
        }
        if (!ok) {
            fprintf(stderr, PROG ": %s wants a number more than 0, not "
                    "'%s'\n", a, v);
            return 2;
        }
    }
    if (path == NULL) {
        fprintf(stderr, PROG ": wants --db FILE (see --help)\n");
        return 2;
    }
    db d = {.path = path};
    if (mpb_store_open(path, 1, &d.s) != MPB_OK) {
        fprintf(stderr, PROG ": %s\n",
                d.s ? mpb_store_errmsg(d.s) : "out of memory");
        mpb_store_close(d.s);
        return 1;
    }
    int status = 1;
    if (experiment == 0 &&
        mpb_store_experiment_latest(d.s, &experiment) != MPB_OK) {
        fprintf(stderr, PROG ": %s: no experiment in the database\n", path);
        goto out;
    }
    double stored_res = 0;
    if (mpb_store_experiment_resolution(d.s, experiment, &stored_res) !=
            MPB_OK) {
        fprintf(stderr, PROG ": %s: no experiment %lld\n", path,
                (long long)experiment);
        goto out;
    }
    if (resolution == 0)
        resolution = stored_res > 0 ? stored_res : DEFAULT_RESOLUTION;
    double open_secs = 0;
    if (load(&d, experiment, robot_dir, &open_secs) != 0)
        goto out;

    if (compare != NULL || run_reps > 0) {
        set_mode(&d, modes[0]);
        status = 0;
        FILE *dump = compare && strcmp(compare, "-") != 0
            ? fopen(compare, "w") : NULL;
        if (compare && strcmp(compare, "-") != 0 && dump == NULL) {
            fprintf(stderr, PROG ": %s: cannot write\n", compare);
            status = 1;
            goto out;
        }
        if (compare != NULL &&
            compare_stored(&d, resolution, dump, label ? label : path))
            status = 1;
        if (dump != NULL && fclose(dump) != 0) {
            fprintf(stderr, PROG ": %s: cannot write\n", compare);
            status = 1;
        }
        if (run_reps > 0)
            per_run(&d, resolution, run_reps, key);
        goto out;
    }
    double checks = count_checks(&d, resolution);
    double n = (double)d.waypoints;
    printf("%s, experiment %lld, resolution %.3g: %d runs with stages (of %d finished), "
           "%d stages, %ld waypoints (%.1f collision checks per waypoint)",
           label ? label : path, (long long)experiment, resolution, d.runs_with_stages,
           d.num_runs, d.num_stages, d.waypoints, checks / n);
    if (d.skipped)
        printf("; %d stages without whole waypoints left out", d.skipped);
    printf("\n  worlds: %d opened in %.3f s (%.1f ms each), not timed below\n",
           d.num_worlds, open_secs, open_secs / d.num_worlds * 1e3);

    /* Once per mode, untimed: the verdicts, against the stored ones. */
    mpb_verdict *verdicts = xcalloc((size_t)d.num_stages, sizeof *verdicts);
    int same[2] = {0, 0}, valid[2] = {0, 0}, proved[2] = {0, 0};
    for (int m = 0; m < num_modes; m++) {
        set_mode(&d, modes[m]);
        pass(&d, resolution, VERIFY, verdicts);
        for (int i = 0; i < d.num_stages; i++) {
            const char *name = mpb_verdict_name(verdicts[i].code);
            same[m] += strcmp(name, d.stages[i].stored) == 0;
            valid[m] += verdicts[i].code == MPB_VERDICT_VALID;
            proved[m] += verdicts[i].certified;
        }
    }
    /* Interleaved: every measurement of one mode, then of the other. */
    timing t[2][NUM_WHAT] = {{{0, 0, 0}}};
    for (long r = 0; r < reps; r++)
        for (int m = 0; m < num_modes; m++) {
            set_mode(&d, modes[m]);
            for (int what = 0; what < NUM_WHAT; what++) {
                timing one = timed(&d, resolution, what, secs, verdicts);
                t[m][what].wall += one.wall / (double)reps;
                t[m][what].cpu += one.cpu / (double)reps;
                t[m][what].passes += one.passes;
            }
        }
    for (int m = 0; m < num_modes; m++) {
        const char *mode = mpb_verification_name((mpb_verification)modes[m]);
        const timing *tm = t[m];
        printf("%s verification:\n", mode);
        printf("  verdicts: %d of %d as stored, %d valid, %d certified\n",
               same[m], d.num_stages, valid[m], proved[m]);
        printf("  verify + metrics %10.0f waypoints/s (%.2f us per waypoint; "
               "CPU time %.0f/s), %ld passes\n", n / tm[BOTH].wall,
               tm[BOTH].wall / n * 1e6, n / tm[BOTH].cpu, tm[BOTH].passes);
        printf("  verify only      %10.0f waypoints/s (CPU time %.0f/s), "
               "%.0f collision checks/s\n", n / tm[VERIFY].wall,
               n / tm[VERIFY].cpu, checks / tm[VERIFY].wall);
        printf("  metrics only     %10.0f waypoints/s (CPU time %.0f/s)\n",
               n / tm[METRICS].wall, n / tm[METRICS].cpu);
        char k[256];
        if (num_modes > 1)
            snprintf(k, sizeof k, "%s_%s", key, mode);
        else
            snprintf(k, sizeof k, "%s", key);
        mpbb_result("%s verification=%s runs=%d finished=%d stages=%d "
                    "waypoints=%ld resolution=%g checks_per_waypoint=%.2f "
                    "same_verdicts=%d valid=%d certified=%d worlds=%d "
                    "world_open_s=%.3f wps=%.0f verify_wps=%.0f "
                    "metrics_wps=%.0f cpu_wps=%.0f cpu_verify_wps=%.0f "
                    "cpu_metrics_wps=%.0f reps=%ld passes=%ld",
                    k, mode, d.runs_with_stages, d.num_runs, d.num_stages,
                    d.waypoints, resolution, checks / n, same[m], valid[m],
                    proved[m], d.num_worlds, open_secs, n / tm[BOTH].wall,
                    n / tm[VERIFY].wall, n / tm[METRICS].wall,
                    n / tm[BOTH].cpu, n / tm[VERIFY].cpu,
                    n / tm[METRICS].cpu, reps, tm[BOTH].passes);
    }
    free(verdicts);
    status = 0;
out:
    db_free(&d);
    return status;
}
