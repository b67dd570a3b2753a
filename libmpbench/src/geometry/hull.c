/*
 * hull.c - the points of a set that may be extreme along some direction
 * (hull.h). Quickhull builds a triangulated hull; then a check that
 * trusts nothing of the build decides which points may be dropped.
 *
 * Why a dropped point x is inside the hull of the kept ones: the live
 * facets form a closed oriented surface (each directed edge in one facet,
 * its reverse in one other). x lies strictly inside every facet's plane,
 * so a ray from x crosses every facet it meets the same way (from the
 * inner side of its plane to the outer): x's winding number is the number
 * of crossings, and a ray toward any facet meets one. A nonzero winding
 * number encloses x, and whatever the surface encloses lies in the hull
 * of its vertices, all kept. The margin covers the rounding of the plane
 * test for facets that are not too thin (MIN_SINE); a thinner facet, or
 * any failed check, keeps every point.
 */
#include "geometry/hull.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/grow.h"

/* The sine of a facet's widest angle at least this: its normal, from two
 * edges, is then good to ~1e-15, and the plane test's rounding stays ~1e-4
 * of the margin. */
#define MIN_SINE 1e-4
/* The initial tetrahedron: points this far (times the largest coordinate)
 * off the line, the plane; closer is a flat set, kept whole. */
#define MIN_SPREAD 1e-6
/* A point this far above a facet's plane is outside it while building. */
#define OUTSIDE_EPS 1e-10
/* Point-plane tests of the final check at most (~0.3 s). */
#define MAX_TESTS 1e8

typedef struct {
    int    v[3];      /* counter-clockwise seen from outside */
    int    nb[3];     /* the facet across edge v[i] -> v[(i + 1) % 3] */
    double n[3], c;   /* unit outward normal; n . x = c on the plane */
    int    head;      /* first of its outside points (list in next), -1 */
    int    far;       /* the farthest of them */
    double fard;
    int    dead;
    int    seen;      /* == stamp: visible from the current eye */
} facet;

typedef struct {
    const double *p;
    int           n;
    double        eps;
    facet        *f;
    int           nf, fcap;
    int          *next;                    /* outside lists, per point */
    int          *sfac, *efac, *sst, *est; /* per point: the new facet whose
                                              horizon edge starts / ends
                                              there, and when */
    int           stamp;
    int          *todo, ntodo, todocap;    /* facets given outside points */
    int          *vis, nvis, viscap;       /* one step's visible facets */
    int          *hor, nhor, horcap;       /* its horizon: a, b, facet */
    int          *orph, norph, orphcap;    /* its points to reassign */
} qh;

static const double *pt(const qh *h, int i)
{
    return h->p + 3 * (size_t)i;
}

static double dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void sub(const double *a, const double *b, double *out)
{
    for (int k = 0; k < 3; k++)
        out[k] = a[k] - b[k];
}

static void cross(const double *u, const double *w, double *out)
{
    out[0] = u[1] * w[2] - u[2] * w[1];
    out[1] = u[2] * w[0] - u[0] * w[2];
    out[2] = u[0] * w[1] - u[1] * w[0];
}

static int push(int **arr, int *len, int *cap, int x)
{
    if (mpb__grow((void **)arr, cap, *len + 1, sizeof **arr) != MPB_OK)
        return -1;
    (*arr)[(*len)++] = x;
    return 0;
}

static double dist(const qh *h, const facet *f, int i)
{
    return dot(f->n, pt(h, i)) - f->c;
}

/* A new facet a b c with its plane, or -1 (no memory, no plane). */
static int new_facet(qh *h, int a, int b, int c)
{
    if (mpb__grow((void **)&h->f, &h->fcap, h->nf + 1, sizeof *h->f) != MPB_OK)
        return -1;
    facet *f = &h->f[h->nf];
    memset(f, 0, sizeof *f);
    f->v[0] = a, f->v[1] = b, f->v[2] = c;
    f->nb[0] = f->nb[1] = f->nb[2] = -1;
    f->head = f->far = -1;
    f->seen = -1;
    double u[3], w[3], n[3];
    sub(pt(h, b), pt(h, a), u);
    sub(pt(h, c), pt(h, a), w);
    cross(u, w, n);
    double len = sqrt(dot(n, n));
    if (!(len > 0) || !isfinite(len))
        return -1;
    for (int k = 0; k < 3; k++)
        f->n[k] = n[k] / len;
    f->c = dot(f->n, pt(h, a));
    return h->nf++;
}

/* The edge of f that runs a -> b, or -1. */
static int edge_of(const facet *f, int a, int b)
{
    for (int e = 0; e < 3; e++)
        if (f->v[e] == a && f->v[(e + 1) % 3] == b)
            return e;
    return -1;
}

/* Put point i in the outside list of the first of facets [lo, hi) it is
 * outside of; none: it is inside for now (the final check decides). */
static int assign(qh *h, int i, int lo, int hi)
{
    for (int fi = lo; fi < hi; fi++) {
        facet *f = &h->f[fi];
        double d = dist(h, f, i);
        if (!(d > h->eps))
            continue;
        if (f->head < 0 && push(&h->todo, &h->ntodo, &h->todocap, fi) != 0)
            return -1;
        h->next[i] = f->head;
        f->head = i;
        if (d > f->fard || f->far < 0) {
            f->fard = d;
            f->far = i;
        }
        return 0;
    }
    return 0;
}

/* The first tetrahedron, from extreme points; -1 for a flat set. */
static int simplex(qh *h, double scale)
{
    int ext[6];
    for (int k = 0; k < 3; k++) {
        ext[2 * k] = ext[2 * k + 1] = 0;
        for (int i = 1; i < h->n; i++) {
            if (pt(h, i)[k] < pt(h, ext[2 * k])[k])
                ext[2 * k] = i;
            if (pt(h, i)[k] > pt(h, ext[2 * k + 1])[k])
                ext[2 * k + 1] = i;
        }
    }
    int s[4] = {0, 0, 0, 0};
    double best = -1, u[3], w[3], n[3];
    for (int i = 0; i < 6; i++)
        for (int j = i + 1; j < 6; j++) {
            sub(pt(h, ext[i]), pt(h, ext[j]), u);
            if (dot(u, u) > best) {
                best = dot(u, u);
                s[0] = ext[i], s[1] = ext[j];
            }
        }
    if (!(sqrt(best) > MIN_SPREAD * scale))
        return -1;
    sub(pt(h, s[1]), pt(h, s[0]), u);
    best = -1;
    for (int i = 0; i < h->n; i++) {   /* farthest from the line */
        sub(pt(h, i), pt(h, s[0]), w);
        cross(u, w, n);
        if (dot(n, n) > best) {
            best = dot(n, n);
            s[2] = i;
        }
    }
    if (!(sqrt(best) / sqrt(dot(u, u)) > MIN_SPREAD * scale))
        return -1;
    sub(pt(h, s[2]), pt(h, s[0]), w);
    cross(u, w, n);
    double len = sqrt(dot(n, n)), far = -1, side = 0;
    for (int i = 0; i < h->n; i++) {   /* farthest from the plane */
        sub(pt(h, i), pt(h, s[0]), w);
        double d = dot(n, w) / len;
        if (fabs(d) > far) {
            far = fabs(d);
            side = d;
            s[3] = i;
        }
    }
    if (!(far > MIN_SPREAD * scale))
        return -1;
    if (side > 0) {           /* s[3] above s0 s1 s2: turn that facet */
        int t = s[1];
        s[1] = s[2], s[2] = t;
    }
    const int tri[4][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}};
    for (int t = 0; t < 4; t++)
        if (new_facet(h, s[tri[t][0]], s[tri[t][1]], s[tri[t][2]]) < 0)
            return -1;
    for (int a = 0; a < 4; a++)
        for (int e = 0; e < 3; e++)
            for (int b = 0; b < 4; b++)
                if (b != a && edge_of(&h->f[b], h->f[a].v[(e + 1) % 3],
                                      h->f[a].v[e]) >= 0)
                    h->f[a].nb[e] = b;
    for (int i = 0; i < h->n; i++)
        if (i != s[0] && i != s[1] && i != s[2] && i != s[3] &&
            assign(h, i, 0, 4) != 0)
            return -1;
    return 0;
}

/* Add facet fi's farthest outside point to the hull: replace the facets
 * it sees with a cone from it to their horizon. -1: a horizon that is not
 * one loop (rounding), a facet without a plane, no memory. */
static int step(qh *h, int fi)
{
    const int eye = h->f[fi].far, st = ++h->stamp;
    h->nvis = h->nhor = h->norph = 0;
    h->f[fi].seen = st;
    if (push(&h->vis, &h->nvis, &h->viscap, fi) != 0)
        return -1;
    for (int k = 0; k < h->nvis; k++)
        for (int e = 0; e < 3; e++) {
            int o = h->f[h->vis[k]].nb[e];
            if (h->f[o].seen != st && dist(h, &h->f[o], eye) > 0) {
                h->f[o].seen = st;
                if (push(&h->vis, &h->nvis, &h->viscap, o) != 0)
                    return -1;
            }
        }
    for (int k = 0; k < h->nvis; k++) {
        const facet *g = &h->f[h->vis[k]];
        for (int e = 0; e < 3; e++)
            if (h->f[g->nb[e]].seen != st &&
                (push(&h->hor, &h->nhor, &h->horcap, g->v[e]) != 0 ||
                 push(&h->hor, &h->nhor, &h->horcap, g->v[(e + 1) % 3]) != 0 ||
                 push(&h->hor, &h->nhor, &h->horcap, g->nb[e]) != 0))
                return -1;
    }
    const int first = h->nf, count = h->nhor / 3;
    for (int k = 0; k < count; k++) {
        int a = h->hor[3 * k], b = h->hor[3 * k + 1], o = h->hor[3 * k + 2];
        if (h->sst[a] == st || h->est[b] == st)
            return -1;
        int nf = new_facet(h, a, b, eye);
        int j = edge_of(&h->f[o], b, a);
        if (nf < 0 || j < 0)
            return -1;
        h->sst[a] = h->est[b] = st;
        h->sfac[a] = h->efac[b] = nf;
        h->f[nf].nb[0] = o;
        h->f[o].nb[j] = nf;
    }
    for (int nf = first; nf < h->nf; nf++) {
        int a = h->f[nf].v[0], b = h->f[nf].v[1];
        if (h->sst[b] != st || h->est[a] != st)
            return -1;
        h->f[nf].nb[1] = h->sfac[b];   /* across b -> eye */
        h->f[nf].nb[2] = h->efac[a];   /* across eye -> a */
    }
    int len = 1;                       /* one loop, not several */
    for (int x = h->f[first].nb[1]; x != first; x = h->f[x].nb[1])
        if (++len > count)
            return -1;
    if (len != count)
        return -1;
    for (int k = 0; k < h->nvis; k++) {
        facet *g = &h->f[h->vis[k]];
        g->dead = 1;
        for (int i = g->head; i >= 0; i = h->next[i])
            if (i != eye && push(&h->orph, &h->norph, &h->orphcap, i) != 0)
                return -1;
    }
    for (int k = 0; k < h->norph; k++)
        if (assign(h, h->orph[k], first, h->nf) != 0)
            return -1;
    return 0;
}

/* Facet f's plane from its widest angle, for the final test: unit normal
 * n and corner *a; -1 when too thin to trust. */
static int trusted_plane(const qh *h, const facet *f, double n[3], int *a)
{
    double len[3], u[3], w[3];
    for (int e = 0; e < 3; e++) {      /* len[e]: the edge opposite v[e] */
        sub(pt(h, f->v[(e + 1) % 3]), pt(h, f->v[(e + 2) % 3]), u);
        len[e] = dot(u, u);
    }
    int e = len[0] >= len[1] && len[0] >= len[2] ? 0 : len[1] >= len[2] ? 1 : 2;
    *a = f->v[e];
    sub(pt(h, f->v[(e + 1) % 3]), pt(h, *a), u);
    sub(pt(h, f->v[(e + 2) % 3]), pt(h, *a), w);
    cross(u, w, n);
    double nn = sqrt(dot(n, n));
    if (!(nn >= MIN_SINE * sqrt(dot(u, u)) * sqrt(dot(w, w))) || !(nn > 0))
        return -1;
    for (int k = 0; k < 3; k++)
        n[k] /= nn;
    return 0;
}

/* keep[] from the live facets, or -1 when they fail a check. */
static int final_keep(qh *h, double margin, unsigned char *keep)
{
    int live = 0, verts = 0;
    memset(keep, 0, (size_t)h->n);
    for (int fi = 0; fi < h->nf; fi++) {
        const facet *f = &h->f[fi];
        if (f->dead)
            continue;
        live++;
        for (int e = 0; e < 3; e++) {
            int o = f->nb[e];
            if (o < 0 || o >= h->nf || h->f[o].dead)
                return -1;
            int j = edge_of(&h->f[o], f->v[(e + 1) % 3], f->v[e]);
            if (j < 0 || h->f[o].nb[j] != fi)
                return -1;
            if (!keep[f->v[e]])
                verts++;
            keep[f->v[e]] = 1;
        }
    }
    if (live % 2 != 0 || verts - 3 * live / 2 + live != 2)
        return -1;
    if ((double)(h->n - verts) * live > MAX_TESTS)
        return -1;            /* a huge hull and many inside: keep all */
    double *pl = malloc((size_t)live * 3 * sizeof *pl);
    int *corner = malloc((size_t)live * sizeof *corner);
    int np = 0, rc = 0;
    if (!pl || !corner)
        rc = -1;
    for (int fi = 0; rc == 0 && fi < h->nf; fi++)
        if (!h->f[fi].dead) {
            rc = trusted_plane(h, &h->f[fi], &pl[3 * np], &corner[np]);
            np++;
        }
    for (int i = 0; rc == 0 && i < h->n; i++) {
        if (keep[i])
            continue;
        for (int k = 0; k < np && !keep[i]; k++) {
            double x[3];
            sub(pt(h, i), pt(h, corner[k]), x);
            keep[i] = !(dot(&pl[3 * k], x) < -margin);
        }
    }
    free(pl);
    free(corner);
    return rc;
}

int mpb__hull_keep(const double *pts, int n, unsigned char *keep)
{
    double scale = 0;         /* the largest coordinate; 0: not finite */
    for (long i = 0; i < 3L * n && scale >= 0; i++)
        scale = isfinite(pts[i]) ? fmax(scale, fabs(pts[i])) : -1;
    qh h;
    memset(&h, 0, sizeof h);
    h.p = pts;
    h.n = n;
    h.eps = OUTSIDE_EPS * scale;
    int rc = -1;
    if (n >= 4 && scale > 0 && isfinite(scale)) {
        h.next = malloc((size_t)n * sizeof *h.next);
        h.sfac = malloc((size_t)n * sizeof *h.sfac);
        h.efac = malloc((size_t)n * sizeof *h.efac);
        h.sst = calloc((size_t)n, sizeof *h.sst);
        h.est = calloc((size_t)n, sizeof *h.est);
        if (h.next && h.sfac && h.efac && h.sst && h.est)
            rc = simplex(&h, scale);
    }
    while (rc == 0 && h.ntodo > 0) {
        int fi = h.todo[--h.ntodo];
        if (!h.f[fi].dead && h.f[fi].head >= 0)
            rc = step(&h, fi);
    }
    if (rc == 0)
        rc = final_keep(&h, MPB__HULL_MARGIN * scale, keep);
    free(h.f);
    free(h.next);
    free(h.sfac);
    free(h.efac);
    free(h.sst);
    free(h.est);
    free(h.todo);
    free(h.vis);
    free(h.hor);
    free(h.orph);
    int kept = 0;
    for (int i = 0; i < n; i++) {
        if (rc != 0)
            keep[i] = 1;
        kept += keep[i];
    }
    return kept;
}
