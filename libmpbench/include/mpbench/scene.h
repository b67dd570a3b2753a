/*
 * scene.h - scenes in MoveIt's plain-text .scene format (what MoveIt's
 * PlanningScene::saveGeometryToStream() writes and loadGeometryFromStream()
 * reads), so existing MoveIt scenes load unchanged; plus objects attached
 * to a robot link (carried objects). docs/scenes.md has the format.
 *
 * In short: the first line is the scene's name; then objects, each
 *     * <object id, the rest of the line>
 *     <x y z>  <qx qy qz qw>          object pose (newer variant only)
 *     <number of shapes>
 *     per shape: <type and dimensions> <x y z> <qx qy qz qw> <r g b a>
 *     <number of subframes>            (newer variant only)
 *     per subframe: <name> <x y z> <qx qy qz qw>
 * and a line "." to end. Shape types: box <x> <y> <z> (side lengths),
 * sphere <r>, cylinder <r> <length>, cone <r> <length>, plane <a> <b> <c>
 * <d>, mesh <V> <T> then V vertices (x y z) and T triangles (3 indices).
 * Shape poses are relative to the object pose. Numbers are separated by any
 * whitespace, line breaks included, as MoveIt reads them. The variant is
 * decided as MoveIt decides it: the line after the first object's '*' line
 * holds a pose (more than one number) in the newer variant, a shape count
 * in the older one. Quaternions are normalised; a zero one is an error.
 * Shapes and positions must also fit the collision world's bounds
 * (MPB_COLLISION_MIN_SIZE, MPB_COLLISION_MAX_COORD in collision.h), so
 * that a bad size is reported with its line.
 *
 * mpbench's extension, after the '.' line (MoveIt stops reading at '.', so
 * such a file still loads in MoveIt): blank lines, '#' comments, and
 *     attach <object id> <link> [<touch link> ...]
 * which makes the object a carried one: its pose is read in the frame of
 * <link> instead of the world's, and the touch links (besides <link>) may
 * touch it. An object id with spaces cannot be named here (use
 * mpb_scene_attach()). The scene does not know the robot: a "urdf" world
 * (world.h) refuses a <link> or touch link the robot lacks, naming the
 * attach line.
 *
 * Octrees and point clouds (mpbench's extension too, docs/scenes.md), as
 * lines after the '.', each an object of its own after the objects above:
 *     octree <id> <binary|full> <resolution> <bytes> <x y z> <qx qy qz qw>
 *     <the OctoMap data (octree.h), base64, over any number of lines>
 *     spheres <id> <radius> <count> <x y z> <qx qy qz qw>
 *     <count points x y z>
 * The octree's object has box shapes whose union is its occupied cells
 * (mpb_octree_boxes(): cells side by side merged; kind MPB_SCENE_OCTREE); the spheres' a sphere per point (MPB_SCENE_SPHERES).
 * A scene file may instead name files, which mpb_scene_resolve() (and so
 * mpb_scene_open()) turns into the lines above:
 *     octree <id> file <path.bt|path.ot> [<x y z> <qx qy qz qw>]
 *     cloud <id> file <path.ply|path.pcd> voxel <side> [<pose>]
 *     cloud <id> file <path.ply|path.pcd> radius <r> [<pose>]
 * mpb_scene_open_text() refuses those: the text that travels (to planners,
 * into the store, under the content hash) holds the data itself.
 */
#ifndef MPBENCH_SCENE_H
#define MPBENCH_SCENE_H

#include <stddef.h>

#include "mpbench/collision.h"
#include "mpbench/octree.h"
#include "mpbench/pose.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mpb_scene mpb_scene;

typedef struct mpb_scene_shape {
    mpb_geometry geometry;  /* MPB_SHAPE_MESH: geometry.mesh is the scene's */
    mpb_pose     pose;      /* in the object's frame */
    float        color[4];  /* r g b a as written; 0 0 0 0 means none */
    int          line;      /* where its type word is, counting from 1 */
} mpb_scene_shape;

typedef struct mpb_scene_subframe {
    const char *name;
    mpb_pose    pose;       /* in the object's frame */
} mpb_scene_subframe;

typedef struct mpb_scene_object {
    const char             *id;
    mpb_pose                pose;   /* in the world frame, or in the frame of
                                       attached_link when that is not NULL;
                                       identity in the older variant */
    int                     num_shapes;
    const mpb_scene_shape  *shapes;
    int                     num_subframes;
    const mpb_scene_subframe *subframes;
    const char             *attached_link;   /* NULL: a world object */
    int                     num_touch_links; /* links besides attached_link
                                                that may touch it */
    const char *const      *touch_links;
    int                     line;   /* of its '*' line */
    int                     attach_line;  /* of its attach line; 0 if not
                                             attached or attached by
                                             mpb_scene_attach() */
    int                     kind;   /* mpb_scene_kind */
    double                  resolution;  /* MPB_SCENE_OCTREE: the finest
                                            cell's side; MPB_SCENE_SPHERES:
                                            the radius; 0 otherwise */
} mpb_scene_object;

/* What an object was written as. */
typedef enum mpb_scene_kind {
    MPB_SCENE_SHAPES = 0,   /* a '*' object: primitives and meshes */
    MPB_SCENE_OCTREE = 1,   /* an octree line: boxes, the occupied cells */
    MPB_SCENE_SPHERES = 2   /* a spheres line: a sphere per point */
} mpb_scene_kind;

/* The most spheres a spheres line may give (a larger cloud: a voxel). */
#define MPB_SCENE_MAX_SPHERES 200000

/* The two variants of the format. */
typedef enum mpb_scene_variant {
    MPB_SCENE_OLD = 1,   /* no object pose, no subframes */
    MPB_SCENE_NEW = 2    /* object pose after the id, subframes after the shapes */
} mpb_scene_variant;

/*
 * Parse the scene text (NUL-terminated; empty or all blank means an empty
 * scene). On success *out is a new scene, freed with mpb_scene_close(). On
 * failure *out is NULL, the return is MPB_EPARSE (MPB_EINVAL for NULL text
 * or out, MPB_ENOMEM) and err (if not NULL) holds one line, "scene line 7:
 * cylinder needs <radius> <length>, found 'x'".
 */
int mpb_scene_open_text(const char *text, mpb_scene **out, char *err,
                        size_t errlen);

/*
 * Read, resolve (mpb_scene_resolve(), against the file's folder) and
 * parse the file at path. As mpb_scene_open_text(), with the file's name in
 * front of the message ("kitchen.scene: scene line 7: ..."), and MPB_EIO
 * when the file (or one it names) cannot be read.
 */
int mpb_scene_open(const char *path, mpb_scene **out, char *err, size_t errlen);

void mpb_scene_close(mpb_scene *s);

/*
 * The scene text with its octree-file and cloud-file lines (above) made
 * into octree and spheres lines, reading the files (relative paths
 * against dir; NULL or "": the current directory), into *out (the caller
 * frees it; the text itself when it names no file). MPB_OK; MPB_EIO,
 * MPB_EPARSE, MPB_EUNSUPPORTED with one line in err naming the scene
 * line and the file's place ("scene line 9: map.bt: data byte 40:
 * truncated ..."); MPB_ENOMEM.
 */
int mpb_scene_resolve(const char *text, const char *dir, char **out,
                      char *err, size_t errlen);

/*
 * The octree line (above) of tree o as object `id` (one word) at pose
 * x y z qx qy qz qw (NULL: the identity), then its binary data in base64,
 * into *out (the caller frees it): text to put after a scene's '.'. The
 * same tree gives the same text. MPB_OK; MPB_EINVAL; MPB_ENOMEM.
 */
int mpb_scene_octree_text(mpb_octree *o, const char *id, const double pose[7],
                          char **out);

/* The name line (trimmed); owned by the scene. */
const char *mpb_scene_name(const mpb_scene *s);

/*
 * The content hash of the text as given (mpb_hash_hex(), 32 hex digits);
 * owned by the scene. It covers the text only: attachments made later with
 * mpb_scene_attach() are not part of it.
 */
const char *mpb_scene_hash(const mpb_scene *s);

/* Which variant the text used (MPB_SCENE_NEW for a scene without objects). */
mpb_scene_variant mpb_scene_variant_of(const mpb_scene *s);

int mpb_scene_num_objects(const mpb_scene *s);

/* Object i (0-based, in file order), owned by the scene; NULL if out of range. */
const mpb_scene_object *mpb_scene_object_at(const mpb_scene *s, int i);

/* The index of the object with this id, or MPB_ENOTFOUND. */
int mpb_scene_find(const mpb_scene *s, const char *id);

/*
 * Make object `id` a carried object of `link`, at pose link_T_object in the
 * link's frame (NULL: keep the object's pose, now read in the link's frame),
 * touchable by the num_touch links named in touch (may be NULL when 0);
 * replaces any earlier attachment. MPB_OK; MPB_ENOTFOUND for an unknown
 * object; MPB_EINVAL for an empty link name or a pose that is not rigid;
 * MPB_ENOMEM.
 */
int mpb_scene_attach(mpb_scene *s, const char *id, const char *link,
                     const mpb_pose *link_T_object,
                     const char *const *touch, int num_touch);

/*
 * Add every world object (attached_link NULL) to c as a static body whose
 * id is the object's index: each shape at object pose * shape pose. MPB_OK,
 * or the first error of mpb_collision_add_static() (detail in
 * mpb_collision_errmsg(c)). Attached objects are left to the caller, who
 * knows where the links are.
 */
int mpb_scene_add_statics(const mpb_scene *s, mpb_collision *c);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_SCENE_H */
