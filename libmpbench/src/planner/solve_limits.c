/*
 * solve_limits.c - when a planner's solve() must end: the one stop check
 * every planner calls (mpb_solve_should_stop()), a budget of its own
 * inside the run's (mpb_solve_limits_moved()), and what it tells the
 * daemon of a model it builds first (mpb_solve_setting_up(),
 * mpb_solve_planning()). planner.h documents them.
 */
#include <stddef.h>

#include "mpbench/mpbench.h"
#include "mpbench/planner.h"
#include "mpb_run_ack_t.h"
#include "planner_internal.h"

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

void mpb_solve_setting_up(const mpb_solve_limits *lim)
{
    if (lim->kit != NULL)
        mpb__tell_phase(lim->kit, MPB_RUN_ACK_T_SETTING_UP);
}

void mpb_solve_planning(const mpb_solve_limits *lim)
{
    if (lim->kit != NULL)
        mpb__tell_phase(lim->kit, MPB_RUN_ACK_T_PLANNING);
}
