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

/* The projection of the origin onto face {p[i], p[j]} (i < j) or
 * {p[i], p[j], p[l]} (i < j < l; l < 0 for an edge), as project() finds
 * it, to the bit, from the differences and dot products the faces share
 * (tab). 1 if it falls inside the face, into out; 0 if not. */
struct simplex_tab {
    double d[4][4][3];          /* d[i][j] = p[j] - p[i], i < j */
    double dd[4][4];            /* d[i][j] . d[i][j] */
    double pd[4][4];            /* p[i] . d[i][j] */
};

static int project_face(double p[][3], const struct simplex_tab *t, int i,
                        int j, int l, double out[3])
{
    const double *e0 = t->d[i][j], *e1 = l >= 0 ? t->d[i][l] : NULL;
    double w0, w1 = 0;
    if (l < 0) {
        double den = t->dd[i][j];
        if (!(den > 0))
            return 0;
        w0 = -t->pd[i][j] / den;
        if (!(w0 > 0) || !(w0 < 1))
            return 0;
    } else {
        double a11 = t->dd[i][j], a12 = dot(e0, e1), a22 = t->dd[i][l];
        double b1 = -t->pd[i][j], b2 = -t->pd[i][l];
        double det = a11 * a22 - a12 * a12;
        if (!(det > 1e-12 * a11 * a22))
            return 0;
        w0 = (b1 * a22 - b2 * a12) / det;
        w1 = (a11 * b2 - a12 * b1) / det;
        if (!(w0 > 0) || !(w1 > 0) || !(w0 + w1 < 1))
            return 0;
    }
    for (int k = 0; k < 3; k++) {
        out[k] = p[i][k];
        out[k] += w0 * e0[k];
        if (e1)
            out[k] += w1 * e1[k];
    }
    return 1;
}

/*
 * Every face in the order of its mask, as project() on each would: the
 * edges and triangles from the differences and dot products they share
 * (the same operations on the same operands, so the same doubles), the
 * tetrahedron by project() itself.
 */
int mpb__simplex_nearest(double p[][3], int m, double v[3])
{
    double best = INFINITY, q[4][3], x[3];
    int best_mask = 1;
    struct simplex_tab t;
    for (int i = 0; i < m; i++)
        for (int j = i + 1; j < m; j++) {
            for (int k = 0; k < 3; k++)
                t.d[i][j][k] = p[j][k] - p[i][k];
            t.dd[i][j] = dot(t.d[i][j], t.d[i][j]);
            t.pd[i][j] = dot(p[i], t.d[i][j]);
        }
    v[0] = p[0][0], v[1] = p[0][1], v[2] = p[0][2];
    for (int mask = 1; mask < (1 << m); mask++) {
        int idx[4], k = 0;
        for (int i = 0; i < m; i++)
            if (mask >> i & 1)
                idx[k++] = i;
        int r;
        if (k == 1) {
            memcpy(x, p[idx[0]], sizeof x);
            r = 1;
        } else if (k < 4) {
            r = project_face(p, &t, idx[0], idx[1], k == 3 ? idx[2] : -1, x);
        } else {
            for (int i = 0; i < 4; i++)
                memcpy(q[i], p[i], sizeof q[0]);
            r = project(q, 4, x);
        }
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
