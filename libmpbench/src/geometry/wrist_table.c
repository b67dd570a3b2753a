/*
 * wrist_table.c - tables over one or two joints that prove a self pair
 * apart (wrist_table.h): which pairs qualify, the bound on how fast the
 * far link moves, the tree of cells, and a table as bytes for the cache
 * on disk (wrist_cache.c keeps the caches).
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "mpbench/mpbench.h"
#include "geometry/collision_internal.h"
#include "core/grow.h"
#include "core/rot3.h"
#include "geometry/wrist_table.h"

/* Below this (m) FCL's distance does not count as apart: far above its
 * rounding, as the rest of the collision world's bounds. */
#define WRIST_MARGIN 1e-4

struct mpb__wrist_table {
    int              num_joints;
    double           lo[2], hi[2];
    /* The tree, root first. A node is (first child << 2) | split, split
     * bit 0 halving joint 0, bit 1 joint 1; its 2 or 4 children are
     * contiguous, the upper half of joint 0 at bit 0 of the child's
     * offset, of joint 1 at the next. A leaf (split 0) is 1 << 2 when
     * proved apart, 0 when left to FCL. */
    uint32_t        *nodes;
    int              num_nodes, cap;
    /* The same leaves painted on a grid of the finest cells, one bit a
     * cell, 2^depth[k] cells along joint k, row by row: a look-up in a
     * few instructions instead of a walk down the tree. NULL when the
     * grid would be too large (MAX_GRID_DEPTH). */
    unsigned char   *grid;
    int              depth[2];
    double           per_rad[2];    /* cells per rad along each joint */
    mpb__wrist_stats stats;
};

#define MAX_GRID_DEPTH 22   /* at most 2^22 cells: 512 KB */

static double min_bound = MPB__WRIST_MIN_BOUND;
static double lipschitz_factor = 1.0;
static int max_distances = MPB__WRIST_MAX_DISTANCES;

void mpb__wrist_set_budget(int distances)
{
    max_distances = distances;
}

/* Triangles of a side, a primitive counted as a box's 12. */
static double side_triangles(const mpb__wrist_side *s)
{
    double n = 0;
    for (int i = 0; i < s->num_shapes; i++)
        n += s->geoms[i].type == MPB_SHAPE_MESH ? s->geoms[i].mesh->num_triangles
                                                 : 12;
    return n;
}

int mpb__wrist_affordable(const mpb__wrist_spec *spec)
{
    return side_triangles(&spec->side[0]) * side_triangles(&spec->side[1]) <=
           MPB__WRIST_MAX_TRIANGLE_PAIRS;
}

void mpb__wrist_set_params(double bound, double factor)
{
    min_bound = bound;
    lipschitz_factor = factor;
}

void mpb__wrist_get_params(double out[4])
{
    out[0] = min_bound;
    out[1] = lipschitz_factor;
    out[2] = WRIST_MARGIN;
    out[3] = max_distances;
}

/* ---- which pairs ------------------------------------------------------ */

/* The pose of a rotation by angle about the unit axis a (Rodrigues). */
static void rot_pose(const double a[3], double angle, mpb_pose *p)
{
    mpb__rot_axis(a, angle, p->R);
    p->t[0] = p->t[1] = p->t[2] = 0.0;
}

/* inv(from) * to */
static void relative(const mpb_pose *from, const mpb_pose *to, mpb_pose *out)
{
    mpb_pose inv;
    mpb_pose_inverse(from, &inv);
    mpb_pose_mul(&inv, to, out);
}

int mpb__wrist_path(const mpb_robot *r, const mpb_pose *poses, int near,
                    int far, int joints[2], mpb__wrist_spec *spec)
{
    int child[2] = {-1, -1}, n = 0;
    joints[0] = joints[1] = -1;
    if (near == far)
        return 0;
    /* Up from the far link; the last joint met is the upper one. */
    int l = far;
    for (; l >= 0 && l != near; l = mpb_robot_get_link(r, l)->parent) {
        const mpb_robot_link *link = mpb_robot_get_link(r, l);
        if (link->joint_type == MPB_JOINT_FIXED)
            continue;
        if ((link->joint_type != MPB_JOINT_REVOLUTE &&
             link->joint_type != MPB_JOINT_CONTINUOUS) ||
            link->chain_joint < 0 || link->mimic_link >= 0 || n == 2)
            return 0;
        child[1] = child[0];
        child[0] = l;
        n++;
    }
    if (l != near || n == 0)
        return 0;
    memset(spec, 0, sizeof *spec);
    spec->num_joints = n;
    mpb_pose from = poses[near];
    for (int k = 0; k < n; k++) {
        const mpb_robot_link *link = mpb_robot_get_link(r, child[k]);
        const mpb_robot_joint *j = mpb_robot_get_joint(r, link->chain_joint);
        mpb_pose to;
        mpb_pose_mul(&poses[link->parent], &j->origin, &to);
        relative(&from, &to, &spec->fixed[k]);
        memcpy(spec->axis[k], j->axis, sizeof spec->axis[k]);
        /* A continuous joint: one turn (its lo and hi say so). */
        spec->lo[k] = j->lo;
        spec->hi[k] = j->hi;
        joints[k] = link->chain_joint;
        /* The joint's child frame at the value FK used for poses. */
        from = poses[child[k]];
    }
    relative(&from, &poses[far], &spec->fixed[n]);
    return 1;
}

/* ---- the bound -------------------------------------------------------- */

/* Corners of a box holding a primitive, in its own frame; 0 for a mesh. */
static int primitive_corners(const mpb_geometry *g, double out[8][3])
{
    double h[3];
    switch (g->type) {
    case MPB_SHAPE_BOX:
        h[0] = g->dims[0] / 2;
        h[1] = g->dims[1] / 2;
        h[2] = g->dims[2] / 2;
        break;
    case MPB_SHAPE_SPHERE:
        h[0] = h[1] = h[2] = g->dims[0];
        break;
    case MPB_SHAPE_CAPSULE:
        h[0] = h[1] = g->dims[0];
        h[2] = g->dims[1] / 2 + g->dims[0];
        break;
    case MPB_SHAPE_CYLINDER:
    case MPB_SHAPE_CONE:
        h[0] = h[1] = g->dims[0];
        h[2] = g->dims[1] / 2;
        break;
    default:
        return 0;
    }
    for (int c = 0; c < 8; c++)
        for (int k = 0; k < 3; k++)
            out[c][k] = (c >> k & 1) ? h[k] : -h[k];
    return 8;
}

/* Distance of x from the line through the origin along the unit a. */
static double axis_dist(const double a[3], const double x[3])
{
    double s = x[0] * a[0] + x[1] * a[1] + x[2] * a[2], d2 = 0;
    for (int k = 0; k < 3; k++) {
        double e = x[k] - s * a[k];
        d2 += e * e;
    }
    return sqrt(d2);
}

/*
 * R1, R2: how far (m per rad) a point of the far link's shapes moves
 * relative to the near link when joint 1 or joint 2 turns.
 *
 * A point turning by an angle d about an axis moves by at most |d| times
 * its distance from the axis (the chord is shorter than the arc). Going
 * from the cell's centre to any state in it, first joint 2 turns (by at
 * most h2) with joint 1 at its centre value, then joint 1 (by at most h1)
 * with joint 2 at its final value, so a point moves by at most R1 h1 +
 * R2 h2 when:
 *   R2 = the greatest distance of a point from axis 2. Turning either
 *        joint moves the point and axis 2 rigidly together, so this
 *        does not depend on the state.
 *   R1 bounds the distance of a point from axis 1 at every value of
 *        joint 2. Write the point as y + e, y its foot on axis 2 (which
 *        joint 2 does not move: y = s a2, s its projection on the axis,
 *        in joint 2's frame) and |e| <= R2. Then dist(point, axis 1) <=
 *        dist(y, axis 1) + R2, and dist(y, axis 1) is convex in s, so it
 *        is greatest at the least or greatest s of the points.
 * With one joint, R1 is the greatest distance from its axis and R2 = 0.
 * The shapes' points: a mesh's vertices, a primitive's box corners;
 * distances from an axis are convex, so the greatest over the shape is
 * at one of these. The distance between the two links' surfaces changes
 * at most as fast as their points move, which is the certificate.
 */
static int wrist_lipschitz(const mpb__wrist_spec *s, double R[2],
                           double **pts, int *num_pts)
{
    int n = s->num_joints, cap = 0;
    const double *a = s->axis[n - 1];       /* the lower joint's axis */
    double rmax = 0, smin = INFINITY, smax = -INFINITY;
    const mpb__wrist_side *far = &s->side[1];
    *num_pts = 0;
    for (int i = 0; i < far->num_shapes; i++) {
        const mpb_geometry *g = &far->geoms[i];
        double corners[8][3];
        int np = primitive_corners(g, corners);
        if (g->type == MPB_SHAPE_MESH)
            np = g->mesh->num_vertices;
        mpb_pose to;    /* shape frame -> the lower joint's child frame */
        mpb_pose_mul(&s->fixed[n], &far->offsets[i], &to);
        for (int v = 0; v < np; v++) {
            double x[3];
            mpb_pose_apply(&to, g->type == MPB_SHAPE_MESH ?
                           &g->mesh->vertices[3 * v] : corners[v], x);
            double d = axis_dist(a, x);
            double p = x[0] * a[0] + x[1] * a[1] + x[2] * a[2];
            rmax = d > rmax ? d : rmax;
            smin = p < smin ? p : smin;
            smax = p > smax ? p : smax;
            if (mpb__grow((void **)pts, &cap, 4 * (*num_pts + 1),
                          sizeof **pts) != MPB_OK)
                return MPB_ENOMEM;
            memcpy(&(*pts)[4 * *num_pts], x, sizeof x);
            (*pts)[4 * *num_pts + 3] = d;
            ++*num_pts;
        }
    }
    if (n == 1 || smin > smax) {
        R[0] = rmax;
        R[1] = 0;
        return MPB_OK;
    }
    double f = 0;
    for (int e = 0; e < 2; e++) {
        double y[3], x[3] = {(e ? smax : smin) * a[0], (e ? smax : smin) * a[1],
                             (e ? smax : smin) * a[2]};
        mpb_pose_apply(&s->fixed[1], x, y);
        double d = axis_dist(s->axis[0], y);
        f = d > f ? d : f;
    }
    R[0] = f + rmax;
    R[1] = rmax;
    return MPB_OK;
}

/*
 * A smaller R1 for one cell, joint 2 within h2 of c2: a point x (in
 * joint 2's frame, at distance r from axis 2) is within r h2 of where it
 * is at c2, so its distance from axis 1 is at most that at c2 plus
 * r h2. Both terms are convex in x, so the greatest is at a vertex or
 * corner. On the Panda's link7 this is 0.16-0.20 m against R1's 0.23.
 */
static double cell_r1(const mpb__wrist_spec *s, const double *pts, int num_pts,
                      double c2, double h2)
{
    mpb_pose rot, m;
    rot_pose(s->axis[1], c2, &rot);
    mpb_pose_mul(&s->fixed[1], &rot, &m);
    double r = 0;
    for (int i = 0; i < num_pts; i++) {
        double y[3];
        mpb_pose_apply(&m, &pts[4 * i], y);
        double d = axis_dist(s->axis[0], y) + pts[4 * i + 3] * h2;
        r = d > r ? d : r;
    }
    return r;
}

/* ---- the tree --------------------------------------------------------- */

typedef struct builder {
    const mpb__wrist_spec *spec;
    mpb__wrist_table      *t;
    mpb_collision         *coll;    /* movable 0 the near link, 1 the far */
    double                 R[2];
    double                *pts;     /* the far side's points in the lower
                                       joint's frame, and their distance
                                       from its axis: 4 a point */
    int                    num_pts;
} builder;

/* FCL's distance of the pair with the joints at v, or `below` when it
 * is at least that; NaN on error. */
static double distance_at(builder *b, const double v[2], double below)
{
    const mpb__wrist_spec *s = b->spec;
    mpb_pose p = s->fixed[0], rot, tmp;
    for (int k = 0; k < s->num_joints; k++) {
        rot_pose(s->axis[k], v[k], &rot);
        mpb_pose_mul(&p, &rot, &tmp);
        mpb_pose_mul(&tmp, &s->fixed[k + 1], &p);
    }
    if (mpb_collision_set_pose(b->coll, 1, &p) != MPB_OK)
        return NAN;
    b->t->stats.distances++;
    return mpb__collision_pair_distance(b->coll, 0, 1, below);
}

/* Fill node i for the cell of centre c, half-widths h. */
static int build_cell(builder *b, int i, const double c[2], const double h[2])
{
    mpb__wrist_table *t = b->t;
    int n = b->spec->num_joints;
    double r1 = b->R[0];
    if (n == 2) {
        double rc = cell_r1(b->spec, b->pts, b->num_pts, c[1], h[1]);
        r1 = rc < r1 ? rc : r1;
    }
    if (t->stats.distances >= max_distances) {
        t->nodes[i] = 0;
        t->stats.open_leaves++;
        t->stats.cut = 1;
        return MPB_OK;
    }
    double term[2] = {lipschitz_factor * r1 * h[0],
                      n == 2 ? lipschitz_factor * b->R[1] * h[1] : 0.0};
    double bound = term[0] + term[1];
    double d = distance_at(b, c, bound + WRIST_MARGIN);
    if (isnan(d))
        return MPB_EERROR;
    if (d >= bound + WRIST_MARGIN) {
        t->nodes[i] = 1u << 2;
        t->stats.apart_leaves++;
        return MPB_OK;
    }
    /* Touching at the centre: nothing in the cell is further apart than
     * its bound, and little of it is proved apart by splitting further,
     * so in the colliding regions the cells stop a level early (half the
     * cells, 47.1k instructions a Panda check either way). */
    if (bound <= min_bound || (d <= WRIST_MARGIN && bound <= 2 * min_bound)) {
        t->nodes[i] = 0;
        t->stats.open_leaves++;
        return MPB_OK;
    }
    /* Halve the joints whose share of the bound is at least half the
     * larger share: cells stay about as long in metres each way. */
    double big = term[0] > term[1] ? term[0] : term[1];
    unsigned split = (term[0] >= 0.5 * big ? 1u : 0u) |
                     (n == 2 && term[1] >= 0.5 * big ? 2u : 0u);
    int kids = split == 3 ? 4 : 2;
    int first = t->num_nodes;
    if (first > (int)(UINT32_MAX >> 3) - kids ||
        mpb__grow((void **)&t->nodes, &t->cap, first + kids,
                  sizeof *t->nodes) != MPB_OK)
        return MPB_ENOMEM;
    t->num_nodes += kids;
    t->nodes[i] = (uint32_t)first << 2 | split;
    for (int k = 0; k < kids; k++) {
        double cc[2] = {c[0], c[1]}, hh[2] = {h[0], h[1]};
        int bit = 0;
        for (int j = 0; j < 2; j++) {
            if (!(split >> j & 1))
                continue;
            hh[j] = h[j] * 0.5;
            cc[j] = (k >> bit & 1) ? c[j] + hh[j] : c[j] - hh[j];
            bit++;
        }
        int rc = build_cell(b, first + k, cc, hh);
        if (rc != MPB_OK)
            return rc;
    }
    return MPB_OK;
}

/* The deepest halving of each joint below node i, k levels down so far. */
static void tree_depth(const mpb__wrist_table *t, int i, const int k[2], int d[2])
{
    uint32_t node = t->nodes[i];
    unsigned split = node & 3u;
    for (int j = 0; j < 2; j++)
        d[j] = k[j] > d[j] ? k[j] : d[j];
    if (!split)
        return;
    int kk[2] = {k[0] + (int)(split & 1u), k[1] + (int)(split >> 1 & 1u)};
    for (int c = 0; c < (split == 3 ? 4 : 2); c++)
        tree_depth(t, (int)(node >> 2) + c, kk, d);
}

/* Paint the apart leaves below node i, whose cell is number at[j] of
 * 2^k[j] along joint j, on the grid. */
static void paint(mpb__wrist_table *t, int i, const int at[2], const int k[2])
{
    uint32_t node = t->nodes[i];
    unsigned split = node & 3u;
    if (!split) {
        if (!node)
            return;
        int s0 = t->depth[0] - k[0], s1 = t->depth[1] - k[1];
        for (long r = (long)at[0] << s0; r < (long)(at[0] + 1) << s0; r++)
            for (long c = (long)at[1] << s1; c < (long)(at[1] + 1) << s1; c++) {
                long bit = (r << t->depth[1]) + c;
                t->grid[bit >> 3] |= (unsigned char)(1u << (bit & 7));
            }
        return;
    }
    for (int c = 0, bit = 0; c < (split == 3 ? 4 : 2); c++, bit = 0) {
        int a[2] = {at[0], at[1]}, kk[2] = {k[0], k[1]};
        for (int j = 0; j < 2; j++)
            if (split >> j & 1u) {
                a[j] = 2 * a[j] + (c >> bit & 1);
                kk[j]++;
                bit++;
            }
        paint(t, (int)(node >> 2) + c, a, kk);
    }
}

/* The grid of the tree's leaves, when it is small enough. */
static int make_grid(mpb__wrist_table *t)
{
    int zero[2] = {0, 0};
    tree_depth(t, 0, zero, t->depth);
    if (t->depth[0] + t->depth[1] > MAX_GRID_DEPTH)
        return MPB_OK;
    long bits = 1L << (t->depth[0] + t->depth[1]);
    if (!(t->grid = calloc((size_t)(bits + 7) / 8, 1)))
        return MPB_ENOMEM;
    paint(t, 0, zero, zero);
    for (int k = 0; k < t->num_joints; k++)
        t->per_rad[k] = (double)(1L << t->depth[k]) / (t->hi[k] - t->lo[k]);
    t->stats.grid_bytes = (int)((bits + 7) / 8);
    return MPB_OK;
}

static int add_side(mpb_collision *coll, int id, const mpb__wrist_side *s)
{
    for (int i = 0; i < s->num_shapes; i++) {
        int rc = mpb_collision_add_movable(coll, id, &s->geoms[i], &s->offsets[i]);
        if (rc != MPB_OK)
            return rc;
    }
    return MPB_OK;
}

void mpb__wrist_table_free(mpb__wrist_table *t)
{
    if (t) {
        free(t->nodes);
        free(t->grid);
    }
    free(t);
}

int mpb__wrist_table_build(const mpb__wrist_spec *spec, mpb__wrist_table **out)
{
    struct timespec t0, t1;     /* CPU time: the machine may be shared */
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t0);
    mpb__wrist_table *t = calloc(1, sizeof *t);
    builder b = {spec, t, NULL, {0, 0}, NULL, 0};
    int rc = t ? mpb_collision_create(&b.coll) : MPB_ENOMEM;
    if (rc == MPB_OK)
        rc = add_side(b.coll, 0, &spec->side[0]);
    if (rc == MPB_OK)
        rc = add_side(b.coll, 1, &spec->side[1]);
    if (rc == MPB_OK)
        rc = mpb__grow((void **)&t->nodes, &t->cap, 1, sizeof *t->nodes);
    if (rc == MPB_OK) {
        int n = t->num_joints = spec->num_joints;
        rc = wrist_lipschitz(spec, b.R, &b.pts, &b.num_pts);
        double c[2] = {0, 0}, h[2] = {0, 0};
        for (int k = 0; k < n; k++) {
            t->lo[k] = spec->lo[k];
            t->hi[k] = spec->hi[k];
            c[k] = 0.5 * (t->lo[k] + t->hi[k]);
            h[k] = 0.5 * (t->hi[k] - t->lo[k]);
        }
        t->num_nodes = 1;
        if (rc == MPB_OK)
            rc = build_cell(&b, 0, c, h);
    }
    mpb_collision_destroy(b.coll);
    free(b.pts);
    if (rc == MPB_OK)
        rc = make_grid(t);
    if (rc != MPB_OK) {
        mpb__wrist_table_free(t);
        return rc;
    }
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t1);
    t->stats.nodes = t->num_nodes;
    t->stats.build_s = (double)(t1.tv_sec - t0.tv_sec) +
                       1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    t->stats.lipschitz[0] = b.R[0];
    t->stats.lipschitz[1] = b.R[1];
    *out = t;
    return MPB_OK;
}

int mpb__wrist_table_apart(const mpb__wrist_table *t, double v0, double v1)
{
    double v[2] = {v0, v1}, c[2], h[2];
    for (int k = 0; k < t->num_joints; k++)
        if (!(v[k] >= t->lo[k] && v[k] <= t->hi[k]))
            return 0;       /* outside, or NaN: FCL decides */
    if (t->grid) {
        /* A value on a cell's edge (to rounding, 1e-15 rad) may land in
         * either cell: both hold it, with the margin to spare. */
        long r = (long)((v0 - t->lo[0]) * t->per_rad[0]), col = 0;
        long nr = 1L << t->depth[0], nc = 1L << t->depth[1];
        if (t->num_joints == 2)
            col = (long)((v1 - t->lo[1]) * t->per_rad[1]);
        r = r < nr ? r : nr - 1;
        col = col < nc ? col : nc - 1;
        long bit = r * nc + col;
        return t->grid[bit >> 3] >> (bit & 7) & 1;
    }
    for (int k = 0; k < t->num_joints; k++) {
        c[k] = 0.5 * (t->lo[k] + t->hi[k]);
        h[k] = 0.5 * (t->hi[k] - t->lo[k]);
    }
    uint32_t node = t->nodes[0];
    while (node & 3u) {
        unsigned split = node & 3u, off = 0;
        int bit = 0;
        for (int j = 0; j < 2; j++) {
            if (!(split >> j & 1))
                continue;
            h[j] *= 0.5;
            if (v[j] >= c[j]) {
                c[j] += h[j];
                off |= 1u << bit;
            } else {
                c[j] -= h[j];
            }
            bit++;
        }
        node = t->nodes[(node >> 2) + off];
    }
    return node != 0;
}

void mpb__wrist_table_stats(const mpb__wrist_table *t, mpb__wrist_stats *out)
{
    *out = t->stats;
}

/* ---- a table as bytes ------------------------------------------------ */

/*
 * A table's bytes (its file's payload, wrist_cache.h), in this machine's
 * byte order: num_joints, num_nodes (uint32); nodes, apart_leaves,
 * open_leaves, distances, cut (int32); build_s, lipschitz[2] (double);
 * the nodes (uint32 each). The range and the grid are not stored: the
 * range is the spec's (which the key holds), the grid is painted again.
 */
#define PAYLOAD_HEAD (2 * 4 + 5 * 4 + 3 * 8)

unsigned char *mpb__wrist_table_encode(const mpb__wrist_table *t, size_t *len)
{
    *len = PAYLOAD_HEAD + 4 * (size_t)t->num_nodes;
    unsigned char *p = malloc(*len), *w = p;
    if (!p)
        return NULL;
    uint32_t u[2] = {(uint32_t)t->num_joints, (uint32_t)t->num_nodes};
    int32_t i[5] = {t->stats.nodes, t->stats.apart_leaves, t->stats.open_leaves,
                    t->stats.distances, t->stats.cut};
    double d[3] = {t->stats.build_s, t->stats.lipschitz[0], t->stats.lipschitz[1]};
    memcpy(w, u, sizeof u);
    memcpy(w += sizeof u, i, sizeof i);
    memcpy(w += sizeof i, d, sizeof d);
    memcpy(w + sizeof d, t->nodes, 4 * (size_t)t->num_nodes);
    return p;
}

/*
 * Is nodes[0 .. n) a tree, root first, for num_joints joints: every
 * node but the root the child of exactly one node before it, leaves 0
 * or 1 << 2, splits along existing joints only, at most 60 halvings of
 * a joint? Then the walks over it (apart(), tree_depth(), paint()) end,
 * stay in the array and shift no further than a long holds.
 */
static int valid_tree(const uint32_t *nodes, int n, int num_joints)
{
    unsigned char *depth = calloc((size_t)n, 2), *seen = calloc((size_t)n, 1);
    int ok = depth && seen;
    for (int i = 0; ok && i < n; i++) {
        uint32_t node = nodes[i];
        unsigned split = node & 3u;
        if (!split) {
            ok = node == 0 || node == 1u << 2;
            continue;
        }
        int first = (int)(node >> 2), kids = split == 3 ? 4 : 2;
        ok = (num_joints == 2 || split == 1) && first > i && first <= n - kids;
        for (int c = 0; ok && c < kids; c++) {
            unsigned char *dc = &depth[2 * (first + c)];
            ok = !seen[first + c];
            seen[first + c] = 1;
            dc[0] = (unsigned char)(depth[2 * i] + (split & 1u));
            dc[1] = (unsigned char)(depth[2 * i + 1] + (split >> 1 & 1u));
            ok = ok && dc[0] <= 60 && dc[1] <= 60;
        }
    }
    for (int i = 1; ok && i < n; i++)
        ok = seen[i];
    free(depth);
    free(seen);
    return ok;
}

int mpb__wrist_table_decode(const mpb__wrist_spec *spec,
                            const unsigned char *p, size_t len,
                            mpb__wrist_table **out)
{
    uint32_t u[2];
    int32_t i[5];
    double d[3];
    if (len < PAYLOAD_HEAD)
        return MPB_EPARSE;
    memcpy(u, p, sizeof u);
    memcpy(i, p + sizeof u, sizeof i);
    memcpy(d, p + sizeof u + sizeof i, sizeof d);
    if (u[0] != (uint32_t)spec->num_joints || u[1] < 1 ||
        u[1] > (UINT32_MAX >> 3) || len != PAYLOAD_HEAD + 4 * (size_t)u[1])
        return MPB_EPARSE;
    mpb__wrist_table *t = calloc(1, sizeof *t);
    if (!t || !(t->nodes = malloc(4 * (size_t)u[1]))) {
        free(t);
        return MPB_ENOMEM;
    }
    memcpy(t->nodes, p + PAYLOAD_HEAD, 4 * (size_t)u[1]);
    t->num_joints = spec->num_joints;
    t->num_nodes = t->cap = (int)u[1];
    for (int k = 0; k < t->num_joints; k++) {
        t->lo[k] = spec->lo[k];
        t->hi[k] = spec->hi[k];
    }
    t->stats = (mpb__wrist_stats){i[0], i[1], i[2], i[3], 0, d[0],
                                  {d[1], d[2]}, i[4], 1};
    int rc = valid_tree(t->nodes, t->num_nodes, t->num_joints) ? make_grid(t)
                                                                : MPB_EPARSE;
    if (rc != MPB_OK) {
        free(t->nodes);
        free(t->grid);
        free(t);
        return rc;
    }
    *out = t;
    return MPB_OK;
}
