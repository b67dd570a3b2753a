/*
 * collision_narrow.cpp - the collision world's narrow phase: FCL (and
 * bvh_collide.h for two meshes) on the pairs the tree and the bounds
 * leave, for collision and distance; nearest points; self pairs.
 */
#include "geometry/collision_world.h"
#include "geometry/bvh_collide.h"
#include "geometry/bvh_distance.h"

namespace mpb {
namespace coll {

bool allowed_static(const Movable *m, int static_id)
{
    for (int s : m->allowed_statics)
        if (s == static_id)
            return true;
    return false;
}

/* FCL's distance of a pair, never negative; or `below` if it is at
 * least that: FCL keeps only what is nearer than its result holds, so
 * started at `below` it skips every part of a mesh that far or further. */
double pair_distance(mpb_collision *c, const Obj *a, const Obj *b, double below)
{
    c->dres.clear();
    c->dres.min_distance = below;
    double d = fcl::distance(a, b, c->dreq, c->dres);
    return d < 0 ? 0.0 : std::min(d, below);
}

/*
 * The distance of movable shape ms and static ss, or `below` if it is at
 * least that: FCL's, through bvh_shape_distance() for a mesh against a
 * primitive (FCL's answer for a fraction of the cost), else through
 * fcl::distance. upper, a bound from above on their distance
 * (mesh_static_lower()), lowers the cutoff to just above it, so that
 * only the parts of the mesh that may be that near are measured. The
 * answer stays FCL's: what is skipped is at least the cutoff away, and
 * something nearer was found; should nothing be (the solver a hair above
 * the bound), it is measured again with `below` alone. upper_vertex, the
 * vertex of ms (an index in ms.verts) at `upper`, or -1: should it be
 * provably the nearest (mesh_static_vertex()), its distance is the
 * answer, with no triangle measured.
 */
double pair_distance_upper(mpb_collision *c, const Shape &ms, const Shape &ss,
                           double below, double upper, int upper_vertex)
{
    if (upper_vertex >= 0) {
        double d = mesh_static_vertex(ms, ss, upper_vertex);
        if (!std::isnan(d))
            return std::min(d, below);
    }
    sync(ms);
    double cut = upper + 1e-7 * (1.0 + upper);
    bool mesh = ms.type == MPB_SHAPE_MESH && ss.type != MPB_SHAPE_MESH;
    for (int pass = cut < below ? 0 : 1; pass < 2; pass++) {
        double lim = pass == 0 ? cut : below, d = NAN;
        if (mesh) {
            sync(ss);
            const BvhHull hull = {ms.verts, ms.num_verts, ms.dirs, ms.vtri_start,
                                  ms.vtris, upper_vertex};
            d = bvh_shape_distance(
                *static_cast<const BvhObbRss *>(ms.obj->collisionGeometry().get()),
                ms.obj->getTransform(), *ss.obj->collisionGeometry(),
                ss.obj->getTransform(), ss.lbox_c, ss.lbox_h,
                c->dreq.distance_tolerance, lim, c->bvh_heap,
                ms.num_verts > 0 ? &hull : nullptr);
            d = d < 0 ? 0.0 : d;
        }
        if (std::isnan(d))
            d = pair_distance(c, ms.obj.get(), ss.obj.get(), lim);
        if (d < lim || pass == 1)
            return d;
    }
    return below;
}

/* Do shapes a and b (synced) collide? Two meshes through bvh_collide(),
 * FCL's verdict for less; anything else through fcl::collide. */
bool narrow_phase(mpb_collision *c, const Shape &a, const Shape &b)
{
    if (a.type == MPB_SHAPE_MESH && b.type == MPB_SHAPE_MESH) {
        int hit = mpb::bvh_collide(
            *static_cast<const mpb::BvhObbRss *>(a.obj->collisionGeometry().get()),
            a.obj->getTransform(),
            *static_cast<const mpb::BvhObbRss *>(b.obj->collisionGeometry().get()),
            b.obj->getTransform());
        if (hit >= 0)
            return hit == 1;
    }
    c->cres.clear();
    fcl::collide(a.obj.get(), b.obj.get(), c->creq, c->cres);
    return c->cres.isCollision();
}

/* Does movable shape ms (of body m) collide with the static of leaf i
 * (allowed pairs never)? FCL's narrow phase if their boxes overlap. */
bool leaf_hit(mpb_collision *c, const Movable &m, const Shape &ms, int i)
{
    const Leaf &l = c->leaves[(size_t)i];
    if (!overlap(l.box, ms.box) || allowed_static(&m, l.body))
        return false;
    const Shape &ss = c->sshapes[(size_t)l.shape];
    if ((ms.has_cap && cap_misses_static(ms, ss)) ||
        (ms.num_verts > 0 && mesh_static_lower(ms, ss, 0, false) > 0))
        return false;
    sync(ms);
    return narrow_phase(c, ms, ss);
}

/*
 * The first static that movable shape ms (of body m) collides with,
 * allowed pairs excepted: FCL's narrow phase on every static whose AABB
 * overlaps ms's; from c->cand if `among`, else from the whole tree. Its
 * body id, or -1 if none.
 */
int static_hit(mpb_collision *c, const Movable &m, const Shape &ms, bool among)
{
    if (among) {
        for (int i : c->cand)
            if (leaf_hit(c, m, ms, i))
                return c->leaves[(size_t)i].body;
        return -1;
    }
    if (c->nodes.empty())
        return -1;
    int stack[MPB__STACK], sp = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        const BNode &n = c->nodes[(size_t)stack[--sp]];
        if (!overlap(n.box, ms.box))
            continue;
        if (n.left >= 0) {
            stack[sp++] = n.right;
            stack[sp++] = n.left;
            continue;
        }
        for (int i = n.first; i < n.first + n.count; i++)
            if (leaf_hit(c, m, ms, i))
                return c->leaves[(size_t)i].body;
    }
    return -1;
}

/* Measure movable shape ms (of body q->m) against the static of leaf i,
 * unless the boxes, the bounding spheres, the seed pair or an allowed
 * pair rule it out; lower q->best if nearer. */
void leaf_distance(Query *q, const Shape &ms, int i)
{
    mpb_collision *c = q->c;
    const Leaf &l = c->leaves[(size_t)i];
    /* boxes and bounding spheres: lower bounds for almost nothing */
    if (!(box_dist2(l.box, ms.box) < q->best * q->best))
        return;
    double dx = ms.wcenter[0] - l.center[0], dy = ms.wcenter[1] - l.center[1],
           dz = ms.wcenter[2] - l.center[2];
    double lower = std::sqrt(dx * dx + dy * dy + dz * dz) - ms.bradius - l.radius;
    const Obj *st = c->sshapes[(size_t)l.shape].obj.get();
    if (!(lower < q->best) || (ms.obj.get() == q->seed_m && st == q->seed_s) ||
        allowed_static(q->m, l.body))
        return;
    const Shape &ss = c->sshapes[(size_t)l.shape];
    if (ms.has_cap && !(cap_static_lower(ms, ss) < q->best))
        return;
    double upper = INFINITY;
    int uv = -1;
    if (ms.num_verts > 0 &&
        !(mesh_static_lower(ms, ss, q->best, true, &upper, &uv) < q->best))
        return;
    double d = pair_distance_upper(c, ms, ss, q->best, upper, uv);
    if (d < q->best) {
        q->best = d;
        q->best_m = ms.obj.get();
        q->best_s = st;
        q->static_id = l.body;
    }
}

/*
 * Lower q->best to the distance from movable shape ms (of body q->m) to
 * the statics, allowed pairs and the seed pair excepted: FCL's distance on
 * every static that the AABBs and the bounding spheres cannot rule out;
 * from c->cand if `among`, else from the tree, nearer subtrees first.
 * Stops at 0.
 */
void static_distance(Query *q, const Shape &ms, bool among)
{
    mpb_collision *c = q->c;
    if (among) {
        for (size_t k = 0; k < c->cand.size() && q->best > 0.0; k++)
            leaf_distance(q, ms, c->cand[k]);
        return;
    }
    if (c->nodes.empty())
        return;
    int stack[MPB__STACK], sp = 0;
    stack[sp++] = 0;
    while (sp > 0 && q->best > 0.0) {
        const BNode &n = c->nodes[(size_t)stack[--sp]];
        if (!(box_dist2(n.box, ms.box) < q->best * q->best))
            continue;
        if (n.left >= 0) {
            double dl = box_dist2(c->nodes[(size_t)n.left].box, ms.box);
            double dr = box_dist2(c->nodes[(size_t)n.right].box, ms.box);
            stack[sp++] = dl <= dr ? n.right : n.left;   /* nearer on top */
            stack[sp++] = dl <= dr ? n.left : n.right;
            continue;
        }
        for (int i = n.first; i < n.first + n.count && q->best > 0.0; i++)
            leaf_distance(q, ms, i);
    }
}

/*
 * The nearest points of the pair (a, b), world frame, into pa and pb;
 * false if FCL's answer does not hold together.
 */
bool nearest_points(mpb_collision *c, const Obj *a, const Obj *b, double dist,
                    fcl::Vector3d &pa, fcl::Vector3d &pb)
{
    /* FCL answers a (shape, mesh) pair as (mesh, shape). */
    bool swap = !is_bvh(a) && is_bvh(b);
    const Obj *first = swap ? b : a, *second = swap ? a : b;
    c->dreq.enable_nearest_points = true;
    c->dres.clear();
    fcl::distance(first, second, c->dreq, c->dres);
    c->dreq.enable_nearest_points = false;
    fcl::Vector3d p1 = c->dres.nearest_points[0], p2 = c->dres.nearest_points[1];
    double tol = 1e-6 * (1.0 + dist);
    if (std::fabs((p1 - p2).norm() - dist) > tol) {
        /* sphere-mesh pairs answer in the two local frames */
        p1 = first->getTransform() * p1;
        p2 = second->getTransform() * p2;
        if (std::fabs((p1 - p2).norm() - dist) > tol)
            return false;
    }
    pa = swap ? p2 : p1;
    pb = swap ? p1 : p2;
    return true;
}

/* Do movable bodies mi and mj touch? Their boxes, then each pair of
 * shapes whose boxes overlap and whose bounding spheres meet, through
 * the narrow phase. */
bool bodies_touch(mpb_collision *c, const Movable &mi, const Movable &mj)
{
    if (!overlap(mi.box, mj.box))
        return false;
    for (int si : mi.shapes) {
        const Shape &shi = c->mshapes[(size_t)si];
        for (int sj : mj.shapes) {
            const Shape &shj = c->mshapes[(size_t)sj];
            if (!overlap(shi.box, shj.box) || spheres_apart(shi, shj) ||
                (shi.has_cap && caps_apart(shi, shj)) ||
                (shj.has_cap && caps_apart(shj, shi)) ||
                (shi.num_verts > 0 && shj.num_verts > 0 && meshes_apart(shi, shj)))
                continue;
            sync(shi);
            sync(shj);
            if (narrow_phase(c, shi, shj))
                return true;
        }
    }
    return false;
}

/* Did the caller prove movables i < j apart where they stand now? */
bool hinted_apart(const mpb_collision *c, int i, int j)
{
    for (const mpb_collision::Hint &h : c->hints)
        if (h.i == i && h.j == j)
            return h.pi == c->movables[(size_t)i].placed &&
                   h.pj == c->movables[(size_t)j].placed;
    return false;
}

/* FCL's distance between movables mi and mj, or `below` if it is at
 * least that (FCL then skips what is further). */
double movables_distance(mpb_collision *c, const Movable &mi, const Movable &mj,
                         double below)
{
    double best = below;
    if (box_dist2(mi.box, mj.box) >= below * below)
        return below;
    for (int si : mi.shapes)
        for (int sj : mj.shapes) {
            const Shape &x = c->mshapes[(size_t)si], &y = c->mshapes[(size_t)sj];
            if (box_dist2(x.box, y.box) >= best * best)
                continue;
            sync(x);
            sync(y);
            /* FCL keeps only what is nearer than the result holds:
             * started at the best so far, it skips the rest. */
            c->dres.clear();
            c->dres.min_distance = best;
            double d = fcl::distance(x.obj.get(), y.obj.get(), c->dreq, c->dres);
            best = std::min(best, d < 0 ? 0.0 : d);
            if (best <= 0)
                return 0.0;
        }
    return best;
}

/* c->self_pairs made again if the allowed pairs changed. */
void ensure_self_pairs(mpb_collision *c)
{
    if (!c->pairs_dirty)
        return;
    size_t n = c->movables.size();
    c->self_pairs.clear();
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++)
            if (!c->is_allowed(i, j))
                c->self_pairs.emplace_back((int)i, (int)j);
    c->pairs_dirty = false;
}

} // namespace coll
} // namespace mpb
