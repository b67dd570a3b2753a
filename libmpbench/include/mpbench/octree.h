/*
 * octree.h - occupancy octrees as OctoMap keeps them: read from OctoMap's
 * .bt and .ot files and from the binary or full data of MoveIt's
 * octomap_msgs/Octomap, made from points (a point cloud, a depth camera's
 * rays), written back as OctoMap's binary stream or a .bt file.
 *
 * The tree is OctoMap's: 16 levels below a root cube of side
 * resolution x 2^16 centred on the origin of its frame; a leaf cell of
 * the finest level is a cube of side `resolution` whose lower corner is
 * a multiple of it. What mpbench keeps is the occupied cells, each a
 * cube (the leaf cells, and larger ones where all eight children of a
 * node are occupied, which OctoMap prunes into their parent): in a
 * collision world each is a box (scene.h). Free and unknown space are not
 * kept. In .ot data a leaf is occupied when its log-odds are at least 0
 * (OctoMap's default threshold, probability 0.5).
 *
 * Bad input gets MPB_EPARSE and one line in err naming the place: the
 * name given (a file), then the header line or the data byte
 * ("map.bt: data byte 1203: truncated: the tree needs more bytes").
 * Memory is bounded: at most MPB_OCTREE_MAX_CELLS occupied cells.
 */
#ifndef MPBENCH_OCTREE_H
#define MPBENCH_OCTREE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* OctoMap's tree depth: keys are 16 bits a coordinate. */
#define MPB_OCTREE_DEPTH 16
/* The resolutions accepted (m): finer cells than a tenth of a millimetre
 * or coarser than a metre are not a scene's. */
#define MPB_OCTREE_MIN_RESOLUTION 1e-4
#define MPB_OCTREE_MAX_RESOLUTION 1.0
/* The most occupied cells a tree may hold (after pruning). */
#define MPB_OCTREE_MAX_CELLS 500000

typedef struct mpb_octree mpb_octree;

/*
 * A new empty tree of cells of side `resolution` (m) in *out (MPB_OK),
 * freed with mpb_octree_destroy(). MPB_EINVAL for NULL out or a resolution
 * that is not finite or outside [MPB_OCTREE_MIN_RESOLUTION,
 * MPB_OCTREE_MAX_RESOLUTION]; MPB_ENOMEM.
 */
int mpb_octree_create(double resolution, mpb_octree **out);

void mpb_octree_destroy(mpb_octree *o);

double mpb_octree_resolution(const mpb_octree *o);

/*
 * Mark the leaf cell that holds point p (the tree's frame) occupied.
 * MPB_OK; MPB_EINVAL for a coordinate that is not finite or beyond the
 * root cube (|x| >= resolution x 2^15); MPB_ENOMEM; MPB_EPARSE when the
 * tree would hold more than MPB_OCTREE_MAX_CELLS cells. Cheap: points
 * are gathered and merged into the cells in batches.
 */
int mpb_octree_add_point(mpb_octree *o, const double p[3]);

/*
 * The number of occupied cells, pruned (any eight occupied siblings are
 * their parent), or a negative code (MPB_ENOMEM; MPB_EPARSE over
 * MPB_OCTREE_MAX_CELLS).
 */
int mpb_octree_num_cells(mpb_octree *o);

/*
 * Cell i (0-based, in OctoMap's depth-first order): its centre (the
 * tree's frame) and side length (m). MPB_OK; MPB_EINVAL out of range or
 * for NULL arguments; a code of mpb_octree_num_cells().
 */
int mpb_octree_cell(mpb_octree *o, int i, double center[3], double *side);

/*
 * The occupied cells as fewer axis-aligned boxes, their union exactly the
 * cells' (runs of cells merged along x, then y, then z where their other
 * sides match): *boxes (6 doubles a box, lower then upper corner, the
 * tree's frame; the caller frees it) and *n. MPB_OK; MPB_EINVAL; a code
 * of mpb_octree_num_cells(); MPB_ENOMEM. The same cells give the same
 * boxes.
 */
int mpb_octree_boxes(mpb_octree *o, double **boxes, int *n);

/*
 * Read OctoMap data of `len` bytes at resolution `resolution`: the
 * binary stream (binary 1: what OcTree::writeBinaryData() writes, the
 * body of a .bt file, MoveIt's data with binary: true) or the full one
 * (binary 0: AbstractOcTree::write()'s body for an "OcTree", a .ot file's
 * body, MoveIt's data with binary: false). Empty data is an empty tree.
 * `name` (may be NULL) goes in front of messages. MPB_OK with *out;
 * MPB_EINVAL for a bad resolution; MPB_EPARSE for truncated or corrupt
 * data, or bytes after the tree; MPB_ENOMEM.
 */
int mpb_octree_create_from_stream(const void *data, size_t len,
                                  double resolution, int binary,
                                  const char *name, mpb_octree **out,
                                  char *err, size_t errlen);

/*
 * Read a whole .bt or .ot file's bytes (told apart by their first line:
 * "# Octomap OcTree binary file" or "# Octomap OcTree file"): the header
 * ("id OcTree", "size N", "res R", comments, then "data") and the tree.
 * Other tree types (ColorOcTree, OcTreeStamped) are MPB_EUNSUPPORTED.
 * Otherwise as mpb_octree_create_from_stream().
 */
int mpb_octree_create_from_bytes(const void *bytes, size_t len,
                                 const char *name, mpb_octree **out,
                                 char *err, size_t errlen);

/* mpb_octree_create_from_bytes() of the file at path; MPB_EIO if it cannot be
 * read. */
int mpb_octree_create_from_file(const char *path, mpb_octree **out,
                                char *err, size_t errlen);

/*
 * The tree as OctoMap's binary stream (mpb_octree_create_from_stream(),
 * binary 1)
 * in *data (the caller frees it) of *len bytes; with header != 0, as a
 * whole .bt file. MPB_OK; MPB_EINVAL; MPB_ENOMEM. The same cells give
 * the same bytes.
 */
int mpb_octree_write(mpb_octree *o, int header, unsigned char **data, size_t *len);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_OCTREE_H */
