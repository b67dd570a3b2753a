/*
 * fidelity.cpp - mpb-bench-fidelity: one motion-planning problem solved by
 * OMPL 1.5's own in-process ompl::tools::Benchmark, for comparison with the
 * same problem planned through mpbenchd and mpb-planner-ompl (bench/run.sh
 * runs both): does mpbench make a planner look slower or faster than it
 * is?
 *
 * The problem is built as mpb-planner-ompl builds it: the world's joints as
 * a real vector space (continuous joints wrap), validity from
 * mpb_world_in_collision(), motions checked every --resolution rad, the
 * goal a joint configuration with a tolerance. Each run is seeded as the
 * planner seeds a request (ompl::RNG::setSeed with the run's seed, before
 * anything of the run draws a number); --seeds gives the runs' seeds, in
 * order, as mpbenchd drew them for the same experiment. No simplification:
 * Benchmark's "time" is the solve, as the mpbench run's "raw" stage time.
 */
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "mpbench/mpbench.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace ot = ompl::tools;

namespace {

// The world's joints; continuous ones wrap (the short way round). The same
// space as mpb-planner-ompl's JointSpace, member for member: its maximum
// extent sets RRTConnect's default range, so a different one is a
// different planner.
class Joints : public ob::RealVectorStateSpace {
public:
    explicit Joints(const mpb_world *w)
        : ob::RealVectorStateSpace(static_cast<unsigned int>(mpb_world_num_joints(w)))
    {
        unsigned int n = getDimension();
        ob::RealVectorBounds b(n);
        wraps_.resize(n);
        for (unsigned int j = 0; j < n; j++) {
            int jj = static_cast<int>(j);
            mpb_world_joint_limits(w, jj, &b.low[j], &b.high[j]);
            wraps_[j] = mpb_world_joint_is_continuous(w, jj) != 0;
            if (wraps_[j]) {
                b.low[j] = -M_PI;
                b.high[j] = M_PI;
            }
        }
        setBounds(b);
    }

    double distance(const ob::State *a, const ob::State *b) const override
    {
        const double *x = a->as<StateType>()->values, *y = b->as<StateType>()->values;
        double sq = 0;
        for (unsigned int j = 0; j < getDimension(); j++) {
            double d = step(j, x[j], y[j]);
            sq += d * d;
        }
        return std::sqrt(sq);
    }

    void interpolate(const ob::State *from, const ob::State *to, double t,
                     ob::State *state) const override
    {
        const double *x = from->as<StateType>()->values, *y = to->as<StateType>()->values;
        double *z = state->as<StateType>()->values;
        for (unsigned int j = 0; j < getDimension(); j++) {
            z[j] = x[j] + t * step(j, x[j], y[j]);
            if (wraps_[j])
                z[j] = std::remainder(z[j], 2 * M_PI);
        }
    }

    void enforceBounds(ob::State *state) const override
    {
        double *z = state->as<StateType>()->values;
        for (unsigned int j = 0; j < getDimension(); j++)
            z[j] = wraps_[j] ? std::remainder(z[j], 2 * M_PI)
                             : std::min(std::max(z[j], bounds_.low[j]), bounds_.high[j]);
    }

    bool satisfiesBounds(const ob::State *state) const override
    {
        const double *z = state->as<StateType>()->values;
        const double eps = std::numeric_limits<double>::epsilon();
        for (unsigned int j = 0; j < getDimension(); j++)
            if (!(z[j] >= bounds_.low[j] - eps && z[j] <= bounds_.high[j] + eps))
                return false;
        return true;
    }

    // A wrapping joint is at most pi away the short way round.
    double getMaximumExtent() const override
    {
        double sq = 0;
        for (unsigned int j = 0; j < getDimension(); j++) {
            double e = wraps_[j] ? M_PI : bounds_.high[j] - bounds_.low[j];
            sq += e * e;
        }
        return std::sqrt(sq);
    }

private:
    double step(unsigned int j, double a, double b) const
    {
        return wraps_[j] ? std::remainder(b - a, 2 * M_PI) : b - a;
    }
    std::vector<bool> wraps_;
};

std::vector<std::string> split(const std::string &s)
{
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, ','))
        if (!item.empty())
            out.push_back(item);
    return out;
}

std::vector<double> numbers(const std::string &s)
{
    std::vector<double> out;
    for (const std::string &x : split(s))
        out.push_back(std::strtod(x.c_str(), nullptr));
    return out;
}

std::string slurp(const char *path)
{
    std::string out;
    FILE *f = std::fopen(path, "rb");
    if (f == nullptr)
        return out;
    char buf[65536];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0)
        out.append(buf, n);
    std::fclose(f);
    return out;
}

double median(std::vector<double> v)
{
    if (v.empty())
        return NAN;
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void usage(FILE *out)
{
    std::fprintf(out,
"usage: mpb-bench-fidelity --robot URDF --scene SCENE --joints A,B,...\n"
"                          --start Q --goal Q --seeds S1,S2,... [options]\n"
"\n"
"Plans start -> goal (joint values, comma-separated, in --joints order)\n"
"with RRTConnect in OMPL's own Benchmark, once per seed, and prints the\n"
"median solve time and the success rate.\n"
"\n"
"options:\n"
"  --time-limit S   per run (default 10)\n"
"  --tolerance RAD  goal tolerance (default 0.01)\n"
"  --resolution RAD motion checks, as mpb-planner-ompl (default 0.005)\n"
"  --per-run        print each run's seed, time and outcome\n");
}

} // namespace

int main(int argc, char **argv)
{
    const char *robot_file = nullptr, *scene_file = nullptr;
    std::string joints_arg, start_arg, goal_arg, seeds_arg;
    double time_limit = 10, tolerance = 0.01, resolution = 0.005;
    bool per_run = false;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : nullptr;
        if (!std::strcmp(a, "--help")) {
            usage(stdout);
            return 0;
        }
        if (!std::strcmp(a, "--per-run")) {
            per_run = true;
            continue;
        }
        if (v == nullptr) {
            usage(stderr);
            return 2;
        }
        i++;
        if (!std::strcmp(a, "--robot")) robot_file = v;
        else if (!std::strcmp(a, "--scene")) scene_file = v;
        else if (!std::strcmp(a, "--joints")) joints_arg = v;
        else if (!std::strcmp(a, "--start")) start_arg = v;
        else if (!std::strcmp(a, "--goal")) goal_arg = v;
        else if (!std::strcmp(a, "--seeds")) seeds_arg = v;
        else if (!std::strcmp(a, "--time-limit")) time_limit = std::atof(v);
        else if (!std::strcmp(a, "--tolerance")) tolerance = std::atof(v);
        else if (!std::strcmp(a, "--resolution")) resolution = std::atof(v);
        else {
            usage(stderr);
            return 2;
        }
    }
    std::vector<std::string> names = split(joints_arg);
    std::vector<double> start = numbers(start_arg), goal = numbers(goal_arg);
    std::vector<std::string> seeds = split(seeds_arg);
    if (!robot_file || !scene_file || names.empty() || start.size() != names.size() ||
        goal.size() != names.size() || seeds.empty() || !(time_limit > 0) ||
        !(resolution > 0)) {
        usage(stderr);
        return 2;
    }
    std::string robot = slurp(robot_file), scene = slurp(scene_file);
    std::vector<const char *> cnames;
    for (const std::string &n : names)
        cnames.push_back(n.c_str());
    mpb_world *world = nullptr;
    char err[256] = "";
    if (robot.empty() ||
        mpb_world_open_group("urdf", robot.c_str(), "moveit-scene", scene.c_str(),
                             cnames.data(), static_cast<int>(cnames.size()),
                             &world, err, sizeof err) != MPB_OK) {
        std::fprintf(stderr, "mpb-bench-fidelity: cannot open the world: %s\n",
                     robot.empty() ? "cannot read the robot" : err);
        return 1;
    }
    // Seeds are nominal here (OMPL 1.5 warns that re-seeding after the
    // first draw is not deterministic): compare distributions, not runs.
    ompl::msg::setLogLevel(ompl::msg::LOG_NONE);

    // The world's joint order is the group's (mpb_world_open_group).
    auto space = std::make_shared<Joints>(world);
    og::SimpleSetup ss(space);
    const ob::SpaceInformationPtr &si = ss.getSpaceInformation();
    Joints *sp = space.get();
    ss.setStateValidityChecker([world, sp](const ob::State *s) {
        return sp->satisfiesBounds(s) &&
               mpb_world_in_collision(
                   world, s->as<ob::RealVectorStateSpace::StateType>()->values) == 0;
    });
    si->setStateValidityCheckingResolution(
        std::min(resolution / space->getMaximumExtent(), 0.5));
    ob::ScopedState<> s0(space), s1(space);
    for (size_t j = 0; j < names.size(); j++) {
        bool wraps = mpb_world_joint_is_continuous(world, static_cast<int>(j)) != 0;
        s0[j] = wraps ? std::remainder(start[j], 2 * M_PI) : start[j];
        s1[j] = wraps ? std::remainder(goal[j], 2 * M_PI) : goal[j];
    }
    ss.setStartAndGoalStates(s0, s1, tolerance);
    ss.setPlanner(std::make_shared<og::RRTConnect>(si));
    ss.setup();

    ot::Benchmark b(ss, "mpbench-fidelity");
    b.addPlanner(std::make_shared<og::RRTConnect>(si));
    size_t run = 0;
    b.setPreRunEvent([&](const ob::PlannerPtr &) {
        // As mpb-planner-ompl seeds a request (32 bits, never 0).
        std::uint64_t u = std::strtoull(seeds[run % seeds.size()].c_str(), nullptr, 10);
        std::uint32_t s = static_cast<std::uint32_t>(u ^ (u >> 32));
        ompl::RNG::setSeed(s != 0 ? s : 0x9e3779b9u);
        run++;
    });
    ot::Benchmark::Request req(time_limit, 4096.0,
                               static_cast<unsigned int>(seeds.size()), 0.05,
                               false, false, false);
    b.benchmark(req);

    const ot::Benchmark::CompleteExperiment &exp = b.getRecordedExperimentData();
    std::vector<double> times;
    int solved = 0, n = 0;
    for (const auto &pe : exp.planners)
        for (const auto &r : pe.runs) {
            n++;
            auto t = r.find("time REAL");
            auto ok = r.find("solved BOOLEAN");
            bool exact = ok != r.end() && ok->second == "1";
            auto approx = r.find("approximate solution BOOLEAN");
            if (approx != r.end() && approx->second == "1")
                exact = false;
            if (exact)
                solved++;
            double secs = t != r.end() ? std::strtod(t->second.c_str(), nullptr) : NAN;
            if (exact)
                times.push_back(secs);
            if (per_run)
                std::printf("  run %d seed %s: %.6f s%s\n", n - 1,
                            seeds[static_cast<size_t>(n - 1) % seeds.size()].c_str(),
                            secs, exact ? "" : " (not solved)");
        }
    double med = median(times);
    std::printf("OMPL Benchmark, RRTConnect, %d runs: median solve time %.6f s "
                "(solved runs), %d solved\n", n, med, solved);
    std::printf("RESULT fidelity_ompl runs=%d median_s=%.6f solved=%d "
                "success=%.4f\n", n, med, solved, n ? (double)solved / n : NAN);

    // The same runs without Benchmark's machinery (its run thread, the
    // thread that polls the time and memory limits, the progress
    // collector): a new planner per run, set up, then solve() alone timed,
    // as mpb-planner-ompl does for a request.
    std::vector<double> plain;
    int plain_solved = 0;
    for (size_t r = 0; r < seeds.size(); r++) {
        std::uint64_t u = std::strtoull(seeds[r].c_str(), nullptr, 10);
        std::uint32_t sd = static_cast<std::uint32_t>(u ^ (u >> 32));
        ompl::RNG::setSeed(sd != 0 ? sd : 0x9e3779b9u);
        ss.getProblemDefinition()->clearSolutionPaths();
        auto planner = std::make_shared<og::RRTConnect>(si);
        planner->setProblemDefinition(ss.getProblemDefinition());
        planner->setup();
        const double t0 = mpb_monotonic_s(), deadline = t0 + time_limit;
        ob::PlannerStatus st = planner->solve(ob::PlannerTerminationCondition(
            [deadline] { return mpb_monotonic_s() >= deadline; }));
        const double secs = mpb_monotonic_s() - t0;
        if (st == ob::PlannerStatus::EXACT_SOLUTION) {
            plain_solved++;
            plain.push_back(secs);
        }
    }
    double pmed = median(plain);
    std::printf("OMPL in process, no Benchmark, RRTConnect, %zu runs: median "
                "solve time %.6f s (solved runs), %d solved\n", seeds.size(),
                pmed, plain_solved);
    std::printf("RESULT fidelity_plain runs=%zu median_s=%.6f solved=%d\n",
                seeds.size(), pmed, plain_solved);
    mpb_world_close(world);
    return 0;
}
