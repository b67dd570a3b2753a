/*
 * certify.h - private: certified segment verification (certify.c), for
 * verify.c.
 */
#ifndef MPB_CERTIFY_H
#define MPB_CERTIFY_H

#include "mpbench/world.h"

/* 1 if w verifies segments by proof (CERTIFIED mode, a world that can). */
int mpb__certify_can(const mpb_world *w);

/* The segments of one path, proved one after the other: what the world
 * may carry from each to the next (certify.c). */
typedef struct mpb__certify_chain {
    double moved;   /* s travelled along the last segment since its last
                       step was measured; negative: nothing carried */
    double horizon; /* joint-space length (rad) the next step may ask
                       for: twice the last step's; 0: no limit */
} mpb__certify_chain;

/* Start a chain: before the first segment of a path. */
void mpb__certify_begin(mpb__certify_chain *chain);

/*
 * Prove the segment a + s d, s in [0, 1], of joint-space length len free,
 * or find a colliding configuration in it (a itself is the caller's to
 * check). q is scratch of w->num_joints values; on a collision it holds
 * the configuration, *hit its s (else -1). *proved is 1 if every part of
 * the segment was proved free, 0 if some part was not (the caller then
 * samples it too). chain: begun before the path's first segment, and
 * each segment's a the last one's end (nothing else done to the world
 * but checks between them). MPB_OK.
 */
int mpb__certify_segment(mpb_world *w, mpb__certify_chain *chain,
                         const double *a, const double *d, double len,
                         double *q, double *hit, int *proved);

#endif /* MPB_CERTIFY_H */
