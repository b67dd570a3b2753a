/*
 * mesh.h - plain triangle meshes, loaded from STL, COLLADA (.dae) and OBJ
 * files through assimp, with package:// and relative URIs resolved against
 * a caller's search path.
 *
 * Resolving a URI against the directories dirs[0 .. num_dirs-1], the first
 * file that exists wins:
 *   package://<pkg>/<path>   <dir>/<pkg>/<path> for each dir, and <dir>/<path>
 *                            when the dir itself is named <pkg> (a ROS package
 *                            path may list packages or their parents);
 *   file:///<abs path>       the absolute path;
 *   /<abs path>              itself;
 *   <relative path>          <dir>/<relative path> for each dir (never the
 *                            current directory unless "." is listed).
 * Other schemes (http://, model://, ...) give MPB_EUNSUPPORTED.
 *
 * What a loaded mesh holds: every triangle of every mesh of the file, with
 * the file's node transforms applied. The root node's rotation is dropped,
 * as ROS tools (RViz, MoveIt) do: assimp turns COLLADA files Y-up there,
 * and ROS meshes are Z-up; a COLLADA <unit meter="..."> is applied, as RViz
 * does. Vertices shared between triangles are merged (normals, colours and
 * texture coordinates are discarded first), so an STL box has 8 vertices
 * and 12 triangles. Points and lines are dropped.
 */
#ifndef MPBENCH_MESH_H
#define MPBENCH_MESH_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mpb_mesh {
    int      num_vertices;
    int      num_triangles;
    double  *vertices;    /* 3 * num_vertices: x y z (m) */
    int32_t *triangles;   /* 3 * num_triangles: 0-based vertex indices */
} mpb_mesh;

/*
 * A new mesh with room for the given counts (>= 0), contents unset (zeroed).
 * NULL when out of memory or a count is negative or too large. Free with
 * mpb_mesh_destroy().
 */
mpb_mesh *mpb_mesh_create(int num_vertices, int num_triangles);

/* Release a mesh and its arrays; NULL does nothing. */
void mpb_mesh_destroy(mpb_mesh *m);

/* A new deep copy of m (NULL when out of memory or m is NULL). */
mpb_mesh *mpb_mesh_copy(const mpb_mesh *m);

/*
 * MPB_OK when m is usable for collision: at least one triangle, every
 * vertex finite, every index in [0, num_vertices). Otherwise MPB_EINVAL and
 * (if err) one line saying what is wrong.
 */
int mpb_mesh_check(const mpb_mesh *m, char *err, size_t errlen);

/*
 * The axis-aligned bounds of the vertices: lo[i] <= every vertex[i] <=
 * hi[i]. MPB_OK, or MPB_EINVAL for a NULL argument or a mesh without
 * vertices.
 */
int mpb_mesh_bounds(const mpb_mesh *m, double lo[3], double hi[3]);

/*
 * Resolve uri (see the top of this file) into path (pathlen bytes, NUL
 * terminated). MPB_OK; MPB_ENOTFOUND when no candidate file exists,
 * MPB_EUNSUPPORTED for an unknown scheme, MPB_EINVAL for a malformed URI,
 * NULL arguments or a path longer than pathlen; err then holds one line
 * naming the URI ("mesh 'package://arm/m.stl': not found in 2 search
 * directories").
 */
int mpb_mesh_resolve(const char *uri, const char *const *dirs, int num_dirs,
                     char *path, size_t pathlen, char *err, size_t errlen);

/*
 * Load the mesh at uri (resolved as above) and scale it per axis (scale
 * NULL means 1 1 1; the URDF <mesh scale="x y z">). On success *out is a
 * new mesh, freed with mpb_mesh_destroy(). On failure *out is NULL, and the
 * return is one of mpb_mesh_resolve()'s codes, MPB_EPARSE (assimp cannot
 * read the file, or it holds no triangles), MPB_EINVAL (a scale not finite
 * or zero) or MPB_ENOMEM; err holds one line naming the file ("mesh
 * '/x/m.stl': assimp: ...").
 */
int mpb_mesh_create_from_uri(const char *uri, const char *const *dirs,
                             int num_dirs, const double scale[3],
                             mpb_mesh **out, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_MESH_H */
