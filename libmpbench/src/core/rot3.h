/*
 * rot3.h - 3x3 rotation matrices (row-major double[9]): products, the
 * rotation about an axis, and back from a rotation to its angle and
 * rotation vector; not part of the API. Inline: forward kinematics runs
 * them in its inner loop.
 */
#ifndef MPB_ROT3_H
#define MPB_ROT3_H

#include "core/mathconst.h"

/* c = a * b, 3x3 row-major; c must not alias a or b. */
static inline void mpb__mat3_mul(const double *a, const double *b, double *c)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            c[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j]
                         + a[3 * i + 2] * b[6 + j];
}

/* out = R * v */
static inline void mpb__mat3_vec(const double *R, const double *v, double *out)
{
    for (int i = 0; i < 3; i++)
        out[i] = R[3 * i] * v[0] + R[3 * i + 1] * v[1] + R[3 * i + 2] * v[2];
}

/* c = a^T * b */
static inline void mpb__mat3_tmul(const double *a, const double *b, double *c)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            c[3 * i + j] = a[i] * b[j] + a[3 + i] * b[3 + j]
                         + a[6 + i] * b[6 + j];
}

/* Rotation by angle about the unit axis a (Rodrigues). */
static inline void mpb__rot_axis(const double a[3], double angle, double R[9])
{
    double c = cos(angle), s = sin(angle), C = 1.0 - c;
    double x = a[0], y = a[1], z = a[2];
    R[0] = c + x * x * C;     R[1] = x * y * C - z * s; R[2] = x * z * C + y * s;
    R[3] = y * x * C + z * s; R[4] = c + y * y * C;     R[5] = y * z * C - x * s;
    R[6] = z * x * C - y * s; R[7] = z * y * C + x * s; R[8] = c + z * z * C;
}

/* The angle of rotation R, in [0, pi]. */
static inline double mpb__rot_angle(const double R[9])
{
    double v0 = R[7] - R[5], v1 = R[2] - R[6], v2 = R[3] - R[1];
    double s = 0.5 * sqrt(v0 * v0 + v1 * v1 + v2 * v2);
    double c = 0.5 * (R[0] + R[4] + R[8] - 1.0);
    return atan2(s, c);
}

/* The rotation vector (axis * angle, angle in [0, pi]) of rotation R. */
static inline void mpb__rot_log(const double R[9], double w[3])
{
    double v[3] = { R[7] - R[5], R[2] - R[6], R[3] - R[1] }; /* 2 sin(th) a */
    double s = 0.5 * sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    double c = 0.5 * (R[0] + R[4] + R[8] - 1.0);
    double th = atan2(s, c);
    if (c > 0.0 || s > 1e-6) {
        double f = s > 1e-12 ? th / (2.0 * s) : 0.5;
        w[0] = f * v[0];
        w[1] = f * v[1];
        w[2] = f * v[2];
        return;
    }
    /* Near pi: R ~ 2 a a^T - I, so (R + I) / 2 ~ a a^T. */
    int k = 0;
    if (R[4] > R[k * 4])
        k = 1;
    if (R[8] > R[k * 4])
        k = 2;
    double B[9];
    for (int i = 0; i < 9; i++)
        B[i] = 0.5 * (R[i] + ((i % 4 == 0) ? 1.0 : 0.0));
    double a[3];
    double ak = sqrt(fmax(B[4 * k], 0.0));
    for (int i = 0; i < 3; i++)
        a[i] = i == k ? ak : (ak > 0 ? 0.5 * (B[3 * k + i] + B[3 * i + k]) / ak : 0.0);
    double n = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (n <= 0.0) {
        w[0] = w[1] = w[2] = 0.0;
        return;
    }
    double sign = (a[0] * v[0] + a[1] * v[1] + a[2] * v[2]) < 0 ? -1.0 : 1.0;
    for (int i = 0; i < 3; i++)
        w[i] = sign * th * a[i] / n;
}

/* 1 if R is exactly the identity. */
static inline int mpb__is_identity3(const double R[9])
{
    for (int i = 0; i < 9; i++)
        if (R[i] != ((i % 4 == 0) ? 1.0 : 0.0))
            return 0;
    return 1;
}

#endif /* MPB_ROT3_H */
