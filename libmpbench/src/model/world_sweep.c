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
 * Tighter, for a revolute joint: a point x moves about the axis at
 * |v_j| dist(x, axis_j), and dist(x, axis_j) <= |x - o_j|. Each shape of
 * b lies in its bounding sphere and, a mesh, in its capsule: its points
 * lie within dist(centre, axis) + radius of the axis (for a capsule, the
 * larger of its ends', distance to a line being convex along a segment).
 * That is where the robot stands; over the motion a point's distance to
 * axis j changes only by the joints below j (those above move x and the
 * axis together, j itself turns x about it), at most by their rate, the
 * partial sum of the walk up to j. So over a horizon of H units of s
 * (the step's want: no step, nor the motion the kept bounds are lowered
 * by, goes further from where the rates are taken; certify.c)
 *     R_j = min(chain bound above, max over shapes of that + rate_below_j H)
 * holds, and the rate is the same sum with these R_j.
 *
 * Two bodies of the robot: a motion of the joints above both of them (up
 * to their lowest common ancestor link) moves them together, rigidly,
 * and changes no distance between them. Seen from that ancestor's frame
 * only the joints below it move them, so their rate of approach is the
 * sum of the two walks stopped there. A walk from a body up to a joint
 * does not depend on where it stops: each body's walk is taken once a
 * step, to the root, with its partial sums at every link on the way.
 *
 * What is the same for every step (the bodies' links, shapes, reaches;
 * the pairs' common ancestors) is found once per world and kept with the
 * chain's bounds (mpb__sweep_user()).
 */
#include "mpbench/mpbench.h"
#include "mpbench/robot.h"

#include <math.h>
#include <stdlib.h>

#include "geometry/collision_internal.h"
#include "model/world_provider.h"
#include "model/world_urdf.h"

/* What is found once per world (see the top). */
typedef struct rates {
    const mpb_robot      *r;         /* made for this robot, */
    const mpb_collision  *coll;      /* this collision world */
    int                   nl, na;    /* and these attached objects */
    int                  *att, *att_link;
    int                   ids;       /* movable ids 0 .. ids - 1 */
    int                  *link;      /* by id: its link, -1 for none */
    double               *reach;     /* by id */
    int                  *bound_off, *bound_len; /* by id: in bounds */
    mpb__body_bound      *bounds;
    double              (*at)[3][3]; /* by bound, each step: its sphere's
                                        centre and capsule's ends, world */
    int                  *depth;     /* by link: hops to the root */
    const mpb_robot_link **lk;       /* by link: the robot's own, to walk
                                        without a call a hop */
    int                  *anc;       /* ids x ids: common ancestor link */
    const double        **axis;      /* by link: its joint's axis (own
                                        frame) if an active revolute one */
    /* each step's */
    double               *rate;      /* by id: to the root */
    struct hop {                     /* by link: the joint to its parent */
        double v;                    /* |rate| */
        double len;                  /* distance between the frame
                                        origins, + v if prismatic */
        double w[3];                 /* revolute: the axis, world */
    }                    *hop;
    double               *partial;   /* by id, depth + 1 each: the rate of
                                        the first k hops of its walk */
    int                  *partial_off;
} rates;

static void rates_free(void *p)
{
    rates *t = p;
    if (!t)
        return;
    free(t->att);
    free(t->att_link);
    free(t->link);
    free(t->reach);
    free(t->bound_off);
    free(t->bound_len);
    free(t->bounds);
    free(t->at);
    free(t->depth);
    free(t->lk);
    free(t->anc);
    free(t->axis);
    free(t->hop);
    free(t->rate);
    free(t->partial);
    free(t->partial_off);
    free(t);
}

/* Is t made for this world? */
static int rates_fit(const rates *t, const mpb_robot *r, const mpb_collision *coll,
                     const int *attached, const int *attached_link, int na)
{
    if (!t || t->r != r || t->coll != coll || t->na != na ||
        t->nl != mpb_robot_num_links(r))
        return 0;
    for (int i = 0; i < na; i++)
        if (t->att[i] != attached[i] || t->att_link[i] != attached_link[i])
            return 0;
    return 1;
}

/* The lowest link above both a and b (or either itself). */
static int common_ancestor(const mpb_robot *r, const int *depth, int a, int b)
{
    while (a >= 0 && b >= 0 && a != b) {
        if (depth[a] >= depth[b])
            a = mpb_robot_get_link(r, a)->parent;
        else
            b = mpb_robot_get_link(r, b)->parent;
    }
    return a == b ? a : -1;
}

/* One body's shapes and reach into t (link l; id). */
static int rates_body(rates *t, mpb_collision *coll, int id, int l, int *used,
                      int *cap)
{
    double reach = mpb__collision_body_reach(coll, id);
    int n = mpb__collision_body_bounds(coll, id, NULL, 0);
    if (!isfinite(reach) || n < 0)
        return MPB_EINVAL;
    if (*used + n > *cap) {
        int c2 = 2 * (*used + n) + 8;
        mpb__body_bound *nb = realloc(t->bounds, (size_t)c2 * sizeof *nb);
        if (!nb)
            return MPB_ENOMEM;
        t->bounds = nb;
        *cap = c2;
    }
    mpb__collision_body_bounds(coll, id, t->bounds + *used, n);
    t->link[id] = l;
    t->reach[id] = reach;
    t->bound_off[id] = *used;
    t->bound_len[id] = n;
    *used += n;
    return MPB_OK;
}

static rates *rates_make(const mpb_robot *r, mpb_collision *coll,
                         const int *attached, const int *attached_link, int na,
                         int *rc)
{
    int nl = mpb_robot_num_links(r), ids = nl;
    for (int i = 0; i < na; i++)
        if (nl + attached[i] + 1 > ids)
            ids = nl + attached[i] + 1;
    rates *t = calloc(1, sizeof *t);
    *rc = MPB_ENOMEM;
    if (!t)
        return NULL;
    t->r = r;
    t->coll = coll;
    t->nl = nl;
    t->na = na;
    t->ids = ids;
    size_t n = (size_t)ids + 1;
    t->att = calloc((size_t)na + 1, sizeof *t->att);
    t->att_link = calloc((size_t)na + 1, sizeof *t->att_link);
    t->link = malloc(n * sizeof *t->link);
    t->reach = calloc(n, sizeof *t->reach);
    t->bound_off = calloc(n, sizeof *t->bound_off);
    t->bound_len = calloc(n, sizeof *t->bound_len);
    t->depth = calloc((size_t)nl + 1, sizeof *t->depth);
    t->lk = calloc((size_t)nl + 1, sizeof *t->lk);
    t->anc = malloc(n * n * sizeof *t->anc);
    t->rate = calloc(n, sizeof *t->rate);
    t->partial_off = calloc(n, sizeof *t->partial_off);
    t->axis = calloc((size_t)nl + 1, sizeof *t->axis);
    t->hop = calloc((size_t)nl + 1, sizeof *t->hop);
    if (!t->att || !t->att_link || !t->link || !t->reach || !t->bound_off ||
        !t->bound_len || !t->depth || !t->lk || !t->anc || !t->rate || !t->partial_off ||
        !t->axis || !t->hop) {
        rates_free(t);
        return NULL;
    }
    for (int i = 0; i < na; i++) {
        t->att[i] = attached[i];
        t->att_link[i] = attached_link[i];
    }
    for (int i = 0; i < ids; i++)
        t->link[i] = -1;
    /* depth: parents need not come first in the link table */
    for (int l = 0; l < nl; l++) {
        t->lk[l] = mpb_robot_get_link(r, l);
        int k = 0;
        for (int p = mpb_robot_get_link(r, l)->parent; p >= 0 && k <= nl;
             p = mpb_robot_get_link(r, p)->parent)
            k++;
        t->depth[l] = k;
    }
    for (int l = 0; l < nl; l++) {
        const mpb_robot_link *link = mpb_robot_get_link(r, l);
        if ((link->joint_type == MPB_JOINT_REVOLUTE ||
             link->joint_type == MPB_JOINT_CONTINUOUS) && link->chain_joint >= 0)
            t->axis[l] = mpb_robot_get_joint(r, link->chain_joint)->axis;
    }
    int used = 0, cap = 0;
    *rc = MPB_OK;
    for (int l = 0; l < nl && *rc == MPB_OK; l++)
        if (mpb_robot_get_link(r, l)->num_collisions > 0)
            *rc = rates_body(t, coll, l, l, &used, &cap);
    for (int i = 0; i < na && *rc == MPB_OK; i++)
        *rc = rates_body(t, coll, nl + attached[i], attached_link[i], &used, &cap);
    int total = 0;
    for (int i = 0; i < ids; i++) {
        t->partial_off[i] = total;
        total += t->link[i] >= 0 ? t->depth[t->link[i]] + 1 : 0;
    }
    t->partial = calloc((size_t)total + 1, sizeof *t->partial);
    t->at = calloc((size_t)used + 1, sizeof *t->at);
    if (*rc == MPB_OK && (!t->partial || !t->at))
        *rc = MPB_ENOMEM;
    for (int a = 0; a < ids; a++)
        for (int b = 0; b < ids; b++)
            t->anc[(size_t)a * (size_t)ids + (size_t)b] =
                t->link[a] < 0 || t->link[b] < 0 ? -1 :
                common_ancestor(r, t->depth, t->link[a], t->link[b]);
    if (*rc != MPB_OK) {
        rates_free(t);
        return NULL;
    }
    return t;
}

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

/* The squared distance of world point x from the line through o along
 * unit w. */
static double line_dist2(const double x[3], const double o[3], const double w[3])
{
    double p[3] = { x[0] - o[0], x[1] - o[1], x[2] - o[2] };
    double c0 = p[1] * w[2] - p[2] * w[1], c1 = p[2] * w[0] - p[0] * w[2],
           c2 = p[0] * w[1] - p[1] * w[0];
    return c0 * c0 + c1 * c1 + c2 * c2;
}

/* fmax() and fmin() inline, NaN as they treat it (the other operand):
 * libm's are calls, here in the innermost loop of every step. */
static inline double max2(double a, double b)
{
    return a > b || b != b ? a : b;
}

static inline double min2(double a, double b)
{
    return a < b || b != b ? a : b;
}

/* Body id's bounds where the robot stands (pose: the body's frame). */
static void place_bounds(rates *t, int id, const mpb_pose *pose)
{
    const mpb__body_bound *b = t->bounds + t->bound_off[id];
    double (*at)[3][3] = t->at + t->bound_off[id];
    for (int k = 0; k < t->bound_len[id]; k++) {
        mpb_pose_apply(pose, b[k].centre, at[k][0]);
        if (b[k].cap_radius >= 0) {
            mpb_pose_apply(pose, b[k].cap[0], at[k][1]);
            mpb_pose_apply(pose, b[k].cap[1], at[k][2]);
        }
    }
}

/* How far body id's points lie from the axis through o along w, where the
 * robot stands (place_bounds()); or, once that plus extra passes cap, any
 * value that does (the caller takes min(cap, this + extra): cap either
 * way). The larger of two square roots is the root of the larger square,
 * to the bit; a capsule is only measured if its sphere reaches further
 * than the bounds before it, else the least of the two cannot matter. */
static double axis_reach(const rates *t, int id, const double o[3],
                         const double w[3], double extra, double cap)
{
    double far = 0.0;
    const mpb__body_bound *b = t->bounds + t->bound_off[id];
    double (*at)[3][3] = t->at + t->bound_off[id];
    for (int k = 0; k < t->bound_len[id]; k++) {
        double r = sqrt(line_dist2(at[k][0], o, w)) + b[k].radius;
        if (b[k].cap_radius >= 0 && !(r <= far)) {
            double rc = sqrt(max2(line_dist2(at[k][1], o, w),
                                  line_dist2(at[k][2], o, w))) + b[k].cap_radius;
            r = min2(r, rc);
        }
        far = max2(far, r);
        if (far + extra >= cap)
            return far;
    }
    return far;
}

/* Each link's joint for the motion d where the robot stands (t->hop). */
static void links_step(rates *t, const mpb_pose *poses, const double *d)
{
    for (int l = 0; l < t->nl; l++) {
        const mpb_robot_link *link = t->lk[l];
        struct hop *o = &t->hop[l];
        if (link->parent < 0)
            continue;
        o->v = joint_rate(t->r, link, d);
        const double *a = poses[l].t, *b = poses[link->parent].t;
        o->len = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                      (a[2] - b[2]) * (a[2] - b[2]));
        if (link->joint_type == MPB_JOINT_PRISMATIC)
            o->len += o->v;
        if (t->axis[l] && o->v > 0) {
            /* the child link's frame turns the joint's axis; it passes
               through that frame's origin */
            const double *R = poses[l].R, *ax = t->axis[l];
            for (int i = 0; i < 3; i++)
                o->w[i] = R[3 * i] * ax[0] + R[3 * i + 1] * ax[1] + R[3 * i + 2] * ax[2];
        }
    }
}

/* Body id's walk to the root: t->rate[id] and its partial sums (see the
 * top), over a horizon of h units of s (links_step() taken). */
static void body_walk(rates *t, const mpb_pose *poses, int id, double h)
{
    int l = t->link[id], k = 0, depth = t->depth[l];
    double *part = t->partial + t->partial_off[id];
    double rate = 0.0, acc = t->reach[id];
    part[0] = 0.0;
    int placed = 0;
    while (k < depth) {
        const mpb_robot_link *link = t->lk[l];
        const struct hop *o = &t->hop[l];
        switch (link->joint_type) {
        case MPB_JOINT_REVOLUTE:
        case MPB_JOINT_CONTINUOUS: {
            double far = acc;
            if (t->axis[l] && o->v > 0) {
                if (!placed++)
                    place_bounds(t, id, &poses[t->link[id]]);
                double extra = rate * h;
                far = min2(far, axis_reach(t, id, poses[l].t, o->w, extra, far) +
                                extra);
            }
            rate += o->v * far;
            break;
        }
        case MPB_JOINT_PRISMATIC:
            rate += o->v;
            break;
        default:                /* fixed; floating and planar are held */
            break;
        }
        acc += o->len;
        part[++k] = rate;
        l = link->parent;
    }
    t->rate[id] = rate;
}

/* The rate at which movables a and b may approach (see the top). */
static double pair_rate(void *ud, int a, int b)
{
    const rates *t = ud;
    if (a < 0 || b < 0 || a >= t->ids || b >= t->ids || t->link[a] < 0 ||
        t->link[b] < 0)
        return NAN;
    int c = t->anc[(size_t)a * (size_t)t->ids + (size_t)b];
    int ka = c < 0 ? t->depth[t->link[a]] : t->depth[t->link[a]] - t->depth[c];
    int kb = c < 0 ? t->depth[t->link[b]] : t->depth[t->link[b]] - t->depth[c];
    return t->partial[t->partial_off[a] + ka] + t->partial[t->partial_off[b] + kb];
}

int mpb__urdf_safe_step(const mpb_robot *r, mpb_collision *coll,
                        const mpb_pose *poses, const int *attached,
                        const int *attached_link, int num_attached,
                        mpb__sweep *st, double moved, const double *d,
                        double margin, double want, double *step)
{
    if (!st)
        return MPB_EINVAL;
    rates *t = mpb__sweep_user(st);
    int rc = MPB_OK;
    if (!rates_fit(t, r, coll, attached, attached_link, num_attached)) {
        t = rates_make(r, coll, attached, attached_link, num_attached, &rc);
        if (!t)
            return rc;
        mpb__sweep_set_user(st, t, rates_free);
    }
    if (!(want > 0))
        return MPB_EINVAL;
    links_step(t, poses, d);
    for (int id = 0; id < t->ids; id++) {
        t->rate[id] = 0.0;
        if (t->link[id] < 0)
            continue;
        body_walk(t, poses, id, want);
        if (!isfinite(t->rate[id]))
            return MPB_EINVAL;
    }
    return mpb__collision_sweep_step(coll, st, moved, t->rate, t->ids, pair_rate,
                                     t, margin, want, step);
}

int mpb__urdf_rates(mpb_world *w, const double *q, const double *d,
                    double horizon, double *rate, double *pair, int n)
{
    if (!w || w->provider != &mpb__world_urdf || !q || !d || !rate || !pair ||
        n < 0 || !(horizon > 0))
        return MPB_EINVAL;
    urdf_world *u = w->impl;
    if (mpb__urdf_place(u, q) != MPB_OK)
        return MPB_EINVAL;
    int rc = MPB_OK;
    rates *t = rates_make(u->robot, u->coll, u->attached, u->attached_link,
                          u->num_attached, &rc);
    if (!t)
        return rc;
    links_step(t, u->poses, d);
    for (int id = 0; id < t->ids; id++) {
        t->rate[id] = 0.0;
        if (t->link[id] >= 0)
            body_walk(t, u->poses, id, horizon);
    }
    for (int a = 0; a < n; a++) {
        rate[a] = a < t->ids && t->link[a] >= 0 ? t->rate[a] : NAN;
        for (int b = 0; b < n; b++)
            pair[(size_t)a * (size_t)n + (size_t)b] = pair_rate(t, a, b);
    }
    rates_free(t);
    return MPB_OK;
}
