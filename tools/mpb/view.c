/*
 * view.c - `mpb view`: one run drawn in 3-D in a self-contained HTML page.
 * Reads the run, its scene and query back, opens the world the verifier
 * checked it in, computes the pose of every moving body at every frame of
 * every stage (libmpbench's forward kinematics), finds where a collision
 * verdict stopped and which two bodies touch there, and hands all that to
 * view_page.c, which writes the page with three.js inlined.
 */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "view.h"

#define CMD "view"

/* Stages with fewer waypoints than this get samples between them, so that
 * the slider and the play button move the robot smoothly. */
#define SMOOTH_FRAMES 240

/* The verifier's step when the database does not say (mpbenchd -r). */
#define DEFAULT_RESOLUTION 0.01

#define THREE_JS_NAME "three.module.min.js"

static void usage(FILE *out)
{
    fprintf(out,
        "usage: mpb view [-o FILE] DB RUN\n"
        "       mpb view [-o PATH] [-e ID] [-s SCENE] [-q QUERY] [-p PLANNER]\n"
        "                [--failed] DB\n"
        "\n"
        "Draw run RUN (its id in the database DB, as the results view gives\n"
        "it) in 3-D: one self-contained HTML file that opens in a browser\n"
        "offline, without mpbench. It shows the scene and the robot with the\n"
        "geometry the verifier checks (primitives and meshes), the start, the\n"
        "goal (the robot at a joint goal, or a goal region's box and\n"
        "orientation cone), and every stage the planner returned, each\n"
        "selectable, animated with a slider and a play button. A stage that\n"
        "failed verification shows the verdict; for a collision, the\n"
        "configuration where the verifier found it, with the two bodies that\n"
        "touch there in red.\n"
        "\n"
        "Without RUN, the finished runs of an experiment that the options\n"
        "name: one run is drawn as RUN would be; several are drawn one page\n"
        "each (run-ID.html) with an index.html listing them all, into the\n"
        "folder PATH (made if missing).\n"
        "\n"
        "Options:\n"
        "  -o, --output PATH    write the page to PATH (replaced if it exists);\n"
        "                       default: a new file (or folder) in $TMPDIR or\n"
        "                       /tmp, whose path is printed\n"
        "  -e, --experiment ID  runs of experiment ID (default: the newest)\n"
        "  -s, --scene NAME     runs in that scene\n"
        "  -q, --query NAME     runs of that query\n"
        "  -p, --planner NAME   runs of that planner configuration\n"
        "                       (\"ompl/RRTConnect\", as mpb report names it)\n"
        "  -f, --failed         runs that are no success\n"
        "  -h, --help           this text\n"
        "\n"
        "three.js is read from $MPB_THREE_JS if set, else from mpbench's data\n"
        "folder (share/mpbench/" THREE_JS_NAME "), else from the source\n"
        "tree's .cache/web (tools/web_env.sh). Meshes of a URDF robot are\n"
        "found as mpbenchd finds them ($MPB_MESH_PATH). docs/reports.md\n"
        "describes the page.\n"
        "\n"
        "Exit status: 0 on success, 1 on an error (an unknown run, a run with\n"
        "no stages, no run that the options name, a database that is not\n"
        "mpbench's), 2 on a bad command line.\n");
}

/* ---- small helpers ---------------------------------------------------- */

static char *dup_or_die(const char *s)
{
    char *d = strdup(s ? s : "");
    if (!d) {
        fprintf(stderr, "mpb " CMD ": out of memory\n");
        exit(MPB_EXIT_ERROR);
    }
    return d;
}

static void *alloc_or_die(size_t n, size_t size)
{
    void *p = calloc(n ? n : 1, size);
    if (!p) {
        fprintf(stderr, "mpb " CMD ": out of memory\n");
        exit(MPB_EXIT_ERROR);
    }
    return p;
}

/* Space-separated numbers into a new array of exactly n; NULL if not n. */
static double *parse_numbers(const char *text, int n)
{
    double *v = alloc_or_die((size_t)n, sizeof *v);
    const char *p = text ? text : "";
    for (int i = 0; i < n; i++) {
        char *end;
        v[i] = strtod(p, &end);
        if (end == p) {
            free(v);
            return NULL;
        }
        p = end;
    }
    return v;
}

/* A file read whole, NUL-terminated; NULL (errno set) if it cannot be. */
static char *read_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *buf = NULL;
    size_t len = 0, cap = 0, got;
    do {
        if (cap - len < 65536) {
            cap = cap ? 2 * cap : 1 << 20;
            char *nb = realloc(buf, cap + 1);
            if (!nb) {
                free(buf);
                fclose(f);
                errno = ENOMEM;
                return NULL;
            }
            buf = nb;
        }
        got = fread(buf + len, 1, cap - len, f);
        len += got;
    } while (got > 0);
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        errno = EIO;
        return NULL;
    }
    buf[len] = '\0';
    return buf;
}

/* three.js, from the first place that has it (see usage()). */
static char *load_three(char *where, size_t len)
{
    char exe[4096];
    const char *env = getenv("MPB_THREE_JS");
    if (env && *env) {
        snprintf(where, len, "%s", env);
        return read_file(where);
    }
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = '\0';
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = '\0';
            int w = snprintf(where, len, "%s/%s/%s", exe, MPB_BIN_TO_DATA,
                             THREE_JS_NAME);
            char *t = w > 0 && (size_t)w < len ? read_file(where) : NULL;
            if (t)
                return t;
        }
    }
    snprintf(where, len, "%s", MPB_SOURCE_THREE_JS);
    return read_file(where);
}

/* ---- reading the run -------------------------------------------------- */

static int on_run(void *ud, const mpb_run_detail *d)
{
    view_run *v = ud;
    v->run = *d;
    const char *const src[] = {d->state, d->planner_config, d->planner_id,
                               d->status, d->message, d->verdict};
    for (int i = 0; i < 6; i++)
        v->strs[i] = dup_or_die(src[i]);
    v->run.state = v->strs[0];
    v->run.planner_config = v->strs[1];
    v->run.planner_id = v->strs[2];
    v->run.status = v->strs[3];
    v->run.message = v->strs[4];
    v->run.verdict = v->strs[5];
    return 0;
}

static int on_experiment(void *ud, const mpb_experiment_row *e)
{
    ((view_run *)ud)->experiment = dup_or_die(e->name);
    return 0;
}

typedef struct scene_text {
    view_run *v;
    char     *robot, *scene, *scene_format;
} scene_text;

static int on_scene(void *ud, const mpb_scene_row *row)
{
    scene_text *t = ud;
    if (row->id != t->v->run.scene_id)
        return 0;
    t->v->scene = dup_or_die(row->name);
    t->v->robot_format = dup_or_die(row->robot_format);
    t->robot = dup_or_die(row->robot);
    t->scene = dup_or_die(row->scene);
    t->scene_format = dup_or_die(row->scene_format);
    return 1;
}

static int on_query(void *ud, const mpb_query_row *q)
{
    view_run *v = ud;
    if (q->id != v->run.query_id)
        return 0;
    v->query = dup_or_die(q->name);
    /* The joint names, space-separated. */
    char *names = dup_or_die(q->joint_names);
    int n = 0;
    for (char *s = strtok(names, " "); s; s = strtok(NULL, " "))
        n++;
    free(names);
    v->num_joints = n;
    v->joint_names = alloc_or_die((size_t)n + 1, sizeof *v->joint_names);
    names = dup_or_die(q->joint_names);
    n = 0;
    for (char *s = strtok(names, " "); s; s = strtok(NULL, " "))
        v->joint_names[n++] = dup_or_die(s);
    free(names);
    v->start = parse_numbers(q->start, v->num_joints);
    v->goal_kind = q->goal_kind;
    if (q->goal_kind == MPB_GOAL_JOINTS) {
        v->goal_joints = parse_numbers(q->goal_joints, v->num_joints);
    } else {
        v->goal_link = dup_or_die(q->goal_link);
        double *r = parse_numbers(q->goal_region, 12);
        if (r) {
            memcpy(v->goal_region, r, sizeof v->goal_region);
            free(r);
        }
    }
    return 1;
}

static int on_stage(void *ud, const mpb_stage_record *st)
{
    view_run *v = ud;
    view_stage *grown = realloc(v->stages, (size_t)(v->num_stages + 1) *
                                           sizeof *grown);
    if (!grown) {
        fprintf(stderr, "mpb " CMD ": out of memory\n");
        exit(MPB_EXIT_ERROR);
    }
    v->stages = grown;
    view_stage *s = &v->stages[v->num_stages++];
    memset(s, 0, sizeof *s);
    s->name = dup_or_die(st->name);
    s->verdict = dup_or_die(st->verdict);
    s->detail = dup_or_die(st->verdict_detail);
    s->valid = st->valid;
    s->segment = st->verdict_segment;
    s->fail_frame = -1;
    s->contact[0] = s->contact[1] = -1;
    /* Waypoints of another size than the robot's cannot be drawn. */
    if (st->num_joints == v->num_joints && st->num_waypoints > 0) {
        s->num_waypoints = st->num_waypoints;
        size_t n = (size_t)st->num_waypoints * (size_t)st->num_joints;
        s->waypoints = alloc_or_die(n, sizeof *s->waypoints);
        memcpy(s->waypoints, st->waypoints, n * sizeof *s->waypoints);
    }
    return 0;
}

/* ---- frames ----------------------------------------------------------- */

/* Append the poses of the moving bodies at q to out (num_moving x 7). */
static int put_poses(view_run *v, mpb_pose *all, const double *q, float *out)
{
    if (mpb_bodies_poses(v->bodies, q, all) != MPB_OK)
        return -1;
    for (int m = 0; m < v->num_moving; m++) {
        const mpb_pose *p = &all[v->moving[m]];
        double quat[4];
        mpb_pose_get_quat(p, quat);
        for (int k = 0; k < 3; k++)
            out[7 * m + k] = (float)p->t[k];
        for (int k = 0; k < 4; k++)
            out[7 * m + 3 + k] = (float)quat[k];
    }
    return 0;
}

/* q = a + s (b - a), continuous joints the short way round. */
static void interpolate(const view_run *v, const double *a, const double *b,
                        double s, double *q)
{
    const unsigned char *wraps = mpb_world_joint_wraps(v->world);
    for (int j = 0; j < v->num_joints; j++)
        q[j] = a[j] + s * mpb_joint_delta(a[j], b[j], wraps[j]);
}

/*
 * Where the verifier stopped on a collision in segment seg: its samples,
 * in its order (verify.c), at the experiment's resolution. 1 with the
 * configuration in q and its place s in the segment, 0 if no sample of
 * the segment collides here (a database from another resolution).
 */
static int find_collision(view_run *v, const double *wp, int n, int seg,
                          double *q, double *s_out)
{
    int nj = v->num_joints;
    if (seg == 0 && mpb_world_in_collision(v->world, wp) == 1) {
        memcpy(q, wp, (size_t)nj * sizeof *q);
        *s_out = 0.0;
        return 1;
    }
    if (seg < 0 || seg + 1 >= n)
        return 0;
    const double *a = wp + (size_t)seg * nj, *b = a + nj;
    const unsigned char *wraps = mpb_world_joint_wraps(v->world);
    double sq = 0.0;
    for (int j = 0; j < nj; j++) {
        double d = mpb_joint_delta(a[j], b[j], wraps[j]);
        sq += d * d;
    }
    double k = ceil(sqrt(sq) / v->resolution);
    if (k < 1)
        k = 1;
    if (k > 1e7)
        return 0;
    for (double s = 1; s <= k; s++) {
        if (s < k)
            interpolate(v, a, b, s / k, q);
        else
            memcpy(q, b, (size_t)nj * sizeof *q);
        if (mpb_world_in_collision(v->world, q) == 1) {
            *s_out = s / k;
            return 1;
        }
    }
    return 0;
}

static int make_frames(view_run *v, view_stage *s, mpb_pose *all)
{
    int n = s->num_waypoints, nj = v->num_joints;
    double *wp = s->waypoints;
    s->waypoints = NULL;
    /* A stage with a NaN or infinite value (verdict not_finite) has no
     * configuration to draw at that waypoint: it is listed, not drawn. */
    for (size_t i = 0; i < (size_t)n * (size_t)nj; i++)
        if (!isfinite(wp[i]))
            n = s->num_waypoints = 0;
    if (n == 0) {
        free(wp);
        return 0;
    }
    int per = n >= SMOOTH_FRAMES || n < 2 ? 1
            : (SMOOTH_FRAMES + n - 2) / (n - 1);
    s->num_frames = (n - 1) * per + 1;
    s->frame_at = alloc_or_die((size_t)s->num_frames, sizeof *s->frame_at);
    s->poses = alloc_or_die((size_t)s->num_frames * (size_t)v->num_moving * 7,
                            sizeof *s->poses);
    double *q = alloc_or_die((size_t)nj, sizeof *q);
    int f = 0, rc = 0;
    for (int i = 0; i < n && rc == 0; i++) {
        const double *a = wp + (size_t)i * nj;
        for (int k = 0; k < (i + 1 < n ? per : 1) && rc == 0; k++) {
            interpolate(v, a, i + 1 < n ? a + nj : a, (double)k / per, q);
            s->frame_at[f] = (float)(i + (double)k / per);
            rc = put_poses(v, all, q, s->poses + (size_t)f * v->num_moving * 7);
            f++;
        }
    }
    /* The frame the verdict points at; for a collision, the configuration
     * where the verifier found it and the bodies that touch there. */
    if (rc == 0 && s->segment >= 0 && s->segment < n)
        s->fail_frame = s->segment * per;
    double cs;
    if (rc == 0 && strcmp(s->verdict, "collision") == 0 &&
        find_collision(v, wp, n, s->segment, q, &cs)) {
        s->has_collision = 1;
        s->collision_s = cs;
        s->fail_frame = (int)lround((s->segment + cs) * per);
        if (s->fail_frame >= s->num_frames)
            s->fail_frame = s->num_frames - 1;
        s->collision_poses = alloc_or_die((size_t)v->num_moving * 7,
                                          sizeof *s->collision_poses);
        rc = put_poses(v, all, q, s->collision_poses);
        if (rc == 0 && mpb_bodies_contact(v->bodies, q, &s->contact[0],
                                          &s->contact[1]) != 1)
            s->contact[0] = s->contact[1] = -1;
    }
    free(q);
    free(wp);
    return rc;
}

/* The world, its bodies, and every pose the page needs. */
static int prepare(view_run *v, scene_text *t, char *err, size_t errlen)
{
    int rc = mpb_world_open_group(v->robot_format, t->robot, t->scene_format,
                                  t->scene, (const char *const *)v->joint_names,
                                  v->num_joints, &v->world, err, errlen);
    if (rc != MPB_OK)
        return -1;
    if (mpb_bodies_open(v->world, &v->bodies, err, errlen) != MPB_OK)
        return -1;
    int nb = mpb_bodies_count(v->bodies);
    v->moving = alloc_or_die((size_t)nb, sizeof *v->moving);
    for (int i = 0; i < nb; i++)
        if (mpb_bodies_get(v->bodies, i)->moves)
            v->moving[v->num_moving++] = i;
    mpb_pose *all = alloc_or_die((size_t)nb, sizeof *all);
    rc = -1;
    snprintf(err, errlen, "the start or goal is not a configuration");
    if (!v->start || mpb_bodies_poses(v->bodies, v->start, all) != MPB_OK)
        goto done;
    v->static_poses = alloc_or_die((size_t)nb * 7, sizeof *v->static_poses);
    for (int i = 0; i < nb; i++) {
        double quat[4];
        mpb_pose_get_quat(&all[i], quat);
        for (int k = 0; k < 3; k++)
            v->static_poses[7 * i + k] = (float)all[i].t[k];
        for (int k = 0; k < 4; k++)
            v->static_poses[7 * i + 3 + k] = (float)quat[k];
    }
    v->start_poses = alloc_or_die((size_t)v->num_moving * 7, sizeof(float));
    if (put_poses(v, all, v->start, v->start_poses) != 0)
        goto done;
    if (v->goal_joints) {
        v->goal_poses = alloc_or_die((size_t)v->num_moving * 7, sizeof(float));
        if (put_poses(v, all, v->goal_joints, v->goal_poses) != 0)
            goto done;
    }
    snprintf(err, errlen, "a waypoint is not a configuration (NaN?)");
    for (int i = 0; i < v->num_stages; i++)
        if (make_frames(v, &v->stages[i], all) != 0)
            goto done;
    rc = 0;
done:
    free(all);
    return rc;
}

/* Everything v holds. */
static void view_free(view_run *v)
{
    mpb_bodies_close(v->bodies);
    mpb_world_close(v->world);
    for (int i = 0; i < 6; i++)
        free(v->strs[i]);
    free(v->experiment);
    free(v->scene);
    free(v->query);
    free(v->robot_format);
    for (int j = 0; j < v->num_joints; j++)
        free(v->joint_names ? v->joint_names[j] : NULL);
    free(v->joint_names);
    free(v->start);
    free(v->goal_joints);
    free(v->goal_link);
    free(v->moving);
    free(v->static_poses);
    free(v->start_poses);
    free(v->goal_poses);
    for (int i = 0; i < v->num_stages; i++) {
        view_stage *st = &v->stages[i];
        free(st->name);
        free(st->verdict);
        free(st->detail);
        free(st->waypoints);
        free(st->frame_at);
        free(st->poses);
        free(st->collision_poses);
    }
    free(v->stages);
    memset(v, 0, sizeof *v);
}

/* ---- output ----------------------------------------------------------- */

/* Write the page to path, through a temporary file beside it. */
static int write_to(const view_run *v, const char *three, const char *path)
{
    size_t len = strlen(path) + 16;
    char *tmp = alloc_or_die(len, 1);
    snprintf(tmp, len, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f) {
        fprintf(stderr, "mpb " CMD ": cannot write %s: %s\n", path,
                strerror(errno));
        free(tmp);
        return -1;
    }
    int bad = view_write_page(v, three, f) != 0;
    bad |= fclose(f) != 0;
    if (bad || rename(tmp, path) != 0) {
        fprintf(stderr, "mpb " CMD ": cannot write %s: %s\n", path,
                strerror(errno));
        remove(tmp);
        free(tmp);
        return -1;
    }
    free(tmp);
    return 0;
}

static const char *tmp_dir(void)
{
    const char *dir = getenv("TMPDIR");
    return dir && *dir ? dir : "/tmp";
}

/* Tell where the page (or the index of pages) is and how to open it. */
static void say_where(const char *path)
{
    const char *display = getenv("DISPLAY"), *wayland =
        getenv("WAYLAND_DISPLAY");
    printf("wrote %s\n", path);
    if ((display && *display) || (wayland && *wayland))
        printf("open it in a browser: xdg-open %s\n", path);
    else
        printf("no display here: copy it to a machine with a browser "
               "and open it there (it needs no network)\n");
}

/*
 * Read run run_id and make it ready to draw into *v. 0, or -1 after one
 * line on stderr; 1 (with why filled, nothing printed) when the run has no
 * stages, which a list of runs notes rather than fails on.
 */
static int view_load(mpb_store *s, const char *db, int64_t run_id,
                     view_run *v, char *why, size_t whylen)
{
    char err[512] = "";
    scene_text t = {v, NULL, NULL, NULL};
    int rc = mpb_store_run_get(s, run_id, on_run, v), status = -1;
    if (rc == MPB_ENOTFOUND) {
        fprintf(stderr, "mpb " CMD ": %s: no run %lld\n", db,
                (long long)run_id);
        return -1;
    }
    if (rc == MPB_OK)
        rc = mpb_store_experiment_get(s, v->run.experiment_id, on_experiment,
                                      v);
    if (rc == MPB_OK)
        rc = mpb_store_scenes(s, v->run.experiment_id, on_scene, &t);
    if (rc == MPB_OK || rc == 1)
        rc = mpb_store_queries(s, v->run.scene_id, on_query, v);
    if (rc == MPB_OK || rc == 1)
        rc = mpb_store_run_stages(s, run_id, on_stage, v);
    if (rc != MPB_OK) {
        fprintf(stderr, "mpb " CMD ": %s: run %lld: %s\n", db,
                (long long)run_id, mpb_store_errmsg(s));
        goto out;
    }
    if (!v->scene || !v->query) {
        fprintf(stderr, "mpb " CMD ": %s: run %lld: its %s is not in the "
                "database\n", db, (long long)run_id, v->scene ? "query"
                                                              : "scene");
        goto out;
    }
    if (v->num_stages == 0) {
        snprintf(why, whylen, "run %lld has no stages to draw (%s%s%s)",
                 (long long)run_id,
                 *v->run.status ? v->run.status : v->run.state,
                 *v->run.message ? ": " : "", v->run.message);
        status = 1;
        goto out;
    }
    double res = 0.0;
    v->resolution = DEFAULT_RESOLUTION;
    if (mpb_store_experiment_resolution(s, v->run.experiment_id, &res) ==
            MPB_OK && res > 0) {
        v->resolution = res;
        v->resolution_known = 1;
    }
    if (prepare(v, &t, err, sizeof err) != 0) {
        fprintf(stderr, "mpb " CMD ": %s: run %lld: scene '%s': %s\n", db,
                (long long)run_id, v->scene, err);
        goto out;
    }
    status = 0;
out:
    free(t.robot);
    free(t.scene);
    free(t.scene_format);
    return status;
}

static int on_nothing(void *ud, const mpb_experiment_row *row)
{
    (void)ud;
    (void)row;
    return 0;
}

/* ---- choosing runs: --experiment, --scene, --query, --planner, --failed -- */

typedef struct selection {
    const char *scene, *query, *planner;
    int         failed;
    mpb_store  *store;
    int64_t    *runs;
    int         num_runs, cap_runs;
    /* names by id, of the experiment's configurations, scenes, queries */
    int64_t    *ids;
    char      **names;
    int         num_names, cap_names;
} selection;

static void add_name(selection *sel, int64_t id, const char *name)
{
    if (sel->num_names == sel->cap_names) {
        sel->cap_names = sel->cap_names ? 2 * sel->cap_names : 64;
        sel->ids = realloc(sel->ids, (size_t)sel->cap_names * sizeof *sel->ids);
        sel->names = realloc(sel->names,
                             (size_t)sel->cap_names * sizeof *sel->names);
        if (!sel->ids || !sel->names) {
            fprintf(stderr, "mpb " CMD ": out of memory\n");
            exit(MPB_EXIT_ERROR);
        }
    }
    sel->ids[sel->num_names] = id;
    sel->names[sel->num_names++] = dup_or_die(name);
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
    if (sel->num_runs == sel->cap_runs) {
        sel->cap_runs = sel->cap_runs ? 2 * sel->cap_runs : 64;
        sel->runs = realloc(sel->runs, (size_t)sel->cap_runs * sizeof *sel->runs);
        if (!sel->runs) {
            fprintf(stderr, "mpb " CMD ": out of memory\n");
            exit(MPB_EXIT_ERROR);
        }
    }
    sel->runs[sel->num_runs++] = row->run_id;
    return 0;
}

/* The finished runs of the experiment that the selection names, in run
 * order, into sel->runs. 0, or -1 after one line. */
static int select_runs(mpb_store *s, const char *db, int64_t experiment,
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

static void selection_free(selection *sel)
{
    for (int i = 0; i < sel->num_names; i++)
        free(sel->names[i]);
    free(sel->names);
    free(sel->ids);
    free(sel->runs);
}

/* An index page (index.html) of one page per run, written into dir. */
static int write_many(mpb_store *s, const char *db, int64_t experiment,
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
    mpb_store_experiment_get(s, experiment, on_experiment, &e);
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
            "<table><tr><th>run</th><th>planner</th><th>scene</th>"
            "<th>query</th><th>rep.</th><th>outcome</th><th>message</th>"
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
                         write_to(&v, three, path) != 0))
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
        view_html_text(index, v.scene ? v.scene : "");
        fputs("</td><td>", index);
        view_html_text(index, v.query ? v.query : "");
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

int cmd_view(int argc, char **argv)
{
    static const struct option longopts[] = {
        {"output", required_argument, NULL, 'o'},
        {"experiment", required_argument, NULL, 'e'},
        {"scene", required_argument, NULL, 's'},
        {"query", required_argument, NULL, 'q'},
        {"planner", required_argument, NULL, 'p'},
        {"failed", no_argument, NULL, 'f'},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    const char *output = NULL;
    selection sel = {0};
    int64_t experiment = 0;
    int opt, selecting = 0;
    optind = 1;
    opterr = 0;
    while ((opt = getopt_long(argc, argv, ":o:e:s:q:p:fh", longopts,
                              NULL)) != -1) {
        switch (opt) {
        case 'o':
            output = optarg;
            break;
        case 'e':
            if (tool_parse_id(optarg, &experiment) != 0) {
                fprintf(stderr, "mpb " CMD ": --experiment wants an "
                        "experiment id (a number), not '%s'\n", optarg);
                return MPB_EXIT_USAGE;
            }
            selecting = 1;
            break;
        case 's':
            sel.scene = optarg;
            selecting = 1;
            break;
        case 'q':
            sel.query = optarg;
            selecting = 1;
            break;
        case 'p':
            sel.planner = optarg;
            selecting = 1;
            break;
        case 'f':
            sel.failed = 1;
            selecting = 1;
            break;
        case 'h':
            usage(stdout);
            return MPB_EXIT_OK;
        default:
            return tool_option_error(CMD, opt, argv);
        }
    }
    int want = selecting ? 1 : 2;
    if (argc - optind < want) {
        fprintf(stderr, "mpb " CMD ": wants a database and %s (try 'mpb "
                CMD " --help')\n", selecting ? "nothing more" : "a run id");
        return MPB_EXIT_USAGE;
    }
    if (argc - optind > 2 || (selecting && argc - optind > 1)) {
        if (selecting && argc - optind == 2)
            fprintf(stderr, "mpb " CMD ": a run id, or --experiment, "
                    "--scene, --query, --planner, --failed: not both\n");
        else
            return tool_extra_argument(CMD, argv[optind + 2]);
        return MPB_EXIT_USAGE;
    }
    const char *db = argv[optind];
    int64_t run_id = 0;
    if (!selecting && tool_parse_id(argv[optind + 1], &run_id) != 0) {
        fprintf(stderr, "mpb " CMD ": RUN is a run id (a number), not '%s'\n",
                argv[optind + 1]);
        return MPB_EXIT_USAGE;
    }

    char where[4096], path[4200];
    char *three = load_three(where, sizeof where);
    if (!three) {
        fprintf(stderr, "mpb " CMD ": cannot read three.js at %s: %s (run "
                "tools/web_env.sh, or set MPB_THREE_JS)\n", where,
                strerror(errno));
        return MPB_EXIT_ERROR;
    }
    mpb_store *s = tool_open_readonly(CMD, db);
    if (!s) {
        free(three);
        return MPB_EXIT_ERROR;
    }
    int status = MPB_EXIT_ERROR;
    if (selecting) {
        if (experiment == 0 &&
            mpb_store_experiment_latest(s, &experiment) != MPB_OK) {
            fprintf(stderr, "mpb " CMD ": %s holds no experiment\n", db);
            goto out;
        }
        if (mpb_store_experiment_get(s, experiment, on_nothing, NULL) ==
                MPB_ENOTFOUND) {
            fprintf(stderr, "mpb " CMD ": %s: no experiment %lld\n", db,
                    (long long)experiment);
            goto out;
        }
        if (select_runs(s, db, experiment, &sel) != 0)
            goto out;
        if (sel.num_runs == 0) {
            fprintf(stderr, "mpb " CMD ": %s: no finished%s run of "
                    "experiment %lld%s%s%s%s%s%s%s%s%s\n", db,
                    sel.failed ? " failed" : "", (long long)experiment,
                    sel.scene ? " in scene '" : "", sel.scene ? sel.scene : "",
                    sel.scene ? "'" : "", sel.query ? " for query '" : "",
                    sel.query ? sel.query : "", sel.query ? "'" : "",
                    sel.planner ? " by '" : "", sel.planner ? sel.planner : "",
                    sel.planner ? "'" : "");
            goto out;
        }
        if (sel.num_runs > 1) {
            /* A folder of pages and their index. */
            if (output) {
                if (mkdir(output, 0777) != 0 && errno != EEXIST) {
                    fprintf(stderr, "mpb " CMD ": cannot make %s: %s\n",
                            output, strerror(errno));
                    goto out;
                }
                snprintf(path, sizeof path, "%s", output);
            } else {
                snprintf(path, sizeof path, "%s/mpb-view-experiment%lld-XXXXXX",
                         tmp_dir(), (long long)experiment);
                if (!mkdtemp(path)) {
                    fprintf(stderr, "mpb " CMD ": cannot make a folder in "
                            "%s: %s\n", tmp_dir(), strerror(errno));
                    goto out;
                }
            }
            if (write_many(s, db, experiment, &sel, three, path) != 0)
                goto out;
            size_t n = strlen(path);
            snprintf(path + n, sizeof path - n, "/index.html");
            say_where(path);
            status = MPB_EXIT_OK;
            goto out;
        }
        run_id = sel.runs[0];
    }

    view_run v = {0};
    char why[512] = "";
    int got = view_load(s, db, run_id, &v, why, sizeof why);
    if (got == 1)
        fprintf(stderr, "mpb " CMD ": %s: %s\n", db, why);
    if (got == 0) {
        if (output) {
            if (write_to(&v, three, output) == 0) {
                printf("wrote %s\n", output);
                status = MPB_EXIT_OK;
            }
        } else {
            snprintf(path, sizeof path, "%s/mpb-view-run%lld-XXXXXX.html",
                     tmp_dir(), (long long)run_id);
            int fd = mkstemps(path, 5);
            if (fd < 0) {
                fprintf(stderr, "mpb " CMD ": cannot make a file in %s: %s\n",
                        tmp_dir(), strerror(errno));
            } else {
                close(fd);
                if (write_to(&v, three, path) == 0) {
                    say_where(path);
                    status = MPB_EXIT_OK;
                } else {
                    remove(path);
                }
            }
        }
    }
    view_free(&v);
out:
    selection_free(&sel);
    mpb_store_close(s);
    free(three);
    return status;
}
