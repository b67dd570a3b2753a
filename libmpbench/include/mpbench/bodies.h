/*
 * bodies.h - what a world (world.h) is made of, for drawing it: its bodies
 * (robot links, obstacles, carried objects), each body's shapes exactly as
 * the collision checks hold them, where every body is at a configuration,
 * and which two bodies touch at a configuration in collision. `mpb view`
 * draws runs with it.
 *
 * A body is one rigid part: a URDF link with its <collision> shapes, a
 * scene object with its shapes, a planar arm's link or obstacle. Its shapes
 * sit at fixed offsets in the body's frame; mpb_bodies_poses() places the
 * bodies, so shape k of body i is at poses[i] * shapes[k].offset (pose.h).
 *
 * The planar world is flat: its links are capsules along the link in the
 * z = 0 plane, as checked; its circles and boxes, checked as 2-D shapes,
 * are given as cylinders and boxes of height 4 link radii (0.1 m when the
 * radius is 0) centred on z = 0, which the links meet exactly where the
 * 2-D shapes do.
 */
#ifndef MPBENCH_BODIES_H
#define MPBENCH_BODIES_H

#include <stddef.h>

#include "mpbench/collision.h"
#include "mpbench/pose.h"

#ifdef __cplusplus
extern "C" {
#endif

struct mpb_world;

typedef struct mpb_body_shape {
    mpb_geometry geometry;  /* a mesh's triangles are owned by the world */
    mpb_pose     offset;    /* in the body's frame */
    float        color[4];  /* r g b a from the scene; 0 0 0 0: none */
} mpb_body_shape;

typedef struct mpb_body {
    const char *name;       /* link name, scene object id, "circle 2" */
    int         robot;      /* 1: a robot link or an object it carries */
    int         moves;      /* 1: its pose depends on the configuration */
    int         num_shapes;
    const mpb_body_shape *shapes;
} mpb_body;

typedef struct mpb_bodies mpb_bodies;

/*
 * The bodies of world w, in *out (MPB_OK), freed with mpb_bodies_close();
 * w must outlive them. Bodies without shapes are left out. MPB_EINVAL for
 * NULL arguments, MPB_EUNSUPPORTED for a world of another format,
 * MPB_ENOMEM; then *out is NULL and err (if not NULL) says why in one line.
 */
int mpb_bodies_open(struct mpb_world *w, mpb_bodies **out, char *err,
                    size_t errlen);

void mpb_bodies_close(mpb_bodies *b);

/* How many bodies; body i (0 .. count-1), owned by b; NULL if out of range. */
int             mpb_bodies_count(const mpb_bodies *b);
const mpb_body *mpb_bodies_get(const mpb_bodies *b, int i);

/*
 * Every body's pose at configuration q (the world's num_joints values) in
 * the world frame, poses[i] for body i, mpb_bodies_count() entries,
 * caller-allocated. MPB_OK; MPB_EINVAL for NULL arguments or a non-finite
 * q (poses then untouched).
 */
int mpb_bodies_poses(mpb_bodies *b, const double *q, mpb_pose *poses);

/*
 * The two bodies that touch at q: 1 with their indices in *a and *c (a
 * robot body first; for self-collision both are the robot's), 0 if q is
 * free, MPB_EINVAL for NULL arguments or a non-finite q. When several
 * pairs touch, the first the world's own check finds (the pair it stops
 * at). Uses w: not thread-safe with other calls on it.
 */
int mpb_bodies_contact(mpb_bodies *b, const double *q, int *a, int *c);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_BODIES_H */
