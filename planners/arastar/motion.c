/* motion.c - segment collision checks at the verifier's resolution. */
#include <math.h>
#include <stdlib.h>

#include "mpbench/metrics.h"
#include "motion.h"

int ara_motion_init(ara_motion *m, mpb_world *w, double resolution)
{
    m->world = w;
    m->wraps = mpb_world_joint_wraps(w);
    m->num_joints = mpb_world_num_joints(w);
    m->resolution = resolution;
    m->checks = 0;
    m->buf = malloc(2 * (size_t)m->num_joints * sizeof *m->buf);
    return m->buf ? 0 : -1;
}

void ara_motion_free(ara_motion *m)
{
    free(m->buf);
    m->buf = NULL;
}

double ara_motion_distance(const ara_motion *m, const double *a,
                           const double *b)
{
    double sq = 0.0;
    for (int j = 0; j < m->num_joints; j++) {
        double d = mpb_joint_delta(a[j], b[j], m->wraps ? m->wraps[j] : 0);
        sq += d * d;
    }
    return sqrt(sq);
}

int ara_motion_state_collides(ara_motion *m, const double *q)
{
    m->checks++;
    return mpb_world_in_collision(m->world, q) != 0;
}

int ara_motion_segment_collides(ara_motion *m, const double *a,
                                const double *b)
{
    int n = m->num_joints;
    double *d = m->buf, *q = m->buf + n, sq = 0.0;
    for (int j = 0; j < n; j++) {
        d[j] = mpb_joint_delta(a[j], b[j], m->wraps ? m->wraps[j] : 0);
        sq += d[j] * d[j];
    }
    /* The same arithmetic as verify.c, sample for sample. */
    double k = ceil(sqrt(sq) / m->resolution);
    if (k < 1)
        k = 1;
    /* The end first: most colliding motions are caught by one check. */
    if (ara_motion_state_collides(m, b))
        return 1;
    for (double s = 1; s < k; s++) {
        for (int j = 0; j < n; j++)
            q[j] = a[j] + (s / k) * d[j];
        if (ara_motion_state_collides(m, q))
            return 1;
    }
    return 0;
}
