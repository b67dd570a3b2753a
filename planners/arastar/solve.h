/* solve.h - one plan request in, one result out: the planner's solve(). */
#ifndef ARASTAR_SOLVE_H
#define ARASTAR_SOLVE_H

#include "mpbench/planner.h"

typedef struct ara_context {
    int verbose;
} ara_context;

/* The planner's mpb_solve_fn; user is an ara_context. */
int ara_solve(void *user, const mpb_plan_request_t *req,
              const mpb_solve_limits *lim, mpb_plan_result_t *res);

#endif
