/* store_outcome.c - the success rule and a run's outcome (outcome.h). */
#include <math.h>

#include "mpbench/outcome.h"

int mpb_run_in_time(int times_sound, double time_total, double took,
                    double time_limit, double slack)
{
    if (!times_sound)
        return 0;
    if (isfinite(time_total) && time_total > time_limit)
        return 0;
    if (took > time_limit + slack)      /* NaN: not known, not late */
        return 0;
    return 1;
}

int mpb_run_success(int claimed, int final_valid, int in_time)
{
    return claimed && final_valid && in_time;
}

mpb_outcome mpb_run_outcome(int claimed, int final_valid, int success)
{
    if (claimed)
        return success ? MPB_OUTCOME_VERIFIED
             : !final_valid ? MPB_OUTCOME_REFUSED : MPB_OUTCOME_LATE;
    return final_valid ? MPB_OUTCOME_UNCLAIMED_VALID : MPB_OUTCOME_UNCLAIMED;
}

const char *mpb_outcome_name(mpb_outcome outcome)
{
    static const char *const names[] = {
#define MPB__OUTCOME_WORD(name, word, text) word,
        MPB_OUTCOME_MAP(MPB__OUTCOME_WORD)
#undef MPB__OUTCOME_WORD
    };
    return (unsigned)outcome < MPB_OUTCOME_COUNT ? names[outcome] : "unknown";
}

const char *mpb_outcome_text(mpb_outcome outcome)
{
    static const char *const texts[] = {
#define MPB__OUTCOME_TEXT(name, word, text) text,
        MPB_OUTCOME_MAP(MPB__OUTCOME_TEXT)
#undef MPB__OUTCOME_TEXT
    };
    return (unsigned)outcome < MPB_OUTCOME_COUNT ? texts[outcome]
                                                 : "no such outcome";
}

int mpb_outcome_claimed(mpb_outcome outcome)
{
    return outcome == MPB_OUTCOME_VERIFIED || outcome == MPB_OUTCOME_REFUSED ||
           outcome == MPB_OUTCOME_LATE;
}
