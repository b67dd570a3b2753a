/*
 * fidelity_pace.h - the timing-fidelity comparison run by run instead of
 * block by block (mpb-bench-fidelity pace; docs/performance.md, 4e).
 *
 * In blocks, mpbench's runs and the in-process runs of the same seeds are
 * seconds apart, and this VM changes speed from one second to the next.
 * Paced, each run through mpbenchd is followed by the in-process runs of
 * its own seed, on the same CPU, before the planner process may start the
 * next one: the planner is held (SIGSTOP) from the moment it publishes a
 * result until mpbenchd has stored it and the in-process runs are done,
 * then let go (SIGCONT). Nothing the planner times is held: it times its
 * solve(), and it is stopped only between runs.
 */
#ifndef MPB_BENCH_FIDELITY_PACE_H
#define MPB_BENCH_FIDELITY_PACE_H

#include <functional>
#include <string>
#include <vector>

#include <sys/types.h>

namespace mpb_fidelity {

struct PaceOptions {
    pid_t planner = 0;          // the planner process to hold between runs
    long runs = 0;              // results to pace, then return
    double idle_timeout_s = 60; // give up after this long without a result
    // Runs the planner took longer than this for (its time_total) are not
    // paced: their seeds' in-process runs would hold it so long that
    // mpbenchd takes it for gone (three heartbeats missed: 1.5 s).
    double max_run_s = 0.3;
    const char *lcm_url = nullptr;      // NULL: mpbench's default
};

struct PaceReport {
    long paced = 0;             // results paced
    double max_hold_s = 0;      // the longest the planner was held
    // Runs whose request mpbenchd had sent before the planner was held
    // after the run before: the planner may have started them while free,
    // so they are not paced runs (their seeds; none are expected).
    std::vector<std::string> late_seeds;
    // Runs longer than max_run_s: between() was not called (their seeds).
    std::vector<std::string> long_seeds;
};

// For each of the next opt.runs results on LCM: hold the planner, wait
// without sleeping (the CPU must not idle, as it does not before the
// planner's own runs here) until mpbenchd acknowledges the result as
// stored, call between(index, seed of that run) unless the run was longer
// than opt.max_run_s, let the planner go.
// Returns 0, or 1 (with a message on stderr) if LCM cannot start or no
// result comes for opt.idle_timeout_s. The planner is never left held:
// also not when this process is ended by SIGINT, SIGTERM or SIGHUP.
int pace(const PaceOptions &opt,
         const std::function<void(long index, const std::string &seed)> &between,
         PaceReport *report);

} // namespace mpb_fidelity

#endif
