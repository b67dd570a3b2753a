/* heap.c - binary min-heap with decrease-key for the OPEN list. */
#include <stdlib.h>
#include <string.h>

#include "heap.h"

void ara_heap_init(ara_heap *hp)
{
    memset(hp, 0, sizeof *hp);
}

void ara_heap_free(ara_heap *hp)
{
    free(hp->items);
    free(hp->pos);
    memset(hp, 0, sizeof *hp);
}

void ara_heap_clear(ara_heap *hp)
{
    for (int i = 0; i < hp->size; i++)
        hp->pos[hp->items[i].id] = -1;
    hp->size = 0;
}

static int less(const ara_heap_item *a, const ara_heap_item *b)
{
    if (a->f != b->f)
        return a->f < b->f;
    if (a->h != b->h)
        return a->h < b->h;
    return a->id < b->id;
}

static void place(ara_heap *hp, int i, ara_heap_item it)
{
    hp->items[i] = it;
    hp->pos[it.id] = i;
}

static void sift_up(ara_heap *hp, int i)
{
    ara_heap_item it = hp->items[i];
    while (i > 0) {
        int parent = (i - 1) / 2;
        if (!less(&it, &hp->items[parent]))
            break;
        place(hp, i, hp->items[parent]);
        i = parent;
    }
    place(hp, i, it);
}

static void sift_down(ara_heap *hp, int i)
{
    ara_heap_item it = hp->items[i];
    for (;;) {
        int c = 2 * i + 1;
        if (c >= hp->size)
            break;
        if (c + 1 < hp->size && less(&hp->items[c + 1], &hp->items[c]))
            c++;
        if (!less(&hp->items[c], &it))
            break;
        place(hp, i, hp->items[c]);
        i = c;
    }
    place(hp, i, it);
}

static int grow_pos(ara_heap *hp, int id)
{
    if (id < hp->pos_cap)
        return 0;
    int cap = hp->pos_cap ? hp->pos_cap : 1024;
    while (cap <= id)
        cap *= 2;
    int *p = realloc(hp->pos, (size_t)cap * sizeof *p);
    if (!p)
        return -1;
    for (int i = hp->pos_cap; i < cap; i++)
        p[i] = -1;
    hp->pos = p;
    hp->pos_cap = cap;
    return 0;
}

int ara_heap_push(ara_heap *hp, int id, double f, double h)
{
    if (id < 0 || grow_pos(hp, id) != 0)
        return -1;
    ara_heap_item it = {f, h, id};
    int i = hp->pos[id];
    if (i >= 0) {
        int up = less(&it, &hp->items[i]);
        hp->items[i] = it;
        if (up)
            sift_up(hp, i);
        else
            sift_down(hp, i);
        return 0;
    }
    if (hp->size == hp->cap) {
        int cap = hp->cap ? 2 * hp->cap : 1024;
        ara_heap_item *p = realloc(hp->items, (size_t)cap * sizeof *p);
        if (!p)
            return -1;
        hp->items = p;
        hp->cap = cap;
    }
    hp->items[hp->size++] = it;
    sift_up(hp, hp->size - 1);
    return 0;
}

ara_heap_item ara_heap_pop(ara_heap *hp)
{
    ara_heap_item top = hp->items[0];
    hp->pos[top.id] = -1;
    hp->size--;
    if (hp->size > 0) {
        hp->items[0] = hp->items[hp->size];
        sift_down(hp, 0);
    }
    return top;
}

const ara_heap_item *ara_heap_top(const ara_heap *hp)
{
    return hp->size > 0 ? &hp->items[0] : NULL;
}

int ara_heap_contains(const ara_heap *hp, int id)
{
    return id >= 0 && id < hp->pos_cap && hp->pos[id] >= 0;
}
