// progress_log.h - an anytime planner's progress (time, best cost, ...),
// sampled from OMPL's progress properties as ompl::tools::Benchmark does,
// but from inside the termination condition: the planner's own thread reads
// its properties between iterations instead of a second thread racing it.
#ifndef MPB_OMPL_PROGRESS_LOG_H
#define MPB_OMPL_PROGRESS_LOG_H

#include <mutex>
#include <string>
#include <vector>

#include <ompl/base/Planner.h>

#include "mpbench/planner.h"

class ProgressLog {
public:
    // Sample planner's numeric progress properties every period seconds
    // from t0 (monotonic s, when solving started).
    ProgressLog(const ompl::base::Planner &planner, double period, double t0);

    // Take a sample if one is due; cheap otherwise. Thread-safe.
    void poll(double now);
    // Take a last sample (the state the planner stopped in).
    void finish(double now);

    // Append the samples to res->progress; MPB_OK or MPB_ENOMEM.
    int addTo(mpb_plan_result_t *res) const;
    std::size_t size() const { return samples_.size(); }

private:
    void take(double now);

    struct Sample {
        double time;
        std::vector<double> values;     // NaN where a property had no number
    };
    std::vector<std::string> names_;    // "best cost", "iterations" ...
    std::vector<ompl::base::Planner::PlannerProgressProperty> getters_;
    double period_, t0_, next_;
    std::mutex mu_;
    std::vector<Sample> samples_;
};

#endif
