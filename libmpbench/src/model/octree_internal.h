/*
 * octree_internal.h - the mpb_octree handle's state, shared by octree.c
 * (cells, points) and octree_io.c (OctoMap's formats).
 */
#ifndef MPB_OCTREE_INTERNAL_H
#define MPB_OCTREE_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "mpbench/octree.h"

/* An occupied cell: the Morton code of its lower corner's key (x in bit
 * 0, y in 1, z in 2 of each triple; OctoMap's child order), and its
 * level (0: a leaf of side res; l: side res x 2^l). */
typedef struct mpb__octree_cell {
    uint64_t code;
    uint8_t  level;
} mpb__octree_cell;

struct mpb_octree {
    double            res;
    mpb__octree_cell *cells;
    size_t            num_cells, cap_cells;
    int               normal;       /* cells sorted, disjoint, pruned */
    uint64_t         *pending;      /* leaf codes of points not yet merged */
    size_t            num_pending, cap_pending;
};

uint64_t mpb__octree_code(const uint32_t k[3]);
void     mpb__octree_key(uint64_t code, uint32_t k[3]);
/* Append a cell (any order: the next normalise sorts). MPB_OK,
 * MPB_ENOMEM, MPB_EPARSE when far over MPB_OCTREE_MAX_CELLS. */
int      mpb__octree_push(mpb_octree *o, uint64_t code, int level);
/* Sort, drop cells inside others, prune; MPB_EPARSE over the limit. */
int      mpb__octree_normalise(mpb_octree *o);

#endif /* MPB_OCTREE_INTERNAL_H */
