/*
 * robot_fk.c - forward kinematics: how a link's pose follows from its
 * parent's (with shortcuts for identity origins and axes along x, y or
 * z), the static poses, and the poses of the links for a configuration.
 */
#include "mpbench/mpbench.h"
#include "mpbench/robot.h"

#include <math.h>
#include <string.h>

#include "core/rot3.h"
#include "model/robot_internal.h"

/* The motion of a joint at value v, as a pose of the child in the joint frame. */
static void joint_motion(mpb_joint_type type, const double axis[3], double v,
                         mpb_pose *m)
{
    mpb_pose_identity(m);
    switch (type) {
    case MPB_JOINT_REVOLUTE:
    case MPB_JOINT_CONTINUOUS:
        mpb__rot_axis(axis, v, m->R);
        break;
    case MPB_JOINT_PRISMATIC:
        for (int i = 0; i < 3; i++)
            m->t[i] = axis[i] * v;
        break;
    default:
        break;
    }
}

/* out->t = P.R v + P.t, out->R = P.R: P followed by a pure translation v. */
static void translate(const mpb_pose *P, const double v[3], mpb_pose *out)
{
    memcpy(out->R, P->R, sizeof P->R);
    mpb__mat3_vec(P->R, v, out->t);
    for (int j = 0; j < 3; j++)
        out->t[j] += P->t[j];
}

/* out = A * (rotation by angle with cosine c and sine s about axis k). */
static void rotate_cols(const double *A, int k, double c, double s, double *out)
{
    int a = (k + 1) % 3, b = (k + 2) % 3;   /* x: y z; y: z x; z: x y */
    for (int r = 0; r < 3; r++) {
        const double *row = A + 3 * r;
        out[3 * r + k] = row[k];
        out[3 * r + a] = c * row[a] + s * row[b];
        out[3 * r + b] = -s * row[a] + c * row[b];
    }
}

/* The pose of link i from its parent's pose; q indexed by active joint. */
static void link_step(const mpb_robot *r, int i, const double *q,
                      const mpb_pose *parent, mpb_pose *out)
{
    const mpb__kin *k = &r->kin[i];
    if (k->chain < 0 && k->mimic < 0) {
        if (k->fixed_pure)
            translate(parent, k->fixed.t, out);
        else
            mpb_pose_mul(parent, &k->fixed, out);
        return;
    }
    mpb_pose a;
    if (k->origin_pure)
        translate(parent, k->origin.t, &a);
    else
        mpb_pose_mul(parent, &k->origin, &a);
    double v = k->chain >= 0 ? q[k->chain] : k->mimic_m * q[k->mimic] + k->mimic_o;
    if (k->type == MPB_JOINT_PRISMATIC) {
        double d[3] = { k->axis[0] * v, k->axis[1] * v, k->axis[2] * v };
        translate(&a, d, out);
    } else if (k->axis_k >= 0) {
        double ang = k->axis_sign * v;
        rotate_cols(a.R, k->axis_k, cos(ang), sin(ang), out->R);
        memcpy(out->t, a.t, sizeof a.t);
    } else {
        double M[9];
        mpb__rot_axis(k->axis, v, M);
        mpb__mat3_mul(a.R, M, out->R);
        memcpy(out->t, a.t, sizeof a.t);
    }
}

void mpb__robot_path_poses(const mpb_robot *r, const double *q, int link,
                           mpb_pose *P, mpb_pose *out)
{
    int len = r->path_len[link];
    if (len == 0) {
        *out = r->static_pose[link];
        return;
    }
    const int *path = r->path_pool + r->path_off[link];
    const mpb_pose *prev = &r->static_pose[r->links[path[0]].parent];
    for (int k = 0; k < len; k++) {
        link_step(r, path[k], q, prev, &P[k]);
        prev = &P[k];
    }
    *out = P[len - 1];
}

void mpb__robot_compute_static(mpb_robot *r)
{
    for (int i = 0; i < r->num_links; i++) {
        mpb_pose_identity(&r->static_pose[i]);
        if (r->links[i].moves || r->links[i].parent < 0)
            continue;
        mpb_pose_mul(&r->static_pose[r->links[i].parent], &r->kin[i].fixed,
                     &r->static_pose[i]);
    }
}

void mpb__robot_set_fixed(mpb__kin *k)
{
    mpb_pose m;
    joint_motion(k->type, k->axis, k->passive, &m);
    mpb_pose_mul(&k->origin, &m, &k->fixed);
    k->fixed_pure = mpb__is_identity3(k->fixed.R);
}

void mpb__robot_kin_shortcuts(mpb__kin *k)
{
    k->origin_pure = mpb__is_identity3(k->origin.R);
    k->axis_k = -1;
    k->axis_sign = 1.0;
    for (int d = 0; d < 3; d++)
        if (fabs(k->axis[d]) == 1.0 && k->axis[(d + 1) % 3] == 0.0
            && k->axis[(d + 2) % 3] == 0.0) {
            k->axis_k = d;
            k->axis_sign = k->axis[d] > 0 ? 1.0 : -1.0;
        }
}

/* ---- forward kinematics -------------------------------------------------- */

int mpb_robot_fk_moving(const mpb_robot *r, const double *q, mpb_pose *poses)
{
    if (!r || !q || !poses || !mpb__robot_q_finite(r, q))
        return MPB_EINVAL;
    for (int m = 0; m < r->num_moving; m++) {
        int i = r->moving[m];
        int p = r->links[i].parent;
        const mpb_pose *pp = r->links[p].moves ? &poses[p] : &r->static_pose[p];
        link_step(r, i, q, pp, &poses[i]);
    }
    return MPB_OK;
}

int mpb_robot_fk(const mpb_robot *r, const double *q, mpb_pose *poses)
{
    if (!r || !q || !poses || !mpb__robot_q_finite(r, q))
        return MPB_EINVAL;
    memcpy(poses, r->static_pose, (size_t)r->num_links * sizeof *poses);
    return mpb_robot_fk_moving(r, q, poses);
}

int mpb_robot_link_pose(const mpb_robot *r, const double *q, int link,
                        mpb_pose *out)
{
    if (!r || !q || !out || link < 0 || link >= r->num_links ||
        !mpb__robot_q_finite(r, q))
        return MPB_EINVAL;
    int len = r->path_len[link];
    if (len == 0) {
        *out = r->static_pose[link];
        return MPB_OK;
    }
    const int *path = r->path_pool + r->path_off[link];
    mpb_pose a = r->static_pose[r->links[path[0]].parent], b;
    for (int k = 0; k < len; k++) {
        link_step(r, path[k], q, &a, &b);
        a = b;
    }
    *out = a;
    return MPB_OK;
}

/* ---- a link's origin along a straight joint-space segment ---------------- */

/* The longest path (moving ancestors and the link) a sweep takes. */
#define MPB__SWEEP_MAX_PATH 64

int mpb__robot_link_sweep(const mpb_robot *r, int link, const double *a,
                          const double *d, int steps, int first, int count,
                          double *xyz);

/* Joints whose cosine and sine are re-taken from cos() and sin() after
 * this many steps of the rotation recurrence, so rounding cannot pile up
 * (each step adds about 1e-16 to them). */
#define MPB__SWEEP_RESEED 32

/* One joint of a link's path as the sweep takes it. */
typedef struct sweep_joint {
    const mpb__kin *k;
    double v0, dv;          /* value at a, and per step of s */
    double c, s, cd, sd;    /* revolute: cos, sin now and of one step */
} sweep_joint;

/* x <- motion of joint j at its value now, then the joint's origin. */
static void sweep_apply(const sweep_joint *j, double v, double x[3])
{
    const mpb__kin *k = j->k;
    double y[3];
    if (k->chain < 0 && k->mimic < 0) {
        if (k->fixed_pure) {
            for (int i = 0; i < 3; i++)
                x[i] += k->fixed.t[i];
        } else {
            mpb__mat3_vec(k->fixed.R, x, y);
            for (int i = 0; i < 3; i++)
                x[i] = y[i] + k->fixed.t[i];
        }
        return;
    }
    if (k->type == MPB_JOINT_PRISMATIC) {
        for (int i = 0; i < 3; i++)
            y[i] = x[i] + k->axis[i] * v;
    } else if (k->axis_k >= 0) {
        int a = (k->axis_k + 1) % 3, b = (k->axis_k + 2) % 3;
        y[k->axis_k] = x[k->axis_k];
        y[a] = j->c * x[a] - j->s * x[b];
        y[b] = j->s * x[a] + j->c * x[b];
    } else {
        double M[9], c = j->c, s = j->s, C = 1.0 - c;
        double ax = k->axis[0], ay = k->axis[1], az = k->axis[2];
        M[0] = c + ax * ax * C;      M[1] = ax * ay * C - az * s;
        M[2] = ax * az * C + ay * s; M[3] = ay * ax * C + az * s;
        M[4] = c + ay * ay * C;      M[5] = ay * az * C - ax * s;
        M[6] = az * ax * C - ay * s; M[7] = az * ay * C + ax * s;
        M[8] = c + az * az * C;
        mpb__mat3_vec(M, x, y);
    }
    if (k->origin_pure) {
        for (int i = 0; i < 3; i++)
            x[i] = y[i] + k->origin.t[i];
    } else {
        mpb__mat3_vec(k->origin.R, y, x);
        for (int i = 0; i < 3; i++)
            x[i] += k->origin.t[i];
    }
}

int mpb__robot_link_sweep(const mpb_robot *r, int link, const double *a,
                          const double *d, int steps, int first, int count,
                          double *xyz)
{
    if (!r || !a || !d || !xyz || steps < 1 || first < 0 || count < 0 ||
        link < 0 || link >= r->num_links)
        return MPB_EINVAL;
    int len = r->path_len[link];
    if (len > MPB__SWEEP_MAX_PATH)
        return MPB_EUNSUPPORTED;
    sweep_joint J[MPB__SWEEP_MAX_PATH];
    const int *path = len > 0 ? r->path_pool + r->path_off[link] : NULL;
    const mpb_pose *base = len > 0
        ? &r->static_pose[r->links[path[0]].parent] : &r->static_pose[link];
    for (int e = 0; e < len; e++) {
        const mpb__kin *k = &r->kin[path[e]];
        sweep_joint *j = &J[e];
        j->k = k;
        j->v0 = j->dv = 0.0;
        if (k->chain >= 0) {
            j->v0 = a[k->chain];
            j->dv = d[k->chain];
        } else if (k->mimic >= 0) {
            j->v0 = k->mimic_m * a[k->mimic] + k->mimic_o;
            j->dv = k->mimic_m * d[k->mimic];
        }
    }
    for (int n = first; n < first + count; n++) {
        double f = (double)n / steps;
        for (int e = 0; e < len; e++) {
            sweep_joint *j = &J[e];
            const mpb__kin *k = j->k;
            if ((k->chain < 0 && k->mimic < 0) ||
                k->type == MPB_JOINT_PRISMATIC)
                continue;
            double sign = k->axis_k >= 0 ? k->axis_sign : 1.0;
            if ((n - first) % MPB__SWEEP_RESEED == 0) {
                double ang = sign * (j->v0 + f * j->dv);
                double step = sign * j->dv / steps;
                j->c = cos(ang);
                j->s = sin(ang);
                j->cd = cos(step);
                j->sd = sin(step);
            } else {
                double c = j->c * j->cd - j->s * j->sd;
                double s = j->s * j->cd + j->c * j->sd;
                j->c = c;
                j->s = s;
            }
        }
        double x[3] = {0.0, 0.0, 0.0}, y[3];
        for (int e = len - 1; e >= 0; e--)
            sweep_apply(&J[e], J[e].v0 + f * J[e].dv, x);
        mpb__mat3_vec(base->R, x, y);
        for (int i = 0; i < 3; i++)
            xyz[3 * (n - first) + i] = y[i] + base->t[i];
    }
    return MPB_OK;
}
