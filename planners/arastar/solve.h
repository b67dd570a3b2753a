/* solve.h - one plan request in, one result out: the planner's solve(). */
#ifndef ARASTAR_SOLVE_H
#define ARASTAR_SOLVE_H

#include <signal.h>

#include "mpbench/planner.h"

typedef struct ara_context {
    volatile sig_atomic_t *stop;
    int verbose;
} ara_context;

int ara_solve(void *user, const mpb_plan_request_t *req,
              mpb_plan_result_t *res);

#endif
