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
 *
 * Behind the process's cache, the one on disk (mesh_disk.c): a mesh file
 * read by assimp is stored there, keyed by its bytes, its scale and the
 * reader, and a later process that loads the same bytes takes the mesh
 * from there without assimp. Nothing there fails a load: a miss, a
 * corrupt or foreign file, or a failed write means assimp reads the file.
 */
#ifndef MPB_MESH_CACHE_H
#define MPB_MESH_CACHE_H

#include <stddef.h>

#include "mpbench/mesh.h"
#include "geometry/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * mpb__mesh_create_from_uri() through the cache: *out is a mesh to read only, shared
 * with whoever else loaded the same file at the same scale, until
 * mpb__mesh_release(). Errors as mpb__mesh_create_from_uri()'s.
 */
int mpb__mesh_load_shared(const char *uri, const char *const *dirs,
                          int num_dirs, const double scale[3],
                          const mpb_mesh **out, char *err, size_t errlen);

/* Give back a mesh of mpb__mesh_load_shared(); NULL does nothing. */
void mpb__mesh_release(const mpb_mesh *m);

/* For tests and measurements: the mesh files read through
 * mpb__mesh_load_shared() since the process began (by assimp or from the
 * cache on disk), and the meshes held now. */
long mpb__mesh_cache_reads(void);
long mpb__mesh_cache_live(void);

/* ---- the cache on disk (mesh_disk.c) ----------------------------------- */

/* An entry's name: the hash of its key and the key's length. */
typedef struct mpb__mesh_disk_id {
    char   hash[33];
    size_t key_len;
} mpb__mesh_disk_id;

/*
 * The id of the mesh file at path read at scale by `reader` (a text that
 * names the reader and how it reads: assimp's version and steps) into
 * *id: reads the whole file. MPB_OK; MPB_ENOTFOUND if it cannot be read;
 * MPB_ENOMEM.
 */
int mpb__mesh_disk_key(const char *path, const double scale[3],
                       const char *reader, mpb__mesh_disk_id *id);

/* The mesh stored under id, a new one the caller frees with
 * mpb__mesh_destroy(); NULL when there is none or it fails a check. */
mpb_mesh *mpb__mesh_disk_get(const mpb__mesh_disk_id *id);

/* Store m under id; a failure is ignored (the next process reads the
 * file). */
void mpb__mesh_disk_put(const mpb__mesh_disk_id *id, const mpb_mesh *m);

/* For tests: the meshes taken from the disk since the process began. */
long mpb__mesh_disk_loads(void);

/* The same for collision_fcl.cpp: BVH models built since the process
 * began, and those alive now (held by some collision world). */
long mpb__bvh_builds(void);
long mpb__bvh_live(void);

#ifdef __cplusplus
}
#endif

#endif /* MPB_MESH_CACHE_H */
