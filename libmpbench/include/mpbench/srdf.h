/*
 * srdf.h - a robot's SRDF (MoveIt's Semantic Robot Description Format),
 * read against its URDF: the planning groups, the named states of groups,
 * the virtual and passive joints, the end effectors. (Its
 * <disable_collisions> pairs are the world's business, world.h; here,
 * only those naming links the URDF lacks: mpb_srdf_skipped_pairs().)
 * docs/robot-model.md says what mpbench makes of each element.
 *
 * Groups. A group's joints follow MoveIt's rules: <joint name=> adds that
 * joint; <link name=> adds the link's parent joint (for the URDF's root
 * link, the virtual joints attached to it); <chain base_link= tip_link=>
 * adds the joints on the path between the two links (from the tip up to
 * the base, not the base's own parent joint; when the base is not above
 * the tip, both sides up to the link they share); <group name=> adds a
 * subgroup's joints. A group's ACTIVE joints are the ones a planner moves:
 * its revolute, continuous and prismatic joints that are not mimic joints
 * (robot.h), not passive (<passive_joint>) and not virtual. mpbench plans
 * one serial chain (robot.h), so a group it plans must have active joints
 * each below the one before: mpb_srdf_group_check().
 *
 * Virtual joints attach the URDF's root link to a frame outside the
 * robot. mpbench holds every one, fixed, floating or planar, at the
 * identity: the root link's frame is the world's. Passive joints are never
 * planned.
 *
 * Ownership. A handle owns every string and array it hands out; they live
 * until mpb_srdf_close(). Lines count from 1 in the SRDF's text.
 */
#ifndef MPBENCH_SRDF_H
#define MPBENCH_SRDF_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mpb_srdf mpb_srdf;

/*
 * Read srdf_text against the robot of urdf_text (both NUL-terminated).
 * On success *out is a new handle, freed with mpb_srdf_close(). On failure
 * *out is NULL and err (if not NULL) holds one line: "urdf: ..." for a
 * fault of the URDF (as robot.h words them), else "srdf line 12: ...":
 *   MPB_EPARSE  not XML or no <robot> root (with the line and column); an
 *               element without an attribute it needs; a group defined
 *               twice, a subgroup that is no group, a group that contains
 *               itself through subgroups ("a -> b -> a"), a group with no
 *               joints; a joint, link or group name the URDF or SRDF does
 *               not have (in a group, a group state, a passive joint, an
 *               end effector); a group state value that
 *               is not a number, or for a joint not in its group; a
 *               virtual joint of another type than fixed, floating or
 *               planar, or not attached to the URDF's root link;
 *   MPB_EINVAL  NULL text or out;  MPB_ENOMEM.
 */
int mpb_srdf_open(const char *urdf_text, const char *srdf_text,
                  mpb_srdf **out, char *err, size_t errlen);

/* Release the handle; NULL does nothing. */
void mpb_srdf_close(mpb_srdf *s);

/* The SRDF's <robot name>, "" if none; owned by s. */
const char *mpb_srdf_robot_name(const mpb_srdf *s);

/*
 * <disable_collisions> pairs that name a link the URDF lacks are skipped,
 * as MoveIt does (it warns and goes on): the load does not fail, and the
 * world (world.h) leaves them out of its matrix. How many were skipped,
 * and one line saying so, for the caller to print as a warning with the
 * SRDF's file name: "2 of 450 disable_collisions pairs name links the
 * URDF lacks and are skipped, as MoveIt does: line 163 (collision_head_link,
 * head: no link 'collision_head_link'), line 170 (...) and N more; the
 * names: collision_head_link, sonar_ring, ...", the first three with their
 * lines, then every name the URDF lacks, once; NULL when none was. Owned
 * by s.
 */
int         mpb_srdf_num_skipped_pairs(const mpb_srdf *s);
const char *mpb_srdf_skipped_pairs(const mpb_srdf *s);

/* ---- groups ------------------------------------------------------------- */

typedef struct mpb_srdf_group {
    const char        *name;
    int                line;
    int                num_joints;
    const char *const *joints;  /* every joint, the virtual ones first, then
                                   in the URDF's depth-first order (robot.h) */
    int                num_active;
    const char *const *active;  /* its active joints, in that order: base
                                   first when they form a chain */
    int                num_subgroups;
    const char *const *subgroups; /* its <group name=> elements, in order */
    const char        *chain_base, *chain_tip; /* its first <chain>, or NULL */
} mpb_srdf_group;

int mpb_srdf_num_groups(const mpb_srdf *s);
/* Group i in file order, owned by s; NULL out of range. */
const mpb_srdf_group *mpb_srdf_get_group(const mpb_srdf *s, int i);
/* Index of the group of that name, or MPB_ENOTFOUND. */
int mpb_srdf_group_index(const mpb_srdf *s, const char *name);

/*
 * Can mpbench plan group i? MPB_OK when its active joints form one serial
 * chain, each below the one before (then `active` is the planning group of
 * robot.h, base first). Else MPB_EUNSUPPORTED with one line in err saying
 * why: the group names a passive, mimic or virtual joint with a <joint>
 * element (such a joint is never planned), has no active joint, or its
 * active joints branch ("... is not a serial chain: 'left_s0' and
 * 'right_s0' are on different branches"). MPB_EINVAL for a bad i.
 */
int mpb_srdf_group_check(const mpb_srdf *s, int i, char *err, size_t errlen);

/* ---- group states -------------------------------------------------------- */

typedef struct mpb_srdf_state {
    const char        *name, *group;
    int                line;
    int                num_values;
    const char *const *joints;  /* as written, in file order */
    const double      *values;
} mpb_srdf_state;

int mpb_srdf_num_states(const mpb_srdf *s);
/* State i in file order, owned by s; NULL out of range. */
const mpb_srdf_state *mpb_srdf_get_state(const mpb_srdf *s, int i);

/*
 * The values of group state `name` of group i for the group's active
 * joints, into q (num_active values, in the order of `active`). MPB_OK;
 * MPB_ENOTFOUND when no state has that name ("group 'panda_arm' has no
 * group_state 'redy' (it has ready, extended)"); MPB_EINVAL when the
 * states of that name are for other groups ("group_state 'open' is for
 * group 'hand', not 'panda_arm'"), when the state leaves an active joint
 * out ("group_state 'half' (srdf line 40) has no value for joint 'j3'"),
 * or for a NULL argument or bad i. One line in err on failure.
 */
int mpb_srdf_state_values(const mpb_srdf *s, int i, const char *name,
                          double *q, char *err, size_t errlen);

/* ---- virtual and passive joints, end effectors ------------------------- */

typedef struct mpb_srdf_virtual_joint {
    const char *name;
    const char *type;           /* "fixed", "floating" or "planar" */
    const char *parent_frame;   /* as written */
    const char *child_link;     /* the URDF's root link */
    int         line;
} mpb_srdf_virtual_joint;

int mpb_srdf_num_virtual_joints(const mpb_srdf *s);
/* Virtual joint i in file order, owned by s; NULL out of range. */
const mpb_srdf_virtual_joint *mpb_srdf_get_virtual_joint(const mpb_srdf *s,
                                                         int i);

/* Passive joint i's name (owned by s) and line; NULL out of range. */
int         mpb_srdf_num_passive_joints(const mpb_srdf *s);
const char *mpb_srdf_passive_joint(const mpb_srdf *s, int i, int *line);
/* The line of the <passive_joint> naming joint, or 0 when it is not
 * passive. */
int         mpb_srdf_is_passive(const mpb_srdf *s, const char *joint);

typedef struct mpb_srdf_end_effector {
    const char *name;
    const char *group;          /* its links and joints */
    const char *parent_link;    /* what it is attached to */
    const char *parent_group;   /* NULL if not given */
    int         line;
} mpb_srdf_end_effector;

int mpb_srdf_num_end_effectors(const mpb_srdf *s);
const mpb_srdf_end_effector *mpb_srdf_get_end_effector(const mpb_srdf *s,
                                                       int i);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_SRDF_H */
