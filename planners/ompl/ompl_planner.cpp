// ompl_planner.cpp - mpb-planner-ompl: OMPL's geometric planners behind the mpbench protocol.
//
// The process: its options and OMPL's messages, then the kit's
// serving loop around solve(). One request is one fresh OMPL problem
// (solve.cpp) over the algorithms of algorithms.cpp; only the parsed world
// (and robot, for IK) is kept between requests (world_cache.cpp), keyed by
// the texts' hashes.

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <ompl/config.h>
#include <ompl/util/Console.h>

#include "mpbench/mpbench.h"
#include "mpbench/planner.h"

#include "algorithms.h"
#include "solve.h"

using mpb_ompl::Algorithm;
using mpb_ompl::algorithms;

namespace {

#define MPB_STR2(x) #x
#define MPB_STR(x) MPB_STR2(x)
const char *const k_version = MPB_VERSION_STRING " (OMPL "
    MPB_STR(OMPL_MAJOR_VERSION) "." MPB_STR(OMPL_MINOR_VERSION) "."
    MPB_STR(OMPL_PATCH_VERSION) ")";

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

    std::vector<const char *> names, approaches;
    for (const Algorithm &a : algorithms()) {
        names.push_back(a.name);
        approaches.push_back("sampling");   /* every one of OMPL's here */
    }

    mpb_ompl::Context ctx;
    mpb_planner_def def;
    std::memset(&def, 0, sizeof def);
    def.language = "c++";
    def.version = k_version;
    def.algorithms = names.data();
    def.num_algorithms = static_cast<int>(names.size());
    def.approaches = approaches.data();
    def.solve = mpb_ompl_solve;
    def.user = &ctx;

    int status = mpb_planner_main(&def, &opt, "mpb-planner-ompl");
    ompl::msg::restorePreviousOutputHandler();
    return status;
}
