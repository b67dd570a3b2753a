/*
 * thin.c - warn of obstacles thinner than the verification step can see.
 * mpbenchd checks a path at joint-space points `resolution` apart
 * (verify.c); between two of them a point of the robot moves up to
 * resolution x the robot's lever arm, and an obstacle thinner than that
 * may be passed through unseen (docs/metrics.md). The lever arm is
 * estimated as the largest end-effector displacement per radian of
 * joint-space motion, from the Jacobian (by finite differences) at the
 * queries' starts and at configurations spread over the joint limits.
 * The planar arm's links are judged too (a thin link passes through an
 * obstacle as well); a URDF robot's links are not yet.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon.h"

#define SAMPLES 64          /* configurations besides the queries' starts */
#define FD_STEP 1e-6        /* rad */

/* |d ee / d q| in the Euclidean norm of q, bounded by the Frobenius norm
 * of the Jacobian: m per rad at q; 0 if the world cannot say. */
static double lever_at(mpb_world *w, const double *q, double *tmp, int nj)
{
    double base[3], moved[3], sum = 0.0;
    if (mpb_world_ee_position(w, q, base) != MPB_OK)
        return 0.0;
    for (int j = 0; j < nj; j++) {
        memcpy(tmp, q, sizeof *tmp * (size_t)nj);
        tmp[j] += FD_STEP;
        if (mpb_world_ee_position(w, tmp, moved) != MPB_OK)
            continue;
        for (int k = 0; k < 3; k++)
            sum += (moved[k] - base[k]) * (moved[k] - base[k]);
    }
    return sqrt(sum) / FD_STEP;
}

double mpbd_lever_arm(const mpbd_experiment *e, int scene)
{
    mpb_world *w = e->scenes[scene].world;
    int nj = e->num_joints;
    double *q = calloc(2 * (size_t)(nj > 0 ? nj : 1), sizeof *q);
    double best = 0.0;
    if (w == NULL || q == NULL) {
        free(q);
        return 0.0;
    }
    double *tmp = q + nj;
    for (int i = 0; i < e->num_queries; i++)
        if (e->queries[i].scene == scene) {
            mpbd_query_hold(e, &e->queries[i]);   /* its held joints */
            double l = lever_at(w, e->queries[i].start, tmp, nj);
            best = l > best ? l : best;
        }
    uint64_t x = 0x9E3779B97F4A7C15ull;     /* the same spread every time */
    for (int s = 0; s < SAMPLES; s++) {
        for (int j = 0; j < nj; j++) {
            double lo, hi;
            x ^= x << 13, x ^= x >> 7, x ^= x << 17;
            double u = (double)(x >> 11) / 9007199254740992.0;
            if (mpb_world_joint_is_continuous(w, j)) {
                lo = -M_PI;
                hi = M_PI;
            } else {
                mpb_world_joint_limits(w, j, &lo, &hi);
            }
            q[j] = lo + u * (hi - lo);
        }
        double l = lever_at(w, q, tmp, nj);
        best = l > best ? l : best;
    }
    free(q);
    return best;
}

/* Say one thin part. */
static void say(void (*out)(void *, const char *), void *ud,
                const char *scene, const char *what, double thick,
                double limit, double resolution, double lever)
{
    char line[512];
    snprintf(line, sizeof line, "scene '%s': %s is %.3g m thick, less than "
             "the %.3g m the end effector may move between two verification "
             "samples (%g rad x %.3g m/rad): a path may pass through it unseen",
             scene, what, thick, limit, resolution, lever);
    out(ud, line);
}

/* The planar scene's circles and boxes (docs/planar-format.md). */
static int thin_planar(const mpbd_scene *sc, double limit, double res,
                       double lever, void (*out)(void *, const char *),
                       void *ud)
{
    int n = 0, line = 0;
    for (const char *p = sc->scene; p != NULL && *p; ) {
        const char *end = strchr(p, '\n');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        char buf[256], what[128];
        double a, b, c, d;
        line++;
        snprintf(buf, sizeof buf, "%.*s", (int)(len < 255 ? len : 255), p);
        if (sscanf(buf, " circle %lf %lf %lf", &a, &b, &c) == 3 &&
            2 * c < limit) {
            snprintf(what, sizeof what, "the circle of line %d", line);
            say(out, ud, sc->name, what, 2 * c, limit, res, lever);
            n++;
        } else if (sscanf(buf, " box %lf %lf %lf %lf", &a, &b, &c, &d) == 4 &&
                   2 * fmin(c, d) < limit) {
            snprintf(what, sizeof what, "the box of line %d", line);
            say(out, ud, sc->name, what, 2 * fmin(c, d), limit, res, lever);
            n++;
        }
        p = end ? end + 1 : NULL;
    }
    return n;
}

/* The thickness of a primitive: its smallest extent; 0 for none known. */
static double thickness(const mpb_geometry *g)
{
    const double *d = g->dims;
    switch (g->type) {
    case MPB_SHAPE_BOX:      return fmin(d[0], fmin(d[1], d[2]));
    case MPB_SHAPE_SPHERE:   return 2 * d[0];
    case MPB_SHAPE_CYLINDER:
    case MPB_SHAPE_CONE:     return fmin(2 * d[0], d[1]);
    default:                 return 0.0;   /* planes, meshes: not judged */
    }
}

static int thin_moveit(const mpbd_scene *sc, double limit, double res,
                       double lever, void (*out)(void *, const char *),
                       void *ud)
{
    mpb_scene *s = NULL;
    int n = 0;
    if (mpb_scene_open_text(sc->scene, &s, NULL, 0) != MPB_OK)
        return 0;
    for (int i = 0; i < mpb_scene_num_objects(s); i++) {
        const mpb_scene_object *o = mpb_scene_object_at(s, i);
        for (int k = 0; k < o->num_shapes; k++) {
            double t = thickness(&o->shapes[k].geometry);
            if (t > 0 && t < limit) {
                char what[160];
                snprintf(what, sizeof what, "object '%.60s' (shape of line %d)",
                         o->id, o->shapes[k].line);
                say(out, ud, sc->name, what, t, limit, res, lever);
                n++;
            }
        }
    }
    mpb_scene_close(s);
    return n;
}

/* The planar arm's links: capsules of link_radius, 2 x that thick. */
static int thin_planar_robot(const mpbd_scene *sc, double limit, double res,
                             double lever, void (*out)(void *, const char *),
                             void *ud)
{
    for (const char *p = sc->robot; p != NULL && *p; ) {
        const char *end = strchr(p, '\n');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        char buf[256], line[512];
        double r;
        snprintf(buf, sizeof buf, "%.*s", (int)(len < 255 ? len : 255), p);
        if (sscanf(buf, " link_radius %lf", &r) == 1 && 2 * r < limit) {
            snprintf(line, sizeof line, "the robot's links are %.3g m thick "
                     "(link_radius %g), less than the %.3g m they may move "
                     "between two verification samples (%g rad x %.3g "
                     "m/rad): a path may pass them through an obstacle "
                     "unseen", 2 * r, r, limit, res, lever);
            out(ud, line);
            return 1;
        }
        p = end ? end + 1 : NULL;
    }
    return 0;
}

int mpbd_warn_thin(const mpbd_experiment *e, double resolution,
                   void (*out)(void *ud, const char *line), void *ud)
{
    int n = 0, robot_said = 0;
    for (int i = 0; i < e->num_scenes; i++) {
        const mpbd_scene *sc = &e->scenes[i];
        double lever = mpbd_lever_arm(e, i);
        double limit = resolution * lever;
        if (!(limit > 0))
            continue;
        if (!robot_said && strcmp(sc->robot_format, "planar") == 0)
            n += robot_said = thin_planar_robot(sc, limit, resolution, lever,
                                                out, ud);
        if (strcmp(sc->scene_format, "planar") == 0)
            n += thin_planar(sc, limit, resolution, lever, out, ud);
        else if (strcmp(sc->scene_format, "moveit-scene") == 0)
            n += thin_moveit(sc, limit, resolution, lever, out, ud);
    }
    return n;
}
