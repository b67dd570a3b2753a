// progress_log.cpp - see progress_log.h.

#include "progress_log.h"

#include <cmath>
#include <cstdlib>
#include <cstring>

#include "mpbench/mpbench.h"

ProgressLog::ProgressLog(const ompl::base::Planner &planner, double period, double t0)
    : period_(period), t0_(t0), next_(t0)
{
    for (const auto &p : planner.getPlannerProgressProperties()) {
        // OMPL names carry a type: "best cost REAL"; keep the name.
        std::string name = p.first;
        std::size_t sp = name.rfind(' ');
        if (sp != std::string::npos)
            name.erase(sp);
        names_.push_back(name);
        getters_.push_back(p.second);
    }
}

void ProgressLog::take(double now)
{
    Sample s{now - t0_, {}};
    for (const auto &get : getters_) {
        std::string text = get();
        char *end;
        double v = std::strtod(text.c_str(), &end);
        s.values.push_back(end != text.c_str() && std::isfinite(v) ? v : NAN);
    }
    samples_.push_back(std::move(s));
}

void ProgressLog::poll(double now)
{
    if (getters_.empty() || now < next_)
        return;
    // PRM evaluates the condition from two threads: one sample is enough.
    std::unique_lock<std::mutex> lock(mu_, std::try_to_lock);
    if (!lock.owns_lock() || now < next_)
        return;
    take(now);
    next_ = now + period_;
}

void ProgressLog::finish(double now)
{
    std::lock_guard<std::mutex> lock(mu_);
    if (!getters_.empty())
        take(now);
}

namespace {

// A malloc'd copy: mpb_result_clear() frees the result with free().
char *dup(const std::string &s)
{
    char *p = static_cast<char *>(std::malloc(s.size() + 1));
    if (p != nullptr)
        std::memcpy(p, s.c_str(), s.size() + 1);
    return p;
}

}  // namespace

int ProgressLog::addTo(mpb_plan_result_t *res) const
{
    if (samples_.empty())
        return MPB_OK;
    std::size_t total = static_cast<std::size_t>(res->num_progress) + samples_.size();
    auto *grown = static_cast<mpb_progress_t *>(
        std::realloc(res->progress, total * sizeof(mpb_progress_t)));
    if (grown == nullptr)
        return MPB_ENOMEM;
    res->progress = grown;
    for (const Sample &s : samples_) {
        // Only numbers are kept: "best cost" is infinite before a solution.
        int n = 0;
        for (double v : s.values)
            n += std::isfinite(v) ? 1 : 0;
        if (n == 0)
            continue;
        mpb_progress_t *p = &res->progress[res->num_progress];
        std::memset(p, 0, sizeof *p);
        p->time = s.time;
        p->values = static_cast<mpb_named_value_t *>(std::calloc(static_cast<std::size_t>(n),
                                                                 sizeof *p->values));
        if (p->values == nullptr)
            return MPB_ENOMEM;
        res->num_progress++;
        for (std::size_t k = 0; k < s.values.size(); k++) {
            if (!std::isfinite(s.values[k]))
                continue;
            mpb_named_value_t *nv = &p->values[p->num_values];
            if ((nv->name = dup(names_[k])) == nullptr)
                return MPB_ENOMEM;
            nv->value = s.values[k];
            p->num_values++;
        }
    }
    return MPB_OK;
}
