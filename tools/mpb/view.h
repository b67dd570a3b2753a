/*
 * view.h - what the files of `mpb view` share: one run read back and drawn
 * ready (view.c), written as a self-contained HTML page (view_page.c).
 */
#ifndef MPB_VIEW_H
#define MPB_VIEW_H

#include <stdint.h>
#include <stdio.h>

#include "mpb.h"

/* One stage of the run, with the poses of the moving bodies per frame. */
typedef struct view_stage {
    char   *name, *verdict, *detail;
    int     valid, segment;        /* segment: the verdict's, -1 if none */
    int     num_waypoints;
    double *waypoints;             /* as stored; freed once framed */
    double *times;                 /* the waypoints' times as stored, or
                                      NULL (an untimed stage) */
    int     num_frames;            /* waypoints, and samples between them
                                      when there are few */
    float  *frame_at;              /* per frame: waypoint index + fraction */
    float  *poses;                 /* frames x moving bodies x 7 (xyz, quat) */
    int     fail_frame;            /* the frame the verdict points at, or -1 */
    /* A collision: the configuration the verifier stopped at. */
    int     has_collision;
    double  collision_s;           /* where in its segment, 0 .. 1 */
    int     contact[2];            /* the two bodies touching, -1 if unknown */
    int     sampled;               /* stored verification "sampled" (or none) */
    int     collision_certified;   /* found by the proof, s exact */
    double *collision_q;           /* the configuration, num_joints values */
    float  *collision_poses;       /* moving bodies x 7 */
} view_stage;

typedef struct view_run {
    mpb_run_detail run;            /* strings copied into strs */
    char          *strs[6];
    char          *experiment, *scene, *query, *robot_format;
    int            num_joints;
    char         **joint_names;
    double        *start;
    double         tolerance;      /* per joint, at the start and a joint goal */
    int            goal_kind;      /* mpb_goal_kind */
    double        *goal_joints;    /* joint goals */
    char          *goal_link;      /* region goals */
    double         goal_region[12];
    int            num_held;       /* joints outside the group the query */
    char         **held_names;     /* holds (queries.held), applied to */
    double        *held_values;    /* the world when it opens */
    double         resolution;     /* the verifier's step, rad */
    int            resolution_known;
    mpb_world     *world;
    mpb_bodies    *bodies;
    int           *moving;         /* indices of the bodies that move */
    int            num_moving;
    float         *static_poses;   /* every body x 7, at the start */
    float         *start_poses;    /* moving bodies x 7 */
    float         *goal_poses;     /* joint goals: moving bodies x 7 */
    view_stage    *stages;
    int            num_stages;
    /* What its planner was given instead of the scene (`seen:`), or
     * seen_world NULL: its obstacles, drawn beside the truth's, and the
     * run's judgement there. */
    char          *seen_how;
    mpb_world     *seen_world;
    mpb_bodies    *seen_bodies;
    float         *seen_poses;     /* every seen body x 7, at the start */
    char          *seen_verdict, *seen_detail;
    int            seen_success;   /* 1, 0; -1: not judged there */
} view_run;

/* calloc and strdup that end mpb with one line when memory runs out. */
void *view_calloc(size_t n, size_t size);
char *view_strdup(const char *s);

/*
 * Read run run_id from s (db names it in messages) and make it ready to
 * draw into *v: 0; -1 after one line on stderr; 1 with why filled and
 * nothing printed when the run has no stages (a list of runs notes that
 * rather than fails). Free *v with view_free() in every case.
 */
int view_load(mpb_store *s, const char *db, int64_t run_id, view_run *v,
              char *why, size_t whylen);
/*
 * As view_load(), without what only a page needs: the run, its query, its
 * stages with their waypoints, and the world it was verified in
 * (v->world), for `mpb verify`; messages start "mpb CMD:". The same
 * returns.
 */
int view_read(const char *cmd, mpb_store *s, const char *db, int64_t run_id,
              view_run *v, char *why, size_t whylen);
void view_free(view_run *v);

/* three.js's source, read from the first place that has it ($MPB_THREE_JS,
 * mpbench's data folder, the source tree's .cache/web); NULL (errno set)
 * if none has, with where naming the last place tried. */
char *view_load_three(char *where, size_t len);

/* Write the page of v to path, through path.tmp renamed; 0, or -1 after
 * one line on stderr. */
int view_write_file(const view_run *v, const char *three, const char *path);

/* Runs chosen by name (view_select.c). */
typedef struct selection {
    const char *scene, *query, *planner;
    int         failed;
    mpb_store  *store;
    int64_t    *runs;
    int         num_runs, cap_runs;
    /* names by id, of the experiment's configurations, scenes, queries */
    int64_t    *ids;
    char      **names;
    int         num_names, cap_names;
} selection;

/* The finished runs of the experiment that sel names, in run order, into
 * sel->runs; 0, or -1 after one line. */
int view_select_runs(mpb_store *s, const char *db, int64_t experiment,
                     selection *sel);
void view_selection_free(selection *sel);

/* One page per run of sel into dir, and dir/index.html listing them all;
 * 0, or -1 after one line. */
int view_write_many(mpb_store *s, const char *db, int64_t experiment,
                    const selection *sel, const char *three, const char *dir);

/*
 * Write the page for run v to out: the HTML, the run's data as JSON, and
 * three.js (three_js, the module's source) inlined. 0, or -1 on a write
 * error (errno set).
 */
int view_write_page(const view_run *v, const char *three_js, FILE *out);

/* Text into HTML: < > & " escaped. */
void view_html_text(FILE *f, const char *s);

/* Where a run is, "scene / query", into buf: the query alone when it
 * names the scene too (MotionBenchMaker's problems name both
 * "cage_panda/0001"; a query "kitchen/x" of the scene "kitchen"). */
const char *view_place(const char *scene, const char *query, char *buf,
                       size_t n);

/*
 * For `mpb verify` (verify.c): run run_id read as view_read() reads it,
 * with the step it is verified at (step, or the run's own resolution when
 * step is 0) and its query's goal, which points into *v. The same
 * returns.
 */
int verify_read_run(mpb_store *s, const char *db, int64_t run_id,
                    double step, view_run *v, double *res, mpb_goal *goal);
/* Stage st of run v verified again at res, in the mode v's world is set
 * to, without the metrics (they cost many times more): its verdict into
 * *out. 0, or -1 after one line on stderr. */
int verify_stage(const view_run *v, const view_stage *st,
                 const mpb_goal *goal, double res, const char *db,
                 int64_t run_id, mpb_verdict *out);

/*
 * `mpb verify --compare` (verify_compare.c): the runs of sel verified
 * again certified and sampled, at step (0: each run's resolution), the
 * differences listed and counted on stdout. MPB_EXIT_OK, MPB_EXIT_ERROR
 * when a sampled collision passes the certified check or on an error.
 */
int verify_compare(mpb_store *s, const char *db, int64_t experiment,
                   const selection *sel, double step);

#endif
