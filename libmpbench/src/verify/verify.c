/* verify.c - mpbench's own verdict on a path: does it solve the query? */
#include "mpbench/mpbench.h"

#include <math.h>
#include <string.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "model/world_provider.h"
#include "verify/certify.h"
#include "verify/locate.h"

static const char *const verdict_names[MPB_VERDICT_COUNT] = {
    [MPB_VERDICT_VALID]       = "valid",
    [MPB_VERDICT_EMPTY]       = "empty",
    [MPB_VERDICT_WRONG_SIZE]  = "wrong_size",
    [MPB_VERDICT_NOT_FINITE]  = "not_finite",
    [MPB_VERDICT_START]       = "start",
    [MPB_VERDICT_GOAL]        = "goal",
    [MPB_VERDICT_JOINT_LIMIT] = "joint_limit",
    [MPB_VERDICT_COLLISION]   = "collision",
    [MPB_VERDICT_UNSUPPORTED] = "unsupported",
    [MPB_VERDICT_BAD_TIMES]   = "bad_times",
    [MPB_VERDICT_VELOCITY_LIMIT] = "velocity_limit",
};

const char *mpb_verdict_name(mpb_verdict_code code)
{
    if ((int)code < 0 || code >= MPB_VERDICT_COUNT || !verdict_names[code])
        return "unknown";
    return verdict_names[code];
}

const char *mpb_verdict_verification(const mpb_verdict *v)
{
    if (v == NULL ||
        (v->code != MPB_VERDICT_VALID && v->code != MPB_VERDICT_COLLISION &&
         v->code != MPB_VERDICT_VELOCITY_LIMIT))
        return NULL;
    return mpb_verification_name(v->certified ? MPB_VERIFY_CERTIFIED
                                              : MPB_VERIFY_SAMPLED);
}

mpb_goal mpb_query_goal(int kind, const double *joints, double joint_tolerance,
                        const char *link, const double *region)
{
    mpb_goal g = {.kind = (mpb_goal_kind)kind, .joints = joints,
                  .joint_tolerance = joint_tolerance, .link = link};
    for (int i = 0; region != NULL && i < 3; i++) {
        g.position[i] = region[i];
        g.position_tolerance[i] = region[3 + i];
        g.orientation_rpy[i] = region[6 + i];
        g.orientation_tolerance[i] = region[9 + i];
    }
    return g;
}

static int verdict(mpb_verdict *out, mpb_verdict_code code, int segment,
                   const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* Fill *out; returns MPB_OK, so that a check can end with return verdict(). */
static int verdict(mpb_verdict *out, mpb_verdict_code code, int segment,
                   const char *fmt, ...)
{
    va_list ap;
    out->code = code;
    out->segment = segment;
    out->certified = 0;
    out->depth_lower = out->depth_upper = out->depth_s = NAN;
    va_start(ap, fmt);
    vsnprintf(out->detail, sizeof out->detail, fmt, ap);
    va_end(ap);
    return MPB_OK;
}

/* Bad arguments: never a VALID verdict, even for a caller who ignores rc. */
static int bad_args(mpb_verdict *out, int rc, const char *why)
{
    if (out)
        verdict(out, MPB_VERDICT_UNSUPPORTED, -1, "cannot verify: %s", why);
    return rc;
}

/*
 * The significant digits that print a and b differently (%.*g), from 6 up
 * to 17, which tells any two doubles apart: a value just past its limit
 * must not read as equal to it ("2.5 is outside [-2.5, 2.5]").
 */
static int digits_apart(double a, double b)
{
    char x[40], y[40];
    for (int p = 6; p < 17; p++) {
        snprintf(x, sizeof x, "%.*g", p, a);
        snprintf(y, sizeof y, "%.*g", p, b);
        if (strcmp(x, y) != 0)
            return p;
    }
    return 17;
}

static double joint_dist(const mpb_world *w, int j, double a, double b)
{
    return fabs(mpb_joint_delta(a, b, w->wraps[j]));
}

/* ": " and the bodies in contact at q, where the world names them. */
static void contact(mpb_world *w, const double *q, char *what, size_t len)
{
    char names[400];      /* two link names of up to ~190 characters */
    if (mpb_world_contact(w, q, names, sizeof names) > 0 && names[0])
        snprintf(what, len, ": %s", names);
    else
        what[0] = '\0';
}

/*
 * How deep a collision verdict goes (mpb_verdict.depth_*): at q (the
 * configuration found, at s = at of the segment a + s d) and at the
 * sampled rule's configurations of the segment, s = j/k, j = 0..k, those
 * in collision; the worst by lower bound, then upper. a NULL: q alone.
 * Left NaN where the world cannot say.
 */
static void collision_depth(mpb_world *w, const double *q, double at,
                            const double *a, const double *d, double k,
                            mpb_verdict *out)
{
    double lo, up;
    if (mpb_world_depth(w, q, &lo, &up) != MPB_OK)
        return;
    out->depth_lower = lo;
    out->depth_upper = up;
    out->depth_s = at;
    const int nj = w->num_joints;
    double *p = a ? malloc((size_t)nj * sizeof *p) : NULL;
    for (double j = 0; p && j <= k; j++) {
        for (int i = 0; i < nj; i++)
            p[i] = a[i] + (j / k) * d[i];
        /* Just under the worst so far: a configuration no deeper by its
         * lower bound is spared the search (its lower comes back under
         * the worst), one as deep is measured to break the tie. */
        double floor = out->depth_lower > 0
                           ? nextafter(out->depth_lower, 0.0) : 0.0;
        if (mpb_world_in_collision(w, p) != 1 ||
            mpb__world_depth_above(w, p, floor, &lo, &up) != MPB_OK)
            continue;
        if (lo > out->depth_lower ||
            (lo == out->depth_lower && up > out->depth_upper)) {
            out->depth_lower = lo;
            out->depth_upper = up;
            out->depth_s = j / k;
        }
    }
    free(p);
}

/*
 * Collision along the path: each segment proved free or a colliding
 * configuration found (certify.c), or sampled in steps of at most
 * resolution (SAMPLED mode, a world that cannot prove, a segment the
 * proof gave up on).
 */
static int check_collision(mpb_world *w, const double *wp, int num_waypoints,
                           int nj, double resolution, mpb_verdict *out)
{
    char what[sizeof out->detail];
    const int can_prove = mpb__certify_can(w);
    if (mpb_world_in_collision(w, wp)) {
        contact(w, wp, what, sizeof what);
        verdict(out, MPB_VERDICT_COLLISION, 0, num_waypoints > 1
                ? "segment 0 collides at s=0 (waypoint 0)%s"
                : "waypoint 0 collides%s", what);
        out->certified = can_prove;
        double *d0 = num_waypoints > 1 ? malloc((size_t)nj * sizeof *d0) : NULL;
        double sq = 0.0;
        for (int j = 0; d0 && j < nj; j++) {
            d0[j] = mpb_joint_delta(wp[j], wp[nj + j], w->wraps[j]);
            sq += d0[j] * d0[j];
        }
        double k = mpb__sample_count(sqrt(sq), resolution);
        collision_depth(w, wp, 0.0, d0 && k <= MPB__MAX_SAMPLES ? wp : NULL,
                        d0, k, out);
        free(d0);
        return MPB_OK;
    }
    double *q = malloc((size_t)nj * sizeof *q);
    double *d = malloc((size_t)nj * sizeof *d);
    if (!q || !d) {
        free(q);
        free(d);
        return bad_args(out, MPB_ENOMEM, "out of memory");
    }
    int rc = MPB_OK, all_proved = can_prove;
    mpb__certify_chain chain;
    mpb__certify_begin(&chain);
    out->code = MPB_VERDICT_VALID;
    for (int i = 0; i + 1 < num_waypoints && out->code == MPB_VERDICT_VALID; i++) {
        const double *a = wp + (size_t)i * (size_t)nj, *b = a + nj;
        double sq = 0.0;
        for (int j = 0; j < nj; j++) {
            d[j] = mpb_joint_delta(a[j], b[j], w->wraps[j]);
            sq += d[j] * d[j];
        }
        double k = mpb__sample_count(sqrt(sq), resolution);
        if (k > MPB__MAX_SAMPLES) {
            rc = bad_args(out, MPB_EINVAL, "resolution too fine for the path");
            break;
        }
        double hit = -1.0, at;
        int proved = 0;
        if (can_prove) {
            mpb__certify_segment(w, &chain, a, d, sqrt(sq), q, &hit, &proved);
            if (hit >= 0) {
                contact(w, q, what, sizeof what);
                verdict(out, MPB_VERDICT_COLLISION, i,
                        "segment %d collides at s=%.17g (waypoints %d-%d)%s",
                        i, hit, i, i + 1, what);
                collision_depth(w, q, hit, a, d, k, out);
                break;
            }
        }
        if (!proved) {
            all_proved = 0;
            if (mpb__sample_segment(w, a, b, d, k, q, &at)) {
                contact(w, q, what, sizeof what);
                verdict(out, MPB_VERDICT_COLLISION, i,
                        "segment %d collides at s=%.4g (waypoints %d-%d)%s",
                        i, at, i, i + 1, what);
                collision_depth(w, q, at, a, d, k, out);
            }
        }
    }
    out->certified = all_proved;
    free(q);
    free(d);
    return rc;
}

int mpb_verify_path(struct mpb_world *w, const double *start,
                    double start_tolerance, const mpb_goal *goal,
                    const double *wp, int num_waypoints, int num_joints,
                    double resolution, mpb_verdict *out)
{
    if (!out)
        return MPB_EINVAL;
    if (!w || !start || !goal)
        return bad_args(out, MPB_EINVAL, "world, start and goal are required");
    if (num_waypoints < 0 || (num_waypoints > 0 && !wp))
        return bad_args(out, MPB_EINVAL, "no waypoint array");
    if (!(resolution > 0) || !isfinite(resolution))
        return bad_args(out, MPB_EINVAL, "resolution must be finite and > 0");
    if (!(start_tolerance >= 0))
        return bad_args(out, MPB_EINVAL, "start tolerance must be >= 0");
    if (goal->kind == MPB_GOAL_JOINTS &&
        (!goal->joints || !(goal->joint_tolerance >= 0)))
        return bad_args(out, MPB_EINVAL, "joint goal needs joints and a "
                        "tolerance >= 0");
    if (goal->kind != MPB_GOAL_JOINTS && goal->kind != MPB_GOAL_POSE_REGION)
        return bad_args(out, MPB_EINVAL, "unknown goal kind");

    const int nj = w->num_joints;

    /* EMPTY, WRONG_SIZE, NOT_FINITE */
    if (num_waypoints == 0)
        return verdict(out, MPB_VERDICT_EMPTY, -1, "no waypoints");
    if (num_joints != nj)
        return verdict(out, MPB_VERDICT_WRONG_SIZE, -1, "waypoints have %d "
                       "joints; the robot has %d", num_joints, nj);
    for (int i = 0; i < num_waypoints; i++)
        for (int j = 0; j < nj; j++)
            if (!isfinite(wp[(size_t)i * nj + j]))
                return verdict(out, MPB_VERDICT_NOT_FINITE, i, "waypoint %d "
                               "joint '%.200s' is %g", i, w->joint_names[j],
                               wp[(size_t)i * nj + j]);

    const double *last = wp + (size_t)(num_waypoints - 1) * (size_t)nj;

    /* START */
    for (int j = 0; j < nj; j++) {
        double e = joint_dist(w, j, start[j], wp[j]);
        if (!(e <= start_tolerance)) {
            int p = digits_apart(e, start_tolerance);
            return verdict(out, MPB_VERDICT_START, 0, "waypoint 0 joint "
                           "'%.200s' is %.*g from the start (tolerance %.*g)",
                           w->joint_names[j], p, e, p, start_tolerance);
        }
    }

    /* GOAL; a kind the world cannot check is decided last (UNSUPPORTED). */
    if (goal->kind == MPB_GOAL_JOINTS) {
        for (int j = 0; j < nj; j++) {
            double e = joint_dist(w, j, goal->joints[j], last[j]);
            if (!(e <= goal->joint_tolerance)) {
                int p = digits_apart(e, goal->joint_tolerance);
                return verdict(out, MPB_VERDICT_GOAL, num_waypoints - 1,
                               "waypoint %d (the last) joint '%.200s' is %.*g "
                               "from the goal (tolerance %.*g)",
                               num_waypoints - 1, w->joint_names[j], p, e, p,
                               goal->joint_tolerance);
            }
        }
    } else {
        char why[sizeof out->detail - 40];
        int in = mpb_world_goal_contains(w, goal, last, why, sizeof why);
        if (in == 0)
            return verdict(out, MPB_VERDICT_GOAL, num_waypoints - 1,
                           "waypoint %d (the last): %s", num_waypoints - 1, why);
        if (in < 0 && in != MPB_EUNSUPPORTED)
            return verdict(out, MPB_VERDICT_UNSUPPORTED, -1, "%s", why);
    }

    /* JOINT_LIMIT: continuous joints have none. */
    for (int i = 0; i < num_waypoints; i++)
        for (int j = 0; j < nj; j++) {
            double v = wp[(size_t)i * nj + j];
            if (!w->wraps[j] && (v < w->lo[j] || v > w->hi[j])) {
                int p = digits_apart(v, v < w->lo[j] ? w->lo[j] : w->hi[j]);
                return verdict(out, MPB_VERDICT_JOINT_LIMIT, i, "waypoint %d "
                               "joint '%.200s' = %.*g is outside [%.*g, %.*g]",
                               i, w->joint_names[j], p, v, p, w->lo[j], p,
                               w->hi[j]);
            }
        }

    /* COLLISION */
    int rc = check_collision(w, wp, num_waypoints, nj, resolution, out);
    if (rc != MPB_OK || out->code != MPB_VERDICT_VALID)
        return rc;

    /* UNSUPPORTED: a pose region the world cannot check. */
    if (goal->kind == MPB_GOAL_POSE_REGION && !w->provider->goal_region)
        return verdict(out, MPB_VERDICT_UNSUPPORTED, -1, "pose-region goals "
                       "cannot be checked in a '%s' world",
                       w->provider->robot_format);

    int certified = out->certified;
    verdict(out, MPB_VERDICT_VALID, -1, "valid");
    out->certified = certified;
    return MPB_OK;
}
