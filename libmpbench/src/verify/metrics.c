/* metrics.c - path length, smoothness and clearance of one joint-space path. */
#include "mpbench/mpbench.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/mathconst.h"
#include "model/world_provider.h"

/* A segment at most this long (joint-space norm) has no direction. */
#define MPB__ZERO_SEGMENT 1e-12

/* A turn smaller than this (rad) is the rounding of two unit vectors that
 * point the same way, not a turn: it counts as 0. Its square, 1e-18 rad^2,
 * is below anything a report shows. */
#define MPB__ZERO_ANGLE 1e-9

double mpb_joint_delta(double a, double b, int wraps)
{
    double d = b - a;
    if (!wraps)
        return d;
    /* remainder() gives [-pi, pi]; the short way round is (-pi, pi]. */
    d = remainder(d, 2.0 * M_PI);
    if (d <= -M_PI)
        d += 2.0 * M_PI;
    return d;
}

/* Joint-space length of the segment from waypoint i to i + 1. */
static double segment(const double *wp, int i, int num_joints,
                      mpb_joint_wrap continuous)
{
    const double *a = wp + (size_t)i * (size_t)num_joints;
    const double *b = a + num_joints;
    double sq = 0.0;
    for (int j = 0; j < num_joints; j++) {
        double d = mpb_joint_delta(a[j], b[j], continuous && continuous[j]);
        sq += d * d;
    }
    return sqrt(sq);
}

double mpb_path_length(const double *wp, int num_waypoints, int num_joints,
                       mpb_joint_wrap continuous)
{
    if (!wp || num_waypoints < 2 || num_joints < 1)
        return 0.0;
    double len = 0.0;
    for (int i = 0; i + 1 < num_waypoints; i++)
        len += segment(wp, i, num_joints, continuous);
    return len;
}

/*
 * The angle (rad) between segments a and b of lengths la, lb > 0, by Kahan's
 * formula 2 atan2(|u - v|, |u + v|) on the unit vectors u = a/la, v = b/lb:
 * accurate near 0 and pi, where acos of the dot product is not.
 */
static double segment_angle(const double *wp, int a, double la, int b,
                            double lb, int num_joints,
                            mpb_joint_wrap continuous)
{
    const double *a0 = wp + (size_t)a * (size_t)num_joints;
    const double *b0 = wp + (size_t)b * (size_t)num_joints;
    double dm = 0.0, dp = 0.0;
    for (int j = 0; j < num_joints; j++) {
        int wraps = continuous && continuous[j];
        double u = mpb_joint_delta(a0[j], a0[j + num_joints], wraps) / la;
        double v = mpb_joint_delta(b0[j], b0[j + num_joints], wraps) / lb;
        dm += (u - v) * (u - v);
        dp += (u + v) * (u + v);
    }
    double angle = 2.0 * atan2(sqrt(dm), sqrt(dp));
    return angle < MPB__ZERO_ANGLE ? 0.0 : angle;
}

/* The angle between vectors u and v of lengths lu, lv > 0, as above. */
static double vector_angle(const double *u, double lu, const double *v,
                           double lv, int n)
{
    double dm = 0.0, dp = 0.0;
    for (int j = 0; j < n; j++) {
        double a = u[j] / lu, b = v[j] / lv;
        dm += (a - b) * (a - b);
        dp += (a + b) * (a + b);
    }
    double angle = 2.0 * atan2(sqrt(dm), sqrt(dp));
    return angle < MPB__ZERO_ANGLE ? 0.0 : angle;
}

static double norm(const double *v, int n)
{
    double sq = 0.0;
    for (int j = 0; j < n; j++)
        sq += v[j] * v[j];
    return sqrt(sq);
}

double mpb_smoothness(const double *wp, int num_waypoints, int num_joints,
                      mpb_joint_wrap continuous)
{
    if (!wp || num_waypoints < 3 || num_joints < 1)
        return 0.0;
    int n = 0;              /* segments longer than MPB__ZERO_SEGMENT */
    int prev = -1;          /* the last of them */
    double prev_len = 0.0, sum = 0.0;
    for (int i = 0; i + 1 < num_waypoints; i++) {
        double len = segment(wp, i, num_joints, continuous);
        if (isnan(len))
            return NAN;
        if (!(len > MPB__ZERO_SEGMENT))
            continue;
        if (prev >= 0) {
            double a = segment_angle(wp, prev, prev_len, i, len, num_joints,
                                     continuous);
            sum += a * a;
        }
        prev = i;
        prev_len = len;
        n++;
    }
    return n < 2 ? 0.0 : sum / n;
}

/*
 * The path cut into MPB_SMOOTHNESS_SEGMENTS pieces of equal joint-space
 * length, each piece taken as the vector from its start to its end (the
 * sum of the parts of the waypoint segments it covers, so continuous
 * joints need no care), and kappa' of those vectors. Where the pieces
 * fall depends only on the path's shape, never on its waypoints.
 */
double mpb_smoothness_resampled(const double *wp, int num_waypoints,
                                int num_joints, mpb_joint_wrap continuous)
{
    if (!wp || num_waypoints < 3 || num_joints < 1)
        return 0.0;
    double total = mpb_path_length(wp, num_waypoints, num_joints, continuous);
    if (isnan(total))
        return NAN;
    if (!(total > MPB__ZERO_SEGMENT))
        return 0.0;
    const int m = MPB_SMOOTHNESS_SEGMENTS;
    double *buf = calloc(3 * (size_t)num_joints, sizeof *buf);
    if (buf == NULL)
        return NAN;
    double *piece = buf, *prev = buf + num_joints, *d = buf + 2 * num_joints;
    double prev_len = 0.0, sum = 0.0, start = 0.0;  /* start: of segment i */
    int k = 0;              /* the piece being filled, [0, m) */
    for (int i = 0; i + 1 < num_waypoints; i++) {
        const double *a = wp + (size_t)i * (size_t)num_joints;
        double len = 0.0;
        for (int j = 0; j < num_joints; j++) {
            d[j] = mpb_joint_delta(a[j], a[j + num_joints],
                                   continuous && continuous[j]);
            len += d[j] * d[j];
        }
        len = sqrt(len);
        if (!(len > MPB__ZERO_SEGMENT))
            continue;
        double end = start + len, at = start;
        /* Close every piece whose end, (k + 1) total / m, lies in this
         * segment; the last piece closes after the last segment. */
        while (k + 1 < m && (double)(k + 1) * total / m <= end) {
            double b = (double)(k + 1) * total / m;
            for (int j = 0; j < num_joints; j++)
                piece[j] += (b - at) / len * d[j];
            double plen = norm(piece, num_joints);
            if (k > 0 && plen > MPB__ZERO_SEGMENT && prev_len > 0.0) {
                double an = vector_angle(prev, prev_len, piece, plen,
                                         num_joints);
                sum += an * an;
            }
            memcpy(prev, piece, sizeof *piece * (size_t)num_joints);
            prev_len = plen;
            memset(piece, 0, sizeof *piece * (size_t)num_joints);
            at = b;
            k++;
        }
        for (int j = 0; j < num_joints; j++)
            piece[j] += (end - at) / len * d[j];
        start = end;
    }
    double plen = norm(piece, num_joints);
    if (plen > MPB__ZERO_SEGMENT && prev_len > 0.0) {
        double an = vector_angle(prev, prev_len, piece, plen, num_joints);
        sum += an * an;
    }
    free(buf);
    return sum / m;
}

void mpb_path_clearances(mpb_world *w, const double *wp, int num_waypoints,
                         int num_joints, double *mean, double *least)
{
    double sum = 0.0, low = INFINITY;
    if (!w || !wp || num_waypoints < 1 || num_joints != mpb_world_num_joints(w)) {
        sum = low = NAN;
    } else {
        for (int i = 0; i < num_waypoints; i++) {
            double c = mpb_world_clearance(w, wp + (size_t)i * (size_t)num_joints);
            sum += c;
            if (isnan(c))
                low = NAN;
            else if (c < low)
                low = c;
        }
        sum /= num_waypoints;
    }
    if (mean)
        *mean = sum;
    if (least)
        *least = low;
}

double mpb_path_clearance(mpb_world *w, const double *wp,
                          int num_waypoints, int num_joints)
{
    double mean;
    mpb_path_clearances(w, wp, num_waypoints, num_joints, &mean, NULL);
    return mean;
}

double mpb_path_min_clearance(mpb_world *w, const double *wp,
                              int num_waypoints, int num_joints)
{
    double least;
    mpb_path_clearances(w, wp, num_waypoints, num_joints, NULL, &least);
    return least;
}

/* Points of one segment the end effector's positions are taken in at a
 * time (mpb_ee_path_length()). */
#define MPB__EE_CHUNK 64

/* |b - a| of two points. */
static double dist3(const double *a, const double *b)
{
    return sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
                (b[2] - a[2]) * (b[2] - a[2]));
}

/*
 * The end effector at a + (k / steps) d, k = first..first + count - 1, into
 * xyz: the world's sweep of the segment where it has one (forward
 * kinematics of the end effector alone, model/robot_fk.c), else point by
 * point. Returns MPB_OK or a negative code.
 */
static int ee_points(mpb_world *w, const double *a, const double *d,
                     int steps, int first, int count, double *q, double *xyz)
{
    const int nj = w->num_joints;
    if (w->provider->ee_sweep != NULL &&
        w->provider->ee_sweep(w->impl, a, d, steps, first, count, xyz) ==
            MPB_OK)
        return MPB_OK;
    for (int k = 0; k < count; k++) {
        double s = (double)(first + k) / steps;
        for (int j = 0; j < nj; j++)
            q[j] = a[j] + s * d[j];
        if (mpb_world_ee_position(w, q, xyz + 3 * k) != MPB_OK)
            return MPB_EINVAL;
    }
    return MPB_OK;
}

double mpb_ee_path_length(mpb_world *w, const double *wp, int num_waypoints,
                          int num_joints, double resolution)
{
    if (!w || !wp || num_waypoints < 1 || !(resolution > 0) ||
        num_joints != mpb_world_num_joints(w) || num_joints > 64)
        return NAN;
    for (size_t i = 0; i < (size_t)num_waypoints * (size_t)num_joints; i++)
        if (!isfinite(wp[i]))
            return NAN;
    const unsigned char *wraps = mpb_world_joint_wraps(w);
    double q[64], prev[3], pts[3 * MPB__EE_CHUNK], total = 0.0;
    if (mpb_world_ee_position(w, wp, prev) != MPB_OK)
        return NAN;
    for (int i = 0; i + 1 < num_waypoints; i++) {
        const double *a = wp + (size_t)i * (size_t)num_joints;
        const double *b = a + num_joints;
        double d[64], len2 = 0.0;
        for (int j = 0; j < num_joints; j++) {
            d[j] = mpb_joint_delta(a[j], b[j], wraps && wraps[j]);
            len2 += d[j] * d[j];
        }
        int steps = (int)ceil(sqrt(len2) / resolution);
        if (steps < 1)
            steps = 1;
        for (int k = 1; k <= steps; k += MPB__EE_CHUNK) {
            int count = steps - k + 1 < MPB__EE_CHUNK ? steps - k + 1
                                                      : MPB__EE_CHUNK;
            if (ee_points(w, a, d, steps, k, count, q, pts) != MPB_OK)
                return NAN;
            for (int n = 0; n < count; n++) {
                total += dist3(prev, pts + 3 * n);
                memcpy(prev, pts + 3 * n, sizeof prev);
            }
        }
    }
    return total;
}

int mpb_times_ok(const double *times, int num_times, int num_waypoints,
                 char *why, size_t whylen)
{
    char local[8];
    if (why == NULL) {
        why = local;
        whylen = sizeof local;
    }
    if (num_times != num_waypoints) {
        snprintf(why, whylen, "%d waypoint times for %d waypoints", num_times,
                 num_waypoints);
        return 0;
    }
    for (int i = 0; i < num_times; i++) {
        if (times == NULL || !isfinite(times[i])) {
            snprintf(why, whylen, "time %d is %s", i,
                     times == NULL ? "missing" : "not finite");
            return 0;
        }
        if (i == 0 && times[0] < 0) {
            snprintf(why, whylen, "time 0 (%.17g s) is negative", times[0]);
            return 0;
        }
        if (i > 0 && times[i] < times[i - 1]) {
            snprintf(why, whylen, "time %d (%.17g s) is below time %d "
                     "(%.17g s)", i, times[i], i - 1, times[i - 1]);
            return 0;
        }
    }
    return 1;
}

/* Joint j's velocity from waypoint a to b, dt apart: 0 where it does not
 * move (even in no time), infinite where it moves in none. */
static double joint_velocity(const double *a, const double *b, int j,
                             double dt, mpb_joint_wrap continuous)
{
    double d = mpb_joint_delta(a[j], b[j], continuous && continuous[j]);
    return d == 0.0 ? 0.0 : d / dt;
}

int mpb_path_timing(const double *wp, const double *times, int num_waypoints,
                    int num_joints, mpb_joint_wrap continuous,
                    const double *max_velocity, mpb_timing *out)
{
    if (out == NULL)
        return MPB_EINVAL;
    *out = (mpb_timing){NAN, NAN, NAN, NAN, -1, -1};
    if (wp == NULL || times == NULL || num_waypoints < 1 || num_joints < 1)
        return MPB_EINVAL;
    out->duration = times[num_waypoints - 1] - times[0];
    out->max_velocity = out->max_acceleration = 0.0;
    int prev = -1;          /* the segment before that was kept */
    for (int i = 0; i + 1 < num_waypoints; i++) {
        const double *a = wp + (size_t)i * (size_t)num_joints;
        const double *b = a + num_joints;
        double dt = times[i + 1] - times[i];
        int moves = 0;
        for (int j = 0; j < num_joints && !moves; j++)
            moves = joint_velocity(a, b, j, 1.0, continuous) != 0.0;
        if (!moves && !(dt > 0.0))
            continue;               /* a waypoint repeated at its time */
        for (int j = 0; j < num_joints; j++) {
            double v = joint_velocity(a, b, j, dt, continuous);
            if (fabs(v) > out->max_velocity)
                out->max_velocity = fabs(v);
            if (max_velocity != NULL && max_velocity[j] > 0) {
                double r = fabs(v) / max_velocity[j];
                if (isnan(out->velocity_ratio) || r > out->velocity_ratio) {
                    out->velocity_ratio = r;
                    out->ratio_segment = i;
                    out->ratio_joint = j;
                }
            }
            if (prev < 0)
                continue;
            const double *p = wp + (size_t)prev * (size_t)num_joints;
            double pdt = times[prev + 1] - times[prev];
            double pv = joint_velocity(p, a, j, pdt, continuous);
            double acc = fabs(v - pv) / ((dt + pdt) / 2.0);
            if (isnan(acc))         /* infinite velocities, or no time */
                acc = v == pv && isfinite(v) ? 0.0 : INFINITY;
            if (acc > out->max_acceleration)
                out->max_acceleration = acc;
        }
        prev = i;
    }
    return MPB_OK;
}
