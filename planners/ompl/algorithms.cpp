// algorithms.cpp - the list of OMPL planners offered, and BiTRRT with the
// connection range as a parameter of its own.
#include <cstring>
#include <memory>

#include <ompl/geometric/planners/est/BiEST.h>
#include <ompl/geometric/planners/est/EST.h>
#include <ompl/geometric/planners/est/ProjEST.h>
#include <ompl/geometric/planners/fmt/BFMT.h>
#include <ompl/geometric/planners/fmt/FMT.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/kpiece/BKPIECE1.h>
#include <ompl/geometric/planners/kpiece/KPIECE1.h>
#include <ompl/geometric/planners/kpiece/LBKPIECE1.h>
#include <ompl/geometric/planners/pdst/PDST.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/LazyPRMstar.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/prm/PRMstar.h>
#include <ompl/geometric/planners/rrt/BiTRRT.h>
#include <ompl/geometric/planners/rrt/InformedRRTstar.h>
#include <ompl/geometric/planners/rrt/LBTRRT.h>
#include <ompl/geometric/planners/rrt/LazyRRT.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/geometric/planners/rrt/TRRT.h>
#include <ompl/geometric/planners/sbl/SBL.h>
#include <ompl/geometric/planners/sst/SST.h>
#include <ompl/geometric/planners/stride/STRIDE.h>

#include "algorithms.h"

namespace mpb_ompl {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

// OMPL 1.5's BiTRRT tries to join its two trees only when the other
// tree's nearest state is within 10 longest valid segments (its
// connectionRange_, set in setup(), with no parameter). OMPL and MoveIt
// check motions at 0.01 of the space's extent by default, which makes
// that 0.1 of the extent (1.34 rad on the Panda); this planner checks
// every `resolution` rad, 0.01 by default, which made it 0.1 rad: in
// seven joints the trees almost never come that close, and BiTRRT timed
// out on every Panda problem. The range is its own parameter here,
// `connection_range` (rad), by default 0.1 of the extent whatever the
// resolution.
class BiTRRT : public og::BiTRRT {
public:
    explicit BiTRRT(const ob::SpaceInformationPtr &si) : og::BiTRRT(si)
    {
        declareParam<double>("connection_range", this, &BiTRRT::setConnectionRange,
                             &BiTRRT::getConnectionRange, "0.:1.:10000.");
    }

    // 0 (the default): 0.1 of the space's maximum extent.
    void setConnectionRange(double range) { range_ = range; }
    double getConnectionRange() const { return range_; }

    void setup() override
    {
        og::BiTRRT::setup();
        connectionRange_ = range_ > 0.0 ? range_ : 0.1 * si_->getMaximumExtent();
    }

private:
    double range_ = 0.0;
};

template <class P> Algorithm alg(const char *name, bool two_threads = false)
{
    return {name, [](const ob::SpaceInformationPtr &si) -> ob::PlannerPtr {
                return std::make_shared<P>(si);
            }, two_threads};
}

}  // namespace

const std::vector<Algorithm> &algorithms()
{
    static const std::vector<Algorithm> list = {
        alg<og::RRTConnect>("RRTConnect"),
        alg<og::RRT>("RRT"),
        alg<og::RRTstar>("RRTstar"),
        alg<og::InformedRRTstar>("InformedRRTstar"),
        alg<og::LazyRRT>("LazyRRT"),
        alg<og::TRRT>("TRRT"),
        alg<BiTRRT>("BiTRRT"),
        alg<og::LBTRRT>("LBTRRT"),
        alg<og::PRM>("PRM", true),          // its solution check runs in a thread
        alg<og::PRMstar>("PRMstar", true),
        alg<og::LazyPRM>("LazyPRM"),
        alg<og::LazyPRMstar>("LazyPRMstar"),
        alg<og::KPIECE1>("KPIECE1"),
        alg<og::BKPIECE1>("BKPIECE1"),
        alg<og::LBKPIECE1>("LBKPIECE1"),
        alg<og::SBL>("SBL"),
        alg<og::EST>("EST"),
        alg<og::BiEST>("BiEST"),
        alg<og::ProjEST>("ProjEST"),
        alg<og::STRIDE>("STRIDE"),
        alg<og::PDST>("PDST"),
        alg<og::BITstar>("BITstar"),
        alg<og::FMT>("FMT"),
        alg<og::BFMT>("BFMT"),
        alg<og::SST>("SST"),
    };
    return list;
}

const Algorithm *find_algorithm(const char *name)
{
    for (const Algorithm &a : algorithms())
        if (std::strcmp(a.name, name) == 0)
            return &a;
    return nullptr;
}

}  // namespace mpb_ompl
