/*
 * locate.c - where a path collides: the sampling rule of the collision
 * check, shared with verify.c, and mpb_find_collision(), which finds a
 * collision verdict's configuration again with the bodies touching there
 * (for `mpb view`, `mpb verify --compare`).
 */
#include "mpbench/mpbench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "model/world_provider.h"
#include "verify/certify.h"
#include "verify/locate.h"

double mpb__sample_count(double len, double resolution)
{
    double k = ceil(len / resolution);
    return k < 1 ? 1 : k;
}

int mpb__sample_segment(mpb_world *w, const double *a, const double *b,
                        const double *d, double k, double *q, double *at)
{
    for (double s = 1; s <= k; s++) {
        const double *p = b;
        if (s < k) {
            for (int j = 0; j < w->num_joints; j++)
                q[j] = a[j] + (s / k) * d[j];
            p = q;
        }
        if (mpb_world_in_collision(w, p)) {
            if (p == b)
                memcpy(q, b, (size_t)w->num_joints * sizeof *q);
            *at = s / k;
            return 1;
        }
    }
    return 0;
}

/* Segment i of the path, as check_collision() (verify.c) takes it: 1
 * found (q, out->s, out->certified), 0 free, MPB_EINVAL too fine. */
static int segment_collision(mpb_world *w, mpb__certify_chain *chain,
                             const double *a, const double *b,
                             double resolution, double *d, double *q,
                             mpb_collision_at *out)
{
    const int nj = w->num_joints;
    double sq = 0.0;
    for (int j = 0; j < nj; j++) {
        d[j] = mpb_joint_delta(a[j], b[j], w->wraps[j]);
        sq += d[j] * d[j];
    }
    double k = mpb__sample_count(sqrt(sq), resolution);
    if (k > MPB__MAX_SAMPLES)
        return MPB_EINVAL;
    int proved = 0;
    if (mpb__certify_can(w)) {
        double hit = -1.0;
        mpb__certify_segment(w, chain, a, d, sqrt(sq), q, &hit, &proved);
        if (hit >= 0) {
            out->s = hit;
            out->certified = 1;
            return 1;
        }
    }
    if (!proved && mpb__sample_segment(w, a, b, d, k, q, &out->s)) {
        out->certified = 0;
        return 1;
    }
    return 0;
}

int mpb_find_collision(mpb_world *w, const double *wp, int num_waypoints,
                       int num_joints, double resolution, int segment,
                       double *q, mpb_collision_at *out)
{
    if (!w || !q || !out || num_waypoints < 0 || (num_waypoints > 0 && !wp) ||
        num_joints != w->num_joints || !(resolution > 0) ||
        !isfinite(resolution))
        return MPB_EINVAL;
    const int nj = num_joints;
    for (size_t i = 0; i < (size_t)num_waypoints * (size_t)nj; i++)
        if (!isfinite(wp[i]))
            return MPB_EINVAL;
    memset(out, 0, sizeof *out);
    if (num_waypoints == 0 || segment >= num_waypoints ||
        (segment > 0 && segment + 1 >= num_waypoints))
        return 0;
    int found = 0;
    if (segment <= 0 && mpb_world_in_collision(w, wp)) {
        memcpy(q, wp, (size_t)nj * sizeof *q);
        out->certified = mpb__certify_can(w);
        found = 1;
    }
    double *d = found ? NULL : malloc((size_t)nj * sizeof *d);
    if (!found && !d)
        return MPB_ENOMEM;
    int first = segment < 0 ? 0 : segment;
    int last = segment < 0 ? num_waypoints - 2 : segment;
    /* The proof carries its bounds from segment to segment (certify.h), and
     * where it stops depends on them: walk the segments before the one
     * asked for as the verifier did, so that s is the verdict's own. */
    mpb__certify_chain chain;
    mpb__certify_begin(&chain);
    if (!found && mpb__certify_can(w))
        for (int i = 0; i < first; i++) {
            const double *a = wp + (size_t)i * (size_t)nj;
            double sq = 0.0, hit = -1.0;
            int proved = 0;
            for (int j = 0; j < nj; j++) {
                d[j] = mpb_joint_delta(a[j], a[nj + j], w->wraps[j]);
                sq += d[j] * d[j];
            }
            mpb__certify_segment(w, &chain, a, d, sqrt(sq), q, &hit, &proved);
        }
    for (int i = first; !found && i <= last && i + 1 < num_waypoints; i++) {
        const double *a = wp + (size_t)i * (size_t)nj;
        found = segment_collision(w, &chain, a, a + nj, resolution, d, q, out);
        if (found < 0) {
            free(d);
            return found;
        }
        out->segment = i;
    }
    free(d);
    if (found && mpb_world_contact(w, q, out->bodies, sizeof out->bodies) <= 0)
        out->bodies[0] = '\0';
    return found;
}
