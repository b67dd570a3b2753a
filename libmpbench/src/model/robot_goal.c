/*
 * robot_goal.c - goal regions for a link: a box for a point on it and
 * roll/pitch/yaw tolerances about a reference orientation; the check, the
 * distance from one, and sampling inside one by inverse kinematics.
 */
#include "mpbench/mpbench.h"
#include "mpbench/robot.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "core/errbuf.h"
#include "core/mathconst.h"
#include "core/rot3.h"
#include "model/robot_internal.h"

int mpb_goal_region_check(const mpb_robot *r, const mpb_goal_region *g,
                          char *err, size_t errlen)
{
    mpb__set_err(err, errlen, "%s", "");
    if (!r || !g) {
        mpb__set_err(err, errlen, "goal region: NULL robot or region");
        return MPB_EINVAL;
    }
    if (g->link < 0 || g->link >= r->num_links) {
        mpb__set_err(err, errlen, "goal region: link %d out of range (%d links)",
                     g->link, r->num_links);
        return MPB_EINVAL;
    }
    if (!mpb__finite3(g->offset) || !mpb__finite3(g->center) || !mpb__finite3(g->ref_rpy)
        || !mpb__finite3(g->half_extents) || !mpb__finite3(g->rpy_tolerance)) {
        mpb__set_err(err, errlen, "goal region: a number is NaN or infinite");
        return MPB_EINVAL;
    }
    for (int i = 0; i < 3; i++)
        if (g->half_extents[i] < 0 || g->rpy_tolerance[i] < 0) {
            mpb__set_err(err, errlen, "goal region: negative half extent or "
                         "tolerance");
            return MPB_EINVAL;
        }
    return MPB_OK;
}

int mpb_goal_region_distance(const mpb_robot *r, const mpb_goal_region *g,
                             const double *q, mpb_goal_distance *out)
{
    if (!out || !q || mpb_goal_region_check(r, g, NULL, 0) != MPB_OK)
        return MPB_EINVAL;
    mpb_pose T, ref;
    if (mpb_robot_link_pose(r, q, g->link, &T) != MPB_OK)
        return MPB_EINVAL;
    mpb_pose_apply(&T, g->offset, out->point);
    double d2 = 0.0;
    for (int i = 0; i < 3; i++) {
        double d = fabs(out->point[i] - g->center[i]) - g->half_extents[i];
        if (d > 0)
            d2 += d * d;
    }
    out->position = sqrt(d2);

    mpb_pose rel;
    mpb_pose_identity(&ref);
    mpb_pose_set_rpy(&ref, g->ref_rpy[0], g->ref_rpy[1], g->ref_rpy[2]);
    mpb_pose_identity(&rel);
    mpb__mat3_tmul(ref.R, T.R, rel.R);
    mpb_pose_get_rpy(&rel, out->rpy_rel);
    out->angle = mpb__rot_angle(rel.R);
    out->orientation = 0.0;
    for (int i = 0; i < 3; i++) {
        double d = fabs(out->rpy_rel[i]) - g->rpy_tolerance[i];
        if (d > out->orientation)
            out->orientation = d;
    }
    return MPB_OK;
}

int mpb_goal_region_contains(const mpb_robot *r, const mpb_goal_region *g,
                             const double *q)
{
    mpb_goal_distance d;
    int rc = mpb_goal_region_distance(r, g, q, &d);
    if (rc != MPB_OK)
        return rc;
    return d.position == 0.0 && d.orientation == 0.0;
}

int mpb_goal_region_sample(const mpb_robot *r, const mpb_goal_region *g,
                           const double *seed, const mpb_ik_options *opt,
                           int max_targets, uint64_t *rng, double *q_out)
{
    if (!rng || !q_out || mpb_goal_region_check(r, g, NULL, 0) != MPB_OK)
        return MPB_EINVAL;
    mpb_ik_options o;
    if (opt) {
        o = *opt;
    } else {
        mpb_ik_options_init(&o);
        o.max_attempts = 20;
    }
    if (g->rpy_tolerance[0] >= M_PI && g->rpy_tolerance[1] >= M_PI
        && g->rpy_tolerance[2] >= M_PI)
        o.position_only = 1;
    if (max_targets <= 0)
        max_targets = 50;

    mpb_pose ref;
    mpb_pose_identity(&ref);
    mpb_pose_set_rpy(&ref, g->ref_rpy[0], g->ref_rpy[1], g->ref_rpy[2]);
    const double cap[3] = { M_PI, M_PI / 2, M_PI };
    int rc = MPB_ENOTFOUND;
    for (int t = 0; t < max_targets; t++) {
        mpb_pose target, rel;
        mpb_pose_identity(&rel);
        double rpy[3];
        for (int i = 0; i < 3; i++) {
            double tol = fmin(g->rpy_tolerance[i], cap[i]);
            rpy[i] = mpb__uniform(rng, -tol, tol);
            target.t[i] = g->center[i]
                        + mpb__uniform(rng, -g->half_extents[i], g->half_extents[i]);
        }
        mpb_pose_set_rpy(&rel, rpy[0], rpy[1], rpy[2]);
        mpb__mat3_mul(ref.R, rel.R, target.R);
        rc = mpb_robot_ik(r, g->link, g->offset, &target, seed, &o, rng, q_out,
                          NULL);
        if (rc == MPB_OK) {
            if (mpb_goal_region_contains(r, g, q_out) == 1)
                return MPB_OK;
            rc = MPB_ENOTFOUND;
        } else if (rc != MPB_ENOTFOUND) {
            return rc;
        }
    }
    return rc;
}
