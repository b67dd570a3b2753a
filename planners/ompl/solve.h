// solve.h - mpb-planner-ompl's solve(): one plan request in, one result
// out, by one fresh OMPL problem over a cached world (solve.cpp).
#ifndef MPB_PLANNER_OMPL_SOLVE_H
#define MPB_PLANNER_OMPL_SOLVE_H

#include "mpbench/mpbench.h"
#include "mpbench/planner.h"

#include "world_cache.h"

namespace mpb_ompl {

// What is kept between requests: the parsed worlds.
struct Context {
    WorldCache worlds;
};

}  // namespace mpb_ompl

// The planner's mpb_solve_fn; user is an mpb_ompl::Context. Every C++
// exception is caught inside: none crosses into the C library.
extern "C" int mpb_ompl_solve(void *user, const mpb_plan_request_t *req,
                              const mpb_solve_limits *lim, mpb_plan_result_t *res);

#endif
