/*
 * outcome.h - what a finished run counts as: the success rule, written once.
 *
 * A planner claims a success by answering SOLVED; mpbench never takes the
 * claim on trust. Every stage of every result is verified whatever the
 * planner's status (FAILED, TIMEOUT and APPROXIMATE answers with stages
 * too), and the run is then counted by its final stage's verdict and its
 * times. mpbenchd (daemon/record.c) and `mpb verify` both decide with
 * these functions, and a report reads each run's outcome from them, so the
 * rule cannot drift apart between the three (docs/metrics.md, "Claims").
 */
#ifndef MPBENCH_OUTCOME_H
#define MPBENCH_OUTCOME_H

#ifdef __cplusplus
extern "C" {
#endif

/*
 * The outcomes of a finished run: name, the word the store keeps
 * (runs.outcome), and what it means. Exactly one holds for each run.
 */
#define MPB_OUTCOME_MAP(X)                                                  \
    X(UNCLAIMED,       "unclaimed",       "not claimed, and no valid "      \
      "final stage (a failure both sides agree on, a crash, no stages)")    \
    X(VERIFIED,        "verified",        "claimed, the final stage "       \
      "valid, in time: a success (s_r)")                                    \
    X(REFUSED,         "refused",         "claimed, and the final stage "   \
      "not valid (or no stage at all): a refused claim")                    \
    X(LATE,            "late",            "claimed and the final stage "    \
      "valid, but over the time limit or with times that are no times")     \
    X(UNCLAIMED_VALID, "unclaimed_valid", "not claimed (FAILED, TIMEOUT, "  \
      "APPROXIMATE ...), yet the final stage valid by mpbench's check")

typedef enum mpb_outcome {
#define MPB__OUTCOME_ENUM(name, word, text) MPB_OUTCOME_##name,
    MPB_OUTCOME_MAP(MPB__OUTCOME_ENUM)
#undef MPB__OUTCOME_ENUM
    MPB_OUTCOME_COUNT
} mpb_outcome;

/*
 * In time: the planner's times are times (sound: finite, not negative,
 * time_other not above time_total), its time_total is at most time_limit,
 * and by mpbenchd's clock the request took at most time_limit + slack
 * from its last send to the result's arrival (took; NaN where not known,
 * which does not count against it). Returns 1 or 0.
 */
int mpb_run_in_time(int times_sound, double time_total, double took,
                    double time_limit, double slack);

/*
 * THE success rule (s_r): a run is a success when the planner claimed it
 * (claimed: it answered SOLVED), its final stage passed mpbench's
 * verification (final_valid: the run has stages and the last one's
 * verdict is valid) and it was in time (in_time, mpb_run_in_time()).
 * Returns 1 or 0.
 */
int mpb_run_success(int claimed, int final_valid, int in_time);

/*
 * The run's outcome from the same facts, with success as
 * mpb_run_success() gave it (or as stored, runs.success): VERIFIED when
 * claimed and a success, REFUSED when claimed and the final stage not
 * valid, LATE when claimed and valid yet not a success, UNCLAIMED_VALID
 * when not claimed and the final stage valid, UNCLAIMED otherwise.
 * Claimed counts VERIFIED + REFUSED + LATE.
 */
mpb_outcome mpb_run_outcome(int claimed, int final_valid, int success);

/* The outcome's word ("unclaimed_valid"), as runs.outcome keeps it;
 * "unknown" out of range. Never NULL. */
const char *mpb_outcome_name(mpb_outcome outcome);

/* Its meaning, one line; never NULL. */
const char *mpb_outcome_text(mpb_outcome outcome);

/* Whether the outcome counts as claimed (VERIFIED, REFUSED, LATE). */
int mpb_outcome_claimed(mpb_outcome outcome);

#ifdef __cplusplus
}
#endif

#endif /* MPBENCH_OUTCOME_H */
