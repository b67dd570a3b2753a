// algorithms.h - the OMPL geometric planners mpb-planner-ompl offers, by
// name, each with a factory.
#ifndef MPB_PLANNER_OMPL_ALGORITHMS_H
#define MPB_PLANNER_OMPL_ALGORITHMS_H

#include <functional>
#include <vector>

#include <ompl/base/Planner.h>
#include <ompl/base/SpaceInformation.h>

namespace mpb_ompl {

using Factory = std::function<ompl::base::PlannerPtr(const ompl::base::SpaceInformationPtr &)>;

struct Algorithm {
    const char *name;
    Factory make;
    bool two_threads;   // checks states from two threads while it solves
};

// Every algorithm offered, in the order --help lists them.
const std::vector<Algorithm> &algorithms();

// The algorithm called name, or nullptr.
const Algorithm *find_algorithm(const char *name);

}  // namespace mpb_ompl

#endif
