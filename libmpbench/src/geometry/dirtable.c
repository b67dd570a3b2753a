/*
 * dirtable.c - the candidates for the farthest point, by direction cell
 * (dirtable.h).
 *
 * Why a cell's list is enough: let d0 be a unit direction and rho a bound
 * on |d - d0| over the cell's unit directions d, w the farthest point
 * along d0 and M0 = d0 . w. A point v within s of the farthest along d has
 * d . v >= d . w - s, so d0 . v = d . v - (d - d0) . v
 * >= d0 . w - (d - d0) . (v - w) - s >= M0 - rho |v - w| - s. The list
 * holds every v that passes this. rho is padded for the rounding of the
 * cell lookup, which may put a direction on a cell's border in the
 * neighbouring cell.
 */
#include "geometry/dirtable.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/grow.h"
#include "mpbench/mpbench.h"

#define RHO_PAD 1e-6

static void unit(double p[3])
{
    double n = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    p[0] /= n, p[1] /= n, p[2] /= n;
}

/* The direction of face point (k, sign, u, v) of the cube [-1, 1]^3. */
static void face_dir(int k, int neg, double u, double v, double p[3])
{
    p[k] = neg ? -1.0 : 1.0;
    p[(k + 1) % 3] = u;
    p[(k + 2) % 3] = v;
    unit(p);
}

int mpb__dirtable_build(mpb__dirtable *t, const double *pts, int n, int g)
{
    if (!t)
        return MPB_EINVAL;
    memset(t, 0, sizeof *t);
    if (!pts || n < 1 || g < 1 || g > 64)
        return MPB_EINVAL;
    double scale = 0;
    for (long i = 0; i < 3L * n; i++) {
        if (!isfinite(pts[i]))
            return MPB_EINVAL;
        scale = fmax(scale, fabs(pts[i]));
    }
    const int cells = 6 * g * g;
    int cap = 0, len = 0;
    t->start = malloc((size_t)(cells + 1) * sizeof *t->start);
    if (!t->start)
        return MPB_ENOMEM;
    for (int c = 0; c < cells; c++) {
        int k = c / (2 * g * g), neg = c / (g * g) % 2;
        int iu = c / g % g, iv = c % g;
        double d0[3], corner[3], rho = 0;
        face_dir(k, neg, -1 + 2 * (iu + 0.5) / g, -1 + 2 * (iv + 0.5) / g, d0);
        for (int q = 0; q < 4; q++) {
            face_dir(k, neg, -1 + 2.0 * (iu + q % 2) / g,
                     -1 + 2.0 * (iv + q / 2) / g, corner);
            double s2 = 0;
            for (int j = 0; j < 3; j++)
                s2 += (corner[j] - d0[j]) * (corner[j] - d0[j]);
            rho = fmax(rho, sqrt(s2));
        }
        rho += RHO_PAD;
        int w = 0;
        double m0 = -INFINITY;
        for (int i = 0; i < n; i++) {
            const double *v = &pts[3 * i];
            double x = d0[0] * v[0] + d0[1] * v[1] + d0[2] * v[2];
            if (x > m0)
                m0 = x, w = i;
        }
        t->start[c] = len;
        for (int i = 0; i < n; i++) {
            const double *v = &pts[3 * i], *vw = &pts[3 * w];
            double x = d0[0] * v[0] + d0[1] * v[1] + d0[2] * v[2];
            double dist = sqrt((v[0] - vw[0]) * (v[0] - vw[0]) +
                               (v[1] - vw[1]) * (v[1] - vw[1]) +
                               (v[2] - vw[2]) * (v[2] - vw[2]));
            if (!(x >= m0 - rho * dist - MPB__DIRTABLE_SLACK * scale))
                continue;
            if (mpb__grow((void **)&t->idx, &cap, len + 1, sizeof *t->idx) != MPB_OK) {
                mpb__dirtable_free(t);
                return MPB_ENOMEM;
            }
            t->idx[len++] = i;
        }
    }
    t->start[cells] = len;
    t->g = g;
    return MPB_OK;
}

void mpb__dirtable_free(mpb__dirtable *t)
{
    if (!t)
        return;
    free(t->start);
    free(t->idx);
    memset(t, 0, sizeof *t);
}
