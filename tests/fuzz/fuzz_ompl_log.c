/* fuzz_ompl_log.c - libFuzzer target: the OMPL / MoveIt benchmark log
 * reader behind `mpb import`, on any bytes (it takes a length, not a
 * string), and the lookups the importer makes on what it read. */
#include <stdint.h>
#include <stdlib.h>

#include "mpbench/mpbench.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    mpb_ompl_log *log = NULL;
    char err[256];
    if (mpb_ompl_log_open((const char *)data, size, &log, err,
                          sizeof err) == MPB_OK) {
        for (int i = 0; i < log->num_planners; i++) {
            const mpb_ompl_planner *p = &log->planners[i];
            volatile double sink = 0;
            int t = mpb_ompl_planner_property(p, "time");
            for (long r = 0; t >= 0 && r < p->num_runs; r++)
                sink += p->values[(size_t)r * (size_t)p->num_properties + (size_t)t];
            if (p->progress_start)
                sink += (double)p->progress_start[p->num_runs];
            (void)sink;
        }
        mpb_ompl_log_close(log);
    }
    return 0;
}
