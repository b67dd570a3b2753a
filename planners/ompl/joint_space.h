/*
 * joint_space.h - the state space mpb-planner-ompl plans in: the world's
 * joints, continuous ones wrapping. Shared with bench/fidelity.cpp, which
 * must plan in the very same space (its maximum extent sets RRTConnect's
 * default range and the motion checks' step: a different space is a
 * different planner).
 */
#ifndef MPB_PLANNER_OMPL_JOINT_SPACE_H
#define MPB_PLANNER_OMPL_JOINT_SPACE_H

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include "mpbench/mpbench.h"

namespace mpb_ompl {

namespace ob = ompl::base;

// A real vector of the world's joints, in the world's order. Continuous
// joints live in [-pi, pi] and wrap: distance and interpolation take the
// short way round, so the metric is the one mpbench verifies and measures
// with (Euclidean in joint space, a continuous joint's difference wrapped).
// Keeping one RealVectorStateSpace (instead of a compound of SO2 and 1-D
// spaces) keeps states flat double arrays and the metric Euclidean, not the
// sum a CompoundStateSpace would make of its components' distances.
class JointSpace : public ob::RealVectorStateSpace {
public:
    explicit JointSpace(const mpb_world *w)
        : ob::RealVectorStateSpace(static_cast<unsigned int>(mpb_world_num_joints(w)))
    {
        unsigned int n = getDimension();
        ob::RealVectorBounds b(n);
        wraps_.resize(n);
        for (unsigned int j = 0; j < n; j++) {
            mpb_world_joint_limits(w, static_cast<int>(j), &b.low[j], &b.high[j]);
            wraps_[j] = mpb_world_joint_is_continuous(w, static_cast<int>(j)) != 0;
            if (wraps_[j]) {
                b.low[j] = -M_PI;
                b.high[j] = M_PI;
                any_wrap_ = true;
            }
            setDimensionName(j, mpb_world_joint_name(w, static_cast<int>(j)));
        }
        setBounds(b);
        setName("mpb_joints");
    }

    double distance(const ob::State *a, const ob::State *b) const override
    {
        if (!any_wrap_)
            return ob::RealVectorStateSpace::distance(a, b);
        const double *x = values(a), *y = values(b);
        double sq = 0.0;
        for (unsigned int j = 0; j < getDimension(); j++) {
            double d = delta(j, x[j], y[j]);
            sq += d * d;
        }
        return std::sqrt(sq);
    }

    void interpolate(const ob::State *from, const ob::State *to, double t,
                     ob::State *state) const override
    {
        const double *x = values(from), *y = values(to);
        double *z = state->as<StateType>()->values;
        for (unsigned int j = 0; j < getDimension(); j++) {
            z[j] = x[j] + t * delta(j, x[j], y[j]);
            if (wraps_[j])
                z[j] = std::remainder(z[j], 2.0 * M_PI);
        }
    }

    void enforceBounds(ob::State *state) const override
    {
        double *z = state->as<StateType>()->values;
        for (unsigned int j = 0; j < getDimension(); j++) {
            if (wraps_[j])
                z[j] = std::remainder(z[j], 2.0 * M_PI);
            else
                z[j] = std::min(std::max(z[j], bounds_.low[j]), bounds_.high[j]);
        }
    }

    bool satisfiesBounds(const ob::State *state) const override
    {
        const double *z = values(state);
        const double eps = std::numeric_limits<double>::epsilon();
        for (unsigned int j = 0; j < getDimension(); j++)
            if (!(z[j] >= bounds_.low[j] - eps && z[j] <= bounds_.high[j] + eps))
                return false;
        return true;
    }

    double getMaximumExtent() const override
    {
        double sq = 0.0;
        for (unsigned int j = 0; j < getDimension(); j++) {
            double e = wraps_[j] ? M_PI : bounds_.high[j] - bounds_.low[j];
            sq += e * e;
        }
        return std::sqrt(sq);
    }

private:
    static const double *values(const ob::State *s)
    {
        return s->as<StateType>()->values;
    }

    double delta(unsigned int j, double from, double to) const
    {
        double d = to - from;
        return wraps_[j] ? std::remainder(d, 2.0 * M_PI) : d;
    }

    std::vector<bool> wraps_;
    bool any_wrap_ = false;
};

}  // namespace mpb_ompl

#endif
