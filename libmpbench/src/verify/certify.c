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

int mpb__certify_segment(mpb_world *w, const double *a, const double *d,
                         double len, double *q, double *hit, int *proved)
{
    const int nj = w->num_joints;
    *hit = -1.0;
    *proved = 1;
    if (!(len > 0))
        return MPB_OK;          /* a == b: the caller checked it */
    const double floor_s = CERT_FLOOR / len;
    double s = 0.0;
    for (int steps = 0;; steps++) {
        if (steps >= CERT_MAX_STEPS) {
            *proved = 0;        /* too slow to prove: the caller samples */
            return MPB_OK;
        }
        for (int j = 0; j < nj; j++)
            q[j] = a[j] + s * d[j];
        double want = 1.0 - s, ds = 0.0;
        if (!(want > 0))
            return MPB_OK;      /* s reached 1 by proved steps */
        int rc = w->provider->safe_step(w->impl, q, d, CERT_MARGIN, want, &ds);
        if (rc != MPB_OK || !(ds >= 0)) {
            *proved = 0;
            return MPB_OK;
        }
        if (ds >= want)
            return MPB_OK;      /* [s, 1] proved: b included */
        if (ds < floor_s) {
            /* within the margin of contact: is q in collision? Else step
               over the floor, unproved, and look there. */
            if (s > 0 && mpb_world_in_collision(w, q)) {
                *hit = s;
                return MPB_OK;
            }
            *proved = 0;
            ds = floor_s;
            if (s + ds >= 1.0) {
                for (int j = 0; j < nj; j++)
                    q[j] = a[j] + d[j];
                if (mpb_world_in_collision(w, q))
                    *hit = 1.0;
                return MPB_OK;
            }
        }
        s += ds;
    }
}
