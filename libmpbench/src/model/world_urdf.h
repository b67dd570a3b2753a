/*
 * world_urdf.h - the "urdf" world's state, shared by the files that make
 * it: world_urdf.c (the provider: the collision world's bodies, opening,
 * the queries), mesh_search.c (where meshes are looked for), acm.c (the
 * allowed-collision matrix) and wrist_hints.c (the wrist tables' hints);
 * not part of the API. The ids of the collision world's bodies are
 * written at the top of world_urdf.c.
 */
#ifndef MPB_WORLD_URDF_H
#define MPB_WORLD_URDF_H

#include <stddef.h>

#include "mpbench/collision.h"
#include "mpbench/robot.h"
#include "mpbench/scene.h"
#include "mpbench/srdf.h"
#include "geometry/wrist_table.h"

typedef struct urdf_world {
    mpb_robot     *robot;
    mpb_scene     *scene;
    mpb_collision *coll;
    mpb_pose      *poses;        /* every link, robot frame */
    int            num_links;
    int           *moving;       /* links with shapes that move */
    int            num_moving;
    int           *attached;     /* scene objects attached to links */
    int           *attached_link;
    int            num_attached;
    const mpb_mesh **meshes;     /* the robot's mesh shapes, shared by
                                    every world (mesh_cache.h) */
    int            num_meshes, cap_meshes;
    int            ee_link;      /* see mpb_world_ee_position() */
    const char   **allowed;      /* num_links^2: why link a may touch b,
                                    NULL where it may not */
    int           *pairs;        /* the allowed pairs a < b, 2 a pair, in
                                    order of a then b */
    int            num_pairs;
    mpb_srdf      *srdf;         /* the SRDF, or NULL; owns its reasons */
    int            from_srdf;    /* 1 if the ACM came from an SRDF */
    const char    *robot_dir;    /* the URDF's folder, or NULL */
    char          *robot_dir_copy; /* owned: for a rebuild after open */
    int            acm_stale;    /* generated ACM: not built for the values
                                    held now; built before the next check */
    int            acm_in_coll;  /* coll holds a built ACM's pairs */
    struct urdf_wrist {          /* self pairs a wrist table may prove
                                    apart (wrist_table.h) */
        int near, far, joint[2];
        const mpb__wrist_table *table;  /* the cache's */
    }             *wrist;
    int            num_wrist, cap_wrist;
    struct mpb__sweep *sweep;    /* certified verification's bounds
                                    (collision_internal.h), or NULL */
} urdf_world;

/* Is link l a body of the collision world (has it shapes)? */
static inline int has_body(const urdf_world *u, int l)
{
    return l >= 0 && mpb_robot_get_link(u->robot, l)->num_collisions > 0;
}

/* Why links a and b may touch (NULL: they may not), as the matrix holds it. */
static inline const char **acm_at(urdf_world *u, int a, int b)
{
    return &u->allowed[(size_t)a * (size_t)u->num_links + (size_t)b];
}

/* ---- world_urdf.c ------------------------------------------------------ */

/* Place every moving body for configuration q. */
int  mpb__urdf_place(urdf_world *u, const double *q);

/*
 * MoveIt's default state: each joint at 0 when 0 is within its limits,
 * else at the middle of them (RobotState::setToDefaultValues()).
 */
void mpb__urdf_default_state(const mpb_robot *r, double *q);

/* ---- mesh_search.c ----------------------------------------------------- */

/* Where meshes are looked for: the folders of MPB_MESH_PATH, then those
 * of ROS_PACKAGE_PATH, as many as they hold, then the URDF's folder when
 * the caller gave it. */
typedef struct mpb__mesh_search {
    char        *buf[2];      /* copies of the two variables, split */
    const char **dirs;
    int          num_dirs;
    int          from_env[2]; /* how many came from each */
    const char  *robot_dir;   /* the URDF's folder, last; or NULL */
} mpb__mesh_search;

/* The folders, from the environment now and robot_dir (may be NULL);
 * MPB_OK or MPB_ENOMEM. Free with mpb__mesh_search_free() either way. */
int  mpb__mesh_search_init(mpb__mesh_search *m, const char *robot_dir);
void mpb__mesh_search_free(mpb__mesh_search *m);

/* After a mesh was not found: the variables and the folders tried, the
 * first few of each, into err after what mpb__mesh_create_from_uri() said. */
void mpb__mesh_not_found(const mpb__mesh_search *m, char *err,
                         size_t errlen);

/* ---- acm.c ------------------------------------------------------------- */

/*
 * Build the matrix (from the SRDF, or generated at q0), list its pairs,
 * and let the collision world skip them, and every pair of fixed links;
 * then the wrist tables of the pairs left. One line in err on failure.
 */
int  mpb__urdf_build_acm(urdf_world *u, const double *q0, char *err,
                         size_t errlen);

/* ---- wrist_hints.c ----------------------------------------------------- */

/*
 * The self pairs a wrist table may prove apart, with their tables, into
 * u->wrist; after the matrix, which decides the pairs.
 */
int  mpb__urdf_find_wrists(urdf_world *u);

/* After mpb__urdf_place(): the wrist pairs their tables prove apart at
 * q, as hints for the next self check (they lapse with the next placing). */
void mpb__urdf_hint_wrists(urdf_world *u, const double *q);

#endif /* MPB_WORLD_URDF_H */
