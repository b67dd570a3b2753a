/*
 * bvh_distance.cpp - a mesh's distance to a primitive shape over FCL's own
 * OBBRSS tree (bvh_distance.h), FCL's answer for less. FCL bounds a
 * node's distance to the shape by the distance between the node's RSS and
 * an RSS around the shape: around a 25 cm cube that is a rectangle swept
 * by a 12.5 cm sphere, so near a box FCL cannot drop a node until the
 * box's corners are that far, and measures dozens of triangles by GJK
 * (about 5,000 instructions each) to find the nearest (a Panda link
 * against a MotionBenchMaker table: ~60 a pair, 96 % of a clearance).
 * Here, in the frame of the shape's own box, a node is bounded by the
 * gap to its box's axis-aligned box there, and a triangle by that of
 * its own, the lines to its vertices and its normal; dives down the
 * nearer child to a triangle, each from the nearest bound waiting, and a
 * node or triangle is measured only while its bound is below the best so
 * far by more than kTie. A triangle measured is proved the nearest, and
 * the walk ends, when the mesh's hull lies beyond the shape's box along
 * the line between their nearest points (mostly the first or second).
 *
 * Why the answer is FCL's: FCL's distance is the least, over the
 * triangles its traversal reaches, of its solver's triangle distance
 * (GJKSolver_libccd::shapeTriangleDistance at the request's tolerance);
 * those it skips lie at least its best so far away. Here the triangles
 * measured are measured by that same call, on the same vertices and
 * transforms (against a box, exactly and with a proof by
 * tri_box_distance(), which GJK on two polytopes matches to far below
 * 1e-9 m; by that call where the proof fails), and those skipped lie
 * at least the best so far away by
 * the bounds above (a gap along any direction is at most the distance;
 * every triangle lies in the box of each node above it; the shape lies
 * in its box; a gap along any line is at most the distance, and every
 * triangle lies in the hull of the mesh's vertices). So both are the
 * least triangle distance, up to the solver's own tolerance.
 * tests/unit/geometry/test_clearance_reference.c checks it.
 */
#include "geometry/bvh_distance.h"
#include "geometry/collision_world.h"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/narrowphase/detail/gjk_solver_libccd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>

namespace mpb {

namespace {

constexpr double kRound = 1e-12;   /* m; bounds lowered by this, for rounding */
/* m; a node is measured only if it may be nearer than the best so far by
 * more than this: a flat face parallel to a box's is many triangles at one
 * distance, and one of them is enough. Well below the 1e-9 m to which the
 * answer must be FCL's, well above the solver's tolerance (1e-10 m is
 * what the collision world asks). */
constexpr double kTie = 2e-10;

/* The mesh's frame in the box's: x_box = R x + T (box centre at 0). */
struct Frame {
    double R[3][3], T[3];
};

inline void to_box(const Frame &f, const fcl::Vector3d &x, double y[3])
{
    for (int k = 0; k < 3; k++)
        y[k] = f.R[k][0] * x[0] + f.R[k][1] * x[1] + f.R[k][2] * x[2] + f.T[k];
}

/* The support of the box of half sides h centred at 0 along u. */
inline double box_support(const double u[3], const double h[3])
{
    return std::fabs(u[0]) * h[0] + std::fabs(u[1]) * h[1] + std::fabs(u[2]) * h[2];
}

/* The distance between the axis-aligned box of centre c and half sides
 * r and the box of half sides h centred at 0 (box frame), and in u the
 * unit direction from the latter to the former (zero if they overlap);
 * INFINITY (u unset) as soon as it is known to be at least `stop`. */
inline double aabb_gap(const double c[3], const double r[3], const double h[3],
                       double stop, double u[3])
{
    double s = 0, g[3];
    for (int k = 0; k < 3; k++) {
        g[k] = std::max(0.0, std::fabs(c[k]) - h[k] - r[k]);
        s += g[k] * g[k];
    }
    if (s >= stop * stop)
        return INFINITY;
    s = std::sqrt(s);
    double inv = s > 0 ? 1.0 / s : 0.0;
    for (int k = 0; k < 3; k++)
        u[k] = (c[k] > 0 ? g[k] : -g[k]) * inv;
    return s;
}

/* A lower bound on the distance from obb (mesh frame) to the box of half
 * sides h centred at 0: the wider of the distance from the box to obb's
 * own axis-aligned box in the box's frame and the gap between the two
 * along the line between those (obb's own axes as well cost more than
 * they spared: 175k against 169k instructions a Panda clearance); or
 * INFINITY once it is known to be at least best. centre (if not null):
 * the distance from obb's centre to the box, which steers the dives. */
inline double node_lower(const Frame &f, const fcl::OBBd &obb, const double h[3],
                         double best, double *centre)
{
    double a[3][3], c[3], r[3]; /* a[j]: obb's axis j in the box's frame */
    const double *e = obb.extent.data();
    for (int j = 0; j < 3; j++)
        for (int k = 0; k < 3; k++)
            a[j][k] = f.R[k][0] * obb.axis(0, j) + f.R[k][1] * obb.axis(1, j) +
                      f.R[k][2] * obb.axis(2, j);
    to_box(f, obb.To, c);
    if (centre) {               /* its centre's distance to the box */
        double s = 0;
        for (int k = 0; k < 3; k++) {
            double g = std::max(0.0, std::fabs(c[k]) - h[k]);
            s += g * g;
        }
        *centre = std::sqrt(s);
    }
    for (int k = 0; k < 3; k++)
        r[k] = std::fabs(a[0][k]) * e[0] + std::fabs(a[1][k]) * e[1] +
               std::fabs(a[2][k]) * e[2];
    double u[3], gap = aabb_gap(c, r, h, best + kRound, u);
    if (gap == INFINITY)
        return gap;             /* enough to drop it */
    if (gap > 0) {              /* obb itself along u: at least as wide */
        double t = c[0] * u[0] + c[1] * u[1] + c[2] * u[2];
        for (int j = 0; j < 3; j++)
            t -= e[j] * std::fabs(a[j][0] * u[0] + a[j][1] * u[1] + a[j][2] * u[2]);
        gap = std::max(gap, t - box_support(u, h));
    }
    return gap - kRound;
}

/* The gap between triangle p and the box along unit direction u. */
inline double tri_gap(const double p[3][3], const double u[3], const double h[3])
{
    double lo = INFINITY;
    for (int i = 0; i < 3; i++)
        lo = std::min(lo, p[i][0] * u[0] + p[i][1] * u[1] + p[i][2] * u[2]);
    return lo - box_support(u, h);
}

/* A lower bound on the distance from triangle p (box frame) to the box:
 * the widest gap between the two along the line from the box to the
 * triangle's axis-aligned box, along the lines from the box to each
 * vertex, and along the triangle's normal. Where a vertex is nearest,
 * as mostly, this is the distance. */
inline double tri_lower(const double p[3][3], const double h[3], double best)
{
    double c[3], r[3], u[3];
    for (int k = 0; k < 3; k++) {
        double lo = std::min(p[0][k], std::min(p[1][k], p[2][k]));
        double hi = std::max(p[0][k], std::max(p[1][k], p[2][k]));
        c[k] = (lo + hi) / 2;
        r[k] = (hi - lo) / 2;
    }
    double gap = aabb_gap(c, r, h, best + kRound, u);
    if (gap == INFINITY)
        return gap;
    if (gap > 0) {
        gap = std::max(gap, tri_gap(p, u, h));
        for (int i = 0; i < 3; i++) {
            double z[3] = {0, 0, 0};
            double vg = aabb_gap(p[i], z, h, INFINITY, u);
            if (vg > 0)
                gap = std::max(gap, tri_gap(p, u, h));
        }
    }
    double a[3], b[3], n[3];
    for (int k = 0; k < 3; k++) {
        a[k] = p[1][k] - p[0][k];
        b[k] = p[2][k] - p[0][k];
    }
    n[0] = a[1] * b[2] - a[2] * b[1];
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
    double nn = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (nn > 1e-300) {
        for (int k = 0; k < 3; k++)
            n[k] /= nn;
        double t = n[0] * p[0][0] + n[1] * p[0][1] + n[2] * p[0][2];
        gap = std::max(gap, std::fabs(t) - box_support(n, h));
    }
    return gap - kRound;
}

/* The gap between the mesh's hull (mesh frame, mapped by f) and the box
 * of half sides h along unit direction u of the box's frame: a lower
 * bound on their distance. */
inline double hull_gap(const Frame &f, const BvhHull &hull, const double u[3],
                       const double h[3])
{
    double l[3];                /* -u in the mesh's frame */
    for (int j = 0; j < 3; j++)
        l[j] = -(f.R[0][j] * u[0] + f.R[1][j] * u[1] + f.R[2][j] * u[2]);
    int c = hull.dirs ? mpb__dirtable_cell(hull.dirs, l) : -1;
    const int *list = c >= 0 ? &hull.dirs->idx[hull.dirs->start[c]] : nullptr;
    int n = c >= 0 ? hull.dirs->start[c + 1] - hull.dirs->start[c] : hull.num;
    double hi = -INFINITY;      /* the most of the hull along -u */
    for (int k = 0; k < n; k++) {
        const double *v = hull.verts[list ? list[k] : k].data();
        hi = std::max(hi, v[0] * l[0] + v[1] * l[1] + v[2] * l[2]);
    }
    return -hi + (f.T[0] * u[0] + f.T[1] * u[1] + f.T[2] * u[2]) - box_support(u, h);
}

/* The point of triangle p nearest to x, into a, by the region of the
 * triangle's plane that x projects to; its squared distance. */
inline double point_tri_nearest(const double x[3], const double p[3][3], double a[3])
{
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    for (int k = 0; k < 3; k++) {
        ab[k] = p[1][k] - p[0][k];
        ac[k] = p[2][k] - p[0][k];
        ap[k] = x[k] - p[0][k];
        bp[k] = x[k] - p[1][k];
        cp[k] = x[k] - p[2][k];
    }
    auto dot = [](const double *u, const double *v) {
        return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    };
    double d1 = dot(ab, ap), d2 = dot(ac, ap), d3 = dot(ab, bp), d4 = dot(ac, bp);
    double d5 = dot(ab, cp), d6 = dot(ac, cp);
    double va = d3 * d6 - d5 * d4, vb = d5 * d2 - d1 * d6, vc = d1 * d4 - d3 * d2;
    double v = 0, w = 0;                /* a = p0 + v ab + w ac */
    if (d1 <= 0 && d2 <= 0) {
    } else if (d3 >= 0 && d4 <= d3) {
        v = 1;
    } else if (d6 >= 0 && d5 <= d6) {
        w = 1;
    } else if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        v = d1 / (d1 - d3);
    } else if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        w = d2 / (d2 - d6);
    } else if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
        w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        v = 1 - w;
    } else if (va + vb + vc != 0) {
        double den = va + vb + vc;
        v = vb / den;
        w = vc / den;
    }
    if (!std::isfinite(v) || !std::isfinite(w))
        v = w = 0;                      /* degenerate: p0, still a point of it */
    double s2 = 0;
    for (int k = 0; k < 3; k++) {
        a[k] = p[0][k] + v * ab[k] + w * ac[k];
        s2 += (x[k] - a[k]) * (x[k] - a[k]);
    }
    return s2;
}

/*
 * The distance between triangle p and the box of half sides h centred at
 * 0 (box frame), exact to rounding, with a proof: the least over the
 * pairs of features where two disjoint polytopes come nearest (a vertex
 * of one and the other; an edge of each), its points a (triangle) and b
 * (box), and the plane between them normal to a - b has the triangle on
 * one side and the box on the other. 0 if a pair of points meet; NaN if
 * the proof fails (they cross; or rounding), for the caller's solver.
 * In u the unit direction from b to a. About a third of libccd's GJK.
 */
inline double tri_box_distance(const double p[3][3], const double h[3], double u[3])
{
    double best = INFINITY, a[3], b[3];
    auto take = [&](double d2, const double *x, const double *y) {
        if (d2 < best) {
            best = d2;
            memcpy(a, x, sizeof a);
            memcpy(b, y, sizeof b);
        }
    };
    for (int i = 0; i < 3; i++) {       /* the triangle's vertices */
        double y[3], d2 = 0;
        for (int k = 0; k < 3; k++) {
            y[k] = std::clamp(p[i][k], -h[k], h[k]);
            d2 += (p[i][k] - y[k]) * (p[i][k] - y[k]);
        }
        take(d2, p[i], y);
    }
    /* A corner or an edge of the box is the nearest only if the triangle
       reaches past each face it bounds (a - b lies in its normal cone):
       out[k][0] past the - face along axis k, out[k][1] past the +. Any
       pair skipped wrongly would fail the proof below, never pass it. */
    bool out[3][2];
    for (int k = 0; k < 3; k++) {
        double lo = std::min(p[0][k], std::min(p[1][k], p[2][k]));
        double hi = std::max(p[0][k], std::max(p[1][k], p[2][k]));
        out[k][0] = lo <= -h[k] + 1e-9;
        out[k][1] = hi >= h[k] - 1e-9;
    }
    for (int c = 0; c < 8; c++) {       /* the box's corners */
        if (!out[0][c & 1] || !out[1][(c >> 1) & 1] || !out[2][(c >> 2) & 1])
            continue;
        double y[3] = {c & 1 ? h[0] : -h[0], c & 2 ? h[1] : -h[1], c & 4 ? h[2] : -h[2]};
        double x[3], d2 = point_tri_nearest(y, p, x);
        take(d2, x, y);
    }
    for (int i = 0; i < 3; i++) {       /* edge against edge */
        const double *e0 = p[i], *e1 = p[(i + 1) % 3];
        for (int k = 0; k < 3; k++) {   /* the box's 4 edges along axis k */
            int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
            for (int c = 0; c < 4; c++) {
                if (!out[k1][c & 1] || !out[k2][(c >> 1) & 1])
                    continue;
                double y0[3], y1[3];
                y0[k1] = y1[k1] = c & 1 ? h[k1] : -h[k1];
                y0[k2] = y1[k2] = c & 2 ? h[k2] : -h[k2];
                y0[k] = -h[k];
                y1[k] = h[k];
                double sp, t, d2 = coll::seg_seg_nearest(e0, e1, y0, y1, &sp, &t);
                if (d2 < best) {
                    double x[3], y[3];
                    for (int j = 0; j < 3; j++) {
                        x[j] = e0[j] + sp * (e1[j] - e0[j]);
                        y[j] = y0[j] + t * (y1[j] - y0[j]);
                    }
                    take(d2, x, y);
                }
            }
        }
    }
    if (!(best > 0))
        return best == 0 ? 0.0 : NAN;
    double d = 0;
    for (int k = 0; k < 3; k++) {
        u[k] = a[k] - b[k];
        d += u[k] * u[k];
    }
    d = std::sqrt(d);
    if (!(d > 1e-9))
        return NAN;             /* a direction too rough to prove by */
    for (int k = 0; k < 3; k++)
        u[k] /= d;
    double ua = u[0] * a[0] + u[1] * a[1] + u[2] * a[2];
    double ub = u[0] * b[0] + u[1] * b[1] + u[2] * b[2];
    for (int i = 0; i < 3; i++)
        if (p[i][0] * u[0] + p[i][1] * u[1] + p[i][2] * u[2] < ua - 1e-12)
            return NAN;
    if (box_support(u, h) > ub + 1e-12)
        return NAN;
    return d;
}

/* A node waiting in the queue, by its lower bound (a min-heap). */
struct Later {
    bool operator()(const BvhQueued &a, const BvhQueued &b) const
    {
        return a.lower > b.lower;
    }
};

template <class Shape>
double traverse(const BvhObbRss &m, const fcl::Transform3d &tf1, const Shape &s,
                const fcl::Transform3d &tf2, const double c[3], const double h[3],
                double tol, double best, std::vector<BvhQueued> &heap,
                const BvhHull *hull)
{
    /* x_box = R2^T (R1 x + t1 - t2) - c */
    Frame f;
    const fcl::Matrix3d R1 = tf1.linear(), R2 = tf2.linear();
    const fcl::Vector3d dt = tf1.translation() - tf2.translation();
    for (int k = 0; k < 3; k++) {
        for (int j = 0; j < 3; j++)
            f.R[k][j] = R2(0, k) * R1(0, j) + R2(1, k) * R1(1, j) + R2(2, k) * R1(2, j);
        f.T[k] = R2(0, k) * dt[0] + R2(1, k) * dt[1] + R2(2, k) * dt[2] - c[k];
    }
    fcl::detail::GJKSolver_libccd<double> solver;
    solver.distance_tolerance = tol;
    /* Triangle t's distance to the shape, and in u the unit direction
       (box frame) between their nearest points (zero if unknown): a box
       by tri_box_distance(), else (or should it fail) by the call FCL's
       own leaf test makes. */
    auto measure = [&](const fcl::Triangle &t, double u[3]) {
        if constexpr (std::is_same<Shape, fcl::Boxd>::value) {
            double p[3][3];
            to_box(f, m.vertices[t[0]], p[0]);
            to_box(f, m.vertices[t[1]], p[1]);
            to_box(f, m.vertices[t[2]], p[2]);
            double d = tri_box_distance(p, h, u);
            if (!std::isnan(d))
                return d;
        }
        double d;
        fcl::Vector3d q1, q2;
        solver.shapeTriangleDistance(s, tf2, m.vertices[t[0]], m.vertices[t[1]],
                                     m.vertices[t[2]], tf1, &d, &q2, &q1);
        fcl::Vector3d w = R2.transpose() * (q1 - q2);
        double wn = w.norm();
        for (int k = 0; k < 3; k++)
            u[k] = wn > 0 ? w[k] / wn : 0.0;
        return d;
    };
    using Node = fcl::BVNode<fcl::OBBRSSd>;
    const Node *nodes = &m.getBV(0);
    const Later later;
    heap.clear();
    /* Dives, each from the nearest bound waiting (the root first) down
       the child whose centre is nearer (a better guide than the bounds:
       79k against 84k instructions a Panda clearance) to a triangle,
       the other child left waiting; with the hull's proof (mostly at
       hand) the first triangles are the answer, for a dozen levels of
       bounds. Without a hull, nearest bound first. Either way every
       node whose bound falls short of the best so far is opened. */
    /* the hint's triangle with the least bound, measured first: mostly
       the nearest, proved so by the hull, with no node bounded */
    if (hull && hull->hint >= 0 && hull->hint < hull->num && hull->tri_start) {
        double lo = INFINITY;
        int tri = -1;
        for (int i = hull->tri_start[hull->hint]; i < hull->tri_start[hull->hint + 1]; i++) {
            const fcl::Triangle &t = m.tri_indices[hull->tris[i]];
            double p[3][3];
            to_box(f, m.vertices[t[0]], p[0]);
            to_box(f, m.vertices[t[1]], p[1]);
            to_box(f, m.vertices[t[2]], p[2]);
            double l = tri_lower(p, h, best);
            if (l < lo) {
                lo = l;
                tri = hull->tris[i];
            }
        }
        if (tri >= 0 && lo < best - kTie) {
            double u[3], d = measure(m.tri_indices[tri], u);
            if (d <= 0)
                return 0.0;
            if (d < best) {
                best = d;
                if ((u[0] != 0 || u[1] != 0 || u[2] != 0) &&
                    hull_gap(f, *hull, u, h) >= best - kTie)
                    return best;
            }
        }
    }
    bool diving = hull != nullptr, next = true;
    BvhQueued top = {node_lower(f, nodes[0].bv.obb, h, best, nullptr), 0};
    for (;;) {
        if (!next) {
            if (heap.empty())
                break;
            std::pop_heap(heap.begin(), heap.end(), later);
            top = heap.back();
            heap.pop_back();
        }
        next = false;
        if (!(top.lower < best - kTie))
            break;              /* nothing left can be nearer */
        const Node &n = nodes[top.node];
        if (n.first_child < 0) {    /* a triangle, its own bound below */
            double u[3], d = measure(m.tri_indices[-(n.first_child + 1)], u);
            if (best <= 0 || d <= 0)
                return 0.0;
            if (!(d < best))
                continue;
            best = d;
            /* the line between the nearest points: should the hull lie
               beyond the box along it by all but kTie, no triangle is
               nearer than this one by more */
            if (hull && (u[0] != 0 || u[1] != 0 || u[2] != 0) &&
                hull_gap(f, *hull, u, h) >= best - kTie)
                return best;
            continue;
        }
        BvhQueued kid[2];
        double ctr[2];
        int nk = 0;
        for (int child = n.first_child; child <= n.first_child + 1; child++) {
            const Node &k = nodes[child];
            double lo;
            if (k.first_child < 0) {
                const fcl::Triangle &t = m.tri_indices[-(k.first_child + 1)];
                double p[3][3];
                to_box(f, m.vertices[t[0]], p[0]);
                to_box(f, m.vertices[t[1]], p[1]);
                to_box(f, m.vertices[t[2]], p[2]);
                lo = tri_lower(p, h, best);
                ctr[nk] = lo;
            } else {
                lo = node_lower(f, k.bv.obb, h, best, &ctr[nk]);
            }
            if (lo < best - kTie)
                kid[nk++] = {std::max(lo, top.lower), child};
        }
        if (diving && nk > 0) {     /* on down the nearer */
            if (nk == 2 && ctr[1] < ctr[0])
                std::swap(kid[0], kid[1]);
            top = kid[0];
            next = true;
            kid[0] = kid[--nk];
        }
        for (int i = 0; i < nk; i++) {
            heap.push_back(kid[i]);
            std::push_heap(heap.begin(), heap.end(), later);
        }
    }
    return best;
}

} // namespace

double bvh_shape_distance(const BvhObbRss &m, const fcl::Transform3d &tf1,
                          const fcl::CollisionGeometryd &g,
                          const fcl::Transform3d &tf2, const double box_c[3],
                          const double box_h[3], double tol, double below,
                          std::vector<BvhQueued> &heap, const BvhHull *hull)
{
    if (m.getModelType() != fcl::BVH_MODEL_TRIANGLES)
        return NAN;
    if (!m.isOccupied())
        return below;
    switch (g.getNodeType()) {
    case fcl::GEOM_BOX:
        return traverse(m, tf1, static_cast<const fcl::Boxd &>(g), tf2, box_c, box_h, tol, below, heap, hull);
    case fcl::GEOM_CYLINDER:
        return traverse(m, tf1, static_cast<const fcl::Cylinderd &>(g), tf2, box_c, box_h, tol, below, heap, hull);
    case fcl::GEOM_CONE:
        return traverse(m, tf1, static_cast<const fcl::Coned &>(g), tf2, box_c, box_h, tol, below, heap, hull);
    case fcl::GEOM_CAPSULE:
        return traverse(m, tf1, static_cast<const fcl::Capsuled &>(g), tf2, box_c, box_h, tol, below, heap, hull);
    default:
        return NAN;
    }
}

} // namespace mpb
