/*
 * collision_depth.cpp - how deep the robot is where it collides: for each
 * overlapping pair a lower and an upper bound on its penetration depth
 * (the shortest translation that parts the two), mpb__collision_depth().
 *
 * Lower bound: the deepest point of one shape inside the other. A point p
 * of shape A that lies inside shape B at distance e from B's surface must
 * leave B before the two are apart, so no translation shorter than e parts
 * them. The points tried (those within the other shape's box): every
 * vertex of a mesh; for a primitive, points spread over its solid (a
 * 9 x 9 x 9 grid of a box, 9 levels of rings along a round shape's axis)
 * and its extreme points along the directions of the upper bound below;
 * both ways round.
 * The distance from a point inside to the surface is exact for boxes,
 * spheres, cylinders and capsules, a lower bound for cones (the distance
 * to the slanted side's line), and for a mesh (closed, by its winding
 * number) the distance to its nearest triangle.
 *
 * Upper bound: for any unit direction n, moving A by -(h_A(n) + h_B(-n)) n
 * (h: a shape's support function, its extent along a direction, exact for
 * primitives and over a mesh's vertices) leaves a plane normal to n
 * between A's hull and B's hull, so A and B apart. The least of that over
 * the directions tried, refined by a local search on the sphere of
 * directions, is an upper bound on the penetration depth of the two
 * shapes' convex hulls and so of the shapes; it is the hulls' own depth
 * when the search finds its minimum (always for two boxes or a sphere
 * against a box, whose optimal directions are among the first tried).
 *
 * A static plane is a surface: a shape crossing it is parted from it by
 * its lesser extent past it, both bounds.
 */
#include <algorithm>
#include <vector>

#include "geometry/collision_world.h"
#include "geometry/collision_internal.h"

namespace mpb {
namespace coll {
namespace {

using V3 = fcl::Vector3d;

V3 to_world(const Shape &s, const V3 &x)
{
    double in[3] = {x[0], x[1], x[2]}, out[3];
    mpb_pose_apply(&s.world, in, out);
    return V3(out[0], out[1], out[2]);
}

V3 to_local(const Shape &s, const V3 &p)
{
    const double *R = s.world.R, *t = s.world.t;
    V3 d(p[0] - t[0], p[1] - t[1], p[2] - t[2]), x;
    for (int k = 0; k < 3; k++)
        x[k] = R[k] * d[0] + R[3 + k] * d[1] + R[6 + k] * d[2];
    return x;
}

V3 dir_local(const Shape &s, const V3 &n)
{
    const double *R = s.world.R;
    V3 x;
    for (int k = 0; k < 3; k++)
        x[k] = R[k] * n[0] + R[3 + k] * n[1] + R[6 + k] * n[2];
    return x;
}

const fcl::BVHModel<fcl::OBBRSSd> *model(const Shape &s)
{
    return static_cast<const fcl::BVHModel<fcl::OBBRSSd> *>(
        s.obj->collisionGeometry().get());
}

/* Shape s's extreme point (world) along the world direction n. */
V3 extreme(const Shape &s, const V3 &n)
{
    return to_world(s, support(s, dir_local(s, n)));
}

/* How far A must move along -n to clear B's hull by a plane normal to n. */
double part_along(const Shape &a, const Shape &b, const V3 &n)
{
    return n.dot(extreme(a, n)) - n.dot(extreme(b, -n));
}

/* The distance from p to the triangle abc. */
double point_triangle(const V3 &p, const V3 &a, const V3 &b, const V3 &c)
{
    V3 ab = b - a, ac = c - a, ap = p - a;
    double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0)
        return ap.norm();
    V3 bp = p - b;
    double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3)
        return bp.norm();
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0)
        return (p - (a + ab * (d1 / (d1 - d3)))).norm();
    V3 cp = p - c;
    double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6)
        return cp.norm();
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0)
        return (p - (a + ac * (d2 / (d2 - d6)))).norm();
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).norm();
    double den = 1.0 / (va + vb + vc);
    return (p - (a + ab * (vb * den) + ac * (vc * den))).norm();
}

/* How deep local point x lies inside mesh s (0 outside): inside by the
 * winding number of its triangles about x, then the nearest triangle.
 * A point inside the mesh is no deeper than inside the mesh's own box (its
 * vertices' bounds; 1e-12 m covers rounding): when that is at most floor,
 * its depth cannot raise a maximum that is floor already, and 0 is
 * returned without reading a triangle. */
double mesh_point_depth(const Shape &s, const V3 &x, double floor)
{
    const auto *m = model(s);
    const fcl::AABBd &bb = m->aabb_local;
    double in_box = INFINITY;
    for (int k = 0; k < 3; k++)
        in_box = std::min({in_box, x[k] - bb.min_[k], bb.max_[k] - x[k]});
    if (in_box + 1e-12 <= floor)
        return 0.0;
    double wind = 0;
    for (int i = 0; i < m->num_tris; i++) {
        const fcl::Triangle &t = m->tri_indices[i];
        V3 a = m->vertices[t[0]] - x, b = m->vertices[t[1]] - x,
           c = m->vertices[t[2]] - x;
        double la = a.norm(), lb = b.norm(), lc = c.norm();
        double num = a.dot(b.cross(c));
        double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
        wind += 2 * std::atan2(num, den);
    }
    /* a closed surface winds 4 pi about a point inside it */
    if (std::fabs(wind) <= 2 * M_PI)
        return 0.0;
    double near = INFINITY;
    for (int i = 0; i < m->num_tris; i++) {
        const fcl::Triangle &t = m->tri_indices[i];
        near = std::min(near, point_triangle(V3(0, 0, 0), m->vertices[t[0]] - x,
                                             m->vertices[t[1]] - x,
                                             m->vertices[t[2]] - x));
    }
    return near;
}

/* How deep world point p lies inside shape s (0 outside or on it; a
 * mesh may answer 0 for a depth of at most floor, mesh_point_depth()). */
double point_depth(const Shape &s, const V3 &p, double floor)
{
    V3 x = to_local(s, p);
    const double *h = s.dims;
    switch (s.type) {
    case MPB_SHAPE_BOX: {
        double e = INFINITY;
        for (int k = 0; k < 3; k++)
            e = std::min(e, h[k] / 2 - std::fabs(x[k]));
        return std::max(0.0, e);
    }
    case MPB_SHAPE_SPHERE:
        return std::max(0.0, h[0] - x.norm());
    case MPB_SHAPE_CYLINDER:
        return std::max(0.0, std::min(h[0] - std::hypot(x[0], x[1]),
                                      h[1] / 2 - std::fabs(x[2])));
    case MPB_SHAPE_CAPSULE: {
        double z = std::clamp(x[2], -h[1] / 2, h[1] / 2);
        return std::max(0.0, h[0] - std::sqrt(x[0] * x[0] + x[1] * x[1] +
                                              (x[2] - z) * (x[2] - z)));
    }
    case MPB_SHAPE_CONE: {
        /* the (rho, z) triangle: base at -h/2, apex at (0, h/2); inside,
           the distance to the slanted side's line is at most the depth */
        double rho = std::hypot(x[0], x[1]), base = x[2] + h[1] / 2;
        double side = (h[0] * (h[1] / 2 - x[2]) - h[1] * rho) /
                      std::hypot(h[0], h[1]);
        if (base < 0 || x[2] > h[1] / 2 || side < 0)
            return 0.0;
        return std::min(base, side);
    }
    case MPB_SHAPE_MESH:
        return mesh_point_depth(s, x, floor);
    case MPB_SHAPE_PLANE:
        break;
    }
    return 0.0;
}

bool in_box(const Box3 &b, const V3 &p)
{
    for (int k = 0; k < 3; k++)
        if (p[k] < b.lo[k] || p[k] > b.hi[k])
            return false;
    return true;
}

/* Points of primitive a (its own frame) spread over its solid: a grid
 * of 9 levels along its axis (a box: 9 x 9 x 9, corners and faces
 * included), each with its centre and 8 points on each of 2 rings. */
void solid_points(const Shape &a, std::vector<V3> &out)
{
    const double *h = a.dims;
    const int L = 9;
    if (a.type == MPB_SHAPE_BOX) {
        for (int i = 0; i < L; i++)
            for (int j = 0; j < L; j++)
                for (int k = 0; k < L; k++)
                    out.emplace_back(h[0] * (i / (L - 1.0) - 0.5),
                                     h[1] * (j / (L - 1.0) - 0.5),
                                     h[2] * (k / (L - 1.0) - 0.5));
        return;
    }
    double r = h[0], len = a.type == MPB_SHAPE_SPHERE ? 2 * r : h[1];
    if (a.type == MPB_SHAPE_CAPSULE)
        len += 2 * r;
    for (int i = 0; i < L; i++) {
        double z = len * (i / (L - 1.0) - 0.5), rho = r;
        if (a.type == MPB_SHAPE_SPHERE)
            rho = std::sqrt(std::max(0.0, r * r - z * z));
        else if (a.type == MPB_SHAPE_CAPSULE && std::fabs(z) > h[1] / 2) {
            double e = std::fabs(z) - h[1] / 2;
            rho = std::sqrt(std::max(0.0, r * r - e * e));
        } else if (a.type == MPB_SHAPE_CONE)
            rho = r * (0.5 - z / len);
        out.emplace_back(0, 0, z);
        for (double f : {0.5, 1.0})
            for (int k = 0; k < 8; k++)
                out.emplace_back(f * rho * std::cos(k * M_PI / 4),
                                 f * rho * std::sin(k * M_PI / 4), z);
    }
}

/* The deepest of a's points tried inside b (the header's list), or floor
 * when none is deeper. */
double deepest_point(const Shape &a, const Shape &b, const std::vector<V3> &dirs,
                     double floor)
{
    double best = floor;
    auto test = [&](const V3 &p) {
        if (in_box(b.box, p))
            best = std::max(best, point_depth(b, p, best));
    };
    if (a.type == MPB_SHAPE_MESH) {
        const auto *m = model(a);
        for (int i = 0; i < m->num_vertices; i++)
            test(to_world(a, m->vertices[i]));
        return best;
    }
    std::vector<V3> pts;
    solid_points(a, pts);
    for (const V3 &x : pts)
        test(to_world(a, x));
    for (const V3 &n : dirs)
        test(extreme(a, n));
    return best;
}

/* The unit directions the upper bound starts from: each shape's axes,
 * the line of their centres, and 13 fixed ones, each both ways. */
std::vector<V3> start_dirs(const Shape &a, const Shape &b)
{
    std::vector<V3> d;
    const Shape *both[2] = {&a, &b};
    for (const Shape *s : both)
        for (int k = 0; k < 3; k++)
            d.emplace_back(s->world.R[k], s->world.R[3 + k], s->world.R[6 + k]);
    V3 cc(b.wcenter[0] - a.wcenter[0], b.wcenter[1] - a.wcenter[1],
          b.wcenter[2] - a.wcenter[2]);
    if (cc.norm() > 1e-12)
        d.push_back(cc / cc.norm());
    for (int i = -1; i <= 1; i++)
        for (int j = -1; j <= 1; j++)
            for (int k = -1; k <= 1; k++) {
                V3 v(i, j, k);
                /* one of each opposite pair: the first nonzero positive */
                if (v.norm() == 0 || (i ? i : (j ? j : k)) < 0)
                    continue;
                d.push_back(v / v.norm());
            }
    size_t n = d.size();
    for (size_t i = 0; i < n; i++)
        d.push_back(-d[i]);
    return d;
}

/* The least part_along() found: the best start, refined by a pattern
 * search on the sphere (steps from 0.1 rad down to 1e-7). *at: where. */
double least_part(const Shape &a, const Shape &b, const std::vector<V3> &dirs, V3 *at)
{
    V3 n = dirs[0];
    double best = INFINITY;
    for (const V3 &d : dirs) {
        double f = part_along(a, b, d);
        if (f < best) {
            best = f;
            n = d;
        }
    }
    for (double step = 0.1; step > 1e-7; step /= 2) {
        for (int round = 0; round < 50; round++) {
            V3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
            bool moved = false;
            const V3 ts[4] = {t1, V3(-t1), t2, V3(-t2)};
            for (const V3 &t : ts) {
                V3 m = (n + step * t).normalized();
                double f = part_along(a, b, m);
                if (f < best) {
                    best = f;
                    n = m;
                    moved = true;
                    break;
                }
            }
            if (!moved)
                break;
        }
    }
    *at = n;
    return best;
}

/* A pair found overlapping: its upper bound, and what its lower bound
 * needs (the directions tried, the best of them among them). */
struct Overlap {
    const Shape *a, *b;
    double upper;
    std::vector<V3> dirs;
};

/* The upper bound of overlapping shapes a and b (the header's). */
Overlap pair_upper(const Shape &a, const Shape &b)
{
    Overlap o{&a, &b, 0.0, start_dirs(a, b)};
    V3 n;
    o.upper = std::max(0.0, least_part(a, b, o.dirs, &n));
    o.dirs.push_back(n);
    o.dirs.push_back(-n);
    return o;
}

/* The lower bound of an overlap (the header's), or at most floor when it
 * is not above floor: the points that cannot beat floor are spared. */
double pair_lower(const Overlap &o, double floor)
{
    double lower = std::max(deepest_point(*o.a, *o.b, o.dirs, floor),
                            deepest_point(*o.b, *o.a, o.dirs, floor));
    /* both exact up to rounding, and lower <= true <= upper: a lower
       above the upper can only be a mesh that is not closed */
    return std::min(lower, o.upper);
}

} // namespace
} // namespace coll
} // namespace mpb

using namespace mpb::coll;

int mpb__collision_depth(mpb_collision *c, double floor,
                         mpb__collision_depth_result *out)
{
    if (!c || !out)
        return MPB_EINVAL;
    *out = mpb__collision_depth_result{0.0, 0.0, -1, -1, 0};
    /* Nothing below floor is sought: lower is max(floor, the true one). */
    double least = floor > 0 ? floor : 0.0;
    auto keep_upper = [&](double up, int m, int other, int self) {
        if (up > out->upper || out->movable < 0) {
            out->upper = std::max(out->upper, up);
            out->movable = m;
            out->other = other;
            out->self = self;
        }
    };
    /* Every overlap's upper bound first, in the order that names the
     * pair of the largest; then the lower bounds, deepest upper first: a
     * pair whose upper bound is no more than the lower bound found so far
     * cannot raise it (its lower is at most its upper), and is spared the
     * points' depths, by far the dearest part. */
    std::vector<Overlap> overlaps;
    return guarded(c, [&]() -> int {
        int rc = ensure_tree(c);
        if (rc != MPB_OK)
            return rc;
        for (const Movable &m : c->movables) {
            if (!m.enabled || m.self_only)
                continue;
            for (int si : m.shapes) {
                const Shape &ms = c->mshapes[(size_t)si];
                gather(c, ms.box);
                std::vector<int> cand = c->cand;
                for (int i : cand) {
                    const Leaf &l = c->leaves[(size_t)i];
                    const Shape &ss = c->sshapes[(size_t)l.shape];
                    if (allowed_static(&m, l.body))
                        continue;
                    sync(ms);
                    sync(ss);
                    if (!narrow_phase(c, ms, ss))
                        continue;
                    overlaps.push_back(pair_upper(ms, ss));
                    keep_upper(overlaps.back().upper, m.id, l.body, 0);
                }
                for (const Plane &p : c->planes) {
                    if (allowed_static(&m, p.id) ||
                        plane_distance(ms, p, nullptr, nullptr) > 0)
                        continue;
                    double hi = p.n.dot(extreme(ms, p.n)) - p.d;
                    double lo = p.d - p.n.dot(extreme(ms, -p.n));
                    double e = std::max(0.0, std::min(hi, lo));
                    out->lower = std::max(out->lower, e);
                    keep_upper(e, m.id, p.id, 0);
                }
            }
        }
        ensure_self_pairs(c);
        for (const auto &pr : c->self_pairs) {
            const Movable &mi = c->movables[(size_t)pr.first];
            const Movable &mj = c->movables[(size_t)pr.second];
            if (!mi.enabled || !mj.enabled || !overlap(mi.box, mj.box))
                continue;
            for (int si : mi.shapes)
                for (int sj : mj.shapes) {
                    const Shape &a = c->mshapes[(size_t)si];
                    const Shape &b = c->mshapes[(size_t)sj];
                    if (!overlap(a.box, b.box))
                        continue;
                    sync(a);
                    sync(b);
                    if (!narrow_phase(c, a, b))
                        continue;
                    int lo = std::min(mi.id, mj.id), hi = std::max(mi.id, mj.id);
                    overlaps.push_back(pair_upper(a, b));
                    keep_upper(overlaps.back().upper, lo, hi, 1);
                }
        }
        std::stable_sort(overlaps.begin(), overlaps.end(),
                         [](const Overlap &x, const Overlap &y) {
                             return x.upper > y.upper;
                         });
        double lower = std::max(least, out->lower);
        for (const Overlap &o : overlaps) {
            if (o.upper <= lower)
                break;
            lower = std::max(lower, pair_lower(o, lower));
        }
        out->lower = lower;
        return MPB_OK;
    });
}
