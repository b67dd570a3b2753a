/*
 * robot.c - the robot model: a planning group (serial chain) over a URDF
 * tree, mimic joints following their leaders, forward kinematics,
 * numerical inverse kinematics (damped least
 * squares with Levenberg-Marquardt damping and random restarts) and goal
 * regions. The URDF itself is read by the C++ bridge robot_urdf.cpp.
 */
#include "mpbench/mpbench.h"
#include "mpbench/robot.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/errbuf.h"
#include "model/robot_urdf.h"
#include "core/mathconst.h"
#include "core/rot3.h"

#define NAME_SHOWN 80                   /* characters of a name in errors */
#define MAX_URDF_BYTES (64L << 20)      /* a bigger file is not a URDF */

/* How a link's pose follows from its parent's. */
typedef struct kin {
    mpb_joint_type type;
    mpb_pose       origin;      /* parent frame -> joint frame */
    double         axis[3];     /* unit (active and moving passive joints) */
    int            chain;       /* active joint index, or -1 */
    int            mimic;       /* a mimic joint: its leader's active joint
                                   index, or -1 when the leader holds */
    double         mimic_m, mimic_o; /* value = mimic_m * leader + mimic_o */
    double         passive;     /* value of a passive joint */
    mpb_pose       fixed;       /* passive: origin * motion(passive) */
    /* Shortcuts for the common cases, chosen once (see kin_shortcuts()). */
    int            origin_pure; /* origin.R is exactly the identity */
    int            fixed_pure;  /* fixed.R is exactly the identity */
    int            axis_k;      /* axis is +-x, +-y, +-z: 0, 1, 2; else -1 */
    double         axis_sign;   /* +1 or -1 with axis_k */
} kin;

struct mpb_robot {
    mpb__urdf_model      model;   /* owns the names and mesh URIs */
    int                  num_links;
    mpb_robot_link      *links;
    kin                 *kin;
    mpb_pose            *static_pose; /* robot frame; identity where moving */
    int                  num_moving;
    int                 *moving;      /* moving links, parents first */
    int                 *path_off;    /* per link: its moving ancestors and */
    int                 *path_len;    /* itself, top down, in path_pool */
    int                 *path_pool;
    int                  num_joints;
    mpb_robot_joint     *joints;
    unsigned char       *wraps;
    int                  num_collisions;
    mpb_robot_collision *collisions;
    int                  base, tip;
};

/* ---- small helpers --------------------------------------------------- */

/* splitmix64: any state is a valid seed. */
static uint64_t rng_next(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* Uniform in [0, 1). */
static double rng_unit(uint64_t *s)
{
    return (double)(rng_next(s) >> 11) * (1.0 / 9007199254740992.0);
}

static double uniform(uint64_t *s, double lo, double hi)
{
    return lo + (hi - lo) * rng_unit(s);
}

/* Into (-pi, pi]. */
static double wrap_angle(double a)
{
    a = fmod(a, 2.0 * M_PI);
    if (a > M_PI)
        a -= 2.0 * M_PI;
    else if (a <= -M_PI)
        a += 2.0 * M_PI;
    return a;
}

static int finite3(const double v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

static int pose_finite(const mpb_pose *p)
{
    for (int i = 0; i < 9; i++)
        if (!isfinite(p->R[i]))
            return 0;
    return finite3(p->t);
}

/* Within the collision world's bounds (collision.h), as m or rad. */
static int bounded(double v)
{
    return fabs(v) <= MPB_COLLISION_MAX_COORD;
}

static int bounded3(const double v[3])
{
    return bounded(v[0]) && bounded(v[1]) && bounded(v[2]);
}

/* The motion of a joint at value v, as a pose of the child in the joint frame. */
static void joint_motion(mpb_joint_type type, const double axis[3], double v,
                         mpb_pose *m)
{
    mpb_pose_identity(m);
    switch (type) {
    case MPB_JOINT_REVOLUTE:
    case MPB_JOINT_CONTINUOUS:
        mpb__rot_axis(axis, v, m->R);
        break;
    case MPB_JOINT_PRISMATIC:
        for (int i = 0; i < 3; i++)
            m->t[i] = axis[i] * v;
        break;
    default:
        break;
    }
}

/* out->t = P.R v + P.t, out->R = P.R: P followed by a pure translation v. */
static void translate(const mpb_pose *P, const double v[3], mpb_pose *out)
{
    memcpy(out->R, P->R, sizeof P->R);
    mpb__mat3_vec(P->R, v, out->t);
    for (int j = 0; j < 3; j++)
        out->t[j] += P->t[j];
}

/* out = A * (rotation by angle with cosine c and sine s about axis k). */
static void rotate_cols(const double *A, int k, double c, double s, double *out)
{
    int a = (k + 1) % 3, b = (k + 2) % 3;   /* x: y z; y: z x; z: x y */
    for (int r = 0; r < 3; r++) {
        const double *row = A + 3 * r;
        out[3 * r + k] = row[k];
        out[3 * r + a] = c * row[a] + s * row[b];
        out[3 * r + b] = -s * row[a] + c * row[b];
    }
}

/* The pose of link i from its parent's pose; q indexed by active joint. */
static void link_step(const mpb_robot *r, int i, const double *q,
                      const mpb_pose *parent, mpb_pose *out)
{
    const kin *k = &r->kin[i];
    if (k->chain < 0 && k->mimic < 0) {
        if (k->fixed_pure)
            translate(parent, k->fixed.t, out);
        else
            mpb_pose_mul(parent, &k->fixed, out);
        return;
    }
    mpb_pose a;
    if (k->origin_pure)
        translate(parent, k->origin.t, &a);
    else
        mpb_pose_mul(parent, &k->origin, &a);
    double v = k->chain >= 0 ? q[k->chain] : k->mimic_m * q[k->mimic] + k->mimic_o;
    if (k->type == MPB_JOINT_PRISMATIC) {
        double d[3] = { k->axis[0] * v, k->axis[1] * v, k->axis[2] * v };
        translate(&a, d, out);
    } else if (k->axis_k >= 0) {
        double ang = k->axis_sign * v;
        rotate_cols(a.R, k->axis_k, cos(ang), sin(ang), out->R);
        memcpy(out->t, a.t, sizeof a.t);
    } else {
        double M[9];
        mpb__rot_axis(k->axis, v, M);
        mpb__mat3_mul(a.R, M, out->R);
        memcpy(out->t, a.t, sizeof a.t);
    }
}

static int q_finite(const mpb_robot *r, const double *q)
{
    for (int j = 0; j < r->num_joints; j++)
        if (!isfinite(q[j]))
            return 0;
    return 1;
}

/*
 * Poses of the path of `link` (its moving ancestors and itself, top down)
 * into P (path_len entries); the link's pose into *out. Static links: out
 * only.
 */
static void path_poses(const mpb_robot *r, const double *q, int link,
                       mpb_pose *P, mpb_pose *out)
{
    int len = r->path_len[link];
    if (len == 0) {
        *out = r->static_pose[link];
        return;
    }
    const int *path = r->path_pool + r->path_off[link];
    const mpb_pose *prev = &r->static_pose[r->links[path[0]].parent];
    for (int k = 0; k < len; k++) {
        link_step(r, path[k], q, prev, &P[k]);
        prev = &P[k];
    }
    *out = P[len - 1];
}

/* Recompute the static link poses (after loading or set_passive). */
static void compute_static(mpb_robot *r)
{
    for (int i = 0; i < r->num_links; i++) {
        mpb_pose_identity(&r->static_pose[i]);
        if (r->links[i].moves || r->links[i].parent < 0)
            continue;
        mpb_pose_mul(&r->static_pose[r->links[i].parent], &r->kin[i].fixed,
                     &r->static_pose[i]);
    }
}

static void set_fixed(kin *k)
{
    mpb_pose m;
    joint_motion(k->type, k->axis, k->passive, &m);
    mpb_pose_mul(&k->origin, &m, &k->fixed);
    k->fixed_pure = mpb__is_identity3(k->fixed.R);
}

static void kin_shortcuts(kin *k)
{
    k->origin_pure = mpb__is_identity3(k->origin.R);
    k->axis_k = -1;
    k->axis_sign = 1.0;
    for (int d = 0; d < 3; d++)
        if (fabs(k->axis[d]) == 1.0 && k->axis[(d + 1) % 3] == 0.0
            && k->axis[(d + 2) % 3] == 0.0) {
            k->axis_k = d;
            k->axis_sign = k->axis[d] > 0 ? 1.0 : -1.0;
        }
}

/* ---- loading ------------------------------------------------------------ */

const char *mpb_joint_type_name(mpb_joint_type type)
{
    switch (type) {
    case MPB_JOINT_FIXED:      return "fixed";
    case MPB_JOINT_REVOLUTE:   return "revolute";
    case MPB_JOINT_CONTINUOUS: return "continuous";
    case MPB_JOINT_PRISMATIC:  return "prismatic";
    case MPB_JOINT_FLOATING:   return "floating";
    case MPB_JOINT_PLANAR:     return "planar";
    }
    return "unknown";
}

static int is_active_type(mpb_joint_type t)
{
    return t == MPB_JOINT_REVOLUTE || t == MPB_JOINT_CONTINUOUS
        || t == MPB_JOINT_PRISMATIC;
}

/* Check what urdfdom lets through: axes, limits, origins, geometry. */
static int validate_model(const mpb__urdf_model *m, char *err, size_t errlen)
{
    for (int i = 0; i < m->num_links; i++) {
        const mpb__urdf_link *l = &m->links[i];
        if (l->parent >= 0) {
            if (!pose_finite(&l->origin)) {
                mpb__set_err(err, errlen, "joint '%.*s': origin is not finite",
                             NAME_SHOWN, l->joint);
                return MPB_EPARSE;
            }
            /* Near 1e306 FCL's tree crashes; see MPB_COLLISION_MAX_COORD. */
            if (!bounded3(l->origin.t)) {
                mpb__set_err(err, errlen, "joint '%.*s': origin xyz is beyond "
                             "%g m", NAME_SHOWN, l->joint,
                             MPB_COLLISION_MAX_COORD);
                return MPB_EPARSE;
            }
            if (is_active_type(l->type)) {
                double n = sqrt(l->axis[0] * l->axis[0] + l->axis[1] * l->axis[1]
                                + l->axis[2] * l->axis[2]);
                if (!finite3(l->axis) || !(n > 1e-12)) {
                    mpb__set_err(err, errlen, "joint '%.*s': axis is zero or not "
                                 "finite", NAME_SHOWN, l->joint);
                    return MPB_EPARSE;
                }
            }
            if (l->type == MPB_JOINT_REVOLUTE || l->type == MPB_JOINT_PRISMATIC) {
                if (!l->has_limits || !isfinite(l->lo) || !isfinite(l->hi)) {
                    mpb__set_err(err, errlen, "joint '%.*s': %s joint needs finite "
                                 "lower and upper limits", NAME_SHOWN, l->joint,
                                 mpb_joint_type_name(l->type));
                    return MPB_EPARSE;
                }
                if (!bounded(l->lo) || !bounded(l->hi)) {
                    mpb__set_err(err, errlen, "joint '%.*s': a limit is beyond "
                                 "%g (m or rad)", NAME_SHOWN, l->joint,
                                 MPB_COLLISION_MAX_COORD);
                    return MPB_EPARSE;
                }
                if (l->lo > l->hi) {
                    mpb__set_err(err, errlen, "joint '%.*s': lower limit %g is above "
                                 "upper limit %g", NAME_SHOWN, l->joint, l->lo, l->hi);
                    return MPB_EPARSE;
                }
            }
        }
        for (int k = 0; k < l->num_geoms; k++) {
            const mpb__urdf_geom *g = &l->geoms[k];
            int ok = pose_finite(&g->origin);
            int nd = g->type == MPB_SHAPE_BOX ? 3
                   : g->type == MPB_SHAPE_SPHERE ? 1
                   : g->type == MPB_SHAPE_CYLINDER ? 2 : 0;
            for (int d = 0; d < nd; d++)
                ok = ok && isfinite(g->dims[d]) && g->dims[d] >= 0.0;
            if (g->type == MPB_SHAPE_MESH)
                ok = ok && g->mesh_uri && g->mesh_uri[0] && finite3(g->mesh_scale)
                     && g->mesh_scale[0] != 0 && g->mesh_scale[1] != 0
                     && g->mesh_scale[2] != 0;
            if (!ok) {
                mpb__set_err(err, errlen, "link '%.*s': collision %d (%s) has a "
                             "negative, zero or non-finite size, scale or origin",
                             NAME_SHOWN, l->name, k, mpb_shape_type_name(g->type));
                return MPB_EPARSE;
            }
            for (int d = 0; d < nd; d++)
                ok = ok && bounded(g->dims[d]);
            if (!ok || !bounded3(g->origin.t)) {
                mpb__set_err(err, errlen, "link '%.*s': collision %d (%s) has a "
                             "size or origin beyond %g m", NAME_SHOWN, l->name, k,
                             mpb_shape_type_name(g->type),
                             MPB_COLLISION_MAX_COORD);
                return MPB_EPARSE;
            }
        }
    }
    return MPB_OK;
}

static int find_link(const mpb__urdf_model *m, const char *name)
{
    for (int i = 0; i < m->num_links; i++)
        if (strcmp(m->links[i].name, name) == 0)
            return i;
    return -1;
}

static int find_joint_link(const mpb__urdf_model *m, const char *joint)
{
    for (int i = 1; i < m->num_links; i++)
        if (m->links[i].joint && strcmp(m->links[i].joint, joint) == 0)
            return i;
    return -1;
}

/* 1 if a is b or an ancestor of b. */
static int is_ancestor(const mpb__urdf_model *m, int a, int b)
{
    for (int i = b; i >= 0; i = m->links[i].parent)
        if (i == a)
            return 1;
    return 0;
}

/* What resolve_mimics() finds, per link (by its parent joint). */
typedef struct mimics {
    int    *lead;               /* the leader's child link, or -1 */
    double *mul, *off;          /* value = mul * leader + off */
} mimics;

/*
 * Follow each mimic joint to its final leader, composing multipliers and
 * offsets on the way. Refuses a leader that is no joint, a mimic or
 * leader that is not revolute, continuous or prismatic, and a loop.
 */
static int resolve_mimics(const mpb__urdf_model *m, mimics *mi, char *err,
                          size_t errlen)
{
    for (int i = 0; i < m->num_links; i++) {
        mi->lead[i] = -1;
        mi->mul[i] = 1.0;
        mi->off[i] = 0.0;
        /* A fixed joint that names a leader still cannot move. */
        if (m->links[i].parent < 0 || !m->links[i].mimic ||
            !is_active_type(m->links[i].type))
            continue;
        double a = 1.0, b = 0.0;
        int at = i;
        for (int steps = 0; m->links[at].parent >= 0 && m->links[at].mimic &&
                            is_active_type(m->links[at].type); steps++) {
            const mpb__urdf_link *x = &m->links[at];
            int next = find_joint_link(m, x->mimic);
            if (next < 0) {
                mpb__set_err(err, errlen, "joint '%.*s' mimics '%.*s', which is "
                             "not a joint of the URDF", NAME_SHOWN, x->joint,
                             NAME_SHOWN, x->mimic);
                return MPB_EPARSE;
            }
            if (!is_active_type(m->links[next].type)) {
                mpb__set_err(err, errlen, "joint '%.*s' (%s) mimics '%.*s' (%s); "
                             "both must be revolute, continuous or prismatic",
                             NAME_SHOWN, x->joint, mpb_joint_type_name(x->type),
                             NAME_SHOWN, x->mimic,
                             mpb_joint_type_name(m->links[next].type));
                return MPB_EPARSE;
            }
            if (!isfinite(x->mimic_multiplier) || !isfinite(x->mimic_offset)) {
                mpb__set_err(err, errlen, "joint '%.*s': mimic multiplier or "
                             "offset is not finite", NAME_SHOWN, x->joint);
                return MPB_EPARSE;
            }
            if (next == i || steps > m->num_links) {
                mpb__set_err(err, errlen, "joint '%.*s' mimics itself through "
                             "other mimic joints", NAME_SHOWN, m->links[i].joint);
                return MPB_EPARSE;
            }
            /* v(at) = mm v(next) + mo, so v(i) = a mm v(next) + a mo + b. */
            b += a * x->mimic_offset;
            a *= x->mimic_multiplier;
            at = next;
        }
        mi->lead[i] = at;
        mi->mul[i] = a;
        mi->off[i] = b;
    }
    return MPB_OK;
}

/*
 * Build r from r->model, the active joints given as the links they move
 * (child[0 .. n-1], top down), base and tip link indices, the mimic
 * joints as resolve_mimics() found them.
 */
static int build(mpb_robot *r, const int *child, int n, int base, int tip,
                 const mimics *mi)
{
    const mpb__urdf_model *m = &r->model;
    int nl = m->num_links;
    r->num_links = nl;
    r->num_joints = n;
    r->base = base;
    r->tip = tip;
    r->links = calloc((size_t)nl, sizeof *r->links);
    r->kin = calloc((size_t)nl, sizeof *r->kin);
    r->static_pose = calloc((size_t)nl, sizeof *r->static_pose);
    r->moving = calloc((size_t)nl, sizeof *r->moving);
    r->path_off = calloc((size_t)nl, sizeof *r->path_off);
    r->path_len = calloc((size_t)nl, sizeof *r->path_len);
    r->joints = calloc((size_t)n, sizeof *r->joints);
    r->wraps = calloc((size_t)n, 1);
    if (!r->links || !r->kin || !r->static_pose || !r->moving || !r->path_off
        || !r->path_len || !r->joints || !r->wraps)
        return MPB_ENOMEM;

    int ncoll = 0;
    for (int i = 0; i < nl; i++)
        ncoll += m->links[i].num_geoms;
    r->collisions = calloc(ncoll > 0 ? (size_t)ncoll : 1, sizeof *r->collisions);
    if (!r->collisions)
        return MPB_ENOMEM;

    /* Links and their kinematics, parents first. */
    size_t pool = 0;
    ncoll = 0;
    for (int i = 0; i < nl; i++) {
        const mpb__urdf_link *ul = &m->links[i];
        mpb_robot_link *l = &r->links[i];
        kin *k = &r->kin[i];
        l->name = ul->name;
        l->parent = ul->parent;
        l->joint = ul->parent >= 0 ? ul->joint : NULL;
        l->joint_type = ul->parent >= 0 ? ul->type : MPB_JOINT_FIXED;
        l->chain_joint = -1;
        l->mimic_link = mi->lead[i];
        l->mimic_multiplier = mi->mul[i];
        l->mimic_offset = mi->off[i];
        k->type = l->joint_type;
        k->chain = -1;
        k->mimic = -1;
        k->origin = ul->origin;
        if (ul->parent < 0)
            mpb_pose_identity(&k->origin);
        double an = sqrt(ul->axis[0] * ul->axis[0] + ul->axis[1] * ul->axis[1]
                         + ul->axis[2] * ul->axis[2]);
        for (int d = 0; d < 3; d++)
            k->axis[d] = an > 0 ? ul->axis[d] / an : 0.0;
        for (int j = 0; j < n; j++) {
            if (child[j] == i)
                l->chain_joint = k->chain = j;
            if (mi->lead[i] >= 0 && child[j] == mi->lead[i])
                k->mimic = j;
        }
        k->mimic_m = mi->mul[i];
        k->mimic_o = mi->off[i];
        if (k->chain < 0 && (k->type == MPB_JOINT_REVOLUTE
                             || k->type == MPB_JOINT_PRISMATIC))
            k->passive = fmin(fmax(0.0, ul->lo), ul->hi);
        set_fixed(k);
        kin_shortcuts(k);
        if (l->parent >= 0) {
            const mpb_robot_link *p = &r->links[l->parent];
            l->moves = p->moves || k->chain >= 0 || k->mimic >= 0;
            l->num_chain_joints = k->chain >= 0 ? k->chain + 1
                                                : p->num_chain_joints;
            r->path_len[i] = l->moves ? r->path_len[l->parent] + 1 : 0;
        }
        if (l->moves)
            r->moving[r->num_moving++] = i;
        r->path_off[i] = (int)pool;
        pool += (size_t)r->path_len[i];
        if (pool > (size_t)1 << 28)     /* a pathological tree */
            return MPB_ENOMEM;

        l->first_collision = ncoll;
        l->num_collisions = ul->num_geoms;
        for (int g = 0; g < ul->num_geoms; g++) {
            const mpb__urdf_geom *ug = &ul->geoms[g];
            mpb_robot_collision *c = &r->collisions[ncoll++];
            c->link = i;
            c->type = ug->type;
            memcpy(c->dims, ug->dims, sizeof c->dims);
            c->mesh_uri = ug->type == MPB_SHAPE_MESH ? ug->mesh_uri : NULL;
            memcpy(c->mesh_scale, ug->mesh_scale, sizeof c->mesh_scale);
            c->origin = ug->origin;
            c->name = ug->name;
        }
    }
    r->num_collisions = ncoll;
    /* A mimic of a held leader holds the value that follows from it. */
    for (int i = 0; i < nl; i++) {
        kin *k = &r->kin[i];
        if (mi->lead[i] >= 0 && k->mimic < 0) {
            k->passive = k->mimic_m * r->kin[mi->lead[i]].passive + k->mimic_o;
            set_fixed(k);
        }
    }

    /* Paths: the parent's path, then the link itself. */
    r->path_pool = calloc(pool > 0 ? pool : 1, sizeof *r->path_pool);
    if (!r->path_pool)
        return MPB_ENOMEM;
    for (int i = 0; i < nl; i++) {
        int len = r->path_len[i];
        if (len == 0)
            continue;
        int *dst = r->path_pool + r->path_off[i];
        if (len > 1)
            memcpy(dst, r->path_pool + r->path_off[r->links[i].parent],
                   (size_t)(len - 1) * sizeof *dst);
        dst[len - 1] = i;
    }

    /* The active joints. */
    for (int j = 0; j < n; j++) {
        const mpb__urdf_link *ul = &m->links[child[j]];
        mpb_robot_joint *J = &r->joints[j];
        J->name = ul->joint;
        J->type = ul->type;
        if (ul->type == MPB_JOINT_CONTINUOUS) {
            J->lo = -M_PI;
            J->hi = M_PI;
            r->wraps[j] = 1;
        } else {
            J->lo = ul->lo;
            J->hi = ul->hi;
        }
        J->max_velocity = ul->has_limits && isfinite(ul->max_velocity)
                        ? ul->max_velocity : 0.0;
        memcpy(J->axis, r->kin[child[j]].axis, sizeof J->axis);
        J->origin = ul->origin;
        J->parent_link = ul->parent;
        J->child_link = child[j];
    }
    compute_static(r);
    return MPB_OK;
}

/*
 * The link below base with the most active joints between them (the first
 * in depth-first order of those), or base itself when none has any.
 */
static int deepest_tip(const mpb__urdf_model *m, int base)
{
    int best = base, most = 0;
    for (int l = 0; l < m->num_links; l++) {
        if (!is_ancestor(m, base, l))
            continue;
        int n = 0;
        for (int i = l; i != base && i >= 0; i = m->links[i].parent)
            n += is_active_type(m->links[i].type) && !m->links[i].mimic;
        if (n > most) {
            most = n;
            best = l;
        }
    }
    return best;
}

/*
 * Parse the text and build a robot, the group either from base/tip names
 * or from joint names. Messages come out as "<prefix>: ...".
 */
static int load(const char *text, const char *base_name, const char *tip_name,
                const char *const *joint_names, int num_names,
                const char *prefix, mpb_robot **out, char *err, size_t errlen)
{
    char msg[512];
    msg[0] = '\0';
    int *child = NULL;
    mimics mi = {0};
    mpb_robot *r = calloc(1, sizeof *r);
    int rc = MPB_ENOMEM;
    if (!r)
        goto fail;
    rc = mpb__urdf_parse(text, &r->model, msg, sizeof msg);
    if (rc != MPB_OK)
        goto fail;
    mpb__urdf_model *m = &r->model;
    rc = validate_model(m, msg, sizeof msg);
    if (rc != MPB_OK)
        goto fail;
    rc = MPB_ENOMEM;
    size_t nl = m->num_links > 0 ? (size_t)m->num_links : 1;
    mi.lead = calloc(nl, sizeof *mi.lead);
    mi.mul = calloc(nl, sizeof *mi.mul);
    mi.off = calloc(nl, sizeof *mi.off);
    if (!mi.lead || !mi.mul || !mi.off)
        goto fail;
    rc = resolve_mimics(m, &mi, msg, sizeof msg);
    if (rc != MPB_OK)
        goto fail;

    int n = 0, base, tip;
    child = calloc((size_t)m->num_links + (size_t)(num_names > 0 ? num_names : 0),
                   sizeof *child);
    rc = MPB_ENOMEM;
    if (!child)
        goto fail;
    rc = MPB_EPARSE;
    if (!joint_names) {
        base = base_name ? find_link(m, base_name) : 0;
        if (base < 0) {
            mpb__set_err(msg, sizeof msg, "base link '%.*s' not found", NAME_SHOWN,
                         base_name);
            goto fail;
        }
        tip = tip_name ? find_link(m, tip_name) : deepest_tip(m, base);
        if (!tip_name)
            tip_name = m->links[tip].name;
        if (tip < 0) {
            mpb__set_err(msg, sizeof msg, "tip link '%.*s' not found", NAME_SHOWN,
                         tip_name);
            goto fail;
        }
        if (tip == base || !is_ancestor(m, base, tip)) {
            mpb__set_err(msg, sizeof msg, "tip link '%.*s' is not below base link "
                         "'%.*s'", NAME_SHOWN, tip_name, NAME_SHOWN, m->links[base].name);
            goto fail;
        }
        /* The path tip -> base, then reversed. */
        for (int i = tip; i != base; i = m->links[i].parent) {
            mpb_joint_type t = m->links[i].type;
            if (t == MPB_JOINT_FLOATING || t == MPB_JOINT_PLANAR) {
                mpb__set_err(msg, sizeof msg, "joint '%.*s' between base and tip is "
                             "%s; only revolute, continuous, prismatic and fixed "
                             "joints can be in a chain", NAME_SHOWN, m->links[i].joint,
                             mpb_joint_type_name(t));
                rc = MPB_EUNSUPPORTED;
                goto fail;
            }
            if (is_active_type(t) && mi.lead[i] < 0)  /* mimics follow */
                child[n++] = i;
        }
        for (int a = 0, b = n - 1; a < b; a++, b--) {
            int t = child[a];
            child[a] = child[b];
            child[b] = t;
        }
        if (n == 0) {
            mpb__set_err(msg, sizeof msg, "no revolute, continuous or prismatic "
                         "joint between base link '%.*s' and tip link '%.*s'",
                         NAME_SHOWN, m->links[base].name, NAME_SHOWN, tip_name);
            goto fail;
        }
    } else {
        if (num_names < 1) {
            mpb__set_err(msg, sizeof msg, "no joints named for the group");
            goto fail;
        }
        for (int j = 0; j < num_names; j++) {
            const char *name = joint_names[j] ? joint_names[j] : "(null)";
            int c = joint_names[j] ? find_joint_link(m, name) : -1;
            if (c < 0) {
                mpb__set_err(msg, sizeof msg, "joint '%.*s' not found", NAME_SHOWN,
                             name);
                goto fail;
            }
            if (!is_active_type(m->links[c].type)) {
                mpb__set_err(msg, sizeof msg, "joint '%.*s' is %s; a group's joints "
                             "must be revolute, continuous or prismatic", NAME_SHOWN,
                             name, mpb_joint_type_name(m->links[c].type));
                goto fail;
            }
            if (mi.lead[c] >= 0) {
                mpb__set_err(msg, sizeof msg, "joint '%.*s' mimics '%.*s' and "
                             "follows it; a mimic joint cannot be in the group",
                             NAME_SHOWN, name, NAME_SHOWN, m->links[c].mimic);
                goto fail;
            }
            for (int i = 0; i < j; i++)
                if (child[i] == c) {
                    mpb__set_err(msg, sizeof msg, "joint '%.*s' is named twice",
                                 NAME_SHOWN, name);
                    goto fail;
                }
            if (j > 0 && !is_ancestor(m, child[j - 1], m->links[c].parent)) {
                mpb__set_err(msg, sizeof msg, "joint '%.*s' is not below joint "
                             "'%.*s': the joints must form one chain, base first",
                             NAME_SHOWN, name, NAME_SHOWN, joint_names[j - 1]);
                goto fail;
            }
            child[n++] = c;
        }
        base = m->links[child[0]].parent;
        tip = child[n - 1];
    }

    rc = build(r, child, n, base, tip, &mi);
    if (rc != MPB_OK)
        goto fail;
    free(child);
    free(mi.lead);
    free(mi.mul);
    free(mi.off);
    *out = r;
    return MPB_OK;

fail:
    if (rc == MPB_ENOMEM)
        mpb__set_err(msg, sizeof msg, "out of memory");
    mpb__set_err(err, errlen, "%s: %s", prefix, msg);
    if (err)
        for (char *c = err; *c; c++)
            if (*c == '\n' || *c == '\r')
                *c = ' ';
    free(child);
    free(mi.lead);
    free(mi.mul);
    free(mi.off);
    mpb_robot_free(r);
    return rc;
}

int mpb_robot_load_urdf(const char *urdf_text, const char *base_link,
                        const char *tip_link, mpb_robot **out,
                        char *err, size_t errlen)
{
    mpb__set_err(err, errlen, "%s", "");
    if (out)
        *out = NULL;
    if (!urdf_text || !out) {
        mpb__set_err(err, errlen, "urdf: text and out are required");
        return MPB_EINVAL;
    }
    return load(urdf_text, base_link, tip_link, NULL, 0, "urdf", out, err,
                errlen);
}

int mpb_robot_load_urdf_joints(const char *urdf_text,
                               const char *const *joint_names, int num_names,
                               mpb_robot **out, char *err, size_t errlen)
{
    mpb__set_err(err, errlen, "%s", "");
    if (out)
        *out = NULL;
    if (!urdf_text || !joint_names || !out) {
        mpb__set_err(err, errlen, "urdf: text, joint names and out are required");
        return MPB_EINVAL;
    }
    return load(urdf_text, NULL, NULL, joint_names, num_names, "urdf", out,
                err, errlen);
}

int mpb_robot_load_urdf_file(const char *path, const char *base_link,
                             const char *tip_link, mpb_robot **out,
                             char *err, size_t errlen)
{
    mpb__set_err(err, errlen, "%s", "");
    if (out)
        *out = NULL;
    if (!path || !tip_link || !out) {
        mpb__set_err(err, errlen, "urdf: path, tip link and out are required");
        return MPB_EINVAL;
    }
    FILE *f = fopen(path, "rb");
    if (!f) {
        mpb__set_err(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return MPB_EIO;
    }
    char *text = NULL;
    size_t len = 0, cap = 0;
    int rc = MPB_OK;
    for (;;) {
        if (len + 4096 + 1 > cap) {
            if (cap >= (size_t)MAX_URDF_BYTES) {
                mpb__set_err(err, errlen, "%s: larger than %ld bytes", path,
                             MAX_URDF_BYTES);
                rc = MPB_EIO;
                break;
            }
            size_t ncap = cap ? 2 * cap : 65536;
            char *t = realloc(text, ncap);
            if (!t) {
                mpb__set_err(err, errlen, "%s: out of memory", path);
                rc = MPB_ENOMEM;
                break;
            }
            text = t;
            cap = ncap;
        }
        size_t got = fread(text + len, 1, cap - len - 1, f);
        len += got;
        if (got == 0) {
            if (ferror(f)) {
                mpb__set_err(err, errlen, "%s: read error", path);
                rc = MPB_EIO;
            }
            break;
        }
    }
    fclose(f);
    if (rc == MPB_OK) {
        text[len] = '\0';
        if (strlen(text) != len) {
            mpb__set_err(err, errlen, "%s: not a text file (NUL byte)", path);
            rc = MPB_EPARSE;
        } else {
            rc = load(text, base_link, tip_link, NULL, 0, path, out, err,
                      errlen);
        }
    }
    free(text);
    return rc;
}

void mpb_robot_free(mpb_robot *r)
{
    if (!r)
        return;
    mpb__urdf_model_clear(&r->model);
    free(r->links);
    free(r->kin);
    free(r->static_pose);
    free(r->moving);
    free(r->path_off);
    free(r->path_len);
    free(r->path_pool);
    free(r->joints);
    free(r->wraps);
    free(r->collisions);
    free(r);
}

/* ---- the model ---------------------------------------------------------- */

const mpb__urdf_model *mpb__robot_model(const mpb_robot *r)
{
    return r ? &r->model : NULL;
}

const char *mpb_robot_name(const mpb_robot *r)
{
    return r ? r->model.name : NULL;
}

int mpb_robot_num_joints(const mpb_robot *r)
{
    return r ? r->num_joints : 0;
}

const mpb_robot_joint *mpb_robot_get_joint(const mpb_robot *r, int joint)
{
    if (!r || joint < 0 || joint >= r->num_joints)
        return NULL;
    return &r->joints[joint];
}

int mpb_robot_joint_index(const mpb_robot *r, const char *name)
{
    if (!r || !name)
        return MPB_ENOTFOUND;
    for (int j = 0; j < r->num_joints; j++)
        if (strcmp(r->joints[j].name, name) == 0)
            return j;
    return MPB_ENOTFOUND;
}

const unsigned char *mpb_robot_joint_wraps(const mpb_robot *r)
{
    return r ? r->wraps : NULL;
}

int mpb_robot_num_links(const mpb_robot *r)
{
    return r ? r->num_links : 0;
}

const mpb_robot_link *mpb_robot_get_link(const mpb_robot *r, int link)
{
    if (!r || link < 0 || link >= r->num_links)
        return NULL;
    return &r->links[link];
}

int mpb_robot_link_index(const mpb_robot *r, const char *name)
{
    if (!r || !name)
        return MPB_ENOTFOUND;
    for (int i = 0; i < r->num_links; i++)
        if (strcmp(r->links[i].name, name) == 0)
            return i;
    return MPB_ENOTFOUND;
}

int mpb_robot_base_link(const mpb_robot *r)
{
    return r ? r->base : MPB_EINVAL;
}

int mpb_robot_tip_link(const mpb_robot *r)
{
    return r ? r->tip : MPB_EINVAL;
}

int mpb_robot_num_collisions(const mpb_robot *r)
{
    return r ? r->num_collisions : 0;
}

const mpb_robot_collision *mpb_robot_get_collision(const mpb_robot *r,
                                                   int index)
{
    if (!r || index < 0 || index >= r->num_collisions)
        return NULL;
    return &r->collisions[index];
}

int mpb_robot_set_passive(mpb_robot *r, const char *joint, double value)
{
    if (!r || !joint)
        return MPB_EINVAL;
    int i = find_joint_link(&r->model, joint);
    if (i < 0)
        return MPB_ENOTFOUND;
    kin *k = &r->kin[i];
    const mpb__urdf_link *ul = &r->model.links[i];
    if (k->chain >= 0 || r->links[i].mimic_link >= 0 || !isfinite(value) ||
        !is_active_type(k->type))
        return MPB_EINVAL;
    if (k->type != MPB_JOINT_CONTINUOUS && (value < ul->lo || value > ul->hi))
        return MPB_EINVAL;
    k->passive = value;
    set_fixed(k);
    for (int f = 0; f < r->num_links; f++)
        if (r->links[f].mimic_link == i) {
            r->kin[f].passive = r->kin[f].mimic_m * value + r->kin[f].mimic_o;
            set_fixed(&r->kin[f]);
        }
    compute_static(r);
    return MPB_OK;
}

int mpb_robot_get_passive(const mpb_robot *r, const char *joint,
                          double *value, double *lo, double *hi)
{
    if (!r || !joint)
        return MPB_EINVAL;
    int i = find_joint_link(&r->model, joint);
    if (i < 0)
        return MPB_ENOTFOUND;
    const kin *k = &r->kin[i];
    if (k->chain >= 0 || !is_active_type(k->type))
        return MPB_EINVAL;
    int wraps = k->type == MPB_JOINT_CONTINUOUS;
    if (value)
        *value = k->passive;
    if (lo)
        *lo = wraps ? -M_PI : r->model.links[i].lo;
    if (hi)
        *hi = wraps ? M_PI : r->model.links[i].hi;
    return MPB_OK;
}

int mpb_robot_within_limits(const mpb_robot *r, const double *q)
{
    if (!r || !q)
        return 0;
    for (int j = 0; j < r->num_joints; j++) {
        if (!isfinite(q[j]))
            return 0;
        if (!r->wraps[j] && (q[j] < r->joints[j].lo || q[j] > r->joints[j].hi))
            return 0;
    }
    return 1;
}

int mpb_robot_random_config(const mpb_robot *r, uint64_t *rng, double *q)
{
    if (!r || !rng || !q)
        return MPB_EINVAL;
    for (int j = 0; j < r->num_joints; j++)
        q[j] = uniform(rng, r->joints[j].lo, r->joints[j].hi);
    return MPB_OK;
}

/* ---- forward kinematics -------------------------------------------------- */

int mpb_robot_fk_moving(const mpb_robot *r, const double *q, mpb_pose *poses)
{
    if (!r || !q || !poses || !q_finite(r, q))
        return MPB_EINVAL;
    for (int m = 0; m < r->num_moving; m++) {
        int i = r->moving[m];
        int p = r->links[i].parent;
        const mpb_pose *pp = r->links[p].moves ? &poses[p] : &r->static_pose[p];
        link_step(r, i, q, pp, &poses[i]);
    }
    return MPB_OK;
}

int mpb_robot_fk(const mpb_robot *r, const double *q, mpb_pose *poses)
{
    if (!r || !q || !poses || !q_finite(r, q))
        return MPB_EINVAL;
    memcpy(poses, r->static_pose, (size_t)r->num_links * sizeof *poses);
    return mpb_robot_fk_moving(r, q, poses);
}

int mpb_robot_link_pose(const mpb_robot *r, const double *q, int link,
                        mpb_pose *out)
{
    if (!r || !q || !out || link < 0 || link >= r->num_links || !q_finite(r, q))
        return MPB_EINVAL;
    int len = r->path_len[link];
    if (len == 0) {
        *out = r->static_pose[link];
        return MPB_OK;
    }
    const int *path = r->path_pool + r->path_off[link];
    mpb_pose a = r->static_pose[r->links[path[0]].parent], b;
    for (int k = 0; k < len; k++) {
        link_step(r, path[k], q, &a, &b);
        a = b;
    }
    *out = a;
    return MPB_OK;
}

/* ---- inverse kinematics -------------------------------------------------- */

void mpb_ik_options_init(mpb_ik_options *opt)
{
    if (!opt)
        return;
    opt->max_attempts = 100;
    opt->max_iterations = 100;
    opt->position_tolerance = 1e-6;
    opt->orientation_tolerance = 1e-6;
    opt->position_only = 0;
}

/* What one solve needs, allocated once per call. */
typedef struct ik_ws {
    const mpb_robot *r;
    int             link;
    int             n;          /* joints 0 .. n-1 move the link */
    int             m;          /* rows: 6, or 3 for position only */
    double          offset[3];
    const mpb_pose *target;
    mpb_pose       *P;          /* poses of the link's path */
    int            *jpos;       /* joint j's child link's place in the path */
    double         *J;          /* m x n, row-major */
    double          p[3];       /* the reference point at the last eval */
    double          e[6];       /* the error at the last eval */
    double          perr, rerr; /* its position and rotation norms */
} ik_ws;

/* Error of q into w->e (target minus current); returns its squared norm. */
static double ik_eval(ik_ws *w, const double *q)
{
    mpb_pose T;
    path_poses(w->r, q, w->link, w->P, &T);
    mpb_pose_apply(&T, w->offset, w->p);
    for (int i = 0; i < 3; i++)
        w->e[i] = w->target->t[i] - w->p[i];
    w->perr = sqrt(w->e[0] * w->e[0] + w->e[1] * w->e[1] + w->e[2] * w->e[2]);
    w->rerr = 0.0;
    if (w->m == 6) {
        double Rt[9], Rerr[9];
        /* Rerr = R_target * R^T: the world-frame rotation still to go. */
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                Rt[3 * i + j] = T.R[3 * j + i];
        mpb__mat3_mul(w->target->R, Rt, Rerr);
        mpb__rot_log(Rerr, w->e + 3);
        w->rerr = sqrt(w->e[3] * w->e[3] + w->e[4] * w->e[4] + w->e[5] * w->e[5]);
    }
    return w->perr * w->perr + w->rerr * w->rerr;
}

/* The Jacobian at the q of the last ik_eval (w->P, w->p). */
static void ik_jacobian(ik_ws *w)
{
    const mpb_robot *r = w->r;
    for (int j = 0; j < w->n; j++) {
        const mpb_pose *C = &w->P[w->jpos[j]];
        const mpb_robot_joint *J = &r->joints[j];
        double a[3], lin[3], ang[3] = { 0, 0, 0 };
        mpb__mat3_vec(C->R, J->axis, a);
        if (J->type == MPB_JOINT_PRISMATIC) {
            lin[0] = a[0];
            lin[1] = a[1];
            lin[2] = a[2];
        } else {
            double d[3] = { w->p[0] - C->t[0], w->p[1] - C->t[1],
                            w->p[2] - C->t[2] };
            lin[0] = a[1] * d[2] - a[2] * d[1];
            lin[1] = a[2] * d[0] - a[0] * d[2];
            lin[2] = a[0] * d[1] - a[1] * d[0];
            ang[0] = a[0];
            ang[1] = a[1];
            ang[2] = a[2];
        }
        for (int i = 0; i < 3; i++) {
            w->J[i * w->n + j] = lin[i];
            if (w->m == 6)
                w->J[(3 + i) * w->n + j] = ang[i];
        }
    }
}

/* Solve A x = b in place (A k x k symmetric positive definite, k <= 7). */
static int chol_solve(double *A, int k, double *b)
{
    for (int j = 0; j < k; j++) {
        double d = A[j * k + j];
        for (int s = 0; s < j; s++)
            d -= A[j * k + s] * A[j * k + s];
        if (!(d > 0.0))
            return -1;
        d = sqrt(d);
        A[j * k + j] = d;
        for (int i = j + 1; i < k; i++) {
            double v = A[i * k + j];
            for (int s = 0; s < j; s++)
                v -= A[i * k + s] * A[j * k + s];
            A[i * k + j] = v / d;
        }
    }
    for (int i = 0; i < k; i++) {           /* L y = b */
        double v = b[i];
        for (int s = 0; s < i; s++)
            v -= A[i * k + s] * b[s];
        b[i] = v / A[i * k + i];
    }
    for (int i = k - 1; i >= 0; i--) {      /* L^T x = y */
        double v = b[i];
        for (int s = i + 1; s < k; s++)
            v -= A[s * k + i] * b[s];
        b[i] = v / A[i * k + i];
    }
    return 0;
}

/* The damped step dq (n values) for damping lambda; -1 if it fails. */
static int ik_step(const ik_ws *w, double lambda, double *dq)
{
    int m = w->m, n = w->n;
    const double *J = w->J;
    double A[36], b[6];
    if (n > m) {            /* dq = J^T (J J^T + lambda I)^-1 e */
        for (int i = 0; i < m; i++) {
            for (int k = 0; k <= i; k++) {
                double s = 0.0;
                for (int j = 0; j < n; j++)
                    s += J[i * n + j] * J[k * n + j];
                A[i * m + k] = A[k * m + i] = s;
            }
            A[i * m + i] += lambda;
            b[i] = w->e[i];
        }
        if (chol_solve(A, m, b) != 0)
            return -1;
        for (int j = 0; j < n; j++) {
            double s = 0.0;
            for (int i = 0; i < m; i++)
                s += J[i * n + j] * b[i];
            dq[j] = s;
        }
    } else {                /* dq = (J^T J + lambda I)^-1 J^T e */
        for (int j = 0; j < n; j++) {
            for (int k = 0; k <= j; k++) {
                double s = 0.0;
                for (int i = 0; i < m; i++)
                    s += J[i * n + j] * J[i * n + k];
                A[j * n + k] = A[k * n + j] = s;
            }
            A[j * n + j] += lambda;
            double s = 0.0;
            for (int i = 0; i < m; i++)
                s += J[i * n + j] * w->e[i];
            b[j] = s;
        }
        if (chol_solve(A, n, b) != 0)
            return -1;
        for (int j = 0; j < n; j++)
            dq[j] = b[j];
    }
    for (int j = 0; j < n; j++)
        if (!isfinite(dq[j]))
            return -1;
    return 0;
}

static double clamp_joint(const mpb_robot *r, int j, double v)
{
    if (r->wraps[j])
        return v;
    return fmin(fmax(v, r->joints[j].lo), r->joints[j].hi);
}

int mpb_robot_ik(const mpb_robot *r, int link, const double offset[3],
                 const mpb_pose *target, const double *seed,
                 const mpb_ik_options *opt, uint64_t *rng, double *q_out,
                 mpb_ik_info *info)
{
    mpb_ik_options o;
    if (opt)
        o = *opt;
    else
        mpb_ik_options_init(&o);
    if (!r || !target || !rng || !q_out || link < 0 || link >= r->num_links)
        return MPB_EINVAL;
    if (!mpb_pose_is_rigid(target) || (offset && !finite3(offset)))
        return MPB_EINVAL;
    if (o.max_attempts < 1 || o.max_iterations < 1
        || !(o.position_tolerance > 0) || !(o.orientation_tolerance > 0)
        || !isfinite(o.position_tolerance) || !isfinite(o.orientation_tolerance))
        return MPB_EINVAL;
    if (seed && !q_finite(r, seed))
        return MPB_EINVAL;

    int N = r->num_joints;
    int n = r->links[link].num_chain_joints;
    int plen = r->path_len[link];
    ik_ws w = { .r = r, .link = link, .n = n, .m = o.position_only ? 3 : 6,
                .target = target };
    if (offset)
        memcpy(w.offset, offset, sizeof w.offset);

    /* One buffer: path poses, then J, q, q_trial, q_best, dq, then jpos. */
    size_t nd = (size_t)(6 * n) + 4 * (size_t)N;
    size_t bytes = (size_t)(plen > 0 ? plen : 1) * sizeof(mpb_pose)
                 + nd * sizeof(double) + (size_t)(n > 0 ? n : 1) * sizeof(int);
    char *buf = malloc(bytes);
    if (!buf)
        return MPB_ENOMEM;
    w.P = (mpb_pose *)buf;
    double *dbl = (double *)(buf + (size_t)(plen > 0 ? plen : 1) * sizeof(mpb_pose));
    w.J = dbl;
    double *q = w.J + 6 * n, *qt = q + N, *qbest = qt + N, *dq = qbest + N;
    w.jpos = (int *)(dq + N);
    const int *path = r->path_pool + r->path_off[link];
    for (int j = 0; j < n; j++) {
        w.jpos[j] = 0;
        for (int k = 0; k < plen; k++)
            if (path[k] == r->joints[j].child_link)
                w.jpos[j] = k;
    }

    /* Joints that do not move the link: from the seed, or mid-range. */
    for (int j = 0; j < N; j++) {
        if (seed)
            q[j] = clamp_joint(r, j, seed[j]);
        else
            q[j] = r->wraps[j] ? 0.0 : 0.5 * (r->joints[j].lo + r->joints[j].hi);
    }
    memcpy(qbest, q, (size_t)N * sizeof *q);
    double best = INFINITY;
    int solved = 0, attempts = 0, iterations = 0;

    for (attempts = 0; attempts < o.max_attempts && !solved; ) {
        if (attempts > 0 || !seed)
            for (int j = 0; j < n; j++)
                q[j] = uniform(rng, r->joints[j].lo, r->joints[j].hi);
        attempts++;
        double cost = ik_eval(&w, q);
        double perr = w.perr, rerr = w.rerr;
        ik_jacobian(&w);
        double lambda = 1e-2, cost_before = cost;
        for (int it = 0; it < o.max_iterations; it++) {
            if (perr <= o.position_tolerance
                && (o.position_only || rerr <= o.orientation_tolerance)) {
                solved = 1;
                break;
            }
            if (n == 0)
                break;
            iterations++;
            /* A local minimum: not 0.1% better over 10 steps. */
            if (it > 0 && it % 10 == 0) {
                if (cost > 0.999 * cost_before)
                    break;
                cost_before = cost;
            }
            memcpy(qt, q, (size_t)N * sizeof *q);
            int ok = ik_step(&w, lambda, dq) == 0;
            /*
             * Joints at a limit that the step pushes further out: drop
             * them from J (until q changes) and solve again without them.
             */
            int locked = 0;
            for (int j = 0; ok && j < n; j++) {
                if (r->wraps[j])
                    continue;
                if ((q[j] <= r->joints[j].lo && dq[j] < 0)
                    || (q[j] >= r->joints[j].hi && dq[j] > 0)) {
                    for (int i = 0; i < w.m; i++)
                        w.J[i * n + j] = 0.0;
                    locked = 1;
                }
            }
            if (ok && locked)
                ok = ik_step(&w, lambda, dq) == 0;
            if (ok)
                for (int j = 0; j < n; j++)
                    qt[j] = clamp_joint(r, j, q[j] + dq[j]);
            double ct = ok ? ik_eval(&w, qt) : INFINITY;
            if (ct < cost) {
                memcpy(q, qt, (size_t)N * sizeof *q);
                cost = ct;
                perr = w.perr;
                rerr = w.rerr;
                ik_jacobian(&w);
                lambda = fmax(lambda * 0.1, 1e-12);
            } else {
                lambda *= 10.0;
                if (lambda > 1e8)
                    break;
            }
        }
        if (perr <= o.position_tolerance
            && (o.position_only || rerr <= o.orientation_tolerance))
            solved = 1;         /* also when the last step got there */
        if (solved || cost < best) {
            best = cost;
            memcpy(qbest, q, (size_t)N * sizeof *q);
        }
        if (n == 0)
            break;              /* nothing moves the link: no use retrying */
    }

    for (int j = 0; j < N; j++)
        q_out[j] = r->wraps[j] ? wrap_angle(qbest[j]) : qbest[j];
    if (info) {
        ik_eval(&w, q_out);
        info->attempts = attempts;
        info->iterations = iterations;
        info->position_error = w.perr;
        /* The angle of R_target^T R, whatever the mode. */
        mpb_pose T;
        double Rrel[9];
        path_poses(r, q_out, link, w.P, &T);
        mpb__mat3_tmul(target->R, T.R, Rrel);
        info->orientation_error = mpb__rot_angle(Rrel);
    }
    free(buf);
    return solved ? MPB_OK : MPB_ENOTFOUND;
}

/* ---- goal regions ------------------------------------------------------- */

int mpb_goal_region_check(const mpb_robot *r, const mpb_goal_region *g,
                          char *err, size_t errlen)
{
    mpb__set_err(err, errlen, "%s", "");
    if (!r || !g) {
        mpb__set_err(err, errlen, "goal region: NULL robot or region");
        return MPB_EINVAL;
    }
    if (g->link < 0 || g->link >= r->num_links) {
        mpb__set_err(err, errlen, "goal region: link %d out of range (%d links)",
                     g->link, r->num_links);
        return MPB_EINVAL;
    }
    if (!finite3(g->offset) || !finite3(g->center) || !finite3(g->ref_rpy)
        || !finite3(g->half_extents) || !finite3(g->rpy_tolerance)) {
        mpb__set_err(err, errlen, "goal region: a number is NaN or infinite");
        return MPB_EINVAL;
    }
    for (int i = 0; i < 3; i++)
        if (g->half_extents[i] < 0 || g->rpy_tolerance[i] < 0) {
            mpb__set_err(err, errlen, "goal region: negative half extent or "
                         "tolerance");
            return MPB_EINVAL;
        }
    return MPB_OK;
}

int mpb_goal_region_distance(const mpb_robot *r, const mpb_goal_region *g,
                             const double *q, mpb_goal_distance *out)
{
    if (!out || !q || mpb_goal_region_check(r, g, NULL, 0) != MPB_OK)
        return MPB_EINVAL;
    mpb_pose T, ref;
    if (mpb_robot_link_pose(r, q, g->link, &T) != MPB_OK)
        return MPB_EINVAL;
    mpb_pose_apply(&T, g->offset, out->point);
    double d2 = 0.0;
    for (int i = 0; i < 3; i++) {
        double d = fabs(out->point[i] - g->center[i]) - g->half_extents[i];
        if (d > 0)
            d2 += d * d;
    }
    out->position = sqrt(d2);

    mpb_pose rel;
    mpb_pose_identity(&ref);
    mpb_pose_set_rpy(&ref, g->ref_rpy[0], g->ref_rpy[1], g->ref_rpy[2]);
    mpb_pose_identity(&rel);
    mpb__mat3_tmul(ref.R, T.R, rel.R);
    mpb_pose_get_rpy(&rel, out->rpy_rel);
    out->angle = mpb__rot_angle(rel.R);
    out->orientation = 0.0;
    for (int i = 0; i < 3; i++) {
        double d = fabs(out->rpy_rel[i]) - g->rpy_tolerance[i];
        if (d > out->orientation)
            out->orientation = d;
    }
    return MPB_OK;
}

int mpb_goal_region_contains(const mpb_robot *r, const mpb_goal_region *g,
                             const double *q)
{
    mpb_goal_distance d;
    int rc = mpb_goal_region_distance(r, g, q, &d);
    if (rc != MPB_OK)
        return rc;
    return d.position == 0.0 && d.orientation == 0.0;
}

int mpb_goal_region_sample(const mpb_robot *r, const mpb_goal_region *g,
                           const double *seed, const mpb_ik_options *opt,
                           int max_targets, uint64_t *rng, double *q_out)
{
    if (!rng || !q_out || mpb_goal_region_check(r, g, NULL, 0) != MPB_OK)
        return MPB_EINVAL;
    mpb_ik_options o;
    if (opt) {
        o = *opt;
    } else {
        mpb_ik_options_init(&o);
        o.max_attempts = 20;
    }
    if (g->rpy_tolerance[0] >= M_PI && g->rpy_tolerance[1] >= M_PI
        && g->rpy_tolerance[2] >= M_PI)
        o.position_only = 1;
    if (max_targets <= 0)
        max_targets = 50;

    mpb_pose ref;
    mpb_pose_identity(&ref);
    mpb_pose_set_rpy(&ref, g->ref_rpy[0], g->ref_rpy[1], g->ref_rpy[2]);
    const double cap[3] = { M_PI, M_PI / 2, M_PI };
    int rc = MPB_ENOTFOUND;
    for (int t = 0; t < max_targets; t++) {
        mpb_pose target, rel;
        mpb_pose_identity(&rel);
        double rpy[3];
        for (int i = 0; i < 3; i++) {
            double tol = fmin(g->rpy_tolerance[i], cap[i]);
            rpy[i] = uniform(rng, -tol, tol);
            target.t[i] = g->center[i]
                        + uniform(rng, -g->half_extents[i], g->half_extents[i]);
        }
        mpb_pose_set_rpy(&rel, rpy[0], rpy[1], rpy[2]);
        mpb__mat3_mul(ref.R, rel.R, target.R);
        rc = mpb_robot_ik(r, g->link, g->offset, &target, seed, &o, rng, q_out,
                          NULL);
        if (rc == MPB_OK) {
            if (mpb_goal_region_contains(r, g, q_out) == 1)
                return MPB_OK;
            rc = MPB_ENOTFOUND;
        } else if (rc != MPB_ENOTFOUND) {
            return rc;
        }
    }
    return rc;
}
