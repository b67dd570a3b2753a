/*
 * octree_boxes.c - an octree's occupied cells as fewer boxes: runs of
 * cells side by side merged along x, then y, then z, where their other
 * sides match. The union is exactly the cells', so a collision world of
 * the boxes collides, measures and proves as one of the cells, for a
 * fraction of the shapes.
 */
#include "mpbench/mpbench.h"
#include "mpbench/octree.h"
#include "model/octree_internal.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct ibox {
    int32_t lo[3], hi[3];       /* leaf keys, hi exclusive */
} ibox;

/* Order by the two sides other than axis a, then along a: boxes that
 * may merge along a are then neighbours. One comparator per axis, as
 * qsort() takes no context. */
static int cmp_along(const ibox *a, const ibox *b, int ax)
{
    for (int k = 1; k <= 2; k++) {
        int j = (ax + k) % 3;
        if (a->lo[j] != b->lo[j])
            return a->lo[j] < b->lo[j] ? -1 : 1;
        if (a->hi[j] != b->hi[j])
            return a->hi[j] < b->hi[j] ? -1 : 1;
    }
    return (a->lo[ax] > b->lo[ax]) - (a->lo[ax] < b->lo[ax]);
}

static int along_x(const void *a, const void *b) { return cmp_along(a, b, 0); }
static int along_y(const void *a, const void *b) { return cmp_along(a, b, 1); }
static int along_z(const void *a, const void *b) { return cmp_along(a, b, 2); }

static size_t merge(ibox *v, size_t n, int a)
{
    static int (*const cmp[3])(const void *, const void *) = {along_x, along_y, along_z};
    qsort(v, n, sizeof *v, cmp[a]);
    size_t m = 0;
    for (size_t i = 0; i < n; i++) {
        if (m > 0) {
            ibox *t = &v[m - 1];
            int j = (a + 1) % 3, k = (a + 2) % 3;
            if (t->lo[j] == v[i].lo[j] && t->hi[j] == v[i].hi[j] &&
                t->lo[k] == v[i].lo[k] && t->hi[k] == v[i].hi[k] &&
                t->hi[a] == v[i].lo[a]) {
                t->hi[a] = v[i].hi[a];
                continue;
            }
        }
        v[m++] = v[i];
    }
    return m;
}

int mpb_octree_boxes(mpb_octree *o, double **boxes, int *n)
{
    if (!o || !boxes || !n)
        return MPB_EINVAL;
    *boxes = NULL;
    *n = 0;
    int cells = mpb_octree_num_cells(o);
    if (cells < 0)
        return cells;
    ibox *v = malloc(((size_t)cells + 1) * sizeof *v);
    if (!v)
        return MPB_ENOMEM;
    for (int i = 0; i < cells; i++) {
        uint32_t k[3];
        mpb__octree_key(o->cells[i].code, k);
        int32_t s = (int32_t)1 << o->cells[i].level;
        for (int j = 0; j < 3; j++) {
            v[i].lo[j] = (int32_t)k[j];
            v[i].hi[j] = (int32_t)k[j] + s;
        }
    }
    size_t m = (size_t)cells;
    for (int a = 0; a < 3; a++)
        m = merge(v, m, a);
    double *b = malloc((m + 1) * 6 * sizeof *b);
    if (!b) {
        free(v);
        return MPB_ENOMEM;
    }
    double half = (double)(1u << (MPB_OCTREE_DEPTH - 1));
    for (size_t i = 0; i < m; i++)
        for (int j = 0; j < 3; j++) {
            b[6 * i + j] = ((double)v[i].lo[j] - half) * o->res;
            b[6 * i + 3 + j] = ((double)v[i].hi[j] - half) * o->res;
        }
    free(v);
    *boxes = b;
    *n = (int)m;
    return MPB_OK;
}
