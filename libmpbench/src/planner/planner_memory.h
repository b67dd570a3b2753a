/*
 * planner_memory.h - a planner process's memory around one solve: its
 * peak measured, a limit enforced, and last words when it dies of it.
 * Used by planner.c; not part of the API (docs/protocol.md, "Memory").
 */
#ifndef MPB_PLANNER_MEMORY_H
#define MPB_PLANNER_MEMORY_H

#include <stddef.h>
#include <sys/resource.h>

#include <lcm/lcm.h>

#include "mpbench/auth.h"

typedef struct mpb__memwatch {
    int    reset;           /* VmHWM was reset: the peak is the solve's */
    int    limited;         /* RLIMIT_DATA lowered for the solve */
    struct rlimit old;      /* RLIMIT_DATA before, restored after */
    double limit_mb;        /* the request's memory_limit, 0: none */
    double data_start_mb;   /* VmData when the solve began */
} mpb__memwatch;

/*
 * Before a solve: reset the peak resident size (Linux: "5" into
 * /proc/self/clear_refs) and, with limit_mb > 0, lower RLIMIT_DATA to the
 * data size now plus limit_mb. Returns 0, or -1 with one line in err when
 * the limit cannot be set (the solve then runs without it).
 */
int mpb__mem_begin(mpb__memwatch *w, double limit_mb, char *err,
                   size_t errlen);

/*
 * After the solve: restore RLIMIT_DATA and return the peak resident size
 * in MB since mpb__mem_begin() (since the process started when w->reset
 * is 0), or NaN where it cannot be read.
 */
double mpb__mem_end(mpb__memwatch *w);

/*
 * Last words: from now until mpb__last_words_disarm(), a fatal signal
 * (SIGABRT, as of an uncaught std::bad_alloc; SIGSEGV; SIGBUS) or a
 * sanitizer's death, once the solve has used at least half of
 * w->limit_mb, publishes the announcement at announce (announce_len
 * encoded bytes, with room for a trailer after them: the planner closing,
 * capacity 0, still working on attempt_id, so that the daemon sends it no
 * other run) and then a MEMORY result for attempt_id, before the process
 * dies. Only for a solve under a limit; lcm, a, announce and the strings
 * must outlive the run. Not thread-safe: one run at a time.
 */
void mpb__last_words_arm(const mpb__memwatch *w, lcm_t *lcm, mpb_auth *a,
                         uint64_t echo, const char *attempt_id,
                         const char *planner_id, unsigned char *announce,
                         int announce_len);
void mpb__last_words_disarm(void);

#endif /* MPB_PLANNER_MEMORY_H */
