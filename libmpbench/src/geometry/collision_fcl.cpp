/*
 * collision_fcl.cpp - the collision world of collision.h over FCL 0.7:
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
 * every pair through FCL (tests/unit/test_mesh_reference.c). A mesh's
 * extent along a direction is read from a few vertices of its hull, those
 * listed for the direction (hull.h, dirtable.h): the same numbers as from
 * all its vertices, for a few percent of the cost. Two meshes that get
 * that far are tested by a traversal of FCL's trees of our own
 * (bvh_collide.h), FCL's verdict at about half the cost.
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
#include "mpbench/mpbench.h"
#include "mpbench/collision.h"
#include "geometry/bvh_collide.h"
#include "geometry/collision_internal.h"
#include "geometry/dirtable.h"
#include "core/errbuf.h"
#include "geometry/hull.h"
#include "geometry/mesh_cache.h"
#include "geometry/simplex.h"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <new>
#include <unordered_map>
#include <vector>

#define MPB__STR2(x) #x
#define MPB__STR(x) MPB__STR2(x)

namespace {

using Obj = fcl::CollisionObjectd;
using Geom = fcl::CollisionGeometryd;

/* An axis-aligned box, world frame: plain doubles, tested inline. */
struct Box3 {
    double lo[3], hi[3];
};

/* Do a and b overlap (touching counts, as in FCL)? */
inline bool overlap(const Box3 &a, const Box3 &b)
{
    return !(a.lo[0] > b.hi[0] || b.lo[0] > a.hi[0] ||
             a.lo[1] > b.hi[1] || b.lo[1] > a.hi[1] ||
             a.lo[2] > b.hi[2] || b.lo[2] > a.hi[2]);
}

/* The squared distance between a and b (0 if they overlap). */
inline double box_dist2(const Box3 &a, const Box3 &b)
{
    double s = 0.0;
    for (int k = 0; k < 3; k++) {
        double g = std::max(a.lo[k] - b.hi[k], b.lo[k] - a.hi[k]);
        if (g > 0)
            s += g * g;
    }
    return s;
}

void box_add(Box3 &a, const Box3 &b)
{
    for (int k = 0; k < 3; k++) {
        a.lo[k] = std::min(a.lo[k], b.lo[k]);
        a.hi[k] = std::max(a.hi[k], b.hi[k]);
    }
}

struct Shape {
    std::unique_ptr<Obj> obj;
    mpb_pose             offset;   /* movable: in the body's frame */
    mpb_pose             world;    /* where it is (plain doubles: cheap to
                                      keep current, even unoptimised) */
    Box3                 box;      /* exact world AABB, kept current */
    mutable bool         stale = false; /* obj's transform is not world's:
                                      set only before a narrow phase */
    int                  body;     /* movable: index in movables; static: id */
    bool                 offset_pure = false; /* offset.R is the identity */
    mpb_shape_type       type;
    double               dims[4];
    fcl::Vector3d        bcenter;  /* a bounding sphere, own frame */
    double               bradius;
    double               wcenter[3]; /* bcenter in the world, kept current */
    /* A movable mesh: a capsule that holds every vertex (segment cap[0]
       to cap[1] in its own frame, radius cap_r), its ends in the world
       in wcap, kept current. Disjoint from it, the mesh is too. */
    bool                 has_cap = false;
    double               cap[2][3], cap_r = 0, wcap[2][3];
    const fcl::Vector3d *verts = nullptr; /* a mesh's vertices that may be
                                      extreme (extreme_vertices()) */
    int                  num_verts = 0;
    const mpb__dirtable *dirs = nullptr; /* which of verts, by direction */
    /* A static: a box that holds it, in its own frame (centre, half
       sides), for the capsule tests. */
    double               lbox_c[3] = {0, 0, 0}, lbox_h[3] = {0, 0, 0};
};

/* A static plane n . x = d in the world frame, |n| = 1. */
struct Plane {
    fcl::Vector3d n;
    double        d;
    int           id;
};

/*
 * The plane a x + b y + c z = d as a unit normal and the signed distance
 * of the plane from the origin. Scaled by the largest of a, b, c first, so
 * that neither 1e-300 nor 1e300 over- or underflows in the squares. False
 * if the coefficients are not finite or the normal is zero.
 */
bool plane_unit(const double dims[4], fcl::Vector3d &n, double &dist)
{
    double scale = std::max({std::fabs(dims[0]), std::fabs(dims[1]),
                             std::fabs(dims[2])});
    if (!(scale > 0) || !std::isfinite(scale) || !std::isfinite(dims[3]))
        return false;
    n = fcl::Vector3d(dims[0] / scale, dims[1] / scale, dims[2] / scale);
    double len = n.norm();      /* in 1 .. sqrt(3) */
    n /= len;
    dist = dims[3] / scale / len;
    return true;
}

struct Movable {
    int                  id;
    bool                 enabled;
    bool                 self_only = false; /* in self checks only */
    std::vector<int>     shapes;          /* indices in mshapes */
    std::vector<int>     allowed_statics; /* static ids it may touch */
    mpb_pose             pose;
    Box3                 box;             /* of its shapes, at pose */
    uint64_t             placed = 0;      /* counts place_body(): a hint
                                             holds for one placing only
                                             (64 bits: never wraps) */
};

/* A node of the static tree: a leaf holds leaves[first .. first + count). */
struct BNode {
    Box3 box;
    int  left, right;                     /* children; left < 0: a leaf */
    int  first, count;
};

/* What the queries read of a static shape, in tree order, contiguous. */
struct Leaf {
    Box3   box;
    double center[3], radius;             /* bounding sphere, world */
    int    body;                          /* static id */
    int    shape;                         /* index in sshapes */
};

/* Finite, and the translation within MPB_COLLISION_MAX_COORD. */
bool finite_pose(const mpb_pose *p)
{
    for (int i = 0; i < 9; i++)
        if (!std::isfinite(p->R[i]))
            return false;
    for (int i = 0; i < 3; i++)
        if (!(std::fabs(p->t[i]) <= MPB_COLLISION_MAX_COORD))
            return false;
    return true;
}

fcl::Transform3d to_tf(const mpb_pose *p)
{
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    if (!p)
        return tf;
    fcl::Matrix3d R;
    R << p->R[0], p->R[1], p->R[2],
         p->R[3], p->R[4], p->R[5],
         p->R[6], p->R[7], p->R[8];
    tf.linear() = R;
    tf.translation() = fcl::Vector3d(p->t[0], p->t[1], p->t[2]);
    return tf;
}

/* A mesh's BVH model, and those of its vertices that may be extreme
 * along some direction (hull.h) with the few of them that may be along
 * each cell of directions (dirtable.h), found for the first movable
 * shape that uses it: extents over them are those over all the vertices. */
struct MeshModel : fcl::BVHModel<fcl::OBBRSSd> {
    std::once_flag             extreme_once;
    std::vector<fcl::Vector3d> extreme;
    mpb__dirtable              dirs = {0, nullptr, nullptr};
    ~MeshModel() { mpb__dirtable_free(&dirs); }
};

/* Cells a cube face for the vertex lists of MeshModel::dirs: 3.5 to 4.5
 * vertices a list for the Panda's links (100 to 260 on their hulls). */
#define MPB__DIR_CELLS 12

static_assert(sizeof(fcl::Vector3d) == 3 * sizeof(double),
              "BVH vertices are read as x y z triples");

const std::vector<fcl::Vector3d> &extreme_vertices(MeshModel &m)
{
    std::call_once(m.extreme_once, [&m] {
        if (m.num_vertices <= 0)
            return;
        std::vector<unsigned char> keep((size_t)m.num_vertices);
        mpb__hull_keep(m.vertices[0].data(), m.num_vertices, keep.data());
        for (int i = 0; i < m.num_vertices; i++)
            if (keep[(size_t)i])
                m.extreme.push_back(m.vertices[i]);
        /* fewer cells for huge hulls: the build costs 12 g^2 dot products
           a vertex; no table (no memory): every vertex is scanned */
        int g = MPB__DIR_CELLS;
        while (g > 1 && 12.0 * g * g * (double)m.extreme.size() > 3e7)
            g--;
        if (!m.extreme.empty())
            mpb__dirtable_build(&m.dirs, m.extreme[0].data(),
                                (int)m.extreme.size(), g);
    });
    return m.extreme;
}

/* The FCL geometry of g (g already checked), or nullptr on a BVH error. */
std::shared_ptr<Geom> make_geometry(const mpb_geometry *g)
{
    const double *d = g->dims;
    switch (g->type) {
    case MPB_SHAPE_BOX:
        return std::make_shared<fcl::Boxd>(d[0], d[1], d[2]);
    case MPB_SHAPE_SPHERE:
        return std::make_shared<fcl::Sphered>(d[0]);
    case MPB_SHAPE_CYLINDER:
        return std::make_shared<fcl::Cylinderd>(d[0], d[1]);
    case MPB_SHAPE_CONE:
        return std::make_shared<fcl::Coned>(d[0], d[1]);
    case MPB_SHAPE_CAPSULE:
        return std::make_shared<fcl::Capsuled>(d[0], d[1]);
    case MPB_SHAPE_PLANE:
        return nullptr;         /* planes are not FCL objects (see the top) */
    case MPB_SHAPE_MESH: {
        const mpb_mesh *m = g->mesh;
        std::vector<fcl::Vector3d> pts((size_t)m->num_vertices);
        for (int i = 0; i < m->num_vertices; i++)
            pts[(size_t)i] = fcl::Vector3d(m->vertices[3 * i], m->vertices[3 * i + 1],
                                           m->vertices[3 * i + 2]);
        std::vector<fcl::Triangle> tris((size_t)m->num_triangles);
        for (int i = 0; i < m->num_triangles; i++)
            tris[(size_t)i].set((size_t)m->triangles[3 * i], (size_t)m->triangles[3 * i + 1],
                                (size_t)m->triangles[3 * i + 2]);
        auto bvh = std::make_shared<MeshModel>();
        if (bvh->beginModel(m->num_triangles, m->num_vertices) != fcl::BVH_OK ||
            bvh->addSubModel(pts, tris) != fcl::BVH_OK ||
            bvh->endModel() != fcl::BVH_OK)
            return nullptr;
        bvh->computeLocalAABB();
        return bvh;
    }
    }
    return nullptr;
}

bool is_bvh(const Obj *o)
{
    return o->getObjectType() == fcl::OT_BVH;
}

double sgn(double x)
{
    return x < 0 ? -1.0 : 1.0;
}

/* The point of shape s (its own frame) farthest along direction u. */
fcl::Vector3d support(const Shape &s, const fcl::Vector3d &u)
{
    const double *d = s.dims;
    double n = u.norm(), rho = std::hypot(u[0], u[1]);
    fcl::Vector3d unit = n > 0 ? fcl::Vector3d(u / n) : fcl::Vector3d(0, 0, 1);
    fcl::Vector3d radial = rho > 0 ? fcl::Vector3d(u[0] / rho, u[1] / rho, 0)
                                   : fcl::Vector3d(0, 0, 0);
    switch (s.type) {
    case MPB_SHAPE_BOX:
        return fcl::Vector3d(sgn(u[0]) * d[0] / 2, sgn(u[1]) * d[1] / 2,
                             sgn(u[2]) * d[2] / 2);
    case MPB_SHAPE_SPHERE:
        return d[0] * unit;
    case MPB_SHAPE_CAPSULE:
        return fcl::Vector3d(0, 0, sgn(u[2]) * d[1] / 2) + d[0] * unit;
    case MPB_SHAPE_CYLINDER:
        return d[0] * radial + fcl::Vector3d(0, 0, sgn(u[2]) * d[1] / 2);
    case MPB_SHAPE_CONE: {
        fcl::Vector3d apex(0, 0, d[1] / 2);
        fcl::Vector3d rim = d[0] * radial + fcl::Vector3d(0, 0, -d[1] / 2);
        return u.dot(apex) >= u.dot(rim) ? apex : rim;
    }
    case MPB_SHAPE_MESH: {
        auto *m = static_cast<const fcl::BVHModel<fcl::OBBRSSd> *>(
            s.obj->collisionGeometry().get());
        const fcl::Vector3d *v = s.num_verts > 0 ? s.verts : m->vertices;
        int nv = s.num_verts > 0 ? s.num_verts : m->num_vertices;
        fcl::Vector3d best = v[0];
        double bd = u.dot(best);
        for (int i = 1; i < nv; i++) {
            double x = u.dot(v[i]);
            if (x > bd) {
                bd = x;
                best = v[i];
            }
        }
        return best;
    }
    case MPB_SHAPE_PLANE:
        break;
    }
    return fcl::Vector3d(0, 0, 0);
}

/*
 * Distance from shape s (at its object's transform) to plane p: 0 when the
 * shape reaches or crosses it. The nearest points if pm and pp are given.
 */
void sync(const Shape &s);

double plane_distance(const Shape &s, const Plane &p, fcl::Vector3d *pm,
                      fcl::Vector3d *pp)
{
    sync(s);
    const fcl::Transform3d &tf = s.obj->getTransform();
    fcl::Vector3d u = tf.linear().transpose() * p.n;
    fcl::Vector3d hi = tf * support(s, u), lo = tf * support(s, -u);
    double shi = p.n.dot(hi) - p.d, slo = p.n.dot(lo) - p.d;
    double dist = 0.0;
    fcl::Vector3d near = lo;
    if (slo > 0) {
        dist = slo;
    } else if (shi < 0) {
        dist = -shi;
        near = hi;
    }
    if (pm)
        *pm = near;
    if (pp)
        *pp = near - (p.n.dot(near) - p.d) * p.n;
    return dist;
}

} // namespace

struct mpb_collision {
    std::vector<Shape>   mshapes;        /* movable shapes */
    std::vector<Movable> movables;
    std::vector<int>     movable_index;  /* id -> index in movables, or -1 */
    std::vector<unsigned char> allowed;  /* movables x movables, row */
    size_t               astride = 0;    /* length astride (grows x2) */
    std::vector<std::pair<int, int>> self_pairs; /* movables i < j not
                                            allowed, for check_self */
    bool                 pairs_dirty = true;  /* self_pairs to redo */
    std::vector<Shape>   sshapes;        /* static shapes in the tree */
    std::vector<Plane>   planes;         /* static planes, kept out of FCL */
    std::vector<BNode>   nodes;          /* the static tree, root first */
    std::vector<int>     order;          /* sshapes indices, leaf by leaf */
    std::vector<Leaf>    leaves;         /* sshapes[order[i]], i.e. leaf i */
    std::vector<int>     cand;           /* a query's leaves (capacity: all) */
    bool                 dirty = false;  /* sshapes changed since the build */
    int                  seed_m = -1;    /* the last nearest pair (shape */
    int                  seed_s = -1;    /* indices), tried first */
    fcl::CollisionRequestd creq;
    fcl::CollisionResultd  cres;
    fcl::DistanceRequestd  dreq;
    fcl::DistanceResultd   dres;
    struct Near { double lower; int shape, leaf; };
    std::vector<Near>    near;           /* a distance query's pairs */
    /* Pairs of movables (indices i < j) the caller proved apart while
       both stood where their placed counts say (mpb__collision_hint_apart) */
    struct Hint { int i, j; uint64_t pi, pj; };
    std::vector<Hint>    hints;
    char                 err[256] = "";

#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    void set_err(const char *fmt, ...)
    {
        va_list ap;
        va_start(ap, fmt);
        mpb__set_err_v(err, sizeof err, fmt, ap);
        va_end(ap);
    }

    Movable *find(int id)
    {
        if (id < 0 || (size_t)id >= movable_index.size() || movable_index[(size_t)id] < 0)
            return nullptr;
        return &movables[(size_t)movable_index[(size_t)id]];
    }

    /* find() for the public calls: an unknown id is the caller's error. */
    Movable *find_or_err(int id)
    {
        Movable *m = find(id);
        if (!m)
            set_err("collision: no movable body %d", id);
        return m;
    }

    bool is_allowed(size_t a, size_t b) const
    {
        return allowed[a * astride + b] != 0;
    }
};

namespace {

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

/* Per-query state of a distance search. */
struct Query {
    mpb_collision *c;
    const Movable *m;
    int            static_id;
    double         best;
    const Obj     *best_m, *best_s;
    const Obj     *seed_m, *seed_s;   /* a pair measured before the search */
};

bool allowed_static(const Movable *m, int static_id)
{
    for (int s : m->allowed_statics)
        if (s == static_id)
            return true;
    return false;
}

/* Write the pose p into FCL's 4x4 column-major matrix. */
void set_tf(fcl::Transform3d &tf, const mpb_pose &p)
{
    double *d = tf.matrix().data();
    for (int r = 0; r < 3; r++) {
        for (int col = 0; col < 3; col++)
            d[4 * col + r] = p.R[3 * r + col];
        d[12 + r] = p.t[r];
        d[4 * r + 3] = 0.0;
    }
    d[15] = 1.0;
}

/* Give s's FCL object its world pose, if it lacks it: before any use of
 * the object by FCL or of its transform (place_shape leaves it stale). */
void sync(const Shape &s)
{
    if (!s.stale)
        return;
    fcl::Transform3d tf;
    set_tf(tf, s.world);
    s.obj->setTransform(tf);
    s.stale = false;
}

/* FCL's distance of a pair, never negative. */
double pair_distance(mpb_collision *c, const Obj *a, const Obj *b)
{
    c->dres.clear();
    double d = fcl::distance(a, b, c->dreq, c->dres);
    return d < 0 ? 0.0 : d;
}

/* A collision check tests each movable shape against the statics near
 * the whole robot when there are at most this many, else walks the tree
 * for each shape. */
#define MPB__FEW 64
/* Leaves of at most this many statics. */
#define MPB__LEAF 4
/* Deep enough for any tree built below (median splits: depth ~ log2 n). */
#define MPB__STACK 128

/* Build the subtree of order[first .. first + count); its node index. */
int build_node(mpb_collision *c, int first, int count)
{
    BNode n;
    n.box = c->sshapes[(size_t)c->order[(size_t)first]].box;
    for (int i = first + 1; i < first + count; i++)
        box_add(n.box, c->sshapes[(size_t)c->order[(size_t)i]].box);
    n.left = n.right = -1;
    n.first = first;
    n.count = count;
    int idx = (int)c->nodes.size();
    c->nodes.push_back(n);
    if (count <= MPB__LEAF)
        return idx;
    /* split at the median centre along the longest axis of the centres */
    double lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    for (int i = first; i < first + count; i++) {
        const Box3 &b = c->sshapes[(size_t)c->order[(size_t)i]].box;
        for (int k = 0; k < 3; k++) {
            double m = 0.5 * (b.lo[k] + b.hi[k]);
            lo[k] = std::min(lo[k], m);
            hi[k] = std::max(hi[k], m);
        }
    }
    int axis = 0;
    for (int k = 1; k < 3; k++)
        if (hi[k] - lo[k] > hi[axis] - lo[axis])
            axis = k;
    int mid = first + count / 2;
    auto centre = [c, axis](int i) {
        const Box3 &b = c->sshapes[(size_t)i].box;
        return b.lo[axis] + b.hi[axis];
    };
    std::nth_element(c->order.begin() + first, c->order.begin() + mid,
                     c->order.begin() + first + count,
                     [&](int a, int b) { return centre(a) < centre(b); });
    int l = build_node(c, first, mid - first);
    int r = build_node(c, mid, first + count - mid);
    c->nodes[(size_t)idx].left = l;
    c->nodes[(size_t)idx].right = r;
    return idx;
}

int ensure_tree(mpb_collision *c)
{
    if (!c->dirty)
        return MPB_OK;
    c->nodes.clear();
    c->order.clear();
    c->nodes.reserve(2 * c->sshapes.size() / MPB__LEAF + 2);
    for (size_t i = 0; i < c->sshapes.size(); i++) {
        c->sshapes[i].obj->setUserData((void *)(intptr_t)i);
        c->order.push_back((int)i);
    }
    if (!c->sshapes.empty())
        build_node(c, 0, (int)c->sshapes.size());
    c->leaves.clear();
    c->leaves.reserve(c->sshapes.size());
    for (int i : c->order) {
        const Shape &s = c->sshapes[(size_t)i];
        Leaf l;
        l.box = s.box;
        for (int k = 0; k < 3; k++)
            l.center[k] = s.wcenter[k];
        l.radius = s.bradius;
        l.body = s.body;
        l.shape = i;
        c->leaves.push_back(l);
    }
    c->cand.clear();
    c->cand.reserve(c->sshapes.size());
    c->dirty = false;
    return MPB_OK;
}

/* The leaves whose boxes pass keep() into c->cand, walking only the
 * nodes whose boxes pass it (no allocation: its capacity is every leaf). */
template <class Keep> void gather_where(mpb_collision *c, Keep keep)
{
    c->cand.clear();
    if (c->nodes.empty())
        return;
    int stack[MPB__STACK], sp = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        const BNode &n = c->nodes[(size_t)stack[--sp]];
        if (!keep(n.box))
            continue;
        if (n.left >= 0) {
            stack[sp++] = n.right;
            stack[sp++] = n.left;
            continue;
        }
        for (int i = n.first; i < n.first + n.count; i++)
            if (keep(c->leaves[(size_t)i].box))
                c->cand.push_back(i);
    }
}

/* The leaves whose boxes overlap b. */
void gather(mpb_collision *c, const Box3 &b)
{
    gather_where(c, [&b](const Box3 &x) { return overlap(x, b); });
}

/* The leaves whose boxes are nearer than d to b. */
void gather_near(mpb_collision *c, const Box3 &b, double d)
{
    const double d2 = d * d;
    gather_where(c, [&b, d2](const Box3 &x) { return box_dist2(x, b) < d2; });
}

/* The union of the enabled movables' boxes into all; false if none. */
bool robot_box(const mpb_collision *c, Box3 &all)
{
    bool any = false;
    for (const Movable &m : c->movables)
        if (m.enabled && !m.self_only && !m.shapes.empty()) {
            if (any)
                box_add(all, m.box);
            else
                all = m.box;
            any = true;
        }
    return any;
}

/* Are the bounding spheres of two movable shapes apart, by far more than
 * FCL's tolerances (libccd's MPR stops at 1e-6)? Then the shapes cannot
 * collide. */
bool spheres_apart(const Shape &a, const Shape &b)
{
    double dx = a.wcenter[0] - b.wcenter[0], dy = a.wcenter[1] - b.wcenter[1],
           dz = a.wcenter[2] - b.wcenter[2];
    double r = a.bradius + b.bradius + 1e-4;
    return dx * dx + dy * dy + dz * dz > r * r;
}

/*
 * The capsule of a movable mesh (s.obj set): for each axis of its own
 * frame, the line along it through the centre of its local box, the least
 * radius about that line that holds every vertex, then the shortest
 * segment on the line that holds them all; the smallest of the three.
 * Meshes of robot links are mostly long and round: much tighter than
 * their boxes or spheres, and two capsules are cheap to test.
 */
void fit_capsule(Shape &s, const mpb_mesh *m)
{
    const fcl::AABBd &box = s.obj->collisionGeometry()->aabb_local;
    double best = INFINITY;
    for (int ax = 0; ax < 3; ax++) {
        int u = (ax + 1) % 3, v = (ax + 2) % 3;
        double cu = (box.min_[u] + box.max_[u]) / 2;
        double cv = (box.min_[v] + box.max_[v]) / 2;
        double r2 = 0;
        for (int i = 0; i < m->num_vertices; i++) {
            const double *x = &m->vertices[3 * i];
            r2 = std::max(r2, (x[u] - cu) * (x[u] - cu) + (x[v] - cv) * (x[v] - cv));
        }
        /* a vertex at t along the line, rho from it, is held when the
           segment reaches t - sqrt(r^2 - rho^2) .. t + sqrt(r^2 - rho^2) */
        double lo = INFINITY, hi = -INFINITY;
        for (int i = 0; i < m->num_vertices; i++) {
            const double *x = &m->vertices[3 * i];
            double rho2 = (x[u] - cu) * (x[u] - cu) + (x[v] - cv) * (x[v] - cv);
            double h = std::sqrt(std::max(0.0, r2 - rho2));
            lo = std::min(lo, x[ax] + h);
            hi = std::max(hi, x[ax] - h);
        }
        if (lo > hi)
            lo = hi = (lo + hi) / 2;
        double r = std::sqrt(r2);
        double vol = r2 * (hi - lo) + 4.0 / 3.0 * r2 * r;  /* over pi */
        if (!(vol < best))
            continue;
        best = vol;
        for (int e = 0; e < 2; e++) {
            s.cap[e][ax] = e ? hi : lo;
            s.cap[e][u] = cu;
            s.cap[e][v] = cv;
        }
        s.cap_r = r;
    }
    s.has_cap = std::isfinite(best);
}

/* A static's box in its own frame (s.obj, s.type, s.dims set). */
void local_box(Shape &s)
{
    const double *d = s.dims;
    double *h = s.lbox_h;
    switch (s.type) {
    case MPB_SHAPE_BOX:
        h[0] = d[0] / 2, h[1] = d[1] / 2, h[2] = d[2] / 2;
        break;
    case MPB_SHAPE_SPHERE:
        h[0] = h[1] = h[2] = d[0];
        break;
    case MPB_SHAPE_CYLINDER:
    case MPB_SHAPE_CONE:
        h[0] = h[1] = d[0], h[2] = d[1] / 2;
        break;
    case MPB_SHAPE_CAPSULE:
        h[0] = h[1] = d[0], h[2] = d[1] / 2 + d[0];
        break;
    default: {
        const fcl::AABBd &b = s.obj->collisionGeometry()->aabb_local;
        for (int k = 0; k < 3; k++) {
            s.lbox_c[k] = (b.min_[k] + b.max_[k]) / 2;
            h[k] = (b.max_[k] - b.min_[k]) / 2;
        }
        break;
    }
    }
}

/* Capsule tests skip a pair only when it clears by this much (m): far
 * above FCL's tolerances and rounding, as spheres_apart(). */
#define MPB__CAP_MARGIN 1e-4
/* Directions gjk_gap() tries at most (instructions a Panda collision
 * check, by that most: 3: 52.7k, 6: 37.4k, 12: 32.1k, 24: 32.1k). */
#define MPB__GJK_STEPS 16

/* The squared distance between segments p0 p1 and q0 q1. */
double seg_seg_dist2(const double p0[3], const double p1[3], const double q0[3],
                     const double q1[3])
{
    double d1[3], d2[3], r[3];
    for (int k = 0; k < 3; k++) {
        d1[k] = p1[k] - p0[k];
        d2[k] = q1[k] - q0[k];
        r[k] = p0[k] - q0[k];
    }
    auto dot = [](const double *a, const double *b) {
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    };
    double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r), sp, t;
    const double tiny = 1e-300;
    if (a <= tiny && e <= tiny) {
        sp = t = 0;
    } else if (a <= tiny) {
        sp = 0;
        t = std::clamp(f / e, 0.0, 1.0);
    } else {
        double cc = dot(d1, r);
        if (e <= tiny) {
            t = 0;
            sp = std::clamp(-cc / a, 0.0, 1.0);
        } else {
            double b = dot(d1, d2), den = a * e - b * b;
            sp = den > 0 ? std::clamp((b * f - cc * e) / den, 0.0, 1.0) : 0.0;
            t = (b * sp + f) / e;
            if (t < 0) {
                t = 0;
                sp = std::clamp(-cc / a, 0.0, 1.0);
            } else if (t > 1) {
                t = 1;
                sp = std::clamp((b - cc) / a, 0.0, 1.0);
            }
        }
    }
    double s2 = 0;
    for (int k = 0; k < 3; k++) {
        double x = p0[k] + d1[k] * sp - (q0[k] + d2[k] * t);
        s2 += x * x;
    }
    return s2;
}

/* Are shape a (with a capsule) and shape b certainly apart: b's capsule,
 * or else its bounding sphere, clears a's capsule by the margin? */
bool caps_apart(const Shape &a, const Shape &b)
{
    double r = a.cap_r + MPB__CAP_MARGIN;
    if (b.has_cap) {
        r += b.cap_r;
        return seg_seg_dist2(a.wcap[0], a.wcap[1], b.wcap[0], b.wcap[1]) > r * r;
    }
    r += b.bradius;
    return seg_seg_dist2(a.wcap[0], a.wcap[1], b.wcenter, b.wcenter) > r * r;
}

/* How far mesh shape s reaches along world direction d: max of d . x
 * over its vertices x in the world, and the (first) vertex there, an index
 * in s.verts. Only the vertices listed for d's cell are scanned: the same
 * value and vertex as a scan of all (dirtable.h). The least is
 * -mesh_reach(-d), to the bit: negation is exact. */
void mesh_reach(const Shape &s, const double d[3], double &hi, int &ihi)
{
    const double *R = s.world.R;
    double l[3];              /* d in the mesh's frame */
    for (int k = 0; k < 3; k++)
        l[k] = R[k] * d[0] + R[3 + k] * d[1] + R[6 + k] * d[2];
    double off = s.world.t[0] * d[0] + s.world.t[1] * d[1] + s.world.t[2] * d[2];
    int c = s.dirs ? mpb__dirtable_cell(s.dirs, l) : -1;
    const int *list = c >= 0 ? &s.dirs->idx[s.dirs->start[c]] : nullptr;
    int n = c >= 0 ? s.dirs->start[c + 1] - s.dirs->start[c] : s.num_verts;
    hi = -INFINITY;
    ihi = 0;
    for (int k = 0; k < n; k++) {
        int i = list ? list[k] : k;
        const double *v = s.verts[i].data();
        double x = v[0] * l[0] + v[1] * l[1] + v[2] * l[2];
        if (x > hi) {
            hi = x;
            ihi = i;
        }
    }
    hi += off;
}

/*
 * The widest gap found between mesh a and a convex set B: the most, over
 * the directions tried, of (min over B of d . x - max over a's vertices of
 * d . x) / |d|, a lower bound on their distance (every point of the mesh
 * lies within its vertices' hull). The directions: d, then those of a GJK
 * search for the nearest points of the two (simplex.h), each from the
 * points that came out nearest along the last ones, until a gap passes
 * stop, the two come within stop (no gap can pass it), or no nearer point
 * is found. Each gap is exact on its own (mesh_reach()), so a poor
 * direction costs time, never a wrong answer. lowest(d, lo): B's min
 * along d, and which point of B is there; point(which, p): that point
 * (world).
 */
template <class Lowest, class Point>
double gjk_gap(const Shape &a, const Lowest &lowest, const Point &point,
               double d[3], double stop)
{
    double simplex[4][3], best = -INFINITY;
    int m = 0;
    for (int iter = 0; iter < MPB__GJK_STEPS; iter++) {
        double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], n = std::sqrt(dd);
        /* past the first, d is a point of B less one of a's hull: the
           two are within |d| */
        if (!(n > 1e-12) || (iter > 0 && !(n > stop)))
            return best;
        double ahi, blo, pa[3], pb[3], w[3];
        int iahi;
        mesh_reach(a, d, ahi, iahi);
        int which = lowest(d, blo);
        if (blo - ahi > stop * n)
            return (blo - ahi) / n;
        best = std::max(best, (blo - ahi) / n);
        point(which, pb);
        mpb_pose_apply(&a.world, a.verts[iahi].data(), pa);
        for (int k = 0; k < 3; k++)
            w[k] = pb[k] - pa[k];
        /* no nearer point of the difference along d: d is about the
           nearest */
        if (iter > 0 && dd - (d[0] * w[0] + d[1] * w[1] + d[2] * w[2]) <= 1e-9 * dd)
            return best;
        memcpy(simplex[m++], w, sizeof w);
        m = mpb__simplex_nearest(simplex, m, d);
        if (m == 0 || m == 4)   /* they overlap */
            return best;
    }
    return best;
}

/*
 * Are meshes a and b certainly apart: is there a plane between all the
 * vertices of one and all of the other, with the margin (gjk_gap(), from
 * the line between the bounding spheres' centres)? Then their convex
 * hulls are apart, and the triangles within them too. Mesh pairs of robot
 * links near each other (two links apart along the arm) are mostly told
 * apart here, where FCL's BVH traversal went hundreds of box tests deep.
 */
bool meshes_apart(const Shape &a, const Shape &b)
{
    double d[3];
    for (int k = 0; k < 3; k++)
        d[k] = b.wcenter[k] - a.wcenter[k];
    auto lowest = [&b](const double *dir, double &lo) {
        double nd[3] = {-dir[0], -dir[1], -dir[2]};
        int i;
        mesh_reach(b, nd, lo, i);
        lo = -lo;
        return i;
    };
    auto point = [&b](int i, double p[3]) {
        mpb_pose_apply(&b.world, b.verts[i].data(), p);
    };
    return gjk_gap(a, lowest, point, d, MPB__CAP_MARGIN) > MPB__CAP_MARGIN;
}

/*
 * A lower bound on the distance from mesh a to static ss: the widest gap
 * between a's vertices and ss's box (which holds the static) along one of
 * the box's axes or the line between their centres (every point of the
 * mesh lies within its vertices' hull); with search, unless that passes
 * stop, also along the directions of gjk_gap() from that line: tighter,
 * for a distance query to skip the pair by. A few dozen dot products:
 * far cheaper than the FCL distance it may spare.
 */
double mesh_static_lower(const Shape &a, const Shape &ss, double stop, bool search)
{
    const double *R = ss.world.R;
    double c[3];              /* the box's centre in the world */
    mpb_pose_apply(&ss.world, ss.lbox_c, c);
    double gap = -INFINITY, d[3];
    for (int k = 0; k < 4; k++) {
        if (k < 3) {
            d[0] = R[k], d[1] = R[3 + k], d[2] = R[6 + k];
        } else {
            for (int i = 0; i < 3; i++)
                d[i] = c[i] - a.wcenter[i];
            double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            if (!(n > 1e-12))
                break;
            for (int i = 0; i < 3; i++)
                d[i] /= n;
        }
        double mid = c[0] * d[0] + c[1] * d[1] + c[2] * d[2], half = 0;
        for (int j = 0; j < 3; j++)
            half += ss.lbox_h[j] * std::fabs(R[j] * d[0] + R[3 + j] * d[1] + R[6 + j] * d[2]);
        double lo, hi, nd[3] = {-d[0], -d[1], -d[2]};
        int ilo, ihi;
        mesh_reach(a, d, hi, ihi);
        mesh_reach(a, nd, lo, ilo);
        lo = -lo;
        gap = std::max(gap, std::max(lo - (mid + half), (mid - half) - hi));
    }
    if (!search || gap - MPB__CAP_MARGIN > stop)
        return gap - MPB__CAP_MARGIN;
    auto lowest = [&](const double *dir, double &lo) {
        int corner = 0;       /* bit j: the box's + side along axis j */
        lo = c[0] * dir[0] + c[1] * dir[1] + c[2] * dir[2];
        for (int j = 0; j < 3; j++) {
            double along = R[j] * dir[0] + R[3 + j] * dir[1] + R[6 + j] * dir[2];
            lo -= ss.lbox_h[j] * std::fabs(along);
            corner |= (along <= 0) << j;
        }
        return corner;
    };
    auto point = [&](int corner, double p[3]) {
        for (int k = 0; k < 3; k++) {
            p[k] = c[k];
            for (int j = 0; j < 3; j++)
                p[k] += (corner >> j & 1 ? ss.lbox_h[j] : -ss.lbox_h[j]) * R[3 * k + j];
        }
    };
    for (int i = 0; i < 3; i++)
        d[i] = c[i] - a.wcenter[i];
    gap = std::max(gap, gjk_gap(a, lowest, point, d, stop + MPB__CAP_MARGIN));
    return gap - MPB__CAP_MARGIN;
}

/* The ends of a's capsule in the frame of static ss's box, from its centre. */
void cap_in_box(const Shape &a, const Shape &ss, double e[2][3])
{
    const double *R = ss.world.R;
    for (int i = 0; i < 2; i++) {
        double d[3];
        for (int k = 0; k < 3; k++)
            d[k] = a.wcap[i][k] - ss.world.t[k];
        for (int k = 0; k < 3; k++)
            e[i][k] = R[k] * d[0] + R[3 + k] * d[1] + R[6 + k] * d[2] - ss.lbox_c[k];
    }
}

/* Does a's capsule certainly miss static ss: its segment misses ss's box
 * grown by the radius and the margin (which holds every point within
 * that distance of the box)? */
bool cap_misses_static(const Shape &a, const Shape &ss)
{
    double e[2][3], t0 = 0, t1 = 1;
    cap_in_box(a, ss, e);
    for (int k = 0; k < 3; k++) {
        double h = ss.lbox_h[k] + a.cap_r + MPB__CAP_MARGIN, d = e[1][k] - e[0][k];
        if (std::fabs(d) < 1e-300) {
            if (e[0][k] < -h || e[0][k] > h)
                return true;
            continue;
        }
        double ta = (-h - e[0][k]) / d, tb = (h - e[0][k]) / d;
        if (ta > tb)
            std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 > t1)
            return true;
    }
    return false;
}

/* A lower bound on the distance from a's capsule to static ss: the widest
 * gap along one axis of ss's box, or to its bounding sphere, less the
 * radii. */
double cap_static_lower(const Shape &a, const Shape &ss)
{
    double e[2][3], gap = 0;
    cap_in_box(a, ss, e);
    for (int k = 0; k < 3; k++) {
        double lo = std::min(e[0][k], e[1][k]), hi = std::max(e[0][k], e[1][k]);
        gap = std::max(gap, std::max(lo - ss.lbox_h[k], -ss.lbox_h[k] - hi));
    }
    double sph = std::sqrt(seg_seg_dist2(a.wcap[0], a.wcap[1], ss.wcenter,
                                         ss.wcenter)) - ss.bradius;
    return std::max(gap, sph) - a.cap_r - MPB__CAP_MARGIN;
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
    if (ms.has_cap &&
        !(cap_static_lower(ms, c->sshapes[(size_t)l.shape]) < q->best))
        return;
    sync(ms);
    double d = pair_distance(c, ms.obj.get(), st);
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
 * Place shape s at s.world: its exact world AABB (a cone gets its
 * cylinder's) and its bounding sphere's centre; its FCL transform only
 * when FCL needs it (sync). Plain doubles, so that it stays cheap in
 * unoptimised builds too.
 */
void place_shape(Shape &s)
{
    const Obj *o = s.obj.get();
    s.stale = true;
    const double *R = s.world.R, *d = s.dims;
    double c[3] = { s.world.t[0], s.world.t[1], s.world.t[2] }, e[3];
    switch (s.type) {
    case MPB_SHAPE_BOX:
        for (int i = 0; i < 3; i++)
            e[i] = (std::fabs(R[3 * i]) * d[0] + std::fabs(R[3 * i + 1]) * d[1] +
                    std::fabs(R[3 * i + 2]) * d[2]) / 2;
        break;
    case MPB_SHAPE_SPHERE:
        e[0] = e[1] = e[2] = d[0];
        break;
    case MPB_SHAPE_CAPSULE:
        for (int i = 0; i < 3; i++)
            e[i] = std::fabs(R[3 * i + 2]) * d[1] / 2 + d[0];
        break;
    case MPB_SHAPE_CYLINDER:
    case MPB_SHAPE_CONE:
        for (int i = 0; i < 3; i++) {
            double a = R[3 * i + 2];
            e[i] = std::fabs(a) * d[1] / 2 + d[0] * std::sqrt(std::max(0.0, 1 - a * a));
        }
        break;
    default: {
        const fcl::AABBd &local = o->collisionGeometry()->aabb_local;
        double lc[3], lh[3];
        for (int k = 0; k < 3; k++) {
            lc[k] = (local.min_[k] + local.max_[k]) / 2;
            lh[k] = (local.max_[k] - local.min_[k]) / 2;
        }
        mpb_pose_apply(&s.world, lc, c);
        for (int i = 0; i < 3; i++)
            e[i] = std::fabs(R[3 * i]) * lh[0] + std::fabs(R[3 * i + 1]) * lh[1] +
                   std::fabs(R[3 * i + 2]) * lh[2];
        break;
    }
    }
    for (int k = 0; k < 3; k++) {
        s.box.lo[k] = c[k] - e[k];
        s.box.hi[k] = c[k] + e[k];
    }
    if (s.bcenter[0] == 0 && s.bcenter[1] == 0 && s.bcenter[2] == 0) {
        for (int k = 0; k < 3; k++)
            s.wcenter[k] = s.world.t[k];
    } else {
        double bc[3] = { s.bcenter[0], s.bcenter[1], s.bcenter[2] };
        mpb_pose_apply(&s.world, bc, s.wcenter);
    }
    if (s.has_cap) {
        mpb_pose_apply(&s.world, s.cap[0], s.wcap[0]);
        mpb_pose_apply(&s.world, s.cap[1], s.wcap[1]);
    }
}

/* Set s.bcenter and s.bradius (s.obj, s.type and s.dims set). */
void bounding_sphere(Shape &s)
{
    const double *d = s.dims;
    s.bcenter = fcl::Vector3d(0, 0, 0);
    switch (s.type) {
    case MPB_SHAPE_BOX:
        s.bradius = 0.5 * std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        break;
    case MPB_SHAPE_SPHERE:
        s.bradius = d[0];
        break;
    case MPB_SHAPE_CAPSULE:
        s.bradius = d[1] / 2 + d[0];
        break;
    case MPB_SHAPE_CYLINDER:
    case MPB_SHAPE_CONE:
        s.bradius = std::hypot(d[0], d[1] / 2);
        break;
    default:
        s.bcenter = s.obj->collisionGeometry()->aabb_center;
        s.bradius = s.obj->collisionGeometry()->aabb_radius;
        break;
    }
}

void place_body(mpb_collision *c, Movable &m)
{
    bool first = true;
    m.placed++;
    for (int si : m.shapes) {
        Shape &sh = c->mshapes[(size_t)si];
        if (sh.offset_pure) {       /* the same product, without the zeros */
            const double *R = m.pose.R, *v = sh.offset.t;
            memcpy(sh.world.R, R, sizeof sh.world.R);
            for (int i = 0; i < 3; i++)
                sh.world.t[i] = R[3 * i] * v[0] + R[3 * i + 1] * v[1] +
                                R[3 * i + 2] * v[2] + m.pose.t[i];
        } else {
            mpb_pose_mul(&m.pose, &sh.offset, &sh.world);
        }
        place_shape(sh);
        if (first)
            m.box = sh.box;
        else
            box_add(m.box, sh.box);
        first = false;
    }
}

int check_args(mpb_collision *c, int id, const mpb_geometry *g, const mpb_pose *pose,
               bool movable)
{
    if (id < 0 || id > MPB_COLLISION_MAX_ID) {
        c->set_err("collision: id %d out of range 0..%d", id, MPB_COLLISION_MAX_ID);
        return MPB_EINVAL;
    }
    char why[200];
    if (mpb_geometry_check(g, why, sizeof why) != MPB_OK) {
        c->set_err("collision: %s %d: %s", movable ? "movable" : "static", id, why);
        return MPB_EINVAL;
    }
    if (movable && g->type == MPB_SHAPE_PLANE) {
        c->set_err("collision: movable %d: a plane can only be static", id);
        return MPB_EINVAL;
    }
    if (pose && (!mpb_pose_is_rigid(pose) || !finite_pose(pose))) {
        c->set_err("collision: %s %d: pose is not finite, too far (%g m at most) "
                   "or its R is not a rotation", movable ? "movable" : "static",
                   id, MPB_COLLISION_MAX_COORD);
        return MPB_EINVAL;
    }
    return MPB_OK;
}

/* Make the next push_back unable to throw (amortised doubling). */
template <class V>
void room_for_one(V &v)
{
    if (v.size() == v.capacity())
        v.reserve(2 * v.size() + 4);
}

template <class F>
int guarded(mpb_collision *c, F f)
{
    try {
        return f();
    } catch (const std::bad_alloc &) {
        if (c)
            c->set_err("collision: out of memory");
        return MPB_ENOMEM;
    } catch (const std::exception &e) {
        if (c)
            c->set_err("collision: FCL: %s", e.what());
        return MPB_EERROR;
    } catch (...) {
        if (c)
            c->set_err("collision: unexpected exception");
        return MPB_EERROR;
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

} // namespace

extern "C" {

const char *mpb_shape_type_name(int type)
{
    switch (type) {
    case MPB_SHAPE_BOX:      return "box";
    case MPB_SHAPE_SPHERE:   return "sphere";
    case MPB_SHAPE_CYLINDER: return "cylinder";
    case MPB_SHAPE_CONE:     return "cone";
    case MPB_SHAPE_CAPSULE:  return "capsule";
    case MPB_SHAPE_PLANE:    return "plane";
    case MPB_SHAPE_MESH:     return "mesh";
    }
    return "unknown";
}

int mpb_geometry_check(const mpb_geometry *g, char *err, size_t errlen)
{
    if (!g) {
        mpb__set_err(err, errlen, "no geometry");
        return MPB_EINVAL;
    }
    /* The type's bits as an int: a C caller may pass any value, and in C++
       loading an enum out of its range is undefined. */
    int type;
    static_assert(sizeof type == sizeof g->type, "enum size");
    memcpy(&type, &g->type, sizeof type);
    int n = 0;
    switch (type) {
    case MPB_SHAPE_BOX:      n = 3; break;
    case MPB_SHAPE_SPHERE:   n = 1; break;
    case MPB_SHAPE_CYLINDER:
    case MPB_SHAPE_CONE:
    case MPB_SHAPE_CAPSULE:  n = 2; break;
    case MPB_SHAPE_PLANE: {
        /* Its coefficients are no lengths: only where it lies is bounded. */
        fcl::Vector3d unit;
        double dist;
        for (int i = 0; i < 4; i++)
            if (!std::isfinite(g->dims[i])) {
                mpb__set_err(err, errlen, "plane: coefficient %c is not finite",
                             "abcd"[i]);
                return MPB_EINVAL;
            }
        if (!plane_unit(g->dims, unit, dist)) {
            mpb__set_err(err, errlen, "plane: normal (a, b, c) is zero");
            return MPB_EINVAL;
        }
        if (!(std::fabs(dist) <= MPB_COLLISION_MAX_COORD)) {
            mpb__set_err(err, errlen, "plane: %g m from the origin, beyond %g m",
                         std::fabs(dist), MPB_COLLISION_MAX_COORD);
            return MPB_EINVAL;
        }
        return MPB_OK;
    }
    case MPB_SHAPE_MESH: {
        char why[160];
        if (mpb_mesh_check(g->mesh, why, sizeof why) != MPB_OK) {
            mpb__set_err(err, errlen, "mesh: %s", why);
            return MPB_EINVAL;
        }
        for (long i = 0; i < 3L * g->mesh->num_vertices; i++)
            if (std::fabs(g->mesh->vertices[i]) > MPB_COLLISION_MAX_COORD) {
                mpb__set_err(err, errlen, "mesh: vertex %ld is beyond %g m", i / 3,
                             MPB_COLLISION_MAX_COORD);
                return MPB_EINVAL;
            }
        return MPB_OK;
    }
    default:
        mpb__set_err(err, errlen, "unknown shape type %d", type);
        return MPB_EINVAL;
    }
    const char *name = mpb_shape_type_name(type);
    for (int i = 0; i < n; i++) {
        if (!std::isfinite(g->dims[i])) {
            mpb__set_err(err, errlen, "%s: dimension %d is not finite", name, i + 1);
            return MPB_EINVAL;
        }
        if (std::fabs(g->dims[i]) > MPB_COLLISION_MAX_COORD) {
            mpb__set_err(err, errlen, "%s: dimension %d (%g) is beyond %g m", name,
                         i + 1, g->dims[i], MPB_COLLISION_MAX_COORD);
            return MPB_EINVAL;
        }
        /* a capsule's radius gives it volume whatever its length */
        double least = type == MPB_SHAPE_CAPSULE && i == 1 ? 0.0 : MPB_COLLISION_MIN_SIZE;
        if (!(g->dims[i] >= least)) {
            mpb__set_err(err, errlen, "%s: dimension %d (%g) is %s", name, i + 1,
                         g->dims[i], g->dims[i] < 0 ? "negative" :
                         "below " MPB__STR(MPB_COLLISION_MIN_SIZE) " m");
            return MPB_EINVAL;
        }
    }
    return MPB_OK;
}

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

int mpb_collision_allow_pair(mpb_collision *c, int movable_a, int movable_b)
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

int mpb_collision_allow_static(mpb_collision *c, int movable, int static_id)
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

int mpb_collision_check_self(mpb_collision *c, int *a, int *b)
{
    if (a)
        *a = -1;
    if (b)
        *b = -1;
    if (!c)
        return MPB_EINVAL;
    return guarded(c, [&]() -> int {
        if (c->pairs_dirty) {
            size_t n = c->movables.size();
            c->self_pairs.clear();
            for (size_t i = 0; i < n; i++)
                for (size_t j = i + 1; j < n; j++)
                    if (!c->is_allowed(i, j))
                        c->self_pairs.emplace_back((int)i, (int)j);
            c->pairs_dirty = false;
        }
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

int mpb_collision_check_pair(mpb_collision *c, int movable_a, int movable_b)
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

int mpb_collision_set_self_only(mpb_collision *c, int id, int self_only)
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
           finely): the last nearest pair gives a tight bound to prune with. */
        if (c->seed_m >= 0 && (size_t)c->seed_m < c->mshapes.size() &&
            c->seed_s >= 0 && (size_t)c->seed_s < c->sshapes.size()) {
            const Shape &ms = c->mshapes[(size_t)c->seed_m];
            const Shape &ss = c->sshapes[(size_t)c->seed_s];
            const Movable &mv = c->movables[(size_t)ms.body];
            if (mv.enabled && !mv.self_only && !allowed_static(&mv, ss.body)) {
                sync(ms);
                q.best = pair_distance(c, ms.obj.get(), ss.obj.get());
                q.best_m = q.seed_m = ms.obj.get();
                q.best_s = q.seed_s = ss.obj.get();
                q.static_id = ss.body;
                best_movable = mv.id;
            }
        }
        /* The statics that may be nearer than the bound to the robot as
           a whole: for a robot among a few dozen obstacles, few are. */
        Box3 all;
        bool among = false;
        if (robot_box(c, all)) {
            if (q.best < std::numeric_limits<double>::infinity())
                gather_near(c, all, q.best);
            else
                gather_where(c, [](const Box3 &) { return true; });
            among = c->cand.size() <= MPB__FEW;
        }
        if (among) {
            /* Best first: every (shape, static) pair with its cheap lower
               bound, nearest first, measured until a bound is no better
               than the best distance so far. The first measured is
               mostly the nearest: one or two FCL distances, where mesh
               links measured in body order took dozens. */
            c->near.clear();
            c->near.reserve(c->mshapes.size() * c->cand.size());
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
                        if (sh.has_cap)
                            lower = std::max(lower, cap_static_lower(sh, ss));
                        if (lower < q.best)
                            c->near.push_back({lower, si, i});
                    }
                }
            }
            std::sort(c->near.begin(), c->near.end(),
                      [](const mpb_collision::Near &a, const mpb_collision::Near &b) {
                          return a.lower < b.lower;
                      });
            for (const auto &p : c->near) {
                if (!(p.lower < q.best) || q.best <= 0.0)
                    break;
                const Shape &sh = c->mshapes[(size_t)p.shape];
                const Leaf &l = c->leaves[(size_t)p.leaf];
                const Shape &ss = c->sshapes[(size_t)l.shape];
                const Obj *st = ss.obj.get();
                if (sh.num_verts > 0 && !(mesh_static_lower(sh, ss, q.best, true) < q.best))
                    continue;
                sync(sh);
                double d = pair_distance(c, sh.obj.get(), st);
                if (d < q.best) {
                    q.best = d;
                    q.best_m = sh.obj.get();
                    q.best_s = st;
                    q.static_id = l.body;
                    best_movable = c->movables[(size_t)sh.body].id;
                }
            }
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

int mpb_collision_num_static_shapes(const mpb_collision *c)
{
    return c ? (int)(c->sshapes.size() + c->planes.size()) : 0;
}

int mpb_collision_num_movable_shapes(const mpb_collision *c)
{
    return c ? (int)c->mshapes.size() : 0;
}

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

double mpb__collision_pair_distance(mpb_collision *c, int a, int b, double below)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    Movable *ma = c ? c->find_or_err(a) : nullptr;
    Movable *mb = ma ? c->find_or_err(b) : nullptr;
    if (!ma || !mb || ma == mb)
        return nan;
    double best = below;
    int rc = guarded(c, [&]() -> int {
        for (int si : ma->shapes)
            for (int sj : mb->shapes) {
                const Shape &x = c->mshapes[(size_t)si], &y = c->mshapes[(size_t)sj];
                sync(x);
                sync(y);
                /* FCL keeps only what is nearer than the result holds:
                 * started at the best so far, it skips the rest. */
                c->dres.clear();
                c->dres.min_distance = best;
                double d = fcl::distance(x.obj.get(), y.obj.get(), c->dreq, c->dres);
                best = std::min(best, d < 0 ? 0.0 : d);
            }
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
