/*
 * collision_sweep.cpp - what certified verification (verify/certify.c)
 * asks of the collision world: how far each movable body reaches from its
 * own frame, and the largest step along a motion that no checked pair can
 * close, given how fast each body may move (conservative advancement).
 *
 * The step: for every pair the checks of collision.h test (a movable
 * against the statics, allowed statics excepted; two movables not allowed
 * to touch), with d a lower bound on its distance now and r an upper
 * bound on how fast the two may approach (rate[a], or rate[a] + rate[b]),
 * neither can touch the other while s advances by less than
 * (d - margin) / r. The margin covers FCL's distance error (GJK stops at
 * 1e-10, measured below 5e-7 m; collision_fcl.cpp). Pairs that cannot
 * approach (r = 0: neither body moves) keep the distance they have, which
 * the caller's check of the start already judged.
 */
#include "geometry/collision_world.h"
#include "geometry/collision_internal.h"

#include <limits>

namespace mpb {
namespace coll {
namespace {

/* The rate of movable index i (0 for an id past the caller's array). */
double rate_of(const mpb_collision *c, size_t i, const double *rate, int n)
{
    int id = c->movables[i].id;
    return id < n ? rate[id] : 0.0;
}

/* The distance from movable m to the statics it may not touch, or
 * `below` if it is at least that. */
double static_gap(mpb_collision *c, const Movable &m, double below)
{
    Query q = {};
    q.c = c;
    q.m = &m;
    q.best = below;
    q.static_id = -1;
    for (int si : m.shapes) {
        const Shape &ms = c->mshapes[(size_t)si];
        static_distance(&q, ms, false);
        for (const Plane &p : c->planes)
            if (!allowed_static(&m, p.id))
                q.best = std::min(q.best, plane_distance(ms, p, nullptr, nullptr));
        if (q.best <= 0)
            return 0.0;
    }
    return q.best;
}

} // namespace
} // namespace coll
} // namespace mpb

using namespace mpb::coll;

extern "C" {

double mpb__collision_body_reach(mpb_collision *c, int id)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    Movable *m = c ? c->find(id) : nullptr;
    if (!m)
        return nan;
    double reach = 0.0;
    for (int si : m->shapes) {
        const Shape &s = c->mshapes[(size_t)si];
        /* the bounding sphere's centre in the body's frame */
        double bc[3] = { s.bcenter[0], s.bcenter[1], s.bcenter[2] }, w[3];
        mpb_pose_apply(&s.offset, bc, w);
        reach = std::max(reach, std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]) +
                                    s.bradius);
    }
    return reach;
}

int mpb__collision_safe_step(mpb_collision *c, const double *rate, int num_rates,
                             double margin, double want, double *step)
{
    return mpb__collision_safe_step_pairs(c, rate, num_rates, nullptr, nullptr,
                                          margin, want, step);
}

int mpb__collision_safe_step_pairs(mpb_collision *c, const double *rate,
                                   int num_rates, double (*pair_rate)(void *ud,
                                   int a, int b), void *ud, double margin,
                                   double want, double *step)
{
    if (!c || !step || (num_rates > 0 && !rate) || !(margin >= 0) || !(want > 0))
        return MPB_EINVAL;
    *step = 0.0;
    for (int i = 0; i < num_rates; i++)
        if (!(rate[i] >= 0) || !std::isfinite(rate[i]))
            return MPB_EINVAL;
    double best = want;         /* the step found so far: s units */
    return guarded(c, [&]() -> int {
        int rc = ensure_tree(c);
        if (rc != MPB_OK)
            return rc;
        size_t n = c->movables.size();
        /* the movables against the statics */
        for (size_t i = 0; i < n && best > 0; i++) {
            const Movable &m = c->movables[i];
            double r = rate_of(c, i, rate, num_rates);
            if (!m.enabled || m.self_only || m.shapes.empty() || !(r > 0))
                continue;
            double d = static_gap(c, m, best * r + margin);
            best = std::min(best, std::max(0.0, (d - margin) / r));
        }
        /* the pairs of movables that may not touch, as in
           mpb_collision_check_self() */
        ensure_self_pairs(c);
        for (size_t k = 0; k < c->self_pairs.size() && best > 0; k++) {
            size_t i = (size_t)c->self_pairs[k].first, j = (size_t)c->self_pairs[k].second;
            const Movable &mi = c->movables[i], &mj = c->movables[j];
            double r = rate_of(c, i, rate, num_rates) + rate_of(c, j, rate, num_rates);
            if (!mi.enabled || !mj.enabled || !(r > 0))
                continue;
            if (pair_rate) {
                r = pair_rate(ud, mi.id, mj.id);
                if (!(r >= 0) || !std::isfinite(r))
                    return MPB_EINVAL;
                if (!(r > 0))
                    continue;   /* they move as one: their distance stays */
            }
            double d = movables_distance(c, mi, mj, best * r + margin);
            best = std::min(best, std::max(0.0, (d - margin) / r));
        }
        *step = best;
        return MPB_OK;
    });
}

} // extern "C"
