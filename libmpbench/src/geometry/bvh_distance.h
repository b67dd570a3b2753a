/*
 * bvh_distance.h - private to libmpbench: the distance between a mesh
 * (an FCL BVH model of OBBRSS nodes) and a primitive shape, FCL's
 * distance for less, by a traversal of FCL's own nodes with tighter
 * bounds against the shape's box (bvh_distance.cpp).
 */
#ifndef MPB_BVH_DISTANCE_H
#define MPB_BVH_DISTANCE_H

#include "geometry/bvh_collide.h"
#include "geometry/dirtable.h"

#include <fcl/geometry/collision_geometry.h>

#include <vector>

namespace mpb {

/* The vertices of a mesh that may be extreme along some direction (own
 * frame; every point of every triangle lies in their hull) and the table
 * of them by direction (dirtable.h): a gap along any line bounds the
 * mesh's distance to a shape from below. */
struct BvhHull {
    const fcl::Vector3d  *verts;
    int                   num;
    const mpb__dirtable  *dirs;
    /* optional: the triangles of each vertex (indices in the model's
       tri_indices), tris[tri_start[i] .. tri_start[i + 1]), and a vertex
       likely nearest the shape (-1: none), whose nearest triangle is
       measured first */
    const int            *tri_start, *tris;
    int                   hint;
};

/* A node of the traversal's queue: its tree index and lower bound. */
struct BvhQueued {
    double lower;
    int    node;
};

/*
 * The distance between mesh m (at tf1) and primitive shape g (at tf2; a
 * box, cylinder, cone or capsule, held in its own frame by the
 * box of centre box_c and half sides box_h), as fcl::distance measures it
 * with the libccd solver at tolerance tol (to within 1e-9 m of it), 0 if
 * they touch; or `below` if it is at least that. NaN if the pair is left
 * to fcl::distance (another shape, a model not made of triangles; a
 * sphere, which FCL measures against a triangle in closed form, not by
 * the GJK solver). heap:
 * the traversal's queue, kept by the caller so that it is allocated once.
 * hull (may be null): m's hull vertices, to stop as soon as the nearest
 * triangle found is proved the nearest (its nearest points' line has
 * every vertex on one side and the shape's box on the other).
 */
double bvh_shape_distance(const BvhObbRss &m, const fcl::Transform3d &tf1,
                          const fcl::CollisionGeometryd &g,
                          const fcl::Transform3d &tf2, const double box_c[3],
                          const double box_h[3], double tol, double below,
                          std::vector<BvhQueued> &heap,
                          const BvhHull *hull = nullptr);

} // namespace mpb

#endif /* MPB_BVH_DISTANCE_H */
