// solve.cpp - one request is one fresh OMPL problem: a joint space over
// the world's joints, a validity checker that asks the mpbench world, a
// goal (a joint configuration, or a pose region answered with IK
// samples), the planner with the request's parameters and the kit's
// deadline, and then the raw path, a shortcut copy and a B-spline-smoothed
// copy as three stages, each checked at the step mpbenchd verifies with
// before it is sent (a stage that fails there is dropped with those after
// it), all within the request's time limit (the budget in solve_inner).

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <system_error>
#include <vector>

#include <ompl/base/Planner.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/util/RandomNumbers.h>

#include "algorithms.h"
#include "final_stage.h"
#include "joint_space.h"
#include "pose_region_goal.h"
#include "progress_log.h"
#include "solve.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace mpb_ompl {
namespace {

// Thrown inside solve() for a request we cannot use (INVALID_REQUEST).
struct InvalidRequest : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Thrown inside solve() for a problem known unsolvable before planning
// (FAILED).
struct Unsolvable : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The validity checker's state. The world is not thread-safe and PRM checks
// goal states from a second thread, hence the mutex, taken only for the
// algorithms that do: uncontended, it still cost 0.8 % of RRTConnect's
// solve time in the PR2 kitchen (bench/fidelity.sh), time that a planner
// in its own process would not spend.
//
// Past `cutoff` (set once the solver has stopped) every state is refused
// unchecked: the simplifiers then keep what they have, as each change they
// try needs a motion found valid, and finish within microseconds.
struct Checker {
    mpb_world *world;
    bool shared;
    std::mutex mu;
    unsigned long calls = 0;
    unsigned long refused = 0;
    double cutoff = std::numeric_limits<double>::infinity();

    bool valid(const double *q)
    {
        if (cutoff < std::numeric_limits<double>::infinity() && mpb_monotonic_s() >= cutoff) {
            refused++;
            return false;
        }
        calls++;
        return mpb_world_in_collision(world, q) == 0;
    }
};

// mpbenchd allows a result this much past the time limit by its own clock,
// which counts from its request and so includes the world's setup
// (MPBD_WALL_SLACK_S, 1 s; docs/metrics.md), less what the network and
// the kit may take (0.25 s): setup beyond this is taken off the budget.
constexpr double kSetupAllowance = 0.75;

// What the answer takes after the last stage is checked (the stages into
// the message, the kit's encoding): a fixed allowance.
constexpr double kAnswerMargin = 0.01;

void check(int rc)
{
    if (rc == MPB_ENOMEM)
        throw std::bad_alloc();
    if (rc != MPB_OK)
        throw std::runtime_error(mpb_strerror(rc));
}

bool parse_double(const char *s, double &out)
{
    char *end;
    errno = 0;
    out = std::strtod(s, &end);
    return errno == 0 && end != s && *end == '\0' && std::isfinite(out);
}

bool parse_bool(const char *s, bool &out)
{
    if (!std::strcmp(s, "1") || !std::strcmp(s, "true") || !std::strcmp(s, "yes")) {
        out = true;
        return true;
    }
    if (!std::strcmp(s, "0") || !std::strcmp(s, "false") || !std::strcmp(s, "no")) {
        out = false;
        return true;
    }
    return false;
}

// OMPL's seed is 32 bits and must not be 0.
std::uint_fast32_t ompl_seed(std::int64_t seed)
{
    std::uint64_t u = static_cast<std::uint64_t>(seed);
    std::uint32_t s = static_cast<std::uint32_t>(u ^ (u >> 32));
    return s != 0 ? s : 0x9e3779b9u;
}

// Waypoints of path, world order, into request order (row after row).
std::vector<double> waypoints(const og::PathGeometric &path,
                              const std::vector<int> &perm)
{
    std::size_t n = perm.size();
    std::vector<double> out(path.getStateCount() * n);
    for (std::size_t i = 0; i < path.getStateCount(); i++) {
        const double *v = path.getState(i)->as<ob::RealVectorStateSpace::StateType>()->values;
        for (std::size_t j = 0; j < n; j++)
            out[i * n + j] = v[perm[j]];
    }
    return out;
}

void add_stage(mpb_plan_result_t *res, const char *name, double time,
               const og::PathGeometric &path, const std::vector<int> &perm)
{
    std::vector<double> wp = waypoints(path, perm);
    check(mpb_result_add_stage(res, name, time, wp.data(),
                               static_cast<int>(path.getStateCount()),
                               static_cast<int>(perm.size())));
}

// The request's pose region as an OMPL goal, its IK seeded by the start
// state and its random state by the request's seed.
std::shared_ptr<PoseRegionGoal> region_goal_of(CachedWorld *cached, const mpb_plan_request_t *req,
                                               const ob::SpaceInformationPtr &si,
                                               const std::vector<int> &perm)
{
    std::string err;
    const mpb_robot *robot = cached_robot(*cached, req, err);
    if (robot == nullptr)
        throw InvalidRequest("goal region: " + err);
    const mpb_goal_t &g = req->goal;
    mpb_goal_region region{};
    region.link = g.link != nullptr ? mpb_robot_link_index(robot, g.link) : -1;
    if (region.link < 0)
        throw InvalidRequest(std::string("goal region: the robot has no link '") +
                             (g.link != nullptr ? g.link : "") + "'");
    for (int i = 0; i < 3; i++) {
        region.center[i] = g.position[i];
        region.half_extents[i] = g.position_tolerance[i];
        region.ref_rpy[i] = g.orientation_rpy[i];
        region.rpy_tolerance[i] = g.orientation_tolerance[i];
    }
    char why[160] = "";
    if (mpb_goal_region_check(robot, &region, why, sizeof why) != MPB_OK)
        throw InvalidRequest(std::string("goal region: ") + why);
    std::vector<double> seed_q(req->start, req->start + req->num_joints);
    return std::make_shared<PoseRegionGoal>(si, robot, region, perm, std::move(seed_q),
                                            static_cast<std::uint64_t>(req->seed));
}

// mpbench's own parameters of a request; the others go to the OMPL planner.
struct Options {
    // Motions are checked at the step mpbenchd verifies with (0.01 rad by
    // default): OMPL then samples a whole segment at the very points the
    // verifier does (k = ceil(L / step) equal steps). The simplifiers'
    // pieces of segments are sampled elsewhere; the final check at
    // verify_resolution catches those (final_stage.h).
    double resolution = 0.01, verify_resolution = 0.01, progress_period = 0.05;
    // The paper's planners stop at their first solution; first_solution=0
    // lets optimizing ones (RRTstar, BITstar, PRMstar ...) use the time
    // limit, reporting their progress.
    bool simplify = true, first_solution = true;
    int goal_targets = 200;
    std::vector<const mpb_param_t *> planner_params;
};

Options parse_options(const mpb_plan_request_t *req)
{
    Options o;
    for (int i = 0; i < req->num_params; i++) {
        const mpb_param_t *p = &req->params[i];
        if (!std::strcmp(p->key, "resolution")) {
            if (!parse_double(p->value, o.resolution) || !(o.resolution > 0))
                throw InvalidRequest("resolution must be a number > 0 (rad)");
        } else if (!std::strcmp(p->key, "verify_resolution")) {
            if (!parse_double(p->value, o.verify_resolution) || !(o.verify_resolution >= 0))
                throw InvalidRequest("verify_resolution must be a number >= 0 (rad; 0: no "
                                     "final check)");
        } else if (!std::strcmp(p->key, "simplify")) {
            if (!parse_bool(p->value, o.simplify))
                throw InvalidRequest("simplify must be 0 or 1");
        } else if (!std::strcmp(p->key, "first_solution")) {
            if (!parse_bool(p->value, o.first_solution))
                throw InvalidRequest("first_solution must be 0 or 1");
        } else if (!std::strcmp(p->key, "progress_period")) {
            if (!parse_double(p->value, o.progress_period) || !(o.progress_period > 0))
                throw InvalidRequest("progress_period must be a number > 0 (s)");
        } else if (!std::strcmp(p->key, "goal_targets")) {
            double v;
            if (!parse_double(p->value, v) || !(v >= 1 && v <= 1e6) || v != std::floor(v))
                throw InvalidRequest("goal_targets must be a whole number >= 1");
            o.goal_targets = static_cast<int>(v);
        } else {
            o.planner_params.push_back(p);
        }
    }
    if (!(req->time_limit > 0) || !std::isfinite(req->time_limit))
        throw InvalidRequest("time_limit must be finite and > 0");
    if (req->goal.kind != MPB_GOAL_T_POSE_REGION && req->goal.kind != MPB_GOAL_T_JOINTS)
        throw InvalidRequest("unknown goal kind " + std::to_string(req->goal.kind));
    return o;
}

// perm[i]: the world joint of the request's joint i.
std::vector<int> joint_perm(mpb_world *world, const mpb_plan_request_t *req)
{
    const int n = mpb_world_num_joints(world);
    if (req->num_joints != n)
        throw InvalidRequest("the request names " + std::to_string(req->num_joints) +
                             " joints, the robot has " + std::to_string(n));
    std::vector<int> perm(static_cast<std::size_t>(n));
    for (int i = 0; i < n; i++) {
        const char *name = req->joint_names[i];
        int found = -1;
        for (int j = 0; j < n && found < 0; j++)
            if (name == nullptr || name[0] == '\0'
                    ? j == i
                    : std::strcmp(name, mpb_world_joint_name(world, j)) == 0)
                found = j;
        if (found < 0)
            throw InvalidRequest(std::string("the robot has no joint '") + name + "'");
        perm[static_cast<std::size_t>(i)] = found;
    }
    return perm;
}

// One run's OMPL problem and what its stages need.
struct Problem {
    CachedWorld *cached;
    mpb_world *world;
    int n;
    std::vector<int> perm;
    bool region_goal;
    const Algorithm *algorithm;
    std::shared_ptr<JointSpace> space;
    ob::SpaceInformationPtr si;
    std::shared_ptr<Checker> checker;
    ob::ProblemDefinitionPtr pdef;
};

// The space, its validity checker (every `resolution` rad) and the
// algorithm.
void make_space(Problem &p, const mpb_plan_request_t *req, const Options &o)
{
    p.space = std::make_shared<JointSpace>(p.world);
    p.si = std::make_shared<ob::SpaceInformation>(p.space);
    p.algorithm = find_algorithm(req->algorithm);
    if (p.algorithm == nullptr)
        throw InvalidRequest(std::string("unknown algorithm ") + req->algorithm);
    p.checker = std::make_shared<Checker>();
    p.checker->world = p.world;
    p.checker->shared = p.algorithm->two_threads;
    JointSpace *sp = p.space.get();
    std::shared_ptr<Checker> checker = p.checker;
    p.si->setStateValidityChecker([checker, sp](const ob::State *s) {
        if (!sp->satisfiesBounds(s))
            return false;
        const double *q = s->as<ob::RealVectorStateSpace::StateType>()->values;
        if (!checker->shared)
            return checker->valid(q);
        std::lock_guard<std::mutex> lock(checker->mu);
        return checker->valid(q);
    });
    // Motions are checked every `resolution` rad (joint space, Euclidean).
    double extent = p.space->getMaximumExtent();
    p.si->setStateValidityCheckingResolution(std::min(o.resolution / extent, 0.5));
    p.si->setup();
}

// Start and goal into p.pdef. Throws Unsolvable, with the times so far in
// res (from t0), when no goal state can be had.
void set_start_and_goal(Problem &p, const mpb_plan_request_t *req, const Options &o,
                        double t0, mpb_plan_result_t *res)
{
    // Start and goal in the world's joint order, continuous joints wrapped.
    ob::ScopedState<> start(p.space), goal(p.space);
    for (std::size_t i = 0; i < p.perm.size(); i++) {
        auto j = static_cast<unsigned int>(p.perm[i]);
        start[j] = req->start[i];
        goal[j] = p.region_goal ? 0.0 : req->goal.joints[i];
    }
    for (unsigned int j = 0; j < static_cast<unsigned int>(p.n); j++)
        if (mpb_world_joint_is_continuous(p.world, static_cast<int>(j))) {
            start[j] = std::remainder(start[j], 2.0 * M_PI);
            goal[j] = std::remainder(goal[j], 2.0 * M_PI);
        }
    p.pdef = std::make_shared<ob::ProblemDefinition>(p.si);
    if (p.region_goal) {
        auto g = region_goal_of(p.cached, req, p.si, p.perm);
        // Setting up the goal is finding a first goal state (tau_other):
        // without one no planner can start a goal tree, nor succeed.
        const double t_goal = mpb_monotonic_s();
        bool primed = g->prime(o.goal_targets);
        check(mpb_result_add_value(res, "goal sampling time", mpb_monotonic_s() - t_goal));
        if (!primed) {
            check(mpb_result_add_value(res, "goal ik calls", static_cast<double>(g->ikCalls())));
            res->time_other = res->time_total = mpb_monotonic_s() - t0;
            throw Unsolvable("no collision-free IK solution found inside the goal "
                             "region of '" + std::string(req->goal.link) + "' in " +
                             std::to_string(o.goal_targets) + " tries (goal_targets)");
        }
        p.pdef->addStartState(start);
        p.pdef->setGoal(g);
    } else {
        // A joint goal is one state: if it is invalid no planner can reach
        // it, and most would spend the whole time limit finding that out.
        if (!p.si->isValid(goal.get())) {
            res->time_other = res->time_total = mpb_monotonic_s() - t0;
            throw Unsolvable("the goal state collides or is outside the joint limits");
        }
        // The goal region is a box of half size joint_tolerance; a ball of
        // that radius lies inside it.
        p.pdef->setStartAndGoalStates(start, goal,
                                      std::max(req->goal.joint_tolerance,
                                               std::numeric_limits<double>::epsilon()));
    }
    if (o.first_solution) {
        // Any solution satisfies an infinite cost threshold: optimizing
        // planners (RRTstar, PRMstar, BITstar ...) stop at their first.
        auto obj = std::make_shared<ob::PathLengthOptimizationObjective>(p.si);
        obj->setCostThreshold(ob::Cost(std::numeric_limits<double>::infinity()));
        p.pdef->setOptimizationObjective(obj);
    }
}

// The OMPL planner with the request's parameters, set up on p.pdef.
ob::PlannerPtr make_planner(const Problem &p, const Options &o)
{
    const Algorithm *a = p.algorithm;
    ob::PlannerPtr planner = a->make(p.si);
    for (const mpb_param_t *q : o.planner_params) {
        if (!planner->params().hasParam(q->key)) {
            std::vector<std::string> names;
            planner->params().getParamNames(names);
            std::string known;
            for (const std::string &k : names)
                known += (known.empty() ? "" : ", ") + k;
            throw InvalidRequest(std::string("unknown parameter '") + q->key + "' for " +
                                 a->name + " (known: " + known +
                                 "; and mpbench's resolution, verify_resolution, simplify, "
                                 "first_solution, progress_period, goal_targets)");
        }
        bool ok;
        try {
            ok = planner->params().setParam(q->key, q->value);
        } catch (const std::exception &) {
            ok = false;     // OMPL throws when the text is not a number
        }
        if (!ok)
            throw InvalidRequest(std::string("bad value '") + q->value +
                                 "' for parameter '" + q->key + "'");
    }
    planner->setProblemDefinition(p.pdef);
    planner->setup();
    return planner;
}

// OMPL's outcome as the result's status and message.
void set_status(const ob::PlannerStatus &status, const Problem &p, mpb_plan_result_t *res)
{
    switch (ob::PlannerStatus::StatusType(status)) {
    case ob::PlannerStatus::EXACT_SOLUTION:
        res->status = MPB_PLAN_RESULT_T_SOLVED;
        break;
    case ob::PlannerStatus::APPROXIMATE_SOLUTION:
        res->status = MPB_PLAN_RESULT_T_APPROXIMATE;
        mpb_result_set_message(res, "approximate solution, %g from the goal",
                               p.pdef->getSolutionDifference());
        break;
    case ob::PlannerStatus::TIMEOUT:
        res->status = MPB_PLAN_RESULT_T_TIMEOUT;
        break;
    case ob::PlannerStatus::INVALID_START:
        res->status = MPB_PLAN_RESULT_T_FAILED;
        mpb_result_set_message(res, "the start state collides or is outside the joint limits");
        break;
    case ob::PlannerStatus::INVALID_GOAL:
        res->status = MPB_PLAN_RESULT_T_FAILED;
        mpb_result_set_message(res, p.region_goal ? "no valid goal state in the goal region"
                                                  : "the goal state collides or is outside "
                                                    "the joint limits");
        break;
    default:
        res->status = MPB_PLAN_RESULT_T_FAILED;
        mpb_result_set_message(res, "OMPL: %s", status.asString().c_str());
        break;
    }
}

// The stages a run found, their names and times, before the final check.
struct Stages {
    std::vector<og::PathGeometric> paths;
    std::vector<std::string> names;
    std::vector<double> times;
};

// The shortcut and smoothed stages, within what the budget leaves.
void simplify_stages(Stages &st, const Problem &p, const Options &o, bool solved,
                     double solve_time, unsigned long solve_checks, double hard_deadline,
                     mpb_plan_result_t *res)
{
    Checker &checker = *p.checker;
    // The simplifiers' share ends where the final check's begins: that
    // check samples each stage at verify_resolution, at most two stages of
    // about the raw path's length, each state taking what one took while
    // solving (solve time over its checks: an overestimate, the solve
    // doing more than checking).
    if (o.verify_resolution > 0 && solved) {
        const og::PathGeometric &raw = st.paths.front();
        double per_check = solve_checks > 0
                               ? solve_time / static_cast<double>(solve_checks)
                               : 0.0;
        double samples = raw.length() / o.verify_resolution +
                         static_cast<double>(raw.getStateCount());
        checker.cutoff = hard_deadline - 2.0 * samples * per_check;
    } else {
        checker.cutoff = hard_deadline;
    }
    og::PathSimplifier ps(p.si);
    double t = mpb_monotonic_s();
    st.paths.push_back(st.paths.back());
    ps.reduceVertices(st.paths.back());
    ps.shortcutPath(st.paths.back());
    double t_shortcut = mpb_monotonic_s();
    st.names.emplace_back("shortcut");
    st.times.push_back(t_shortcut - t);

    t = mpb_monotonic_s();
    st.paths.push_back(st.paths.back());
    ps.smoothBSpline(st.paths.back());
    st.names.emplace_back("smoothed");
    st.times.push_back(mpb_monotonic_s() - t);
    checker.cutoff = std::numeric_limits<double>::infinity();
    if (checker.refused > 0)
        check(mpb_result_add_value(res, "checks refused past the budget",
                                   static_cast<double>(checker.refused)));
}

// The final check: how many stages to send, ending with the last one valid
// at the verifier's step; those after it are dropped, and said so.
std::size_t stages_to_keep(const Stages &st, const Problem &p, const Options &o,
                           mpb_plan_result_t *res)
{
    std::vector<std::vector<double>> wp;
    std::vector<int> world_order(p.perm.size());
    for (std::size_t j = 0; j < p.perm.size(); j++)
        world_order[j] = static_cast<int>(j);
    for (const og::PathGeometric &path : st.paths)
        wp.push_back(waypoints(path, world_order));
    std::string dropped;
    const double t_check = mpb_monotonic_s();
    int last = last_valid_stage(p.world, wp, st.names, p.n, o.verify_resolution, &dropped);
    check(mpb_result_add_value(res, "final check time", mpb_monotonic_s() - t_check));
    check(mpb_result_add_value(res, "stages dropped",
                               static_cast<double>(st.paths.size() - 1 -
                                                   static_cast<std::size_t>(
                                                       std::max(last, 0)))));
    if (last < 0) {
        res->status = MPB_PLAN_RESULT_T_FAILED;
        mpb_result_set_message(res, "the path fails the check at the verify_resolution "
                               "%g rad: %s", o.verify_resolution, dropped.c_str());
        return 1;   // the raw path, sent for the record, not as a solution
    }
    std::size_t keep = static_cast<std::size_t>(last) + 1;
    if (keep < st.paths.size())
        mpb_result_set_message(res, "dropped at the verify_resolution %g rad: %s",
                               o.verify_resolution, dropped.c_str());
    return keep;
}

// The stages of a solved (or approximate) run into res.
void add_stages(const Problem &p, const Options &o, double solve_time,
                unsigned long solve_checks, double hard_deadline, mpb_plan_result_t *res)
{
    const bool solved = res->status == MPB_PLAN_RESULT_T_SOLVED;
    Stages st;
    st.paths.emplace_back(*p.pdef->getSolutionPath()->as<og::PathGeometric>());
    st.names.emplace_back("raw");
    st.times.push_back(solve_time);
    if (o.simplify)
        simplify_stages(st, p, o, solved, solve_time, solve_checks, hard_deadline, res);
    std::size_t keep = st.paths.size();
    if (o.verify_resolution > 0 && solved)
        keep = stages_to_keep(st, p, o, res);
    for (std::size_t i = 0; i < keep; i++)
        add_stage(res, st.names[i].c_str(), st.times[i], st.paths[i], p.perm);
}

// The world of the request, held as it says; its setup time, when this
// request built it, goes to res and onto *t0, and the daemon is told of
// the build (its deadline waits for it).
Problem open_problem(Context *ctx, const mpb_plan_request_t *req,
                     const mpb_solve_limits *lim, double *t0,
                     mpb_plan_result_t *res)
{
    Problem p{};
    std::string err;
    bool built;
    const double t_world = mpb_monotonic_s();
    p.cached = ctx->worlds.get(req, lim, err, &built);
    if (p.cached == nullptr)
        throw InvalidRequest("world: " + err);
    if (built) {
        // Parsing the robot and scene (meshes too) is the world's, not this
        // run's: reported on its own and left out of tau_t, as
        // ompl::tools::Benchmark leaves out its setup.
        const double setup = mpb_monotonic_s() - t_world;
        check(mpb_result_add_value(res, MPB_WORLD_SETUP_TIME, setup));
        *t0 += setup;
    }
    p.world = p.cached->world;
    // The joints outside the group hold this request's values, in the
    // world and in the robot for IK, whatever the last request held.
    char held_err[256];
    if (mpb_request_hold(req, p.world, p.cached->robot, held_err, sizeof held_err) != MPB_OK)
        throw InvalidRequest(std::string("held joints: ") + held_err);
    p.perm = joint_perm(p.world, req);
    p.n = static_cast<int>(p.perm.size());
    p.region_goal = req->goal.kind == MPB_GOAL_T_POSE_REGION;
    return p;
}

void solve_inner(Context *ctx, const mpb_plan_request_t *req, const mpb_solve_limits *lim,
                 mpb_plan_result_t *res)
{
    double t0 = mpb_monotonic_s();
    const double t_entry = t0;
    const Options o = parse_options(req);
    Problem p = open_problem(ctx, req, lim, &t0, res);

    // Every random generator of this run is made after this, in the same
    // order each time: the same seed gives the same samples (OMPL 1.5
    // re-seeds its seed generator even after generators were made).
    ompl::RNG::setSeed(ompl_seed(req->seed));
    make_space(p, req, o);
    set_start_and_goal(p, req, o, t0, res);
    ob::PlannerPtr planner = make_planner(p, o);
    const double t_setup = mpb_monotonic_s();
    res->time_other = t_setup - t0;

    // The budget. mpbenchd counts a run in time by its time_total (from t0,
    // the world's setup left out) and by its own clock, setup included,
    // with a slack (kSetupAllowance): the whole answer, simplifiers and
    // final check included, must be ready by hard_deadline, the kit's
    // deadline moved by the setup it allows. The solver stops early enough
    // for those: 2 % of the limit (10 ms to 0.5 s), or for an anytime run,
    // which would spend all it is given, 10 % (at most 2 s). What the
    // simplifiers then find left is theirs (the checker's cutoff).
    const double setup = t0 - t_entry;
    const bool log_progress = !o.first_solution;
    const double hard_deadline = lim->deadline + setup -
                                 std::max(0.0, setup - kSetupAllowance) - kAnswerMargin;
    const double deadline =
        hard_deadline - (log_progress ? std::min(0.1 * req->time_limit, 2.0)
                                      : std::min(std::max(0.02 * req->time_limit, 0.01), 0.5));
    std::atomic<bool> interrupted{false};
    ProgressLog progress(*planner, o.progress_period, t_setup);
    const mpb_solve_limits solver_limits = mpb_solve_limits_moved(lim, deadline - lim->deadline);
    // The kit's one stop check, on the solver's part of the budget.
    ob::PlannerTerminationCondition ptc([&solver_limits, &interrupted, &progress, log_progress] {
        if (log_progress)
            progress.poll(mpb_monotonic_s());
        if (!mpb_solve_should_stop(&solver_limits))
            return false;
        if (solver_limits.stop != nullptr && *solver_limits.stop != 0)
            interrupted = true;
        return true;
    });
    // solve() alone, the span ompl::tools::Benchmark times; Benchmark also
    // counts the start and stop of a thread that checks its limit, which
    // the inline check above does without (docs/performance.md, 4b).
    ob::PlannerStatus status = planner->solve(ptc);
    const double t_raw = mpb_monotonic_s();
    if (log_progress) {
        progress.finish(t_raw);
        check(progress.addTo(res));
    }
    const unsigned long solve_checks = p.checker->calls;

    set_status(status, p, res);
    if (interrupted) {
        // Cut short by SIGINT/SIGTERM: whatever was found is not what the
        // request asked for (an anytime planner had less time).
        res->status = MPB_PLAN_RESULT_T_FAILED;
        mpb_result_set_message(res, "interrupted after %.3f s: the planner "
                               "process is stopping", t_raw - t_setup);
    }

    check(mpb_result_add_value(res, "state checks in solve", static_cast<double>(solve_checks)));
    if (p.region_goal) {
        auto g = std::static_pointer_cast<PoseRegionGoal>(p.pdef->getGoal());
        check(mpb_result_add_value(res, "goal states", static_cast<double>(g->numGoalStates())));
        check(mpb_result_add_value(res, "goal ik calls", static_cast<double>(g->ikCalls())));
    }

    bool have_path = (status == ob::PlannerStatus::EXACT_SOLUTION ||
                      status == ob::PlannerStatus::APPROXIMATE_SOLUTION) &&
                     p.pdef->getSolutionPath() != nullptr;
    if (have_path)
        add_stages(p, o, t_raw - t_setup, solve_checks, hard_deadline, res);
    // The graph's size, from a copy of it that takes microseconds a state:
    // 0.3 s for the 110,000 states a 1.5 s search of a planar arm grows.
    // Left out when the solver ran to its deadline and less than a tenth
    // of the limit is left, lest the count make the answer late.
    if (t_raw < deadline || hard_deadline - mpb_monotonic_s() >= 0.1 * req->time_limit) {
        ob::PlannerData data(p.si);
        planner->getPlannerData(data);
        check(mpb_result_add_value(res, "graph states", data.numVertices()));
        check(mpb_result_add_value(res, "graph motions", data.numEdges()));
    }
    check(mpb_result_add_value(res, "state checks", static_cast<double>(p.checker->calls)));
    res->time_total = mpb_monotonic_s() - t0;
}

}  // namespace
}  // namespace mpb_ompl

using namespace mpb_ompl;

extern "C" int mpb_ompl_solve(void *user, const mpb_plan_request_t *req,
                              const mpb_solve_limits *lim, mpb_plan_result_t *res)
{
    const char *what = nullptr;
    try {
        solve_inner(static_cast<Context *>(user), req, lim, res);
        return MPB_OK;
    } catch (const InvalidRequest &e) {
        mpb_result_clear(res);
        mpb_result_set_message(res, "%s", e.what());
        return MPB_EINVAL;
    } catch (const Unsolvable &e) {
        // Keep the times and values measured so far: only the status changes.
        res->status = MPB_PLAN_RESULT_T_FAILED;
        mpb_result_set_message(res, "%s", e.what());
        return MPB_OK;
    } catch (const std::bad_alloc &) {
        // Past the request's memory_limit (RLIMIT_DATA, set by the kit
        // around solve()), or the machine's: MEMORY, with the peak the
        // kit measures. What OMPL allocated is freed by now.
        mpb_result_clear(res);
        res->status = MPB_PLAN_RESULT_T_MEMORY;
        mpb_result_set_message(res, "out of memory (std::bad_alloc)");
        return MPB_OK;
    } catch (const std::system_error &e) {
        // A thread OMPL starts (PRM's roadmap, a timed termination
        // condition) needs its stack, 8 MB, which the limit counts: its
        // EAGAIN is memory too. Any other system error is a failure.
        const bool memory = e.code() == std::errc::resource_unavailable_try_again ||
                            e.code() == std::errc::not_enough_memory;
        mpb_result_clear(res);
        res->status = memory ? MPB_PLAN_RESULT_T_MEMORY : MPB_PLAN_RESULT_T_FAILED;
        mpb_result_set_message(res, "%s: %s", memory ? "out of memory" : "exception",
                               e.what());
        return MPB_OK;
    } catch (const std::exception &e) {
        what = e.what();
        mpb_result_clear(res);
        mpb_result_set_message(res, "exception: %s", what);
    } catch (...) {
        mpb_result_clear(res);
        mpb_result_set_message(res, "unknown exception");
    }
    res->status = MPB_PLAN_RESULT_T_FAILED;
    return MPB_OK;
}
