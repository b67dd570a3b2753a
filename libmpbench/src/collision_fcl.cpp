/*
 * collision_fcl.cpp - the collision world of collision.h over FCL 0.7:
 * static shapes in a dynamic AABB tree, movable bodies made of shapes at
 * fixed offsets, collision and distance queries that allocate nothing. The
 * C++ stays inside; every extern "C" function catches every exception.
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
 *     AABBs are set instead (TightObj), a cheap win for long links;
 *   - libccd's MPR loops forever on degenerate shapes (zero radius, flat
 *     boxes, aspect ratios ~1e14) and the AABB tree crashes on coordinates
 *     ~1e306: sizes and coordinates are bounded (collision.h).
 */
#include "mpbench/mpbench.h"
#include "mpbench/collision.h"

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
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
#include <new>
#include <vector>

#define MPB__STR2(x) #x
#define MPB__STR(x) MPB__STR2(x)

namespace {

using Obj = fcl::CollisionObjectd;
using Geom = fcl::CollisionGeometryd;

/*
 * A collision object whose world AABB is set here: FCL's computeAABB()
 * bounds a rotated shape by its bounding sphere, too loose for long links.
 */
struct TightObj : public Obj {
    using Obj::Obj;
    void set_aabb(const fcl::AABBd &b) { aabb = b; }
};

struct Shape {
    std::unique_ptr<TightObj> obj;
    mpb_pose             offset;   /* movable: in the body's frame */
    mpb_pose             world;    /* where it is (plain doubles: cheap to
                                      keep current, even unoptimised) */
    int                  body;     /* movable: index in movables; static: id */
    mpb_shape_type       type;
    double               dims[4];
    fcl::Vector3d        bcenter;  /* a bounding sphere, own frame */
    double               bradius;
    double               wcenter[3]; /* bcenter in the world, kept current */
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
    std::vector<int>     shapes;          /* indices in mshapes */
    std::vector<int>     allowed_statics; /* static ids it may touch */
    mpb_pose             pose;
    fcl::AABBd           aabb;            /* of its shapes, at pose */
};

#if defined(__GNUC__)
__attribute__((format(printf, 3, 0)))
#endif
void fmt_err(char *buf, size_t len, const char *fmt, va_list ap)
{
    vsnprintf(buf, len, fmt, ap);
    for (char *p = buf; *p; p++)
        if (*p == '\n' || *p == '\r')
            *p = ' ';
}

void put_err(char *err, size_t errlen, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

void put_err(char *err, size_t errlen, const char *fmt, ...)
{
    if (!err || errlen == 0)
        return;
    va_list ap;
    va_start(ap, fmt);
    fmt_err(err, errlen, fmt, ap);
    va_end(ap);
}

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
        auto bvh = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
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
        fcl::Vector3d best = m->vertices[0];
        double bd = u.dot(best);
        for (int i = 1; i < m->num_vertices; i++) {
            double x = u.dot(m->vertices[i]);
            if (x > bd) {
                bd = x;
                best = m->vertices[i];
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
double plane_distance(const Shape &s, const Plane &p, fcl::Vector3d *pm,
                      fcl::Vector3d *pp)
{
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
    std::vector<Shape>   sshapes;        /* static shapes in the tree */
    std::vector<Plane>   planes;         /* static planes, kept out of FCL */
    fcl::DynamicAABBTreeCollisionManagerd tree;
    bool                 dirty = false;  /* sshapes changed since the build */
    int                  seed_m = -1;    /* the last nearest pair (shape */
    int                  seed_s = -1;    /* indices), tried first */
    fcl::CollisionRequestd creq;
    fcl::CollisionResultd  cres;
    fcl::DistanceRequestd  dreq;
    fcl::DistanceResultd   dres;
    char                 err[256] = "";

#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    void set_err(const char *fmt, ...)
    {
        va_list ap;
        va_start(ap, fmt);
        fmt_err(err, sizeof err, fmt, ap);
        va_end(ap);
    }

    Movable *find(int id)
    {
        if (id < 0 || (size_t)id >= movable_index.size() || movable_index[(size_t)id] < 0)
            return nullptr;
        return &movables[(size_t)movable_index[(size_t)id]];
    }

    bool is_allowed(size_t a, size_t b) const
    {
        return allowed[a * astride + b] != 0;
    }
};

namespace {

/* Per-query state handed to the FCL callbacks. */
struct Query {
    mpb_collision *c;
    const Movable *m;
    const Obj     *query;
    bool           hit;
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

const Shape &static_of(const mpb_collision *c, const Obj *o)
{
    return c->sshapes[(size_t)(intptr_t)o->getUserData()];
}

bool collide_cb(Obj *o1, Obj *o2, void *data)
{
    Query *q = static_cast<Query *>(data);
    Obj *st = (o2 == q->query) ? o1 : o2;
    const Shape &s = static_of(q->c, st);
    if (allowed_static(q->m, s.body))
        return false;
    q->c->cres.clear();
    fcl::collide(q->query, st, q->c->creq, q->c->cres);
    if (q->c->cres.isCollision()) {
        q->hit = true;
        q->static_id = s.body;
        return true;
    }
    return false;
}

/* FCL's distance of a pair, never negative. */
double pair_distance(mpb_collision *c, const Obj *a, const Obj *b)
{
    c->dres.clear();
    double d = fcl::distance(a, b, c->dreq, c->dres);
    return d < 0 ? 0.0 : d;
}

bool distance_cb(Obj *o1, Obj *o2, void *data, double &dist)
{
    Query *q = static_cast<Query *>(data);
    Obj *st = (o2 == q->query) ? o1 : o2;
    const Shape &s = static_of(q->c, st);
    const Shape &ms = q->c->mshapes[(size_t)(intptr_t)q->query->getUserData()];
    /* bounding spheres first: a lower bound for almost nothing */
    double dx = ms.wcenter[0] - s.wcenter[0], dy = ms.wcenter[1] - s.wcenter[1],
           dz = ms.wcenter[2] - s.wcenter[2];
    double lower = std::sqrt(dx * dx + dy * dy + dz * dz) - ms.bradius - s.bradius;
    if (lower < q->best && !(q->query == q->seed_m && st == q->seed_s) &&
        !allowed_static(q->m, s.body)) {
        double d = pair_distance(q->c, q->query, st);
        if (d < q->best) {
            q->best = d;
            q->best_m = q->query;
            q->best_s = st;
            q->static_id = s.body;
        }
    }
    dist = q->best;             /* prune the rest of the tree with it */
    return q->best <= 0.0;
}

int ensure_tree(mpb_collision *c)
{
    if (!c->dirty)
        return MPB_OK;
    c->tree.clear();
    std::vector<Obj *> objs;
    objs.reserve(c->sshapes.size());
    for (size_t i = 0; i < c->sshapes.size(); i++) {
        c->sshapes[i].obj->setUserData((void *)(intptr_t)i);
        objs.push_back(c->sshapes[i].obj.get());
    }
    c->tree.registerObjects(objs);
    c->tree.setup();
    c->dirty = false;
    return MPB_OK;
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

/*
 * Place shape s at s.world: its FCL transform, its exact world AABB (a
 * cone gets its cylinder's) and its bounding sphere's centre. Plain
 * doubles, so that it stays cheap in unoptimised builds too.
 */
void place_shape(Shape &s)
{
    TightObj *o = s.obj.get();
    fcl::Transform3d tf;
    set_tf(tf, s.world);
    o->setTransform(tf);
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
    o->set_aabb(fcl::AABBd(fcl::Vector3d(c[0] - e[0], c[1] - e[1], c[2] - e[2]),
                           fcl::Vector3d(c[0] + e[0], c[1] + e[1], c[2] + e[2])));
    double bc[3] = { s.bcenter[0], s.bcenter[1], s.bcenter[2] };
    mpb_pose_apply(&s.world, bc, s.wcenter);
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
    for (int si : m.shapes) {
        Shape &sh = c->mshapes[(size_t)si];
        Obj *o = sh.obj.get();
        mpb_pose_mul(&m.pose, &sh.offset, &sh.world);
        place_shape(sh);
        if (first)
            m.aabb = o->getAABB();
        else
            m.aabb += o->getAABB();
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
        put_err(err, errlen, "no geometry");
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
    case MPB_SHAPE_PLANE:    n = 4; break;
    case MPB_SHAPE_MESH: {
        char why[160];
        if (mpb_mesh_check(g->mesh, why, sizeof why) != MPB_OK) {
            put_err(err, errlen, "mesh: %s", why);
            return MPB_EINVAL;
        }
        for (long i = 0; i < 3L * g->mesh->num_vertices; i++)
            if (std::fabs(g->mesh->vertices[i]) > MPB_COLLISION_MAX_COORD) {
                put_err(err, errlen, "mesh: vertex %ld is beyond %g m", i / 3,
                        MPB_COLLISION_MAX_COORD);
                return MPB_EINVAL;
            }
        return MPB_OK;
    }
    default:
        put_err(err, errlen, "unknown shape type %d", type);
        return MPB_EINVAL;
    }
    const char *name = mpb_shape_type_name(type);
    for (int i = 0; i < n; i++) {
        if (!std::isfinite(g->dims[i])) {
            put_err(err, errlen, "%s: dimension %d is not finite", name, i + 1);
            return MPB_EINVAL;
        }
        if (std::fabs(g->dims[i]) > MPB_COLLISION_MAX_COORD) {
            put_err(err, errlen, "%s: dimension %d (%g) is beyond %g m", name,
                    i + 1, g->dims[i], MPB_COLLISION_MAX_COORD);
            return MPB_EINVAL;
        }
        /* a capsule's radius gives it volume whatever its length */
        double least = type == MPB_SHAPE_CAPSULE && i == 1 ? 0.0 : MPB_COLLISION_MIN_SIZE;
        if (type != MPB_SHAPE_PLANE && !(g->dims[i] >= least)) {
            put_err(err, errlen, "%s: dimension %d (%g) is %s", name, i + 1,
                    g->dims[i], g->dims[i] < 0 ? "negative" :
                    "below " MPB__STR(MPB_COLLISION_MIN_SIZE) " m");
            return MPB_EINVAL;
        }
    }
    if (type == MPB_SHAPE_PLANE && g->dims[0] == 0 && g->dims[1] == 0 && g->dims[2] == 0) {
        put_err(err, errlen, "plane: normal (a, b, c) is zero");
        return MPB_EINVAL;
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
            const double *d = g->dims;
            double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            fcl::Vector3d nl(d[0] / len, d[1] / len, d[2] / len);
            Plane p;
            p.n = tf.linear() * nl;
            p.d = d[3] / len + p.n.dot(tf.translation());
            p.id = id;
            c->planes.push_back(p);
            return MPB_OK;
        }
        std::shared_ptr<Geom> geom = make_geometry(g);
        if (!geom) {
            c->set_err("collision: static %d: FCL could not build the %s", id,
                       mpb_shape_type_name(g->type));
            return MPB_EINVAL;
        }
        Shape s;
        s.obj.reset(new TightObj(geom, tf));
        mpb_pose_identity(&s.offset);
        if (pose)
            s.world = *pose;
        else
            mpb_pose_identity(&s.world);
        s.body = id;
        s.type = g->type;
        memcpy(s.dims, g->dims, sizeof s.dims);
        bounding_sphere(s);
        place_shape(s);
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
        std::shared_ptr<Geom> geom = make_geometry(g);
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
            m = &c->movables.back();
        }
        room_for_one(m->shapes);
        mpb_pose_mul(&m->pose, &s.offset, &s.world);
        s.obj.reset(new TightObj(geom, to_tf(&s.world)));
        bounding_sphere(s);
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
    Movable *m = c->find(id);
    if (!m) {
        c->set_err("collision: no movable body %d", id);
        return MPB_ENOTFOUND;
    }
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
    Movable *m = c->find(id);
    if (!m) {
        c->set_err("collision: no movable body %d", id);
        return MPB_ENOTFOUND;
    }
    m->enabled = enabled != 0;
    return MPB_OK;
}

int mpb_collision_allow_pair(mpb_collision *c, int movable_a, int movable_b)
{
    if (!c)
        return MPB_EINVAL;
    Movable *a = c->find(movable_a), *b = c->find(movable_b);
    if (!a || !b) {
        c->set_err("collision: no movable body %d", a ? movable_b : movable_a);
        return MPB_ENOTFOUND;
    }
    if (a == b) {
        c->set_err("collision: a body cannot be paired with itself (%d)", movable_a);
        return MPB_EINVAL;
    }
    size_t ia = (size_t)c->movable_index[(size_t)movable_a];
    size_t ib = (size_t)c->movable_index[(size_t)movable_b];
    c->allowed[ia * c->astride + ib] = c->allowed[ib * c->astride + ia] = 1;
    return MPB_OK;
}

int mpb_collision_allow_static(mpb_collision *c, int movable, int static_id)
{
    if (!c)
        return MPB_EINVAL;
    Movable *m = c->find(movable);
    if (!m) {
        c->set_err("collision: no movable body %d", movable);
        return MPB_ENOTFOUND;
    }
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
        Query q = {};
        q.c = c;
        for (const Movable &m : c->movables) {
            if (!m.enabled)
                continue;
            q.m = &m;
            for (int si : m.shapes) {
                Obj *o = c->mshapes[(size_t)si].obj.get();
                q.query = o;
                c->tree.collide(o, &q, collide_cb);
                for (size_t k = 0; !q.hit && k < c->planes.size(); k++) {
                    const Plane &p = c->planes[k];
                    if (allowed_static(&m, p.id))
                        continue;
                    if (plane_distance(c->mshapes[(size_t)si], p, nullptr, nullptr) <= 0) {
                        q.hit = true;
                        q.static_id = p.id;
                    }
                }
                if (q.hit) {
                    if (movable)
                        *movable = m.id;
                    if (static_id)
                        *static_id = q.static_id;
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
        size_t n = c->movables.size();
        for (size_t i = 0; i < n; i++) {
            const Movable &mi = c->movables[i];
            if (!mi.enabled)
                continue;
            for (size_t j = i + 1; j < n; j++) {
                const Movable &mj = c->movables[j];
                if (!mj.enabled || c->is_allowed(i, j) || !mi.aabb.overlap(mj.aabb))
                    continue;
                for (int si : mi.shapes) {
                    const Obj *oi = c->mshapes[(size_t)si].obj.get();
                    for (int sj : mj.shapes) {
                        const Obj *oj = c->mshapes[(size_t)sj].obj.get();
                        if (!oi->getAABB().overlap(oj->getAABB()))
                            continue;
                        c->cres.clear();
                        fcl::collide(oi, oj, c->creq, c->cres);
                        if (c->cres.isCollision()) {
                            int x = mi.id, y = mj.id;
                            if (a)
                                *a = x < y ? x : y;
                            if (b)
                                *b = x < y ? y : x;
                            return 1;
                        }
                    }
                }
            }
        }
        return 0;
    });
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
            if (mv.enabled && !allowed_static(&mv, ss.body)) {
                q.best = pair_distance(c, ms.obj.get(), ss.obj.get());
                q.best_m = q.seed_m = ms.obj.get();
                q.best_s = q.seed_s = ss.obj.get();
                q.static_id = ss.body;
                best_movable = mv.id;
            }
        }
        for (const Movable &m : c->movables) {
            if (q.best <= 0.0)
                break;
            if (!m.enabled)
                continue;
            q.m = &m;
            for (int si : m.shapes) {
                const Shape &sh = c->mshapes[(size_t)si];
                Obj *o = sh.obj.get();
                q.query = o;
                double before = q.best;
                c->tree.distance(o, &q, distance_cb);
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

} // extern "C"
