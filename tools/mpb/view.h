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
    int     num_frames;            /* waypoints, and samples between them
                                      when there are few */
    float  *frame_at;              /* per frame: waypoint index + fraction */
    float  *poses;                 /* frames x moving bodies x 7 (xyz, quat) */
    int     fail_frame;            /* the frame the verdict points at, or -1 */
    /* A collision: the configuration the verifier stopped at. */
    int     has_collision;
    double  collision_s;           /* where in its segment, 0 .. 1 */
    int     contact[2];            /* the two bodies touching, -1 if unknown */
    float  *collision_poses;       /* moving bodies x 7 */
} view_stage;

typedef struct view_run {
    mpb_run_detail run;            /* strings copied into strs */
    char          *strs[6];
    char          *experiment, *scene, *query, *robot_format;
    int            num_joints;
    char         **joint_names;
    double        *start;
    int            goal_kind;      /* mpb_goal_kind */
    double        *goal_joints;    /* joint goals */
    char          *goal_link;      /* region goals */
    double         goal_region[12];
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
} view_run;

/*
 * Write the page for run v to out: the HTML, the run's data as JSON, and
 * three.js (three_js, the module's source) inlined. 0, or -1 on a write
 * error (errno set).
 */
int view_write_page(const view_run *v, const char *three_js, FILE *out);

/* Text into HTML: < > & " escaped. */
void view_html_text(FILE *f, const char *s);

#endif
