/*
 * final_stage.h - the last check mpb-planner-ompl makes before it answers:
 * is each stage it is about to send valid at the step mpbenchd verifies
 * with? OMPL's simplifiers split segments that were checked whole (a
 * shortcut starts inside a segment, a B-spline pass halves them), and the
 * pieces are sampled at other points than the whole was, so a thin
 * obstacle can sit between the planner's samples and on the verifier's.
 * The stages are checked with the verifier's own function and sampling
 * (mpb_verify_path: k = ceil(L / resolution) steps a segment), last stage
 * first; the answer ends with the last one that passes.
 *
 * Plain C++ over the C library (no OMPL), so that it can be tested alone.
 */
#ifndef MPB_PLANNER_OMPL_FINAL_STAGE_H
#define MPB_PLANNER_OMPL_FINAL_STAGE_H

#include <string>
#include <vector>

#include "mpbench/mpbench.h"

namespace mpb_ompl {

/* Does path (num_joints values a waypoint, the world's joint order) pass
 * the verifier's checks other than start and goal (finite values, joint
 * limits, collision sampled at resolution) in world w? On a failure, why
 * holds the verdict's one line. */
bool stage_valid(mpb_world *w, const std::vector<double> &path, int num_joints,
                 double resolution, std::string *why);

/* The index of the last of stages (each a path as above) that is valid,
 * trying the last first and stopping at the first valid one; -1 if none
 * is. dropped (if not NULL) gets, for each stage past the one returned, a
 * line naming it (names[i]) and why it failed. */
int last_valid_stage(mpb_world *w, const std::vector<std::vector<double>> &stages,
                     const std::vector<std::string> &names, int num_joints,
                     double resolution, std::string *dropped);

}  // namespace mpb_ompl

#endif
