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
 *
 * Two bodies of the robot: a motion of the joints above both of them (up
 * to their lowest common ancestor link) moves them together, rigidly,
 * and changes no distance between them. Seen from that ancestor's frame
 * only the joints below it move them, so their rate of approach is the
 * sum of the two walks stopped there.
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

/* The rate (m per unit s) of a body of the given reach on link l, from
 * the joints between it and link stop (-1: the root). */
static double body_rate(const mpb_robot *r, const mpb_pose *poses, int l,
                        double reach, const double *d, int stop)
{
    double rate = 0.0, acc = reach;
    while (l >= 0 && l != stop) {
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

/* What pair_rate() reads: the robot where it stands, the motion, and
 * each body's link and reach by movable id. */
typedef struct sweep {
    const mpb_robot *r;
    const mpb_pose  *poses;
    const double    *d;
    const int       *link;      /* by movable id, -1 for none */
    const double    *reach;
    int              ids;
} sweep;

/* Is link a an ancestor of link b (or b itself)? */
static int above(const mpb_robot *r, int a, int b)
{
    for (; b >= 0; b = mpb_robot_get_link(r, b)->parent)
        if (b == a)
            return 1;
    return 0;
}

/* The rate at which movables a and b may approach (see the top). */
static double pair_rate(void *ud, int a, int b)
{
    const sweep *w = ud;
    if (a < 0 || b < 0 || a >= w->ids || b >= w->ids || w->link[a] < 0 ||
        w->link[b] < 0)
        return NAN;
    int la = w->link[a], lb = w->link[b], c = la;
    while (c >= 0 && !above(w->r, c, lb))
        c = mpb_robot_get_link(w->r, c)->parent;
    return body_rate(w->r, w->poses, la, w->reach[a], w->d, c) +
           body_rate(w->r, w->poses, lb, w->reach[b], w->d, c);
}

int mpb__urdf_safe_step(const mpb_robot *r, mpb_collision *coll,
                        const mpb_pose *poses, const int *attached,
                        const int *attached_link, int num_attached,
                        mpb__sweep *st, double moved, const double *d,
                        double margin, double want, double *step)
{
    int nl = mpb_robot_num_links(r), ids = nl;
    for (int i = 0; i < num_attached; i++)
        if (nl + attached[i] + 1 > ids)
            ids = nl + attached[i] + 1;
    double *rate = calloc((size_t)ids + 1, sizeof *rate);
    double *reach_of = calloc((size_t)ids + 1, sizeof *reach_of);
    int *link_of = malloc(((size_t)ids + 1) * sizeof *link_of);
    if (!rate || !reach_of || !link_of) {
        free(rate);
        free(reach_of);
        free(link_of);
        return MPB_ENOMEM;
    }
    for (int i = 0; i <= ids; i++)
        link_of[i] = -1;
    int rc = MPB_OK;
    for (int l = 0; l < nl && rc == MPB_OK; l++) {
        const mpb_robot_link *link = mpb_robot_get_link(r, l);
        if (link->num_collisions == 0)
            continue;
        double reach = mpb__collision_body_reach(coll, l);
        if (!isfinite(reach))
            rc = MPB_EINVAL;
        else if (link->moves)
            rate[l] = body_rate(r, poses, l, reach, d, -1);
        link_of[l] = l;
        reach_of[l] = reach;
    }
    for (int i = 0; i < num_attached && rc == MPB_OK; i++) {
        int id = nl + attached[i];
        double reach = mpb__collision_body_reach(coll, id);
        if (!isfinite(reach))
            rc = MPB_EINVAL;
        else
            rate[id] = body_rate(r, poses, attached_link[i], reach, d, -1);
        link_of[id] = attached_link[i];
        reach_of[id] = reach;
    }
    for (int i = 0; i <= ids - 1 && rc == MPB_OK; i++)
        if (!isfinite(rate[i]))
            rc = MPB_EINVAL;
    sweep w = { r, poses, d, link_of, reach_of, ids };
    if (rc == MPB_OK)
        rc = mpb__collision_sweep_step(coll, st, moved, rate, ids, pair_rate,
                                       &w, margin, want, step);
    free(rate);
    free(reach_of);
    free(link_of);
    return rc;
}
