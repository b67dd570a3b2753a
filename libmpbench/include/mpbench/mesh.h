/*
 * mesh.h - plain triangle meshes, as collision.h's mpb_geometry holds them
 * (a caller's own arrays, or what the library read from STL, COLLADA and
 * OBJ files through assimp), and how a mesh URI is found on disk:
 * package:// and relative URIs resolved against a caller's search path.
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
 * Resolve uri (see the top of this file) into path (pathlen bytes, NUL
 * terminated). MPB_OK; MPB_ENOTFOUND when no candidate file exists,
 * MPB_EUNSUPPORTED for an unknown scheme, MPB_EINVAL for a malformed URI,
 * NULL arguments or a path longer than pathlen; err then holds one line
 * naming the URI ("mesh 'package://arm/m.stl': not found in 2 search
 * directories").
 */
int mpb_mesh_resolve(const char *uri, const char *const *dirs, int num_dirs,
                     char *path, size_t pathlen, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_MESH_H */
