/*
 * bvh_collide.h - private to libmpbench: the collision test of two meshes
 * (FCL BVH models of OBBRSS nodes), with fcl::collide's verdict, by a
 * traversal of FCL's own nodes that costs less (bvh_collide.cpp).
 */
#ifndef MPB_BVH_COLLIDE_H
#define MPB_BVH_COLLIDE_H

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>

namespace mpb {

using BvhObbRss = fcl::BVHModel<fcl::OBBRSSd>;

/*
 * 1 if meshes m1 (at tf1) and m2 (at tf2) collide, 0 if not: the verdict
 * of fcl::collide with no contacts wanted; -1 if the test is left to
 * fcl::collide (a model not made of triangles, or trees deeper than the
 * traversal's stack).
 */
int bvh_collide(const BvhObbRss &m1, const fcl::Transform3d &tf1,
                const BvhObbRss &m2, const fcl::Transform3d &tf2);

} // namespace mpb

#endif /* MPB_BVH_COLLIDE_H */
