// pose_region_goal.h - the paper's end-effector goal region as an OMPL goal.
//
// Membership and distance come from libmpbench (mpb_goal_region_contains,
// mpb_goal_region_distance), the very functions mpbenchd verifies with, so
// a path OMPL accepts ends where the daemon agrees it ends. Goal states are
// IK solutions inside the region (mpb_goal_region_sample) that the space
// information calls valid. Being a GoalSampleableRegion, bidirectional
// planners (RRTConnect, SBL, LBKPIECE1 ...) root goal trees in them.
//
// Sampling is synchronous and draws from the goal's own random state,
// seeded from the request: unlike GoalLazySamples (a sampling thread racing
// the planner) the same seed gives the same goal states in the same order.
#ifndef MPB_OMPL_POSE_REGION_GOAL_H
#define MPB_OMPL_POSE_REGION_GOAL_H

#include <cstdint>
#include <mutex>
#include <vector>

#include <ompl/base/goals/GoalSampleableRegion.h>

#include "mpbench/robot.h"

class PoseRegionGoal : public ompl::base::GoalSampleableRegion {
public:
    // robot: in the request's joint order; perm[i] is the state index of
    // the request's joint i. seed_q (request order) seeds every IK.
    PoseRegionGoal(const ompl::base::SpaceInformationPtr &si, const mpb_robot *robot,
                   const mpb_goal_region &region, std::vector<int> perm,
                   std::vector<double> seed_q, std::uint64_t seed);

    // Look for a first valid goal state, drawing up to max_targets region
    // poses; true when one was found (and kept for sampleGoal()).
    bool prime(int max_targets);

    void sampleGoal(ompl::base::State *st) const override;
    unsigned int maxSampleCount() const override;
    double distanceGoal(const ompl::base::State *st) const override;
    bool isSatisfied(const ompl::base::State *st) const override;
    bool isSatisfied(const ompl::base::State *st, double *distance) const override;

    std::size_t numGoalStates() const;
    unsigned long ikCalls() const { return ik_calls_; }

private:
    // One more valid IK solution into pool_ (tries up to max_targets region
    // poses); false if none was found. Caller holds mu_.
    bool grow(int max_targets) const;
    void toRequest(const ompl::base::State *st, double *q) const;

    const mpb_robot *robot_;
    mpb_goal_region region_;
    std::vector<int> perm_;
    std::vector<double> seed_q_;
    mutable std::mutex mu_;             // PRM samples goals from a second thread
    mutable std::uint64_t rng_;
    mutable std::vector<std::vector<double>> pool_;  // state order
    mutable unsigned long calls_ = 0;
    mutable unsigned long ik_calls_ = 0;
};

#endif
