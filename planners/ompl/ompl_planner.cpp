// ompl_planner.cpp - mpb-planner-ompl: OMPL's geometric planners behind the mpbench protocol.
//
// One request is one fresh OMPL problem: a joint space over the world's
// joints, a validity checker that asks the mpbench world, a goal (a joint
// configuration, or a pose region answered with IK samples), the planner
// with the request's parameters, a time limit, and then the raw path, a
// shortcut copy and a B-spline-smoothed copy as three stages, each
// checked at the step mpbenchd verifies with before it is sent (a stage
// that fails there is dropped with those after it), all within the
// request's time limit (the budget in solve_inner). Only the
// parsed world (and robot, for IK) is kept between requests, keyed by the
// texts' hashes.
//
// Everything C++ stays inside solve(): every exception is caught there and
// becomes a FAILED result, so none crosses into the C library.

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <functional>
#include <limits>
#include <list>
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
#include <ompl/config.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

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

#include "mpbench/mpbench.h"
#include "mpbench/planner.h"
#include "mpbench/robot.h"

#include "final_stage.h"
#include "joint_space.h"
#include "pose_region_goal.h"
#include "progress_log.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

volatile std::sig_atomic_t g_stop = 0;

extern "C" void on_signal(int) { g_stop = 1; }

#define MPB_STR2(x) #x
#define MPB_STR(x) MPB_STR2(x)
const char *const k_version = MPB_VERSION_STRING " (OMPL "
    MPB_STR(OMPL_MAJOR_VERSION) "." MPB_STR(OMPL_MINOR_VERSION) "."
    MPB_STR(OMPL_PATCH_VERSION) ")";

// ---- the algorithms ------------------------------------------------------

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

using Factory = std::function<ob::PlannerPtr(const ob::SpaceInformationPtr &)>;

struct Algorithm {
    const char *name;
    Factory make;
    bool two_threads;   // checks states from two threads while it solves
};

template <class P> Algorithm alg(const char *name, bool two_threads = false)
{
    return {name, [](const ob::SpaceInformationPtr &si) -> ob::PlannerPtr {
                return std::make_shared<P>(si);
            }, two_threads};
}

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

// ---- the joint space -----------------------------------------------------

using mpb_ompl::JointSpace;    // joint_space.h

// ---- the world cache -----------------------------------------------------

struct CachedWorld {
    std::string key;
    mpb_world *world;
    mpb_robot *robot;       // for IK; loaded at the first pose-region goal
};

// The robot of a urdf world in the request's joint order, for IK and goal
// regions. The world keeps its own robot private (its format may have
// none); parsing the URDF once more per cached world costs milliseconds.
mpb_robot *cached_robot(CachedWorld &c, const mpb_plan_request_t *req, std::string &err)
{
    if (c.robot != nullptr)
        return c.robot;
    if (req->robot_format == nullptr || std::strcmp(req->robot_format, "urdf") != 0) {
        err = "pose-region goals need a urdf robot";
        return nullptr;
    }
    char msg[256] = "";
    if (mpb_robot_load_urdf_joints(req->robot, req->joint_names, req->num_joints,
                                   &c.robot, msg, sizeof msg) != MPB_OK ||
        mpb_request_hold(req, nullptr, c.robot, msg, sizeof msg) != MPB_OK) {
        err = msg;
        return nullptr;
    }
    return c.robot;
}

class WorldCache {
public:
    ~WorldCache()
    {
        for (CachedWorld &c : list_)
            close(c);
    }

    // The world of a request, parsed once per robot and scene; nullptr
    // with err filled when it does not parse. Owned by the cache. *built
    // says whether this call parsed it.
    CachedWorld *get(const mpb_plan_request_t *req, std::string &err, bool *built)
    {
        *built = false;
        std::string key = part(req->robot_format, req->robot_hash, req->robot) +
                          '\n' + part(req->scene_format, req->scene_hash, req->scene);
        for (int j = 0; j < req->num_joints; j++)
            key += std::string("\n") + req->joint_names[j];
        for (auto it = list_.begin(); it != list_.end(); ++it)
            if (it->key == key) {
                list_.splice(list_.begin(), list_, it);
                return &list_.front();
            }
        mpb_world *w = nullptr;
        char msg[256] = "";
        int rc = mpb_world_open_group(req->robot_format, req->robot,
                                      req->scene_format, req->scene,
                                      req->joint_names, req->num_joints, &w,
                                      msg, sizeof msg);
        if (rc != MPB_OK || w == nullptr) {
            err = msg[0] != '\0' ? msg : mpb_strerror(rc);
            return nullptr;
        }
        *built = true;
        list_.push_front(CachedWorld{key, w, nullptr});
        while (list_.size() > kSize) {
            close(list_.back());
            list_.pop_back();
        }
        return &list_.front();
    }

private:
    static constexpr std::size_t kSize = 4;

    static void close(CachedWorld &c)
    {
        mpb_world_close(c.world);
        mpb_robot_free(c.robot);
    }

    // A hash names the text; without one, the text names itself.
    static std::string part(const char *format, const char *hash, const char *text)
    {
        std::string s = format != nullptr ? format : "";
        s += ':';
        if (hash != nullptr && hash[0] != '\0')
            s += hash;
        else
            s += std::string("text:") + (text != nullptr ? text : "");
        return s;
    }

    std::list<CachedWorld> list_;
};

// ---- solving -------------------------------------------------------------

struct Context {
    WorldCache worlds;
};

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

void solve_inner(Context *ctx, const mpb_plan_request_t *req, const mpb_solve_limits *lim,
                 mpb_plan_result_t *res)
{
    double t0 = mpb_monotonic_s();
    const double t_entry = t0;

    // mpbench's own parameters; the others go to the OMPL planner.
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
    for (int i = 0; i < req->num_params; i++) {
        const mpb_param_t *p = &req->params[i];
        if (!std::strcmp(p->key, "resolution")) {
            if (!parse_double(p->value, resolution) || !(resolution > 0))
                throw InvalidRequest("resolution must be a number > 0 (rad)");
        } else if (!std::strcmp(p->key, "verify_resolution")) {
            if (!parse_double(p->value, verify_resolution) || !(verify_resolution >= 0))
                throw InvalidRequest("verify_resolution must be a number >= 0 (rad; 0: no "
                                     "final check)");
        } else if (!std::strcmp(p->key, "simplify")) {
            if (!parse_bool(p->value, simplify))
                throw InvalidRequest("simplify must be 0 or 1");
        } else if (!std::strcmp(p->key, "first_solution")) {
            if (!parse_bool(p->value, first_solution))
                throw InvalidRequest("first_solution must be 0 or 1");
        } else if (!std::strcmp(p->key, "progress_period")) {
            if (!parse_double(p->value, progress_period) || !(progress_period > 0))
                throw InvalidRequest("progress_period must be a number > 0 (s)");
        } else if (!std::strcmp(p->key, "goal_targets")) {
            double v;
            if (!parse_double(p->value, v) || !(v >= 1 && v <= 1e6) || v != std::floor(v))
                throw InvalidRequest("goal_targets must be a whole number >= 1");
            goal_targets = static_cast<int>(v);
        } else {
            planner_params.push_back(p);
        }
    }
    if (!(req->time_limit > 0) || !std::isfinite(req->time_limit))
        throw InvalidRequest("time_limit must be finite and > 0");
    const bool region_goal = req->goal.kind == MPB_GOAL_T_POSE_REGION;
    if (!region_goal && req->goal.kind != MPB_GOAL_T_JOINTS)
        throw InvalidRequest("unknown goal kind " + std::to_string(req->goal.kind));

    std::string err;
    bool built;
    const double t_world = mpb_monotonic_s();
    CachedWorld *cached = ctx->worlds.get(req, err, &built);
    if (cached == nullptr)
        throw InvalidRequest("world: " + err);
    if (built) {
        // Parsing the robot and scene (meshes too) is the world's, not this
        // run's: reported on its own and left out of tau_t, as
        // ompl::tools::Benchmark leaves out its setup.
        const double setup = mpb_monotonic_s() - t_world;
        check(mpb_result_add_value(res, MPB_WORLD_SETUP_TIME, setup));
        t0 += setup;
    }
    mpb_world *world = cached->world;
    // The joints outside the group hold this request's values, in the
    // world and in the robot for IK, whatever the last request held.
    char held_err[256];
    if (mpb_request_hold(req, world, cached->robot, held_err, sizeof held_err) != MPB_OK)
        throw InvalidRequest(std::string("held joints: ") + held_err);

    // perm[i]: the world joint of the request's joint i.
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

    // Every random generator of this run is made after this, in the same
    // order each time: the same seed gives the same samples (OMPL 1.5
    // re-seeds its seed generator even after generators were made).
    ompl::RNG::setSeed(ompl_seed(req->seed));

    auto space = std::make_shared<JointSpace>(world);
    auto si = std::make_shared<ob::SpaceInformation>(space);
    const Algorithm *a = find_algorithm(req->algorithm);
    if (a == nullptr)
        throw InvalidRequest(std::string("unknown algorithm ") + req->algorithm);
    auto checker = std::make_shared<Checker>();
    checker->world = world;
    checker->shared = a->two_threads;
    JointSpace *sp = space.get();
    si->setStateValidityChecker([checker, sp](const ob::State *s) {
        if (!sp->satisfiesBounds(s))
            return false;
        const double *q = s->as<ob::RealVectorStateSpace::StateType>()->values;
        if (!checker->shared)
            return checker->valid(q);
        std::lock_guard<std::mutex> lock(checker->mu);
        return checker->valid(q);
    });
    // Motions are checked every `resolution` rad (joint space, Euclidean).
    double extent = space->getMaximumExtent();
    si->setStateValidityCheckingResolution(std::min(resolution / extent, 0.5));
    si->setup();

    // Start and goal in the world's joint order, continuous joints wrapped.
    ob::ScopedState<> start(space), goal(space);
    for (std::size_t i = 0; i < perm.size(); i++) {
        auto j = static_cast<unsigned int>(perm[i]);
        start[j] = req->start[i];
        goal[j] = region_goal ? 0.0 : req->goal.joints[i];
    }
    for (unsigned int j = 0; j < static_cast<unsigned int>(n); j++)
        if (mpb_world_joint_is_continuous(world, static_cast<int>(j))) {
            start[j] = std::remainder(start[j], 2.0 * M_PI);
            goal[j] = std::remainder(goal[j], 2.0 * M_PI);
        }
    auto pdef = std::make_shared<ob::ProblemDefinition>(si);
    if (region_goal) {
        auto g = region_goal_of(cached, req, si, perm);
        // Setting up the goal is finding a first goal state (tau_other):
        // without one no planner can start a goal tree, nor succeed.
        const double t_goal = mpb_monotonic_s();
        bool primed = g->prime(goal_targets);
        check(mpb_result_add_value(res, "goal sampling time", mpb_monotonic_s() - t_goal));
        if (!primed) {
            check(mpb_result_add_value(res, "goal ik calls", static_cast<double>(g->ikCalls())));
            res->time_other = res->time_total = mpb_monotonic_s() - t0;
            throw Unsolvable("no collision-free IK solution found inside the goal "
                             "region of '" + std::string(req->goal.link) + "' in " +
                             std::to_string(goal_targets) + " tries (goal_targets)");
        }
        pdef->addStartState(start);
        pdef->setGoal(g);
    } else {
        // A joint goal is one state: if it is invalid no planner can reach
        // it, and most would spend the whole time limit finding that out.
        if (!si->isValid(goal.get())) {
            res->time_other = res->time_total = mpb_monotonic_s() - t0;
            throw Unsolvable("the goal state collides or is outside the joint limits");
        }
        // The goal region is a box of half size joint_tolerance; a ball of
        // that radius lies inside it.
        pdef->setStartAndGoalStates(start, goal,
                                    std::max(req->goal.joint_tolerance,
                                             std::numeric_limits<double>::epsilon()));
    }
    if (first_solution) {
        // Any solution satisfies an infinite cost threshold: optimizing
        // planners (RRTstar, PRMstar, BITstar ...) stop at their first.
        auto obj = std::make_shared<ob::PathLengthOptimizationObjective>(si);
        obj->setCostThreshold(ob::Cost(std::numeric_limits<double>::infinity()));
        pdef->setOptimizationObjective(obj);
    }

    ob::PlannerPtr planner = a->make(si);
    for (const mpb_param_t *p : planner_params) {
        if (!planner->params().hasParam(p->key)) {
            std::vector<std::string> names;
            planner->params().getParamNames(names);
            std::string known;
            for (const std::string &k : names)
                known += (known.empty() ? "" : ", ") + k;
            throw InvalidRequest(std::string("unknown parameter '") + p->key + "' for " +
                                 a->name + " (known: " + known +
                                 "; and mpbench's resolution, verify_resolution, simplify, "
                                 "first_solution, progress_period, goal_targets)");
        }
        bool ok;
        try {
            ok = planner->params().setParam(p->key, p->value);
        } catch (const std::exception &) {
            ok = false;     // OMPL throws when the text is not a number
        }
        if (!ok)
            throw InvalidRequest(std::string("bad value '") + p->value +
                                 "' for parameter '" + p->key + "'");
    }
    planner->setProblemDefinition(pdef);
    planner->setup();
    const double t_setup = mpb_monotonic_s();
    res->time_other = t_setup - t0;

    // The budget. mpbenchd counts a run in time by its time_total (from t0,
    // the world's setup left out) and by its own clock, setup included,
    // with a slack (kSetupAllowance): the whole answer, simplifiers and
    // final check included, must be ready by hard_deadline, the kit's
    // deadline moved by the setup it allows. The solver
    // stops early enough for those: 2 % of the limit (10 ms to 0.5 s), or
    // for an anytime run, which would spend all it is given, 10 % (at most
    // 2 s). What the simplifiers then find left is theirs (the checker's
    // cutoff, below).
    const bool log_progress = !first_solution;
    const double setup = t0 - t_entry;
    const double hard_deadline = lim->deadline + setup -
                                 std::max(0.0, setup - kSetupAllowance) - kAnswerMargin;
    const double deadline =
        hard_deadline - (log_progress ? std::min(0.1 * req->time_limit, 2.0)
                                      : std::min(std::max(0.02 * req->time_limit, 0.01), 0.5));
    std::atomic<bool> interrupted{false};
    ProgressLog progress(*planner, progress_period, t_setup);
    volatile sig_atomic_t *stop = lim->stop;
    ob::PlannerTerminationCondition ptc([deadline, stop, &interrupted, &progress, log_progress] {
        if (stop != nullptr && *stop != 0)
            interrupted = true;
        double now = mpb_monotonic_s();
        if (log_progress)
            progress.poll(now);
        return interrupted || now >= deadline;
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
    const unsigned long solve_checks = checker->calls;

    switch (ob::PlannerStatus::StatusType(status)) {
    case ob::PlannerStatus::EXACT_SOLUTION:
        res->status = MPB_PLAN_RESULT_T_SOLVED;
        break;
    case ob::PlannerStatus::APPROXIMATE_SOLUTION:
        res->status = MPB_PLAN_RESULT_T_APPROXIMATE;
        mpb_result_set_message(res, "approximate solution, %g from the goal",
                               pdef->getSolutionDifference());
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
        mpb_result_set_message(res, region_goal ? "no valid goal state in the goal region"
                                                : "the goal state collides or is outside "
                                                  "the joint limits");
        break;
    default:
        res->status = MPB_PLAN_RESULT_T_FAILED;
        mpb_result_set_message(res, "OMPL: %s", status.asString().c_str());
        break;
    }
    if (interrupted) {
        // Cut short by SIGINT/SIGTERM: whatever was found is not what the
        // request asked for (an anytime planner had less time).
        res->status = MPB_PLAN_RESULT_T_FAILED;
        mpb_result_set_message(res, "interrupted after %.3f s: the planner "
                               "process is stopping", t_raw - t_setup);
    }

    check(mpb_result_add_value(res, "state checks in solve", static_cast<double>(solve_checks)));
    if (region_goal) {
        auto g = std::static_pointer_cast<PoseRegionGoal>(pdef->getGoal());
        check(mpb_result_add_value(res, "goal states", static_cast<double>(g->numGoalStates())));
        check(mpb_result_add_value(res, "goal ik calls", static_cast<double>(g->ikCalls())));
    }

    bool have_path = (status == ob::PlannerStatus::EXACT_SOLUTION ||
                      status == ob::PlannerStatus::APPROXIMATE_SOLUTION) &&
                     pdef->getSolutionPath() != nullptr;
    if (have_path) {
        const bool solved = res->status == MPB_PLAN_RESULT_T_SOLVED;
        std::vector<og::PathGeometric> paths;
        std::vector<std::string> names;
        std::vector<double> times;
        paths.emplace_back(*pdef->getSolutionPath()->as<og::PathGeometric>());
        names.emplace_back("raw");
        times.push_back(t_raw - t_setup);
        if (simplify) {
            // The simplifiers' share ends where the final check's begins:
            // that check samples each stage at verify_resolution, at most
            // two stages of about the raw path's length, each state taking
            // what one took while solving (solve time over its checks: an
            // overestimate, the solve doing more than checking).
            if (verify_resolution > 0 && solved) {
                const og::PathGeometric &raw = paths.front();
                double per_check = solve_checks > 0
                                       ? (t_raw - t_setup) / static_cast<double>(solve_checks)
                                       : 0.0;
                double samples = raw.length() / verify_resolution +
                                 static_cast<double>(raw.getStateCount());
                checker->cutoff = hard_deadline - 2.0 * samples * per_check;
            } else {
                checker->cutoff = hard_deadline;
            }
            og::PathSimplifier ps(si);
            double t = mpb_monotonic_s();
            paths.push_back(paths.back());
            ps.reduceVertices(paths.back());
            ps.shortcutPath(paths.back());
            double t_shortcut = mpb_monotonic_s();
            names.emplace_back("shortcut");
            times.push_back(t_shortcut - t);

            t = mpb_monotonic_s();
            paths.push_back(paths.back());
            ps.smoothBSpline(paths.back());
            names.emplace_back("smoothed");
            times.push_back(mpb_monotonic_s() - t);
            checker->cutoff = std::numeric_limits<double>::infinity();
            if (checker->refused > 0)
                check(mpb_result_add_value(res, "checks refused past the budget",
                                           static_cast<double>(checker->refused)));
        }
        // The final check: the stages sent end with the last one valid at
        // the verifier's step; those after it are dropped, and said so.
        std::size_t keep = paths.size();
        if (verify_resolution > 0 && solved) {
            std::vector<std::vector<double>> wp;
            std::vector<int> world_order(perm.size());
            for (std::size_t j = 0; j < perm.size(); j++)
                world_order[j] = static_cast<int>(j);
            for (const og::PathGeometric &p : paths)
                wp.push_back(waypoints(p, world_order));
            std::string dropped;
            const double t_check = mpb_monotonic_s();
            int last = mpb_ompl::last_valid_stage(world, wp, names, n, verify_resolution,
                                                  &dropped);
            check(mpb_result_add_value(res, "final check time", mpb_monotonic_s() - t_check));
            check(mpb_result_add_value(res, "stages dropped",
                                       static_cast<double>(paths.size() - 1 -
                                                           static_cast<std::size_t>(
                                                               std::max(last, 0)))));
            if (last < 0) {
                keep = 1;   // the raw path, sent for the record, not as a solution
                res->status = MPB_PLAN_RESULT_T_FAILED;
                mpb_result_set_message(res, "the path fails the check at the verify_resolution "
                                       "%g rad: %s", verify_resolution, dropped.c_str());
            } else {
                keep = static_cast<std::size_t>(last) + 1;
                if (keep < paths.size())
                    mpb_result_set_message(res, "dropped at the verify_resolution %g rad: %s",
                                           verify_resolution, dropped.c_str());
            }
        }
        for (std::size_t i = 0; i < keep; i++)
            add_stage(res, names[i].c_str(), times[i], paths[i], perm);
    }
    // The graph's size, from a copy of it that takes microseconds a state:
    // 0.3 s for the 110,000 states a 1.5 s search of a planar arm grows.
    // Left out when the solver ran to its deadline and less than a tenth
    // of the limit is left, lest the count make the answer late.
    if (t_raw < deadline || hard_deadline - mpb_monotonic_s() >= 0.1 * req->time_limit) {
        ob::PlannerData data(si);
        planner->getPlannerData(data);
        check(mpb_result_add_value(res, "graph states", data.numVertices()));
        check(mpb_result_add_value(res, "graph motions", data.numEdges()));
    }
    check(mpb_result_add_value(res, "state checks", static_cast<double>(checker->calls)));
    res->time_total = mpb_monotonic_s() - t0;
}

extern "C" int solve(void *user, const mpb_plan_request_t *req, const mpb_solve_limits *lim,
                     mpb_plan_result_t *res)
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

// ---- the process ---------------------------------------------------------

// OMPL's messages go to stderr with --verbose, else nowhere. Re-seeding per
// run makes OMPL complain that "random number generation already started";
// that is expected here and dropped.
class LogHandler : public ompl::msg::OutputHandler {
public:
    void log(const std::string &text, ompl::msg::LogLevel level, const char *,
             int) override
    {
        if (text.find("Random number generation already started") != std::string::npos)
            return;
        static const char *const names[] = {"debug", "info", "warning", "error"};
        int i = static_cast<int>(level);
        std::fprintf(stderr, "mpb-planner-ompl: OMPL %s: %s\n",
                     i >= 0 && i < 4 ? names[i] : "", text.c_str());
    }
};

void usage(std::FILE *out)
{
    std::fprintf(out,
"usage: mpb-planner-ompl [--lcm-url URL] [--name NAME] [--max-runs N] [--verbose]\n"
"                        [--secret-file FILE]\n"
"\n"
"A planner process for mpbench that plans with OMPL %d.%d.%d's geometric\n"
"planners. For each plan request it builds the robot's joint space (continuous\n"
"joints wrap), checks states against the request's world, reaches a joint\n"
"goal or a pose region (IK samples inside it, seeded by the request), runs the\n"
"requested algorithm with its parameters until it solves or the time limit\n"
"passes, and answers with up to three stages: \"raw\" (the path as found),\n"
"\"shortcut\" (a shortcut copy) and \"smoothed\" (a B-spline-smoothed copy\n"
"of that), each with its own time. The same seed gives the same samples and\n"
"goal states, so the same raw path.\n"
"\n"
"It announces itself on LCM as NAME@host:pid and serves until SIGINT or\n"
"SIGTERM (or N runs). It prints one line when it starts, nothing per run.\n"
"\n"
"options:\n"
"  --lcm-url URL   LCM URL to join (default %s;\n"
"                  the daemon must use the same one)\n"
"  --name NAME     planner name used in experiment files (default \"ompl\")\n"
"  --max-runs N    exit after answering N runs (default 0: no limit)\n"
"  --secret-file F authenticate every message with the shared secret in F\n"
"                  (the daemon must use the same file)\n"
"  --verbose       show OMPL's own log messages on stderr\n"
"  --help          show this text\n"
"\n"
"parameters a request may carry, besides the algorithm's own OMPL parameters\n"
"(e.g. range, goal_bias; an unknown one makes the request INVALID_REQUEST):\n"
"  resolution      joint-space step (rad) for checking motions (default\n"
"                  0.01, the step mpbenchd verifies with by default)\n"
"  verify_resolution  the step (rad) each stage is checked at, as mpbenchd\n"
"                  verifies, before it is sent; a stage that fails is\n"
"                  dropped with those after it (default 0.01, mpbenchd's\n"
"                  default --resolution; 0: no such check)\n"
"  simplify        0: report the raw path only (default 1)\n"
"  first_solution  0: optimizing planners (RRTstar, BITstar, PRMstar ...)\n"
"                  use the whole time limit and report their progress\n"
"                  (best cost, iterations ...) every progress_period s\n"
"                  (default 1: they stop at their first solution, as in\n"
"                  the paper)\n"
"  progress_period seconds between progress samples (default 0.05)\n"
"  goal_targets    region poses tried for IK before a pose-region goal is\n"
"                  given up as FAILED (default 200)\n"
"  connection_range  BiTRRT only: how near (rad) its trees must be for it\n"
"                  to try to join them (default 0: 0.1 of the space's\n"
"                  maximum extent, not OMPL's 10 resolution steps)\n"
"\n"
"algorithms:",
        OMPL_MAJOR_VERSION, OMPL_MINOR_VERSION, OMPL_PATCH_VERSION,
        MPB_DEFAULT_LCM_URL);
    int col = 80;
    for (const Algorithm &a : algorithms()) {
        int len = static_cast<int>(std::strlen(a.name)) + 1;
        if (col + len > 76) {
            std::fprintf(out, "\n ");
            col = 1;
        }
        std::fprintf(out, " %s", a.name);
        col += len;
    }
    std::fprintf(out, "\n");
}

extern "C" void on_warning(void *, const char *line)
{
    std::fprintf(stderr, "mpb-planner-ompl: %s\n", line);
}

extern "C" void on_ready(void *, const char *planner_id)
{
    std::printf("mpb-planner-ompl: serving as %s\n", planner_id);
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char **argv)
{
    mpb_planner_options opt;
    std::memset(&opt, 0, sizeof opt);
    opt.name = "ompl";
    bool verbose = false;
    char err[256] = "";

    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int took = mpb_planner_option(argc, argv, &i, &opt, err, sizeof err);
        if (took < 0) {
            std::fprintf(stderr, "mpb-planner-ompl: %s (see --help)\n", err);
            return 2;
        }
        if (took)
            continue;
        if (!std::strcmp(a, "--help") || !std::strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        }
        if (!std::strcmp(a, "--verbose")) {
            verbose = true;
            continue;
        }
        std::fprintf(stderr, "mpb-planner-ompl: unknown argument '%s' (see --help)\n", a);
        return 2;
    }

    LogHandler log;
    ompl::msg::useOutputHandler(&log);
    ompl::msg::setLogLevel(verbose ? ompl::msg::LOG_INFO : ompl::msg::LOG_NONE);

    struct sigaction sa;
    std::memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);

    std::vector<const char *> names;
    for (const Algorithm &a : algorithms())
        names.push_back(a.name);

    Context ctx;
    mpb_planner_def def;
    std::memset(&def, 0, sizeof def);
    def.name = opt.name;
    def.language = "c++";
    def.version = k_version;
    def.algorithms = names.data();
    def.num_algorithms = static_cast<int>(names.size());
    def.solve = solve;
    def.user = &ctx;
    def.on_ready = on_ready;
    def.on_warning = on_warning;
    def.secret_file = opt.secret_file;

    int rc = mpb_planner_serve(&def, opt.lcm_url, &g_stop, opt.max_runs, err,
                               sizeof err);
    ompl::msg::restorePreviousOutputHandler();
    if (rc != MPB_OK) {
        std::fprintf(stderr, "mpb-planner-ompl: %s\n", err[0] ? err : mpb_strerror(rc));
        return 1;
    }
    return 0;
}
