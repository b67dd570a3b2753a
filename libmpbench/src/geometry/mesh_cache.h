/*
 * mesh_cache.h - private to libmpbench and its tests: meshes and FCL BVH
 * models shared by every world of the process.
 *
 * A robot's link meshes are the same in every scene of an experiment (700
 * for MotionBenchMaker's Panda), yet each world read them with assimp and
 * built their BVH models anew. Here a mesh file is read once while any
 * world holds it: the key is the resolved path, the file's device, inode,
 * size, modification and change times (ns), and the scale, so two files of
 * the same name in different folders are two meshes, and a file changed
 * between two opens (an experiment resumed after an edit) is read again.
 * A mesh is freed with its last holder. The BVH models of collision_fcl.cpp
 * are shared the same way, by contents (collision_fcl.cpp's
 * shared_geometry()). Both are thread-safe.
 */
#ifndef MPB_MESH_CACHE_H
#define MPB_MESH_CACHE_H

#include <stddef.h>

#include "mpbench/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * mpb_mesh_load() through the cache: *out is a mesh to read only, shared
 * with whoever else loaded the same file at the same scale, until
 * mpb__mesh_release(). Errors as mpb_mesh_load()'s.
 */
int mpb__mesh_load_shared(const char *uri, const char *const *dirs,
                          int num_dirs, const double scale[3],
                          const mpb_mesh **out, char *err, size_t errlen);

/* Give back a mesh of mpb__mesh_load_shared(); NULL does nothing. */
void mpb__mesh_release(const mpb_mesh *m);

/* For tests and measurements: the mesh files read by assimp through
 * mpb__mesh_load_shared() since the process began, and the meshes held
 * now. */
long mpb__mesh_cache_reads(void);
long mpb__mesh_cache_live(void);

/* The same for collision_fcl.cpp: BVH models built since the process
 * began, and those alive now (held by some collision world). */
long mpb__bvh_builds(void);
long mpb__bvh_live(void);

#ifdef __cplusplus
}
#endif

#endif /* MPB_MESH_CACHE_H */
