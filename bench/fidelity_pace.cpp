/*
 * fidelity_pace.cpp - holds the planner process between runs so that the
 * in-process runs of each seed come right after its run through mpbenchd
 * (fidelity_pace.h). It listens to the requests, the results and the
 * daemon's acknowledgements, and sends nothing on LCM.
 */
#include "fidelity_pace.h"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <unordered_map>

#include <sched.h>
#include <signal.h>
#include <unistd.h>

#include <lcm/lcm.h>

#include "mpbench/mpbench.h"
#include "mpb_plan_request_t.h"
#include "mpb_plan_result_t.h"
#include "mpb_run_ack_t.h"

namespace mpb_fidelity {
namespace {

// The planner to let go if this process is ended while it is held.
volatile sig_atomic_t held_pid = 0;

void let_go_and_exit(int sig)
{
    if (held_pid > 0)
        kill(static_cast<pid_t>(held_pid), SIGCONT);
    signal(sig, SIG_DFL);
    raise(sig);
}

struct Request {
    int64_t utime;      // the daemon's first send
    std::string seed;
};

struct Pacer {
    pid_t planner;
    std::unordered_map<std::string, Request> requests;
    std::set<std::string> paced;
    std::string holding;        // the run whose result came; planner held
    int64_t held_at = 0;        // utime when it was held
    double held_mono = 0;
    double run_s = 0;           // the planner's time_total for it
    bool stored = false;        // mpbenchd acknowledged `holding`
};

// A planner id ends in ":PID" (mpb_planner_id_make).
bool is_held_planner(const Pacer *p, const char *planner_id)
{
    const char *colon = planner_id ? std::strrchr(planner_id, ':') : nullptr;
    return colon != nullptr && std::atol(colon + 1) == static_cast<long>(p->planner);
}

void on_request(const lcm_recv_buf_t *rbuf, const char *, void *user)
{
    Pacer *p = static_cast<Pacer *>(user);
    mpb_plan_request_t m;
    if (!mpb_wire_check(MPB_WIRE_PLAN_REQUEST, rbuf->data, rbuf->data_size, nullptr, 0) ||
        mpb_plan_request_t_decode(rbuf->data, 0, static_cast<int>(rbuf->data_size), &m) < 0)
        return;
    // Only the held planner's requests: with other planners on the URL
    // (bench/fidelity.sh --busy), theirs are not paced.
    if (mpb_attempt_id_is_valid(m.attempt_id) && !p->requests.count(m.attempt_id) &&
        is_held_planner(p, m.planner_id))
        p->requests[m.attempt_id] = {m.utime, std::to_string(static_cast<long long>(m.seed))};
    for (int i = 0; i < m.num_stored; i++)
        if (!p->holding.empty() && p->holding == m.stored[i])
            p->stored = true;
    mpb_plan_request_t_decode_cleanup(&m);
}

void on_result(const lcm_recv_buf_t *rbuf, const char *, void *user)
{
    Pacer *p = static_cast<Pacer *>(user);
    mpb_plan_result_t m;
    if (!mpb_wire_check(MPB_WIRE_PLAN_RESULT, rbuf->data, rbuf->data_size, nullptr, 0) ||
        mpb_plan_result_t_decode(rbuf->data, 0, static_cast<int>(rbuf->data_size), &m) < 0)
        return;
    // The first result of a run this process saw requested; a result
    // re-sent while mpbenchd was storing it is the same run.
    if (p->holding.empty() && p->requests.count(m.attempt_id) && !p->paced.count(m.attempt_id)) {
        held_pid = p->planner;
        kill(p->planner, SIGSTOP);
        p->held_at = mpb_utime_now();
        p->held_mono = mpb_monotonic_s();
        p->holding = m.attempt_id;
        p->run_s = m.time_total;
        p->stored = false;
    }
    mpb_plan_result_t_decode_cleanup(&m);
}

void on_ack(const lcm_recv_buf_t *rbuf, const char *, void *user)
{
    Pacer *p = static_cast<Pacer *>(user);
    mpb_run_ack_t m;
    if (!mpb_wire_check(MPB_WIRE_RUN_ACK, rbuf->data, rbuf->data_size, nullptr, 0) ||
        mpb_run_ack_t_decode(rbuf->data, 0, static_cast<int>(rbuf->data_size), &m) < 0)
        return;
    if ((m.kind == MPB_RUN_ACK_T_RESULT_STORED || m.kind == MPB_RUN_ACK_T_RESULT_REJECTED) &&
        !p->holding.empty() && p->holding == m.attempt_id)
        p->stored = true;
    mpb_run_ack_t_decode_cleanup(&m);
}

} // namespace

int pace(const PaceOptions &opt,
         const std::function<void(long index, const std::string &seed)> &between,
         PaceReport *report)
{
    *report = PaceReport();
    if (opt.planner <= 0 || kill(opt.planner, 0) != 0) {
        std::fprintf(stderr, "mpb-bench-fidelity pace: no process %d to hold: %s\n",
                     static_cast<int>(opt.planner), std::strerror(errno));
        return 1;
    }
    lcm_t *lcm = lcm_create(opt.lcm_url ? opt.lcm_url : MPB_DEFAULT_LCM_URL);
    if (lcm == nullptr) {
        std::fprintf(stderr, "mpb-bench-fidelity pace: cannot start LCM\n");
        return 1;
    }
    for (int sig : {SIGINT, SIGTERM, SIGHUP})
        std::signal(sig, let_go_and_exit);

    Pacer p;
    p.planner = opt.planner;
    // The held planner's own request and ack channels (its id ends in
    // ":PID"): other planners' traffic (--busy) would fill the queues
    // while this process runs the in-process sides.
    const std::string own = ".*:" + std::to_string(static_cast<long>(opt.planner));
    const std::string requests = MPB_CHANNEL_REQUEST_PREFIX + own;
    const std::string acks = MPB_CHANNEL_ACK_PREFIX + own;
    lcm_subscription_t *subs[] = {
        lcm_subscribe(lcm, requests.c_str(), on_request, &p),
        lcm_subscribe(lcm, MPB_CHANNEL_RESULT, on_result, &p),
        lcm_subscribe(lcm, acks.c_str(), on_ack, &p),
    };
    for (lcm_subscription_t *s : subs)
        lcm_subscription_set_queue_capacity(s, 1000);
    std::fprintf(stderr, "mpb-bench-fidelity pace: listening, planner %d\n",
                 static_cast<int>(opt.planner));

    int64_t last_held_at = 0;
    int rc = 0;
    while (report->paced < opt.runs) {
        // The planner plans on this CPU: wait for its result asleep.
        double idle_since = mpb_monotonic_s();
        while (p.holding.empty() && mpb_monotonic_s() - idle_since < opt.idle_timeout_s)
            lcm_handle_timeout(lcm, 100);
        if (p.holding.empty()) {
            std::fprintf(stderr, "mpb-bench-fidelity pace: no result for %.0f s after %ld "
                         "paced runs\n", opt.idle_timeout_s, report->paced);
            rc = 1;
            break;
        }
        // A copy: requests that arrive meanwhile may rehash the table.
        const Request req = p.requests.at(p.holding);
        if (req.utime <= last_held_at)
            report->late_seeds.push_back(req.seed);
        // mpbenchd verifies and stores it on another CPU; this one must not
        // idle meanwhile (an idle virtual CPU resumes slower: 4b), as it
        // does not before a run of the planner's.
        double waiting = mpb_monotonic_s();
        while (!p.stored && mpb_monotonic_s() - waiting < opt.idle_timeout_s) {
            lcm_handle_timeout(lcm, 0);
            sched_yield();
        }
        if (!p.stored)
            std::fprintf(stderr, "mpb-bench-fidelity pace: run %s not acknowledged as "
                         "stored; going on\n", p.holding.c_str());
        if (p.run_s > opt.max_run_s)
            report->long_seeds.push_back(req.seed);
        else
            between(report->paced, req.seed);
        double held = mpb_monotonic_s() - p.held_mono;
        if (held > report->max_hold_s)
            report->max_hold_s = held;
        kill(p.planner, SIGCONT);
        held_pid = 0;
        last_held_at = p.held_at;
        p.paced.insert(p.holding);
        p.holding.clear();
        report->paced++;
    }
    if (!p.holding.empty())
        kill(p.planner, SIGCONT);
    held_pid = 0;
    for (lcm_subscription_t *s : subs)
        lcm_unsubscribe(lcm, s);
    lcm_destroy(lcm);
    return rc;
}

} // namespace mpb_fidelity
