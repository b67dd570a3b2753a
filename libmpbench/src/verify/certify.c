/*
 * certify.c - certified segment verification: a straight joint-space
 * segment proved collision-free over its whole continuum, or a colliding
 * configuration found (docs/verification.md).
 *
 * Conservative advancement: from s = 0, the world's safe_step (distance
 * lower bounds over an upper bound on how fast any point of the robot
 * moves, world_provider.h) proves [s, s + ds] free; s advances by ds. Near
 * contact the proved steps shrink towards 0; below the floor (1e-6 rad of
 * joint-space travel) the segment is no longer proved: s steps by the
 * floor and the configuration there is checked, so a thin obstacle the
 * robot runs into is found just past the contact. A segment left unproved
 * is sampled by the caller as well, so nothing the sampled check finds is
 * missed.
 *
 * The steps of a path form one chain (*chain): each call of safe_step
 * says how far the robot went since the last one, along the last one's
 * segment, so that the world may keep its pairs' distance bounds from
 * step to step and from segment to segment (segment k's end is segment
 * k + 1's start) and measure only the pairs whose bound ran out.
 *
 * The world's motion bounds are tighter over a short horizon (a point's
 * distance to a joint's axis grows only so fast; world_sweep.c): each
 * step asks for at most twice the joint-space length of the last one
 * (want), and the world's bounds hold over want. So no motion the world
 * is told of (moved) is longer than the want of the step it follows: a
 * proved step is at most want, a floor step at most want too (want is
 * never below twice the floor unless the rest of the segment is), and
 * a segment left after too many steps forgets the chain.
 */
#include "mpbench/mpbench.h"

#include <math.h>

#include "model/world_provider.h"
#include "verify/certify.h"

/* FCL's distances are within 5e-7 m (collision_fcl.cpp): each distance is
 * taken less this before it proves anything. */
#define CERT_MARGIN 1e-6
/* The least joint-space step (rad) a proof may take. */
#define CERT_FLOOR 1e-6
/* Steps a segment may take before it is left to sampling. */
#define CERT_MAX_STEPS 20000

static const char *const mode_names[] = { "certified", "sampled" };

const char *mpb_verification_name(mpb_verification mode)
{
    if ((int)mode < 0 || (int)mode > 1)
        return "unknown";
    return mode_names[mode];
}

int mpb_world_set_verification(struct mpb_world *w, mpb_verification mode)
{
    if (!w || ((int)mode != MPB_VERIFY_CERTIFIED && (int)mode != MPB_VERIFY_SAMPLED))
        return MPB_EINVAL;
    w->verification = (int)mode;
    return MPB_OK;
}

int mpb__certify_can(const mpb_world *w)
{
    return w->verification == MPB_VERIFY_CERTIFIED && w->provider->safe_step;
}

void mpb__certify_begin(mpb__certify_chain *chain)
{
    chain->moved = -1.0;
    chain->horizon = 0.0;
}

/* The segment left at its end b, having called safe_step last at s = at
 * (negative: not at all on this segment, the chain unchanged). */
static void chain_to_end(mpb__certify_chain *chain, double at)
{
    if (at >= 0)
        chain->moved = 1.0 - at;
}

int mpb__certify_segment(mpb_world *w, mpb__certify_chain *chain,
                         const double *a, const double *d, double len,
                         double *q, double *hit, int *proved)
{
    const int nj = w->num_joints;
    *hit = -1.0;
    *proved = 1;
    if (!(len > 0))
        return MPB_OK;          /* a == b: the caller checked it; the
                                   chain stays where it is */
    const double floor_s = CERT_FLOOR / len;
    double s = 0.0, at = -1.0;  /* at: the s of the last safe_step */
    for (int steps = 0;; steps++) {
        if (steps >= CERT_MAX_STEPS) {
            *proved = 0;        /* too slow to prove: the caller samples */
            chain->moved = -1.0;    /* further than the last step asked */
            return MPB_OK;
        }
        for (int j = 0; j < nj; j++)
            q[j] = a[j] + s * d[j];
        double rest = 1.0 - s, ds = 0.0;
        if (!(rest > 0)) {
            chain_to_end(chain, at);
            return MPB_OK;      /* s reached 1 by proved steps */
        }
        /* The world's rates hold over what a step asks for (want): the
           less, the tighter. Ask for twice the last step, never less
           than the floor (a floor step moves that far). */
        double want = rest;
        if (chain->horizon > 0)
            want = fmin(rest, fmax(chain->horizon / len, 2 * floor_s));
        double moved = at >= 0 ? s - at : chain->moved;
        int rc = w->provider->safe_step(w->impl, q, d, CERT_MARGIN, want,
                                        moved, &ds);
        at = s;
        if (rc != MPB_OK || !(ds >= 0)) {
            *proved = 0;
            chain->moved = -1.0;    /* what the world knows is lost */
            return MPB_OK;
        }
        chain->horizon = fmax(2 * fmin(ds, want) * len, 2 * CERT_FLOOR);
        if (ds >= want && want >= rest) {
            chain_to_end(chain, at);
            return MPB_OK;      /* [s, 1] proved: b included */
        }
        if (ds >= want)
            ds = want;
        if (ds < floor_s) {
            /* within the margin of contact: is q in collision? Else step
               over the floor, unproved, and look there. */
            if (s > 0 && mpb_world_in_collision(w, q)) {
                *hit = s;
                chain->moved = -1.0;
                return MPB_OK;
            }
            *proved = 0;
            ds = floor_s;
            if (s + ds >= 1.0) {
                for (int j = 0; j < nj; j++)
                    q[j] = a[j] + d[j];
                if (mpb_world_in_collision(w, q))
                    *hit = 1.0;
                chain_to_end(chain, at);
                return MPB_OK;
            }
        }
        s += ds;
    }
}
