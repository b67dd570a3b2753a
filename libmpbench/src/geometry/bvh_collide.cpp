/*
 * bvh_collide.cpp - two meshes' collision test over FCL's own OBBRSS trees
 * (bvh_collide.h), the verdict of fcl::collide for less: FCL's traversal
 * spends most of a Panda self check on its box tests (two 3x3 products
 * per node pair before the separating-axis test), virtual calls and
 * recursion. Here a box of the second tree is brought into the first
 * model's frame once and kept on an explicit stack while the first tree
 * is descended under it, and the separating-axis test computes the
 * relative rotation row by row, leaving at the first separating axis.
 *
 * Why the verdict is FCL's: a node pair is dropped only when its boxes
 * are apart by more than kMargin, far above rounding at any coordinate
 * collision.h allows; every triangle lies in the box of each node above
 * it, so no dropped triangle pair can touch. The triangle pairs reached
 * are tested with FCL's own triangle test, on the relative transform
 * FCL computes. So the meshes collide here if and only if some triangle
 * pair intersects by FCL's test: FCL's answer, which stops at the first
 * such pair (one contact wanted). tests/unit/geometry/test_bvh_collide.c checks it.
 */
#include "geometry/bvh_collide.h"

#include <fcl/math/geometry.h>
#include <fcl/narrowphase/detail/traversal/collision/intersect.h>

#include <cmath>

namespace mpb {

namespace {

constexpr double kMargin = 1e-4;  /* m; boxes closer than this are kept */
constexpr int kStack = 128;       /* node pairs; depth of both trees */

/* A box of the second model, in the first model's frame. */
struct Box2 {
    double a[3][3];  /* a[j]: axis j */
    double c[3];     /* centre */
};

inline double dot3(const double *u, const double *v)
{
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

/* Bring obb (second model's frame) into the first's: x -> R x + T. */
inline void place(Box2 &w, const fcl::OBBd &obb, const fcl::Matrix3d &R,
                  const fcl::Vector3d &T)
{
    for (int j = 0; j < 3; j++) {
        fcl::Vector3d v = R * obb.axis.col(j);
        w.a[j][0] = v[0];
        w.a[j][1] = v[1];
        w.a[j][2] = v[2];
    }
    fcl::Vector3d c = R * obb.To + T;
    w.c[0] = c[0];
    w.c[1] = c[1];
    w.c[2] = c[2];
}

/*
 * Are box o (first model) and box w (second, placed) apart by more than
 * kMargin along one of the 15 axes of the separating-axis test? In o's
 * frame; o's own axes first, the rows of the relative rotation R computed
 * only as they are needed. FCL's padding of |R| (against cross products
 * of near-parallel edges) is left out: a degenerate axis projects both
 * boxes and their distance to about 0, which the margin never drops.
 * Written out: as loops, with (i + 1) % 3, it costs half as much again.
 */
inline bool apart(const fcl::OBBd &o, const Box2 &w, const fcl::Vector3d &eb)
{
    const double *ax = o.axis.data();    /* column-major: axis i at 3i */
    const double *a = o.extent.data(), *b = eb.data();
    const double d[3] = {w.c[0] - o.To[0], w.c[1] - o.To[1], w.c[2] - o.To[2]};
    double R[3][3], Q[3][3], T[3];      /* Q = |R| */
    /* FCL fits axis 2 to the box's thinnest side: the likeliest to
     * separate, so tried first */
#define MPB__FACE_A(i)                                                        \
    T[i] = dot3(ax + 3 * i, d);                                               \
    R[i][0] = dot3(ax + 3 * i, w.a[0]);                                       \
    R[i][1] = dot3(ax + 3 * i, w.a[1]);                                       \
    R[i][2] = dot3(ax + 3 * i, w.a[2]);                                       \
    Q[i][0] = std::fabs(R[i][0]);                                             \
    Q[i][1] = std::fabs(R[i][1]);                                             \
    Q[i][2] = std::fabs(R[i][2]);                                             \
    if (std::fabs(T[i]) >                                                     \
        a[i] + Q[i][0] * b[0] + Q[i][1] * b[1] + Q[i][2] * b[2] + kMargin)    \
        return true;
    MPB__FACE_A(2)
    MPB__FACE_A(1)
    MPB__FACE_A(0)
#undef MPB__FACE_A
#define MPB__FACE_B(j)                                                        \
    if (std::fabs(R[0][j] * T[0] + R[1][j] * T[1] + R[2][j] * T[2]) >         \
        b[j] + Q[0][j] * a[0] + Q[1][j] * a[1] + Q[2][j] * a[2] + kMargin)    \
        return true;
    MPB__FACE_B(2)
    MPB__FACE_B(1)
    MPB__FACE_B(0)
#undef MPB__FACE_B
    /* axis i of o crossed with axis j of w */
#define MPB__CROSS(i, i1, i2, j, j1, j2)                                      \
    if (std::fabs(T[i2] * R[i1][j] - T[i1] * R[i2][j]) >                      \
        a[i1] * Q[i2][j] + a[i2] * Q[i1][j] + b[j1] * Q[i][j2] +              \
            b[j2] * Q[i][j1] + kMargin)                                       \
        return true;
    MPB__CROSS(0, 1, 2, 0, 1, 2)
    MPB__CROSS(0, 1, 2, 1, 2, 0)
    MPB__CROSS(0, 1, 2, 2, 0, 1)
    MPB__CROSS(1, 2, 0, 0, 1, 2)
    MPB__CROSS(1, 2, 0, 1, 2, 0)
    MPB__CROSS(1, 2, 0, 2, 0, 1)
    MPB__CROSS(2, 0, 1, 0, 1, 2)
    MPB__CROSS(2, 0, 1, 1, 2, 0)
    MPB__CROSS(2, 0, 1, 2, 0, 1)
#undef MPB__CROSS
    return false;
}

/* Do the triangles of leaves n1 and n2 intersect, by FCL's test? */
bool triangles_meet(const BvhObbRss &m1, const fcl::BVNode<fcl::OBBRSSd> &n1,
                    const BvhObbRss &m2, const fcl::BVNode<fcl::OBBRSSd> &n2,
                    const fcl::Matrix3d &R, const fcl::Vector3d &T)
{
    const fcl::Triangle &t1 = m1.tri_indices[-(n1.first_child + 1)];
    const fcl::Triangle &t2 = m2.tri_indices[-(n2.first_child + 1)];
    const fcl::Vector3d *v1 = m1.vertices, *v2 = m2.vertices;
    return fcl::detail::Intersect<double>::intersect_Triangle(
        v1[t1[0]], v1[t1[1]], v1[t1[2]], v2[t2[0]], v2[t2[1]], v2[t2[2]], R, T);
}

} // namespace

int bvh_collide(const BvhObbRss &m1, const fcl::Transform3d &tf1,
                const BvhObbRss &m2, const fcl::Transform3d &tf2)
{
    if (m1.getModelType() != fcl::BVH_MODEL_TRIANGLES ||
        m2.getModelType() != fcl::BVH_MODEL_TRIANGLES)
        return -1;
    if (!m1.isOccupied() || !m2.isOccupied())
        return 0;                   /* FCL tests no triangles then */
    fcl::Matrix3d R;
    fcl::Vector3d T;
    fcl::relativeTransform(tf1.linear(), tf1.translation(), tf2.linear(),
                           tf2.translation(), R, T);

    /* getBV() is out of line; the nodes lie in one array */
    using Node = fcl::BVNode<fcl::OBBRSSd>;
    const Node *nodes1 = &m1.getBV(0), *nodes2 = &m2.getBV(0);

    /* Pair k of the stack is (n1[k], n2[k]), n2[k]'s box placed in w[k]. */
    int n1[kStack], n2[kStack];
    Box2 w[kStack];
    int sp = 0;
    n1[0] = 0;
    n2[0] = 0;
    place(w[0], nodes2[0].bv.obb, R, T);
    sp = 1;
    while (sp > 0) {
        const int k = --sp;
        const Node &a = nodes1[n1[k]];
        const Node &b = nodes2[n2[k]];
        if (apart(a.bv.obb, w[k], b.bv.obb.extent))
            continue;
        const bool la = a.first_child < 0, lb = b.first_child < 0;
        if (la && lb) {
            if (triangles_meet(m1, a, m2, b, R, T))
                return 1;
            continue;
        }
        if (sp + 2 > kStack)
            return -1;
        /* Split the first node unless it is a leaf or the second is
         * longer (FCL compares the extents' squared norms: 2 % more
         * instructions); the left child is visited first. */
        if (lb || (!la && a.bv.obb.extent.maxCoeff() > b.bv.obb.extent.maxCoeff())) {
            const int b2 = n2[k];
            w[k + 1] = w[k];
            n1[k] = a.first_child + 1;
            n2[k] = b2;
            n1[k + 1] = a.first_child;
            n2[k + 1] = b2;
        } else {
            const int b1 = n1[k];
            n1[k] = b1;
            n2[k] = b.first_child + 1;
            place(w[k], nodes2[b.first_child + 1].bv.obb, R, T);
            n1[k + 1] = b1;
            n2[k + 1] = b.first_child;
            place(w[k + 1], nodes2[b.first_child].bv.obb, R, T);
        }
        sp = k + 2;
    }
    return 0;
}

} // namespace mpb
