/*
 * collision_world.h - private to geometry/'s C++ files: the collision
 * world's structures (struct mpb_collision, its shapes, bodies and static
 * tree) and the functions its files share, in namespace mpb::coll. The
 * files, each one concern:
 *   collision_fcl.cpp      the C API of collision.h (worlds, bodies, queries)
 *   collision_input.cpp    checks of what callers pass in
 *   collision_shapes.cpp   placing shapes, their boxes, spheres, capsules,
 *                          support points and planes
 *   collision_registry.cpp the BVH models shared by every world of a process
 *   collision_tree.cpp     the static tree
 *   collision_bounds.cpp   cheap "certainly apart" bounds (capsules, GJK gaps)
 *   collision_narrow.cpp   the narrow phase: FCL on the pairs that remain
 *   collision_depth.cpp    bounds on how deep overlapping pairs go
 * C++ only.
 */
#ifndef MPB_COLLISION_WORLD_H
#define MPB_COLLISION_WORLD_H

#include "mpbench/mpbench.h"
#include "mpbench/collision.h"
#include "core/cxx_guard.h"
#include "core/errbuf.h"
#include "geometry/dirtable.h"
#include "geometry/bvh_distance.h"

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
#include <exception>
#include <memory>
#include <mutex>
#include <new>
#include <utility>
#include <vector>

namespace mpb {
namespace coll {

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

inline void box_add(Box3 &a, const Box3 &b)
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
    const int           *vtri_start = nullptr, *vtris = nullptr; /* the
                                      triangles of each of verts (MeshModel) */
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

/* A mesh's BVH model, and those of its vertices that may be extreme
 * along some direction (hull.h) with the few of them that may be along
 * each cell of directions (dirtable.h), found for the first movable
 * shape that uses it: extents over them are those over all the vertices. */
struct MeshModel : fcl::BVHModel<fcl::OBBRSSd> {
    std::once_flag             extreme_once;
    std::vector<fcl::Vector3d> extreme;
    /* the triangles of extreme[i]: tris[tri_start[i] .. tri_start[i + 1]) */
    std::vector<int>           tri_start, tris;
    mpb__dirtable              dirs = {0, nullptr, nullptr};
    ~MeshModel() { mpb__dirtable_free(&dirs); }
};

} // namespace coll
} // namespace mpb

struct mpb_collision {
    using Shape = mpb::coll::Shape;
    using Plane = mpb::coll::Plane;
    using Movable = mpb::coll::Movable;
    using BNode = mpb::coll::BNode;
    using Leaf = mpb::coll::Leaf;

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
    std::vector<mpb::BvhQueued> bvh_heap; /* bvh_shape_distance()'s queue */
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

namespace mpb {
namespace coll {

/* Per-query state of a distance search. */
struct Query {
    mpb_collision *c;
    const Movable *m;
    int            static_id;
    double         best;
    const Obj     *best_m, *best_s;
    const Obj     *seed_m, *seed_s;   /* a pair measured before the search */
};

/* A collision check tests each movable shape against the statics near
 * the whole robot when there are at most this many, else walks the tree
 * for each shape. */
#define MPB__FEW 64
/* Leaves of at most this many statics. */
#define MPB__LEAF 4
/* Deep enough for any tree built below (median splits: depth ~ log2 n). */
#define MPB__STACK 128

/* The leaves whose boxes pass keep() into c->cand,
 * walking only the nodes whose boxes pass it (no allocation: its capacity
 * is every leaf). */
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

/* Make the next push_back unable to throw (amortised doubling). */
template <class V>
void room_for_one(V &v)
{
    if (v.size() == v.capacity())
        v.reserve(2 * v.size() + 4);
}

/* f(), every exception caught and turned into an error code and c's
 * message: what every extern "C" function runs its body through
 * (core/cxx_guard.h, as every C++ bridge of the library). */
template <class F>
int guarded(mpb_collision *c, F f)
{
    static const mpb__cxx_guard g = {"collision: ", "FCL: ", MPB_EERROR,
                                     "unexpected exception", MPB_EERROR};
    return mpb__cxx_guarded(c ? c->err : nullptr, c ? sizeof c->err : 0, g, f);
}

/* Hot and small: inline in every file. */
/* Write the pose p into FCL's 4x4 column-major matrix. */
inline void set_tf(fcl::Transform3d &tf, const mpb_pose &p)
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
inline void sync(const Shape &s)
{
    if (!s.stale)
        return;
    fcl::Transform3d tf;
    set_tf(tf, s.world);
    s.obj->setTransform(tf);
    s.stale = false;
}

/* Are the bounding spheres of two movable shapes apart, by far more than
 * FCL's tolerances (libccd's MPR stops at 1e-6)? Then the shapes cannot
 * collide. */
inline bool spheres_apart(const Shape &a, const Shape &b)
{
    double dx = a.wcenter[0] - b.wcenter[0], dy = a.wcenter[1] - b.wcenter[1],
           dz = a.wcenter[2] - b.wcenter[2];
    double r = a.bradius + b.bradius + 1e-4;
    return dx * dx + dy * dy + dz * dz > r * r;
}

/* collision_input.cpp */
/* Finite, and the translation within MPB_COLLISION_MAX_COORD. */
bool finite_pose(const mpb_pose *p);
/* The plane a x + b y + c z = d (dims) as a unit normal and its signed
 * distance from the origin; false if not finite or the normal is zero. */
bool plane_unit(const double dims[4], fcl::Vector3d &n, double &dist);
/* The checks of mpb_collision_add_*()'s arguments, into c's message. */
int check_args(mpb_collision *c, int id, const mpb_geometry *g, const mpb_pose *pose,
               bool movable);

/* collision_shapes.cpp */
fcl::Transform3d to_tf(const mpb_pose *p);
/* m's vertices that may be extreme along some direction (built once). */
const std::vector<fcl::Vector3d> &extreme_vertices(MeshModel &m);
/* The FCL geometry of g (g already checked), or nullptr on a BVH error. */
std::shared_ptr<Geom> make_geometry(const mpb_geometry *g);
bool is_bvh(const Obj *o);
/* The point of shape s (its own frame) farthest along direction u. */
fcl::Vector3d support(const Shape &s, const fcl::Vector3d &u);
/* Distance from shape s to plane p (0 if it reaches it); nearest points. */
double plane_distance(const Shape &s, const Plane &p, fcl::Vector3d *pm,
                      fcl::Vector3d *pp);
/* The capsule of a movable mesh that holds every vertex. */
void fit_capsule(Shape &s, const mpb_mesh *m);
/* A static's box in its own frame. */
void local_box(Shape &s);
/* Place shape s at s.world: its exact AABB, its sphere's and capsule's ends. */
void place_shape(Shape &s);
/* Set s.bcenter and s.bradius. */
void bounding_sphere(Shape &s);
/* Place every shape of m at m.pose; m.box their union. */
void place_body(mpb_collision *c, Movable &m);

/* collision_registry.cpp */
/* make_geometry(), a mesh's model shared with every world of the process. */
std::shared_ptr<Geom> shared_geometry(const mpb_geometry *g);

/* collision_tree.cpp */
int ensure_tree(mpb_collision *c);
/* The leaves whose boxes overlap b, into c->cand. */
void gather(mpb_collision *c, const Box3 &b);
/* The leaves whose boxes are nearer than d to b, into c->cand. */
void gather_near(mpb_collision *c, const Box3 &b, double d);
/* The union of the enabled movables' boxes into all; false if none. */
bool robot_box(const mpb_collision *c, Box3 &all);

/* collision_bounds.cpp */
/* The squared distance between segments p0 p1 and q0 q1, and the
 * parameters (0 to 1) of their nearest points along each. */
double seg_seg_nearest(const double p0[3], const double p1[3], const double q0[3],
                       const double q1[3], double *s_out, double *t_out);
/* Capsule tests skip a pair only when it clears by this much (m). */
#define MPB__CAP_MARGIN 1e-4
bool caps_apart(const Shape &a, const Shape &b);
/* How far mesh shape s reaches along world direction d (vertex ihi). */
void mesh_reach(const Shape &s, const double d[3], double &hi, int &ihi);
/* A lower bound on the distance between meshes a and b: the widest gap
 * between their vertex hulls (which hold them) along the directions of a
 * GJK search of the hulls' difference, from the line between their
 * centres, until a gap passes stop or no nearer point is found; -INFINITY
 * if no direction gave one (collision_bounds.cpp). */
double meshes_gap(const Shape &a, const Shape &b, double stop);
bool meshes_apart(const Shape &a, const Shape &b);
double mesh_static_lower(const Shape &a, const Shape &ss, double stop, bool search,
                         double *upper = nullptr, int *upper_vertex = nullptr);
/* The distance from world point p to static ss (INFINITY: no bound). */
double point_static_distance(const Shape &ss, const double p[3]);
/* The same, and the unit direction from ss's nearest point to p. */
double point_static_away(const Shape &ss, const double p[3], double u[3]);
/* Mesh a's distance to static ss if vertex i is provably nearest, or NaN. */
double mesh_static_vertex(const Shape &a, const Shape &ss, int i);
bool cap_misses_static(const Shape &a, const Shape &ss);
double cap_static_lower(const Shape &a, const Shape &ss);

/* collision_narrow.cpp */
bool allowed_static(const Movable *m, int static_id);
/* FCL's distance of a pair, never negative; or `below` if it is at
 * least that (FCL then skips what is further). */
double pair_distance(mpb_collision *c, const Obj *a, const Obj *b,
                     double below = INFINITY);
/* FCL's distance of movable shape ms and static ss, or `below` if it is
 * at least that; upper, if finite, bounds the distance from above (a
 * cutoff that prunes FCL's traversal, never the answer). */
double pair_distance_upper(mpb_collision *c, const Shape &ms, const Shape &ss,
                           double below, double upper, int upper_vertex = -1);
bool narrow_phase(mpb_collision *c, const Shape &a, const Shape &b);
int static_hit(mpb_collision *c, const Movable &m, const Shape &ms, bool among);
void static_distance(Query *q, const Shape &ms, bool among);
bool nearest_points(mpb_collision *c, const Obj *a, const Obj *b, double dist,
                    fcl::Vector3d &pa, fcl::Vector3d &pb);
bool bodies_touch(mpb_collision *c, const Movable &mi, const Movable &mj);
bool hinted_apart(const mpb_collision *c, int i, int j);
/* FCL's distance between movables mi and mj (their boxes first), or
 * `below` if it is at least that. */
double movables_distance(mpb_collision *c, const Movable &mi, const Movable &mj,
                         double below);
/* c->self_pairs: the movables i < j not allowed to touch, made again if
 * the allowed pairs changed. */
void ensure_self_pairs(mpb_collision *c);

} // namespace coll
} // namespace mpb

#endif /* MPB_COLLISION_WORLD_H */
