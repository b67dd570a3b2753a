/*
 * simplex.h - the point of a simplex (1 to 4 points) nearest the origin,
 * the step of a GJK search for a plane between two convex sets
 * (collision_fcl.cpp's meshes_apart()). Private to libmpbench and its
 * tests.
 */
#ifndef MPB_SIMPLEX_H
#define MPB_SIMPLEX_H

#ifdef __cplusplus
extern "C" {
#endif

/*
 * v = the point of the hull of p[0 .. m) (1 <= m <= 4) nearest the origin;
 * p then starts with the fewest of the points whose hull holds it, in
 * their order, and that number is returned. 0: the origin is inside the
 * tetrahedron p[0 .. 4) (v is then 0). Degenerate subsets (flat, doubled)
 * are passed over: the point found is never nearer than the true nearest.
 */
int mpb__simplex_nearest(double p[][3], int m, double v[3]);

#ifdef __cplusplus
}
#endif

#endif /* MPB_SIMPLEX_H */
