/*
 * sense.h - what depth cameras would see of a scene: each camera casts a
 * ray through every pixel against the scene's world objects (boxes,
 * spheres, cylinders, cones, planes, meshes; carried objects are not
 * seen), adds Gaussian noise along the ray, and the hits within range are
 * fused into an occupancy octree (octree.h). `mpb sense` writes the
 * result as a scene of one octree object; the same text can be made in
 * memory (mpb_scene_sense_text()), so that a sensed twin of a scene needs
 * no generated file.
 *
 * A camera is a pinhole at `eye` looking at `at`, its image upright (up
 * is +z; +x for a camera looking straight up or down): width x height
 * pixels over a horizontal field of view of fov degrees, the vertical one
 * in proportion, one ray through the centre of each pixel. A ray's hit is
 * the nearest surface it meets. It is kept when it lies near .. far from
 * the eye; then it is moved along the ray by noise times a standard
 * Gaussian draw, and the octree cell that holds it is occupied. A point
 * beyond the octree's reach (|x| >= resolution x 2^15) is dropped. Free
 * space is not carved: a cell is occupied once any ray ends in it.
 *
 * The noise comes from a generator of the call's own (splitmix64 seeded
 * with `seed`, then Box-Muller), one draw a pixel whether its ray hits or
 * not, camera after camera, row after row from the top: the same scene
 * and options give the same cells and the same text. Nothing is global
 * and the scene is only read, so calls may run in several threads at
 * once.
 *
 * The cost is width x height rays a camera, each tested against every
 * shape of the scene (every triangle of a mesh); memory is the octree's,
 * at most MPB_OCTREE_MAX_CELLS cells.
 *
 * Errors: MPB_EINVAL for a NULL argument or an option out of its range
 * (mpb_sense_options_check()); MPB_EPARSE, octree.h's code for it, when
 * the hits occupy more than MPB_OCTREE_MAX_CELLS cells; MPB_ENOMEM. Each
 * comes with one line in why (if why is not NULL and len not 0).
 */
#ifndef MPBENCH_SENSE_H
#define MPBENCH_SENSE_H

#include <stddef.h>
#include <stdint.h>

#include "mpbench/octree.h"
#include "mpbench/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The most cameras one call takes. */
#define MPB_SENSE_MAX_CAMERAS 16
/* The most pixels of an image's side (width, height). */
#define MPB_SENSE_MAX_SIDE 4096
/* The horizontal field of view is below this many degrees (and above 0). */
#define MPB_SENSE_MAX_FOV 170.0

/* A camera at eye (m, the scene's frame) looking at at; eye != at. */
typedef struct mpb_camera {
    double eye[3], at[3];
} mpb_camera;

/* What the cameras are and how they see; mpb_sense_options_init() fills
 * the defaults, mpb_sense_options_check() says whether a set is good. */
typedef struct mpb_sense_options {
    mpb_camera cameras[MPB_SENSE_MAX_CAMERAS];
    int        num_cameras;   /* 0 .. MPB_SENSE_MAX_CAMERAS; 0: those of
                                 mpb_sense_default_cameras() */
    int        width, height; /* pixels, 1 .. MPB_SENSE_MAX_SIDE */
    double     fov;           /* horizontal, degrees, (0, MPB_SENSE_MAX_FOV) */
    double     near, far;     /* the range kept, m, 0 <= near < far */
    double     noise;         /* m, the Gaussian's standard deviation along
                                 the ray, >= 0 (0: none drawn) */
    double     resolution;    /* the octree's cells, m, within
                                 MPB_OCTREE_MIN_RESOLUTION ..
                                 MPB_OCTREE_MAX_RESOLUTION */
    uint64_t   seed;          /* the noise's; any value */
} mpb_sense_options;

/*
 * Fill o with the defaults, `mpb sense`'s: no cameras (so the default
 * ones), 160 x 120 pixels, fov 60 degrees, range 0.3 .. 4 m, noise
 * 0.002 m, resolution 0.01 m, seed 1. Nothing happens for NULL o.
 */
void mpb_sense_options_init(mpb_sense_options *o);

/*
 * MPB_OK when every option of o is within its range (above; every number
 * finite), else MPB_EINVAL with one line in why naming the first bad
 * option by its field, its value and the range:
 * "resolution 0 is outside 0.0001 .. 1 m", "camera 2: eye and at are the
 * same point". MPB_EINVAL for NULL o.
 */
int mpb_sense_options_check(const mpb_sense_options *o, char *why, size_t len);

/*
 * Two cameras over scene s, as a robot's head and a second view would
 * see it, into o->cameras[0..1], o->num_cameras = 2: each looking at c,
 * the mean of the positions of the world objects' shapes (planes left
 * out; the origin when there is none), camera 1 from c + (-1.5, 1, 1),
 * camera 2 from c + (-1.5, -1, 1) (m). The other options are left alone.
 * Nothing happens for NULL s or o.
 */
void mpb_sense_default_cameras(const mpb_scene *s, mpb_sense_options *o);

/*
 * Cast every camera's rays against s and fuse the hits into a new octree
 * of o->resolution: MPB_OK with *out (freed with mpb_octree_destroy()) and,
 * if hits is not NULL, *hits, the number of rays whose points went into
 * the tree. With o->num_cameras 0 the cameras are
 * mpb_sense_default_cameras()'; o itself is not changed. On failure *out
 * is NULL and why holds one line (above); an octree overflow names the
 * camera that reached it: "camera 2: more occupied cells than an octree
 * may hold".
 */
int mpb_scene_sense(const mpb_scene *s, const mpb_sense_options *o,
                    mpb_octree **out, long *hits, char *why, size_t len);

/*
 * The whole sensed scene as `mpb sense` writes it: the name line
 * "<s's name> (sensed)", the '.' line, a comment line
 * "# mpb sense: 2 camera(s) 160x120, fov 60, range 0.3 .. 4 m, noise
 * 0.002 m, seed 1, resolution 0.01 m: <hits> hits, <cells> cells", a
 * comment line a camera ("# camera 1 at EX EY EZ looking at AX AY AZ"),
 * then the octree's object "sensed" (mpb_scene_octree_text(), the
 * identity pose): a scene text mpb_scene_open_text() takes. MPB_OK with *text
 * (the caller frees it with free()) and, where not NULL, *hits (as
 * mpb_scene_sense()) and *cells (the tree's occupied cells, pruned). On
 * failure *text is NULL; otherwise as mpb_scene_sense().
 */
int mpb_scene_sense_text(const mpb_scene *s, const mpb_sense_options *o,
                         char **text, long *hits, int *cells, char *why,
                         size_t len);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_SENSE_H */
