/*
 * geometry/mesh.h - private to libmpbench and its tests: making, checking
 * and reading the plain triangle meshes of mpbench/mesh.h (mesh_assimp.cpp).
 *
 * What a loaded mesh holds: every triangle of every mesh of the file, with
 * the file's node transforms applied. The root node's rotation is dropped,
 * as ROS tools (RViz, MoveIt) do: assimp turns COLLADA files Y-up there,
 * and ROS meshes are Z-up; a COLLADA <unit meter="..."> is applied, as RViz
 * does. Vertices shared between triangles are merged (normals, colours and
 * texture coordinates are discarded first), so an STL box has 8 vertices
 * and 12 triangles. Points and lines are dropped.
 */
#ifndef MPB_GEOMETRY_MESH_H
#define MPB_GEOMETRY_MESH_H

#include <stddef.h>

#include "mpbench/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * A new mesh with room for the given counts (>= 0), contents unset (zeroed).
 * NULL when out of memory or a count is negative or too large. Free with
 * mpb__mesh_destroy().
 */
mpb_mesh *mpb__mesh_create(int num_vertices, int num_triangles);

/* Release a mesh and its arrays; NULL does nothing. */
void mpb__mesh_destroy(mpb_mesh *m);

/* A new deep copy of m (NULL when out of memory or m is NULL). */
mpb_mesh *mpb__mesh_copy(const mpb_mesh *m);

/*
 * MPB_OK when m is usable for collision: at least one triangle, every
 * vertex finite, every index in [0, num_vertices). Otherwise MPB_EINVAL and
 * (if err) one line saying what is wrong.
 */
int mpb__mesh_check(const mpb_mesh *m, char *err, size_t errlen);

/*
 * The axis-aligned bounds of the vertices: lo[i] <= every vertex[i] <=
 * hi[i]. MPB_OK, or MPB_EINVAL for a NULL argument or a mesh without
 * vertices.
 */
int mpb__mesh_bounds(const mpb_mesh *m, double lo[3], double hi[3]);

/*
 * Load the mesh at uri (resolved as above) and scale it per axis (scale
 * NULL means 1 1 1; the URDF <mesh scale="x y z">). On success *out is a
 * new mesh, freed with mpb__mesh_destroy(). On failure *out is NULL, and the
 * return is one of mpb_mesh_resolve()'s codes, MPB_EPARSE (assimp cannot
 * read the file, or it holds no triangles), MPB_EINVAL (a scale not finite
 * or zero) or MPB_ENOMEM; err holds one line naming the file ("mesh
 * '/x/m.stl': assimp: ...").
 */
int mpb__mesh_create_from_uri(const char *uri, const char *const *dirs,
                             int num_dirs, const double scale[3],
                             mpb_mesh **out, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif

#endif /* MPB_GEOMETRY_MESH_H */
