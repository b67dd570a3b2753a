/*
 * collision_shapes.cpp - the collision world's shapes: FCL geometry from
 * mpb_geometry, placing a shape (exact AABB, bounding sphere, capsule),
 * support points and the exact plane distance (collision_world.h).
 */
#include "geometry/collision_world.h"

#include "geometry/hull.h"

#include <cstring>

namespace mpb {
namespace coll {

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
        /* only the vertices of a triangle: each kept is then a point of
           the surface (mesh_static_vertex() relies on it) */
        std::vector<unsigned char> used((size_t)m.num_vertices, 0);
        for (int t = 0; t < m.num_tris; t++)
            for (int k = 0; k < 3; k++)
                used[(size_t)m.tri_indices[t][k]] = 1;
        std::vector<fcl::Vector3d> pts;
        std::vector<int> src;
        for (int i = 0; i < m.num_vertices; i++)
            if (used[(size_t)i]) {
                pts.push_back(m.vertices[i]);
                src.push_back(i);
            }
        if (pts.empty())
            return;
        std::vector<unsigned char> keep(pts.size());
        mpb__hull_keep(pts[0].data(), (int)pts.size(), keep.data());
        std::vector<int> at((size_t)m.num_vertices, -1);
        for (size_t i = 0; i < pts.size(); i++)
            if (keep[i]) {
                at[(size_t)src[i]] = (int)m.extreme.size();
                m.extreme.push_back(pts[i]);
            }
        /* each kept vertex's triangles, for bvh_distance.cpp's first guess */
        m.tri_start.assign(m.extreme.size() + 1, 0);
        for (int t = 0; t < m.num_tris; t++)
            for (int k = 0; k < 3; k++)
                if (at[(size_t)m.tri_indices[t][k]] >= 0)
                    m.tri_start[(size_t)at[(size_t)m.tri_indices[t][k]] + 1]++;
        for (size_t i = 0; i < m.extreme.size(); i++)
            m.tri_start[i + 1] += m.tri_start[i];
        m.tris.resize((size_t)m.tri_start.back());
        std::vector<int> fill(m.tri_start.begin(), m.tri_start.end() - 1);
        for (int t = 0; t < m.num_tris; t++)
            for (int k = 0; k < 3; k++) {
                int e = at[(size_t)m.tri_indices[t][k]];
                if (e >= 0)
                    m.tris[(size_t)fill[(size_t)e]++] = t;
            }
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

} // namespace coll
} // namespace mpb
