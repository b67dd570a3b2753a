/*
 * collision_registry.cpp - the BVH models of every collision world of the
 * process, shared by the worlds whose meshes are the same (mesh_cache.h).
 */
#include "geometry/collision_world.h"
#include "geometry/mesh_cache.h"

#include <cstring>
#include <unordered_map>

namespace mpb {
namespace coll {

/*
 * The BVH models of every collision world of the process (mesh_cache.h),
 * under a hash of their mesh's vertices and triangles; each alive while a
 * world holds it. Expired entries are swept when the map has doubled.
 */
struct BvhRegistry {
    std::mutex mu;
    std::unordered_multimap<uint64_t, std::weak_ptr<Geom>> models;
    size_t sweep_at = 64;
    long   builds = 0;
};

BvhRegistry &bvh_registry()
{
    static BvhRegistry *r = new BvhRegistry();  /* never destroyed: models
                                                   outlive static teardown */
    return *r;
}

uint64_t mesh_hash(const mpb_mesh *m)
{
    uint64_t h = 1469598103934665603ull;
    auto mix = [&h](uint64_t w) { h = (h ^ w) * 1099511628211ull; };
    mix((uint64_t)m->num_vertices);
    mix((uint64_t)m->num_triangles);
    for (long i = 0; i < 3L * m->num_vertices; i++) {
        uint64_t w;
        memcpy(&w, &m->vertices[i], sizeof w);
        mix(w);
    }
    for (long i = 0; i < 3L * m->num_triangles; i++)
        mix((uint64_t)(uint32_t)m->triangles[i]);
    return h;
}

/* Was the BVH model geom built from exactly m's vertices and triangles? */
bool built_from(const Geom *geom, const mpb_mesh *m)
{
    auto *b = static_cast<const fcl::BVHModel<fcl::OBBRSSd> *>(geom);
    if (b->num_vertices != m->num_vertices || b->num_tris != m->num_triangles)
        return false;
    for (int i = 0; i < m->num_vertices; i++)
        for (int k = 0; k < 3; k++)
            if (b->vertices[i][k] != m->vertices[3 * i + k])
                return false;
    for (int i = 0; i < m->num_triangles; i++)
        for (int k = 0; k < 3; k++)
            if ((long)b->tri_indices[i][k] != (long)m->triangles[3 * i + k])
                return false;
    return true;
}

/*
 * The FCL geometry of g, as make_geometry(); a mesh whose vertices and
 * triangles equal those of a BVH model some world of the process holds
 * (the two fingers of a gripper, a robot's links in every scene of an
 * experiment) gets that model: built once. Models are only read by the
 * queries, so worlds in different threads may share them.
 */
std::shared_ptr<Geom> shared_geometry(const mpb_geometry *g)
{
    if (g->type != MPB_SHAPE_MESH)
        return make_geometry(g);
    const mpb_mesh *m = g->mesh;
    const uint64_t h = mesh_hash(m);
    BvhRegistry &r = bvh_registry();
    {
        std::lock_guard<std::mutex> lock(r.mu);
        auto range = r.models.equal_range(h);
        for (auto it = range.first; it != range.second; ++it) {
            std::shared_ptr<Geom> geom = it->second.lock();
            if (geom && built_from(geom.get(), m))
                return geom;
        }
    }
    /* Built outside the lock; two threads may build the same model once
     * each, and both are kept, correct if not shared. */
    std::shared_ptr<Geom> geom = make_geometry(g);
    if (!geom)
        return geom;
    std::lock_guard<std::mutex> lock(r.mu);
    r.builds++;
    if (r.models.size() >= r.sweep_at) {
        for (auto it = r.models.begin(); it != r.models.end();)
            it = it->second.expired() ? r.models.erase(it) : std::next(it);
        r.sweep_at = 2 * r.models.size() + 64;
    }
    r.models.emplace(h, geom);
    return geom;
}

} // namespace coll
} // namespace mpb

using namespace mpb::coll;

extern "C" {

long mpb__bvh_builds(void)
{
    BvhRegistry &r = bvh_registry();
    std::lock_guard<std::mutex> lock(r.mu);
    return r.builds;
}

long mpb__bvh_live(void)
{
    BvhRegistry &r = bvh_registry();
    std::lock_guard<std::mutex> lock(r.mu);
    long n = 0;
    for (const auto &e : r.models)
        n += !e.second.expired();
    return n;
}

} // extern "C"
