/*
 * pose.h - a rigid transform (rotation and translation) shared by the
 * kinematics, the scenes and the collision world, and small inline helpers
 * to build and combine them. Header only; needs <math.h> (link with -lm).
 *
 * A pose maps coordinates of a child frame into its parent frame:
 *     p_parent = R * p_child + t
 * R is row-major: R[3 * row + col]. Units: metres.
 *
 * Quaternions are (x, y, z, w), the order of MoveIt's .scene files and of
 * geometry_msgs/Quaternion. Roll/pitch/yaw follow URDF: R = Rz(yaw) *
 * Ry(pitch) * Rx(roll), angles in radians.
 */
#ifndef MPBENCH_POSE_H
#define MPBENCH_POSE_H

#include <math.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mpb_pose { double R[9]; double t[3]; } mpb_pose; /* rotation row-major, translation m */

/* The identity pose. */
static inline void mpb_pose_identity(mpb_pose *p)
{
    for (int i = 0; i < 9; i++)
        p->R[i] = (i % 4 == 0) ? 1.0 : 0.0;
    p->t[0] = p->t[1] = p->t[2] = 0.0;
}

/*
 * Set p->R from the quaternion (x, y, z, w), normalised first; p->t is left
 * alone. Returns MPB_OK, or MPB_EERROR (-1: this header stands alone) for
 * a quaternion that is zero or not finite (then R is the identity). Any
 * other scale is fine: 1e300 and 1e-300 included.
 */
static inline int mpb_pose_set_quat(mpb_pose *p, double x, double y,
                                    double z, double w)
{
    /* Scaled by the largest first, so that the squares cannot overflow
     * or underflow. */
    double s = fmax(fmax(fabs(x), fabs(y)), fmax(fabs(z), fabs(w)));
    if (!(s > 0.0) || !isfinite(x) || !isfinite(y) || !isfinite(z) ||
        !isfinite(w)) {
        for (int i = 0; i < 9; i++)
            p->R[i] = (i % 4 == 0) ? 1.0 : 0.0;
        return -1;
    }
    x /= s; y /= s; z /= s; w /= s;
    double n = sqrt(x * x + y * y + z * z + w * w);   /* in 1 .. 2 */
    x /= n; y /= n; z /= n; w /= n;
    p->R[0] = 1 - 2 * (y * y + z * z);
    p->R[1] = 2 * (x * y - z * w);
    p->R[2] = 2 * (x * z + y * w);
    p->R[3] = 2 * (x * y + z * w);
    p->R[4] = 1 - 2 * (x * x + z * z);
    p->R[5] = 2 * (y * z - x * w);
    p->R[6] = 2 * (x * z - y * w);
    p->R[7] = 2 * (y * z + x * w);
    p->R[8] = 1 - 2 * (x * x + y * y);
    return 0;
}

/* The unit quaternion of p->R as q[0..3] = x y z w, with w >= 0. */
static inline void mpb_pose_get_quat(const mpb_pose *p, double q[4])
{
    const double *R = p->R;
    double tr = R[0] + R[4] + R[8], x, y, z, w;
    if (tr > 0) {
        double s = 2 * sqrt(tr + 1.0);
        w = 0.25 * s;
        x = (R[7] - R[5]) / s;
        y = (R[2] - R[6]) / s;
        z = (R[3] - R[1]) / s;
    } else if (R[0] > R[4] && R[0] > R[8]) {
        double s = 2 * sqrt(1.0 + R[0] - R[4] - R[8]);
        w = (R[7] - R[5]) / s;
        x = 0.25 * s;
        y = (R[1] + R[3]) / s;
        z = (R[2] + R[6]) / s;
    } else if (R[4] > R[8]) {
        double s = 2 * sqrt(1.0 + R[4] - R[0] - R[8]);
        w = (R[2] - R[6]) / s;
        x = (R[1] + R[3]) / s;
        y = 0.25 * s;
        z = (R[5] + R[7]) / s;
    } else {
        double s = 2 * sqrt(1.0 + R[8] - R[0] - R[4]);
        w = (R[3] - R[1]) / s;
        x = (R[2] + R[6]) / s;
        y = (R[5] + R[7]) / s;
        z = 0.25 * s;
    }
    double sign = w < 0 ? -1.0 : 1.0;
    double n = sqrt(x * x + y * y + z * z + w * w);
    q[0] = sign * x / n;
    q[1] = sign * y / n;
    q[2] = sign * z / n;
    q[3] = sign * w / n;
}

/* Set p->R from URDF roll, pitch, yaw; p->t is left alone. */
static inline void mpb_pose_set_rpy(mpb_pose *p, double roll, double pitch,
                                    double yaw)
{
    double cr = cos(roll), sr = sin(roll);
    double cp = cos(pitch), sp = sin(pitch);
    double cy = cos(yaw), sy = sin(yaw);
    p->R[0] = cy * cp;
    p->R[1] = cy * sp * sr - sy * cr;
    p->R[2] = cy * sp * cr + sy * sr;
    p->R[3] = sy * cp;
    p->R[4] = sy * sp * sr + cy * cr;
    p->R[5] = sy * sp * cr - cy * sr;
    p->R[6] = -sp;
    p->R[7] = cp * sr;
    p->R[8] = cp * cr;
}

/*
 * Roll, pitch, yaw of p->R (rpy[0..2]); pitch in [-pi/2, pi/2], roll and
 * yaw in (-pi, pi]. At pitch = +-pi/2 (gimbal lock) yaw is reported as 0.
 */
static inline void mpb_pose_get_rpy(const mpb_pose *p, double rpy[3])
{
    const double *R = p->R;
    double c = sqrt(R[0] * R[0] + R[3] * R[3]);
    rpy[1] = atan2(-R[6], c);
    if (c > 1e-12) {
        rpy[0] = atan2(R[7], R[8]);
        rpy[2] = atan2(R[3], R[0]);
    } else {
        rpy[0] = atan2(-R[5], R[4]);
        rpy[2] = 0.0;
    }
}

/*
 * 1 if every number of p is finite and p->R is a rotation (R^T R = I and
 * det R = +1, each to within 1e-6), else 0.
 */
static inline int mpb_pose_is_rigid(const mpb_pose *p)
{
    for (int i = 0; i < 9; i++)
        if (!isfinite(p->R[i]))
            return 0;
    for (int i = 0; i < 3; i++)
        if (!isfinite(p->t[i]))
            return 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double d = p->R[i] * p->R[j] + p->R[3 + i] * p->R[3 + j]
                     + p->R[6 + i] * p->R[6 + j] - (i == j ? 1.0 : 0.0);
            if (fabs(d) > 1e-6)
                return 0;
        }
    const double *R = p->R;
    double det = R[0] * (R[4] * R[8] - R[5] * R[7])
               - R[1] * (R[3] * R[8] - R[5] * R[6])
               + R[2] * (R[3] * R[7] - R[4] * R[6]);
    return fabs(det - 1.0) <= 1e-6;
}

/* out = a * b (apply b, then a); out may be a or b. */
static inline void mpb_pose_mul(const mpb_pose *a, const mpb_pose *b,
                                mpb_pose *out)
{
    mpb_pose r;
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            r.R[3 * i + j] = a->R[3 * i] * b->R[j] + a->R[3 * i + 1] * b->R[3 + j]
                           + a->R[3 * i + 2] * b->R[6 + j];
        r.t[i] = a->R[3 * i] * b->t[0] + a->R[3 * i + 1] * b->t[1]
               + a->R[3 * i + 2] * b->t[2] + a->t[i];
    }
    *out = r;
}

/* The inverse of a rigid pose (R orthonormal); out may be p. */
static inline void mpb_pose_inverse(const mpb_pose *p, mpb_pose *out)
{
    mpb_pose r;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            r.R[3 * i + j] = p->R[3 * j + i];
    for (int i = 0; i < 3; i++)
        r.t[i] = -(r.R[3 * i] * p->t[0] + r.R[3 * i + 1] * p->t[1]
                   + r.R[3 * i + 2] * p->t[2]);
    *out = r;
}

/* out = R * v + t, a point of the child frame in the parent frame; out may be v. */
static inline void mpb_pose_apply(const mpb_pose *p, const double v[3],
                                  double out[3])
{
    double x = v[0], y = v[1], z = v[2];
    for (int i = 0; i < 3; i++)
        out[i] = p->R[3 * i] * x + p->R[3 * i + 1] * y + p->R[3 * i + 2] * z + p->t[i];
}

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_POSE_H */
