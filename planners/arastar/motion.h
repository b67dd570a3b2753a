/*
 * motion.h - joint-space distances and collision checks of straight
 * segments, sampled exactly as the daemon's verifier samples them
 * (verify.h: k = max(1, ceil(L / resolution)) steps, the short way round
 * for continuous joints), so a segment this accepts the verifier accepts.
 */
#ifndef ARASTAR_MOTION_H
#define ARASTAR_MOTION_H

#include "mpbench/world.h"

typedef struct ara_motion {
    mpb_world           *world;
    const unsigned char *wraps;      /* per joint, nonzero if continuous */
    int                  num_joints;
    double               resolution; /* rad, the verifier's */
    double              *buf;        /* 2 x num_joints scratch */
    long                 checks;     /* configurations checked so far */
} ara_motion;

/* 0, or -1 out of memory. */
int  ara_motion_init(ara_motion *m, mpb_world *w, double resolution);
void ara_motion_free(ara_motion *m);

/* Joint-space length of a -> b (Euclidean, continuous joints wrapped). */
double ara_motion_distance(const ara_motion *m, const double *a,
                           const double *b);

/* 1 if the configuration q collides (or the check fails), else 0. */
int ara_motion_state_collides(ara_motion *m, const double *q);

/*
 * 1 if some sample of the segment a -> b after a collides (b included, a
 * not: the caller has checked it), else 0.
 */
int ara_motion_segment_collides(ara_motion *m, const double *a,
                                const double *b);

#endif
