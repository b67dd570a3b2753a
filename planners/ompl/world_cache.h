// world_cache.h - the worlds mpb-planner-ompl keeps between requests:
// the last few parsed, keyed by the robot's and the scene's hashes and the
// joints, each with its robot for IK once a pose-region goal needs it.
#ifndef MPB_PLANNER_OMPL_WORLD_CACHE_H
#define MPB_PLANNER_OMPL_WORLD_CACHE_H

#include <cstddef>
#include <list>
#include <string>

#include "mpbench/mpbench.h"
#include "mpbench/planner.h"
#include "mpbench/robot.h"

namespace mpb_ompl {

struct CachedWorld {
    std::string key;
    mpb_world *world;
    mpb_robot *robot;       // for IK; loaded at the first pose-region goal
};

// The robot of a urdf world in the request's joint order, for IK and goal
// regions; nullptr with err filled when there is none.
mpb_robot *cached_robot(CachedWorld &c, const mpb_plan_request_t *req, std::string &err);

class WorldCache {
public:
    ~WorldCache();

    // The world of a request, parsed once per robot and scene; nullptr
    // with err filled when it does not parse. Owned by the cache. *built
    // says whether this call parsed it; a parse is told to the daemon
    // through lim (mpb_solve_setting_up(), then mpb_solve_planning()).
    CachedWorld *get(const mpb_plan_request_t *req, const mpb_solve_limits *lim,
                     std::string &err, bool *built);

private:
    static constexpr std::size_t kSize = 4;

    std::list<CachedWorld> list_;
};

}  // namespace mpb_ompl

#endif
