/*
 * solve_limits.c - when a planner's solve() must end: the one stop check
 * every planner calls (mpb_solve_should_stop()), and a budget of its own
 * inside the run's (mpb_solve_limits_moved()). planner.h documents both.
 */
#include <stddef.h>

#include "mpbench/mpbench.h"
#include "mpbench/planner.h"

int mpb_solve_should_stop(const mpb_solve_limits *lim)
{
    return (lim->stop != NULL && *lim->stop) ||
           mpb_monotonic_s() >= lim->deadline;
}

mpb_solve_limits mpb_solve_limits_moved(const mpb_solve_limits *lim,
                                        double seconds)
{
    mpb_solve_limits moved = *lim;
    moved.deadline += seconds;
    return moved;
}
