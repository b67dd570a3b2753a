/*
 * srdf_xml.h - private: a robot's SRDF (MoveIt's Semantic Robot Description
 * Format) as plain C, filled by the C++ bridge srdf_tinyxml.cpp (TinyXML,
 * the reader urdfdom uses) and checked against the URDF by srdf.c. Every
 * pointer here is malloc'd; mpb__srdf_clear() frees them all. Lines count
 * from 1, in the SRDF's own text.
 */
#ifndef MPB_SRDF_XML_H
#define MPB_SRDF_XML_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mpb__srdf_pair {
    char *link1, *link2;
    char *reason;               /* as written; "" if absent */
    int   line;                 /* of the element, from 1 */
} mpb__srdf_pair;

/* What one child element of a <group> names. */
typedef enum mpb__srdf_elem_kind {
    MPB__SRDF_JOINT = 0,        /* <joint name=>: the joint */
    MPB__SRDF_LINK = 1,         /* <link name=>: the link's parent joint */
    MPB__SRDF_CHAIN = 2,        /* <chain base_link= tip_link=>: the joints
                                   of the path between the two links */
    MPB__SRDF_GROUP = 3         /* <group name=>: a subgroup's joints */
} mpb__srdf_elem_kind;

typedef struct mpb__srdf_elem {
    mpb__srdf_elem_kind kind;
    char *name;                 /* CHAIN: the base link */
    char *tip;                  /* CHAIN: the tip link; else NULL */
    int   line;
} mpb__srdf_elem;

typedef struct mpb__srdf_group {
    char           *name;
    int             line;
    int             num_elems;
    mpb__srdf_elem *elems;      /* in file order */
} mpb__srdf_group;

typedef struct mpb__srdf_value {
    char  *joint;
    double value;               /* finite */
    int    line;
} mpb__srdf_value;

typedef struct mpb__srdf_state {
    char            *name, *group;
    int              line;
    int              num_values;
    mpb__srdf_value *values;    /* in file order */
} mpb__srdf_state;

typedef struct mpb__srdf_vjoint {
    char *name;
    char *type;                 /* "fixed", "floating" or "planar" */
    char *parent_frame, *child_link;
    int   line;
} mpb__srdf_vjoint;

typedef struct mpb__srdf_passive {
    char *name;
    int   line;
} mpb__srdf_passive;

typedef struct mpb__srdf_eef {
    char *name, *group, *parent_link;
    char *parent_group;         /* NULL if not given */
    int   line;
} mpb__srdf_eef;

typedef struct mpb__srdf {
    char              *robot_name;  /* <robot name>, "" if absent */
    int                num_pairs;
    mpb__srdf_pair    *pairs;       /* each list in file order */
    int                num_groups;
    mpb__srdf_group   *groups;
    int                num_states;
    mpb__srdf_state   *states;
    int                num_vjoints;
    mpb__srdf_vjoint  *vjoints;
    int                num_passive;
    mpb__srdf_passive *passive;
    int                num_eefs;
    mpb__srdf_eef     *eefs;
} mpb__srdf;

/*
 * Parse SRDF text into *s (zeroed first). The root element must be
 * <robot>; under it <group>, <group_state>, <virtual_joint>,
 * <passive_joint>, <end_effector> and <disable_collisions> are read, each
 * with the attributes it needs. Inside a <group> the <joint>, <link>,
 * <chain> and <group> elements count, as in MoveIt; others are skipped.
 * Other elements under <robot> are skipped too. Names are checked here
 * only where the SRDF alone can tell: a group defined twice, a subgroup
 * that no group has, a subgroup cycle, a state named twice for a group,
 * a virtual joint of a type other than fixed, floating or planar.
 * MPB_OK; MPB_EPARSE with one line in err naming the line ("line 7:
 * disable_collisions has no link2", "line 12, column 3: not well-formed
 * XML: ..."); MPB_ENOMEM. On failure *s holds nothing to free.
 */
int mpb__srdf_parse(const char *text, mpb__srdf *s, char *err, size_t errlen);

/* mpb__srdf_parse() through the process's cache of parsed texts
 * (parse_cache.h): the same results and errors, the text parsed once. */
int mpb__srdf_parse_cached(const char *text, mpb__srdf *s, char *err,
                           size_t errlen);

/* Free everything *s holds and zero it; NULL does nothing. */
void mpb__srdf_clear(mpb__srdf *s);

/* Index of the group of that name, or -1. */
int mpb__srdf_find_group(const mpb__srdf *s, const char *name);

struct mpb_srdf;            /* mpbench/srdf.h */
struct mpb_robot;           /* mpbench/robot.h */

/*
 * Check *raw against the URDF the robot was loaded from (srdf.c) and make
 * the handle of mpbench/srdf.h of it, which takes everything *raw holds
 * (*raw is zeroed, on failure too). The handle borrows the robot's names:
 * the robot must outlive it. MPB_OK; MPB_EPARSE with one line in err,
 * "line 12: ..." (no "srdf" prefix); MPB_ENOMEM.
 */
int mpb__srdf_bind_robot(mpb__srdf *raw, const struct mpb_robot *r,
                         struct mpb_srdf **out, char *err, size_t errlen);

/* The parsed SRDF a handle was made of; owned by it. */
const mpb__srdf *mpb__srdf_raw(const struct mpb_srdf *s);

#ifdef __cplusplus
}
#endif

#endif /* MPB_SRDF_XML_H */
