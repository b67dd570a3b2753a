/* world_bodies.c - a world's bodies, their shapes and poses, for drawing (bodies.h). */
#include "mpbench/mpbench.h"
#include "mpbench/bodies.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/errbuf.h"
#include "core/grow.h"
#include "model/world_provider.h"
#include "core/mathconst.h"
#include "geometry/collision_internal.h"

/* Where a body comes from, to place it and to map collision ids to it. */
typedef struct body_src {
    int first_shape; /* its shapes: first_shape .. + num_shapes - 1 */
    int link;        /* urdf: the link it is, or carries it; planar: link */
    int object;      /* urdf: scene object index, -1 for a link */
    mpb_pose fixed;  /* a world object's pose (or a carried one's offset in
                        its link's frame) */
} body_src;

struct mpb_bodies {
    mpb_world      *world;
    int             urdf;          /* else planar */
    mpb__urdf_model model;
    mpb__planar_model planar;
    int             num, cap;
    mpb_body       *bodies;
    body_src       *src;
    char          **names;         /* the names made here (planar) */
    mpb_body_shape *shapes;        /* all shapes, bodies point into it */
    int             num_shapes, cap_shapes;
    mpb_pose       *links;         /* urdf: FK scratch, num_links */
    int             num_links;
    int            *link_body;     /* urdf: link -> body, -1 if none */
    int            *object_body;   /* urdf: scene object -> body */
    double         *xy;            /* planar: FK scratch */
};

/* Append a body; its shapes are the ones added after it. */
static int add_body(mpb_bodies *b, const char *name, int robot, int moves,
                    body_src src)
{
    if (b->num == b->cap) {
        /* Two arrays of one capacity, each grown from the same one. */
        int cap[2] = {b->cap, b->cap};
        if (mpb__grow((void **)&b->bodies, &cap[0], b->num + 1,
                      sizeof *b->bodies) != MPB_OK ||
            mpb__grow((void **)&b->src, &cap[1], b->num + 1, sizeof *b->src) !=
                MPB_OK)
            return MPB_ENOMEM;
        b->cap = cap[0];
    }
    b->bodies[b->num] = (mpb_body){name, robot, moves, 0, NULL};
    src.first_shape = b->num_shapes;
    b->src[b->num++] = src;
    return MPB_OK;
}

static int add_shape(mpb_bodies *b, const mpb_geometry *g,
                     const mpb_pose *offset, const float color[4])
{
    if (mpb__grow((void **)&b->shapes, &b->cap_shapes, b->num_shapes + 1,
                  sizeof *b->shapes) != MPB_OK)
        return MPB_ENOMEM;
    mpb_body_shape *s = &b->shapes[b->num_shapes++];
    s->geometry = *g;
    s->offset = *offset;
    for (int i = 0; i < 4; i++)
        s->color[i] = color ? color[i] : 0.0f;
    b->bodies[b->num - 1].num_shapes++;
    return MPB_OK;
}

/* Once every shape is in: bodies point into the final shapes array. */
static void fix_shapes(mpb_bodies *b)
{
    for (int i = 0; i < b->num; i++)
        b->bodies[i].shapes = b->shapes + b->src[i].first_shape;
}

static int open_urdf(mpb_bodies *b)
{
    const mpb__urdf_model *m = &b->model;
    const mpb_robot *r = m->robot;
    int rc, mesh = 0, nobj = mpb_scene_num_objects(m->scene);
    b->num_links = mpb_robot_num_links(r);
    b->links = calloc((size_t)b->num_links + 1, sizeof *b->links);
    b->link_body = malloc(((size_t)b->num_links + 1) * sizeof *b->link_body);
    b->object_body = malloc(((size_t)nobj + 1) * sizeof *b->object_body);
    if (!b->links || !b->link_body || !b->object_body)
        return MPB_ENOMEM;
    for (int l = 0; l < b->num_links; l++) {
        const mpb_robot_link *link = mpb_robot_get_link(r, l);
        b->link_body[l] = -1;
        if (link->num_collisions == 0)
            continue;
        b->link_body[l] = b->num;
        if ((rc = add_body(b, link->name, 1, link->moves,
                           (body_src){.link = l, .object = -1})) != MPB_OK)
            return rc;
        for (int k = 0; k < link->num_collisions; k++) {
            const mpb_robot_collision *c =
                mpb_robot_get_collision(r, link->first_collision + k);
            mpb_geometry g = {.type = c->type};
            memcpy(g.dims, c->dims, sizeof g.dims);
            if (c->type == MPB_SHAPE_MESH) {
                if (mesh >= m->num_meshes)
                    return MPB_EINVAL;
                g.mesh = m->meshes[mesh++];
            }
            if ((rc = add_shape(b, &g, &c->origin, NULL)) != MPB_OK)
                return rc;
        }
    }
    for (int k = 0; k < nobj; k++) {
        const mpb_scene_object *o = mpb_scene_object_at(m->scene, k);
        b->object_body[k] = -1;
        if (o->num_shapes == 0)
            continue;
        int l = o->attached_link ? mpb_robot_link_index(r, o->attached_link)
                                 : -1;
        int moves = l >= 0 && mpb_robot_get_link(r, l)->moves;
        b->object_body[k] = b->num;
        if ((rc = add_body(b, o->id, l >= 0, moves,
                           (body_src){.link = l, .object = k,
                                      .fixed = o->pose})) != MPB_OK)
            return rc;
        for (int s = 0; s < o->num_shapes; s++)
            if ((rc = add_shape(b, &o->shapes[s].geometry, &o->shapes[s].pose,
                                o->shapes[s].color)) != MPB_OK)
                return rc;
    }
    return MPB_OK;
}

/* The planar obstacles' height (bodies.h). */
static double planar_height(const mpb__planar_model *p)
{
    return p->radius > 0 ? 4.0 * p->radius : 0.1;
}

static int open_planar(mpb_bodies *b)
{
    const mpb__planar_model *p = &b->planar;
    int rc, nobs = p->num_circles + p->num_boxes;
    double h = planar_height(p);
    b->names = calloc((size_t)(p->n + nobs) + 1, sizeof *b->names);
    b->xy = malloc(2 * ((size_t)p->n + 1) * sizeof *b->xy);
    if (!b->names || !b->xy)
        return MPB_ENOMEM;
    int named = 0;
    for (int i = 0; i < p->n; i++) {
        const char *joint = mpb_world_joint_name(b->world, i);
        size_t len = strlen(joint) + 16;
        if (!(b->names[named] = malloc(len)))
            return MPB_ENOMEM;
        snprintf(b->names[named], len, "link %d (%s)", i, joint);
        if ((rc = add_body(b, b->names[named++], 1, 1,
                           (body_src){.link = i, .object = -1})) != MPB_OK)
            return rc;
        /* A capsule lies along z: turn z onto the link's x, centre it. */
        mpb_geometry g = {.type = MPB_SHAPE_CAPSULE,
                          .dims = {p->radius, p->length[i]}};
        mpb_pose off;
        mpb_pose_identity(&off);
        mpb_pose_set_rpy(&off, 0.0, M_PI / 2, 0.0);
        off.t[0] = p->length[i] / 2;
        if ((rc = add_shape(b, &g, &off, NULL)) != MPB_OK)
            return rc;
    }
    for (int k = 0; k < nobs; k++) {
        double v[4];
        mpb__planar_obstacle(b->world, k, v);
        int is_box = k >= p->num_circles;
        if (!(b->names[named] = malloc(32)))
            return MPB_ENOMEM;
        snprintf(b->names[named], 32, "%s %d", is_box ? "box" : "circle",
                 is_box ? k - p->num_circles : k);
        body_src src = {.link = -1, .object = k};
        mpb_pose_identity(&src.fixed);
        mpb_geometry g = {.type = MPB_SHAPE_CYLINDER, .dims = {v[2], h}};
        if (is_box) {
            g = (mpb_geometry){.type = MPB_SHAPE_BOX,
                               .dims = {v[2] - v[0], v[3] - v[1], h}};
            src.fixed.t[0] = (v[0] + v[2]) / 2;
            src.fixed.t[1] = (v[1] + v[3]) / 2;
        } else {
            src.fixed.t[0] = v[0];
            src.fixed.t[1] = v[1];
        }
        if ((rc = add_body(b, b->names[named++], 0, 0, src)) != MPB_OK)
            return rc;
        mpb_pose id;
        mpb_pose_identity(&id);
        if ((rc = add_shape(b, &g, &id, NULL)) != MPB_OK)
            return rc;
    }
    return MPB_OK;
}

int mpb_bodies_open(mpb_world *w, mpb_bodies **out, char *err, size_t errlen)
{
    mpb__set_err(err, errlen, "%s", "");
    if (!out)
        return MPB_EINVAL;
    *out = NULL;
    if (!w) {
        mpb__set_err(err, errlen, "bodies: no world");
        return MPB_EINVAL;
    }
    mpb_bodies *b = calloc(1, sizeof *b);
    if (!b) {
        mpb__set_err(err, errlen, "bodies: out of memory");
        return MPB_ENOMEM;
    }
    b->world = w;
    int rc;
    if (mpb__urdf_get_model(w, &b->model) == MPB_OK) {
        b->urdf = 1;
        rc = open_urdf(b);
    } else if (mpb__planar_get_model(w, &b->planar) == MPB_OK) {
        rc = open_planar(b);
    } else {
        rc = MPB_EUNSUPPORTED;
    }
    if (rc != MPB_OK) {
        mpb__set_err(err, errlen, "bodies: %s", rc == MPB_EUNSUPPORTED
                     ? "the world's format has no bodies to list"
                     : mpb_strerror(rc));
        mpb_bodies_close(b);
        return rc;
    }
    fix_shapes(b);
    *out = b;
    return MPB_OK;
}

void mpb_bodies_close(mpb_bodies *b)
{
    if (!b)
        return;
    if (b->names)
        for (int i = 0; b->names[i]; i++)
            free(b->names[i]);
    free(b->names);
    free(b->bodies);
    free(b->src);
    free(b->shapes);
    free(b->links);
    free(b->link_body);
    free(b->object_body);
    free(b->xy);
    free(b);
}

int mpb_bodies_count(const mpb_bodies *b)
{
    return b ? b->num : 0;
}

const mpb_body *mpb_bodies_get(const mpb_bodies *b, int i)
{
    return b && i >= 0 && i < b->num ? &b->bodies[i] : NULL;
}

static int finite_q(const mpb_bodies *b, const double *q)
{
    int n = mpb_world_num_joints(b->world);
    for (int j = 0; j < n; j++)
        if (!isfinite(q[j]))
            return 0;
    return 1;
}

int mpb_bodies_poses(mpb_bodies *b, const double *q, mpb_pose *poses)
{
    if (!b || !q || !poses || !finite_q(b, q))
        return MPB_EINVAL;
    if (b->urdf) {
        if (mpb_robot_fk(b->model.robot, q, b->links) != MPB_OK)
            return MPB_EINVAL;
        for (int i = 0; i < b->num; i++) {
            const body_src *s = &b->src[i];
            if (s->object < 0)
                poses[i] = b->links[s->link];
            else if (s->link >= 0)
                mpb_pose_mul(&b->links[s->link], &s->fixed, &poses[i]);
            else
                poses[i] = s->fixed;
        }
        return MPB_OK;
    }
    mpb__planar_points(b->world, q, b->xy);
    double theta = 0.0;
    for (int i = 0; i < b->num; i++) {
        const body_src *s = &b->src[i];
        if (s->link < 0) {
            poses[i] = s->fixed;
            continue;
        }
        theta += q[s->link];   /* links come first, in order */
        mpb_pose_identity(&poses[i]);
        mpb_pose_set_rpy(&poses[i], 0.0, 0.0, theta);
        poses[i].t[0] = b->xy[2 * s->link];
        poses[i].t[1] = b->xy[2 * s->link + 1];
    }
    return MPB_OK;
}

/* The body of a urdf collision id. */
static int urdf_movable_body(const mpb_bodies *b, int id)
{
    return id < b->num_links ? b->link_body[id]
                             : b->object_body[id - b->num_links];
}

/* The body of a urdf static id: a scene object (the robot's fixed links
 * are self-only movable bodies, world_urdf.c). */
static int urdf_static_body(const mpb_bodies *b, int id)
{
    return b->object_body[id];
}

int mpb_bodies_contact(mpb_bodies *b, const double *q, int *a, int *c)
{
    if (!b || !q || !a || !c || !finite_q(b, q))
        return MPB_EINVAL;
    if (!b->urdf) {
        int link, obstacle;
        if (mpb__planar_contact(b->world, q, &link, &obstacle) != 1)
            return 0;
        *a = link;   /* the links are bodies 0 .. n-1, then the obstacles */
        *c = b->planar.n + obstacle;
        return 1;
    }
    /* The world's check places every body at q (world_urdf.c), and stops
     * at the pair asked for next. */
    if (mpb_world_in_collision(b->world, q) != 1)
        return 0;
    int m, s;
    if (mpb_collision_check(b->model.coll, &m, &s) == 1) {
        *a = urdf_movable_body(b, m);
        *c = urdf_static_body(b, s);
        return 1;
    }
    if (mpb__collision_check_self(b->model.coll, &m, &s) == 1) {
        *a = urdf_movable_body(b, m);
        *c = urdf_movable_body(b, s);
        return 1;
    }
    return 0;
}
