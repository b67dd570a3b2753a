// ompl_benchmark_log.cpp - writes a benchmark log with OMPL's own
// ompl::tools::Benchmark, so that `mpb import` is tested (and measured) on
// what OMPL really writes, not on our idea of it.
//
// Usage: mpb-test-ompl-log OUT.log [RUNS] [SECONDS]
// A point in the unit square goes around a wall, planned by RRTConnect,
// RRT and PRM (PRM runs to the time limit: its progress properties are in
// the log too). The wall's size and the space's dimension are experiment
// parameters, as a user of OMPL would record them.
#include <cstdio>
#include <cstdlib>
#include <memory>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

namespace ob = ompl::base;
namespace og = ompl::geometric;

int main(int argc, char **argv)
{
    if (argc < 2) {
        std::fprintf(stderr, "usage: mpb-test-ompl-log OUT.log [RUNS] [SECONDS]\n");
        return 2;
    }
    const unsigned runs = argc > 2 ? static_cast<unsigned>(std::atoi(argv[2])) : 5;
    const double seconds = argc > 3 ? std::atof(argv[3]) : 0.05;
    ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
    ompl::RNG::setSeed(42);

    auto space = std::make_shared<ob::RealVectorStateSpace>(2);
    space->setBounds(0.0, 1.0);
    og::SimpleSetup ss(space);
    // A wall at x = 0.5 from y = 0 to 0.8: the way round is over its top.
    ss.setStateValidityChecker([](const ob::State *s) {
        const auto *v = s->as<ob::RealVectorStateSpace::StateType>()->values;
        return !(v[0] > 0.45 && v[0] < 0.55 && v[1] < 0.8);
    });
    ss.getSpaceInformation()->setStateValidityCheckingResolution(0.005);
    ob::ScopedState<> start(space), goal(space);
    start[0] = 0.1; start[1] = 0.1;
    goal[0] = 0.9;  goal[1] = 0.1;
    ss.setStartAndGoalStates(start, goal, 0.01);

    ompl::tools::Benchmark bench(ss, "wall");
    bench.addExperimentParameter("wall_width", "REAL", "0.1");
    bench.addExperimentParameter("wall height", "REAL", "0.8");
    bench.addExperimentParameter("dimensions", "INTEGER", "2");
    auto si = ss.getSpaceInformation();
    bench.addPlanner(std::make_shared<og::RRTConnect>(si));
    bench.addPlanner(std::make_shared<og::RRT>(si));
    bench.addPlanner(std::make_shared<og::PRM>(si));
    // Progress every 0.05 s, no console capture, paths simplified (the
    // log then has "simplified ..." properties too).
    ompl::tools::Benchmark::Request req(seconds, 1024.0, runs, 0.05, false,
                                        false, true);
    bench.benchmark(req);
    if (!bench.saveResultsToFile(argv[1])) {
        std::fprintf(stderr, "mpb-test-ompl-log: cannot write %s\n", argv[1]);
        return 1;
    }
    return 0;
}
