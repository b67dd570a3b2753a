/* state_table.c - hash table of lattice states (open addressing, linear probing). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "state_table.h"

int ara_states_init(ara_state_table *t, int num_joints, int max_states)
{
    memset(t, 0, sizeof *t);
    if (num_joints <= 0 || max_states <= 0 || max_states > (1 << 28))
        return -1;
    t->num_joints = num_joints;
    t->max_states = max_states;
    t->num_slots = 1024;
    while (t->num_slots < 2u * (unsigned)max_states)
        t->num_slots *= 2;
    t->slots = malloc((size_t)t->num_slots * sizeof *t->slots);
    if (!t->slots)
        return -1;
    memset(t->slots, 0xff, (size_t)t->num_slots * sizeof *t->slots);
    return 0;
}

void ara_states_free(ara_state_table *t)
{
    free(t->coords);
    free(t->states);
    free(t->slots);
    memset(t, 0, sizeof *t);
}

static unsigned hash_coords(const int16_t *c, int n)
{
    uint64_t h = 1469598103934665603ull;      /* FNV-1a over the values */
    for (int i = 0; i < n; i++) {
        h ^= (uint16_t)c[i];
        h *= 1099511628211ull;
    }
    return (unsigned)(h ^ (h >> 32));
}

static unsigned probe(const ara_state_table *t, const int16_t *coords, int *id)
{
    unsigned mask = t->num_slots - 1;
    unsigned i = hash_coords(coords, t->num_joints) & mask;
    size_t bytes = (size_t)t->num_joints * sizeof *coords;
    while (t->slots[i] >= 0 &&
           memcmp(ara_states_coords(t, t->slots[i]), coords, bytes) != 0)
        i = (i + 1) & mask;
    *id = t->slots[i];
    return i;
}

int ara_states_find(const ara_state_table *t, const int16_t *coords)
{
    int id;
    probe(t, coords, &id);
    return id;
}

/* Grow the state arrays geometrically, never past max_states. */
static int reserve(ara_state_table *t)
{
    if (t->size < t->cap)
        return 0;
    int cap = t->cap ? 2 * t->cap : 4096;
    if (cap > t->max_states)
        cap = t->max_states;
    int16_t *c = realloc(t->coords, (size_t)cap * (size_t)t->num_joints *
                                        sizeof *c);
    if (!c)
        return -1;
    t->coords = c;
    ara_state *s = realloc(t->states, (size_t)cap * sizeof *s);
    if (!s)
        return -1;
    t->states = s;
    t->cap = cap;
    return 0;
}

int ara_states_get(ara_state_table *t, const int16_t *coords, int *added)
{
    int id;
    unsigned slot = probe(t, coords, &id);
    *added = 0;
    if (id >= 0)
        return id;
    if (t->size >= t->max_states || reserve(t) != 0)
        return -1;
    id = t->size++;
    memcpy(t->coords + (long)id * t->num_joints, coords,
           (size_t)t->num_joints * sizeof *coords);
    t->states[id] = (ara_state){INFINITY, 0.0, INFINITY, -1, 0, 0, 0, 0, 0};
    t->slots[slot] = id;
    *added = 1;
    return id;
}
