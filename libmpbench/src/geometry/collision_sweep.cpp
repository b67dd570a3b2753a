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
 *
 * Chained (mpb__collision_sweep_step()): a lower bound per pair (movable
 * shape against one static; two movables) is kept from step to step and
 * lowered by rate x s moved; only a pair whose bound no longer covers the
 * step is measured, cheap bounds first (boxes, spheres, capsules, a mesh's
 * vertex hull against a static's box), FCL's distance only when those
 * fall short of a tenth of what the step wants or under 1 mm. Any lower
 * bound proves; a looser one only shortens the step.
 */
#include "geometry/collision_world.h"
#include "geometry/collision_internal.h"

#include <cstring>
#include <limits>


/* A cheap lower bound that is at least this part of what a step wants
 * stands in for FCL's distance, unless it is under MPB__SWEEP_NEAR (m):
 * near contact a loose bound would make the steps too short. */
#define MPB__SWEEP_ENOUGH 0.1
#define MPB__SWEEP_NEAR 1e-3
/* Taken off a gap between vertex hulls: the rounding of the dot products
 * (m), as collision_bounds.cpp's MPB__CAP_MARGIN. */
#define MPB__HULL_MARGIN 1e-4

namespace mpb {
namespace coll {
/* collision_bounds.cpp: the squared distance between segments p0 p1 and
 * q0 q1 (not in collision_world.h). */
double seg_seg_dist2(const double p0[3], const double p1[3], const double q0[3],
                     const double q1[3]);
namespace {

/* The rate of movable index i (0 for an id past the caller's array). */
double rate_of(const mpb_collision *c, size_t i, const double *rate, int n)
{
    int id = c->movables[i].id;
    return id < n ? rate[id] : 0.0;
}

/* A lower bound on the distance from movable shape ms to the static of
 * leaf l, cheap ones first: the boxes, the bounding spheres, the mesh's
 * vertices or capsule against the static's box; FCL's distance (stopped
 * at `below`: FCL skips what is further) only when those say less than
 * `need`. */
double leaf_lower(mpb_collision *c, const Shape &ms, const Leaf &l, double need,
                  double below)
{
    double lb = std::sqrt(box_dist2(l.box, ms.box));
    double dx = ms.wcenter[0] - l.center[0], dy = ms.wcenter[1] - l.center[1],
           dz = ms.wcenter[2] - l.center[2];
    lb = std::max(lb, std::sqrt(dx * dx + dy * dy + dz * dz) - ms.bradius - l.radius);
    if (lb >= need)
        return lb;
    const Shape &ss = c->sshapes[(size_t)l.shape];
    double upper = INFINITY;
    if (ms.verts) {
        lb = std::max(lb, mesh_static_lower(ms, ss, need, true, &upper));
        /* good enough, if not what the step wants: a step a little
           shorter costs less than FCL's distance on the mesh */
        if (lb >= need * MPB__SWEEP_ENOUGH && lb > MPB__SWEEP_NEAR)
            return lb;
    } else if (ms.has_cap) {
        lb = std::max(lb, cap_static_lower(ms, ss));
        if (lb >= need)
            return lb;
    }
    double d = pair_distance_upper(c, ms, ss, below, upper);
    return std::max(lb, std::min(below, d));
}

/* A lower bound on the distance between movables mi and mj: each pair
 * of their shapes by boxes, bounding spheres and capsules (meshes), FCL's
 * distance (stopped at below) only if those say less than enough of need
 * for some pair. */
double movables_lower(mpb_collision *c, const Movable &mi, const Movable &mj,
                      double need, double below)
{
    double lb = std::sqrt(box_dist2(mi.box, mj.box));
    if (lb >= need)
        return lb;
    double low = INFINITY;
    for (int si : mi.shapes)
        for (int sj : mj.shapes) {
            const Shape &x = c->mshapes[(size_t)si], &y = c->mshapes[(size_t)sj];
            double b = std::sqrt(box_dist2(x.box, y.box));
            double dx = x.wcenter[0] - y.wcenter[0], dy = x.wcenter[1] - y.wcenter[1],
                   dz = x.wcenter[2] - y.wcenter[2];
            b = std::max(b, std::sqrt(dx * dx + dy * dy + dz * dz) - x.bradius - y.bradius);
            if (x.has_cap && y.has_cap && b < need)
                b = std::max(b, std::sqrt(seg_seg_dist2(x.wcap[0], x.wcap[1], y.wcap[0],
                                                        y.wcap[1])) - x.cap_r - y.cap_r);
            if (x.verts && y.verts && b < need)
                b = std::max(b, meshes_gap(x, y, need) - MPB__HULL_MARGIN);
            low = std::min(low, b);
        }
    lb = std::max(lb, low);
    if (lb >= need * MPB__SWEEP_ENOUGH && lb > MPB__SWEEP_NEAR)
        return lb;
    return std::max(lb, movables_distance(c, mi, mj, below));
}

} // namespace
} // namespace coll
} // namespace mpb

/*
 * What a chain of steps knows (mpb__collision_sweep_step()): for each
 * pair, a lower bound on its distance where the robot stands now, and
 * the rates of approach the last step's motion had, to lower the bounds
 * by what that motion may have closed.
 */
struct mpb__sweep {
    const mpb_collision *c = nullptr;   /* the bounds hold for this world */
    size_t               ns = 0, nt = 0, np = 0;  /* and these sizes */
    /* movable shape x (leaves, planes): a lower bound as measured, and
     * its body's closing (cum) when measured: it holds now less what the
     * body has closed since, cum - stat_at. One number a body, not one a
     * pair, is lowered at each step, so that a step costs what the pairs
     * near the robot cost, not what every static does. */
    std::vector<double>  stat, stat_at;
    std::vector<double>  cum;      /* by movable index: rate x s, summed */
    std::vector<double>  self;     /* by self pair */
    std::vector<double>  mrate;    /* last rate by movable index */
    std::vector<double>  prate;    /* last rate by self pair */
    std::vector<int>     near;     /* a shape's leaves near enough to ask */
    bool                 known = false;
    long                 measured = 0, skipped = 0;  /* counters, tests */
    void                *user = nullptr;   /* the caller's (mpb__sweep_user) */
    void               (*user_free)(void *) = nullptr;
    ~mpb__sweep() { if (user_free) user_free(user); }
};

using namespace mpb::coll;

namespace {

/* Forget every bound (a new chain, or a changed world). */
void sweep_reset(mpb__sweep *st, const mpb_collision *c)
{
    st->c = c;
    st->ns = c->mshapes.size();
    st->nt = c->leaves.size() + c->planes.size();
    st->np = c->self_pairs.size();
    st->stat.assign(st->ns * st->nt, -1.0);
    st->stat_at.assign(st->ns * st->nt, 0.0);
    st->cum.assign(c->movables.size(), 0.0);
    st->self.assign(st->np, -1.0);
    st->mrate.assign(c->movables.size(), 0.0);
    st->prate.assign(st->np, 0.0);
    st->known = true;
}

/* What the last motion, moved units of s at the last rates, may have
 * closed: each body's closing grows by its rate x moved (the bounds of
 * its shapes are lowered by it when read), each self pair's bound by
 * its own. */
void sweep_decay(mpb__sweep *st, double moved)
{
    if (!(moved > 0))
        return;
    for (size_t i = 0; i < st->cum.size(); i++)
        st->cum[i] += st->mrate[i] * moved;
    for (size_t k = 0; k < st->np; k++)
        st->self[k] -= st->prate[k] * moved;
}

/* The bound of shape si's pair t now, and where it is kept. */
struct pair_bound {
    double *b, *at;
    double now(double cum) const { return *b - (cum - *at); }
};

pair_bound bound_of(mpb__sweep *st, size_t si, size_t t)
{
    return {st->stat.data() + si * st->nt + t, st->stat_at.data() + si * st->nt + t};
}

} // namespace

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

int mpb__collision_body_bounds(mpb_collision *c, int id, mpb__body_bound *out,
                               int max)
{
    Movable *m = c ? c->find(id) : nullptr;
    if (!m || max < 0 || (max > 0 && !out))
        return -1;
    int n = 0;
    for (int si : m->shapes) {
        if (n < max) {
            const Shape &s = c->mshapes[(size_t)si];
            mpb__body_bound &b = out[n];
            double bc[3] = { s.bcenter[0], s.bcenter[1], s.bcenter[2] };
            mpb_pose_apply(&s.offset, bc, b.centre);
            b.radius = s.bradius;
            b.cap_radius = s.has_cap ? s.cap_r : -1.0;
            for (int e = 0; e < 2; e++)
                if (s.has_cap)
                    mpb_pose_apply(&s.offset, s.cap[e], b.cap[e]);
                else
                    memcpy(b.cap[e], b.centre, sizeof b.centre);
        }
        n++;
    }
    return n;
}

void *mpb__sweep_user(const mpb__sweep *st)
{
    return st ? st->user : nullptr;
}

void mpb__sweep_set_user(mpb__sweep *st, void *user, void (*user_free)(void *))
{
    if (st->user_free)
        st->user_free(st->user);
    st->user = user;
    st->user_free = user_free;
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
    mpb__sweep st;              /* a chain of one step */
    return mpb__collision_sweep_step(c, &st, -1.0, rate, num_rates, pair_rate, ud,
                                     margin, want, step);
}

mpb__sweep *mpb__sweep_new(void)
{
    return new (std::nothrow) mpb__sweep();
}

void mpb__sweep_free(mpb__sweep *st)
{
    delete st;
}

void mpb__sweep_counts(const mpb__sweep *st, long *measured, long *skipped)
{
    *measured = st ? st->measured : 0;
    *skipped = st ? st->skipped : 0;
}

int mpb__collision_sweep_step(mpb_collision *c, mpb__sweep *st, double moved,
                              const double *rate, int num_rates,
                              double (*pair_rate)(void *ud, int a, int b),
                              void *ud, double margin, double want,
                              double *step)
{
    if (!st)
        return mpb__collision_safe_step_pairs(c, rate, num_rates, pair_rate, ud,
                                              margin, want, step);
    if (!c || !step || (num_rates > 0 && !rate) || !(margin >= 0) || !(want > 0))
        return MPB_EINVAL;
    *step = 0.0;
    for (int i = 0; i < num_rates; i++)
        if (!(rate[i] >= 0) || !std::isfinite(rate[i]))
            return MPB_EINVAL;
    double best = want;         /* the step found so far: s units */
    int rc = guarded(c, [&]() -> int {
        bool fresh = !(moved >= 0) || !st->known || st->c != c || c->dirty ||
                     c->pairs_dirty;
        int rc2 = ensure_tree(c);
        if (rc2 != MPB_OK)
            return rc2;
        ensure_self_pairs(c);
        if (fresh || st->ns != c->mshapes.size() ||
            st->nt != c->leaves.size() + c->planes.size() ||
            st->np != c->self_pairs.size() || st->mrate.size() != c->movables.size())
            sweep_reset(st, c);
        else
            sweep_decay(st, moved);
        /* Until the step is found the rates are set to 0: an error below
           leaves bounds that no decay may trust, so forget them. */
        st->known = false;
        size_t n = c->movables.size(), nl = c->leaves.size();
        /* the movables against the statics, shape by static: the leaves
           near enough to be reached by the longest step asked for (the
           static tree's boxes; every other one is further than any step
           this shape may take), then the planes */
        for (size_t i = 0; i < n; i++) {
            const Movable &m = c->movables[i];
            double r = rate_of(c, i, rate, num_rates);
            st->mrate[i] = 0.0;
            if (!m.enabled || m.self_only || m.shapes.empty() || !(r > 0))
                continue;
            st->mrate[i] = r;
            double cum = st->cum[i];
            for (int si : m.shapes) {
                const Shape &ms = c->mshapes[(size_t)si];
                gather_near(c, ms.box, want * r + margin);
                /* leaf_lower() may gather for itself */
                st->near.assign(c->cand.begin(), c->cand.end());
                st->skipped += (long)(nl - st->near.size());
                size_t nn = st->near.size(), np_ = c->planes.size();
                for (size_t k = 0; k < nn + np_; k++) {
                    size_t t = k < nn ? (size_t)st->near[k] : nl + (k - nn);
                    pair_bound pb = bound_of(st, (size_t)si, t);
                    double need = best * r + margin;
                    if (pb.now(cum) >= need) {
                        st->skipped++;
                        continue;
                    }
                    int body = t < nl ? c->leaves[t].body : c->planes[t - nl].id;
                    if (allowed_static(&m, body)) {
                        *pb.b = INFINITY;   /* never measured again */
                        continue;
                    }
                    st->measured++;
                    /* a bound to last: twice what this step needs */
                    double below = 2 * need + 0.02;
                    *pb.b = t < nl ? leaf_lower(c, ms, c->leaves[t], need, below)
                                   : plane_distance(ms, c->planes[t - nl], nullptr,
                                                    nullptr);
                    *pb.at = cum;
                    best = std::min(best, std::max(0.0, (*pb.b - margin) / r));
                }
            }
        }
        /* the pairs of movables that may not touch, as in
           mpb__collision_check_self() */
        for (size_t k = 0; k < c->self_pairs.size(); k++) {
            size_t i = (size_t)c->self_pairs[k].first, j = (size_t)c->self_pairs[k].second;
            const Movable &mi = c->movables[i], &mj = c->movables[j];
            double r = rate_of(c, i, rate, num_rates) + rate_of(c, j, rate, num_rates);
            st->prate[k] = 0.0;
            if (!mi.enabled || !mj.enabled || !(r > 0))
                continue;
            if (pair_rate) {
                r = pair_rate(ud, mi.id, mj.id);
                if (!(r >= 0) || !std::isfinite(r))
                    return MPB_EINVAL;
                if (!(r > 0))
                    continue;   /* they move as one: their distance stays */
            }
            st->prate[k] = r;
            double need = best * r + margin;
            if (st->self[k] >= need) {
                st->skipped++;
                continue;
            }
            st->measured++;
            double lb = movables_lower(c, mi, mj, need, 2 * need + 0.02);
            st->self[k] = lb;
            best = std::min(best, std::max(0.0, (lb - margin) / r));
        }
        st->known = true;
        *step = best;
        return MPB_OK;
    });
    if (rc != MPB_OK)
        st->known = false;
    return rc;
}

} // extern "C"
