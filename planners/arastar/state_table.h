/*
 * state_table.h - the states the search has generated: lattice coordinates
 * (steps from the start, one int16 per joint), found again through an
 * open-addressing hash table. Bounded: at most max_states states, so a
 * search that would exhaust memory fails instead.
 */
#ifndef ARASTAR_STATE_TABLE_H
#define ARASTAR_STATE_TABLE_H

#include <stdint.h>

typedef struct ara_state {
    double g;           /* best cost from the start found so far */
    double h;           /* heuristic, joint-cost units */
    double goal_dist;   /* m to the goal region, or rad to the goal joints */
    int    parent;      /* state id, -1 for the start */
    int    closed_iter; /* ARA* iteration that expanded it, 0 if none */
    unsigned char blocked;    /* collides or outside the limits */
    unsigned char snap_tried; /* the goal snap was tried from here */
    unsigned char in_incons;  /* on the INCONS list */
    unsigned char edge_ok;    /* the motion from parent is checked free */
} ara_state;

typedef struct ara_state_table {
    int        num_joints;
    int        size, cap, max_states;
    int16_t   *coords;     /* size x num_joints */
    ara_state *states;
    int       *slots;      /* hash slots: state id or -1 */
    unsigned   num_slots;  /* power of two, > 2 * max_states */
} ara_state_table;

/* 0, or -1 out of memory / bad arguments. */
int  ara_states_init(ara_state_table *t, int num_joints, int max_states);
void ara_states_free(ara_state_table *t);

/*
 * The id of the state at coords, adding it (g = INFINITY, parent -1)
 * if new; *added says which. -1 when the table is full or out of memory.
 */
int  ara_states_get(ara_state_table *t, const int16_t *coords, int *added);
/* The id at coords, or -1. */
int  ara_states_find(const ara_state_table *t, const int16_t *coords);

static inline const int16_t *ara_states_coords(const ara_state_table *t,
                                               int id)
{
    return t->coords + (long)id * t->num_joints;
}

#endif
