/*
 * collision_reference.cpp - test support: the slow reference answers of
 * collision_internal.h (every pair through FCL's narrow phase, no tree,
 * no boxes, no bounds) and the mesh probes the tests check the fast
 * queries against. Linked only into the tests, never into libmpbench.
 */
#include "geometry/collision_world.h"
#include "geometry/bvh_collide.h"
#include "geometry/collision_internal.h"

#include <limits>

using namespace mpb::coll;

extern "C" {

int mpb__mesh_pair_collide(mpb_collision *c, int a, const mpb_pose *pa, int b,
                           const mpb_pose *pb, int reference)
{
    if (!c || !pa || !pb || a < 0 || b < 0 || a >= (int)c->mshapes.size() ||
        b >= (int)c->mshapes.size() || !finite_pose(pa) || !finite_pose(pb))
        return MPB_EINVAL;
    const Shape &sa = c->mshapes[(size_t)a], &sb = c->mshapes[(size_t)b];
    if (sa.type != MPB_SHAPE_MESH || sb.type != MPB_SHAPE_MESH)
        return MPB_EUNSUPPORTED;
    return guarded(c, [&]() -> int {
        const Geom *ga = sa.obj->collisionGeometry().get();
        const Geom *gb = sb.obj->collisionGeometry().get();
        const fcl::Transform3d ta = to_tf(pa), tb = to_tf(pb);
        if (!reference) {
            int hit = mpb::bvh_collide(*static_cast<const mpb::BvhObbRss *>(ga), ta,
                                       *static_cast<const mpb::BvhObbRss *>(gb), tb);
            return hit >= 0 ? hit : MPB_EUNSUPPORTED;
        }
        fcl::CollisionResultd res;
        fcl::collide(ga, ta, gb, tb, c->creq, res);
        return res.isCollision() ? 1 : 0;
    });
}

/*
 * The references of collision_internal.h: every pair through FCL's narrow
 * phase, no tree, no boxes, no bounds.
 */
int mpb__collision_check_brute(mpb_collision *c)
{
    if (!c)
        return MPB_EINVAL;
    return guarded(c, [&]() -> int {
        for (const Shape &ms : c->mshapes)
            sync(ms);
        size_t n = c->movables.size();
        for (size_t i = 0; i < n; i++) {
            const Movable &m = c->movables[i];
            if (!m.enabled)
                continue;
            for (size_t k = 0; !m.self_only && k < m.shapes.size(); k++) {
                const Shape &ms = c->mshapes[(size_t)m.shapes[k]];
                for (const Shape &ss : c->sshapes) {
                    if (allowed_static(&m, ss.body))
                        continue;
                    c->cres.clear();
                    fcl::collide(ms.obj.get(), ss.obj.get(), c->creq, c->cres);
                    if (c->cres.isCollision())
                        return 1;
                }
                for (const Plane &p : c->planes)
                    if (!allowed_static(&m, p.id) &&
                        plane_distance(ms, p, nullptr, nullptr) <= 0)
                        return 1;
            }
            for (size_t j = i + 1; j < n; j++) {
                const Movable &mj = c->movables[j];
                if (!mj.enabled || c->is_allowed(i, j))
                    continue;
                for (int si : m.shapes)
                    for (int sj : mj.shapes) {
                        c->cres.clear();
                        fcl::collide(c->mshapes[(size_t)si].obj.get(),
                                     c->mshapes[(size_t)sj].obj.get(), c->creq,
                                     c->cres);
                        if (c->cres.isCollision())
                            return 1;
                    }
            }
        }
        return 0;
    });
}

int mpb__collision_mesh_reach(mpb_collision *c, int i, const double d[3],
                              double *fast, double *all)
{
    if (!c || i < 0 || (size_t)i >= c->mshapes.size() || !d || !fast || !all)
        return MPB_EINVAL;
    const Shape &s = c->mshapes[(size_t)i];
    if (s.type != MPB_SHAPE_MESH || s.num_verts <= 0)
        return MPB_EINVAL;
    int at;
    mesh_reach(s, d, *fast, at);
    Shape every;              /* the same, without the hull or the lists */
    auto *m = static_cast<const fcl::BVHModel<fcl::OBBRSSd> *>(
        s.obj->collisionGeometry().get());
    every.world = s.world;
    every.verts = m->vertices;
    every.num_verts = m->num_vertices;
    mesh_reach(every, d, *all, at);
    return MPB_OK;
}

double mpb__collision_distance_brute(mpb_collision *c)
{
    double best = std::numeric_limits<double>::infinity();
    if (!c)
        return std::numeric_limits<double>::quiet_NaN();
    int rc = guarded(c, [&]() -> int {
        for (const Movable &m : c->movables) {
            if (!m.enabled || m.self_only)
                continue;
            for (int si : m.shapes) {
                const Shape &ms = c->mshapes[(size_t)si];
                sync(ms);
                for (const Shape &ss : c->sshapes)
                    if (!allowed_static(&m, ss.body))
                        best = std::min(best, pair_distance(c, ms.obj.get(),
                                                            ss.obj.get()));
                for (const Plane &p : c->planes)
                    if (!allowed_static(&m, p.id))
                        best = std::min(best, plane_distance(ms, p, nullptr,
                                                             nullptr));
            }
        }
        return MPB_OK;
    });
    return rc == MPB_OK ? best : std::numeric_limits<double>::quiet_NaN();
}

} // extern "C"
