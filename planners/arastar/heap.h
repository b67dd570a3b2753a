/*
 * heap.h - the OPEN list of the search: a binary min-heap of state ids keyed
 * by (f, h), with decrease-key. Ties on f go to the smaller h (nearer the
 * goal), then to the smaller id, so the order never depends on chance.
 */
#ifndef ARASTAR_HEAP_H
#define ARASTAR_HEAP_H

#include <stddef.h>

typedef struct ara_heap_item {
    double f, h;
    int    id;
} ara_heap_item;

typedef struct ara_heap {
    ara_heap_item *items;
    int            size, cap;
    int           *pos;       /* pos[id]: index in items, or -1 */
    int            pos_cap;
} ara_heap;

void ara_heap_init(ara_heap *hp);
void ara_heap_free(ara_heap *hp);
/* Empty the heap, keeping its memory. */
void ara_heap_clear(ara_heap *hp);
/* Insert id, or move it to the new key if present. 0, or -1 out of memory. */
int  ara_heap_push(ara_heap *hp, int id, double f, double h);
/* Remove and return the smallest item; the heap must not be empty. */
ara_heap_item ara_heap_pop(ara_heap *hp);
const ara_heap_item *ara_heap_top(const ara_heap *hp);
int  ara_heap_contains(const ara_heap *hp, int id);

#endif
