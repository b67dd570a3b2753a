/*
 * dirtable.h - for a point set, by direction: the few points that can be
 * the farthest along it. Directions are cut into cells (the 6 g x g
 * squares of a cube's faces, seen from its centre); a cell lists, in
 * ascending order, every point within MPB__DIRTABLE_SLACK (times the
 * largest coordinate) of the farthest along some direction of the cell.
 * The farthest along d among the cell's points is then the farthest of
 * all, to the last bit and the same index (rounding is ~1e-15 of the
 * largest coordinate). Private to libmpbench and its tests
 * (collision_fcl.cpp's mesh extents).
 */
#ifndef MPB_DIRTABLE_H
#define MPB_DIRTABLE_H

#include <math.h>

#ifdef __cplusplus
extern "C" {
#endif

#define MPB__DIRTABLE_SLACK 1e-9

typedef struct mpb__dirtable {
    int  g;              /* cells per cube edge; 0: no table */
    int *start;          /* cell c's points: idx[start[c] .. start[c + 1]) */
    int *idx;
} mpb__dirtable;

/*
 * The table of the n points pts[3 i .. 3 i + 2] with g x g cells a face
 * (1 <= g <= 64). MPB_OK, MPB_EINVAL (bad arguments, a point not finite),
 * MPB_ENOMEM; *t is then empty (g = 0).
 */
int mpb__dirtable_build(mpb__dirtable *t, const double *pts, int n, int g);

void mpb__dirtable_free(mpb__dirtable *t);

/* The cell of direction d (any length), or -1 for a zero or non-finite
 * d or an empty table: then every point is a candidate. */
static inline int mpb__dirtable_cell(const mpb__dirtable *t, const double d[3])
{
    double ax = fabs(d[0]), ay = fabs(d[1]), az = fabs(d[2]);
    int k = ax >= ay ? (ax >= az ? 0 : 2) : (ay >= az ? 1 : 2);
    double a = k == 0 ? ax : k == 1 ? ay : az;
    if (!(a > 0 && a < INFINITY) || t->g <= 0)
        return -1;
    /* |u|, |v| <= 1 exactly: a is the largest */
    double half = 0.5 * t->g / a;
    int iu = (int)(d[(k + 1) % 3] * half + 0.5 * t->g);
    int iv = (int)(d[(k + 2) % 3] * half + 0.5 * t->g);
    iu = iu < t->g ? iu : t->g - 1;
    iv = iv < t->g ? iv : t->g - 1;
    return ((2 * k + (d[k] < 0)) * t->g + iu) * t->g + iv;
}

#ifdef __cplusplus
}
#endif

#endif /* MPB_DIRTABLE_H */
