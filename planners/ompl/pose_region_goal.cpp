// pose_region_goal.cpp - see pose_region_goal.h.

#include "pose_region_goal.h"

#include <limits>
#include <utility>

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>

#include "mpbench/mpbench.h"

namespace ob = ompl::base;

namespace {

// Goal states drawn at most; past this sampleGoal() cycles through them.
// Also what maxSampleCount() says: BITstar takes that many goals at once.
constexpr std::size_t kMaxPool = 16;
// Region poses tried per new goal state asked for during planning.
constexpr int kTargetsPerSample = 2;

}  // namespace

PoseRegionGoal::PoseRegionGoal(const ob::SpaceInformationPtr &si, const mpb_robot *robot,
                               const mpb_goal_region &region, std::vector<int> perm,
                               std::vector<double> seed_q, std::uint64_t seed)
    : ob::GoalSampleableRegion(si), robot_(robot), region_(region),
      perm_(std::move(perm)), seed_q_(std::move(seed_q)), rng_(seed)
{
    // Membership is the region's own test, not a distance threshold.
    setThreshold(0.0);
}

void PoseRegionGoal::toRequest(const ob::State *st, double *q) const
{
    const double *v = st->as<ob::RealVectorStateSpace::StateType>()->values;
    for (std::size_t i = 0; i < perm_.size(); i++)
        q[i] = v[perm_[i]];
}

bool PoseRegionGoal::grow(int max_targets) const
{
    std::size_t n = perm_.size();
    std::vector<double> q(n);
    ob::State *st = si_->allocState();
    double *v = st->as<ob::RealVectorStateSpace::StateType>()->values;
    bool found = false;
    for (int t = 0; t < max_targets && !found; t++) {
        ik_calls_++;
        // Seeded by the start, IK lands near it, which is where the path is
        // short, but every answer near a colliding one collides too: mostly
        // start IK from random configurations (the rng's, so runs repeat).
        const double *seed = ik_calls_ % 8 == 1 ? seed_q_.data() : nullptr;
        if (mpb_goal_region_sample(robot_, &region_, seed, nullptr, 1, &rng_,
                                   q.data()) != MPB_OK)
            continue;
        for (std::size_t i = 0; i < n; i++)
            v[perm_[i]] = q[i];
        // In the region and collision-free: only such states are goals.
        if (si_->isValid(st)) {
            pool_.emplace_back(v, v + n);
            found = true;
        }
    }
    si_->freeState(st);
    return found;
}

bool PoseRegionGoal::prime(int max_targets)
{
    std::lock_guard<std::mutex> lock(mu_);
    return !pool_.empty() || grow(max_targets);
}

void PoseRegionGoal::sampleGoal(ob::State *st) const
{
    std::lock_guard<std::mutex> lock(mu_);
    // A new goal state while there are few, so they spread over the
    // region as planning goes on; then (or when IK finds none) an old one.
    bool fresh = pool_.size() < kMaxPool && grow(kTargetsPerSample);
    const std::vector<double> &g = fresh ? pool_.back() : pool_[calls_ % pool_.size()];
    calls_++;
    double *v = st->as<ob::RealVectorStateSpace::StateType>()->values;
    std::copy(g.begin(), g.end(), v);
}

unsigned int PoseRegionGoal::maxSampleCount() const
{
    // Finite: planners such as BITstar take goal states while they last.
    // None before prime() found one.
    std::lock_guard<std::mutex> lock(mu_);
    return pool_.empty() ? 0u : static_cast<unsigned int>(kMaxPool);
}

std::size_t PoseRegionGoal::numGoalStates() const
{
    std::lock_guard<std::mutex> lock(mu_);
    return pool_.size();
}

double PoseRegionGoal::distanceGoal(const ob::State *st) const
{
    std::vector<double> q(perm_.size());
    toRequest(st, q.data());
    mpb_goal_distance d;
    if (mpb_goal_region_distance(robot_, &region_, q.data(), &d) != MPB_OK)
        return std::numeric_limits<double>::infinity();
    // Metres and radians added: only an ordering for approximate solutions.
    return d.position + d.orientation;
}

bool PoseRegionGoal::isSatisfied(const ob::State *st) const
{
    std::vector<double> q(perm_.size());
    toRequest(st, q.data());
    return mpb_goal_region_contains(robot_, &region_, q.data()) == 1;
}

bool PoseRegionGoal::isSatisfied(const ob::State *st, double *distance) const
{
    bool in = isSatisfied(st);
    if (distance != nullptr)
        *distance = in ? 0.0 : distanceGoal(st);
    return in;
}
