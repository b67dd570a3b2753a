/*
 * collision_input.cpp - the collision world's checks of what callers pass in:
 * shapes and their sizes, poses, ids (collision.h, collision_world.h).
 */
#include "geometry/collision_world.h"
#include "geometry/mesh.h"
#include "geometry/collision_internal.h"

#include <cstdio>

namespace mpb {
namespace coll {

/* Finite, and the translation within MPB_COLLISION_MAX_COORD. */
bool finite_pose(const mpb_pose *p)
{
    for (int i = 0; i < 9; i++)
        if (!std::isfinite(p->R[i]))
            return false;
    for (int i = 0; i < 3; i++)
        if (!(std::fabs(p->t[i]) <= MPB_COLLISION_MAX_COORD))
            return false;
    return true;
}

/*
 * The plane a x + b y + c z = d as a unit normal and the signed distance
 * of the plane from the origin. Scaled by the largest of a, b, c first, so
 * that neither 1e-300 nor 1e300 over- or underflows in the squares. False
 * if the coefficients are not finite or the normal is zero.
 */
bool plane_unit(const double dims[4], fcl::Vector3d &n, double &dist)
{
    double scale = std::max({std::fabs(dims[0]), std::fabs(dims[1]),
                             std::fabs(dims[2])});
    if (!(scale > 0) || !std::isfinite(scale) || !std::isfinite(dims[3]))
        return false;
    n = fcl::Vector3d(dims[0] / scale, dims[1] / scale, dims[2] / scale);
    double len = n.norm();      /* in 1 .. sqrt(3) */
    n /= len;
    dist = dims[3] / scale / len;
    return true;
}

int check_args(mpb_collision *c, int id, const mpb_geometry *g, const mpb_pose *pose,
               bool movable)
{
    if (id < 0 || id > MPB_COLLISION_MAX_ID) {
        c->set_err("collision: id %d out of range 0..%d", id, MPB_COLLISION_MAX_ID);
        return MPB_EINVAL;
    }
    char why[200];
    if (mpb__geometry_check(g, why, sizeof why) != MPB_OK) {
        c->set_err("collision: %s %d: %s", movable ? "movable" : "static", id, why);
        return MPB_EINVAL;
    }
    if (movable && g->type == MPB_SHAPE_PLANE) {
        c->set_err("collision: movable %d: a plane can only be static", id);
        return MPB_EINVAL;
    }
    if (pose && (!mpb_pose_is_rigid(pose) || !finite_pose(pose))) {
        c->set_err("collision: %s %d: pose is not finite, too far (%g m at most) "
                   "or its R is not a rotation", movable ? "movable" : "static",
                   id, MPB_COLLISION_MAX_COORD);
        return MPB_EINVAL;
    }
    return MPB_OK;
}

} // namespace coll
} // namespace mpb

#define MPB__STR2(x) #x
#define MPB__STR(x) MPB__STR2(x)

using namespace mpb::coll;

extern "C" {

const char *mpb_shape_type_name(int type)
{
    switch (type) {
    case MPB_SHAPE_BOX:      return "box";
    case MPB_SHAPE_SPHERE:   return "sphere";
    case MPB_SHAPE_CYLINDER: return "cylinder";
    case MPB_SHAPE_CONE:     return "cone";
    case MPB_SHAPE_CAPSULE:  return "capsule";
    case MPB_SHAPE_PLANE:    return "plane";
    case MPB_SHAPE_MESH:     return "mesh";
    }
    return "unknown";
}

int mpb__geometry_check(const mpb_geometry *g, char *err, size_t errlen)
{
    if (!g) {
        mpb__set_err(err, errlen, "no geometry");
        return MPB_EINVAL;
    }
    /* The type's bits as an int: a C caller may pass any value, and in C++
       loading an enum out of its range is undefined. */
    int type;
    static_assert(sizeof type == sizeof g->type, "enum size");
    memcpy(&type, &g->type, sizeof type);
    int n = 0;
    switch (type) {
    case MPB_SHAPE_BOX:      n = 3; break;
    case MPB_SHAPE_SPHERE:   n = 1; break;
    case MPB_SHAPE_CYLINDER:
    case MPB_SHAPE_CONE:
    case MPB_SHAPE_CAPSULE:  n = 2; break;
    case MPB_SHAPE_PLANE: {
        /* Its coefficients are no lengths: only where it lies is bounded. */
        fcl::Vector3d unit;
        double dist;
        for (int i = 0; i < 4; i++)
            if (!std::isfinite(g->dims[i])) {
                mpb__set_err(err, errlen, "plane: coefficient %c is not finite",
                             "abcd"[i]);
                return MPB_EINVAL;
            }
        if (!plane_unit(g->dims, unit, dist)) {
            mpb__set_err(err, errlen, "plane: normal (a, b, c) is zero");
            return MPB_EINVAL;
        }
        if (!(std::fabs(dist) <= MPB_COLLISION_MAX_COORD)) {
            mpb__set_err(err, errlen, "plane: %g m from the origin, beyond %g m",
                         std::fabs(dist), MPB_COLLISION_MAX_COORD);
            return MPB_EINVAL;
        }
        return MPB_OK;
    }
    case MPB_SHAPE_MESH: {
        char why[160];
        if (mpb__mesh_check(g->mesh, why, sizeof why) != MPB_OK) {
            mpb__set_err(err, errlen, "mesh: %s", why);
            return MPB_EINVAL;
        }
        for (long i = 0; i < 3L * g->mesh->num_vertices; i++)
            if (std::fabs(g->mesh->vertices[i]) > MPB_COLLISION_MAX_COORD) {
                mpb__set_err(err, errlen, "mesh: vertex %ld is beyond %g m", i / 3,
                             MPB_COLLISION_MAX_COORD);
                return MPB_EINVAL;
            }
        return MPB_OK;
    }
    default:
        mpb__set_err(err, errlen, "unknown shape type %d", type);
        return MPB_EINVAL;
    }
    const char *name = mpb_shape_type_name(type);
    for (int i = 0; i < n; i++) {
        if (!std::isfinite(g->dims[i])) {
            mpb__set_err(err, errlen, "%s: dimension %d is not finite", name, i + 1);
            return MPB_EINVAL;
        }
        if (std::fabs(g->dims[i]) > MPB_COLLISION_MAX_COORD) {
            mpb__set_err(err, errlen, "%s: dimension %d (%g) is beyond %g m", name,
                         i + 1, g->dims[i], MPB_COLLISION_MAX_COORD);
            return MPB_EINVAL;
        }
        /* a capsule's radius gives it volume whatever its length */
        double least = type == MPB_SHAPE_CAPSULE && i == 1 ? 0.0 : MPB_COLLISION_MIN_SIZE;
        if (!(g->dims[i] >= least)) {
            mpb__set_err(err, errlen, "%s: dimension %d (%g) is %s", name, i + 1,
                         g->dims[i], g->dims[i] < 0 ? "negative" :
                         "below " MPB__STR(MPB_COLLISION_MIN_SIZE) " m");
            return MPB_EINVAL;
        }
    }
    return MPB_OK;
}

} // extern "C"
