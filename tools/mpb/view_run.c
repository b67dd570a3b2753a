/*
 * view_run.c - `mpb view`'s one run: read back with its scene and query,
 * the world the verifier checked it in opened, the pose of every moving
 * body computed at every frame of every stage (libmpbench's forward
 * kinematics), the configuration where a collision verdict stopped found
 * again (mpb_find_collision()) with the two bodies that touch there; and
 * the page written (view_page.c) into a file.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view.h"

#define CMD "view"

/* Stages with fewer waypoints than this get samples between them, so that
 * the slider and the play button move the robot smoothly. */
#define SMOOTH_FRAMES 240

/* The verifier's step when the database does not say (mpbenchd -r). */
#define DEFAULT_RESOLUTION 0.01

char *view_strdup(const char *s)
{
    char *d = strdup(s ? s : "");
    if (!d) {
        fprintf(stderr, "mpb " CMD ": out of memory\n");
        exit(MPB_EXIT_ERROR);
    }
    return d;
}

void *view_calloc(size_t n, size_t size)
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
    double *v = view_calloc((size_t)n, sizeof *v);
    if (mpb_store_numbers(text, v, n) != MPB_OK) {
        free(v);
        return NULL;
    }
    return v;
}

/* ---- reading the run -------------------------------------------------- */

static int on_run(void *ud, const mpb_run_detail *d)
{
    view_run *v = ud;
    v->run = *d;
    const char *const src[] = {d->state, d->planner_config, d->planner_id,
                               d->status, d->message, d->verdict};
    for (int i = 0; i < 6; i++)
        v->strs[i] = view_strdup(src[i]);
    v->run.state = v->strs[0];
    v->run.planner_config = v->strs[1];
    v->run.planner_id = v->strs[2];
    v->run.status = v->strs[3];
    v->run.message = v->strs[4];
    v->run.verdict = v->strs[5];
    v->seen_success = d->seen_success;
    if (d->seen_verdict != NULL) {
        v->seen_verdict = view_strdup(d->seen_verdict);
        v->seen_detail = view_strdup(d->seen_detail);
    }
    v->run.seen_verdict = v->seen_verdict;
    v->run.seen_detail = v->seen_detail;
    return 0;
}

static int on_experiment(void *ud, const mpb_experiment_row *e)
{
    ((view_run *)ud)->experiment = view_strdup(e->name);
    return 0;
}

typedef struct scene_text {
    view_run *v;
    char     *robot, *scene, *scene_format;
    char     *seen, *seen_format;   /* what its planners were given, or NULL */
} scene_text;

static int on_scene(void *ud, const mpb_scene_row *row)
{
    scene_text *t = ud;
    if (row->id != t->v->run.scene_id)
        return 0;
    t->v->scene = view_strdup(row->name);
    t->v->robot_format = view_strdup(row->robot_format);
    t->robot = view_strdup(row->robot);
    t->scene = view_strdup(row->scene);
    t->scene_format = view_strdup(row->scene_format);
    if (row->seen != NULL) {
        t->seen = view_strdup(row->seen);
        t->seen_format = view_strdup(row->seen_format);
        t->v->seen_how = view_strdup(row->seen_how);
    }
    return 1;
}

static int on_query(void *ud, const mpb_query_row *q)
{
    view_run *v = ud;
    if (q->id != v->run.query_id)
        return 0;
    v->query = view_strdup(q->name);
    /* The joint names, space-separated. */
    char *names = view_strdup(q->joint_names);
    int n = 0;
    for (char *s = strtok(names, " "); s; s = strtok(NULL, " "))
        n++;
    free(names);
    v->num_joints = n;
    v->joint_names = view_calloc((size_t)n + 1, sizeof *v->joint_names);
    names = view_strdup(q->joint_names);
    n = 0;
    for (char *s = strtok(names, " "); s; s = strtok(NULL, " "))
        v->joint_names[n++] = view_strdup(s);
    free(names);
    v->start = parse_numbers(q->start, v->num_joints);
    /* The joints outside the group it holds: "name=value name=value". */
    if (q->held) {
        char *text = view_strdup(q->held), *save = NULL;
        size_t words = 1;
        for (const char *c = text; *c; c++)
            words += *c == ' ';
        v->held_names = view_calloc(words, sizeof *v->held_names);
        v->held_values = view_calloc(words, sizeof *v->held_values);
        for (char *s = strtok_r(text, " ", &save); s;
             s = strtok_r(NULL, " ", &save)) {
            char *eq = strrchr(s, '=');
            if (!eq)
                continue;
            *eq = '\0';
            v->held_names[v->num_held] = view_strdup(s);
            v->held_values[v->num_held++] = strtod(eq + 1, NULL);
        }
        free(text);
    }
    v->tolerance = q->goal_tolerance;
    v->goal_kind = q->goal_kind;
    if (q->goal_kind == MPB_GOAL_JOINTS) {
        v->goal_joints = parse_numbers(q->goal_joints, v->num_joints);
    } else {
        v->goal_link = view_strdup(q->goal_link);
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
    s->name = view_strdup(st->name);
    s->verdict = view_strdup(st->verdict);
    s->detail = view_strdup(st->verdict_detail);
    s->valid = st->valid;
    /* Stored before certified verification (NULL), or by it: the rule
     * its collision was found by. */
    s->sampled = !st->verification || strcmp(st->verification, "sampled") == 0;
    s->segment = st->verdict_segment;
    s->fail_frame = -1;
    s->contact[0] = s->contact[1] = -1;
    /* Waypoints of another size than the robot's cannot be drawn. */
    if (st->num_joints == v->num_joints && st->num_waypoints > 0) {
        s->num_waypoints = st->num_waypoints;
        size_t n = (size_t)st->num_waypoints * (size_t)st->num_joints;
        s->waypoints = view_calloc(n, sizeof *s->waypoints);
        memcpy(s->waypoints, st->waypoints, n * sizeof *s->waypoints);
        if (st->times != NULL) {
            s->times = view_calloc((size_t)st->num_waypoints, sizeof *s->times);
            memcpy(s->times, st->times,
                   (size_t)st->num_waypoints * sizeof *s->times);
        }
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
    s->frame_at = view_calloc((size_t)s->num_frames, sizeof *s->frame_at);
    s->poses = view_calloc((size_t)s->num_frames * (size_t)v->num_moving * 7,
                            sizeof *s->poses);
    double *q = view_calloc((size_t)nj, sizeof *q);
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
    /* Found again by the library, by the rule the stage was verified
     * with (its stored verification): the proof's configuration, or the
     * sample's. A stage stored "sampled" by a certified check (some
     * earlier segment only sampled) may have had its collision found by
     * the proof: then the other rule finds it. A database from another
     * resolution or world may have none there. */
    mpb_collision_at at;
    int found = 0;
    for (int k = 0; k < 2 && !found && rc == 0 &&
                    strcmp(s->verdict, "collision") == 0; k++) {
        mpb_world_set_verification(v->world, s->sampled == (k == 0)
                                   ? MPB_VERIFY_SAMPLED : MPB_VERIFY_CERTIFIED);
        found = mpb_find_collision(v->world, wp, n, nj, v->resolution,
                                   s->segment, q, &at) == 1;
    }
    if (found) {
        s->has_collision = 1;
        s->segment = at.segment;
        s->collision_s = at.s;
        s->collision_certified = at.certified;
        s->collision_q = view_calloc((size_t)nj, sizeof *s->collision_q);
        memcpy(s->collision_q, q, (size_t)nj * sizeof *q);
        s->fail_frame = (int)lround((s->segment + at.s) * per);
        if (s->fail_frame >= s->num_frames)
            s->fail_frame = s->num_frames - 1;
        s->collision_poses = view_calloc((size_t)v->num_moving * 7,
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

/* The world's bodies, and every pose the page needs. */
static int prepare(view_run *v, char *err, size_t errlen)
{
    int rc;
    if (mpb_bodies_open(v->world, &v->bodies, err, errlen) != MPB_OK)
        return -1;
    int nb = mpb_bodies_count(v->bodies);
    v->moving = view_calloc((size_t)nb, sizeof *v->moving);
    for (int i = 0; i < nb; i++)
        if (mpb_bodies_get(v->bodies, i)->moves)
            v->moving[v->num_moving++] = i;
    mpb_pose *all = view_calloc((size_t)nb, sizeof *all);
    rc = -1;
    snprintf(err, errlen, "the start or goal is not a configuration");
    if (!v->start || mpb_bodies_poses(v->bodies, v->start, all) != MPB_OK)
        goto done;
    v->static_poses = view_calloc((size_t)nb * 7, sizeof *v->static_poses);
    for (int i = 0; i < nb; i++) {
        double quat[4];
        mpb_pose_get_quat(&all[i], quat);
        for (int k = 0; k < 3; k++)
            v->static_poses[7 * i + k] = (float)all[i].t[k];
        for (int k = 0; k < 4; k++)
            v->static_poses[7 * i + 3 + k] = (float)quat[k];
    }
    v->start_poses = view_calloc((size_t)v->num_moving * 7, sizeof(float));
    if (put_poses(v, all, v->start, v->start_poses) != 0)
        goto done;
    if (v->goal_joints) {
        v->goal_poses = view_calloc((size_t)v->num_moving * 7, sizeof(float));
        if (put_poses(v, all, v->goal_joints, v->goal_poses) != 0)
            goto done;
    }
    if (v->seen_world != NULL) {
        if (mpb_bodies_open(v->seen_world, &v->seen_bodies, err, errlen)
                != MPB_OK)
            goto done;
        int ns = mpb_bodies_count(v->seen_bodies);
        mpb_pose *seen = view_calloc((size_t)ns, sizeof *seen);
        snprintf(err, errlen, "the start is not a configuration");
        if (mpb_bodies_poses(v->seen_bodies, v->start, seen) != MPB_OK) {
            free(seen);
            goto done;
        }
        v->seen_poses = view_calloc((size_t)ns * 7, sizeof *v->seen_poses);
        for (int i = 0; i < ns; i++) {
            double quat[4];
            mpb_pose_get_quat(&seen[i], quat);
            for (int k = 0; k < 3; k++)
                v->seen_poses[7 * i + k] = (float)seen[i].t[k];
            for (int k = 0; k < 4; k++)
                v->seen_poses[7 * i + 3 + k] = (float)quat[k];
        }
        free(seen);
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

void view_free(view_run *v)
{
    mpb_bodies_close(v->bodies);
    mpb_world_close(v->world);
    mpb_bodies_close(v->seen_bodies);
    mpb_world_close(v->seen_world);
    free(v->seen_how);
    free(v->seen_poses);
    free(v->seen_verdict);
    free(v->seen_detail);
    for (int i = 0; i < 6; i++)
        free(v->strs[i]);
    free(v->experiment);
    free(v->scene);
    free(v->query);
    free(v->robot_format);
    for (int j = 0; j < v->num_joints; j++)
        free(v->joint_names ? v->joint_names[j] : NULL);
    free(v->joint_names);
    for (int j = 0; j < v->num_held; j++)
        free(v->held_names[j]);
    free(v->held_names);
    free(v->held_values);
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
        free(st->times);
        free(st->frame_at);
        free(st->poses);
        free(st->collision_poses);
        free(st->collision_q);
    }
    free(v->stages);
    memset(v, 0, sizeof *v);
}

int view_read(const char *cmd, mpb_store *s, const char *db, int64_t run_id,
              view_run *v, char *why, size_t whylen)
{
    char err[512] = "";
    scene_text t = {v, NULL, NULL, NULL, NULL, NULL};
    int rc = mpb_store_run_get(s, run_id, on_run, v), status = -1;
    if (rc == MPB_ENOTFOUND) {
        fprintf(stderr, "mpb %s: %s: no run %lld\n", cmd, db,
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
        fprintf(stderr, "mpb %s: %s: run %lld: %s\n", cmd, db,
                (long long)run_id, mpb_store_errmsg(s));
        goto out;
    }
    if (!v->scene || !v->query) {
        fprintf(stderr, "mpb %s: %s: run %lld: its %s is not in the "
                "database\n", cmd, db, (long long)run_id, v->scene ? "query"
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
    if (mpb_world_open_group(v->robot_format, t.robot, t.scene_format,
                             t.scene, (const char *const *)v->joint_names,
                             v->num_joints, &v->world, err, sizeof err)
            != MPB_OK) {
        fprintf(stderr, "mpb %s: %s: run %lld: scene '%s': %s\n", cmd, db,
                (long long)run_id, v->scene, err);
        goto out;
    }
    /* The values the query held, as every world of the run held them. */
    if (mpb_world_hold(v->world, (const char *const *)v->held_names,
                       v->held_values, v->num_held, err, sizeof err)
            != MPB_OK) {
        fprintf(stderr, "mpb %s: %s: run %lld: query '%s': held joints: %s\n",
                cmd, db, (long long)run_id, v->query, err);
        goto out;
    }
    /* What its planner saw, as the daemon judged it there. */
    if (t.seen != NULL &&
        (mpb_world_open_group(v->robot_format, t.robot, t.seen_format, t.seen,
                              (const char *const *)v->joint_names,
                              v->num_joints, &v->seen_world, err, sizeof err)
             != MPB_OK ||
         mpb_world_hold(v->seen_world, (const char *const *)v->held_names,
                        v->held_values, v->num_held, err, sizeof err)
             != MPB_OK)) {
        fprintf(stderr, "mpb %s: %s: run %lld: scene '%s', what was seen: %s\n",
                cmd, db, (long long)run_id, v->scene, err);
        goto out;
    }
    status = 0;
out:
    free(t.robot);
    free(t.scene);
    free(t.scene_format);
    free(t.seen);
    free(t.seen_format);
    return status;
}

int view_load(mpb_store *s, const char *db, int64_t run_id, view_run *v,
              char *why, size_t whylen)
{
    int status = view_read(CMD, s, db, run_id, v, why, whylen);
    if (status != 0)
        return status;
    char err[512] = "";
    if (prepare(v, err, sizeof err) != 0) {
        fprintf(stderr, "mpb " CMD ": %s: run %lld: scene '%s': %s\n", db,
                (long long)run_id, v->scene, err);
        return -1;
    }
    return 0;
}

/* ---- output ----------------------------------------------------------- */

int view_write_file(const view_run *v, const char *three, const char *path)
{
    size_t len = strlen(path) + 16;
    char *tmp = view_calloc(len, 1);
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
