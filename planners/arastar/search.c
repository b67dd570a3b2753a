/*
 * search.c - ARA* over joint-space motion primitives.
 *
 * The goal snap: a lattice of 4-degree steps almost never lands inside a
 * 2 cm, 0.05 rad region. So when a state being expanded has its
 * end-effector within snap_distance of the region, the search asks IK for
 * a configuration inside the region, starting from that state's own joints
 * (so the answer is usually a small joint change away), and tries the
 * straight joint-space segment to it. If the segment is free, the region
 * is reached from that state at the segment's cost. A joint goal is
 * snapped to the same way, with the goal joints themselves as the target.
 * Each state tries once. IK draws from a generator seeded by the state's
 * coordinates, so the same request always gives the same path.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "heap.h"
#include "mpbench/planner.h"
#include "mpbench/proto.h"
#include "search.h"
#include "state_table.h"

typedef struct prim {
    int joint, cells;
    double cost;
} prim;

typedef struct cand {
    double g;
    int    id;
} cand;

typedef struct search {
    const ara_problem *p;
    ara_solution      *out;
    int                nj;
    ara_state_table    states;
    ara_heap           open;
    int               *incons;
    int                num_incons, cap_incons;
    prim              *prims;
    int                num_prims;
    cand              *cands;   /* num_prims, for validate() */
    double            *lo, *hi;
    const unsigned char *wraps;
    double            *q, *q2, *qgoal;
    int16_t           *coords;
    double             eps;
    int                iter;
    /* The best solution so far: its last lattice state and snap target. */
    double             goal_g;
    int                goal_parent;
    double            *goal_q;
    double             t0;
} search;

static void lattice_q(const search *s, const int16_t *c, double *q)
{
    for (int j = 0; j < s->nj; j++)
        q[j] = s->p->start[j] + c[j] * s->p->step;
}

static double joint_distance_to_goal(const search *s, const double *q)
{
    return ara_motion_distance(s->p->motion, q, s->p->goal_joints);
}

/* Heuristic and distance to the goal of the configuration q. */
static int evaluate(search *s, const double *q, double *h, double *goal_dist)
{
    const ara_problem *p = s->p;
    double ee[3], rot = 0.0;
    if (p->region) {
        mpb_goal_distance gd;
        if (mpb_goal_region_distance(p->robot, p->region, q, &gd) != 0)
            return -1;
        memcpy(ee, gd.point, sizeof ee);
        rot = gd.angle;
        /* 0 only inside the region, orientation included. */
        *goal_dist = gd.position == 0.0 && gd.orientation == 0.0
                         ? 0.0 : fmax(gd.position, 1e-9);
    } else {
        mpb_pose pose;
        if (mpb_robot_link_pose(p->robot, q, p->ee_link, &pose) != 0)
            return -1;
        for (int i = 0; i < 3; i++)
            ee[i] = pose.t[i] + pose.R[3 * i] * p->ee_offset[0] +
                    pose.R[3 * i + 1] * p->ee_offset[1] +
                    pose.R[3 * i + 2] * p->ee_offset[2];
        *goal_dist = joint_distance_to_goal(s, q);
    }
    double metres = 0.0;
    if (p->grid) {
        int32_t cells = ara_grid_distance_at(p->grid, ee);
        /* Outside the grid or walled off: far, but never pruned (the
           grid is coarser than the collision model). */
        metres = cells == ARA_BFS_UNREACHED ? 2.0 : cells * p->grid->cell;
    }
    *h = p->h_position * metres + p->h_rotation * rot;
    if (!p->region && *goal_dist > *h)
        *h = *goal_dist;
    return 0;
}

static int within_limits(const search *s, int j, double v)
{
    return s->wraps[j] || (v >= s->lo[j] && v <= s->hi[j]);
}

static int push_incons(search *s, int id)
{
    if (s->states.states[id].in_incons)
        return 0;
    if (s->num_incons == s->cap_incons) {
        int cap = s->cap_incons ? 2 * s->cap_incons : 1024;
        int *n = realloc(s->incons, (size_t)cap * sizeof *n);
        if (!n)
            return -1;
        s->incons = n;
        s->cap_incons = cap;
    }
    s->incons[s->num_incons++] = id;
    s->states.states[id].in_incons = 1;
    return 0;
}

static int open_push(search *s, int id)
{
    ara_state *st = &s->states.states[id];
    return ara_heap_push(&s->open, id, st->g + s->eps * st->h, st->h);
}

/* A solution through state id to target q (g = cost). */
static void found(search *s, int id, const double *target, double cost)
{
    if (!(cost < s->goal_g))
        return;
    s->goal_g = cost;
    s->goal_parent = id;
    memcpy(s->goal_q, target, (size_t)s->nj * sizeof *target);
    s->out->epsilon = s->eps;
    if (s->p->on_solution)
        s->p->on_solution(s->p->user, mpb_monotonic_s() - s->t0, cost,
                          s->eps, s->out->expansions);
}

static uint64_t coords_seed(const search *s, const int16_t *c)
{
    uint64_t h = s->p->ik_seed ^ 0x9e3779b97f4a7c15ull;
    for (int j = 0; j < s->nj; j++)
        h = (h ^ (uint16_t)c[j]) * 0x100000001b3ull;
    return h;
}

/* Try to reach the goal from expanded state id (at q) by one straight segment. */
static void try_snap(search *s, int id, const double *q)
{
    const ara_problem *p = s->p;
    ara_state *st = &s->states.states[id];
    if (st->snap_tried || !(st->goal_dist <= p->snap_distance))
        return;
    st->snap_tried = 1;
    s->out->snaps_tried++;
    if (p->region) {
        uint64_t rng = coords_seed(s, ara_states_coords(&s->states, id));
        mpb_ik_options opt;
        mpb_ik_options_init(&opt);
        opt.max_attempts = 1;     /* from this state's joints only */
        if (mpb_goal_region_sample(p->robot, p->region, q, &opt, 1, &rng,
                                   s->qgoal) != 0)
            return;
        s->out->snaps_ik++;
    } else {
        memcpy(s->qgoal, p->goal_joints, (size_t)s->nj * sizeof *s->qgoal);
    }
    if (ara_motion_segment_collides(p->motion, q, s->qgoal))
        return;
    s->out->snaps_found++;
    found(s, id, s->qgoal, st->g + ara_motion_distance(p->motion, q, s->qgoal));
}

/* Returns 0, or an outcome that ends the search. */
static int expand(search *s, int id)
{
    const ara_problem *p = s->p;
    int nj = s->nj;
    s->out->expansions++;
    s->states.states[id].closed_iter = s->iter;
    memcpy(s->coords, ara_states_coords(&s->states, id),
           (size_t)nj * sizeof *s->coords);
    lattice_q(s, s->coords, s->q);
    if (s->states.states[id].goal_dist == 0.0)   /* inside the goal itself */
        found(s, id, s->q, s->states.states[id].g);
    try_snap(s, id, s->q);
    double g = s->states.states[id].g;
    for (int k = 0; k < s->num_prims; k++) {
        const prim *pr = &s->prims[k];
        int j = pr->joint;
        int c = s->coords[j] + pr->cells;
        if (c < INT16_MIN || c > INT16_MAX)
            continue;
        double v = p->start[j] + c * p->step;
        if (!within_limits(s, j, v))
            continue;
        double ng = g + pr->cost;
        s->coords[j] = (int16_t)c;
        int added, sid = ara_states_get(&s->states, s->coords, &added);
        s->coords[j] = (int16_t)(c - pr->cells);
        if (sid < 0)
            return ARA_STATE_LIMIT;
        ara_state *succ = &s->states.states[sid];
        if (succ->blocked || !(ng < succ->g))
            continue;
        memcpy(s->q2, s->q, (size_t)nj * sizeof *s->q2);
        s->q2[j] = v;
        if (added) {
            s->out->generated++;
            if (ara_motion_state_collides(p->motion, s->q2)) {
                succ->blocked = 1;
                continue;
            }
            double h, dist;
            if (evaluate(s, s->q2, &h, &dist) != 0) {
                succ->blocked = 1;
                continue;
            }
            succ->h = h;
            succ->goal_dist = dist;
        }
        /* Lazy: the motion's inside is checked when succ is popped, unless
           succ was ever expanded (children may rely on its parent). */
        int expanded = succ->closed_iter != 0;
        if (expanded && ara_motion_segment_collides(p->motion, s->q, s->q2))
            continue;     /* this edge only: the state may be reached otherwise */
        succ->edge_ok = (unsigned char)expanded;
        succ->g = ng;
        succ->parent = id;
        if (succ->closed_iter != s->iter) {
            if (open_push(s, sid) != 0)
                return ARA_NOMEM;
        } else if (push_incons(s, sid) != 0) {
            return ARA_NOMEM;
        }
    }
    return 0;
}

static int build_prims(search *s)
{
    int per = s->p->long_step > 1 ? 4 : 2;
    s->prims = malloc((size_t)(per * s->nj) * sizeof *s->prims);
    s->cands = malloc((size_t)(per * s->nj) * sizeof *s->cands);
    if (!s->prims || !s->cands)
        return -1;
    for (int j = 0; j < s->nj; j++) {
        const int cells[4] = {1, -1, s->p->long_step, -s->p->long_step};
        for (int k = 0; k < per; k++)
            s->prims[s->num_prims++] =
                (prim){j, cells[k], abs(cells[k]) * s->p->step};
    }
    return 0;
}

/* The path start .. goal_parent, then the snap target if it differs. */
static int extract(search *s)
{
    int n = 0;
    for (int id = s->goal_parent; id >= 0; id = s->states.states[id].parent)
        n++;
    int nj = s->nj;
    lattice_q(s, ara_states_coords(&s->states, s->goal_parent), s->q);
    int extra = memcmp(s->q, s->goal_q, (size_t)nj * sizeof *s->q) != 0;
    double *wp = malloc((size_t)(n + extra) * (size_t)nj * sizeof *wp);
    if (!wp)
        return -1;
    int i = n - 1;
    for (int id = s->goal_parent; id >= 0; id = s->states.states[id].parent)
        lattice_q(s, ara_states_coords(&s->states, id), wp + (size_t)(i--) * nj);
    if (extra)
        memcpy(wp + (size_t)n * nj, s->goal_q, (size_t)nj * sizeof *wp);
    free(s->out->waypoints);
    s->out->waypoints = wp;
    s->out->num_waypoints = n + extra;
    s->out->cost = s->goal_g;
    return 0;
}

/*
 * A popped state whose motion from its parent is not checked yet: check
 * it. 0 if free (expand the state). If not, the cheapest of its expanded
 * neighbours whose motion to it is free becomes its parent and the state
 * goes back into OPEN with that cost; with none, it waits, parentless,
 * until a later expansion reaches it. Then 1; ARA_NOMEM on failure.
 */
static int validate(search *s, int id)
{
    const ara_problem *p = s->p;
    ara_state *st = &s->states.states[id];
    if (st->edge_ok || st->parent < 0)
        return 0;
    lattice_q(s, ara_states_coords(&s->states, id), s->q2);
    lattice_q(s, ara_states_coords(&s->states, st->parent), s->q);
    if (!ara_motion_segment_collides(p->motion, s->q, s->q2)) {
        st->edge_ok = 1;
        return 0;
    }
    /* Candidates, one per primitive at most, sorted by cost then id. */
    int failed = st->parent, num = 0;
    memcpy(s->coords, ara_states_coords(&s->states, id),
           (size_t)s->nj * sizeof *s->coords);
    for (int k = 0; k < s->num_prims; k++) {
        const prim *pr = &s->prims[k];
        int c = s->coords[pr->joint] - pr->cells;
        if (c < INT16_MIN || c > INT16_MAX)
            continue;
        s->coords[pr->joint] = (int16_t)c;
        int n = ara_states_find(&s->states, s->coords);
        s->coords[pr->joint] = (int16_t)(c + pr->cells);
        if (n < 0 || n == failed)
            continue;
        const ara_state *ns = &s->states.states[n];
        /* Only expanded states whose own cost is checked. */
        if (ns->closed_iter == 0 || !(ns->edge_ok || ns->parent < 0) ||
            ns->g == INFINITY)
            continue;
        cand c_ = {ns->g + pr->cost, n};
        int i = num++;
        while (i > 0 && (s->cands[i - 1].g > c_.g ||
                         (s->cands[i - 1].g == c_.g && s->cands[i - 1].id > n))) {
            s->cands[i] = s->cands[i - 1];
            i--;
        }
        s->cands[i] = c_;
    }
    st->g = INFINITY;
    st->parent = -1;
    for (int i = 0; i < num; i++) {
        lattice_q(s, ara_states_coords(&s->states, s->cands[i].id), s->q);
        if (ara_motion_segment_collides(p->motion, s->q, s->q2))
            continue;
        st->g = s->cands[i].g;
        st->parent = s->cands[i].id;
        st->edge_ok = 1;
        return open_push(s, id) != 0 ? ARA_NOMEM : 1;
    }
    return 1;
}

/* One ARA* iteration (ImprovePath); 0 or an ending outcome. */
static int improve_path(search *s)
{
    const ara_problem *p = s->p;
    for (;;) {
        const ara_heap_item *top = ara_heap_top(&s->open);
        if (!top || !(top->f < s->goal_g))
            return top || s->goal_g < INFINITY ? 0 : ARA_NO_PATH;
        const mpb_solve_limits lim = {.deadline = p->deadline, .stop = p->stop};
        if (mpb_solve_should_stop(&lim))
            return ARA_TIMEOUT;
        ara_heap_item it = ara_heap_pop(&s->open);
        int rc = validate(s, it.id);
        if (rc == 0)
            rc = expand(s, it.id);
        else if (rc == 1)
            rc = 0;     /* re-queued with a checked parent, or dropped */
        if (rc != 0)
            return rc;
    }
}

/* Next iteration: OPEN gets INCONS, every key is recomputed with eps. */
static int next_iteration(search *s)
{
    int *ids = malloc((size_t)(s->open.size + s->num_incons + 1) * sizeof *ids);
    if (!ids)
        return -1;
    int n = 0;
    for (int i = 0; i < s->open.size; i++)
        ids[n++] = s->open.items[i].id;
    for (int i = 0; i < s->num_incons; i++) {
        s->states.states[s->incons[i]].in_incons = 0;
        if (!ara_heap_contains(&s->open, s->incons[i]))
            ids[n++] = s->incons[i];
    }
    s->num_incons = 0;
    ara_heap_clear(&s->open);
    s->iter++;
    int rc = 0;
    for (int i = 0; i < n && rc == 0; i++)
        rc = open_push(s, ids[i]);
    free(ids);
    return rc;
}

static void run(search *s)
{
    const ara_problem *p = s->p;
    ara_solution *out = s->out;
    int nj = s->nj;
    int16_t *zero = calloc((size_t)nj, sizeof *zero);
    if (!zero) {
        out->outcome = ARA_NOMEM;
        return;
    }
    int added, id = ara_states_get(&s->states, zero, &added);
    free(zero);
    if (id < 0) {
        out->outcome = ARA_NOMEM;
        return;
    }
    ara_state *st = &s->states.states[id];
    double h, dist;
    if (!mpb_robot_within_limits(p->robot, p->start) ||
        ara_motion_state_collides(p->motion, p->start) ||
        evaluate(s, p->start, &h, &dist) != 0) {
        out->outcome = ARA_START_INVALID;
        return;
    }
    st->g = 0.0;
    st->h = h;
    st->goal_dist = dist;
    out->generated = 1;
    if (open_push(s, id) != 0) {
        out->outcome = ARA_NOMEM;
        return;
    }
    int rc;
    for (;;) {
        out->iterations++;
        rc = improve_path(s);
        if (rc != 0 || s->goal_g == INFINITY || !p->improve || s->eps <= 1.0)
            break;
        if (extract(s) != 0) {
            rc = ARA_NOMEM;
            break;
        }
        s->eps = fmax(1.0, s->eps * p->epsilon_decay);
        if (next_iteration(s) != 0) {
            rc = ARA_NOMEM;
            break;
        }
    }
    /* An anytime search interrupted after its first solution still solved. */
    if (s->goal_g < INFINITY) {
        out->outcome = extract(s) == 0 ? ARA_SOLVED : ARA_NOMEM;
        return;
    }
    out->outcome = rc != 0 ? (ara_outcome)rc : ARA_NO_PATH;
}

void ara_search(const ara_problem *p, ara_solution *out)
{
    memset(out, 0, sizeof *out);
    search s;
    memset(&s, 0, sizeof s);
    s.p = p;
    s.out = out;
    s.nj = p->motion->num_joints;
    s.eps = p->epsilon;
    s.iter = 1;
    s.goal_g = INFINITY;
    s.goal_parent = -1;
    s.t0 = mpb_monotonic_s();
    s.wraps = p->motion->wraps;
    ara_heap_init(&s.open);
    size_t nj = (size_t)s.nj;
    s.lo = malloc(nj * sizeof *s.lo);
    s.hi = malloc(nj * sizeof *s.hi);
    s.q = malloc(nj * sizeof *s.q);
    s.q2 = malloc(nj * sizeof *s.q2);
    s.qgoal = malloc(nj * sizeof *s.qgoal);
    s.goal_q = malloc(nj * sizeof *s.goal_q);
    s.coords = malloc(nj * sizeof *s.coords);
    if (!s.lo || !s.hi || !s.q || !s.q2 || !s.qgoal || !s.goal_q ||
        !s.coords || build_prims(&s) != 0 ||
        ara_states_init(&s.states, s.nj, p->max_states) != 0) {
        out->outcome = ARA_NOMEM;
    } else {
        for (int j = 0; j < s.nj; j++)
            mpb_world_joint_limits(p->motion->world, j, &s.lo[j], &s.hi[j]);
        run(&s);
    }
    ara_states_free(&s.states);
    ara_heap_free(&s.open);
    free(s.incons);
    free(s.prims);
    free(s.cands);
    free(s.lo);
    free(s.hi);
    free(s.q);
    free(s.q2);
    free(s.qgoal);
    free(s.goal_q);
    free(s.coords);
}
