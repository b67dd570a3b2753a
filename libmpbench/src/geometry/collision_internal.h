/*
 * collision_internal.h - private to libmpbench and its tests: slow reference
 * answers of the collision world (collision_fcl.cpp), every pair through
 * FCL's narrow phase with no broad phase and no bounds, to check the fast
 * queries of collision.h against, and the mesh extents they rest on (these
 * four are test support: defined in tests/support/collision_reference.cpp,
 * linked only into the tests, never into libmpbench); and the pair
 * distance and hints that the wrist tables (wrist_table.h) are built from
 * and speak through (in the library).
 */
#ifndef MPB_COLLISION_INTERNAL_H
#define MPB_COLLISION_INTERNAL_H

#include "mpbench/collision.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * The rest of a collision world's API, for the library's robots and
 * verdicts (model/, verify/) and the tests: robots' self checks and the
 * pairs allowed to touch, how deep bodies overlap, shape counts. A planner
 * that checks a robot's self collisions uses mpb_world (world.h).
 */

/*
 * MPB_OK if g is well formed (dims finite and within the bounds above, a
 * mesh that passes mpb__mesh_check() with its vertices within bounds);
 * MPB_EINVAL and one line in err (if not NULL) if not.
 */
int mpb__geometry_check(const mpb_geometry *g, char *err, size_t errlen);

/*
 * Make the movable body `id` take part in self checks only (self_only = 1)
 * or in every query (0, the default): mpb_collision_check() and
 * mpb_collision_distance() skip a self-only body, mpb__collision_check_self()
 * and mpb__collision_check_pair() do not. For a robot's fixed links: the
 * moving links must not pass through them, but they stand where the robot
 * stands (on the floor, say) and are no part of the clearance to the
 * environment. MPB_OK or MPB_ENOTFOUND.
 */
int mpb__collision_set_self_only(mpb_collision *c, int id, int self_only);

/*
 * Let movable bodies a and b touch: mpb__collision_check_self() skips the
 * pair. MPB_OK; MPB_ENOTFOUND for an unknown body; MPB_EINVAL for a == b.
 */
int mpb__collision_allow_pair(mpb_collision *c, int movable_a, int movable_b);

/*
 * Let the movable body `movable` touch the static body `static_id` (e.g. a
 * robot's base link and the floor it stands on): both
 * mpb_collision_check() and mpb_collision_distance() skip the pair.
 * MPB_OK; MPB_ENOTFOUND for an unknown movable (the static need not exist
 * yet); MPB_EINVAL for a bad id; MPB_ENOMEM.
 */
int mpb__collision_allow_static(mpb_collision *c, int movable, int static_id);

/*
 * Do two enabled movable bodies touch, pairs allowed with
 * mpb__collision_allow_pair() excepted? 1 with the first pair found
 * (*a < *b), 0 if none, negative on error as above.
 */
int mpb__collision_check_self(mpb_collision *c, int *a, int *b);

/*
 * Do the movable bodies a and b touch where they are now, whatever
 * mpb__collision_allow_pair() and mpb_collision_set_enabled() say? 1 if
 * so, 0 if not; MPB_ENOTFOUND for an unknown body, MPB_EINVAL for a == b,
 * another negative code on error as above. For building an
 * allowed-collision matrix pair by pair.
 */
int mpb__collision_check_pair(mpb_collision *c, int a, int b);

/*
 * How deep the bodies overlap where they stand (collision_depth.cpp): over
 * every colliding pair that mpb_collision_check() and
 * mpb__collision_check_self() test (a movable shape against a static
 * shape or plane, a shape of one movable against one of another, pairs
 * allowed to touch excepted), bounds on the penetration depth of each
 * pair of shapes (the shortest translation that parts them), m:
 *   lower  the most, over the pairs, of the deepest point found of one
 *          shape inside the other (mesh vertices; a primitive's corners
 *          and extreme points), its distance to that shape's surface;
 *   upper  the most, over the pairs, of the least h_A(n) + h_B(-n) found
 *          over unit directions n (h: the support function), the depth
 *          of the shapes' convex hulls when the search finds its least.
 * lower <= the deepest pair's depth <= upper; a plane's pair is exact.
 * Both 0 when nothing overlaps. movable, other: the pair of the upper
 * bound (other a static id, or a movable id when self is 1); -1 if none.
 * With floor > 0, lower is max(floor, its value): what cannot beat floor
 * is not sought (for the worst of several configurations). MPB_OK, or a
 * negative code as for mpb_collision_check(). For refused paths only: a
 * few milliseconds a configuration on meshes.
 */
typedef struct mpb__collision_depth_result {
    double lower, upper;
    int    movable, other, self;
} mpb__collision_depth_result;

int mpb__collision_depth(mpb_collision *c, double floor,
                         mpb__collision_depth_result *out);

/* Counts, for tests and reports. */
int mpb__collision_num_static_shapes(const mpb_collision *c);
int mpb__collision_num_movable_shapes(const mpb_collision *c);

/* Reference answers and the wrist tables' queries. */

/*
 * 1 if any enabled movable body touches a static body or another enabled
 * movable body (allowed pairs excepted), as mpb_collision_check() ||
 * mpb__collision_check_self(); 0 if not; negative on error.
 */
int mpb__collision_check_brute(mpb_collision *c);

/* The minimum distance, as mpb_collision_distance()'s (NaN on error). */
double mpb__collision_distance_brute(mpb_collision *c);

/*
 * How far movable shape i (0 .. mpb__collision_num_movable_shapes() - 1, a
 * mesh) reaches along world direction d where it is now: max of d . x
 * over its vertices, as the queries find it (*fast: the hull's vertices
 * listed for d's cell) and over every vertex of its mesh (*all), with the
 * same arithmetic: the two must be equal to the bit. MPB_OK, or
 * MPB_EINVAL when shape i is not a movable mesh.
 */
int mpb__collision_mesh_reach(mpb_collision *c, int i, const double d[3],
                              double *fast, double *all);

/*
 * Do movable shapes a and b of c, both meshes, collide at poses pa and pb
 * (in place of their own)? Through the traversal of the collision world
 * (bvh_collide.h) if reference is 0, through fcl::collide if 1: 1 if they
 * do, 0 if not; MPB_EUNSUPPORTED if either is no mesh or the traversal
 * leaves the pair to FCL, another negative code on error.
 */
int mpb__mesh_pair_collide(mpb_collision *c, int a, const mpb_pose *pa, int b,
                           const mpb_pose *pb, int reference);

/*
 * FCL's distance between the movable bodies a and b where they stand, if
 * it is below `below`: the least over their pairs of shapes, 0 if any
 * touch (no broad phase, no bounds); else `below` (FCL then skips what
 * is further, which makes "are they at least this far apart?" cheap;
 * INFINITY for the distance itself). For tables built ahead of the
 * queries (wrist_table.h). NaN for an unknown body, a == b, or an error.
 */
double mpb__collision_pair_distance(mpb_collision *c, int a, int b, double below);

/*
 * Tell the next self checks that movables a and b are apart where they
 * stand now (the caller proved it, e.g. from a wrist table):
 * mpb__collision_check_self() skips the pair. The hint lapses as soon as
 * either body is placed again (mpb_collision_set_pose(), a shape added),
 * so it can never outlive the poses it was proved for. The references
 * above ignore hints. MPB_OK; MPB_ENOTFOUND; MPB_EINVAL for a == b;
 * MPB_ENOMEM.
 */
int mpb__collision_hint_apart(mpb_collision *c, int a, int b);

/*
 * For certified verification (collision_sweep.cpp): how far any point of
 * movable body id's shapes lies from the body's own frame origin (m), an
 * upper bound from each shape's bounding sphere; NaN for an unknown id.
 */
double mpb__collision_body_reach(mpb_collision *c, int id);

/*
 * What holds each shape of movable body id, in the body's own frame: a
 * sphere (centre, radius) and, for a mesh, a capsule (segment cap[0]
 * cap[1], cap_radius; cap_radius < 0 if the shape has none). Up to max
 * shapes are written to out; returns the body's number of shapes, or -1
 * for an unknown id. For certified verification's motion bounds
 * (world_sweep.c).
 */
typedef struct mpb__body_bound {
    double centre[3], radius;
    double cap[2][3], cap_radius;
} mpb__body_bound;
int mpb__collision_body_bounds(mpb_collision *c, int id, mpb__body_bound *out,
                               int max);

/*
 * Conservative advancement's step where the bodies stand now. rate[id]
 * (num_rates entries, by movable id; ids past the array count 0) bounds
 * how far any point of body id can move per unit of the caller's
 * parameter s. *step is the largest ds <= want such that no pair the
 * collision checks test (movable against static, allowed statics
 * excepted; movable pairs not allowed) can touch while s advances by ds:
 * min over those pairs of (distance - margin) / (rate of approach); 0 if
 * some pair is within margin; want if none limits it. Pairs that cannot
 * approach (rate 0) are left out: their distance does not change. MPB_OK;
 * MPB_EINVAL for bad arguments (a negative or non-finite rate).
 */
int mpb__collision_safe_step(mpb_collision *c, const double *rate, int num_rates,
                             double margin, double want, double *step);

/*
 * As mpb__collision_safe_step(), with the rate of approach of a pair of
 * movables (ids a, b) from pair_rate(ud, a, b) instead of rate[a] +
 * rate[b]: the caller may know a tighter bound (two links of one chain
 * move together with every joint above both). pair_rate NULL: the sum.
 */
int mpb__collision_safe_step_pairs(mpb_collision *c, const double *rate,
                                   int num_rates, double (*pair_rate)(void *ud,
                                   int a, int b), void *ud, double margin,
                                   double want, double *step);

/*
 * A chain of conservative-advancement steps that remembers, pair by pair,
 * a lower bound on the distance where the robot stands (collision_sweep
 * .cpp): each step lowers every bound by what the last step's motion may
 * have closed (its rate of approach times the s it moved) and measures
 * again only the pairs whose bound no longer covers the step, so a far
 * pair is measured once for many steps, across segments too. Owned by
 * the caller; one per collision world.
 */
typedef struct mpb__sweep mpb__sweep;
mpb__sweep *mpb__sweep_new(void);       /* NULL: out of memory */
void mpb__sweep_free(mpb__sweep *st);   /* NULL is fine */
/* Pairs measured and pairs skipped since st was made (for tests). */
void mpb__sweep_counts(const mpb__sweep *st, long *measured, long *skipped);
/* The caller's own data kept with st (what it computes once per world),
 * freed by user_free (if not NULL) when replaced or when st is freed. */
void *mpb__sweep_user(const mpb__sweep *st);
void mpb__sweep_set_user(mpb__sweep *st, void *user, void (*user_free)(void *));

/*
 * As mpb__collision_safe_step_pairs(), remembering bounds in st. moved:
 * how far (units of s) the robot went, along the last call's motion at
 * its rates, from where the last call on st stood to where it stands now;
 * negative to start afresh (a new path, or the world changed: the bounds
 * are forgotten then too if the world's bodies, statics or pairs
 * changed). The rates must hold over the whole of the last motion from
 * the last call's place: moved never exceeds the last call's want, and
 * the caller's rates hold for any s within want of where they were taken
 * (world_sweep.c's do, for a straight joint-space segment).
 * st NULL: mpb__collision_safe_step_pairs().
 */
int mpb__collision_sweep_step(mpb_collision *c, mpb__sweep *st, double moved,
                              const double *rate, int num_rates,
                              double (*pair_rate)(void *ud, int a, int b),
                              void *ud, double margin, double want,
                              double *step);

#ifdef __cplusplus
}
#endif

#endif /* MPB_COLLISION_INTERNAL_H */
