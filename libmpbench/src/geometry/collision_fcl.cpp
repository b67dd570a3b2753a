/*
 * collision_fcl.cpp - the C API of the collision world of collision.h over
 * FCL 0.7 (its other files: collision_world.h):
 * static shapes in a bounding-volume tree of their own (flat arrays of
 * exact AABBs, inline tests), movable bodies made of shapes at fixed
 * offsets, collision and distance queries that allocate nothing; FCL does
 * the narrow phase. The C++ stays inside; every extern "C" function
 * catches every exception.
 *
 * Why not FCL's broadphase managers: for a robot among a few dozen
 * obstacles, walking FCL's dynamic AABB tree (an out-of-line call per node
 * and per AABB test) cost about half of a collision check and most of a
 * distance query, for almost no narrow-phase work (PR2 arm in the kitchen,
 * callgrind). The tree here visits the same pairs (those whose AABBs
 * overlap, for collision; those whose AABB distance is below the best so
 * far, for distance) in a few instructions each.
 *
 * Meshes (robot links of real robots): a mesh's BVH model is built once
 * and shared by every shape of every world of the process with the same
 * vertices and triangles (shared_geometry(), mesh_cache.h). Before FCL's
 * narrow phase, a movable mesh's pair is ruled out by a capsule fitted
 * around it and by a plane between its vertices
 * and the other's (another mesh's vertices, a static's box); a distance
 * query measures its pairs nearest lower bound first, and skips those
 * whose bound from the vertices is no better than the best so far. All
 * are exact bounds with a margin: verdicts and distances are those of
 * every pair through FCL (tests/unit/geometry/test_mesh_reference.c). A mesh's
 * extent along a direction is read from a few vertices of its hull, those
 * listed for the direction (hull.h, dirtable.h): the same numbers as from
 * all its vertices, for a few percent of the cost. Two meshes that get
 * that far are tested by a traversal of FCL's trees of our own
 * (bvh_collide.h), FCL's verdict at about half the cost. A mesh's distance
 * to a primitive static is measured over FCL's tree with bounds against
 * the primitive's own box (bvh_distance.h), FCL's answer for a fraction of
 * the cost, cut off just above a bound from the mesh's vertices; the last
 * query's nearest pair bounds the next query the same way, with no FCL
 * call (test_clearance_reference.c).
 *
 * What FCL 0.7 gets wrong, and what is done about it (see the tests):
 *   - plane distances crash (libccd) or are wrong (independent GJK): planes
 *     are kept out of FCL and handled here exactly, with support points;
 *   - GJK distances stop at 1e-6 by default, leaving errors up to ~3 mm
 *     (cones, cylinders): the tolerance is set to 1e-10, which measures
 *     below 5e-7 m against closed forms and fine meshes, for ~30% more time;
 *   - the independent GJK solver is wrong for cones: libccd is used;
 *   - nearest points of a sphere and a mesh come in the two local frames,
 *     and those of (shape, mesh) pairs in swapped order: both are undone;
 *   - computeAABB() bounds a rotated shape by its bounding sphere: exact
 *     AABBs are computed here instead (place_shape), a cheap win for long
 *     links;
 *   - libccd's MPR loops forever on degenerate shapes (zero radius, flat
 *     boxes, aspect ratios ~1e14) and FCL's AABB tree crashed on coordinates
 *     ~1e306: sizes and coordinates are bounded (collision.h).
 */
#include "geometry/collision_world.h"
#include "geometry/collision_internal.h"

#include <cstring>
#include <limits>

using namespace mpb::coll;

extern "C" {

int mpb_collision_create(mpb_collision **out)
{
    if (!out)
        return MPB_EINVAL;
    *out = nullptr;
    return guarded(nullptr, [&]() -> int {
        mpb_collision *c = new mpb_collision();
        c->creq.num_max_contacts = 1;
        c->creq.enable_contact = false;
        c->dreq.enable_nearest_points = false;
        c->dreq.enable_signed_distance = false;
        c->dreq.distance_tolerance = 1e-10;   /* see the top of this file */
        c->dreq.gjk_solver_type = fcl::GST_LIBCCD;
        c->creq.gjk_solver_type = fcl::GST_LIBCCD;
        /* Reserve so that the first query does not allocate either. */
        c->cres.clear();
        c->cres.addContact(fcl::Contactd());
        c->cres.clear();
        *out = c;
        return MPB_OK;
    });
}

void mpb_collision_destroy(mpb_collision *c)
{
    try {
        delete c;
    } catch (...) {
    }
}

const char *mpb_collision_errmsg(const mpb_collision *c)
{
    return c ? c->err : "collision: no world";
}

int mpb_collision_add_static(mpb_collision *c, int id, const mpb_geometry *g,
                             const mpb_pose *pose)
{
    if (!c)
        return MPB_EINVAL;
    c->err[0] = '\0';
    return guarded(c, [&]() -> int {
        int rc = check_args(c, id, g, pose, false);
        if (rc != MPB_OK)
            return rc;
        fcl::Transform3d tf = to_tf(pose);
        if (g->type == MPB_SHAPE_PLANE) {
            fcl::Vector3d nl;
            double dist = 0;
            plane_unit(g->dims, nl, dist);   /* true: check_args checked it */
            Plane p;
            p.n = tf.linear() * nl;
            p.d = dist + p.n.dot(tf.translation());
            p.id = id;
            c->planes.push_back(p);
            return MPB_OK;
        }
        std::shared_ptr<Geom> geom = shared_geometry(g);
        if (!geom) {
            c->set_err("collision: static %d: FCL could not build the %s", id,
                       mpb_shape_type_name(g->type));
            return MPB_EINVAL;
        }
        Shape s;
        s.obj.reset(new Obj(geom, tf));
        mpb_pose_identity(&s.offset);
        if (pose)
            s.world = *pose;
        else
            mpb_pose_identity(&s.world);
        s.body = id;
        s.type = g->type;
        memcpy(s.dims, g->dims, sizeof s.dims);
        bounding_sphere(s);
        local_box(s);
        place_shape(s);
        s.stale = false;                /* tf is s.world already */
        c->sshapes.push_back(std::move(s));
        c->dirty = true;
        return MPB_OK;
    });
}

int mpb_collision_add_movable(mpb_collision *c, int id, const mpb_geometry *g,
                              const mpb_pose *offset)
{
    if (!c)
        return MPB_EINVAL;
    c->err[0] = '\0';
    return guarded(c, [&]() -> int {
        int rc = check_args(c, id, g, offset, true);
        if (rc != MPB_OK)
            return rc;
        std::shared_ptr<Geom> geom = shared_geometry(g);
        if (!geom) {
            c->set_err("collision: movable %d: FCL could not build the %s", id,
                       mpb_shape_type_name(g->type));
            return MPB_EINVAL;
        }
        /* Everything that may throw first, then the changes that cannot. */
        Shape s;
        if (offset)
            s.offset = *offset;
        else
            mpb_pose_identity(&s.offset);
        s.type = g->type;
        memcpy(s.dims, g->dims, sizeof s.dims);
        s.offset_pure = true;
        for (int i = 0; i < 9; i++)
            s.offset_pure = s.offset_pure && s.offset.R[i] == (i % 4 == 0 ? 1.0 : 0.0);
        room_for_one(c->mshapes);
        Movable *m = c->find(id);
        if (!m) {
            /* A new body: grow the id map and the allowed-pair matrix. */
            size_t n = c->movables.size();
            if (n + 1 > c->astride) {
                size_t st = 2 * c->astride + 4;
                std::vector<unsigned char> allowed(st * st, 0);
                for (size_t a = 0; a < n; a++)
                    for (size_t b = 0; b < n; b++)
                        allowed[a * st + b] = c->allowed[a * c->astride + b];
                c->allowed.swap(allowed);
                c->astride = st;
            }
            Movable nm;
            nm.id = id;
            nm.enabled = true;
            mpb_pose_identity(&nm.pose);
            nm.shapes.reserve(1);
            if ((size_t)id >= c->movable_index.size())
                c->movable_index.resize((size_t)id + 1, -1);
            room_for_one(c->movables);
            c->movables.push_back(std::move(nm));
            c->movable_index[(size_t)id] = (int)n;
            c->pairs_dirty = true;
            m = &c->movables.back();
        }
        room_for_one(m->shapes);
        mpb_pose_mul(&m->pose, &s.offset, &s.world);
        s.obj.reset(new Obj(geom, to_tf(&s.world)));
        bounding_sphere(s);
        if (g->type == MPB_SHAPE_MESH) {
            fit_capsule(s, g->mesh);
            const auto &ext = extreme_vertices(*static_cast<MeshModel *>(geom.get()));
            s.verts = ext.data();
            s.num_verts = (int)ext.size();
            s.dirs = &static_cast<MeshModel *>(geom.get())->dirs;
            if (!ext.empty()) {
                s.vtri_start = static_cast<MeshModel *>(geom.get())->tri_start.data();
                s.vtris = static_cast<MeshModel *>(geom.get())->tris.data();
            }
        }
        s.body = c->movable_index[(size_t)id];
        s.obj->setUserData((void *)(intptr_t)c->mshapes.size());
        c->mshapes.push_back(std::move(s));
        m->shapes.push_back((int)c->mshapes.size() - 1);
        place_body(c, *m);
        return MPB_OK;
    });
}

int mpb_collision_set_pose(mpb_collision *c, int id, const mpb_pose *pose)
{
    if (!c)
        return MPB_EINVAL;
    Movable *m = c->find_or_err(id);
    if (!m)
        return MPB_ENOTFOUND;
    if (!pose || !finite_pose(pose)) {
        c->set_err("collision: movable %d: pose missing, not finite or too far "
                   "(%g m at most)", id, MPB_COLLISION_MAX_COORD);
        return MPB_EINVAL;
    }
    return guarded(c, [&]() -> int {
        m->pose = *pose;
        place_body(c, *m);
        return MPB_OK;
    });
}

int mpb_collision_set_enabled(mpb_collision *c, int id, int enabled)
{
    if (!c)
        return MPB_EINVAL;
    Movable *m = c->find_or_err(id);
    if (!m)
        return MPB_ENOTFOUND;
    m->enabled = enabled != 0;
    return MPB_OK;
}

int mpb__collision_allow_pair(mpb_collision *c, int movable_a, int movable_b)
{
    if (!c)
        return MPB_EINVAL;
    Movable *a = c->find_or_err(movable_a);
    Movable *b = a ? c->find_or_err(movable_b) : nullptr;
    if (!a || !b)
        return MPB_ENOTFOUND;
    if (a == b) {
        c->set_err("collision: a body cannot be paired with itself (%d)", movable_a);
        return MPB_EINVAL;
    }
    size_t ia = (size_t)c->movable_index[(size_t)movable_a];
    size_t ib = (size_t)c->movable_index[(size_t)movable_b];
    c->allowed[ia * c->astride + ib] = c->allowed[ib * c->astride + ia] = 1;
    c->pairs_dirty = true;
    return MPB_OK;
}

int mpb__collision_allow_static(mpb_collision *c, int movable, int static_id)
{
    if (!c)
        return MPB_EINVAL;
    Movable *m = c->find_or_err(movable);
    if (!m)
        return MPB_ENOTFOUND;
    if (static_id < 0 || static_id > MPB_COLLISION_MAX_ID) {
        c->set_err("collision: static id %d out of range 0..%d", static_id,
                   MPB_COLLISION_MAX_ID);
        return MPB_EINVAL;
    }
    return guarded(c, [&]() -> int {
        if (!allowed_static(m, static_id))
            m->allowed_statics.push_back(static_id);
        return MPB_OK;
    });
}

int mpb_collision_check(mpb_collision *c, int *movable, int *static_id)
{
    if (movable)
        *movable = -1;
    if (static_id)
        *static_id = -1;
    if (!c)
        return MPB_EINVAL;
    return guarded(c, [&]() -> int {
        int rc = ensure_tree(c);
        if (rc != MPB_OK)
            return rc;
        /* The statics near the robot as a whole first: for a robot among
         * a few dozen obstacles, few are; each shape then tests those. */
        Box3 all;
        bool among = false;
        if (robot_box(c, all)) {
            gather(c, all);
            among = c->cand.size() <= MPB__FEW;
        }
        for (const Movable &m : c->movables) {
            if (!m.enabled || m.self_only)
                continue;
            for (int si : m.shapes) {
                const Shape &ms = c->mshapes[(size_t)si];
                int hit = static_hit(c, m, ms, among);
                for (size_t k = 0; hit < 0 && k < c->planes.size(); k++) {
                    const Plane &p = c->planes[k];
                    if (allowed_static(&m, p.id))
                        continue;
                    if (plane_distance(ms, p, nullptr, nullptr) <= 0)
                        hit = p.id;
                }
                if (hit >= 0) {
                    if (movable)
                        *movable = m.id;
                    if (static_id)
                        *static_id = hit;
                    return 1;
                }
            }
        }
        return 0;
    });
}

int mpb__collision_check_self(mpb_collision *c, int *a, int *b)
{
    if (a)
        *a = -1;
    if (b)
        *b = -1;
    if (!c)
        return MPB_EINVAL;
    return guarded(c, [&]() -> int {
        ensure_self_pairs(c);
        for (const auto &pr : c->self_pairs) {
            const Movable &mi = c->movables[(size_t)pr.first];
            const Movable &mj = c->movables[(size_t)pr.second];
            /* Hints are looked at only for bodies whose boxes overlap. */
            if (!mi.enabled || !mj.enabled || !overlap(mi.box, mj.box) ||
                (!c->hints.empty() && hinted_apart(c, pr.first, pr.second)) ||
                !bodies_touch(c, mi, mj))
                continue;
            int x = mi.id, y = mj.id;
            if (a)
                *a = x < y ? x : y;
            if (b)
                *b = x < y ? y : x;
            return 1;
        }
        return 0;
    });
}

int mpb__collision_check_pair(mpb_collision *c, int movable_a, int movable_b)
{
    if (!c)
        return MPB_EINVAL;
    Movable *ma = c->find_or_err(movable_a);
    Movable *mb = ma ? c->find_or_err(movable_b) : nullptr;
    if (!ma || !mb)
        return MPB_ENOTFOUND;
    if (ma == mb) {
        c->set_err("collision: a body cannot be paired with itself (%d)", movable_a);
        return MPB_EINVAL;
    }
    return guarded(c, [&]() -> int { return bodies_touch(c, *ma, *mb) ? 1 : 0; });
}

int mpb__collision_set_self_only(mpb_collision *c, int id, int self_only)
{
    if (!c)
        return MPB_EINVAL;
    Movable *m = c->find_or_err(id);
    if (!m)
        return MPB_ENOTFOUND;
    m->self_only = self_only != 0;
    return MPB_OK;
}

int mpb_collision_distance(mpb_collision *c, int want_points,
                           mpb_collision_distance_result *out)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (out) {
        out->distance = nan;
        out->movable = out->static_id = -1;
        for (int k = 0; k < 3; k++)
            out->point_movable[k] = out->point_static[k] = nan;
    }
    if (!c)
        return MPB_EINVAL;
    return guarded(c, [&]() -> int {
        int rc = ensure_tree(c);
        if (rc != MPB_OK)
            return rc;
        Query q = {};
        q.c = c;
        q.best = std::numeric_limits<double>::infinity();
        q.static_id = -1;
        int best_movable = -1;
        const Shape *best_shape = nullptr;      /* for a plane */
        const Plane *best_plane = nullptr;
        /* Successive queries are mostly near each other (a path sampled
           finely): the last nearest pair gives a tight bound to prune
           with. A mesh's bound from above comes from its vertices
           (mesh_static_lower()), with no FCL call: the pair is then
           measured in its turn like any other, and only if it may be the
           nearest. Anything else is measured now. */
        double bound = INFINITY;        /* the least distance is below */
        const Shape *seed_ms = nullptr, *seed_ss = nullptr;
        if (c->seed_m >= 0 && (size_t)c->seed_m < c->mshapes.size() &&
            c->seed_s >= 0 && (size_t)c->seed_s < c->sshapes.size()) {
            const Shape &ms = c->mshapes[(size_t)c->seed_m];
            const Shape &ss = c->sshapes[(size_t)c->seed_s];
            const Movable &mv = c->movables[(size_t)ms.body];
            if (mv.enabled && !mv.self_only && !allowed_static(&mv, ss.body)) {
                seed_ms = &ms;
                seed_ss = &ss;
                if (ms.num_verts > 0) {
                    mesh_static_lower(ms, ss, INFINITY, true, &bound);
                    /* the slack of pair_distance_upper(): the pair's own
                       FCL distance is below it */
                    bound += 1e-7 * (1.0 + bound);
                }
            }
        }
        auto measure_seed = [&]() {
            const Shape &ms = *seed_ms, &ss = *seed_ss;
            double upper = INFINITY;
            int uv = -1;
            if (ms.num_verts > 0)
                mesh_static_lower(ms, ss, INFINITY, true, &upper, &uv);
            q.best = pair_distance_upper(c, ms, ss, INFINITY, upper, uv);
            q.best_m = q.seed_m = ms.obj.get();
            q.best_s = q.seed_s = ss.obj.get();
            q.static_id = ss.body;
            best_movable = c->movables[(size_t)ms.body].id;
        };
        if (seed_ms && !(bound < INFINITY))
            measure_seed();
        /* The statics that may be nearer than the bound to the robot as
           a whole: for a robot among a few dozen obstacles, few are. */
        Box3 all;
        bool among = false;
        if (robot_box(c, all)) {
            double b = std::min(q.best, bound);
            if (b < std::numeric_limits<double>::infinity())
                gather_near(c, all, b);
            else
                gather_where(c, [](const Box3 &) { return true; });
            among = c->cand.size() <= MPB__FEW;
        }
        if (!among && bound < INFINITY) {
            measure_seed();     /* the tree's walk prunes with q.best */
            bound = INFINITY;
        }
        for (int attempt = 0; among && attempt < 2; attempt++) {
            /* Best first: every (shape, static) pair with its cheap lower
               bound, nearest first, measured until a bound is no better
               than the best distance so far. The first measured is
               mostly the nearest: one or two FCL distances, where mesh
               links measured in body order took dozens. */
            c->near.clear();
            c->near.reserve(c->mshapes.size() * c->cand.size());
            const double cap = std::min(q.best, bound);
            for (const Movable &m : c->movables) {
                if (!m.enabled || m.self_only)
                    continue;
                for (int si : m.shapes) {
                    const Shape &sh = c->mshapes[(size_t)si];
                    for (int i : c->cand) {
                        const Leaf &l = c->leaves[(size_t)i];
                        const Shape &ss = c->sshapes[(size_t)l.shape];
                        if (allowed_static(&m, l.body) ||
                            (sh.obj.get() == q.seed_m && ss.obj.get() == q.seed_s))
                            continue;
                        double dx = sh.wcenter[0] - l.center[0],
                               dy = sh.wcenter[1] - l.center[1],
                               dz = sh.wcenter[2] - l.center[2];
                        double lower = std::max(
                            std::sqrt(box_dist2(l.box, sh.box)),
                            std::sqrt(dx * dx + dy * dy + dz * dz) - sh.bradius - l.radius);
                        if (sh.has_cap && lower < cap)
                            lower = std::max(lower, cap_static_lower(sh, ss));
                        if (lower < cap)
                            c->near.push_back({lower, si, i});
                    }
                }
            }
            std::sort(c->near.begin(), c->near.end(),
                      [](const mpb_collision::Near &a, const mpb_collision::Near &b) {
                          return a.lower < b.lower;
                      });
            for (const auto &p : c->near) {
                double lim = std::min(q.best, bound);
                if (!(p.lower < lim) || q.best <= 0.0)
                    break;
                const Shape &sh = c->mshapes[(size_t)p.shape];
                const Leaf &l = c->leaves[(size_t)p.leaf];
                const Shape &ss = c->sshapes[(size_t)l.shape];
                const Obj *st = ss.obj.get();
                double upper = INFINITY;
                int uv = -1;
                if (sh.num_verts > 0 &&
                    !(mesh_static_lower(sh, ss, lim, true, &upper, &uv) < lim))
                    continue;
                double d = pair_distance_upper(c, sh, ss, lim, upper, uv);
                if (d < lim) {
                    q.best = d;
                    q.best_m = sh.obj.get();
                    q.best_s = st;
                    q.static_id = l.body;
                    best_movable = c->movables[(size_t)sh.body].id;
                }
            }
            /* The seed's bound holds its own pair's distance, which was
               measured unless a nearer was: never again, but should the
               solver disagree, the pairs are measured with no bound. */
            if (q.best < INFINITY || !(bound < INFINITY))
                break;
            bound = INFINITY;
            gather_where(c, [](const Box3 &) { return true; });
            among = c->cand.size() <= MPB__FEW;
        }
        if (among) {
            for (const Movable &m : c->movables) {
                if (!m.enabled || m.self_only)
                    continue;
                for (int si : m.shapes) {
                    const Shape &sh = c->mshapes[(size_t)si];
                    for (const Plane &p : c->planes) {
                        if (q.best <= 0.0 || allowed_static(&m, p.id))
                            continue;
                        double d = plane_distance(sh, p, nullptr, nullptr);
                        if (d < q.best) {
                            q.best = d;
                            q.static_id = p.id;
                            best_movable = m.id;
                            best_plane = &p;
                            best_shape = &sh;
                        }
                    }
                }
            }
        }
        for (const Movable &m : c->movables) {
            if (among || q.best <= 0.0)
                break;
            if (!m.enabled || m.self_only)
                continue;
            q.m = &m;
            for (int si : m.shapes) {
                const Shape &sh = c->mshapes[(size_t)si];
                double before = q.best;
                static_distance(&q, sh, among);
                if (q.best < before) {
                    best_movable = m.id;
                    best_plane = nullptr;
                }
                for (const Plane &p : c->planes) {
                    if (q.best <= 0.0)
                        break;
                    if (allowed_static(&m, p.id))
                        continue;
                    double d = plane_distance(sh, p, nullptr, nullptr);
                    if (d < q.best) {
                        q.best = d;
                        q.static_id = p.id;
                        best_movable = m.id;
                        best_plane = &p;
                        best_shape = &sh;
                    }
                }
                if (q.best <= 0.0)
                    break;
            }
            if (q.best <= 0.0)
                break;
        }
        if (!best_plane && q.best_m) {
            c->seed_m = (int)(intptr_t)q.best_m->getUserData();
            c->seed_s = (int)(intptr_t)q.best_s->getUserData();
        }
        if (!out)
            return MPB_OK;
        out->distance = q.best;
        if (best_movable < 0)
            return MPB_OK;
        out->movable = best_movable;
        out->static_id = q.static_id;
        if (!want_points || !(q.best > 0.0))
            return MPB_OK;
        fcl::Vector3d pm, ps;
        if (best_plane)
            plane_distance(*best_shape, *best_plane, &pm, &ps);
        else if (!nearest_points(c, q.best_m, q.best_s, q.best, pm, ps))
            return MPB_OK;      /* leave them NaN rather than wrong */
        for (int k = 0; k < 3; k++) {
            out->point_movable[k] = pm[k];
            out->point_static[k] = ps[k];
        }
        return MPB_OK;
    });
}

int mpb__collision_num_static_shapes(const mpb_collision *c)
{
    return c ? (int)(c->sshapes.size() + c->planes.size()) : 0;
}

int mpb__collision_num_movable_shapes(const mpb_collision *c)
{
    return c ? (int)c->mshapes.size() : 0;
}

double mpb__collision_pair_distance(mpb_collision *c, int a, int b, double below)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    Movable *ma = c ? c->find_or_err(a) : nullptr;
    Movable *mb = ma ? c->find_or_err(b) : nullptr;
    if (!ma || !mb || ma == mb)
        return nan;
    double best = below;
    int rc = guarded(c, [&]() -> int {
        best = movables_distance(c, *ma, *mb, below);
        return MPB_OK;
    });
    return rc == MPB_OK ? best : nan;
}

int mpb__collision_hint_apart(mpb_collision *c, int a, int b)
{
    if (!c)
        return MPB_EINVAL;
    Movable *ma = c->find_or_err(a);
    Movable *mb = ma ? c->find_or_err(b) : nullptr;
    if (!ma || !mb)
        return MPB_ENOTFOUND;
    if (ma == mb)
        return MPB_EINVAL;
    int i = c->movable_index[(size_t)a], j = c->movable_index[(size_t)b];
    if (i > j)
        std::swap(i, j);
    mpb_collision::Hint h = {i, j, c->movables[(size_t)i].placed,
                             c->movables[(size_t)j].placed};
    for (mpb_collision::Hint &old : c->hints)
        if (old.i == i && old.j == j) {
            old = h;
            return MPB_OK;
        }
    return guarded(c, [&]() -> int {
        c->hints.push_back(h);
        return MPB_OK;
    });
}

} // extern "C"
