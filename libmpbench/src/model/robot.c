/*
 * robot.c - the robot model: loading a planning group (serial chain) over
 * a URDF tree, mimic joints following their leaders, and the model's
 * joints, links and shapes. The URDF itself is read by the C++ bridge
 * robot_urdf.cpp; kinematics and goal regions are in robot_fk.c,
 * robot_ik.c and robot_goal.c.
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
#include "core/mathconst.h"
#include "core/readfile.h"
#include "model/robot_internal.h"
#include "model/robot_urdf.h"

#define NAME_SHOWN 80                   /* characters of a name in errors */
#define MAX_URDF_BYTES (64L << 20)      /* a bigger file is not a URDF */

/* ---- small helpers --------------------------------------------------- */

static int pose_finite(const mpb_pose *p)
{
    for (int i = 0; i < 9; i++)
        if (!isfinite(p->R[i]))
            return 0;
    return mpb__finite3(p->t);
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
                if (!mpb__finite3(l->axis) || !(n > 1e-12)) {
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
                ok = ok && g->mesh_uri && g->mesh_uri[0] && mpb__finite3(g->mesh_scale)
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
        mpb__kin *k = &r->kin[i];
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
        mpb__robot_set_fixed(k);
        mpb__robot_kin_shortcuts(k);
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
        mpb__kin *k = &r->kin[i];
        if (mi->lead[i] >= 0 && k->mimic < 0) {
            k->passive = k->mimic_m * r->kin[mi->lead[i]].passive + k->mimic_o;
            mpb__robot_set_fixed(k);
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
    mpb__robot_compute_static(r);
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
    rc = mpb__urdf_parse_cached(text, &r->model, msg, sizeof msg);
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
    mpb_robot_close(r);
    return rc;
}

int mpb_robot_open_urdf(const char *urdf_text, const char *base_link,
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

int mpb_robot_open_urdf_joints(const char *urdf_text,
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

int mpb_robot_open_urdf_file(const char *path, const char *base_link,
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
    char *text;
    size_t len;
    int rc = mpb__read_file(path, (size_t)MAX_URDF_BYTES, &text, &len, err,
                            errlen);
    if (rc != MPB_OK)
        return rc;
    if (strlen(text) != len) {
        mpb__set_err(err, errlen, "%s: not a text file (NUL byte)", path);
        rc = MPB_EPARSE;
    } else {
        rc = load(text, base_link, tip_link, NULL, 0, path, out, err, errlen);
    }
    free(text);
    return rc;
}

void mpb_robot_close(mpb_robot *r)
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
    mpb__kin *k = &r->kin[i];
    const mpb__urdf_link *ul = &r->model.links[i];
    if (k->chain >= 0 || r->links[i].mimic_link >= 0 || !isfinite(value) ||
        !is_active_type(k->type))
        return MPB_EINVAL;
    if (k->type != MPB_JOINT_CONTINUOUS && (value < ul->lo || value > ul->hi))
        return MPB_EINVAL;
    k->passive = value;
    mpb__robot_set_fixed(k);
    for (int f = 0; f < r->num_links; f++)
        if (r->links[f].mimic_link == i) {
            r->kin[f].passive = r->kin[f].mimic_m * value + r->kin[f].mimic_o;
            mpb__robot_set_fixed(&r->kin[f]);
        }
    mpb__robot_compute_static(r);
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
    const mpb__kin *k = &r->kin[i];
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
        q[j] = mpb__uniform(rng, r->joints[j].lo, r->joints[j].hi);
    return MPB_OK;
}

