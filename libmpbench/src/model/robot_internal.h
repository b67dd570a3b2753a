/*
 * robot_internal.h - the robot model's state, shared by the files that
 * make it: robot.c (loading, the model), robot_fk.c (forward
 * kinematics), robot_ik.c (inverse kinematics) and robot_goal.c (goal
 * regions); not part of the API.
 */
#ifndef MPB_ROBOT_INTERNAL_H
#define MPB_ROBOT_INTERNAL_H

#include <math.h>
#include <stdint.h>

#include "mpbench/robot.h"
#include "model/robot_urdf.h"

/* How a link's pose follows from its parent's. */
typedef struct mpb__kin {
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
} mpb__kin;

struct mpb_robot {
    mpb__urdf_model      model;   /* owns the names and mesh URIs */
    int                  num_links;
    mpb_robot_link      *links;
    mpb__kin            *kin;
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

/* splitmix64: any state is a valid seed. */
static inline uint64_t mpb__rng_next(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* Uniform in [0, 1). */
static inline double mpb__rng_unit(uint64_t *s)
{
    return (double)(mpb__rng_next(s) >> 11) * (1.0 / 9007199254740992.0);
}

static inline double mpb__uniform(uint64_t *s, double lo, double hi)
{
    return lo + (hi - lo) * mpb__rng_unit(s);
}

static inline int mpb__finite3(const double v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

static inline int mpb__robot_q_finite(const mpb_robot *r, const double *q)
{
    for (int j = 0; j < r->num_joints; j++)
        if (!isfinite(q[j]))
            return 0;
    return 1;
}

/* ---- robot_fk.c: how each link follows its parent --------------------- */

/* Set k->fixed (origin * motion at the passive value) and fixed_pure. */
void mpb__robot_set_fixed(mpb__kin *k);

/* Choose k's shortcuts for the common cases, once, after loading. */
void mpb__robot_kin_shortcuts(mpb__kin *k);

/* Recompute the static link poses (after loading or set_passive). */
void mpb__robot_compute_static(mpb_robot *r);

/*
 * Poses of the path of `link` (its moving ancestors and itself, top down)
 * into P (path_len entries); the link's pose into *out. Static links: out
 * only.
 */
void mpb__robot_path_poses(const mpb_robot *r, const double *q, int link,
                           mpb_pose *P, mpb_pose *out);

#endif /* MPB_ROBOT_INTERNAL_H */
