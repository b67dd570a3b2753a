/*
 * hull.h - which points of a set can be extreme along some direction: the
 * rest lie inside the convex hull of these, so the extent of the set along
 * any direction (min and max of d . x) is attained among them. Private to
 * libmpbench and its tests (collision_fcl.cpp scans a mesh's vertices for
 * extents, hundreds of times a collision check).
 */
#ifndef MPB_HULL_H
#define MPB_HULL_H

#ifdef __cplusplus
extern "C" {
#endif

/*
 * keep[i] = 1 for each of the n points pts[3 i .. 3 i + 2] that may be
 * extreme, 0 for one proved inside the hull of the kept points: inside
 * every facet plane, by more than MPB__HULL_MARGIN times the largest
 * coordinate, of a closed oriented surface of triangles over kept points
 * (quickhull's). Everything is kept when that surface cannot be built or
 * checked (fewer than 4 points, flat or collinear sets, a facet too thin
 * to trust, a horizon that is not one loop, V - E + F != 2, no memory).
 * Returns the number kept.
 */
#define MPB__HULL_MARGIN 1e-9
int mpb__hull_keep(const double *pts, int n, unsigned char *keep);

#ifdef __cplusplus
}
#endif

#endif /* MPB_HULL_H */
