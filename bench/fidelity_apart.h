/*
 * fidelity_apart.h - the "apart" side of the timing-fidelity comparison
 * (mpb-bench-fidelity; docs/performance.md, 4h): a bare solve() in a process
 * of its own, which waits between runs for the next seed as a planner
 * process waits for its next request, but with no LCM, no daemon and none
 * of mpbench's planner kit.
 *
 * Through mpbench a run is planned in another process than the in-process
 * sides it is compared with: its own copy of the world and the planner, at
 * other addresses, and a process that sleeps between runs. The apart side
 * has all of that and nothing else of mpbench, so what mpbench reads over
 * the in-process bare solve() and the apart side does not is mpbench's.
 *
 * The worker is this program again (`mpb-bench-fidelity apart-worker` with
 * the problem's options): it reads one seed a line on its standard input,
 * plans it, and answers one line, "SECONDS SOLVED GRAPH_STATES".
 */
#ifndef MPB_BENCH_FIDELITY_APART_H
#define MPB_BENCH_FIDELITY_APART_H

#include <functional>
#include <string>
#include <vector>

#include <sys/types.h>

namespace mpb_fidelity {

class ApartProcess {
public:
    ApartProcess() = default;
    ApartProcess(const ApartProcess &) = delete;
    ApartProcess &operator=(const ApartProcess &) = delete;
    // Closes the worker's input, so that it ends, and waits for it.
    ~ApartProcess();

    // Starts this program (/proc/self/exe) with args, its standard input
    // and output pipes to this process. False, with a message on stderr,
    // if it cannot.
    bool start(const std::vector<std::string> &args);

    // Sends seed and waits for the worker's answer line (without its
    // newline). False, with a message on stderr, if the worker is gone.
    bool ask(const std::string &seed, std::string *answer);

private:
    pid_t pid_ = -1;
    int to_ = -1, from_ = -1;
    std::string pending_;       // read past the last answer line
};

// The worker's loop: for each seed line on standard input, one line of
// answer(seed) on standard output, flushed. Returns 0 at the end of input.
int apart_serve(const std::function<std::string(const std::string &seed)> &answer);

} // namespace mpb_fidelity

#endif
