/*
 * robot.h - a robot from URDF: its links and their collision geometry, a
 * planning group (a serial chain of joints), forward kinematics for every
 * link, numerical inverse kinematics, and goal regions as the paper defines
 * them (a point of a link inside a box, roll/pitch/yaw within tolerances).
 * docs/robot-model.md has the details and the reasons.
 *
 * Frames. Every pose is in the ROBOT FRAME, the frame of the URDF's root
 * link (what MoveIt calls the model frame and plans in). Poses are
 * mpb_pose (pose.h): p_parent = R * p_child + t, R row-major.
 *
 * Links and joints. All links of the URDF are loaded, indexed 0 ..
 * num_links-1 in a depth-first order from the root (index 0), so a link's
 * parent always has a smaller index. The planning group is a serial chain
 * of num_joints ACTIVE joints (revolute, continuous or prismatic), indexed
 * 0 .. num_joints-1 from base to tip; a configuration q is num_joints
 * values in that order (rad, or m for prismatic joints). Every other joint
 * of the URDF is PASSIVE: it holds a value (0, moved into its limits; see
 * mpb_robot_set_passive()). Fixed joints on the chain are passive too.
 * A MIMIC joint (URDF <mimic joint= multiplier= offset=>) is neither: it
 * follows its leader everywhere, value = multiplier * leader + offset
 * (multiplier 1 and offset 0 when not written), whether the leader is
 * active or holds a value; a leader that mimics another is followed to
 * the first joint that does not. A mimic joint is never active. A link
 * MOVES when an active joint, or a mimic joint of an active leader, lies
 * between it and the root (the links of the chain below the first active
 * joint and everything attached below them, e.g. a gripper on the tip and
 * its mimic fingers); every other link is STATIC: its pose is the same
 * for every q (the base, the torso, the other arm ...).
 *
 * Ownership. A robot owns every string and array it hands out; they live
 * until mpb_robot_close(). Nothing returned needs freeing by the caller.
 *
 * Threads. After loading, a robot is read-only, so FK, IK and goal-region
 * calls may run on one robot from several threads at once, each with its
 * own output buffers and RNG state. mpb_robot_set_passive() is the one
 * writer: do not call it while other calls run.
 *
 * Randomness. IK and sampling take `uint64_t *rng`, a state the caller
 * owns: any value is a valid seed, each call advances it (splitmix64). The
 * same robot, arguments and seed give the same result on every run.
 */
#ifndef MPBENCH_ROBOT_H
#define MPBENCH_ROBOT_H

#include <stddef.h>
#include <stdint.h>

#include "mpbench/collision.h"  /* mpb_shape_type */
#include "mpbench/pose.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mpb_robot mpb_robot;

typedef enum mpb_joint_type {
    MPB_JOINT_FIXED = 0,
    MPB_JOINT_REVOLUTE = 1,     /* rotation about axis, limited */
    MPB_JOINT_CONTINUOUS = 2,   /* rotation about axis, unlimited, wraps */
    MPB_JOINT_PRISMATIC = 3,    /* translation along axis, limited */
    MPB_JOINT_FLOATING = 4,     /* passive only, held at the identity */
    MPB_JOINT_PLANAR = 5        /* passive only, held at the identity */
} mpb_joint_type;

/* Lower-case URDF name of a joint type ("revolute"), static; "unknown" if
 * out of range. */
const char *mpb_joint_type_name(mpb_joint_type type);

/* An active joint of the chain. */
typedef struct mpb_robot_joint {
    const char    *name;
    mpb_joint_type type;        /* REVOLUTE, CONTINUOUS or PRISMATIC */
    double         lo, hi;      /* limits, rad or m; CONTINUOUS: -pi, pi
                                   (as mpb_world reports them; the joint
                                   wraps and has no limits) */
    double         max_velocity;/* URDF <limit velocity>, 0 if absent */
    double         axis[3];     /* unit vector, in the joint frame (which
                                   is the child link's frame) */
    mpb_pose       origin;      /* parent link frame -> joint frame at 0 */
    int            parent_link; /* link indices */
    int            child_link;
} mpb_robot_joint;

/* A link of the URDF. */
typedef struct mpb_robot_link {
    const char    *name;
    int            parent;      /* link index; -1 for the root */
    const char    *joint;       /* URDF joint from the parent; NULL at root */
    mpb_joint_type joint_type;  /* of that joint (FIXED at the root) */
    int            chain_joint; /* that joint's index in the chain, or -1 */
    int            moves;       /* 1 if its pose depends on q, else 0 */
    int            num_chain_joints; /* the active joints on its path to
                                   the root are 0 .. num_chain_joints-1
                                   (0 if static); a mimic joint on the path
                                   moves it too, and adds none */
    int            first_collision;  /* its shapes: collisions
                                   first_collision .. + num_collisions - 1 */
    int            num_collisions;
    /* Last, so that the fields above keep their places. */
    int            mimic_link;  /* its joint is a mimic joint: the link
                                   whose parent joint it follows in the
                                   end (the leader's child link); else -1 */
    double         mimic_multiplier, mimic_offset; /* value = multiplier *
                                   leader + offset, mimics of mimics
                                   composed */
} mpb_robot_link;

/*
 * One <collision> element of a link. Primitive conventions are those of
 * mpb_geometry (collision.h), which are URDF's: centred on the shape frame,
 * a box by its full side lengths, a cylinder along z.
 */
typedef struct mpb_robot_collision {
    int            link;        /* link index */
    mpb_shape_type type;        /* BOX, SPHERE, CYLINDER or MESH */
    double         dims[4];     /* BOX x y z; SPHERE r; CYLINDER r length */
    const char    *mesh_uri;    /* MESH: the filename as written in the URDF
                                   (package://, file://, relative ...),
                                   not resolved; NULL for primitives */
    double         mesh_scale[3]; /* MESH: per-axis scale (1 1 1 default) */
    mpb_pose       origin;      /* link frame -> shape frame */
    const char    *name;        /* <collision name="...">, NULL if none */
} mpb_robot_collision;

/* ---- loading ------------------------------------------------------------ */

/*
 * Load the URDF text (NUL-terminated) with the planning group from
 * base_link down to tip_link: the active joints are the revolute,
 * continuous and prismatic joints on the path between them, base first.
 * base_link NULL means the URDF's root link; tip_link NULL the link below
 * the base with the most active joints above it (the first in depth-first
 * order of those): the robot's longest chain.
 *
 * On success *out is a new robot, freed with mpb_robot_close(). On failure
 * *out is NULL and err (if not NULL) holds one line starting "urdf: ":
 *   MPB_EPARSE       not XML, not a valid URDF (urdfdom's messages, joined;
 *                    anything urdfdom reports as an error counts, even an
 *                    element it would skip), a link missing, tip_link not
 *                    below base_link, no active joint between them, a zero
 *                    or non-finite axis, lower > upper, a bad geometry;
 *                    a mimic joint whose leader is no joint, is not
 *                    revolute, continuous or prismatic, or is (through
 *                    other mimics) itself (a fixed joint's <mimic> is
 *                    ignored: it cannot move);
 *   MPB_EUNSUPPORTED a floating or planar joint inside the chain;
 *   MPB_EINVAL       NULL urdf_text or out; MPB_ENOMEM.
 * urdfdom's console output is captured while parsing (console_bridge's
 * handler is swapped for the duration, under a lock), never printed.
 */
int mpb_robot_open_urdf(const char *urdf_text, const char *base_link,
                        const char *tip_link, mpb_robot **out,
                        char *err, size_t errlen);

/*
 * As mpb_robot_open_urdf(), the group given as its active joints, named in
 * order from base to tip. They must lie on one path from the root, each
 * below the one before; joints on that path not named become passive. The
 * base link is the first joint's parent, the tip link the last's child.
 * MPB_EPARSE also for an unknown joint name, a name given twice, a fixed,
 * floating, planar or mimic joint named, or joints not on one path in
 * order.
 */
int mpb_robot_open_urdf_joints(const char *urdf_text,
                               const char *const *joint_names, int num_names,
                               mpb_robot **out, char *err, size_t errlen);

/*
 * Read the file at path and load it as mpb_robot_open_urdf() does; the
 * message then starts with the path instead of "urdf"
 * ("robots/pr2.urdf: tip link 'r_hand' not found"). MPB_EIO when the file
 * cannot be read.
 */
int mpb_robot_open_urdf_file(const char *path, const char *base_link,
                             const char *tip_link, mpb_robot **out,
                             char *err, size_t errlen);

/* Release a robot and everything it handed out; NULL does nothing. */
void mpb_robot_close(mpb_robot *r);

/* ---- the model ---------------------------------------------------------- */

/* The URDF <robot name>; owned by r. */
const char *mpb_robot_name(const mpb_robot *r);

/* Active joints of the chain, owned by r; out of range gives NULL. */
int                    mpb_robot_num_joints(const mpb_robot *r);
const mpb_robot_joint *mpb_robot_get_joint(const mpb_robot *r, int joint);
/* Index of the active joint of that name, or MPB_ENOTFOUND. */
int                    mpb_robot_joint_index(const mpb_robot *r,
                                             const char *name);
/*
 * One byte per active joint, nonzero where it is continuous: the
 * mpb_joint_wrap of metrics.h. Owned by r.
 */
const unsigned char   *mpb_robot_joint_wraps(const mpb_robot *r);

/* All links, owned by r; out of range gives NULL. */
int                    mpb_robot_num_links(const mpb_robot *r);
const mpb_robot_link  *mpb_robot_get_link(const mpb_robot *r, int link);
/* Index of the link of that name, or MPB_ENOTFOUND. */
int                    mpb_robot_link_index(const mpb_robot *r,
                                            const char *name);
/* The chain's base and tip link indices. */
int                    mpb_robot_base_link(const mpb_robot *r);
int                    mpb_robot_tip_link(const mpb_robot *r);

/* All collision shapes, grouped by link in link order; NULL if out of range. */
int                        mpb_robot_num_collisions(const mpb_robot *r);
const mpb_robot_collision *mpb_robot_get_collision(const mpb_robot *r,
                                                   int index);

/*
 * Set the value of a passive joint (rad or m) by its URDF name, e.g. the
 * torso height of a PR2 whose group starts above it; the static link poses
 * are recomputed, and the joints that mimic it follow. MPB_OK;
 * MPB_ENOTFOUND for no such joint; MPB_EINVAL for an active joint, a
 * mimic joint (set its leader), a fixed, floating or planar one, a
 * non-finite value or one outside a revolute or prismatic joint's limits.
 * Not thread-safe (see the top of this file).
 */
int mpb_robot_set_passive(mpb_robot *r, const char *joint, double value);

/*
 * The value a passive joint holds now and its limits (a continuous joint:
 * -pi .. pi, though it takes any finite value), by its URDF name; any
 * pointer may be NULL. MPB_OK; MPB_ENOTFOUND for no such joint; MPB_EINVAL
 * for a joint of the chain or one that cannot hold a value (fixed,
 * floating, planar).
 */
int mpb_robot_get_passive(const mpb_robot *r, const char *joint,
                          double *value, double *lo, double *hi);

/*
 * 1 if every value of q is finite and inside its joint's limits (a
 * continuous joint takes any finite value), else 0 (also for NULL r or q).
 */
int mpb_robot_within_limits(const mpb_robot *r, const double *q);

/*
 * A random configuration, uniform inside the limits (continuous joints in
 * [-pi, pi)), in q (num_joints values). Advances *rng. MPB_OK or MPB_EINVAL.
 */
int mpb_robot_random_config(const mpb_robot *r, uint64_t *rng, double *q);

/* ---- forward kinematics -------------------------------------------------- */

/*
 * The pose of every link at q (num_joints finite values; continuous joints
 * take any value, limits are not checked), in the robot frame:
 * poses[i] for link i, num_links entries, caller-allocated. Allocates
 * nothing. MPB_OK; MPB_EINVAL for NULL arguments or a non-finite q (poses
 * then untouched).
 */
int mpb_robot_fk(const mpb_robot *r, const double *q, mpb_pose *poses);

/*
 * The fast path for repeated calls: as mpb_robot_fk() but writes only the
 * entries of moving links; the static entries are left as they were (fill
 * them once with mpb_robot_fk()).
 */
int mpb_robot_fk_moving(const mpb_robot *r, const double *q,
                        mpb_pose *poses);

/*
 * The pose of one link at q, walking only the links between it and the
 * root. Same rules as mpb_robot_fk(); MPB_EINVAL also for a bad link.
 */
int mpb_robot_link_pose(const mpb_robot *r, const double *q, int link,
                        mpb_pose *out);

/* ---- inverse kinematics -------------------------------------------------- */

typedef struct mpb_ik_options {
    int    max_attempts;        /* starts: the seed (if given), then random
                                   configurations; default 100 */
    int    max_iterations;      /* Levenberg-Marquardt steps per start;
                                   default 100 */
    double position_tolerance;  /* m, default 1e-6 */
    double orientation_tolerance; /* rad, default 1e-6 */
    int    position_only;       /* nonzero: ignore the orientation */
} mpb_ik_options;

/* Fill *opt with the defaults above. */
void mpb_ik_options_init(mpb_ik_options *opt);

typedef struct mpb_ik_info {
    int    attempts;            /* starts used */
    int    iterations;          /* steps over all starts */
    double position_error;      /* m, of the returned q */
    double orientation_error;   /* rad, rotation angle of R_target^T R */
} mpb_ik_info;

/*
 * Solve for q such that the frame of link `link` moved by `offset` (a
 * point of the link frame; NULL means its origin) is at `target` in the
 * robot frame: the offset point at target->t and the link's rotation
 * target->R (ignored with position_only). Only joints 0 ..
 * num_chain_joints-1 of the link are varied; the others keep their value
 * from seed, or the middle of their limits (0 if continuous) without a
 * seed (a mimic joint on the link's path follows its leader's value, so
 * a link moved by the mimic of a later joint is reached as that joint
 * holds).
 *
 * Damped least squares with Levenberg-Marquardt damping on the 6-D error
 * (position, rotation vector), steps clamped to the joint limits (a joint
 * at a limit that the step pushes outwards sits the step out), from the
 * seed (if not NULL, clamped into the limits) and then from random
 * configurations until the error is within both tolerances or the
 * attempts run out; a start is abandoned after max_iterations steps or
 * when ten steps gain less than 0.1%. Continuous joints of the answer are
 * wrapped into (-pi, pi]; every value is within its limits.
 *
 * MPB_OK with the solution in q_out (num_joints values); MPB_ENOTFOUND
 * with the closest configuration found in q_out; MPB_EINVAL for NULL r,
 * target, rng or q_out, a bad link, a non-rigid target, options out of
 * range; MPB_ENOMEM. opt NULL means the defaults; info (may be NULL) is
 * filled on OK and ENOTFOUND. Allocates one work buffer per call.
 */
int mpb_robot_ik(const mpb_robot *r, int link, const double offset[3],
                 const mpb_pose *target, const double *seed,
                 const mpb_ik_options *opt, uint64_t *rng, double *q_out,
                 mpb_ik_info *info);

/* ---- goal regions ------------------------------------------------------- */

/*
 * The paper's goal region, in the robot frame: the reference point of a
 * link (its origin moved by `offset`, in the link frame) inside an
 * axis-aligned box, and the link's orientation within per-axis tolerances
 * of a reference orientation.
 *
 * How orientation is measured: R_rel = R_ref^T * R, the link's rotation R
 * relative to the reference R_ref (from ref_rpy), is expressed as URDF
 * roll/pitch/yaw (mpb_pose_get_rpy(): R_rel = Rz(y) Ry(p) Rx(r), pitch in
 * [-pi/2, pi/2]); the region holds it when |r| <= tol[0], |p| <= tol[1] and
 * |y| <= tol[2]. Unlike a difference of two rpy triples, this needs no
 * angle wrapping and stays well defined when the reference itself is at
 * pitch +-pi/2 (a gripper pointing straight down): the relative rotation
 * is near the identity there, far from its own gimbal lock. A tolerance
 * >= pi leaves that component free. (MoveIt's OrientationConstraint
 * measures the same R_ref^T R.)
 *
 * All comparisons are <=, so the boundary is inside.
 */
typedef struct mpb_goal_region {
    int    link;                /* link index */
    double offset[3];           /* reference point in the link frame (m) */
    double center[3];           /* box centre, robot frame (m) */
    double half_extents[3];     /* box half sizes (m, >= 0): the paper's
                                   2 cm cube has 0.01 0.01 0.01 */
    double ref_rpy[3];          /* reference orientation, URDF rpy (rad) */
    double rpy_tolerance[3];    /* rad, >= 0 */
} mpb_goal_region;

/*
 * MPB_OK if g fits r (a valid link, every number finite, half extents and
 * tolerances >= 0), else MPB_EINVAL with one line in err (if not NULL).
 */
int mpb_goal_region_check(const mpb_robot *r, const mpb_goal_region *g,
                          char *err, size_t errlen);

/*
 * 1 if the robot at q satisfies g, 0 if not; MPB_EINVAL for NULL
 * arguments, a non-finite q or a g that fails mpb_goal_region_check().
 */
int mpb_goal_region_contains(const mpb_robot *r, const mpb_goal_region *g,
                             const double *q);

/* How far a configuration is from a goal region, for messages and tests. */
typedef struct mpb_goal_distance {
    double position;            /* m: Euclidean distance from the reference
                                   point to the box, 0 inside */
    double orientation;         /* rad: max over r, p, y of (|rpy_rel| - tol),
                                   0 when within every tolerance */
    double angle;               /* rad: rotation angle of R_rel, [0, pi] */
    double point[3];            /* the reference point, robot frame */
    double rpy_rel[3];          /* roll, pitch, yaw of R_rel */
} mpb_goal_distance;

/*
 * Fill *out for the robot at q. Inside the region exactly when
 * out->position == 0 and out->orientation == 0. MPB_OK or MPB_EINVAL as
 * for mpb_goal_region_contains().
 */
int mpb_goal_region_distance(const mpb_robot *r, const mpb_goal_region *g,
                             const double *q, mpb_goal_distance *out);

/*
 * Find a configuration inside g: up to max_targets times, draw a pose
 * uniformly inside the region (the point uniform in the box, each relative
 * rpy component uniform within its tolerance), solve IK for it (opt, NULL:
 * defaults with max_attempts 20; position only when all three tolerances
 * are >= pi) and keep the answer if mpb_goal_region_contains() accepts it.
 * seed (may be NULL) seeds each IK. max_targets <= 0 means 50.
 * MPB_OK with q_out (num_joints values) inside g; MPB_ENOTFOUND (q_out
 * then the last IK answer); MPB_EINVAL as above or for NULL rng or q_out;
 * MPB_ENOMEM.
 */
int mpb_goal_region_sample(const mpb_robot *r, const mpb_goal_region *g,
                           const double *seed, const mpb_ik_options *opt,
                           int max_targets, uint64_t *rng, double *q_out);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_ROBOT_H */
