/*
 * wrist_table.h - private to libmpbench and its tests: tables over one or
 * two joints that prove a self pair of a robot apart, so that the self
 * check can skip it before FCL.
 *
 * A pair of links, one the ancestor of the other with one or two
 * revolute (or continuous) joints between them, has a relative pose that
 * depends on those joints alone: the Panda's link5 against link7 and the
 * hand (joints 6 and 7), nearly half of its mesh-mesh narrow phases. Over
 * a cell of the joints' box, centre c, half-widths h1 h2, every point of
 * the far link moves relative to the near one by at most R1 h1 + R2 h2
 * (wrist_lipschitz() in wrist_table.c says why); if FCL's distance of the
 * pair at c exceeds that plus a margin (1e-4 m), the pair is apart over
 * the whole cell. A table is a tree of such cells, split in halves where
 * they cannot be proved until their bound is below a minimum; the cells
 * left unproved, and values outside the joints' range, go to FCL.
 *
 * Tables are made once per process for what determines them (the
 * joints, the fixed transforms between, both links' shapes, mesh contents
 * included, and the build's parameters: the key) and shared by every
 * world, read-only: thread-safe. They are read from the cache on disk
 * (wrist_cache.h) when a process has built them before, and written
 * there when built.
 */
#ifndef MPB_WRIST_TABLE_H
#define MPB_WRIST_TABLE_H

#include <stddef.h>

#include "mpbench/collision.h"
#include "mpbench/robot.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mpb__wrist_table mpb__wrist_table;

/* One side of the pair: its shapes, as the collision world holds them. */
typedef struct mpb__wrist_side {
    int                 num_shapes;
    const mpb_geometry *geoms;
    const mpb_pose     *offsets;    /* in the link's frame */
} mpb__wrist_side;

/*
 * The far link's pose in the near link's frame is
 *   fixed[0] * rot(axis[0], q0) * fixed[1] * rot(axis[1], q1) * fixed[2]
 * with one joint: fixed[0] * rot(axis[0], q0) * fixed[1] (axis[1],
 * fixed[2] unused). lo, hi: the joints' range (a continuous joint's one
 * turn, -pi .. pi).
 */
typedef struct mpb__wrist_spec {
    int             num_joints;     /* 1 or 2 */
    mpb_pose        fixed[3];
    double          axis[2][3];     /* unit */
    double          lo[2], hi[2];
    mpb__wrist_side side[2];        /* near, far */
} mpb__wrist_spec;

/*
 * Does the pair (near, far) of r qualify, and how does it move: 1 with
 * *joints (the chain indices of its one or two joints, joints[1] -1 for
 * one) and the kinematic part of *spec (not its sides) filled, when
 * `near` is an ancestor of `far` and the links between, `far` included,
 * hang on fixed joints and one or two active revolute or continuous
 * joints (no prismatic, mimic, floating, planar or held ones); 0 if not.
 * poses: every link's pose at any one state (mpb_robot_fk()).
 */
int mpb__wrist_path(const mpb_robot *r, const mpb_pose *poses, int near,
                    int far, int joints[2], mpb__wrist_spec *spec);

/*
 * Is a table for spec cheap enough to build when a world opens? Its cost
 * is a few thousand FCL distances between the two sides, each dearer the
 * more triangles they have: the product of their triangle counts (a
 * primitive counts as 12) must be at most MPB__WRIST_MAX_TRIANGLE_PAIRS.
 * The Panda's pairs are 6k-60k; the UR5's, with its Robotiq gripper,
 * 0.7M-30M, whose tables took 36 s.
 */
#define MPB__WRIST_MAX_TRIANGLE_PAIRS 250000.0
int mpb__wrist_affordable(const mpb__wrist_spec *spec);

/*
 * The table for spec, from the process-wide cache, else from the disk
 * cache, else built now (and stored in both).
 * A build stops refining after MPB__WRIST_MAX_DISTANCES FCL distances
 * (the Panda's largest takes 5,993, 0.4 s), leaving the cells it has not
 * reached to FCL: slower checks, never other verdicts. A count, not a
 * time, so that a table is the same on every machine (and under
 * valgrind).
 * MPB_OK with *out, held by the cache for the life of the process;
 * MPB_ENOMEM; MPB_EERROR if FCL failed.
 */
int mpb__wrist_table_get(const mpb__wrist_spec *spec,
                         const mpb__wrist_table **out);

/* 1 if the table proves the pair apart at joint values (v0, v1; v1 is
 * ignored for one joint), 0 if FCL must decide. */
int mpb__wrist_table_apart(const mpb__wrist_table *t, double v0, double v1);

/* What a table holds, for tests and measurements. */
typedef struct mpb__wrist_stats {
    int    nodes;           /* cells of the tree, leaves and splits */
    int    apart_leaves;    /* leaves proved apart */
    int    open_leaves;     /* leaves left to FCL */
    int    distances;       /* FCL distances the build took */
    int    grid_bytes;      /* the look-up grid, 0 if none */
    double build_s;         /* its CPU time (s) */
    double lipschitz[2];    /* R1, R2 (m per rad) */
    int    cut;             /* 1 if MPB__WRIST_MAX_DISTANCES stopped it */
    int    cached;          /* 1 if read from the disk cache (the rest
                               as the build that wrote it measured) */
} mpb__wrist_stats;
void mpb__wrist_table_stats(const mpb__wrist_table *t, mpb__wrist_stats *out);

/*
 * Build parameters, for tests and measurements: the least bound a cell
 * is split down to (m; default MPB__WRIST_MIN_BOUND), and a factor on
 * R1 and R2 (default 1; a test sets it below 1 to see a wrong bound
 * caught). Part of the cache's key. Not thread-safe: set before worlds
 * open.
 */
#define MPB__WRIST_MIN_BOUND 0.004
void mpb__wrist_set_params(double min_bound, double lipschitz_factor);

/* The FCL distances a build may take (default MPB__WRIST_MAX_DISTANCES),
 * for tests. Part of the cache's key. Not thread-safe, as above. */
#define MPB__WRIST_MAX_DISTANCES 8192
void mpb__wrist_set_budget(int distances);

/*
 * For wrist_cache.c, which keeps the tables: build one (MPB_OK with *out,
 * MPB_ENOMEM, MPB_EERROR), free one (NULL: nothing), the build's
 * parameters that its key must hold (least bound, Lipschitz factor,
 * margin, distance budget), a table as bytes (malloc()ed, the caller
 * frees; NULL when out of memory) and back (MPB_OK with *out; MPB_EPARSE
 * when the bytes are not a table for spec: wrong sizes, or not a tree;
 * MPB_ENOMEM).
 */
int mpb__wrist_table_build(const mpb__wrist_spec *spec, mpb__wrist_table **out);
void mpb__wrist_table_free(mpb__wrist_table *t);
void mpb__wrist_get_params(double out[4]);
unsigned char *mpb__wrist_table_encode(const mpb__wrist_table *t, size_t *len);
int mpb__wrist_table_decode(const mpb__wrist_spec *spec,
                            const unsigned char *p, size_t len,
                            mpb__wrist_table **out);

/* Tables built since the process began (misses of both caches). */
long mpb__wrist_builds(void);

/* Tables read from the disk cache since the process began. */
long mpb__wrist_loads(void);

/* Empty the process-wide cache, so that the next world reads the disk
 * cache again: for tests, with no world open. */
void mpb__wrist_forget(void);

#ifdef __cplusplus
}
#endif

#endif /* MPB_WRIST_TABLE_H */
