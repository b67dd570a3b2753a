/*
 * world_sweep.c - how fast a URDF robot's bodies can move along a straight
 * joint-space motion, for certified verification (world_provider.h's
 * safe_step; docs/verification.md).
 *
 * The bound. Along q(s) = q0 + s d, a point x of body b (a link, or an
 * object attached to one) moves with velocity
 *     dx/ds = sum over the joints j on b's path to the root of
 *             v_j (w_j x (x - o_j))   revolute or continuous,
 *             v_j a_j                 prismatic,
 * with v_j the joint's rate (d of its chain joint; a mimic joint's
 * multiplier times its leader's), w_j and a_j unit axes, o_j a point of
 * the axis: the origin of the joint's child link frame. So
 *     |dx/ds| <= sum_j |v_j| R_j (revolute) + sum_j |v_j| (prismatic),
 * R_j any bound on |x - o_j| over the motion. By the triangle inequality
 * along the path, |x - o_j| <= reach(b) + the sum, over the links p
 * between b and joint j's child link (b included, the child excluded),
 * of |t_p - t_parent(p)|: the distance between consecutive frame
 * origins, which rotation of any joint leaves unchanged and which a
 * prismatic joint changes by at most |v_j| per unit s (added, so that
 * the bound holds for every s in [0, 1] from any s it is taken at).
 * reach(b) bounds the distance of b's points from its own frame origin
 * (mpb__collision_body_reach: each shape's bounding sphere). The bound
 * holds for every configuration of the motion, not only where it is
 * taken; the rate of a body is that sum, in m per unit s.
 */
#include "mpbench/mpbench.h"
#include "mpbench/robot.h"

#include <math.h>
#include <stdlib.h>

#include "geometry/collision_internal.h"
#include "model/world_provider.h"

/* |v| of the joint between link l and its parent: its own chain joint's
 * rate, or its leader's times the mimic multiplier; 0 if it is held. */
static double joint_rate(const mpb_robot *r, const mpb_robot_link *l,
                         const double *d)
{
    if (l->chain_joint >= 0)
        return fabs(d[l->chain_joint]);
    if (l->mimic_link >= 0) {
        const mpb_robot_link *lead = mpb_robot_get_link(r, l->mimic_link);
        if (lead && lead->chain_joint >= 0)
            return fabs(l->mimic_multiplier) * fabs(d[lead->chain_joint]);
    }
    return 0.0;
}

/* The rate (m per unit s) of a body of the given reach on link l. */
static double body_rate(const mpb_robot *r, const mpb_pose *poses, int l,
                        double reach, const double *d)
{
    double rate = 0.0, acc = reach;
    while (l >= 0) {
        const mpb_robot_link *link = mpb_robot_get_link(r, l);
        if (!link || link->parent < 0)
            break;
        double v = joint_rate(r, link, d);
        const double *a = poses[l].t, *b = poses[link->parent].t;
        double hop = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                          (a[2] - b[2]) * (a[2] - b[2]));
        switch (link->joint_type) {
        case MPB_JOINT_REVOLUTE:
        case MPB_JOINT_CONTINUOUS:
            rate += v * acc;
            break;
        case MPB_JOINT_PRISMATIC:
            rate += v;
            hop += v;
            break;
        default:                /* fixed; floating and planar are held */
            break;
        }
        acc += hop;
        l = link->parent;
    }
    return rate;
}

int mpb__urdf_safe_step(const mpb_robot *r, mpb_collision *coll,
                        const mpb_pose *poses, const int *attached,
                        const int *attached_link, int num_attached,
                        const double *d, double margin, double want,
                        double *step)
{
    int nl = mpb_robot_num_links(r), ids = nl;
    for (int i = 0; i < num_attached; i++)
        if (nl + attached[i] + 1 > ids)
            ids = nl + attached[i] + 1;
    double *rate = calloc((size_t)ids + 1, sizeof *rate);
    if (!rate)
        return MPB_ENOMEM;
    int rc = MPB_OK;
    for (int l = 0; l < nl && rc == MPB_OK; l++) {
        const mpb_robot_link *link = mpb_robot_get_link(r, l);
        if (!link->moves || link->num_collisions == 0)
            continue;
        double reach = mpb__collision_body_reach(coll, l);
        if (!isfinite(reach))
            rc = MPB_EINVAL;
        else
            rate[l] = body_rate(r, poses, l, reach, d);
    }
    for (int i = 0; i < num_attached && rc == MPB_OK; i++) {
        int id = nl + attached[i];
        double reach = mpb__collision_body_reach(coll, id);
        if (!isfinite(reach))
            rc = MPB_EINVAL;
        else
            rate[id] = body_rate(r, poses, attached_link[i], reach, d);
    }
    for (int i = 0; i <= ids - 1 && rc == MPB_OK; i++)
        if (!isfinite(rate[i]))
            rc = MPB_EINVAL;
    if (rc == MPB_OK)
        rc = mpb__collision_safe_step(coll, rate, ids, margin, want, step);
    free(rate);
    return rc;
}
