/*
 * main.c - mpbenchd: options, signals, setting up the experiment in the
 * store, and the single-threaded poll loop that drives everything else.
 */
#include <errno.h>
#include <math.h>
#include <getopt.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "daemon.h"

static volatile sig_atomic_t stop_signal;

static void on_signal(int sig)
{
    stop_signal = sig;
}

static void usage(FILE *out)
{
    fprintf(out,
"usage: mpbenchd [options] EXPERIMENT.yaml\n"
"\n"
"Runs a motion-planning benchmark: sends the experiment's runs over LCM to\n"
"the planner processes that offer its algorithms, verifies and measures every\n"
"trajectory they return, and stores everything in an SQLite database. Exits\n"
"when every run is done. Started again on the same database, it resumes an\n"
"unfinished experiment of the same name and file content, unless its robot\n"
"or scene files have changed since; on a complete one, it says so and exits\n"
"0 without running anything (--again runs it once more).\n"
"\n"
"options:\n"
"  -d, --db PATH         database file (default: mpbench.db)\n"
"  -u, --lcm-url URL     LCM URL (default: " MPB_DEFAULT_LCM_URL ")\n"
"  -r, --resolution RAD  every segment is proved free of collisions; where\n"
"                        a proof cannot finish (or with verification:\n"
"                        sampled) it is sampled at this joint-space step,\n"
"                        as the end-effector path length is (default:\n"
"                        0.01, at most 0.1); kept with the experiment,\n"
"                        which resumes only at the same step\n"
"      --secret-file F   authenticate every message with the shared secret in\n"
"                        F (planners need the same file); messages without\n"
"                        the right tag are rejected\n"
"      --new             start a new experiment even if one can be resumed\n"
"      --again           if the experiment is complete, run it once more as a\n"
"                        new experiment (an unfinished one is resumed)\n"
"      --check           check the experiment file and exit\n"
"      --mesh-path       print the folder planners need in MPB_MESH_PATH to\n"
"                        find the robot's meshes as mpbenchd does (its URDF's\n"
"                        folder), and exit\n"
"      --list-planners   print the planner families the experiment names\n"
"                        (its configurations' planner:), one per line, and\n"
"                        exit\n"
"      --replay LOG      rebuild the experiment's results from LOG, an\n"
"                        lcm-logger log of a live run, into a new experiment\n"
"                        in the database; plans nothing, sends nothing\n"
"                        (docs/record-and-replay.md)\n"
"      --backlog N       send no request while N results await verification\n"
"                        (default %d; 0: no bound by count) ...\n"
"      --backlog-mb MB   ... or while they hold MB megabytes (default %d;\n"
"                        0: no bound by size); requests go again as they\n"
"                        drain, so memory stays bounded\n"
"      --verify-threads N\n"
"                        verify and measure results in N threads, each with\n"
"                        its own copy of the scenes' worlds (default: this\n"
"                        host's cores less one, at least 1; here %d)\n"
"  -v, --verbose         log every run\n"
"  -h, --help            show this help\n"
"\n"
"The experiment file format is described in docs/experiment-format.md.\n",
            MPBD_BACKLOG_RESULTS, MPBD_BACKLOG_MB,
            mpbd_verifier_threads_default());
}

typedef struct options {
    const char *db, *lcm_url, *experiment, *secret_file;
    const char *replay;              /* --replay LOG, or NULL */
    double resolution;
    long backlog, backlog_mb;
    int verify_threads;
    int fresh, again, check, verbose, mesh_path, list_planners;
} options;

static int parse_options(int argc, char **argv, options *o)
{
    static const struct option longopts[] = {
        {"db", required_argument, NULL, 'd'},
        {"lcm-url", required_argument, NULL, 'u'},
        {"resolution", required_argument, NULL, 'r'},
        {"new", no_argument, NULL, 'N'},
        {"again", no_argument, NULL, 'A'},
        {"secret-file", required_argument, NULL, 'S'},
        {"check", no_argument, NULL, 'C'},
        {"mesh-path", no_argument, NULL, 'M'},
        {"list-planners", no_argument, NULL, 'L'},
        {"replay", required_argument, NULL, 'R'},
        {"backlog", required_argument, NULL, 'B'},
        {"backlog-mb", required_argument, NULL, 'b'},
        {"verify-threads", required_argument, NULL, 'T'},
        {"verbose", no_argument, NULL, 'v'},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    int c;
    char *end;
    *o = (options){.db = "mpbench.db", .lcm_url = MPB_DEFAULT_LCM_URL,
                   .resolution = 0.01, .backlog = MPBD_BACKLOG_RESULTS,
                   .backlog_mb = MPBD_BACKLOG_MB,
                   .verify_threads = mpbd_verifier_threads_default()};
    opterr = 0;     /* one line of our own for a bad option, below */
    while ((c = getopt_long(argc, argv, ":d:u:r:vh", longopts, NULL)) != -1) {
        switch (c) {
        case 'd': o->db = optarg; break;
        case 'u': o->lcm_url = optarg; break;
        case 'r':
            o->resolution = strtod(optarg, &end);
            if (end == optarg || *end != '\0' || !(o->resolution > 0) ||
                o->resolution > MPBD_RESOLUTION_MAX) {
                fprintf(stderr, "mpbenchd: --resolution must be a number of "
                                "radians > 0 and <= %g, not '%s'\n",
                        MPBD_RESOLUTION_MAX, optarg);
                return -1;
            }
            break;
        case 'B':
        case 'b': {
            long v = strtol(optarg, &end, 10);
            if (end == optarg || *end != '\0' || v < 0 || v > 100000000L) {
                fprintf(stderr, "mpbenchd: %s must be a whole number from 0 "
                                "to 100000000, not '%s'\n",
                        c == 'B' ? "--backlog" : "--backlog-mb", optarg);
                return -1;
            }
            *(c == 'B' ? &o->backlog : &o->backlog_mb) = v;
            break;
        }
        case 'T': {
            long v = strtol(optarg, &end, 10);
            if (end == optarg || *end != '\0' || v < 1 || v > MPBD_VERIFY_THREADS_MAX) {
                fprintf(stderr, "mpbenchd: --verify-threads must be a whole "
                                "number from 1 to %d, not '%s'\n",
                        MPBD_VERIFY_THREADS_MAX, optarg);
                return -1;
            }
            o->verify_threads = (int)v;
            break;
        }
        case 'N': o->fresh = 1; break;
        case 'A': o->again = 1; break;
        case 'S': o->secret_file = optarg; break;
        case 'C': o->check = 1; break;
        case 'M': o->mesh_path = 1; break;
        case 'L': o->list_planners = 1; break;
        case 'R': o->replay = optarg; break;
        case 'v': o->verbose = 1; break;
        case 'h': usage(stdout); exit(0);
        case ':':
            fprintf(stderr, "mpbenchd: %s needs a value (try 'mpbenchd "
                            "--help')\n", argv[optind - 1]);
            return -1;
        default:
            fprintf(stderr, "mpbenchd: unknown option '%s' (try 'mpbenchd "
                            "--help')\n", argv[optind - 1]);
            return -1;
        }
    }
    if (optind != argc - 1) {
        fprintf(stderr, "mpbenchd: expected one experiment file\n"
                        "Try 'mpbenchd --help'.\n");
        return -1;
    }
    o->experiment = argv[optind];
    return 0;
}

/* At most MPBD_RUNS_TOTAL_MAX: the loader checks it. */
static int64_t count_runs(const mpbd_experiment *e)
{
    int64_t n = 0;
    for (int c = 0; c < e->num_configs; c++)
        n += (int64_t)e->configs[c].runs * e->num_queries;
    return n;
}

/* An experiment to resume must go on being verified at the step its
 * first runs were: a report cannot tell apart runs checked at two
 * resolutions. 0 if it may be resumed. */
static int resolution_differs(mpbd *d, const char *db, int64_t id)
{
    double was = 0.0;
    int rc = mpb_store_experiment_resolution(d->store, id, &was);
    if (rc == MPB_OK && (was == 0.0 || was == d->resolution))
        return 0;
    if (rc != MPB_OK)
        fprintf(stderr, "mpbenchd: %s: %s\n", db, mpb_store_errmsg(d->store));
    else
        fprintf(stderr, "mpbenchd: %s: experiment '%s' (id %lld) is verified at "
                "--resolution %g, not %g: resume it with that, or start a new "
                "one with --new\n", db, d->exp->name, (long long)id, was,
                d->resolution);
    return 1;
}

typedef struct input_check {
    const mpbd_experiment *e;
    const char *db;
    int64_t     id;
    int         differs;
} input_check;

/* Whether two robot texts differ in their URDF (mpb_robot_text_split()):
 * 0 when only the SRDF that follows it differs. */
static int urdf_part_differs(const char *a, const char *b)
{
    size_t la, lb, sa, sb;
    if (mpb_robot_text_split(a, &la, &sa) != MPB_OK ||
        mpb_robot_text_split(b, &lb, &sb) != MPB_OK)
        return 1;
    return la != lb || memcmp(a, b, la) != 0;
}

/* The experiment file names its robot and scene files; their text is not
 * part of its hash, so an edit to one of them since the experiment began is
 * found here, scene by scene, against what the database keeps. */
static int compare_scene(void *ud, const mpb_scene_row *row)
{
    input_check *ic = ud;
    const mpbd_experiment *e = ic->e;
    for (int i = 0; i < e->num_scenes; i++) {
        const mpbd_scene *sc = &e->scenes[i];
        if (strcmp(sc->name, row->name) != 0)
            continue;
        const char *what = NULL, *file = NULL;
        if (strcmp(sc->robot_hash, row->robot_hash) != 0) {
            what = "robot", file = e->robot_file;
            if (e->srdf_file != NULL && row->robot != NULL &&
                !urdf_part_differs(sc->robot, row->robot))
                what = "robot SRDF", file = e->srdf_file;
        } else if (strcmp(sc->scene_hash, row->scene_hash) != 0) {
            what = "scene", file = sc->scene_file;
        } else if ((sc->seen == NULL) != (row->seen_hash == NULL) ||
                   (sc->seen != NULL &&
                    strcmp(sc->seen_hash, row->seen_hash) != 0)) {
            what = "seen scene";
        }
        if (what == NULL)
            return 0;
        fprintf(stderr, "mpbenchd: %s: experiment '%s' (id %lld) began with "
                "another %s for scene '%s'%s%s%s: restore it to resume, or "
                "start a new experiment with --new\n", ic->db, e->name,
                (long long)ic->id, what, sc->name, file ? " (" : "",
                file ? file : "", file ? " has changed since)" : "");
        ic->differs = 1;
        return 1;
    }
    return 0;
}

/*
 * Whether the unfinished experiment this file would resume may be resumed:
 * 0 if so, or if there is none. One whose file has changed is not resumed
 * (a new experiment begins), and that is said, so that its runs are not
 * thought lost.
 */
static int cannot_resume(mpbd *d, const char *db)
{
    int64_t id;
    mpbd_experiment *e = d->exp;
    int rc = mpb_store_experiment_find_unfinished(d->store, e->name, e->hash, &id);
    if (rc == MPB_ENOTFOUND) {
        if (mpb_store_experiment_find_unfinished(d->store, e->name, NULL,
                                                 &id) == MPB_OK)
            mpbd_log("experiment '%s' (id %lld) is unfinished, but its file "
                     "has changed since: a new one begins (the file as it "
                     "was resumes the old one)", e->name, (long long)id);
        return 0;
    }
    if (rc != MPB_OK) {
        fprintf(stderr, "mpbenchd: %s: %s\n", db, mpb_store_errmsg(d->store));
        return 1;
    }
    if (resolution_differs(d, db, id))
        return 1;
    input_check ic = {e, db, id, 0};
    rc = mpb_store_scenes(d->store, id, compare_scene, &ic);
    if (rc != MPB_OK && !ic.differs) {
        fprintf(stderr, "mpbenchd: %s: %s\n", db, mpb_store_errmsg(d->store));
        return 1;
    }
    return ic.differs;
}

typedef struct complete_find {
    const mpbd_experiment *e;
    int64_t id;
    double finished;
} complete_find;

static int find_complete(void *ud, const mpb_experiment_row *row)
{
    complete_find *cf = ud;
    if (strcmp(row->name, cf->e->name) == 0 && row->config_hash != NULL &&
        strcmp(row->config_hash, cf->e->hash) == 0 && !isnan(row->finished)) {
        cf->id = row->id;       /* in id order: the newest, at the end */
        cf->finished = row->finished;
    }
    return 0;
}

/*
 * 1 if this file's experiment is complete in the database and none of it
 * is unfinished: said in one line, for the caller to exit 0 having run
 * nothing. -1 on a database error (said too), else 0.
 */
static int complete_already(mpbd *d, const char *db)
{
    int64_t id;
    complete_find cf = {d->exp, 0, 0.0};
    int rc = mpb_store_experiment_find_unfinished(d->store, d->exp->name,
                                                  d->exp->hash, &id);
    if (rc == MPB_OK)
        return 0;
    if (rc == MPB_ENOTFOUND)
        rc = mpb_store_experiments(d->store, find_complete, &cf);
    if (rc != MPB_OK) {
        fprintf(stderr, "mpbenchd: %s: %s\n", db, mpb_store_errmsg(d->store));
        return -1;
    }
    if (cf.id == 0)
        return 0;
    mpb_run_counts c = {0};
    mpb_store_run_counts(d->store, cf.id, &c);
    char when[32] = "";
    time_t t = (time_t)cf.finished;
    struct tm tm;
    if (localtime_r(&t, &tm) != NULL)
        strftime(when, sizeof when, "%Y-%m-%d %H:%M", &tm);
    printf("mpbenchd: %s: experiment '%s' (id %lld) is complete: %d runs, "
           "%d succeeded, %d crashed, finished %s; nothing to do (--again "
           "runs it once more)\n", db, d->exp->name, (long long)cf.id,
           c.total, c.succeeded, c.crashed, when);
    return 1;
}

/* Runs not done, as a resume counts them: the database's count, which a
 * transaction that failed left as it was (a result stored in it is not
 * done); in memory if the database cannot tell. */
static long runs_left(mpbd *d)
{
    mpb_run_counts c;
    if (mpb_store_run_counts(d->store, d->experiment_id, &c) == MPB_OK)
        return (long)c.total - c.done;
    return d->runs.total_pending + d->runs.num_flights + mpbd_acks_due(d) +
           mpbd_verifier_pending(d);
}

/* Everything the experiment is made of, written idempotently: a resumed
 * experiment takes the same path and finds its rows already there. */
static int setup_experiment(mpbd *d, int fresh)
{
    mpbd_experiment *e = d->exp;
    mpb_store *s = d->store;
    int rc, max_runs = 0;
    mpb_experiment_info info = {
        .name = e->name, .config_file = e->file, .config_hash = e->hash,
        .config_text = e->text, .runs_per_query = e->runs,
        .time_limit = e->time_limit, .memory_limit = e->memory_limit,
    };

    if ((rc = mpb_store_begin(s)) != MPB_OK)
        return rc;
    rc = fresh ? MPB_ENOTFOUND
               : mpb_store_experiment_find_unfinished(s, e->name, e->hash,
                                                      &d->experiment_id);
    if (rc == MPB_OK)
        mpbd_log("resuming experiment '%s' (id %lld)", e->name,
                 (long long)d->experiment_id);
    else if (rc == MPB_ENOTFOUND &&
             (rc = mpb_store_experiment_create(s, &info, &d->experiment_id)) == MPB_OK)
        rc = mpb_store_experiment_set_resolution(s, d->experiment_id,
                                                 d->resolution);
    for (int i = 0; rc == MPB_OK && i < e->num_configs; i++) {
        mpbd_config *c = &e->configs[i];
        rc = mpb_store_planner_config_add(s, d->experiment_id, c->name,
                                          c->planner, c->algorithm,
                                          c->params_text, &c->db_id);
        /* The file's approach stands over any a planner announces. */
        if (rc == MPB_OK && c->approach != NULL) {
            rc = mpb_store_planner_config_set_approach(s, c->db_id,
                                                       c->approach, 0);
            c->approach_known = 1;
        }
        if (c->runs > max_runs)
            max_runs = c->runs;
    }
    for (int i = 0; rc == MPB_OK && i < e->num_scenes; i++) {
        mpbd_scene *sc = &e->scenes[i];
        mpb_scene_info si = {
            .name = sc->name,
            .robot_format = sc->robot_format, .robot_hash = sc->robot_hash,
            .robot = sc->robot, .scene_format = sc->scene_format,
            .scene_hash = sc->scene_hash, .scene = sc->scene,
        };
        rc = mpb_store_scene_add(s, d->experiment_id, &si, &sc->db_id);
        if (rc == MPB_OK && sc->problem_set != NULL)
            rc = mpb_store_scene_set_problem_set(s, sc->db_id,
                                                 sc->problem_set);
        if (rc == MPB_OK && sc->seen != NULL) {
            mpb_seen_scene seen = {sc->seen_format, sc->seen_hash, sc->seen,
                                   sc->seen_how};
            rc = mpb_store_scene_set_seen(s, sc->db_id, &seen);
        }
    }
    for (int i = 0; rc == MPB_OK && i < e->num_queries; i++) {
        mpbd_query *q = &e->queries[i];
        double region[12];
        mpbd_query_region(q, region);
        int is_region = q->goal_kind == MPB_GOAL_POSE_REGION;
        mpb_query_info qi = {
            .name = q->name, .num_joints = e->num_joints,
            .joint_names = (const char *const *)e->joint_names,
            .start = q->start, .goal_kind = q->goal_kind,
            .goal_joints = q->goal, .goal_tolerance = q->tolerance,
            .goal_link = q->goal_link, .goal_region = is_region ? region : NULL,
        };
        rc = mpb_store_query_add(s, e->scenes[q->scene].db_id, &qi, &q->db_id);
        if (rc == MPB_OK)
            rc = mpb_store_query_set_held(s, q->db_id, e->num_held,
                                          (const char *const *)e->held_names,
                                          q->held);
    }
    /* Repetition first, so that a partial experiment covers every planner
     * and query evenly. */
    for (int r = 0; rc == MPB_OK && r < max_runs; r++)
        for (int q = 0; rc == MPB_OK && q < e->num_queries; q++)
            for (int c = 0; rc == MPB_OK && c < e->num_configs; c++)
                if (r < e->configs[c].runs)
                    rc = mpb_store_run_add(s, d->experiment_id,
                                           e->configs[c].db_id,
                                           e->queries[q].db_id, r,
                                           mpbd_run_seed(e, c, q, r));
    if (rc != MPB_OK) {
        mpb_store_rollback(s);
        return rc;
    }
    return mpb_store_commit(s);
}

/* Wait for the LCM socket to be readable, at most timeout_ms, or for the
 * verifier to finish a result (its pipe, fd2; -1: none). Whether the LCM
 * socket is readable. */
static int wait_readable(int fd, int fd2, int timeout_ms)
{
    struct pollfd pfd[2] = {{.fd = fd, .events = POLLIN},
                            {.fd = fd2, .events = POLLIN}};
    int n = poll(pfd, fd2 >= 0 ? 2 : 1, timeout_ms);
    return n > 0 && (pfd[0].revents & POLLIN);
}

/* How run_loop() ends, besides 0 (every run done) and 1 (a signal). */
enum { LOOP_DB_ERROR = -1, LOOP_DB_GONE = -2, LOOP_NOT_ALONE = -3,
       LOOP_DOOMED = -4, LOOP_HUB_GONE = -5 };

/* The loop, until every run is done, a signal or a database failure;
 * LOOP_DB_GONE says why in gone (cap bytes). */
static int run_loop(mpbd *d, char *gone, size_t cap)
{
    int fd = lcm_get_fileno(d->lcm);
    double now = mpb_monotonic_s(), listen_until = now + MPBD_LISTEN_S;
    const double start = now;
    const long unproven = d->count.unproven;

    mpbd_status_publish(d, "waiting", now);
    while (!stop_signal) {
        double last = now;
        int ready = wait_readable(fd, mpbd_verifier_fd(d), 20);
        now = mpb_monotonic_s();
        /* A round of the loop that took seconds: the daemon was stopped,
         * its machine suspended, or it was busy. It read no message then,
         * so that time is not its planners' silence. */
        if (now - last > MPBD_STALL_S)
            mpbd_scheduler_stalled(d, now - last);
        mpbd_hub_news hub;
        if (mpbd_hub_watch(d, now, now - last > MPBD_STALL_S ? 0 : now - last,
                           &hub))
            return LOOP_HUB_GONE;
        if (hub.relinked)
            mpbd_scheduler_relink(d, now);
        if (hub.away_s > 0)
            mpbd_scheduler_pause(d, hub.away_s);
        /* One transaction: the runs sent last time, then what has arrived
         * (bounded, so that timers still run under a flood). */
        if (mpb_store_begin(d->store) != MPB_OK ||
            mpbd_runs_record_sent(d) != MPB_OK) {
            mpbd_db_error(d);
            mpb_store_rollback(d->store);
            return LOOP_DB_ERROR;
        }
        for (int n = 0; ready && n < 4096; n++) {
            if (lcm_handle(d->lcm) != 0)
                break;
            ready = wait_readable(fd, -1, 0);
        }
        /* The results verified beside the loop, stored in this
         * transaction in the order they were finished (verifier.c). */
        mpbd_verifier_settle(d, MPBD_SETTLE_S);
        mpbd_verifier_collect(d);
        mpbd_planners_expire(d, now);
        mpbd_scheduler_tick(d, now);
        if (mpb_store_commit(d->store) != MPB_OK) {
            mpbd_db_error(d);
            mpb_store_rollback(d->store);
            return LOOP_DB_ERROR;
        }
        d->db_error[0] = '\0';
        if (d->elder[0] != '\0')
            return LOOP_NOT_ALONE;
        if (d->doomed.stop)
            return LOOP_DOOMED;
        /* Then the next requests: a run's latency ends with its commit,
         * not with the next run's request, and each request carries the
         * acknowledgements this commit made true (acks.c). */
        mpbd_acks_flush(d);
        /* A message with the right tag echoing another process, heard
         * while listening: a planner serving another daemon on this URL
         * (or a replay). That daemon's answer to this one's status may
         * be slow in coming on a loaded machine (263 ms seen): listen on
         * through its next periodic status before sending anything. */
        if (now < listen_until && d->count.unproven != unproven)
            listen_until = start + MPBD_STATUS_PERIOD_S + MPBD_LISTEN_S;
        if (now >= listen_until)
            mpbd_scheduler_dispatch(d, now);
        mpbd_owed_send(d, now, 0);
        /* Results written to a file that lost its name are lost: looked
         * at once a status period, and before saying the work is done. */
        int done = mpbd_runs_done(d) && mpbd_verifier_pending(d) == 0;
        if ((done || now - d->last_status >= MPBD_STATUS_PERIOD_S) &&
            mpb_store_check_file(d->store) != MPB_OK) {
            snprintf(gone, cap, "%s", mpb_store_errmsg(d->store));
            return LOOP_DB_GONE;
        }
        if (done)
            return 0;
        if (now - d->last_status >= MPBD_STATUS_PERIOD_S)
            mpbd_status_publish(d, d->num_planners ? "running" : "waiting", now);
    }
    return 1;
}

/* What the daemon added to its runs (with a planner that answers at once):
 * request first sent to result committed. */
static void log_latency(const mpbd *d)
{
    long med = mpbd_latency_quantile_us(&d->acks.latency, 0.5);
    long p99 = mpbd_latency_quantile_us(&d->acks.latency, 0.99);
    if (med < 0)
        return;
    mpbd_log("latency of a run, request sent to result committed: median "
             "%s%ld us, p99 %s%ld us (%llu runs)",
             med >= MPBD_LATENCY_MAX_US ? "over " : "", med,
             p99 >= MPBD_LATENCY_MAX_US ? "over " : "", p99,
             (unsigned long long)d->acks.latency.n);
}

/* A warning about the experiment, on stderr, at --check and at load. */
static void warn_line(void *ud, const char *line)
{
    (void)ud;
    mpbd_log("warning: %s", line);
}

/* --mesh-path and --list-planners: an answer about the experiment file,
 * on stdout; the exit code. */
static int answer_query(const options *o)
{
    char err[1024], dir[4096];
    if (o->mesh_path) {
        if (mpbd_mesh_path(o->experiment, dir, sizeof dir, err, sizeof err)) {
            fprintf(stderr, "mpbenchd: %s\n", err);
            return 1;
        }
        if (dir[0] != '\0')
            printf("%s\n", dir);
        return 0;
    }
    if (mpbd_planner_families(o->experiment, stdout, err, sizeof err)) {
        fprintf(stderr, "mpbenchd: %s\n", err);
        return 1;
    }
    return 0;
}

/* Read and check the whole experiment before touching the database, and
 * say what may surprise about it. -1 to go on, else the exit code (1 on
 * a fault, said on stderr; 0 after --check). */
static int load_experiment(const options *o, mpbd *d)
{
    char err[1024];
    if ((d->exp = mpbd_experiment_load(o->experiment, err, sizeof err)) == NULL) {
        fprintf(stderr, "mpbenchd: %s\n", err);
        return 1;
    }
    /* A request over the bound would be dropped by every planner. */
    if (mpbd_requests_fit(d->exp, o->secret_file != NULL, err, sizeof err) !=
        MPB_OK) {
        fprintf(stderr, "mpbenchd: %s\n", err);
        return 1;
    }
    d->runs_total = (int)count_runs(d->exp);
    if (d->exp->srdf_warning != NULL)
        warn_line(NULL, d->exp->srdf_warning);
    if (mpbd_experiment_acm_note(d->exp, err, sizeof err))
        mpbd_log("%s", err);
    if (mpbd_experiment_moveit_note(d->exp, err, sizeof err))
        mpbd_log("%s", err);
    if (mpbd_experiment_scene_acm_note(d->exp, err, sizeof err))
        warn_line(NULL, err);
    mpbd_warn_thin(d->exp, o->resolution, warn_line, NULL);
    if (mpbd_mesh_note(d->exp, err, sizeof err))
        warn_line(NULL, err);
    if (mpbd_experiment_orientation_note(d->exp, err, sizeof err))
        warn_line(NULL, err);
    if (mpbd_experiment_seen_note(d->exp, err, sizeof err))
        mpbd_log("%s", err);
    if (o->check) {
        const mpbd_experiment *e = d->exp;
        printf("%s: ok: %d scene%s, %d quer%s, %d planner configuration%s, "
               "%d run%s\n", o->experiment, e->num_scenes,
               e->num_scenes == 1 ? "" : "s", e->num_queries,
               e->num_queries == 1 ? "y" : "ies", e->num_configs,
               e->num_configs == 1 ? "" : "s", d->runs_total,
               d->runs_total == 1 ? "" : "s");
        return 0;
    }
    return -1;
}

/* The secret, the LCM link and the database, claimed for this daemon.
 * -1 to go on, else the exit code; *filtered: the kernel drops what the
 * daemon does not read (lcm_filter.h). */
static int open_links(const options *o, mpbd *d, int *filtered)
{
    char err[1024], host[256] = "";
    int rc;
    if (o->secret_file &&
        mpb_auth_open(o->secret_file, &d->auth, err, sizeof err) != MPB_OK) {
        fprintf(stderr, "mpbenchd: %s\n", err);
        return 1;
    }
    d->resolution = o->resolution;
    d->verbose = o->verbose;
    d->backlog.max = o->backlog;
    d->backlog.bytes_max = (double)o->backlog_mb * 1048576.0;
    gethostname(host, sizeof host - 1);
    mpb_planner_id_make("mpbenchd", host, (long)getpid(), d->daemon_id,
                        sizeof d->daemon_id);

    if (o->replay && mpbd_replay_log_readable(o->replay) != 0)
        return 1;
    /* LCM before the database: a daemon that cannot talk to its planners
     * writes nothing (a replay talks to none). What it subscribes to, and
     * nothing else: its own requests and acknowledgements, and malformed
     * datagrams, are dropped by the kernel, not after a wake-up of LCM's
     * thread (lcm_filter.h). Statuses pass, its own once a second with
     * them, for the other daemons' (daemons.c). */
    static const char *const wanted[] = {MPB_CHANNEL_ANNOUNCE,
                                         MPB_CHANNEL_RESULT, MPB_CHANNEL_ACK,
                                         MPB_CHANNEL_STATUS};
    *filtered = 0;
    if (!o->replay &&
        (d->lcm = mpb_lcm_create(o->lcm_url, wanted, 4, filtered)) == NULL) {
        fprintf(stderr, "mpbenchd: cannot start LCM on %s (%s)\n", o->lcm_url,
                mpb_lcm_url_is_hub(o->lcm_url)
                    ? "a hub's URL is tcpq://HOST:PORT"
                    : "no multicast route? see README");
        return 1;
    }
    /* A hub's link connects in the background: a moment for it now
     * saves a line saying it is not there yet. */
    if (d->lcm != NULL)
        mpb_lcm_hub_wait(d->lcm, 2.0);
    d->db_path = o->db;
    if ((rc = mpb_store_open(o->db, 0, &d->store)) != MPB_OK) {
        fprintf(stderr, "mpbenchd: %s\n", mpb_store_errmsg(d->store));
        return 1;
    }
    /* One daemon per database, whatever its experiment: a second one on
     * the same runs would send each twice. */
    if ((rc = mpb_store_claim(d->store)) != MPB_OK) {
        if (rc == MPB_EBUSY)
            fprintf(stderr, "mpbenchd: %s is in use by another mpbenchd: "
                    "wait for it to end, or give another --db\n", o->db);
        else
            fprintf(stderr, "mpbenchd: %s\n", mpb_store_errmsg(d->store));
        return 1;
    }
    return -1;
}

/* The experiment's rows, new or resumed, and its runs not done loaded.
 * -1 to go on, else the exit code (0: complete already). */
static int prepare_runs(const options *o, mpbd *d)
{
    /* A replay always fills a new experiment of its own. */
    if (!(o->fresh || o->replay) && cannot_resume(d, o->db))
        return 1;
    if (!(o->fresh || o->replay || o->again)) {
        int complete = complete_already(d, o->db);
        if (complete != 0)
            return complete > 0 ? 0 : 1;
    }
    if (setup_experiment(d, o->fresh || o->replay) != MPB_OK) {
        fprintf(stderr, "mpbenchd: %s: %s\n", o->db, mpb_store_errmsg(d->store));
        return 1;
    }
    if (mpbd_runs_load(d) != MPB_OK) {
        fprintf(stderr, "mpbenchd: %s: cannot load runs: %s\n", o->db,
                mpb_store_errmsg(d->store));
        return 1;
    }
    return -1;
}

/* Why the loop ended (run_loop()'s rc), said in the log and the last
 * status; the exit code. */
static int say_why_stopped(const options *o, mpbd *d, int rc, const char *gone,
                           double elapsed)
{
    if (rc == 0) {
        mpb_run_counts counts = {0};
        mpb_store_run_counts(d->store, d->experiment_id, &counts);
        mpbd_status_publish(d, "done", mpb_monotonic_s());
        mpbd_log("experiment '%s' complete: %d runs, %d succeeded, %d crashed "
                 "(%ld rejected messages), %.1f s", d->exp->name, counts.total,
                 counts.succeeded, counts.crashed, d->count.rejected, elapsed);
        return 0;
    }
    mpbd_status_publish(d, "stopped", mpb_monotonic_s());
    if (rc > 0) {
        mpbd_log("stopped by signal %d with %ld runs left; run the same "
                 "command to resume", (int)stop_signal, runs_left(d));
        return 128 + (int)stop_signal;
    }
    if (rc == LOOP_DB_GONE)
        mpbd_log("stopped with %ld runs left: %s",
                 d->runs.total_pending + d->runs.num_flights, gone);
    else if (rc == LOOP_DOOMED)
        mpbd_log("stopped: the first run of every planner configuration "
                 "(%d) failed with the same error, so every run would: "
                 "%s; %ld runs left: fix it and run the same command to "
                 "resume", d->exp->num_configs, d->doomed.why,
                 runs_left(d));
    else if (rc == LOOP_HUB_GONE)
        mpbd_log("stopped: the hub at %s has been away or stalled for "
                 "%.0f s, with "
                 "%ld runs left; run the same command to resume once it "
                 "is back", o->lcm_url, MPBD_HUB_AWAY_MAX_S, runs_left(d));
    else if (rc == LOOP_NOT_ALONE)
        mpbd_log("stopped: another mpbenchd, %s, is on this LCM URL "
                 "(%s), and two would disturb each other's runs: give "
                 "this benchmark its own URL (-u, and the same on its "
                 "planners), or run the same command once the other "
                 "ends", d->elder, o->lcm_url);
    else
        mpbd_log("stopped by a database error with %ld runs left; run "
                 "the same command to resume", runs_left(d));
    return 1;
}

/* The benchmark itself: handlers, signals, the verifier, the loop, and
 * what is left written for a resume. The exit code. */
static int run(const options *o, mpbd *d, int filtered)
{
    /* A resumed experiment's status counts its runs done before, too. */
    mpb_run_counts before = {0};
    if (mpb_store_run_counts(d->store, d->experiment_id, &before) == MPB_OK) {
        d->count.succeeded = before.succeeded;
        d->count.crashed = before.crashed;
        d->count.failed = before.done - before.succeeded - before.crashed;
    }
    mpbd_announce_subscribe(d);
    mpbd_scheduler_subscribe(d);
    mpbd_results_subscribe(d);
    mpbd_daemons_subscribe(d);
    if (d->lcm != NULL && !filtered)
        mpbd_log("%s", MPB_LCM_UNFILTERED);

    struct sigaction sa = {.sa_handler = on_signal};
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    signal(SIGPIPE, SIG_IGN);

    d->started = mpb_monotonic_s();
    d->started_utime = mpb_utime_now();
    /* Planners announce within a heartbeat: say nothing of waiting before. */
    d->last_wait_log = d->started - 4.0;
    mpbd_log("experiment '%s' (id %lld): %ld of %d runs to do, database %s",
             d->exp->name, (long long)d->experiment_id, d->runs.total_pending,
             d->runs_total, o->db);
    if (mpbd_verifier_start(d, o->verify_threads) != MPB_OK)
        mpbd_log("cannot start the verification threads: results are "
                 "verified in the loop");
    else if (o->verify_threads > 1)
        mpbd_log("verifying in %d threads, each with its own copy of the "
                 "%d scene world%s", o->verify_threads, d->exp->num_scenes,
                 d->exp->num_scenes == 1 ? "" : "s");
    char gone[256] = "";
    int rc = run_loop(d, gone, sizeof gone);
    /* Results not stored yet are dropped: their runs stay sent, and a
     * resume runs them again, as after a crash. */
    mpbd_verifier_stop(d);
    mpbd_owed_send(d, 0.0, 1);     /* no more requests to ride on */
    /* Runs in flight keep their ids for a resume. */
    if (d->runs.num_unrecorded > 0 &&
        (mpb_store_begin(d->store) != MPB_OK ||
         mpbd_runs_record_sent(d) != MPB_OK ||
         mpb_store_commit(d->store) != MPB_OK)) {
        mpbd_db_error(d);
        mpb_store_rollback(d->store);
    }
    double elapsed = mpb_monotonic_s() - d->started;
    log_latency(d);
    if (rc == 0 && mpb_store_experiment_finish(d->store, d->experiment_id) != MPB_OK) {
        mpbd_db_error(d);
        rc = LOOP_DB_ERROR;
    }
    return say_why_stopped(o, d, rc, gone, elapsed);
}

/* Everything d holds, released in the reverse order of its making. */
static void release(mpbd *d)
{
    if (d->lcm) {
        if (d->sub_announce)
            lcm_unsubscribe(d->lcm, d->sub_announce);
        if (d->sub_ack)
            lcm_unsubscribe(d->lcm, d->sub_ack);
        if (d->sub_result)
            lcm_unsubscribe(d->lcm, d->sub_result);
        if (d->sub_status)
            lcm_unsubscribe(d->lcm, d->sub_status);
        mpb_lcm_destroy(d->lcm);
    }
    mpbd_acks_free(d);
    mpbd_doomed_free(d);
    mpbd_runs_free(d);
    mpbd_planners_free(d);
    mpb_store_close(d->store);
    mpbd_experiment_free(d->exp);
    mpb_auth_close(d->auth);
}

int main(int argc, char **argv)
{
    options o;
    mpbd d = {0};
    int filtered = 0, code;

    if (parse_options(argc, argv, &o) != 0)
        return 2;
    if (o.mesh_path || o.list_planners)
        return answer_query(&o);
    if ((code = load_experiment(&o, &d)) < 0 &&
        (code = open_links(&o, &d, &filtered)) < 0 &&
        (code = prepare_runs(&o, &d)) < 0) {
        if (mpbd_acks_init(&d) != MPB_OK)
            mpbd_log("out of memory for the latency count: not counted");
        code = o.replay ? (mpbd_replay(&d, o.replay) == 0 ? 0 : 1)
                        : run(&o, &d, filtered);
    }
    release(&d);
    return code;
}
