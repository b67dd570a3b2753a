/*
 * world.h - a robot in a scene: joint names and limits, collision checks and
 * clearance at a configuration. One opaque handle over several formats, each
 * a provider behind a private table of functions (libmpbench/src/world_*.c).
 *
 * Formats (the robot_format / scene_format strings of a plan request):
 *   "planar"  A planar arm among circles and boxes, the small world of the
 *             walking skeleton and of fast tests (for users:
 *             docs/planar-format.md). Robot text, one item a line,
 *             '#' starts a comment:
 *                 base <x> <y>                 (m, optional, default 0 0)
 *                 link_radius <r>              (m, required, >= 0; every
 *                                               link is a capsule)
 *                 joint <name> <lo> <hi> <length>  (rad, lo <= hi; m, > 0)
 *                 joint <name> continuous <length>  (wraps; m, > 0)
 *             At least one joint; names unique. Joint i is revolute about z,
 *             at the end of link i-1 (joint 0 at the base); its angle adds to
 *             the ones before it (q = 0 everywhere: the arm lies along +x);
 *             link i runs from joint i to joint i+1 (or the tip). Scene text
 *             (may be empty or NULL):
 *                 circle <cx> <cy> <r>                 (r >= 0)
 *                 box <cx> <cy> <half_x> <half_y>      (axis-aligned, >= 0)
 *             Every number is within +-1e5 (MPB_COLLISION_MAX_COORD, m
 *             or rad). Distances are exact (capsule to circle, capsule to
 *             box). The planar arm has NO self-collision: links may cross
 *             each other.
 *   "urdf"    A robot from URDF (robot.h), among the objects of a MoveIt
 *             .scene file, scene format "moveit-scene" (scene.h); meshes
 *             through assimp, collision and distance through FCL
 *             (collision.h). The planning group is named by its joints.
 *             The robot text may go on, on the line after the URDF's
 *             closing </robot>, with the robot's SRDF (MoveIt's semantic
 *             description); its line numbers in messages ("srdf line 7:
 *             ...") count from there. The whole SRDF is read and its
 *             names checked against the URDF as mpb_srdf_open() (srdf.h)
 *             does, so a bad one is refused by every process that opens
 *             the world alike; a passive joint of the SRDF in the group is
 *             refused. Of what it says, the world uses its
 *             <disable_collisions link1= link2=/> pairs (every one,
 *             whatever its reason; one naming a link the URDF lacks is
 *             skipped, as MoveIt does: srdf.h mpb_srdf_skipped_pairs()); its virtual joints are held at the
 *             identity (the URDF's root frame is the world's); mimic
 *             joints follow their leaders (robot.h); groups and
 *             group states are for the caller, who names the group's
 *             joints (srdf.h). Self-collision follows MoveIt: every pair of
 *             links is checked, a moving link against the robot's fixed
 *             links too, unless the allowed-collision matrix (ACM) allows
 *             the pair; two fixed links are never checked. The ACM is the
 *             SRDF's pairs plus the adjacent links; without an SRDF it is
 *             generated as MoveIt's setup assistant does (see
 *             mpb_world_allowed_pair()). Clearance is to the scene only.
 *
 * A world is not thread-safe; use one per thread.
 */
#ifndef MPBENCH_WORLD_H
#define MPBENCH_WORLD_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mpb_world mpb_world;

/*
 * A robot text of format "urdf" is a URDF, perhaps followed by its SRDF
 * (docs/scenes.md). Where one ends and the other begins: the URDF is
 * text[0, *urdf_len), which ends with the line of its root element's end
 * tag (the first "</robot" outside comments); the SRDF is text + *srdf_at
 * to the end, or there is none when *srdf_at == strlen(text) (only blanks
 * and comments follow). A text without that tag is all URDF. The one rule
 * the library, the daemon and the planners (the Python kit, through
 * ctypes) share. MPB_OK, or MPB_EINVAL for a NULL argument. No ownership:
 * both are offsets into text.
 */
int mpb_robot_text_split(const char *text, size_t *urdf_len, size_t *srdf_at);

/*
 * Build a world from the robot and scene texts. On success *out is a new
 * world, freed with mpb_world_close(). On failure *out is NULL, the return
 * is MPB_EPARSE / MPB_EUNSUPPORTED / MPB_ENOMEM (MPB_EINVAL for a NULL
 * format, robot text or out), and err (if not NULL) holds one line naming
 * what is wrong and where ("robot line 3: joint needs ...", "scene line 2:
 * ..."; lines count from 1). A robot_format / scene_format pair that no
 * provider reads gives MPB_EUNSUPPORTED.
 */
int mpb_world_open(const char *robot_format, const char *robot_text,
                   const char *scene_format, const char *scene_text,
                   mpb_world **out, char *err, size_t errlen);

/*
 * As mpb_world_open(), with the planning group named by its joints, in the
 * order their values are given (a plan request's joint_names). For "urdf"
 * the joints must be given; for "planar" they may be NULL (all joints) or
 * must be the robot's joints in order.
 */
int mpb_world_open_group(const char *robot_format, const char *robot_text,
                         const char *scene_format, const char *scene_text,
                         const char *const *joints, int num_joints,
                         mpb_world **out, char *err, size_t errlen);

/*
 * As mpb_world_open_group(), for a robot read from a file in the folder
 * robot_dir (may be NULL): the last place the robot's meshes are looked
 * for, after MPB_MESH_PATH and ROS_PACKAGE_PATH (docs/scenes.md). The
 * folder is used while opening only.
 */
int mpb_world_open_group_in(const char *robot_format, const char *robot_text,
                            const char *robot_dir, const char *scene_format,
                            const char *scene_text, const char *const *joints,
                            int num_joints, mpb_world **out, char *err,
                            size_t errlen);

void mpb_world_close(mpb_world *w);

/*
 * The scene format that goes with robot_format ("planar" for "planar",
 * "moveit-scene" for "urdf"), or NULL when no provider reads robot_format:
 * tells which of the two formats an MPB_EUNSUPPORTED is about.
 */
const char *mpb_world_scene_format(const char *robot_format);

/*
 * Hold n joints outside the planning group at the values given (rad or m),
 * from now on: a "urdf" robot's passive joints (robot.h), the Panda's
 * fingers or a PR2's torso. Joints not named keep what they held (at
 * opening: 0, moved into the joint's limits). Every world of a run must
 * hold the same values, so the daemon sends them in each plan request
 * (plan_request_t.held_names, docs/protocol.md) and a planner applies them
 * to its world with this call. A generated allowed-collision matrix (no
 * SRDF) is made for the values held: after a hold that changes a value it
 * is made again before the next check (the collision world with it,
 * meshes loaded again), so hold before checking when you can.
 * MPB_OK (n = 0 too, in any world); MPB_ENOTFOUND for a joint the robot
 * lacks; MPB_EINVAL for a joint of the group, one that cannot move (fixed),
 * a non-finite value or one outside the joint's limits; MPB_EUNSUPPORTED
 * in a world without such joints (planar). On failure err (if not NULL)
 * holds one line naming the joint, and the joints before it in the list
 * hold their new values.
 */
int mpb_world_hold(mpb_world *w, const char *const *joints,
                   const double *values, int n, char *err, size_t errlen);

/*
 * The value a joint outside the group holds now, and its limits (a
 * continuous joint: -pi .. pi); any of value, lo, hi may be NULL. Codes as
 * mpb_world_hold().
 */
int mpb_world_held(const mpb_world *w, const char *joint, double *value,
                   double *lo, double *hi);

/* Accessors; a joint out of range gives NULL / NaN limits / 0. */
int         mpb_world_num_joints(const mpb_world *w);
/* Owned by the world. */
const char *mpb_world_joint_name(const mpb_world *w, int joint);
/* Limits of a joint; a continuous joint reports -pi .. pi and wraps. */
void        mpb_world_joint_limits(const mpb_world *w, int joint,
                                   double *lo, double *hi);
int         mpb_world_joint_is_continuous(const mpb_world *w, int joint);
/* A joint's velocity limit, rad/s or m/s, as its URDF <limit velocity>
 * gives it; 0 where none is given (a planar world's joints, a continuous
 * joint without <limit>, a joint out of range). */
double      mpb_world_joint_max_velocity(const mpb_world *w, int joint);
/* One byte per joint, nonzero where the joint wraps; owned by the world. */
const unsigned char *mpb_world_joint_wraps(const mpb_world *w);

/*
 * 1 if the robot at q (num_joints values) touches an obstacle (or itself,
 * where the format models that), 0 if free. Touching counts: in collision
 * with the scene exactly when mpb_world_clearance() <= 0 (self-collision
 * has no part in the clearance). A non-finite q counts as in
 * collision; NULL w or q gives MPB_EINVAL (nonzero, so still "not free").
 */
int mpb_world_in_collision(mpb_world *w, const double *q);

/*
 * Smallest distance (m) from the robot's moving links (and what they
 * carry) to any obstacle of the scene; 0 or less when
 * in collision, +INFINITY in an empty scene, NaN for a non-finite q (or NULL
 * w or q).
 */
double mpb_world_clearance(mpb_world *w, const double *q);

/*
 * The end effector's position at q, in the robot's frame (m): the planar
 * arm's tip (z = 0); for a URDF group, the last link of the chain, followed
 * down through fixed joints while there is exactly one (the PR2's
 * r_wrist_roll_link leads to r_gripper_tool_frame). MPB_OK, or MPB_EINVAL
 * for NULL arguments or a non-finite q.
 */
int mpb_world_ee_position(mpb_world *w, const double *q, double xyz[3]);

/*
 * The allowed-collision matrix of a "urdf" world: the pairs of links that
 * may touch, in the robot's link order (robot.h: depth-first from the
 * root) of link1, then of link2, link1 before link2. From an SRDF: its
 * <disable_collisions> pairs with their reasons as written, and every
 * adjacent pair it leaves out ("Adjacent"). Generated (no SRDF), as
 * MoveIt's setup assistant does, each pair for the first reason that holds:
 *   "Adjacent"  parent and child links, across any joint, fixed ones
 *               included; a link without collision shapes joins its
 *               neighbours (both links of a pair have shapes);
 *   "Default"   in collision at the default state, MoveIt's: every joint
 *               of the group at 0 when 0 is within its limits, else at the
 *               middle of them;
 *   "Always"    in collision in more than 95 % of a batch of 200 random
 *               states, batches drawn until one adds no pair;
 *   "Never"     in collision in none of MPB_WORLD_ACM_SAMPLES random
 *               states (uniform within the limits; the generator of
 *               robot.h, seeded with MPB_WORLD_ACM_SEED, so the same robot
 *               gives the same matrix on every run). Two fixed links are
 *               "Never" unless they touch at the default state.
 * Only the group's joints move; the others hold their values (robot.h).
 * All the states come from one generator seeded with MPB_WORLD_ACM_SEED.
 */
#define MPB_WORLD_ACM_SAMPLES 10000   /* the setup assistant's default */
#define MPB_WORLD_ACM_SEED    1

typedef struct mpb_world_acm_pair {
    const char *link1, *link2;  /* owned by the world */
    const char *reason;         /* "Adjacent", "Default", "Always",
                                   "Never", or the SRDF's reason
                                   attribute ("" if none) */
    int         from_srdf;      /* 1 if the matrix came from an SRDF */
} mpb_world_acm_pair;

/* How many pairs the matrix allows; 0 for a world without one (planar). */
int mpb_world_num_allowed_pairs(const mpb_world *w);

/* Pair i (0 .. count-1) into *out: MPB_OK, or MPB_EINVAL out of range. */
int mpb_world_allowed_pair(const mpb_world *w, int i,
                           mpb_world_acm_pair *out);

/* What mpb_world_contact() found the robot touching. */
#define MPB_CONTACT_SCENE 1  /* a scene object (or, in a world that cannot
                                tell, something) */
#define MPB_CONTACT_SELF  2  /* its own body: two of its links the
                                allowed-collision matrix does not allow */

/*
 * Is the robot at q in collision, and with what? MPB_CONTACT_SCENE or
 * MPB_CONTACT_SELF (a scene object is looked for first) with one phrase
 * in what (may be NULL) naming the bodies in contact ("self-collision
 * between r_gripper_palm_link and torso_lift_link", "r_forearm_link
 * touches scene object table"); 0 if free; negative on error (MPB_EINVAL
 * for NULL w or q, a non-finite q). Worlds that cannot name bodies
 * (planar) answer as mpb_world_in_collision() with what empty.
 */
int mpb_world_contact(mpb_world *w, const double *q, char *what, size_t len);

/*
 * How deep the robot at q goes into what it collides with, m
 * (src/geometry/collision_depth.cpp): *lower, the deepest robot point
 * found inside an obstacle (or another link), its distance to that
 * body's surface; *upper, the penetration depth of the colliding shapes'
 * convex hulls as found. lower <= the true depth <= upper; both 0 when q
 * is free. MPB_OK; MPB_EUNSUPPORTED for a world that cannot say (planar);
 * MPB_EINVAL for NULL arguments or a non-finite q; another negative code
 * on error.
 */
int mpb_world_depth(mpb_world *w, const double *q, double *lower,
                    double *upper);

struct mpb_goal;

/*
 * Is the robot at q inside the pose-region goal g (verify.h)? 1 if so, 0 if
 * not, with one line in detail (may be NULL) saying how far; MPB_EUNSUPPORTED
 * where the world cannot check pose regions (planar); another negative code
 * when g does not fit the robot (an unknown link). A non-finite q is outside.
 */
int mpb_world_goal_contains(mpb_world *w, const struct mpb_goal *g,
                            const double *q, char *detail, size_t len);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_WORLD_H */
