/*
 * world_provider.h - private: the mpb_world handle and the table of
 * functions behind which each robot/scene format lives. One provider a file
 * (world_planar.c, later world_fcl.cpp); world.c picks one by format names
 * and forwards every call to it.
 *
 * Adding a provider: write a const mpb__world_provider filled with
 * designated initialisers, declare it below, list it in world.c's table.
 */
#ifndef MPB_WORLD_PROVIDER_H
#define MPB_WORLD_PROVIDER_H

#include <stdarg.h>
#include <stddef.h>

#include "mpbench/pose.h"
#include "mpbench/verify.h"
#include "mpbench/world.h"

typedef struct mpb__world_provider {
    const char *robot_format;   /* "planar", "urdf" */
    const char *scene_format;   /* the scene format it reads with it */

    /*
     * Parse the texts; declare the joints with mpb__world_add_joint() in
     * order and set w->impl. On failure return MPB_EPARSE / MPB_ENOMEM with
     * one line in err ("robot line 3: ..."); world.c then calls close on
     * whatever w->impl holds (possibly NULL) and frees w.
     */
    int    (*open)(mpb_world *w, const char *robot_text,
                   const char *scene_text, const char *const *joints,
                   int num_joints, char *err, size_t errlen);
    void   (*close)(void *impl);                 /* impl may be NULL */

    /* q has w->num_joints finite values (world.c checks). */
    int    (*in_collision)(void *impl, const double *q);
    double (*clearance)(void *impl, const double *q);

    /*
     * Optional: 1 if the robot at q is inside the pose-region goal g, 0 if
     * not (with one line in detail), negative if g cannot be checked (an
     * unknown link, say; detail says why). NULL: pose regions unsupported.
     */
    int    (*goal_region)(void *impl, const mpb_goal *g, const double *q,
                          char *detail, size_t len);

    /* Where the end effector is at q, in the robot's frame (m). */
    void   (*ee_position)(void *impl, const double *q, double xyz[3]);

    /*
     * Optional: where the end effector is at q = a + (n / steps) d, for
     * n = first..first + count - 1, into xyz (3 count values), as
     * ee_position would say
     * to within rounding; d is the joint-space step from a (continuous
     * joints the short way). Returns MPB_OK or a negative code (the
     * caller then asks ee_position point by point). NULL: no such path.
     */
    int    (*ee_sweep)(void *impl, const double *a, const double *d,
                       int steps, int first, int count, double *xyz);

    /*
     * Optional: 1 if the robot at q is in collision, with a phrase in what
     * naming the bodies in contact ("self-collision between a and b"), 0
     * if free, negative on error. NULL: no names to give.
     */
    int    (*contact)(void *impl, const double *q, char *what, size_t len);

    /* Optional: joints outside the group (mpb_world_hold()); NULL: none. */
    int    (*hold)(void *impl, const char *const *joints, const double *values,
                   int n, char *err, size_t errlen);
    int    (*held)(void *impl, const char *joint, double *value, double *lo,
                   double *hi);

    /* Optional: the allowed-collision matrix (world.h); NULL: none. */
    int    (*num_allowed)(void *impl);
    int    (*allowed_pair)(void *impl, int i, mpb_world_acm_pair *out);

    /*
     * Optional, for certified verification (verify/certify.c): along the
     * straight joint-space motion q + s d (continuous joints unwrapped),
     * the largest ds <= want such that no pair the collision check tests
     * can touch while s grows by ds from here (q itself), each distance
     * taken less margin (m): a proof, from distance lower bounds and an
     * upper bound on how fast any point of the robot moves per unit s
     * (docs/verification.md). 0 when some pair is within margin. MPB_OK;
     * a negative code if it cannot say (the caller then samples). NULL:
     * the world samples.
     *
     * moved chains the calls: how far (units of s) the robot went from
     * the last call's q along the last call's d, to reach q; negative if
     * q is not so reached (a new path; anything changed in the world
     * since). A world may then keep, pair by pair, a lower bound on the
     * distance lowered by what the motion may have closed, and measure
     * again only the pairs whose bound no longer covers the step.
     */
    int    (*safe_step)(void *impl, const double *q, const double *d,
                        double margin, double want, double moved,
                        double *step);

    /* Optional: bounds on how deep the robot at q collides
     * (mpb_world_depth()); *lower exact only where above floor (else at
     * most floor), mpb__world_depth_above(). NULL: the world cannot say. */
    int    (*depth)(void *impl, const double *q, double floor,
                    double *lower, double *upper);
} mpb__world_provider;

struct mpb_world {
    const mpb__world_provider *provider;
    const char    *robot_dir;     /* while open runs: the folder of the
                                     robot's file, or NULL (the caller's) */
    void          *impl;          /* the provider's state */
    int            num_joints;
    int            cap;
    char         **joint_names;
    double        *lo, *hi;
    unsigned char *wraps;         /* nonzero where the joint is continuous */
    double        *max_velocity;  /* URDF <limit velocity>, rad/s or m/s;
                                     0 where none is given */
    int            verification;  /* mpb_verification: 0 certified */
};

/*
 * Append a joint (name is copied, namelen bytes). Continuous joints get the
 * limits -pi .. pi whatever lo and hi say; max_velocity not finite and
 * above 0 is kept as 0 (none). MPB_OK or MPB_ENOMEM.
 */
/*
 * mpb_world_depth(), for the worst of several configurations: *lower is
 * exact where it is above floor (>= 0), else some value at most floor,
 * so that the work that cannot beat floor is spared; *upper is exact.
 */
int mpb__world_depth_above(mpb_world *w, const double *q, double floor,
                           double *lower, double *upper);

int mpb__world_add_joint(mpb_world *w, const char *name, size_t namelen,
                         double lo, double hi, int continuous,
                         double max_velocity);

/*
 * URDF only, for world_urdf.c's safe_step: the step of certified
 * verification (world_provider.h) with the robot placed at poses (every
 * link, robot frame) and moving by d per unit s; the bodies are those of
 * coll as world_urdf.c numbers them (movable id = link, or num_links + k
 * for scene object k attached to link attached_link[i], k = attached[i]).
 * st, moved: as mpb__collision_sweep_step() (collision_internal.h).
 * world_sweep.c.
 */
struct mpb_robot;
struct mpb_collision;
struct mpb__sweep;
int mpb__urdf_safe_step(const struct mpb_robot *r, struct mpb_collision *coll,
                        const mpb_pose *poses, const int *attached,
                        const int *attached_link, int num_attached,
                        struct mpb__sweep *st, double moved,
                        const double *d, double margin, double want,
                        double *step);

/*
 * For tests (test_certify_rates.c): the rates mpb__urdf_safe_step() takes
 * at q for the motion d over a horizon of h units of s: rate[id], and
 * pair[a * n + b] the rate at which bodies a and b may approach (ids
 * below n; NaN where there is no body). MPB_OK; MPB_EINVAL for a world
 * not "urdf" or bad arguments.
 */
int mpb__urdf_rates(mpb_world *w, const double *q, const double *d, double h,
                    double *rate, double *pair, int n);

/* The providers. */
/* robot_fk.c, for world_urdf.c's ee_sweep. */
/*
 * The origin of `link` in the robot's frame at q = a + (n / steps) d for
 * n = first..first + count - 1, into xyz (3 count values): forward kinematics of that
 * link alone, position only, each revolute joint's cosine and sine
 * carried from one point to the next by a rotation (re-taken from cos()
 * and sin() every few points). Equal to mpb_robot_link_pose() at the
 * same points within about 1e-15 m. Returns MPB_OK, MPB_EINVAL, or
 * MPB_EUNSUPPORTED for a path of more than 64 links.
 */
int mpb__robot_link_sweep(const struct mpb_robot *r, int link, const double *a,
                          const double *d, int steps, int first, int count,
                          double *xyz);

extern const mpb__world_provider mpb__world_planar;
extern const mpb__world_provider mpb__world_urdf;

/*
 * Planar only, for tests: the positions of the joints and the tip of the
 * planar arm at q, xy[2 * i], xy[2 * i + 1] for i = 0 .. num_joints (the
 * base first, the tip last). MPB_EINVAL if w is not a planar world.
 */
int mpb__planar_points(const mpb_world *w, const double *q, double *xy);

/*
 * URDF only, for tests: the collision world behind w (owned by w), where
 * the robot stands after the last query on w; NULL if w is not a urdf
 * world.
 */
struct mpb_collision;
struct mpb_collision *mpb__urdf_collision(mpb_world *w);

/*
 * Planar only, for bodies.c: the arm and its obstacles as parsed. length
 * (n values) is owned by w. Obstacles are numbered circles first, then
 * boxes. MPB_EINVAL if w is not a planar world.
 */
typedef struct mpb__planar_model {
    int           n;             /* joints = links */
    double        base[2];
    double        radius;        /* of every link's capsule */
    const double *length;
    int           num_circles, num_boxes;
} mpb__planar_model;
int mpb__planar_get_model(const mpb_world *w, mpb__planar_model *out);
/* Obstacle k: a circle's cx cy r (v[3] = 0) or a box's xmin ymin xmax ymax. */
int mpb__planar_obstacle(const mpb_world *w, int k, double v[4]);
/* The first link and obstacle that touch at q (1), or 0 if q is free; the
 * same tests, in the same order, as the world's own collision check. */
int mpb__planar_contact(mpb_world *w, const double *q, int *link,
                        int *obstacle);

/*
 * URDF only, for bodies.c: the parts of the world (owned by it). The
 * collision world's ids are those written at the top of world_urdf.c:
 * movable = link index (the links that do not move are self-only bodies),
 * or num_links + k for scene object k when attached; static = k for scene
 * object k. meshes are the robot's mesh shapes in the order of
 * mpb_robot_get_collision(). MPB_EINVAL if w is not a urdf world. The
 * parts are valid until a mpb_world_hold() that changes a value of a
 * robot without an SRDF (its matrix, and so its collision world, are
 * made again): hold first.
 */
struct mpb_robot;
struct mpb_scene;
struct mpb_mesh;
typedef struct mpb__urdf_model {
    struct mpb_robot     *robot;
    struct mpb_scene     *scene;
    struct mpb_collision *coll;
    const struct mpb_mesh **meshes;
    int                   num_meshes;
} mpb__urdf_model;
int mpb__urdf_get_model(mpb_world *w, mpb__urdf_model *out);

/*
 * URDF only, for tests: the self pairs a wrist table proves apart where
 * it can (wrist_table.h): how many (0 if w is not a urdf world), and the
 * i-th's links, chain joints (joint[1] -1 for one) and table. MPB_EINVAL
 * for a bad w or i.
 */
struct mpb__wrist_table;
int mpb__urdf_num_wrists(mpb_world *w);
int mpb__urdf_wrist(mpb_world *w, int i, int *near, int *far, int joint[2],
                    const struct mpb__wrist_table **table);

#endif /* MPB_WORLD_PROVIDER_H */
