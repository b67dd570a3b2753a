/*
 * octree.c - the mpb_octree handle: occupied cells as Morton codes of
 * their lower corners with their levels, sorted, pruned; points gathered
 * in batches and merged into them.
 */
#include "mpbench/mpbench.h"
#include "mpbench/octree.h"
#include "model/octree_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Points gathered before they are merged into the cells: bounds the
 * memory of a large cloud to its distinct cells and this batch. */
#define BATCH (1 << 20)

static uint64_t spread(uint32_t v)
{
    uint64_t x = v & 0xffffu;
    x = (x | x << 32) & 0x1f00000000ffffull;
    x = (x | x << 16) & 0x1f0000ff0000ffull;
    x = (x | x << 8) & 0x100f00f00f00f00full;
    x = (x | x << 4) & 0x10c30c30c30c30c3ull;
    x = (x | x << 2) & 0x1249249249249249ull;
    return x;
}

static uint32_t gather(uint64_t x)
{
    x &= 0x1249249249249249ull;
    x = (x | x >> 2) & 0x10c30c30c30c30c3ull;
    x = (x | x >> 4) & 0x100f00f00f00f00full;
    x = (x | x >> 8) & 0x1f0000ff0000ffull;
    x = (x | x >> 16) & 0x1f00000000ffffull;
    x = (x | x >> 32) & 0xffffu;
    return (uint32_t)x;
}

uint64_t mpb__octree_code(const uint32_t k[3])
{
    return spread(k[0]) | spread(k[1]) << 1 | spread(k[2]) << 2;
}

void mpb__octree_key(uint64_t code, uint32_t k[3])
{
    k[0] = gather(code);
    k[1] = gather(code >> 1);
    k[2] = gather(code >> 2);
}

int mpb_octree_create(double resolution, mpb_octree **out)
{
    if (!out)
        return MPB_EINVAL;
    *out = NULL;
    if (!(resolution >= MPB_OCTREE_MIN_RESOLUTION &&
          resolution <= MPB_OCTREE_MAX_RESOLUTION))
        return MPB_EINVAL;
    mpb_octree *o = calloc(1, sizeof *o);
    if (!o)
        return MPB_ENOMEM;
    o->res = resolution;
    *out = o;
    return MPB_OK;
}

void mpb_octree_destroy(mpb_octree *o)
{
    if (!o)
        return;
    free(o->cells);
    free(o->pending);
    free(o);
}

double mpb_octree_resolution(const mpb_octree *o)
{
    return o ? o->res : NAN;
}

int mpb__octree_push(mpb_octree *o, uint64_t code, int level)
{
    if (o->num_cells >= MPB_OCTREE_MAX_CELLS + (size_t)BATCH)
        return MPB_EPARSE;
    if (o->num_cells == o->cap_cells) {
        size_t cap = o->cap_cells ? 2 * o->cap_cells : 64;
        mpb__octree_cell *c = realloc(o->cells, cap * sizeof *c);
        if (!c)
            return MPB_ENOMEM;
        o->cells = c;
        o->cap_cells = cap;
    }
    o->cells[o->num_cells].code = code;
    o->cells[o->num_cells].level = (uint8_t)level;
    o->num_cells++;
    o->normal = 0;
    return MPB_OK;
}

static int by_code(const void *a, const void *b)
{
    const mpb__octree_cell *x = a, *y = b;
    if (x->code != y->code)
        return x->code < y->code ? -1 : 1;
    return (int)y->level - (int)x->level;   /* the larger first */
}

static uint64_t span(int level)
{
    return (uint64_t)1 << (3 * level);
}

/* Sorted, none inside another, eight occupied siblings their parent. */
static int normalise(mpb_octree *o)
{
    if (o->num_pending > 0) {
        for (size_t i = 0; i < o->num_pending; i++) {
            int rc = mpb__octree_push(o, o->pending[i], 0);
            if (rc != MPB_OK)
                return rc;
        }
        o->num_pending = 0;
    }
    if (o->normal)
        return o->num_cells > MPB_OCTREE_MAX_CELLS ? MPB_EPARSE : MPB_OK;
    if (o->num_cells > 1)
        qsort(o->cells, o->num_cells, sizeof *o->cells, by_code);
    /* a stack over the cells array itself: n <= i always */
    size_t n = 0;
    for (size_t i = 0; i < o->num_cells; i++) {
        mpb__octree_cell c = o->cells[i];
        if (n > 0) {
            const mpb__octree_cell *t = &o->cells[n - 1];
            if (c.code < t->code + span(t->level))
                continue;       /* inside the one before */
        }
        o->cells[n++] = c;
        /* eight siblings of one level, aligned and in a row: their parent */
        while (n >= 8) {
            mpb__octree_cell *f = &o->cells[n - 8];
            int l = f->level;
            if (l + 1 >= MPB_OCTREE_DEPTH || f->code % span(l + 1) != 0)
                break;
            int ok = 1;
            for (int k = 1; k < 8 && ok; k++)
                ok = f[k].level == l && f[k].code == f->code + (uint64_t)k * span(l);
            if (!ok)
                break;
            f->level = (uint8_t)(l + 1);
            n -= 7;
        }
    }
    o->num_cells = n;
    o->normal = 1;
    return n > MPB_OCTREE_MAX_CELLS ? MPB_EPARSE : MPB_OK;
}

int mpb__octree_normalise(mpb_octree *o)
{
    return normalise(o);
}

int mpb_octree_add_point(mpb_octree *o, const double p[3])
{
    if (!o || !p)
        return MPB_EINVAL;
    uint32_t k[3];
    double half = o->res * (double)(1u << (MPB_OCTREE_DEPTH - 1));
    for (int i = 0; i < 3; i++) {
        if (!(fabs(p[i]) < half))
            return MPB_EINVAL;
        double f = floor(p[i] / o->res) + (double)(1u << (MPB_OCTREE_DEPTH - 1));
        if (f < 0 || f > 65535)
            return MPB_EINVAL;
        k[i] = (uint32_t)f;
    }
    if (o->num_pending == o->cap_pending) {
        if (o->cap_pending >= BATCH) {
            int rc = normalise(o);
            if (rc != MPB_OK)
                return rc;
        } else {
            size_t cap = o->cap_pending ? 2 * o->cap_pending : 256;
            uint64_t *q = realloc(o->pending, cap * sizeof *q);
            if (!q)
                return MPB_ENOMEM;
            o->pending = q;
            o->cap_pending = cap;
        }
    }
    o->pending[o->num_pending++] = mpb__octree_code(k);
    return MPB_OK;
}

int mpb_octree_num_cells(mpb_octree *o)
{
    if (!o)
        return MPB_EINVAL;
    int rc = normalise(o);
    return rc != MPB_OK ? rc : (int)o->num_cells;
}

int mpb_octree_cell(mpb_octree *o, int i, double center[3], double *side)
{
    if (!o || !center || !side)
        return MPB_EINVAL;
    int rc = normalise(o);
    if (rc != MPB_OK)
        return rc;
    if (i < 0 || (size_t)i >= o->num_cells)
        return MPB_EINVAL;
    uint32_t k[3];
    mpb__octree_key(o->cells[i].code, k);
    double s = o->res * (double)(1u << o->cells[i].level);
    for (int j = 0; j < 3; j++)
        center[j] = ((double)k[j] - (double)(1u << (MPB_OCTREE_DEPTH - 1))) * o->res + s / 2;
    *side = s;
    return MPB_OK;
}
