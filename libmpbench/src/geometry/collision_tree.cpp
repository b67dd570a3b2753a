/*
 * collision_tree.cpp - the collision world's static tree: a bounding-volume
 * tree of the static shapes over flat arrays of exact AABBs, built when
 * the statics change, walked with inline box tests.
 */
#include "geometry/collision_world.h"

namespace mpb {
namespace coll {

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

} // namespace coll
} // namespace mpb
