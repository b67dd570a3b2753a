/*
 * locate.h - private: the sampling rule of the collision check
 * (locate.c), shared by mpb_verify_path() (verify.c) and
 * mpb_find_collision(), so that both find the same configuration.
 */
#ifndef MPB_LOCATE_H
#define MPB_LOCATE_H

#include "mpbench/world.h"

/* A guard against never finishing, not a practical limit. */
#define MPB__MAX_SAMPLES 1e9

/* The samples of a segment of joint-space length len: k steps of len / k
 * <= resolution, k = max(1, ceil(len / resolution)). */
double mpb__sample_count(double len, double resolution);

/*
 * Sample the segment a + (s/k) d, s = 1..k, the last sample b itself: 1
 * with the first colliding sample's configuration in q (w's num_joints
 * values) and its s/k in *at, 0 if none collides.
 */
int mpb__sample_segment(mpb_world *w, const double *a, const double *b,
                        const double *d, double k, double *q, double *at);

#endif /* MPB_LOCATE_H */
