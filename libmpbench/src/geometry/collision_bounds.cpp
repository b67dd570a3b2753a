/*
 * collision_bounds.cpp - cheap bounds that prove two shapes of the collision
 * world "certainly apart" before any narrow phase: bounding spheres,
 * capsules around meshes, planes between vertex sets (GJK steps). Each
 * keeps a margin, so that a verdict is never other than FCL's.
 */
#include "geometry/collision_world.h"

#include "geometry/simplex.h"

namespace mpb {
namespace coll {


/* Directions gjk_gap() tries at most (instructions a Panda collision
 * check, by that most: 3: 52.7k, 6: 37.4k, 12: 32.1k, 24: 32.1k). */
#define MPB__GJK_STEPS 16

/* The squared distance between segments p0 p1 and q0 q1, and in *s_out
 * and *t_out the parameters of their nearest points (p0 + s (p1 - p0),
 * q0 + t (q1 - q0)). */
double seg_seg_nearest(const double p0[3], const double p1[3], const double q0[3],
                       const double q1[3], double *s_out, double *t_out)
{
    double d1[3], d2[3], r[3];
    for (int k = 0; k < 3; k++) {
        d1[k] = p1[k] - p0[k];
        d2[k] = q1[k] - q0[k];
        r[k] = p0[k] - q0[k];
    }
    auto dot = [](const double *a, const double *b) {
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    };
    double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r), sp, t;
    const double tiny = 1e-300;
    if (a <= tiny && e <= tiny) {
        sp = t = 0;
    } else if (a <= tiny) {
        sp = 0;
        t = std::clamp(f / e, 0.0, 1.0);
    } else {
        double cc = dot(d1, r);
        if (e <= tiny) {
            t = 0;
            sp = std::clamp(-cc / a, 0.0, 1.0);
        } else {
            double b = dot(d1, d2), den = a * e - b * b;
            sp = den > 0 ? std::clamp((b * f - cc * e) / den, 0.0, 1.0) : 0.0;
            t = (b * sp + f) / e;
            if (t < 0) {
                t = 0;
                sp = std::clamp(-cc / a, 0.0, 1.0);
            } else if (t > 1) {
                t = 1;
                sp = std::clamp((b - cc) / a, 0.0, 1.0);
            }
        }
    }
    double s2 = 0;
    for (int k = 0; k < 3; k++) {
        double x = p0[k] + d1[k] * sp - (q0[k] + d2[k] * t);
        s2 += x * x;
    }
    *s_out = sp;
    *t_out = t;
    return s2;
}

/* The squared distance between segments p0 p1 and q0 q1. */
double seg_seg_dist2(const double p0[3], const double p1[3], const double q0[3],
                     const double q1[3])
{
    double s, t;
    return seg_seg_nearest(p0, p1, q0, q1, &s, &t);
}

/* Are shape a (with a capsule) and shape b certainly apart: b's capsule,
 * or else its bounding sphere, clears a's capsule by the margin? */
bool caps_apart(const Shape &a, const Shape &b)
{
    double r = a.cap_r + MPB__CAP_MARGIN;
    if (b.has_cap) {
        r += b.cap_r;
        return seg_seg_dist2(a.wcap[0], a.wcap[1], b.wcap[0], b.wcap[1]) > r * r;
    }
    r += b.bradius;
    return seg_seg_dist2(a.wcap[0], a.wcap[1], b.wcenter, b.wcenter) > r * r;
}

/* How far mesh shape s reaches along world direction d: max of d . x
 * over its vertices x in the world, and the (first) vertex there, an index
 * in s.verts. Only the vertices listed for d's cell are scanned: the same
 * value and vertex as a scan of all (dirtable.h). The least is
 * -mesh_reach(-d), to the bit: negation is exact. */
void mesh_reach(const Shape &s, const double d[3], double &hi, int &ihi)
{
    const double *R = s.world.R;
    double l[3];              /* d in the mesh's frame */
    for (int k = 0; k < 3; k++)
        l[k] = R[k] * d[0] + R[3 + k] * d[1] + R[6 + k] * d[2];
    double off = s.world.t[0] * d[0] + s.world.t[1] * d[1] + s.world.t[2] * d[2];
    int c = s.dirs ? mpb__dirtable_cell(s.dirs, l) : -1;
    const int *list = c >= 0 ? &s.dirs->idx[s.dirs->start[c]] : nullptr;
    int n = c >= 0 ? s.dirs->start[c + 1] - s.dirs->start[c] : s.num_verts;
    hi = -INFINITY;
    ihi = 0;
    for (int k = 0; k < n; k++) {
        int i = list ? list[k] : k;
        const double *v = s.verts[i].data();
        double x = v[0] * l[0] + v[1] * l[1] + v[2] * l[2];
        if (x > hi) {
            hi = x;
            ihi = i;
        }
    }
    hi += off;
}

/*
 * The widest gap found between mesh a and a convex set B: the most, over
 * the directions tried, of (min over B of d . x - max over a's vertices of
 * d . x) / |d|, a lower bound on their distance (every point of the mesh
 * lies within its vertices' hull). The directions: d, then those of a GJK
 * search for the nearest points of the two (simplex.h), each from the
 * points that came out nearest along the last ones, until a gap passes
 * stop, the two come within stop (no gap can pass it), or no nearer point
 * is found. Each gap is exact on its own (mesh_reach()), so a poor
 * direction costs time, never a wrong answer. lowest(d, lo): B's min
 * along d, and which point of B is there; point(which, p): that point
 * (world); visit(i): each vertex of a found extreme along the way.
 */
template <class Lowest, class Point, class Visit>
double gjk_gap(const Shape &a, const Lowest &lowest, const Point &point,
               double d[3], double stop, const Visit &visit)
{
    double simplex[4][3], best = -INFINITY;
    int m = 0;
    for (int iter = 0; iter < MPB__GJK_STEPS; iter++) {
        double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], n = std::sqrt(dd);
        /* past the first, d is a point of B less one of a's hull: the
           two are within |d| */
        if (!(n > 1e-12) || (iter > 0 && !(n > stop)))
            return best;
        double ahi, blo, pa[3], pb[3], w[3];
        int iahi;
        mesh_reach(a, d, ahi, iahi);
        visit(iahi);
        int which = lowest(d, blo);
        best = std::max(best, (blo - ahi) / n);
        if (blo - ahi > stop * n)
            return best;
        point(which, pb);
        mpb_pose_apply(&a.world, a.verts[iahi].data(), pa);
        for (int k = 0; k < 3; k++)
            w[k] = pb[k] - pa[k];
        /* no nearer point of the difference along d: d is about the
           nearest */
        if (iter > 0 && dd - (d[0] * w[0] + d[1] * w[1] + d[2] * w[2]) <= 1e-9 * dd)
            return best;
        memcpy(simplex[m++], w, sizeof w);
        m = mpb__simplex_nearest(simplex, m, d);
        if (m == 0 || m == 4)   /* they overlap */
            return best;
    }
    return best;
}

double meshes_gap(const Shape &a, const Shape &b, double stop)
{
    double d[3];
    for (int k = 0; k < 3; k++)
        d[k] = b.wcenter[k] - a.wcenter[k];
    auto lowest = [&b](const double *dir, double &lo) {
        double nd[3] = {-dir[0], -dir[1], -dir[2]};
        int i;
        mesh_reach(b, nd, lo, i);
        lo = -lo;
        return i;
    };
    auto point = [&b](int i, double p[3]) {
        mpb_pose_apply(&b.world, b.verts[i].data(), p);
    };
    return gjk_gap(a, lowest, point, d, stop, [](int) {});
}

/*
 * Are meshes a and b certainly apart: is there a plane between all the
 * vertices of one and all of the other, with the margin (meshes_gap())?
 * Then their convex hulls are apart, and the triangles within them too.
 * Mesh pairs of robot links near each other (two links apart along the
 * arm) are mostly told apart here, where FCL's BVH traversal went
 * hundreds of box tests deep.
 */
bool meshes_apart(const Shape &a, const Shape &b)
{
    return meshes_gap(a, b, MPB__CAP_MARGIN) > MPB__CAP_MARGIN;
}

/*
 * A lower bound on the distance from mesh a to static ss: the widest gap
 * between a's vertices and ss's box (which holds the static) along one of
 * the box's axes or the line between their centres (every point of the
 * mesh lies within its vertices' hull); with search, unless that passes
 * stop, also along the directions of gjk_gap() from that line: tighter,
 * for a distance query to skip the pair by. A few dozen dot products:
 * far cheaper than the FCL distance it may spare. upper (if not null):
 * the least distance from the vertices of a met on the search to ss
 * (point_static_distance()), an upper bound on the pair's distance;
 * INFINITY if none was measured; upper_vertex (if not null): that
 * vertex, an index in a.verts, or -1.
 */
double mesh_static_lower(const Shape &a, const Shape &ss, double stop, bool search,
                         double *upper, int *upper_vertex)
{
    if (upper)
        *upper = INFINITY;
    if (upper_vertex)
        *upper_vertex = -1;
    const double *R = ss.world.R;
    double c[3];              /* the box's centre in the world */
    mpb_pose_apply(&ss.world, ss.lbox_c, c);
    double gap = -INFINITY, d[3];
    for (int k = 0; k < 4; k++) {
        if (k < 3) {
            d[0] = R[k], d[1] = R[3 + k], d[2] = R[6 + k];
        } else {
            for (int i = 0; i < 3; i++)
                d[i] = c[i] - a.wcenter[i];
            double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            if (!(n > 1e-12))
                break;
            for (int i = 0; i < 3; i++)
                d[i] /= n;
        }
        double mid = c[0] * d[0] + c[1] * d[1] + c[2] * d[2], half = 0;
        for (int j = 0; j < 3; j++)
            half += ss.lbox_h[j] * std::fabs(R[j] * d[0] + R[3 + j] * d[1] + R[6 + j] * d[2]);
        double lo, hi, nd[3] = {-d[0], -d[1], -d[2]};
        int ilo, ihi;
        mesh_reach(a, d, hi, ihi);
        mesh_reach(a, nd, lo, ilo);
        lo = -lo;
        gap = std::max(gap, std::max(lo - (mid + half), (mid - half) - hi));
    }
    if (!search || gap - MPB__CAP_MARGIN > stop)
        return gap - MPB__CAP_MARGIN;
    auto lowest = [&](const double *dir, double &lo) {
        int corner = 0;       /* bit j: the box's + side along axis j */
        lo = c[0] * dir[0] + c[1] * dir[1] + c[2] * dir[2];
        for (int j = 0; j < 3; j++) {
            double along = R[j] * dir[0] + R[3 + j] * dir[1] + R[6 + j] * dir[2];
            lo -= ss.lbox_h[j] * std::fabs(along);
            corner |= (along <= 0) << j;
        }
        return corner;
    };
    auto point = [&](int corner, double p[3]) {
        for (int k = 0; k < 3; k++) {
            p[k] = c[k];
            for (int j = 0; j < 3; j++)
                p[k] += (corner >> j & 1 ? ss.lbox_h[j] : -ss.lbox_h[j]) * R[3 * k + j];
        }
    };
    for (int i = 0; i < 3; i++)
        d[i] = c[i] - a.wcenter[i];
    auto visit = [&](int i) {
        if (!upper)
            return;
        double p[3];
        mpb_pose_apply(&a.world, a.verts[i].data(), p);
        double dp = point_static_distance(ss, p);
        if (dp < *upper) {
            *upper = dp;
            if (upper_vertex)
                *upper_vertex = i;
        }
    };
    gap = std::max(gap, gjk_gap(a, lowest, point, d, stop + MPB__CAP_MARGIN, visit));
    return gap - MPB__CAP_MARGIN;
}

/*
 * The distance from world point p to static ss: exact (to rounding) for a
 * box, sphere, cylinder or capsule, 0 inside; INFINITY for any other
 * shape (no bound).
 */
double point_static_distance(const Shape &ss, const double p[3])
{
    const double *R = ss.world.R, *t = ss.world.t, *h = ss.dims;
    double x[3];              /* p in ss's frame */
    for (int k = 0; k < 3; k++)
        x[k] = R[k] * (p[0] - t[0]) + R[3 + k] * (p[1] - t[1]) + R[6 + k] * (p[2] - t[2]);
    switch (ss.type) {
    case MPB_SHAPE_BOX: {
        double s = 0;
        for (int k = 0; k < 3; k++) {
            double g = std::fabs(x[k]) - h[k] / 2;
            if (g > 0)
                s += g * g;
        }
        return std::sqrt(s);
    }
    case MPB_SHAPE_SPHERE:
        return std::max(0.0, std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) - h[0]);
    case MPB_SHAPE_CYLINDER: {
        double r = std::max(0.0, std::sqrt(x[0] * x[0] + x[1] * x[1]) - h[0]);
        double z = std::max(0.0, std::fabs(x[2]) - h[1] / 2);
        return std::sqrt(r * r + z * z);
    }
    case MPB_SHAPE_CAPSULE: {
        double z = std::clamp(x[2], -h[1] / 2, h[1] / 2);
        double r = std::sqrt(x[0] * x[0] + x[1] * x[1] + (x[2] - z) * (x[2] - z));
        return std::max(0.0, r - h[0]);
    }
    default:
        return INFINITY;
    }
}

/*
 * The distance from world point p to static ss, and in u the unit
 * direction (world) from the point of ss nearest to p towards p: exact
 * (to rounding) for a box, sphere, cylinder or capsule; 0 (u unset) if p
 * is in ss; INFINITY (u unset) for any other shape.
 */
double point_static_away(const Shape &ss, const double p[3], double u[3])
{
    const double *R = ss.world.R, *t = ss.world.t, *h = ss.dims;
    double x[3], g[3] = {0, 0, 0}; /* p in ss's frame; p less its nearest */
    for (int k = 0; k < 3; k++)
        x[k] = R[k] * (p[0] - t[0]) + R[3 + k] * (p[1] - t[1]) + R[6 + k] * (p[2] - t[2]);
    double d;
    switch (ss.type) {
    case MPB_SHAPE_BOX:
        for (int k = 0; k < 3; k++) {
            double e = std::fabs(x[k]) - h[k] / 2;
            g[k] = e > 0 ? std::copysign(e, x[k]) : 0.0;
        }
        d = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
        break;
    case MPB_SHAPE_SPHERE: {
        double r = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        if (!(r > h[0]))
            return 0.0;
        for (int k = 0; k < 3; k++)
            g[k] = x[k] / r;
        d = r - h[0];
        break;
    }
    case MPB_SHAPE_CYLINDER: {
        double r = std::sqrt(x[0] * x[0] + x[1] * x[1]), e = std::fabs(x[2]) - h[1] / 2;
        if (r > h[0]) {
            g[0] = x[0] * (1 - h[0] / r);
            g[1] = x[1] * (1 - h[0] / r);
        }
        g[2] = e > 0 ? std::copysign(e, x[2]) : 0.0;
        d = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
        break;
    }
    case MPB_SHAPE_CAPSULE: {
        double z = std::clamp(x[2], -h[1] / 2, h[1] / 2);
        g[0] = x[0], g[1] = x[1], g[2] = x[2] - z;
        double r = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
        if (!(r > h[0]))
            return 0.0;
        d = r - h[0];
        for (int k = 0; k < 3; k++)
            g[k] /= r;
        break;
    }
    default:
        return INFINITY;
    }
    if (!(d > 0))
        return 0.0;
    double n = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    for (int k = 0; k < 3; k++)
        u[k] = (R[3 * k] * g[0] + R[3 * k + 1] * g[1] + R[3 * k + 2] * g[2]) / n;
    return d;
}

/*
 * The distance from mesh a to static ss if vertex i of a (an index in
 * a.verts) is provably the nearest to it, else NaN. The proof: with u
 * the direction from ss's point nearest to the vertex towards it, every
 * vertex of a lies at least as far along u as that one, so the plane
 * through the vertex normal to u has a's hull (and every triangle) on
 * one side, and ss (convex, its nearest point on the plane through that
 * point normal to u) on the other: no two of their points are nearer
 * than the vertex and its nearest point, which is the distance. A
 * vertex in ss: they touch, 0. Each of a.verts is a vertex of some
 * triangle (extreme_vertices()), so the distance is that of the
 * surface, which FCL measures. Mostly so for a link above a table,
 * for two dozen dot products where the triangle search took
 * thousands of instructions. A box or a sphere only (see below).
 */
double mesh_static_vertex(const Shape &a, const Shape &ss, int i)
{
    /* FCL measures a triangle against a box by GJK, which ends on a
       polytope's own features, and against a sphere in closed form:
       both exact. Against a cylinder, cone or capsule its GJK stops up
       to a few 1e-9 m above the distance: those are left to it. */
    if (i < 0 || i >= a.num_verts ||
        (ss.type != MPB_SHAPE_BOX && ss.type != MPB_SHAPE_SPHERE))
        return NAN;
    double p[3], u[3];
    mpb_pose_apply(&a.world, a.verts[i].data(), p);
    double d = point_static_away(ss, p, u);
    if (d == INFINITY)
        return NAN;
    if (!(d > 0))
        return 0.0;
    double nu[3] = {-u[0], -u[1], -u[2]}, hi;
    int ihi;
    mesh_reach(a, nu, hi, ihi);         /* -hi: the least of a along u */
    /* rounding of the two dot products: far below the 1e-9 m asked */
    return -hi >= u[0] * p[0] + u[1] * p[1] + u[2] * p[2] - 1e-12 ? d : NAN;
}

/* The ends of a's capsule in the frame of static ss's box, from its centre. */
void cap_in_box(const Shape &a, const Shape &ss, double e[2][3])
{
    const double *R = ss.world.R;
    for (int i = 0; i < 2; i++) {
        double d[3];
        for (int k = 0; k < 3; k++)
            d[k] = a.wcap[i][k] - ss.world.t[k];
        for (int k = 0; k < 3; k++)
            e[i][k] = R[k] * d[0] + R[3 + k] * d[1] + R[6 + k] * d[2] - ss.lbox_c[k];
    }
}

/* Does a's capsule certainly miss static ss: its segment misses ss's box
 * grown by the radius and the margin (which holds every point within
 * that distance of the box)? */
bool cap_misses_static(const Shape &a, const Shape &ss)
{
    double e[2][3], t0 = 0, t1 = 1;
    cap_in_box(a, ss, e);
    for (int k = 0; k < 3; k++) {
        double h = ss.lbox_h[k] + a.cap_r + MPB__CAP_MARGIN, d = e[1][k] - e[0][k];
        if (std::fabs(d) < 1e-300) {
            if (e[0][k] < -h || e[0][k] > h)
                return true;
            continue;
        }
        double ta = (-h - e[0][k]) / d, tb = (h - e[0][k]) / d;
        if (ta > tb)
            std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 > t1)
            return true;
    }
    return false;
}

/* A lower bound on the distance from a's capsule to static ss: the widest
 * gap along one axis of ss's box, or to its bounding sphere, less the
 * radii. */
double cap_static_lower(const Shape &a, const Shape &ss)
{
    double e[2][3], gap = 0;
    cap_in_box(a, ss, e);
    for (int k = 0; k < 3; k++) {
        double lo = std::min(e[0][k], e[1][k]), hi = std::max(e[0][k], e[1][k]);
        gap = std::max(gap, std::max(lo - ss.lbox_h[k], -ss.lbox_h[k] - hi));
    }
    double sph = std::sqrt(seg_seg_dist2(a.wcap[0], a.wcap[1], ss.wcenter,
                                         ss.wcenter)) - ss.bradius;
    return std::max(gap, sph) - a.cap_r - MPB__CAP_MARGIN;
}

} // namespace coll
} // namespace mpb
