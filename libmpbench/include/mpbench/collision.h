/*
 * collision.h - shapes, and a collision world of FCL objects behind a C API:
 * static objects (the environment) and movable bodies (robot links, carried
 * objects), collision and minimum-distance queries between them. Knows
 * nothing of robots: the caller moves the bodies (forward kinematics) and
 * says which pairs may touch.
 *
 * Bodies and ids. Every shape belongs to a body named by the caller's id, an
 * int in [0, MPB_COLLISION_MAX_ID]. Movable bodies and static bodies have
 * separate id spaces (a movable 3 and a static 3 are different bodies).
 *   - A static body is any number of shapes, each placed once in the world.
 *   - A movable body is any number of shapes, each at a fixed offset in the
 *     body's frame; mpb_collision_set_pose() places the body, and with it
 *     all its shapes (a URDF link with several <collision> elements is one
 *     body; a carried object is either more shapes of its link's body or a
 *     body of its own).
 * Queries report body ids.
 *
 * Geometry conventions (those of URDF, MoveIt and FCL): every primitive is
 * centred on its frame's origin. A box is given by its full side lengths; a
 * cylinder, cone and capsule lie along z (length is the cylinder's and
 * cone's full height, the capsule's distance between its two sphere
 * centres); a cone's apex is at +length/2. A plane is the infinite surface
 * a x + b y + c z = d in its frame (the equation MoveIt's FCL checker uses
 * for the coefficients of a .scene "plane" line). A mesh is its triangles
 * only, a surface: an object wholly inside a closed mesh, touching none of
 * its triangles, does not collide with it, and its distance is to the
 * surface. This is FCL's (and MoveIt's) behaviour.
 *
 * Distances are FCL's (libccd solver): exact in closed form for sphere
 * against sphere, box, capsule, cylinder and triangle, and capsule against
 * capsule; otherwise GJK, run here to a tolerance of 1e-10 (FCL's default
 * 1e-6 leaves errors up to ~3 mm for cones and cylinders), which measures
 * below 5e-7 m against closed forms and finely tessellated shapes. Planes
 * are handled by mpbench itself, exactly (FCL 0.7's plane distances are
 * broken). Overlapping pairs are at distance 0 (how deep a robot goes:
 * mpb_world_depth(), world.h); touching within ~1e-9 m may be reported
 * either way by the two queries.
 *
 * Cost: queries allocate nothing in this API (the static objects sit in a
 * bounding-volume tree of exact AABBs, built once and reused; movable
 * shapes get exact AABBs, and their FCL transforms only when a narrow
 * phase needs them; requests and results are kept in the handle; the last
 * nearest pair seeds the next distance query). FCL itself allocates two small
 * objects for each narrow-phase GJK test of a pair that has no closed form
 * (e.g. a box against a cylinder). Measured (7 capsule/cylinder links among
 * 20 boxes, RelWithDebInfo, 2026-11-23): set_pose x7 + check 0.3-0.4 us
 * when free, ~1.4 us when colliding; set_pose x7 + distance 5-8 us along a
 * random walk, 14-22 us for unrelated configurations
 * (tests/unit/geometry/test_collision.c prints these). Mesh links cost more: the
 * Panda (SRDF, collision meshes) in a MotionBenchMaker scene, 10-13 us a
 * check, 0.2-0.25 ms a distance (bench/meshcheck.c, docs/performance.md).
 *
 * A world is not thread-safe; use one per thread.
 */
#ifndef MPBENCH_COLLISION_H
#define MPBENCH_COLLISION_H

#include <stddef.h>

#include "mpbench/mesh.h"
#include "mpbench/pose.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mpb_shape_type {
    MPB_SHAPE_BOX = 0,      /* dims: x y z side lengths (m) */
    MPB_SHAPE_SPHERE = 1,   /* dims: radius (m) */
    MPB_SHAPE_CYLINDER = 2, /* dims: radius, length (m); along z */
    MPB_SHAPE_CONE = 3,     /* dims: radius, length (m); apex at +z */
    MPB_SHAPE_CAPSULE = 4,  /* dims: radius, length (m, may be 0); along z */
    MPB_SHAPE_PLANE = 5,    /* dims: a b c d, a x + b y + c z = d, (a,b,c) != 0,
                               at most MPB_COLLISION_MAX_COORD from the
                               origin; static only */
    MPB_SHAPE_MESH = 6      /* mesh: the triangles */
} mpb_shape_type;

/* Lower-case name of a shape type ("box"), static; "unknown" if out of
 * range. */
const char *mpb_shape_type_name(int type);

typedef struct mpb_geometry {
    mpb_shape_type  type;
    double          dims[4];  /* as listed at mpb_shape_type; unused are 0 */
    const mpb_mesh *mesh;     /* MPB_SHAPE_MESH only; not owned */
} mpb_geometry;

/*
 * The sizes a world accepts (m). Every dimension of a primitive is at least
 * MPB_COLLISION_MIN_SIZE (a capsule's length may be anything from 0; a
 * plane's coefficients are free) and at most MPB_COLLISION_MAX_COORD, as is every
 * mesh vertex coordinate, every pose's translation and a plane's distance
 * from the origin. Degenerate shapes (a
 * sphere of radius 0, a flat box) and aspect ratios near 1e14 send libccd's
 * MPR into an endless loop, and coordinates near 1e306 crash FCL's tree;
 * these bounds, fuzzed with 10^6 random pairs, keep well clear of both.
 */
#define MPB_COLLISION_MIN_SIZE  1e-6
#define MPB_COLLISION_MAX_COORD 1e5

#define MPB_COLLISION_MAX_ID 1000000

typedef struct mpb_collision mpb_collision;

/*
 * A new empty world in *out (MPB_OK), freed with mpb_collision_destroy().
 * MPB_EINVAL for NULL out, MPB_ENOMEM (then *out is NULL).
 */
int mpb_collision_create(mpb_collision **out);

void mpb_collision_destroy(mpb_collision *c);

/*
 * The last error of c as one line ("" if none); owned by c, valid until the
 * next call on c. A NULL c gives a static message.
 */
const char *mpb_collision_errmsg(const mpb_collision *c);

/*
 * Add a shape of geometry g at world pose `pose` (NULL: identity) to the
 * static body `id` (created on first use). The geometry is copied (a mesh
 * too). MPB_OK; MPB_EINVAL for a bad id, geometry or pose (a pose must pass
 * mpb_pose_is_rigid(), its translation within MPB_COLLISION_MAX_COORD);
 * MPB_ENOMEM.
 * Statics may be added at any time; the next query rebuilds the tree once.
 */
int mpb_collision_add_static(mpb_collision *c, int id, const mpb_geometry *g,
                             const mpb_pose *pose);

/*
 * Add a shape of geometry g to the movable body `id` (created on first use,
 * enabled, at the identity pose), at `offset` in the body's frame (NULL:
 * identity). Copied like statics. Same return codes as
 * mpb_collision_add_static(); a plane gives MPB_EINVAL.
 */
int mpb_collision_add_movable(mpb_collision *c, int id, const mpb_geometry *g,
                              const mpb_pose *offset);

/*
 * Place the movable body `id` at `pose` in the world: each of its shapes is
 * then at pose * offset. Cheap (no allocation). MPB_OK; MPB_ENOTFOUND for
 * an unknown body; MPB_EINVAL for a NULL or non-finite pose or a translation
 * beyond MPB_COLLISION_MAX_COORD (R is not checked for orthonormality here:
 * pass rotations).
 */
int mpb_collision_set_pose(mpb_collision *c, int id, const mpb_pose *pose);

/*
 * Include (enabled = 1, the default) or leave out (0) the movable body `id`
 * in every query. MPB_OK or MPB_ENOTFOUND.
 */
int mpb_collision_set_enabled(mpb_collision *c, int id, int enabled);

/*
 * Does any enabled movable body touch any static body (allowed pairs
 * excepted)? 1 if so, with the first pair found in *movable and *static_id
 * (either may be NULL); 0 if none; a negative code on error (MPB_EINVAL for
 * NULL c, MPB_ENOMEM while rebuilding the tree, MPB_EERROR if FCL throws).
 * Stops at the first colliding pair.
 */
int mpb_collision_check(mpb_collision *c, int *movable, int *static_id);

typedef struct mpb_collision_distance_result {
    double distance;         /* m: >= 0; 0 when some pair overlaps;
                                +INFINITY when there is no pair to measure */
    int    movable;          /* the nearest pair's bodies; -1 if none */
    int    static_id;
    double point_movable[3]; /* world frame, on the two shapes; NaN unless
                                nearest points were asked for and the */
    double point_static[3];  /* distance is > 0 */
} mpb_collision_distance_result;

/*
 * The minimum distance between the enabled movable bodies and the static
 * bodies (allowed pairs excepted), with the nearest pair; with
 * nearest_points != 0 also the nearest points (one more FCL distance call,
 * on that pair). Stops early at the first overlapping pair (distance 0).
 * Fills *out (may be NULL) and returns MPB_OK, or a negative code as for
 * mpb_collision_check() (then out->distance is NaN).
 */
int mpb_collision_distance(mpb_collision *c, int nearest_points,
                           mpb_collision_distance_result *out);


#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_COLLISION_H */
