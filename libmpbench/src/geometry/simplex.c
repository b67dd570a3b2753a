/*
 * simplex.c - the point of a simplex nearest the origin (simplex.h).
 *
 * The nearest point lies inside one face of the simplex (a vertex, an
 * edge, a triangle, the whole), where it is the origin's projection onto
 * that face's plane with positive weights. Every face is tried, and the
 * nearest of the projections that fall inside their face wins: each is a
 * point of the simplex, so none is nearer than the true nearest, and the
 * true nearest is among them. 15 faces at most, each a 2x2 or 3x3 system.
 */
#include "geometry/simplex.h"

#include <math.h>
#include <string.h>

static double dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The origin's projection onto face q[0 .. k) into out, if it falls
 * inside the face: 1; 0 if not (or the face is degenerate); -1 when k is
 * 4 and the origin is inside. */
static int project(double q[][3], int k, double out[3])
{
    double e[3][3], w[3] = {0, 0, 0};
    for (int i = 1; i < k; i++)
        for (int j = 0; j < 3; j++)
            e[i - 1][j] = q[i][j] - q[0][j];
    if (k == 2) {
        double den = dot(e[0], e[0]);
        if (!(den > 0))
            return 0;
        w[0] = -dot(q[0], e[0]) / den;
    } else if (k == 3) {
        double a11 = dot(e[0], e[0]), a12 = dot(e[0], e[1]), a22 = dot(e[1], e[1]);
        double b1 = -dot(q[0], e[0]), b2 = -dot(q[0], e[1]);
        double det = a11 * a22 - a12 * a12;
        if (!(det > 1e-12 * a11 * a22))
            return 0;
        w[0] = (b1 * a22 - b2 * a12) / det;
        w[1] = (a11 * b2 - a12 * b1) / det;
    } else if (k == 4) {
        double c[3][3];         /* Cramer: rows e x e */
        for (int i = 0; i < 3; i++) {
            const double *u = e[(i + 1) % 3], *v = e[(i + 2) % 3];
            c[i][0] = u[1] * v[2] - u[2] * v[1];
            c[i][1] = u[2] * v[0] - u[0] * v[2];
            c[i][2] = u[0] * v[1] - u[1] * v[0];
        }
        double det = dot(e[0], c[0]);
        double scale = sqrt(dot(e[0], e[0]) * dot(e[1], e[1]) * dot(e[2], e[2]));
        if (!(fabs(det) > 1e-12 * scale))
            return 0;
        for (int i = 0; i < 3; i++)
            w[i] = -dot(q[0], c[i]) / det;
    }
    double sum = 0;
    for (int i = 0; i < k - 1; i++) {
        if (!(w[i] > 0))
            return 0;
        sum += w[i];
    }
    if (k > 1 && !(sum < 1))
        return 0;
    if (k == 4)
        return -1;
    for (int j = 0; j < 3; j++) {
        out[j] = q[0][j];
        for (int i = 0; i < k - 1; i++)
            out[j] += w[i] * e[i][j];
    }
    return 1;
}

int mpb__simplex_nearest(double p[][3], int m, double v[3])
{
    double best = INFINITY, q[4][3], x[3];
    int best_mask = 1;
    v[0] = p[0][0], v[1] = p[0][1], v[2] = p[0][2];
    for (int mask = 1; mask < (1 << m); mask++) {
        int k = 0;
        for (int i = 0; i < m; i++)
            if (mask >> i & 1)
                memcpy(q[k++], p[i], sizeof q[0]);
        int r = project(q, k, x);
        if (r < 0) {
            v[0] = v[1] = v[2] = 0;
            return 0;
        }
        if (r > 0 && dot(x, x) < best) {
            best = dot(x, x);
            best_mask = mask;
            memcpy(v, x, sizeof x);
        }
    }
    int k = 0;
    for (int i = 0; i < m; i++)
        if (best_mask >> i & 1)
            memcpy(q[k++], p[i], sizeof q[0]);
    memcpy(p, q, (size_t)k * sizeof q[0]);
    return k;
}
