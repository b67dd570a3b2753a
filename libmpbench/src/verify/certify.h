/*
 * certify.h - private: certified segment verification (certify.c), for
 * verify.c.
 */
#ifndef MPB_CERTIFY_H
#define MPB_CERTIFY_H

#include "mpbench/world.h"

/* 1 if w verifies segments by proof (CERTIFIED mode, a world that can). */
int mpb__certify_can(const mpb_world *w);

/*
 * Prove the segment a + s d, s in [0, 1], of joint-space length len free,
 * or find a colliding configuration in it (a itself is the caller's to
 * check). q is scratch of w->num_joints values; on a collision it holds
 * the configuration, *hit its s (else -1). *proved is 1 if every part of
 * the segment was proved free, 0 if some part was not (the caller then
 * samples it too). MPB_OK.
 */
int mpb__certify_segment(mpb_world *w, const double *a, const double *d,
                         double len, double *q, double *hit, int *proved);

#endif /* MPB_CERTIFY_H */
