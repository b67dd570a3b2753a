/*
 * cloud.h - point clouds from PLY and PCD files (ASCII and binary), as
 * an occupancy octree of a voxel size (octree.h) or as points to be
 * spheres of a radius (scene.h).
 *
 * PLY: "format ascii 1.0", "binary_little_endian 1.0" or
 * "binary_big_endian 1.0"; the "vertex" element's x, y and z properties
 * (any of PLY's scalar types), its other properties skipped; elements
 * before "vertex" skipped if they have no list properties. PCD (v0.7 and
 * older): FIELDS with x y z, SIZE, TYPE, COUNT, WIDTH, HEIGHT, POINTS,
 * DATA ascii or binary (binary_compressed is MPB_EUNSUPPORTED).
 *
 * Bad input gets MPB_EPARSE and one line in err naming the file and the
 * place: a header line, a point with its line (ASCII) or byte (binary):
 * "scan.ply: vertex 17 (line 29): z is not finite". Refused: a point
 * that is not finite (PCL marks missing points NaN: remove them first), a
 * header whose point count the file cannot hold (checked before any
 * memory is taken), more than MPB_CLOUD_MAX_POINTS points, a file over
 * MPB_CLOUD_MAX_BYTES. Memory: the file, and the octree's cells (or the
 * points asked for).
 */
#ifndef MPBENCH_CLOUD_H
#define MPBENCH_CLOUD_H

#include <stddef.h>

#include "mpbench/octree.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MPB_CLOUD_MAX_POINTS 100000000L
#define MPB_CLOUD_MAX_BYTES  ((size_t)1 << 31)

/*
 * Called for every point of a cloud, in file order (index i from 0).
 * Returns MPB_OK to go on, or a negative code that stops the reading and
 * is returned (with msg, if the callback wrote one line there, after the
 * point's place).
 */
typedef int (*mpb_cloud_point_fn)(void *ctx, long i, const double p[3],
                                  char *msg, size_t msglen);

/*
 * Read the cloud in bytes[0 .. len) (a PLY or PCD file's bytes: told apart
 * by their first line, "ply" or not), calling fn for each point; *count
 * (may be NULL) gets the number of points. name goes in front of
 * messages. MPB_OK; MPB_EPARSE, MPB_EUNSUPPORTED with one line; fn's code.
 */
int mpb_cloud_read(const void *bytes, size_t len, const char *name,
                   mpb_cloud_point_fn fn, void *ctx, long *count,
                   char *err, size_t errlen);

/*
 * The cloud at path as an octree of cells of side `voxel` (m): each
 * point's cell is occupied. MPB_OK with *out (mpb_octree_destroy()); MPB_EIO;
 * MPB_EINVAL for a voxel outside the octree's resolutions (octree.h);
 * otherwise as mpb_cloud_read(), a point beyond the octree's reach
 * MPB_EPARSE.
 */
int mpb_cloud_load_octree(const char *path, double voxel, mpb_octree **out,
                          char *err, size_t errlen);

/*
 * The cloud at path as points: *xyz (3 doubles a point; the caller frees
 * it) and *n; more than max points is MPB_EPARSE. Otherwise as
 * mpb_cloud_load_octree().
 */
int mpb_cloud_load_points(const char *path, long max, double **xyz, long *n,
                          char *err, size_t errlen);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_CLOUD_H */
