/*
 * robot_ik.c - numerical inverse kinematics: damped least squares with
 * Levenberg-Marquardt damping, joints at a limit locked out of a step,
 * and random restarts.
 */
#include "mpbench/mpbench.h"
#include "mpbench/robot.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/mathconst.h"
#include "core/rot3.h"
#include "model/robot_internal.h"

/* Into (-pi, pi]. */
static double wrap_angle(double a)
{
    a = fmod(a, 2.0 * M_PI);
    if (a > M_PI)
        a -= 2.0 * M_PI;
    else if (a <= -M_PI)
        a += 2.0 * M_PI;
    return a;
}

void mpb_ik_options_init(mpb_ik_options *opt)
{
    if (!opt)
        return;
    opt->max_attempts = 100;
    opt->max_iterations = 100;
    opt->position_tolerance = 1e-6;
    opt->orientation_tolerance = 1e-6;
    opt->position_only = 0;
}

/* What one solve needs, allocated once per call. */
typedef struct ik_ws {
    const mpb_robot *r;
    int             link;
    int             n;          /* joints 0 .. n-1 move the link */
    int             m;          /* rows: 6, or 3 for position only */
    double          offset[3];
    const mpb_pose *target;
    mpb_pose       *P;          /* poses of the link's path */
    int            *jpos;       /* joint j's child link's place in the path */
    double         *J;          /* m x n, row-major */
    double          p[3];       /* the reference point at the last eval */
    double          e[6];       /* the error at the last eval */
    double          perr, rerr; /* its position and rotation norms */
} ik_ws;

/* Error of q into w->e (target minus current); returns its squared norm. */
static double ik_eval(ik_ws *w, const double *q)
{
    mpb_pose T;
    mpb__robot_path_poses(w->r, q, w->link, w->P, &T);
    mpb_pose_apply(&T, w->offset, w->p);
    for (int i = 0; i < 3; i++)
        w->e[i] = w->target->t[i] - w->p[i];
    w->perr = sqrt(w->e[0] * w->e[0] + w->e[1] * w->e[1] + w->e[2] * w->e[2]);
    w->rerr = 0.0;
    if (w->m == 6) {
        double Rt[9], Rerr[9];
        /* Rerr = R_target * R^T: the world-frame rotation still to go. */
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                Rt[3 * i + j] = T.R[3 * j + i];
        mpb__mat3_mul(w->target->R, Rt, Rerr);
        mpb__rot_log(Rerr, w->e + 3);
        w->rerr = sqrt(w->e[3] * w->e[3] + w->e[4] * w->e[4] + w->e[5] * w->e[5]);
    }
    return w->perr * w->perr + w->rerr * w->rerr;
}

/* The Jacobian at the q of the last ik_eval (w->P, w->p). */
static void ik_jacobian(ik_ws *w)
{
    const mpb_robot *r = w->r;
    for (int j = 0; j < w->n; j++) {
        const mpb_pose *C = &w->P[w->jpos[j]];
        const mpb_robot_joint *J = &r->joints[j];
        double a[3], lin[3], ang[3] = { 0, 0, 0 };
        mpb__mat3_vec(C->R, J->axis, a);
        if (J->type == MPB_JOINT_PRISMATIC) {
            lin[0] = a[0];
            lin[1] = a[1];
            lin[2] = a[2];
        } else {
            double d[3] = { w->p[0] - C->t[0], w->p[1] - C->t[1],
                            w->p[2] - C->t[2] };
            lin[0] = a[1] * d[2] - a[2] * d[1];
            lin[1] = a[2] * d[0] - a[0] * d[2];
            lin[2] = a[0] * d[1] - a[1] * d[0];
            ang[0] = a[0];
            ang[1] = a[1];
            ang[2] = a[2];
        }
        for (int i = 0; i < 3; i++) {
            w->J[i * w->n + j] = lin[i];
            if (w->m == 6)
                w->J[(3 + i) * w->n + j] = ang[i];
        }
    }
}

/* Solve A x = b in place (A k x k symmetric positive definite, k <= 7). */
static int chol_solve(double *A, int k, double *b)
{
    for (int j = 0; j < k; j++) {
        double d = A[j * k + j];
        for (int s = 0; s < j; s++)
            d -= A[j * k + s] * A[j * k + s];
        if (!(d > 0.0))
            return -1;
        d = sqrt(d);
        A[j * k + j] = d;
        for (int i = j + 1; i < k; i++) {
            double v = A[i * k + j];
            for (int s = 0; s < j; s++)
                v -= A[i * k + s] * A[j * k + s];
            A[i * k + j] = v / d;
        }
    }
    for (int i = 0; i < k; i++) {           /* L y = b */
        double v = b[i];
        for (int s = 0; s < i; s++)
            v -= A[i * k + s] * b[s];
        b[i] = v / A[i * k + i];
    }
    for (int i = k - 1; i >= 0; i--) {      /* L^T x = y */
        double v = b[i];
        for (int s = i + 1; s < k; s++)
            v -= A[s * k + i] * b[s];
        b[i] = v / A[i * k + i];
    }
    return 0;
}

/* The damped step dq (n values) for damping lambda; -1 if it fails. */
static int ik_step(const ik_ws *w, double lambda, double *dq)
{
    int m = w->m, n = w->n;
    const double *J = w->J;
    double A[36], b[6];
    if (n > m) {            /* dq = J^T (J J^T + lambda I)^-1 e */
        for (int i = 0; i < m; i++) {
            for (int k = 0; k <= i; k++) {
                double s = 0.0;
                for (int j = 0; j < n; j++)
                    s += J[i * n + j] * J[k * n + j];
                A[i * m + k] = A[k * m + i] = s;
            }
            A[i * m + i] += lambda;
            b[i] = w->e[i];
        }
        if (chol_solve(A, m, b) != 0)
            return -1;
        for (int j = 0; j < n; j++) {
            double s = 0.0;
            for (int i = 0; i < m; i++)
                s += J[i * n + j] * b[i];
            dq[j] = s;
        }
    } else {                /* dq = (J^T J + lambda I)^-1 J^T e */
        for (int j = 0; j < n; j++) {
            for (int k = 0; k <= j; k++) {
                double s = 0.0;
                for (int i = 0; i < m; i++)
                    s += J[i * n + j] * J[i * n + k];
                A[j * n + k] = A[k * n + j] = s;
            }
            A[j * n + j] += lambda;
            double s = 0.0;
            for (int i = 0; i < m; i++)
                s += J[i * n + j] * w->e[i];
            b[j] = s;
        }
        if (chol_solve(A, n, b) != 0)
            return -1;
        for (int j = 0; j < n; j++)
            dq[j] = b[j];
    }
    for (int j = 0; j < n; j++)
        if (!isfinite(dq[j]))
            return -1;
    return 0;
}

static double clamp_joint(const mpb_robot *r, int j, double v)
{
    if (r->wraps[j])
        return v;
    return fmin(fmax(v, r->joints[j].lo), r->joints[j].hi);
}

int mpb_robot_ik(const mpb_robot *r, int link, const double offset[3],
                 const mpb_pose *target, const double *seed,
                 const mpb_ik_options *opt, uint64_t *rng, double *q_out,
                 mpb_ik_info *info)
{
    mpb_ik_options o;
    if (opt)
        o = *opt;
    else
        mpb_ik_options_init(&o);
    if (!r || !target || !rng || !q_out || link < 0 || link >= r->num_links)
        return MPB_EINVAL;
    if (!mpb_pose_is_rigid(target) || (offset && !mpb__finite3(offset)))
        return MPB_EINVAL;
    if (o.max_attempts < 1 || o.max_iterations < 1
        || !(o.position_tolerance > 0) || !(o.orientation_tolerance > 0)
        || !isfinite(o.position_tolerance) || !isfinite(o.orientation_tolerance))
        return MPB_EINVAL;
    if (seed && !mpb__robot_q_finite(r, seed))
        return MPB_EINVAL;

    int N = r->num_joints;
    int n = r->links[link].num_chain_joints;
    int plen = r->path_len[link];
    ik_ws w = { .r = r, .link = link, .n = n, .m = o.position_only ? 3 : 6,
                .target = target };
    if (offset)
        memcpy(w.offset, offset, sizeof w.offset);

    /* One buffer: path poses, then J, q, q_trial, q_best, dq, then jpos. */
    size_t nd = (size_t)(6 * n) + 4 * (size_t)N;
    size_t bytes = (size_t)(plen > 0 ? plen : 1) * sizeof(mpb_pose)
                 + nd * sizeof(double) + (size_t)(n > 0 ? n : 1) * sizeof(int);
    char *buf = malloc(bytes);
    if (!buf)
        return MPB_ENOMEM;
    w.P = (mpb_pose *)buf;
    double *dbl = (double *)(buf + (size_t)(plen > 0 ? plen : 1) * sizeof(mpb_pose));
    w.J = dbl;
    double *q = w.J + 6 * n, *qt = q + N, *qbest = qt + N, *dq = qbest + N;
    w.jpos = (int *)(dq + N);
    const int *path = r->path_pool + r->path_off[link];
    for (int j = 0; j < n; j++) {
        w.jpos[j] = 0;
        for (int k = 0; k < plen; k++)
            if (path[k] == r->joints[j].child_link)
                w.jpos[j] = k;
    }

    /* Joints that do not move the link: from the seed, or mid-range. */
    for (int j = 0; j < N; j++) {
        if (seed)
            q[j] = clamp_joint(r, j, seed[j]);
        else
            q[j] = r->wraps[j] ? 0.0 : 0.5 * (r->joints[j].lo + r->joints[j].hi);
    }
    memcpy(qbest, q, (size_t)N * sizeof *q);
    double best = INFINITY;
    int solved = 0, attempts = 0, iterations = 0;

    for (attempts = 0; attempts < o.max_attempts && !solved; ) {
        if (attempts > 0 || !seed)
            for (int j = 0; j < n; j++)
                q[j] = mpb__uniform(rng, r->joints[j].lo, r->joints[j].hi);
        attempts++;
        double cost = ik_eval(&w, q);
        double perr = w.perr, rerr = w.rerr;
        ik_jacobian(&w);
        double lambda = 1e-2, cost_before = cost;
        for (int it = 0; it < o.max_iterations; it++) {
            if (perr <= o.position_tolerance
                && (o.position_only || rerr <= o.orientation_tolerance)) {
                solved = 1;
                break;
            }
            if (n == 0)
                break;
            iterations++;
            /* A local minimum: not 0.1% better over 10 steps. */
            if (it > 0 && it % 10 == 0) {
                if (cost > 0.999 * cost_before)
                    break;
                cost_before = cost;
            }
            memcpy(qt, q, (size_t)N * sizeof *q);
            int ok = ik_step(&w, lambda, dq) == 0;
            /*
             * Joints at a limit that the step pushes further out: drop
             * them from J (until q changes) and solve again without them.
             */
            int locked = 0;
            for (int j = 0; ok && j < n; j++) {
                if (r->wraps[j])
                    continue;
                if ((q[j] <= r->joints[j].lo && dq[j] < 0)
                    || (q[j] >= r->joints[j].hi && dq[j] > 0)) {
                    for (int i = 0; i < w.m; i++)
                        w.J[i * n + j] = 0.0;
                    locked = 1;
                }
            }
            if (ok && locked)
                ok = ik_step(&w, lambda, dq) == 0;
            if (ok)
                for (int j = 0; j < n; j++)
                    qt[j] = clamp_joint(r, j, q[j] + dq[j]);
            double ct = ok ? ik_eval(&w, qt) : INFINITY;
            if (ct < cost) {
                memcpy(q, qt, (size_t)N * sizeof *q);
                cost = ct;
                perr = w.perr;
                rerr = w.rerr;
                ik_jacobian(&w);
                lambda = fmax(lambda * 0.1, 1e-12);
            } else {
                lambda *= 10.0;
                if (lambda > 1e8)
                    break;
            }
        }
        if (perr <= o.position_tolerance
            && (o.position_only || rerr <= o.orientation_tolerance))
            solved = 1;         /* also when the last step got there */
        if (solved || cost < best) {
            best = cost;
            memcpy(qbest, q, (size_t)N * sizeof *q);
        }
        if (n == 0)
            break;              /* nothing moves the link: no use retrying */
    }

    for (int j = 0; j < N; j++)
        q_out[j] = r->wraps[j] ? wrap_angle(qbest[j]) : qbest[j];
    if (info) {
        ik_eval(&w, q_out);
        info->attempts = attempts;
        info->iterations = iterations;
        info->position_error = w.perr;
        /* The angle of R_target^T R, whatever the mode. */
        mpb_pose T;
        double Rrel[9];
        mpb__robot_path_poses(r, q_out, link, w.P, &T);
        mpb__mat3_tmul(target->R, T.R, Rrel);
        info->orientation_error = mpb__rot_angle(Rrel);
    }
    free(buf);
    return solved ? MPB_OK : MPB_ENOTFOUND;
}
