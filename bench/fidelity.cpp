/*
 * fidelity.cpp - mpb-bench-fidelity: does mpbench make a planner look slower
 * or faster than it is? One motion-planning problem solved in process, by
 * OMPL 1.5's own ompl::tools::Benchmark and by a bare solve(), for
 * comparison with the same problem planned through mpbenchd and
 * mpb-planner-ompl; then the statistics of the comparison (bench/fidelity.sh
 * runs the three sides in interleaved blocks).
 *
 *   mpb-bench-fidelity run --robot URDF --scene SCENE --joints A,B,...
 *                      --start Q --goal Q --seeds S1,S2,... [options]
 *   mpb-bench-fidelity pace --planner-pid PID --runs N --robot URDF ...
 *   mpb-bench-fidelity stats [--boot N] FILE
 *   mpb-bench-fidelity seeds EXPERIMENT_SEED N
 *   mpb-bench-fidelity apart-worker --robot URDF ...   (the apart side's
 *                      process: fidelity_apart.h)
 *
 * The problem is built as mpb-planner-ompl builds it for a request: the
 * world's joints as a real vector space (continuous joints wrap), validity
 * from mpb_world_in_collision(), motions checked every --resolution rad,
 * the goal a joint configuration with a tolerance, RRTConnect with its
 * default range, no simplification. Each run is seeded as the planner seeds
 * a request: ompl::RNG::setSeed with the run's seed, then the same objects
 * made in the same order, so that the state sampler gets the same seed and
 * a run of a seed is the same run on every side (its graph states, printed,
 * show it).
 *
 * `run` prints one line per run:
 *   RUN SIDE BLOCK SEED SECONDS SOLVED VERIFIED GRAPH_STATES
 * (VERIFIED is "-" here; bench/fidelity.sh writes mpbench's runs, from the
 * database, in the same form). `pace` prints the same lines, for each run
 * mpbenchd sends the planner process meanwhile, right after it
 * (fidelity_pace.h). `stats` reads such lines and compares the
 * median solve times of the solved runs, side against side.
 */
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "fidelity_apart.h"
#include "fidelity_pace.h"
#include "joint_space.h"
#include "mpbench/mpbench.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace ot = ompl::tools;

namespace {

// ---- the problem, as mpb-planner-ompl builds it ----------------------------

// The world's joints, continuous ones wrapping: mpb-planner-ompl's own
// space (planners/ompl/joint_space.h), so that both plan in the same one.
using Joints = mpb_ompl::JointSpace;

struct Query {
    mpb_world *world;
    std::vector<double> start, goal;    // the world's joint order
    double tolerance, resolution, time_limit;
};

// One request's problem, made in mpb-planner-ompl's order: the space, its
// information with the validity checker (bounds, then the world; the
// planner process adds a mutex and a counter), the motion step, setup (its
// random projection draws a seed), start and goal (continuous joints
// wrapped), the problem definition.
struct Problem {
    std::shared_ptr<Joints> space;
    ob::SpaceInformationPtr si;
    ob::ProblemDefinitionPtr pdef;
};

Problem make_problem(const Query &q)
{
    Problem p;
    p.space = std::make_shared<Joints>(q.world);
    p.si = std::make_shared<ob::SpaceInformation>(p.space);
    mpb_world *world = q.world;
    Joints *sp = p.space.get();
    p.si->setStateValidityChecker([world, sp](const ob::State *s) {
        return sp->satisfiesBounds(s) &&
               mpb_world_in_collision(
                   world, s->as<ob::RealVectorStateSpace::StateType>()->values) == 0;
    });
    p.si->setStateValidityCheckingResolution(
        std::min(q.resolution / p.space->getMaximumExtent(), 0.5));
    p.si->setup();
    ob::ScopedState<> s0(p.space), s1(p.space);
    for (size_t j = 0; j < q.start.size(); j++) {
        bool wraps = mpb_world_joint_is_continuous(world, static_cast<int>(j)) != 0;
        s0[j] = wraps ? std::remainder(q.start[j], 2 * M_PI) : q.start[j];
        s1[j] = wraps ? std::remainder(q.goal[j], 2 * M_PI) : q.goal[j];
    }
    p.pdef = std::make_shared<ob::ProblemDefinition>(p.si);
    p.pdef->setStartAndGoalStates(s0, s1, q.tolerance);
    return p;
}

// As mpb-planner-ompl seeds a request (32 bits, never 0).
void seed_run(const std::string &seed)
{
    std::uint64_t u = static_cast<std::uint64_t>(std::strtoll(seed.c_str(), nullptr, 10));
    std::uint32_t s = static_cast<std::uint32_t>(u ^ (u >> 32));
    ompl::RNG::setSeed(s != 0 ? s : 0x9e3779b9u);
}

struct Run {
    double secs;
    bool solved;
    unsigned graph_states;
    double inner = NAN;     // ompl and thread sides: the solve() inside
};

// RRTConnect whose solve(ptc) times itself: the planner's own time, without
// the start and join of OMPL's time-limit thread that Planner::solve(fn,
// period), and with it Benchmark's stopwatch, holds around it.
class TimedRRTConnect : public og::RRTConnect {
public:
    using og::RRTConnect::RRTConnect;
    using og::RRTConnect::solve;
    ob::PlannerStatus solve(const ob::PlannerTerminationCondition &ptc) override
    {
        const double t0 = mpb_monotonic_s();
        ob::PlannerStatus st = og::RRTConnect::solve(ptc);
        last_secs = mpb_monotonic_s() - t0;
        return st;
    }
    double last_secs = NAN;
};

// A bare run: the request's objects made anew, the planner set up, then
// solve() alone timed, its time limit checked inline at each iteration (no
// thread), as mpb-planner-ompl does. With period > 0, the time limit is
// checked as Benchmark has it checked (Planner::solve(fn, period)): by a
// thread that OMPL starts, wakes every millisecond and joins inside the
// solve() timed; the run's inner time is then the planner's solve() alone.
Run plain_run(const Query &q, const std::string &seed, double period = 0)
{
    seed_run(seed);
    Problem p = make_problem(q);
    auto planner = std::make_shared<TimedRRTConnect>(p.si);
    planner->setProblemDefinition(p.pdef);
    planner->setup();
    const double t0 = mpb_monotonic_s(), deadline = t0 + q.time_limit;
    auto expired = [deadline] { return mpb_monotonic_s() >= deadline; };
    ob::PlannerStatus st =
        period > 0 ? static_cast<ob::Planner &>(*planner).solve(expired, period)
                   : planner->solve(ob::PlannerTerminationCondition(expired));
    const double secs = mpb_monotonic_s() - t0;
    ob::PlannerData data(p.si);
    planner->getPlannerData(data);
    return {secs, st == ob::PlannerStatus::EXACT_SOLUTION, data.numVertices(),
            period > 0 ? planner->last_secs : NAN};
}

// OMPL's own Benchmark, one run per seed. It is kept from one call to the
// next (pace asks for one seed at a time) and keeps one planner, which it
// clears between runs; before each run the pre-run event seeds OMPL and
// makes (and drops) the objects the planner process makes before its
// solve(), so that the sampler solve() allocates gets the same seed there
// and here. Benchmark's "time" is what it reports: solve() and the
// termination condition's thread around it.
class BenchmarkSide {
public:
    explicit BenchmarkSide(const Query &q) : q_(q), p_(make_problem(q))
    {
        ss_ = std::make_unique<og::SimpleSetup>(p_.si);
        ss_->getProblemDefinition()->addStartState(p_.pdef->getStartState(0));
        ss_->setGoal(p_.pdef->getGoal());
        ss_->setPlanner(std::make_shared<og::RRTConnect>(p_.si));
        ss_->setup();
        b_ = std::make_unique<ot::Benchmark>(*ss_, "mpbench-fidelity");
        timed_ = std::make_shared<TimedRRTConnect>(p_.si);
        b_->addPlanner(timed_);
        b_->setPostRunEvent([this](const ob::PlannerPtr &, ot::Benchmark::RunProperties &) {
            inner_.push_back(timed_->last_secs);
        });
        b_->setPreRunEvent([this](const ob::PlannerPtr &) {
            seed_run((*seeds_)[next_++ % seeds_->size()]);
            Problem twin = make_problem(q_);
            og::RRTConnect draws(twin.si);
            draws.setProblemDefinition(twin.pdef);
            draws.setup();
        });
    }

    std::vector<Run> runs(const std::vector<std::string> &seeds)
    {
        seeds_ = &seeds;
        next_ = 0;
        inner_.clear();
        ot::Benchmark::Request req(q_.time_limit, 4096.0, static_cast<unsigned>(seeds.size()),
                                   0.05, false, false, false);
        b_->benchmark(req);
        std::vector<Run> out;
        for (const auto &pe : b_->getRecordedExperimentData().planners)
            for (const auto &r : pe.runs) {
                auto get = [&r](const char *key) {
                    auto it = r.find(key);
                    return it != r.end() ? it->second : std::string();
                };
                bool exact = get("solved BOOLEAN") == "1" &&
                             get("approximate solution BOOLEAN") != "1";
                std::string t = get("time REAL");
                size_t i = out.size();
                out.push_back({t.empty() ? NAN : std::strtod(t.c_str(), nullptr), exact,
                               static_cast<unsigned>(std::strtoul(
                                   get("graph states INTEGER").c_str(), nullptr, 10)),
                               i < inner_.size() ? inner_[i] : NAN});
            }
        return out;
    }

private:
    Query q_;
    Problem p_;
    std::unique_ptr<og::SimpleSetup> ss_;
    std::unique_ptr<ot::Benchmark> b_;
    std::shared_ptr<TimedRRTConnect> timed_;
    std::vector<double> inner_;     // each run's solve(), in order
    const std::vector<std::string> *seeds_ = nullptr;
    size_t next_ = 0;
};

// ---- statistics ------------------------------------------------------------

double median(std::vector<double> v)
{
    if (v.empty())
        return NAN;
    size_t n = v.size(), h = n / 2;
    std::nth_element(v.begin(), v.begin() + static_cast<long>(h), v.end());
    double hi = v[h];
    if (n % 2)
        return hi;
    return 0.5 * (*std::max_element(v.begin(), v.begin() + static_cast<long>(h)) + hi);
}

// The p-quantile of sorted values (linear between order statistics).
double quantile(const std::vector<double> &sorted, double p)
{
    if (sorted.empty())
        return NAN;
    double x = p * static_cast<double>(sorted.size() - 1);
    size_t i = static_cast<size_t>(x);
    if (i + 1 >= sorted.size())
        return sorted.back();
    return sorted[i] + (x - static_cast<double>(i)) * (sorted[i + 1] - sorted[i]);
}

struct Line {
    std::string side;
    int block;
    std::string seed;
    double secs;
    bool solved;
    int verified;       // -1: not known
    long graph_states;
};

// One side's runs, by block.
struct Side {
    std::map<int, std::vector<double>> times;     // solved runs only
    int runs = 0, solved = 0, verified = 0, verified_known = 0;
    // Solved runs by block and seed: time, graph states.
    std::map<std::pair<int, std::string>, std::pair<double, long>> by_seed;
};

std::string fmt(double v, int prec = 4)
{
    if (!std::isfinite(v))
        return "nan";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", prec, v);
    return buf;
}

std::vector<double> pooled(const Side &s)
{
    std::vector<double> v;
    for (const auto &b : s.times)
        v.insert(v.end(), b.second.begin(), b.second.end());
    return v;
}

// A resample of a side: each block's solved times drawn with replacement,
// as many as it has, pooled.
void resample_within(const Side &s, std::mt19937_64 &rng, std::vector<double> &out)
{
    out.clear();
    for (const auto &b : s.times) {
        const std::vector<double> &v = b.second;
        if (v.empty())
            continue;
        std::uniform_int_distribution<size_t> pick(0, v.size() - 1);
        for (size_t i = 0; i < v.size(); i++)
            out.push_back(v[pick(rng)]);
    }
}

// Is the difference of two success rates within noise? Within 1.96
// standard errors of the pooled rate (and equal rates always are).
const char *same_rate(int s1, int n1, int s2, int n2)
{
    if (n1 == 0 || n2 == 0)
        return "not measured";
    double p1 = double(s1) / n1, p2 = double(s2) / n2, p = double(s1 + s2) / (n1 + n2);
    double se = std::sqrt(p * (1 - p) * (1.0 / n1 + 1.0 / n2));
    return std::fabs(p1 - p2) <= 1.96 * se ? "same" : "different";
}

// "met" when the interval lies inside [lo_ok, hi_ok], "missed" when
// outside it, else "not_settled".
const char *verdict(double lo, double hi, double lo_ok, double hi_ok)
{
    if (!std::isfinite(lo) || !std::isfinite(hi))
        return "not_measured";
    if (lo >= lo_ok && hi <= hi_ok)
        return "met";
    if (hi < lo_ok || lo > hi_ok)
        return "missed";
    return "not_settled";
}

// Side a against side b: the ratio of the pooled medians of the solved
// runs (a / b), its bootstrap 95 % interval resampling the runs within each
// side (and block), the median of the blocks' own ratios, the interval of
// a resampling of whole blocks (the noise that hits a block of one side at
// once), and the runs of the same seed on both sides: how many did the same
// work (the same graph), the median of their time ratios.
void compare(const char *key, const char *a_name, const Side &a, const char *b_name,
             const Side &b, int boots, double lo_ok, double hi_ok)
{
    std::vector<double> pa = pooled(a), pb = pooled(b);
    double ma = median(pa), mb = median(pb), ratio = ma / mb;

    std::mt19937_64 rng(20261123);
    std::vector<double> ra, rb, boot;
    for (int i = 0; i < boots; i++) {
        resample_within(a, rng, ra);
        resample_within(b, rng, rb);
        boot.push_back(median(ra) / median(rb));
    }
    std::sort(boot.begin(), boot.end());
    double lo = quantile(boot, 0.025), hi = quantile(boot, 0.975);

    std::vector<int> blocks;
    std::vector<double> block_ratios;
    for (const auto &blk : a.times) {
        auto it = b.times.find(blk.first);
        if (it == b.times.end() || blk.second.empty() || it->second.empty())
            continue;
        blocks.push_back(blk.first);
        block_ratios.push_back(median(blk.second) / median(it->second));
    }
    std::vector<double> sorted_br = block_ratios;
    std::sort(sorted_br.begin(), sorted_br.end());

    std::vector<double> bboot;
    if (!blocks.empty()) {
        std::uniform_int_distribution<size_t> pick(0, blocks.size() - 1);
        for (int i = 0; i < boots; i++) {
            ra.clear();
            rb.clear();
            for (size_t k = 0; k < blocks.size(); k++) {
                int blk = blocks[pick(rng)];
                const std::vector<double> &va = a.times.at(blk), &vb = b.times.at(blk);
                ra.insert(ra.end(), va.begin(), va.end());
                rb.insert(rb.end(), vb.begin(), vb.end());
            }
            bboot.push_back(median(ra) / median(rb));
        }
        std::sort(bboot.begin(), bboot.end());
    }

    // The seeds solved on both sides, by block: a's and b's times.
    int paired = 0, same_graph = 0;
    std::vector<double> seed_ratios, seed_diffs;
    std::map<int, std::vector<std::pair<double, double>>> pairs;
    for (const auto &s : a.by_seed) {
        auto it = b.by_seed.find(s.first);
        if (it == b.by_seed.end())
            continue;
        paired++;
        pairs[s.first.first].push_back({s.second.first, it->second.first});
        if (s.second.second == it->second.second) {
            same_graph++;
            seed_ratios.push_back(s.second.first / it->second.first);
            seed_diffs.push_back(s.second.first - it->second.first);
        }
    }
    // The same ratio of medians, the seeds resampled within each block with
    // both sides' runs of a seed kept together: a seed's own difficulty, the
    // same on both sides, is then no noise of the comparison.
    std::vector<double> pboot;
    if (!pairs.empty()) {
        for (int i = 0; i < boots; i++) {
            ra.clear();
            rb.clear();
            for (const auto &blk : pairs) {
                const auto &v = blk.second;
                std::uniform_int_distribution<size_t> pick(0, v.size() - 1);
                for (size_t k = 0; k < v.size(); k++) {
                    const auto &ab = v[pick(rng)];
                    ra.push_back(ab.first);
                    rb.push_back(ab.second);
                }
            }
            pboot.push_back(median(ra) / median(rb));
        }
        std::sort(pboot.begin(), pboot.end());
    }

    double plo = quantile(pboot, 0.025), phi = quantile(pboot, 0.975);
    double blo = quantile(bboot, 0.025), bhi = quantile(bboot, 0.975);
    double brmin = sorted_br.empty() ? NAN : sorted_br.front();
    double brmax = sorted_br.empty() ? NAN : sorted_br.back();
    // The verdict is the paired interval's: a seed is the same run on both
    // sides, so its difficulty (1 to 4 ms in the kitchen, 10 to 400 ms in
    // the narrow passage) is no noise of the comparison; resampling each
    // side alone counts it twice.
    const char *v = verdict(lo, hi, lo_ok, hi_ok), *pv = verdict(plo, phi, lo_ok, hi_ok);
    std::printf("%s / %s: median solve time (solved runs) %.3f / %.3f ms, ratio %.4f\n"
                "  95 %% CI %.4f-%.4f (runs resampled within each side and block: %s)\n"
                "  95 %% CI %.4f-%.4f (seeds resampled, both sides together): %s\n"
                "  95 %% CI %.4f-%.4f (whole blocks resampled)\n"
                "  the %zu blocks' own ratios: median %.4f, %.4f-%.4f\n"
                "  %d of %d seeds solved on both sides made the same graph; the "
                "median of their time ratios %.4f, of their differences %+.0f us\n",
                a_name, b_name, ma * 1e3, mb * 1e3, ratio, lo, hi, v, plo, phi, pv, blo, bhi,
                block_ratios.size(), median(block_ratios), brmin, brmax, same_graph, paired,
                median(seed_ratios), median(seed_diffs) * 1e6);
    std::printf("RESULT %s blocks=%zu runs_a=%d solved_a=%d runs_b=%d solved_b=%d "
                "success=%s median_a_s=%s median_b_s=%s ratio=%s ci_lo=%s ci_hi=%s "
                "runs_verdict=%s paired_lo=%s paired_hi=%s verdict=%s "
                "blockboot_lo=%s blockboot_hi=%s block_ratio_median=%s "
                "block_ratio_min=%s block_ratio_max=%s seeds_paired=%d "
                "seeds_same_graph=%d seed_ratio_median=%s seed_diff_median_us=%s\n",
                key, block_ratios.size(), a.runs, a.solved, b.runs, b.solved,
                same_rate(a.solved, a.runs, b.solved, b.runs), fmt(ma, 6).c_str(),
                fmt(mb, 6).c_str(), fmt(ratio).c_str(), fmt(lo).c_str(), fmt(hi).c_str(), v,
                fmt(plo).c_str(), fmt(phi).c_str(), pv, fmt(blo).c_str(), fmt(bhi).c_str(),
                fmt(median(block_ratios)).c_str(), fmt(brmin).c_str(), fmt(brmax).c_str(),
                paired, same_graph, fmt(median(seed_ratios)).c_str(),
                fmt(median(seed_diffs) * 1e6, 1).c_str());
}

int stats(int argc, char **argv)
{
    int boots = 2000;
    const char *file = nullptr;
    for (int i = 0; i < argc; i++) {
        if (!std::strcmp(argv[i], "--boot") && i + 1 < argc)
            boots = std::atoi(argv[++i]);
        else if (file == nullptr && argv[i][0] != '-')
            file = argv[i];
        else
            return 2;
    }
    if (file == nullptr || boots < 100)
        return 2;
    FILE *f = std::fopen(file, "r");
    if (f == nullptr) {
        std::fprintf(stderr, "mpb-bench-fidelity: cannot open %s\n", file);
        return 1;
    }
    std::map<std::string, Side> sides;
    char buf[512];
    while (std::fgets(buf, sizeof buf, f)) {
        char side[32], seed[32], verified[8];
        int block, solved;
        double secs;
        long graph;
        if (std::sscanf(buf, "RUN %31s %d %31s %lf %d %7s %ld", side, &block, seed, &secs,
                        &solved, verified, &graph) != 7)
            continue;
        Side &s = sides[side];
        s.runs++;
        if (verified[0] != '-') {
            s.verified_known++;
            s.verified += std::atoi(verified) != 0;
        }
        if (solved && std::isfinite(secs)) {
            s.solved++;
            s.times[block].push_back(secs);
            s.by_seed[{block, seed}] = {secs, graph};
        } else {
            s.times[block];     // a block with no solved run is still a block
        }
    }
    std::fclose(f);
    for (const auto &s : sides)
        std::printf("RESULT fidelity_side_%s runs=%d solved=%d verified=%s blocks=%zu\n",
                    s.first.c_str(), s.second.runs, s.second.solved,
                    s.second.verified_known ? std::to_string(s.second.verified).c_str() : "-",
                    s.second.times.size());
    const Side &m = sides["mpbench"], &o = sides["ompl"], &p = sides["plain"];
    // Sides a file has no run of (a run of mpb-bench-fidelity alone has
    // no mpbench side) are not compared.
    if (m.runs > 0) {
        compare("fidelity_ompl", "mpbench", m, "OMPL Benchmark", o, boots, 0.97, 1.03);
        compare("fidelity_plain", "mpbench", m, "bare solve()", p, boots, 0.97, 1.03);
    }
    if (o.runs > 0)
        compare("fidelity_bench_plain", "OMPL Benchmark", o, "bare solve()", p, boots, 0.97,
                1.03);
    // Benchmark's "time" holds its planner's solve() and, around it, the
    // start and the join of OMPL's time-limit thread: its planner's own
    // solve(), timed inside Benchmark, is the time Benchmark itself
    // measures of the planner.
    if (sides.count("ompl_solve")) {
        const Side &os = sides["ompl_solve"];
        compare("fidelity_ompl_solve", "mpbench", m, "solve() inside OMPL Benchmark", os, boots,
                0.97, 1.03);
        compare("fidelity_solve_plain", "solve() inside OMPL Benchmark", os, "bare solve()", p,
                boots, 0.97, 1.03);
        compare("fidelity_bench_solve", "OMPL Benchmark", o, "solve() inside it", os, boots,
                0.97, 1.03);
    }
    // The apart side plans as bare as the plain side, but in a process of
    // its own that waits between runs, as mpbench's planner process does:
    // what mpbench reads over it is mpbench's own.
    if (sides.count("apart")) {
        const Side &ap = sides["apart"];
        if (m.runs > 0)
            compare("fidelity_apart", "mpbench", m, "bare solve() apart", ap, boots, 0.97, 1.03);
        compare("fidelity_apart_plain", "bare solve() apart", ap, "bare solve()", p, boots, 0.97,
                1.03);
    }
    if (sides.count("thread")) {
        const Side &t = sides["thread"];
        compare("fidelity_thread_plain", "solve() with Benchmark's time-limit thread", t,
                "bare solve()", p, boots, 0.97, 1.03);
        compare("fidelity_bench_thread", "OMPL Benchmark", o,
                "solve() with Benchmark's time-limit thread", t, boots, 0.97, 1.03);
        compare("fidelity_thread_solve_plain", "solve() inside, with the thread", sides["thread_solve"],
                "bare solve()", p, boots, 0.97, 1.03);
    }
    return 0;
}

// ---- seeds -----------------------------------------------------------------

// The seeds mpbenchd gives the first n runs of an experiment of one planner
// configuration and one query: daemon/experiment.c's mpbd_run_seed(), so
// that the in-process sides can run a block's seeds before mpbenchd has
// drawn them (bench/fidelity.sh checks them against the database after).
std::uint64_t mix(std::uint64_t x)
{
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

int seeds(int argc, char **argv)
{
    if (argc != 2)
        return 2;
    char *end;
    long long e = std::strtoll(argv[0], &end, 10);
    long n = std::strtol(argv[1], nullptr, 10);
    if (*end != '\0' || n < 1)
        return 2;
    for (long r = 0; r < n; r++) {
        std::uint64_t h = mix(static_cast<std::uint64_t>(e));
        h = mix(h ^ 0);     // the configuration
        h = mix(h ^ 0);     // the query
        h = mix(h ^ static_cast<std::uint64_t>(r));
        std::printf("%s%lld", r ? "," : "", static_cast<long long>(h & 0x7fffffff));
    }
    std::printf("\n");
    return 0;
}

// ---- run -------------------------------------------------------------------

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

void usage(FILE *out)
{
    std::fprintf(out,
"usage: mpb-bench-fidelity run --robot URDF --scene SCENE --joints A,B,...\n"
"                          --start Q --goal Q --seeds S1,S2,... [options]\n"
"       mpb-bench-fidelity pace --planner-pid PID --runs N --robot URDF\n"
"                          --scene SCENE --joints A,B,... --start Q --goal Q\n"
"                          [options]\n"
"       mpb-bench-fidelity stats [--boot N] FILE\n"
"       mpb-bench-fidelity seeds EXPERIMENT_SEED N\n"
"\n"
"run: plans start -> goal (joint values, comma-separated, in --joints order)\n"
"with RRTConnect once per seed on each side asked for, in order, and prints\n"
"  RUN SIDE BLOCK SEED SECONDS SOLVED - GRAPH_STATES\n"
"per run. Sides: \"ompl\" (OMPL's Benchmark, its \"time\"), \"plain\" (a bare\n"
"solve(), timed alone, as mpb-planner-ompl times it), \"thread\" (as plain,\n"
"the time limit checked by OMPL's thread, every 0.1 s, as Benchmark has it),\n"
"\"apart\" (as plain, in a process of its own that waits on a pipe between\n"
"runs, as a planner process waits for its next request, with no LCM and\n"
"no daemon: this program again, as apart-worker).\n"
"The ompl and thread sides also print SIDE_solve lines: the planner's\n"
"solve() timed inside, without the thread's start and join around it.\n"
"  --sides A,B      default ompl,plain\n"
"  --interleave run each seed on every side in turn (A,B then B,A), not\n"
"                   each side's seeds one after the other (block, default)\n"
"  --block K        the block number printed (default 0)\n"
"  --warmup N       runs of the first seeds on each side first, not printed\n"
"                   (default 5)\n"
"  --gap-us N       sleep N us after each run, as a planner process\n"
"                   waits for its next request (a diagnostic; block only)\n"
"  --time-limit S   per run (default 10)\n"
"  --tolerance RAD  goal tolerance (default 0.01)\n"
"  --resolution RAD motion checks, as mpb-planner-ompl (default 0.01)\n"
"\n"
"pace: the same sides run by run with a benchmark that runs meanwhile\n"
"through mpbenchd and the planner process PID (one planner, on this CPU):\n"
"for each of the next N results on LCM, holds the planner (SIGSTOP), waits\n"
"without sleeping until mpbenchd has stored the result, runs that run's\n"
"seed on each side (in turns: A,B then B,A), lets the planner go on\n"
"(SIGCONT). RUN lines as run's, for all but the first --warmup runs; LATE\n"
"lines name the runs the planner may have started before it was held, LONG\n"
"lines those it took more than --max-run-s for (default 0.3 s; their sides\n"
"would hold it so long that mpbenchd takes it for gone): none of their\n"
"sides run, leave them out of mpbench's. A RESULT line counts. --block,\n"
"--sides, --warmup, --time-limit, --tolerance and --resolution as for run;\n"
"--url URL the LCM URL (default mpbench's). It sends nothing, but joins\n"
"the LCM group: run it only inside a private network namespace, as\n"
"bench/fidelity.sh does.\n"
"\n"
"stats: the RUN lines of FILE (sides mpbench, ompl, plain; ompl_solve,\n"
"thread and apart when there), side against side: the ratio of the median solve\n"
"times of the solved runs, its bootstrap 95 %% intervals (N resamples,\n"
"default 2000), the blocks' own ratios, the median per-seed ratio and\n"
"difference, the success rates; RESULT lines.\n"
"\n"
"seeds: the seeds mpbenchd gives the first N runs of an experiment of one\n"
"planner configuration and one query, comma-separated.\n");
}

// What run, pace and the apart worker share: the problem and the sides.
struct Setup {
    Query q{};
    std::vector<std::string> seeds, sides;
    std::vector<std::string> problem_args;     // for the apart worker
    int block = 0, warmup = 5, gap_us = 0;
    bool by_run = false;                // run: --interleave run
    long planner_pid = 0, runs = 0;     // pace
    double max_run_s = 0.3;             // pace
    std::string url;                    // pace
};

enum class Mode { run, pace, apart_worker };

// Parses the options of `run`, `pace` or `apart-worker` and opens the
// world. Returns 0, 1 (a message printed) or 2 (usage).
int setup(int argc, char **argv, Mode mode, Setup &o)
{
    const bool pace = mode == Mode::pace, worker = mode == Mode::apart_worker;
    const char *robot_file = nullptr, *scene_file = nullptr;
    std::string joints_arg, start_arg, goal_arg, seeds_arg, sides_arg = "ompl,plain";
    double time_limit = 10, tolerance = 0.01, resolution = 0.01;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : nullptr;
        if (v == nullptr)
            return 2;
        i++;
        static const char *const problem[] = {"--robot", "--scene", "--joints", "--start",
                                              "--goal", "--time-limit", "--tolerance",
                                              "--resolution"};
        for (const char *opt : problem)
            if (!std::strcmp(a, opt)) {
                o.problem_args.push_back(a);
                o.problem_args.push_back(v);
            }
        if (!std::strcmp(a, "--robot")) robot_file = v;
        else if (!std::strcmp(a, "--scene")) scene_file = v;
        else if (!std::strcmp(a, "--joints")) joints_arg = v;
        else if (!std::strcmp(a, "--start")) start_arg = v;
        else if (!std::strcmp(a, "--goal")) goal_arg = v;
        else if (!std::strcmp(a, "--sides")) sides_arg = v;
        else if (!std::strcmp(a, "--block")) o.block = std::atoi(v);
        else if (!std::strcmp(a, "--warmup")) o.warmup = std::atoi(v);
        else if (!std::strcmp(a, "--time-limit")) time_limit = std::atof(v);
        else if (!std::strcmp(a, "--tolerance")) tolerance = std::atof(v);
        else if (!std::strcmp(a, "--resolution")) resolution = std::atof(v);
        else if (mode == Mode::run && !std::strcmp(a, "--seeds")) seeds_arg = v;
        else if (mode == Mode::run && !std::strcmp(a, "--gap-us")) o.gap_us = std::atoi(v);
        else if (mode == Mode::run && !std::strcmp(a, "--interleave")) {
            if (std::strcmp(v, "run") && std::strcmp(v, "block"))
                return 2;
            o.by_run = !std::strcmp(v, "run");
        }
        else if (pace && !std::strcmp(a, "--planner-pid")) o.planner_pid = std::atol(v);
        else if (pace && !std::strcmp(a, "--runs")) o.runs = std::atol(v);
        else if (pace && !std::strcmp(a, "--url")) o.url = v;
        else if (pace && !std::strcmp(a, "--max-run-s")) o.max_run_s = std::atof(v);
        else return 2;
    }
    std::vector<std::string> names = split(joints_arg);
    o.seeds = split(seeds_arg);
    o.sides = split(sides_arg);
    o.q = Query{nullptr, numbers(start_arg), numbers(goal_arg), tolerance, resolution,
                time_limit};
    bool sides_ok = !o.sides.empty();
    for (const std::string &s : o.sides)
        sides_ok = sides_ok && (s == "ompl" || s == "plain" || s == "thread" || s == "apart");
    bool what_ok = pace     ? o.planner_pid > 0 && o.runs > 0 && o.max_run_s > 0
                   : worker ? true
                            : !o.seeds.empty() && !(o.by_run && o.gap_us > 0);
    if (!robot_file || !scene_file || names.empty() || o.q.start.size() != names.size() ||
        o.q.goal.size() != names.size() || !what_ok || !(time_limit > 0) ||
        !(resolution > 0) || !sides_ok || o.warmup < 0)
        return 2;
    std::string robot = slurp(robot_file), scene = slurp(scene_file);
    std::vector<const char *> cnames;
    for (const std::string &n : names)
        cnames.push_back(n.c_str());
    char err[256] = "";
    if (robot.empty() ||
        mpb_world_open_group("urdf", robot.c_str(), "moveit-scene", scene.c_str(),
                             cnames.data(), static_cast<int>(cnames.size()),
                             &o.q.world, err, sizeof err) != MPB_OK) {
        std::fprintf(stderr, "mpb-bench-fidelity: cannot open the world: %s\n",
                     robot.empty() ? "cannot read the robot" : err);
        return 1;
    }
    // Re-seeding after the first draw is what makes the runs repeatable
    // (OMPL 1.5 re-seeds its seed generator); its warning is expected.
    ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
    return 0;
}

// A run's RUN line; for the sides with OMPL's time-limit thread (ompl,
// thread), a second line for the solve() inside, side name + "_solve".
void print_run(const std::string &side, int block, const std::string &seed, const Run &r)
{
    std::printf("RUN %s %d %s %.9f %d - %u\n", side.c_str(), block, seed.c_str(), r.secs,
                r.solved ? 1 : 0, r.graph_states);
    if (!std::isnan(r.inner))
        std::printf("RUN %s_solve %d %s %.9f %d - %u\n", side.c_str(), block, seed.c_str(),
                    r.inner, r.solved ? 1 : 0, r.graph_states);
}

// A bare run's answer line from the apart worker: "SECONDS SOLVED GRAPH_STATES".
std::string apart_answer(const Run &r)
{
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.9f %d %u", r.secs, r.solved ? 1 : 0, r.graph_states);
    return buf;
}

// One run of a seed on a side; Benchmark is kept from one call to the next,
// and so is the apart worker, started at its side's first run.
class Sides {
public:
    Sides(const Query &q, const std::vector<std::string> &problem_args)
        : q_(q), problem_args_(problem_args), bench_(q) {}

    Run one(const std::string &side, const std::string &seed)
    {
        if (side == "ompl")
            return bench_.runs({seed}).at(0);
        if (side == "apart")
            return apart(seed);
        return plain_run(q_, seed, side == "thread" ? 0.1 : 0);
    }

    std::vector<Run> many(const std::string &side, const std::vector<std::string> &seeds)
    {
        if (side == "ompl")
            return bench_.runs(seeds);
        std::vector<Run> out;
        for (const std::string &s : seeds)
            out.push_back(one(side, s));
        return out;
    }

private:
    // A bare solve() in the worker process; the worker's time, as it timed
    // it. A worker that cannot start or answer ends this program: the
    // comparison would be one side short.
    Run apart(const std::string &seed)
    {
        if (!apart_) {
            std::vector<std::string> args{"apart-worker"};
            args.insert(args.end(), problem_args_.begin(), problem_args_.end());
            apart_ = std::make_unique<mpb_fidelity::ApartProcess>();
            if (!apart_->start(args))
                std::exit(1);
        }
        std::string answer;
        Run r{NAN, false, 0};
        int solved = 0;
        if (!apart_->ask(seed, &answer) ||
            std::sscanf(answer.c_str(), "%lf %d %u", &r.secs, &solved, &r.graph_states) != 3) {
            std::fprintf(stderr, "mpb-bench-fidelity: no answer from the apart worker for "
                         "seed %s\n", seed.c_str());
            std::exit(1);
        }
        r.solved = solved != 0;
        return r;
    }

    const Query &q_;
    const std::vector<std::string> &problem_args_;
    BenchmarkSide bench_;
    std::unique_ptr<mpb_fidelity::ApartProcess> apart_;
};

int run(int argc, char **argv)
{
    Setup o;
    int rc = setup(argc, argv, Mode::run, o);
    if (rc != 0)
        return rc;
    const std::vector<std::string> &seeds = o.seeds;
    std::vector<std::string> warm(seeds.begin(),
                                  seeds.begin() + std::min<size_t>(seeds.size(),
                                                                   static_cast<size_t>(o.warmup)));
    Sides sides(o.q, o.problem_args);
    std::map<std::string, std::vector<Run>> runs;
    for (const std::string &side : o.sides)
        sides.many(side, warm);
    if (o.by_run) {
        // Each seed on every side in turn (A,B then B,A): the sides' runs
        // of a seed milliseconds apart, so the machine's drift cancels.
        for (size_t i = 0; i < seeds.size(); i++) {
            std::vector<std::string> order = o.sides;
            if (i % 2)
                std::reverse(order.begin(), order.end());
            for (const std::string &side : order)
                runs[side].push_back(sides.one(side, seeds[i]));
        }
    } else {
        for (const std::string &side : o.sides) {
            if (o.gap_us <= 0) {
                runs[side] = sides.many(side, seeds);
                continue;
            }
            for (const std::string &s : seeds) {
                runs[side].push_back(sides.one(side, s));
                // A pause between runs, as a planner process has while the
                // daemon verifies, stores and sends the next request.
                usleep(static_cast<useconds_t>(o.gap_us));
            }
        }
    }
    for (const std::string &side : o.sides) {
        const std::vector<Run> &v = runs[side];
        int solved = 0;
        std::vector<double> times;
        for (size_t r = 0; r < v.size(); r++) {
            print_run(side, o.block, seeds[r], v[r]);
            if (v[r].solved) {
                solved++;
                times.push_back(v[r].secs);
            }
        }
        std::fprintf(stderr, "mpb-bench-fidelity: block %d, %s: %zu runs, %d solved, "
                     "median %.3f ms\n", o.block, side.c_str(), v.size(), solved,
                     median(times) * 1e3);
    }
    mpb_world_close(o.q.world);
    return 0;
}

int pace(int argc, char **argv)
{
    Setup o;
    int rc = setup(argc, argv, Mode::pace, o);
    if (rc != 0)
        return rc;
    Sides sides(o.q, o.problem_args);
    mpb_fidelity::PaceOptions opt;
    opt.planner = static_cast<pid_t>(o.planner_pid);
    opt.runs = o.runs;
    opt.max_run_s = o.max_run_s;
    opt.lcm_url = o.url.empty() ? nullptr : o.url.c_str();
    mpb_fidelity::PaceReport report;
    rc = mpb_fidelity::pace(opt, [&](long index, const std::string &seed) {
        // The sides in turns, so that neither always comes first after
        // the planner's run.
        std::vector<std::string> order = o.sides;
        if (index % 2)
            std::reverse(order.begin(), order.end());
        for (const std::string &side : order) {
            Run r = sides.one(side, seed);
            if (index >= o.warmup)
                print_run(side, o.block, seed, r);
        }
        std::fflush(stdout);
    }, &report);
    if (rc != 0 && report.paced == 0) {
        mpb_world_close(o.q.world);
        return rc;
    }
    for (const std::string &seed : report.late_seeds)
        std::printf("LATE %d %s\n", o.block, seed.c_str());
    for (const std::string &seed : report.long_seeds)
        std::printf("LONG %d %s\n", o.block, seed.c_str());
    std::printf("RESULT fidelity_pace block=%d paced=%ld late=%zu long=%zu max_hold_ms=%.1f\n",
                o.block, report.paced, report.late_seeds.size(), report.long_seeds.size(),
                report.max_hold_s * 1e3);
    std::fprintf(stderr, "mpb-bench-fidelity pace: block %d: %ld runs paced, %zu late, "
                 "%zu long, the planner held at most %.1f ms\n", o.block, report.paced,
                 report.late_seeds.size(), report.long_seeds.size(), report.max_hold_s * 1e3);
    mpb_world_close(o.q.world);
    return rc;
}

// The apart side's process (fidelity_apart.h): a bare solve() of each seed
// it is sent, in its own copy of the world.
int apart_worker(int argc, char **argv)
{
    Setup o;
    int rc = setup(argc, argv, Mode::apart_worker, o);
    if (rc != 0)
        return rc;
    rc = mpb_fidelity::apart_serve(
        [&o](const std::string &seed) { return apart_answer(plain_run(o.q, seed)); });
    mpb_world_close(o.q.world);
    return rc;
}

} // namespace

int main(int argc, char **argv)
{
    if (argc >= 2 && (!std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h"))) {
        usage(stdout);
        return 0;
    }
    int rc = 2;
    if (argc >= 2 && !std::strcmp(argv[1], "run"))
        rc = run(argc - 2, argv + 2);
    else if (argc >= 2 && !std::strcmp(argv[1], "pace"))
        rc = pace(argc - 2, argv + 2);
    else if (argc >= 2 && !std::strcmp(argv[1], "stats"))
        rc = stats(argc - 2, argv + 2);
    else if (argc >= 2 && !std::strcmp(argv[1], "seeds"))
        rc = seeds(argc - 2, argv + 2);
    else if (argc >= 2 && !std::strcmp(argv[1], "apart-worker"))
        rc = apart_worker(argc - 2, argv + 2);
    if (rc == 2)
        usage(stderr);
    return rc;
}
